//! The integration against closed forms: the suspended wheelset's free lateral and yaw
//! oscillations (a damped linear oscillator), its static deflection under a held load, the spin
//! under a constant axle moment, and the free wheelset's uniformly accelerated motion.

use super::*;
use approx::assert_relative_eq;

/// The cited passenger-coach wheelset (data/wheelset/passenger_coach.toml) at 30 m/s.
fn coach() -> Parameters {
    Parameters {
        mass: 1813.0,
        yaw_inertia: 1120.0,
        spin_inertia: 112.0,
        longitudinal_stiffness: 31.391e6,
        longitudinal_damping: 15.0e3,
        lateral_stiffness: 3.884e6,
        lateral_damping: 2.0e3,
        lateral_semi_spacing: 1.0,
        forward_speed: 30.0,
        derailment_displacement: 0.01,
    }
}

/// x(t) of ẍ + c ẋ + k x = 0 from x(0) = x0, ẋ(0) = 0, underdamped (c² < 4k).
fn damped_oscillation(k: f64, c: f64, x0: f64, t: f64) -> f64 {
    let decay = c / 2.0;
    let omega_d = (k - decay * decay).sqrt();
    (-decay * t).exp() * x0 * ((omega_d * t).cos() + decay / omega_d * (omega_d * t).sin())
}

/// `steps` communication steps of `step` from `start` without loads: the state after each.
fn run(parameters: &Parameters, start: State, step: f64, steps: usize) -> Vec<State> {
    let mut state = start;
    (0..steps)
        .map(|_| {
            state = advance(parameters, &state, &Loads::default(), step).unwrap();
            state
        })
        .collect()
}

/// The free lateral oscillation: ω² = 2 k_y/m, damping 2 c_y/m (ω = 65.5 rad/s, ζ = 1.7 %).
#[test]
fn lateral_oscillation_matches_the_damped_oscillator() {
    let p = coach();
    let (k, c) = (2.0 * p.lateral_stiffness / p.mass, 2.0 * p.lateral_damping / p.mass);
    let y0 = 2e-3;
    let start = State { lateral_displacement: y0, ..State::rolling(30.0, 0.46) };
    for (step, steps, tolerance) in [(1e-3, 200, 1e-6), (0.05, 4, 1e-4)] {
        for (i, state) in run(&p, start, step, steps).iter().enumerate() {
            let t = step * (i + 1) as f64;
            let expected = damped_oscillation(k, c, y0, t);
            assert!((state.lateral_displacement - expected).abs() < tolerance * y0, "h = {step}, t = {t}");
            assert_eq!((state.yaw_angle, state.yaw_rate), (0.0, 0.0));
            assert_eq!(state.wheel_angular_speed, 30.0 / 0.46);
        }
    }
    // The frequency itself, √(2 k_y/m), as the closed form above takes it.
    assert_relative_eq!(k.sqrt(), 65.4566, max_relative = 1e-5);
}

/// The free yaw oscillation: ω² = 2 k_x b₁²/I (237 rad/s), damping 2 c_x b₁²/I (ζ = 5.7 %).
#[test]
fn yaw_oscillation_matches_the_damped_oscillator() {
    let p = coach();
    let arm = p.lateral_semi_spacing * p.lateral_semi_spacing;
    let (k, c) =
        (2.0 * p.longitudinal_stiffness * arm / p.yaw_inertia, 2.0 * p.longitudinal_damping * arm / p.yaw_inertia);
    let psi0 = 1e-3;
    let start = State { yaw_angle: psi0, ..State::default() };
    for (step, steps, tolerance) in [(2e-4, 500, 1e-6), (0.02, 5, 1e-4)] {
        for (i, state) in run(&p, start, step, steps).iter().enumerate() {
            let t = step * (i + 1) as f64;
            assert!(
                (state.yaw_angle - damped_oscillation(k, c, psi0, t)).abs() < tolerance * psi0,
                "h = {step}, t = {t}"
            );
            assert_eq!(state.lateral_displacement, 0.0);
        }
    }
    assert_relative_eq!(k.sqrt(), 236.74, max_relative = 1e-4);
}

