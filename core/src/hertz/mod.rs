//! Hertz normal contact: the contact ellipse, maximum pressure and approach from the normal load,
//! the relative curvatures of the undeformed surfaces and the elastic constants.
//!
//! Exact elliptic-integral solution (Hertz 1882; Johnson, *Contact Mechanics*, 1985, ch. 3 on
//! the Hertz pressure over an ellipse and §4.2), written with Carlson's symmetric integrals
//! (DLMF §19.16, 19.25.1), which need no eccentricity and lose no digits for slender ellipses.
//! For the pressure p = p0·√(1 − x²/a² − y²/b²) on an ellipse with semi-axis a along x and b
//! along y,
//!
//! ```text
//! A = Q·R_D(0, b², a²) / (2π E*),   B = Q·R_D(0, a², b²) / (2π E*),
//! p0 = 3Q / (2π a b),               δ = 3Q·R_F(0, a², b²) / (2π E*),
//! ```
//!
//! where A, B are the relative curvatures along x and y (the gap is A x² + B y²) and δ the
//! approach of distant points. They are Johnson's M/(πE*), N/(πE*), L/(πE*) with
//! (K − E)/e² = R_D(0, k², 1)/3, (E − k²K)/(e²k²) = R_D(0, 1, k²)/3 and K = R_F(0, k², 1),
//! k = b/a (Carlson), and they hold for either ordering of a and b. Dividing the first two,
//! the shape k = b/a is the root of
//!
//! ```text
//! R_D(0, 1, k²) / R_D(0, k², 1) = B / A,
//! ```
//!
//! strictly decreasing in k, so the semi-axis is longer along the flatter direction. By
//! homogeneity (R_D is of degree −3/2) a³ = Q·R_D(0, k², 1)/(2π E* A).
//!
//! **Which axis is which.** `semi_axis_a` always lies along the curvature given as `rolling`
//! (A, x, the rolling direction), `semi_axis_b` along `lateral` (B, y), matching
//! [`crate::ContactInput`]. Published tables often order the curvatures as A ≤ B and call the
//! longer semi-axis a; for the Eurosprinter case of CONTACT (`examples/tractcurv`: wheel
//! radius 0.625 m, so the rolling curvature is 1/(2·0.625 m) = 0.8 /m, and lateral 0.2814 /m)
//! this module gives a = 6.304 mm in the rolling direction and b = 12.61 mm, as CONTACT prints;
//! with the curvatures swapped the semi-axes swap.

pub(crate) mod table;

use std::f64::consts::PI;

use crate::contact_input::hertz_max_pressure;
use crate::InvalidInput;

/// Largest ratio of the two relative curvatures accepted (b/a ≈ 2.5·10⁻⁷ there). Hertz's
/// half-space theory has long lost its meaning before that; the bound keeps k² far from underflow.
const CURVATURE_RATIO_MAX: f64 = 1e12;
/// Root-finder tolerance on ln(b/a): a relative accuracy of the semi-axes near f64 resolution.
const SHAPE_TOLERANCE: f64 = 1e-14;
/// More than enough for the safeguarded secant on a monotone smooth function; a safety net only.
const SHAPE_ITERATIONS_MAX: usize = 200;

/// Relative curvatures of the undeformed wheel and rail surfaces at the contact point [1/m]:
/// the gap between them is A·x² + B·y² (x rolling, y lateral). Both must be > 0 (a
/// non-conformal, convex gap; Hertz's theory does not apply otherwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelativeCurvature {
    rolling: f64,
    lateral: f64,
}

