//! The scene options, one evaluation each: Hertz's ellipse from the load, creepages from
//! kinematics, one relaxation step; and Polach fed by the kinematics, against Polach alone.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use wheel_rail_contact::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use wheel_rail_contact::scene::kinematics::{WheelKinematics, DEFAULT_REGULARISATION_SPEED};
use wheel_rail_contact::scene::relaxation::RelaxationLengths;
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

fn hertz(c: &mut Criterion) {
    let modulus = contact_modulus(8.2e10, 0.28).unwrap();
    let curvature = RelativeCurvature::from_radii(0.46, f64::INFINITY, 0.3).unwrap();
    c.bench_function("hertz_from_radii", |bencher| {
        bencher.iter(|| HertzContact::solve(black_box(80e3), black_box(&curvature), black_box(modulus)))
    });
}

fn kinematics() -> WheelKinematics {
    WheelKinematics {
        rolling_speed: 20.0,
        wheel_angular_speed: 20.03 / 0.46,
        wheel_rolling_radius: 0.46,
        lateral_slip_velocity: -0.016,
        spin_angular_velocity: 0.4 * 20.0,
    }
}

fn creepages(c: &mut Criterion) {
    let kinematics = kinematics();
    c.bench_function("creepages_from_kinematics", |bencher| {
        bencher.iter(|| black_box(&kinematics).creepages(black_box(DEFAULT_REGULARISATION_SPEED)))
    });
}

fn relaxation(c: &mut Criterion) {
    let lengths = RelaxationLengths::from_contact(6.3e-3, 4.1e-3, 0.28).unwrap();
    c.bench_function("relaxation_step", |bencher| {
        bencher.iter(|| {
            lengths.advance(black_box([1.2e3, -4e3]), black_box([8e3, -6e3]), black_box(20.0), black_box(1e-3))
        })
    });
}

/// The cost of computing the creepages in front of Polach, in one run with Polach alone on the
/// same contact (ellipse from Hertz, creepages from the kinematics).
fn polach_with_kinematics(c: &mut Criterion) {
    let model = Polach::default();
    let kinematics = kinematics();
    let creepages = kinematics.creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
    let curvature = RelativeCurvature::from_radii(0.46, f64::INFINITY, 0.3).unwrap();
    let ellipse = HertzContact::solve(80e3, &curvature, contact_modulus(8.2e10, 0.28).unwrap()).unwrap();
    let input = ContactInput {
        creepage_longitudinal: creepages.longitudinal,
        creepage_lateral: creepages.lateral,
        spin_creepage: creepages.spin,
        normal_force: 80e3,
        semi_axis_a: ellipse.semi_axis_a,
        semi_axis_b: ellipse.semi_axis_b,
        friction_coefficient: 0.35,
        shear_modulus: 8.2e10,
        poisson_ratio: 0.28,
    };
    c.bench_function("polach_alone", |bencher| bencher.iter(|| model.creep_forces(black_box(&input))));
    c.bench_function("polach_from_kinematics", |bencher| {
        bencher.iter(|| {
            let creepages = black_box(&kinematics).creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
            let with_creepages = ContactInput {
                creepage_longitudinal: creepages.longitudinal,
                creepage_lateral: creepages.lateral,
                spin_creepage: creepages.spin,
                ..input
            };
            model.creep_forces(&with_creepages)
        })
    });
}

criterion_group!(benches, hertz, creepages, relaxation, polach_with_kinematics);
criterion_main!(benches);
