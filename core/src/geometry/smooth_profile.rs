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
//! A smoothing spline for measured, noisy profiles (CONTACT's `smooth_profile.m`) is not here
//! yet.
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
        let mut knots = Vec::with_capacity(y.len());
        knots.push(0.0);
        for i in 1..y.len() {
            knots.push(knots[i - 1] + (y[i] - y[i - 1]).hypot(z[i] - z[i - 1]));
        }
        Ok(Self { lateral: CubicSpline::natural(&knots, y), vertical: CubicSpline::natural(&knots, z), knots })
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
