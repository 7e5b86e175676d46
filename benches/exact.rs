//! Kalker's exact theory on CONTACT's published spin case (partial slip, F_y ≈ −0.61 μN) at
//! 20 × 20, 40 × 40, 44 × 44 (CONTACT's grid) and 80 × 80 elements over the potential contact
//! area. Work grows as N² per sweep times sweeps ∝ √N.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use wheel_rail_contact::{CreepForceModel, ExactTheory};

#[allow(dead_code)] // the bench uses one of the published cases
#[path = "../tests/data/contact_published_cases.rs"]
mod published;

fn exact_theory_spin_case(c: &mut Criterion) {
    let input = published::FASTSIM_CASE;
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
