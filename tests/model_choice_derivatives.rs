//! `ModelChoice` hands directional derivatives to the chosen model (exact dual numbers for
//! Polach, Kalker's linear theory and Shen–Hedrick–Elkins, FASTSIM's own central difference),
//! and FASTSIM's derivative agrees with finite differences to its documented tolerance.

mod common;

use common::{all_models, contact, fastsim};
use wheel_rail_contact::{
    ContactInput, CreepForceModel, CreepForces, KalkerLinear, ModelChoice, Polach, ShenHedrickElkins, TractionBound,
};

/// A direction moving every input but ν by about 1e-3 of its size per unit.
fn direction(x: &ContactInput) -> ContactInput {
    ContactInput {
        creepage_longitudinal: 3e-4,
        creepage_lateral: -7e-4,
        spin_creepage: 0.05,
        normal_force: -2e-3 * x.normal_force,
        semi_axis_a: 1e-3 * x.semi_axis_a,
        semi_axis_b: -5e-4 * x.semi_axis_b,
        friction_coefficient: 2e-4,
        shear_modulus: 1e-4 * x.shear_modulus,
        poisson_ratio: 0.0,
    }
}

fn outputs(f: &CreepForces) -> [f64; 4] {
    [f.force_longitudinal, f.force_lateral, f.adhesion_utilisation, f.spin_moment.unwrap_or(0.0)]
}

#[test]
fn model_choice_gives_the_chosen_models_own_derivative_bit_for_bit() {
    let x = contact(1.07, 0.28, 2e-3, -1e-3, 0.3);
    let d = direction(&x);
    for choice in all_models() {
        let inner: &dyn CreepForceModel = match &choice {
            ModelChoice::Polach(model) => model,
            ModelChoice::KalkerLinear(model) => model,
            ModelChoice::ShenHedrickElkins(model) => model,
            ModelChoice::Fastsim(model) => model,
        };
        let through_choice = choice.directional_derivative(&x, &d).unwrap();
        assert_eq!(through_choice, inner.directional_derivative(&x, &d).unwrap(), "{}", choice.name());
    }
    // The smooth models' derivatives are the exact ones, not the trait's default difference
    // quotient (which differs from them in the last digits).
    for model in [
        ModelChoice::Polach(Polach::default()),
        ModelChoice::KalkerLinear(KalkerLinear),
        ModelChoice::ShenHedrickElkins(ShenHedrickElkins),
    ] {
        struct DefaultOnly(ModelChoice);
        impl CreepForceModel for DefaultOnly {
            fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, wheel_rail_contact::InvalidInput> {
                self.0.creep_forces(input)
            }
        }
        let exact = model.directional_derivative(&x, &d).unwrap();
        let difference = DefaultOnly(model).directional_derivative(&x, &d).unwrap();
        assert_ne!(exact, difference, "{}", model.name());
        assert!(
            (exact.force_longitudinal - difference.force_longitudinal).abs() < 1e-5 * exact.force_longitudinal.abs()
        );
    }
}

/// FASTSIM's derivative (a central difference moving the inputs by 1e-6 of their size) against
/// a central difference with a 100 times larger step, on 10², 30² and 100² grids, away from
/// zero creepages (where the blended flexibilities have kinks): both see FASTSIM's piecewise-
/// smooth forces, so they agree only as far as the forces are smooth on that scale.
#[test]
fn fastsim_derivative_agrees_with_finite_differences_to_its_documented_tolerance() {
    let mut worst: f64 = 0.0;
    for (bound, n) in
        [TractionBound::Parabolic, TractionBound::Elliptic].into_iter().flat_map(|b| [(b, 10), (b, 30), (b, 100)])
    {
        let model = ModelChoice::Fastsim(fastsim(n, bound));
        for a_over_b in [0.3, 1.07, 3.3] {
            for (xi, eta, phi) in [(1e-4, 2e-5, 0.01), (2e-3, -1e-3, 0.1), (5e-4, 1e-3, 0.3), (8e-3, 4e-3, 0.5)] {
                let x = contact(a_over_b, 0.28, xi, eta, phi);
                let d = direction(&x);
                let derivative = outputs(&model.directional_derivative(&x, &d).unwrap());
                // Moves every input by at most 1e-4 of its size: 100 times FASTSIM's own step.
                let sizes = [
                    (x.creepage_longitudinal, d.creepage_longitudinal),
                    (x.creepage_lateral, d.creepage_lateral),
                    (x.spin_creepage, d.spin_creepage),
                    (x.normal_force, d.normal_force),
                ];
                let t = sizes.iter().map(|(value, rate)| 1e-4 * value.abs() / rate.abs()).fold(f64::INFINITY, f64::min);
                let at = |s: f64| {
                    let moved = ContactInput {
                        creepage_longitudinal: x.creepage_longitudinal + s * d.creepage_longitudinal,
                        creepage_lateral: x.creepage_lateral + s * d.creepage_lateral,
                        spin_creepage: x.spin_creepage + s * d.spin_creepage,
                        normal_force: x.normal_force + s * d.normal_force,
                        semi_axis_a: x.semi_axis_a + s * d.semi_axis_a,
                        semi_axis_b: x.semi_axis_b + s * d.semi_axis_b,
                        friction_coefficient: x.friction_coefficient + s * d.friction_coefficient,
                        shear_modulus: x.shear_modulus + s * d.shear_modulus,
                        poisson_ratio: x.poisson_ratio,
                    };
                    outputs(&model.creep_forces(&moved).unwrap())
                };
                let (plus, minus, value) = (at(t), at(-t), at(0.0));
                for k in 0..4 {
                    let difference = (plus[k] - minus[k]) / (2.0 * t);
                    // Each output on its own scale: the direction moves the inputs by ~1e-3 of
                    // their size per unit, so the output's own size times 1e-3 is its natural rate.
                    let scale = derivative[k].abs().max(1e-3 * value[k].abs());
                    if scale > 0.0 {
                        worst = worst.max((derivative[k] - difference).abs() / scale);
                    }
                }
            }
        }
    }
    // Measured worst: 4e-3 (30 × 30, elliptic bound, a/b = 0.3): an element switching between
    // adhesion and slip inside the larger step. The documented tolerance is 1e-2.
    println!("FASTSIM: worst relative difference {worst:e}");
    assert!(worst < 1e-2, "{worst}");
}
