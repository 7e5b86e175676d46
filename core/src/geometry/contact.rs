//! A wheel on its rail: placement on the track, the undeformed gap, the contact
//! points (tread and flange, each a local minimum of the gap) and the normal problem with a
//! Hertz ellipse per patch.
//!
//! Conventions (CONTACT's module 1): track coordinates x along the track in the rolling
//! direction, y lateral positive to the right, z downward; roll about x. The profiles are the
//! right side's, in their own coordinates (y lateral, z downward, metres).
//!
//! Placement. The rail: turned by its cant about its profile's origin (towards the track's
//! centre), its highest point at z = 0 and its gauge face — the point on its inner (y < 0) flank
//! at the gauge measuring height below its top — at y = gauge/2, as CONTACT places it. The wheel: its profile's flange back
//! (y = `flange_back_position`) lies at y = `flange_back_distance`/2 in wheelset coordinates,
//! the profile's z = 0 on the nominal radius r0 below the axle. The wheelset at (y_ws, z_ws,
//! roll φ, yaw ψ): the wheel is the surface of revolution of its profile about the axle; its
//! point at profile y, angle θ from the bottom, (r sin θ, Y, r cos θ) from the axle centre
//! (Y = profile y + the flange back's offset, r = r0 + z_wheel), goes to c + R_z(ψ)R_x(φ)·(that),
//! c = (0, y_ws, z_ws − r0). With φ = ψ = 0, z_ws = 0 the wheel's datum is at the rail top's
//! level (as CONTACT's Z_WS; its case A-2.2 deck reports z_ws = 0.198 mm on y_ws = 0).
//!
//! Yaw. The rail is straight along x, so its normal has no x component, and at a contact
//! point the wheel's normal must not have one either: per profile point, the angle θ where the
//! turned normal (sin θ cos γ, −sin γ, cos θ cos γ) (γ the profile's slope) has no x component
//! solves A sin θ + B cos θ = C in closed form (A = cos γ cos ψ, B = cos γ sin φ sin ψ, C = −sin γ
//! cos φ sin ψ). These points form the wheel's contact locus; θ ≈ −tan γ tan ψ puts a flange
//! contact (tan γ ≈ 2) 20–30 mm ahead of or behind the axle at ψ = 10–24 mrad, and shifts it
//! 0.1–0.7 mm laterally. The gap is taken between the rail and the locus, whose track y follows
//! the profile's y by a fixed-point iteration. On A-2.2 the contact positions agree with
//! CONTACT's within 0.004 mm on the flange, 0.03 mm in x (0.07–0.1 mm on the flange without
//! yaw).
//!
//! Contact points. The gap g(y) = z_rail(y) − z_wheel(y) (vertical, undeformed) is sampled every
//! 0.2 mm over the profiles' common lateral range; each interior local minimum, refined by
//! Brent's method, is a candidate contact point. The wheelset's vertical position shifts
//! the gap uniformly, so the candidates do not depend on it: a candidate with g_i < z_ws is in
//! contact, penetrating vertically by z_ws − g_i, along its normal by (z_ws − g_i) cos δ.
//! Two candidates whose interpenetration regions join are one patch (the deeper one kept).
//! Where two such minima swap which is deeper, the patch's point jumps between them: for S1002
//! on UIC60 at y_ws ≈ 0.22 mm on the tread and ≈ 6.62 mm from the flange root to the flange
//! (`core/tests/library/geometry_benchmark.rs`); CONTACT, which solves the non-Hertzian patch, moves its
//! contact reference between the same places between its A-2.2 cases. Elsewhere the points move
//! continuously with y_ws, and the load passes between separate patches continuously.
//!
//! Contact table. The gap is scanned on the sampled profiles (`sampled_profile.rs`); the full scan
//! reads ≈ 400 samples. At placement a table stores the gap's minima of the unyawed wheel every
//! 0.1 mm of the wheel bottom's lateral position y_ws − r0 sin φ − Y (1 − cos ψ) (±20 mm) and
//! every 0.002 rad of roll (±0.012 rad); a search then scans, on the same samples, from 1 mm
//! before the first to 1 mm beyond the last minimum of the neighbouring rows (0.2 mm of key, more
//! under yaw) and rolls — one stretch, so that a minimum born between the nodes where the gap is
//! flat, between their minima, is found too; it finds what the full scan finds near contact
//! (tested over 20 000 random poses each run, 200 000 once: identical). Beyond the table, and beyond 0.025 rad of yaw,
//! the full scan runs.
//!
//! Ellipse: Hertz per patch ([`crate::hertz::HertzContact`]) from the relative curvatures at the
//! contact point. The wheel's principal curvatures are cos γ/r along its parallel (Meusnier's
//! theorem) and −κ_wheel along its profile; the rail bends only laterally (κ_rail; curvatures
//! positive bending downward: the rail's convex crown, the wheel's concave throat). Without yaw
//! the parallel runs along x: A = cos γ/(2 r), B = (κ_rail − κ_wheel)/2. With yaw it is turned
//! from x by the angle whose cosine c is the locus' `circumferential_x`, and Euler's theorem
//! gives the curvatures along x and across: A = (c² cos γ/r − (1 − c²) κ_wheel)/2, B = (κ_rail +
//! (1 − c²) cos γ/r − c² κ_wheel)/2 (the twist term is dropped: the ellipse stays aligned with
//! x). Hertz because it is what multibody codes use online and needs one evaluation per patch;
//! on A-2.2 its patches give, with the exact theory, creep forces within 0.041 μN of CONTACT's
//! non-Hertzian solution (`core/tests/library/geometry_wheel_forces.rs`), inside the 0.12 μN of CONTACT's
//! own fast methods. Normal force from the normal penetration δ_n by Hertz's
//! Q ∝ δ_n^{3/2} (the same ellipse solution at 1 N gives the constant).
//!
//! The left wheel on the left rail is the right side mirrored (y → −y, roll → −roll, yaw → −yaw; reported
//! positions and contact angles mirrored back), as CONTACT does.
//!
//! The creepages and forces of the patches: [`crate::wheel`].

use super::normal_problem::{Candidate, ContactCandidates};
use super::patch::{ContactPatch, ContactPoint, WheelSide};
use super::profile_file::ProfileError;
use super::sampled_profile::SampledProfile;
use super::smooth_profile::{ProfilePoint, SmoothProfile};
use super::strip_grid::StripGrid;
use super::strip_table::StripTable;
use crate::hertz::contact_modulus;
use crate::InvalidInput;
use std::sync::OnceLock;

impl WheelSide {
    /// The right wheel's position that mirrors this side's: y_ws and roll change sign.
    fn mirror_position(self, position: &WheelsetPosition) -> WheelsetPosition {
        match self {
            Self::Right => *position,
            Self::Left => {
                WheelsetPosition { lateral: -position.lateral, roll: -position.roll, yaw: -position.yaw, ..*position }
            }
        }
    }
}

/// The track and wheelset dimensions the placement needs \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackDimensions {
    /// Gauge between the rails' gauge faces.
    pub gauge: f64,
    /// How far below the rail top the gauge is measured (14 mm in EN 13848-1).
    pub gauge_measuring_height: f64,
    /// Distance between the wheels' flange backs.
    pub flange_back_distance: f64,
    /// The flange back's lateral position in the wheel profile's coordinates.
    pub flange_back_position: f64,
    /// The wheel's radius at its profile's z = 0.
    pub nominal_radius: f64,
    /// The rail's cant \[rad\]: the rail profile turned by this angle about its own origin,
    /// towards the track's centre (as CONTACT's CANT), on top of any inclination its points
    /// already have (UIC60 1:40 as shipped is "already canted": 0 here).
    pub rail_cant: f64,
}

