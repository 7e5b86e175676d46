//! Unit tests of fmi2Get/Set with the contact's variables (an Enumeration read as an Integer and
//! refused as a Real); the generic rules are tested in `fmi2-slave/src/instance/tests.rs`.

use super::test_support::*;
use super::*;
use crate::logging::Status;
use crate::model_description::value_reference as vr;

#[test]
fn set_and_get_check_their_references_and_set_all_or_nothing() {
    let (mut instance, log) = stepping();
    let cases: [(u32, &str); 3] = [
        (999, "fmi2SetReal: unknown value reference 999"),
        (vr::STIFFNESS_SOURCE, "fmi2SetReal: value reference 102 (stiffness_source) is not a Real"),
        (vr::FORCE_LATERAL, "fmi2SetReal: force_lateral is an output and cannot be set"),
    ];
    for (value_reference, expected) in cases {
        assert_eq!(instance.set_real(&[vr::CREEPAGE_LATERAL, value_reference], &[1e-3, 1.0]), Status::Error);
        assert_eq!(last_message(&log), expected);
        assert_eq!(instance.model_state().values.inputs.creepage_lateral, 0.0, "nothing set");
    }
    let mut value = [0.0];
    assert_eq!(instance.get_real(&[1000], &mut value), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetReal: unknown value reference 1000");
    let mut source = [0];
    assert_eq!(instance.get_integer(&[vr::STIFFNESS_SOURCE], &mut source), Status::Ok);
    assert_eq!(source, [1]);
    // No Boolean variables: only n = 0 succeeds.
    assert_eq!(instance.get_boolean(&[], &mut []), Status::Ok);
    assert_eq!(instance.get_boolean(&[vr::NORMAL_FORCE], &mut [0]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetBoolean: value reference 3 (normal_force) is not a Boolean");
    assert_eq!(instance.set_boolean(&[vr::NORMAL_FORCE], &[1]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetBoolean: value reference 3 (normal_force) is not a Boolean");
    assert_eq!(instance.set_string(&[], &[]), Status::Ok);
}
