//! The profile readers, the built-in profiles and their smooth representation
//! (`wheel_rail_contact::geometry`), against the profiles' published dimensions and exact curves.

use wheel_rail_contact::geometry::{
    builtin_profile, parse_profile, ProfileError, ProfileFormat, ProfilePoints, SmoothProfile, BUILTIN_PROFILE_NAMES,
};

fn smooth(name: &str) -> SmoothProfile {
    SmoothProfile::new(&builtin_profile(name).unwrap()).unwrap()
}

/// y [m] where the smooth profile's z crosses `z` between `from` and `to` (z monotonic there).
fn lateral_at_height(profile: &SmoothProfile, z: f64, mut from: f64, mut to: f64) -> f64 {
    let above = |y: f64| profile.at_lateral(y).unwrap().vertical > z;
    let from_above = above(from);
    assert_ne!(from_above, above(to), "z = {z} is not crossed in [{from}, {to}]");
    for _ in 0..80 {
        let middle = 0.5 * (from + to);
        if above(middle) == from_above {
            from = middle;
        } else {
            to = middle;
        }
    }
    0.5 * (from + to)
}

/// The smooth profile's extreme z over [from, to] by sampling every 0.01 mm: (y, z, point).
fn extreme(profile: &SmoothProfile, from: f64, to: f64, highest: bool) -> wheel_rail_contact::geometry::ProfilePoint {
    let samples = ((to - from) / 1e-5) as usize;
    (0..=samples)
        .map(|i| profile.at_lateral(from + (to - from) * i as f64 / samples as f64).unwrap())
        .min_by(|a, b| {
            let (a, b) = if highest { (a.vertical, b.vertical) } else { (b.vertical, a.vertical) };
            a.total_cmp(&b)
        })
        .unwrap()
}

#[test]
fn s1002_has_its_standard_dimensions() {
    // EN 13715 (S1002, new): the profile's datum is the running circle, 70 mm from the flange
    // back (z = 0 at y = 0); flange height 28 mm; flange thickness 32.5 mm, measured 10 mm
    // below the running circle from the flange back (y = −70 mm: CONTACT's flange-back position).
    let wheel = smooth("MBench_S1002");
    let (first, last) = wheel.lateral_range();
    assert!(first < -0.069 && last >= 0.060, "the flange (y < 0) to the field side: {first} … {last}");
    assert!(wheel.at_lateral(0.0).unwrap().vertical.abs() < 1e-6);
    let tip = extreme(&wheel, -0.060, -0.050, false);
    println!("flange tip at y = {} mm, z = {} mm", tip.lateral * 1e3, tip.vertical * 1e3);
    assert!((tip.vertical - 0.028).abs() < 0.05e-3, "flange height {} mm", tip.vertical * 1e3);
    let flange_face = lateral_at_height(&wheel, 0.010, tip.lateral, -0.020);
    let thickness = flange_face - (-0.070);
    println!("flange thickness {} mm", thickness * 1e3);
    assert!((thickness - 0.0325).abs() < 0.1e-3, "flange thickness {} mm", thickness * 1e3);
}

#[test]
fn uic60_has_its_standard_crown() {
    // EN 13674-1 (60E1/UIC60): the head's crown is a 300 mm radius, flanked by 80 mm radii and
    // the 13 mm gauge corners. On the highest point (canted 1:40, at its side of the crown) the
    // curvature is the crown's.
    let rail = smooth("MBench_UIC60");
    let top = extreme(&rail, -0.020, 0.020, true);
    println!("rail top at y = {} mm, z = {} mm, κ = {} 1/m", top.lateral * 1e3, top.vertical * 1e3, top.curvature);
    assert!((top.curvature - 1.0 / 0.300).abs() < 0.05 / 0.300, "crown curvature {} 1/m", top.curvature);
    // The gauge side (y < 0, the track's inside for the right rail): the 13 mm gauge corner,
    // then the 80 mm radius. Inside each arc, away from the joints (where the curvature jumps and
    // the interpolating spline overshoots over about one point spacing), every sampled curvature
    // is the arc's within 1 %.
    for (from, to, radius) in [(-0.0428, -0.0347, 0.013), (-0.0323, -0.0260, 0.080)] {
        for i in 0..=200 {
            let y = from + (to - from) * f64::from(i) / 200.0;
            let curvature = rail.at_lateral(y).unwrap().curvature;
            assert!((curvature * radius - 1.0).abs() < 0.01, "κ({} mm) = {curvature} 1/m, radius {radius} m", y * 1e3);
        }
    }
}

