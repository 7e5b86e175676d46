//! Contact stiffness from a measured creep curve: Polach's eqs. (33)–(36), ERRATA E7.
//!
//! A measured curve is summarised by its peak adhesion F_max/Q, the creepage s_max at the peak,
//! and the kinetic friction f_k reached at large creepage. With different static and kinetic
//! friction, k = f_s/f_k (eq. 33), the force law becomes eq. (34):
//!
//! ```text
//! F = (2 Q f_k / π) · ( k ε/(k² + ε²) + arctan ε ),
//! ```
//!
//! which peaks at ε_max(k) of eq. (35). Solving F(ε_max(k)) = F_max for k gives the curve's
//! shape; eq. (36) then gives the stiffness C that puts the peak at s_max.
//!
//! The peak value F_max/(Q f_k) = (2/π)(k ε/(k²+ε²) + arctan ε) at ε_max grows monotonically from
//! 1 (k → 1⁺) to 1 + 1/π (k → ∞), so a curve exists exactly for f_k < F_max/Q < (1 + 1/π) f_k.

use std::f64::consts::{FRAC_1_PI, PI};
use std::fmt;

use crate::numerics::Scalar;

/// Bracket of t = k − 1 searched for the friction ratio. Below 1e-15 the peak is
/// indistinguishable from f_k in double precision; above 1e12, from (1 + 1/π) f_k.
const RATIO_EXCESS_RANGE: (f64, f64) = (1e-15, 1e12);

/// A creep curve fitted to a measured peak, ready to set Polach's stiffness.
///
/// A peak F_max/Q = 0.36 at s_max = 3e-3 with kinetic friction 0.3: eqs. (33)–(35) solved by an
/// independent script (`core/tests/data/paper_hand_values.py`: k = f_s/f_k = 4.459546, ε_max =
/// 6.276695), and eq. (36)'s C = 3 Q f_k ε_max / (2π a² b s_max):
///
/// ```
/// use wheel_rail_contact::{MeasuredCurve, MeasuredCurveError};
///
/// let curve = MeasuredCurve::from_peak(0.36, 3e-3, 0.3).unwrap();
/// assert!((curve.friction_ratio() - 4.45954602211261).abs() < 1e-7);
/// assert!((curve.gradient_at_peak() - 6.276695363863038).abs() < 1e-6);
/// let (q, a, b) = (82e3, 8e-3, 4e-3);
/// let expected = 3.0 * q * 0.3 * curve.gradient_at_peak() / (2.0 * std::f64::consts::PI * a * a * b * 3e-3);
/// assert!((curve.contact_stiffness(q, a, b) / expected - 1.0).abs() < 1e-12);
/// // A peak below the kinetic friction has no rising curve to fit.
/// assert!(matches!(MeasuredCurve::from_peak(0.2, 3e-3, 0.3), Err(MeasuredCurveError::PeakNotAboveKineticFriction { .. })));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredCurve {
    friction_ratio: f64,
    gradient_at_peak: f64,
    creepage_at_peak: f64,
    kinetic_friction: f64,
}

/// Why a measured curve cannot be fitted; names the parameter and the offending value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeasuredCurveError {
    /// A value is NaN, infinite, or not positive.
    NotPositive { variable: &'static str, value: f64 },
    /// F_max/Q ≤ f_k: eq. (34) has no interior maximum (E7).
    PeakNotAboveKineticFriction { peak_adhesion: f64, kinetic_friction: f64 },
    /// F_max/Q ≥ (1 + 1/π)·f_k: beyond the largest peak eq. (34) can form, for any k.
    PeakTooHigh { peak_adhesion: f64, largest_possible: f64 },
}

impl fmt::Display for MeasuredCurveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NotPositive { variable, value } => {
                write!(f, "{variable} = {value} is invalid: must be finite and > 0")
            }
            Self::PeakNotAboveKineticFriction { peak_adhesion, kinetic_friction } => write!(
                f,
                "measured_peak_adhesion = {peak_adhesion} is invalid: a creep curve with a peak needs \
                 F_max/Q > f_k = measured_kinetic_friction = {kinetic_friction} (Polach eq. 34)"
            ),
            Self::PeakTooHigh { peak_adhesion, largest_possible } => write!(
                f,
                "measured_peak_adhesion = {peak_adhesion} is invalid: Polach's eq. (34) peaks at most at \
                 (1 + 1/pi)·f_k = {largest_possible}"
            ),
        }
    }
}

impl std::error::Error for MeasuredCurveError {}

