//! A profile's smooth representation: y(s), z(s) as natural cubic interpolating splines over the
//! chord length s of its points, with the curvature from their derivatives.
//!
//! Why parametric: rail heads and wheel flanges have near-vertical flanks (the UIC60 file steps
//! 1e-6 mm in y while z falls millimetres), where z(y) has no bounded derivative and a spline in
//! y oscillates; over the arc length both coordinates are smooth. Why interpolating and
//! hand-written: the shipped files carry `approx.smooth = 0` (SIMPACK interpolates them too),
//! and no well-kept Rust crate gives a parametric cubic spline with its second derivatives
//! (`splines` has no derivatives, `bspline` no fitting); the spline is thirty lines (the
//! tridiagonal system of de Boor, "A Practical Guide to Splines", ch. IV, with natural ends).
//!
//! Smoothing ([`SmoothProfile::smoothed`]), for measured, noisy profiles: CONTACT's weighted
//! smoothing spline with a second-order penalty (its `ISMOOTH = 1`, user guide §"Profile
//! smoothing"; E.A.H. Vollebregt, "Detailed wheel/rail geometry processing with the conformal
//! contact approach", Multibody System Dynamics 52, 2021, and CM2022). Each coordinate f ∈ {y, z}
//! of the profile over its chord length s minimises Σ wᵢ (fᵢ − f(sᵢ))² + λ ∫ f″(s)² ds with
//! weights wᵢ = (sᵢ₊₁ − sᵢ₋₁)/2 (half the chords at the ends) and λ = (L/2π)⁴ from the filter
//! wavelength L: a low-pass filter that roughly halves undulations of wavelength L, damps shorter
//! ones more and keeps longer ones. The minimiser is the natural cubic spline on the same knots
//! whose values g and second derivatives γ solve Reinsch's system (R + λ QᵀW⁻¹Q) γ = Qᵀf,
//! g = f − λ W⁻¹Q γ (P.J. Green, B.W. Silverman, "Nonparametric regression and generalized
//! linear models", 1994, §2.3.3): a symmetric positive definite five-band system, solved here by
//! its LDLᵀ factors. L = 0 is interpolation, exactly [`SmoothProfile::new`]. Written from the
//! method's description, not from CONTACT's code.
//!
//! Accuracy (core/tests/library/geometry_profiles.rs): on points of a 300 mm circle every 0.5 mm the slope is
//! within 1e-7 rad and κ within 1e-4 of 1/R more than 20 points inside the ends (the natural
//! ends' zero curvature fades over about five points); on the shipped UIC60 the 13 mm, 80 mm and
//! 300 mm radii of EN 13674-1 come out within 1 %, except within about one point spacing of the
//! joints between arcs, where the curvature jumps and the spline overshoots (84 1/m against
//! 77 1/m at the gauge corner's joint).
//!
//! Curvature: κ = (y′z″ − z′y″)/(y′² + z′²)^{3/2} with s increasing with y; positive where the
//! profile bends towards +z (downward). For a rail (material below) κ > 0 is convex, e.g. the
//! 300 mm crown of UIC60; for a wheel (material above) κ > 0 is concave, e.g. the flange root.

use super::profile_file::{ProfileError, ProfilePoints};

/// The narrowest and widest profile placed \[m\]: a wheel's or a rail head's running surface
/// is 60–150 mm wide; a profile outside these bounds is in other units, or not a profile.
pub const PROFILE_WIDTH: (f64, f64) = (0.01, 0.5);
/// The tallest profile placed \[m\]: a whole rail with its foot is 0.17 m tall, a wheel profile
/// with its flange some 0.04 m.
pub const PROFILE_HEIGHT: f64 = 0.25;

/// The chord lengths s of the points (y, z): the splines' knots, from 0.
fn chord_lengths(y: &[f64], z: &[f64]) -> Vec<f64> {
    let mut knots = Vec::with_capacity(y.len());
    knots.push(0.0);
    for i in 1..y.len() {
        knots.push(knots[i - 1] + (y[i] - y[i - 1]).hypot(z[i] - z[i - 1]));
    }
    knots
}

