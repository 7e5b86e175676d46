//! Builds the `wheel_rail_contact` FMU and drives it.
//!
//! - [`fmu`]: builds the FMI adapter's cdylib (`fmu/`) with cargo and zips `target/fmu/wheel_rail_contact.fmu`
//!   (`build.rs` cannot zip the library its own crate is still compiling);
//! - [`documentation`]: `documentation/index.html`, generated from the same variable table the
//!   adapter uses, with a plot of the default creep-force curve computed by the core;
//! - [`default_scene`]: the creepage sweep of the README's first command, through the packaged
//!   `.fmu`, loaded by the C-ABI master (`fmu_master`, libloading);
//! - [`reference`](mod@reference): the core's forces for rows of inputs (CSV), the reference of the fmpy tests;
//! - [`exact_table`](mod@exact_table): generates the `exact_table` model's table from the exact
//!   solver (`cargo fmu exact-table`), resumable;
//! - [`profile_figure`]: the documentation's figure of `contact_geometry = profiles` (the built-in
//!   profiles in contact, the patches marked), computed by the core;
//! - [`plot`]: the small SVG line plot both of the above draw.

#![forbid(unsafe_code)]

pub mod default_scene;
pub mod documentation;
pub mod exact_table;
pub mod fmu;
pub mod plot;
pub mod profile_figure;
pub mod reference;