#[test]
fn a_circles_spline_has_the_circles_slope_and_curvature() {
    // A rail crown of radius R (z downward, centre below): z = R − √(R² − y²), κ = 1/R,
    // slope angle atan(y/√(R² − y²)); points every 0.5 mm over ±30 mm as in a profile file,
    // checked more than 20 points inside the ends (the natural ends' zero curvature fades over
    // about five points: 7e-7 rad in slope 5 points inside).
    let radius = 0.3;
    let lateral: Vec<f64> = (-60..=60).map(|i| f64::from(i) * 0.5e-3).collect();
    let vertical = lateral.iter().map(|y| radius - (radius * radius - y * y).sqrt()).collect();
    let profile = SmoothProfile::new(&ProfilePoints { lateral, vertical }).unwrap();
    for i in -36..=36 {
        let y = f64::from(i) * 0.55e-3;
        let point = profile.at_lateral(y).unwrap();
        let root = (radius * radius - y * y).sqrt();
        assert!((point.lateral - y).abs() < 1e-12);
        assert!((point.vertical - (radius - root)).abs() < 1e-10, "z({y})");
        assert!(
            (point.slope_angle - (y / root).atan()).abs() < 1e-7,
            "slope({y}): {}",
            point.slope_angle - (y / root).atan()
        );
        assert!((point.curvature * radius - 1.0).abs() < 1e-4, "κ({y}) = {}", point.curvature);
    }
    assert!(profile.at_lateral(0.031).is_none() && profile.at_lateral(-0.031).is_none());
}

#[test]
fn the_miniprof_rail_is_the_simpack_rail_mirrored() {
    // CONTACT ships UIC60 in both formats; the MiniProf file is written with y mirrored.
    let simpack = smooth("MBench_UIC60");
    let miniprof_text = include_str!("../../../data/profiles/MBench_UIC60_v3.ban");
    let miniprof = parse_profile(miniprof_text, ProfileFormat::MiniProf).unwrap();
    // 495 points declared (`XYPoints`), 19 of them commented out with `"`.
    assert_eq!(miniprof.lateral.len(), 476);
    let miniprof = SmoothProfile::new(&miniprof).unwrap();
    for i in 0..=100 {
        let y = -0.030 + 0.060 * f64::from(i) / 100.0;
        let (a, b) = (simpack.at_lateral(y).unwrap(), miniprof.at_lateral(-y).unwrap());
        assert!((a.vertical - b.vertical).abs() < 1e-7, "z({y}): {} vs {}", a.vertical, b.vertical);
    }
}

#[test]
fn formats_follow_the_extension() {
    assert_eq!(ProfileFormat::from_file_name("a/b/S1002.PRW"), Some(ProfileFormat::Simpack));
    assert_eq!(ProfileFormat::from_file_name("uic60.prr"), Some(ProfileFormat::Simpack));
    assert_eq!(ProfileFormat::from_file_name("worn.whl"), Some(ProfileFormat::MiniProf));
    assert_eq!(ProfileFormat::from_file_name("rail.ban"), Some(ProfileFormat::MiniProf));
    assert_eq!(ProfileFormat::from_file_name("rail.txt"), None);
    assert_eq!(ProfileFormat::from_file_name("rail"), None);
}