impl TrackDimensions {
    /// The Manchester contact benchmark's track and wheelset (case A-2.2 as CONTACT's example
    /// decks state it): gauge 1435 mm measured 14 mm below the rail top, flange backs 1360 mm
    /// apart at −70 mm in the S1002 profile's coordinates, nominal radius 460 mm.
    pub const MANCHESTER_BENCHMARK: Self = Self {
        gauge: 1.435,
        gauge_measuring_height: 0.014,
        flange_back_distance: 1.360,
        flange_back_position: -0.070,
        nominal_radius: 0.460,
        rail_cant: 0.0,
    };
}

/// The wheelset's position relative to the track.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelsetPosition {
    /// y_ws \[m\], positive to the right.
    pub lateral: f64,
    /// z_ws \[m\], downward (module doc).
    pub vertical: f64,
    /// φ_ws \[rad\], about x.
    pub roll: f64,
    /// ψ_ws \[rad\], about z (positive turns the wheelset's heading towards +y).
    pub yaw: f64,
}

/// A point of the wheel's contact locus (module doc, "Yaw").
#[derive(Debug, Clone, Copy)]
struct WheelLocusPoint {
    /// The wheel profile's point.
    profile: ProfilePoint,
    /// The wheel's radius there, r0 + z_wheel.
    radius: f64,
    /// The point's depth below the axle in the wheel's plane x = 0, r cos θ: the radius that
    /// turns the wheel's angular speed into its circumferential speed along x.
    rolling_radius: f64,
    /// Track x, y, z of the point.
    longitudinal: f64,
    lateral: f64,
    vertical: f64,
    /// cos of the angle between the wheel's circumferential direction there and track x.
    circumferential_x: f64,
}

/// Sampling step of the gap \[m\]: finer than the profiles' point spacing (≈ 0.35 mm). The
/// samples only bracket the gap's minima for Brent's refinement and give the barriers between
/// them; at 0.2 mm the search reads half the samples of 0.1 mm (the step before: 6 000–8 000
/// fewer instructions per wheel step where it scans 10–14 mm) and finds the same candidates near
/// contact, within 4.3e-8 m, a minimum being born 13 µm of y_ws later
/// (`sampling_every_0_2_mm_finds_what_0_1_mm_finds`).
const SAMPLE_STEP: f64 = 2e-4;

/// Profile samples per step of the gap ([`SampledProfile`]: 0.025 mm, its heights within 2 nm).
const SAMPLES_PER_STEP: u32 = 8;

/// A wheel profile and a rail profile placed on a track.
///
/// The right wheel of the Manchester benchmark's wheelset 3 mm to the right, frictionless under
/// 500 N, against CONTACT's module 1 on the same profiles (`core/tests/data/conicity_contact.csv`:
/// rail y −20.44 mm, wheel y −12.91 mm, rolling radius 460.76 mm, contact angle −0.0908 rad,
/// z_ws −0.0338 mm):
///
/// ```
/// use wheel_rail_contact::geometry::{builtin_profile, SmoothProfile, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition};
///
/// let profile = |name| SmoothProfile::new(&builtin_profile(name).unwrap()).unwrap();
/// let (wheel, rail) = (profile("MBench_S1002"), profile("MBench_UIC60"));
/// let placed = WheelOnRail::new(wheel, rail, TrackDimensions::MANCHESTER_BENCHMARK, WheelSide::Right, 82e9, 0.28).unwrap();
/// let position = WheelsetPosition { lateral: 3e-3, ..WheelsetPosition::default() };
/// // The candidates (the gap's local minima): the deepest is where the wheel touches.
/// let points = placed.contact_points(&position).unwrap();
/// let touch = points.iter().min_by(|a, b| a.gap_at_zero.total_cmp(&b.gap_at_zero)).unwrap();
/// assert!((touch.rail_lateral + 20.44e-3).abs() < 0.1e-3, "rail y {}", touch.rail_lateral);
/// assert!((touch.wheel_lateral + 12.91e-3).abs() < 0.1e-3, "wheel y {}", touch.wheel_lateral);
/// assert!((touch.rolling_radius - 0.46076).abs() < 0.05e-3, "r {}", touch.rolling_radius);
/// assert!((touch.contact_angle + 0.0908).abs() < 0.002, "δ {}", touch.contact_angle);
/// // The contact table's search finds what the full scan finds.
/// assert_eq!(placed.candidates_by_full_scan(&position).unwrap().points(), points);
/// // Prescribed force: 500 N carried by N cos δ (frictionless).
/// let (height, patches) = placed.patches_for_force(500.0, &position, |point| point.contact_angle.cos()).unwrap();
/// assert!((height + 0.0338e-3).abs() < 0.5e-6, "z_ws {height}");
/// let carried: f64 = patches.iter().map(|p| p.normal_force * p.point.contact_angle.cos()).sum();
/// assert!((carried - 500.0).abs() < 1e-6);
/// // Prescribed position: the same height gives the same patches.
/// let at_height = WheelsetPosition { vertical: height, ..position };
/// assert_eq!(placed.patches_at(&at_height).unwrap(), patches);
/// assert_eq!(placed.wheelset_centre(&at_height), [0.0, 3e-3, height - 0.46]);
/// ```
#[derive(Debug, Clone)]
pub struct WheelOnRail {
    pub(super) wheel: SmoothProfile,
    rail: SmoothProfile,
    pub(super) dimensions: TrackDimensions,
    side: WheelSide,
    /// The contact table (module doc, "Contact table"), built at placement.
    table: ContactTable,
    /// The profiles sampled for the contact search ([`SampledProfile`]).
    wheel_samples: SampledProfile,
    pub(super) rail_samples: SampledProfile,
    /// Track y of the rail profile's origin.
    pub(super) rail_offset: f64,
    /// Track z of the rail profile's origin: its highest point lies at z = 0 (as CONTACT places
    /// a rail on a track).
    pub(super) rail_lift: f64,
    /// Wheelset y of the wheel profile's origin.
    pub(super) wheel_offset: f64,
    contact_modulus: f64,
    /// Where the non-Hertzian strips lie on the wheel profile (`strip_grid.rs`), made at the
    /// first non-Hertzian use ([`Self::strip_grid`]): a wheel in Hertz contact does not pay it.
    strip_grid: OnceLock<StripGrid>,
    /// The non-Hertzian strips' wheel table ([`Self::with_strip_table`]), if built.
    pub(super) strip_table: Option<StripTable>,
}

