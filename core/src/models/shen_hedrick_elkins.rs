//! Shen, Hedrick & Elkins' saturation of Kalker's linear theory (Z.Y. Shen, J.K. Hedrick,
//! J.A. Elkins, "A comparison of alternative creep force models for rail vehicle dynamic
//! analysis", Proc. 8th IAVSD Symposium, Cambridge MA, 1983, pp. 591–605).
//!
//! The linear forces F_x', F_y' (which include the lateral force from spin, −G c³ C23 φ; see
//! [`KalkerLinear`](crate::models::kalker_linear::KalkerLinear)) are scaled by one common factor
//! so that their resultant follows Johnson and Vermeulen's cubic:
//!
//! ```text
//! F' = √(F_x'² + F_y'²),  β = F' / (μQ)
//! F  = μQ (β − β²/3 + β³/27)   for β < 3,   F = μQ   for β ≥ 3
//! ε  = F / F' = 1 − β/3 + β²/27   (β < 3),   ε = 1/β   (β ≥ 3)
//! F_x = ε F_x',  F_y = ε F_y'
//! ```
//!
//! Spin therefore enters the saturation only through its lateral force −G c³ C23 φ. The paper
//! saturates the forces only, so the model has no spin moment (`spin_moment` is `None`): the
//! linear M_z' scaled by ε is not bounded (for a/b → 0, C33 grows like 1/g while F' stays small).
//! The curve is continuous with a continuous slope at β = 3.

use crate::creep_force_model::{dual_derivative, NoForceBoundary};
use crate::models::kalker_linear::LinearTheory;
use crate::models::rung::Rung;
use crate::numerics::{magnitude, value, Scalar};
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, ModelChoice};

/// β at which the cubic reaches μQ with zero slope.
const FULL_SLIP_RATIO: f64 = 3.0;

/// Shen–Hedrick–Elkins: Kalker's linear forces with a cubic saturation to μQ.
///
/// On the contact of [`KalkerLinear`](crate::KalkerLinear)'s example (μQ = 24.6 kN, G ab C11 =
/// 13.383 MN): the linear force F' at β = F'/(μQ) = 1.5 becomes μQ(β − β²/3 + β³/27) =
/// 0.875 μQ = 21 525 N, and μQ from β = 3 on:
///
/// ```
/// use wheel_rail_contact::{ContactInput, CreepForceModel, ShenHedrickElkins};
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
/// let stiffness = 82e9 * 32e-6 * 5.10;
/// let at = |beta: f64| ShenHedrickElkins.creep_forces(&contact(beta * 24.6e3 / stiffness, 0.0, 0.0)).unwrap();
/// assert!((at(1.5).force_longitudinal + 21525.0).abs() < 1e-6);
/// assert!((at(4.0).force_longitudinal + 24.6e3).abs() < 1e-6 && at(4.0).adhesion_utilisation == 1.0);
/// assert_eq!(at(1.5).spin_moment, None, "the paper saturates the forces only");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShenHedrickElkins;

/// Shen–Hedrick–Elkins' rung of the ladder.
pub const RUNG: Rung = Rung {
    name: "shen_hedrick_elkins",
    fmu_value: 3,
    type_name: "ShenHedrickElkins",
    fmu_parameters: &[],
    spin_moment: false,
    friction_limited: true,
    offline: false,
    summary: "the linear forces with a cubic saturation to μQ",
    source: "Shen, Hedrick & Elkins 1983",
    documentation: "Shen, Hedrick &amp; Elkins (1983): the linear forces scaled so that their
resultant follows F = μQ(β − β²/3 + β³/27), β = F′/(μQ) &lt; 3, else μQ. No spin moment: <code>spin_moment</code> = 0.",
    default_model: || Ok(ModelChoice::ShenHedrickElkins(ShenHedrickElkins)),
};

impl CreepForceModel for ShenHedrickElkins {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        Ok(saturated_forces(input))
    }

    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        dual_derivative(input, direction, NoForceBoundary::Continuous, saturated_forces)
    }
}

/// The saturated forces for a validated input, over any [`Scalar`].
fn saturated_forces<D: Scalar>(input: &ContactInput<D>) -> CreepForces<D> {
    if input.transmits_no_force() {
        return CreepForces::zero();
    }
    let (fx, fy) = LinearTheory::new(input).forces(input);
    let limit = input.friction_limit();
    // |F'| scaled by its largest component, so that neither square overflows.
    let largest = value(fx).abs().max(value(fy).abs());
    if largest == 0.0 {
        return CreepForces::zero();
    }
    let (unit_x, unit_y) = (fx / largest, fy / largest);
    let unit_norm = magnitude(unit_x, unit_y);
    let beta = D::from(largest) / limit * unit_norm;
    if value(beta) < FULL_SLIP_RATIO {
        let factor = -beta / 3.0 + beta * beta / 27.0 + 1.0;
        CreepForces::new(fx * factor, fy * factor, None, limit)
    } else {
        // Full slip: F = μQ along F'.
        CreepForces::new(limit * unit_x / unit_norm, limit * unit_y / unit_norm, None, limit)
    }
}

/// Nothing carried from one evaluation to the next: a closed form of the input.
impl crate::models::sequence::SequenceModel for ShenHedrickElkins {
    type Memory = ();
    type Cache = ();
}
