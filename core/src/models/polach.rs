//! Polach's fast analytical creep-force law (Polách, "Solution of wheel-rail contact forces
//! suitable for calculation of rail vehicle dynamics"; equation numbers below are the paper's,
//! E-numbers are the corrections in docs/reference/polach-errata.md).
//!
//! The creep force is Freibauer's closed-form integral of a Hertzian traction bound over an
//! elliptic contact with a linear adhesion zone (eq. 14). Spin adds a lateral force from the
//! a/b → 0 solution (eqs. 16–20), corrected for finite a/b by K_S (eq. 24). The stiffness that
//! sets the gradient ε comes either from Kalker's linear theory (eqs. 26–32) or from a measured
//! creep curve (eqs. 33–36, see [`MeasuredCurve`]).

use std::f64::consts::PI;

use crate::creep_force_model::{dual_derivative, NoForceBoundary};
use crate::models::polach2005::LargeCreepage;
use crate::models::rung::Rung;
use crate::numerics::{magnitude, value, Scalar};
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, KalkerCoefficients, MeasuredCurve, ModelChoice};

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

/// Polach's method with a choice of stiffness source and, optionally, his 2005 extension.
///
/// Pure spin Φ = 1 /m on a = 8 mm, b = 4 mm, Q = 82 kN, μ = 0.3, G = 82 GPa, ν = 0.25: eqs.
/// (21)–(25) (with ERRATA E2, E4) give K_S = 6.4474, ε_s = 0.65387, K_M = −0.21390 and F_y =
/// −19 083.66 N, computed by hand outside the code (`core/tests/data/paper_hand_values.py`), half of
/// Kalker's linear value: the spin force saturates.
///
/// ```
/// use wheel_rail_contact::models::polach::{spin_moment_factor, PolachShape, ShapeCache};
/// use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};
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
/// let spin = Polach::default().creep_forces(&contact(0.0, 0.0, 1.0)).unwrap();
/// assert!((spin.force_lateral / -19083.659328199366 - 1.0).abs() < 1e-9);
/// assert_eq!((spin.force_longitudinal, spin.spin_moment), (0.0, None));
/// // Eq. (20)'s K_M in its closed form −(2/3) ε/(1 + ε²)².
/// assert!((spin_moment_factor(0.65387_f64) + 0.21390).abs() < 1e-5);
/// // The resulting creepage s_C (eqs. 21, 22): spin enlarging η counts, a·Φ = 8e-3.
/// assert!((Polach::resulting_creepage(0.0, 1e-3, 1.0, 8e-3) - 9e-3).abs() < 1e-15);
/// // Saturation: |F| → μQ at large creepage, bounded by it everywhere.
/// let sliding = Polach::default().creep_forces(&contact(0.5, 0.0, 0.0)).unwrap();
/// assert!(sliding.adhesion_utilisation > 0.99 && sliding.adhesion_utilisation <= 1.0);
/// // The same forces, bit for bit, with the shape factors cached across calls of one shape.
/// let mut cache = ShapeCache::default();
/// for xi in [1e-4, 1e-3, 1e-2] {
///     let cached = Polach::default().creep_forces_with_cache(&contact(xi, 0.0, 0.0), &mut cache).unwrap();
///     assert_eq!(cached, Polach::default().creep_forces(&contact(xi, 0.0, 0.0)).unwrap());
/// }
/// assert_eq!(PolachShape::new(2.0, 0.25), PolachShape::new(2.0, 0.25));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Polach {
    /// Where the contact stiffness comes from.
    pub stiffness: StiffnessSource,
    /// Polach's 2005 extension (friction falling with slip velocity, reduced stiffness); `None`
    /// is the original method and costs one branch.
    pub large_creepage: Option<LargeCreepage>,
}

/// Polach's rung of the ladder: the FMU's default model.
pub const RUNG: Rung = Rung {
    name: "polach",
    fmu_value: 1,
    type_name: "Polach",
    fmu_parameters: &["stiffness_source", "measured_peak_adhesion", "measured_creepage_at_peak", "measured_kinetic_friction"],
    spin_moment: false,
    friction_limited: true,
    offline: false,
    summary: "Polach's analytical solution, Kalker's or a measured curve's stiffness (`MeasuredCurve`), optional Polach 2005 falling friction (`LargeCreepage`)",
    source: "Polach 1999 (the paper in `docs/reference/`, equations cited by number, errata E1–E8)",
    documentation: "Polách's method, above. No spin moment: <code>spin_moment</code> = 0.",
    default_model: || Ok(ModelChoice::Polach(Polach::default())),
};

