//! The rolling-radius difference Δr(y) of a wheelset on its track and its equivalent conicity
//! tan γ_e(A) (`docs/conicity.md`).
//!
//! Sign convention (EN 15302:2008+A1:2010, clause 3: Δr = r_1 − r_2, y positive towards wheel 1)
//! with CONTACT's y positive to the right: wheel 1 is the right wheel, Δr(y) = r_right − r_left, and
//! Δr > 0 for y > 0 (the right wheel rolls towards its flange). Units: metres, radians.
//!
//! Δr(y): the wheelset at lateral displacement y with zero roll and yaw (a simplification: the
//! rigid wheelset on both rails rolls by a fraction of a milliradian on the tread, which
//! EN 15302 includes). Each wheel's rolling radius is the wheel profile's radius r0 + z_wheel at
//! the point where it first touches its rail — the deepest of its contact candidates, the lowest
//! undeformed gap ([`ContactCandidates::touch`](super::ContactCandidates::touch)): the rigid
//! contact point of EN 15302. Where two candidates swap which is lowest (for S1002 on UIC60 1:40
//! at y ≈ 0.22, 5.0 and 6.6 mm) Δr jumps.
//!
//! Equivalent conicity, by the principle of EN 15302 (clause 4, Annex B: "integration of the
//! nonlinear differential equation"): tan γ_e(A) is the conicity of the conical wheelset whose
//! kinematic (Klingel) wavelength λ = 2π √(e r0 / tan γ) equals that of the real wheelset's
//! kinematic motion of amplitude A, y'' = −Δr(y) / (2 e r0) (x the distance travelled, e half
//! the distance between the contact points). Its first integral (y' = 0 at y = A) is
//! y'² = F(y) / (e r0) with F(y) = ∫_y^A Δr(u) du, so a quarter wavelength is
//! √(e r0) · I with I = ∫_0^A dy / √F(y), and
//!
//!   tan γ_e(A) = (π/2)² / I²                                                        (1)
//!
//! (e r0 cancels; a cone, Δr = 2 tan γ y, gives back tan γ). I is taken over y = A sin θ, which
//! removes the integrable 1/√(A − y) singularity at the turning point, by the midpoint rule.
//! Δr is read from its samples by linear interpolation and symmetrised, Δr_odd(y) =
//! (Δr(y) − Δr(−y))/2, as the quarter-wave construction assumes (a symmetric wheelset gives an
//! odd Δr; asymmetric ones, which Annex B handles with an offset centre, are not covered).
//!
//! For comparison, the harmonic linearisation (describing function) of the same Δr: the first
//! Fourier coefficient of Δr(A sin φ), tan γ_h(A) = 2/(π A) ∫_0^{π/2} Δr_odd(A sin φ) sin φ dφ
//! (2); (1) and (2) agree for a cone and differ where Δr is nonlinear.

use super::contact::{WheelOnRail, WheelsetPosition};
use super::patch::ContactPoint;
use super::profile_file::ProfileError;
use std::f64::consts::FRAC_PI_2;
use std::fmt;

/// Midpoint-rule nodes over θ ∈ [0, π/2] in (1) and (2): their error on the S1002/UIC60 Δr
/// (jumps of 0.5 mm and 2 mm) is below 1e-5 in tan γ_e (halving the nodes changes it less).
const QUADRATURE_NODES: usize = 20_000;

/// Most samples a Δr function may have.
const MAX_SAMPLES: usize = 1_000_001;

/// Why Δr or the conicity cannot be computed.
#[derive(Debug, Clone, PartialEq)]
pub enum ConicityError {
    /// The contact search failed at a displacement (e.g. the profiles no longer overlap).
    Geometry {
        /// The wheelset's lateral displacement \[m\].
        lateral: f64,
        /// The contact search's error.
        error: ProfileError,
    },
    /// An argument out of range: its name, value and the rule it breaks.
    InvalidArgument {
        /// The argument's name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The rule.
        requirement: &'static str,
    },
    /// Δr gives no kinematic oscillation of this amplitude: ∫_y^A Δr du ≤ 0 for some y in
    /// [0, A) (Δr not positive for y > 0, as with a negative conicity).
    NoOscillation {
        /// The amplitude \[m\].
        amplitude: f64,
    },
}

