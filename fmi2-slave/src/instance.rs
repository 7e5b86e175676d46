//! A generic FMU instance for models whose variables are all Reals: the Co-Simulation state
//! machine ([`crate::mode`]), logging, status inquiries, Get/Set checked against the model's
//! variable table, the communication-step checks and FMU states, around a [`Model`] that only
//! holds its values and computes. [`Instance`] implements [`Slave`], so a cdylib needs nothing
//! but `export_fmi2!(fmi2_slave::instance::Instance<MyModel>)`.
//!
//! Rules (FMI 2.0.4, section 4.2.4), shared with the contact FMU's own instance
//! (`fmu/src/instance`) through the functions here that check arguments and word messages
//! ([`instantiate_problem`], [`experiment_problem`], [`step_end`], [`panic_message`],
//! [`discard_message`], [`unknown_categories_message`]): a call outside the states that allow it returns `Error` and logs
//! `fmi2XXX: illegal call in state YYY`, the state unchanged; an invalid value is reported where
//! the model computes (ExitInitializationMode, DoStep, GetReal of an output in initialization
//! mode) as `Error` naming the variable and value, and the instance keeps its state so that the
//! master can correct it; a panic inside a call becomes `Fatal`, after which the instance accepts
//! nothing but fmi2FreeInstance.
//!
//! The contact FMU keeps its own instance for now (it has Integer, Enumeration and String
//! variables, warnings from the exact solve, directional derivatives): moving it onto this one
//! is the next step of the slave layer.

use std::borrow::Cow;
use std::ffi::CString;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::logging::{LogFilter, LogSink, Logger, Status};
use crate::mode::{Call, Mode, Modes, LIVE};
use crate::state_format::StateFormat;
use crate::variables::{Causality, Kind, Variability, Variable};
use crate::{InstantiateArguments, Slave, StatusKind, Unsupported};

/// Two communication points closer than this (relative to max(1, |t|)) are the same: masters
/// compute t + h in their own rounding.
pub const TIME_TOLERANCE: f64 = 1e-9;

