//! Measured profiles (issue 39): real MiniProf and SIMPACK measurements from CONTACT's test bank
//! (`core/tests/data/profiles/measured/README.md`) read, cleaned and smoothed; files that must be
//! refused, refused with the line and the reason.

use wheel_rail_contact::geometry::{
    builtin_profile, read_measured_profile, MeasuredOptions, MeasuredProfile, Orientation, ProfileFormat, ProfileKind,
    SmoothProfile, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition, MEASURED_FILTER_WAVELENGTH,
};

use crate::common::{measured_text as text, read_measured as read, read_measured_as as read_as};

fn top(profile: &MeasuredProfile) -> (f64, f64) {
    let (y, z) = (&profile.points.lateral, &profile.points.vertical);
    let i = (0..z.len()).min_by(|&a, &b| z[a].total_cmp(&z[b])).unwrap();
    (y[i], z[i])
}

fn lowest(profile: &MeasuredProfile) -> (f64, f64) {
    let (y, z) = (&profile.points.lateral, &profile.points.vertical);
    let i = (0..z.len()).max_by(|&a, &b| z[a].total_cmp(&z[b])).unwrap();
    (y[i], z[i])
}

#[test]
fn every_real_file_is_read_with_its_running_surface() {
    // (file, points read, kept, zig-zags merged, back-steps dropped, overhang dropped, y mirrored, z mirrored)
    let cases = [
        ("Car7216_0001r.whl", 645, 536, 0, 109, 0, false, false),
        ("avg_wheel.whl", 728, 671, 0, 57, 0, false, false),
        ("left-wheel-v1-pre-dry.whl", 667, 667, 0, 0, 0, false, false),
        ("right-wheel-v1-pre-dry.whl", 664, 664, 0, 0, 0, false, false),
        ("avg_HR.BAN", 147, 146, 1, 0, 0, true, true),
        ("avg_low2.ban", 526, 334, 1, 166, 25, true, true),
        ("rail_left_iter288.ban", 571, 521, 0, 47, 3, true, true),
        ("site_b_hr.prr", 493, 462, 0, 31, 0, false, false),
    ];
    for (name, points_read, kept, zigzags, back_steps, overhang, y_mirrored, z_mirrored) in cases {
        let profile = read(name);
        let y = &profile.points.lateral;
        assert_eq!(
            (profile.points_read, y.len(), profile.zigzags, profile.back_steps, profile.overhang_points),
            (points_read, kept, zigzags, back_steps, overhang),
            "{name}"
        );
        assert_eq!(profile.close_points, 0, "{name}");
        assert_eq!((profile.lateral_mirrored, profile.vertical_mirrored), (y_mirrored, z_mirrored), "{name}");
        assert!(y.windows(2).all(|w| w[1] > w[0]), "{name}: y strictly increasing");
        let (first, last) = (profile.points.vertical[0], profile.points.vertical[y.len() - 1]);
        match ProfileKind::from_file_name(name).unwrap() {
            ProfileKind::Rail => {
                // z downward: the head's top within 2 mm of the origin, both ends below it.
                let (_, top_z) = top(&profile);
                assert!((0.0..2e-3).contains(&top_z), "{name}: top at {top_z}");
                assert!(
                    first > top_z && last > top_z && first.max(last) - top_z > 10e-3,
                    "{name}: ends {first} {last}, top {top_z}"
                );
                assert_eq!(profile.flange_back_position, None);
            }
            ProfileKind::Wheel => {
                // z downward: the flange tip 27–29 mm below the tread (z ≈ 0 at 70 mm from the
                // flange back, y = 0, for a MiniProf wheel), on the −y side; the faces above.
                let (tip_y, tip_z) = lowest(&profile);
                assert!((27e-3..29e-3).contains(&tip_z), "{name}: flange tip at z {tip_z}");
                assert!((10e-3..25e-3).contains(&tip_y), "{name}: flange tip at y {tip_y}");
                let tread = SmoothProfile::new(&profile.points).unwrap().at_lateral(70e-3).unwrap().vertical;
                assert!(tread.abs() < 1e-3, "{name}: tread at {tread}");
                // The field face rises above the tread; the flange back from the flange tip.
                assert!(last < tread && first < tip_z, "{name}: faces {first} {last}");
                assert_eq!(profile.flange_back_position, Some(0.0));
            }
        }
    }
}

