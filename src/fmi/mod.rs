//! FMI 2.0 Co-Simulation adapter around the core.
//!
//! - [`model_description`]: the interface, generated from `modelDescription.xml`.
//! - [`scene`]: maps the instance's values to the core's [`crate::ContactInput`] and model, and
//!   the forces back to outputs.
//! - [`derivative`]: fmi2GetDirectionalDerivative's J·v through the core's derivatives.
//! - [`fmu_state`]: what an FMU state holds and its checked byte format.
//! - [`instance`]: one FMU instance: its values, the standard's state machine, logging.
//! - [`ffi`]: the C exports; the only file with `unsafe`.

pub mod derivative;
pub mod ffi;
pub mod fmu_state;
pub mod instance;
pub mod model_description;
pub mod scene;
