//! Sign, oddness and saturation invariants for every model of the ladder, and the extremes grid.

use crate::common;

use common::{all_models, saturating_models, typical_contact};
use wheel_rail_contact::{ContactInput, CreepForceModel, ModelChoice};

fn forces(model: &ModelChoice, input: &ContactInput) -> (f64, f64, Option<f64>) {
    let f = model.creep_forces(input).unwrap();
    (f.force_longitudinal, f.force_lateral, f.spin_moment)
}

#[test]
fn forces_oppose_the_creepages() {
    for model in all_models() {
        for s in [1e-5, 1e-3, 1e-1] {
            let (fx, _, _) = forces(&model, &typical_contact(s, 0.0, 0.0));
            let (_, fy, _) = forces(&model, &typical_contact(0.0, s, 0.0));
            assert!(fx < 0.0 && fy < 0.0, "{}: s = {s}: fx {fx}, fy {fy}", model.name());
            // Positive spin pushes F_y negative (−G c³ C23 φ) and, where a moment exists, M_z too.
            let (_, fy_spin, mz) = forces(&model, &typical_contact(0.0, 0.0, s * 100.0));
            assert!(fy_spin < 0.0, "{}: spin {s}: fy {fy_spin}", model.name());
            if let Some(mz) = mz {
                assert!(mz < 0.0, "{}: spin {s}: mz {mz}", model.name());
            }
        }
    }
}

#[test]
fn forces_are_odd_in_the_creepages() {
    for model in all_models() {
        for (xi, eta, phi) in [(1e-3, 2e-4, 0.3), (-2e-3, 5e-3, -1.0), (3e-2, -1e-2, 2.0)] {
            let (fx, fy, mz) = forces(&model, &typical_contact(xi, eta, phi));
            let (gx, gy, mz_neg) = forces(&model, &typical_contact(-xi, -eta, -phi));
            let tolerance = 1e-12 * (fx.abs() + fy.abs());
            assert!((fx + gx).abs() <= tolerance && (fy + gy).abs() <= tolerance, "{}", model.name());
            if let (Some(m), Some(n)) = (mz, mz_neg) {
                assert!((m + n).abs() <= 1e-12 * m.abs(), "{}: {m} vs {n}", model.name());
            }
            // ξ alone flips F_x only (no ξ–η coupling in any model; y-symmetry of the contact).
            let (hx, hy, _) = forces(&model, &typical_contact(-xi, eta, phi));
            assert!((fx + hx).abs() <= tolerance && (fy - hy).abs() <= tolerance, "{}", model.name());
        }
    }
}

#[test]
fn saturating_models_stay_within_coulomb_and_saturate_monotonically() {
    for model in saturating_models() {
        for (dx, dy, dphi) in [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.6, -0.8, 0.0), (0.3, 0.5, 200.0)] {
            let mut previous = 0.0;
            for step in 0..200 {
                let s = 1e-6 * 1.08_f64.powi(step);
                let f = model.creep_forces(&typical_contact(dx * s, dy * s, dphi * s)).unwrap();
                let utilisation = f.adhesion_utilisation;
                assert!(utilisation <= 1.0 + 1e-12, "{}: {utilisation} at s = {s}", model.name());
                if dphi == 0.0 {
                    // Without spin the resultant grows monotonically to μQ.
                    assert!(utilisation >= previous - 1e-12, "{}: not monotone at s = {s}", model.name());
                }
                previous = utilisation;
            }
            let pure = dphi == 0.0;
            assert!(!pure || previous > 0.999, "{}: full slip reaches only {previous}", model.name());
        }
    }
}

#[test]
#[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
fn extremes_grid_is_finite_bounded_and_never_panics() {
    let magnitudes = [0.0, 1e-300, 1e-12, 1e-6, 1e-3, 1.0, 1e3, 1e6];
    let creepages: Vec<f64> = magnitudes.iter().flat_map(|&m| [m, -m]).skip(1).collect();
    let ratios: [f64; 5] = [1e-3, 0.05, 1.0, 20.0, 1e3];
    let loads = [0.0, 1e-12, 1.0, 1e4, 1e7];
    let frictions = [0.0, 1e-12, 0.3, 1.0];
    let models = all_models();
    for &a_over_b in &ratios {
        for &q in &loads {
            for &mu in &frictions {
                for &xi in &creepages {
                    for &eta in &creepages {
                        for &phi in &creepages {
                            let input = ContactInput {
                                creepage_longitudinal: xi,
                                creepage_lateral: eta,
                                spin_creepage: phi,
                                normal_force: q,
                                semi_axis_a: 5e-3 * a_over_b.sqrt(),
                                semi_axis_b: 5e-3 / a_over_b.sqrt(),
                                friction_coefficient: mu,
                                shear_modulus: 8e10,
                                poisson_ratio: 0.28,
                            };
                            check_extreme(&models, &input);
                        }
                    }
                }
            }
        }
    }
}

fn check_extreme(models: &[ModelChoice], input: &ContactInput) {
    for model in models {
        let a_over_b = input.semi_axis_a / input.semi_axis_b;
        let outside_table = matches!(model, ModelChoice::ExactTable(table) if !table.table().covers_a_over_b(a_over_b));
        if outside_table && !input.transmits_no_force() {
            // Outside its table: a clear error naming the semi-axes, not an extrapolation (after
            // lift-off or without friction, zero force like every model).
            let error = model.creep_forces(input).expect_err("outside the table's a/b range");
            assert_eq!((error.variable, error.with[0].map(|w| w.0)), ("semi_axis_a", Some("semi_axis_b")), "{error}");
            continue;
        }
        let f = model.creep_forces(input).unwrap_or_else(|e| panic!("{}: {e} for {input:?}", model.name()));
        let values = [f.force_longitudinal, f.force_lateral, f.spin_moment.unwrap_or(0.0), f.adhesion_utilisation];
        assert!(values.iter().all(|v| v.is_finite()), "{}: {f:?} for {input:?}", model.name());
        if matches!(model, ModelChoice::KalkerLinear(_)) {
            continue; // Linear theory is not friction-limited by definition; finite is its bound.
        }
        let limit = input.friction_limit();
        assert!(
            f.force_longitudinal.abs() <= limit * (1.0 + 1e-12) && f.force_lateral.abs() <= limit * (1.0 + 1e-12),
            "{}: {f:?} exceeds μQ = {limit} for {input:?}",
            model.name()
        );
        if let Some(mz) = f.spin_moment {
            // |M_z| ≤ μQ · max(a, b): no traction can exceed μ p_z, no lever arm the contact size.
            let bound = limit * input.semi_axis_a.max(input.semi_axis_b) * (1.0 + 1e-12);
            assert!(mz.abs() <= bound, "{}: M_z {mz} > {bound} for {input:?}", model.name());
        }
    }
}
