//! The figures of `contact_method = non_hertzian` in the FMU's documentation: the patch's shape
//! and its pressure on the FMU's default profiles (the built-in S1002 wheel on the UIC60 rail
//! 1:40, the Manchester benchmark's track, right wheel, 10 kN frictionless), at the centred
//! wheelset, where the gap is flat within microns over about 10 mm, and at the tread–flange
//! transition, where Hertz finds two patches at the gap's two minima and the profiles' regions
//! join into one. Each beside Hertz's ellipse at the same pose (`contact_method = hertz`).
//! Computed with the core, as the FMU computes it.

use wheel_rail_contact::geometry::{ContactPatch, NonHertzianPatch, Strip, WheelOnRail, WheelSide, WheelsetPosition};

use crate::plot::{line_plot, Series};

/// The wheelset's lateral displacements drawn \[m\]: centred, and at the transition.
pub const DISPLACEMENTS: [f64; 2] = [0.0, 5e-3];
/// The wheel load \[N\].
pub const LOAD: f64 = 10e3;
/// Points on each half of a Hertz ellipse's outline.
const ELLIPSE_POINTS: usize = 24;

/// Both solutions of one pose: the non-Hertzian patches and Hertz's.
pub struct Pose {
    pub lateral: f64,
    pub non_hertzian: Vec<NonHertzianPatch>,
    pub hertz: Vec<ContactPatch>,
}

/// The right wheel at `lateral` (roll and yaw 0) carrying [`LOAD`], frictionless, by both methods.
pub fn pose(lateral: f64) -> Pose {
    let wheel = WheelOnRail::manchester_benchmark(WheelSide::Right);
    let position = WheelsetPosition { lateral, ..Default::default() };
    let non_hertzian =
        wheel.non_hertzian_patches_for_force(LOAD, &position).expect("the benchmark's wheel is in contact");
    let (_, hertz) = wheel
        .patches_for_force(LOAD, &position, |point| point.contact_angle.cos())
        .expect("the benchmark's wheel is in contact");
    Pose { lateral, non_hertzian: non_hertzian.patches, hertz }
}

fn millimetres(metres: f64) -> f64 {
    metres * 1e3
}

/// A non-Hertzian patch's strips as curves against their position on the rail \[mm\], one value
/// a strip at its centre, falling to 0 at the edges of each of its regions (a strip beyond the
/// next is the start of another region), so that two regions of one patch are drawn apart.
fn by_region(patch: &NonHertzianPatch, value: impl Fn(&Strip) -> f64) -> Vec<(f64, f64)> {
    let mut points = Vec::with_capacity(patch.strips.len() + 4);
    for (k, strip) in patch.strips.iter().enumerate() {
        let edge = strip.width / 2.0;
        let starts = k == 0 || (strip.rail_lateral - patch.strips[k - 1].rail_lateral).abs() > 3.0 * edge;
        if starts {
            // The strips run from the field side (+y on the right rail) to the gauge side.
            if let Some(last) = k.checked_sub(1).map(|j| &patch.strips[j]) {
                points.push((millimetres(last.rail_lateral - last.width / 2.0), 0.0));
            }
            points.push((millimetres(strip.rail_lateral + edge), 0.0));
        }
        points.push((millimetres(strip.rail_lateral), value(strip)));
    }
    if let Some(last) = patch.strips.last() {
        points.push((millimetres(last.rail_lateral - last.width / 2.0), 0.0));
    }
    points
}

/// A non-Hertzian patch's outline in plan view: the strips' ends ±L along x \[mm\], closed.
fn strip_outline(patch: &NonHertzianPatch) -> Vec<(f64, f64)> {
    let ahead = by_region(patch, |s| millimetres(s.half_length));
    let behind = ahead.iter().rev().map(|&(y, x)| (y, -x));
    let mut outline: Vec<(f64, f64)> = ahead.iter().copied().chain(behind).collect();
    outline.extend(outline.first().copied());
    outline
}

/// Hertz's ellipse in the same plan view: semi-axis a along x, b along the contact plane,
/// projected on the rail's y by cos δ, closed.
fn ellipse_outline(patch: &ContactPatch) -> Vec<(f64, f64)> {
    let across = patch.ellipse.semi_axis_b * patch.point.contact_angle.cos();
    (0..=2 * ELLIPSE_POINTS)
        .map(|i| {
            let t = std::f64::consts::PI * i as f64 / ELLIPSE_POINTS as f64;
            (millimetres(patch.point.rail_lateral + across * t.cos()), millimetres(patch.ellipse.semi_axis_a * t.sin()))
        })
        .collect()
}

/// A non-Hertzian patch's pressure along x = 0, strip by strip \[MPa\].
fn strip_pressure(patch: &NonHertzianPatch) -> Vec<(f64, f64)> {
    by_region(patch, |s| s.max_pressure / 1e6)
}

