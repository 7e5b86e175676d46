//! A wheel on its rail: placement on the track, the undeformed gap, the contact
//! points (tread and flange, each a local minimum of the gap) and the normal problem with a
//! Hertz ellipse per patch.
//!
//! Conventions (CONTACT's module 1): track coordinates x along the track in the rolling
//! direction, y lateral positive to the right, z downward; roll about x. The profiles are the
//! right side's, in their own coordinates (y lateral, z downward, metres).
//!
//! Placement. The rail: its gauge face — the point on its inner (y < 0) flank at the gauge
//! measuring height below its top — lies at y = gauge/2. The wheel: its profile's flange back
//! (y = `flange_back_position`) lies at y = `flange_back_distance`/2 in wheelset coordinates,
//! the profile's z = 0 on the nominal radius r0 below the axle. The wheelset at (y_ws, z_ws,
//! roll φ, yaw ψ): the wheel is the surface of revolution of its profile about the axle; its
//! point at profile y, angle θ from the bottom, (r sin θ, Y, r cos θ) from the axle centre
//! (Y = profile y + the flange back's offset, r = r0 + z_wheel), goes to c + R_z(ψ)R_x(φ)·(that),
//! c = (0, y_ws, z_ws − r0). With φ = ψ = 0, z_ws = 0 the wheel's datum is at the rail top's
//! level (as CONTACT's Z_WS; its case deck reports z_ws = 0.198 mm on y_ws = 0).
//!
//! Yaw. The rail is straight along x, so its normal has no x component, and at a contact
//! point the wheel's normal must not have one either: per profile point, the angle θ where the
//! turned normal (sin θ cos γ, −sin γ, cos θ cos γ) (γ the profile's slope) has no x component
//! solves A sin θ + B cos θ = C in closed form (A = cos γ cos ψ, B = cos γ sin φ sin ψ, C = −sin γ
//! cos φ sin ψ). These points form the wheel's contact locus; θ ≈ −tan γ tan ψ puts a flange
//! contact (tan γ ≈ 2) 20–30 mm ahead of or behind the axle at ψ = 10–24 mrad, and shifts it
//! 0.1–0.7 mm laterally. The gap is taken between the rail and the locus, whose track y follows
//! the profile's y by a fixed-point iteration. On the contact positions agree with
//! CONTACT's within 0.004 mm on the flange, 0.03 mm in x (0.07–0.1 mm on the flange without
//! yaw).
//!
//! Contact points. The gap g(y) = z_rail(y) − z_wheel(y) (vertical, undeformed) is sampled every
//! 0.1 mm over the profiles' common lateral range; each interior local minimum, refined by
//! golden-section search, is a candidate contact point. The wheelset's vertical position shifts
//! the gap uniformly, so the candidates do not depend on it: a candidate with g_i < z_ws is in
//! contact, penetrating vertically by z_ws − g_i, along its normal by (z_ws − g_i) cos δ.
//! Two candidates whose interpenetration regions join are one patch (the deeper one kept).
//! Where two such minima swap which is deeper, the patch's point jumps between them: for S1002
//! on UIC60 at y_ws ≈ 0.22 mm on the tread and ≈ 6.62 mm from the flange root to the flange
//! (`tests/geometry_benchmark.rs`); CONTACT, which solves the non-Hertzian patch, moves its
//! contact reference between the same places between its cases. Elsewhere the points move
//! continuously with y_ws, and the load passes between separate patches continuously.
//!
//! Ellipse: Hertz per patch (the scene's [`HertzContact`]) from the relative curvatures at the
//! contact point. The wheel's principal curvatures are cos γ/r along its parallel (Meusnier's
//! theorem) and −κ_wheel along its profile; the rail bends only laterally (κ_rail; curvatures
//! positive bending downward: the rail's convex crown, the wheel's concave throat). Without yaw
//! the parallel runs along x: A = cos γ/(2 r), B = (κ_rail − κ_wheel)/2. With yaw it is turned
//! from x by the angle whose cosine c is the locus' `circumferential_x`, and Euler's theorem
//! gives the curvatures along x and across: A = (c² cos γ/r − (1 − c²) κ_wheel)/2, B = (κ_rail +
//! (1 − c²) cos γ/r − c² κ_wheel)/2 (the twist term is dropped: the ellipse stays aligned with
//! x). Hertz because it is what multibody codes use online and needs one evaluation per patch;
//! on its patches give, with the exact theory, creep forces within 0.041 μN of CONTACT's
//! non-Hertzian solution (`tests/geometry_wheel_forces.rs`), inside the 0.12 μN of CONTACT's
//! own fast methods. Normal force from the normal penetration δ_n by Hertz's
//! Q ∝ δ_n^{3/2} (the same ellipse solution at 1 N gives the constant).
//!
//! The left wheel on the left rail is the right side mirrored (y → −y, roll → −roll, yaw → −yaw; reported
//! positions and contact angles mirrored back), as CONTACT does.
//!
//! The creepages and forces of the patches: [`super::wheel_forces`]. Not here yet: rail cant
//! other than the profile's own.