impl RelativeCurvature {
    /// From the curvature sums A (`rolling`) and B (`lateral`) [1/m], i.e. half the sum of the
    /// two bodies' principal curvatures in each direction (Johnson §4.1, with A + B the
    /// half-sum of all four).
    pub fn new(rolling: f64, lateral: f64) -> Result<Self, InvalidInput> {
        for (variable, value) in [("curvature_rolling", rolling), ("curvature_lateral", lateral)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(InvalidInput::new(variable, value, "must be finite and > 0"));
            }
        }
        let ratio = lateral / rolling;
        if !(1.0 / CURVATURE_RATIO_MAX..=CURVATURE_RATIO_MAX).contains(&ratio) {
            return Err(InvalidInput::new(
                "curvature_lateral",
                lateral,
                "must lie within 1e-12 … 1e12 times curvature_rolling",
            ));
        }
        Ok(Self { rolling, lateral })
    }

    /// From the radii \[m\] of a wheel on a straight rail (the rail is flat in the rolling
    /// direction): A = 1/(2 r), B = (1/R_w + 1/R_r)/2.
    ///
    /// A radius is positive where the surface is convex (centre of curvature inside the body),
    /// negative where concave (a hollow-worn tread or the flange root), and ±∞ where the
    /// profile is straight (a conical tread). B must stay > 0: a concave wheel profile must be
    /// flatter than the rail head (|R_w| > R_r), otherwise the contact is conformal and not
    /// Hertzian. Off the tread, at contact angle γ, the wheel's curvature in the rolling
    /// direction is cos γ / r (Meusnier): pass r / cos γ as `wheel_rolling_radius` there.
    pub fn from_radii(
        wheel_rolling_radius: f64,
        wheel_profile_radius: f64,
        rail_profile_radius: f64,
    ) -> Result<Self, InvalidInput> {
        if !(wheel_rolling_radius > 0.0 && wheel_rolling_radius.is_finite()) {
            return Err(InvalidInput::new("wheel_rolling_radius", wheel_rolling_radius, "must be finite and > 0"));
        }
        for (variable, value) in
            [("wheel_profile_radius", wheel_profile_radius), ("rail_profile_radius", rail_profile_radius)]
        {
            if value.is_nan() || value == 0.0 {
                return Err(InvalidInput::new(variable, value, "must be non-zero (±inf for a straight profile)"));
            }
        }
        // 1/±inf = 0: a straight profile contributes no curvature.
        let lateral = 0.5 * (1.0 / wheel_profile_radius + 1.0 / rail_profile_radius);
        if lateral <= 0.0 {
            return Err(if wheel_profile_radius < 0.0 && rail_profile_radius > 0.0 {
                InvalidInput::new(
                    "wheel_profile_radius",
                    wheel_profile_radius,
                    "must leave a convex gap: a concave wheel profile needs |radius| > rail_profile_radius",
                )
            } else {
                // Not a concave wheel more curved than the rail: the rail is
                // straight or concave and the wheel does not make up for it.
                InvalidInput::new(
                    "rail_profile_radius",
                    rail_profile_radius,
                    "gives no contact ellipse: the combined lateral curvature (1/wheel_profile_radius + \
                     1/rail_profile_radius)/2 must be positive",
                )
                .involving([Some(("wheel_profile_radius", wheel_profile_radius)), None])
            });
        }
        Self::new(0.5 / wheel_rolling_radius, lateral)
    }

    /// From the signed profile curvatures [1/m] of wheel and rail in the lateral plane (> 0
    /// convex, < 0 concave, 0 straight) and the wheel's rolling radius \[m\], on a straight rail:
    /// A = 1/(2 r), B = (wheel_profile_curvature + rail_profile_curvature)/2, as
    /// [`RelativeCurvature::from_radii`]. These are the FMU's variables, and every error names
    /// them (never A or B) with their values and the reason.
    pub fn from_profile_curvatures(
        wheel_rolling_radius: f64,
        wheel_profile_curvature: f64,
        rail_profile_curvature: f64,
    ) -> Result<Self, InvalidInput> {
        let radius = ("wheel_rolling_radius", wheel_rolling_radius);
        let wheel = ("wheel_profile_curvature", wheel_profile_curvature);
        let rail = ("rail_profile_curvature", rail_profile_curvature);
        if !(wheel_rolling_radius > 0.0 && wheel_rolling_radius.is_finite()) {
            return Err(InvalidInput::new(radius.0, radius.1, "must be finite and > 0"));
        }
        let rolling = 0.5 / wheel_rolling_radius;
        if !rolling.is_finite() {
            return Err(InvalidInput::new(
                radius.0,
                radius.1,
                "must be large enough for a finite rolling curvature 1/(2·wheel_rolling_radius)",
            ));
        }
        for (variable, value) in [wheel, rail] {
            if !value.is_finite() {
                return Err(InvalidInput::new(variable, value, "must be finite"));
            }
        }
        // Halves first: no overflow for any finite curvatures.
        let lateral = 0.5 * wheel_profile_curvature + 0.5 * rail_profile_curvature;
        if lateral <= 0.0 {
            return Err(if wheel_profile_curvature < 0.0 && rail_profile_curvature > 0.0 {
                InvalidInput::new(
                    wheel.0,
                    wheel.1,
                    "gives no contact ellipse: a concave wheel profile must be flatter than the rail head \
                     (wheel_profile_curvature + rail_profile_curvature > 0), otherwise the contact is \
                     conformal, outside Hertz's theory",
                )
                .involving([Some(rail), None])
            } else {
                InvalidInput::new(
                    rail.0,
                    rail.1,
                    "gives no contact ellipse: the combined lateral curvature (wheel_profile_curvature + \
                     rail_profile_curvature)/2 must be positive (straight or concave profiles that do not \
                     close the gap touch along a line or conform)",
                )
                .involving([Some(wheel), None])
            });
        }
        let ratio = lateral / rolling;
        if ratio < 1.0 / CURVATURE_RATIO_MAX {
            return Err(InvalidInput::new(
                rail.0,
                rail.1,
                "gives too slender a contact ellipse (a/b below 2.5e-7): the combined lateral curvature \
                 (wheel_profile_curvature + rail_profile_curvature)/2 must be at least 1e-12 times the \
                 rolling curvature 1/(2·wheel_rolling_radius)",
            )
            .involving([Some(wheel), Some(radius)]));
        }
        if ratio > CURVATURE_RATIO_MAX {
            return Err(InvalidInput::new(
                radius.0,
                radius.1,
                "gives too slender a contact ellipse (b/a below 2.5e-7): the rolling curvature \
                 1/(2·wheel_rolling_radius) must be at least 1e-12 times the combined lateral curvature \
                 (wheel_profile_curvature + rail_profile_curvature)/2",
            )
            .involving([Some(wheel), Some(rail)]));
        }
        Ok(Self { rolling, lateral })
    }

    /// A, the relative curvature in the rolling direction [1/m].
    pub fn rolling(&self) -> f64 {
        self.rolling
    }

    /// B, the relative curvature in the lateral direction [1/m].
    pub fn lateral(&self) -> f64 {
        self.lateral
    }
}

