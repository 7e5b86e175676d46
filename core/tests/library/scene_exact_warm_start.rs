//! The scene evaluates the exact theory from the previous step's tractions (a warm start): each
//! step's forces equal a cold solve of the same inputs within the solver's tolerance, through a
//! slowly varying co-simulation and across a jump that a poor start makes (other creepage sign,
//! other ellipse, lift-off and back).

use wheel_rail_contact::scene::{Evaluation, Scene, SceneCache, SceneInput, SceneState};
use wheel_rail_contact::{CreepForceModel, ExactTheory, ModelChoice};

fn input(xi: f64, eta: f64, spin: f64, normal_force: f64, semi_axis_a: f64) -> SceneInput {
    SceneInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: spin,
        normal_force,
        semi_axis_a,
        semi_axis_b: 5.4e-3,
        friction_coefficient: 0.3,
        rolling_speed: 20.0,
        ..SceneInput::default()
    }
}

#[test]
fn warm_started_steps_equal_cold_solves() {
    let exact = ExactTheory::new(32, 32);
    let scene = Scene::of_model(ModelChoice::Exact(exact), 82e9, 0.28);
    let (mut state, mut cache) = (SceneState::default(), SceneCache::default());
    let mut cases: Vec<SceneInput> =
        (0..12).map(|k| input(4e-4 + 1e-4 * k as f64, -2e-4, 0.3 + 0.02 * k as f64, 100e3, 7.2e-3)).collect();
    // Poor starts: the creepage reversed, another ellipse, lift-off, and back.
    cases.extend([
        input(-1.2e-3, 3e-4, -0.5, 100e3, 7.2e-3),
        input(-1.2e-3, 3e-4, -0.5, 60e3, 4.0e-3),
        input(1e-3, 0.0, 0.0, -1.0, 7.2e-3),
        input(1e-3, 0.0, 0.0, 100e3, 7.2e-3),
    ]);
    for (k, case) in cases.iter().enumerate() {
        let warm;
        (warm, state) = scene.evaluate(case, &state, &mut cache, Evaluation::Step(1e-3)).unwrap();
        let cold = exact.creep_forces(&scene.contact_input(case)).unwrap();
        let limit = 0.3 * case.normal_force.max(0.0);
        for (warm, cold) in
            [(warm.force_longitudinal, cold.force_longitudinal), (warm.force_lateral, cold.force_lateral)]
        {
            assert!((warm - cold).abs() <= 1e-6 * limit.max(1.0), "case {k}: warm {warm}, cold {cold}");
        }
        assert!((warm.spin_moment - cold.spin_moment.unwrap()).abs() <= 1e-6 * limit * 7.2e-3 + 1e-9, "case {k}");
    }
}