use super::profile_file::ProfileError;
use super::smooth_profile::{ProfilePoint, SmoothProfile};
use crate::scene::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use crate::InvalidInput;

/// Which wheel of the wheelset, on which rail.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WheelSide {
    /// y > 0: the profiles as given.
    Right,
    /// y < 0: the profiles mirrored in y, as CONTACT does.
    Left,
}

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

    /// A right-side point seen on this side: lateral positions (track and both profiles', as
    /// CONTACT reports them for the left side) and the contact angle change sign.
    fn mirror_point(self, point: &ContactPoint) -> ContactPoint {
        match self {
            Self::Right => *point,
            Self::Left => ContactPoint {
                track_lateral: -point.track_lateral,
                rail_lateral: -point.rail_lateral,
                wheel_lateral: -point.wheel_lateral,
                contact_angle: -point.contact_angle,
                ..*point
            },
        }
    }

    fn mirror_patches(self, patches: Vec<ContactPatch>) -> Vec<ContactPatch> {
        patches.into_iter().map(|patch| ContactPatch { point: self.mirror_point(&patch.point), ..patch }).collect()
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
    /// The Manchester contact benchmark's track and wheelset (case as CONTACT's example
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

/// Iterations of the locus point's fixed point in y (each gains ≈ 1.5 digits on the flange).
const LOCUS_ITERATIONS: usize = 12;

/// One contact point's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Track x \[m\]: ahead of the wheelset's centre (non-zero with yaw).
    pub track_longitudinal: f64,
    /// Track y \[m\].
    pub track_lateral: f64,
    /// Track z of the rail surface \[m\].
    pub track_vertical: f64,
    /// y in the rail profile's coordinates \[m\].
    pub rail_lateral: f64,
    /// y in the wheel profile's coordinates \[m\].
    pub wheel_lateral: f64,
    /// The surfaces' inclination atan(dz/dy) in track coordinates \[rad\] (CONTACT's DELTCP).
    pub contact_angle: f64,
    /// The wheel's rolling radius at the contact point \[m\]: its depth below the axle in the
    /// wheel's plane (r0 + z_wheel without yaw; with yaw the point lies ahead of or behind the
    /// axle, and this is r cos θ, as CONTACT's r0 + ZCP(W)).
    pub rolling_radius: f64,
    /// The undeformed vertical gap at the contact point with z_ws = 0 \[m\].
    pub gap_at_zero: f64,
    /// Relative curvature along x, A \[1/m\] (module doc, "Ellipse"; cos γ/(2 r) without yaw).
    pub curvature_rolling: f64,
    /// Relative curvature along the patch's lateral axis, B \[1/m\] ((κ_rail − κ_wheel)/2 without
    /// yaw).
    pub curvature_lateral: f64,
}

/// A loaded patch: its contact point, normal penetration, normal force and Hertz ellipse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPatch {
    /// Where it is.
    pub point: ContactPoint,
    /// Penetration along the contact normal \[m\].
    pub penetration: f64,
    /// Normal force \[N\].
    pub normal_force: f64,
    /// Hertz's ellipse for that force.
    pub ellipse: HertzContact,
}

