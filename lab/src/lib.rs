//! The lab beside the product (`publish = false`): studies and experiments that measure the
//! core or made its data, as binaries (`cargo run --release -p lab --bin NAME`):
//!
//! - `trade_report`: every rung against Kalker's exact theory, error and time side by side
//!   (docs/trade/, docs/trade.md);
//! - `convergence_survey`: cold exact-theory solves of random contacts on one grid;
//! - `node_grid_study`, `kink_alignment_experiment`, `exact_table_at_point`: how exact_table's
//!   nodes were chosen and where its errors come from (docs/exact_table.md);
//! - `exact_table_load_time`: what reading, checking and decoding the table costs the FMU
//!   (docs/exact_table.md, "Where the table lives");
//! - `kalker_table_check`, `kalker_c33_check`: the exact solver against Kalker's table
//!   (docs/reference/);
//! - `wheelset_contact_data`: the passenger-coach wheelset's contact data on S1002/UIC60 for the
//!   linear stability reference (data/wheelset/, docs/wheelset.md);
//! - `coupling_stability_map`: the wheelset FMU and two contact units coupled by a fixed-step
//!   master, which steps stay bounded (docs/coupling-stability.md).
//!
//! What they share is here: [`random_contacts`], [`wheelset_parameters`], [`coupling`].

pub mod coupling;
pub mod random_contacts;
pub mod wheelset_parameters;