#[test]
fn builtins_are_known_by_name() {
    assert_eq!(BUILTIN_PROFILE_NAMES, ["MBench_S1002", "MBench_UIC60"]);
    let wheel = builtin_profile("MBench_S1002").unwrap();
    assert_eq!(wheel.lateral.len(), 399); // 400 points in the file, the first commented out
    let error = builtin_profile("S1002").unwrap_err();
    assert_eq!(error.to_string(), "no built-in profile `S1002` (known: MBench_S1002, MBench_UIC60)");
}

/// A SIMPACK file with the given options and points (mm).
fn simpack(options: &str, points: &str) -> String {
    format!("  header.begin\n    type = 0 ! rail\n  header.end\n  spline.begin\n{options}\n    point.begin\n{points}\n    point.end\n  spline.end\n")
}

const POINTS: &str = "-2.0 1.0\n-1.0 0.25\n0.0 0.0 1.0\n1.0 0.25\n2.0 1.0";

#[test]
fn simpack_options_are_applied_in_simpacks_order() {
    let units = "    units.len.f = 1000.0";
    let plain = parse_profile(&simpack(units, POINTS), ProfileFormat::Simpack).unwrap();
    assert_eq!(plain.lateral, [-2e-3, -1e-3, 0.0, 1e-3, 2e-3]);
    assert_eq!(plain.vertical, [1e-3, 0.25e-3, 0.0, 0.25e-3, 1e-3]);
    // Shift, then mirror y (shifted points mirrored), inversion (order only: the reader sorts
    // by y again), z mirrored; shifts in the file's units, applied before the unit.
    let options =
        "shift.y = 1.0\nshift.z = 0.5 ! comment\nmirror.y = 1\nmirror.z = 1\ninversion = 1\nunits.len.f = 1000";
    let moved = parse_profile(&simpack(options, POINTS), ProfileFormat::Simpack).unwrap();
    assert_eq!(moved.lateral, [-3e-3, -2e-3, -1e-3, 0.0, 1e-3]);
    assert_eq!(moved.vertical, [-1.5e-3, -0.75e-3, -0.5e-3, -0.75e-3, -1.5e-3]);
    // Metres when no unit is given.
    let metres = parse_profile(&simpack("", "-0.02 0.01\n-0.01 0\n0 0\n0.01 0.001"), ProfileFormat::Simpack);
    assert_eq!(metres.unwrap().lateral, [-0.02, -0.01, 0.0, 0.01]);
    // A quarter turn about x: (y, z) → (−z, y); then the bounds drop the points with y outside
    // [−1.6, 0] (in the file's units, before the unit).
    let turned =
        "rotate = 90.0\nunits.ang.f = 57.29577951308232\nbound.y.min = -1.6\nbound.y.max = 0.0\nunits.len.f = 1000";
    let turned = parse_profile(&simpack(turned, "-2 0\n-1 0.5\n0 1\n1 1.5\n2 1.75\n3 2"), ProfileFormat::Simpack);
    let turned = turned.unwrap();
    assert_eq!(turned.lateral.len(), 4);
    let expected = [(-1.5e-3, 1e-3), (-1e-3, 0.0), (-0.5e-3, -1e-3), (0.0, -2e-3)];
    for ((y, z), (expected_y, expected_z)) in turned.lateral.iter().zip(&turned.vertical).zip(expected) {
        assert!((y - expected_y).abs() < 1e-15 && (z - expected_z).abs() < 1e-15, "({y}, {z})");
    }
}

fn simpack_error(options: &str, points: &str) -> ProfileError {
    parse_profile(&simpack(options, points), ProfileFormat::Simpack).unwrap_err()
}

