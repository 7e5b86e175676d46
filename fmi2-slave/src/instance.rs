//! The generic FMU instance: the Co-Simulation and Model Exchange state machines
//! ([`crate::mode`]), the continuous states and their derivatives, logging, status
//! inquiries, Get/Set of Real, Integer, Enumeration and String variables checked against the
//! model's access table, the communication-step checks, FMU states in the versioned state
//! format ([`crate::state_format`]) and directional derivatives, around a [`Model`] that holds
//! its values and computes. [`Instance`] implements [`Slave`], so a cdylib needs nothing but
//! `export_fmi2!(fmi2_slave::instance::Instance<MyModel>)`. Both FMUs of the workspace are
//! models on it: the contact FMU (`fmu/src/model.rs`) and the wheelset (`wheelset/src/model.rs`).
//!
//! Rules (FMI 2.0.4, section 4.2.4), with the functions here that check arguments and word
//! messages ([`instantiate_problem`], [`experiment_problem`], [`step_end`], [`panic_message`],
//! [`discard_message`], [`unknown_categories_message`]):
//! - a call outside the states that allow it returns `Error` and logs
//!   `fmi2XXX: illegal call in state YYY`, the state unchanged;
//! - an invalid value is reported where the model computes (ExitInitializationMode, DoStep, a
//!   Get of an output in initialization mode) as `Error` naming the variable and value, and the
//!   instance keeps its state so that the master can correct it (it never enters the standard's
//!   `error` state); an evaluation may instead warn (`Warning`, logged) and keep its outputs;
//! - a panic inside a call becomes `Fatal`, after which the instance accepts nothing but
//!   fmi2FreeInstance.
//!
//! The hot path (fmi2SetReal/DoStep/GetReal) does no allocation, no string comparison and no
//! search: one byte of the model's dense access table per value reference, a bit test for the
//! state, and a log filter decided once per fmi2SetDebugLogging; the model evaluates in place.

use std::borrow::Cow;
use std::ffi::CString;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::logging::{LogFilter, LogSink, Logger, Status};
use crate::mode::{Call, Interface, Mode, Modes, LIVE};
use crate::state_format::StateFormat;
use serde::{Deserialize, Serialize};

use crate::variables::{access, Causality, Kind, Variable};
use crate::{EventInfo, InstantiateArguments, Slave, StatusKind, Unsupported};

/// Two communication points closer than this (relative to max(1, |t|)) are the same: masters
/// compute t + h in their own rounding.
pub const TIME_TOLERANCE: f64 = 1e-9;

/// fmi2Instantiate's arguments checked for an FMU with this GUID and model identifier, which
/// supports Model Exchange or not: why they are refused (an empty name, an unknown fmuType,
/// Model Exchange where the FMU has none, another GUID), if they are.
pub fn instantiate_problem(
    arguments: &InstantiateArguments,
    guid: &str,
    model_identifier: &str,
    model_exchange: bool,
) -> Option<String> {
    if arguments.instance_name.trim().is_empty() {
        Some("instanceName must not be empty".to_owned())
    } else if let Err(fmu_type) = arguments.interface {
        Some(format!("fmuType = {fmu_type} is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)"))
    } else if arguments.interface == Ok(Interface::ModelExchange) && !model_exchange {
        Some(format!("this FMU supports Co-Simulation only (modelIdentifier {model_identifier})"))
    } else if arguments.guid != guid {
        Some(format!("fmuGUID {} does not match this FMU's GUID {guid}", arguments.guid))
    } else {
        None
    }
}

/// The largest magnitude of an instance's time \[s\] (about 31 700 years): beyond it a step of
/// a millisecond is below the resolution of the time (its ulp is 1.2e-4 s at 1e12 s), so a
/// time of −1e300 would never advance.
pub const MAX_TIME: f64 = 1e12;

/// Why `time` (named `name`) cannot be an instance's time, if it cannot: not finite, or beyond
/// ±[`MAX_TIME`].
pub fn time_problem(name: &str, time: f64) -> Option<String> {
    (!(-MAX_TIME..=MAX_TIME).contains(&time))
        .then(|| format!("{name} = {time:e} is invalid: must be finite and within ±{MAX_TIME:e} s"))
}

/// fmi2SetupExperiment's times checked: why they are refused, if they are.
pub fn experiment_problem(start_time: f64, stop_time: Option<f64>) -> Option<String> {
    times_problem(("startTime", start_time), stop_time)
}

/// Why a time (`name`, value) and a stop time cannot be an instance's, if they cannot: the
/// time as [`time_problem`] checks it, a stop time NaN or before it. fmi2SetupExperiment's
/// check, and a restored FMU state's (its time named `time`).
pub fn times_problem((name, time): (&str, f64), stop_time: Option<f64>) -> Option<String> {
    time_problem(name, time).or_else(|| {
        stop_time
            .filter(|stop| stop.is_nan() || *stop < time)
            .map(|stop| format!("stopTime = {stop} is invalid: must be >= {name} = {time}"))
    })
}

/// fmi2DoStep's arguments checked against the instance's `time` and `stop_time`: the step's end,
/// or why the step is refused.
pub fn step_end(time: f64, stop_time: Option<f64>, t: f64, h: f64) -> Result<f64, String> {
    if !(h > 0.0 && h.is_finite()) {
        return Err(format!("communicationStepSize = {h} is invalid: must be finite and > 0"));
    }
    let tolerance = TIME_TOLERANCE * time.abs().max(1.0);
    let on_time = (t - time).abs() <= tolerance; // false for a NaN t
    if !on_time {
        return Err(format!("currentCommunicationPoint = {t} is not the instance's time {time}"));
    }
    let end = t + h;
    if !(-MAX_TIME..=MAX_TIME).contains(&end) {
        return Err(format!(
            "the step would end at {end:e}: currentCommunicationPoint = {t:e} plus communicationStepSize = {h:e} is \
             beyond ±{MAX_TIME:e} s"
        ));
    }
    if end == t {
        return Err(format!(
            "communicationStepSize = {h:e} is below the resolution of the time {t:e}: the step would not advance it"
        ));
    }
    match stop_time.filter(|stop| end > stop + tolerance) {
        Some(stop) => Err(format!("the step would end at {end}, after stopTime = {stop}")),
        None => Ok(end),
    }
}