impl fmt::Display for ConicityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Geometry { lateral, error } => write!(f, "no contact at lateral displacement {lateral} m: {error}"),
            Self::InvalidArgument { name, value, requirement } => write!(f, "{name} = {value} {requirement}"),
            Self::NoOscillation { amplitude } => write!(
                f,
                "the rolling-radius difference gives no kinematic oscillation of amplitude {amplitude} m \
                 (its integral from y to the amplitude is not positive)"
            ),
        }
    }
}

impl std::error::Error for ConicityError {}

fn invalid(name: &'static str, value: f64, requirement: &'static str) -> ConicityError {
    ConicityError::InvalidArgument { name, value, requirement }
}

/// The point where `wheel` first touches its rail with the wheelset at lateral displacement
/// `lateral` \[m\], zero roll and yaw: its candidate with the lowest undeformed gap (module doc).
pub fn first_touch(wheel: &WheelOnRail, lateral: f64) -> Result<ContactPoint, ConicityError> {
    if !lateral.is_finite() {
        return Err(invalid("lateral", lateral, "must be finite"));
    }
    let position = WheelsetPosition { lateral, vertical: 0.0, roll: 0.0, yaw: 0.0 };
    let candidates = wheel.candidates(&position).map_err(|error| ConicityError::Geometry { lateral, error })?;
    candidates
        .points()
        .into_iter()
        .min_by(|a, b| a.gap_at_zero.total_cmp(&b.gap_at_zero))
        .ok_or_else(|| ConicityError::Geometry { lateral, error: ProfileError::whole("no contact candidate") })
}

/// Δr(y) = r_right − r_left \[m\] sampled over the wheelset's lateral displacement y \[m\]
/// (module doc), linear between samples.
///
/// A conical wheelset of slope γ has Δr = 2γy and, at every amplitude, the conicity γ; the
/// S1002 wheels on UIC60 1:40 of the Manchester benchmark have tan γ_e = 0.1803 at 3 mm by
/// CONTACT's Δr (`core/tests/data/conicity_contact.csv`):
///
/// ```
/// use wheel_rail_contact::geometry::{first_touch, RollingRadiusDifference, WheelOnRail, WheelSide};
///
/// let lateral: Vec<f64> = (-10..=10).map(|i| f64::from(i) * 1e-3).collect();
/// let difference = lateral.iter().map(|y| 2.0 * 0.04 * y).collect();
/// let cone = RollingRadiusDifference::from_samples(lateral, difference).unwrap();
/// assert_eq!((cone.lateral().len(), cone.difference()[20]), (21, 2.0 * 0.04 * 0.01));
/// assert!((cone.at(2.5e-3).unwrap() - 2e-4).abs() < 1e-15, "linear between samples");
/// assert!(cone.at(0.011).is_err(), "outside the samples");
/// for amplitude in [1e-3, 4e-3, 9e-3] {
///     assert!((cone.equivalent_conicity(amplitude).unwrap() - 0.04).abs() < 1e-6);
///     assert!((cone.harmonic_conicity(amplitude).unwrap() - 0.04).abs() < 1e-6);
/// }
///
/// let (right, left) = (WheelOnRail::manchester_benchmark(WheelSide::Right), WheelOnRail::manchester_benchmark(WheelSide::Left));
/// // CONTACT: the right wheel rolls on 460.76 mm with the wheelset 3 mm to the right.
/// assert!((first_touch(&right, 3e-3).unwrap().rolling_radius - 0.46076).abs() < 0.05e-3);
/// let s1002 = RollingRadiusDifference::from_wheelset(&right, &left, 3e-3, 1e-4).unwrap();
/// let conicity = s1002.equivalent_conicity(3e-3).unwrap();
/// assert!((conicity - 0.1803).abs() < 2e-4, "tan γ_e(3 mm) = {conicity}");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RollingRadiusDifference {
    lateral: Vec<f64>,
    difference: Vec<f64>,
    /// ∫ Δr from the first sample to each sample (trapezoids: exact for the linear pieces).
    cumulative: Vec<f64>,
}

