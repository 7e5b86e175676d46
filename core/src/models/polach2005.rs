//! Polach's extension for large creepages (Polach 2005, "Creep forces in simulations of traction
//! vehicles running on adhesion limit", Wear 258, 992–1000; docs/reference/polach-errata.md E8).
//!
//! Measured creep curves of locomotives fall beyond their peak and rise less steeply than
//! Kalker's theory predicts. Polach models both:
//!
//! ```text
//! μ(w) = μ0 · ((1 − A) e^{−B w} + A),        w = s_C · |V|   (slip velocity)
//! F = (2 Q μ / π) · ( k_A ε / (1 + (k_A ε)²) + arctan(k_S ε) ),  ε with μ(w)
//! ```
//!
//! with k_A the stiffness reduction in the adhesion area and k_S in the slip area,
//! 0 < k_S ≤ k_A ≤ 1. The initial slope is reduced by (k_A + k_S)/2.

use crate::numerics::Scalar;
use crate::InvalidInput;

/// The parameters of Polach's 2005 extension, validated.
///
/// Friction falls with the slip velocity w as μ(w) = μ0((1 − A)e^{−Bw} + A) (Polach 2005, eq.
/// 5): with the dry set (A = 0.4, B = 0.6 s/m) and μ0 = 0.55 it is 0.55 at rest, 0.55(0.6e^{−0.6}
/// + 0.4) = 0.4011 at 1 m/s and tends to 0.22:
///
/// ```
/// use wheel_rail_contact::models::polach2005::LargeCreepage;
/// use wheel_rail_contact::Polach2005;
///
/// let dry = Polach2005::DRY;
/// let mu0 = Polach2005::DRY_MAXIMUM_FRICTION;
/// assert_eq!((dry.adhesion_reduction(), dry.slip_reduction()), (1.0, 0.4));
/// assert_eq!(dry.friction(mu0, 0.0), 0.55);
/// assert!((dry.friction(mu0, 1.0) - 0.55 * (0.6 * (-0.6_f64).exp() + 0.4)).abs() < 1e-15);
/// assert!((dry.friction(mu0, 1e3) - 0.22).abs() < 1e-12);
/// assert_eq!(Polach2005::WET_MAXIMUM_FRICTION, 0.30);
/// assert_eq!(Polach2005::new(0.3, 0.1, 0.4, 0.2).unwrap(), Polach2005::WET);
/// // k_S must not exceed k_A: the error names it.
/// assert_eq!(Polach2005::new(0.3, 0.5, 0.4, 0.2).unwrap_err().variable, "slip_reduction_factor");
/// assert!(LargeCreepage::new(dry, 30.0).is_ok() && LargeCreepage::new(dry, f64::NAN).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polach2005 {
    adhesion_reduction: f64,
    slip_reduction: f64,
    friction_limit_ratio: f64,
    friction_decay: f64,
}

impl Polach2005 {
    /// Polach's recommended set for dry rails (Polach 2005; errata E8), to be used with μ0 = 0.55.
    pub const DRY: Self =
        Self { adhesion_reduction: 1.0, slip_reduction: 0.4, friction_limit_ratio: 0.4, friction_decay: 0.6 };
    /// μ0 of Polach's dry set.
    pub const DRY_MAXIMUM_FRICTION: f64 = 0.55;
    /// Polach's recommended set for wet rails (Polach 2005; errata E8), to be used with μ0 = 0.30.
    pub const WET: Self =
        Self { adhesion_reduction: 0.3, slip_reduction: 0.1, friction_limit_ratio: 0.4, friction_decay: 0.2 };
    /// μ0 of Polach's wet set.
    pub const WET_MAXIMUM_FRICTION: f64 = 0.30;

    /// k_A, k_S with 0 < k_S ≤ k_A ≤ 1; A = μ∞/μ0 in [0, 1]; B ≥ 0 [s/m].
    pub fn new(
        adhesion_reduction: f64,
        slip_reduction: f64,
        friction_limit_ratio: f64,
        friction_decay: f64,
    ) -> Result<Self, InvalidInput> {
        let in_range = |variable, value: f64, low: f64, high: f64, rule| {
            if value >= low && value <= high {
                Ok(())
            } else {
                Err(InvalidInput::new(variable, value, rule))
            }
        };
        in_range("adhesion_reduction_factor", adhesion_reduction, f64::MIN_POSITIVE, 1.0, "k_A must lie in (0, 1]")?;
        in_range(
            "slip_reduction_factor",
            slip_reduction,
            f64::MIN_POSITIVE,
            adhesion_reduction,
            "k_S must lie in (0, k_A]",
        )?;
        in_range("friction_limit_ratio", friction_limit_ratio, 0.0, 1.0, "A = mu_inf/mu_0 must lie in [0, 1]")?;
        in_range("friction_decay_rate", friction_decay, 0.0, f64::MAX, "B must be finite and >= 0 [s/m]")?;
        Ok(Self { adhesion_reduction, slip_reduction, friction_limit_ratio, friction_decay })
    }

    /// k_A: stiffness reduction in the adhesion area \[1\].
    pub fn adhesion_reduction(&self) -> f64 {
        self.adhesion_reduction
    }

    /// k_S: stiffness reduction in the slip area \[1\].
    pub fn slip_reduction(&self) -> f64 {
        self.slip_reduction
    }

    /// μ(w) = μ0((1 − A) e^{−B w} + A) for the maximum friction μ0 at zero slip velocity and slip
    /// velocity w ≥ 0 [m/s].
    pub fn friction<D: Scalar>(&self, maximum_friction: D, slip_velocity: D) -> D {
        let a = self.friction_limit_ratio;
        maximum_friction * ((slip_velocity * -self.friction_decay).exp() * (1.0 - a) + a)
    }
}

/// Polach 2005 applied at a rolling speed: the speed turns creepage into slip velocity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LargeCreepage {
    extension: Polach2005,
    rolling_speed: f64,
}

impl LargeCreepage {
    /// The extension at rolling speed V [m/s] (either sign; the slip velocity is w = s_C·|V|).
    pub fn new(extension: Polach2005, rolling_speed: f64) -> Result<Self, InvalidInput> {
        if rolling_speed.is_finite() {
            Ok(Self { extension, rolling_speed })
        } else {
            Err(InvalidInput::new("rolling_speed", rolling_speed, "must be finite"))
        }
    }

    /// Friction μ(w) and the reduction factors (k_A, k_S) for maximum friction μ0 and
    /// resulting creepage s_C.
    pub(crate) fn law<D: Scalar>(&self, maximum_friction: D, creepage: D) -> (D, f64, f64) {
        let friction = self.extension.friction(maximum_friction, creepage * self.rolling_speed.abs());
        (friction, self.extension.adhesion_reduction, self.extension.slip_reduction)
    }
}