/// A held lateral force and yaw moment deflect the suspension statically: y → F/(2 k_y),
/// ψ → M/(2 k_x b₁²), in the forces' directions.
#[test]
fn held_loads_deflect_the_suspension_statically() {
    let p = coach();
    let loads = Loads { lateral_force: 10e3, yaw_moment: -20e3, axle_moment: 0.0 };
    let mut state = State::default();
    for _ in 0..200 {
        state = advance(&p, &state, &loads, 0.1).unwrap();
    }
    assert_relative_eq!(state.lateral_displacement, 10e3 / (2.0 * p.lateral_stiffness), max_relative = 1e-9);
    assert_relative_eq!(state.yaw_angle, -20e3 / (2.0 * p.longitudinal_stiffness), max_relative = 1e-9);
}

/// A constant moment about the axle: Ω̇ = −M_y/I_s, exactly (M_y < 0, a braking creep force at the
/// contact, spins the wheels up).
#[test]
fn an_axle_moment_changes_the_spin_at_its_rate() {
    let p = coach();
    let loads = Loads { axle_moment: -560.0, ..Loads::default() };
    let start = State::rolling(30.0, 0.46);
    let after = advance(&p, &start, &loads, 0.25).unwrap();
    // Exact but for rounding over the 330 substeps the yaw mode sets.
    assert_relative_eq!(after.wheel_angular_speed, 30.0 / 0.46 + 560.0 / 112.0 * 0.25, max_relative = 1e-13);
}

/// Without suspension (the Klingel variant) the wheelset moves freely: a held force gives
/// y = F t²/(2m) exactly, in one substep whatever the step.
#[test]
fn the_free_wheelset_accelerates_uniformly() {
    let p = Parameters {
        longitudinal_stiffness: 0.0,
        longitudinal_damping: 0.0,
        lateral_stiffness: 0.0,
        lateral_damping: 0.0,
        ..coach()
    };
    assert_eq!(p.fastest_rate(), 0.0);
    let loads = Loads { lateral_force: 90.65, yaw_moment: 11.2, axle_moment: 0.0 };
    let after = advance(&p, &State::default(), &loads, 0.4).unwrap();
    assert_relative_eq!(after.lateral_displacement, 90.65 / 1813.0 * 0.4 * 0.4 / 2.0, max_relative = 1e-14);
    assert_relative_eq!(after.lateral_velocity, 90.65 / 1813.0 * 0.4, max_relative = 1e-14);
    assert_relative_eq!(after.yaw_angle, 11.2 / 1120.0 * 0.4 * 0.4 / 2.0, max_relative = 1e-14);
}

/// The substep follows the fastest mode: the yaw mode's ρ = ω + 2ζω of the cited suspension.
#[test]
fn the_substep_bound_is_the_fastest_modes_rate() {
    let p = coach();
    let yaw = (2.0 * p.longitudinal_stiffness / p.yaw_inertia).sqrt() + 2.0 * p.longitudinal_damping / p.yaw_inertia;
    assert_relative_eq!(p.fastest_rate(), yaw, max_relative = 1e-15);
    // An overdamped oscillator is bounded by its damping rate.
    let overdamped = Parameters { lateral_damping: 1e7, ..coach() };
    assert_relative_eq!(overdamped.fastest_rate(), 2e7 / 1813.0 + (2.0 * 3.884e6 / 1813.0_f64).sqrt());
    // The springs' lever arm b1 enters the yaw mode squared (k_ψ = 2 k_x b1², c_ψ = 2 c_x b1²):
    // at b1 = 0.8 m, ω = √(2 · 31.391e6 · 0.64 / 1120) = 189.4 rad/s, 2ζω = 17.1 1/s.
    let narrow = Parameters { lateral_semi_spacing: 0.8, ..coach() };
    let yaw = (2.0 * 31.391e6 * 0.64 / 1120.0_f64).sqrt() + 2.0 * 15e3 * 0.64 / 1120.0;
    assert_relative_eq!(narrow.fastest_rate(), yaw, max_relative = 1e-15);
    assert_relative_eq!(yaw, 206.55, max_relative = 1e-4);
    // A soft yaw spring: the lateral mode, √(2 k_y/m) + 2 c_y/m, is the fastest.
    let soft_yaw = Parameters { longitudinal_stiffness: 1e3, longitudinal_damping: 0.0, ..coach() };
    let lateral = (2.0 * 3.884e6 / 1813.0_f64).sqrt() + 2.0 * 2e3 / 1813.0;
    assert_relative_eq!(soft_yaw.fastest_rate(), lateral, max_relative = 1e-15);
}