/// Sampling step of the gap \[m\]: finer than the profiles' point spacing (≈ 0.35 mm).
const SAMPLE_STEP: f64 = 1e-4;

/// A wheel profile and a rail profile placed on a track.
#[derive(Debug, Clone)]
pub struct WheelOnRail {
    wheel: SmoothProfile,
    rail: SmoothProfile,
    dimensions: TrackDimensions,
    side: WheelSide,
    /// Track y of the rail profile's origin.
    rail_offset: f64,
    /// Wheelset y of the wheel profile's origin.
    wheel_offset: f64,
    contact_modulus: f64,
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
        if dimensions.rail_cant != 0.0 {
            return Err(ProfileError::whole(format!(
                "rail_cant = {} rad: only 0 is modelled yet (give the cant in the rail profile's points)",
                dimensions.rail_cant
            )));
        }
        let gauge_face = gauge_face(&rail, dimensions.gauge_measuring_height)?;
        Ok(Self {
            rail_offset: 0.5 * dimensions.gauge - gauge_face,
            wheel_offset: 0.5 * dimensions.flange_back_distance - dimensions.flange_back_position,
            wheel,
            rail,
            dimensions,
            side,
            contact_modulus: modulus,
        })
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
        if !(ratio.abs() < 1.0) {
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

    /// The wheel's contact locus point at track y (fixed-point iteration on the profile's y:
    /// the locus' track y moves with the profile's y at a rate within a few per cent of
    /// cos φ cos ψ), `None` off the profile.
    fn wheel_at(&self, y: f64, position: &WheelsetPosition) -> Option<WheelLocusPoint> {
        let rate = position.roll.cos() * position.yaw.cos();
        let mut profile_y = (y - position.lateral) / rate - self.wheel_offset;
        let mut point = self.locus_at(profile_y, position)?;
        for _ in 0..LOCUS_ITERATIONS {
            let miss = y - point.lateral;
            if miss.abs() < 1e-12 {
                break;
            }
            profile_y += miss / rate;
            point = self.locus_at(profile_y, position)?;
        }
        Some(point)
    }

    /// The vertical gap at track y with z_ws = 0, and the two surface points.
    fn gap(&self, y: f64, position: &WheelsetPosition) -> Option<(f64, WheelLocusPoint, ProfilePoint)> {
        let at_zero = WheelsetPosition { vertical: 0.0, ..*position };
        let wheel = self.wheel_at(y, &at_zero)?;
        let rail = self.rail.at_lateral(y - self.rail_offset)?;
        Some((rail.vertical - wheel.vertical, wheel, rail))
    }

    /// The wheelset's centre on its axle, (0, y_ws, z_ws − r0) in track axes \[m\].
    pub fn wheelset_centre(&self, position: &WheelsetPosition) -> [f64; 3] {
        [0.0, position.lateral, position.vertical - self.dimensions.nominal_radius]
    }

    /// The candidate contact points (module doc) for the wheelset's lateral position and roll,
    /// tread first (ordered from the rail's field side to its gauge side); the vertical position
    /// is not used.
    pub fn contact_points(&self, position: &WheelsetPosition) -> Result<Vec<ContactPoint>, ProfileError> {
        check_position(position)?;
        let points = self.right_points(&self.side.mirror_position(position))?;
        Ok(points.iter().map(|p| self.side.mirror_point(p)).collect())
    }

    /// [`Self::contact_points`] for the right side's position.
    fn right_points(&self, position: &WheelsetPosition) -> Result<Vec<ContactPoint>, ProfileError> {
        let (rail_first, rail_last) = self.rail.lateral_range();
        let (wheel_first, wheel_last) = self.wheel.lateral_range();
        let wheel_shift = position.lateral + self.wheel_offset;
        let from = (rail_first + self.rail_offset).max(wheel_first + wheel_shift) + SAMPLE_STEP;
        let to = (rail_last + self.rail_offset).min(wheel_last + wheel_shift) - SAMPLE_STEP;
        let samples: Vec<(f64, f64)> = (0..)
            .map(|i| from + f64::from(i) * SAMPLE_STEP)
            .take_while(|&y| y <= to)
            .filter_map(|y| self.gap(y, position).map(|(g, _, _)| (y, g)))
            .collect();
        if samples.len() < 3 {
            return Err(ProfileError::whole(format!(
                "the wheel and the rail profile do not overlap laterally at wheelset_lateral_displacement = {} m",
                position.lateral
            )));
        }
        let mut points = Vec::new();
        for window in samples.windows(3) {
            if window[1].1 < window[0].1 && window[1].1 <= window[2].1 {
                let y = self.refine_minimum(window[0].0, window[2].0, position);
                points.push(self.contact_point(y, position)?);
            }
        }
        if points.is_empty() {
            return Err(ProfileError::whole(format!(
                "the profiles never touch at wheelset_lateral_displacement = {} m: the gap has no minimum inside their common range",
                position.lateral
            )));
        }
        // Tread first: from the rail's field side (large y) to its gauge side.
        points.reverse();
        Ok(points)
    }

    /// Golden-section search for the gap's minimum in [low, high].
    fn refine_minimum(&self, mut low: f64, mut high: f64, position: &WheelsetPosition) -> f64 {
        let gap = |y: f64| self.gap(y, position).map_or(f64::INFINITY, |(g, _, _)| g);
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let (mut left, mut right) = (high - ratio * (high - low), low + ratio * (high - low));
        let (mut g_left, mut g_right) = (gap(left), gap(right));
        while high - low > 1e-9 {
            if g_left < g_right {
                high = right;
                (right, g_right) = (left, g_left);
                left = high - ratio * (high - low);
                g_left = gap(left);
            } else {
                low = left;
                (left, g_left) = (right, g_right);
                right = low + ratio * (high - low);
                g_right = gap(right);
            }
        }
        0.5 * (low + high)
    }

    fn contact_point(&self, y: f64, position: &WheelsetPosition) -> Result<ContactPoint, ProfileError> {
        let (gap, wheel, rail) = self
            .gap(y, position)
            .ok_or_else(|| ProfileError::whole(format!("contact point y = {y} m off the profiles")))?;
        // Relative curvatures (module doc, "Ellipse"): the wheel's principal curvatures are
        // cos γ/r along its circumference and −κ_wheel along its profile; seen along the track's
        // x axis, at cos² = c² of the circumference's angle to it (Euler's theorem), and along
        // the patch's lateral axis at 1 − c². The straight rail bends only laterally.
        let circumferential = wheel.profile.slope_angle.cos() / wheel.radius;
        let along_x = wheel.circumferential_x * wheel.circumferential_x;
        Ok(ContactPoint {
            track_longitudinal: wheel.longitudinal,
            track_lateral: y,
            track_vertical: rail.vertical,
            rail_lateral: rail.lateral,
            wheel_lateral: wheel.profile.lateral,
            contact_angle: rail.slope_angle,
            rolling_radius: wheel.rolling_radius,
            gap_at_zero: gap,
            curvature_rolling: 0.5 * (along_x * circumferential - (1.0 - along_x) * wheel.profile.curvature),
            curvature_lateral: 0.5
                * (rail.curvature + (1.0 - along_x) * circumferential - along_x * wheel.profile.curvature),
        })
    }

    /// The loaded patches at the wheelset's vertical position (prescribed position): every
    /// candidate the wheel penetrates, merged where their interpenetration joins.
    pub fn patches_at(&self, position: &WheelsetPosition) -> Result<Vec<ContactPatch>, ProfileError> {
        check_position(position)?;
        let position = self.side.mirror_position(position);
        let points = self.right_points(&position)?;
        Ok(self.side.mirror_patches(self.load(&points, &position)?))
    }

    fn load(&self, points: &[ContactPoint], position: &WheelsetPosition) -> Result<Vec<ContactPatch>, ProfileError> {
        let z = position.vertical;
        let mut active: Vec<ContactPoint> = Vec::new();
        for point in points.iter().filter(|p| p.gap_at_zero < z) {
            if let Some(last) = active.last_mut() {
                if self.interpenetration_joins(last.track_lateral, point.track_lateral, z, position) {
                    if point.gap_at_zero < last.gap_at_zero {
                        *last = *point;
                    }
                    continue;
                }
            }
            active.push(*point);
        }
        active.iter().map(|point| self.patch(*point, (z - point.gap_at_zero) * point.contact_angle.cos())).collect()
    }

    /// Whether the gap stays below −z_ws everywhere between two track positions.
    fn interpenetration_joins(&self, from: f64, to: f64, vertical: f64, position: &WheelsetPosition) -> bool {
        let steps = ((to - from).abs() / SAMPLE_STEP).ceil().max(1.0) as usize;
        (0..=steps).all(|i| {
            let y = from + (to - from) * i as f64 / steps as f64;
            self.gap(y, position).is_some_and(|(g, _, _)| g < vertical)
        })
    }

    fn patch(&self, point: ContactPoint, penetration: f64) -> Result<ContactPatch, ProfileError> {
        let named = |e: InvalidInput| {
            ProfileError::whole(format!(
                "Hertz does not apply at the contact point y = {:.4} mm on the rail: {e}",
                point.rail_lateral * 1e3
            ))
        };
        let curvature = RelativeCurvature::new(point.curvature_rolling, point.curvature_lateral).map_err(named)?;
        // Hertz: δ ∝ Q^{2/3}, so Q = (δ/δ₁)^{3/2} with δ₁ the approach under 1 N.
        let unit = HertzContact::solve(1.0, &curvature, self.contact_modulus).map_err(named)?;
        let normal_force = (penetration / unit.approach).powf(1.5);
        let ellipse = HertzContact::solve(normal_force, &curvature, self.contact_modulus).map_err(named)?;
        Ok(ContactPatch { point, penetration, normal_force, ellipse })
    }

    /// Prescribed vertical force on the wheel \[N\]: the wheelset's vertical position at which
    /// the patches carry it, Σ Q_i·s_i = F_z with `vertical_share` s_i the vertical force a patch
    /// carries per newton of normal force (cos δ alone; [`super::wheel_forces`] adds its
    /// tangential force's share), found by bisection; returns it with the patches. F_z ≤ 0 is
    /// lift-off: no patch, the position where the wheel just touches.
    pub fn patches_for_force(
        &self,
        vertical_force: f64,
        position: &WheelsetPosition,
        vertical_share: impl Fn(&ContactPoint) -> f64,
    ) -> Result<(f64, Vec<ContactPatch>), ProfileError> {
        if !vertical_force.is_finite() {
            return Err(ProfileError::whole(format!("vertical_force = {vertical_force} must be finite")));
        }
        check_position(position)?;
        let position = &self.side.mirror_position(position);
        let points = self.right_points(position)?;
        let touch = points.iter().map(|p| p.gap_at_zero).fold(f64::INFINITY, f64::min);
        if vertical_force <= 0.0 {
            return Ok((touch, Vec::new()));
        }
        let carried = |z: f64| -> Result<(f64, Vec<ContactPatch>), ProfileError> {
            let patches = self.load(&points, &WheelsetPosition { vertical: z, ..*position })?;
            let carried = patches.iter().map(|p| p.normal_force * vertical_share(&self.side.mirror_point(&p.point)));
            Ok((carried.sum(), patches))
        };
        let (mut low, mut high) = (touch, touch + 1e-5);
        while carried(high)?.0 < vertical_force {
            low = high;
            high = touch + 2.0 * (high - touch);
            if high - touch > 0.1 {
                return Err(ProfileError::whole(format!(
                    "vertical_force = {vertical_force} N is not carried within 0.1 m of penetration"
                )));
            }
        }
        while high - low > 1e-13 {
            let middle = 0.5 * (low + high);
            if carried(middle)?.0 < vertical_force {
                low = middle;
            } else {
                high = middle;
            }
        }
        let z = 0.5 * (low + high);
        Ok((z, self.side.mirror_patches(carried(z)?.1)))
    }
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

/// The rail profile's gauge face: y of its inner (y < 0 side) flank at `height` below its top.
fn gauge_face(rail: &SmoothProfile, height: f64) -> Result<f64, ProfileError> {
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
    Ok(0.5 * (low + high))
}
