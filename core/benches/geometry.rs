//! One wheel's contact from profiles: the contact search and normal problem alone
//! (`geometry_direct_*`), one Polach evaluation for scale, whole wheel steps (geometry, normal
//! problem with the creep forces' share, the forces) at four poses, with Hertz's patches and
//! with the non-Hertzian ones (`wheel_step_non_hertzian_*`; with the strip table,
//! `wheel_step_non_hertzian_table_*`; the same step repeated, from a cold cache (`_cold_`), or
//! with the wheelset moving, every step a new pose (`_moving_`, Polach)), and the Manchester
//! benchmark's steps (`a22_*`: each wheel's cases in one iteration; the time over the count is
//! the mean step). The goal for a whole wheel step is ≤ 5 µs.

#![allow(clippy::result_large_err)] // the errors of the library (src/lib.rs)

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wheel_rail_contact::geometry::{ContactPoint, WheelOnRail, WheelSide, WheelsetPosition};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTable, ModelChoice, Polach};

/// A patch's vertical share per newton of normal force without tangential forces: cos δ.
fn cosine(point: &ContactPoint) -> f64 {
    point.contact_angle.cos()
}

fn geometry(c: &mut Criterion) {
    let pair = WheelOnRail::manchester_benchmark(WheelSide::Right);
    for (name, lateral) in [("geometry_direct_tread", 0.002), ("geometry_direct_flange", 0.007)] {
        let position = WheelsetPosition { lateral, vertical: 0.0, roll: 0.0, yaw: 0.0 };
        c.bench_function(name, |bencher| {
            bencher.iter(|| pair.patches_for_force(black_box(10e3), black_box(&position), cosine))
        });
    }
    let input = ContactInput {
        creepage_longitudinal: 1e-3,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        normal_force: 10e3,
        semi_axis_a: 3.7e-3,
        semi_axis_b: 1.7e-3,
        friction_coefficient: 0.3,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    };
    let model = Polach::default();
    c.bench_function("geometry_polach_scale", |bencher| bencher.iter(|| model.creep_forces(black_box(&input))));
    // A whole wheel step: geometry, normal problem with the creep forces' share, the forces;
    // with Hertz's patches and with the non-Hertzian ones (`wheel_step_non_hertzian_*`).
    for (model, model_name) in [
        (ModelChoice::Polach(Polach::default()), "polach"),
        (ModelChoice::ExactTable(ExactTable::new().unwrap()), "exact_table"),
    ] {
        for (method, method_name) in [(ContactMethod::Hertz, ""), (ContactMethod::NonHertzian, "non_hertzian_")] {
            let contact = WheelRailContact::new(pair.clone(), Scene::of_model(model, 82e9, 0.28)).with_method(method);
            wheel_steps(c, &contact, &format!("wheel_step_{method_name}{model_name}"), Steps::Repeated);
        }
        if model_name == "polach" {
            let contact = WheelRailContact::new(pair.clone(), Scene::of_model(model, 82e9, 0.28));
            wheel_steps(c, &contact, "wheel_step_moving_polach", Steps::Moving);
        }
        let contact = WheelRailContact::new(pair.clone(), Scene::of_model(model, 82e9, 0.28))
            .with_method(ContactMethod::NonHertzian)
            .with_strip_table();
        wheel_steps(c, &contact, &format!("wheel_step_non_hertzian_table_{model_name}"), Steps::Repeated);
        wheel_steps(c, &contact, &format!("wheel_step_non_hertzian_table_cold_{model_name}"), Steps::Cold);
        if model_name == "polach" {
            wheel_steps(c, &contact, "wheel_step_non_hertzian_table_moving_polach", Steps::Moving);
        }
    }
}

/// How a benchmark's wheel steps follow each other.
#[derive(Clone, Copy, PartialEq)]
enum Steps {
    /// The same step repeated, its state and cache kept: the non-Hertzian balance starts from
    /// the last step's z_ws (its state's `BalanceStart`), which a repeated step meets at once.
    Repeated,
    /// Each step from an empty state and cache, as a first step.
    Cold,
    /// The wheelset moving, its state and cache kept, as a simulation's steps: y_ws swings by ±0.1 mm
    /// about the pose over 64 steps (up to 10 µm a step; at 1 ms steps 10 mm/s at most, a
    /// slow hunting motion), so that every step is a new pose.
    Moving,
}

