//! Exact directional derivatives (forward-mode dual numbers) against finite differences.

use crate::common;

use common::{all_models, contact, contact_case, fastsim, moved, relative_difference, NO_RATES};
use wheel_rail_contact::{
    ContactInput, CreepForceModel, CreepForces, ExactTheory, InvalidInput, KalkerCoefficients, KalkerLinear,
    LargeCreepage, MeasuredCurve, ModelChoice, Polach, Polach2005, ShenHedrickElkins, StiffnessSource, TractionBound,
};

/// F_x, F_y, |F|/μQ and M_z (0 for models without one).
fn outputs(f: &CreepForces) -> [f64; 4] {
    [f.force_longitudinal, f.force_lateral, f.adhesion_utilisation, f.spin_moment.unwrap_or(0.0)]
}

/// Fourth-order central difference (Richardson): error O(t⁴) + rounding/t.
fn finite_difference(model: &dyn CreepForceModel, x: &ContactInput, d: &ContactInput, t: f64) -> [f64; 4] {
    let at = |s: f64| outputs(&model.creep_forces(&moved(x, d, s)).unwrap());
    let (p1, m1, p2, m2) = (at(t), at(-t), at(2.0 * t), at(-2.0 * t));
    std::array::from_fn(|k| (8.0 * (p1[k] - m1[k]) - (p2[k] - m2[k])) / (12.0 * t))
}

/// One direction per input, each scaled to move its input by 1e-3 of a typical value per unit.
fn unit_directions(x: &ContactInput) -> Vec<(&'static str, ContactInput)> {
    let zero = NO_RATES;
    vec![
        ("xi", ContactInput { creepage_longitudinal: 1e-3, ..zero }),
        ("eta", ContactInput { creepage_lateral: 1e-3, ..zero }),
        ("phi", ContactInput { spin_creepage: 0.1, ..zero }),
        ("Q", ContactInput { normal_force: 1e-3 * x.normal_force, ..zero }),
        ("a", ContactInput { semi_axis_a: 1e-3 * x.semi_axis_a, ..zero }),
        ("b", ContactInput { semi_axis_b: 1e-3 * x.semi_axis_b, ..zero }),
        ("mu", ContactInput { friction_coefficient: 1e-3, ..zero }),
        ("G", ContactInput { shear_modulus: 1e-3 * x.shear_modulus, ..zero }),
        (
            "all",
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
            },
        ),
    ]
}

fn assert_matches_finite_differences(model: &dyn CreepForceModel, x: &ContactInput, label: &str) {
    for (name, d) in unit_directions(x) {
        // At Φ = 0 eq. (21) switches s_yC: the forces have one-sided derivatives in Φ there
        // (see `spin_derivative_at_zero_spin_is_one_sided`), so central differences do not apply.
        if x.spin_creepage == 0.0 && d.spin_creepage != 0.0 {
            continue;
        }
        let t = 1e-3;
        let exact = outputs(&model.directional_derivative(x, &d).unwrap());
        let fd = finite_difference(model, x, &d, t);
        // Each output on its own scale. The difference carries the rounding of the values it
        // subtracts, ~|F|·ε/t: it dominates near saturation, where the forces barely move.
        let values = outputs(&model.creep_forces(x).unwrap());
        for k in 0..4 {
            let rounding = 10.0 * values[k].abs() * f64::EPSILON / t;
            assert!(
                (exact[k] - fd[k]).abs() <= 1e-6 * fd[k].abs() + rounding,
                "{label}, direction {name}, output {k}: exact {} vs finite difference {}",
                exact[k],
                fd[k]
            );
        }
    }
}