/// fmi2SerializeFMUstate's copy of an `encoded` state into the master's buffer `bytes`, or why
/// not (a buffer of another size than fmi2SerializedFMUstateSize gave).
pub fn copy_serialized(encoded: &[u8], bytes: &mut [u8]) -> Result<(), String> {
    if bytes.len() != encoded.len() {
        let (size, needed) = (bytes.len(), encoded.len());
        return Err(format!("size = {size} is not the serialized size {needed} (see fmi2SerializedFMUstateSize)"));
    }
    bytes.copy_from_slice(encoded);
    Ok(())
}

/// The message of a panic caught in `call`.
pub fn panic_message(call: Call, payload: &(dyn std::any::Any + Send)) -> String {
    let reason = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_owned());
    format!("{call}: internal error ({reason}); this instance can only be freed")
}

/// The message of an fmi2GetXXXStatus asked for a kind there is nothing to report on.
pub fn discard_message(call: Call, kind: StatusKind) -> String {
    format!("{call}: no {kind:?} to report: fmi2DoStep never returns fmi2Pending or fmi2Discard")
}

/// The warning of an fmi2SetDebugLogging that named categories the FMU does not have, if it did.
pub fn unknown_categories_message(categories: &[&str], known: &[&str]) -> Option<String> {
    let unknown: Vec<&&str> = categories.iter().filter(|c| !known.contains(c)).collect();
    (!unknown.is_empty())
        .then(|| format!("{}: unknown log categories {unknown:?} ignored; known: {known:?}", Call::SetDebugLogging))
}

/// What [`Model::evaluate`] is asked to compute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Evaluation {
    /// The outputs at the start, from the parameters and inputs (ExitInitializationMode; a read
    /// of an output in initialization mode).
    Initialise,
    /// Over one communication step from `time` of `size` > 0, the inputs held.
    Step { time: f64, size: f64 },
    /// The outputs and the state derivatives at the current inputs (and, in Model Exchange, the
    /// continuous states) at the instance's `time`, without advancing the model's state: direct
    /// feedthrough (a read of an output after an input it depends on was written in step mode),
    /// and every evaluation of Model Exchange (fmi2GetDerivatives, a read of an output after
    /// fmi2SetContinuousStates, fmi2SetTime or an input was written).
    Feedthrough { time: f64 },
}

/// A model as the generated interface and its physics give it: its variables' values (what an
/// FMU state saves, [`Model::State`]) and, in the model itself, whatever the instance keeps that
/// is not state (a cache derived from the parameters, the resources directory).
pub trait Model: Sized {
    /// What an FMU state saves beyond the mode, time and stop time: every variable's value and
    /// the state the model carries from step to step.
    type State: Clone + PartialEq + std::fmt::Debug;

    /// The GUID that fmi2Instantiate requires.
    const GUID: &'static str;
    const MODEL_IDENTIFIER: &'static str;
    /// The log categories of `<LogCategories>`.
    const LOG_CATEGORIES: &'static [&'static str];
    /// Tags a serialized FMU state with the variable layout it was written with.
    const STATE_LAYOUT_TAG: u64;
    /// The first bytes of this FMU's serialized states ([`crate::state_format`]).
    const STATE_MAGIC: [u8; 8];
    /// The version of this FMU's payload ([`Model::encode`]) in its serialized states.
    const STATE_FORMAT_VERSION: u16;
    /// `providesDirectionalDerivative`: whether [`Model::directional_derivative`] is implemented;
    /// if not, fmi2GetDirectionalDerivative is refused as unsupported.
    const PROVIDES_DIRECTIONAL_DERIVATIVE: bool = false;
    /// Whether the FMU declares `<ModelExchange>`: fmi2Instantiate accepts fmi2ModelExchange.
    const MODEL_EXCHANGE: bool = false;
    /// The continuous states of Model Exchange as (state, its derivative, nominal value), in the
    /// order of `<Derivatives>`: value references into [`Model::real`]. The derivatives are
    /// computed by [`Model::evaluate`].
    const CONTINUOUS_STATES: &'static [(u32, u32, f64)] = &[];
    /// `numberOfEventIndicators`.
    const EVENT_INDICATORS: usize = 0;

    /// The model of a new instance given the master's resource location (a `file:` URI, or
    /// `None` for NULL), and a note for the call trace; or why the FMU cannot be instantiated
    /// (a resource it needs is missing, naming it).
    fn instantiate(resource_location: Option<&str>) -> Result<(Self, Option<String>), String>;
    /// fmi2Reset: back to the model of a new instance (the resources stay).
    fn reset(&mut self);
    /// The start values.
    fn start() -> Self::State;

    /// The variable with this value reference.
    fn variable(value_reference: u32) -> Option<&'static Variable>;
    /// Every variable, in the model description's order.
    fn variables() -> &'static [Variable];
    /// The [`access`] bits of a value reference (0 if there is none). Generated models answer
    /// from their dense table (`access_of`), which is what the hot path reads.
    #[inline]
    fn access(value_reference: u32) -> u8 {
        Self::variable(value_reference).map_or(0, |v| access::of(v, Self::variables()))
    }

    fn real(state: &Self::State, value_reference: u32) -> Option<f64>;
    fn real_mut(state: &mut Self::State, value_reference: u32) -> Option<&mut f64>;
    /// An Integer or Enumeration value (none without such variables).
    fn integer(_state: &Self::State, _value_reference: u32) -> Option<i32> {
        None
    }
    fn integer_mut(_state: &mut Self::State, _value_reference: u32) -> Option<&mut i32> {
        None
    }
    /// A String value (none without such variables).
    fn string(_state: &Self::State, _value_reference: u32) -> Option<&str> {
        None
    }
    fn string_mut(_state: &mut Self::State, _value_reference: u32) -> Option<&mut String> {
        None
    }

    /// Computes the outputs (and advances the model's state, for a step) in `state`: `Ok` with a
    /// warning for the master if the outputs are to be used with care (an iteration that
    /// stopped at its limits), or why not, naming the variable and its value; on error nothing
    /// is changed. [`keep_if_finite`] gives that for a model that computes on a copy.
    fn evaluate(&mut self, state: &mut Self::State, evaluation: Evaluation) -> Result<Option<String>, String>;
    /// A parameter was written (fmi2Set*): what the model derived from the parameters is stale.
    fn parameters_changed(&mut self) {}
    /// Why the model cannot run as Model Exchange with the values of `state`, if it cannot (an
    /// option whose state advances only over Co-Simulation steps): checked at
    /// fmi2ExitInitializationMode, which then fails and stays in initialization mode.
    fn model_exchange_problem(_state: &Self::State) -> Option<String> {
        None
    }
    /// fmi2CompletedIntegratorStep (Model Exchange), with the outputs and derivatives up to date
    /// at `state`, the master's accepted point at `time`: `Ok(true)` if the model asks for event
    /// mode there (a step event: a continuous state to reset, [`Model::new_discrete_states`]),
    /// `Ok(false)` to go on, or why it cannot go on (the reason names the variable and its
    /// value).
    fn completed_integrator_step(&mut self, _state: &Self::State, _time: f64) -> Result<bool, String> {
        Ok(false)
    }
    /// fmi2NewDiscreteStates (Model Exchange, event mode), with the outputs up to date at
    /// `state`: resets the continuous states the event calls for, in place; whether any changed.
    fn new_discrete_states(&mut self, _state: &mut Self::State) -> bool {
        false
    }
    /// fmi2GetEventIndicators (Model Exchange), with the outputs up to date at `state`: the
    /// [`Model::EVENT_INDICATORS`] values, whose sign changes where the model's outputs jump.
    /// Only called with a non-zero count.
    fn event_indicators(&self, _state: &Self::State, _indicators: &mut [f64]) {}
    /// fmi2SetFMUstate is about to replace `current` by `restored`.
    fn restoring(&mut self, _current: &Self::State, _restored: &Self::State) {}
    /// fmi2GetDirectionalDerivative (only called with [`Model::PROVIDES_DIRECTIONAL_DERIVATIVE`]):
    /// `unknown_rates` = J·`known_rates` at `state`, or why not (an argument or a value, named).
    fn directional_derivative(
        &mut self,
        _state: &Self::State,
        _unknowns: &[u32],
        _knowns: &[u32],
        _known_rates: &[f64],
        _unknown_rates: &mut [f64],
    ) -> Result<(), String> {
        Err("not supported".to_owned())
    }

    /// The payload of a serialized FMU state (the slave layer's header goes around it,
    /// [`Instance::encode_state`]); deterministic, so that its length is the serialized size.
    fn encode(state: &FmuState<Self::State>) -> Vec<u8>;
    /// The inverse of [`Model::encode`], checking every byte.
    fn decode(payload: &[u8]) -> Result<FmuState<Self::State>, String>;
    /// Whether a deserialized state can be this FMU's in `mode` (its sense, after the bytes'
    /// integrity and the mode, time and stop time are checked): what the state holds (finite
    /// outputs, the model's bounds) and, where the model requires it, the parameters. Inputs,
    /// and parameters the next computation checks, may hold any value, as after fmi2SetReal.
    /// The reason names the variable and its value.
    fn check_state(state: &Self::State, mode: Mode) -> Result<(), String>;
}

