//! Kalker's linear theory of rolling contact: the small-creepage limit of the exact theory, with
//! no slip anywhere in the contact (Kalker 1967; Kalker 1990, *Three-dimensional elastic bodies
//! in rolling contact*, §E and Table E.3).
//!
//! With c = √(ab) and the coefficients of [`KalkerCoefficients`], forces and moment on the wheel
//! (Kalker's and CONTACT's convention: they oppose the creepages, C32 = −C23):
//!
//! ```text
//! F_x = −G c² C11 ξ
//! F_y = −G c² C22 η − G c³ C23 φ
//! M_z =  G c³ C23 η − G c⁴ C33 φ
//! ```
//!
//! The forces are not limited by friction: this is the theory's definition, and the reason the
//! saturating models exist. They are finite for every valid input (products beyond `f64::MAX`
//! are held at ±`f64::MAX`).

use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, KalkerCoefficients};

/// Kalker's linear theory: F_x, F_y and M_z proportional to the creepages.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KalkerLinear;

/// Linear-theory stiffnesses G c^n C_ij of one contact, each held finite.
pub(crate) struct LinearTheory {
    /// G c² C11 [N].
    k11: f64,
    /// G c² C22 [N].
    k22: f64,
    /// G c³ C23 [N·m].
    k23: f64,
}

impl CreepForceModel for KalkerLinear {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        if input.transmits_no_force() {
            return Ok(CreepForces::default());
        }
        let theory = LinearTheory::new(input);
        let (fx, fy) = theory.forces(input);
        let area = input.semi_axis_a * input.semi_axis_b;
        let c33 = KalkerCoefficients::spin_moment_c33(input.semi_axis_a / input.semi_axis_b, input.poisson_ratio);
        let k33 = finite(input.shear_modulus * (area * area) * c33);
        let spin_moment = finite(term(theory.k23, input.creepage_lateral) - term(k33, input.spin_creepage));
        Ok(CreepForces::new(fx, fy, Some(spin_moment), input.friction_limit()))
    }
}

impl LinearTheory {
    /// Stiffnesses for a validated input.
    pub(crate) fn new(input: &ContactInput) -> Self {
        let area = input.semi_axis_a * input.semi_axis_b; // c²
        let c = KalkerCoefficients::new(input.semi_axis_a / input.semi_axis_b, input.poisson_ratio);
        let g = input.shear_modulus;
        Self {
            k11: finite(g * area * c.c11),
            k22: finite(g * area * c.c22),
            k23: finite(g * (area.sqrt() * area) * c.c23),
        }
    }

    /// (F_x, F_y) [N] of the module documentation.
    pub(crate) fn forces(&self, input: &ContactInput) -> (f64, f64) {
        let force_longitudinal = -term(self.k11, input.creepage_longitudinal);
        let force_lateral = -finite(term(self.k22, input.creepage_lateral) + term(self.k23, input.spin_creepage));
        (force_longitudinal, force_lateral)
    }
}

/// stiffness × creepage, 0 for zero creepage (also when the stiffness is huge), held finite.
fn term(stiffness: f64, creepage: f64) -> f64 {
    if creepage == 0.0 {
        0.0
    } else {
        finite(stiffness * creepage)
    }
}

/// Holds ±∞ at ±`f64::MAX`.
fn finite(value: f64) -> f64 {
    value.clamp(-f64::MAX, f64::MAX)
}