impl RollingRadiusDifference {
    /// Δr of the wheelset whose wheels are `right` and `left` (placed on the same track, sides
    /// [`WheelSide::Right`](super::WheelSide::Right) and [`WheelSide::Left`](super::WheelSide::Left)),
    /// every `step` of y over [−`max_displacement`, `max_displacement`] (y = 0 included) \[m\].
    pub fn from_wheelset(
        right: &WheelOnRail,
        left: &WheelOnRail,
        max_displacement: f64,
        step: f64,
    ) -> Result<Self, ConicityError> {
        if !(step > 0.0 && step.is_finite()) {
            return Err(invalid("step", step, "must be finite and > 0"));
        }
        if !(max_displacement > 0.0 && max_displacement.is_finite()) {
            return Err(invalid("max_displacement", max_displacement, "must be finite and > 0"));
        }
        let half = (max_displacement / step + 1e-9).floor();
        if 2.0 * half + 1.0 > MAX_SAMPLES as f64 {
            return Err(invalid("step", step, "gives more than 10⁶ samples over the displacements"));
        }
        let half = half as i64;
        let mut lateral = Vec::with_capacity((2 * half + 1) as usize);
        let mut difference = Vec::with_capacity(lateral.capacity());
        for k in -half..=half {
            let y = k as f64 * step;
            lateral.push(y);
            difference.push(first_touch(right, y)?.rolling_radius - first_touch(left, y)?.rolling_radius);
        }
        Self::from_samples(lateral, difference)
    }

    /// Δr from samples (y increasing, both finite, at least two, the same count) \[m\]: e.g.
    /// another program's.
    pub fn from_samples(lateral: Vec<f64>, difference: Vec<f64>) -> Result<Self, ConicityError> {
        if lateral.len() != difference.len() {
            return Err(invalid("difference.len()", difference.len() as f64, "must equal lateral.len()"));
        }
        if lateral.len() < 2 || lateral.len() > MAX_SAMPLES {
            return Err(invalid("lateral.len()", lateral.len() as f64, "must be within 2 ..= 10⁶ + 1"));
        }
        if let Some(&bad) = lateral.iter().chain(&difference).find(|v| !v.is_finite()) {
            return Err(invalid("sample", bad, "must be finite"));
        }
        if let Some(w) = lateral.windows(2).find(|w| w[1] <= w[0]) {
            return Err(invalid("lateral", w[1], "must increase"));
        }
        let mut cumulative = vec![0.0; lateral.len()];
        for i in 1..lateral.len() {
            cumulative[i] =
                cumulative[i - 1] + 0.5 * (difference[i] + difference[i - 1]) * (lateral[i] - lateral[i - 1]);
        }
        Ok(Self { lateral, difference, cumulative })
    }

    /// The sampled lateral displacements y \[m\].
    pub fn lateral(&self) -> &[f64] {
        &self.lateral
    }

    /// Δr at each sample \[m\].
    pub fn difference(&self) -> &[f64] {
        &self.difference
    }

    /// Δr(y), linear between samples; an error outside them.
    pub fn at(&self, y: f64) -> Result<f64, ConicityError> {
        let (first, last) = (self.lateral[0], self.lateral[self.lateral.len() - 1]);
        if !(y >= first && y <= last) {
            return Err(invalid("y", y, "must lie within the sampled displacements"));
        }
        Ok(self.segment(y).1)
    }