/// For a [`Model::evaluate`] that computes on a copy of the state: runs `compute` on a copy and
/// keeps it only if it succeeded with every output finite: the last guard of "never NaN or Inf
/// out, never a half-updated model", for finite values whose arithmetic overflows (V/r with
/// r = 5e-324) where the model's own checks missed it.
pub fn keep_if_finite<M: Model>(
    state: &mut M::State,
    compute: impl FnOnce(&mut M::State) -> Result<(), String>,
) -> Result<(), String> {
    let mut next = state.clone();
    compute(&mut next)?;
    if let Some(problem) = non_finite_output::<M>(&next) {
        return Err(problem);
    }
    *state = next;
    Ok(())
}

/// Why `state`'s outputs cannot be kept, if they cannot: the first non-finite output, its value
/// and what it was computed from: the inputs it depends on (`<ModelStructure>`) with their
/// values, or, for an output no input acts on directly, the parameters and the state.
fn non_finite_output<M: Model>(state: &M::State) -> Option<String> {
    let value = |variable: &Variable| M::real(state, variable.value_reference).unwrap_or(f64::NAN);
    // The values in Debug form: 1e308, not its 309 digits.
    let (output, x) = M::variables()
        .iter()
        .filter(|v| matches!(v.causality, Causality::Output | Causality::Local) && matches!(v.kind, Kind::Real { .. }))
        .map(|v| (v, value(v)))
        .find(|(_, x)| !x.is_finite())?;
    let sources = if output.dependencies.is_empty() {
        "the parameters and the state (no input acts on it directly)".to_owned()
    } else {
        let inputs: Vec<String> = output
            .dependencies
            .iter()
            .filter_map(|&r| M::variable(r))
            .map(|v| format!("{} = {:?}", v.name, value(v)))
            .collect();
        inputs.join(", ")
    };
    Some(format!(
        "{} = {x:?} is not finite, computed from {sources}: a value beyond the floating-point range; the previous \
         values are kept",
        output.name
    ))
}

/// Mode, time, stop time and the model's state: what an FMU state saves and restores. Not
/// saved, because they are the master's settings rather than the instance's state: the
/// instance name, the resource location, the logger and the debug-logging selection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FmuState<S> {
    /// The state-machine mode (never `Fatal`: a fatal instance gives no state).
    pub mode: Mode,
    /// The instance's time: the end of the last step.
    pub time: f64,
    /// fmi2SetupExperiment's stop time, if one was given.
    pub stop_time: Option<f64>,
    /// The variables' values and the model's state.
    pub model: S,
}

impl<S> FmuState<S> {
    /// A freshly instantiated instance's: `model` (the start values), time 0.
    pub fn instantiated(model: S) -> Self {
        FmuState { mode: Mode::Instantiated, time: 0.0, stop_time: None, model }
    }
}

/// The length of [`encode_run`]'s run data: mode, time, stop time.
const RUN_BYTES: usize = 1 + 8 + 8;

/// A payload for a model whose state is plain bytes ([`Model::encode`]): mode (1 byte), time
/// (8), stop time (8, NaN for none), then `model`; little-endian.
pub fn encode_run<S>(state: &FmuState<S>, model: &[u8]) -> Vec<u8> {
    let mut payload = Vec::with_capacity(RUN_BYTES + model.len());
    payload.push(state.mode as u8);
    payload.extend(state.time.to_le_bytes());
    payload.extend(state.stop_time.unwrap_or(f64::NAN).to_le_bytes());
    payload.extend(model);
    payload
}

