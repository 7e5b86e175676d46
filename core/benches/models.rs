//! One evaluation of every real-time rung of the ladder at its default (`ModelChoice::RUNGS`; with
//! spin, in partial slip, including validation and the Kalker coefficient lookup) and of each on
//! the same 64 contacts (`cases/…`: time per evaluation is the reported time / 64); FASTSIM at
//! several more grids (ns per element = time / n²). The exact theory has its own (`exact.rs`).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wheel_rail_contact::{
    ContactInput, CreepForceModel, Discretisation, Fastsim, Flexibility, ModelChoice, TractionBound,
};

/// A worn-wheel tread contact in partial slip with all three creepages (utilisation ≈ 0.6).
fn input() -> ContactInput {
    ContactInput {
        creepage_longitudinal: -1.0e-3,
        creepage_lateral: 1.2e-3,
        spin_creepage: -0.8,
        normal_force: 60e3,
        semi_axis_a: 5.5e-3,
        semi_axis_b: 3.4e-3,
        friction_coefficient: 0.4,
        shear_modulus: 8.0e10,
        poisson_ratio: 0.27,
    }
}

fn bench_model(c: &mut Criterion, name: &str, model: &dyn CreepForceModel) {
    let input = input();
    c.bench_function(name, |bencher| bencher.iter(|| model.creep_forces(black_box(&input))));
}

/// 64 contacts: a/b from 0.2 to 5, every creepage direction, from the linear range to full slip.
fn cases() -> Vec<ContactInput> {
    let mut cases = Vec::new();
    for (i, a_over_b) in [0.2, 0.6, 1.5, 5.0].into_iter().enumerate() {
        for (j, level) in [0.05, 0.5, 1.5, 6.0].into_iter().enumerate() {
            for (k, (xi, eta, phi)) in
                [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.6, -0.8, 0.0), (0.3, 0.5, -150.0)].into_iter().enumerate()
            {
                let c = 4.5e-3;
                cases.push(ContactInput {
                    creepage_longitudinal: level * xi * 1e-3,
                    creepage_lateral: level * eta * 1e-3,
                    spin_creepage: level * phi * 1e-3,
                    semi_axis_a: c * f64::sqrt(a_over_b),
                    semi_axis_b: c / f64::sqrt(a_over_b),
                    poisson_ratio: 0.25 + 0.01 * (i + j + k) as f64,
                    ..input()
                });
            }
        }
    }
    cases
}

fn bench_cases(c: &mut Criterion, name: &str, model: &dyn CreepForceModel, cases: &[ContactInput]) {
    c.bench_function(name, |bencher| {
        bencher.iter(|| {
            for case in cases {
                black_box(model.creep_forces(black_box(case)).ok());
            }
        })
    });
}

fn models(c: &mut Criterion) {
    let cases = cases();
    for rung in ModelChoice::RUNGS.iter().filter(|rung| !rung.offline) {
        let model = (rung.default_model)().unwrap_or_else(|e| panic!("{}: {e}", rung.name));
        bench_model(c, rung.name, &model);
        bench_cases(c, &format!("cases/{}", rung.name), &model, &cases);
    }
    // CONTACT's blended flexibilities (the default; 20 × 20 is `fastsim` above); the unblended
    // 5 × 5 shows the blend's cost.
    for n in [5, 10, 40, 100] {
        let model = Fastsim::new(n, n, TractionBound::Parabolic, Flexibility::ThreeBlended).unwrap();
        bench_model(c, &format!("fastsim_parabolic_{n}x{n}"), &model);
    }
    let unblended = Fastsim::new(5, 5, TractionBound::Parabolic, Flexibility::Three).unwrap();
    bench_model(c, "fastsim_parabolic_unblended_5x5", &unblended);
    let elliptic = Fastsim::new(20, 20, TractionBound::Elliptic, Flexibility::ThreeBlended).unwrap();
    bench_model(c, "fastsim_elliptic_20x20", &elliptic);
    // CONTACT's discretisation on CONTACT's grid: 44 × 44 over 1.1 × the contact, ≈ 1257 of
    // the 1936 elements inside the ellipse.
    let contact_grid = Fastsim::new(44, 44, TractionBound::Parabolic, Flexibility::ThreeBlended)
        .unwrap()
        .with_discretisation(Discretisation::ContactGrid);
    bench_model(c, "fastsim_contact_grid_parabolic_44x44", &contact_grid);
}

criterion_group!(benches, models);
criterion_main!(benches);