#[test]
fn polach_derivatives_match_finite_differences_across_the_regimes() {
    let model = Polach::default();
    // Off the rows of Kalker's table: the coefficients are piecewise linear in a/b, so at a row
    // the derivative in a or b is one-sided (the segment above it).
    for a_over_b in [0.23, 0.55, 1.07, 2.2, 4.7, 0.05, 30.0] {
        for (xi, eta, phi) in [
            (1e-4, 0.0, 0.0),    // linear range
            (2e-3, -1e-3, 0.0),  // transition
            (0.05, 0.02, 0.0),   // near saturation
            (5e-4, 1e-3, 0.3),   // spin enlarging η: s_yC = η + aΦ
            (5e-4, 1e-3, -0.1),  // spin against η, |η + aΦ| < |η|: s_yC = η
            (0.0, -6e-4, 0.625), // CONTACT's case 2 creepages
            (1e-3, 0.0, 2.0),    // spin dominated
        ] {
            let x = contact(a_over_b, 0.28, xi, eta, phi);
            assert_matches_finite_differences(&model, &x, &format!("a/b = {a_over_b}, ({xi}, {eta}, {phi})"));
        }
    }
}

#[test]
fn linear_and_shen_hedrick_elkins_derivatives_match_finite_differences() {
    for a_over_b in [0.23, 1.07, 4.7, 0.05, 30.0] {
        for (xi, eta, phi) in [(1e-4, 0.0, 0.0), (2e-3, -1e-3, 0.4), (0.05, 0.02, -0.3), (0.0, -6e-4, 0.625)] {
            let x = contact(a_over_b, 0.28, xi, eta, phi);
            let label = format!("a/b = {a_over_b}, ({xi}, {eta}, {phi})");
            assert_matches_finite_differences(&KalkerLinear, &x, &format!("linear, {label}"));
            assert_matches_finite_differences(&ShenHedrickElkins, &x, &format!("SHE, {label}"));
        }
    }
    // The linear theory's derivative is its stiffness, everywhere.
    let x = contact(2.0, 0.28, 3e-3, 0.0, 0.0);
    let d = ContactInput { creepage_longitudinal: 1.0, ..ContactInput { ..unit_directions(&x)[1].1 } };
    let d = ContactInput { creepage_lateral: 0.0, ..d };
    let c = KalkerCoefficients::new(2.0, 0.28);
    let stiffness = -x.shear_modulus * x.semi_axis_a * x.semi_axis_b * c.c11;
    assert!(
        relative_difference(KalkerLinear.directional_derivative(&x, &d).unwrap().force_longitudinal, stiffness) < 1e-14
    );
}

#[test]
fn derivatives_on_both_sides_of_the_spin_switch() {
    // Eq. (21) switches at aΦ = −2η: the forces are continuous there but have a kink, so the
    // derivative is checked 1 % off it on each side (the differences step 0.2 % of η at most).
    let base = contact(1.07, 0.28, 2e-4, 1e-3, 0.0);
    let phi_switch = -2.0 * 1e-3 / base.semi_axis_a;
    for side in [1.0 - 1e-2, 1.0 + 1e-2] {
        let x = ContactInput { spin_creepage: phi_switch * side, ..base };
        assert_matches_finite_differences(&Polach::default(), &x, &format!("switch side {side}"));
    }
}

#[test]
fn measured_curve_and_polach_2005_derivatives_match_finite_differences() {
    let curve = MeasuredCurve::from_peak(0.4, 0.01, 0.35).unwrap();
    let measured = Polach { stiffness: StiffnessSource::MeasuredCurve(curve), ..Polach::default() };
    let falling =
        Polach { large_creepage: Some(LargeCreepage::new(Polach2005::DRY, 20.0).unwrap()), ..Polach::default() };
    for (xi, eta, phi) in [(3e-3, 0.0, 0.0), (0.02, -4e-3, 0.5), (0.2, 0.0, 0.0)] {
        let x = ContactInput { friction_coefficient: 0.35, ..contact(1.5, 0.28, xi, eta, phi) };
        assert_matches_finite_differences(&measured, &x, "measured curve");
        assert_matches_finite_differences(&falling, &x, "Polach 2005 dry");
    }
}