impl CreepForceModel for Polach {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        Ok(self.forces(input, None))
    }

    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        dual_derivative(input, direction, NoForceBoundary::Continuous, |dual| self.forces(dual, None))
    }
}

/// What Polach's method derives from the ellipse's shape alone — a/b and ν: Kalker's
/// coefficients and the spin correction K_S of eq. (24). Together about a third of an
/// evaluation, and constant while the shape is (given semi-axes, or Hertz with fixed curvatures).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolachShape {
    a_over_b: f64,
    poisson_ratio: f64,
    coefficients: KalkerCoefficients,
    spin_correction: f64,
}

impl PolachShape {
    /// The shape factors for semi-axis ratio a/b and Poisson's ratio ν.
    pub fn new(a_over_b: f64, poisson_ratio: f64) -> Self {
        Self {
            a_over_b,
            poisson_ratio,
            coefficients: KalkerCoefficients::new(a_over_b, poisson_ratio),
            spin_correction: spin_correction(a_over_b),
        }
    }

    /// Whether these are the factors of exactly this a/b and ν (bit for bit: no approximation).
    fn is_for(&self, a_over_b: f64, poisson_ratio: f64) -> bool {
        self.a_over_b.to_bits() == a_over_b.to_bits() && self.poisson_ratio.to_bits() == poisson_ratio.to_bits()
    }
}

/// A one-shape cache for [`Polach::creep_forces_with_cache`]: a scene that evaluates one contact
/// step after step keeps one and pays for the shape factors only when a/b or ν change.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShapeCache(Option<PolachShape>);

impl Polach {
    /// [`CreepForceModel::creep_forces`], bit for bit, reusing the shape factors in `cache` when
    /// the input's a/b and ν are the cached ones (and caching them otherwise).
    pub fn creep_forces_with_cache(
        &self,
        input: &ContactInput,
        cache: &mut ShapeCache,
    ) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        let (a_over_b, poisson_ratio) = (input.semi_axis_a / input.semi_axis_b, input.poisson_ratio);
        let shape = match &mut cache.0 {
            Some(shape) if shape.is_for(a_over_b, poisson_ratio) => shape,
            slot => slot.insert(PolachShape::new(a_over_b, poisson_ratio)),
        };
        Ok(self.forces(input, Some(shape)))
    }
}

/// K_S = 1 + 6.3 (1 − e^{−a/b}) of eq. (24): the finite-a/b correction of the spin force.
fn spin_correction<D: Scalar>(a_over_b: D) -> D {
    (-(-a_over_b).exp() + 1.0) * 6.3 + 1.0
}

impl Polach {
    /// Polach's resulting creepage s_C \[1\] of eqs. (21), (22), for creepages ξ, η \[1\], spin
    /// φ [1/m] and semi-axis a \[m\]: the spin counts towards the lateral creepage only where it
    /// enlarges it. Polach 2005's slip velocity is s_C·|V|. (Creepages beyond 1e150 are scaled
    /// down together, as in the force evaluation.)
    pub fn resulting_creepage(
        creepage_longitudinal: f64,
        creepage_lateral: f64,
        spin_creepage: f64,
        semi_axis_a: f64,
    ) -> f64 {
        resulting_creepage_at(creepage_longitudinal, creepage_lateral, spin_creepage, semi_axis_a)
    }