/// One coordinate's cubic spline on the shared knots: values and second derivatives at the knots.
#[derive(Debug, Clone)]
struct CubicSpline {
    values: Vec<f64>,
    second: Vec<f64>,
}

impl CubicSpline {
    /// The natural (zero end curvature) interpolating spline through `values` at `knots`.
    fn natural(knots: &[f64], values: &[f64]) -> Self {
        let n = knots.len();
        let h: Vec<f64> = knots.windows(2).map(|k| k[1] - k[0]).collect();
        // Interior equations h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = 6 Δ-slope,
        // solved by the Thomas algorithm (diagonally dominant: stable without pivoting).
        let mut diagonal = vec![1.0; n];
        let mut rhs = vec![0.0; n];
        let mut upper = vec![0.0; n];
        for i in 1..n - 1 {
            let slope_difference = (values[i + 1] - values[i]) / h[i] - (values[i] - values[i - 1]) / h[i - 1];
            let lower = h[i - 1];
            diagonal[i] = 2.0 * (h[i - 1] + h[i]) - lower * upper[i - 1];
            upper[i] = h[i] / diagonal[i];
            rhs[i] = (6.0 * slope_difference - lower * rhs[i - 1]) / diagonal[i];
        }
        let mut second = vec![0.0; n];
        for i in (1..n - 1).rev() {
            second[i] = rhs[i] - upper[i] * second[i + 1];
        }
        Self { values: values.to_vec(), second }
    }

    /// The smoothing splines' values g of y and z at `knots` with λ (module doc, "Smoothing"):
    /// Reinsch's system for the interior second derivatives γ, one LDLᵀ factorisation for both
    /// coordinates.
    fn smoothed_values(knots: &[f64], lateral: &[f64], vertical: &[f64], lambda: f64) -> (Vec<f64>, Vec<f64>) {
        let n = knots.len();
        let h: Vec<f64> = knots.windows(2).map(|k| k[1] - k[0]).collect();
        let weight = |i: usize| 0.5 * (knots[(i + 1).min(n - 1)] - knots[i.saturating_sub(1)]);
        // Column j (knot j, 1 ≤ j ≤ n−2) of Q: rows j−1, j, j+1 hold (1/h[j−1], −1/h[j−1] − 1/h[j], 1/h[j]).
        let q = |j: usize| (1.0 / h[j - 1], -1.0 / h[j - 1] - 1.0 / h[j], 1.0 / h[j]);
        let m = n - 2;
        // The matrix's three bands (diagonal, first and second off-diagonal), row r = knot r + 1.
        let mut band = vec![[0.0; 3]; m];
        for (r, row) in band.iter_mut().enumerate() {
            let j = r + 1;
            let (a, b, c) = q(j);
            row[0] =
                (h[j - 1] + h[j]) / 3.0 + lambda * (a * a / weight(j - 1) + b * b / weight(j) + c * c / weight(j + 1));
            if r + 1 < m {
                let (a1, b1, _) = q(j + 1);
                row[1] = h[j] / 6.0 + lambda * (b * a1 / weight(j) + c * b1 / weight(j + 1));
            }
            if r + 2 < m {
                row[2] = lambda * c * q(j + 2).0 / weight(j + 1);
            }
        }
        // LDLᵀ: l1[r] = L[r][r−1], l2[r] = L[r][r−2].
        let (mut d, mut l1, mut l2) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
        for r in 0..m {
            if r >= 2 {
                l2[r] = band[r - 2][2] / d[r - 2];
            }
            if r >= 1 {
                let across = if r >= 2 { l2[r] * l1[r - 1] * d[r - 2] } else { 0.0 };
                l1[r] = (band[r - 1][1] - across) / d[r - 1];
            }
            d[r] = band[r][0]
                - if r >= 1 { l1[r] * l1[r] * d[r - 1] } else { 0.0 }
                - if r >= 2 { l2[r] * l2[r] * d[r - 2] } else { 0.0 };
        }
        let solve = |values: &[f64]| -> Vec<f64> {
            let mut x: Vec<f64> =
                (1..=m).map(|j| (values[j + 1] - values[j]) / h[j] - (values[j] - values[j - 1]) / h[j - 1]).collect();
            for r in 0..m {
                x[r] -= if r >= 1 { l1[r] * x[r - 1] } else { 0.0 } + if r >= 2 { l2[r] * x[r - 2] } else { 0.0 };
            }
            for r in 0..m {
                x[r] /= d[r];
            }
            for r in (0..m).rev() {
                x[r] -= if r + 1 < m { l1[r + 1] * x[r + 1] } else { 0.0 }
                    + if r + 2 < m { l2[r + 2] * x[r + 2] } else { 0.0 };
            }
            let mut second = vec![0.0; n];
            second[1..=m].copy_from_slice(&x);
            // g = f − λ W⁻¹ Q γ, (Qγ)ᵢ = γᵢ₋₁/h[i−1] − γᵢ (1/h[i−1] + 1/h[i]) + γᵢ₊₁/h[i] (γ = 0 at the ends).
            (0..n)
                .map(|i| {
                    let mut q_gamma = 0.0;
                    if i >= 1 {
                        q_gamma += (second[i - 1] - second[i]) / h[i - 1];
                    }
                    if i + 1 < n {
                        q_gamma += (second[i + 1] - second[i]) / h[i];
                    }
                    values[i] - lambda * q_gamma / weight(i)
                })
                .collect()
        };
        (solve(lateral), solve(vertical))
    }

