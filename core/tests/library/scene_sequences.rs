//! Sequences of evaluations through the scene pipeline (the FMU's steps), for every rung with
//! every option: random jumps, ramps, drops of μ and Q, lift-offs and reloads, random step sizes,
//! the state saved and restored at a random step. At every step every output is finite and the
//! force within the friction limit μQ of that step's μ and Q (Kalker's linear theory, which has
//! none, excepted); a run restored from a saved state repeats the uninterrupted run bit for bit.

use crate::common;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use wheel_rail_contact::scene::{
    CreepageSource, EllipseSource, Evaluation, Relaxation, Scene, SceneCache, SceneInput, SceneOutput, SceneState,
    TractionLaw,
};
use wheel_rail_contact::{ExactTheory, KalkerLinear, ModelChoice, Polach, Polach2005};

const G: f64 = 82e9;
const NU: f64 = 0.28;
const RADIUS: f64 = 0.46;

/// The rungs: every saturating model (FASTSIM on a coarse grid), the exact theory on a small
/// grid (it warm-starts from step to step like any grid), and Kalker's linear theory.
fn models() -> Vec<ModelChoice> {
    let mut models = common::saturating_models();
    models.push(ModelChoice::Fastsim(common::fastsim(8, wheel_rail_contact::TractionBound::Parabolic)));
    models.push(ModelChoice::Exact(ExactTheory::new(12, 10)));
    models.push(ModelChoice::KalkerLinear(KalkerLinear));
    models
}

/// The scene of `model` with the options of `options`' bits: 1 relaxation (length from the
/// contact, or 5 mm), 2 creepages from kinematics, 4 Hertz's ellipse, 8 Polach 2005 (Polach
/// only).
fn scene(model: ModelChoice, options: u8) -> Scene {
    Scene {
        creepages: if options & 2 != 0 {
            CreepageSource::Kinematics { regularisation_speed: 0.01 }
        } else {
            CreepageSource::Inputs
        },
        ellipse: if options & 4 != 0 {
            EllipseSource::Hertz { wheel_profile_curvature: 0.0, rail_profile_curvature: 1.0 / 0.3 }
        } else {
            EllipseSource::Inputs
        },
        traction_law: if options & 8 != 0 && matches!(model, ModelChoice::Polach(_)) {
            TractionLaw::Polach2005(Polach2005::DRY)
        } else {
            TractionLaw::Coulomb
        },
        relaxation: match options & 17 {
            1 => Relaxation::On { length: 0.0 },
            17 => Relaxation::On { length: 5e-3 },
            _ => Relaxation::Off,
        },
        ..Scene::of_model(model, G, NU)
    }
}

/// One change of the inputs between steps.
#[derive(Debug, Clone, Copy)]
enum Change {
    /// Every creepage, speed and the ellipse anew.
    Jump { xi: f64, eta: f64, phi: f64, speed: f64, a_over_b: f64 },
    /// The creepages a little further.
    Ramp(f64),
    /// μ times this factor (< 1).
    FrictionDrop(f64),
    /// Q times this factor (< 1).
    LoadDrop(f64),
    /// Q ≤ 0.
    LiftOff(f64),
    /// Q back to this value.
    Reload(f64),
}

fn creepage() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), -2e-2..2e-2, -1e-4..1e-4]
}

fn change() -> impl Strategy<Value = Change> {
    prop_oneof![
        (
            creepage(),
            creepage(),
            prop_oneof![Just(0.0), -2.0..2.0],
            prop_oneof![-40.0..-0.5, 0.5..40.0, Just(0.0)],
            0.3..3.0
        )
            .prop_map(|(xi, eta, phi, speed, a_over_b)| Change::Jump { xi, eta, phi, speed, a_over_b }),
        (-1e-3..1e-3).prop_map(Change::Ramp),
        (0.05..0.9).prop_map(Change::FrictionDrop),
        (0.02..0.9).prop_map(Change::LoadDrop),
        prop_oneof![Just(0.0), Just(-1.0)].prop_map(Change::LiftOff),
        (1e3..150e3).prop_map(Change::Reload),
    ]
}

fn apply(change: Change, input: &mut SceneInput) {
    match change {
        Change::Jump { xi, eta, phi, speed, a_over_b } => {
            let area = 40e-6;
            input.semi_axis_b = (area / a_over_b).sqrt();
            input.semi_axis_a = a_over_b * input.semi_axis_b;
            (input.creepage_longitudinal, input.creepage_lateral, input.spin_creepage) = (xi, eta, phi);
            input.rolling_speed = speed;
            // The wheel's velocities that give these creepages at this speed.
            input.wheel_angular_speed = speed * (1.0 + xi) / RADIUS;
            input.lateral_slip_velocity = eta * speed;
            input.spin_angular_velocity = phi * speed;
        }
        Change::Ramp(delta) => {
            input.creepage_longitudinal += delta;
            input.creepage_lateral -= 0.5 * delta;
            input.wheel_angular_speed += delta * input.rolling_speed / RADIUS;
            input.lateral_slip_velocity -= 0.5 * delta * input.rolling_speed;
        }
        Change::FrictionDrop(factor) => input.friction_coefficient *= factor,
        Change::LoadDrop(factor) => input.normal_force *= factor,
        Change::LiftOff(load) => input.normal_force = load,
        Change::Reload(load) => input.normal_force = load,
    }
}

