//! Unit tests of the instance's lifecycle, call table, logging and status inquiries.

use super::test_support::*;
use super::*;
use crate::logging::Status;
use crate::mode::Mode::{InitializationMode, Instantiated, StepComplete, Terminated};
use crate::mode::{Call, Mode, Modes, LIVE, NEVER, READABLE, STEPPED, WRITABLE};
use crate::model_description::{value_reference as vr, Inputs, GUID};
use crate::snapshot::{ContactState, Snapshot};

#[test]
fn instantiate_copies_name_and_resources_and_checks_the_guid() {
    let (instance, _) = new_instance();
    assert_eq!((instance.name(), instance.resource_location()), ("wheel 1", Some("file:///tmp/resources/")));
    assert_eq!(instance.mode(), Instantiated);
    for (guid, co_simulation, name, expected) in [
        ("{wrong}", true, "wheel", "fmi2Instantiate: fmuGUID {wrong} does not match"),
        (GUID, false, "wheel", "fmi2Instantiate: this FMU supports Co-Simulation only"),
        (GUID, true, " ", "fmi2Instantiate: instanceName must not be empty"),
    ] {
        let log = Log::default();
        let arguments = InstantiateArguments { co_simulation, instance_name: name, ..arguments(guid) };
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

/// Every call outside the states the standard allows it in is refused, the state unchanged.
#[test]
fn illegal_calls_are_refused_in_every_state() {
    type Call = fn(&mut Instance) -> Status;
    let calls: [(&str, Call, Modes); 17] = [
        ("fmi2SetupExperiment", |i| i.setup_experiment(0.0, None), Modes::of(&[Instantiated])),
        ("fmi2EnterInitializationMode", Instance::enter_initialization_mode, Modes::of(&[Instantiated])),
        ("fmi2ExitInitializationMode", Instance::exit_initialization_mode, Modes::of(&[InitializationMode])),
        ("fmi2DoStep", |i| i.do_step(0.0, 1e-3), Modes::of(&[StepComplete])),
        ("fmi2Terminate", Instance::terminate, Modes::of(&[StepComplete])),
        ("fmi2CancelStep", Instance::cancel_step, NEVER),
        ("fmi2GetReal", |i| i.get_real(&[0], &mut [0.0]), READABLE),
        ("fmi2SetReal", |i| i.set_real(&[0], &[0.0]), WRITABLE),
        ("fmi2GetStatus", |i| i.get_status(StatusKind::DoStepStatus), STEPPED),
        (
            "fmi2GetRealStatus",
            |i| i.get_real_status(StatusKind::LastSuccessfulTime).err().unwrap_or(Status::Ok),
            STEPPED,
        ),
        ("fmi2Reset", Instance::reset, LIVE),
        ("fmi2GetFMUstate", |i| i.get_fmu_state().err().unwrap_or(Status::Ok), LIVE),
        ("fmi2SetFMUstate", |i| i.set_fmu_state(&Snapshot::instantiated(ContactState::start())), LIVE),
        ("fmi2FreeFMUstate", Instance::free_fmu_state, LIVE),
        (
            "fmi2SerializedFMUstateSize",
            |i| i.serialized_fmu_state_size(&Snapshot::instantiated(ContactState::start())).err().unwrap_or(Status::Ok),
            LIVE,
        ),
        ("fmi2DeSerializeFMUstate", |i| i.deserialize_fmu_state(&[]).err().unwrap_or(Status::Ok), LIVE),
        (
            "fmi2GetDirectionalDerivative",
            |i| i.get_directional_derivative(&[vr::FORCE_LATERAL], &[vr::CREEPAGE_LATERAL], &[1.0], &mut [0.0]),
            READABLE,
        ),
    ];
    /// An instance in the state, logging to the log given.
    type Make = fn(&Log) -> Instance;
    let states: [(Mode, Make); 4] = [
        (Instantiated, instance_logging_to),
        (InitializationMode, |log| {
            let mut i = instance_logging_to(log);
            i.enter_initialization_mode();
            i
        }),
        (StepComplete, stepping_logging_to),
        (Terminated, |log| {
            let mut i = stepping_logging_to(log);
            i.terminate();
            i
        }),
    ];
    for (state, make) in states {
        for (name, call, allowed) in &calls {
            let log = Log::default();
            let mut instance = make(&log);
            log.borrow_mut().clear();
            let status = call(&mut instance);
            let message = last_message(&log);
            if allowed.contains(state) {
                assert!(!message.contains("illegal call"), "{name} in {state:?}: {message}");
            } else {
                assert_eq!(status, Status::Error, "{name} in {state:?}");
                assert_eq!(message, format!("{name}: illegal call in state {}", state.name()));
                assert_eq!(instance.mode(), state);
            }
        }
    }
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

#[test]
fn status_inquiries_answer_as_specified() {
    let (mut instance, log) = stepping();
    instance.do_step(0.0, 0.125);
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.125));
    assert_eq!(instance.get_boolean_status(StatusKind::Terminated), Ok(false));
    assert_eq!(instance.get_status(StatusKind::DoStepStatus), Status::Discard);
    assert!(last_message(&log).starts_with("fmi2GetStatus: no DoStepStatus to report"));
    assert_eq!(instance.get_integer_status(StatusKind::LastSuccessfulTime), Status::Discard);
    assert_eq!(instance.get_string_status(StatusKind::PendingStatus), Status::Discard);
    assert_eq!(instance.get_real_status(StatusKind::Terminated), Err(Status::Discard));
}

#[test]
fn unsupported_capabilities_name_their_flag() {
    let (mut instance, log) = stepping();
    assert_eq!(instance.unsupported(Unsupported::RealOutputDerivatives), Status::Error);
    let expected = "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder = 0 in modelDescription.xml)";
    assert_eq!(last_message(&log), expected);
    instance.unsupported(Unsupported::RealInputDerivatives);
    assert!(last_message(&log).contains("canInterpolateInputs = false"));
}

#[test]
fn debug_logging_selects_categories() {
    let (mut instance, log) = new_instance();
    // Logging off: status messages only.
    instance.setup_experiment(0.0, None);
    instance.do_step(0.0, 1.0);
    assert_eq!(log.borrow().len(), 1);
    assert_eq!(log.borrow()[0].1, "logStatusError");
    // On, all categories: call traces too.
    assert_eq!(instance.set_debug_logging(true, &[]), Status::Ok);
    instance.enter_initialization_mode();
    assert_eq!(last_message(&log), "fmi2EnterInitializationMode");
    // A selection filters the call traces only: an error reaches the logger whatever is
    // selected, the trace of a successful call does not.
    log.borrow_mut().clear();
    assert_eq!(instance.set_debug_logging(true, &["logStatusWarning"]), Status::Ok);
    assert_eq!(instance.do_step(0.0, 1.0), Status::Error);
    instance.exit_initialization_mode();
    assert_eq!(log.borrow().len(), 1, "{:?}", log.borrow());
    assert_eq!(last_message(&log), "fmi2DoStep: illegal call in state initializationMode");
    // Only the traces: errors still reach the logger.
    log.borrow_mut().clear();
    instance.set_debug_logging(true, &["logCalls"]);
    instance.exit_initialization_mode();
    assert_eq!(last_message(&log), "fmi2ExitInitializationMode: illegal call in state stepComplete");
    assert_eq!(log.borrow().len(), 2, "the trace, then the error: {:?}", log.borrow());
    // An unknown category alone: the call's own warning reaches the logger.
    log.borrow_mut().clear();
    assert_eq!(instance.set_debug_logging(true, &["bogus"]), Status::Warning);
    assert!(last_message(&log).starts_with("fmi2SetDebugLogging: unknown log categories [\"bogus\"] ignored"));
    // logAll: everything; an unknown category is a warning.
    assert_eq!(instance.set_debug_logging(true, &["logAll", "noSuchCategory"]), Status::Warning);
    assert!(last_message(&log).starts_with("fmi2SetDebugLogging: unknown log categories [\"noSuchCategory\"] ignored"));
    instance.do_step(0.0, 1.0);
    assert_eq!(last_message(&log), "fmi2DoStep: currentCommunicationPoint = 0, communicationStepSize = 1");
}

#[test]
fn a_panic_becomes_fatal_and_only_freeing_remains() {
    let (mut instance, log) = stepping();
    let status = instance.guarded(Call::DoStep, |_| panic!("a bug"));
    assert_eq!(status, Status::Fatal);
    assert_eq!(instance.mode(), Mode::Fatal);
    let (status, category, message) = log.borrow().last().cloned().unwrap();
    assert_eq!((status, category.as_str()), (Status::Fatal, "logStatusFatal"));
    assert_eq!(message, "fmi2DoStep: internal error (a bug); this instance can only be freed");
    assert_eq!(instance.guarded(Call::Reset, Instance::reset), Status::Error);
    assert_eq!(last_message(&log), "fmi2Reset: illegal call in state fatal");
}