#[test]
fn the_worn_rails_show_their_wear_on_the_right_side() {
    // Mirrored to the right side, the high rail's gauge face (measured 25 mm deep) lies at −y, and
    // the left rail's worn top is off towards the field side (+y), the gauge corner worn down.
    let high = read("avg_HR.BAN");
    assert!((high.points.lateral[0] + 46.59e-3).abs() < 1e-9 && (high.points.vertical[0] - 25.42e-3).abs() < 1e-9);
    let left = read("rail_left_iter288.ban");
    let (top_y, top_z) = top(&left);
    assert!(top_y > 15e-3, "top at y {top_y}");
    assert!((top_z - 1.7281e-3).abs() < 1e-3, "top at z {top_z}");
    // The low rail's field-side lip is kept to its tip, 54.06 mm out; what turns back under the
    // gauge corner (25 points) is dropped.
    let low = read("avg_low2.ban");
    assert!((low.points.lateral[low.points.lateral.len() - 1] - 54.06e-3).abs() < 1e-9);
}

#[test]
fn a_left_measurement_is_mirrored_into_the_right_one() {
    // The right wheel's file written as a left-side frame would write it (y negated): detected by
    // its flange, mirrored, and then the very same points.
    let right_text = text("right-wheel-v1-pre-dry.whl");
    let mut left_text = String::new();
    let mut in_points = false;
    for line in right_text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        in_points |= line.starts_with("XYPoints");
        match (in_points, fields.as_slice()) {
            (true, [y, z]) if y.parse::<f64>().is_ok() => {
                left_text.push_str(&format!("{} {z}\n", -y.parse::<f64>().unwrap()))
            }
            _ => left_text.push_str(&format!("{line}\n")),
        }
    }
    let right = read("right-wheel-v1-pre-dry.whl");
    let left = read_as(&left_text, "left.whl").unwrap();
    // Written with z upward, the same wheel is turned back to the same points.
    let upward: String = left_text
        .lines()
        .map(|line| match line.split_whitespace().collect::<Vec<_>>().as_slice() {
            [y, z] if z.parse::<f64>().is_ok() => format!("{y} {}\n", -z.parse::<f64>().unwrap()),
            _ => format!("{line}\n"),
        })
        .collect();
    let upward = read_as(&upward, "upward.whl").unwrap();
    assert!(upward.vertical_mirrored && upward.lateral_mirrored && !left.vertical_mirrored);
    assert_eq!(upward.points, right.points);
    assert!(left.lateral_mirrored && !right.lateral_mirrored);
    assert_eq!(left.points, right.points);
    // The UIC60 rail as CONTACT writes it in MiniProf's frame (track centre at +y, z downward) is
    // the SIMPACK rail once mirrored: no option needed.
    let ban =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/profiles/MBench_UIC60_v3.ban")).unwrap();
    let miniprof = read_as(&ban, "uic60.ban").unwrap();
    assert!(miniprof.lateral_mirrored && !miniprof.vertical_mirrored);
    let simpack = SmoothProfile::new(&builtin_profile("MBench_UIC60").unwrap()).unwrap();
    let miniprof = SmoothProfile::new(&miniprof.points).unwrap();
    for i in 0..=100 {
        let y = -0.030 + 0.060 * f64::from(i) / 100.0;
        let (a, b) = (simpack.at_lateral(y).unwrap().vertical, miniprof.at_lateral(y).unwrap().vertical);
        assert!((a - b).abs() < 1e-7, "z({y}): {a} vs {b}");
    }
}

#[test]
fn the_caller_may_say_the_orientation() {
    let name = "avg_HR.BAN";
    let options =
        MeasuredOptions { lateral: Orientation::AsRead, vertical: Orientation::Mirrored, ..MeasuredOptions::default() };
    let as_read = read_measured_profile(&text(name), ProfileFormat::MiniProf, ProfileKind::Rail, &options).unwrap();
    let detected = read(name);
    assert!(!as_read.lateral_mirrored && as_read.vertical_mirrored);
    let mirrored_back: Vec<f64> = as_read.points.lateral.iter().rev().map(|y| -y).collect();
    assert_eq!(mirrored_back, detected.points.lateral);
}