/// The whole wheel step at four poses, each its own benchmark `{prefix}_{place}`, the steps
/// following each other as `steps` says.
fn wheel_steps(c: &mut Criterion, contact: &WheelRailContact, prefix: &str, steps: Steps) {
    for (place, lateral, yaw) in
        [("tread", 0.002, 0.0048), ("centred", 0.0, 0.0), ("two_minima", 0.005, 0.0), ("flange", 0.007, 0.0168)]
    {
        let input = WheelInput {
            position: WheelsetPosition { lateral, yaw, ..WheelsetPosition::default() },
            velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3478, ..Default::default() },
            vertical: VerticalContact::PrescribedForce(10e3),
            friction_coefficient: 0.3,
        };
        // The state carries the last balance's z_ws, where the next one starts (`BalanceStart`).
        let (mut cache, mut state) = (WheelCache::default(), WheelState::default());
        let swing: Vec<WheelInput> = (0..64)
            .map(|k| {
                let mut moved = input;
                moved.position.lateral += 0.1e-3 * (2.0 * std::f64::consts::PI * f64::from(k) / 64.0).sin();
                moved
            })
            .collect();
        let mut step = 0;
        c.bench_function(&format!("{prefix}_{place}"), |bencher| {
            bencher.iter(|| {
                let input = match steps {
                    Steps::Repeated => &input,
                    Steps::Cold => {
                        (cache, state) = (WheelCache::default(), WheelState::default());
                        &input
                    }
                    Steps::Moving => {
                        step = (step + 1) % swing.len();
                        &swing[step]
                    }
                };
                let (output, next) =
                    contact.evaluate(black_box(input), &state, &mut cache, Evaluation::Step(1e-3)).unwrap();
                state = next;
                output
            })
        });
    }
}

/// The Manchester benchmark's steps (`core/tests/data/manchester_a22_inputs.csv`: 21 positions
/// per wheel, y_ws 0–10 mm with their yaw and roll, 10 kN), each wheel's 21 steps in one
/// iteration: criterion's time divided by 21 is the mean wheel step over the benchmark.
fn a22(c: &mut Criterion) {
    for (model, model_name) in [
        (ModelChoice::Polach(Polach::default()), "polach"),
        (ModelChoice::ExactTable(ExactTable::new().unwrap()), "exact_table"),
    ] {
        for (side, side_name) in [(WheelSide::Right, "right"), (WheelSide::Left, "left")] {
            let pair = WheelOnRail::manchester_benchmark(side);
            let contact = WheelRailContact::new(pair, Scene::of_model(model, 82e9, 0.28));
            let inputs: Vec<WheelInput> = include_str!("../tests/data/manchester_a22_inputs.csv")
                .lines()
                .filter(|line| line.starts_with(&format!("{side_name},")))
                .map(|line| {
                    let f: Vec<f64> = line.split(',').skip(1).map(|v| v.parse().unwrap()).collect();
                    WheelInput {
                        position: WheelsetPosition { lateral: f[1] * 1e-3, vertical: 0.0, roll: f[3], yaw: f[2] },
                        velocity: WheelsetVelocity {
                            rolling_speed: f[5] * 1e-3,
                            wheel_angular_speed: -f[6],
                            ..WheelsetVelocity::default()
                        },
                        vertical: VerticalContact::PrescribedForce(f[4]),
                        friction_coefficient: 0.3,
                    }
                })
                .collect();
            assert_eq!(inputs.len(), 21);
            let (mut cache, mut state) = (WheelCache::default(), WheelState::default());
            let name = format!("a22_{model_name}_{side_name}_{}_steps", inputs.len());
            c.bench_function(&name, |bencher| {
                bencher.iter(|| {
                    for input in &inputs {
                        let (output, next) =
                            contact.evaluate(black_box(input), &state, &mut cache, Evaluation::Step(1e-3)).unwrap();
                        state = next;
                        black_box(output);
                    }
                })
            });
        }
    }
}

criterion_group!(benches, geometry, a22);
criterion_main!(benches);