/// Hertz's pressure along its ellipse's b axis, p0 √(1 − (y/b)²) \[MPa\].
fn ellipse_pressure(patch: &ContactPatch) -> Vec<(f64, f64)> {
    let across = patch.ellipse.semi_axis_b * patch.point.contact_angle.cos();
    (0..=2 * ELLIPSE_POINTS)
        .map(|i| {
            let t = std::f64::consts::PI * i as f64 / (2 * ELLIPSE_POINTS) as f64;
            (millimetres(patch.point.rail_lateral - across * t.cos()), patch.ellipse.max_pressure * t.sin() / 1e6)
        })
        .collect()
}

/// The pose's curves: its non-Hertzian patches and Hertz's ellipses, each labelled.
fn curves(
    pose: &Pose,
    non_hertzian: fn(&NonHertzianPatch) -> Vec<(f64, f64)>,
    hertz: fn(&ContactPatch) -> Vec<(f64, f64)>,
) -> Vec<Series> {
    let y_ws = millimetres(pose.lateral);
    let non_hertzian = pose.non_hertzian.iter().enumerate().map(|(k, patch)| Series {
        label: format!(
            "non_hertzian, y_ws = {y_ws} mm, patch {}: N = {:.2} kN, δ = {:.3} rad",
            k + 1,
            patch.patch.normal_force / 1e3,
            patch.patch.point.contact_angle
        ),
        points: non_hertzian(patch),
    });
    let hertz = pose.hertz.iter().enumerate().map(|(k, patch)| Series {
        label: format!(
            "hertz, y_ws = {y_ws} mm, patch {}: N = {:.2} kN, δ = {:.3} rad",
            k + 1,
            patch.normal_force / 1e3,
            patch.point.contact_angle
        ),
        points: hertz(patch),
    });
    non_hertzian.chain(hertz).collect()
}

/// The two figures of one pose as SVG documents: the patches' shape, and their pressure.
pub fn figures(lateral: f64) -> String {
    let pose = pose(lateral);
    let title =
        |what: &str| format!("S1002 on UIC60 1:40, right wheel, y_ws = {} mm, 10 kN: {what}", millimetres(lateral));
    let shape = line_plot(
        &title("the patches in plan view"),
        "rail y [mm] (the rail profile's; the gauge side to the left)",
        "x along the track [mm]",
        &curves(&pose, strip_outline, ellipse_outline),
    );
    let pressure = line_plot(
        &title("the pressure along x = 0"),
        "rail y [mm] (the rail profile's; the gauge side to the left)",
        "pressure [MPa]",
        &curves(&pose, strip_pressure, ellipse_pressure),
    );
    shape + &pressure
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Centred: one patch by both methods, the non-Hertzian one wider than Hertz's ellipse (the
    /// gap is flat; CONTACT's patch reaches 15.8 mm across, from a gauge-side lobe over the
    /// tread), its centroid further to the gauge side (CONTACT's case 1: −9.09 mm on the
    /// rail; Hertz's gap minimum −7.28 mm). At 5 mm Hertz's two minima (tread and flange root)
    /// become one joined patch, as CONTACT finds it.
    #[test]
    fn centred_wide_and_low_at_5_mm_one_joined_patch_where_hertz_has_two() {
        let centred = pose(0.0);
        assert_eq!((centred.non_hertzian.len(), centred.hertz.len()), (1, 1));
        let (wide, ellipse) = (&centred.non_hertzian[0], &centred.hertz[0]);
        let width = wide.strips[0].rail_lateral - wide.strips.last().unwrap().rail_lateral;
        assert!((12e-3..16e-3).contains(&width), "{width}");
        assert!(
            width > 2.0 * ellipse.ellipse.semi_axis_b,
            "{width} against 2b = {}",
            2.0 * ellipse.ellipse.semi_axis_b
        );
        assert!((wide.patch.point.rail_lateral + 9.09e-3).abs() < 0.65e-3, "{}", wide.patch.point.rail_lateral);
        assert!(wide.patch.point.rail_lateral < ellipse.point.rail_lateral - 0.5e-3);

        let transition = pose(5e-3);
        assert_eq!((transition.non_hertzian.len(), transition.hertz.len()), (1, 2));
        // Every strip's force sums to the patch's vertical load.
        let patch = &transition.non_hertzian[0];
        let vertical: f64 = patch.strips.iter().map(|s| s.normal_force * s.contact_angle.cos()).sum();
        assert!((vertical - LOAD).abs() < 1e-6 * LOAD, "{vertical}");
    }

    #[test]
    fn each_pose_draws_its_patches_twice() {
        for lateral in DISPLACEMENTS {
            let pose = pose(lateral);
            let svg = figures(lateral);
            let patches = pose.non_hertzian.len() + pose.hertz.len();
            assert_eq!(svg.matches("<polyline").count(), 2 * patches);
            // Outlines close on themselves.
            for curve in curves(&pose, strip_outline, ellipse_outline) {
                let (first, last) = (curve.points[0], curve.points[curve.points.len() - 1]);
                assert!((first.0 - last.0).abs() < 1e-9 && (first.1 - last.1).abs() < 1e-9, "{}", curve.label);
            }
        }
    }
}