    /// Value, first and second derivative on segment `i` at `t` = s − s_i, segment length `h`.
    fn evaluate(&self, i: usize, t: f64, h: f64) -> [f64; 3] {
        let (m0, m1) = (self.second[i], self.second[i + 1]);
        let (v0, v1) = (self.values[i], self.values[i + 1]);
        let u = h - t;
        let value =
            (m0 * u * u * u + m1 * t * t * t) / (6.0 * h) + (v0 / h - m0 * h / 6.0) * u + (v1 / h - m1 * h / 6.0) * t;
        let first = (-m0 * u * u + m1 * t * t) / (2.0 * h) + (v1 - v0) / h - (m1 - m0) * h / 6.0;
        let second = (m0 * u + m1 * t) / h;
        [value, first, second]
    }
}

/// A point of a smooth profile with its derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfilePoint {
    /// y \[m\].
    pub lateral: f64,
    /// z \[m\], downward.
    pub vertical: f64,
    /// The surface's inclination: atan(dz/dy) \[rad\], positive where z grows with y.
    pub slope_angle: f64,
    /// κ \[1/m\], positive bending towards +z (module doc).
    pub curvature: f64,
}

/// A profile as y(s), z(s) natural cubic splines over the chord length s (module doc).
///
/// A rail crown of radius R = 300 mm sampled every 0.5 mm over ±30 mm, as a profile file
/// gives it: away from the ends the spline has the circle's height R − √(R² − y²), slope
/// angle atan(y/√(R² − y²)) and curvature 1/R:
///
/// ```
/// use wheel_rail_contact::geometry::{ProfilePoints, SmoothProfile};
///
/// let radius = 0.3;
/// let lateral: Vec<f64> = (-60..=60).map(|i| f64::from(i) * 0.5e-3).collect();
/// let vertical = lateral.iter().map(|y| radius - (radius * radius - y * y).sqrt()).collect();
/// let crown = SmoothProfile::new(&ProfilePoints { lateral, vertical }).unwrap();
/// assert_eq!(crown.lateral_range(), (-0.03, 0.03));
/// let y = 0.012;
/// let root = (radius * radius - y * y).sqrt();
/// let point = crown.at_lateral(y).unwrap();
/// assert!((point.vertical - (radius - root)).abs() < 1e-10);
/// assert!((point.slope_angle - (y / root).atan()).abs() < 1e-7);
/// assert!((point.curvature * radius - 1.0).abs() < 1e-4);
/// assert!(crown.at_lateral(0.031).is_none(), "outside the profile");
/// // 60 mm wide, 1.5 mm from its top to its ends: a rail's size.
/// let (top, ends) = crown.vertical_range();
/// assert_eq!(top, 0.0);
/// assert!((ends - (radius - (radius * radius - 0.03f64 * 0.03).sqrt())).abs() < 1e-15);
/// assert!(crown.check_extent("rail").is_ok());
/// // The same points read in metres as if they were millimetres: 60 µm wide.
/// let tiny: Vec<f64> = (-60..=60).map(|i| f64::from(i) * 0.5e-6).collect();
/// let tiny = SmoothProfile::new(&ProfilePoints { vertical: vec![0.0; tiny.len()], lateral: tiny }).unwrap();
/// let error = tiny.check_extent("rail").unwrap_err();
/// assert!(error.reason.starts_with("the rail profile is 0.060000 mm wide"), "{error}");
/// // Along the profile: its length is the chord polygon's (2R·asin(0.1) less a little).
/// let arc = 2.0 * radius * (0.03 / radius).asin();
/// assert!(crown.length() < arc && crown.length() > arc - 1e-8);
/// assert!((crown.at_parameter(0.5 * crown.length()).lateral).abs() < 1e-12, "the middle is the crown");
/// // Turned by α = 0.05 rad about the origin, the circle's centre (0, R) moves to
/// // (−R sin α, R cos α), and with it the crown's top: slope 0 at y = −R sin α, z = −R(1 − cos α).
/// let alpha = 0.05_f64;
/// let top = crown.rotated(alpha).unwrap().at_lateral(-radius * alpha.sin()).unwrap();
/// assert!(top.slope_angle.abs() < 1e-7 && (top.vertical + radius * (1.0 - alpha.cos())).abs() < 1e-10);
/// ```
#[derive(Debug, Clone)]
pub struct SmoothProfile {
    knots: Vec<f64>,
    lateral: CubicSpline,
    vertical: CubicSpline,
}

