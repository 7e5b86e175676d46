//! Polach's fast analytical creep-force law (Polách, "Solution of wheel-rail contact forces
//! suitable for calculation of rail vehicle dynamics"; equation numbers below are the paper's,
//! E-numbers are `ERRATA.md`'s corrections, kept with the project's docs).
//!
//! The creep force is Freibauer's closed-form integral of a Hertzian traction bound over an
//! elliptic contact with a linear adhesion zone (eq. 14). Spin adds a lateral force from the
//! a/b → 0 solution (eqs. 16–20), corrected for finite a/b by K_S (eq. 24). The stiffness that
//! sets the gradient ε comes either from Kalker's linear theory (eqs. 26–32) or from a measured
//! creep curve (eqs. 33–36, see [`MeasuredCurve`]).

use std::f64::consts::PI;

use crate::numerics::magnitude;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, KalkerCoefficients, MeasuredCurve};

/// Largest gradient ε used. Beyond it the force is saturated to within 1e-150 relative, and
/// ε² stays finite, so `ε/(1+ε²)` and `(1+ε²)²` can neither overflow nor become NaN.
const GRADIENT_MAX: f64 = 1e150;
/// Largest creepage magnitude used (ξ, η and aΦ are scaled down together beyond it): every model
/// is in full slip long before, and squares of creepages stay finite.
const CREEPAGE_MAX: f64 = 1e150;

/// Where the contact stiffness (the gradient ε of the tangential stress) comes from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum StiffnessSource {
    /// Kalker's linear theory: identical initial slope (eqs. 26–32 with E1, E2).
    #[default]
    Kalker,
    /// A measured creep curve's peak (eqs. 33–36, E7).
    MeasuredCurve(MeasuredCurve),
}

/// Polach's method with a choice of stiffness source.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Polach {
    /// Where the contact stiffness comes from.
    pub stiffness: StiffnessSource,
}

impl CreepForceModel for Polach {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        if input.transmits_no_force() {
            return Ok(CreepForces::default());
        }
        let a = input.semi_axis_a;
        let b = input.semi_axis_b;
        // μQ formed once: every force below is μQ times a dimensionless factor, so |F| ≤ μQ holds
        // to rounding even where μQ is subnormal.
        let friction_limit = input.normal_force * input.friction_coefficient;
        // Spin as a creepage, aΦ (eq. 21); its product can overflow, so it is clamped first.
        let spin_shift = (input.spin_creepage * a).clamp(-CREEPAGE_MAX, CREEPAGE_MAX);
        let [xi, eta, spin_shift] =
            bounded_creepages([input.creepage_longitudinal, input.creepage_lateral, spin_shift]);

        // Eq. (21): spin counts towards the lateral creepage only where it enlarges it.
        let eta_with_spin = eta + spin_shift;
        let s_yc = if eta_with_spin.abs() > eta.abs() { eta_with_spin } else { eta };
        // Eq. (22): resulting creepage.
        let s_c = magnitude(xi, s_yc);
        if s_c == 0.0 {
            return Ok(CreepForces::default()); // E6: no creepage, no force.
        }
        // Eq. (24): finite-a/b correction of the spin force.
        let k_s = 1.0 + 6.3 * (1.0 - (-a / b).exp());

        // ε = κ·s_C (eq. 7) and ε_s = κ_s·|s_yC| (eq. 25); `friction_ratio` is k of eq. (34).
        let (kappa, kappa_spin, friction_ratio) = match &self.stiffness {
            StiffnessSource::Kalker => {
                let c = KalkerCoefficients::new(a / b, input.poisson_ratio);
                // E3: ε = π G a b c_jj s_C / (4 Q f), from eq. (7) with C of eq. (28).
                let kappa = PI * input.shear_modulus * a * b * direction_weighted_c(xi, eta, c.c11, c.c22)
                    / (4.0 * friction_limit);
                // E2: ε_s = (8/3) G b √(ab) c23 |s_yC| / (Q f K_S), eq. (25) with C_s of eq. (32).
                let kappa_spin = 8.0 / 3.0 * input.shear_modulus * b * (a * b).sqrt() * c.c23 / (friction_limit * k_s);
                (kappa, kappa_spin, 1.0)
            }
            StiffnessSource::MeasuredCurve(curve) => {
                let kappa = curve.gradient_per_creepage(input.friction_coefficient);
                (kappa, kappa / k_s, curve.friction_ratio())
            }
        };
        // `min` also maps a NaN (0/0 from underflowing products) to the saturated end.
        let epsilon = (kappa * s_c).min(GRADIENT_MAX);
        let epsilon_spin = (kappa_spin * s_yc.abs()).min(GRADIENT_MAX);

