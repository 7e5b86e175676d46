//! # wheel-rail-contact-fmu
//!
//! The FMI 2.0 Co-Simulation adapter around the physics core (`wheel_rail_contact`): the FMU's
//! shared library. It decodes FMI values into the core's typed [`wheel_rail_contact::scene::Scene`]
//! and encodes the outputs; all physics is the core's. It alone holds `unsafe` code, in [`ffi`].
//!
//! - [`model_description`]: the interface, generated from `modelDescription.xml`.
//! - [`scene`]: the instance's values ↔ the core's scene (decode parameters and inputs, encode
//!   outputs, directional derivatives).
//! - [`profiles`]: `contact_geometry = profiles`: the profiles read (the adapter's only file
//!   I/O) and placed, the wheel's inputs and outputs.
//! - [`resources`]: the FMU's resources directory from the master's resource URI, and files
//!   named relative to it.
//! - [`mode`]: the Co-Simulation state machine: modes, and the typed call table saying which
//!   modes allow each call.
//! - [`logging`]: statuses, and which messages reach the master's logger.
//! - [`snapshot`]: what an FMU state holds and its checked byte format.
//! - [`instance`]: one FMU instance: lifecycle, values, the step, FMU states, derivatives (one
//!   file each).
//! - [`options`]: which variables each model choice and option uses, declared once.
//! - [`fmi2`]: the FMI 2.0 C types; [`ffi`]: the C exports, the only file with `unsafe`.

#![deny(unsafe_code)]

pub mod ffi;
pub mod fmi2;
pub mod instance;
pub mod logging;
pub mod mode;
pub mod model_description;
pub mod options;
pub mod profiles;
pub mod resources;
pub mod scene;
pub mod snapshot;
