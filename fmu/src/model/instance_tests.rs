//! Unit tests of the contact FMU's lifecycle through the generic instance: instantiation,
//! initialization and reset with this model's values. The state machine, logging and status
//! inquiries, the same for every model, are tested once in `fmi2-slave/src/instance/tests.rs`.

use super::test_support::*;
use super::*;
use crate::logging::Status;
use crate::mode::Interface;
use crate::mode::Mode::{InitializationMode, Instantiated};
use crate::model_description::{value_reference as vr, Inputs, GUID};

#[test]
fn instantiate_copies_name_and_resources_and_checks_the_guid() {
    let (instance, _) = new_instance();
    assert_eq!((instance.name(), instance.resource_location()), ("wheel 1", Some("file:///tmp/resources/")));
    assert_eq!(instance.mode(), Instantiated);
    let model_exchange = InstantiateArguments { interface: Ok(Interface::ModelExchange), ..arguments(GUID) };
    let log = Log::default();
    let instance = Instance::instantiate(model_exchange, Box::new(Recorder(log.clone()))).expect("Model Exchange");
    assert_eq!(instance.interface(), Interface::ModelExchange);
    for (guid, interface, name, expected) in [
        ("{wrong}", Ok(Interface::CoSimulation), "wheel", "fmi2Instantiate: fmuGUID {wrong} does not match"),
        (GUID, Err(3), "wheel", "fmi2Instantiate: fmuType = 3 is neither"),
        (GUID, Ok(Interface::CoSimulation), " ", "fmi2Instantiate: instanceName must not be empty"),
    ] {
        let log = Log::default();
        let arguments = InstantiateArguments { interface, instance_name: name, ..arguments(guid) };
        assert!(Instance::instantiate(arguments, Box::new(Recorder(log.clone()))).is_none());
        assert!(last_message(&log).starts_with(expected), "{}", last_message(&log));
        assert_eq!(log.borrow()[0].0, Status::Error);
    }
}

#[test]
fn impossible_measured_curve_is_an_error_at_exit_initialization() {
    let (mut instance, log) = new_instance();
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    instance.set_integer(&[vr::STIFFNESS_SOURCE], &[MEASURED_CURVE]);
    instance.set_real(&[vr::MEASURED_PEAK_ADHESION], &[0.25]);
    assert_eq!(instance.exit_initialization_mode(), Status::Error);
    assert!(last_message(&log).starts_with("fmi2ExitInitializationMode: measured_peak_adhesion = 0.25 is invalid"));
    assert_eq!(instance.mode(), InitializationMode, "the master may correct the value");
    instance.set_real(&[vr::MEASURED_PEAK_ADHESION], &[0.34]);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
}

#[test]
fn reset_returns_to_the_start_values() {
    let (mut instance, _) = stepping();
    instance.set_real(&[vr::NORMAL_FORCE, vr::SHEAR_MODULUS], &[50e3, 80e9]);
    instance.do_step(0.0, 1.0);
    assert_eq!(instance.reset(), Status::Ok);
    assert_eq!(instance.mode(), Instantiated);
    assert_eq!(instance.model_state().values.inputs, Inputs::default());
    assert_eq!(instance.model_state().values.parameters.shear_modulus, 82e9);
    // A new run starts from the new start time.
    instance.setup_experiment(3.0, None);
    instance.enter_initialization_mode();
    instance.exit_initialization_mode();
    assert_eq!(instance.do_step(3.0, 0.5), Status::Ok);
}

/// Get/Set read the generated access table, which must say of each variable what the slave
/// layer's rule says (`fmi2_slave::variables::access::of`).
#[test]
fn the_access_table_is_the_slave_layers_rule_for_every_variable() {
    for variable in ContactModel::variables() {
        let bits = fmi2_slave::variables::access::of(variable, ContactModel::variables());
        assert_eq!(ContactModel::access(variable.value_reference), bits, "{}", variable.name);
    }
    assert_eq!(ContactModel::access(4095), 0);
}
