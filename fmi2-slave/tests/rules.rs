//! The slave layer's argument checks and messages (FMI 2.0.4, section 4.2.4), which both FMUs of
//! the workspace use, against the rules they implement: the values at and beside each boundary,
//! and each message word for word.

use fmi2_slave::instance::{
    copy_serialized, discard_message, experiment_problem, instantiate_problem, panic_message, step_end,
    unknown_categories_message, TIME_TOLERANCE,
};
use fmi2_slave::mode::{Call, Interface};
use fmi2_slave::{InstantiateArguments, StatusKind};

const GUID: &str = "{guid}";

const CS: Result<Interface, u32> = Ok(Interface::CoSimulation);
const ME: Result<Interface, u32> = Ok(Interface::ModelExchange);

fn arguments<'a>(instance_name: &'a str, interface: Result<Interface, u32>, guid: &'a str) -> InstantiateArguments<'a> {
    InstantiateArguments { instance_name, interface, guid, resource_location: None, logging_on: false }
}

#[test]
fn instantiation_needs_a_name_an_interface_the_fmu_has_and_the_guid() {
    assert_eq!(instantiate_problem(&arguments("wheel", CS, GUID), GUID, "m", false), None);
    assert_eq!(instantiate_problem(&arguments("wheel", ME, GUID), GUID, "m", true), None);
    assert_eq!(instantiate_problem(&arguments("wheel", CS, GUID), GUID, "m", true), None);
    assert_eq!(
        instantiate_problem(&arguments(" \t", CS, GUID), GUID, "m", true).as_deref(),
        Some("instanceName must not be empty")
    );
    assert_eq!(
        instantiate_problem(&arguments("wheel", ME, GUID), GUID, "m", false).as_deref(),
        Some("this FMU supports Co-Simulation only (modelIdentifier m)")
    );
    assert_eq!(
        instantiate_problem(&arguments("wheel", Err(5), GUID), GUID, "m", true).as_deref(),
        Some("fmuType = 5 is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)")
    );
    assert_eq!(
        instantiate_problem(&arguments("wheel", CS, "{other}"), GUID, "m", true).as_deref(),
        Some("fmuGUID {other} does not match this FMU's GUID {guid}")
    );
}

#[test]
fn an_experiment_starts_at_a_finite_time_and_stops_no_earlier() {
    assert_eq!(experiment_problem(0.0, None), None);
    assert_eq!(experiment_problem(-2.0, Some(-2.0)), None); // stop = start is allowed
    assert_eq!(experiment_problem(1.0, Some(5.0)), None);
    // Finite and within ±1e12 s, where a millisecond step still advances the time (its ulp is
    // 1.2e-4 s there); the bound itself is allowed.
    assert_eq!(experiment_problem(-1e12, Some(1e12)), None);
    for start in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1e300, 1.0000001e12] {
        assert_eq!(
            experiment_problem(start, None),
            Some(format!("startTime = {start:e} is invalid: must be finite and within ±1e12 s"))
        );
    }
    assert_eq!(
        experiment_problem(1.0, Some(0.5)).as_deref(),
        Some("stopTime = 0.5 is invalid: must be >= startTime = 1")
    );
    assert_eq!(
        experiment_problem(1.0, Some(f64::NAN)).as_deref(),
        Some("stopTime = NaN is invalid: must be >= startTime = 1")
    );
}

