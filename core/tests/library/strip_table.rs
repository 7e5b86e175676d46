//! The non-Hertzian strips from the strip table (`WheelOnRail::with_strip_table`) against the
//! exact path (an exact spline point per strip) over many poses: both wheels, y_ws −10…10 mm,
//! roll ±0.01 rad, yaw ±0.02 rad, 5–100 kN, frictionless. The table's only error is the rail's
//! Hermite interpolation (2 nm in height; `geometry/strip_table.rs`), and the stretch's ends (one
//! strip out of contact beyond each, where the exact path's scan step leaves one or two).
//!
//! Measured by `cargo test -p wheel-rail-contact --release --test library strip_table -- --nocapture`.

use std::time::Instant;
use wheel_rail_contact::geometry::{
    builtin_profile, NonHertzianContact, SmoothProfile, WheelOnRail, WheelSide, WheelsetPosition,
};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ExactTable, ModelChoice, Polach};

/// A reproducible spread of numbers in [0, 1) (the golden ratio's multiples, fractional parts).
fn spread(i: u32, salt: f64) -> f64 {
    (f64::from(i) * 0.618_033_988_749_895 + salt).fract()
}

/// The worst differences between the table's patches and the exact ones: contact point's rail y
/// \[m\], contact angle \[rad\], the strips' contact angles (the rail's slope from its samples)
/// \[rad\], normal force (relative), z_ws \[m\], equivalent ellipse's semi-axes
/// (relative).
#[derive(Debug, Default)]
struct Worst {
    point: f64,
    angle: f64,
    strip_angle: f64,
    normal: f64,
    vertical: f64,
    axes: f64,
}

fn compare(exact: &NonHertzianContact, tabled: &NonHertzianContact, worst: &mut Worst, what: &str) {
    assert_eq!(exact.patches.len(), tabled.patches.len(), "{what}: {exact:?}\n{tabled:?}");
    worst.vertical = worst.vertical.max((exact.vertical - tabled.vertical).abs());
    for (a, b) in exact.patches.iter().zip(&tabled.patches) {
        // The strips in contact, each with its slope (the rail's, from its samples in the table).
        assert_eq!(a.strips.len(), b.strips.len(), "{what}: strips");
        for (s, t) in a.strips.iter().zip(&b.strips) {
            worst.strip_angle = worst.strip_angle.max((s.contact_angle - t.contact_angle).abs());
        }
        let (a, b) = (&a.patch, &b.patch);
        worst.point = worst.point.max((a.point.rail_lateral - b.point.rail_lateral).abs());
        worst.angle = worst.angle.max((a.point.contact_angle - b.point.contact_angle).abs());
        worst.normal = worst.normal.max((a.normal_force / b.normal_force - 1.0).abs());
        for (x, y) in [(a.ellipse.semi_axis_a, b.ellipse.semi_axis_a), (a.ellipse.semi_axis_b, b.ellipse.semi_axis_b)] {
            worst.axes = worst.axes.max((x / y - 1.0).abs());
        }
    }
}

#[test]
fn the_strip_table_gives_the_exact_patches() {
    let mut worst = Worst::default();
    let mut count = 0;
    for side in [WheelSide::Right, WheelSide::Left] {
        let exact = WheelOnRail::manchester_benchmark(side);
        let tabled = exact.clone().with_strip_table();
        let sign = if side == WheelSide::Right { 1.0 } else { -1.0 };
        for i in 0..300 {
            let position = WheelsetPosition {
                lateral: sign * (-10e-3 + 20e-3 * spread(i, 0.1)),
                vertical: 0.0,
                roll: 0.02 * (spread(i, 0.3) - 0.5),
                yaw: 0.04 * (spread(i, 0.7) - 0.5),
            };
            let load = 5e3 + 95e3 * spread(i, 0.9);
            let what = format!("{side:?} {position:?} {load} N");
            let (Ok(a), Ok(b)) = (
                exact.non_hertzian_patches_for_force(load, &position),
                tabled.non_hertzian_patches_for_force(load, &position),
            ) else {
                panic!("{what}: one of them failed")
            };
            compare(&a, &b, &mut worst, &what);
            count += 1;
        }
    }
    println!("{count} poses: {worst:?}");
    // Measured (600 poses): 0.5 nm, 7e-8 rad, 1.3e-6 rad for the strips, 1.2e-7, 0.35 nm, 1.7e-6;
    // bounded with margin.
    assert!(worst.point < 1e-8 && worst.angle < 1e-6 && worst.normal < 1e-5, "{worst:?}");
    assert!(worst.strip_angle < 1e-5, "{worst:?}");
    assert!(worst.vertical < 1e-8 && worst.axes < 1e-4, "{worst:?}");
}

/// The table is built at initialisation within the 1 s: one exact spline point per strip
/// of the wheel profile (S1002: 852 strips over its 129.6 mm, every 0.1 mm off the tread and 0.2 mm
/// on it), measured with the strip grid 0.43 ms in release (on a machine 1.8 × slower than the one
/// that measured 0.23 ms for 1 296 strips before).
#[test]
fn the_strip_table_is_built_within_a_second() {
    let (from, to) = SmoothProfile::new(&builtin_profile("MBench_S1002").unwrap()).unwrap().lateral_range();
    let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
    let start = Instant::now();
    let tabled = placed.with_strip_table();
    let elapsed = start.elapsed();
    println!("strips over {:.1} mm of profile in {elapsed:?}", (to - from) * 1e3);
    assert!(elapsed.as_secs_f64() < 1.0, "{elapsed:?}");
    assert!(tabled.non_hertzian_patches_for_force(10e3, &WheelsetPosition::default()).is_ok());
}

