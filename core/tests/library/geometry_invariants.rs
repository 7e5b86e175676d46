//! What the profile contact (`wheel_rail_contact::geometry`) must satisfy whatever the pose, both
//! wheels: Hertz's relations between a patch's load and its ellipse, on the tread and on the
//! flange; the smooth profile's point at a lateral position lying there; what the documented
//! interfaces do not read (the vertical position for the candidates, and under a prescribed
//! force). The expected values are closed-form relations and documented contracts, never the
//! code's own output.

use wheel_rail_contact::geometry::{
    builtin_profile, ContactPoint, ProfilePoints, SmoothProfile, WheelOnRail, WheelSide, WheelsetPosition,
};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ModelChoice, Polach};

fn pair(side: WheelSide) -> WheelOnRail {
    WheelOnRail::manchester_benchmark(side)
}

fn cosine(point: &ContactPoint) -> f64 {
    point.contact_angle.cos()
}

#[test]
fn each_patch_is_a_hertz_ellipse_under_its_own_load() {
    // Hertz (Johnson, "Contact Mechanics", § 4.2): the pressure is p₀ √(1 − x²/a² − y²/b²), so
    // the load is Q = (2/3) π a b p₀; the approach of distant points is the normal penetration.
    // On the tread (y_ws = 0, 2 mm), at the tread-to-flange-root pair of patches (5 mm) and on the
    // flange (8 mm), under 1, 10 and 100 kN, both wheels.
    for side in [WheelSide::Right, WheelSide::Left] {
        let pair = pair(side);
        let sign = if side == WheelSide::Right { 1.0 } else { -1.0 };
        let mut patches_seen = 0;
        for lateral in [0.0, 0.002, 0.005, 0.008] {
            for force in [1e3, 10e3, 100e3] {
                let position = WheelsetPosition { lateral: sign * lateral, ..WheelsetPosition::default() };
                let (_, patches) = pair.patches_for_force(force, &position, cosine).unwrap();
                assert!(!patches.is_empty());
                for patch in &patches {
                    let ellipse = &patch.ellipse;
                    let load = 2.0 / 3.0
                        * std::f64::consts::PI
                        * ellipse.semi_axis_a
                        * ellipse.semi_axis_b
                        * ellipse.max_pressure;
                    assert!(
                        (load / patch.normal_force - 1.0).abs() < 1e-9,
                        "{side:?} y_ws {lateral}, {force} N: (2/3)π a b p₀ = {load} N, Q = {} N",
                        patch.normal_force
                    );
                    assert_eq!(ellipse.approach, patch.penetration);
                    patches_seen += 1;
                }
            }
        }
        assert!(patches_seen >= 12, "{side:?}: {patches_seen} patches");
    }
}

#[test]
fn the_ellipse_grows_as_hertz_says_with_the_penetration() {
    // Hertz at fixed curvatures: Q ∝ δ^{3/2}, a, b, p₀ ∝ Q^{1/3} ∝ δ^{1/2}. Four times the
    // penetration: eight times the load, twice the semi-axes and the peak pressure.
    for side in [WheelSide::Right, WheelSide::Left] {
        let pair = pair(side);
        let sign = if side == WheelSide::Right { 1.0 } else { -1.0 };
        for lateral in [0.002, 0.003, 0.008] {
            let position = WheelsetPosition { lateral: sign * lateral, ..WheelsetPosition::default() };
            let touch = pair.candidates(&position).unwrap().touch();
            let at = |depth: f64| pair.patches_at(&WheelsetPosition { vertical: touch + depth, ..position }).unwrap();
            let (shallow, deep) = (at(10e-6), at(40e-6));
            assert_eq!(shallow.len(), 1, "{side:?} y_ws {lateral}");
            assert_eq!(deep.len(), 1, "{side:?} y_ws {lateral}");
            let (s, d) = (&shallow[0], &deep[0]);
            for (what, ratio, expected) in [
                ("Q", d.normal_force / s.normal_force, 8.0),
                ("a", d.ellipse.semi_axis_a / s.ellipse.semi_axis_a, 2.0),
                ("b", d.ellipse.semi_axis_b / s.ellipse.semi_axis_b, 2.0),
                ("p0", d.ellipse.max_pressure / s.ellipse.max_pressure, 2.0),
                ("δ", d.penetration / s.penetration, 4.0),
            ] {
                assert!((ratio / expected - 1.0).abs() < 1e-9, "{side:?} y_ws {lateral}: {what} ratio {ratio}");
            }
        }
    }
}

