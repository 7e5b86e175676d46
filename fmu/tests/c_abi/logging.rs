//! The log through the C ABI: a category selection filters the call traces, never the message of
//! a failing call.

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::value_reference as vr;

const FATAL: u32 = wheel_rail_contact_fmu::fmi2::fmi2Status_fmi2Fatal;

/// A category selection filters the call traces, never the message of a failing call.
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
