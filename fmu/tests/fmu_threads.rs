//! Eight threads, each with its own instance, run the same scene through the C ABI and get
//! bit-identical outputs to a single-threaded run: the FMU has no global mutable state, and an
//! instance's results depend only on its own calls. Each thread also rolls back through an FMU
//! state halfway, so the state functions run concurrently too.

mod c_abi;

use c_abi::{bits, run_scene, Fmu, OK};

const STEPS: usize = 2_000;
const STEP: f64 = 1e-3;
const THREADS: usize = 8;

/// The scene's outputs for every step, with a detour: at step STEPS/2 the run takes a state,
/// runs 50 steps, restores the state and continues, so the outputs must still be the plain run's.
fn run(name: &str) -> Vec<[u64; 3]> {
    let fmu = Fmu::stepping(name, 0.0);
    let half = STEPS / 2;
    let mut outputs = run_scene(&fmu, 0, half, 0.0, STEP);
    let state = fmu.get_state();
    run_scene(&fmu, half, 50, half as f64 * STEP, STEP);
    assert_eq!(fmu.set_state(state), OK);
    fmu.free_state(state);
    outputs.extend(run_scene(&fmu, half, STEPS - half, half as f64 * STEP, STEP));
    bits(&outputs)
}

#[test]
fn eight_threads_with_their_own_instances_match_a_single_threaded_run_bit_for_bit() {
    let reference = run("single thread");
    let results: Vec<Vec<[u64; 3]>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..THREADS).map(|k| scope.spawn(move || run(&format!("thread {k}")))).collect();
        handles.into_iter().map(|h| h.join().expect("no thread panics")).collect()
    });
    for (k, result) in results.iter().enumerate() {
        assert_eq!(result.len(), STEPS);
        assert!(result == &reference, "thread {k} differs from the single-threaded run");
    }
    // The scene exercises the model: lift-off zeros and saturated forces both occur.
    assert!(reference.iter().any(|row| row[0] == 0.0f64.to_bits()));
    assert!(reference.iter().map(|row| f64::from_bits(row[2])).any(|u| u > 0.9));
}
