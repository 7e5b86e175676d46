//! One Polach evaluation with spin, including validation and the Kalker coefficient lookup.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

fn polach_with_spin(c: &mut Criterion) {
    let model = Polach::default();
    let input = ContactInput {
        creepage_longitudinal: 1.5e-3,
        creepage_lateral: -0.8e-3,
        spin_creepage: 0.4,
        normal_force: 80e3,
        semi_axis_a: 6.3e-3,
        semi_axis_b: 4.1e-3,
        friction_coefficient: 0.35,
        shear_modulus: 8.2e10,
        poisson_ratio: 0.28,
    };
    c.bench_function("polach_with_spin", |bencher| bencher.iter(|| model.creep_forces(black_box(&input))));
}

criterion_group!(benches, polach_with_spin);
criterion_main!(benches);
