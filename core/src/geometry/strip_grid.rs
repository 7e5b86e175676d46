//! Where the non-Hertzian strips lie on the wheel profile: a fixed grid in the profile's y,
//! built once when the wheel is placed.
//!
//! Fixed on the wheel, the strips do not move with the wheelset, so a patch's strips enter and
//! leave one by one as the pose changes and the forces stay continuous in it. Their spacing
//! follows the patches' width where they lie: every [`STRIP_WIDTH`] (0.1 mm) of y where the wheel
//! profile is steeper than [`TREAD_SLOPE`] — the flange root and the flange, whose patches are
//! 1–4 mm wide across y, 6–9 strips on a flange at 10 kN — and every other one there, every
//! [`TREAD_STRIP_WIDTH`] (0.2 mm, CONTACT's lateral step DS in its decks), on the tread,
//! whose patches are 6–16 mm wide (the centred wheelset's, 132 strips at 0.1 mm, 67 at 0.2 mm).
//! Every 0.2 mm everywhere, the flange's strips made its normal force jump by 1 % of the load as
//! they entered; every 0.2 mm along the profile (as fine as 0.1 mm of y on a flange at 60°),
//! the converged flange-root angle of CONTACT's case y_ws 6.72 mm, 50 kN lay 0.0501 rad off its
//! 0.05 rad tolerance, 0.0494 on this grid (docs/geometry.md, "Speed"): the flange keeps the
//! grid its checks against CONTACT were made on.

use super::smooth_profile::SmoothProfile;

/// The strips' spacing in the wheel profile's y off the tread \[m\].
pub const STRIP_WIDTH: f64 = 1e-4;

/// The strips' spacing in the wheel profile's y on the tread \[m\]: every other strip of the
/// [`STRIP_WIDTH`] grid (those at even multiples of it).
pub const TREAD_STRIP_WIDTH: f64 = 2.0 * STRIP_WIDTH;

/// The wheel profile's inclination up to which it is tread \[rad\]: S1002's tread stays below
/// 0.12 rad over the cases; its flange root rises from 0.25 rad.
pub const TREAD_SLOPE: f64 = 0.2;

/// The wheel profile's y at each strip's centre, in increasing order.
#[derive(Debug, Clone)]
pub(super) struct StripGrid {
    lateral: Vec<f64>,
}

impl StripGrid {
    pub(super) fn new(wheel: &SmoothProfile) -> Self {
        let (from, to) = wheel.lateral_range();
        let (first, last) = ((from / STRIP_WIDTH).ceil() as i64, (to / STRIP_WIDTH).floor() as i64);
        let lateral = (first..=last)
            .map_while(|k| Some((k, wheel.at_lateral(k as f64 * STRIP_WIDTH)?)))
            .filter(|(k, point)| k % 2 == 0 || point.slope_angle.abs() > TREAD_SLOPE)
            .map(|(k, _)| k as f64 * STRIP_WIDTH)
            .collect();
        Self { lateral }
    }

    /// The number of strips.
    pub(super) fn len(&self) -> usize {
        self.lateral.len()
    }

    /// The wheel profile's y of strip `k`; beyond the profile's ends (no strip there, `None` for
    /// its geometry) the end strip's y moved on by [`TREAD_STRIP_WIDTH`] a strip.
    pub(super) fn lateral(&self, k: i64) -> f64 {
        let last = self.lateral.len() as i64 - 1;
        match usize::try_from(k) {
            Ok(i) if k <= last => self.lateral[i],
            Ok(_) => self.lateral[last as usize] + (k - last) as f64 * TREAD_STRIP_WIDTH,
            Err(_) => self.lateral[0] + k as f64 * TREAD_STRIP_WIDTH,
        }
    }

    /// The first strip at `y` or beyond (the strip count where none is).
    pub(super) fn first_from(&self, y: f64) -> i64 {
        self.lateral.partition_point(|&v| v < y) as i64
    }

