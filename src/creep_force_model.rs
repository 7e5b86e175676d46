//! The one interface every rung of the speed–accuracy ladder implements.

use crate::{ContactInput, CreepForces, InvalidInput};

/// A creep-force model: contact state in, tangential forces out.
///
/// Implementations validate the input (returning [`InvalidInput`]), return zero force when
/// [`ContactInput::transmits_no_force`], and never return NaN or infinity for a valid input.
pub trait CreepForceModel {
    /// Evaluates the forces for one contact patch.
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput>;
}
