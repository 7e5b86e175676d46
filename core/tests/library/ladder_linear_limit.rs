//! Every model's small-creepage limit is Kalker's linear theory; FASTSIM's discretisation error
//! shrinks at second order in the strip count; C33 follows Kalker's table and asymptote.

use crate::common;

use common::{fastsim, typical_contact};
use std::f64::consts::PI;
use wheel_rail_contact::{
    ContactInput, CreepForceModel, Fastsim, Flexibility, KalkerCoefficients, KalkerLinear, Polach, ShenHedrickElkins,
    TractionBound,
};

#[test]
fn kalker_linear_is_the_published_formula() {
    let input = typical_contact(1e-3, -2e-3, 0.5);
    let (a, b, g) = (input.semi_axis_a, input.semi_axis_b, input.shear_modulus);
    let c = KalkerCoefficients::new(a / b, 0.28);
    let c33 = KalkerCoefficients::spin_moment_c33(a / b, 0.28);
    let area = a * b;
    let forces = KalkerLinear.creep_forces(&input).unwrap();
    let expected_fx = -g * area * c.c11 * 1e-3;
    let expected_fy = -g * area * c.c22 * -2e-3 - g * area.powf(1.5) * c.c23 * 0.5;
    let expected_mz = g * area.powf(1.5) * c.c23 * -2e-3 - g * area * area * c33 * 0.5;
    assert!((forces.force_longitudinal / expected_fx - 1.0).abs() < 1e-14);
    assert!((forces.force_lateral / expected_fy - 1.0).abs() < 1e-14);
    assert!((forces.spin_moment.unwrap() / expected_mz - 1.0).abs() < 1e-14);
}

#[test]
fn c33_equals_kalkers_table_at_its_nodes() {
    // Table E.3 entries at ν = 0, 0.25, 0.5 (data/kalker_c33.csv).
    for (a_over_b, values) in [(0.1, [6.42, 8.28, 11.7]), (1.0, [1.21, 1.19, 1.16]), (2.0, [0.958, 0.819, 0.650])] {
        for (nu, expected) in [0.0, 0.25, 0.5].into_iter().zip(values) {
            let c33 = KalkerCoefficients::spin_moment_c33(a_over_b, nu);
            assert!((c33 / expected - 1.0).abs() < 1e-12, "a/b {a_over_b} nu {nu}: {c33} vs {expected}");
        }
    }
}

#[test]
fn c33_is_continuous_and_tends_to_the_thin_strip_asymptote() {
    for nu in [0.0, 0.28, 0.5] {
        for g in [0.1, 10.0] {
            let below = KalkerCoefficients::spin_moment_c33(g * (1.0 - 1e-9), nu);
            let above = KalkerCoefficients::spin_moment_c33(g * (1.0 + 1e-9), nu);
            assert!((below / above - 1.0).abs() < 1e-6, "jump at a/b = {g}, nu = {nu}");
        }
        let g = 1e-8;
        let asymptote = PI * PI / (16.0 * (1.0 - nu) * g);
        assert!((KalkerCoefficients::spin_moment_c33(g, nu) / asymptote - 1.0).abs() < 1e-6);
    }
}

/// |model / linear − 1| for F_x (pure ξ) and F_y (pure η, pure φ) at creepages far in adhesion.
fn linear_limit_errors(model: &dyn CreepForceModel) -> [f64; 3] {
    let cases = [
        (typical_contact(1e-9, 0.0, 0.0), 0),
        (typical_contact(0.0, 1e-9, 0.0), 1),
        (typical_contact(0.0, 0.0, 1e-7), 1),
    ];
    cases.map(|(input, component)| {
        let got = model.creep_forces(&input).unwrap();
        let linear = KalkerLinear.creep_forces(&input).unwrap();
        let pick = |f: &wheel_rail_contact::CreepForces| [f.force_longitudinal, f.force_lateral][component];
        (pick(&got) / pick(&linear) - 1.0).abs()
    })
}

#[test]
fn shen_hedrick_elkins_and_polach_meet_the_linear_theory() {
    for error in linear_limit_errors(&ShenHedrickElkins) {
        assert!(error < 1e-6, "{error}");
    }
    // Polach's spin force uses its own K_S-corrected stiffness but the same initial slope (E2).
    let polach = linear_limit_errors(&Polach::default());
    assert!(polach[0] < 1e-6 && polach[1] < 1e-6, "{polach:?}");
}

