//! The rolling-radius difference Δr(y) and the equivalent conicity tan γ_e(A) of S1002 on UIC60
//! 1:40 (the Manchester benchmark's wheelset and track: gauge 1435 mm at 14 mm below the rail
//! top, flange backs 1360 mm apart at −70 mm, r0 = 460 mm), zero roll and yaw, against CONTACT
//! rev. 2707 module 1 on the same profiles (`core/tests/data/conicity_contact.csv`, made by
//! `core/tests/data/conicity_contact.py`; its docstring gives the decks and commands) and against the
//! equivalent conicity of CONTACT's Δr by an independent method (Runge–Kutta integration of
//! Klingel's kinematic motion, `core/tests/data/conicity_contact_tan_gamma.csv`, same script).

use wheel_rail_contact::geometry::{first_touch, ConicityError, RollingRadiusDifference, WheelOnRail, WheelSide};

fn wheel(side: WheelSide) -> WheelOnRail {
    WheelOnRail::manchester_benchmark(side)
}

/// One wheel's contact in CONTACT's output: y on the wheel and rolling radius [m].
type WheelContact = (f64, f64);

/// CONTACT's samples: (y_ws, right wheel, left wheel) [m], every 0.1 mm from −10 to 10 mm; one
/// patch per wheel and case in this file.
fn contact_samples() -> Vec<(f64, WheelContact, WheelContact)> {
    let rows: Vec<(String, f64, f64, f64)> = include_str!("../data/conicity_contact.csv")
        .lines()
        .filter(|l| l.starts_with("right,") || l.starts_with("left,"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f[3], "1", "one patch per case: {l}");
            let v = |i: usize| f[i].parse::<f64>().unwrap() * 1e-3;
            (f[0].to_string(), v(2), v(7), 0.46 + v(8))
        })
        .collect();
    let right: Vec<_> = rows.iter().filter(|r| r.0 == "right").collect();
    let left: Vec<_> = rows.iter().filter(|r| r.0 == "left").collect();
    assert_eq!((right.len(), left.len()), (201, 201));
    right.iter().zip(&left).map(|(r, l)| (assert_eq!(r.1, l.1), (r.1, (r.2, r.3), (l.2, l.3))).1).collect()
}

/// CONTACT-derived (A, tan γ_e) [m, 1].
fn contact_conicity() -> Vec<(f64, f64)> {
    include_str!("../data/conicity_contact_tan_gamma.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("amplitude"))
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            (f[0] * 1e-3, f[1])
        })
        .collect()
}

fn ours() -> RollingRadiusDifference {
    RollingRadiusDifference::from_wheelset(&wheel(WheelSide::Right), &wheel(WheelSide::Left), 0.010, 1e-4).unwrap()
}

/// Δr against CONTACT's at all 201 displacements, −10 … 10 mm every 0.1 mm.
///
/// Tolerances. Ours is the rigid first-touch point (the lowest undeformed gap), CONTACT's the
/// contact reference of a 500 N patch (elastic approach 2 µm on the tread): the geometry tests
/// (`core/tests/library/geometry_benchmark.rs`) place contact points within 0.4 mm of CONTACT's on the tread
/// (slope ≤ 0.1 there: ≤ 0.04 mm of radius) and 0.004 mm on the flange. Measured here: ≤ 0.0061 mm
/// on the tread (|y| ≤ 5 mm), ≤ 0.035 mm in flange contact (5.1–10 mm, where both wheels' radii
/// differ by 0.01–0.03 mm: CONTACT's reference lies inside the 1.5 kN flange patch), and
/// 0.030 / 0.089 mm at the one sample next to the tread jump (|y| = 0.2 mm: the right wheel's
/// point 1.07 mm from CONTACT's, on the flat gap) and next to the flange jump (|y| = 6.6 mm, on the
/// steep flange root). Asserted: 0.01 mm on the tread, 0.04 mm in flange contact, 0.1 mm at those
/// four samples; and both codes' points on the same part of each wheel (within 2 mm) everywhere.
#[test]
fn delta_r_matches_contact_at_every_displacement() {
    let (right, left) = (wheel(WheelSide::Right), wheel(WheelSide::Left));
    let ours = ours();
    let (mut worst_tread, mut worst_flange, mut worst_jump): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (i, (y, (wr, rr), (wl, rl))) in contact_samples().into_iter().enumerate() {
        assert!((ours.lateral()[i] - y).abs() < 1e-12);
        let (pr, pl) = (first_touch(&right, y).unwrap(), first_touch(&left, y).unwrap());
        let (theirs, mine) = (rr - rl, ours.difference()[i]);
        // Our Δr is r_right − r_left of the same first-touch points.
        assert_eq!(mine, pr.rolling_radius - pl.rolling_radius);
        println!(
            "y {:6.1} mm: Δr ours {:8.4} CONTACT {:8.4} mm (diff {:7.4}); wheel y right {:7.2}/{:7.2}, left {:7.2}/{:7.2} mm",
            y * 1e3,
            mine * 1e3,
            theirs * 1e3,
            (mine - theirs) * 1e3,
            pr.wheel_lateral * 1e3,
            wr * 1e3,
            pl.wheel_lateral * 1e3,
            wl * 1e3
        );
        assert!((pr.wheel_lateral - wr).abs() < 2e-3 && (pl.wheel_lateral - wl).abs() < 2e-3, "y {y}: branches");
        let error = (mine - theirs).abs();
        let at_jump = [0.2e-3, 6.6e-3].iter().any(|j| (y.abs() - j).abs() < 1e-9);
        let (worst, tolerance) = if at_jump {
            (&mut worst_jump, 0.1e-3)
        } else if y.abs() <= 5.0e-3 + 1e-9 {
            (&mut worst_tread, 0.01e-3)
        } else {
            (&mut worst_flange, 0.04e-3)
        };
        *worst = worst.max(error);
        assert!(error < tolerance, "y {y}: Δr {mine} vs CONTACT {theirs}");
    }
    println!(
        "max |Δr ours − CONTACT|: tread {:.4} mm, flange contact {:.4} mm, next to the jumps {:.4} mm",
        worst_tread * 1e3,
        worst_flange * 1e3,
        worst_jump * 1e3
    );
}