impl WheelOnRail {
    /// Places the profiles (given for the right side) on `side` (module doc); G, ν for the
    /// Hertz ellipses.
    pub fn new(
        wheel: SmoothProfile,
        rail: SmoothProfile,
        dimensions: TrackDimensions,
        side: WheelSide,
        shear_modulus: f64,
        poisson_ratio: f64,
    ) -> Result<Self, ProfileError> {
        let named = |e: InvalidInput| ProfileError::whole(e.to_string());
        let modulus = contact_modulus(shear_modulus, poisson_ratio).map_err(named)?;
        for (name, value) in [
            ("track_gauge", dimensions.gauge),
            ("gauge_measuring_height", dimensions.gauge_measuring_height),
            ("flange_back_distance", dimensions.flange_back_distance),
            ("wheel_nominal_radius", dimensions.nominal_radius),
        ] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(ProfileError::whole(format!("{name} = {value} must be finite and > 0")));
            }
        }
        if !dimensions.flange_back_position.is_finite() {
            return Err(ProfileError::whole(format!(
                "flange_back_position = {} must be finite",
                dimensions.flange_back_position
            )));
        }
        if !(-0.1..=0.1).contains(&dimensions.rail_cant) {
            return Err(ProfileError::whole(format!("rail_cant = {} rad must be within ±0.1", dimensions.rail_cant)));
        }
        wheel.check_extent("wheel")?;
        rail.check_extent("rail")?;
        // The cant turns the rail towards the track's centre (for the right rail, the field
        // side up: −cant about x), about its profile's origin, as CONTACT's CANT.
        let rail = if dimensions.rail_cant == 0.0 {
            rail
        } else {
            rail.rotated(-dimensions.rail_cant)
                .map_err(|e| ProfileError::whole(format!("rail_cant = {} rad: {e}", dimensions.rail_cant)))?
        };
        let (gauge_face, top) = gauge_face(&rail, dimensions.gauge_measuring_height)?;
        let mut placed = Self {
            table: ContactTable { minima: Vec::new() },
            rail_offset: 0.5 * dimensions.gauge - gauge_face,
            rail_lift: -top,
            wheel_offset: 0.5 * dimensions.flange_back_distance - dimensions.flange_back_position,
            wheel_samples: SampledProfile::new(&wheel, SAMPLE_STEP / f64::from(SAMPLES_PER_STEP)),
            rail_samples: SampledProfile::new(&rail, SAMPLE_STEP / f64::from(SAMPLES_PER_STEP)),
            strip_grid: OnceLock::new(),
            wheel,
            rail,
            dimensions,
            side,
            contact_modulus: modulus,
            strip_table: None,
        };
        placed.table = ContactTable::new(&placed);
        crate::hertz::table::prepare();
        Ok(placed)
    }

    /// Where the non-Hertzian strips lie on the wheel profile (made on the first call).
    pub(super) fn strip_grid(&self) -> &StripGrid {
        self.strip_grid.get_or_init(|| StripGrid::new(&self.wheel))
    }

    /// The Manchester contact benchmark's wheel on its rail, on `side`: the built-in S1002 wheel
    /// on the UIC60 rail (canted 1:40 in its file), [`TrackDimensions::MANCHESTER_BENCHMARK`],
    /// steel with G = 82 GPa and ν = 0.28 (CONTACT's decks of case A-2.2). The set-up of the
    /// benchmark's tests, examples and figures, in one place.
    ///
    /// The benchmark's wheelset is symmetric: the left wheel at y_ws = −3 mm touches as the right
    /// one does at +3 mm, on the mirrored side of the track.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    ///
    /// let touch = |side, lateral| {
    ///     let placed = WheelOnRail::manchester_benchmark(side);
    ///     let position = WheelsetPosition { lateral, ..WheelsetPosition::default() };
    ///     let points = placed.contact_points(&position).unwrap();
    ///     *points.iter().min_by(|a, b| a.gap_at_zero.total_cmp(&b.gap_at_zero)).unwrap()
    /// };
    /// let (right, left) = (touch(WheelSide::Right, 3e-3), touch(WheelSide::Left, -3e-3));
    /// // CONTACT's module 1 on these profiles: wheel y −12.91 mm, rolling radius 460.76 mm.
    /// assert!((right.wheel_lateral + 12.91e-3).abs() < 0.1e-3, "wheel y {}", right.wheel_lateral);
    /// assert!((right.rolling_radius - 0.46076).abs() < 0.05e-3, "r {}", right.rolling_radius);
    /// assert!((left.rolling_radius - right.rolling_radius).abs() < 1e-12);
    /// assert!((left.track_lateral + right.track_lateral).abs() < 1e-12, "{} {}", left.track_lateral, right.track_lateral);
    /// ```
    pub fn manchester_benchmark(side: WheelSide) -> Self {
        let profile = |name| {
            let points = super::builtin_profile(name).expect("a built-in profile's name");
            SmoothProfile::new(&points).expect("the built-in profiles are smooth")
        };
        Self::new(
            profile("MBench_S1002"),
            profile("MBench_UIC60"),
            TrackDimensions::MANCHESTER_BENCHMARK,
            side,
            82e9,
            0.28,
        )
        .expect("the benchmark's track and steel are valid")
    }

    /// The wheel's contact locus at wheel profile y `profile_y` (module doc, "Yaw"): the point
    /// of the wheel's circle there whose surface normal has no x component in track
    /// coordinates, with its track position (x, y, z at z_ws = `position.vertical`) and the
    /// cosine between the wheel's circumferential direction there and the track's x axis.
    fn locus_at(&self, profile_y: f64, position: &WheelsetPosition) -> Option<WheelLocusPoint> {
        let profile = self.wheel.at_lateral(profile_y)?;
        let radius = self.dimensions.nominal_radius + profile.vertical;
        let (sin_roll, cos_roll) = position.roll.sin_cos();
        let (sin_yaw, cos_yaw) = position.yaw.sin_cos();
        let (sin_slope, cos_slope) = profile.slope_angle.sin_cos();
        // Normal (sin θ cos γ, −sin γ, cos θ cos γ) in wheelset axes, turned by R_z(ψ)R_x(φ):
        // its x component A sin θ + B cos θ − C vanishes, A sin θ + B cos θ = C.
        let (a, b) = (cos_slope * cos_yaw, cos_slope * sin_roll * sin_yaw);
        let c = -sin_slope * cos_roll * sin_yaw;
        let amplitude = a.hypot(b);
        let ratio = c / amplitude;
        if ratio.is_nan() || ratio.abs() >= 1.0 {
            return None;
        }
        // The branch near the bottom of the wheel (θ = 0 without yaw).
        let angle = ratio.asin() - b.atan2(a);
        let (sin_angle, cos_angle) = angle.sin_cos();
        let wheelset_y = profile_y + self.wheel_offset;
        // The point (r sin θ, Y, r cos θ) from the axle centre, turned by R_x(φ), then R_z(ψ).
        let (qx, qy, qz) = (radius * sin_angle, wheelset_y, radius * cos_angle);
        let (ry, rz) = (qy * cos_roll - qz * sin_roll, qy * sin_roll + qz * cos_roll);
        Some(WheelLocusPoint {
            profile,
            radius,
            rolling_radius: qz,
            longitudinal: qx * cos_yaw - ry * sin_yaw,
            lateral: position.lateral + qx * sin_yaw + ry * cos_yaw,
            vertical: position.vertical - self.dimensions.nominal_radius + rz,
            // The circumferential tangent (cos θ, 0, −sin θ) turned the same way, its x.
            circumferential_x: cos_angle * cos_yaw - sin_angle * sin_roll * sin_yaw,
        })
    }

    /// The wheelset's centre on its axle, (0, y_ws, z_ws − r0) in track axes \[m\].
    pub fn wheelset_centre(&self, position: &WheelsetPosition) -> [f64; 3] {
        [0.0, position.lateral, position.vertical - self.dimensions.nominal_radius]
    }

    /// The candidate contact points (module doc) for the wheelset's lateral position, roll and
    /// yaw, tread first (ordered from the rail's field side to its gauge side); the vertical
    /// position is not used.
    pub fn contact_points(&self, position: &WheelsetPosition) -> Result<Vec<ContactPoint>, ProfileError> {
        Ok(self.candidates(position)?.points())
    }

    /// The loaded patches at the wheelset's vertical position (prescribed position): every
    /// candidate the wheel penetrates, merged where their interpenetration joins.
    pub fn patches_at(&self, position: &WheelsetPosition) -> Result<Vec<ContactPatch>, ProfileError> {
        self.candidates(position)?.patches_at(position.vertical)
    }

    /// Prescribed vertical force on the wheel \[N\] ([`ContactCandidates::patches_for_force`]).
    pub fn patches_for_force(
        &self,
        vertical_force: f64,
        position: &WheelsetPosition,
        vertical_share: impl Fn(&ContactPoint) -> f64,
    ) -> Result<(f64, Vec<ContactPatch>), ProfileError> {
        self.candidates(position)?.patches_for_force(vertical_force, vertical_share)
    }

    /// The contact search (module doc, "Contact points") for the wheelset's lateral position,
    /// roll and yaw: the candidates, from which the normal problem is solved at any vertical
    /// position or force without searching again. Started from the contact table's minima where
    /// it covers the position (module doc, "Contact table"), by the full scan elsewhere.
    pub fn candidates(&self, position: &WheelsetPosition) -> Result<ContactCandidates, ProfileError> {
        check_position(position)?;
        let position = WheelsetPosition { vertical: 0.0, ..self.side.mirror_position(position) };
        let search = GapSearch::new(self, &position);
        let (minima, barriers) = self.search(&search)?;
        self.candidates_at(&minima, barriers, &position)
    }

    /// The gap's minima of the contact search (wheel profile y, refined) and the barriers between
    /// them: from the contact table's span where it covers the pose, by the full scan elsewhere.
    fn search(&self, search: &GapSearch) -> Result<(Vec<f64>, Vec<f64>), ProfileError> {
        Ok(search.refined(self.sampled_search(search)?))
    }

    /// [`Self::search`]'s pass over the sampled gap, its minima not yet refined.
    fn sampled_search(&self, search: &GapSearch) -> Result<Minima, ProfileError> {
        let position = &search.position;
        let span = (position.yaw.abs() <= TABLE_YAW_REACH)
            .then(|| self.table.span(search.table_key(), search.key_reach(), position.roll))
            .flatten();
        match span.and_then(|span| search.sampled_near(span)) {
            Some(found) => Ok(found),
            None => search.sampled_scan(),
        }
    }

    /// The contact search's minima of the right-side pose `right` (z_ws = 0) as (wheel profile
    /// y, the sampled gap there): the lowest sample of each, not refined by Brent's method (its
    /// exact point is not needed, and refining was half the search's cost): where the
    /// non-Hertzian strip table's stretches start (`strip_table.rs`), which grow from them strip
    /// by strip while the gap lies within reach.
    pub(super) fn gap_minima(&self, right: &WheelsetPosition) -> Result<Vec<(f64, f64)>, ProfileError> {
        let search = GapSearch::new(self, right);
        let found = self.sampled_search(&search)?;
        Ok(found.minima.iter().map(|minimum| minimum.lowest).collect())
    }

    /// [`Self::candidates`] by the full scan alone, never from the contact table: the reference
    /// the table's searches are measured against (`core/tests/library/geometry_benchmark.rs`).
    pub fn candidates_by_full_scan(&self, position: &WheelsetPosition) -> Result<ContactCandidates, ProfileError> {
        check_position(position)?;
        let position = WheelsetPosition { vertical: 0.0, ..self.side.mirror_position(position) };
        let (minima, barriers) = GapSearch::new(self, &position).scan()?;
        self.candidates_at(&minima, barriers, &position)
    }

    /// The pose in the right side's frame at z_ws = 0, checked: what the non-Hertzian normal
    /// problem ([`super::non_hertzian`]) evaluates its strips in.
    pub(super) fn right_pose(&self, position: &WheelsetPosition) -> Result<WheelsetPosition, ProfileError> {
        check_position(position)?;
        Ok(WheelsetPosition { vertical: 0.0, ..self.side.mirror_position(position) })
    }

    /// The side this wheel is on.
    pub(super) fn side(&self) -> WheelSide {
        self.side
    }

    /// E* = G/(1 − ν) \[Pa\] of the wheel and rail.
    pub(super) fn contact_modulus(&self) -> f64 {
        self.contact_modulus
    }

    /// The undeformed vertical gap of the right-side pose `right` (z_ws = 0) as a function of the
    /// wheel profile's y, read from the sampled profiles as the contact search reads it (+∞ off
    /// the profiles), and the wheel profile's y range that lies over the rail (the full scan's).
    pub(super) fn gap_function(&self, right: &WheelsetPosition) -> (impl Fn(f64) -> f64 + '_, (f64, f64)) {
        let search = GapSearch::new(self, right);
        let range = search.range_over_rail();
        (move |profile_y| search.gap(profile_y), range)
    }

    /// The exact (spline) geometry at wheel profile y of the right-side pose `right`, as a
    /// candidate contact point there: track and profile positions, the rail's slope (its
    /// `contact_angle`), the rolling radius, the gap at z_ws = 0 and the curvatures.
    pub(super) fn surface_point(&self, profile_y: f64, right: &WheelsetPosition) -> Result<ContactPoint, ProfileError> {
        Ok(self.candidate(profile_y, right)?.point)
    }

    fn candidates_at(
        &self,
        minima: &[f64],
        barriers: Vec<f64>,
        position: &WheelsetPosition,
    ) -> Result<ContactCandidates, ProfileError> {
        let candidates =
            minima.iter().map(|&profile_y| self.candidate(profile_y, position)).collect::<Result<_, _>>()?;
        Ok(ContactCandidates::new(self.side, candidates, barriers))
    }

    /// The candidate at wheel profile y (exact splines); its Hertz solution under 1 N is solved
    /// when it is first loaded.
    fn candidate(&self, profile_y: f64, position: &WheelsetPosition) -> Result<Candidate, ProfileError> {
        let off = || ProfileError::whole(format!("contact point at wheel profile y = {profile_y} m off the profiles"));
        let wheel = self.locus_at(profile_y, position).ok_or_else(off)?;
        let rail = self.rail.at_lateral(wheel.lateral - self.rail_offset).ok_or_else(off)?;
        // Relative curvatures (module doc, "Ellipse"): the wheel's principal curvatures are
        // cos γ/r along its circumference and −κ_wheel along its profile; seen along the track's
        // x axis, at cos² = c² of the circumference's angle to it (Euler's theorem), and along
        // the patch's lateral axis at 1 − c². The straight rail bends only laterally.
        let circumferential = wheel.profile.slope_angle.cos() / wheel.radius;
        let along_x = wheel.circumferential_x * wheel.circumferential_x;
        let point = ContactPoint {
            track_longitudinal: wheel.longitudinal,
            track_lateral: wheel.lateral,
            track_vertical: rail.vertical + self.rail_lift,
            rail_lateral: rail.lateral,
            wheel_lateral: wheel.profile.lateral,
            contact_angle: rail.slope_angle,
            contact_angle_sin_cos: rail.slope_angle.sin_cos(),
            rolling_radius: wheel.rolling_radius,
            gap_at_zero: rail.vertical + self.rail_lift - wheel.vertical,
            curvature_rolling: 0.5 * (along_x * circumferential - (1.0 - along_x) * wheel.profile.curvature),
            curvature_lateral: 0.5
                * (rail.curvature + (1.0 - along_x) * circumferential - along_x * wheel.profile.curvature),
        };
        Ok(Candidate::new(point, self.contact_modulus))
    }
}

