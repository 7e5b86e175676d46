//! Unit tests of the FMU-state calls with the contact's state (values, scene, cache rebuilt for
//! other parameters); sizes and the byte format's checks are the slave layer's.

use super::test_support::*;
use super::*;
use crate::logging::Status;
use crate::model_description::value_reference as vr;

#[test]
fn an_fmu_state_restores_mode_time_and_every_value() {
    let (mut instance, _) = at_a_general_point();
    let saved = instance.get_fmu_state().unwrap();
    let before =
        (instance.mode(), instance.model_state().values, instance.get_real_status(StatusKind::LastSuccessfulTime));
    instance.set_real(&[vr::NORMAL_FORCE, vr::SHEAR_MODULUS], &[20e3, 70e9]);
    instance.set_integer(&[vr::STIFFNESS_SOURCE], &[MEASURED_CURVE]);
    instance.do_step(0.1, 0.2);
    instance.terminate();
    assert_eq!(instance.set_fmu_state(&saved), Status::Ok);
    let after =
        (instance.mode(), instance.model_state().values, instance.get_real_status(StatusKind::LastSuccessfulTime));
    assert_eq!(after, before);
    // Through bytes, into an instance in another mode: the same.
    let mut bytes = vec![0; instance.serialized_fmu_state_size(&saved).unwrap()];
    assert_eq!(instance.serialize_fmu_state(&saved, &mut bytes), Status::Ok);
    let (mut fresh, _) = new_instance();
    let restored = fresh.deserialize_fmu_state(&bytes).unwrap();
    assert_eq!(restored, saved);
    fresh.set_fmu_state(&restored);
    assert_eq!((fresh.mode(), fresh.model_state().values), (before.0, before.1));
    // The master's settings are not part of the state.
    assert_eq!(fresh.name(), "wheel 1");
}

#[test]
fn a_restored_state_steps_as_the_first_time_with_its_own_parameters_or_others() {
    let (mut instance, _) = at_a_general_point();
    let saved = instance.get_fmu_state().unwrap();
    let time = instance.get_real_status(StatusKind::LastSuccessfulTime).unwrap();
    assert_eq!(instance.do_step(time, 0.1), Status::Ok);
    let first = instance.model_state().values;
    // The same parameters: the model kept.
    instance.set_fmu_state(&saved);
    assert_eq!(instance.do_step(time, 0.1), Status::Ok);
    assert_eq!(instance.model_state().values, first);
    // A step with other parameters since: the model rebuilt for the state's (else the step
    // below would use the other shear modulus, and the cache's debug check fail).
    instance.set_real(&[vr::SHEAR_MODULUS], &[70e9]);
    assert_eq!(instance.do_step(time + 0.1, 0.1), Status::Ok);
    instance.set_fmu_state(&saved);
    assert_eq!(instance.do_step(time, 0.1), Status::Ok);
    assert_eq!(instance.model_state().values, first);
}
