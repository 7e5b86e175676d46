//! Kalker's exact theory (FFT Newton–GMRES solver), one thread: CONTACT's published spin case
//! (η with spin, partial slip, F_y ≈ −0.61 μN) and a pure-ξ partial-slip case (ξ = 1e-3 on
//! CONTACT's ellipse, F_x ≈ −0.47 μN) at 40 × 40, 80 × 80 and 160 × 160 elements over the
//! potential contact area; a warm-started co-simulation on 40 × 40 and 200 × 50, each step
//! starting from the previous one's tractions while the creepages and the ellipse vary slowly;
//! and a sequence of random jumps on 200 × 50, its worst step against a cold solve.
//!
//! Run: `cargo bench --bench exact`. The solver's iterations and operator products per case are
//! printed before the timings.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::hint::black_box;
use wheel_rail_contact::{ContactInput, ExactTheory};

use wheel_rail_contact::reference_cases as published;

const GRIDS: [usize; 3] = [40, 80, 160];

fn cases() -> [(&'static str, ContactInput); 2] {
    let spin = published::FASTSIM_CASE;
    let pure_xi = ContactInput {
        creepage_longitudinal: 1e-3,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        ..published::FASTSIM_CASE
    };
    [("spin_case", spin), ("pure_xi_partial_slip", pure_xi)]
}

fn exact_theory_cases(c: &mut Criterion) {
    for (name, input) in cases() {
        let mut group = c.benchmark_group(format!("exact_theory_{name}"));
        group.sample_size(10);
        for elements in GRIDS {
            let model = ExactTheory::new(elements, elements);
            let solution = model.solve(&input).unwrap();
            println!(
                "{name} {elements}x{elements}: {} Newton steps, {} operator products",
                solution.iterations, solution.operator_products
            );
            group.bench_with_input(BenchmarkId::from_parameter(elements), &model, |bencher, model| {
                bencher.iter(|| model.solve(black_box(&input)).unwrap().forces)
            });
        }
        group.finish();
    }
}

/// Step k of a slowly varying scene: creepages and ellipse drift by ≈ 0.1–0.3 % per step
/// around CONTACT's spin case (with some longitudinal creepage).
fn scene_step(k: usize) -> ContactInput {
    let t = k as f64 * 0.01;
    let base = published::FASTSIM_CASE;
    ContactInput {
        creepage_longitudinal: 4e-4 * (1.0 + 0.3 * t.sin()),
        creepage_lateral: base.creepage_lateral * (1.0 + 0.2 * (0.7 * t).sin()),
        spin_creepage: base.spin_creepage * (1.0 + 0.2 * (1.3 * t).cos()),
        semi_axis_a: base.semi_axis_a * (1.0 + 0.05 * (0.5 * t).sin()),
        normal_force: base.normal_force * (1.0 + 0.1 * (0.9 * t).sin()),
        ..base
    }
}

/// Warm-started steps on 40 × 40 (the target grid of the issue) and on 200 × 50 (the proposed
/// default of `model = exact`: 200 elements along the rolling direction, where the grid error
/// comes from).
fn exact_theory_warm_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact_theory_warm_step");
    group.sample_size(20);
    for (longitudinal, lateral) in [(40, 40), (200, 50)] {
        let model = ExactTheory::new(longitudinal, lateral);
        let mut start = model.solve(&scene_step(0)).unwrap().warm_start();
        let (mut products, mut iterations) = (0, 0);
        for k in 1..=100 {
            let solution = model.solve_from(&scene_step(k), Some(&start)).unwrap();
            products += solution.operator_products;
            iterations += solution.iterations;
            start = solution.warm_start();
        }
        println!(
            "warm steps {longitudinal}x{lateral}: {:.1} Newton steps, {:.1} operator products per step",
            iterations as f64 / 100.0,
            products as f64 / 100.0
        );
        group.bench_function(format!("{longitudinal}x{lateral}"), |bencher| {
            let mut k = 0;
            bencher.iter(|| {
                k += 1;
                let solution = model.solve_from(black_box(&scene_step(k)), Some(&start)).unwrap();
                start = solution.warm_start();
                solution.forces
            })
        });
    }
    group.finish();
}

/// Steps of a co-simulation whose contact jumps at every step (24 jumps between random contacts
/// of CONTACT's ellipse area: a/b log-uniform in [0.06, 16], ν in [0, 0.5], |(ξ, η)|
/// log-uniform in [1e-5, 3e-2] in any direction, φ up to that over √(ab); seeded), each started
/// from the previous step's solution on 200 × 50: every step's operator products against a cold
/// solve's are printed, and the step with the largest ratio is timed warm-started and cold.
fn exact_theory_jump_steps(c: &mut Criterion) {
    let model = ExactTheory::new(200, 50);
    let base = published::FASTSIM_CASE;
    let area = base.semi_axis_a * base.semi_axis_b;
    let mut runner = TestRunner::new_with_rng(Config::default(), TestRng::from_seed(RngAlgorithm::ChaCha, &[31; 32]));
    let strategy = (-1.2..1.2f64, 0.0..0.5f64, -5.0..-1.5f64, 0.0..std::f64::consts::TAU, -1.0..1.0f64);
    let contacts: Vec<ContactInput> = (0..=24)
        .map(|_| {
            let (log_ratio, poisson_ratio, log_creepage, angle, spin) =
                strategy.new_tree(&mut runner).unwrap().current();
            let (creepage, ratio) = (10f64.powf(log_creepage), 10f64.powf(log_ratio));
            ContactInput {
                creepage_longitudinal: creepage * angle.cos(),
                creepage_lateral: creepage * angle.sin(),
                spin_creepage: spin * creepage / area.sqrt(),
                semi_axis_a: (area * ratio).sqrt(),
                semi_axis_b: (area / ratio).sqrt(),
                poisson_ratio,
                ..base
            }
        })
        .collect();
    let mut start = model.solve(&contacts[0]).unwrap().warm_start();
    let mut worst = (0.0, 0, start.clone());
    for (step, contact) in contacts.iter().enumerate().skip(1) {
        let warm = model.solve_from(contact, Some(&start)).unwrap();
        let cold = model.solve(contact).unwrap();
        let ratio = warm.operator_products as f64 / cold.operator_products as f64;
        println!(
            "jump {step}: {} operator products warm-started, {} cold ({ratio:.2})",
            warm.operator_products, cold.operator_products
        );
        if ratio > worst.0 {
            worst = (ratio, step, start);
        }
        start = warm.warm_start();
    }
    let (ratio, step, start) = worst;
    println!("worst step: jump {step}, {ratio:.2} × a cold solve's operator products");
    let mut group = c.benchmark_group("exact_theory_worst_jump_step_200x50");
    group.sample_size(10);
    group.bench_function("warm_started", |bencher| {
        bencher.iter(|| model.solve_from(black_box(&contacts[step]), Some(&start)).unwrap().forces)
    });
    group.bench_function("cold", |bencher| bencher.iter(|| model.solve(black_box(&contacts[step])).unwrap().forces));
    group.finish();
}

criterion_group!(benches, exact_theory_cases, exact_theory_warm_steps, exact_theory_jump_steps);
criterion_main!(benches);
