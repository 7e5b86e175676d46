//! Measured profiles: MiniProf (`.whl`, `.ban`) and SIMPACK (`.prw`, `.prr`) files as
//! instruments and tools write them — worn shapes, hundreds of noisy points, back-steps in y,
//! overhanging flanks, either side, z up or down — read into the running surface a contact
//! search can use (y strictly increasing, z downward, the right side's, metres).
//!
//! What is done, in CONTACT's order (its `read_miniprof_profile`, `filter_close_points`,
//! `filter_double_kinks`, `check_z_pos_down` in `src/m_profile.f90`, and its user guide's
//! "Curation of anomalous input data"; the code is this project's own):
//!
//! 1. the file's points in its order: MiniProf's header forms ([`super::profile_file`]'s reader),
//!    its `Xoffset`/`Yoffset` added; SIMPACK's own options applied;
//! 2. a point within 0.1 µm of the last one kept is dropped (CONTACT's `point_dist_min`, 1e-4
//!    mm);
//! 3. zig-zags — two successive segments each turning by more than the threshold (default 5π/6,
//!    CONTACT's `ZIGTHRS`), as where two measured sections are stitched with their joint point
//!    repeated — the two points are replaced by their mean;
//! 4. z made downward (module 1): detected, unless the caller says it ([`Orientation`]). A rail's
//!    ends (its flanks, web or foot) lie below the median height of its points, a wheel's (its
//!    flange back and field face) above it; within 1 mm the file does not say, and the profile is
//!    refused rather than guessed (CONTACT's `check_z_pos_down` looks at the same side faces);
//! 5. y made the right side's (the track's centre towards −y): detected unless the caller says
//!    it. A wheel by its flange, the lowest point, which must lie on the −y half of the profile.
//!    A rail's shape does not say its gauge side, so a MiniProf rail is mirrored — MiniProf
//!    draws a rail with the track's centre towards +y: CONTACT's user guide says MiniProf rails
//!    "usually need mirror_y = 1", and its test bank reads every MiniProf rail so (`MIRRORY = 1`)
//!    and every MiniProf wheel as is — and a SIMPACK rail is taken as its own options leave it;
//! 6. ordered by increasing y, then the running surface kept: from the rail's top (least z) or
//!    the wheel's flange tip (greatest z), outwards on each side, each point that advances in y
//!    is kept; a point that steps back by less than the turn-back tolerance (default 2 mm:
//!    MiniProf's y wanders some 0.1 mm along a steep flank, and stitched sections overlap, by
//!    0.6 mm at the flange tip of the test file `Car7216_0001r.whl`) is noise and dropped; where
//!    the profile steps back by more, it turns under (a rail head's underside, web and foot, a lip,
//!    a flange back that turns under) and the rest of that side, which no wheel reaches, is
//!    dropped. CONTACT instead shifts steep points sideways (`remove_vertical_slopes`); dropping
//!    keeps every kept point as measured.
//!
//! Refused, with the line where one is to blame: what the readers refuse (a non-number, a header
//! line among the points, a point more than [`super::MAX_COORDINATE`] away), a profile whose z
//! direction cannot be told, fewer than four points kept.
//!
//! MiniProf's own axes: a wheel's y is measured from its flange back (y = 0 there, so
//! [`MeasuredProfile::flange_back_position`] is 0 for a MiniProf wheel, to pass to
//! [`super::TrackDimensions`]); a rail is measured in its own axes, not inclined, so the track's
//! rail inclination (1:40) is the placement's `rail_cant`.
//!
//! Smoothing is the caller's choice when the profile is made smooth ([`MeasuredProfile::smooth`],
//! [`SmoothProfile::smoothed`]); [`MEASURED_FILTER_WAVELENGTH`] is the default for measured
//! profiles.

