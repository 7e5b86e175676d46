//! The state of one contact patch: what every creep-force model takes as input.

use crate::invalid_input::InvalidInput;
use crate::numerics::{value, Scalar};

/// One contact patch, in SI units.
///
/// Axes follow Kalker: x in the rolling direction, y lateral, z normal into the wheel.
/// Creepages are rigid-slip velocities divided by the rolling speed.
///
/// `T` is `f64` for values; models evaluate a dual-number `ContactInput` to differentiate.
///
/// ```
/// use wheel_rail_contact::ContactInput;
///
/// let contact = ContactInput {
///     creepage_longitudinal: 0.002,
///     creepage_lateral: 0.0,
///     spin_creepage: 0.0,
///     normal_force: 100e3,
///     semi_axis_a: 7.2e-3,
///     semi_axis_b: 5.4e-3,
///     friction_coefficient: 0.3,
///     shear_modulus: 82e9,
///     poisson_ratio: 0.28,
/// };
/// assert!(contact.validate().is_ok() && !contact.transmits_no_force());
/// assert_eq!(contact.friction_limit(), 30e3);
/// // Hertz's p₀ = 3Q/(2πab) (Johnson, eq. 3.65): 1.228 GPa.
/// let p0 = 3.0 * 100e3 / (2.0 * std::f64::consts::PI * 7.2e-3 * 5.4e-3);
/// assert!((contact.max_pressure() - p0).abs() < 1e-3 && (p0 - 1.228e9).abs() < 1e6);
/// // Lifted off: valid, no force. A bad value: an error naming it.
/// let lifted = ContactInput { normal_force: -10.0, ..contact };
/// assert!(lifted.validate().is_ok() && lifted.transmits_no_force() && lifted.friction_limit() == 0.0);
/// let error = ContactInput { semi_axis_b: f64::NAN, ..contact }.validate().unwrap_err();
/// assert_eq!(error.to_string(), "semi_axis_b = NaN is invalid: must be finite and > 0");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactInput<T = f64> {
    /// Longitudinal creepage ξ (s_x in Polach) \[1\].
    pub creepage_longitudinal: T,
    /// Lateral creepage η (s_y in Polach) \[1\].
    pub creepage_lateral: T,
    /// Spin creepage φ (Φ in Polach) [1/m].
    pub spin_creepage: T,
    /// Normal force Q \[N\]. Q ≤ 0 means the wheel has lifted off: every model returns zero force.
    pub normal_force: T,
    /// Contact-ellipse semi-axis a in the rolling direction \[m\].
    pub semi_axis_a: T,
    /// Contact-ellipse semi-axis b in the lateral direction \[m\].
    pub semi_axis_b: T,
    /// Coulomb friction coefficient μ (f in Polach) \[1\]. μ = 0 gives zero force.
    pub friction_coefficient: T,
    /// Combined shear modulus G of wheel and rail \[Pa\].
    pub shear_modulus: T,
    /// Combined Poisson's ratio ν \[1\], in [0, 0.5].
    pub poisson_ratio: T,
}

impl ContactInput {
    /// Checks every value; the error names the first offending variable and its value.
    ///
    /// Not errors: Q ≤ 0 (lift-off) and μ = 0 (no friction); both give zero force.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        // Straight-line checks: this runs on every evaluation, the error is built off the hot path.
        finite("creepage_longitudinal", self.creepage_longitudinal)?;
        finite("creepage_lateral", self.creepage_lateral)?;
        finite("spin_creepage", self.spin_creepage)?;
        finite("normal_force", self.normal_force)?;
        positive("semi_axis_a", self.semi_axis_a)?;
        positive("semi_axis_b", self.semi_axis_b)?;
        positive("shear_modulus", self.shear_modulus)?;
        check(
            "friction_coefficient",
            self.friction_coefficient,
            (0.0..=f64::MAX).contains(&self.friction_coefficient),
            "must be finite and >= 0",
        )?;
        check("poisson_ratio", self.poisson_ratio, (0.0..=0.5).contains(&self.poisson_ratio), "must lie in [0, 0.5]")?;
        // Each finite, yet μQ could overflow: the Coulomb limit itself must be a number.
        check(
            "friction_coefficient",
            self.friction_coefficient,
            self.normal_force <= 0.0 || self.friction_coefficient * self.normal_force <= f64::MAX,
            "times normal_force (the Coulomb limit μQ) must be finite",
        )
    }
}

