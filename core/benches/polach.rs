//! Polach's method per evaluation, validation and Kalker coefficient lookup included: the
//! issue's case (with spin), without spin, with the measured-curve stiffness, with Polach 2005
//! switched on, with the shape factors cached, and the exact directional derivative (dual numbers).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wheel_rail_contact::{
    ContactInput, CreepForceModel, LargeCreepage, MeasuredCurve, Polach, Polach2005, ShapeCache, StiffnessSource,
};

use wheel_rail_contact::reference_cases::BENCHMARK_WITH_SPIN as WITH_SPIN;

fn polach(c: &mut Criterion) {
    let base = Polach::default();
    let without_spin = ContactInput { spin_creepage: 0.0, ..WITH_SPIN };
    let measured = Polach {
        stiffness: StiffnessSource::MeasuredCurve(MeasuredCurve::from_peak(0.4, 0.01, 0.35).unwrap()),
        ..Polach::default()
    };
    let falling =
        Polach { large_creepage: Some(LargeCreepage::new(Polach2005::DRY, 20.0).unwrap()), ..Polach::default() };
    let direction = ContactInput {
        creepage_longitudinal: 1.0,
        creepage_lateral: 0.5,
        spin_creepage: 0.0,
        normal_force: 100.0,
        semi_axis_a: 0.0,
        semi_axis_b: 0.0,
        friction_coefficient: 0.0,
        shear_modulus: 0.0,
        poisson_ratio: 0.0,
    };
    assert!(base.directional_derivative(&WITH_SPIN, &direction).is_ok());

    c.bench_function("polach_with_spin", |b| b.iter(|| base.creep_forces(black_box(&WITH_SPIN))));
    c.bench_function("polach_without_spin", |b| b.iter(|| base.creep_forces(black_box(&without_spin))));
    // The same shape step after step (the FMU's case): Kalker's coefficients and K_S cached.
    let mut cache = ShapeCache::default();
    c.bench_function("polach_with_spin_shape_cached", |b| {
        b.iter(|| base.creep_forces_with_cache(black_box(&WITH_SPIN), &mut cache))
    });
    c.bench_function("polach_measured_curve", |b| b.iter(|| measured.creep_forces(black_box(&WITH_SPIN))));
    c.bench_function("polach_2005_dry", |b| b.iter(|| falling.creep_forces(black_box(&WITH_SPIN))));
    c.bench_function("polach_directional_derivative", |b| {
        b.iter(|| base.directional_derivative(black_box(&WITH_SPIN), black_box(&direction)))
    });
}

criterion_group!(benches, polach);
criterion_main!(benches);