use super::profile_file::{finish, miniprof_points, simpack_points, RawPoint, MINIPROF_UNITS, MIN_POINTS};
use super::profile_file::{ProfileError, ProfileFormat, ProfileKind, ProfilePoints};
use super::smooth_profile::SmoothProfile;
use std::f64::consts::PI;

/// Points closer than this to the last point kept are one point \[m\] (CONTACT's
/// `point_dist_min`, 1e-4 mm).
const CLOSEST_POINTS: f64 = 1e-7;

/// Within this height of the points' median, a profile's ends do not say which way z points \[m\].
const ORIENTATION_MARGIN: f64 = 1e-3;

/// The smoothing's filter wavelength for measured profiles \[m\]: 5 mm. The contact's Hertz
/// ellipse needs the profiles' curvatures, which a profile's noise spoils first: a 10 µm
/// zig-zag at 0.25 mm spacing on a 300 mm crown leaves the curvature 4.6 times off at 2 mm,
/// 0.9 at 3 mm, 0.12 at 5 mm, 0.02 at 8 mm (`core/tests/library/geometry_measured.rs`). On the
/// six MiniProf files of the tests the smoothed profile at 5 mm departs from the points by an
/// RMS of 4.5–27 µm, of the order of the measurement's own scatter, and the contact search
/// finds one contact where the unsmoothed profiles give it four noise minima. CONTACT leaves
/// smoothing off by default; its test bank smooths these files with its unweighted spline at
/// λ = 10 (`testbank.inp`), some 7–8 mm at their spacing by its user guide's conversion
/// L = 2π(λ·δs)^{1/4}; 5 mm keeps a low rail's field-side lip and a worn flange's shape a little
/// better.
pub const MEASURED_FILTER_WAVELENGTH: f64 = 5e-3;

/// How a measured profile's axis is turned: detected from its shape (module doc), or said by the
/// caller.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Orientation {
    /// Detected (module doc, steps 4 and 5).
    Detect,
    /// The file's direction kept.
    AsRead,
    /// The file's direction reversed (the coordinate negated).
    Mirrored,
}

/// The reading's choices (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredOptions {
    /// y: the right side's (track centre towards −y).
    pub lateral: Orientation,
    /// z: downward.
    pub vertical: Orientation,
    /// The zig-zag threshold \[rad\] (step 3); π or more disables it.
    pub zigzag_threshold: f64,
    /// How far \[m\] the profile may step back in y and still be noise on a flank (step 6).
    pub turn_back_tolerance: f64,
}

impl Default for MeasuredOptions {
    fn default() -> Self {
        Self {
            lateral: Orientation::Detect,
            vertical: Orientation::Detect,
            zigzag_threshold: 5.0 * PI / 6.0,
            turn_back_tolerance: 2e-3,
        }
    }
}

/// A measured profile as read and cleaned, with what was done to it.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredProfile {
    /// The running surface's points: y strictly increasing, z downward, the right side's.
    pub points: ProfilePoints,
    /// Whether y was mirrored.
    pub lateral_mirrored: bool,
    /// Whether z was mirrored.
    pub vertical_mirrored: bool,
    /// The flange back's y in these points' coordinates \[m\], where the file's axes say it
    /// (a MiniProf wheel: 0).
    pub flange_back_position: Option<f64>,
    /// The points the file holds.
    pub points_read: usize,
    /// Dropped within 0.1 µm of their neighbour.
    pub close_points: usize,
    /// Zig-zags, each pair of points replaced by its mean.
    pub zigzags: usize,
    /// Steps back in y within the tolerance, dropped as noise.
    pub back_steps: usize,
    /// Dropped beyond where the profile turns under.
    pub overhang_points: usize,
}