impl SmoothProfile {
    /// The interpolating spline through the points (y strictly increasing, as the readers give).
    pub fn new(points: &ProfilePoints) -> Result<Self, ProfileError> {
        let (y, z) = (&points.lateral, &points.vertical);
        if y.len() != z.len() || y.len() < 4 {
            return Err(ProfileError::whole(format!(
                "{} y and {} z values; a profile needs at least 4 points",
                y.len(),
                z.len()
            )));
        }
        if y.iter().chain(z).any(|v| !v.is_finite()) || y.windows(2).any(|w| w[1] <= w[0]) {
            return Err(ProfileError::whole("profile points must be finite with y strictly increasing"));
        }
        let knots = chord_lengths(y, z);
        Ok(Self { lateral: CubicSpline::natural(&knots, y), vertical: CubicSpline::natural(&knots, z), knots })
    }

    /// The profile smoothed with filter wavelength `wavelength` \[m\] (module doc, "Smoothing";
    /// CONTACT's L_filt of its `ISMOOTH = 1`): undulations of about that wavelength are halved,
    /// shorter ones damped more, longer ones kept. The smoothing spline's values at the points are
    /// interpolated as by [`Self::new`] — on the same knots that is the smoothing spline itself,
    /// the unique natural cubic spline through its values — except that a point whose smoothed y
    /// no longer advances (on a near-vertical face, where the measured y wanders and the smoothing
    /// averages it) is left out, so that y still increases along the profile. 0 interpolates the
    /// points themselves ([`Self::new`], bit for bit).
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{ProfilePoints, SmoothProfile};
    ///
    /// // A straight tread every 0.2 mm with a ±0.02 mm zig-zag in z (wavelength 0.4 mm).
    /// let lateral: Vec<f64> = (0..300).map(|i| f64::from(i) * 0.2e-3).collect();
    /// let vertical = (0..300).map(|i| if i % 2 == 0 { 0.02e-3 } else { -0.02e-3 }).collect();
    /// let points = ProfilePoints { lateral, vertical };
    /// let raw = SmoothProfile::new(&points).unwrap();
    /// let smooth = SmoothProfile::smoothed(&points, 5e-3).unwrap();
    /// // Interpolated, the zig-zag stays; with L = 5 mm it is gone (< 0.1 µm) away from the ends.
    /// assert!(raw.at_lateral(30e-3).unwrap().vertical > 0.019e-3);
    /// for k in 50..250 {
    ///     let y = f64::from(k) * 0.2e-3;
    ///     assert!(smooth.at_lateral(y).unwrap().vertical.abs() < 1e-7, "z({y})");
    /// }
    /// // L = 0 is the interpolation itself.
    /// let same = SmoothProfile::smoothed(&points, 0.0).unwrap();
    /// assert_eq!(same.at_lateral(30e-3), raw.at_lateral(30e-3));
    /// assert!(SmoothProfile::smoothed(&points, -1.0).is_err());
    /// ```
    pub fn smoothed(points: &ProfilePoints, wavelength: f64) -> Result<Self, ProfileError> {
        if !(wavelength >= 0.0 && wavelength.is_finite()) {
            return Err(ProfileError::whole(format!(
                "the smoothing's filter wavelength must be finite and ≥ 0 m, found {wavelength}"
            )));
        }
        let interpolated = Self::new(points)?;
        if wavelength == 0.0 {
            return Ok(interpolated);
        }
        let lambda = (wavelength / std::f64::consts::TAU).powi(4);
        let (lateral, vertical) =
            CubicSpline::smoothed_values(&interpolated.knots, &points.lateral, &points.vertical, lambda);
        let mut kept =
            ProfilePoints { lateral: Vec::with_capacity(lateral.len()), vertical: Vec::with_capacity(lateral.len()) };
        for (y, z) in lateral.into_iter().zip(vertical) {
            if kept.lateral.last().is_none_or(|&last| y > last) {
                kept.lateral.push(y);
                kept.vertical.push(z);
            }
        }
        Self::new(&kept)
    }

