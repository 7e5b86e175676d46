//! Eight threads, each with its own instance, run the same scene through the C ABI and get
//! bit-identical outputs to a single-threaded run: the FMU has no global mutable state, and an
//! instance's results depend only on its own calls. Each thread also rolls back through an FMU
//! state halfway, so the state functions run concurrently too. Creep relaxation is on, so the
//! outputs depend on the instance's internal state (the relaxed forces) as well as on the
//! inputs, and the reference is a run without the detour: a roll-back that lost or ignored the
//! relaxed forces would show.

use fmu_test_master::{bits, run_scene, Fmu, OK};
use wheel_rail_contact_fmu::ffi::{fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2SetupExperiment};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Switch};

const STEPS: usize = 2_000;
const STEP: f64 = 1e-3;
const THREADS: usize = 8;

/// An instance in step mode with creep relaxation on over 0.02 m: at the scene's default
/// rolling speed of 20 m/s that is τ = 1 ms, one step, so every step carries a transient.
fn relaxing(name: &str) -> Fmu {
    let fmu = Fmu::instantiate(name, None);
    assert_eq!(fmu.set_integer(&[vr::CREEP_RELAXATION], &[Switch::On as i32]), OK);
    assert_eq!(fmu.set_real(&[vr::RELAXATION_LENGTH], &[0.02]), OK);
    // SAFETY: live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
    fmu
}

/// The scene's outputs for every step; with `detour`, at step STEPS/2 the run takes a state,
/// runs 50 steps, restores the state and continues, so the outputs must still be the plain run's.
fn run(name: &str, detour: bool) -> Vec<[u64; 3]> {
    let fmu = relaxing(name);
    let half = STEPS / 2;
    let mut outputs = run_scene(&fmu, 0, half, 0.0, STEP);
    if detour {
        let state = fmu.get_state();
        run_scene(&fmu, half, 50, half as f64 * STEP, STEP);
        assert_eq!(fmu.set_state(state), OK);
        fmu.free_state(state);
    }
    outputs.extend(run_scene(&fmu, half, STEPS - half, half as f64 * STEP, STEP));
    bits(&outputs)
}

#[test]
fn eight_threads_with_their_own_instances_match_a_single_threaded_run_bit_for_bit() {
    let reference = run("single thread", false);
    let results: Vec<Vec<[u64; 3]>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..THREADS).map(|k| scope.spawn(move || run(&format!("thread {k}"), true))).collect();
        handles.into_iter().map(|h| h.join().expect("no thread panics")).collect()
    });
    for (k, result) in results.iter().enumerate() {
        assert_eq!(result.len(), STEPS);
        assert!(result == &reference, "thread {k} differs from the single-threaded run");
    }
    // The relaxation shapes the outputs: without it the same scene gives other forces.
    let unrelaxed = Fmu::stepping("unrelaxed", 0.0);
    let unrelaxed = bits(&run_scene(&unrelaxed, 0, STEPS, 0.0, STEP));
    let differing = reference.iter().zip(&unrelaxed).filter(|(relaxed, plain)| relaxed[0] != plain[0]).count();
    assert!(differing > STEPS / 2, "only {differing} steps differ");
    // The scene exercises the model: lift-off zeros and saturated forces both occur.
    assert!(reference.iter().any(|row| row[0] == 0.0f64.to_bits()));
    assert!(reference.iter().map(|row| f64::from_bits(row[2])).any(|u| u > 0.9));
}