fn start() -> SceneInput {
    SceneInput {
        creepage_longitudinal: 2e-3,
        normal_force: 100e3,
        semi_axis_a: 7.2e-3,
        semi_axis_b: 5.4e-3,
        friction_coefficient: 0.4,
        rolling_speed: 20.0,
        wheel_angular_speed: 20.0 * 1.002 / RADIUS,
        wheel_rolling_radius: RADIUS,
        ..SceneInput::default()
    }
}

/// The outputs after each of `steps` from `state`, and the state after the last.
fn run(
    scene: &Scene,
    inputs: &[SceneInput],
    steps: &[f64],
    mut state: SceneState,
    cache: &mut SceneCache,
) -> (Vec<SceneOutput>, SceneState) {
    let outputs = inputs
        .iter()
        .zip(steps)
        .map(|(input, &step)| {
            let output;
            (output, state) = scene.evaluate(input, &state, cache, Evaluation::Step(step)).unwrap();
            output
        })
        .collect();
    (outputs, state)
}

fn bits(outputs: &[SceneOutput]) -> Vec<[u64; 13]> {
    outputs.iter().map(|o| common::scene_outputs(o).map(f64::to_bits)).collect()
}

fn check_step(model: &ModelChoice, input: &SceneInput, output: &SceneOutput) -> Result<(), TestCaseError> {
    let values = bits(std::slice::from_ref(output))[0].map(f64::from_bits);
    prop_assert!(values.iter().all(|v| v.is_finite()), "non-finite output {output:?}");
    if matches!(model, ModelChoice::KalkerLinear(_)) {
        return Ok(());
    }
    let limit = output.current_friction_coefficient * input.normal_force.max(0.0);
    let magnitude = output.force_longitudinal.hypot(output.force_lateral);
    prop_assert!(magnitude <= limit * (1.0 + 1e-9) + 1e-9, "|F| = {magnitude} > μQ = {limit}: {output:?}");
    prop_assert!(output.adhesion_utilisation <= 1.0 + 1e-9, "{output:?}");
    Ok(())
}

/// The property for one rung and option set, over `cases` random sequences.
fn sequences_hold(model: ModelChoice, options: u8, cases: u32) {
    let scene = scene(model, options);
    let config = Config { cases, failure_persistence: None, ..Config::default() };
    // A fixed seed per rung and option set: CI runs the same sequences every time.
    let seed = [(model.name().len() as u8).wrapping_mul(16).wrapping_add(options); 32];
    let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &seed));
    let strategy = (prop::collection::vec((change(), 1e-5..1e-2), 4..24), any::<prop::sample::Index>());
    runner
        .run(&strategy, |(changes, save_at)| {
            let mut input = start();
            let mut inputs = Vec::new();
            let mut steps = Vec::new();
            for (change, step) in &changes {
                apply(*change, &mut input);
                inputs.push(input);
                steps.push(*step);
            }
            let mut cache = SceneCache::default();
            let (_, initial) =
                scene.evaluate(&start(), &SceneState::default(), &mut cache, Evaluation::Initialise).unwrap();
            let (outputs, _) = run(&scene, &inputs, &steps, initial.clone(), &mut cache);
            for (input, output) in inputs.iter().zip(&outputs) {
                check_step(&model, input, output)?;
            }
            // Saved after step k, restored into a fresh cache: the rest repeats bit for bit.
            let k = save_at.index(inputs.len());
            let (_, saved) = run(&scene, &inputs[..k], &steps[..k], initial, &mut SceneCache::default());
            let (restored, _) = run(&scene, &inputs[k..], &steps[k..], saved, &mut SceneCache::default());
            prop_assert_eq!(bits(&restored), bits(&outputs[k..]), "restored after step {}", k);
            Ok(())
        })
        .unwrap_or_else(|failure| panic!("{} with options {options:#06b}: {failure}", model.name()));
}

#[test]
fn every_rung_with_every_option_keeps_its_invariants_over_random_sequences() {
    for model in models() {
        let cases = if matches!(model, ModelChoice::Exact(_)) { 4 } else { 12 };
        for options in [0, 1, 2, 3, 4, 5, 6, 7, 17, 23] {
            sequences_hold(model, options, cases);
        }
    }
    for options in [8, 9, 11, 15, 31] {
        sequences_hold(ModelChoice::Polach(Polach::default()), options, 24);
    }
}

/// Kalker's linear theory has no friction limit: with relaxation its force relaxes to its own
/// steady state even where that exceeds μQ (the friction limit of the relaxed force applies to
/// the friction-limited models only).
#[test]
fn the_linear_theory_relaxes_to_its_steady_state_beyond_mu_q() {
    let scene = scene(ModelChoice::KalkerLinear(KalkerLinear), 1);
    let input = SceneInput { creepage_longitudinal: 2e-2, ..start() };
    let mut cache = SceneCache::default();
    let steady = Scene { relaxation: Relaxation::Off, ..scene }
        .evaluate(&input, &SceneState::default(), &mut cache, Evaluation::Initialise)
        .unwrap()
        .0;
    assert!(steady.force_longitudinal.abs() > 5.0 * 0.4 * 100e3, "{steady:?}");
    // From rest at zero force, 1 s at 20 m/s: thousands of relaxation lengths.
    let (output, _) = scene.evaluate(&input, &SceneState::default(), &mut cache, Evaluation::Step(1.0)).unwrap();
    assert_eq!(output.force_longitudinal, steady.force_longitudinal);
}