/// σ of the points' noise, normal to the profile, from each point's distance to the chord of its
/// neighbours (white noise σ gives a distance of variance 1.5 σ²; the profile's own curvature adds
/// κh²/8 ≈ 0.2 µm at 0.25 mm spacing and 30 mm radius).
fn noise(points: &wheel_rail_contact::geometry::ProfilePoints) -> f64 {
    let (y, z) = (&points.lateral, &points.vertical);
    let distances: Vec<f64> = (1..y.len() - 1)
        .map(|i| {
            let (dy, dz) = (y[i + 1] - y[i - 1], z[i + 1] - z[i - 1]);
            ((y[i] - y[i - 1]) * dz - (z[i] - z[i - 1]) * dy) / dy.hypot(dz)
        })
        .collect();
    (distances.iter().map(|d| d * d).sum::<f64>() / distances.len() as f64 / 1.5).sqrt()
}

#[test]
fn the_smoothed_measured_profile_stays_within_the_measurement_noise() {
    for name in [
        "Car7216_0001r.whl",
        "avg_wheel.whl",
        "right-wheel-v1-pre-dry.whl",
        "avg_HR.BAN",
        "avg_low2.ban",
        "rail_left_iter288.ban",
    ] {
        let profile = read(name);
        let sigma = noise(&profile.points);
        let smooth = profile.smooth(MEASURED_FILTER_WAVELENGTH).unwrap();
        let residuals: Vec<f64> = profile
            .points
            .lateral
            .iter()
            .zip(&profile.points.vertical)
            .filter_map(|(&y, &z)| {
                let point = smooth.at_lateral(y)?;
                Some((point.vertical - z) * point.slope_angle.cos())
            })
            .collect();
        let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len() as f64).sqrt();
        // The points' point-to-point scatter is 1.5–12 µm; smoothed, the profile departs from
        // them by 4.5–27 µm RMS (the scatter and the measurement's waviness shorter than the
        // filter's 5 mm, as where sections are stitched); the bound is 30 µm, the largest 27 µm.
        assert!((1e-6..15e-6).contains(&sigma), "{name}: noise σ {sigma}");
        assert!(rms < 30e-6, "{name}: residual rms {rms}");
        // Interpolated, the profile keeps every point.
        let raw = profile.smooth(0.0).unwrap();
        let y = profile.points.lateral[100];
        assert!((raw.at_lateral(y).unwrap().vertical - profile.points.vertical[100]).abs() < 1e-12);
    }
}

#[test]
fn the_contact_search_on_measured_profiles_finds_the_contact_not_the_noise() {
    // A measured wheel (MiniProf, flange back at y = 0) on a measured high rail (MiniProf, in its
    // own axes: inclined 1:40 by the placement), wheelset centred and ±2 mm.
    let (wheel, rail) = (read("right-wheel-v1-pre-dry.whl"), read("avg_HR.BAN"));
    let dimensions = TrackDimensions {
        flange_back_position: wheel.flange_back_position.unwrap(),
        rail_cant: (1.0f64 / 40.0).atan(),
        ..TrackDimensions::MANCHESTER_BENCHMARK
    };
    let place = |wavelength| {
        WheelOnRail::new(
            wheel.smooth(wavelength).unwrap(),
            rail.smooth(wavelength).unwrap(),
            dimensions,
            WheelSide::Right,
            82e9,
            0.28,
        )
        .unwrap()
    };
    let (raw, smooth) = (place(0.0), place(MEASURED_FILTER_WAVELENGTH));
    let centred = WheelsetPosition::default();
    // Unsmoothed, the gap has a local minimum at every bump of the noise: four within 6 mm on
    // the tread.
    let raw_points = raw.contact_points(&centred).unwrap();
    assert_eq!(raw_points.len(), 4, "{raw_points:?}");
    for lateral in [-2e-3, 0.0, 2e-3] {
        let position = WheelsetPosition { lateral, ..centred };
        let points = smooth.contact_points(&position).unwrap();
        assert!((1..=2).contains(&points.len()), "y_ws = {lateral}: {points:?}");
        let lowest = points.iter().map(|p| p.gap_at_zero).fold(f64::INFINITY, f64::min);
        let patches = smooth.patches_at(&WheelsetPosition { vertical: lowest + 0.1e-3, ..position }).unwrap();
        assert_eq!(patches.len(), 1, "y_ws = {lateral}");
    }
    // Centred, the one contact is on the tread, 75 mm from the flange back, rolling on the
    // nominal radius within a millimetre.
    let points = smooth.contact_points(&centred).unwrap();
    let contact = points.iter().min_by(|a, b| a.gap_at_zero.total_cmp(&b.gap_at_zero)).unwrap();
    assert!((contact.wheel_lateral - 75e-3).abs() < 3e-3, "{contact:?}");
    assert!((contact.rolling_radius - 0.460).abs() < 1e-3, "{contact:?}");
}

