//! Kalker's linear-theory coefficients as the exact solver's grid gives them.

use super::ExactTheory;
use crate::{ContactInput, CreepForceModel, InvalidInput};

/// The creepage and spin coefficients of one ellipse shape and material (Kalker 1990, §E):
/// F_x = −G c² C11 ξ, F_y = −G c² C22 η − G c³ C23 φ, M_z = −G c⁴ C33 φ (c = √(ab)), the
/// coefficients of [`crate::KalkerCoefficients`] and [`crate::KalkerCoefficients::spin_moment_c33`].
///
/// The exact theory's own coefficients on a 40 × 40 grid against Kalker's Table E.3 at a/b = 1,
/// ν = 0.25 (C11 = 4.12, C22 = 3.67, C23 = 1.47, C33 = 1.19):
///
/// ```
/// use wheel_rail_contact::ExactTheory;
///
/// let own = ExactTheory::new(40, 40).linear_coefficients(1.0, 0.25).unwrap();
/// for (ours, kalker) in [(own.c11, 4.12), (own.c22, 3.67), (own.c23, 1.47)] {
///     assert!((ours / kalker - 1.0).abs() < 0.02, "{ours} vs {kalker}");
/// }
/// // C33 as transcribed lies 1–5 % below this solver over the table (data/kalker_c33.csv).
/// assert!((own.c33 / 1.19 - 1.0).abs() < 0.05, "{}", own.c33);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearCoefficients {
    /// Longitudinal creepage coefficient C11.
    pub c11: f64,
    /// Lateral creepage coefficient C22.
    pub c22: f64,
    /// Lateral force from spin, C23.
    pub c23: f64,
    /// Spin moment from spin, C33.
    pub c33: f64,
}

/// Creepages in units of the characteristic ones (the linear force reaching μQ): small enough
/// that no element slips, whatever the grid, large enough to stay far from underflow.
const RELATIVE_CREEPAGE: f64 = 1e-9;

impl ExactTheory {
    /// The coefficients of the solution in full adhesion on this grid, for the ellipse of
    /// semi-axis ratio `a_over_b` and Poisson's ratio `poisson_ratio`: two solves (ξ = η, and
    /// φ alone) at creepages of 1e-9 of saturation, so nothing slips. With a fine grid, the
    /// exact theory's own coefficients, to compare with Kalker's table (core/tests/library/exact_theory.rs,
    /// `cargo run --release -p lab --bin kalker_table_check`).
    pub fn linear_coefficients(&self, a_over_b: f64, poisson_ratio: f64) -> Result<LinearCoefficients, InvalidInput> {
        let (shear_modulus, normal_force, friction_coefficient, c) = (8e10, 1e5, 0.3, 5e-3);
        let rest = ContactInput {
            creepage_longitudinal: 0.0,
            creepage_lateral: 0.0,
            spin_creepage: 0.0,
            normal_force,
            semi_axis_a: c * a_over_b.sqrt(),
            semi_axis_b: c / a_over_b.sqrt(),
            friction_coefficient,
            shear_modulus,
            poisson_ratio,
        };
        // μQ/(G c²): the creepage at which the linear force would reach μQ with C = 1.
        let creepage = RELATIVE_CREEPAGE * friction_coefficient * normal_force / (shear_modulus * c * c);
        let spin = creepage / c;
        // ξ and η together: by the symmetry y → −y neither drives the other's force.
        let creep =
            self.creep_forces(&ContactInput { creepage_longitudinal: creepage, creepage_lateral: creepage, ..rest })?;
        let spinning = self.creep_forces(&ContactInput { spin_creepage: spin, ..rest })?;
        let unit = shear_modulus * c * c * creepage;
        Ok(LinearCoefficients {
            c11: -creep.force_longitudinal / unit,
            c22: -creep.force_lateral / unit,
            c23: -spinning.force_lateral / unit,
            c33: -spinning.spin_moment.unwrap_or(0.0) / (unit * c),
        })
    }
}