/// Reads and cleans a measured profile of `kind` (module doc).
///
/// ```
/// use wheel_rail_contact::geometry::{read_measured_profile, MeasuredOptions, ProfileFormat, ProfileKind};
///
/// // An old-style MiniProf wheel: z downward, y from the flange back; a zig-zag in y at
/// // lines 7–8 (y 2.0 then 1.99 mm) on the flange back's face.
/// let text = "MINIPROF 101 148 1994 3 24\nwheel.prd\n32.58 37.11 14.71  (Sd/Sh/qR)\n\n\
///             0 -10\n1 10\n2.0 20\n1.99 21\n3 26\n5 28\n8 26\n12 18\n20 6\n40 1\n70 0\n100 -1\n130 -3\n131 -20\n";
/// let wheel = read_measured_profile(text, ProfileFormat::MiniProf, ProfileKind::Wheel, &MeasuredOptions::default()).unwrap();
/// assert_eq!(wheel.points_read, 14);
/// assert_eq!((wheel.back_steps, wheel.lateral_mirrored, wheel.vertical_mirrored), (1, false, false));
/// assert_eq!(wheel.points.lateral.len(), 13);
/// assert_eq!(wheel.flange_back_position, Some(0.0));
/// assert_eq!(wheel.points.vertical.iter().copied().fold(f64::MIN, f64::max), 28e-3, "the flange tip");
/// // The same wheel written with z upward is turned back.
/// let upward: String = text.lines().enumerate().map(|(i, line)| {
///     if i < 4 { format!("{line}\n") } else {
///         let (y, z) = line.split_once(' ').unwrap();
///         format!("{y} {}\n", -z.parse::<f64>().unwrap())
///     }
/// }).collect();
/// let turned = read_measured_profile(&upward, ProfileFormat::MiniProf, ProfileKind::Wheel, &MeasuredOptions::default()).unwrap();
/// assert!(turned.vertical_mirrored);
/// assert_eq!(turned.points, wheel.points);
/// // Smoothed for the contact search with the measured profiles' default wavelength.
/// assert!(wheel.smooth(wheel_rail_contact::geometry::MEASURED_FILTER_WAVELENGTH).is_ok());
/// ```
pub fn read_measured_profile(
    text: &str,
    format: ProfileFormat,
    kind: ProfileKind,
    options: &MeasuredOptions,
) -> Result<MeasuredProfile, ProfileError> {
    let (points, units) = match format {
        ProfileFormat::MiniProf => (miniprof_points(text)?, MINIPROF_UNITS.to_string()),
        ProfileFormat::Simpack => simpack_points(text, Some(kind))?,
    };
    let points_read = points.len();
    if points_read < MIN_POINTS {
        return Err(ProfileError::whole(format!(
            "{points_read} profile points; a profile needs at least {MIN_POINTS}"
        )));
    }
    let mut points = drop_close_points(points);
    let close_points = points_read - points.len();
    let before = points.len();
    points = merge_zigzags(&points, options.zigzag_threshold);
    let zigzags = before - points.len();

    let vertical_mirrored = match options.vertical {
        Orientation::AsRead => false,
        Orientation::Mirrored => true,
        Orientation::Detect => z_points_up(&points, kind)?,
    };
    if vertical_mirrored {
        points.iter_mut().for_each(|p| p.z = -p.z);
    }
    let lateral_mirrored = match options.lateral {
        Orientation::AsRead => false,
        Orientation::Mirrored => true,
        Orientation::Detect => match kind {
            ProfileKind::Wheel => flange_towards_positive_y(&points),
            ProfileKind::Rail => format == ProfileFormat::MiniProf,
        },
    };
    if lateral_mirrored {
        points.iter_mut().for_each(|p| p.y = -p.y);
    }
    if points[points.len() - 1].y < points[0].y {
        points.reverse();
    }
    let surface = running_surface(&points, kind, options.turn_back_tolerance);
    let kept = surface.points.len();
    if kept < MIN_POINTS {
        return Err(ProfileError::whole(format!(
            "only {kept} points keep advancing in y around the {}'s {}{}: not a profile's running surface",
            kind.name(),
            match kind {
                ProfileKind::Rail => "top",
                ProfileKind::Wheel => "flange tip",
            },
            surface.turn_line.map_or(String::new(), |line| format!(" (it turns back at line {line})"))
        )));
    }
    let flange_back_position = (format == ProfileFormat::MiniProf && kind == ProfileKind::Wheel).then_some(0.0);
    Ok(MeasuredProfile {
        points: finish(surface.points, &units)?,
        lateral_mirrored,
        vertical_mirrored,
        flange_back_position,
        points_read,
        close_points,
        zigzags,
        back_steps: surface.back_steps,
        overhang_points: surface.overhang_points,
    })
}