/// The inverse of [`encode_run`]: the run data, with the model's bytes.
pub fn decode_run(payload: &[u8]) -> Result<FmuState<&[u8]>, String> {
    if payload.len() < RUN_BYTES {
        return Err(format!(
            "corrupted: a payload of {} bytes, shorter than its {RUN_BYTES}-byte run data",
            payload.len()
        ));
    }
    let word = |at: usize| f64::from_le_bytes(<[u8; 8]>::try_from(&payload[at..at + 8]).expect("8 bytes"));
    let modes = [
        Mode::Instantiated,
        Mode::InitializationMode,
        Mode::StepComplete,
        Mode::EventMode,
        Mode::ContinuousTimeMode,
        Mode::Terminated,
    ];
    let Some(&mode) = modes.iter().find(|m| **m as u8 == payload[0]) else {
        return Err(format!("mode byte {} is not a state an FMU state can hold", payload[0]));
    };
    let (time, stop) = (word(1), word(9));
    Ok(FmuState { mode, time, stop_time: (!stop.is_nan()).then_some(stop), model: &payload[RUN_BYTES..] })
}

/// What an intact but forged state must still satisfy: a live mode, a time fmi2SetupExperiment
/// and the steps could have reached (finite, within ±[`MAX_TIME`]), a stop time the time has not
/// passed, and the model's own checks.
fn check_sense<M: Model>(state: &FmuState<M::State>) -> Result<(), String> {
    if state.mode == Mode::Fatal {
        return Err("mode fatal".to_owned());
    }
    if let Some(problem) = times_problem(("time", state.time), state.stop_time) {
        return Err(problem);
    }
    M::check_state(&state.model, state.mode)
}

/// The FMI base types of the Get/Set functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ValueType {
    Real,
    Integer,
    Boolean,
    String,
}

impl ValueType {
    /// The [`access`] bit of the type (none for Boolean: no FMU of this layer has such
    /// variables).
    #[inline]
    fn access_bit(self) -> u8 {
        match self {
            ValueType::Real => access::REAL,
            ValueType::Integer => access::INTEGER,
            ValueType::String => access::STRING,
            ValueType::Boolean => 0,
        }
    }

    fn name(self) -> &'static str {
        match self {
            ValueType::Real => "Real",
            ValueType::Integer => "Integer",
            ValueType::Boolean => "Boolean",
            ValueType::String => "String",
        }
    }
}

/// One instance of an FMU whose model is `M`.
pub struct Instance<M: Model> {
    name: String,
    resource_location: Option<String>,
    /// Mode, time and the model's state: exactly what an FMU state saves and restores.
    run: FmuState<M::State>,
    /// What is not state: derived from the parameters (told when they change) or the master's
    /// settings (the resources).
    model: M,
    /// What the last fmi2GetString returned: the master's pointers point into these.
    returned_strings: Vec<CString>,
    /// The master's logger (with its own copy of the instance name) behind the log filter.
    log: Logger,
    /// The interface the master instantiated (fmi2Instantiate's `fmuType`).
    interface: Interface,
    /// The [`access`] bits whose writing makes the outputs stale: [`access::FEEDTHROUGH`] in
    /// Co-Simulation, any in Model Exchange (one bit test on the hot path).
    stale_on: u8,
    /// Whether what the outputs (and state derivatives) are computed from was written since
    /// they were last computed: in Co-Simulation an input that an output depends on directly
    /// ([`access::FEEDTHROUGH`]), in Model Exchange any input, the continuous states or the
    /// time. The next read of an output (or fmi2GetDerivatives) after initialization computes
    /// them first (FMI 2.0, §4.2.1: a master may set inputs and read the outputs that depend
    /// on them to solve an algebraic loop; §3.2: Model Exchange evaluates on demand).
    outputs_stale: bool,
}

impl<M: Model> Instance<M> {
    /// The name the master gave.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The resource location the master gave (`None` if it passed NULL).
    pub fn resource_location(&self) -> Option<&str> {
        self.resource_location.as_deref()
    }

    /// The state-machine mode.
    pub fn mode(&self) -> Mode {
        self.run.mode
    }

    /// The interface the master instantiated.
    pub fn interface(&self) -> Interface {
        self.interface
    }

    /// The model's state: every variable's value (inputs, parameters, last outputs) and what it
    /// carries from step to step.
    pub fn model_state(&self) -> &M::State {
        &self.run.model
    }

    /// The byte format of this FMU's serialized states (for tools and tests that read or forge
    /// one: its payload is [`Model::encode`]'s).
    pub fn state_format() -> StateFormat {
        StateFormat {
            magic: M::STATE_MAGIC,
            version: M::STATE_FORMAT_VERSION,
            layout_tag: M::STATE_LAYOUT_TAG,
            guid: M::GUID,
        }
    }

    /// The serialized bytes of `state` (their length is exactly what fmi2SerializedFMUstateSize
    /// reports: the encoding is deterministic).
    pub fn encode_state(state: &FmuState<M::State>) -> Vec<u8> {
        Self::state_format().encode(&M::encode(state))
    }

    /// The state in `bytes`, or why they are not a state this FMU wrote or can be in: the
    /// header ([`crate::state_format`]), the payload ([`Model::decode`]), then its sense.
    pub fn decode_state(bytes: &[u8]) -> Result<FmuState<M::State>, String> {
        let payload = Self::state_format().decode(bytes)?;
        let state = M::decode(payload)?;
        check_sense::<M>(&state).map_err(|reason| format!("not a state this FMU can be in: {reason}"))?;
        Ok(state)
    }

    #[cold]
    fn panicked(&mut self, call: Call, payload: &(dyn std::any::Any + Send)) -> Status {
        self.run.mode = Mode::Fatal;
        self.log.emit(Status::Fatal, &panic_message(call, payload));
        Status::Fatal
    }

    /// The call legal now: of this instance's interface (or common to both) and allowed in its
    /// mode.
    #[inline]
    fn require(&mut self, call: Call) -> Result<(), Status> {
        if call.interface().is_some_and(|interface| interface != self.interface) {
            return Err(self.wrong_interface(call));
        }
        self.require_in(call, call.allowed())
    }

    #[cold]
    fn wrong_interface(&mut self, call: Call) -> Status {
        let (own, other) = (self.interface.name(), self.interface.other().name());
        self.log.fail(call, &format!("a {other} function, but this instance was instantiated for {own}"))
    }

    /// Whether an instance of this interface can be in `mode` (a restored FMU state's).
    fn holds(&self, mode: Mode) -> bool {
        !self.interface.other().own_modes().contains(mode)
    }

    /// Like [`Instance::require`] with other modes than the call's own (an argument error is
    /// reported in every live mode).
    #[inline]
    fn require_in(&mut self, call: Call, allowed: Modes) -> Result<(), Status> {
        if allowed.contains(self.run.mode) {
            Ok(())
        } else {
            Err(self.illegal_call(call))
        }
    }

