//! The leak check's workload (run under valgrind by `scripts/leak-check`): N cycles (default
//! 10 000, or the first argument) of instantiate → set up and initialise → steps, some with
//! invalid inputs (error messages through the logger) → FMU state get / set / serialise /
//! deserialise (and a corrupted deserialisation) / free → directional derivative → terminate →
//! free, through the C ABI; every hundredth cycle also a wheel on profiles (String parameters set
//! and read, the profiles loaded, steps, its state serialised and restored). Every allocation of
//! a cycle must be released by its end.

use fmu_test_master::{run_scene, Fmu, LogCounter, ERROR, INPUTS, OK, OUTPUTS};
use std::ffi::CString;
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::model_description::value_reference as vr;

fn cycle(k: usize, counter: &LogCounter) {
    let fmu = Fmu::instantiate(&format!("leak check {k}"), Some(counter));
    let all = CString::new("logAll").unwrap();
    // SAFETY: live instance; one category string; valid pointers throughout.
    unsafe {
        assert_eq!(fmi2SetDebugLogging(fmu.c, (k % 2) as i32, 1, &all.as_ptr()), OK);
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
    run_scene(&fmu, k, 5, 0.0, 1e-3);
    assert_eq!(fmu.set_real(&[vr::SEMI_AXIS_A], &[f64::NAN]), OK);
    assert_eq!(fmu.do_step(5e-3, 1e-3), ERROR);
    assert_eq!(fmu.set_real(&[vr::SEMI_AXIS_A], &[7e-3]), OK);
    let state = fmu.get_state();
    run_scene(&fmu, k + 5, 5, 5e-3, 1e-3);
    assert_eq!(fmu.set_state(state), OK);
    let bytes = fmu.serialize(state);
    let restored = fmu.deserialize(&bytes).expect("intact bytes");
    assert_eq!(fmu.deserialize(&bytes[..bytes.len() / 2]), Err(ERROR));
    assert_eq!(fmu.set_state(restored), OK);
    fmu.free_state(restored);
    fmu.free_state(state);
    let mut derivative = [0.0; 3];
    // SAFETY: live instance; matching lengths.
    unsafe {
        let status = fmi2GetDirectionalDerivative(
            fmu.c,
            OUTPUTS.as_ptr(),
            3,
            INPUTS.as_ptr(),
            1,
            &1e-3,
            derivative.as_mut_ptr(),
        );
        assert_eq!(status, OK);
        assert_eq!(fmi2Terminate(fmu.c), OK);
    }
}

/// A wheel on its profiles: the Strings copied in and out, the contact built, stepped, its state
/// (the patches') serialised and restored.
fn profiles_cycle(k: usize, counter: &LogCounter) {
    use wheel_rail_contact_fmu::model_description::ContactGeometry;
    let fmu = Fmu::instantiate(&format!("leak check profiles {k}"), Some(counter));
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE], &["MBench_S1002", "MBench_UIC60"]), OK);
    // SAFETY: live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.get_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE]), ["MBench_S1002", "MBench_UIC60"]);
    assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[5e-3]), OK);
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK);
    for step in 0..3 {
        assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[(5 + step) as f64 * 1e-3]), OK);
        assert_eq!(fmu.do_step(step as f64 * 1e-3, 1e-3), OK);
    }
    let state = fmu.get_state();
    let restored = fmu.deserialize(&fmu.serialize(state)).expect("intact bytes");
    assert_eq!(fmu.set_state(restored), OK);
    fmu.free_state(restored);
    fmu.free_state(state);
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, OK);
}

fn main() {
    let cycles: usize = std::env::args().nth(1).map_or(10_000, |n| n.parse().expect("a number of cycles"));
    let counter = LogCounter(0.into());
    for k in 0..cycles {
        cycle(k, &counter);
        if k % 100 == 0 {
            profiles_cycle(k, &counter);
        }
    }
    let messages = counter.0.load(std::sync::atomic::Ordering::Relaxed);
    println!("{cycles} instantiate/run/state/free cycles, {messages} log messages");
}
