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
//! saturating models exist. At μ = 0 and Q ≤ 0 the force is zero (no contact to transmit it),
//! so it jumps at μ = 0⁺ and Q = 0⁺: there the derivative is that of the zero force, with no
//! one-sided derivative in μ or Q. They are finite for every valid input (products beyond `f64::MAX`
//! are held at ±`f64::MAX`).

use crate::creep_force_model::{dual_derivative, NoForceBoundary};
use crate::kalker_coefficients::spin_moment_c33_at;
use crate::models::rung::Rung;
use crate::numerics::{value, Scalar};
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, KalkerCoefficients, ModelChoice};

/// Kalker's linear theory: F_x, F_y and M_z proportional to the creepages.
///
/// a = 8 mm, b = 4 mm (a/b = 2: Table E.3's row b/a = 0.5), ν = 0.25 (a table column): C11 =
/// 5.10, C22 = 4.90, C23 = 2.62 as Kalker prints them, so F_x = −G ab C11 ξ = −13.383 MN · ξ:
///
/// ```
/// use wheel_rail_contact::{ContactInput, CreepForceModel, KalkerLinear};
///
/// let contact = |xi: f64, eta: f64, phi: f64| ContactInput {
///     creepage_longitudinal: xi,
///     creepage_lateral: eta,
///     spin_creepage: phi,
///     normal_force: 82e3,
///     semi_axis_a: 8e-3,
///     semi_axis_b: 4e-3,
///     friction_coefficient: 0.3,
///     shear_modulus: 82e9,
///     poisson_ratio: 0.25,
/// };
/// let forces = KalkerLinear.creep_forces(&contact(1e-3, 0.0, 0.0)).unwrap();
/// assert!((forces.force_longitudinal + 82e9 * 32e-6 * 5.10 * 1e-3).abs() < 1e-6);
/// // Not friction-limited: twice the creepage, twice the force, beyond μQ = 24.6 kN.
/// let doubled = KalkerLinear.creep_forces(&contact(2e-3, 0.0, 0.0)).unwrap();
/// assert_eq!(doubled.force_longitudinal, 2.0 * forces.force_longitudinal);
/// assert!(doubled.adhesion_utilisation > 1.0);
/// // Spin: F_y = −G c³ C23 φ, with c = √(ab).
/// let spin = KalkerLinear.creep_forces(&contact(0.0, 0.0, 0.05)).unwrap();
/// assert!((spin.force_lateral + 82e9 * 32e-6_f64.powf(1.5) * 2.62 * 0.05).abs() < 1e-6);
/// assert!(spin.spin_moment.unwrap() < 0.0, "M_z = −G c⁴ C33 φ opposes the spin");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KalkerLinear;

/// Kalker's linear theory's rung of the ladder.
pub const RUNG: Rung = Rung {
    name: "kalker_linear",
    fmu_value: 2,
    type_name: "KalkerLinear",
    fmu_parameters: &[],
    spin_moment: true,
    friction_limited: false,
    offline: false,
    summary: "F, M_z proportional to the creepages (C11, C22, C23, C33); not friction-limited",
    source: "Kalker 1967/1990, Table E.3",
    documentation: "Kalker's linear theory (Kalker 1967; 1990, Table E.3): F<sub>x</sub> = −G c² C11 ξ,
F<sub>y</sub> = −G c² C22 η − G c³ C23 φ, M<sub>z</sub> = G c³ C23 η − G c⁴ C33 φ, c = √(ab). Not friction-limited
(the theory's definition): the utilisation can exceed 1.",
    default_model: || Ok(ModelChoice::KalkerLinear(KalkerLinear)),
};

/// Linear-theory stiffnesses G c^n C_ij of one contact, each held finite.
pub(crate) struct LinearTheory<D> {
    /// G c² C11 \[N\].
    k11: D,
    /// G c² C22 \[N\].
    k22: D,
    /// G c³ C23 [N·m].
    k23: D,
}

impl CreepForceModel for KalkerLinear {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        Ok(linear_forces(input))
    }

    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        dual_derivative(input, direction, NoForceBoundary::Jump, linear_forces)
    }
}

/// The linear forces and moment for a validated input, over any [`Scalar`].
pub(crate) fn linear_forces<D: Scalar>(input: &ContactInput<D>) -> CreepForces<D> {
    if input.transmits_no_force() {
        return CreepForces::zero();
    }
    let theory = LinearTheory::new(input);
    let (fx, fy) = theory.forces(input);
    let area = input.semi_axis_a * input.semi_axis_b;
    let c33 = spin_moment_c33_at(input.semi_axis_a / input.semi_axis_b, value(input.poisson_ratio));
    let k33 = finite(input.shear_modulus * (area * area) * c33);
    let spin_moment = finite(term(theory.k23, input.creepage_lateral) - term(k33, input.spin_creepage));
    CreepForces::new(fx, fy, Some(spin_moment), input.friction_limit())
}

impl<D: Scalar> LinearTheory<D> {
    pub(crate) fn new(input: &ContactInput<D>) -> Self {
        let area = input.semi_axis_a * input.semi_axis_b; // c²
        let c = KalkerCoefficients::at(input.semi_axis_a / input.semi_axis_b, value(input.poisson_ratio));
        let g = input.shear_modulus;
        Self {
            k11: finite(g * area * c.c11),
            k22: finite(g * area * c.c22),
            k23: finite(g * (area.sqrt() * area) * c.c23),
        }
    }

    /// (F_x', F_y') of the linear theory.
    pub(crate) fn forces(&self, input: &ContactInput<D>) -> (D, D) {
        let force_longitudinal = -term(self.k11, input.creepage_longitudinal);
        let force_lateral = -finite(term(self.k22, input.creepage_lateral) + term(self.k23, input.spin_creepage));
        (force_longitudinal, force_lateral)
    }
}

/// stiffness × creepage, exactly 0 for zero creepage even where the stiffness is held at f64::MAX.
fn term<D: Scalar>(stiffness: D, creepage: D) -> D {
    if value(creepage) == 0.0 {
        // Keeps the derivative: d(k·s) = k·ds at s = 0.
        stiffness * creepage
    } else {
        finite(stiffness * creepage)
    }
}

/// `x` held within ±f64::MAX by value.
fn finite<D: Scalar>(x: D) -> D {
    if value(x).abs() <= f64::MAX {
        x
    } else {
        D::from(f64::MAX.copysign(value(x)))
    }
}

/// Nothing carried from one evaluation to the next: the forces are linear in the input.
impl crate::models::sequence::SequenceModel for KalkerLinear {
    type Memory = ();
    type Cache = ();
}