/// Whole wheel steps (`WheelRailContact::evaluate`, 10 kN prescribed and balanced with the creep
/// forces) with the strip table against the exact strips: both wheels, Polach and `exact_table`,
/// 100 poses each (y_ws −2…9 mm, roll ±0.002 rad, yaw ±0.015 rad, 5–100 kN, creepages from the
/// motion). Each path's answer is an answer of the other: the other's strips at its z_ws
/// (prescribed) give its patches and forces, and carry the load. Where the balance has one root
/// the two answers are the same (measured: z_ws within 0.64 nm, contact points 0.51 nm, N 1.7e-6,
/// each patch's creep forces 1.1e-6 μN; asserted at 10 nm, 10 nm, 1e-4 and 1e-4 μN); where a
/// region joins a patch within the balance's reach, G(z_ws) jumps and the balance has two roots
/// (1 of the 400: the right wheel at y_ws 6.42 mm, 58.7 kN, where a tread region 14 mm from the
/// flange root joins at 1.24 µm more approach, its patch b 2.1 → 7.4 mm), and the two paths,
/// whose searches start from touches a sampling apart, may settle on either.
#[test]
fn wheel_steps_with_the_strip_table_are_the_exact_ones() {
    let (mut vertical, mut point, mut normal, mut creep) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut two_roots = 0;
    for model in [ModelChoice::Polach(Polach::default()), ModelChoice::ExactTable(ExactTable::new().unwrap())] {
        for side in [WheelSide::Right, WheelSide::Left] {
            let sign = if side == WheelSide::Right { 1.0 } else { -1.0 };
            let exact =
                WheelRailContact::new(WheelOnRail::manchester_benchmark(side), Scene::of_model(model, 82e9, 0.28))
                    .with_method(ContactMethod::NonHertzian);
            let tabled = exact.clone().with_strip_table();
            for i in 0..100 {
                let speed = 2.0 + 20.0 * spread(i, 0.2);
                let load = 5e3 + 95e3 * spread(i, 0.9);
                let input = WheelInput {
                    position: WheelsetPosition {
                        lateral: sign * (-2e-3 + 11e-3 * spread(i, 0.1)),
                        vertical: 0.0,
                        roll: 0.004 * (spread(i, 0.3) - 0.5),
                        yaw: 0.03 * (spread(i, 0.7) - 0.5),
                    },
                    velocity: WheelsetVelocity {
                        rolling_speed: speed,
                        wheel_angular_speed: speed / 0.46 * (1.0 + 0.004 * (spread(i, 0.4) - 0.5)),
                        lateral_velocity: 0.01 * (spread(i, 0.6) - 0.5),
                        yaw_rate: 0.0,
                    },
                    vertical: VerticalContact::PrescribedForce(load),
                    friction_coefficient: 0.3,
                };
                let step = |contact: &WheelRailContact, input: &WheelInput| {
                    let mut cache = WheelCache::default();
                    contact.evaluate(input, &WheelState::default(), &mut cache, Evaluation::Initialise).unwrap().0
                };
                let (a, b) = (step(&exact, &input), step(&tabled, &input));
                let apart = (a.wheelset_vertical_position - b.wheelset_vertical_position).abs();
                if apart > 1e-8 {
                    two_roots += 1;
                } else {
                    vertical = vertical.max(apart);
                }
                for (answer, other) in [(&a, &tabled), (&b, &exact)] {
                    let placed = WheelInput {
                        position: WheelsetPosition { vertical: answer.wheelset_vertical_position, ..input.position },
                        vertical: VerticalContact::PrescribedPosition,
                        ..input
                    };
                    let there = step(other, &placed);
                    let what = format!("{side:?} {input:?}");
                    assert_eq!(there.patches.len(), answer.patches.len(), "{what}");
                    // It carries the load as the balance did (1e-10 of it), but for the strips' difference.
                    assert!((there.track_force[2] / -load - 1.0).abs() < 1e-5, "{what}: F_z {}", there.track_force[2]);
                    for (p, q) in there.patches.iter().zip(&answer.patches) {
                        let limit = 0.3 * p.patch.normal_force;
                        point = point.max((p.patch.point.rail_lateral - q.patch.point.rail_lateral).abs());
                        normal = normal.max((p.patch.normal_force / q.patch.normal_force - 1.0).abs());
                        creep = creep.max((p.output.force_longitudinal - q.output.force_longitudinal).abs() / limit);
                        creep = creep.max((p.output.force_lateral - q.output.force_lateral).abs() / limit);
                    }
                }
            }
        }
    }
    println!("z_ws {vertical:e} m, point {point:e} m, N {normal:e}, creep forces {creep:e} μN; {two_roots} poses with two roots");
    assert!(vertical < 1e-8 && point < 1e-8, "z_ws {vertical:e} m, point {point:e} m");
    assert!(normal < 1e-4 && creep < 1e-4, "N {normal:e}, creep forces {creep:e} μN");
    // Two roots only where a jump of G lies within a balance's rounds: rare. More would mean the
    // paths' searches start further apart than their touches' sampling.
    assert!(two_roots <= 4, "{two_roots} of 400 poses settled on different roots");
}
