//! FMI 2.0 Co-Simulation adapter around the core.
//!
//! - [`model_description`]: the interface, generated from `modelDescription.xml`.
//! - [`scene`]: maps the instance's values to the core's [`crate::ContactInput`] and model, and
//!   the forces back to outputs.
//! - [`instance`]: one FMU instance: its values, the standard's state machine, logging.
//! - [`ffi`]: the C exports; the only file with `unsafe`.

pub mod ffi;
pub mod instance;
pub mod model_description;
pub mod scene;