/// The rotation R_z(ψ)R_x(φ) of a wheelset position and the constants of its contact locus'
/// equation A sin θ + B cos θ = C (module doc, "Yaw"), with cos γ divided out: A/cos γ = cos ψ,
/// B/cos γ = sin φ sin ψ, C/cos γ = −tan γ cos φ sin ψ.
#[derive(Clone, Copy)]
pub(super) struct LocusFrame {
    sin_roll: f64,
    cos_roll: f64,
    sin_yaw: f64,
    cos_yaw: f64,
    /// sin β, cos β of β = atan2(B, A).
    sin_phase: f64,
    cos_phase: f64,
    /// −cos φ sin ψ / √(A² + B²) (per unit tan γ, cos γ divided out).
    ratio_per_slope: f64,
    lateral: f64,
}

impl LocusFrame {
    pub(super) fn new(position: &WheelsetPosition) -> Self {
        let (sin_roll, cos_roll) = position.roll.sin_cos();
        let (sin_yaw, cos_yaw) = position.yaw.sin_cos();
        let (a, b) = (cos_yaw, sin_roll * sin_yaw);
        let amplitude = a.hypot(b);
        Self {
            sin_roll,
            cos_roll,
            sin_yaw,
            cos_yaw,
            sin_phase: b / amplitude,
            cos_phase: a / amplitude,
            ratio_per_slope: -cos_roll * sin_yaw / amplitude,
            lateral: position.lateral,
        }
    }