#[test]
fn malformed_simpack_files_name_the_line_and_reason() {
    let e = simpack_error("", "-2.0 1.0\n-1.0 x\n0 0\n1 1");
    assert_eq!(e.to_string(), "line 8: expected a number, found `x` in `-1.0 x`");
    let e = simpack_error("", "-2.0 1.0\n-1.0\n0 0\n1 1");
    assert_eq!(e.line, Some(8));
    assert!(e.reason.contains("too few columns"), "{e}");
    let e = simpack_error("", "-2.0 1.0\n-1.0 NaN\n0 0\n1 1");
    assert_eq!(e.to_string(), "line 8: the value `NaN` is not finite");
    // y turns back: the line of the point that breaks the order is named.
    let e = simpack_error("units.len.f = 1000", "-2.0 1.0\n-1.0 0.5\n-1.5 0.4\n1 1\n2 2");
    assert_eq!(e.to_string(), "line 9: the profile is not monotonic in y: y = -1.5 mm follows y = -1 mm (line 8)");
    let e = simpack_error("units.len.f = 1000", "-2.0 1.0\n-1.0 0.5\n-1.0 0.4\n1 1");
    assert_eq!(e.line, Some(9));
    let e = simpack_error("units.len.f = 1000", "-2.0 1.0\n-1.0 0.5\n1 1");
    assert_eq!(e.to_string(), "3 profile points; a profile needs at least 4");
    let e = simpack_error("mirror.y = 2", POINTS);
    assert_eq!(e.to_string(), "line 5: `mirror.y` must be 0 or 1, found `2`");
    let e = simpack_error("units.len.f = 0", POINTS);
    assert_eq!(e.to_string(), "line 5: `units.len.f` must be > 0, found `0`");
    let e = simpack_error("shift.y = abc", POINTS);
    assert_eq!(e.to_string(), "line 5: `shift.y` must be a finite number, found `abc`");
    let e = parse_profile("header.begin\nheader.end\n", ProfileFormat::Simpack).unwrap_err();
    assert_eq!(e.to_string(), "no `point.begin` block: not a SIMPACK profile");
    let e = parse_profile("point.begin\n0 0\n1 1\n2 2\n3 3\n", ProfileFormat::Simpack).unwrap_err();
    assert_eq!(e.to_string(), "line 5: `point.begin` without `point.end`");
}

#[test]
fn malformed_miniprof_files_name_the_line_and_reason() {
    let header = "Filename=x.whl\nColumnDef=Y,X\n";
    // Columns as ColumnDef names them: Y (vertical) first here.
    let ok = parse_profile(
        &format!("{header}1.0, -2.0\n\"9 9\n0.0 -1.0 ! note\n0.0 1.0\n1.0 2.0\n"),
        ProfileFormat::MiniProf,
    );
    let ok = ok.unwrap();
    assert_eq!(ok.lateral, [-2e-3, -1e-3, 1e-3, 2e-3]);
    assert_eq!(ok.vertical, [1e-3, 0.0, 0.0, 1e-3]);
    let e = parse_profile("ColumnDef=A,B\n0 0\n", ProfileFormat::MiniProf).unwrap_err();
    assert_eq!(e.to_string(), "line 1: `ColumnDef=A,B` names no X and Y columns");
    let e = parse_profile(&format!("{header}1 -2\n0 -1\n0.5 -1.5\n1 2\n"), ProfileFormat::MiniProf).unwrap_err();
    assert_eq!(e.line, Some(5));
    assert!(e.reason.starts_with("the profile is not monotonic in y"), "{e}");
    let e = parse_profile(&format!("{header}1 -2\n0 inf\n"), ProfileFormat::MiniProf).unwrap_err();
    assert_eq!(e.to_string(), "line 4: the value `inf` is not finite");
}

#[test]
fn the_smooth_profile_refuses_bad_points() {
    let bad = ProfilePoints { lateral: vec![0.0, 1.0, 1.0, 2.0], vertical: vec![0.0; 4] };
    assert!(SmoothProfile::new(&bad).is_err());
    let bad = ProfilePoints { lateral: vec![0.0, 1.0, f64::NAN, 2.0], vertical: vec![0.0; 4] };
    assert!(SmoothProfile::new(&bad).is_err());
    let bad = ProfilePoints { lateral: vec![0.0, 1.0, 2.0], vertical: vec![0.0; 3] };
    assert!(SmoothProfile::new(&bad).is_err());
}