    /// Whether ±`reach` lies within the samples (`value` is reported).
    fn check_range(&self, name: &'static str, reach: f64, value: f64) -> Result<(), ConicityError> {
        let (first, last) = (self.lateral[0], self.lateral[self.lateral.len() - 1]);
        if !(reach.is_finite() && -reach >= first && reach <= last) {
            return Err(invalid(name, value, "must lie within the sampled displacements (±)"));
        }
        Ok(())
    }

    /// The segment index i (y in [y_i, y_{i+1}]) and Δr(y) there (y within the samples).
    fn segment(&self, y: f64) -> (usize, f64) {
        let n = self.lateral.len();
        let i = self.lateral.partition_point(|&v| v <= y).clamp(1, n - 1) - 1;
        let (y0, y1) = (self.lateral[i], self.lateral[i + 1]);
        let t = (y - y0) / (y1 - y0);
        (i, self.difference[i] + t * (self.difference[i + 1] - self.difference[i]))
    }

    /// P(y) = ∫ Δr from the first sample to y, exact for the linear interpolant.
    fn primitive(&self, y: f64) -> f64 {
        let (i, value) = self.segment(y);
        self.cumulative[i] + 0.5 * (self.difference[i] + value) * (y - self.lateral[i])
    }

    /// Δr_odd(y) = (Δr(y) − Δr(−y))/2.
    fn odd(&self, y: f64) -> f64 {
        0.5 * (self.segment(y).1 - self.segment(-y).1)
    }

    /// G(y) = ∫_0^y Δr_odd du = (P(y) + P(−y) − 2 P(0))/2.
    fn odd_primitive(&self, y: f64, at_zero: f64) -> f64 {
        0.5 * (self.primitive(y) + self.primitive(-y)) - at_zero
    }

    fn check_amplitude(&self, amplitude: f64) -> Result<(), ConicityError> {
        if amplitude.is_nan() || amplitude <= 0.0 {
            return Err(invalid("amplitude", amplitude, "must be > 0"));
        }
        self.check_range("amplitude", amplitude, amplitude)
    }

    /// tan γ_e(A) by EN 15302's principle, the kinematic wavelength of the nonlinear motion
    /// (module doc, equation (1)); `amplitude` A \[m\], with ±A within the samples.
    pub fn equivalent_conicity(&self, amplitude: f64) -> Result<f64, ConicityError> {
        self.check_amplitude(amplitude)?;
        let at_zero = self.primitive(0.0);
        let top = self.odd_primitive(amplitude, at_zero);
        let h = FRAC_PI_2 / QUADRATURE_NODES as f64;
        let mut integral = 0.0;
        for k in 0..QUADRATURE_NODES {
            let theta = (k as f64 + 0.5) * h;
            let y = amplitude * theta.sin();
            // F(y) = ∫_y^A Δr_odd du = G(A) − G(y).
            let energy = top - self.odd_primitive(y, at_zero);
            if energy.is_nan() || energy <= 0.0 {
                return Err(ConicityError::NoOscillation { amplitude });
            }
            integral += amplitude * theta.cos() / energy.sqrt();
        }
        integral *= h;
        Ok(FRAC_PI_2 * FRAC_PI_2 / (integral * integral))
    }

    /// tan γ_h(A) by harmonic linearisation (module doc, equation (2)), for comparison.
    pub fn harmonic_conicity(&self, amplitude: f64) -> Result<f64, ConicityError> {
        self.check_amplitude(amplitude)?;
        let h = FRAC_PI_2 / QUADRATURE_NODES as f64;
        let sum: f64 = (0..QUADRATURE_NODES)
            .map(|k| {
                let phi = (k as f64 + 0.5) * h;
                self.odd(amplitude * phi.sin()) * phi.sin()
            })
            .sum();
        Ok(2.0 / (std::f64::consts::PI * amplitude) * sum * h)
    }
}