impl MeasuredCurve {
    /// Fits the curve to a measured peak adhesion F_max/Q \[1\] at creepage s_max \[1\], with kinetic
    /// friction f_k \[1\] at large creepage.
    pub fn from_peak(
        peak_adhesion: f64,
        creepage_at_peak: f64,
        kinetic_friction: f64,
    ) -> Result<Self, MeasuredCurveError> {
        for (variable, value) in [
            ("measured_peak_adhesion", peak_adhesion),
            ("measured_creepage_at_peak", creepage_at_peak),
            ("measured_kinetic_friction", kinetic_friction),
        ] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(MeasuredCurveError::NotPositive { variable, value });
            }
        }
        // Target of F_max/(Q f_k) − 1, formed without cancellation.
        let target_excess = (peak_adhesion - kinetic_friction) / kinetic_friction;
        if target_excess <= 0.0 {
            return Err(MeasuredCurveError::PeakNotAboveKineticFriction { peak_adhesion, kinetic_friction });
        }
        if target_excess >= FRAC_1_PI {
            return Err(MeasuredCurveError::PeakTooHigh {
                peak_adhesion,
                largest_possible: (1.0 + FRAC_1_PI) * kinetic_friction,
            });
        }
        let excess = solve_increasing(|t| peak_excess(1.0 + t), target_excess, RATIO_EXCESS_RANGE);
        let friction_ratio = 1.0 + excess;
        Ok(Self {
            friction_ratio,
            gradient_at_peak: gradient_at_peak(friction_ratio),
            creepage_at_peak,
            kinetic_friction,
        })
    }

    /// k = f_s/f_k of eq. (33) \[1\].
    pub fn friction_ratio(&self) -> f64 {
        self.friction_ratio
    }

    /// ε_max of eq. (35) \[1\].
    pub fn gradient_at_peak(&self) -> f64 {
        self.gradient_at_peak
    }

    /// Contact stiffness C of eq. (36) [N/m³] for a contact with normal force Q \[N\] and semi-axes
    /// a, b \[m\]: C = 3 Q f_k ε_max / (2 π a² b s_max).
    pub fn contact_stiffness(&self, normal_force: f64, semi_axis_a: f64, semi_axis_b: f64) -> f64 {
        3.0 * normal_force * self.kinetic_friction * self.gradient_at_peak
            / (2.0 * PI * semi_axis_a * semi_axis_a * semi_axis_b * self.creepage_at_peak)
    }

    /// dε/ds for the friction coefficient μ of the scene: eq. (7) with C of eq. (36),
    /// ε = (2/3) C π a² b s / (Q μ) = ε_max · (s/s_max) · (f_k/μ).
    ///
    /// C is taken at the scene's own Q, a, b: under Hertz scaling a²b/Q does not change with the
    /// load, so the curve peaks at s_max for every load, and at μ = f_k it is the measured curve.
    pub(crate) fn gradient_per_creepage<D: Scalar>(&self, friction_coefficient: D) -> D {
        D::from(self.gradient_at_peak * self.kinetic_friction) / (friction_coefficient * self.creepage_at_peak)
    }
}

/// ε_max² from eq. (35): the root of dF/dε = 0 for eq. (34), k > 1.
fn gradient_at_peak(k: f64) -> f64 {
    let discriminant = (((k + 8.0) * k + 2.0) * k - 8.0) * k + 1.0;
    (k / (2.0 * (k - 1.0)) * (k * k + 2.0 * k - 1.0 + discriminant.sqrt())).sqrt()
}

/// F_max/(Q f_k) − 1 for friction ratio k, written as (2/π)(kε/(k²+ε²) − arctan(1/ε))
/// using arctan ε = π/2 − arctan(1/ε), so that no 1 is subtracted from a number near 1.
fn peak_excess(k: f64) -> f64 {
    let e = gradient_at_peak(k);
    2.0 / PI * (k * e / (k * k + e * e) - (1.0 / e).atan())
}

/// Solves increasing(x) = target on [low, high] (both > 0) by bisection in log x, to the last
/// bit of x. Targets outside the bracket's values give the nearer end.
fn solve_increasing(increasing: impl Fn(f64) -> f64, target: f64, (mut low, mut high): (f64, f64)) -> f64 {
    loop {
        let middle = (low * high).sqrt();
        if middle <= low || middle >= high {
            return middle;
        }
        if increasing(middle) < target {
            low = middle;
        } else {
            high = middle;
        }
    }
}