#[test]
fn a_step_starts_at_the_instances_time_and_ends_finite_and_by_the_stop_time() {
    assert_eq!(step_end(0.0, None, 0.0, 0.5), Ok(0.5));
    // A step below the time's resolution would not advance it.
    assert_eq!(
        step_end(5e11, None, 5e11, 1e-6),
        Err("communicationStepSize = 1e-6 is below the resolution of the time 5e11: the step would not advance it"
            .into())
    );
    assert_eq!(step_end(5e11, None, 5e11, 1e-3), Ok(5e11 + 1e-3));
    for h in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        assert_eq!(
            step_end(0.0, None, 0.0, h),
            Err(format!("communicationStepSize = {h} is invalid: must be finite and > 0"))
        );
    }
    // The master's time may differ from the instance's by its rounding: 1e-9 of max(1, |t|).
    let time = 1000.0;
    let slack = TIME_TOLERANCE * time;
    assert_eq!(step_end(time, None, time + 0.9 * slack, 1.0), Ok(time + 0.9 * slack + 1.0));
    assert_eq!(step_end(time, None, time - 0.9 * slack, 1.0), Ok(time - 0.9 * slack + 1.0));
    assert_eq!(
        step_end(time, None, time + 1.1 * slack, 1.0),
        Err(format!("currentCommunicationPoint = {} is not the instance's time 1000", time + 1.1 * slack))
    );
    // Near t = 0 the tolerance is absolute, 1e-9.
    assert!(step_end(0.0, None, 0.9e-9, 1.0).is_ok() && step_end(0.0, None, 1.1e-9, 1.0).is_err());
    assert!(step_end(0.0, None, f64::NAN, 1.0).is_err());
    assert_eq!(
        step_end(1e308, None, 1e308, 1e308),
        Err("the step would end at inf: currentCommunicationPoint = 1e308 plus communicationStepSize = 1e308 is beyond \
             ±1e12 s"
            .to_owned())
    );
    assert_eq!(
        step_end(0.0, None, 0.0, 2e12),
        Err("the step would end at 2e12: currentCommunicationPoint = 0e0 plus communicationStepSize = 2e12 is beyond \
             ±1e12 s"
            .to_owned())
    );
    // The stop time, with the same tolerance.
    assert_eq!(step_end(0.0, Some(1.0), 0.0, 1.0), Ok(1.0));
    assert_eq!(step_end(0.0, Some(1.0), 0.0, 1.0 + 0.9e-9), Ok(1.0 + 0.9e-9));
    assert_eq!(step_end(0.0, Some(1.0), 0.0, 1.5), Err("the step would end at 1.5, after stopTime = 1".to_owned()));
}

#[test]
fn messages_name_the_call_and_say_what_happened() {
    let text: Box<dyn std::any::Any + Send> = Box::new("index out of bounds");
    assert_eq!(
        panic_message(Call::DoStep, text.as_ref()),
        "fmi2DoStep: internal error (index out of bounds); this instance can only be freed"
    );
    let owned: Box<dyn std::any::Any + Send> = Box::new(String::from("formatted 42"));
    assert_eq!(
        panic_message(Call::GetReal, owned.as_ref()),
        "fmi2GetReal: internal error (formatted 42); this instance can only be freed"
    );
    let other: Box<dyn std::any::Any + Send> = Box::new(42_u8);
    assert_eq!(
        panic_message(Call::SetReal, other.as_ref()),
        "fmi2SetReal: internal error (unknown panic); this instance can only be freed"
    );
    assert_eq!(
        discard_message(Call::GetStatus, StatusKind::PendingStatus),
        "fmi2GetStatus: no PendingStatus to report: fmi2DoStep never returns fmi2Pending or fmi2Discard"
    );
    let known = ["logAll", "logCalls"];
    assert_eq!(unknown_categories_message(&["logAll"], &known), None);
    assert_eq!(unknown_categories_message(&[], &known), None);
    assert_eq!(
        unknown_categories_message(&["logCalls", "verbose"], &known).as_deref(),
        Some(r#"fmi2SetDebugLogging: unknown log categories ["verbose"] ignored; known: ["logAll", "logCalls"]"#)
    );
}

#[test]
fn a_serialized_state_fills_a_buffer_of_exactly_its_size() {
    let mut buffer = [0u8; 3];
    assert_eq!(copy_serialized(&[1, 2, 3], &mut buffer), Ok(()));
    assert_eq!(buffer, [1, 2, 3]);
    let mut short = [9u8; 2];
    assert_eq!(
        copy_serialized(&[1, 2, 3], &mut short),
        Err("size = 2 is not the serialized size 3 (see fmi2SerializedFMUstateSize)".to_owned())
    );
    assert_eq!(short, [9, 9]);
}