#[test]
fn fastsim_meets_the_linear_theory_with_second_order_convergence() {
    for bound in [TractionBound::Parabolic, TractionBound::Elliptic] {
        let errors: Vec<[f64; 3]> = [10, 20, 40, 80].iter().map(|&n| linear_limit_errors(&fastsim(n, bound))).collect();
        for component in 0..3 {
            for pair in errors.windows(2) {
                let ratio = pair[0][component] / pair[1][component];
                // Midpoint rule across the strips: error ∝ 1/n², so halving the strips' width
                // divides it by 4 (the spin force's (1 − y²)^{3/2} profile gives slightly less).
                assert!(ratio > 3.0, "{bound:?} component {component}: errors {errors:?}");
            }
            assert!(errors[3][component] < 2e-4, "{bound:?}: {errors:?}");
        }
    }
    // For ξ and η (tractions linear along the strip) the element count along the strips does not
    // matter in adhesion: the march and the midpoint sum are exact there.
    let coarse_along = Fastsim::new(40, 3, TractionBound::Parabolic, Flexibility::Three).unwrap();
    let fine_along = Fastsim::new(40, 300, TractionBound::Parabolic, Flexibility::Three).unwrap();
    let input = typical_contact(1e-9, 1e-9, 0.0);
    let (c, f) = (coarse_along.creep_forces(&input).unwrap(), fine_along.creep_forces(&input).unwrap());
    assert!((c.force_longitudinal / f.force_longitudinal - 1.0).abs() < 1e-12);
    assert!((c.force_lateral / f.force_lateral - 1.0).abs() < 1e-12);
}

#[test]
fn fastsim_single_flexibility_meets_the_linear_theory_for_each_pure_creepage() {
    // With one creepage the weighted L equals that creepage's own flexibility.
    let model = Fastsim::new(80, 80, TractionBound::Elliptic, Flexibility::SingleWeighted).unwrap();
    for error in linear_limit_errors(&model) {
        assert!(error < 2e-4, "{error}");
    }
}

/// Kalker's single flexibility weighted by the creepages (1982), L = (|ξ|L1 + |η|L2 + c|φ|L3) /
/// √(ξ² + η² + c²φ²), with L1 = 8a/(3 C11 G) and L3 = πa√(a/b)/(4 G C23): in the linear range the
/// simplified theory's F_x is Kalker's −G ab C11 ξ scaled by L1/L (spin adds none to F_x, odd in
/// y), for ξ and φ together.
#[test]
fn fastsim_single_weighted_flexibility_is_kalkers_for_combined_creepages() {
    let model = Fastsim::new(200, 200, TractionBound::Parabolic, Flexibility::SingleWeighted).unwrap();
    for (xi, phi) in [(1e-9, 4e-7), (-2e-9, 1e-7), (1e-9, -1e-6)] {
        let input = typical_contact(xi, 0.0, phi);
        let (a, b, g) = (input.semi_axis_a, input.semi_axis_b, input.shear_modulus);
        let c = (a * b).sqrt();
        let k = KalkerCoefficients::new(a / b, input.poisson_ratio);
        let (l1, l3) = (8.0 * a / (3.0 * k.c11 * g), PI * a * (a / b).sqrt() / (4.0 * g * k.c23));
        let weighted = (xi.abs() * l1 + c * phi.abs() * l3) / (xi * xi + c * c * phi * phi).sqrt();
        let expected = -g * a * b * k.c11 * xi * l1 / weighted;
        let got = model.creep_forces(&input).unwrap().force_longitudinal;
        assert!((got / expected - 1.0).abs() < 1e-3, "ξ {xi}, φ {phi}: {got} vs {expected}");
    }
}

#[test]
fn fastsim_spin_moment_meets_the_simplified_theory_linear_limit() {
    // Simplified theory in adhesion: M_z = −8 φ a² b³ / (15 L3) − ... ; for pure spin the lateral
    // part integrates to zero by symmetry, so M_z = −(8/15) a² b³ φ / L3 with
    // L3 = π a √(a/b) / (4 G C23). (It differs from Kalker's exact −G c⁴ C33 φ: FASTSIM's M_z is
    // the simplified theory's.)
    let input = typical_contact(0.0, 0.0, 1e-7);
    let (a, b) = (input.semi_axis_a, input.semi_axis_b);
    let c23 = KalkerCoefficients::new(a / b, 0.28).c23;
    let l3 = PI * a * (a / b).sqrt() / (4.0 * input.shear_modulus * c23);
    let expected = -8.0 / 15.0 * a * a * b.powi(3) * 1e-7 / l3;
    let got = fastsim(160, TractionBound::Parabolic).creep_forces(&input).unwrap().spin_moment.unwrap();
    assert!((got / expected - 1.0).abs() < 1e-3, "{got} vs {expected}");
}