impl<T: Scalar> ContactInput<T> {
    /// True when no tangential force can be transmitted: lift-off (Q ≤ 0) or μ = 0.
    pub fn transmits_no_force(&self) -> bool {
        value(self.normal_force) <= 0.0 || value(self.friction_coefficient) == 0.0
    }

    /// Hertz's maximum pressure p₀ = 3Q/(2πab) of this ellipse \[Pa\], 0 after lift-off.
    pub fn max_pressure(&self) -> T {
        hertz_max_pressure(self.normal_force, self.semi_axis_a, self.semi_axis_b)
    }

    /// The Coulomb limit μQ \[N\] (0 after lift-off).
    pub fn friction_limit(&self) -> T {
        if self.transmits_no_force() {
            T::from(0.0)
        } else {
            self.friction_coefficient * self.normal_force
        }
    }
}

/// Hertz's maximum pressure p₀ = 3Q/(2πab) \[Pa\] of an elliptic contact under normal force Q
/// (Johnson 1985, eq. 3.65: Q is the integral of the semi-ellipsoidal pressure), 0 after
/// lift-off (Q ≤ 0).
pub(crate) fn hertz_max_pressure<T: Scalar>(normal_force: T, semi_axis_a: T, semi_axis_b: T) -> T {
    if value(normal_force) > 0.0 {
        normal_force * 3.0 / (semi_axis_a * (2.0 * std::f64::consts::PI)) / semi_axis_b
    } else {
        T::from(0.0)
    }
}

fn finite(variable: &'static str, value: f64) -> Result<(), InvalidInput> {
    check(variable, value, value.is_finite(), "must be finite")
}

fn positive(variable: &'static str, value: f64) -> Result<(), InvalidInput> {
    // Two float comparisons (NaN fails both), cheaper than `> 0.0 && is_finite()`.
    check(variable, value, value > 0.0 && value <= f64::MAX, "must be finite and > 0")
}

#[inline(always)]
fn check(variable: &'static str, value: f64, valid: bool, requirement: &'static str) -> Result<(), InvalidInput> {
    if valid {
        Ok(())
    } else {
        Err(InvalidInput::new(variable, value, requirement))
    }
}

#[cfg(test)]
mod tests {
    use super::hertz_max_pressure;

    /// p₀ = 3Q/(2πab) where a·b underflows (a = 1e-200, b = 1e-120 m; Q = 1e-20 N): still to
    /// full precision, 3/(2π)·1e300 Pa (3/(2π) = 0.477464829275686 by hand), not a quotient of a
    /// subnormal product.
    #[test]
    fn max_pressure_where_the_area_underflows() {
        let p0 = hertz_max_pressure(1e-20, 1e-200, 1e-120);
        let expected = 0.477_464_829_275_686e300;
        assert!((p0 - expected).abs() <= 1e-14 * expected, "{p0:e} against {expected:e}");
    }

    /// The usual case: Q = 100 kN on a = 7.2, b = 5.4 mm: 3Q/(2πab) = 1.228047400400427 GPa
    /// (by hand), to rounding.
    #[test]
    fn max_pressure_of_a_wheel_patch() {
        let p0 = hertz_max_pressure(100e3, 7.2e-3, 5.4e-3);
        assert!((p0 - 1.228_047_400_400_427e9).abs() <= 1e-6, "{p0}");
        assert_eq!(hertz_max_pressure(0.0, 7.2e-3, 5.4e-3), 0.0, "lift-off");
    }
}