#[test]
fn the_point_at_a_lateral_position_lies_there() {
    // `SmoothProfile::at_lateral` inverts y(s): the point it returns has the asked y, to the
    // 1e-13 m its iteration stops at (plus the rounding of s), everywhere on both built-in
    // profiles, flanks included.
    for name in ["MBench_S1002", "MBench_UIC60"] {
        let points = builtin_profile(name).unwrap();
        let profile = SmoothProfile::new(&points).unwrap();
        let (first, last) = profile.lateral_range();
        let mut worst = 0.0f64;
        for i in 0..=20_000 {
            let y = first + (last - first) * (f64::from(i) + 0.5) / 20_001.0;
            let point = profile.at_lateral(y).unwrap();
            worst = worst.max((point.lateral - y).abs());
        }
        // Inside every interval between the file's points, the near-vertical ones included
        // (UIC60 steps 1e-9 m in y there): a quarter, half and three quarters of the way.
        for pair in points.lateral.windows(2) {
            for fraction in [0.25, 0.5, 0.75] {
                let y = pair[0] + fraction * (pair[1] - pair[0]);
                let point = profile.at_lateral(y).unwrap();
                worst = worst.max((point.lateral - y).abs());
            }
        }
        assert!(worst <= 2e-13, "{name}: y off by {worst:e} m");
    }
    // A profile whose spline y(s) is not monotone inside its intervals: a near-vertical step of
    // 2 mm over 10 nm of y at its start (a measured profile's glitch), then a rough edge. There
    // Newton's step leaves its bracket (at 67 of these 1000 positions, counted once with a
    // scratch counter) and the bisection takes over; the point is still the asked y.
    let glitch = ProfilePoints {
        lateral: vec![0.0, 1e-8, 0.5e-3, 0.6e-3, 1.2e-3],
        vertical: vec![0.0, 2e-3, 2.5e-3, 3.5e-3, 2e-3],
    };
    let profile = SmoothProfile::new(&glitch).unwrap();
    for i in 0..1000 {
        let y = 1.2e-3 * (f64::from(i) + 0.5) / 1000.0;
        let point = profile.at_lateral(y).unwrap();
        assert!((point.lateral - y).abs() <= 2e-13, "y {y:e}: off by {:e} m", point.lateral - y);
    }
}

#[test]
fn the_candidates_do_not_depend_on_the_vertical_position() {
    // The wheelset's height shifts the gap uniformly (module doc of `contact`): the candidates,
    // their gaps at z_ws = 0 included, are the same whatever `vertical` the position carries, by
    // the table's search and by the full scan.
    for side in [WheelSide::Right, WheelSide::Left] {
        let pair = pair(side);
        for lateral in [-0.004, 0.0, 0.003, 0.0065] {
            let level = WheelsetPosition { lateral, roll: 0.002, yaw: 0.004, ..WheelsetPosition::default() };
            let raised = WheelsetPosition { vertical: 0.005, ..level };
            assert_eq!(pair.contact_points(&raised).unwrap(), pair.contact_points(&level).unwrap());
            assert_eq!(
                pair.candidates_by_full_scan(&raised).unwrap().points(),
                pair.candidates_by_full_scan(&level).unwrap().points(),
                "{side:?} y_ws {lateral}"
            );
        }
    }
}

#[test]
fn a_prescribed_force_does_not_read_the_vertical_position() {
    // `VerticalContact::PrescribedForce`: "the wheelset's vertical position is solved for (the
    // position's `vertical` is not read)": the forces, the solved height and the moments about
    // the wheelset's centre at that height are the same whatever `vertical` holds.
    for side in [WheelSide::Right, WheelSide::Left] {
        let sign = if side == WheelSide::Right { 1.0 } else { -1.0 };
        let contact =
            WheelRailContact::new(pair(side), Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28));
        for lateral in [0.003, 0.0065] {
            let input = |vertical| WheelInput {
                position: WheelsetPosition { lateral: sign * lateral, vertical, roll: 0.001, yaw: 0.003 },
                velocity: WheelsetVelocity {
                    rolling_speed: 20.0,
                    wheel_angular_speed: 20.0 / 0.46,
                    ..WheelsetVelocity::default()
                },
                vertical: VerticalContact::PrescribedForce(50e3),
                friction_coefficient: 0.3,
            };
            let evaluate = |vertical| {
                contact
                    .evaluate(
                        &input(vertical),
                        &WheelState::default(),
                        &mut WheelCache::default(),
                        Evaluation::Initialise,
                    )
                    .unwrap()
            };
            assert_eq!(evaluate(0.01), evaluate(0.0), "{side:?} y_ws {lateral}");
        }
    }
}