/// Hertz's contact modulus E* \[Pa\] of two bodies of the same material, from the shear modulus G
/// and Poisson's ratio ν that [`crate::ContactInput`] carries: 1/E* = 2(1 − ν²)/E with
/// E = 2G(1 + ν), so E* = G/(1 − ν). For G = 82 GPa, ν = 0.28 this is 82000/(1 − 0.28) N/mm²,
/// the value of the issue's reference cases.
pub fn contact_modulus(shear_modulus: f64, poisson_ratio: f64) -> Result<f64, InvalidInput> {
    if !(shear_modulus > 0.0 && shear_modulus.is_finite()) {
        return Err(InvalidInput::new("shear_modulus", shear_modulus, "must be finite and > 0"));
    }
    if !(0.0..=0.5).contains(&poisson_ratio) {
        return Err(InvalidInput::new("poisson_ratio", poisson_ratio, "must lie in [0, 0.5]"));
    }
    Ok(shear_modulus / (1.0 - poisson_ratio))
}

/// The Hertzian contact of one wheel on one rail, SI units.
///
/// Equal curvatures A = B = 1/(2R) (a ball of radius R on a flat, or a wheel of radius R on a
/// rail head of the same crown radius) give a circle with Hertz's closed form (Johnson,
/// *Contact Mechanics*, eqs. 4.22–4.23): a³ = 3QR/(4E*), δ = a²/R, p₀ = 3Q/(2πa²):
///
/// ```
/// use wheel_rail_contact::hertz::{contact_modulus, HertzContact, RelativeCurvature};
///
/// // E* = G/(1 − ν) for two bodies of one steel.
/// let modulus = contact_modulus(82e9, 0.28).unwrap();
/// assert!((modulus - 82e9 / 0.72).abs() < 1.0);
/// let (load, radius) = (100e3, 0.46);
/// let wheel_on_crown = RelativeCurvature::from_radii(radius, f64::INFINITY, radius).unwrap();
/// assert_eq!((wheel_on_crown.rolling(), wheel_on_crown.lateral()), (0.5 / radius, 0.5 / radius));
/// let contact = HertzContact::solve(load, &wheel_on_crown, modulus).unwrap();
/// let a = (3.0 * load * radius / (4.0 * modulus)).cbrt();
/// assert!((contact.semi_axis_a / a - 1.0).abs() < 1e-9 && (contact.semi_axis_b / a - 1.0).abs() < 1e-9);
/// assert!((contact.approach / (a * a / radius) - 1.0).abs() < 1e-9);
/// assert!((contact.max_pressure / (3.0 * load / (2.0 * std::f64::consts::PI * a * a)) - 1.0).abs() < 1e-12);
/// // The FMU's variables (profile curvatures): the same gap, the same contact.
/// let same = RelativeCurvature::from_profile_curvatures(radius, 0.0, 1.0 / radius).unwrap();
/// assert_eq!(HertzContact::solve(load, &same, modulus).unwrap(), contact);
/// // Flatter across (B < A): the ellipse is longer across, b > a.
/// let ellipse = HertzContact::solve(load, &RelativeCurvature::new(1.0, 0.25).unwrap(), modulus).unwrap();
/// assert!(ellipse.semi_axis_b > ellipse.semi_axis_a);
/// // Lift-off is not an error, a concave gap is (naming the variable).
/// assert_eq!(HertzContact::solve(-1.0, &same, modulus).unwrap().semi_axis_a, 0.0);
/// let error = RelativeCurvature::from_radii(radius, -0.2, 0.3).unwrap_err();
/// assert_eq!(error.variable, "wheel_profile_radius");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HertzContact {
    /// Semi-axis a along the rolling direction (the `rolling` curvature) \[m\].
    pub semi_axis_a: f64,
    /// Semi-axis b along the lateral direction \[m\].
    pub semi_axis_b: f64,
    /// Maximum contact pressure p0 = 3Q/(2πab) \[Pa\].
    pub max_pressure: f64,
    /// Approach δ of distant points of wheel and rail \[m\].
    pub approach: f64,
}