#[test]
fn bad_measured_files_are_refused_with_the_line_and_the_reason() {
    let wheel = |text: &str| read_as(text, "bad.whl").unwrap_err();
    let points = "0 -10\n1 10\n3 26\n5 28\n8 26\n12 18\n20 6\n40 1\n70 0\n100 -1\n130 -3\n131 -20\n";
    let good = read_as(&format!("#MINIWHEELPROF\nwheel\n\n{points}"), "good.whl").unwrap();
    assert_eq!(good.points.lateral.len(), 12);
    // A point repeated, and one 0.05 µm from it, are one point (CONTACT's 0.1 µm); 0.2 µm
    // apart they are two.
    let close = points.replace("5 28\n", "5 28\n5 28\n5.00005 28\n5.0002 28\n");
    let close = read_as(&format!("ColumnDef=X,Y\n\n{close}"), "good.whl").unwrap();
    assert_eq!((close.points_read, close.close_points, close.points.lateral.len()), (15, 2, 13));
    // A stitched joint on the tread (41 then back to 40.5 mm): the zig-zag's two points become
    // their mean, 40.75 mm.
    let stitched = points.replace("40 1\n", "40 1\n41 1\n40.5 1\n");
    let stitched = read_as(&format!("ColumnDef=X,Y\n\n{stitched}"), "good.whl").unwrap();
    assert_eq!((stitched.zigzags, stitched.back_steps, stitched.points.lateral.len()), (1, 0, 13));
    assert!(stitched
        .points
        .lateral
        .iter()
        .zip(&stitched.points.vertical)
        .any(|(&y, &z)| (y - 40.75e-3).abs() < 1e-15 && z == 1e-3));
    // The z direction does not depend on where the file puts z = 0 (`Yoffset`, mm).
    for offset in [-40.0, 40.0] {
        let moved = read_as(&format!("Yoffset={offset}\n\n{points}"), "good.whl").unwrap();
        assert!(!moved.vertical_mirrored, "Yoffset {offset}");
        assert_eq!(moved.points.lateral, good.points.lateral);
    }
    // A `=` in a point's comment is no header line; `Xoffset` moves the points (mm).
    let shifted = read_as(&format!("Xoffset=1.5\n\n0 -10 ! x=0\n{}", &points[6..]), "good.whl").unwrap();
    assert_eq!(shifted.points.lateral.len(), 12);
    assert!((shifted.points.lateral[11] - 132.5e-3).abs() < 1e-15);
    let e = wheel(&format!("ColumnDef=X,Y\n\n{points}XYPoints=12\n"));
    assert_eq!(e.to_string(), "line 15: a header line `XYPoints=12` among the points");
    let e = wheel(&format!("ColumnDef=X,Y\n\n0 -10\n1 1O\n{points}"));
    assert_eq!(e.to_string(), "line 4: expected a number, found `1O` in `1 1O`");
    let e = wheel(&format!("Xoffset=abc\n\n{points}"));
    assert_eq!(e.to_string(), "line 1: `Xoffset` must be a finite number, found `abc`");
    let e = wheel("ColumnDef=X,Y\n\n0 1\n1 2\n2 3\n");
    assert_eq!(e.to_string(), "3 profile points; a profile needs at least 4");
    let e = wheel(&format!("ColumnDef=X,Y\n\n{points}140 5000\n"));
    assert_eq!(e.line, Some(15));
    assert!(e.reason.contains("more than 1 m from the profile's origin"), "{e}");
    // A tread alone, no faces: which way z points cannot be told.
    let e = wheel("ColumnDef=X,Y\n\n40 1\n50 0.8\n60 0.5\n70 0\n80 -0.2\n90 -0.5\n");
    assert!(e.reason.starts_with("cannot tell which way z points"), "{e}");
    assert_eq!(e.line, None);
    // A "rail" that turns back 5 mm just beside its top keeps three points: no running surface.
    let as_read =
        MeasuredOptions { lateral: Orientation::AsRead, vertical: Orientation::AsRead, ..MeasuredOptions::default() };
    let e = read_measured_profile(
        "ColumnDef=X,Y\n\n-1 30\n0 0\n1 1\n-4 2\n5 30\n",
        ProfileFormat::MiniProf,
        ProfileKind::Rail,
        &as_read,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "only 3 points keep advancing in y around the rail's top (it turns back at line 6): not a profile's running surface"
    );
}

