//! Defects found by an independent review of the packaged FMU (issue 14), each reproduced
//! through the C ABI as a master meets it; every test here failed before its fix.

mod c_abi;

use std::f64::consts::PI;

use c_abi::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::value_reference as vr;

const FATAL: u32 = wheel_rail_contact_fmu::fmi2::fmi2Status_fmi2Fatal;

/// 14.1: d(max_pressure) is taken at the current inputs, not from the last step's output:
/// p₀ = 3Q/(2πab), so dp₀/dQ = 3/(2πab) whatever Q is, and dp₀/da = −p₀/a at the current Q.
#[test]
fn max_pressure_derivative_is_at_the_current_inputs() {
    let fmu = Fmu::stepping("max_pressure", 0.0);
    let (a, b) = (7.2e-3, 5.4e-3);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[100e3]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    // A new load, no step: the derivative is of the outputs at 50 kN.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[50e3]), OK);
    let (status, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert_eq!(status, OK);
    let per_newton = 3.0 / (2.0 * PI * a * b); // 12280.47 Pa/N
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{} vs {per_newton}", rates[0]);
    // A new semi-axis: dp₀/da = −3Q/(2πa²b) at Q = 50 kN and the new a.
    let a_new = 9e-3;
    assert_eq!(fmu.set_real(&[vr::SEMI_AXIS_A], &[a_new]), OK);
    let (_, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::SEMI_AXIS_A], &[1.0]);
    let expected = -3.0 * 50e3 / (2.0 * PI * a_new * a_new * b);
    assert!((rates[0] / expected - 1.0).abs() < 1e-12, "{} vs {expected}", rates[0]);
    // After a lift-off step, loaded again without a step: the loaded rate, not 0.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE, vr::SEMI_AXIS_A], &[-1.0, a]), OK);
    assert_eq!(fmu.do_step(1e-3, 1e-3), OK);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[80e3]), OK);
    let (_, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{}", rates[0]);
}

/// 14.1, in initialisation mode before any output was computed: the rate at the start values.
#[test]
fn max_pressure_derivative_in_initialisation_mode() {
    let fmu = Fmu::instantiate("initialisation", None);
    // SAFETY: a live instance.
    unsafe {
        use wheel_rail_contact_fmu::ffi::{fmi2EnterInitializationMode, fmi2SetupExperiment};
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    let (status, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert_eq!(status, OK);
    let per_newton = 3.0 / (2.0 * PI * 7.2e-3 * 5.4e-3);
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{}", rates[0]);
}

/// 14.3: a category selection filters the call traces, never the message of a failing call.
#[test]
fn errors_and_warnings_reach_the_logger_whatever_the_selection() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("logging", &log);
    fmu.initialise(0.0);
    assert_eq!(fmu.set_debug_logging(true, &["logCalls"]), OK);
    // A bad input: the step that uses it fails, with its reason in the log.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[f64::NAN]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    let texts = log.texts();
    assert_eq!(texts.last().unwrap(), "fmi2DoStep: normal_force = NaN is invalid: must be finite", "{texts:?}");
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[1e5]), OK);
    // An error of DoStep's own arguments (not at the instance's time).
    assert_eq!(fmu.do_step(5.0, 1e-3), ERROR);
    assert_eq!(log.texts().last().unwrap(), "fmi2DoStep: currentCommunicationPoint = 5 is not the instance's time 0");
    // An unknown category alone: the call's own warning is logged.
    log.0.lock().unwrap().clear();
    assert_eq!(fmu.set_debug_logging(true, &["bogus"]), 1, "fmi2Warning");
    let texts = log.texts();
    assert_eq!(texts.len(), 1, "{texts:?}");
    assert!(texts[0].starts_with("fmi2SetDebugLogging: unknown log categories [\"bogus\"] ignored"), "{texts:?}");
    // With that selection, a successful call's trace is filtered, an error is not.
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    assert_eq!(log.texts().len(), 2);
    assert!(log.0.lock().unwrap().iter().all(|(status, _, _)| *status != FATAL));
}

/// 14.4: a step whose end time overflows is an error naming the values, and changes nothing.
#[test]
fn an_overflowing_step_end_is_an_error_and_changes_nothing() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("overflow", &log);
    fmu.initialise(1e308);
    let before = fmu.get_real(&[vr::FORCE_LONGITUDINAL]);
    assert_eq!(fmu.do_step(1e308, 1e308), ERROR);
    assert_eq!(
        log.texts().last().unwrap(),
        "fmi2DoStep: the step would end at inf: currentCommunicationPoint = 1e308 plus communicationStepSize = 1e308 is not finite"
    );
    // The instance's time is still 1e308: a good step from there succeeds.
    assert_eq!(fmu.do_step(1e308, 1e292), OK);
    assert_eq!(fmu.get_real(&[vr::FORCE_LONGITUDINAL]), before);
}

/// A zero output is +0, never −0 (masters print `-0` into their result files).
#[test]
fn zero_outputs_are_positive_zeros() {
    // ξ = ±0 (the core's F_x = −k·ξ is −0 for ξ = +0) and lift-off: zero forces.
    for (xi, q) in [(0.0, 1e5), (-0.0, 1e5), (1e-3, -5.0)] {
        let fmu = Fmu::stepping("zeros", 0.0);
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::NORMAL_FORCE], &[xi, q]), OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), OK);
        let outputs = fmu.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT, vr::SLIP_VELOCITY]);
        assert!(outputs.contains(&0.0));
        for value in outputs.iter().filter(|v| **v == 0.0) {
            assert!(value.is_sign_positive(), "ξ = {xi}, Q = {q}: {outputs:?}");
        }
    }
}