/// The simplified theory's adhesion area under a pure longitudinal creepage, parabolic bound:
/// on the strip of half-length l the traction ξ(l − x)/L1 reaches the bound μp_max(l² − x²)/a² at
/// x = κ − l, κ = ξa²/(L1 μ p_max), so the strip adheres over 2l − κ. With ε = κ/(2a) =
/// 3π C11 G ab ξ/(32 μQ) (L1 = 8a/(3 C11 G), p_max = 2Q/(πab)) the strips with l > εa adhere, and
/// the adhering share of the ellipse is 2(asin U − εU)/π, U = √(1 − ε²): 1 at rest, 0 at ε = 1.
#[test]
fn fastsim_adhesion_area_is_the_simplified_theorys() {
    let model = Fastsim::new(200, 200, TractionBound::Parabolic, Flexibility::ThreeBlended).unwrap();
    let input = typical_contact(0.0, 0.0, 0.0);
    let (a, b, q, mu, g) =
        (input.semi_axis_a, input.semi_axis_b, input.normal_force, input.friction_coefficient, input.shear_modulus);
    let c11 = KalkerCoefficients::new(a / b, input.poisson_ratio).c11;
    for epsilon in [0.1, 0.3, 0.5, 0.8] {
        let xi = epsilon * 32.0 * mu * q / (3.0 * PI * c11 * g * a * b);
        let result = model.evaluate(&ContactInput { creepage_longitudinal: xi, ..input }).unwrap();
        let u = (1.0 - epsilon * epsilon).sqrt();
        let expected = 2.0 * (u.asin() - epsilon * u) / PI;
        // Measured on 400 × 400: within 5e-5 of it at every ε (0.8729, 0.6238, 0.3910, 0.1041).
        assert!(
            (result.adhesion_area_fraction - expected).abs() < 2e-3,
            "ε {epsilon}: {} vs {expected}",
            result.adhesion_area_fraction
        );
    }
}

#[test]
fn fastsim_blend_leaves_pure_creepages_unchanged() {
    // With one creepage CONTACT's combined flexibility L_crss is that creepage's own L_i, so the
    // blend changes nothing, from the linear range to full slip.
    let three = Fastsim::new(30, 30, TractionBound::Parabolic, Flexibility::Three).unwrap();
    let blended = Fastsim::new(30, 30, TractionBound::Parabolic, Flexibility::ThreeBlended).unwrap();
    for s in [1e-7, 1e-4, 1e-3, 1e-2, 1.0] {
        for input in [typical_contact(s, 0.0, 0.0), typical_contact(0.0, s, 0.0), typical_contact(0.0, 0.0, 100.0 * s)]
        {
            let (t, b) = (three.creep_forces(&input).unwrap(), blended.creep_forces(&input).unwrap());
            for (x, y) in [(t.force_longitudinal, b.force_longitudinal), (t.force_lateral, b.force_lateral)] {
                assert!((x - y).abs() <= 1e-12 * x.abs().max(y.abs()), "{input:?}: {x} vs {y}");
            }
        }
    }
}

#[test]
fn fastsim_blend_vanishes_linearly_in_the_linear_range() {
    // Combined η and φ: the blend weight is proportional to the creepage's size (f_crp / 3), so the
    // blended model meets the unblended one (and hence Kalker's linear theory) to first order.
    let three = Fastsim::new(40, 40, TractionBound::Elliptic, Flexibility::Three).unwrap();
    let blended = Fastsim::new(40, 40, TractionBound::Elliptic, Flexibility::ThreeBlended).unwrap();
    let deviation = |s: f64| {
        let input = typical_contact(0.0, s, 1000.0 * s);
        let lateral = |m: &Fastsim| m.creep_forces(&input).unwrap().force_lateral;
        (lateral(&blended) / lateral(&three) - 1.0).abs()
    };
    let (coarse, fine) = (deviation(1e-7), deviation(1e-8));
    assert!(coarse > 0.0 && (coarse / fine / 10.0 - 1.0).abs() < 0.01, "{coarse} vs {fine}");
    assert!(coarse < 1e-4, "{coarse}");
}

/// The linear theory is not friction-limited, so its products can leave f64's range: each is held
/// at ±f64::MAX with the sign of the exact value (module documentation), never ±inf or NaN.
/// G = 1e300 Pa on a 1 m × 1 m contact: G·ab·C11·ξ = 3.4e300·ξ overflows for ξ = ±1e10.
#[test]
fn kalker_linear_holds_overflowing_forces_at_the_largest_finite_value() {
    let huge =
        ContactInput { semi_axis_a: 1.0, semi_axis_b: 1.0, shear_modulus: 1e300, ..typical_contact(1e10, -1e10, 0.0) };
    let forces = KalkerLinear.creep_forces(&huge).unwrap();
    assert_eq!(forces.force_longitudinal, -f64::MAX);
    assert_eq!(forces.force_lateral, f64::MAX);
    // Spin alone: G c³ C23 φ overflows too, and so does the moment's G c⁴ C33 φ.
    let spin_only = ContactInput { creepage_longitudinal: 0.0, creepage_lateral: 0.0, spin_creepage: 1e10, ..huge };
    let spinning = KalkerLinear.creep_forces(&spin_only).unwrap();
    assert_eq!(spinning.force_lateral, -f64::MAX);
    assert_eq!(spinning.spin_moment, Some(-f64::MAX));
}