#[test]
fn at_zero_creepage_the_derivative_is_kalkers_stiffness() {
    let x = contact_case();
    let c = KalkerCoefficients::new(2.0, 0.28);
    let ab = x.semi_axis_a * x.semi_axis_b;
    let g = x.shear_modulus;
    let along = |xi: f64, eta: f64, phi: f64| {
        let d = ContactInput { creepage_longitudinal: xi, creepage_lateral: eta, spin_creepage: phi, ..NO_RATES };
        Polach::default().directional_derivative(&x, &d).unwrap()
    };
    assert!(relative_difference(along(1.0, 0.0, 0.0).force_longitudinal, -g * ab * c.c11) < 1e-12);
    assert!(relative_difference(along(0.0, 1.0, 0.0).force_lateral, -g * ab * c.c22) < 1e-12);
    assert!(relative_difference(along(0.0, 0.0, 1.0).force_lateral, -g * ab.powf(1.5) * c.c23) < 1e-12);
    // Loads, axes and friction do not move a force that is zero for every value of theirs.
    let load =
        ContactInput { normal_force: 1.0, creepage_longitudinal: 0.0, ..ContactInput { shear_modulus: 0.0, ..x } };
    let d = ContactInput { semi_axis_a: 0.0, semi_axis_b: 0.0, friction_coefficient: 0.0, poisson_ratio: 0.0, ..load };
    assert_eq!(Polach::default().directional_derivative(&x, &d).unwrap(), CreepForces::default());
}

#[test]
fn spin_derivative_at_zero_spin_is_one_sided() {
    // With η > 0, Φ < 0 keeps s_yC = η (eq. 21) and Φ > 0 makes it η + aΦ: at Φ = 0 the
    // derivative in Φ is the one of the s_yC = η side, i.e. of Φ → 0⁻.
    let model = Polach::default();
    let x = contact(1.07, 0.28, 5e-4, 1e-3, 0.0);
    let d = ContactInput { spin_creepage: 1.0, ..unit_directions(&x)[0].1 };
    let d = ContactInput { creepage_longitudinal: 0.0, ..d };
    let exact = model.directional_derivative(&x, &d).unwrap().force_lateral;
    let at = |phi: f64| model.creep_forces(&ContactInput { spin_creepage: phi, ..x }).unwrap().force_lateral;
    // Second-order one-sided difference from the left: (3 f(0) − 4 f(−t) + f(−2t)) / 2t.
    let t = 1e-4;
    let left = (3.0 * at(0.0) - 4.0 * at(-t) + at(-2.0 * t)) / (2.0 * t);
    let right = (-3.0 * at(0.0) + 4.0 * at(t) - at(2.0 * t)) / (2.0 * t);
    assert!(relative_difference(exact, left) < 1e-6, "{exact} vs left {left}");
    assert!(relative_difference(left, right) > 1e-3, "no kink? left {left}, right {right}");
}

#[test]
fn bad_directions_are_named() {
    let x = contact_case();
    let nan_rate = ContactInput { creepage_lateral: f64::NAN, ..x };
    assert_eq!(Polach::default().directional_derivative(&x, &nan_rate).unwrap_err().variable, "creepage_lateral");
    let poisson_rate = ContactInput { poisson_ratio: 1.0, ..x };
    assert_eq!(Polach::default().directional_derivative(&x, &poisson_rate).unwrap_err().variable, "poisson_ratio");
}

/// The direction of [`unit_directions`] that moves every input but ν.
fn all_inputs_direction(x: &ContactInput) -> ContactInput {
    unit_directions(x).pop().expect("the last direction moves all inputs").1
}