    /// Track y and z (z_ws = 0) of the locus point at wheel profile y with height z_wheel and
    /// slope tan γ, and its rolling radius r cos θ (as [`WheelOnRail::locus_at`]'s); `None`
    /// where the locus has no point (|sin θ + β| would exceed 1).
    #[inline(always)]
    pub(super) fn track_position(
        &self,
        wheel: &WheelOnRail,
        profile_y: f64,
        height: f64,
        slope: f64,
    ) -> Option<(f64, f64, f64)> {
        let placement = (wheel.dimensions.nominal_radius, wheel.wheel_offset);
        self.track_position_of::<true>(placement, profile_y, height, slope)
    }

    /// [`Self::track_position`]; `YAWED = false` only where the yaw is 0 (`sin_yaw` = 0,
    /// `cos_yaw` = 1): there θ = 0 (ratio ±0, β = 0: sin θ = ±0, cos θ = 1 exactly) and the
    /// rotation is the roll's alone, the same numbers without the square root and the
    /// multiplications by 0 and 1 (`the_unyawed_locus_is_the_yawed_one_at_zero_yaw`).
    #[inline(always)]
    fn track_position_of<const YAWED: bool>(
        &self,
        (nominal_radius, wheel_offset): (f64, f64),
        profile_y: f64,
        height: f64,
        slope: f64,
    ) -> Option<(f64, f64, f64)> {
        let ratio = self.ratio_per_slope * slope;
        if ratio.is_nan() || ratio.abs() >= 1.0 {
            return None;
        }
        let radius = nominal_radius + height;
        let qy = profile_y + wheel_offset;
        if !YAWED {
            let (ry, rz) = (qy * self.cos_roll - radius * self.sin_roll, qy * self.sin_roll + radius * self.cos_roll);
            return Some((self.lateral + ry, rz - nominal_radius, radius));
        }
        // θ = asin(ratio) − β without trigonometry: sin θ = ratio cos β − √(1 − ratio²) sin β.
        let root = (1.0 - ratio * ratio).sqrt();
        let sin_angle = ratio * self.cos_phase - root * self.sin_phase;
        let cos_angle = root * self.cos_phase + ratio * self.sin_phase;
        let (qx, qz) = (radius * sin_angle, radius * cos_angle);
        let (ry, rz) = (qy * self.cos_roll - qz * self.sin_roll, qy * self.sin_roll + qz * self.cos_roll);
        Some((self.lateral + qx * self.sin_yaw + ry * self.cos_yaw, rz - nominal_radius, qz))
    }

    /// Whether the yaw is 0: [`Self::track_position_of`] without it.
    fn unyawed(&self) -> bool {
        self.sin_yaw == 0.0 && self.cos_yaw == 1.0
    }
}

/// The undeformed gap of one wheel pose (right side, z_ws = 0) as a function of the wheel
/// profile's y, read from the sampled profiles.
struct GapSearch<'a> {
    wheel: &'a WheelOnRail,
    locus: LocusFrame,
    position: WheelsetPosition,
    /// Wheel samples per gap sample: [`SAMPLES_PER_STEP`] (a finer one in a test).
    stride: usize,
}

impl<'a> GapSearch<'a> {
    fn new(wheel: &'a WheelOnRail, position: &WheelsetPosition) -> Self {
        Self { wheel, locus: LocusFrame::new(position), position: *position, stride: SAMPLES_PER_STEP as usize }
    }

    /// The contact table's key of this pose: the lateral position of the wheel's bottom,
    /// y_ws − r0 sin φ − Y (1 − cos ψ) (roll turns the wheel about its axle, moving its bottom
    /// sideways; yaw draws the wheel, Y from the centre, towards it).
    fn table_key(&self) -> f64 {
        self.position.lateral
            - self.wheel.dimensions.nominal_radius * self.locus.sin_roll
            - self.wheel.wheel_offset * (1.0 - self.locus.cos_yaw)
    }

    /// How far from the table's minima the search scans \[m\]: [`TABLE_REACH`], and further
    /// under yaw, which moves a flange contact (slope tan γ ≤ 3) across the wheel by up to
    /// r tan γ ψ² ≈ 1.5 ψ² m beyond what the key accounts for.
    fn reach(&self) -> f64 {
        TABLE_REACH + 1.5 * self.position.yaw * self.position.yaw
    }

    /// How far in the key the table's rows are read \[m\]: [`TABLE_KEY_REACH`], and further
    /// under yaw, which moves a flange's contact point (slope tan γ ≤ 3) ahead of the axle by
    /// r tan γ ψ and so sideways by r tan γ ψ² ≈ 1.5 ψ² m more than the key accounts for.
    fn key_reach(&self) -> f64 {
        TABLE_KEY_REACH + 1.5 * self.position.yaw * self.position.yaw
    }

    /// The gap at the locus point of a wheel sample (profile y, height, slope).
    #[inline(always)]
    fn gap_of(&self, profile_y: f64, (height, slope): (f64, f64)) -> Option<f64> {
        let (lateral, vertical, _) = self.locus.track_position(self.wheel, profile_y, height, slope)?;
        let rail_height = self.wheel.rail_samples.height_at(lateral - self.wheel.rail_offset)?;
        Some(rail_height + self.wheel.rail_lift - vertical)
    }

    /// The gap at wheel profile y, +∞ off the profiles.
    fn gap(&self, profile_y: f64) -> f64 {
        self.wheel
            .wheel_samples
            .at(profile_y)
            .and_then(|sample| self.gap_of(profile_y, sample))
            .unwrap_or(f64::INFINITY)
    }

