//! Unit tests of the generic instance's rules, through a small model with every kind of
//! variable the layer handles (Real, Integer, String; no Boolean), an evaluation that can warn
//! and fail, a cache it is told about, resources and directional derivatives. The rules of one
//! FMU's own model are tested in its crate (`fmu/src/model/*_tests.rs`, `wheelset/`).

use std::borrow::Cow;
use std::cell::RefCell;
use std::rc::Rc;

use super::*;
use crate::mode::Mode::{InitializationMode, Instantiated, StepComplete, Terminated};
use crate::mode::{Modes, NEVER, READABLE, STEPPED, WRITABLE};
use crate::variables::Variability;

const X: u32 = 0; // Real input
const GAIN: u32 = 1; // Real parameter, fixed
const OFFSET: u32 = 2; // Real parameter, tunable
const LEVEL: u32 = 3; // Integer parameter, tunable
const LABEL: u32 = 4; // String parameter, fixed
const Y: u32 = 10; // Real output: GAIN · X + OFFSET
const COUNT: u32 = 11; // Integer output: the evaluations so far

const fn variable(
    name: &'static str,
    value_reference: u32,
    causality: Causality,
    variability: Variability,
    kind: Kind,
) -> Variable {
    let dependencies: &[u32] = if value_reference == Y { &[X] } else { &[] };
    Variable {
        name,
        value_reference,
        causality,
        variability,
        kind,
        unit: None,
        display_unit: None,
        description: "",
        dependencies,
    }
}

static VARIABLES: [Variable; 7] = [
    variable("x", X, Causality::Input, Variability::Continuous, Kind::Real { start: Some(0.0) }),
    variable("gain", GAIN, Causality::Parameter, Variability::Fixed, Kind::Real { start: Some(2.0) }),
    variable("offset", OFFSET, Causality::Parameter, Variability::Tunable, Kind::Real { start: Some(0.0) }),
    variable("level", LEVEL, Causality::Parameter, Variability::Tunable, Kind::Integer { start: Some(1) }),
    variable("label", LABEL, Causality::Parameter, Variability::Fixed, Kind::String { start: "start" }),
    variable("y", Y, Causality::Output, Variability::Continuous, Kind::Real { start: None }),
    variable("count", COUNT, Causality::Output, Variability::Continuous, Kind::Integer { start: None }),
];

/// An input value that makes the evaluation warn, and one that makes it panic.
const WARNING_X: f64 = 7.0;

#[derive(Debug, Clone, PartialEq)]
struct Values {
    x: f64,
    gain: f64,
    offset: f64,
    level: i32,
    label: String,
    y: f64,
    count: i32,
}

/// What the model was told, shared with the test.
#[derive(Debug, Default)]
struct Told {
    parameters_changed: usize,
    restorings: usize,
    resets: usize,
    feedthroughs: usize,
}

struct Affine {
    told: Rc<RefCell<Told>>,
}

thread_local! {
    /// The `Told` of the instance a test instantiates next.
    static TOLD: RefCell<Rc<RefCell<Told>>> = RefCell::default();
}

impl Model for Affine {
    type State = Values;

    const GUID: &'static str = "{affine}";
    const MODEL_IDENTIFIER: &'static str = "affine";
    const LOG_CATEGORIES: &'static [&'static str] =
        &["logStatusWarning", "logStatusDiscard", "logStatusError", "logStatusFatal", "logCalls", "logAll"];
    const STATE_LAYOUT_TAG: u64 = 7;
    const STATE_MAGIC: [u8; 8] = *b"AFFstate";
    const STATE_FORMAT_VERSION: u16 = 1;
    const PROVIDES_DIRECTIONAL_DERIVATIVE: bool = true;
    /// Algebraic (no states): the Model Exchange state machine with nothing to integrate.
    const MODEL_EXCHANGE: bool = true;

    /// Refuses a resource location without `resources`; notes one that is not a `file:` URI.
    fn instantiate(resource_location: Option<&str>) -> Result<(Self, Option<String>), String> {
        let location = resource_location.unwrap_or("file:///resources");
        if !location.contains("resources") {
            return Err(format!("no resources at {location}"));
        }
        let note = (!location.starts_with("file:")).then(|| format!("{location} is not a file URI"));
        Ok((Affine { told: TOLD.with(|told| told.borrow().clone()) }, note))
    }

    fn reset(&mut self) {
        self.told.borrow_mut().resets += 1;
    }

    fn start() -> Values {
        Values { x: 0.0, gain: 2.0, offset: 0.0, level: 1, label: "start".to_owned(), y: 0.0, count: 0 }
    }

    fn variable(value_reference: u32) -> Option<&'static Variable> {
        VARIABLES.iter().find(|v| v.value_reference == value_reference)
    }

    fn variables() -> &'static [Variable] {
        &VARIABLES
    }

    fn real(state: &Values, value_reference: u32) -> Option<f64> {
        match value_reference {
            X => Some(state.x),
            GAIN => Some(state.gain),
            OFFSET => Some(state.offset),
            Y => Some(state.y),
            _ => None,
        }
    }

    fn real_mut(state: &mut Values, value_reference: u32) -> Option<&mut f64> {
        match value_reference {
            X => Some(&mut state.x),
            GAIN => Some(&mut state.gain),
            OFFSET => Some(&mut state.offset),
            _ => None,
        }
    }

    fn integer(state: &Values, value_reference: u32) -> Option<i32> {
        match value_reference {
            LEVEL => Some(state.level),
            COUNT => Some(state.count),
            _ => None,
        }
    }

    fn integer_mut(state: &mut Values, value_reference: u32) -> Option<&mut i32> {
        (value_reference == LEVEL).then_some(&mut state.level)
    }

    fn string(state: &Values, value_reference: u32) -> Option<&str> {
        (value_reference == LABEL).then_some(state.label.as_str())
    }

    fn string_mut(state: &mut Values, value_reference: u32) -> Option<&mut String> {
        (value_reference == LABEL).then_some(&mut state.label)
    }

    fn evaluate(&mut self, state: &mut Values, evaluation: Evaluation) -> Result<Option<String>, String> {
        if !state.x.is_finite() {
            return Err(format!("x = {} is invalid: must be finite", state.x));
        }
        assert!(state.offset != f64::MAX, "forced by a test");
        state.y = state.gain * state.x + state.offset;
        // The count is the model's state: a step advances it, the feedthrough does not.
        match evaluation {
            Evaluation::Initialise | Evaluation::Step { .. } => state.count += 1,
            Evaluation::Feedthrough { .. } => self.told.borrow_mut().feedthroughs += 1,
        }
        Ok((state.x == WARNING_X).then(|| format!("x = {WARNING_X} is where the model warns")))
    }

    fn parameters_changed(&mut self) {
        self.told.borrow_mut().parameters_changed += 1;
    }

    /// A label that only Co-Simulation can run, to test the check.
    fn model_exchange_problem(state: &Values) -> Option<String> {
        (state.label == "co-simulation only").then(|| "label = co-simulation only needs Co-Simulation".to_owned())
    }

    fn restoring(&mut self, _current: &Values, _restored: &Values) {
        self.told.borrow_mut().restorings += 1;
    }

    /// d y / d x = gain; knowns other than x are refused.
    fn directional_derivative(
        &mut self,
        state: &Values,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Result<(), String> {
        if let Some(known) = knowns.iter().find(|&&k| k != X) {
            return Err(format!("value reference {known} cannot be a known"));
        }
        let rate: f64 = known_rates.iter().sum();
        for (slot, _) in unknown_rates.iter_mut().zip(unknowns) {
            *slot = state.gain * rate;
        }
        Ok(())
    }

    fn encode(state: &FmuState<Values>) -> Vec<u8> {
        let values = &state.model;
        let mut bytes: Vec<u8> =
            [values.x, values.gain, values.offset, values.y].iter().flat_map(|v| v.to_le_bytes()).collect();
        bytes.extend(values.level.to_le_bytes());
        bytes.extend(values.count.to_le_bytes());
        bytes.extend(values.label.as_bytes());
        encode_run(state, &bytes)
    }

    fn decode(payload: &[u8]) -> Result<FmuState<Values>, String> {
        let run = decode_run(payload)?;
        let bytes = run.model;
        if bytes.len() < 40 {
            return Err(format!("{} bytes of values", bytes.len()));
        }
        let real = |i: usize| f64::from_le_bytes(bytes[8 * i..8 * i + 8].try_into().expect("8 bytes"));
        let integer = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        let label = String::from_utf8(bytes[40..].to_vec()).map_err(|e| e.to_string())?;
        let model = Values {
            x: real(0),
            gain: real(1),
            offset: real(2),
            y: real(3),
            level: integer(32),
            count: integer(36),
            label,
        };
        Ok(FmuState { mode: run.mode, time: run.time, stop_time: run.stop_time, model })
    }

    fn check_state(state: &Values, _mode: Mode) -> Result<(), String> {
        match state.y.is_finite() {
            true => Ok(()),
            false => Err(format!("y = {} is invalid: an output is always finite", state.y)),
        }
    }
}