#[test]
fn the_smoothing_spline_is_a_smooth_cubic_spline_and_filters_noise() {
    // A 300 mm crown every 0.25 mm with a ±10 µm zig-zag (0.5 mm wavelength).
    let radius = 0.3;
    let lateral: Vec<f64> = (-160..=160).map(|i| f64::from(i) * 0.25e-3).collect();
    let exact = |y: f64| radius - (radius * radius - y * y).sqrt();
    let vertical =
        lateral.iter().enumerate().map(|(i, &y)| exact(y) + if i % 2 == 0 { 10e-6 } else { -10e-6 }).collect();
    let points = wheel_rail_contact::geometry::ProfilePoints { lateral, vertical };
    // The curvature is what the noise spoils first (the choice of MEASURED_FILTER_WAVELENGTH):
    // its worst relative error over ±30 mm by filter wavelength.
    let worst_curvature = |wavelength: f64| {
        let smooth = SmoothProfile::smoothed(&points, wavelength).unwrap();
        (-100..=100)
            .map(|k| (smooth.at_lateral(f64::from(k) * 0.3e-3).unwrap().curvature * radius - 1.0).abs())
            .fold(0.0f64, f64::max)
    };
    for (wavelength, low, high) in [(2e-3, 4.0, 5.0), (3e-3, 0.8, 1.0), (8e-3, 0.01, 0.03)] {
        let worst = worst_curvature(wavelength);
        assert!((low..high).contains(&worst), "L = {wavelength}: {worst}");
    }
    let smooth = SmoothProfile::smoothed(&points, MEASURED_FILTER_WAVELENGTH).unwrap();
    for k in -100..=100 {
        let y = f64::from(k) * 0.3e-3;
        let point = smooth.at_lateral(y).unwrap();
        assert!((point.vertical - exact(y)).abs() < 0.1e-6, "z({y}) off by {}", point.vertical - exact(y));
        assert!((point.curvature * radius - 1.0).abs() < 0.13, "κ({y}) = {}", point.curvature);
        // Slope continuous across the knots (C¹: the smoothing's γ consistent with its values).
        let (left, right) = (smooth.at_lateral(y - 1e-9).unwrap(), smooth.at_lateral(y + 1e-9).unwrap());
        assert!((left.slope_angle - right.slope_angle).abs() < 1e-6, "slope jumps at {y}");
    }
    // A very short wavelength is (nearly) interpolation: the zig-zag stays.
    let sharp = SmoothProfile::smoothed(&points, 0.05e-3).unwrap();
    let y = points.lateral[160];
    assert!((sharp.at_lateral(y).unwrap().vertical - points.vertical[160]).abs() < 0.1e-6);
}