#[test]
fn errors_name_the_parameter_and_value() {
    let cases = [
        (Parameters { mass: -1.0, ..coach() }, "mass = -1 is invalid: must be finite and > 0"),
        (Parameters { spin_inertia: 0.0, ..coach() }, "spin_inertia = 0 is invalid: must be finite and > 0"),
        (
            Parameters { lateral_stiffness: -1.0, ..coach() },
            "lateral_stiffness = -1 is invalid: must be finite and >= 0",
        ),
        (
            Parameters { lateral_damping: f64::NAN, ..coach() },
            "lateral_damping = NaN is invalid: must be finite and >= 0",
        ),
        (Parameters { forward_speed: f64::INFINITY, ..coach() }, "forward_speed = inf is invalid: must be finite"),
        (
            Parameters { lateral_damping: f64::INFINITY, ..coach() },
            "lateral_damping = inf is invalid: must be finite and >= 0",
        ),
    ];
    for (parameters, message) in cases {
        let error = advance(&parameters, &State::default(), &Loads::default(), 1e-3).unwrap_err();
        assert_eq!(error.to_string(), message);
    }
    for (step, shown) in [(f64::NAN, "NaN"), (f64::INFINITY, "inf"), (-1e-3, "-0.001")] {
        let error = advance(&coach(), &State::default(), &Loads::default(), step).unwrap_err();
        assert_eq!(error.to_string(), format!("communicationStepSize = {shown} s is invalid: must be finite and >= 0"));
    }
    let error = advance(&coach(), &State::default(), &Loads::default(), 1e6).unwrap_err();
    assert!(matches!(error, WheelsetError::StepTooLong { .. }), "{error}");
    let nan = Loads { yaw_moment: f64::NAN, ..Loads::default() };
    assert!(matches!(advance(&coach(), &State::default(), &nan, 1e-3), Err(WheelsetError::NotFinite { .. })));
}

/// A free wheelset at rest exactly on the derailment bound stays there, within the bound (as an
/// initial displacement on it is, `model.rs`).
#[test]
fn a_wheelset_resting_on_the_bound_is_within_it() {
    let free = Parameters { lateral_stiffness: 0.0, lateral_damping: 0.0, ..coach() };
    let start = State { lateral_displacement: -0.01, ..State::rolling(30.0, 0.46) };
    let after = advance(&free, &start, &Loads::default(), 1e-3).unwrap();
    assert_eq!(after.lateral_displacement, -0.01);
}

/// A lateral force beyond what the suspension holds within the bound derails the wheelset.
#[test]
fn a_wheelset_pushed_beyond_the_bound_derails() {
    let p = coach();
    // Static deflection 20 mm > 10 mm: the bound is crossed within the first half period.
    let loads = Loads { lateral_force: 2.0 * p.lateral_stiffness * 0.02, ..Loads::default() };
    let mut state = State::default();
    let error = (0..100).find_map(|_| match advance(&p, &state, &loads, 1e-3) {
        Ok(next) => {
            state = next;
            None
        }
        Err(error) => Some(error),
    });
    let Some(WheelsetError::Derailed { lateral_displacement, limit }) = error else { panic!("{error:?}") };
    // Detected at the end of the step that crosses it: y(t) = 0.02 (1 − cos ωt) crosses 10 mm at
    // 1.13 m/s, so within 1.13 mm past the bound with 1 ms steps.
    let speed = 0.02 * (2.0 * p.lateral_stiffness / p.mass).sqrt() * (60f64).to_radians().sin();
    assert!(lateral_displacement > 0.01 && lateral_displacement < 0.01 + speed * 1e-3, "{lateral_displacement}");
    assert_eq!(limit, 0.01);
}
