//! FMU state through the C ABI: rolled-back runs repeat bit for bit, serialised states continue
//! bit for bit in a fresh instance, and damaged byte strings are rejected without effect.

mod c_abi;

use c_abi::{bits, run_scene, Fmu, ERROR, OK, OUTPUTS};
use wheel_rail_contact_fmu::ffi::{fmi2GetFMUstate, fmi2Terminate};
use wheel_rail_contact_fmu::fmi2::fmi2FMUstate;

const STEP: f64 = 1e-3;

/// A run 250 steps in, where the creepage ramp is well into partial slip.
fn mid_run() -> Fmu {
    let fmu = Fmu::stepping("rolled back", 0.0);
    run_scene(&fmu, 0, 250, 0.0, STEP);
    fmu
}

#[test]
fn get_state_run_100_steps_set_state_run_again_is_bit_identical() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let time = 250.0 * STEP;
    let first = run_scene(&fmu, 250, 100, time, STEP);
    assert_eq!(fmu.set_state(state), OK);
    let second = run_scene(&fmu, 250, 100, time, STEP);
    assert_eq!(bits(&first), bits(&second));
    // The run really moved: the outputs vary along it.
    assert!(first.iter().any(|row| row[0] != first[0][0]));
    fmu.free_state(state);
}

#[test]
fn a_serialised_state_continues_bit_identically_in_a_fresh_instance() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    fmu.free_state(state);
    let expected = run_scene(&fmu, 250, 100, 250.0 * STEP, STEP);

    // A fresh instance that has never stepped, still in `instantiated`.
    let fresh = Fmu::instantiate("fresh", None);
    let restored = fresh.deserialize(&bytes).unwrap();
    assert_eq!(fresh.set_state(restored), OK);
    assert_eq!(fresh.get_real(&OUTPUTS), fmu_outputs_at_250());
    let continued = run_scene(&fresh, 250, 100, 250.0 * STEP, STEP);
    assert_eq!(bits(&expected), bits(&continued));
    // Serialising the restored state again gives the same bytes.
    assert_eq!(fresh.serialize(restored), bytes);
    fresh.free_state(restored);
}

fn fmu_outputs_at_250() -> Vec<f64> {
    mid_run().get_real(&OUTPUTS)
}

#[test]
fn corrupted_truncated_and_foreign_byte_strings_are_fmi2_error_and_change_nothing() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    let outputs = fmu.get_real(&OUTPUTS);
    let mut rejected =
        vec![Vec::new(), bytes[..bytes.len() - 1].to_vec(), bytes[..20].to_vec(), b"{\"state\": 1}".to_vec()];
    for position in [0, 9, 12, bytes.len() / 2, bytes.len() - 1] {
        let mut corrupted = bytes.clone();
        corrupted[position] ^= 0x20;
        rejected.push(corrupted);
    }
    let mut longer = bytes.clone();
    longer.extend_from_slice(&[0; 8]);
    rejected.push(longer);
    for blob in &rejected {
        assert_eq!(fmu.deserialize(blob), Err(ERROR), "{blob:?}");
    }
    // Nothing changed: same outputs, and the run continues as the original would.
    assert_eq!(fmu.get_real(&OUTPUTS), outputs);
    let after_rejections = run_scene(&fmu, 250, 20, 250.0 * STEP, STEP);
    assert_eq!(fmu.set_state(state), OK);
    assert_eq!(bits(&after_rejections), bits(&run_scene(&fmu, 250, 20, 250.0 * STEP, STEP)));
    fmu.free_state(state);
}

#[test]
fn a_state_is_reused_when_passed_back_and_restores_the_mode() {
    let fmu = mid_run();
    let mut state: fmi2FMUstate = fmu.get_state();
    let first = state;
    run_scene(&fmu, 250, 10, 250.0 * STEP, STEP);
    // SAFETY: live instance; `state` is this FMU's and is overwritten in place.
    assert_eq!(unsafe { fmi2GetFMUstate(fmu.c, &mut state) }, OK);
    assert_eq!(state, first, "the same allocation, updated");
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, OK);
    assert_eq!(fmu.do_step(260.0 * STEP, STEP), ERROR, "terminated");
    assert_eq!(fmu.set_state(state), OK);
    assert_eq!(run_scene(&fmu, 260, 5, 260.0 * STEP, STEP).len(), 5, "stepping again from t = 0.26");
    fmu.free_state(state);
}
