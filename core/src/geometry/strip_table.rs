//! The non-Hertzian strips' geometry from tables ([`WheelOnRail::with_strip_table`]): what a
//! pose's strips cost without an exact spline point per strip.
//!
//! What the strips depend on. A strip is fixed in the wheel profile's y (a multiple of
//! [`STRIP_WIDTH`], [`super::non_hertzian`], module doc, 1); its geometry at a pose is the wheel's
//! contact locus there (`contact.rs`, module doc, "Yaw") and the rail under it. The locus is the
//! wheel profile's point at the strip (its height z_w and slope tan γ_w: fixed per strip) moved by
//! the wheelset's rigid motion: in closed form in y_ws, roll and yaw, a square root and a dozen
//! multiplications ([`LocusFrame::track_position`]). Only the rail depends on the pose through a
//! profile: its height and slope at the locus' track y. So a table over the pose (y_ws, roll,
//! yaw) is not needed: the wheel's profile per strip is tabulated exactly (one spline point per
//! strip, once), and the rail is read from its samples every 0.025 mm by cubic Hermite
//! interpolation, as the contact search reads it (`sampled_profile.rs`: within 2 nm in height
//! and 2e-5 rad in slope up to 70°). Exact in the pose, no yaw correction, no range to fall out
//! of; the only error is the rail's interpolation, measured in
//! `core/tests/library/strip_table.rs`.
//!
//! Where the strips start. The exact path scans the sampled gap every 0.2 mm over the wheel's
//! whole width to find the stretch within reach of the gap's minimum; here the contact search's
//! minima (its scan of the sampled gap, started from the contact table: each minimum's lowest
//! sample, neither refined by Brent's method nor an exact point as in
//! [`WheelOnRail::candidates`]) start the stretch,
//! which grows strip by strip from them while the gap lies within reach: every strip within reach
//! of the minimum lies in a basin of a minimum within reach (a connected run of strips below a
//! level holds a local minimum of the gap), the strips between two such minima are cut as the
//! exact path cuts them, and one strip beyond each end (out of contact: its gap lies above any
//! z_ws solved on this reach) closes the stretch as the exact path's scan step does.

use super::contact::{LocusFrame, WheelOnRail, WheelsetPosition};
use super::non_hertzian::StripPoint;
use super::profile_file::ProfileError;

/// The wheel profile at every strip's centre.
#[derive(Debug, Clone)]
pub(super) struct StripTable {
    /// The wheel profile's y \[m\], height z_w \[m\] and slope tan γ_w at strip k of the wheel's
    /// strip grid (`strip_grid.rs`).
    wheel: Vec<(f64, f64, f64)>,
}

impl StripTable {
    /// The exact spline point of every strip over the wheel profile's lateral extent.
    fn new(placed: &WheelOnRail) -> Self {
        let grid = placed.strip_grid();
        let wheel = (0..grid.len() as i64)
            .map(|k| grid.lateral(k))
            .map_while(|lateral| Some((lateral, placed.wheel.at_lateral(lateral)?)))
            .map(|(lateral, point)| (lateral, point.vertical, point.slope_angle.tan()))
            .collect();
        Self { wheel }
    }

    /// Strip k's wheel profile y and its geometry at the pose of `frame` (right side, z_ws = 0);
    /// `None` off the profiles. Inlined into the cut's loop (it was called there, its result
    /// passed through memory): one criterion run against the call, non-Hertzian wheel steps
    /// 3–10 % faster repeated, 2–7 % moving.
    #[inline(always)]
    pub(super) fn strip(&self, placed: &WheelOnRail, frame: &LocusFrame, k: i64) -> (f64, Option<StripPoint>) {
        match usize::try_from(k).ok().and_then(|i| self.wheel.get(i)) {
            Some(&(lateral, height, slope)) => (lateral, Self::point(placed, frame, lateral, height, slope)),
            None => (placed.strip_grid().lateral(k), None),
        }
    }

    /// The geometry of the strip at wheel profile y `lateral` (height, slope tan γ_w there).
    #[inline(always)]
    fn point(placed: &WheelOnRail, frame: &LocusFrame, lateral: f64, height: f64, slope: f64) -> Option<StripPoint> {
        let (track_lateral, vertical, rolling_radius) = frame.track_position(placed, lateral, height, slope)?;
        let rail_lateral = track_lateral - placed.rail_offset;
        let (rail_height, rail_slope) = placed.rail_samples.at(rail_lateral)?;
        let track_vertical = rail_height + placed.rail_lift;
        // sin γ, cos γ of γ = atan(dz/dy) without trigonometry.
        let cos = 1.0 / (1.0 + rail_slope * rail_slope).sqrt();
        Some(StripPoint {
            gap: track_vertical - vertical,
            rolling_radius,
            track_lateral,
            rail_lateral,
            track_vertical,
            sin_cos: (rail_slope * cos, cos),
        })
    }

    /// The contact search's minima of the gap at the right-side pose `right` as strips:
    /// (k, the lowest sampled gap of the minimum, z_ws = 0), where the stretches start (module
    /// doc); the lowest of them is the pose's touch, which the strips' reach is measured from.
    pub(super) fn minima(placed: &WheelOnRail, right: &WheelsetPosition) -> Result<Vec<(i64, f64)>, ProfileError> {
        let minima = placed.gap_minima(right)?;
        Ok(minima.into_iter().map(|(profile_y, gap)| (placed.strip_grid().nearest(profile_y), gap)).collect())
    }
}

impl WheelOnRail {
    /// The same wheel with its non-Hertzian strips' geometry from tables (the wheel's profile at
    /// every strip's centre, the rail's samples; module doc of `geometry/strip_table.rs`) instead
    /// of an exact spline point per strip and pose: the non-Hertzian normal problem
    /// ([`Self::non_hertzian_pose`]) of every pose costs a fraction, within 2 nm of the exact
    /// gap. Built in under half a millisecond on S1002 (852 strips); only worth it with the non-Hertzian contact.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    ///
    /// let exact = WheelOnRail::manchester_benchmark(WheelSide::Left);
    /// let tabled = exact.clone().with_strip_table();
    /// let position = WheelsetPosition { lateral: -5e-3, yaw: -2e-3, ..Default::default() };
    /// let (a, b) = (
    ///     exact.non_hertzian_patches_for_force(10e3, &position).unwrap(),
    ///     tabled.non_hertzian_patches_for_force(10e3, &position).unwrap(),
    /// );
    /// assert_eq!(a.patches.len(), b.patches.len());
    /// for (a, b) in a.patches.iter().zip(&b.patches) {
    ///     assert!((a.patch.point.rail_lateral - b.patch.point.rail_lateral).abs() < 1e-5);
    ///     assert!((a.patch.normal_force / b.patch.normal_force - 1.0).abs() < 1e-3);
    /// }
    /// ```
    pub fn with_strip_table(self) -> Self {
        let mut placed = self;
        placed.strip_table = Some(StripTable::new(&placed));
        placed
    }
}
