//! The non-Hertzian strips from the strip table (`WheelOnRail::with_strip_table`) against the
//! exact path (an exact spline point per strip) over many poses: both wheels, y_ws −10…10 mm,
//! roll ±0.01 rad, yaw ±0.02 rad, 5–100 kN, frictionless. The table's only error is the rail's
//! Hermite interpolation (2 nm in height; `geometry/strip_table.rs`), and the stretch's ends (one
//! strip out of contact beyond each, where the exact path's scan step leaves one or two).
//!
//! Measured by `cargo test -p wheel-rail-contact --release --test library strip_table -- --nocapture`.

use wheel_rail_contact::geometry::{NonHertzianContact, WheelOnRail, WheelSide, WheelsetPosition};

/// A reproducible spread of numbers in [0, 1) (the golden ratio's multiples, fractional parts).
fn spread(i: u32, salt: f64) -> f64 {
    (f64::from(i) * 0.618_033_988_749_895 + salt).fract()
}

/// The worst differences between the table's patches and the exact ones: contact point's rail y
/// \[m\], contact angle \[rad\], normal force (relative), z_ws \[m\], equivalent ellipse's semi-axes
/// (relative).
#[derive(Debug, Default)]
struct Worst {
    point: f64,
    angle: f64,
    normal: f64,
    vertical: f64,
    axes: f64,
}

fn compare(exact: &NonHertzianContact, tabled: &NonHertzianContact, worst: &mut Worst, what: &str) {
    assert_eq!(exact.patches.len(), tabled.patches.len(), "{what}: {exact:?}\n{tabled:?}");
    worst.vertical = worst.vertical.max((exact.vertical - tabled.vertical).abs());
    for (a, b) in exact.patches.iter().zip(&tabled.patches) {
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
    // Measured (600 poses): 0.5 nm, 7e-8 rad, 1.2e-7, 0.35 nm, 1.7e-6; bounded with margin.
    assert!(worst.point < 1e-8 && worst.angle < 1e-6 && worst.normal < 1e-5, "{worst:?}");
    assert!(worst.vertical < 1e-8 && worst.axes < 1e-4, "{worst:?}");
}