#[test]
fn model_choice_gives_the_chosen_models_own_derivative_bit_for_bit() {
    let x = contact(1.07, 0.28, 2e-3, -1e-3, 0.3);
    let d = all_inputs_direction(&x);
    for choice in all_models() {
        let inner: &dyn CreepForceModel = match &choice {
            ModelChoice::Polach(model) => model,
            ModelChoice::KalkerLinear(model) => model,
            ModelChoice::ShenHedrickElkins(model) => model,
            ModelChoice::Fastsim(model) => model,
            ModelChoice::Exact(model) => model,
            ModelChoice::ExactTable(model) => model,
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
            fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
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
                let d = all_inputs_direction(&x);
                let derivative = outputs(&model.directional_derivative(&x, &d).unwrap());
                // Moves every input by at most 1e-4 of its size: 100 times FASTSIM's own step.
                let sizes = [
                    (x.creepage_longitudinal, d.creepage_longitudinal),
                    (x.creepage_lateral, d.creepage_lateral),
                    (x.spin_creepage, d.spin_creepage),
                    (x.normal_force, d.normal_force),
                ];
                let t = sizes.iter().map(|(value, rate)| 1e-4 * value.abs() / rate.abs()).fold(f64::INFINITY, f64::min);
                let at = |s: f64| outputs(&model.creep_forces(&moved(&x, &d, s)).unwrap());
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

/// The FMU's default scene: Q = 100 kN, a = 7.2 mm, b = 5.4 mm, ξ = 1e-3, G = 82 GPa, ν = 0.28,
/// with friction coefficient `mu`.
fn default_scene(mu: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: 1e-3,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        normal_force: 100e3,
        semi_axis_a: 7.2e-3,
        semi_axis_b: 5.4e-3,
        friction_coefficient: mu,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    }
}

/// One-sided difference (F(x + h·d) − F(x))/h: the forces are 0 at x on the no-force boundary,
/// so there is no cancellation and the error is the curvature's, O(h).
fn one_sided_difference(model: &dyn CreepForceModel, x: &ContactInput, d: &ContactInput, h: f64) -> [f64; 4] {
    let (inside, on) =
        (outputs(&model.creep_forces(&moved(x, d, h)).unwrap()), outputs(&model.creep_forces(x).unwrap()));
    std::array::from_fn(|k| (inside[k] - on[k]) / h)
}

/// Issue 14, item 5: at μ = 0 the derivative in μ is the right-hand one, not 0. Every
/// friction-limited model is in full slip as μ → 0⁺ (the creepage is fixed, the saturating
/// creepage μQ/(G·ab·C) vanishes), so F → −μQ·ξ/s_C and dF_x/dμ = −Q = −1e5 N at the default
/// scene (pure ξ): checked against that limit and against one-sided differences of each model
/// (h = 1e-6: μQ = 0.1 N, 1e-6 of the saturating limit 0.1·G·ab·C11, so the contact is in full
/// slip and the O(h) error is below 1e-9). The exact theory is checked on a 20 × 20 grid.
#[test]
fn at_zero_friction_the_derivative_is_the_right_hand_one() {
    let x = default_scene(0.0);
    let d = ContactInput { friction_coefficient: 1.0, ..NO_RATES };
    let mut models = common::saturating_models();
    models.push(ModelChoice::Exact(ExactTheory::new(20, 20)));
    for model in &models {
        let derivative = model.directional_derivative(&x, &d).unwrap();
        let difference = one_sided_difference(model, &x, &d, 1e-6);
        assert!(
            relative_difference(derivative.force_longitudinal, -1e5) < 1e-6,
            "{}: dF_x/dμ = {} (difference {})",
            model.name(),
            derivative.force_longitudinal,
            difference[0]
        );
        assert!(relative_difference(derivative.force_longitudinal, difference[0]) < 1e-6, "{}", model.name());
        assert!(derivative.force_lateral.abs() < 1e-6 && difference[1].abs() < 1e-6, "{}", model.name());
        // A negative rate gives the negative: the right-hand Jacobian applied to the direction.
        let opposite = ContactInput { friction_coefficient: -1.0, ..NO_RATES };
        assert!(
            relative_difference(model.directional_derivative(&x, &opposite).unwrap().force_longitudinal, 1e5) < 1e-6,
            "{}",
            model.name()
        );
    }
    // Polach away from the boundary, for scale: at μ = 0.3 the contact is in partial slip and
    // dF_x/dμ is well below Q in size.
    let at_default = Polach::default().directional_derivative(&default_scene(0.3), &d).unwrap().force_longitudinal;
    let difference = finite_difference(&Polach::default(), &default_scene(0.3), &d, 1e-4)[0];
    assert!(relative_difference(at_default, difference) < 1e-8, "{at_default} vs {difference}");
    assert!(at_default < 0.0 && at_default > -1e5, "{at_default}");
}

/// Combined creepage and spin at μ = 0 (Polach): F_x → −μQ·ξ/s_C and F_y → −μQ·η/s_C (the spin
/// term K_M vanishes in full slip), with s_C of eqs. (21), (22): ξ = 1e-3, η = −2e-3, aΦ = 7.2e-3
/// · 0.1 = 7.2e-4 does not enlarge |η| (opposite sign), so s_C = √(1e-6 + 4e-6) = 2.236e-3.
#[test]
fn at_zero_friction_with_spin_the_derivative_is_the_full_slip_direction() {
    let x = ContactInput { creepage_lateral: -2e-3, spin_creepage: 0.1, ..default_scene(0.0) };
    let d = ContactInput { friction_coefficient: 1.0, ..NO_RATES };
    let s_c = 5e-6_f64.sqrt();
    let derivative = Polach::default().directional_derivative(&x, &d).unwrap();
    assert!(relative_difference(derivative.force_longitudinal, -1e5 * 1e-3 / s_c) < 1e-9, "{derivative:?}");
    assert!(relative_difference(derivative.force_lateral, 1e5 * 2e-3 / s_c) < 1e-9, "{derivative:?}");
    let difference = one_sided_difference(&Polach::default(), &x, &d, 1e-6);
    assert!(relative_difference(derivative.force_lateral, difference[1]) < 1e-6, "{difference:?}");
}

/// Q → 0⁺ with μ = 0.3: the contact closes in full slip, F → −μQ·ξ/s_C, so dF_x/dQ = −μ = −0.3
/// (the a, b given, as without Hertz). The left side is lift-off (zero force); the derivative
/// given at Q = 0 is the right-hand one, the contact closing.
#[test]
fn at_zero_load_the_derivative_is_the_closing_contacts() {
    let x = ContactInput { normal_force: 0.0, ..default_scene(0.3) };
    let d = ContactInput { normal_force: 1.0, ..NO_RATES };
    for model in common::saturating_models() {
        let derivative = model.directional_derivative(&x, &d).unwrap();
        let difference = one_sided_difference(&model, &x, &d, 1e-2);
        assert!(relative_difference(derivative.force_longitudinal, -0.3) < 1e-6, "{}: {derivative:?}", model.name());
        assert!(relative_difference(difference[0], -0.3) < 1e-6, "{}: {difference:?}", model.name());
    }
    // Lifted off (Q < 0): zero force around, zero derivative.
    let lifted = ContactInput { normal_force: -1.0, ..x };
    assert_eq!(Polach::default().directional_derivative(&lifted, &d).unwrap().force_longitudinal, 0.0);
}

/// Kalker's linear theory ignores friction, so its force jumps at μ = 0 (from 0 to −G·ab·C11·ξ
/// for any μ > 0): there is no one-sided derivative in μ, and the derivative given is that of
/// the zero force the value takes, which is exact in every other input (F ≡ 0 at μ = 0).
#[test]
fn kalker_linear_jumps_at_zero_friction_and_its_derivative_is_the_zero_forces() {
    let x = default_scene(0.0);
    let jump = KalkerLinear.creep_forces(&default_scene(1e-12)).unwrap().force_longitudinal;
    let c11 = KalkerCoefficients::new(7.2 / 5.4, 0.28).c11;
    assert!(relative_difference(jump, -82e9 * 7.2e-3 * 5.4e-3 * c11 * 1e-3) < 1e-12, "{jump}");
    assert_eq!(KalkerLinear.creep_forces(&x).unwrap().force_longitudinal, 0.0);
    let d = ContactInput { creepage_longitudinal: 1.0, friction_coefficient: 1.0, ..NO_RATES };
    assert_eq!(KalkerLinear.directional_derivative(&x, &d).unwrap().force_longitudinal, 0.0);
}

/// The exact theory's derivative (the trait's central difference, inputs moved by 1e-6 of their
/// size) against a fourth-order central difference 100 times wider (inputs moved by ≤ 1e-4), on a
/// 20 × 20 grid at partial-slip points (creepage, spin, both), along every unit direction and
/// all inputs together. Both see the same discretised forces, piecewise smooth (elements switch
/// between adhesion and slip), so they agree as far as the forces are smooth on that scale.
#[test]
fn exact_theory_derivative_agrees_with_finite_differences() {
    let model = ModelChoice::Exact(ExactTheory::new(20, 20));
    let mut worst = (0.0, String::new());
    for (xi, eta, phi) in [(1e-3, 0.0, 0.0), (0.0, -6.25e-4, 0.625), (2e-3, -1e-3, 0.3)] {
        let x = contact(2.0, 0.28, xi, eta, phi);
        for (name, d) in unit_directions(&x) {
            if name == "phi" && phi == 0.0 {
                continue; // Φ = 0 is a kink of the spin's effect: no central difference there
            }
            let derivative = outputs(&model.directional_derivative(&x, &d).unwrap());
            // t moves no input by more than 1e-4 of its size (creepages: of the creepage that
            // saturates the contact, μQ/(G·ab·3), as the model's own difference does).
            let saturation = x.friction_limit() / (x.shear_modulus * x.semi_axis_a * x.semi_axis_b * 3.0);
            let t = [
                (x.creepage_longitudinal.abs().max(saturation), d.creepage_longitudinal),
                (x.creepage_lateral.abs().max(saturation), d.creepage_lateral),
                (x.spin_creepage.abs().max(saturation / x.semi_axis_a), d.spin_creepage),
                (x.normal_force, d.normal_force),
                (x.semi_axis_a, d.semi_axis_a),
                (x.semi_axis_b, d.semi_axis_b),
                (x.friction_coefficient, d.friction_coefficient),
                (x.shear_modulus, d.shear_modulus),
            ]
            .iter()
            .filter(|(_, rate)| *rate != 0.0)
            .map(|(size, rate)| 1e-4 * size / rate.abs())
            .fold(f64::INFINITY, f64::min);
            let wide = finite_difference(&model, &x, &d, t);
            // The force's rate as a vector (a cross term such as dF_y/dξ is measured against
            // the whole force rate: it is where elements switching between adhesion and slip
            // within the wider step show most), the utilisation and M_z each on their own scale,
            // with a floor of 1e-3 of the natural rate (inputs move by 1e-3 of their size per
            // unit: 1e-3·μQ, 1e-3, 1e-3·μQ·a) for rates that vanish by symmetry.
            let limit = x.friction_limit();
            let force_rate = derivative[0].hypot(derivative[1]).max(1e-6 * limit);
            let force_difference = (derivative[0] - wide[0]).hypot(derivative[1] - wide[1]) / force_rate;
            let utilisation_difference = (derivative[2] - wide[2]).abs() / derivative[2].abs().max(1e-6);
            let moment_scale = derivative[3].abs().max(1e-6 * limit * x.semi_axis_a);
            let moment_difference = (derivative[3] - wide[3]).abs() / moment_scale;
            for (output, difference) in
                [("F", force_difference), ("|F|/μQ", utilisation_difference), ("M_z", moment_difference)]
            {
                if difference > worst.0 {
                    worst = (
                        difference,
                        format!("({xi}, {eta}, {phi}) along {name}, {output}: {derivative:?} vs {wide:?}"),
                    );
                }
            }
        }
    }
    eprintln!("exact theory: worst relative difference {:.2e} at {}", worst.0, worst.1);
    // Measured worst: 6.5e-3 (M_z along ξ without spin, a rate that vanishes by symmetry: the
    // solver's noise at the floor); the force vectors agree to 2.4e-6.
    assert!(worst.0 < 2e-2, "worst relative difference {:.2e} at {}", worst.0, worst.1);
}

/// On the no-force boundary at extreme scales (the depth μQ of the one-sided difference can
/// underflow) every derivative stays finite.
#[test]
fn at_zero_friction_extreme_scales_give_finite_derivatives() {
    let d = ContactInput { friction_coefficient: 1.0, normal_force: 1.0, creepage_longitudinal: 1.0, ..NO_RATES };
    for (q, xi) in [(1e300, 1e-300), (1e-300, 1e300), (0.0, 1e-300), (1e300, 0.0)] {
        let x = ContactInput { normal_force: q, creepage_longitudinal: xi, ..default_scene(0.0) };
        for model in common::all_models() {
            let derivative = model.directional_derivative(&x, &d).unwrap();
            let values = outputs(&derivative);
            assert!(values.iter().all(|v| v.is_finite()), "{} at Q = {q}, ξ = {xi}: {derivative:?}", model.name());
        }
    }
}

/// A model that records where it is evaluated (its forces are zero).
struct Recorder(std::cell::RefCell<Vec<ContactInput>>);

impl CreepForceModel for Recorder {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        self.0.borrow_mut().push(*input);
        Ok(CreepForces { spin_moment: Some(0.0), ..CreepForces::default() })
    }
}

/// `central_difference` steps as its documentation says: by 1e-6 of the larger of the input's
/// own size, the saturation creepage μQ/(G·ab·3) (the spin's over a) and 1e-3 of the resultant
/// creepage |ξ| + |η| + a|φ| (the spin's over a), at x ± t·d.
#[test]
fn the_central_difference_steps_as_documented() {
    let x = ContactInput { creepage_longitudinal: 0.0, creepage_lateral: 0.0, spin_creepage: 0.0, ..contact_case() };
    let (a, b) = (x.semi_axis_a, x.semi_axis_b);
    let saturation = x.friction_coefficient * x.normal_force / (x.shear_modulus * a * b * 3.0);
    let along_xi = ContactInput { creepage_longitudinal: 1.0, ..NO_RATES };
    let along_spin = ContactInput { spin_creepage: 2.0, ..NO_RATES };
    // (The own-size case, 0.02, lies above it too.)
    assert!(1e-3 * 10.0 > saturation);
    for (at, direction, known, step) in [
        // At rest: the saturation creepage, and for spin that over a.
        (x, along_xi, 0, 1e-6 * saturation),
        (x, along_spin, 2, 1e-6 * saturation / a / 2.0),
        // A creepage of its own: its size.
        (ContactInput { creepage_longitudinal: -0.02, ..x }, along_xi, 0, 1e-6 * 0.02),
        // Zero beside large ones (beyond 1e3 saturation creepages): 1e-3 of the resultant (for
        // spin, over a).
        (ContactInput { creepage_lateral: 10.0, ..x }, along_xi, 0, 1e-9 * 10.0),
        (
            ContactInput { creepage_longitudinal: 5.0, creepage_lateral: 10.0, ..x },
            along_spin,
            2,
            1e-9 * 15.0 / a / 2.0,
        ),
    ] {
        let recorder = Recorder(Default::default());
        wheel_rail_contact::central_difference(&recorder, &at, &direction).unwrap();
        let points = recorder.0.into_inner();
        let value = |p: &ContactInput| [p.creepage_longitudinal, p.creepage_lateral, p.spin_creepage][known];
        let moved: Vec<f64> = points.iter().map(|p| value(p) - value(&at)).collect();
        let rate = [direction.creepage_longitudinal, direction.creepage_lateral, direction.spin_creepage][known];
        assert_eq!(moved.len(), 2, "{at:?}");
        for (moved, sign) in moved.iter().zip([1.0, -1.0]) {
            let expected = sign * step * rate;
            assert!(
                (moved - expected).abs() <= 1e-9 * expected.abs(),
                "{at:?}: moved {moved:e}, expected {expected:e}"
            );
        }
    }
}