type Log = Rc<RefCell<Vec<(Status, String, String)>>>;

struct Recorder(Log);

impl LogSink for Recorder {
    fn log(&mut self, status: Status, category: &str, message: &str) {
        self.0.borrow_mut().push((status, category.to_owned(), message.to_owned()));
    }
}

fn arguments(resource_location: Option<&str>) -> InstantiateArguments<'_> {
    InstantiateArguments {
        instance_name: "affine 1",
        interface: Ok(Interface::CoSimulation),
        guid: Affine::GUID,
        resource_location,
        logging_on: false,
    }
}

/// A new instance logging to `log`, and what its model is told.
fn instance_logging_to(log: &Log) -> (Instance<Affine>, Rc<RefCell<Told>>) {
    let told = Rc::new(RefCell::new(Told::default()));
    TOLD.with(|cell| *cell.borrow_mut() = told.clone());
    let sink = Box::new(Recorder(log.clone()));
    (Instance::instantiate(arguments(Some("file:///tmp/resources/")), sink).unwrap(), told)
}

fn new_instance() -> (Instance<Affine>, Log) {
    let log = Log::default();
    (instance_logging_to(&log).0, log)
}

fn stepping_logging_to(log: &Log) -> Instance<Affine> {
    let mut instance = instance_logging_to(log).0;
    assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
    assert_eq!(instance.enter_initialization_mode(), Status::Ok);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    instance
}

fn stepping() -> (Instance<Affine>, Log) {
    let log = Log::default();
    (stepping_logging_to(&log), log)
}

/// A Model Exchange instance logging to `log`, with what its model is told.
fn model_exchange_told(log: &Log) -> (Instance<Affine>, Rc<RefCell<Told>>) {
    let told = Rc::new(RefCell::new(Told::default()));
    TOLD.with(|cell| *cell.borrow_mut() = told.clone());
    let arguments = InstantiateArguments { interface: Ok(Interface::ModelExchange), ..arguments(None) };
    (Instance::instantiate(arguments, Box::new(Recorder(log.clone()))).unwrap(), told)
}

fn model_exchange_logging_to(log: &Log) -> Instance<Affine> {
    model_exchange_told(log).0
}

fn last_message(log: &Log) -> String {
    log.borrow().last().map(|(_, _, m)| m.clone()).unwrap_or_default()
}

fn get(instance: &mut Instance<Affine>, value_reference: u32) -> f64 {
    let mut value = [f64::NAN];
    assert_eq!(instance.get_real(&[value_reference], &mut value), Status::Ok, "{value_reference}");
    value[0]
}

#[test]
fn instantiate_keeps_name_and_resources_and_checks_guid_and_model() {
    let (instance, _) = new_instance();
    assert_eq!((instance.name(), instance.resource_location()), ("affine 1", Some("file:///tmp/resources/")));
    assert_eq!(instance.mode(), Instantiated);
    let co_simulation = Ok(Interface::CoSimulation);
    for (guid, interface, name, location, expected) in [
        (
            "{wrong}",
            co_simulation,
            "a",
            None,
            "fmi2Instantiate: fmuGUID {wrong} does not match this FMU's GUID {affine}",
        ),
        (
            Affine::GUID,
            Err(2),
            "a",
            None,
            "fmi2Instantiate: fmuType = 2 is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)",
        ),
        (Affine::GUID, co_simulation, " ", None, "fmi2Instantiate: instanceName must not be empty"),
        (
            Affine::GUID,
            co_simulation,
            "a",
            Some("file:///elsewhere"),
            "fmi2Instantiate: no resources at file:///elsewhere",
        ),
    ] {
        let log = Log::default();
        let arguments = InstantiateArguments { interface, instance_name: name, guid, ..arguments(location) };
        assert!(Instance::<Affine>::instantiate(arguments, Box::new(Recorder(log.clone()))).is_none());
        assert_eq!(log.borrow().as_slice(), [(Status::Error, "logStatusError".to_owned(), expected.to_owned())]);
    }
    // The model's note follows the call's trace.
    let log = Log::default();
    let arguments = InstantiateArguments { logging_on: true, ..arguments(Some("resources")) };
    assert!(Instance::<Affine>::instantiate(arguments, Box::new(Recorder(log.clone()))).is_some());
    let messages: Vec<String> = log.borrow().iter().map(|(_, _, m)| m.clone()).collect();
    assert_eq!(
        messages,
        ["fmi2Instantiate: resourceLocation = resources", "fmi2Instantiate: resources is not a file URI"]
    );
}