impl HertzContact {
    /// Solves Hertz's problem for normal force Q \[N\], the relative curvatures and the contact
    /// modulus E* \[Pa\] (see [`contact_modulus`]).
    ///
    /// Q ≤ 0 (lift-off) is not an error: it gives a zero contact (a = b = p0 = δ = 0).
    pub fn solve(normal_force: f64, curvature: &RelativeCurvature, contact_modulus: f64) -> Result<Self, InvalidInput> {
        if !normal_force.is_finite() {
            return Err(InvalidInput::new("normal_force", normal_force, "must be finite"));
        }
        if !(contact_modulus > 0.0 && contact_modulus.is_finite()) {
            return Err(InvalidInput::new("contact_modulus", contact_modulus, "must be finite and > 0"));
        }
        if normal_force <= 0.0 {
            return Ok(Self { semi_axis_a: 0.0, semi_axis_b: 0.0, max_pressure: 0.0, approach: 0.0 });
        }
        let b_over_a = shape_ratio(curvature.lateral / curvature.rolling);
        // a³ = Q·R_D(0, k², 1)/(2π E* A); the cube roots are taken factor by factor so that no
        // intermediate product can overflow for any finite input.
        let load_per_stiffness = normal_force.cbrt() / (contact_modulus.cbrt() * curvature.rolling.cbrt());
        let shape_rd = carlson_rd(0.0, b_over_a * b_over_a, 1.0);
        let semi_axis_a = load_per_stiffness * (shape_rd / (2.0 * PI)).cbrt();
        let semi_axis_b = b_over_a * semi_axis_a;
        let max_pressure = hertz_max_pressure(normal_force, semi_axis_a, semi_axis_b);
        // δ = 3Q·R_F(0, a², b²)/(2π E*) = 3Q·R_F(0, 1, k²)/(2π E* a) by homogeneity (degree −1/2),
        // and Q/(2π E*) = a³A/R_D(0, k², 1) from a³ above: δ = 3a·(aA)·R_F(0, 1, k²)/R_D(0, k², 1).
        // Written in a and A, so δ underflows only where δ itself does (Q/E* alone can, e.g.
        // Q = 1e-280 N on E* = 1e97 Pa, while δ ≈ 1e-252 m).
        let shape_rf_over_rd = carlson_rf(0.0, 1.0, b_over_a * b_over_a) / shape_rd;
        let approach = 3.0 * semi_axis_a * (semi_axis_a * curvature.rolling) * shape_rf_over_rd;
        let contact = Self { semi_axis_a, semi_axis_b, max_pressure, approach };
        if [semi_axis_a, semi_axis_b, max_pressure, approach].iter().all(|value| value.is_finite() && *value > 0.0) {
            Ok(contact)
        } else {
            Err(InvalidInput::new(
                "normal_force",
                normal_force,
                "gives a contact beyond f64 range for these curvatures",
            ))
        }
    }
}

/// k = b/a for the curvature ratio B/A in [1e-12, 1e12].
///
/// The shape equation maps k → 1/k and B/A → A/B onto each other (R_D is homogeneous), so only
/// B/A ≥ 1 (k ≤ 1) is solved, and swapping the curvatures swaps the semi-axes exactly.
fn shape_ratio(lateral_over_rolling: f64) -> f64 {
    if lateral_over_rolling >= 1.0 {
        slender_shape_ratio(lateral_over_rolling)
    } else {
        1.0 / slender_shape_ratio(1.0 / lateral_over_rolling)
    }
}

/// Root k ≤ 1 of R_D(0, 1, k²)/R_D(0, k², 1) = `ratio` ≥ 1, found in u = ln k where the equation
/// is smooth and nearly linear (k ≈ ratio^{−2/3}, Johnson §4.2): bracketed, then the
/// Anderson–Björck safeguarded secant, which converges superlinearly and never leaves the bracket.
fn slender_shape_ratio(ratio: f64) -> f64 {
    if ratio == 1.0 {
        return 1.0; // a circle: exactly.
    }
    let log_ratio = ratio.ln();
    // Decreasing in u; ≤ 0 at u = 0 (k = 1, left side 1).
    let residual = |u: f64| {
        let k2 = (2.0 * u).exp();
        (carlson_rd(0.0, 1.0, k2) / carlson_rd(0.0, k2, 1.0)).ln() - log_ratio
    };
    let (mut u_high, mut r_high) = (0.0, -log_ratio);
    // The left side is below 1/k² (2E ≤ (1 + k²)K), so the root lies below u = −ln(ratio)/2 and
    // near the power-law guess; step down from the guess until the residual changes sign.
    let mut u_low = -2.0 / 3.0 * log_ratio;
    let mut r_low = residual(u_low);
    let mut step = 0.25 * log_ratio.max(1.0);
    while r_low < 0.0 {
        (u_high, r_high) = (u_low, r_low);
        u_low -= step;
        r_low = residual(u_low);
        step *= 2.0;
    }
    for _ in 0..SHAPE_ITERATIONS_MAX {
        if u_high - u_low <= SHAPE_TOLERANCE {
            break;
        }
        let u = (u_low * r_high - u_high * r_low) / (r_high - r_low);
        let r = residual(u);
        if r == 0.0 {
            return u.exp();
        }
        if r > 0.0 {
            // The root lies above u: u replaces the low end; damp the retained high end.
            let damping = 1.0 - r / r_low;
            r_high *= if damping > 0.0 { damping } else { 0.5 };
            (u_low, r_low) = (u, r);
        } else {
            let damping = 1.0 - r / r_high;
            r_low *= if damping > 0.0 { damping } else { 0.5 };
            (u_high, r_high) = (u, r);
        }
    }
    (0.5 * (u_low + u_high)).exp()
}