impl MeasuredProfile {
    /// The smooth profile of the points with filter wavelength `wavelength` \[m\]
    /// ([`SmoothProfile::smoothed`]; [`MEASURED_FILTER_WAVELENGTH`] for measured profiles, 0 to
    /// interpolate the noise too).
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{
    ///     read_measured_profile, MeasuredOptions, ProfileFormat, ProfileKind, MEASURED_FILTER_WAVELENGTH,
    /// };
    ///
    /// // A rail crown of 300 mm radius every 0.25 mm, with a ±0.01 mm zig-zag in z, MiniProf's z up.
    /// let mut text = String::from("ColumnDef=X,Y\n\n");
    /// for i in -120i32..=120 {
    ///     let y = f64::from(i) * 0.25;
    ///     let noise = if i % 2 == 0 { 0.01 } else { -0.01 };
    ///     text.push_str(&format!("{y} {}\n", -(300.0 - (300.0f64 * 300.0 - y * y).sqrt()) + noise - if i.abs() > 100 { 5.0 } else { 0.0 }));
    /// }
    /// let rail = read_measured_profile(&text, ProfileFormat::MiniProf, ProfileKind::Rail, &MeasuredOptions::default()).unwrap();
    /// assert!(rail.vertical_mirrored && rail.lateral_mirrored);
    /// let smooth = rail.smooth(MEASURED_FILTER_WAVELENGTH).unwrap();
    /// let top = smooth.at_lateral(0.0).unwrap();
    /// assert!(top.vertical.abs() < 0.1e-6, "the crown's top: {}", top.vertical);
    /// assert!((top.curvature * 0.3 - 1.0).abs() < 0.15, "κ = {}", top.curvature);
    /// // Interpolated, the zig-zag's curvature swamps the crown's.
    /// let raw = rail.smooth(0.0).unwrap().at_lateral(0.0).unwrap();
    /// assert!(raw.curvature.abs() > 100.0, "κ = {}", raw.curvature);
    /// ```
    pub fn smooth(&self, wavelength: f64) -> Result<SmoothProfile, ProfileError> {
        SmoothProfile::smoothed(&self.points, wavelength)
    }
}

/// Step 2: each point within [`CLOSEST_POINTS`] of the last one kept dropped.
fn drop_close_points(points: Vec<RawPoint>) -> Vec<RawPoint> {
    let mut kept: Vec<RawPoint> = Vec::with_capacity(points.len());
    for p in points {
        match kept.last() {
            Some(last) if (p.y - last.y).hypot(p.z - last.z) < CLOSEST_POINTS => {}
            _ => kept.push(p),
        }
    }
    kept
}

/// Step 3: where segment i turns from segment i−1 and segment i+1 from segment i each by more
/// than `threshold`, segment i's two points are replaced by their mean.
fn merge_zigzags(points: &[RawPoint], threshold: f64) -> Vec<RawPoint> {
    let angle = |i: usize| (points[i + 1].z - points[i].z).atan2(points[i + 1].y - points[i].y);
    // The turn between two segments' angles, wrapped to [−π, π).
    let turn = |from: f64, to: f64| (to - from + PI).rem_euclid(2.0 * PI) - PI;
    let mut kept = Vec::with_capacity(points.len());
    let mut i = 0;
    while i < points.len() {
        let zigzag = i >= 1
            && i + 2 < points.len()
            && turn(angle(i - 1), angle(i)).abs() > threshold
            && turn(angle(i), angle(i + 1)).abs() > threshold;
        if zigzag {
            let (a, b) = (points[i], points[i + 1]);
            kept.push(RawPoint { y: 0.5 * (a.y + b.y), z: 0.5 * (a.z + b.z), line: a.line });
            i += 2;
        } else {
            kept.push(points[i]);
            i += 1;
        }
    }
    kept
}

/// Step 4: whether the points' z points up (module doc), an error if their ends do not say.
fn z_points_up(points: &[RawPoint], kind: ProfileKind) -> Result<bool, ProfileError> {
    let mut heights: Vec<f64> = points.iter().map(|p| p.z).collect();
    heights.sort_by(f64::total_cmp);
    let median = heights[heights.len() / 2];
    let ends = 0.5 * (points[0].z + points[points.len() - 1].z) - median;
    if ends.abs() < ORIENTATION_MARGIN {
        return Err(ProfileError::whole(format!(
            "cannot tell which way z points: the {} profile's ends lie {:.3} mm from its points' median height \
             (its flanks or faces are not measured); say it (`MeasuredOptions::vertical`)",
            kind.name(),
            ends * 1e3
        )));
    }
    // z downward: a rail's ends below (greater z), a wheel's above (smaller z).
    Ok(match kind {
        ProfileKind::Rail => ends < 0.0,
        ProfileKind::Wheel => ends > 0.0,
    })
}

/// Step 5 for a wheel (z downward): whether its flange tip, the greatest z, lies on the +y half.
fn flange_towards_positive_y(points: &[RawPoint]) -> bool {
    let tip = points.iter().max_by(|a, b| a.z.total_cmp(&b.z)).map_or(0.0, |p| p.y);
    let (least, most) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, m), p| (l.min(p.y), m.max(p.y)));
    tip > 0.5 * (least + most)
}

