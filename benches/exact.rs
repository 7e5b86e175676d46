//! Kalker's exact theory on CONTACT's published spin case (partial slip, F_y ≈ −0.61 μN) at
//! 20 × 20, 40 × 40, 44 × 44 (CONTACT's grid) and 80 × 80 elements over the potential contact
//! area. Work grows as N² per sweep times sweeps ∝ √N.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTheory};

fn exact_theory_spin_case(c: &mut Criterion) {
    let input = ContactInput {
        creepage_longitudinal: 0.0,
        creepage_lateral: -6.25e-4,
        spin_creepage: 0.625,
        normal_force: 82e3,
        semi_axis_a: 8e-3,
        semi_axis_b: 4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    };
    let mut group = c.benchmark_group("exact_theory_spin_case");
    group.sample_size(10);
    for elements in [20, 40, 44, 80] {
        let model = ExactTheory::new(elements, elements);
        group.bench_with_input(BenchmarkId::from_parameter(elements), &model, |bencher, model| {
            bencher.iter(|| model.creep_forces(black_box(&input)))
        });
    }
    group.finish();
}

criterion_group!(benches, exact_theory_spin_case);
criterion_main!(benches);