    /// The gap's local minima over the wheel samples every [`SAMPLE_STEP`] whose profile y lies
    /// in [from, to] (those over the rail; on the full scan's grid, multiples of the stride,
    /// wherever it starts), refined by Brent's method (wheel profile y, increasing), with the
    /// highest sampled gap between neighbours, and how many samples lay over the rail. Read in
    /// one pass, without storing the samples: a sample is a minimum when it is below the one
    /// before and not above the one after.
    fn minima_between(&self, from: f64, to: f64) -> Minima {
        let samples = &self.wheel.wheel_samples;
        let stride = self.stride;
        let first = samples.index_at(from).max(0.0).ceil() as usize;
        let last = samples.index_at(to).min((samples.len() - 1) as f64).floor();
        if last.is_nan() || (last as usize) < first {
            return Minima { minima: Vec::new(), barriers: Vec::new(), samples: 0 };
        }
        let start = first.div_ceil(stride) * stride;
        if self.locus.unyawed() {
            self.minima_over::<false>(start, last as usize)
        } else {
            self.minima_over::<true>(start, last as usize)
        }
    }

    /// [`Self::minima_between`] over the wheel samples start, start + stride, … ≤ last.
    #[inline(always)]
    fn minima_over<const YAWED: bool>(&self, start: usize, last: usize) -> Minima {
        // Copies of what each sample reads, for the registers.
        let (wheel, locus) = (self.wheel, self.locus);
        let (samples, rail) = (wheel.wheel_samples.view(), wheel.rail_samples.view());
        let placement = (wheel.dimensions.nominal_radius, wheel.wheel_offset);
        let (rail_offset, rail_lift) = (wheel.rail_offset, wheel.rail_lift);
        let stride = self.stride;
        let mut found = Minima { minima: Vec::new(), barriers: Vec::new(), samples: 0 };
        // The last two samples over the rail (profile y, gap; NaN before the first two: no
        // comparison holds) and the highest gap since the last minimum (from it on).
        let (mut before, mut middle) = ((0.0, f64::NAN), (0.0, f64::NAN));
        let mut highest = f64::MIN;
        // k and k as f64 (exact) for the sample's y.
        let (mut k, mut index) = (start, start as f64);
        while k <= last {
            let profile_y = samples.lateral_at(index);
            let (height, slope) = samples.sample(k);
            (k, index) = (k + stride, index + stride as f64);
            // The gap as `gap_of`.
            let Some((lateral, vertical, _)) = locus.track_position_of::<YAWED>(placement, profile_y, height, slope)
            else {
                continue;
            };
            let Some(rail_height) = rail.height_at(lateral - rail_offset) else { continue };
            let gap = rail_height + rail_lift - vertical;
            if middle.1 < before.1 && middle.1 <= gap {
                if !found.minima.is_empty() {
                    found.barriers.push(highest);
                }
                // Its neighbours bracket it for the refinement.
                found.minima.push(SampledMinimum { bracket: (before.0, profile_y), lowest: middle });
                highest = middle.1;
            }
            // (`highest` is never NaN: a NaN gap leaves it, as `f64::max` would.)
            if gap > highest {
                highest = gap;
            }
            (before, middle) = (middle, (profile_y, gap));
            found.samples += 1;
        }
        found
    }

    /// The minima found by [`Self::minima_between`], refined by Brent's method (wheel profile y),
    /// and the barriers between them.
    fn refined(&self, found: Minima) -> (Vec<f64>, Vec<f64>) {
        let refine = |minimum: &SampledMinimum| brent_minimum(|y| self.gap(y), minimum.bracket.0, minimum.bracket.1);
        (found.minima.iter().map(refine).collect(), found.barriers)
    }

    /// The wheel profile's y range over the rail: track y ≈ y_ws + (profile y + offset) cos φ
    /// − r0 sin φ (yaw moves it by less than a millimetre), with 5 mm to spare.
    fn range_over_rail(&self) -> (f64, f64) {
        let (wheel, position) = (self.wheel, &self.position);
        let (rail_first, rail_last) = wheel.rail.lateral_range();
        let profile_y_at = |track_y: f64| {
            (track_y - position.lateral + wheel.dimensions.nominal_radius * self.locus.sin_roll) / self.locus.cos_roll
                - wheel.wheel_offset
        };
        (profile_y_at(rail_first + wheel.rail_offset) - 5e-3, profile_y_at(rail_last + wheel.rail_offset) + 5e-3)
    }

    /// The full scan: the gap every [`SAMPLE_STEP`] over the rail's extent, each local minimum
    /// refined by Brent's method; the minima (wheel profile y, increasing) and the highest
    /// sampled gap between neighbours.
    fn scan(&self) -> Result<(Vec<f64>, Vec<f64>), ProfileError> {
        Ok(self.refined(self.sampled_scan()?))
    }

    /// [`Self::scan`]'s pass over the samples, its minima not yet refined.
    fn sampled_scan(&self) -> Result<Minima, ProfileError> {
        let position = &self.position;
        let (from, to) = self.range_over_rail();
        let found = self.minima_between(from, to);
        if found.samples < 3 {
            return Err(ProfileError::whole(format!(
                "the wheel and the rail profile do not overlap laterally at wheelset_lateral_displacement = {} m",
                position.lateral
            )));
        }
        if found.minima.is_empty() {
            return Err(ProfileError::whole(format!(
                "the profiles never touch at wheelset_lateral_displacement = {} m: the gap has no minimum inside their common range",
                position.lateral
            )));
        }
        Ok(found)
    }

    /// The scan from the first to the last of the contact table's minima near this pose
    /// (`span`) and [`Self::reach`] around them: one stretch, so that a minimum born between the
    /// table's nodes where the gap is flat, between two of their minima, is found too (a search
    /// within reach of each minimum alone missed some). The same samples, minima and barriers as
    /// the full scan there, not yet refined. `None` — scan everything instead — if it finds no
    /// minimum.
    fn sampled_near(&self, (first, last): (f64, f64)) -> Option<Minima> {
        let reach = self.reach();
        let found = self.minima_between(first - reach, last + reach);
        (!found.minima.is_empty()).then_some(found)
    }
}

/// What one pass over the gap's samples finds ([`GapSearch::minima_between`]).
struct Minima {
    minima: Vec<SampledMinimum>,
    /// barriers[i]: the highest sampled gap between minima i and i + 1.
    barriers: Vec<f64>,
    /// How many samples lay over the rail.
    samples: usize,
}

/// A local minimum of the sampled gap ([`GapSearch::minima_between`]).
struct SampledMinimum {
    /// Its neighbours' profile y (Brent's bracket).
    bracket: (f64, f64),
    /// The lowest sample: its profile y and gap.
    lowest: (f64, f64),
}

/// How far from a contact table's minimum the search looks \[m\].
const TABLE_REACH: f64 = 1e-3;

/// The gap's minima (wheel profile y) of the unyawed wheelset every [`TABLE_STEP`] of the
/// wheel bottom's lateral position (the table key) and every [`TABLE_ROLL_STEP`] of roll: where
/// the contact search starts (module doc, "Contact table").
#[derive(Debug, Clone)]
struct ContactTable {
    /// minima[j][k]: at roll −[`TABLE_ROLL_REACH`] + j·[`TABLE_ROLL_STEP`] and key
    /// −[`TABLE_REACH_LATERAL`] + k·[`TABLE_STEP`].
    minima: Vec<Vec<Vec<f64>>>,
}