/// Step 6's result.
struct RunningSurface {
    points: Vec<RawPoint>,
    back_steps: usize,
    overhang_points: usize,
    /// The line where a side turned back, if one did.
    turn_line: Option<usize>,
}

/// Step 6 (module doc): from the rail's top or the wheel's flange tip outwards, the points that
/// advance in y; back-steps within `tolerance` dropped, a side ended where it turns back further.
fn running_surface(points: &[RawPoint], kind: ProfileKind, tolerance: f64) -> RunningSurface {
    let anchor = match kind {
        ProfileKind::Rail => points.iter().enumerate().min_by(|a, b| a.1.z.total_cmp(&b.1.z)),
        ProfileKind::Wheel => points.iter().enumerate().max_by(|a, b| a.1.z.total_cmp(&b.1.z)),
    }
    .map_or(0, |(i, _)| i);
    let mut surface = RunningSurface { points: Vec::new(), back_steps: 0, overhang_points: 0, turn_line: None };
    // One side: `outward` is +1 towards increasing y (after the anchor), −1 before it.
    let mut side = |order: &mut dyn Iterator<Item = usize>, outward: f64| -> Vec<RawPoint> {
        let mut kept = Vec::new();
        let mut reach = points[anchor].y * outward;
        let remaining: Vec<usize> = order.collect();
        for (k, &i) in remaining.iter().enumerate() {
            let advance = points[i].y * outward - reach;
            if advance > 0.0 {
                reach += advance;
                kept.push(points[i]);
            } else if advance >= -tolerance {
                surface.back_steps += 1;
            } else {
                surface.overhang_points += remaining.len() - k;
                surface.turn_line = surface.turn_line.or(Some(points[i].line));
                break;
            }
        }
        kept
    };
    let mut before = side(&mut (0..anchor).rev(), -1.0);
    let after = side(&mut (anchor + 1..points.len()), 1.0);
    before.reverse();
    before.push(points[anchor]);
    before.extend(after);
    surface.points = before;
    surface
}