    #[cold]
    fn illegal_call(&mut self, call: Call) -> Status {
        let state = self.run.mode.name();
        self.log.fail(call, &format!("illegal call in state {state}"))
    }

    /// Whether a variable of these [`access`] bits can be written as `value_type` now: fixed
    /// parameters until initialization ends; in continuous-time mode only the continuous inputs
    /// (FMI 2.0, §3.2.3: Real inputs; tunable parameters change at events).
    #[inline]
    fn settable(&self, bits: u8, value_type: ValueType) -> bool {
        let of_type = bits & value_type.access_bit() != 0;
        if bits & access::WRITABLE != 0 {
            of_type
                && (self.run.mode != Mode::ContinuousTimeMode
                    || (bits & access::PARAMETER == 0 && value_type == ValueType::Real))
        } else {
            of_type
                && bits & access::FIXED != 0
                && matches!(self.run.mode, Mode::Instantiated | Mode::InitializationMode)
        }
    }

    /// Why `value_reference` cannot be written as `value_type` now (only called when it cannot).
    #[cold]
    fn not_settable(&self, value_reference: u32, value_type: ValueType) -> String {
        match M::variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) if access::of(v, M::variables()) & value_type.access_bit() == 0 => {
                format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name())
            }
            Some(v) if v.causality == Causality::Output => format!("{} is an output and cannot be set", v.name),
            Some(v) if v.causality == Causality::Local => {
                format!("{} is computed by the model and cannot be set", v.name)
            }
            Some(v) if v.variability == crate::variables::Variability::Fixed => {
                format!("{} is a fixed parameter and cannot be set after initialization", v.name)
            }
            Some(v) => format!("{} can be set at events, not in continuousTimeMode", v.name),
        }
    }

    #[inline]
    fn readable(value_reference: u32, value_type: ValueType) -> bool {
        M::access(value_reference) & value_type.access_bit() != 0
    }

    #[cold]
    fn not_readable(value_reference: u32, value_type: ValueType) -> String {
        match M::variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) => format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name()),
        }
    }

    /// Checks every reference first, so that a call sets either all its values or none; when
    /// one is a parameter, the model is told. One pass over one byte of the access table per
    /// reference.
    #[inline]
    fn prepare_set(&mut self, call: Call, value_references: &[u32], value_type: ValueType) -> Result<(), Status> {
        self.require(call)?;
        let mut written = 0;
        for &value_reference in value_references {
            let bits = M::access(value_reference);
            if !self.settable(bits, value_type) {
                let reason = self.not_settable(value_reference, value_type);
                return Err(self.log.fail(call, &reason));
            }
            written |= bits;
        }
        if written & access::PARAMETER != 0 {
            self.model.parameters_changed();
        }
        if written & self.stale_on != 0 {
            self.outputs_stale = true;
        }
        Ok(())
    }

    /// Checks the references and, in initialization mode, brings the outputs up to date with
    /// the values just set if any is read: the status of the call (fmi2Warning after an
    /// evaluation's warning), or the error.
    #[inline]
    fn prepare_get(&mut self, call: Call, value_references: &[u32], value_type: ValueType) -> Result<Status, Status> {
        self.require(call)?;
        if let Some(&value_reference) = value_references.iter().find(|&&r| !Self::readable(r, value_type)) {
            let reason = Self::not_readable(value_reference, value_type);
            return Err(self.log.fail(call, &reason));
        }
        let reads_output = || value_references.iter().any(|&r| M::access(r) & access::OUTPUT != 0);
        if self.run.mode == Mode::InitializationMode && reads_output() {
            return self.evaluate(call, Evaluation::Initialise);
        }
        if self.outputs_stale && reads_output() {
            return self.refresh(call);
        }
        Ok(Status::Ok)
    }

    /// After initialization: the outputs and state derivatives brought up to date if what they
    /// are computed from was written since ([`Instance::outputs_stale`]).
    #[inline]
    fn refresh(&mut self, call: Call) -> Result<Status, Status> {
        let running = matches!(self.run.mode, Mode::StepComplete | Mode::EventMode | Mode::ContinuousTimeMode);
        if !(self.outputs_stale && running) {
            return Ok(Status::Ok);
        }
        let status = self.evaluate(call, Evaluation::Feedthrough { time: self.run.time })?;
        self.outputs_stale = false;
        Ok(status)
    }

    /// fmi2XXX's array length `n` checked against the `expected` one (`what`: the modelDescription's
    /// count it must equal).
    fn require_length(&mut self, call: Call, n: usize, expected: usize, what: &str) -> Result<(), Status> {
        if n == expected {
            Ok(())
        } else {
            Err(self.log.fail(call, &format!("n = {n} is not this FMU's {what} {expected}")))
        }
    }

    /// The common checks of the Model Exchange functions that pass the states: legal now, and
    /// `n` their number.
    fn require_states(&mut self, call: Call, n: usize) -> Result<(), Status> {
        self.require(call)?;
        self.require_length(call, n, M::CONTINUOUS_STATES.len(), "number of continuous states")
    }

    /// Brings the outputs up to date: `Ok(Status::Ok)`, or `Ok(Status::Warning)` after logging
    /// why the outputs are to be used with care; the error is logged. On error the model's
    /// state is unchanged ([`Model::evaluate`]'s contract).
    #[inline]
    fn evaluate(&mut self, call: Call, evaluation: Evaluation) -> Result<Status, Status> {
        match self.model.evaluate(&mut self.run.model, evaluation) {
            Ok(None) => Ok(Status::Ok),
            Ok(Some(warning)) => Ok(self.warn(call, &warning)),
            Err(reason) => Err(self.log.fail(call, &reason)),
        }
    }

    #[cold]
    fn warn(&mut self, call: Call, warning: &str) -> Status {
        self.log.emit(Status::Warning, &format!("{call}: {warning}"));
        Status::Warning
    }

    fn discard_status(&mut self, call: Call, kind: StatusKind) -> Status {
        self.log.emit(Status::Discard, &discard_message(call, kind));
        Status::Discard
    }
}

impl<M: Model> Slave for Instance<M> {
    type FmuState = FmuState<M::State>;