#[test]
fn a_point_on_a_near_vertical_flank_is_found_at_its_lateral_position() {
    // A flange-like step: flat, a flank rising 1 mm over 2 µm of y, flat again (mm). Along the
    // flank y(s) is nearly flat in s, so Newton's step on y(s) from the linear guess leaves its
    // bracket and the bracket's bisection takes over: every y on the flank is found to 1e-13 m,
    // at a height between the flank's ends.
    let lateral = [-3.0, -2.0, -1.0, 0.0, 0.001, 0.002, 1.0, 2.0, 3.0].map(|y: f64| y * 1e-3).to_vec();
    let vertical = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0].map(|z: f64| z * 1e-3).to_vec();
    let step = SmoothProfile::new(&ProfilePoints { lateral, vertical }).unwrap();
    for i in 0..=100 {
        let y = 2e-6 * f64::from(i) / 100.0;
        let point = step.at_lateral(y).unwrap();
        assert!((point.lateral - y).abs() <= 1e-13, "y {y}: found {}", point.lateral);
        assert!(point.vertical > -0.2e-3 && point.vertical < 1.2e-3, "z({y}) = {}", point.vertical);
    }
}

#[test]
fn a_turned_profile_keeps_its_running_surface_and_drops_flanks_turned_past_the_vertical() {
    // A rail-head-like profile (mm): steep flanks (1 mm across for 18 mm down) beside a crown.
    let lateral = [-31.0, -30.5, -30.0, -20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 30.5, 31.0].map(|y: f64| y * 1e-3);
    let vertical = [20.0, 10.0, 2.0, 0.8, 0.2, 0.0, 0.2, 0.8, 2.0, 10.0, 20.0].map(|z: f64| z * 1e-3);
    let head = SmoothProfile::new(&ProfilePoints { lateral: lateral.to_vec(), vertical: vertical.to_vec() }).unwrap();
    let turn = |angle: f64, i: usize| {
        let (sin, cos) = angle.sin_cos();
        (lateral[i] * cos - vertical[i] * sin, lateral[i] * sin + vertical[i] * cos)
    };
    // Turned by 0.1 rad, (y, z) → (y cos α − z sin α, y sin α + z cos α), the right flank's y
    // runs 29.65, 29.35, 28.85 mm: it turns back after point 8, so points 9 and 10 are dropped;
    // the left flank's y still increases (−32.84, −31.35, −30.05 mm) and is kept whole.
    let turned = head.rotated(0.1).unwrap();
    let (first, last) = turned.lateral_range();
    assert!((first - turn(0.1, 0).0).abs() < 1e-15, "first y {first}");
    assert!((last - turn(0.1, 8).0).abs() < 1e-15, "last y {last}");
    // Its highest point (least z) is point 3, its lowest point 0: the kept knots' own values.
    let (top, bottom) = turned.vertical_range();
    assert!((top - turn(0.1, 3).1).abs() < 1e-15 && (bottom - turn(0.1, 0).1).abs() < 1e-15, "{top} {bottom}");
    // Turned by −0.1 rad, the mirror image: points 0 and 1 dropped.
    let (first, last) = head.rotated(-0.1).unwrap().lateral_range();
    assert!((first - turn(-0.1, 2).0).abs() < 1e-15 && (last - turn(-0.1, 10).0).abs() < 1e-15, "{first} {last}");
    // Nearly upside down (3 rad), three points remain before y turns back: an error saying so.
    let error = head.rotated(3.0).unwrap_err();
    assert!(error.reason.contains("keeps 3 points around its top"), "{error}");
}