        // Eq. (14), generalised to eq. (34) by k (k = 1 reproduces eq. 14 bit for bit).
        let k = friction_ratio;
        // For k = 1 the factor rises monotonically to 1; for a measured curve (k > 1) it peaks at
        // F_max/(Q f_k) ≤ 1 + 1/π and then falls back to 1.
        let saturation = 2.0 / PI * (k * epsilon / (k * k + epsilon * epsilon) + epsilon.atan());
        let force = friction_limit * saturation;
        // Eq. (3) with the sign convention E4: forces oppose the creepages.
        let force_longitudinal = -force * (xi / s_c);
        let force_lateral_creep = -force * (eta / s_c);
        // Eqs. (23), (24): spin's lateral force, with K_M of eq. (20) in closed form. The factor
        // a·Φ/s_C is `spin_shift / s_c`, and |a·Φ| ≤ 2·s_C by eq. (21), so it is bounded.
        let force_lateral_spin =
            9.0 / 16.0 * friction_limit * spin_moment_factor(epsilon_spin) * k_s * (spin_shift / s_c);
        let force_lateral = force_lateral_creep + force_lateral_spin;
        Ok(CreepForces::new(force_longitudinal, force_lateral, None, friction_limit))
    }
}

/// K_M of eq. (20) for gradient ε ≥ 0, in closed form.
///
/// With δ = (ε²−1)/(ε²+1) (eq. 12): 1 − δ = 2/(1+ε²), 1 + 2δ = (3ε²−1)/(1+ε²),
/// δ³/3 − δ²/2 + 1/6 = (1−δ)²(1+2δ)/6 and √(1−δ²) = 2ε/(1+ε²), so eq. (20) becomes
///
/// ```text
/// K_M = −(2/3) · ε / (1 + ε²)²
/// ```
///
/// exactly: no cancellation at any ε (the concern of E5), and |K_M| ≤ √3/8 (at ε = 1/√3).
pub fn spin_moment_factor(epsilon: f64) -> f64 {
    let d = 1.0 + epsilon * epsilon;
    -2.0 / 3.0 * (epsilon / d) / d
}

/// Eq. (29) as corrected by E1: c_jj = √((c11·s_x/s)² + (c22·s_y/s)²), s = √(s_x² + s_y²).
/// For s = 0 (pure spin) c_jj only multiplies s_x/s_C = s_y/s_C = 0 (E6): return c22.
fn direction_weighted_c(xi: f64, eta: f64, c11: f64, c22: f64) -> f64 {
    let largest = xi.abs().max(eta.abs());
    if largest == 0.0 {
        return c22;
    }
    // Scaled by the largest component so that neither square can underflow.
    let (x, y) = (xi / largest, eta / largest);
    ((c11 * c11 * x * x + c22 * c22 * y * y) / (x * x + y * y)).sqrt()
}

/// Scales the creepages (ξ, η, aΦ) by one common factor so that none exceeds CREEPAGE_MAX: their
/// direction, and so eq. (21), is kept; at that size the force is saturated either way.
fn bounded_creepages(creepages: [f64; 3]) -> [f64; 3] {
    let largest = creepages.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    if largest <= CREEPAGE_MAX {
        creepages
    } else {
        creepages.map(|c| c * (CREEPAGE_MAX / largest))
    }
}