/// tan γ_e(A), A = 0.5 … 9 mm, against the same method's independent implementation on
/// CONTACT's Δr (Runge–Kutta through the kinematic motion, `conicity_contact.py`).
/// Tolerance: the Δr functions differ by ≤ 0.006 mm on ≥ 0.5 mm of Δr on the tread (≤ 1.2 %,
/// 0.6 % at 1 mm and beyond) and ≤ 0.2 % in flange contact; asserted 1 % (measured ≤ 0.18 %;
/// 0.1804 against 0.1803 at A = 3 mm).
#[test]
fn equivalent_conicity_matches_contacts() {
    let ours = ours();
    let mut worst: f64 = 0.0;
    for (a, theirs) in contact_conicity() {
        let mine = ours.equivalent_conicity(a).unwrap();
        let harmonic = ours.harmonic_conicity(a).unwrap();
        println!("A {:4.1} mm: tan γ_e ours {mine:.4} CONTACT {theirs:.4} (harmonic {harmonic:.4})", a * 1e3);
        worst = worst.max((mine / theirs - 1.0).abs());
        assert!((mine / theirs - 1.0).abs() < 0.01, "A {a}: {mine} vs {theirs}");
    }
    println!("max relative difference {:.3} %", worst * 100.0);
    // The values the docs quote, at A = 3 mm.
    let at_3mm = contact_conicity().into_iter().find(|&(a, _)| (a - 3e-3).abs() < 1e-12).unwrap().1;
    assert!((at_3mm - 0.1803).abs() < 1e-4);
}