/// The contact table's steps and reaches in the key and in roll \[m, rad\].
const TABLE_STEP: f64 = 1e-4;
/// The rows read around a key \[m\], beyond the yaw's share ([`GapSearch::key_reach`]): the
/// key is exact at the table's nodes; between two rolls the minima of both are read, and a
/// minimum born between nodes where the gap is flat lies between the minima read, which one
/// stretch covers. 0.2 mm finds every minimum the full scan finds within 1 mm of touching over
/// 200 000 random poses in a scratch run (0.1 mm did too; `the_contact_table_finds_what_the_full_scan_finds`
/// checks 20 000 each run); stretches around each minimum alone, with 1 mm, missed 15.
const TABLE_KEY_REACH: f64 = 2e-4;
const TABLE_REACH_LATERAL: f64 = 0.02;
const TABLE_ROLL_STEP: f64 = 0.002;
const TABLE_ROLL_REACH: f64 = 0.012;
/// Beyond this yaw \[rad\] the flange's minima move further than the table's reach: the full
/// scan searches there (`the_contact_table_finds_what_the_full_scan_finds`).
const TABLE_YAW_REACH: f64 = 0.025;

impl ContactTable {
    fn new(wheel: &WheelOnRail) -> Self {
        let rows = (2.0 * TABLE_REACH_LATERAL / TABLE_STEP).round() as usize + 1;
        let rolls = (2.0 * TABLE_ROLL_REACH / TABLE_ROLL_STEP).round() as usize + 1;
        let minima = (0..rolls)
            .map(|j| {
                let roll = -TABLE_ROLL_REACH + j as f64 * TABLE_ROLL_STEP;
                (0..rows)
                    .map(|k| {
                        let key = -TABLE_REACH_LATERAL + k as f64 * TABLE_STEP;
                        let lateral = key + wheel.dimensions.nominal_radius * roll.sin();
                        let position = WheelsetPosition { lateral, roll, ..WheelsetPosition::default() };
                        // A pose where the profiles do not meet has no minima: the search scans there.
                        GapSearch::new(wheel, &position).scan().map(|(minima, _)| minima).unwrap_or_default()
                    })
                    .collect()
            })
            .collect();
        Self { minima }
    }

    /// The lowest and highest of the minima at the two rolls around `roll` in the rows within
    /// `key_reach` of `key`; `None` outside the table or where those rows hold none.
    fn span(&self, key: f64, key_reach: f64, roll: f64) -> Option<(f64, f64)> {
        let reach = (key_reach / TABLE_STEP).ceil() as usize;
        let row = (key + TABLE_REACH_LATERAL) / TABLE_STEP;
        let column = (roll + TABLE_ROLL_REACH) / TABLE_ROLL_STEP;
        let rows = self.minima.first().map_or(0, Vec::len);
        // The sum in floating point: in usize it would wrap for a huge key (y_ws ≥ 2e15 m). A
        // row ≥ 0 truncates to its floor (the cast saturates beyond usize; NaN fails the first test).
        let inside = row >= reach as f64 && (row as usize as f64) + 1.0 + (reach as f64) < rows as f64;
        // (NaN fails `inside` and the column's range.)
        if !inside || !(0.0..self.minima.len().saturating_sub(1) as f64).contains(&column) {
            return None;
        }
        let (k, j) = (row as usize, column as usize);
        self.minima[j..=j + 1]
            .iter()
            .flat_map(|rolled| rolled[k - reach..=k + 1 + reach].iter().flatten())
            .fold(None, |span: Option<(f64, f64)>, &y| {
                Some(span.map_or((y, y), |(low, high)| (low.min(y), high.max(y))))
            })
    }
}