    /// `None` (after logging why) for a wrong GUID, an empty name, Model Exchange, or a model
    /// that refuses (a resource it needs missing).
    fn instantiate(arguments: InstantiateArguments, sink: Box<dyn LogSink>) -> Option<Self> {
        let mut log = Logger::new(arguments.logging_on, sink);
        let InstantiateArguments { instance_name, resource_location, interface, .. } = arguments;
        let model = match instantiate_problem(&arguments, M::GUID, M::MODEL_IDENTIFIER, M::MODEL_EXCHANGE) {
            Some(problem) => Err(problem),
            None => M::instantiate(resource_location),
        };
        let (model, note) = match model {
            Ok(model) => model,
            Err(problem) => {
                log.fail(Call::Instantiate, &problem);
                return None;
            }
        };
        let mut instance = Instance {
            name: instance_name.to_owned(),
            resource_location: resource_location.map(str::to_owned),
            run: FmuState::instantiated(M::start()),
            model,
            returned_strings: Vec::new(),
            log,
            interface: interface.unwrap_or(Interface::CoSimulation),
            stale_on: match interface {
                Ok(Interface::ModelExchange) => u8::MAX,
                _ => access::FEEDTHROUGH,
            },
            outputs_stale: false,
        };
        instance.log.trace(|| format!("fmi2Instantiate: resourceLocation = {}", resource_location.unwrap_or("NULL")));
        if let Some(note) = note {
            instance.log.trace(|| format!("fmi2Instantiate: {note}"));
        }
        Some(instance)
    }

    /// A panic inside it (a bug: no valid input panics) becomes `Fatal`, is logged, and leaves
    /// the instance in the `fatal` state, where every call but fmi2FreeInstance is refused.
    /// `AssertUnwindSafe` is sound for that reason: nothing reads the values a panic may have
    /// left half-updated.
    #[inline]
    fn guarded(&mut self, call: Call, body: impl FnOnce(&mut Self) -> Status) -> Status {
        match catch_unwind(AssertUnwindSafe(|| body(self))) {
            Ok(status) => status,
            Err(payload) => self.panicked(call, payload.as_ref()),
        }
    }

    fn invalid_argument(&mut self, call: Call, reason: &str) -> Status {
        if let Err(status) = self.require_in(call, LIVE) {
            return status;
        }
        self.log.fail(call, reason)
    }

    fn unsupported(&mut self, capability: Unsupported) -> Status {
        let (call, flag) = capability.describe();
        if let Err(status) = self.require(call) {
            return status;
        }
        self.log.fail(call, &format!("not supported ({flag} in modelDescription.xml)"))
    }

