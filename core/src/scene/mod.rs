//! Options a scene switches on when its master cannot supply what the creep-force models need:
//! the contact ellipse from the load and geometry ([`crate::hertz`]), creepages from velocities down to
//! standstill ([`kinematics`]), and the build-up of creep force over a rolling distance
//! ([`relaxation`]). Each is a pure function of its inputs (SI units); a scene that leaves an
//! option off never calls it. [`Scene`] composes them with the chosen model: one evaluation
//! for the FMU, the packaging tool's reference outputs and Rust users.

pub mod kinematics;
mod pipeline;
pub mod relaxation;

pub use pipeline::{
    CreepageSource, EllipseSource, Evaluation, Relaxation, Scene, SceneCache, SceneError, SceneInput, SceneOutput,
    SceneState, TractionLaw,
};