/// Brent's minimisation of `f` in [low, high] to 1 nm: golden-section steps, parabolic ones
/// where the parabola through the last three points is trusted (R. P. Brent, "Algorithms for
/// Minimization without Derivatives", 1973, ch. 5): ten to fifteen evaluations on the gap's
/// smooth minima, against golden section's thirty.
fn brent_minimum(f: impl Fn(f64) -> f64, mut low: f64, mut high: f64) -> f64 {
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    const TOLERANCE: f64 = 1e-9;
    let mut x = low + GOLDEN * (high - low);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut step, mut previous_step) = (0.0f64, 0.0f64);
    for _ in 0..100 {
        let middle = 0.5 * (low + high);
        if (x - middle).abs() <= 2.0 * TOLERANCE - 0.5 * (high - low) {
            break;
        }
        let mut parabolic = false;
        if previous_step.abs() > TOLERANCE {
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let before = previous_step;
            previous_step = step;
            if p.abs() < (0.5 * q * before).abs() && p > q * (low - x) && p < q * (high - x) {
                step = p / q;
                let u = x + step;
                if u - low < 2.0 * TOLERANCE || high - u < 2.0 * TOLERANCE {
                    step = TOLERANCE.copysign(middle - x);
                }
                parabolic = true;
            }
        }
        if !parabolic {
            previous_step = if x >= middle { low - x } else { high - x };
            step = GOLDEN * previous_step;
        }
        let u = if step.abs() >= TOLERANCE { x + step } else { x + TOLERANCE.copysign(step) };
        let fu = f(u);
        if fu <= fx {
            if u >= x {
                low = x;
            } else {
                high = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                low = u;
            } else {
                high = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    x
}

fn check_position(position: &WheelsetPosition) -> Result<(), ProfileError> {
    for (name, value) in [
        ("wheelset_lateral_displacement", position.lateral),
        ("wheelset_vertical_position", position.vertical),
        ("wheelset_roll_angle", position.roll),
        ("wheelset_yaw_angle", position.yaw),
    ] {
        if !value.is_finite() {
            return Err(ProfileError::whole(format!("{name} = {value} must be finite")));
        }
    }
    for (name, value) in [("wheelset_roll_angle", position.roll), ("wheelset_yaw_angle", position.yaw)] {
        if value.abs() > 0.1 {
            return Err(ProfileError::whole(format!("{name} = {value} rad must be within ±0.1")));
        }
    }
    Ok(())
}

/// The rail profile's gauge face, y of its inner (y < 0 side) flank at `height` below its top,
/// and the top's z.
fn gauge_face(rail: &SmoothProfile, height: f64) -> Result<(f64, f64), ProfileError> {
    let (first, last) = rail.lateral_range();
    let samples: Vec<ProfilePoint> =
        (0..=10_000).filter_map(|i| rail.at_lateral(first + (last - first) * f64::from(i) / 10_000.0)).collect();
    let top = samples.iter().map(|p| p.vertical).fold(f64::INFINITY, f64::min);
    let level = top + height;
    // From the top towards the inner end, the first crossing of the measuring level.
    let top_index = samples.iter().position(|p| p.vertical == top).unwrap_or(0);
    let crossing = samples[..=top_index].windows(2).rev().find(|w| w[0].vertical >= level && w[1].vertical < level);
    let [outer, inner] = crossing.map(|w| [w[0], w[1]]).ok_or_else(|| {
        ProfileError::whole(format!("the rail profile does not reach {height} m below its top on its inner side"))
    })?;
    // Bisection between the two samples.
    let (mut low, mut high) = (outer.lateral, inner.lateral);
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        match rail.at_lateral(middle) {
            Some(p) if p.vertical >= level => low = middle,
            _ => high = middle,
        }
    }
    Ok((0.5 * (low + high), top))
}

#[cfg(test)]
mod tests {
    use super::{brent_minimum, GapSearch, LocusFrame, WheelOnRail, WheelSide, WheelsetPosition, SAMPLES_PER_STEP};
    use crate::geometry::{ContactCandidates, ContactPoint};
    use std::cell::Cell;

    /// The scan's locus without yaw gives the general formula's numbers at yaw 0, bit for bit
    /// (on every wheel sample, at rolls and lateral positions on and off the table's nodes, 0 and
    /// −0 among them), and both refuse the same samples.
    #[test]
    fn the_unyawed_locus_is_the_yawed_one_at_zero_yaw() {
        let pair = WheelOnRail::manchester_benchmark(WheelSide::Right);
        let samples = &pair.wheel_samples;
        let placement = (pair.dimensions.nominal_radius, pair.wheel_offset);
        for (lateral, roll) in [(0.0, 0.0), (-0.0, -0.0), (3.7e-3, 0.0), (-8.2e-3, 0.0113), (1e-3, -0.004), (0.0, 0.1)]
        {
            let locus = LocusFrame::new(&WheelsetPosition { lateral, roll, ..WheelsetPosition::default() });
            assert!(locus.unyawed());
            for k in 0..samples.len() {
                let (height, slope) = samples.sample(k);
                let (y, general, unyawed) = (
                    samples.lateral(k),
                    locus.track_position_of::<true>(placement, samples.lateral(k), height, slope),
                    locus.track_position_of::<false>(placement, samples.lateral(k), height, slope),
                );
                let bits = |p: Option<(f64, f64, f64)>| {
                    p.map(|(a, b, c)| ((a + 0.0).to_bits(), (b + 0.0).to_bits(), (c + 0.0).to_bits()))
                };
                assert_eq!(bits(general), bits(unyawed), "y {y}, at ({lateral}, {roll})");
            }
            // Beyond the profile's slopes: a sample the locus refuses either way.
            assert_eq!(locus.track_position_of::<false>(placement, 0.0, 0.0, f64::NAN), None);
        }
        let yawed = LocusFrame::new(&WheelsetPosition { yaw: 1e-9, ..WheelsetPosition::default() });
        assert!(!yawed.unyawed());
    }

    /// The gap sampled every 0.2 mm ([`super::SAMPLE_STEP`]) against every 0.1 mm (the sampling
    /// before): the samples only bracket the minima that Brent's method refines to 1 nm, so both
    /// find the same candidates, where the gap is flat (its minima within microns over
    /// millimetres) as far apart as the refinement's rounding lets a flat minimum move; and a
    /// minimum being born, a shallow dip between two samples, is seen a little later in y_ws.
    /// Over y_ws −12…12 mm every 0.1 mm, rolls up to ±0.011 rad and yaws up to ±0.03 rad (the
    /// table's and beyond), both sides: the same candidates within 1 mm of touching, except
    /// where one is being born (then the same within 20 µm of y_ws: measured at y_ws = ∓0.4
    /// mm, a minimum 24 µm above the touch that the 0.2 mm sampling sees from 13 µm further
    /// on); positions within 6e-8 m, gaps within 1e-12 m, and at 10 and 100 kN the same patches,
    /// z_ws within 2e-9 m, normal forces within 3e-6 of each other (measured 4.3e-8 m, 6e-14 m,
    /// 8.8e-10 m, 1.4e-6, all on the flat gap near y_ws = 0).
    #[test]
    fn sampling_every_0_2_mm_finds_what_0_1_mm_finds() {
        let near = |c: &ContactCandidates| -> Vec<ContactPoint> {
            let touch = c.touch();
            c.points().into_iter().filter(|p| p.gap_at_zero - touch < 1e-3).collect()
        };
        let cosine = |point: &ContactPoint| point.contact_angle_sin_cos().1;
        let (mut worst, mut born) = ([0.0f64; 4], 0);
        for side in [WheelSide::Right, WheelSide::Left] {
            let pair = WheelOnRail::manchester_benchmark(side);
            // The candidates sampled every `stride` wheel samples, by the full scan.
            let scan = |position: &WheelsetPosition, stride: usize| -> ContactCandidates {
                let right = side.mirror_position(position);
                let (minima, barriers) = GapSearch { stride, ..GapSearch::new(&pair, &right) }.scan().unwrap();
                pair.candidates_at(&minima, barriers, &right).unwrap()
            };
            for step in -120..=120 {
                for (roll, yaw) in [(0.0, 0.0), (0.0037, 0.0), (-0.011, 0.0048), (0.006, -0.0168), (-0.002, 0.03)] {
                    let position = WheelsetPosition { lateral: f64::from(step) * 1e-4, roll, yaw, vertical: 0.0 };
                    let (coarse, fine) = (scan(&position, SAMPLES_PER_STEP as usize), scan(&position, 4));
                    assert_eq!(coarse.points(), pair.candidates_by_full_scan(&position).unwrap().points());
                    let (ours, theirs) = (near(&coarse), near(&fine));
                    if ours.len() != theirs.len() {
                        let shifted = |shift: f64| {
                            let lateral = position.lateral + shift;
                            near(&scan(&WheelsetPosition { lateral, ..position }, SAMPLES_PER_STEP as usize)).len()
                        };
                        assert!(shifted(2e-5) == theirs.len() || shifted(-2e-5) == theirs.len(), "{position:?}");
                        born += 1;
                        continue;
                    }
                    for (a, b) in ours.iter().zip(&theirs) {
                        worst[0] = worst[0].max((a.track_lateral - b.track_lateral).abs());
                        worst[1] = worst[1].max((a.gap_at_zero - b.gap_at_zero).abs());
                    }
                    for load in [10e3, 100e3] {
                        let (z, patches) = coarse.patches_for_force(load, cosine).unwrap();
                        let (z_fine, patches_fine) = fine.patches_for_force(load, cosine).unwrap();
                        assert_eq!(patches.len(), patches_fine.len(), "{side:?} {position:?}");
                        worst[2] = worst[2].max((z - z_fine).abs());
                        for (a, b) in patches.iter().zip(&patches_fine) {
                            worst[3] = worst[3].max((a.normal_force / b.normal_force - 1.0).abs());
                        }
                    }
                }
            }
        }
        println!(
            "positions {:.1e} m, gaps {:.1e} m, z_ws {:.1e} m, normal forces {:.1e}; {born} poses where a minimum is born",
            worst[0], worst[1], worst[2], worst[3]
        );
        assert!(born <= 2 && worst[0] < 6e-8 && worst[1] < 1e-12 && worst[2] < 2e-9 && worst[3] < 3e-6, "{worst:?}");
    }

    /// Brent's method on smooth minima as the search brackets them (±0.2 mm): the minimum within
    /// its 1 nm tolerance in at most 11 evaluations — parabolic steps taken where trusted (golden
    /// section alone needs ≈ 24 here).
    #[test]
    fn brent_finds_smooth_minima_to_a_nanometre_in_few_evaluations() {
        type Shape = (&'static str, fn(f64) -> f64);
        let shapes: [Shape; 3] = [
            ("parabola", |d| 3.0 * d * d),
            ("cubic", |d| d * d * (1.0 + 2e3 * d)),
            ("quartic and parabola", |d| d * d + 5e6 * d.powi(4)),
        ];
        for (name, shape) in shapes {
            for i in 0..200 {
                let minimum = -0.04 + 1e-3 * f64::from(i) * 0.37;
                let (low, high) = (minimum - 2e-4 + 3e-7 * f64::from(i % 7), minimum + 2e-4);
                let evaluations = Cell::new(0);
                let found = brent_minimum(
                    |y| {
                        evaluations.set(evaluations.get() + 1);
                        shape(y - minimum)
                    },
                    low,
                    high,
                );
                assert!((found - minimum).abs() <= 1e-9, "{name}: {found} for {minimum}");
                assert!(evaluations.get() <= 11, "{name}: {} evaluations", evaluations.get());
            }
        }
    }
}