/// Carlson's R_D. The arguments used here (two of them > 0, k² > 1e-14) are always inside its
/// domain; a NaN would be caught by the finiteness check of [`HertzContact::solve`].
fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    ellip::elliprd(x, y, z).unwrap_or(f64::NAN)
}

/// Carlson's R_F, see [`carlson_rd`].
fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    ellip::elliprf(x, y, z).unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const MM: f64 = 1e-3;
    /// G = 82 GPa, ν = 0.28 → E* = 82000/(1 − 0.28) N/mm².
    fn steel() -> f64 {
        contact_modulus(82e9, 0.28).unwrap()
    }
    fn per_mm(value: f64) -> f64 {
        value / MM
    }
    /// |value − expected| within half a unit of the last of the 4 significant digits given.
    fn assert_four_digits(value: f64, expected: f64) {
        let unit = 10f64.powf(expected.abs().log10().floor() - 3.0);
        assert!((value - expected).abs() <= 0.5 * unit, "{value} ≠ {expected} to 4 digits");
    }
    fn solve(q: f64, rolling: f64, lateral: f64) -> HertzContact {
        HertzContact::solve(q, &RelativeCurvature::new(rolling, lateral).unwrap(), steel()).unwrap()
    }

    #[test]
    fn contact_modulus_is_the_issues_value() {
        assert_relative_eq!(steel(), 82000.0 / 0.72 * 1e6, max_relative = 1e-15);
    }

    /// Issue 5 / CONTACT `examples/fastsim`: a = 8 mm (rolling), b = 4 mm; p_max 1223 N/mm²,
    /// approach 9.266e-2 mm.
    #[test]
    fn fastsim_case_gives_8_by_4_mm() {
        let c = solve(82e3, per_mm(0.8464e-3), per_mm(2.406e-3));
        assert_four_digits(c.semi_axis_a / MM, 8.000);
        assert_four_digits(c.semi_axis_b / MM, 4.000);
        assert_four_digits(c.max_pressure / 1e6, 1223.0);
        // CONTACT's approach comes from its 40 × 40 element solution, not the closed form: it
        // agrees to 1e-4 (ours 9.2668e-2 mm), the discretisation error of that grid.
        assert_relative_eq!(c.approach / MM, 9.266e-2, max_relative = 1e-4);
    }

    /// Issue 5 / CONTACT `examples/tractcurv` (Eurosprinter): rolling curvature 1/(2·625 mm),
    /// lateral 0.2814e-3 /mm → a = 6.304 mm in the rolling direction, b = 12.61 mm.
    #[test]
    fn eurosprinter_case_gives_6_304_by_12_61_mm() {
        let c = solve(106.7e3, per_mm(0.8e-3), per_mm(0.2814e-3));
        assert_four_digits(c.semi_axis_a / MM, 6.304);
        assert_four_digits(c.semi_axis_b / MM, 12.61);
        // The issue's ordering (A, B) = (0.2814e-3, 0.8e-3) /mm swaps the axes exactly.
        let swapped = solve(106.7e3, per_mm(0.2814e-3), per_mm(0.8e-3));
        assert_relative_eq!(swapped.semi_axis_a, c.semi_axis_b, max_relative = 1e-14);
        assert_relative_eq!(swapped.semi_axis_b, c.semi_axis_a, max_relative = 1e-14);
        assert_relative_eq!(swapped.approach, c.approach, max_relative = 1e-14);
    }

    #[test]
    fn radii_on_a_straight_rail_give_the_eurosprinter_rolling_curvature() {
        let curvature = RelativeCurvature::from_radii(0.625, f64::INFINITY, 1.0 / (2.0 * per_mm(0.2814e-3))).unwrap();
        assert_relative_eq!(curvature.rolling(), per_mm(0.8e-3), max_relative = 1e-15);
        assert_relative_eq!(curvature.lateral(), per_mm(0.2814e-3), max_relative = 1e-15);
    }

    #[test]
    fn concave_wheel_profile_reduces_lateral_curvature_and_must_stay_flatter_than_the_rail() {
        let hollow = RelativeCurvature::from_radii(0.46, -0.5, 0.3).unwrap();
        assert_relative_eq!(hollow.lateral(), 0.5 * (1.0 / 0.3 - 1.0 / 0.5), max_relative = 1e-15);
        let conformal = RelativeCurvature::from_radii(0.46, -0.3, 0.3).unwrap_err();
        assert_eq!(conformal.variable, "wheel_profile_radius");
        assert_eq!(RelativeCurvature::from_radii(0.46, 0.0, 0.3).unwrap_err().variable, "wheel_profile_radius");
        assert_eq!(RelativeCurvature::from_radii(-0.46, 0.5, 0.3).unwrap_err().variable, "wheel_rolling_radius");
    }

    /// Issue 14, item 6: each error of the FMU's constructor names the FMU's variables with
    /// their values and the actual reason, never A or B (`curvature_lateral`).
    #[test]
    fn profile_curvature_errors_name_the_fmu_variables_and_the_reason() {
        let message = |r: f64, wheel: f64, rail: f64| {
            RelativeCurvature::from_profile_curvatures(r, wheel, rail).unwrap_err().to_string()
        };
        assert_eq!(
            message(0.46, 0.0, 1e-20),
            "rail_profile_curvature = 1e-20 is invalid with wheel_profile_curvature = 0, wheel_rolling_radius = \
             0.46: gives too slender a contact ellipse (a/b below 2.5e-7): the combined lateral curvature \
             (wheel_profile_curvature + rail_profile_curvature)/2 must be at least 1e-12 times the rolling \
             curvature 1/(2·wheel_rolling_radius)"
        );
        let no_ellipse = "gives no contact ellipse: the combined lateral curvature (wheel_profile_curvature + \
                          rail_profile_curvature)/2 must be positive (straight or concave profiles that do not \
                          close the gap touch along a line or conform)";
        assert_eq!(
            message(0.46, 0.0, 0.0),
            format!("rail_profile_curvature = 0 is invalid with wheel_profile_curvature = 0: {no_ellipse}")
        );
        assert_eq!(
            message(0.46, 0.0, -1.0),
            format!("rail_profile_curvature = -1 is invalid with wheel_profile_curvature = 0: {no_ellipse}")
        );
        // A convex wheel on a more concave rail: the rail's doing, not a "concave wheel".
        assert_eq!(
            message(0.46, 2.0, -3.0),
            format!("rail_profile_curvature = -3 is invalid with wheel_profile_curvature = 2: {no_ellipse}")
        );
        assert_eq!(
            message(0.46, -5.0, 1.0 / 0.3),
            "wheel_profile_curvature = -5 is invalid with rail_profile_curvature = 3.3333333333333335: gives no \
             contact ellipse: a concave wheel profile must be flatter than the rail head (wheel_profile_curvature \
             + rail_profile_curvature > 0), otherwise the contact is conformal, outside Hertz's theory"
        );
        assert_eq!(
            message(1e16, 1.0, 1.0),
            "wheel_rolling_radius = 1e16 is invalid with wheel_profile_curvature = 1, rail_profile_curvature = 1: \
             gives too slender a contact ellipse (b/a below 2.5e-7): the rolling curvature \
             1/(2·wheel_rolling_radius) must be at least 1e-12 times the combined lateral curvature \
             (wheel_profile_curvature + rail_profile_curvature)/2"
        );
        for (r, text) in [(0.0, "0"), (-0.46, "-0.46"), (f64::NAN, "NaN")] {
            assert_eq!(
                message(r, 0.0, 3.0),
                format!("wheel_rolling_radius = {text} is invalid: must be finite and > 0")
            );
        }
        assert_eq!(
            message(1e-320, 0.0, 3.0),
            "wheel_rolling_radius = 1e-320 is invalid: must be large enough for a finite rolling curvature \
             1/(2·wheel_rolling_radius)"
        );
        assert_eq!(message(0.46, f64::INFINITY, 3.0), "wheel_profile_curvature = inf is invalid: must be finite");
        assert_eq!(message(0.46, 0.0, f64::NAN), "rail_profile_curvature = NaN is invalid: must be finite");
        // The valid neighbours: the same A and B as from the radii.
        let hollow = RelativeCurvature::from_profile_curvatures(0.46, -2.0, 1.0 / 0.3).unwrap();
        assert_eq!(hollow, RelativeCurvature::from_radii(0.46, -0.5, 0.3).unwrap());
        let conical = RelativeCurvature::from_profile_curvatures(0.46, 0.0, 1.0 / 0.3).unwrap();
        assert_relative_eq!(conical.lateral(), 0.5 / 0.3, max_relative = 1e-15);
        assert_relative_eq!(conical.rolling(), 0.5 / 0.46, max_relative = 1e-15);
    }

    /// The radii constructor blames the rail when the rail (straight or concave) is the cause.
    #[test]
    fn radius_errors_name_the_actual_cause() {
        for (wheel, rail) in [(f64::INFINITY, f64::INFINITY), (f64::INFINITY, -1.0), (0.5, -0.3)] {
            let error = RelativeCurvature::from_radii(0.46, wheel, rail).unwrap_err();
            assert_eq!((error.variable, error.value), ("rail_profile_radius", rail));
            assert_eq!(error.with, [Some(("wheel_profile_radius", wheel)), None]);
            assert!(error.requirement.starts_with("gives no contact ellipse"), "{error}");
        }
    }

    /// Equal curvatures A = B = 1/(2R): a circle with a³ = 3QR/(4E*), δ = a²/R, p0 = 3Q/(2πa²).
    #[test]
    fn equal_curvatures_give_the_circular_solution() {
        let (q, radius) = (50e3, 0.3);
        let c = solve(q, 0.5 / radius, 0.5 / radius);
        let a = (3.0 * q * radius / (4.0 * steel())).cbrt();
        assert_relative_eq!(c.semi_axis_a, a, max_relative = 1e-14);
        assert_eq!(c.semi_axis_b, c.semi_axis_a);
        assert_relative_eq!(c.approach, a * a / radius, max_relative = 1e-14);
        assert_relative_eq!(c.max_pressure, 3.0 * q / (2.0 * PI * a * a), max_relative = 1e-14);
    }

    /// Johnson §4.2: the shape from Legendre's K(e), E(e) with e² = 1 − (b/a)², a ≥ b,
    /// B/A = ((a/b)² E − K)/(K − E): an independent check of the Carlson form. (Beyond 1e6 the
    /// Legendre form itself loses digits to 1 − e² and is not a reference any more.)
    #[test]
    fn shape_matches_legendre_form_over_many_ratios() {
        for ratio in [1.0001, 1.5, 2.843, 10.0, 1e3, 1e6] {
            let k = shape_ratio(ratio);
            let m = 1.0 - k * k;
            let (big_k, big_e) = (ellip::ellipk(m).unwrap(), ellip::ellipe(m).unwrap());
            let legendre_ratio = (big_e / (k * k) - big_k) / (big_k - big_e);
            assert_relative_eq!(legendre_ratio, ratio, max_relative = 1e-9);
            assert_relative_eq!(shape_ratio(1.0 / ratio), 1.0 / k, max_relative = 1e-15);
        }
    }

    /// Slender limit k → 0: K → ln(4/k), E → 1, so B/A → 1/(k²(ln(4/k) − 1)) with a relative
    /// error O(k² ln k).
    #[test]
    fn shape_matches_slender_asymptote_at_the_largest_ratio() {
        let k = shape_ratio(1e12);
        assert_relative_eq!(1.0 / (k * k * ((4.0 / k).ln() - 1.0)), 1e12, max_relative = 1e-8);
    }

    #[test]
    fn lift_off_gives_a_zero_contact_and_bad_values_are_named() {
        let curvature = RelativeCurvature::new(1.0, 2.0).unwrap();
        let zero = HertzContact::solve(-5.0, &curvature, steel()).unwrap();
        assert_eq!((zero.semi_axis_a, zero.semi_axis_b, zero.max_pressure, zero.approach), (0.0, 0.0, 0.0, 0.0));
        assert_eq!(HertzContact::solve(f64::NAN, &curvature, steel()).unwrap_err().variable, "normal_force");
        assert_eq!(HertzContact::solve(1e3, &curvature, 0.0).unwrap_err().variable, "contact_modulus");
        assert_eq!(RelativeCurvature::new(0.0, 1.0).unwrap_err().variable, "curvature_rolling");
        assert_eq!(RelativeCurvature::new(1.0, 1e13).unwrap_err().variable, "curvature_lateral");
        assert_eq!(contact_modulus(8e10, 0.6).unwrap_err().variable, "poisson_ratio");
    }

    proptest! {
        /// a, b ∝ Q^{1/3}, p0 ∝ Q^{1/3}, δ ∝ Q^{2/3}; the shape b/a does not depend on Q.
        #[test]
        fn semi_axes_scale_with_cube_root_of_load(
            q in 1.0..1e6_f64, factor in 1.1..1e3_f64, rolling in 0.1..100.0_f64, lateral in 0.1..100.0_f64,
        ) {
            let c = solve(q, rolling, lateral);
            let scaled = solve(q * factor, rolling, lateral);
            let cube_root = factor.cbrt();
            prop_assert!((scaled.semi_axis_a / c.semi_axis_a / cube_root - 1.0).abs() < 1e-12);
            prop_assert!((scaled.semi_axis_b / c.semi_axis_b / cube_root - 1.0).abs() < 1e-12);
            prop_assert!((scaled.max_pressure / c.max_pressure / cube_root - 1.0).abs() < 1e-12);
            prop_assert!((scaled.approach / c.approach / (cube_root * cube_root) - 1.0).abs() < 1e-12);
        }

        /// The flatter direction carries the longer semi-axis, and the load integrates to Q.
        #[test]
        fn longer_axis_along_flatter_direction(rolling in 1e-3..1e3_f64, lateral in 1e-3..1e3_f64, q in 1e-3..1e7_f64) {
            let c = solve(q, rolling, lateral);
            prop_assert_eq!(c.semi_axis_a >= c.semi_axis_b, rolling <= lateral);
            let load = 2.0 / 3.0 * PI * c.semi_axis_a * c.semi_axis_b * c.max_pressure;
            prop_assert!((load / q - 1.0).abs() < 1e-13);
        }

        /// Over the accepted domain of finite inputs the solution is Ok, finite and positive
        /// wherever its values are representable, and an error (naming normal_force) only where
        /// one of them is not. Which is which is predicted independently from the circle of the
        /// same curvature product (c = √(ab), c³ = 3Q/(8E*√(AB)), p0 = 3Q/(2πc²), δ ≈ 2c²√(AB));
        /// the ellipse's shape moves a and b by at most 10^±5.4 from c at B/A = 10^±12, so a
        /// margin of 20 decades from f64's range separates the two verdicts.
        #[test]
        fn ok_wherever_the_contact_is_representable(
            log_q in -300.0..300.0_f64, log_rolling in -150.0..150.0_f64, log_ratio in -12.0..12.0_f64,
            log_modulus in -100.0..100.0_f64,
        ) {
            let log_lateral = log_rolling + log_ratio;
            let curvature = RelativeCurvature::new(10f64.powf(log_rolling), 10f64.powf(log_lateral)).unwrap();
            let log_mean_curvature = 0.5 * (log_rolling + log_lateral);
            let log_c = (log_q - log_modulus - log_mean_curvature + (3.0_f64 / 8.0).log10()) / 3.0;
            let log_pressure = log_q + (1.5 / PI).log10() - 2.0 * log_c;
            let log_approach = 2.0 * log_c + log_mean_curvature + 2f64.log10();
            let logs = [log_c, log_pressure, log_approach];
            let result = HertzContact::solve(10f64.powf(log_q), &curvature, 10f64.powf(log_modulus));
            if logs.iter().all(|l| l.abs() < 280.0) {
                let c = result.unwrap();
                prop_assert!(c.semi_axis_a > 0.0 && c.semi_axis_b > 0.0 && c.max_pressure > 0.0 && c.approach > 0.0);
                prop_assert!(c.semi_axis_a.is_finite() && c.semi_axis_b.is_finite());
                prop_assert!(c.max_pressure.is_finite() && c.approach.is_finite());
                // p0 is Hertz's 3Q/(2πab) to rounding: the result is the contact, not just finite.
                let load = 2.0 / 3.0 * PI * c.semi_axis_a * (c.semi_axis_b * c.max_pressure);
                prop_assert!((load / 10f64.powf(log_q) - 1.0).abs() < 1e-12);
            } else if logs.iter().any(|l| *l > 330.0 || *l < -345.0) {
                prop_assert_eq!(result.unwrap_err().variable, "normal_force");
            }
        }
    }

    /// A concave wheel on a straight or concave rail: the rail does not close the gap, so the
    /// error names the rail (the wheel is blamed only when a convex rail could have made up
    /// for it).
    #[test]
    fn a_concave_wheel_on_a_rail_that_does_not_close_the_gap_blames_the_rail() {
        for rail in [0.0, -1.0] {
            let error = RelativeCurvature::from_profile_curvatures(0.46, -2.0, rail).unwrap_err();
            assert_eq!((error.variable, error.value), ("rail_profile_curvature", rail));
        }
    }

    /// The slenderness limits are inclusive: B/A exactly 1e12 or 1e-12 is still an ellipse.
    #[test]
    fn the_slenderness_limits_themselves_are_accepted() {
        // r = 0.5 m: A = 1 /m exactly, so B = (wheel + rail)/2 sets B/A exactly.
        for (wheel, rail) in [(0.0, 2e12), (0.0, 2e-12)] {
            let curvature = RelativeCurvature::from_profile_curvatures(0.5, wheel, rail).unwrap();
            assert_eq!(curvature.lateral() / curvature.rolling(), 0.5 * rail);
        }
        assert!(RelativeCurvature::from_profile_curvatures(0.5, 0.0, 2.0000001e12).is_err());
        assert!(RelativeCurvature::from_profile_curvatures(0.5, 0.0, 1.9999999e-12).is_err());
    }
}