    /// The last strip at `y` or before (−1 where none is).
    pub(super) fn last_to(&self, y: f64) -> i64 {
        self.lateral.partition_point(|&v| v <= y) as i64 - 1
    }

    /// The strip nearest to `y` (an end strip beyond the profile's ends; the lower of two as
    /// near).
    pub(super) fn nearest(&self, y: f64) -> i64 {
        let above = self.lateral.partition_point(|&v| v < y).min(self.lateral.len() - 1);
        let below = above.saturating_sub(1);
        if y - self.lateral[below] <= self.lateral[above] - y {
            below as i64
        } else {
            above as i64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ProfilePoints;

    /// A wheel-like profile from y = −5 to 15 mm: flat, rising at 60° (a flange flank) from 5 to
    /// 9 mm, then flat again.
    fn tread_and_flank() -> SmoothProfile {
        let slope = 60f64.to_radians().tan();
        let lateral: Vec<f64> = (-50..=150).map(|i| f64::from(i) * 0.1e-3).collect();
        let vertical = lateral.iter().map(|&y| (y.clamp(5e-3, 9e-3) - 5e-3) * slope).collect();
        SmoothProfile::new(&ProfilePoints { lateral, vertical }).unwrap()
    }

    /// 0.2 mm apart on the flat (at even multiples of 0.1 mm), 0.1 mm on the flank; the
    /// searches find the strips around a y.
    #[test]
    fn the_strips_are_twice_as_far_apart_on_the_tread() {
        let grid = StripGrid::new(&tread_and_flank());
        let y = |k: i64| grid.lateral(k);
        let tread = grid.first_from(-2.05e-3);
        assert!((y(tread) + 2e-3).abs() < 1e-15 && (y(tread + 1) + 1.8e-3).abs() < 1e-15);
        let flank = grid.first_from(7e-3);
        assert!((y(flank) - 7e-3).abs() < 1e-15 && (y(flank + 1) - 7.1e-3).abs() < 1e-15);
        let beyond = grid.first_from(12.05e-3);
        assert!((y(beyond) - 12.2e-3).abs() < 1e-15 && (y(beyond + 1) - 12.4e-3).abs() < 1e-15);
        // The whole profile, in increasing order: from −5 mm to 15 mm, 50 + 40 + 30 strips (the
        // flank's 41 from 5.0 to 9.0 mm; where the spline's slope passes 0.2 rad either side,
        // odd strips kept a little beyond).
        let n = grid.len() as i64;
        assert!((0..n - 1).all(|k| y(k + 1) > y(k)));
        assert!((y(0) + 5e-3).abs() < 1e-15 && (y(n - 1) - 15e-3).abs() < 1e-15, "{} {}", y(0), y(n - 1));
        assert!((118..=126).contains(&n), "{n} strips");
        // The searches: first at or beyond, last at or before, nearest.
        let between = y(tread) + 0.3 * TREAD_STRIP_WIDTH;
        assert_eq!((grid.first_from(between), grid.last_to(between), grid.nearest(between)), (tread + 1, tread, tread));
        assert_eq!(grid.nearest(y(tread) + 0.7 * TREAD_STRIP_WIDTH), tread + 1);
        assert_eq!((grid.first_from(y(tread)), grid.last_to(y(tread))), (tread, tread));
        // Beyond the ends: moved on by the tread's spacing a strip; the searches stay at the ends.
        assert!((y(-2) - (-5e-3 - 2.0 * TREAD_STRIP_WIDTH)).abs() < 1e-15);
        assert!((y(n + 1) - (15e-3 + 2.0 * TREAD_STRIP_WIDTH)).abs() < 1e-15);
        assert_eq!((grid.first_from(-1.0), grid.last_to(-1.0), grid.nearest(-1.0)), (0, -1, 0));
        assert_eq!((grid.first_from(1.0), grid.last_to(1.0), grid.nearest(1.0)), (n, n - 1, n - 1));
    }
}