/// Invariants: Δr is odd (the left wheel is the right one mirrored) and never decreases with y
/// on S1002/UIC60 (true of CONTACT's too); the conicity of a cone is its cone's, and of a pure
/// step Δr = c sign(y) the closed forms π²c/(16A) (the kinematic motion at constant
/// acceleration) and 2c/(πA) (harmonic). Note: the small-amplitude limit is not the tread's
/// conicity here: Δr jumps by 0.47 mm at |y| = 0.2–0.3 mm, so tan γ_e grows as A → 0 (0.60 at
/// 0.5 mm), in CONTACT's Δr as in ours.
#[test]
fn invariants_hold() {
    let ours = ours();
    let (y, d) = (ours.lateral(), ours.difference());
    let n = y.len();
    for i in 0..n {
        assert!((y[i] + y[n - 1 - i]).abs() < 1e-15);
        assert!((d[i] + d[n - 1 - i]).abs() < 1e-12, "odd at {}", y[i]);
    }
    assert!(d.windows(2).all(|w| w[1] >= w[0]), "non-decreasing");
    let contact: Vec<f64> = contact_samples().iter().map(|s| s.1 .1 - s.2 .1).collect();
    assert!(contact.windows(2).all(|w| w[1] >= w[0]));
    // A cone: Δr = 2 tan γ y.
    let ys: Vec<f64> = (-100..=100).map(|k| k as f64 * 1e-4).collect();
    let cone = RollingRadiusDifference::from_samples(ys.clone(), ys.iter().map(|y| 2.0 * 0.04 * y).collect()).unwrap();
    for a in [1e-4, 3e-3, 1e-2] {
        assert!((cone.equivalent_conicity(a).unwrap() - 0.04).abs() < 1e-6);
        assert!((cone.harmonic_conicity(a).unwrap() - 0.04).abs() < 1e-6);
    }
    // The same cone on a wheelset whose wheels differ in radius by 0.2 mm (Δr offset): the
    // symmetrisation takes the offset out, the conicity is the cone's.
    let offset = ys.iter().map(|y| 2.0 * 0.04 * y + 2e-4).collect();
    let offset_cone = RollingRadiusDifference::from_samples(ys.clone(), offset).unwrap();
    for a in [1e-4, 3e-3, 1e-2] {
        assert!((offset_cone.equivalent_conicity(a).unwrap() - 0.04).abs() < 1e-6, "{a}");
        assert!((offset_cone.harmonic_conicity(a).unwrap() - 0.04).abs() < 1e-6, "{a}");
    }
    // A step of c = 1 mm, sampled [-h, h] around 0 (h = 1 µm).
    let (c, a, h) = (1e-3, 3e-3, 1e-6);
    let step = RollingRadiusDifference::from_samples(vec![-0.01, -h, h, 0.01], vec![-c, -c, c, c]).unwrap();
    let kinematic = std::f64::consts::PI.powi(2) * c / (16.0 * a);
    assert!((step.equivalent_conicity(a).unwrap() / kinematic - 1.0).abs() < 2e-3);
    assert!((step.harmonic_conicity(a).unwrap() / (2.0 * c / (std::f64::consts::PI * a)) - 1.0).abs() < 2e-3);
    assert_eq!(step.at(0.0).unwrap(), 0.0);
    assert_eq!(step.at(0.005).unwrap(), c);
}

#[test]
fn bad_input_is_an_error() {
    let ys = vec![-1e-3, 0.0, 1e-3];
    let good = RollingRadiusDifference::from_samples(ys.clone(), vec![-1e-4, 0.0, 1e-4]).unwrap();
    for a in [0.0, -1e-3, f64::NAN, f64::INFINITY, 2e-3] {
        assert!(matches!(good.equivalent_conicity(a), Err(ConicityError::InvalidArgument { name: "amplitude", .. })));
        assert!(good.harmonic_conicity(a).is_err());
    }
    assert!(good.at(2e-3).is_err() && good.at(f64::NAN).is_err());
    // Δr negative for y > 0: no oscillation.
    let negative = RollingRadiusDifference::from_samples(ys.clone(), vec![1e-4, 0.0, -1e-4]).unwrap();
    assert_eq!(negative.equivalent_conicity(1e-3), Err(ConicityError::NoOscillation { amplitude: 1e-3 }));
    assert!(RollingRadiusDifference::from_samples(vec![0.0, 0.0], vec![0.0, 0.0]).is_err());
    assert!(RollingRadiusDifference::from_samples(vec![0.0, 1.0], vec![0.0]).is_err());
    assert!(RollingRadiusDifference::from_samples(vec![0.0, 1.0], vec![0.0, f64::NAN]).is_err());
    assert!(RollingRadiusDifference::from_samples(vec![0.0], vec![0.0]).is_err());
    let (right, left) = (wheel(WheelSide::Right), wheel(WheelSide::Left));
    for (max, step, name) in [
        (0.01, 0.0, "step"),
        (0.01, -1e-4, "step"),
        (0.01, f64::INFINITY, "step"),
        (0.01, f64::NAN, "step"),
        (-0.01, 1e-4, "max_displacement"),
        (f64::INFINITY, 1e-4, "max_displacement"),
        (0.01, 1e-12, "step"),
    ] {
        let error = RollingRadiusDifference::from_wheelset(&right, &left, max, step).unwrap_err();
        assert!(matches!(error, ConicityError::InvalidArgument { name: n, .. } if n == name), "{max} {step}: {error}");
    }
    // Two samples are the fewest that make a Δr.
    assert!(RollingRadiusDifference::from_samples(vec![0.0, 1e-3], vec![0.0, 1e-4]).is_ok());
    assert!(first_touch(&right, f64::NAN).is_err());
    // So far off that the profiles do not overlap: the contact search's error, with y.
    let error = RollingRadiusDifference::from_wheelset(&right, &left, 0.5, 0.25).unwrap_err();
    assert!(matches!(error, ConicityError::Geometry { .. }), "{error}");
    assert!(error.to_string().contains("lateral displacement -0.5 m"), "{error}");
}
