//! fmi2DoStep's edges through the C ABI: a step end that overflows, and zero outputs.

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::value_reference as vr;

/// A step whose end time overflows is an error naming the values, and changes nothing.
#[test]
fn a_step_ending_beyond_the_times_range_is_an_error_and_changes_nothing() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("overflow", &log);
    // Times are bounded by ±1e12 s (beyond, a millisecond step would not advance them).
    fmu.initialise(5e11);
    let before = fmu.get_real(&[vr::FORCE_LONGITUDINAL]);
    assert_eq!(fmu.do_step(5e11, f64::MAX), ERROR);
    assert_eq!(
        log.texts().last().unwrap(),
        "fmi2DoStep: the step would end at 1.7976931348623157e308: currentCommunicationPoint = 5e11 plus \
         communicationStepSize = 1.7976931348623157e308 is beyond ±1e12 s"
    );
    // The instance's time is still 5e11: a good step from there succeeds.
    assert_eq!(fmu.do_step(5e11, 1e-3), OK);
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