    /// The profile turned by `angle` \[rad\] about its origin, about the x axis: (y, z) →
    /// (y cos α − z sin α, y sin α + z cos α). Exact: the splines are linear in their knot
    /// values, and a rotation keeps the chord lengths.
    ///
    /// A flank turned past the vertical (a rail head's steep side, canted further) would make
    /// y turn back: the profile then keeps its running surface, the knots on either side of the
    /// highest point (least z) as far as y still increases, and drops the flanks' lower parts
    /// beyond, which no wheel reaches (the same piecewise cubics on the knots kept). It is an
    /// error only if fewer than four knots remain.
    pub fn rotated(&self, angle: f64) -> Result<Self, ProfileError> {
        let (sin, cos) = angle.sin_cos();
        let turn = |y: &[f64], z: &[f64]| -> (Vec<f64>, Vec<f64>) {
            y.iter().zip(z).map(|(&y, &z)| (y * cos - z * sin, y * sin + z * cos)).unzip()
        };
        let (lateral, vertical) = turn(&self.lateral.values, &self.vertical.values);
        let (lateral_second, vertical_second) = turn(&self.lateral.second, &self.vertical.second);
        let top = vertical.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |(i, _)| i);
        let mut first = top;
        while first > 0 && lateral[first - 1] < lateral[first] {
            first -= 1;
        }
        let mut last = top;
        while last + 1 < lateral.len() && lateral[last + 1] > lateral[last] {
            last += 1;
        }
        if last - first + 1 < 4 {
            return Err(ProfileError::whole(format!(
                "the profile turned by {angle} rad keeps {} points around its top before a flank turns past the \
                 vertical (y no longer increases); a profile needs at least 4",
                last - first + 1
            )));
        }
        let kept = first..=last;
        // The chord length is measured from the first knot kept.
        let start = self.knots[first];
        Ok(Self {
            knots: self.knots[kept.clone()].iter().map(|knot| knot - start).collect(),
            lateral: CubicSpline {
                values: lateral[kept.clone()].to_vec(),
                second: lateral_second[kept.clone()].to_vec(),
            },
            vertical: CubicSpline { values: vertical[kept.clone()].to_vec(), second: vertical_second[kept].to_vec() },
        })
    }

    /// The profile's extent checked against [`PROFILE_WIDTH`] and [`PROFILE_HEIGHT`] (`name`:
    /// "wheel" or "rail", for the message); [`WheelOnRail::new`](super::WheelOnRail::new)
    /// checks both profiles so. Besides the user's mistakes it catches (a length unit, a spike),
    /// it bounds what the placement allocates: the contact search samples the profiles every
    /// 0.025 mm over their width.
    pub fn check_extent(&self, name: &str) -> Result<(), ProfileError> {
        let (first, last) = self.lateral_range();
        let (top, bottom) = self.vertical_range();
        let (width, height) = (last - first, bottom - top);
        let (narrowest, widest) = PROFILE_WIDTH;
        if !(narrowest..=widest).contains(&width) {
            return Err(ProfileError::whole(format!(
                "the {name} profile is {:.6} mm wide (y from {:.6} to {:.6} mm): a wheel or rail profile is {} to {} mm \
                 wide (are its lengths in the units the file declares?)",
                width * 1e3,
                first * 1e3,
                last * 1e3,
                narrowest * 1e3,
                widest * 1e3
            )));
        }
        if !(..=PROFILE_HEIGHT).contains(&height) {
            return Err(ProfileError::whole(format!(
                "the {name} profile is {:.6} mm tall (z from {:.6} to {:.6} mm): a wheel or rail profile is at most {} mm \
                 tall (a spike, or a mistyped point?)",
                height * 1e3,
                top * 1e3,
                bottom * 1e3,
                PROFILE_HEIGHT * 1e3
            )));
        }
        Ok(())
    }

    /// The profile's lowest and highest z at its points \[m\] (z downward: its top first).
    pub fn vertical_range(&self) -> (f64, f64) {
        let values = &self.vertical.values;
        (values.iter().copied().fold(f64::INFINITY, f64::min), values.iter().copied().fold(f64::NEG_INFINITY, f64::max))
    }

    /// The profile's lateral extent \[m\]: its first and last point's y.
    pub fn lateral_range(&self) -> (f64, f64) {
        (self.lateral.values[0], self.lateral.values[self.lateral.values.len() - 1])
    }

    /// The profile's length along its points \[m\] (the largest s).
    pub fn length(&self) -> f64 {
        self.knots[self.knots.len() - 1]
    }

    /// The point at chord length `s` ∈ [0, length] (clamped to it).
    pub fn at_parameter(&self, s: f64) -> ProfilePoint {
        let s = s.clamp(0.0, self.length());
        let i = self.knots.partition_point(|&k| k <= s).clamp(1, self.knots.len() - 1) - 1;
        let h = self.knots[i + 1] - self.knots[i];
        let t = s - self.knots[i];
        let [y, dy, ddy] = self.lateral.evaluate(i, t, h);
        let [z, dz, ddz] = self.vertical.evaluate(i, t, h);
        let speed_squared = dy * dy + dz * dz;
        ProfilePoint {
            lateral: y,
            vertical: z,
            slope_angle: dz.atan2(dy),
            curvature: (dy * ddz - dz * ddy) / (speed_squared * speed_squared.sqrt()),
        }
    }

    /// The point at lateral position `y`, `None` outside the profile's lateral extent. Found by
    /// bisection on y(s) in its knot interval, then Newton on the cubic (y(s) increases along
    /// the profile; on near-vertical flanks the first point found with that y is returned).
    pub fn at_lateral(&self, y: f64) -> Option<ProfilePoint> {
        let (first, last) = self.lateral_range();
        if !(first..=last).contains(&y) {
            return None;
        }
        let values = &self.lateral.values;
        let i = values.partition_point(|&v| v < y).clamp(1, values.len() - 1) - 1;
        let h = self.knots[i + 1] - self.knots[i];
        let (mut low, mut high) = (0.0, h);
        let mut t = h * (y - values[i]) / (values[i + 1] - values[i]);
        for _ in 0..60 {
            let [value, slope, _] = self.lateral.evaluate(i, t, h);
            let residual = value - y;
            if residual.abs() <= 1e-13 {
                break;
            }
            if residual > 0.0 {
                high = t;
            } else {
                low = t;
            }
            let newton = t - residual / slope;
            // Newton inside the bracket, bisection when it would leave it.
            t = if slope > 0.0 && newton > low && newton < high { newton } else { 0.5 * (low + high) };
        }
        Some(self.at_parameter(self.knots[i] + t))
    }
}