/// fmi2Instantiate's arguments checked for an FMU with this GUID and model identifier: why they
/// are refused (an empty name, Model Exchange, another GUID), if they are.
pub fn instantiate_problem(arguments: &InstantiateArguments, guid: &str, model_identifier: &str) -> Option<String> {
    if arguments.instance_name.trim().is_empty() {
        Some("instanceName must not be empty".to_owned())
    } else if !arguments.co_simulation {
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

/// A model with Real variables only, as the generated interface and its physics give it.
pub trait Model: Clone + Default {
    /// The GUID that fmi2Instantiate requires.
    const GUID: &'static str;
    const MODEL_IDENTIFIER: &'static str;
    /// The log categories of `<LogCategories>`.
    const LOG_CATEGORIES: &'static [&'static str];
    /// Tags a serialized FMU state with the variable layout it was written with.
    const STATE_LAYOUT_TAG: u64;
    /// The first bytes of this FMU's serialized states ([`crate::state_format`]).
    const STATE_MAGIC: [u8; 8];

    /// The variable with this value reference.
    fn variable(value_reference: u32) -> Option<&'static Variable>;
    /// Every variable, in the model description's order.
    fn variables() -> &'static [Variable];
    fn real(&self, value_reference: u32) -> Option<f64>;
    fn real_mut(&mut self, value_reference: u32) -> Option<&mut f64>;
    /// Computes the outputs at the start (ExitInitializationMode; a read of an output in
    /// initialization mode) from the parameters and inputs, or says why not, naming the
    /// variable and its value; on error nothing is changed.
    fn initialize(&mut self) -> Result<(), String>;
    /// Advances from `time` over `step` > 0 with the inputs held, or says why not (naming the
    /// variable, the time and the value); on error nothing is changed.
    fn step(&mut self, time: f64, step: f64) -> Result<(), String>;
    /// The model's values (and any state beyond them) as bytes, for fmi2SerializeFMUstate.
    fn to_bytes(&self) -> Vec<u8>;
    /// The inverse of [`Model::to_bytes`], checking every byte.
    fn from_bytes(bytes: &[u8]) -> Result<Self, String>;
    /// Whether a deserialized model can be this FMU's in `mode` (its sense, after the bytes'
    /// integrity and the mode, time and stop time are checked): what the state holds (finite
    /// outputs, the model's bounds) and, once initialized, the parameters as initialize checked
    /// them. Inputs, and parameters before initialization, may hold any value, as after
    /// fmi2SetReal: the next computation reports an invalid one. The reason names the variable
    /// and its value.
    fn check_state(&self, mode: Mode) -> Result<(), String>;
}

/// The version of the generic instance's payload: mode, time, stop time, the model's bytes.
const FORMAT_VERSION: u16 = 2;

/// Mode, time and the model: what an FMU state saves and restores.
#[derive(Debug, Clone, PartialEq)]
pub struct FmuState<M> {
    mode: Mode,
    time: f64,
    stop_time: Option<f64>,
    model: M,
}

impl<M: Model> FmuState<M> {
    fn instantiated() -> Self {
        FmuState { mode: Mode::Instantiated, time: 0.0, stop_time: None, model: M::default() }
    }

    /// The byte format of this FMU's serialized states (for tools and tests that read or forge
    /// one: its payload is mode, time, stop time and the model's bytes, see `encode`).
    pub fn format() -> StateFormat {
        StateFormat { magic: M::STATE_MAGIC, version: FORMAT_VERSION, layout_tag: M::STATE_LAYOUT_TAG, guid: M::GUID }
    }

    /// The slave layer's header ([`crate::state_format`]) around: mode (1 byte), time (8), stop
    /// time (8, NaN for none), then the model's bytes; little-endian.
    fn encode(&self) -> Vec<u8> {
        let mut payload = vec![self.mode as u8];
        payload.extend(self.time.to_le_bytes());
        payload.extend(self.stop_time.unwrap_or(f64::NAN).to_le_bytes());
        payload.extend(self.model.to_bytes());
        Self::format().encode(&payload)
    }

    fn decode(bytes: &[u8]) -> Result<Self, String> {
        const RUN: usize = 1 + 8 + 8;
        let payload = Self::format().decode(bytes)?;
        if payload.len() < RUN {
            return Err(format!(
                "corrupted: a payload of {} bytes, shorter than its {RUN}-byte run data",
                payload.len()
            ));
        }
        let word = |at: usize| f64::from_le_bytes(<[u8; 8]>::try_from(&payload[at..at + 8]).expect("8 bytes"));
        let modes = [Mode::Instantiated, Mode::InitializationMode, Mode::StepComplete, Mode::Terminated];
        let Some(&mode) = modes.iter().find(|m| **m as u8 == payload[0]) else {
            return Err(format!("mode byte {} is not a state an FMU state can hold", payload[0]));
        };
        let (time, stop) = (word(1), word(9));
        let model = M::from_bytes(&payload[RUN..])?;
        let state = FmuState { mode, time, stop_time: (!stop.is_nan()).then_some(stop), model };
        state.check_sense().map_err(|reason| format!("not a state this FMU can be in: {reason}"))?;
        Ok(state)
    }

    /// What an intact but forged state must still satisfy (the mode is one a state holds by
    /// construction): a time fmi2SetupExperiment and the steps could have reached (finite, within
    /// ±[`MAX_TIME`]), a stop time the time has not passed, and the model's own checks.
    fn check_sense(&self) -> Result<(), String> {
        if let Some(problem) = times_problem(("time", self.time), self.stop_time) {
            return Err(problem);
        }
        self.model.check_state(self.mode)
    }
}

/// One instance of an FMU whose model is `M`.
pub struct Instance<M> {
    run: FmuState<M>,
    /// The master's logger (with its own copy of the instance name) behind the log filter.
    log: Logger,
}

impl<M: Model> Instance<M> {
    fn require(&mut self, call: Call) -> Result<(), Status> {
        self.require_in(call, call.allowed())
    }

    fn require_in(&mut self, call: Call, allowed: Modes) -> Result<(), Status> {
        if allowed.contains(self.run.mode) {
            Ok(())
        } else {
            let state = self.run.mode.name();
            Err(self.log.fail(call, &format!("illegal call in state {state}")))
        }
    }

    /// Why `value_reference` cannot be written now, if it cannot (`real`: as a Real).
    fn not_settable(&self, value_reference: u32, real: bool, type_name: &str) -> Option<String> {
        match M::variable(value_reference) {
            None => Some(format!("unknown value reference {value_reference}")),
            Some(v) if !(real && matches!(v.kind, Kind::Real { .. })) => {
                Some(format!("value reference {value_reference} ({}) is not a {type_name}", v.name))
            }
            Some(v) if v.causality == Causality::Output => Some(format!("{} is an output and cannot be set", v.name)),
            Some(v) if v.variability == Variability::Fixed && self.run.mode == Mode::StepComplete => {
                Some(format!("{} is a fixed parameter and cannot be set after initialization", v.name))
            }
            Some(_) => None,
        }
    }

    fn not_readable(value_reference: u32, real: bool, type_name: &str) -> Option<String> {
        match M::variable(value_reference) {
            None => Some(format!("unknown value reference {value_reference}")),
            Some(v) if !(real && matches!(v.kind, Kind::Real { .. })) => {
                Some(format!("value reference {value_reference} ({}) is not a {type_name}", v.name))
            }
            Some(_) => None,
        }
    }

    /// Checks every reference first (all or nothing).
    fn prepare_set(&mut self, call: Call, value_references: &[u32], real: bool, type_name: &str) -> Result<(), Status> {
        self.require(call)?;
        match value_references.iter().find_map(|&r| self.not_settable(r, real, type_name)) {
            Some(reason) => Err(self.log.fail(call, &reason)),
            None => Ok(()),
        }
    }

    /// Checks the references and, in initialization mode, computes the outputs if one is read.
    fn prepare_get(&mut self, call: Call, value_references: &[u32], real: bool, type_name: &str) -> Result<(), Status> {
        self.require(call)?;
        if let Some(reason) = value_references.iter().find_map(|&r| Self::not_readable(r, real, type_name)) {
            return Err(self.log.fail(call, &reason));
        }
        let reads_output =
            value_references.iter().any(|&r| M::variable(r).is_some_and(|v| v.causality == Causality::Output));
        if self.run.mode == Mode::InitializationMode && reads_output {
            if let Err(reason) = self.computed(M::initialize) {
                return Err(self.log.fail(call, &reason));
            }
        }
        Ok(())
    }

    /// Runs `compute` (initialize or a step) on a copy of the model and keeps the copy only if
    /// it succeeded with every output finite: the last guard of "never NaN or Inf out, never a
    /// half-updated model", for finite values whose arithmetic overflows (V/r with r = 5e-324)
    /// where the model's own checks missed it.
    fn computed(&mut self, compute: impl FnOnce(&mut M) -> Result<(), String>) -> Result<(), String> {
        let mut next = self.run.model.clone();
        compute(&mut next)?;
        if let Some(problem) = non_finite_output(&next) {
            return Err(problem);
        }
        self.run.model = next;
        Ok(())
    }

    fn discard_status(&mut self, call: Call, kind: StatusKind) -> Status {
        self.log.emit(Status::Discard, &discard_message(call, kind));
        Status::Discard
    }
}

impl<M: Model> Slave for Instance<M> {
    type FmuState = FmuState<M>;

    /// `None` (after logging why) for a wrong GUID, an empty name or Model Exchange.
    fn instantiate(arguments: InstantiateArguments, sink: Box<dyn LogSink>) -> Option<Self> {
        let mut log = Logger::new(arguments.logging_on, sink);
        if let Some(problem) = instantiate_problem(&arguments, M::GUID, M::MODEL_IDENTIFIER) {
            log.fail(Call::Instantiate, &problem);
            return None;
        }
        let resource_location = arguments.resource_location;
        let mut instance = Instance { run: FmuState::instantiated(), log };
        instance.log.trace(|| format!("fmi2Instantiate: resourceLocation = {}", resource_location.unwrap_or("NULL")));
        Some(instance)
    }

    /// `AssertUnwindSafe` is sound: after a panic the instance is `fatal` and nothing reads the
    /// values the panic may have left half-updated.
    fn guarded(&mut self, call: Call, body: impl FnOnce(&mut Self) -> Status) -> Status {
        match catch_unwind(AssertUnwindSafe(|| body(self))) {
            Ok(status) => status,
            Err(payload) => {
                self.run.mode = Mode::Fatal;
                self.log.emit(Status::Fatal, &panic_message(call, payload.as_ref()));
                Status::Fatal
            }
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
        match self.computed(M::initialize) {
            Ok(()) => {
                self.run.mode = Mode::StepComplete;
                Status::Ok
            }
            Err(reason) => self.log.fail(CALL, &reason),
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

    /// Back to the start values and the `instantiated` state (the log settings stay).
    fn reset(&mut self) -> Status {
        const CALL: Call = Call::Reset;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run = FmuState::instantiated();
        Status::Ok
    }

    fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status {
        if let Err(status) = self.prepare_get(Call::GetReal, value_references, true, "Real") {
            return status;
        }
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = self.run.model.real(value_reference).unwrap_or(f64::NAN);
        }
        self.log.trace(|| format!("fmi2GetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    /// No Integer variables: only n = 0 succeeds.
    fn get_integer(&mut self, value_references: &[u32], _values: &mut [i32]) -> Status {
        let result = self.prepare_get(Call::GetInteger, value_references, false, "Integer");
        status(result)
    }

    /// No Boolean variables: only n = 0 succeeds.
    fn get_boolean(&mut self, value_references: &[u32], _values: &mut [i32]) -> Status {
        let result = self.prepare_get(Call::GetBoolean, value_references, false, "Boolean");
        status(result)
    }

    /// No String variables: only n = 0 succeeds.
    fn get_string(&mut self, value_references: &[u32]) -> Result<&[CString], Status> {
        self.prepare_get(Call::GetString, value_references, false, "String")?;
        Ok(&[])
    }

    fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status {
        if let Err(status) = self.prepare_set(Call::SetReal, value_references, true, "Real") {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.model.real_mut(value_reference) {
                *field = value;
            }
        }
        self.log.trace(|| format!("fmi2SetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    fn set_integer(&mut self, value_references: &[u32], _values: &[i32]) -> Status {
        let result = self.prepare_set(Call::SetInteger, value_references, false, "Integer");
        status(result)
    }

    fn set_boolean(&mut self, value_references: &[u32], _values: &[i32]) -> Status {
        let result = self.prepare_set(Call::SetBoolean, value_references, false, "Boolean");
        status(result)
    }

    fn set_string(&mut self, value_references: &[u32], _values: &[Cow<'_, str>]) -> Status {
        let result = self.prepare_set(Call::SetString, value_references, false, "String");
        status(result)
    }

    fn get_fmu_state(&mut self) -> Result<FmuState<M>, Status> {
        const CALL: Call = Call::GetFMUstate;
        self.require(CALL)?;
        let (mode, time) = (self.run.mode, self.run.time);
        self.log.trace(|| format!("{CALL}: state {}, time {time}", mode.name()));
        Ok(self.run.clone())
    }

    fn set_fmu_state(&mut self, state: &FmuState<M>) -> Status {
        const CALL: Call = Call::SetFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: state {}, time {}", state.mode.name(), state.time));
        self.run.clone_from(state);
        Status::Ok
    }

    fn free_fmu_state(&mut self) -> Status {
        let result = self.require(Call::FreeFMUstate);
        status(result)
    }

    fn serialized_fmu_state_size(&mut self, state: &FmuState<M>) -> Result<usize, Status> {
        self.require(Call::SerializedFMUstateSize)?;
        Ok(state.encode().len())
    }

    fn serialize_fmu_state(&mut self, state: &FmuState<M>, bytes: &mut [u8]) -> Status {
        const CALL: Call = Call::SerializeFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        match copy_serialized(&state.encode(), bytes) {
            Ok(()) => Status::Ok,
            Err(reason) => self.log.fail(CALL, &reason),
        }
    }

    fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<FmuState<M>, Status> {
        const CALL: Call = Call::DeSerializeFMUstate;
        self.require(CALL)?;
        FmuState::decode(bytes).map_err(|reason| self.log.fail(CALL, &format!("serializedState rejected: {reason}")))
    }

    fn get_directional_derivative(&mut self, _: &[u32], _: &[u32], _: &[f64], _: &mut [f64]) -> Status {
        self.unsupported(Unsupported::DirectionalDerivative)
    }

    /// The model advanced over the step; the time only if it succeeded.
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
        match self.computed(|model| model.step(t, h)) {
            Ok(()) => {
                self.run.time = end;
                Status::Ok
            }
            Err(reason) => self.log.fail(CALL, &reason),
        }
    }

    /// DoStep never returns fmi2Pending, so there is never a step to cancel.
    fn cancel_step(&mut self) -> Status {
        let result = self.require(Call::CancelStep);
        status(result)
    }

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

    fn get_string_status(&mut self, kind: StatusKind) -> Status {
        match self.require(Call::GetStringStatus) {
            Ok(()) => self.discard_status(Call::GetStringStatus, kind),
            Err(status) => status,
        }
    }
}

/// The status of a call that either succeeds silently or has already logged its error.
fn status(result: Result<(), Status>) -> Status {
    match result {
        Ok(()) => Status::Ok,
        Err(status) => status,
    }
}

/// Why `model`'s outputs cannot be kept, if they cannot: the first non-finite output, its value
/// and what it was computed from: the inputs it depends on (`<ModelStructure>`) with their
/// values, or, for an output no input acts on directly, the parameters and the state.
fn non_finite_output<M: Model>(model: &M) -> Option<String> {
    let value = |variable: &Variable| model.real(variable.value_reference).unwrap_or(f64::NAN);
    // The values in Debug form: 1e308, not its 309 digits.
    let (output, x) = M::variables()
        .iter()
        .filter(|v| v.causality == Causality::Output)
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