    /// The forces for a validated input, over any [`Scalar`]: `f64` for values, a dual number
    /// for their exact derivative. Branches look at values only.
    ///
    /// `shape`: a precomputed [`PolachShape`] to use if it is this input's (values only).
    fn forces<D: Scalar>(&self, input: &ContactInput<D>, shape: Option<&PolachShape>) -> CreepForces<D> {
        if input.transmits_no_force() {
            return CreepForces::zero();
        }
        let a = input.semi_axis_a;
        let b = input.semi_axis_b;
        let a_over_b = a / b;
        let poisson_ratio = value(input.poisson_ratio);
        // Dual numbers never take the cached shape: its values carry no derivative in a and b.
        let cached = shape.filter(|s| D::NDERIV == 0 && s.is_for(value(a_over_b), poisson_ratio));
        let ResultingCreepage { xi, eta, spin_shift, s_yc, s_c } =
            ResultingCreepage::new(input.creepage_longitudinal, input.creepage_lateral, input.spin_creepage, a);
        if value(s_c) == 0.0 {
            return CreepForces::zero(); // E6: no creepage, no force.
        }
        // Polach 2005: friction falls with the slip velocity w = s_C·|V|; k_A, k_S scale ε.
        let (friction, adhesion_reduction, slip_reduction) = match &self.large_creepage {
            None => (input.friction_coefficient, 1.0, 1.0),
            Some(large_creepage) => large_creepage.law(input.friction_coefficient, s_c),
        };
        // μQ formed once: every force below is μQ times a dimensionless factor, so |F| ≤ μQ holds
        // to rounding even where μQ is subnormal. (μQ can underflow to 0 for Q, μ > 0: no force.)
        let friction_limit = input.normal_force * friction;
        if value(friction_limit) == 0.0 {
            return CreepForces::zero();
        }
        // Reciprocals of quantities known from the inputs alone are formed up front, so that no
        // division waits for the coefficient lookup (the evaluation is latency-bound).
        let inverse_quarter_limit = (friction_limit * 4.0).recip();
        let direction = CreepDirection::new(xi, eta);
        let (xi_share, eta_share) = (xi / s_c, eta / s_c);

        // ε = κ·s_C (eq. 7); `law_adhesion` is 1/k of eq. (34).
        let (kappa, law_adhesion, kalker_c23) = match &self.stiffness {
            StiffnessSource::Kalker => {
                let c = match cached {
                    Some(shape) => shape.coefficients.map(D::from),
                    None => KalkerCoefficients::at(a_over_b, poisson_ratio),
                };
                // E3: ε = π G a b c_jj s_C / (4 Q f), from eq. (7) with C of eq. (28).
                let kappa = input.shear_modulus * PI * a * b * direction.weighted(c.c11, c.c22) * inverse_quarter_limit;
                (kappa, 1.0, Some(c.c23))
            }
            StiffnessSource::MeasuredCurve(curve) => {
                (curve.gradient_per_creepage(friction), 1.0 / curve.friction_ratio(), None)
            }
        };
        // The cap also maps a NaN (0/0 from underflowing products) to the saturated end.
        let epsilon = capped(kappa * s_c, GRADIENT_MAX);

        // One law covers eq. (14) (k_A = k_S = 1, bit for bit), eq. (34) (k_A = 1/k, since
        // kε/(k²+ε²) = (ε/k)/(1+(ε/k)²)) and Polach 2005 (its k_A, k_S; errata E8):
        //     F = μQ · (2/π) · ( k_A ε/(1 + (k_A ε)²) + arctan(k_S ε) ).
        // The factor rises monotonically to 1 for k_A = k_S = 1; otherwise it may peak above 1
        // (at most 1 + 1/π) and falls back towards 1 at large ε.
        let adhesion_gradient = epsilon * (law_adhesion * adhesion_reduction);
        let saturation = (adhesion_gradient / (adhesion_gradient * adhesion_gradient + 1.0)
            + (epsilon * slip_reduction).atan())
            * (2.0 / PI);
        // Forces as fractions of μQ. Eq. (3) with the sign convention E4: they oppose the creepages.
        let longitudinal = -saturation * xi_share;
        let mut lateral = -saturation * eta_share;
        // Eqs. (23)–(25): spin's lateral force. Without spin it is zero and is skipped (its
        // derivative in Φ is not zero, so dual numbers always evaluate it).
        if value(spin_shift) != 0.0 || D::NDERIV > 0 {
            let k_s = match cached {
                Some(shape) => D::from(shape.spin_correction),
                None => spin_correction(a_over_b),
            };
            let kappa_spin = match kalker_c23 {
                // E2: ε_s = (8/3) G b √(ab) c23 |s_yC| / (Q f K_S), eq. (25) with C_s of eq. (32).
                Some(c23) => {
                    input.shear_modulus * (8.0 / 3.0) * b * (a * b).sqrt() * c23 * inverse_quarter_limit * 4.0 / k_s
                }
                // Eq. (25) with the measured curve's C.
                None => kappa / k_s,
            };
            let epsilon_spin = capped(kappa_spin * s_yc.abs(), GRADIENT_MAX);
            // K_M of eq. (20) in closed form. The factor a·Φ/s_C is `spin_shift / s_c`, and
            // |a·Φ| ≤ 2·s_C by eq. (21), so it is bounded.
            lateral += spin_moment_factor(epsilon_spin) * (9.0 / 16.0) * k_s * (spin_shift / s_c);
        }
        CreepForces {
            force_longitudinal: friction_limit * longitudinal,
            force_lateral: friction_limit * lateral,
            spin_moment: None,
            adhesion_utilisation: magnitude(longitudinal, lateral),
        }
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
pub fn spin_moment_factor<D: Scalar>(epsilon: D) -> D {
    let d = epsilon * epsilon + 1.0;
    epsilon / d / d * (-2.0 / 3.0)
}

/// The direction of the creepage (ξ, η) without spin, for Kalker's direction-weighted
/// coefficient: eq. (29) as corrected by E1, c_jj = √((c11·s_x/s)² + (c22·s_y/s)²), s = √(s_x² + s_y²).
struct CreepDirection<D> {
    /// (s_x/m)², (s_y/m)² with m = max(|s_x|, |s_y|), so that neither square can underflow.
    squares: Option<(D, D)>,
    /// 1/((s_x/m)² + (s_y/m)²), formed before the coefficients are known.
    inverse_norm: D,
}

impl<D: Scalar> CreepDirection<D> {
    fn new(xi: D, eta: D) -> Self {
        let largest = value(xi).abs().max(value(eta).abs());
        if largest == 0.0 {
            return Self { squares: None, inverse_norm: D::from(1.0) };
        }
        let (x, y) = (xi / largest, eta / largest);
        let (x2, y2) = (x * x, y * y);
        Self { squares: Some((x2, y2)), inverse_norm: (x2 + y2).recip() }
    }

    /// c_jj. For s = 0 (pure spin) c_jj only multiplies s_x/s_C = s_y/s_C = 0 (E6): c22.
    fn weighted(&self, c11: D, c22: D) -> D {
        match self.squares {
            None => c22,
            Some((x2, y2)) => ((c11 * c11 * x2 + c22 * c22 * y2) * self.inverse_norm).sqrt(),
        }
    }
}

/// [`Polach::resulting_creepage`] over any [`Scalar`] (dual numbers give its derivative).
pub(crate) fn resulting_creepage_at<D: Scalar>(xi: D, eta: D, spin: D, semi_axis_a: D) -> D {
    ResultingCreepage::new(xi, eta, spin, semi_axis_a).s_c
}

/// The creepages of eqs. (21), (22) after the overflow guard.
struct ResultingCreepage<D> {
    xi: D,
    eta: D,
    /// aΦ, the spin as a lateral creepage.
    spin_shift: D,
    /// s_yC of eq. (21).
    s_yc: D,
    /// s_C of eq. (22).
    s_c: D,
}

impl<D: Scalar> ResultingCreepage<D> {
    fn new(xi: D, eta: D, spin: D, semi_axis_a: D) -> Self {
        // Spin as a creepage, aΦ (eq. 21); its product can overflow, so it is clamped first.
        let spin_shift = clamp_value(spin * semi_axis_a, CREEPAGE_MAX);
        let [xi, eta, spin_shift] = bounded_creepages([xi, eta, spin_shift]);
        // Eq. (21): spin counts towards the lateral creepage only where it enlarges it.
        let eta_with_spin = eta + spin_shift;
        let s_yc = if value(eta_with_spin).abs() > value(eta).abs() { eta_with_spin } else { eta };
        // Eq. (22): resulting creepage.
        Self { xi, eta, spin_shift, s_yc, s_c: magnitude(xi, s_yc) }
    }
}

/// Scales the creepages (ξ, η, aΦ) by one common factor so that none exceeds CREEPAGE_MAX: their
/// direction, and so eq. (21), is kept; at that size the force is saturated either way.
fn bounded_creepages<D: Scalar>(creepages: [D; 3]) -> [D; 3] {
    let largest = creepages.iter().fold(0.0_f64, |m, c| m.max(value(*c).abs()));
    if largest <= CREEPAGE_MAX {
        creepages
    } else {
        creepages.map(|c| c * (CREEPAGE_MAX / largest))
    }
}

/// `x` limited to [−limit, limit] by value (an infinite product becomes ±limit).
fn clamp_value<D: Scalar>(x: D, limit: f64) -> D {
    if value(x).abs() > limit {
        D::from(limit.copysign(value(x)))
    } else {
        x
    }
}

/// `x` capped at `limit` by value; NaN becomes `limit`, as `f64::min` does.
fn capped<D: Scalar>(x: D, limit: f64) -> D {
    if value(x) <= limit {
        x
    } else {
        D::from(limit)
    }
}

/// Polach's shape factors for the last a/b and ν are cached between evaluations ([`ShapeCache`]):
/// bit-identical results, paid only when the shape changes.
impl crate::models::sequence::SequenceModel for Polach {
    type Memory = ();
    type Cache = ShapeCache;

    #[inline]
    fn creep_forces_in_sequence(
        &self,
        input: &ContactInput,
        _memory: &(),
        cache: &mut ShapeCache,
    ) -> Result<crate::SequenceStep<()>, InvalidInput> {
        let forces = self.creep_forces_with_cache(input, cache)?;
        Ok(crate::SequenceStep { forces, memory: (), unconverged_grid: None })
    }
}

#[cfg(test)]
mod tests {
    use super::spin_moment_factor;

    /// Eq. (20) as printed, with δ of eq. (12).
    fn printed_eq_20(epsilon: f64) -> f64 {
        let delta = (epsilon * epsilon - 1.0) / (epsilon * epsilon + 1.0);
        epsilon * (delta.powi(3) / 3.0 - delta * delta / 2.0 + 1.0 / 6.0) - (1.0 - delta * delta).powf(1.5) / 3.0
    }

    /// ERRATA E5's cancellation-free form with h = 1 − δ = 2/(ε² + 1).
    fn errata_e5(epsilon: f64) -> f64 {
        let h = 2.0 / (epsilon * epsilon + 1.0);
        epsilon * h * h * (0.5 - h / 3.0) - (h * (2.0 - h)).powf(1.5) / 3.0
    }

    #[test]
    fn closed_form_equals_eq_20_and_e5() {
        for epsilon in [1e-3, 0.1, 0.5, 1.0 / 3f64.sqrt(), 1.0, 2.0, 5.0, 20.0] {
            let closed = spin_moment_factor(epsilon);
            assert!((closed - printed_eq_20(epsilon)).abs() < 1e-13, "eq. 20 at {epsilon}");
            assert!((closed - errata_e5(epsilon)).abs() < 1e-15, "E5 at {epsilon}");
        }
        // Hand values: ε = 1 → δ = 0 → K_M = 1/6 − 1/3; ε = 2 → δ = 0.6 → −0.053333….
        assert_eq!(spin_moment_factor(1.0_f64), -1.0 / 6.0);
        assert!((spin_moment_factor(2.0_f64) + 0.16 / 3.0).abs() < 1e-16);
    }

    #[test]
    fn large_gradients_keep_full_precision() {
        // K_M → −(2/3) ε⁻³; eq. (20) as printed has lost every digit here (E5).
        for epsilon in [1e3_f64, 1e6, 1e20, 1e100] {
            let asymptote = -2.0 / 3.0 / epsilon.powi(3);
            let relative = (spin_moment_factor(epsilon) / asymptote - 1.0).abs();
            assert!(relative < 3.0 / (epsilon * epsilon) + 1e-15, "ε = {epsilon}: {relative}");
        }
        assert_eq!(spin_moment_factor(1e150_f64), 0.0);
        assert!(spin_moment_factor(1e150_f64).is_sign_negative());
    }
}