    /// Unknown categories are ignored with a warning.
    fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        const CALL: Call = Call::SetDebugLogging;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.select(LogFilter::new(logging_on, (!categories.is_empty()).then_some(categories)));
        self.log.trace(|| format!("{CALL}: loggingOn = {logging_on}, categories = {categories:?}"));
        match unknown_categories_message(categories, M::LOG_CATEGORIES) {
            None => Status::Ok,
            Some(message) => {
                self.log.emit(Status::Warning, &message);
                Status::Warning
            }
        }
    }

    /// The tolerance is not used: the master's step is the model's.
    fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Status {
        const CALL: Call = Call::SetupExperiment;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: startTime = {start_time}, stopTime = {stop_time:?}"));
        if let Some(problem) = experiment_problem(start_time, stop_time) {
            return self.log.fail(CALL, &problem);
        }
        self.run.time = start_time;
        self.run.stop_time = stop_time;
        Status::Ok
    }

    fn enter_initialization_mode(&mut self) -> Status {
        const CALL: Call = Call::EnterInitializationMode;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run.mode = Mode::InitializationMode;
        Status::Ok
    }

    /// Computes the outputs; with an invalid value it stays in initialization mode so that the
    /// master can correct it.
    fn exit_initialization_mode(&mut self) -> Status {
        const CALL: Call = Call::ExitInitializationMode;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        if self.interface == Interface::ModelExchange {
            if let Some(problem) = M::model_exchange_problem(&self.run.model) {
                return self.log.fail(CALL, &problem);
            }
        }
        match self.evaluate(CALL, Evaluation::Initialise) {
            Ok(status) => {
                self.run.mode = self.interface.after_initialization();
                // Model Exchange: the derivatives are computed at the first read, from the
                // inputs the master has set by then.
                self.outputs_stale = self.interface == Interface::ModelExchange;
                status
            }
            Err(status) => status,
        }
    }

    fn terminate(&mut self) -> Status {
        const CALL: Call = Call::Terminate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run.mode = Mode::Terminated;
        Status::Ok
    }

    /// Back to the start values and the `instantiated` state (the log settings and the
    /// resources stay).
    fn reset(&mut self) -> Status {
        const CALL: Call = Call::Reset;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run = FmuState::instantiated(M::start());
        self.model.reset();
        self.outputs_stale = false;
        Status::Ok
    }

    #[inline]
    fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status {
        let status = match self.prepare_get(Call::GetReal, value_references, ValueType::Real) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = M::real(&self.run.model, value_reference).unwrap_or(f64::NAN);
        }
        self.log.trace(|| format!("fmi2GetReal: {value_references:?} = {values:?}"));
        status
    }

    /// Integer and Enumeration variables.
    fn get_integer(&mut self, value_references: &[u32], values: &mut [i32]) -> Status {
        let status = match self.prepare_get(Call::GetInteger, value_references, ValueType::Integer) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = M::integer(&self.run.model, value_reference).unwrap_or_default();
        }
        self.log.trace(|| format!("fmi2GetInteger: {value_references:?} = {values:?}"));
        status
    }

    /// No Boolean variables: only n = 0 succeeds.
    fn get_boolean(&mut self, value_references: &[u32], _values: &mut [i32]) -> Status {
        match self.prepare_get(Call::GetBoolean, value_references, ValueType::Boolean) {
            Ok(status) | Err(status) => status,
        }
    }

    /// The values as C strings, kept by the instance until its next fmi2GetString (FMI 2.0
    /// §2.1.7: valid until the next call on the instance, and longer).
    fn get_string(&mut self, value_references: &[u32]) -> Result<&[CString], Status> {
        self.prepare_get(Call::GetString, value_references, ValueType::String)?;
        let texts: Vec<CString> = value_references
            .iter()
            .map(|&r| {
                // A NUL cannot come through fmi2SetString (it ends a C string).
                CString::new(M::string(&self.run.model, r).unwrap_or_default()).unwrap_or_default()
            })
            .collect();
        self.log.trace(|| format!("fmi2GetString: {value_references:?} = {texts:?}"));
        self.returned_strings = texts;
        Ok(&self.returned_strings)
    }

    #[inline]
    fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetReal, value_references, ValueType::Real) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = M::real_mut(&mut self.run.model, value_reference) {
                *field = value;
            }
        }
        self.log.trace(|| format!("fmi2SetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    /// Integer and Enumeration variables.
    fn set_integer(&mut self, value_references: &[u32], values: &[i32]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetInteger, value_references, ValueType::Integer) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = M::integer_mut(&mut self.run.model, value_reference) {
                *field = value;
            }
        }
        self.log.trace(|| format!("fmi2SetInteger: {value_references:?} = {values:?}"));
        Status::Ok
    }

    /// No Boolean variables: only n = 0 succeeds.
    fn set_boolean(&mut self, value_references: &[u32], _values: &[i32]) -> Status {
        match self.prepare_set(Call::SetBoolean, value_references, ValueType::Boolean) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// Copies of the texts (the caller's pointers are not kept).
    fn set_string(&mut self, value_references: &[u32], values: &[Cow<'_, str>]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetString, value_references, ValueType::String) {
            return status;
        }
        for (&value_reference, value) in value_references.iter().zip(values) {
            if let Some(field) = M::string_mut(&mut self.run.model, value_reference) {
                value.as_ref().clone_into(field);
            }
        }
        self.log.trace(|| {
            let texts: Vec<&str> = values.iter().map(AsRef::as_ref).collect();
            format!("fmi2SetString: {value_references:?} = {texts:?}")
        });
        Status::Ok
    }

    /// A copy of the instance's mode, time and model state.
    fn get_fmu_state(&mut self) -> Result<Self::FmuState, Status> {
        const CALL: Call = Call::GetFMUstate;
        self.require(CALL)?;
        let (mode, time) = (self.run.mode, self.run.time);
        self.log.trace(|| format!("{CALL}: state {}, time {time}", mode.name()));
        Ok(self.run.clone())
    }

    /// From here on the instance behaves exactly as when `state` was taken.
    fn set_fmu_state(&mut self, state: &Self::FmuState) -> Status {
        const CALL: Call = Call::SetFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: state {}, time {}", state.mode.name(), state.time));
        if !self.holds(state.mode) {
            let reason = format!(
                "FMUstate was taken in state {}, which an instance of {} never is in",
                state.mode.name(),
                self.interface.name()
            );
            return self.log.fail(CALL, &reason);
        }
        self.model.restoring(&self.run.model, &state.model);
        self.run.clone_from(state);
        // The state may have been taken after an input was written and before the outputs were
        // brought up to date: the next read computes them at the restored inputs.
        self.outputs_stale = true;
        Status::Ok
    }

    /// Whether the call is legal now (the C layer releases the memory).
    fn free_fmu_state(&mut self) -> Status {
        match self.require(Call::FreeFMUstate) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    fn serialized_fmu_state_size(&mut self, state: &Self::FmuState) -> Result<usize, Status> {
        self.require(Call::SerializedFMUstateSize)?;
        Ok(Self::encode_state(state).len())
    }

    fn serialize_fmu_state(&mut self, state: &Self::FmuState, bytes: &mut [u8]) -> Status {
        const CALL: Call = Call::SerializeFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        match copy_serialized(&Self::encode_state(state), bytes) {
            Ok(()) => Status::Ok,
            Err(reason) => self.log.fail(CALL, &reason),
        }
    }

    /// The state in `bytes`, after checking all of them ([`Instance::decode_state`]); the
    /// instance itself is not changed.
    fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<Self::FmuState, Status> {
        const CALL: Call = Call::DeSerializeFMUstate;
        self.require(CALL)?;
        Self::decode_state(bytes).map_err(|reason| self.log.fail(CALL, &format!("serializedState rejected: {reason}")))
    }

    /// The model's ([`Model::directional_derivative`]), or unsupported if it provides none.
    fn get_directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Status {
        const CALL: Call = Call::GetDirectionalDerivative;
        if !M::PROVIDES_DIRECTIONAL_DERIVATIVE {
            return self.unsupported(Unsupported::DirectionalDerivative);
        }
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: unknowns {unknowns:?}, knowns {knowns:?} = {known_rates:?}"));
        match self.model.directional_derivative(&self.run.model, unknowns, knowns, known_rates, unknown_rates) {
            Ok(()) => Status::Ok,
            Err(reason) => self.log.fail(CALL, &reason),
        }
    }

    /// The model advanced over the step, the outputs at its end; the time only if it succeeded.
    #[inline]
    fn do_step(&mut self, current_communication_point: f64, communication_step_size: f64) -> Status {
        const CALL: Call = Call::DoStep;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        let (t, h) = (current_communication_point, communication_step_size);
        self.log.trace(|| format!("{CALL}: currentCommunicationPoint = {t}, communicationStepSize = {h}"));
        let end = match step_end(self.run.time, self.run.stop_time, t, h) {
            Ok(end) => end,
            Err(problem) => return self.log.fail(CALL, &problem),
        };
        match self.evaluate(CALL, Evaluation::Step { time: t, size: h }) {
            Ok(status) => {
                self.run.time = end;
                self.outputs_stale = false;
                status
            }
            Err(status) => status,
        }
    }

    /// DoStep never returns fmi2Pending, so there is never a step to cancel.
    fn cancel_step(&mut self) -> Status {
        match self.require(Call::CancelStep) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// Nothing to report (steps are synchronous and never discarded).
    fn get_status(&mut self, kind: StatusKind) -> Status {
        match self.require(Call::GetStatus) {
            Ok(()) => self.discard_status(Call::GetStatus, kind),
            Err(status) => status,
        }
    }

    /// `fmi2LastSuccessfulTime` is the end of the last completed step.
    fn get_real_status(&mut self, kind: StatusKind) -> Result<f64, Status> {
        self.require(Call::GetRealStatus)?;
        match kind {
            StatusKind::LastSuccessfulTime => Ok(self.run.time),
            _ => Err(self.discard_status(Call::GetRealStatus, kind)),
        }
    }

    /// The standard defines no integer status.
    fn get_integer_status(&mut self, kind: StatusKind) -> Status {
        match self.require(Call::GetIntegerStatus) {
            Ok(()) => self.discard_status(Call::GetIntegerStatus, kind),
            Err(status) => status,
        }
    }

    /// `fmi2Terminated` is false: this FMU never asks to stop.
    fn get_boolean_status(&mut self, kind: StatusKind) -> Result<bool, Status> {
        self.require(Call::GetBooleanStatus)?;
        match kind {
            StatusKind::Terminated => Ok(false),
            _ => Err(self.discard_status(Call::GetBooleanStatus, kind)),
        }
    }

    /// `fmi2PendingStatus` has nothing to report (no pending step).
    fn get_string_status(&mut self, kind: StatusKind) -> Status {
        match self.require(Call::GetStringStatus) {
            Ok(()) => self.discard_status(Call::GetStringStatus, kind),
            Err(status) => status,
        }
    }

    fn enter_event_mode(&mut self) -> Status {
        self.enter(Call::EnterEventMode, Mode::EventMode)
    }

    /// The model resets what the event calls for ([`Model::new_discrete_states`]); no discrete
    /// states and no time events, so the event iteration ends at once.
    fn new_discrete_states(&mut self) -> Result<EventInfo, Status> {
        const CALL: Call = Call::NewDiscreteStates;
        self.require(CALL)?;
        self.refresh(CALL)?;
        let values_of_continuous_states_changed = self.model.new_discrete_states(&mut self.run.model);
        self.outputs_stale |= values_of_continuous_states_changed;
        self.log.trace(|| format!("{CALL}: continuous states changed: {values_of_continuous_states_changed}"));
        Ok(EventInfo { values_of_continuous_states_changed, ..EventInfo::default() })
    }

    fn enter_continuous_time_mode(&mut self) -> Status {
        self.enter(Call::EnterContinuousTimeMode, Mode::ContinuousTimeMode)
    }

    /// The model checks the accepted point and may ask for a step event
    /// ([`Model::completed_integrator_step`]); the simulation is never terminated here.
    fn completed_integrator_step(&mut self) -> Result<(bool, bool), Status> {
        const CALL: Call = Call::CompletedIntegratorStep;
        self.require(CALL)?;
        self.log.trace(|| format!("{CALL}: time {}", self.run.time));
        self.refresh(CALL)?;
        match self.model.completed_integrator_step(&self.run.model, self.run.time) {
            Ok(enter_event_mode) => Ok((enter_event_mode, false)),
            Err(reason) => Err(self.log.fail(CALL, &reason)),
        }
    }

    fn set_time(&mut self, time: f64) -> Status {
        const CALL: Call = Call::SetTime;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: time = {time}"));
        if let Some(problem) = time_problem("time", time) {
            return self.log.fail(CALL, &problem);
        }
        self.run.time = time;
        self.outputs_stale = true;
        Status::Ok
    }

    /// All or nothing: every value finite, or none is written.
    fn set_continuous_states(&mut self, states: &[f64]) -> Status {
        const CALL: Call = Call::SetContinuousStates;
        if let Err(status) = self.require_states(CALL, states.len()) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: x = {states:?}"));
        let bad = M::CONTINUOUS_STATES.iter().zip(states).find(|(_, x)| !x.is_finite());
        if let Some((&(state, ..), x)) = bad {
            let name = M::variable(state).map_or("?", |v| v.name);
            return self.log.fail(CALL, &format!("{name} = {x} is invalid: a continuous state must be finite"));
        }
        for (&(state, ..), &x) in M::CONTINUOUS_STATES.iter().zip(states) {
            if let Some(field) = M::real_mut(&mut self.run.model, state) {
                *field = x;
            }
        }
        self.outputs_stale = true;
        Status::Ok
    }

    fn get_derivatives(&mut self, derivatives: &mut [f64]) -> Status {
        const CALL: Call = Call::GetDerivatives;
        if let Err(status) = self.require_states(CALL, derivatives.len()) {
            return status;
        }
        let status = match self.refresh(CALL) {
            Ok(status) => status,
            Err(status) => return status,
        };
        for (&(_, derivative, _), slot) in M::CONTINUOUS_STATES.iter().zip(derivatives.iter_mut()) {
            *slot = M::real(&self.run.model, derivative).unwrap_or(f64::NAN);
        }
        self.log.trace(|| format!("{CALL}: {derivatives:?}"));
        status
    }

    /// The `numberOfEventIndicators` values ([`Model::event_indicators`]) at the current inputs
    /// and states; in initialization mode first computed from the values set, as the states.
    fn get_event_indicators(&mut self, indicators: &mut [f64]) -> Status {
        const CALL: Call = Call::GetEventIndicators;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        if let Err(status) = self.require_length(CALL, indicators.len(), M::EVENT_INDICATORS, "numberOfEventIndicators")
        {
            return status;
        }
        if indicators.is_empty() {
            return Status::Ok;
        }
        let evaluated = if self.run.mode == Mode::InitializationMode {
            self.evaluate(CALL, Evaluation::Initialise)
        } else {
            self.refresh(CALL)
        };
        let status = match evaluated {
            Ok(status) => status,
            Err(status) => return status,
        };
        self.model.event_indicators(&self.run.model, indicators);
        self.log.trace(|| format!("{CALL}: {indicators:?}"));
        status
    }

    /// In initialization mode the states are first computed from the values set.
    fn get_continuous_states(&mut self, states: &mut [f64]) -> Status {
        const CALL: Call = Call::GetContinuousStates;
        if let Err(status) = self.require_states(CALL, states.len()) {
            return status;
        }
        let status = if self.run.mode == Mode::InitializationMode && !states.is_empty() {
            match self.evaluate(CALL, Evaluation::Initialise) {
                Ok(status) => status,
                Err(status) => return status,
            }
        } else {
            Status::Ok
        };
        for (&(state, ..), slot) in M::CONTINUOUS_STATES.iter().zip(states.iter_mut()) {
            *slot = M::real(&self.run.model, state).unwrap_or(f64::NAN);
        }
        self.log.trace(|| format!("{CALL}: {states:?}"));
        status
    }

    fn get_nominals_of_continuous_states(&mut self, nominals: &mut [f64]) -> Status {
        if let Err(status) = self.require_states(Call::GetNominalsOfContinuousStates, nominals.len()) {
            return status;
        }
        for (&(.., nominal), slot) in M::CONTINUOUS_STATES.iter().zip(nominals.iter_mut()) {
            *slot = nominal;
        }
        Status::Ok
    }
}

impl<M: Model> Instance<M> {
    /// fmi2EnterEventMode, fmi2EnterContinuousTimeMode: legal now, then in `mode`.
    fn enter(&mut self, call: Call, mode: Mode) -> Status {
        if let Err(status) = self.require(call) {
            return status;
        }
        self.log.trace(|| call.name().to_owned());
        self.run.mode = mode;
        Status::Ok
    }
}

#[cfg(test)]
mod tests;