/// Every call outside the states the standard allows it in is refused, the state unchanged.
#[test]
fn illegal_calls_are_refused_in_every_state() {
    type Call = fn(&mut Instance<Affine>) -> Status;
    let calls: [(&str, Call, Modes); 21] = [
        ("fmi2SetupExperiment", |i| i.setup_experiment(0.0, None), Modes::of(&[Instantiated])),
        ("fmi2EnterInitializationMode", |i| i.enter_initialization_mode(), Modes::of(&[Instantiated])),
        ("fmi2ExitInitializationMode", |i| i.exit_initialization_mode(), Modes::of(&[InitializationMode])),
        ("fmi2DoStep", |i| i.do_step(0.0, 1e-3), Modes::of(&[StepComplete])),
        ("fmi2Terminate", |i| i.terminate(), Modes::of(&[StepComplete])),
        ("fmi2CancelStep", |i| i.cancel_step(), NEVER),
        ("fmi2GetReal", |i| i.get_real(&[X], &mut [0.0]), READABLE),
        ("fmi2GetInteger", |i| i.get_integer(&[LEVEL], &mut [0]), READABLE),
        ("fmi2GetString", |i| i.get_string(&[LABEL]).err().unwrap_or(Status::Ok), READABLE),
        ("fmi2SetReal", |i| i.set_real(&[X], &[0.0]), WRITABLE),
        ("fmi2SetInteger", |i| i.set_integer(&[LEVEL], &[0]), WRITABLE),
        ("fmi2SetString", |i| i.set_string(&[], &[]), WRITABLE),
        ("fmi2GetStatus", |i| i.get_status(StatusKind::DoStepStatus), STEPPED),
        (
            "fmi2GetRealStatus",
            |i| i.get_real_status(StatusKind::LastSuccessfulTime).err().unwrap_or(Status::Ok),
            STEPPED,
        ),
        ("fmi2Reset", |i| i.reset(), LIVE),
        ("fmi2GetFMUstate", |i| i.get_fmu_state().err().unwrap_or(Status::Ok), LIVE),
        ("fmi2SetFMUstate", |i| i.set_fmu_state(&FmuState::instantiated(Affine::start())), LIVE),
        ("fmi2FreeFMUstate", |i| i.free_fmu_state(), LIVE),
        (
            "fmi2SerializedFMUstateSize",
            |i| i.serialized_fmu_state_size(&FmuState::instantiated(Affine::start())).err().unwrap_or(Status::Ok),
            LIVE,
        ),
        ("fmi2DeSerializeFMUstate", |i| i.deserialize_fmu_state(&[]).err().unwrap_or(Status::Ok), LIVE),
        ("fmi2GetDirectionalDerivative", |i| i.get_directional_derivative(&[Y], &[X], &[1.0], &mut [0.0]), READABLE),
    ];
    /// An instance in the state, logging to the log given.
    type Make = fn(&Log) -> Instance<Affine>;
    let states: [(Mode, Make); 4] = [
        (Instantiated, |log| instance_logging_to(log).0),
        (InitializationMode, |log| {
            let mut i = instance_logging_to(log).0;
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

/// The Model Exchange state machine (FMI 2.0.4 §3.2.3, its table written out here): every call in
/// every state of a Model Exchange instance, refused outside the states the table allows it in,
/// the state unchanged; the Co-Simulation functions refused everywhere by interface.
#[test]
fn model_exchange_calls_are_refused_outside_their_states() {
    use crate::mode::Mode::{ContinuousTimeMode, EventMode};
    type Call = fn(&mut Instance<Affine>) -> Status;
    let event_and_continuous = Modes::of(&[EventMode, ContinuousTimeMode]);
    let calls: [(&str, Call, Modes); 17] = [
        ("fmi2EnterEventMode", |i| i.enter_event_mode(), event_and_continuous),
        ("fmi2NewDiscreteStates", |i| i.new_discrete_states().err().unwrap_or(Status::Ok), Modes::of(&[EventMode])),
        ("fmi2EnterContinuousTimeMode", |i| i.enter_continuous_time_mode(), Modes::of(&[EventMode])),
        (
            "fmi2CompletedIntegratorStep",
            |i| i.completed_integrator_step().err().unwrap_or(Status::Ok),
            Modes::of(&[ContinuousTimeMode]),
        ),
        ("fmi2SetTime", |i| i.set_time(1.0), event_and_continuous),
        ("fmi2SetContinuousStates", |i| i.set_continuous_states(&[]), Modes::of(&[ContinuousTimeMode])),
        ("fmi2GetDerivatives", |i| i.get_derivatives(&mut []), Modes::of(&[EventMode, ContinuousTimeMode, Terminated])),
        (
            "fmi2GetEventIndicators",
            |i| i.get_event_indicators(&mut []),
            Modes::of(&[InitializationMode, EventMode, ContinuousTimeMode, Terminated]),
        ),
        (
            "fmi2GetContinuousStates",
            |i| i.get_continuous_states(&mut []),
            Modes::of(&[InitializationMode, EventMode, ContinuousTimeMode, Terminated]),
        ),
        (
            "fmi2GetNominalsOfContinuousStates",
            |i| i.get_nominals_of_continuous_states(&mut []),
            Modes::of(&[Instantiated, EventMode, ContinuousTimeMode, Terminated]),
        ),
        ("fmi2Terminate", |i| i.terminate(), event_and_continuous),
        ("fmi2ExitInitializationMode", |i| i.exit_initialization_mode(), Modes::of(&[InitializationMode])),
        (
            "fmi2GetReal",
            |i| i.get_real(&[Y], &mut [0.0]),
            Modes::of(&[InitializationMode, EventMode, ContinuousTimeMode, Terminated]),
        ),
        // An input in every mode before termination; a tunable parameter not between events.
        (
            "fmi2SetReal",
            |i| i.set_real(&[X], &[1.0]),
            Modes::of(&[Instantiated, InitializationMode, EventMode, ContinuousTimeMode]),
        ),
        (
            "fmi2SetInteger",
            |i| i.set_integer(&[LEVEL], &[2]),
            Modes::of(&[Instantiated, InitializationMode, EventMode]),
        ),
        ("fmi2SetReal", |i| i.set_real(&[OFFSET], &[1.0]), Modes::of(&[Instantiated, InitializationMode, EventMode])),
        ("fmi2DoStep", |i| i.do_step(0.0, 1e-3), NEVER),
    ];
    type Make = fn(&Log) -> Instance<Affine>;
    let states: [(Mode, Make); 5] = [
        (Instantiated, model_exchange_logging_to),
        (InitializationMode, |log| {
            let mut i = model_exchange_logging_to(log);
            i.enter_initialization_mode();
            i
        }),
        (EventMode, |log| {
            let mut i = model_exchange_logging_to(log);
            i.enter_initialization_mode();
            assert_eq!(i.exit_initialization_mode(), Status::Ok);
            i
        }),
        (ContinuousTimeMode, |log| {
            let mut i = model_exchange_logging_to(log);
            i.enter_initialization_mode();
            i.exit_initialization_mode();
            assert_eq!(i.enter_continuous_time_mode(), Status::Ok);
            i
        }),
        (Terminated, |log| {
            let mut i = model_exchange_logging_to(log);
            i.enter_initialization_mode();
            i.exit_initialization_mode();
            assert_eq!(i.terminate(), Status::Ok);
            i
        }),
    ];
    for (state, make) in states {
        for (name, call, allowed) in &calls {
            let log = Log::default();
            let mut instance = make(&log);
            assert_eq!(instance.mode(), state);
            log.borrow_mut().clear();
            let status = call(&mut instance);
            let message = last_message(&log);
            if allowed.contains(state) {
                assert!(status != Status::Error, "{name} in {state:?}: {message}");
            } else if *name == "fmi2DoStep" {
                assert_eq!(status, Status::Error);
                assert_eq!(
                    message,
                    "fmi2DoStep: a Co-Simulation function, but this instance was instantiated for Model Exchange"
                );
                assert_eq!(instance.mode(), state);
            } else {
                assert_eq!(status, Status::Error, "{name} in {state:?}");
                let refusal = if *name == "fmi2SetInteger" && state == ContinuousTimeMode {
                    "fmi2SetInteger: level can be set at events, not in continuousTimeMode".to_owned()
                } else if *name == "fmi2SetReal" && state == ContinuousTimeMode {
                    "fmi2SetReal: offset can be set at events, not in continuousTimeMode".to_owned()
                } else {
                    format!("{name}: illegal call in state {}", state.name())
                };
                assert_eq!(message, refusal, "{name} in {state:?}");
                assert_eq!(instance.mode(), state);
            }
        }
    }
}

/// The model evaluates only when what the outputs are computed from was written: in Co-Simulation
/// an input an output depends on (a read of anything else, or a second read, evaluates nothing),
/// in Model Exchange any input or parameter, the states or the time (fmi2GetDerivatives twice
/// evaluates once).
#[test]
fn the_model_evaluates_only_after_a_write_it_depends_on() {
    let log = Log::default();
    let mut cs = stepping_logging_to(&log);
    let told = TOLD.with(|cell| cell.borrow().clone());
    let mut count = [0];
    assert_eq!(cs.get_integer(&[COUNT], &mut count), Status::Ok);
    assert_eq!((count[0], told.borrow().feedthroughs), (1, 0), "initialised once, nothing since");
    get(&mut cs, Y);
    assert_eq!(told.borrow().feedthroughs, 0);
    // An invalid input is reported where the model computes: reading the input itself is fine.
    assert_eq!(cs.set_real(&[X], &[f64::NAN]), Status::Ok);
    assert!(get(&mut cs, X).is_nan());
    assert_eq!(cs.get_real(&[Y], &mut [0.0]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetReal: x = NaN is invalid: must be finite");

    let (mut me, told) = model_exchange_told(&log);
    me.enter_initialization_mode();
    assert_eq!(me.exit_initialization_mode(), Status::Ok);
    // A tunable parameter written at an event acts on the next read (y = 2 x + offset).
    assert_eq!(me.set_real(&[X, OFFSET], &[1.0, 0.5]), Status::Ok);
    assert_eq!(get(&mut me, Y), 2.5);
    assert_eq!(me.set_real(&[OFFSET], &[1.5]), Status::Ok);
    assert_eq!(get(&mut me, Y), 3.5, "a parameter alone, which no output lists, makes the outputs stale too");
    assert_eq!(me.enter_continuous_time_mode(), Status::Ok);
    let before = told.borrow().feedthroughs;
    assert_eq!(me.set_real(&[X], &[3.0]), Status::Ok);
    assert_eq!(me.get_derivatives(&mut []), Status::Ok);
    assert_eq!(me.get_derivatives(&mut []), Status::Ok);
    assert_eq!(get(&mut me, Y), 7.5);
    assert_eq!(told.borrow().feedthroughs, before + 1, "one evaluation for one write");
}

/// A model's Model Exchange problem stops fmi2ExitInitializationMode of a Model Exchange
/// instance (which stays correctable in initialization mode) and not a Co-Simulation one; an FMU
/// state restores only into an instance of the interface it was taken in.
#[test]
fn model_exchange_is_checked_at_exit_initialization_and_states_keep_to_their_interface() {
    let log = Log::default();
    let mut me = model_exchange_logging_to(&log);
    assert_eq!(me.set_string(&[LABEL], &[Cow::Borrowed("co-simulation only")]), Status::Ok);
    me.enter_initialization_mode();
    assert_eq!(me.exit_initialization_mode(), Status::Error);
    assert_eq!(last_message(&log), "fmi2ExitInitializationMode: label = co-simulation only needs Co-Simulation");
    assert_eq!(me.mode(), InitializationMode);
    let mut cs = instance_logging_to(&log).0;
    assert_eq!(cs.set_string(&[LABEL], &[Cow::Borrowed("co-simulation only")]), Status::Ok);
    cs.enter_initialization_mode();
    assert_eq!(cs.exit_initialization_mode(), Status::Ok);
    let stepped = cs.get_fmu_state().unwrap();
    assert_eq!(me.set_fmu_state(&stepped), Status::Error);
    assert_eq!(
        last_message(&log),
        "fmi2SetFMUstate: FMUstate was taken in state stepComplete, which an instance of Model Exchange never is in"
    );
    assert_eq!(me.mode(), InitializationMode);
}

/// In Model Exchange the output follows each input as soon as it is read (no step), and a
/// Co-Simulation instance refuses the Model Exchange functions.
#[test]
fn model_exchange_evaluates_on_demand_and_each_interface_keeps_to_its_functions() {
    let log = Log::default();
    let mut me = model_exchange_logging_to(&log);
    me.enter_initialization_mode();
    assert_eq!(me.exit_initialization_mode(), Status::Ok);
    assert_eq!(me.mode(), crate::mode::Mode::EventMode);
    assert_eq!(me.enter_continuous_time_mode(), Status::Ok);
    for x in [1.5, -4.0] {
        assert_eq!(me.set_real(&[X], &[x]), Status::Ok);
        assert_eq!(get(&mut me, Y), 2.0 * x, "y = gain · x + offset at the input just set");
    }
    // A model without step events (the trait's defaults): no event asked, none to handle.
    assert_eq!(me.completed_integrator_step(), Ok((false, false)));
    assert_eq!(me.enter_event_mode(), Status::Ok);
    assert_eq!(me.new_discrete_states(), Ok(crate::EventInfo::default()));
    let (mut cs, log) = stepping();
    assert_eq!(cs.set_time(0.5), Status::Error);
    assert_eq!(
        last_message(&log),
        "fmi2SetTime: a Model Exchange function, but this instance was instantiated for Co-Simulation"
    );
    assert_eq!(cs.get_derivatives(&mut []), Status::Error);
    assert_eq!(cs.mode(), StepComplete);
}

#[test]
fn status_inquiries_answer_as_specified() {
    let (mut instance, log) = stepping();
    instance.do_step(0.0, 0.125);
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.125));
    assert_eq!(instance.get_boolean_status(StatusKind::Terminated), Ok(false));
    assert_eq!(instance.get_status(StatusKind::DoStepStatus), Status::Discard);
    assert_eq!(
        last_message(&log),
        "fmi2GetStatus: no DoStepStatus to report: fmi2DoStep never returns fmi2Pending or fmi2Discard"
    );
    assert_eq!(instance.get_integer_status(StatusKind::LastSuccessfulTime), Status::Discard);
    assert_eq!(instance.get_string_status(StatusKind::PendingStatus), Status::Discard);
    assert_eq!(instance.get_real_status(StatusKind::Terminated), Err(Status::Discard));
    assert_eq!(instance.get_boolean_status(StatusKind::DoStepStatus), Err(Status::Discard));
}

#[test]
fn unsupported_capabilities_and_invalid_arguments_are_errors_naming_why() {
    let (mut instance, log) = stepping();
    assert_eq!(instance.unsupported(Unsupported::RealOutputDerivatives), Status::Error);
    let expected = "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder = 0 in modelDescription.xml)";
    assert_eq!(last_message(&log), expected);
    instance.unsupported(Unsupported::RealInputDerivatives);
    assert!(last_message(&log).contains("canInterpolateInputs = false"));
    assert_eq!(instance.invalid_argument(Call::SetReal, "NULL array pointer with n > 0"), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetReal: NULL array pointer with n > 0");
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
    assert_eq!(instance.guarded(Call::Reset, |i| i.reset()), Status::Error);
    assert_eq!(last_message(&log), "fmi2Reset: illegal call in state fatal");
    // A panic of the model's evaluation, in a guarded call.
    let (mut instance, log) = stepping();
    instance.set_real(&[OFFSET], &[f64::MAX]);
    assert_eq!(instance.guarded(Call::DoStep, |i| i.do_step(0.0, 1.0)), Status::Fatal);
    assert!(last_message(&log).starts_with("fmi2DoStep: internal error (forced by a test"));
}

/// An output cannot be set in any state; a fixed parameter only before initialization ends;
/// references are checked before anything is set (all or nothing), in every Set.
#[test]
fn set_checks_type_causality_and_variability_all_or_nothing() {
    let (mut instance, log) = new_instance();
    let refuse_output = |instance: &mut Instance<Affine>, log: &Log| {
        assert_eq!(instance.set_real(&[Y], &[1.0]), Status::Error);
        assert_eq!(last_message(log), "fmi2SetReal: y is an output and cannot be set");
        assert_eq!(instance.set_integer(&[COUNT], &[1]), Status::Error);
        assert_eq!(last_message(log), "fmi2SetInteger: count is an output and cannot be set");
    };
    refuse_output(&mut instance, &log);
    assert_eq!(instance.set_real(&[GAIN], &[3.0]), Status::Ok);
    assert_eq!(instance.set_string(&[LABEL], &[Cow::Borrowed("early")]), Status::Ok);
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    refuse_output(&mut instance, &log);
    assert_eq!(instance.set_real(&[GAIN], &[4.0]), Status::Ok, "fixed: still before initialization ends");
    instance.exit_initialization_mode();
    refuse_output(&mut instance, &log);
    assert_eq!(instance.set_real(&[X, GAIN], &[1.0, 5.0]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetReal: gain is a fixed parameter and cannot be set after initialization");
    assert_eq!(instance.set_string(&[LABEL], &[Cow::Borrowed("late")]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetString: label is a fixed parameter and cannot be set after initialization");
    for (references, expected) in [
        (&[X, 99][..], "fmi2SetReal: unknown value reference 99"),
        (&[X, LEVEL][..], "fmi2SetReal: value reference 3 (level) is not a Real"),
        (&[X, LABEL][..], "fmi2SetReal: value reference 4 (label) is not a Real"),
    ] {
        assert_eq!(instance.set_real(references, &[1.0, 1.0]), Status::Error);
        assert_eq!(last_message(&log), expected);
    }
    assert_eq!(instance.set_integer(&[LEVEL, X], &[5, 1]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetInteger: value reference 0 (x) is not a Integer");
    assert_eq!(instance.set_string(&[X], &[Cow::Borrowed("1")]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetString: value reference 0 (x) is not a String");
    assert_eq!((instance.model_state().x, instance.model_state().level), (0.0, 1), "nothing set");
    assert_eq!((instance.model_state().gain, instance.model_state().label.as_str()), (4.0, "early"));
    // No Boolean variables: only n = 0 succeeds.
    assert_eq!(instance.set_boolean(&[], &[]), Status::Ok);
    assert_eq!(instance.set_boolean(&[X], &[1]), Status::Error);
    assert_eq!(last_message(&log), "fmi2SetBoolean: value reference 0 (x) is not a Boolean");
}

#[test]
fn get_checks_its_references_and_reads_every_type() {
    let (mut instance, log) = stepping();
    assert_eq!(instance.set_integer(&[LEVEL], &[-3]), Status::Ok);
    let mut integers = [0; 2];
    assert_eq!(instance.get_integer(&[LEVEL, COUNT], &mut integers), Status::Ok);
    assert_eq!(integers, [-3, 1], "one evaluation: ExitInitializationMode");
    let mut value = [0.0];
    assert_eq!(instance.get_real(&[1000], &mut value), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetReal: unknown value reference 1000");
    assert_eq!(instance.get_real(&[COUNT], &mut value), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetReal: value reference 11 (count) is not a Real");
    assert_eq!(instance.get_integer(&[Y], &mut [0]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetInteger: value reference 10 (y) is not a Integer");
    assert_eq!(instance.get_boolean(&[], &mut []), Status::Ok);
    assert_eq!(instance.get_boolean(&[X], &mut [0]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetBoolean: value reference 0 (x) is not a Boolean");
    assert_eq!(instance.get_string(&[X]), Err(Status::Error));
    assert_eq!(last_message(&log), "fmi2GetString: value reference 0 (x) is not a String");
}

/// The C strings fmi2GetString returns stay where they are until the next fmi2GetString (the
/// master holds pointers into them).
#[test]
fn returned_strings_are_kept_until_the_next_get_string() {
    let (mut instance, _) = new_instance();
    assert_eq!(instance.set_string(&[LABEL], &[Cow::Borrowed("wheel")]), Status::Ok);
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    let first = instance.get_string(&[LABEL, LABEL]).unwrap();
    assert_eq!(first.iter().map(|s| s.to_str().unwrap()).collect::<Vec<_>>(), ["wheel", "wheel"]);
    let pointer = first[0].as_ptr();
    // Other calls leave them alone.
    assert_eq!(instance.set_real(&[X], &[1.0]), Status::Ok);
    assert_eq!(get(&mut instance, Y), 2.0);
    assert_eq!(instance.returned_strings[0].as_ptr(), pointer);
    assert_eq!(instance.returned_strings[0].to_str(), Ok("wheel"));
    assert_eq!(instance.get_string(&[]).unwrap(), &[] as &[CString]);
}

/// In initialization mode a read of an output first computes the outputs from the values set;
/// the outputs otherwise change with ExitInitializationMode and DoStep only.
#[test]
fn outputs_follow_the_inputs_set_before_each_evaluation() {
    let (mut instance, _) = new_instance();
    instance.setup_experiment(0.5, Some(2.0));
    instance.enter_initialization_mode();
    instance.set_real(&[X], &[3.0]);
    assert_eq!(get(&mut instance, Y), 6.0);
    assert_eq!(get(&mut instance, X), 3.0);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    assert_eq!(instance.do_step(0.5, 0.25), Status::Ok);
    assert_eq!(get(&mut instance, Y), 6.0);
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.75));
}

/// Direct feedthrough (FMI 2.0, §4.2.1): in step mode an output read after an input it depends
/// on (`<ModelStructure>`) was written is computed at the new input — once, however often it
/// is read — without advancing the time or the model's state; an input no output depends on, a
/// parameter, or a step in between makes no extra evaluation.
#[test]
fn an_output_read_after_its_input_is_written_follows_it_within_the_step() {
    let (mut instance, told) = instance_logging_to(&Log::default());
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    instance.set_real(&[X], &[3.0]);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    assert_eq!(instance.do_step(0.0, 0.25), Status::Ok);
    let count = |instance: &mut Instance<Affine>| {
        let mut value = [0];
        assert_eq!(instance.get_integer(&[COUNT], &mut value), Status::Ok);
        value[0]
    };
    assert_eq!((get(&mut instance, Y), count(&mut instance)), (6.0, 2));
    instance.set_real(&[X], &[4.0]);
    assert_eq!(get(&mut instance, Y), 8.0, "the output at the new input");
    assert_eq!(get(&mut instance, Y), 8.0);
    assert_eq!(told.borrow().feedthroughs, 1, "one evaluation for two reads");
    assert_eq!(count(&mut instance), 2, "the state did not advance");
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.25), "nor the time");
    // A step computes the outputs itself: no feedthrough before or after it.
    instance.set_real(&[X], &[5.0]);
    assert_eq!(instance.do_step(0.25, 0.25), Status::Ok);
    assert_eq!((get(&mut instance, Y), count(&mut instance)), (10.0, 3));
    // A tunable parameter is not a feedthrough input (its effect waits for the step) …
    instance.set_real(&[OFFSET], &[1.0]);
    assert_eq!(get(&mut instance, Y), 10.0);
    assert_eq!(told.borrow().feedthroughs, 1);
    // … and a restored state is brought up to date at its own inputs when an output is read.
    let state = instance.get_fmu_state().unwrap();
    instance.set_real(&[X], &[6.0]);
    assert_eq!(instance.set_fmu_state(&state), Status::Ok);
    assert_eq!(get(&mut instance, Y), 11.0);
    assert_eq!((told.borrow().feedthroughs, count(&mut instance)), (2, 3));
}

/// A feedthrough that fails is the read's error, naming the call and the value; the outputs and
/// the state stay, and the next read tries again.
#[test]
fn a_feedthrough_that_fails_is_the_reads_error() {
    let (mut instance, log) = stepping();
    assert_eq!(instance.do_step(0.0, 0.25), Status::Ok);
    instance.set_real(&[X], &[f64::NAN]);
    let mut value = [0.0];
    assert_eq!(instance.get_real(&[Y], &mut value), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetReal: x = NaN is invalid: must be finite");
    instance.set_real(&[X], &[2.0]);
    assert_eq!(get(&mut instance, Y), 2.0 * 2.0);
}

/// An evaluation's warning is the status of the call that evaluated (logged with its name), and
/// the outputs and time are kept; its error leaves the state, the time and the mode as they
/// were, so that the master can correct the value.
#[test]
fn an_evaluation_warns_or_fails_naming_the_call() {
    let (mut instance, log) = new_instance();
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    instance.set_real(&[X], &[WARNING_X]);
    assert_eq!(instance.get_real(&[Y], &mut [0.0]), Status::Warning);
    assert_eq!(log.borrow().last().unwrap().0, Status::Warning);
    assert_eq!(last_message(&log), "fmi2GetReal: x = 7 is where the model warns");
    assert_eq!(instance.get_integer(&[COUNT], &mut [0]), Status::Warning, "an output read: evaluated again");
    assert_eq!(instance.get_integer(&[LEVEL], &mut [0]), Status::Ok, "no output read");
    assert_eq!(instance.exit_initialization_mode(), Status::Warning);
    assert_eq!(last_message(&log), "fmi2ExitInitializationMode: x = 7 is where the model warns");
    assert_eq!(instance.mode(), StepComplete);
    assert_eq!(instance.do_step(0.0, 0.5), Status::Warning);
    assert_eq!(last_message(&log), "fmi2DoStep: x = 7 is where the model warns");
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.5));
    assert_eq!(get(&mut instance, Y), 14.0);
    let before = instance.model_state().clone();
    instance.set_real(&[X], &[f64::NAN]);
    assert_eq!(instance.do_step(0.5, 0.5), Status::Error);
    assert_eq!(last_message(&log), "fmi2DoStep: x = NaN is invalid: must be finite");
    assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.5));
    assert_eq!((instance.model_state().y, instance.model_state().count), (before.y, before.count));
    // At initialization: it stays in initialization mode.
    let (mut instance, log) = new_instance();
    instance.setup_experiment(0.0, None);
    instance.enter_initialization_mode();
    instance.set_real(&[X], &[f64::INFINITY]);
    assert_eq!(instance.exit_initialization_mode(), Status::Error);
    assert_eq!(last_message(&log), "fmi2ExitInitializationMode: x = inf is invalid: must be finite");
    assert_eq!(instance.mode(), InitializationMode, "the master may correct the value");
    instance.set_real(&[X], &[1.0]);
    assert_eq!(instance.exit_initialization_mode(), Status::Ok);
}

#[test]
fn do_step_checks_time_and_step_size() {
    let (mut instance, log) = new_instance();
    instance.setup_experiment(0.0, Some(1.0));
    instance.enter_initialization_mode();
    instance.exit_initialization_mode();
    for (t, h, expected) in [
        (0.0, 0.0, "fmi2DoStep: communicationStepSize = 0 is invalid: must be finite and > 0"),
        (0.0, -1e-3, "fmi2DoStep: communicationStepSize = -0.001 is invalid: must be finite and > 0"),
        (0.0, f64::NAN, "fmi2DoStep: communicationStepSize = NaN is invalid: must be finite and > 0"),
        (0.1, 1e-3, "fmi2DoStep: currentCommunicationPoint = 0.1 is not the instance's time 0"),
        (f64::NAN, 1e-3, "fmi2DoStep: currentCommunicationPoint = NaN is not the instance's time 0"),
        (0.0, 1.5, "fmi2DoStep: the step would end at 1.5, after stopTime = 1"),
    ] {
        assert_eq!(instance.do_step(t, h), Status::Error);
        assert_eq!(last_message(&log), expected);
    }
    // A master's own rounding of t + h is accepted.
    assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
    assert_eq!(instance.do_step(0.1 + 1e-15, 0.2), Status::Ok);
    // Variable step sizes, each continuing from the end of the last.
    for (t, h) in [(0.3, 1e-3), (0.301, 0.249), (0.55, 0.45)] {
        assert_eq!(instance.do_step(t, h), Status::Ok, "t = {t}, h = {h}");
    }
}

/// The model is told of what makes its derived data stale: a parameter written (not an input),
/// a state restored, a reset; a reset also brings back the start values.
#[test]
fn the_model_is_told_when_parameters_change_a_state_is_restored_or_the_instance_reset() {
    let log = Log::default();
    let (mut instance, told) = instance_logging_to(&log);
    let counts = |told: &Rc<RefCell<Told>>| {
        let told = told.borrow();
        (told.parameters_changed, told.restorings, told.resets)
    };
    instance.set_real(&[X], &[1.0]);
    assert_eq!(counts(&told), (0, 0, 0));
    instance.set_real(&[X, OFFSET], &[1.0, 0.5]);
    instance.set_integer(&[LEVEL], &[2]);
    instance.set_string(&[LABEL], &[Cow::Borrowed("b")]);
    assert_eq!(instance.set_real(&[Y], &[1.0]), Status::Error);
    assert_eq!(counts(&told), (3, 0, 0), "once per call that writes a parameter, not for a refused one");
    let state = instance.get_fmu_state().unwrap();
    assert_eq!(instance.set_fmu_state(&state), Status::Ok);
    assert_eq!(counts(&told), (3, 1, 0));
    instance.setup_experiment(2.0, None);
    instance.enter_initialization_mode();
    instance.exit_initialization_mode();
    assert_eq!(instance.reset(), Status::Ok);
    assert_eq!(counts(&told), (3, 1, 1));
    assert_eq!((instance.mode(), instance.model_state()), (Instantiated, &Affine::start()));
    // A new run starts from the new start time.
    instance.setup_experiment(3.0, None);
    instance.enter_initialization_mode();
    instance.exit_initialization_mode();
    assert_eq!(instance.do_step(3.0, 0.5), Status::Ok);
}

#[test]
fn an_fmu_state_restores_mode_time_and_every_value() {
    let (mut instance, _) = stepping();
    instance.set_real(&[X, OFFSET], &[1.5, 0.25]);
    instance.set_integer(&[LEVEL], &[9]);
    instance.do_step(0.0, 0.5);
    let saved = instance.get_fmu_state().unwrap();
    let before =
        (instance.mode(), instance.model_state().clone(), instance.get_real_status(StatusKind::LastSuccessfulTime));
    instance.set_real(&[X], &[-1.0]);
    instance.do_step(0.5, 0.5);
    instance.terminate();
    assert_eq!(instance.set_fmu_state(&saved), Status::Ok);
    let after =
        (instance.mode(), instance.model_state().clone(), instance.get_real_status(StatusKind::LastSuccessfulTime));
    assert_eq!(after, before);
    // Through bytes, into an instance in another mode: the same.
    let mut bytes = vec![0; instance.serialized_fmu_state_size(&saved).unwrap()];
    assert_eq!(instance.serialize_fmu_state(&saved, &mut bytes), Status::Ok);
    assert_eq!(bytes, Instance::<Affine>::encode_state(&saved));
    assert_eq!(&bytes[..8], b"AFFstate");
    let (mut fresh, _) = new_instance();
    let restored = fresh.deserialize_fmu_state(&bytes).unwrap();
    assert_eq!(restored, saved);
    fresh.set_fmu_state(&restored);
    assert_eq!((fresh.mode(), fresh.model_state()), (before.0, &before.1));
}

#[test]
fn serialisation_checks_sizes_and_rejects_bad_bytes_by_reason() {
    let (mut instance, log) = stepping();
    let state = instance.get_fmu_state().unwrap();
    let size = instance.serialized_fmu_state_size(&state).unwrap();
    assert_eq!(instance.serialize_fmu_state(&state, &mut vec![0; size + 1]), Status::Error);
    let expected = format!(
        "fmi2SerializeFMUstate: size = {} is not the serialized size {size} (see fmi2SerializedFMUstateSize)",
        size + 1
    );
    assert_eq!(last_message(&log), expected);
    assert_eq!(instance.deserialize_fmu_state(b"AFFst").unwrap_err(), Status::Error);
    let expected = "fmi2DeSerializeFMUstate: serializedState rejected: truncated: 5 bytes, the state needs at least 19";
    assert_eq!(last_message(&log), expected);
    // Intact bytes of a state this FMU cannot be in: the model's payload checks, the layer's
    // checks of mode and times, then the model's of what the state holds.
    /// A change made to a saved state.
    type Forgery = fn(&mut FmuState<Values>);
    let forged = |forge: Forgery| {
        let mut state = state.clone();
        forge(&mut state);
        Instance::<Affine>::encode_state(&state)
    };
    let forgeries: [(Forgery, &str); 4] = [
        (|s| s.mode = Mode::Fatal, "mode byte 4 is not a state an FMU state can hold"),
        (
            |s| s.time = f64::NAN,
            "not a state this FMU can be in: time = NaN is invalid: must be finite and within ±1e12 s",
        ),
        (|s| s.stop_time = Some(-1.0), "not a state this FMU can be in: stopTime = -1 is invalid: must be >= time = 0"),
        (
            |s| s.model.y = f64::INFINITY,
            "not a state this FMU can be in: y = inf is invalid: an output is always finite",
        ),
    ];
    for (forge, reason) in forgeries {
        assert_eq!(instance.deserialize_fmu_state(&forged(forge)).unwrap_err(), Status::Error);
        assert_eq!(last_message(&log), format!("fmi2DeSerializeFMUstate: serializedState rejected: {reason}"));
    }
    // A model whose payload can hold a fatal mode: the layer refuses it.
    let mut fatal = state.clone();
    fatal.mode = Mode::Fatal;
    assert_eq!(check_sense::<Affine>(&fatal), Err("mode fatal".to_owned()));
}

#[test]
fn directional_derivatives_are_the_models_or_unsupported() {
    let (mut instance, log) = stepping();
    let mut rates = [f64::NAN; 2];
    assert_eq!(instance.get_directional_derivative(&[Y, Y], &[X, X], &[1.0, 0.5], &mut rates), Status::Ok);
    assert_eq!(rates, [3.0, 3.0]);
    assert_eq!(instance.get_directional_derivative(&[Y], &[GAIN], &[1.0], &mut rates[..1]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetDirectionalDerivative: value reference 1 cannot be a known");
    // A model that provides none: refused as unsupported, in the modes the call is legal in.
    let mut wheel = Instance::<NoDerivatives>::instantiate(arguments(None), Box::new(Recorder(log.clone()))).unwrap();
    assert_eq!(wheel.get_directional_derivative(&[Y], &[X], &[1.0], &mut rates[..1]), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetDirectionalDerivative: illegal call in state instantiated");
    wheel.enter_initialization_mode();
    assert_eq!(wheel.get_directional_derivative(&[Y], &[X], &[1.0], &mut rates[..1]), Status::Error);
    assert_eq!(
        last_message(&log),
        "fmi2GetDirectionalDerivative: not supported (providesDirectionalDerivative = false in modelDescription.xml)"
    );
}

/// [`Affine`] without directional derivatives.
struct NoDerivatives(Affine);

impl Model for NoDerivatives {
    type State = Values;

    const GUID: &'static str = Affine::GUID;
    const MODEL_IDENTIFIER: &'static str = Affine::MODEL_IDENTIFIER;
    const LOG_CATEGORIES: &'static [&'static str] = Affine::LOG_CATEGORIES;
    const STATE_LAYOUT_TAG: u64 = Affine::STATE_LAYOUT_TAG;
    const STATE_MAGIC: [u8; 8] = Affine::STATE_MAGIC;
    const STATE_FORMAT_VERSION: u16 = Affine::STATE_FORMAT_VERSION;

    fn instantiate(resource_location: Option<&str>) -> Result<(Self, Option<String>), String> {
        Affine::instantiate(resource_location).map(|(model, note)| (NoDerivatives(model), note))
    }

    fn reset(&mut self) {}

    fn start() -> Values {
        Affine::start()
    }

    fn variable(value_reference: u32) -> Option<&'static Variable> {
        Affine::variable(value_reference)
    }

    fn variables() -> &'static [Variable] {
        Affine::variables()
    }

    fn real(state: &Values, value_reference: u32) -> Option<f64> {
        Affine::real(state, value_reference)
    }

    fn real_mut(state: &mut Values, value_reference: u32) -> Option<&mut f64> {
        Affine::real_mut(state, value_reference)
    }

    fn evaluate(&mut self, state: &mut Values, evaluation: Evaluation) -> Result<Option<String>, String> {
        self.0.evaluate(state, evaluation)
    }

    fn encode(state: &FmuState<Values>) -> Vec<u8> {
        Affine::encode(state)
    }

    fn decode(payload: &[u8]) -> Result<FmuState<Values>, String> {
        Affine::decode(payload)
    }

    fn check_state(state: &Values, mode: Mode) -> Result<(), String> {
        Affine::check_state(state, mode)
    }
}

/// [`keep_if_finite`]: a model that computes on a copy keeps it only with every output finite,
/// naming the first that is not, with its inputs.
#[test]
fn keep_if_finite_keeps_only_finite_outputs() {
    let mut state = Affine::start();
    state.x = 1e308;
    let error = keep_if_finite::<Affine>(&mut state, |next| {
        next.y = next.x * 10.0;
        next.count = 99;
        Ok(())
    })
    .unwrap_err();
    assert_eq!(
        error,
        "y = inf is not finite, computed from x = 1e308: a value beyond the floating-point range; the previous values \
         are kept"
    );
    assert_eq!((state.y, state.count), (0.0, 0));
    assert_eq!(
        keep_if_finite::<Affine>(&mut state, |next| Err(format!("x = {:?} is too large", next.x))),
        Err("x = 1e308 is too large".to_owned())
    );
    assert_eq!(
        keep_if_finite::<Affine>(&mut state, |next| {
            next.y = 1.0;
            Ok(())
        }),
        Ok(())
    );
    assert_eq!(state.y, 1.0);
}

/// The run data of a plain-bytes payload: round trip at its length; one byte short is refused
/// naming both lengths, and a payload of the run data alone is a state with an empty model.
#[test]
fn run_data_round_trips_and_a_short_payload_is_refused() {
    let state = FmuState { mode: Mode::StepComplete, time: 0.25, stop_time: Some(2.0), model: () };
    let payload = encode_run(&state, &[7, 8]);
    assert_eq!(payload.len(), RUN_BYTES + 2);
    let decoded = decode_run(&payload).unwrap();
    assert_eq!(
        (decoded.mode, decoded.time, decoded.stop_time, decoded.model),
        (state.mode, 0.25, Some(2.0), &[7, 8][..])
    );
    let alone = decode_run(&payload[..RUN_BYTES]).unwrap();
    assert!(alone.model.is_empty());
    assert_eq!(
        decode_run(&payload[..RUN_BYTES - 1]).map(|s| s.time),
        Err("corrupted: a payload of 16 bytes, shorter than its 17-byte run data".to_owned())
    );
}
