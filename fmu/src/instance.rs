//! One FMU instance: its values, the FMI 2.0 Co-Simulation state machine, and logging.
//!
//! Safe code only: `ffi` turns C arguments into slices and strings and calls these methods, so
//! unit tests drive every rule here without the C boundary.
//!
//! Rules (FMI 2.0.4, section 4.2.4, Co-Simulation state machine):
//! - a call outside the states that allow it returns `Error` and logs
//!   `fmi2XXX: illegal call in state YYY`; the state does not change;
//! - an invalid value (NaN, a ≤ 0, …) is reported where outputs are computed
//!   (ExitInitializationMode, DoStep, GetReal of an output in InitializationMode) as `Error`
//!   naming the variable and value. The instance keeps its state, so the master can set a good
//!   value and carry on (this FMU never enters the standard's `error` state);
//! - a panic inside a call (a bug) is caught by [`Instance::guarded`]: `Fatal`, logged, and the
//!   instance accepts nothing but fmi2FreeInstance afterwards.
//!
//! The hot path (fmi2SetReal/DoStep/GetReal) does no allocation, no string comparison and no
//! search: one dense-table lookup per value reference, a bit test for the state, and a log
//! filter decided once per fmi2SetDebugLogging.

use std::panic::{catch_unwind, AssertUnwindSafe};

use serde::{Deserialize, Serialize};

use super::scene::directional_derivative;
use super::fmu_state::{decode, encode, FmuState, RunState};
use super::model_description::{self, variable, Causality, Kind, Outputs, Values, Variability, LOG_CATEGORIES};
use super::scene::{compute_outputs, ModelCache};
use wheel_rail_contact::scene::Evaluation;

/// What an FMI call returns (`fmi2Status` without `fmi2Pending`: every call is synchronous).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Ok,
    Warning,
    Discard,
    Error,
    Fatal,
}

/// The states of the Co-Simulation state machine that this FMU can be in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum State {
    Instantiated,
    InitializationMode,
    StepComplete,
    Terminated,
    Fatal,
}

impl State {
    /// The state's name as the standard writes it.
    pub fn name(self) -> &'static str {
        match self {
            State::Instantiated => "instantiated",
            State::InitializationMode => "initializationMode",
            State::StepComplete => "stepComplete",
            State::Terminated => "terminated",
            State::Fatal => "fatal",
        }
    }
}

use State::{InitializationMode, Instantiated, StepComplete, Terminated};

/// A set of states as a bit mask: membership is one bit test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct States(u8);

impl States {
    const fn of(states: &[State]) -> States {
        let mut mask = 0;
        let mut i = 0;
        while i < states.len() {
            mask |= 1 << states[i] as u8;
            i += 1;
        }
        States(mask)
    }

    #[inline]
    pub fn contains(self, state: State) -> bool {
        self.0 & (1 << state as u8) != 0
    }
}

/// Where SetDebugLogging, Reset and the FMU-state functions are allowed.
const LIVE: States = States::of(&[Instantiated, InitializationMode, StepComplete, Terminated]);
/// Where values may be read (and directional derivatives taken).
const READABLE: States = States::of(&[InitializationMode, StepComplete, Terminated]);
/// Where values may be written (which ones: see [`Instance::check_settable`]).
const WRITABLE: States = States::of(&[Instantiated, InitializationMode, StepComplete]);
/// Where the step status may be inquired.
const STEPPED: States = States::of(&[StepComplete, Terminated]);
/// Nowhere.
const NEVER: States = States::of(&[]);

/// The FMI base types of the Get/Set functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ValueType {
    Real,
    Integer,
    Boolean,
    String,
}

impl ValueType {
    fn of(kind: &Kind) -> ValueType {
        match kind {
            Kind::Real { .. } => ValueType::Real,
            Kind::Integer { .. } | Kind::Enumeration { .. } => ValueType::Integer,
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

/// `fmi2StatusKind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusKind {
    DoStepStatus,
    PendingStatus,
    LastSuccessfulTime,
    Terminated,
}

/// Receives the messages that pass the instance's log filter (the master's logger callback).
pub trait LogSink {
    fn log(&mut self, status: Status, category: &str, message: &str);
}

/// Which messages reach the logger: one flag per status (each status has one category),
/// decided when the selection changes, so a call checks one bool.
///
/// A message with a non-OK status (warning, discard, error, fatal) always reaches the logger,
/// whatever fmi2SetDebugLogging selected: the standard's status descriptions say the FMU calls
/// the logger for those, and a master must learn why its call failed (as the Reference FMUs'
/// logError). The selection filters the call traces (status OK, category logCalls) only: they
/// pass with debug logging on and no category given, `logCalls` or `logAll` selected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct LogFilter {
    passes: [bool; 5],
}

impl LogFilter {
    fn new(debug_logging: bool, categories: Option<&[&str]>) -> LogFilter {
        let passes = |status: Status| match (status, debug_logging, categories) {
            (Status::Warning | Status::Discard | Status::Error | Status::Fatal, _, _) => true,
            (Status::Ok, false, _) => false,
            (Status::Ok, true, None) => true,
            (Status::Ok, true, Some(selected)) => {
                selected.iter().any(|c| *c == status_category(status) || *c == "logAll")
            }
        };
        LogFilter { passes: STATUSES.map(passes) }
    }

    #[inline]
    fn passes(&self, status: Status) -> bool {
        self.passes[status as usize]
    }
}

/// Every status, in the order of their discriminants.
const STATUSES: [Status; 5] = [Status::Ok, Status::Warning, Status::Discard, Status::Error, Status::Fatal];

fn status_category(status: Status) -> &'static str {
    match status {
        Status::Ok => "logCalls",
        Status::Warning => "logStatusWarning",
        Status::Discard => "logStatusDiscard",
        Status::Error => "logStatusError",
        Status::Fatal => "logStatusFatal",
    }
}

/// Two communication points closer than this (relative to max(1, |t|)) are the same: masters
/// compute t + h in their own rounding.
const TIME_TOLERANCE: f64 = 1e-9;

/// Under `cfg(test)` only: a log category that makes fmi2SetDebugLogging panic, so that a test
/// can drive a real panic through an export and see it become fmi2Fatal. Not in any FMU binary.
#[cfg(test)]
pub(crate) const PANIC_CATEGORY_FOR_TESTS: &str = "panicForTests";

/// One instance of the FMU.
pub struct Instance {
    name: String,
    resource_location: Option<String>,
    /// Mode, time, values and model state: exactly what an FMU state saves and restores.
    run: RunState,
    /// A cache derived from the parameters (not state: it is refitted whenever they differ).
    model: ModelCache,
    log_filter: LogFilter,
    sink: Box<dyn LogSink>,
}

/// What fmi2Instantiate received, decoded.
pub struct InstantiateArguments<'a> {
    pub instance_name: &'a str,
    pub co_simulation: bool,
    pub guid: &'a str,
    pub resource_location: Option<&'a str>,
    pub logging_on: bool,
}

impl Instance {
    /// fmi2Instantiate: `None` (after logging why) for a wrong GUID, an empty name or Model
    /// Exchange.
    pub fn instantiate(arguments: InstantiateArguments, mut sink: Box<dyn LogSink>) -> Option<Instance> {
        let InstantiateArguments { instance_name, co_simulation, guid, resource_location, logging_on } = arguments;
        let problem = if instance_name.trim().is_empty() {
            Some("instanceName must not be empty".to_owned())
        } else if !co_simulation {
            Some(format!(
                "this FMU supports Co-Simulation only (modelIdentifier {})",
                model_description::MODEL_IDENTIFIER
            ))
        } else if guid != model_description::GUID {
            Some(format!("fmuGUID {guid} does not match this FMU's GUID {}", model_description::GUID))
        } else {
            None
        };
        if let Some(problem) = problem {
            sink.log(Status::Error, status_category(Status::Error), &format!("fmi2Instantiate: {problem}"));
            return None;
        }
        let mut instance = Instance {
            name: instance_name.to_owned(),
            resource_location: resource_location.map(str::to_owned),
            run: RunState::instantiated(),
            model: ModelCache::default(),
            log_filter: LogFilter::new(logging_on, None),
            sink,
        };
        instance.trace(|| format!("fmi2Instantiate: resourceLocation = {}", resource_location.unwrap_or("NULL")));
        Some(instance)
    }

    /// The name the master gave.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The resource location the master gave (`None` if it passed NULL).
    pub fn resource_location(&self) -> Option<&str> {
        self.resource_location.as_deref()
    }

    pub fn state(&self) -> State {
        self.run.mode
    }

    /// The instance's values (inputs, parameters, last outputs).
    pub fn values(&self) -> &Values {
        &self.run.values
    }

    /// Runs one FMI call. A panic inside it (a bug: no valid input panics) becomes `Fatal`, is
    /// logged, and leaves the instance in the `fatal` state, where every call but
    /// fmi2FreeInstance is refused. `AssertUnwindSafe` is sound for that reason: nothing reads
    /// the values a panic may have left half-updated.
    #[inline]
    pub fn guarded(&mut self, call: &str, body: impl FnOnce(&mut Instance) -> Status) -> Status {
        match catch_unwind(AssertUnwindSafe(|| body(self))) {
            Ok(status) => status,
            Err(payload) => self.panicked(call, payload.as_ref()),
        }
    }

    #[cold]
    fn panicked(&mut self, call: &str, payload: &(dyn std::any::Any + Send)) -> Status {
        self.run.mode = State::Fatal;
        let reason = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_owned());
        let message = format!("{call}: internal error ({reason}); this instance can only be freed");
        self.emit(Status::Fatal, &message);
        Status::Fatal
    }

    fn emit(&mut self, status: Status, message: &str) {
        if self.log_filter.passes(status) {
            self.sink.log(status, status_category(status), message);
        }
    }

    /// Logs a call trace (category logCalls); the message is only formatted when it will be sent.
    #[inline]
    fn trace(&mut self, message: impl FnOnce() -> String) {
        if self.log_filter.passes(Status::Ok) {
            let text = message();
            self.sink.log(Status::Ok, status_category(Status::Ok), &text);
        }
    }

    fn fail(&mut self, call: &str, reason: &str) -> Status {
        self.emit(Status::Error, &format!("{call}: {reason}"));
        Status::Error
    }

    #[inline]
    fn require(&mut self, call: &str, allowed: States) -> Result<(), Status> {
        if allowed.contains(self.run.mode) {
            Ok(())
        } else {
            Err(self.illegal_call(call))
        }
    }

    #[cold]
    fn illegal_call(&mut self, call: &str) -> Status {
        let state = self.run.mode.name();
        self.fail(call, &format!("illegal call in state {state}"))
    }

    /// fmi2SetDebugLogging. Unknown categories are ignored with a warning.
    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        const CALL: &str = "fmi2SetDebugLogging";
        #[cfg(test)]
        if categories.contains(&PANIC_CATEGORY_FOR_TESTS) {
            panic!("forced by a test through the category {PANIC_CATEGORY_FOR_TESTS}");
        }
        if let Err(status) = self.require(CALL, LIVE) {
            return status;
        }
        let selection = if categories.is_empty() { None } else { Some(categories) };
        self.log_filter = LogFilter::new(logging_on, selection);
        let unknown: Vec<&&str> = categories.iter().filter(|c| !LOG_CATEGORIES.contains(c)).collect();
        self.trace(|| format!("{CALL}: loggingOn = {logging_on}, categories = {categories:?}"));
        if unknown.is_empty() {
            Status::Ok
        } else {
            let message = format!("{CALL}: unknown log categories {unknown:?} ignored; known: {LOG_CATEGORIES:?}");
            self.emit(Status::Warning, &message);
            Status::Warning
        }
    }

    /// fmi2SetupExperiment. The tolerance is not used: the outputs are algebraic in the inputs.
    pub fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Status {
        const CALL: &str = "fmi2SetupExperiment";
        if let Err(status) = self.require(CALL, States::of(&[Instantiated])) {
            return status;
        }
        self.trace(|| format!("{CALL}: startTime = {start_time}, stopTime = {stop_time:?}"));
        if !start_time.is_finite() {
            return self.fail(CALL, &format!("startTime = {start_time} is invalid: must be finite"));
        }
        if let Some(stop) = stop_time.filter(|stop| stop.is_nan() || *stop < start_time) {
            return self.fail(CALL, &format!("stopTime = {stop} is invalid: must be >= startTime = {start_time}"));
        }
        self.run.time = start_time;
        self.run.stop_time = stop_time;
        Status::Ok
    }

    pub fn enter_initialization_mode(&mut self) -> Status {
        const CALL: &str = "fmi2EnterInitializationMode";
        if let Err(status) = self.require(CALL, States::of(&[Instantiated])) {
            return status;
        }
        self.trace(|| CALL.to_owned());
        self.run.mode = InitializationMode;
        Status::Ok
    }

    /// fmi2ExitInitializationMode: computes the outputs; with an invalid value it stays in
    /// initialization mode so that the master can correct it.
    pub fn exit_initialization_mode(&mut self) -> Status {
        const CALL: &str = "fmi2ExitInitializationMode";
        if let Err(status) = self.require(CALL, States::of(&[InitializationMode])) {
            return status;
        }
        self.trace(|| CALL.to_owned());
        if let Err(status) = self.update_outputs(CALL, Evaluation::Initialise) {
            return status;
        }
        self.run.mode = StepComplete;
        Status::Ok
    }

    pub fn terminate(&mut self) -> Status {
        const CALL: &str = "fmi2Terminate";
        if let Err(status) = self.require(CALL, States::of(&[StepComplete])) {
            return status;
        }
        self.trace(|| CALL.to_owned());
        self.run.mode = Terminated;
        Status::Ok
    }

    /// fmi2Reset: back to the start values and the `instantiated` state (the log settings stay).
    pub fn reset(&mut self) -> Status {
        const CALL: &str = "fmi2Reset";
        if let Err(status) = self.require(CALL, LIVE) {
            return status;
        }
        self.trace(|| CALL.to_owned());
        self.run = RunState::instantiated();
        self.model = ModelCache::default();
        Status::Ok
    }

    #[inline]
    fn update_outputs(&mut self, call: &str, evaluation: Evaluation) -> Result<(), Status> {
        // The model state advances on a copy, kept only if the outputs are good.
        let mut model_state = self.run.model_state;
        let outputs = compute_outputs(&self.run.values, &mut self.model, &mut model_state.relaxed_forces, evaluation)
            .and_then(|outputs| finite(&outputs).map(|_| outputs));
        match outputs {
            Ok(outputs) => {
                self.run.values.outputs = outputs;
                self.run.model_state = model_state;
                Ok(())
            }
            Err(reason) => Err(self.fail(call, &reason)),
        }
    }

    /// Whether `value_reference` can be written as `value_type` now.
    #[inline]
    fn settable(&self, value_reference: u32, value_type: ValueType) -> bool {
        variable(value_reference).is_some_and(|v| {
            ValueType::of(&v.kind) == value_type
                && match (v.causality, v.variability) {
                    (Causality::Output, _) => false,
                    (Causality::Parameter, Variability::Fixed) => self.run.mode != StepComplete,
                    _ => true,
                }
        })
    }

    /// Why `value_reference` cannot be written as `value_type` now (only called when it cannot).
    #[cold]
    fn not_settable(&self, value_reference: u32, value_type: ValueType) -> String {
        match variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) if ValueType::of(&v.kind) != value_type => {
                format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name())
            }
            Some(v) if v.causality == Causality::Output => format!("{} is an output and cannot be set", v.name),
            Some(v) => format!("{} is a fixed parameter and cannot be set after initialization", v.name),
        }
    }

    #[inline]
    fn readable(value_reference: u32, value_type: ValueType) -> bool {
        variable(value_reference).is_some_and(|v| ValueType::of(&v.kind) == value_type)
    }

    #[cold]
    fn not_readable(value_reference: u32, value_type: ValueType) -> String {
        match variable(value_reference) {
            None => format!("unknown value reference {value_reference}"),
            Some(v) => format!("value reference {value_reference} ({}) is not a {}", v.name, value_type.name()),
        }
    }

    /// Checks every reference first, so that a call sets either all its values or none.
    #[inline]
    fn prepare_set(&mut self, call: &str, value_references: &[u32], value_type: ValueType) -> Result<(), Status> {
        self.require(call, WRITABLE)?;
        match value_references.iter().find(|&&r| !self.settable(r, value_type)) {
            None => Ok(()),
            Some(&value_reference) => {
                let reason = self.not_settable(value_reference, value_type);
                Err(self.fail(call, &reason))
            }
        }
    }

    /// Checks the references and, in initialization mode, brings the outputs up to date with
    /// the values just set if any is read.
    #[inline]
    fn prepare_get(&mut self, call: &str, value_references: &[u32], value_type: ValueType) -> Result<(), Status> {
        self.require(call, READABLE)?;
        if let Some(&value_reference) = value_references.iter().find(|&&r| !Self::readable(r, value_type)) {
            let reason = Self::not_readable(value_reference, value_type);
            return Err(self.fail(call, &reason));
        }
        let reads_output =
            || value_references.iter().any(|&r| variable(r).is_some_and(|v| v.causality == Causality::Output));
        if self.run.mode == InitializationMode && reads_output() {
            self.update_outputs(call, Evaluation::Initialise)?;
        }
        Ok(())
    }

    #[inline]
    pub fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status {
        if let Err(status) = self.prepare_set("fmi2SetReal", value_references, ValueType::Real) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.values.real_mut(value_reference) {
                *field = value;
            }
        }
        self.trace(|| format!("fmi2SetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    #[inline]
    pub fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status {
        if let Err(status) = self.prepare_get("fmi2GetReal", value_references, ValueType::Real) {
            return status;
        }
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = self.run.values.real(value_reference).unwrap_or(f64::NAN);
        }
        self.trace(|| format!("fmi2GetReal: {value_references:?} = {values:?}"));
        Status::Ok
    }

    /// fmi2SetInteger: Integer and Enumeration variables.
    pub fn set_integer(&mut self, value_references: &[u32], values: &[i32]) -> Status {
        if let Err(status) = self.prepare_set("fmi2SetInteger", value_references, ValueType::Integer) {
            return status;
        }
        for (&value_reference, &value) in value_references.iter().zip(values) {
            if let Some(field) = self.run.values.integer_mut(value_reference) {
                *field = value;
            }
        }
        self.trace(|| format!("fmi2SetInteger: {value_references:?} = {values:?}"));
        Status::Ok
    }

    pub fn get_integer(&mut self, value_references: &[u32], values: &mut [i32]) -> Status {
        if let Err(status) = self.prepare_get("fmi2GetInteger", value_references, ValueType::Integer) {
            return status;
        }
        for (&value_reference, slot) in value_references.iter().zip(values.iter_mut()) {
            *slot = self.run.values.integer(value_reference).unwrap_or_default();
        }
        self.trace(|| format!("fmi2GetInteger: {value_references:?} = {values:?}"));
        Status::Ok
    }

    /// fmi2GetBoolean / fmi2GetString: this FMU has no such variables, so only n = 0 succeeds.
    pub fn get_absent_type(&mut self, call: &str, value_type: ValueType, value_references: &[u32]) -> Status {
        match self.prepare_get(call, value_references, value_type) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// fmi2SetBoolean / fmi2SetString: this FMU has no such variables, so only n = 0 succeeds.
    pub fn set_absent_type(&mut self, call: &str, value_type: ValueType, value_references: &[u32]) -> Status {
        match self.prepare_set(call, value_references, value_type) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// fmi2DoStep: outputs at t + h from the inputs set before the step (the model is algebraic).
    #[inline]
    pub fn do_step(&mut self, current_communication_point: f64, communication_step_size: f64) -> Status {
        const CALL: &str = "fmi2DoStep";
        if let Err(status) = self.require(CALL, States::of(&[StepComplete])) {
            return status;
        }
        let (t, h) = (current_communication_point, communication_step_size);
        self.trace(|| format!("{CALL}: currentCommunicationPoint = {t}, communicationStepSize = {h}"));
        if !(h > 0.0 && h.is_finite()) {
            return self.fail(CALL, &format!("communicationStepSize = {h} is invalid: must be finite and > 0"));
        }
        let tolerance = TIME_TOLERANCE * self.run.time.abs().max(1.0);
        let on_time = (t - self.run.time).abs() <= tolerance; // false for a NaN t
        if !on_time {
            let time = self.run.time;
            return self.fail(CALL, &format!("currentCommunicationPoint = {t} is not the instance's time {time}"));
        }
        let end = t + h;
        if !end.is_finite() {
            return self.fail(
                CALL,
                &format!("the step would end at {end}: currentCommunicationPoint = {t:e} plus communicationStepSize = {h:e} is not finite"),
            );
        }
        if let Some(stop) = self.run.stop_time.filter(|stop| end > stop + tolerance) {
            return self.fail(CALL, &format!("the step would end at {end}, after stopTime = {stop}"));
        }
        if let Err(status) = self.update_outputs(CALL, Evaluation::Step(h)) {
            return status;
        }
        self.run.time = end;
        Status::Ok
    }

    /// fmi2CancelStep: DoStep never returns fmi2Pending, so there is never a step to cancel.
    pub fn cancel_step(&mut self) -> Status {
        match self.require("fmi2CancelStep", NEVER) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    fn discard_status(&mut self, call: &str, kind: StatusKind) -> Status {
        let message = format!("{call}: no {kind:?} to report: fmi2DoStep never returns fmi2Pending or fmi2Discard");
        self.emit(Status::Discard, &message);
        Status::Discard
    }

    /// fmi2GetStatus: nothing to report (steps are synchronous and never discarded).
    pub fn get_status(&mut self, kind: StatusKind) -> Status {
        const CALL: &str = "fmi2GetStatus";
        if let Err(status) = self.require(CALL, STEPPED) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// fmi2GetRealStatus: `fmi2LastSuccessfulTime` is the end of the last completed step.
    pub fn get_real_status(&mut self, kind: StatusKind) -> Result<f64, Status> {
        const CALL: &str = "fmi2GetRealStatus";
        self.require(CALL, STEPPED)?;
        match kind {
            StatusKind::LastSuccessfulTime => Ok(self.run.time),
            _ => Err(self.discard_status(CALL, kind)),
        }
    }

    /// fmi2GetIntegerStatus: the standard defines no integer status.
    pub fn get_integer_status(&mut self, kind: StatusKind) -> Status {
        const CALL: &str = "fmi2GetIntegerStatus";
        if let Err(status) = self.require(CALL, STEPPED) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// fmi2GetBooleanStatus: `fmi2Terminated` is false: this FMU never asks to stop.
    pub fn get_boolean_status(&mut self, kind: StatusKind) -> Result<bool, Status> {
        const CALL: &str = "fmi2GetBooleanStatus";
        self.require(CALL, STEPPED)?;
        match kind {
            StatusKind::Terminated => Ok(false),
            _ => Err(self.discard_status(CALL, kind)),
        }
    }

    /// fmi2GetStringStatus: `fmi2PendingStatus` has nothing to report (no pending step).
    pub fn get_string_status(&mut self, kind: StatusKind) -> Status {
        const CALL: &str = "fmi2GetStringStatus";
        if let Err(status) = self.require(CALL, STEPPED) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// fmi2GetFMUstate: a copy of the instance's mode, time, values and model state.
    pub fn get_fmu_state(&mut self) -> Result<FmuState, Status> {
        const CALL: &str = "fmi2GetFMUstate";
        self.require(CALL, LIVE)?;
        let (mode, time) = (self.run.mode, self.run.time);
        self.trace(|| format!("{CALL}: state {}, time {time}", mode.name()));
        Ok(FmuState(self.run.clone()))
    }

    /// fmi2SetFMUstate: from here on the instance behaves exactly as when `state` was taken.
    pub fn set_fmu_state(&mut self, state: &FmuState) -> Status {
        const CALL: &str = "fmi2SetFMUstate";
        if let Err(status) = self.require(CALL, LIVE) {
            return status;
        }
        self.trace(|| format!("{CALL}: state {}, time {}", state.0.mode.name(), state.0.time));
        self.run.clone_from(&state.0);
        Status::Ok
    }

    /// fmi2FreeFMUstate: whether the call is legal now (the C layer releases the memory).
    pub fn free_fmu_state(&mut self) -> Status {
        const CALL: &str = "fmi2FreeFMUstate";
        match self.require(CALL, LIVE) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// fmi2SerializedFMUstateSize: the exact length fmi2SerializeFMUstate writes.
    pub fn serialized_fmu_state_size(&mut self, state: &FmuState) -> Result<usize, Status> {
        self.require("fmi2SerializedFMUstateSize", LIVE)?;
        Ok(encode(&state.0).len())
    }

    /// fmi2SerializeFMUstate: `bytes` must have exactly the serialized size.
    pub fn serialize_fmu_state(&mut self, state: &FmuState, bytes: &mut [u8]) -> Status {
        const CALL: &str = "fmi2SerializeFMUstate";
        if let Err(status) = self.require(CALL, LIVE) {
            return status;
        }
        let encoded = encode(&state.0);
        if bytes.len() != encoded.len() {
            let (size, needed) = (bytes.len(), encoded.len());
            return self.fail(
                CALL,
                &format!("size = {size} is not the serialized size {needed} (see fmi2SerializedFMUstateSize)"),
            );
        }
        bytes.copy_from_slice(&encoded);
        Status::Ok
    }

    /// fmi2DeSerializeFMUstate: the state in `bytes`, after checking all of them (see
    /// [`decode`]); the instance itself is not changed.
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<FmuState, Status> {
        const CALL: &str = "fmi2DeSerializeFMUstate";
        self.require(CALL, LIVE)?;
        decode(bytes).map(FmuState).map_err(|reason| self.fail(CALL, &format!("serializedState rejected: {reason}")))
    }

    /// fmi2GetDirectionalDerivative: `unknown_rates` = J·`known_rates`, J = ∂(outputs)/∂(inputs)
    /// at the current values. Knowns must be continuous inputs (a value reference given twice
    /// adds its rates), unknowns outputs; all-or-nothing like Get.
    pub fn get_directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Status {
        const CALL: &str = "fmi2GetDirectionalDerivative";
        if let Err(status) = self.require(CALL, READABLE) {
            return status;
        }
        self.trace(|| format!("{CALL}: unknowns {unknowns:?}, knowns {knowns:?} = {known_rates:?}"));
        let mut rates = Values::default();
        for input in model_description::VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
            if let Some(rate) = rates.real_mut(input.value_reference) {
                *rate = 0.0;
            }
        }
        for (&value_reference, &rate) in knowns.iter().zip(known_rates) {
            match variable(value_reference) {
                Some(v) if is_known(v.causality, v.variability, &v.kind) && rate.is_finite() => {
                    *rates.real_mut(value_reference).expect("a Real input") += rate;
                }
                Some(v) if is_known(v.causality, v.variability, &v.kind) => {
                    return self.fail(CALL, &format!("dvKnown = {rate} for {} is invalid: must be finite", v.name));
                }
                Some(v) => {
                    let reason = format!(
                        "{} (value reference {value_reference}) cannot be a known: derivatives are taken with \
                         respect to the continuous Real inputs only",
                        v.name
                    );
                    return self.fail(CALL, &reason);
                }
                None => return self.fail(CALL, &format!("unknown value reference {value_reference}")),
            }
        }
        if let Some(&value_reference) =
            unknowns.iter().find(|&&r| variable(r).is_none_or(|v| v.causality != Causality::Output))
        {
            let reason = match variable(value_reference) {
                Some(v) => {
                    format!("{} (value reference {value_reference}) cannot be an unknown: not an output", v.name)
                }
                None => format!("unknown value reference {value_reference}"),
            };
            return self.fail(CALL, &reason);
        }
        let derivative = directional_derivative(&self.run.values, &mut self.model, &rates.inputs)
            .and_then(|outputs| finite(&outputs).map(|_| Values { outputs, ..rates }));
        match derivative {
            Ok(derivative) => {
                for (&value_reference, slot) in unknowns.iter().zip(unknown_rates.iter_mut()) {
                    *slot = derivative.real(value_reference).unwrap_or(f64::NAN);
                }
                Status::Ok
            }
            Err(reason) => self.fail(CALL, &reason),
        }
    }

    /// An unsupported capability: `Error` with the capability flag that says so.
    pub fn unsupported(&mut self, capability: Unsupported) -> Status {
        let (call, allowed, flag) = capability.describe();
        if let Err(status) = self.require(call, allowed) {
            return status;
        }
        self.fail(call, &format!("not supported ({flag} in modelDescription.xml)"))
    }

    /// An argument the C layer found unusable (a NULL pointer with n > 0, an unknown enum value).
    pub fn invalid_argument(&mut self, call: &str, reason: &str) -> Status {
        if let Err(status) = self.require(call, LIVE) {
            return status;
        }
        self.fail(call, reason)
    }
}

/// The capabilities this FMU declares false.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unsupported {
    RealInputDerivatives,
    RealOutputDerivatives,
}

impl Unsupported {
    fn describe(self) -> (&'static str, States, &'static str) {
        match self {
            Unsupported::RealInputDerivatives => {
                ("fmi2SetRealInputDerivatives", WRITABLE, "canInterpolateInputs = false")
            }
            Unsupported::RealOutputDerivatives => {
                ("fmi2GetRealOutputDerivatives", STEPPED, "maxOutputDerivativeOrder = 0")
            }
        }
    }
}

/// Every output finite, or why not: the last guard of "never NaN or Inf out", for finite
/// inputs so large that a model's arithmetic overflows. A few compares on the hot path; the
/// message is built only on failure.
fn finite(outputs: &Outputs) -> Result<(), String> {
    let reals = outputs.reals();
    if reals.iter().all(|x| x.is_finite()) {
        return Ok(());
    }
    let overflowing: Vec<String> = Outputs::NAMES
        .iter()
        .zip(reals)
        .filter(|(_, x)| !x.is_finite())
        .map(|(name, x)| format!("{name} = {x}"))
        .collect();
    Err(format!(
        "{} for these values: an input or parameter is too large for the model's floating-point range",
        overflowing.join(", ")
    ))
}

/// Whether a variable can be a known of fmi2GetDirectionalDerivative: a continuous Real input.
fn is_known(causality: Causality, variability: Variability, kind: &Kind) -> bool {
    causality == Causality::Input && variability == Variability::Continuous && matches!(kind, Kind::Real { .. })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model_description::{value_reference as vr, Inputs, GUID, VARIABLES};
    use std::cell::RefCell;
    use std::rc::Rc;

    type Log = Rc<RefCell<Vec<(Status, String, String)>>>;

    struct Recorder(Log);

    impl LogSink for Recorder {
        fn log(&mut self, status: Status, category: &str, message: &str) {
            self.0.borrow_mut().push((status, category.to_owned(), message.to_owned()));
        }
    }

    fn arguments(guid: &str) -> InstantiateArguments<'_> {
        InstantiateArguments {
            instance_name: "wheel 1",
            co_simulation: true,
            guid,
            resource_location: Some("file:///tmp/resources/"),
            logging_on: false,
        }
    }

    fn new_instance() -> (Instance, Log) {
        let log = Log::default();
        let instance = Instance::instantiate(arguments(GUID), Box::new(Recorder(log.clone()))).unwrap();
        (instance, log)
    }

    fn last_message(log: &Log) -> String {
        log.borrow().last().map(|(_, _, m)| m.clone()).unwrap_or_default()
    }

    /// Instantiated → initialization mode → step mode, with the start values.
    fn stepping() -> (Instance, Log) {
        let (mut instance, log) = new_instance();
        assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
        assert_eq!(instance.enter_initialization_mode(), Status::Ok);
        assert_eq!(instance.exit_initialization_mode(), Status::Ok);
        (instance, log)
    }

    fn get(instance: &mut Instance, value_reference: u32) -> f64 {
        let mut value = [f64::NAN];
        assert_eq!(instance.get_real(&[value_reference], &mut value), Status::Ok, "{value_reference}");
        value[0]
    }

    #[test]
    fn instantiate_copies_name_and_resources_and_checks_the_guid() {
        let (instance, _) = new_instance();
        assert_eq!((instance.name(), instance.resource_location()), ("wheel 1", Some("file:///tmp/resources/")));
        assert_eq!(instance.state(), Instantiated);
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
    fn outputs_follow_the_inputs_set_before_each_step() {
        let (mut instance, _) = new_instance();
        instance.setup_experiment(0.5, Some(2.0));
        instance.enter_initialization_mode();
        assert_eq!(instance.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[-2e-3]), Status::Ok);
        // In initialization mode a Get sees the input just set.
        let traction = get(&mut instance, vr::FORCE_LONGITUDINAL);
        assert!(traction > 0.0, "negative creepage gives a positive force: {traction}");
        assert_eq!(instance.exit_initialization_mode(), Status::Ok);
        assert_eq!(get(&mut instance, vr::FORCE_LONGITUDINAL), traction);
        // After the step, not before: the outputs change with DoStep only.
        instance.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[2e-3]);
        assert_eq!(get(&mut instance, vr::FORCE_LONGITUDINAL), traction);
        assert_eq!(instance.do_step(0.5, 0.25), Status::Ok);
        assert_eq!(get(&mut instance, vr::FORCE_LONGITUDINAL), -traction, "odd in the creepage");
        assert_eq!(instance.get_real_status(StatusKind::LastSuccessfulTime), Ok(0.75));
        // Variable step sizes, each continuing from the end of the last.
        for (t, h) in [(0.75, 1e-3), (0.751, 0.249), (1.0, 1.0)] {
            assert_eq!(instance.do_step(t, h), Status::Ok, "t = {t}, h = {h}");
        }
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
    }

    #[test]
    fn invalid_values_are_errors_naming_them_and_the_instance_recovers() {
        let (mut instance, log) = stepping();
        let before = *instance.values();
        for (value_reference, value, expected) in [
            (vr::CREEPAGE_LATERAL, f64::NAN, "fmi2DoStep: creepage_lateral = NaN is invalid: must be finite"),
            (vr::NORMAL_FORCE, f64::INFINITY, "fmi2DoStep: normal_force = inf is invalid: must be finite"),
            (vr::SEMI_AXIS_A, 0.0, "fmi2DoStep: semi_axis_a = 0 is invalid: must be finite and > 0"),
            (
                vr::FRICTION_COEFFICIENT,
                -0.1,
                "fmi2DoStep: friction_coefficient = -0.1 is invalid: must be finite and >= 0",
            ),
            (vr::SHEAR_MODULUS, -1.0, "fmi2DoStep: shear_modulus = -1 is invalid: must be finite and > 0"),
            (vr::POISSON_RATIO, 0.6, "fmi2DoStep: poisson_ratio = 0.6 is invalid: must lie in [0, 0.5]"),
        ] {
            assert_eq!(instance.set_real(&[value_reference], &[value]), Status::Ok);
            assert_eq!(instance.do_step(0.0, 0.1), Status::Error);
            assert_eq!(last_message(&log), expected);
            assert_eq!(instance.values().outputs, before.outputs, "outputs keep their last valid values");
            let start = before.real(value_reference).unwrap();
            instance.set_real(&[value_reference], &[start]);
        }
        assert_eq!(instance.do_step(0.0, 0.1), Status::Ok, "usable again once the values are good");
        assert_eq!(*instance.values(), before);
    }

    #[test]
    fn impossible_measured_curve_is_an_error_at_exit_initialization() {
        let (mut instance, log) = new_instance();
        instance.setup_experiment(0.0, None);
        instance.enter_initialization_mode();
        instance.set_integer(&[vr::STIFFNESS_SOURCE], &[StiffnessSourceValue::MEASURED]);
        instance.set_real(&[vr::MEASURED_PEAK_ADHESION], &[0.25]);
        assert_eq!(instance.exit_initialization_mode(), Status::Error);
        assert!(last_message(&log).starts_with("fmi2ExitInitializationMode: measured_peak_adhesion = 0.25 is invalid"));
        assert_eq!(instance.state(), InitializationMode, "the master may correct the value");
        instance.set_real(&[vr::MEASURED_PEAK_ADHESION], &[0.34]);
        assert_eq!(instance.exit_initialization_mode(), Status::Ok);
    }

    struct StiffnessSourceValue;
    impl StiffnessSourceValue {
        const MEASURED: i32 = crate::model_description::StiffnessSource::MeasuredCurve as i32;
    }

    #[test]
    fn lift_off_gives_zero_forces_without_error() {
        let (mut instance, _) = stepping();
        instance.set_real(&[vr::NORMAL_FORCE], &[-10.0]);
        assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
        let mut outputs = [f64::NAN; 3];
        instance.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION], &mut outputs);
        assert_eq!(outputs, [0.0; 3]);
    }

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
            assert_eq!(instance.values().inputs.creepage_lateral, 0.0, "nothing set");
        }
        let mut value = [0.0];
        assert_eq!(instance.get_real(&[1000], &mut value), Status::Error);
        assert_eq!(last_message(&log), "fmi2GetReal: unknown value reference 1000");
        let mut source = [0];
        assert_eq!(instance.get_integer(&[vr::STIFFNESS_SOURCE], &mut source), Status::Ok);
        assert_eq!(source, [1]);
        assert_eq!(instance.get_absent_type("fmi2GetBoolean", ValueType::Boolean, &[]), Status::Ok);
        assert_eq!(instance.get_absent_type("fmi2GetBoolean", ValueType::Boolean, &[vr::NORMAL_FORCE]), Status::Error);
        assert_eq!(last_message(&log), "fmi2GetBoolean: value reference 3 (normal_force) is not a Boolean");
        assert_eq!(instance.set_absent_type("fmi2SetString", ValueType::String, &[]), Status::Ok);
    }

    /// Every call outside the states the standard allows it in is refused, the state unchanged.
    #[test]
    fn illegal_calls_are_refused_in_every_state() {
        type Call = fn(&mut Instance) -> Status;
        let calls: [(&str, Call, States); 17] = [
            ("fmi2SetupExperiment", |i| i.setup_experiment(0.0, None), States::of(&[Instantiated])),
            ("fmi2EnterInitializationMode", Instance::enter_initialization_mode, States::of(&[Instantiated])),
            ("fmi2ExitInitializationMode", Instance::exit_initialization_mode, States::of(&[InitializationMode])),
            ("fmi2DoStep", |i| i.do_step(0.0, 1e-3), States::of(&[StepComplete])),
            ("fmi2Terminate", Instance::terminate, States::of(&[StepComplete])),
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
            ("fmi2SetFMUstate", |i| i.set_fmu_state(&FmuState(RunState::instantiated())), LIVE),
            ("fmi2FreeFMUstate", Instance::free_fmu_state, LIVE),
            (
                "fmi2SerializedFMUstateSize",
                |i| i.serialized_fmu_state_size(&FmuState(RunState::instantiated())).err().unwrap_or(Status::Ok),
                LIVE,
            ),
            ("fmi2DeSerializeFMUstate", |i| i.deserialize_fmu_state(&[]).err().unwrap_or(Status::Ok), LIVE),
            (
                "fmi2GetDirectionalDerivative",
                |i| i.get_directional_derivative(&[vr::FORCE_LATERAL], &[vr::CREEPAGE_LATERAL], &[1.0], &mut [0.0]),
                READABLE,
            ),
        ];
        let states: [(State, fn() -> Instance); 4] = [
            (Instantiated, || new_instance().0),
            (InitializationMode, || {
                let mut i = new_instance().0;
                i.enter_initialization_mode();
                i
            }),
            (StepComplete, || stepping().0),
            (Terminated, || {
                let mut i = stepping().0;
                i.terminate();
                i
            }),
        ];
        for (state, make) in states {
            for (name, call, allowed) in &calls {
                let log = Log::default();
                let mut instance = make();
                instance.sink = Box::new(Recorder(log.clone()));
                let status = call(&mut instance);
                let message = last_message(&log);
                if allowed.contains(state) {
                    assert!(!message.contains("illegal call"), "{name} in {state:?}: {message}");
                } else {
                    assert_eq!(status, Status::Error, "{name} in {state:?}");
                    assert_eq!(message, format!("{name}: illegal call in state {}", state.name()));
                    assert_eq!(instance.state(), state);
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
        assert_eq!(instance.state(), Instantiated);
        assert_eq!(instance.values().inputs, Inputs::default());
        assert_eq!(instance.values().parameters.shear_modulus, 82e9);
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
        let expected =
            "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder = 0 in modelDescription.xml)";
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
        assert!(
            last_message(&log).starts_with("fmi2SetDebugLogging: unknown log categories [\"noSuchCategory\"] ignored")
        );
        instance.do_step(0.0, 1.0);
        assert_eq!(last_message(&log), "fmi2DoStep: currentCommunicationPoint = 0, communicationStepSize = 1");
    }

    /// A point where every input matters: combined creepage with spin, partly saturated.
    fn at_a_general_point() -> (Instance, Log) {
        let (mut instance, log) = stepping();
        instance.set_real(&[vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE], &[-0.6e-3, 0.3]);
        assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
        (instance, log)
    }

    const OUTPUTS: [u32; 3] = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];

    #[test]
    fn directional_derivative_is_the_core_models_along_the_given_rates() {
        let (mut instance, _) = at_a_general_point();
        let knowns = [vr::CREEPAGE_LONGITUDINAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE, vr::CREEPAGE_LONGITUDINAL];
        let rates = [1.0, -0.5, 2e3, 0.25];
        let mut derivative = [f64::NAN; 3];
        assert_eq!(instance.get_directional_derivative(&OUTPUTS, &knowns, &rates, &mut derivative), Status::Ok);
        let input = crate::scene::contact_input(instance.values());
        let direction = wheel_rail_contact::ContactInput {
            creepage_longitudinal: 1.25, // a known given twice adds its rates
            creepage_lateral: 0.0,
            spin_creepage: -0.5,
            normal_force: 2e3,
            semi_axis_a: 0.0,
            semi_axis_b: 0.0,
            friction_coefficient: 0.0,
            shear_modulus: 0.0,
            poisson_ratio: 0.0,
        };
        use wheel_rail_contact::CreepForceModel;
        let expected = wheel_rail_contact::Polach::default().directional_derivative(&input, &direction).unwrap();
        assert_eq!(derivative, [expected.force_longitudinal, expected.force_lateral, expected.adhesion_utilisation]);
        // Unknowns in any order and subset.
        let mut lateral = [f64::NAN];
        instance.get_directional_derivative(&[vr::FORCE_LATERAL], &knowns, &rates, &mut lateral);
        assert_eq!(lateral[0], derivative[1]);
        // No knowns: zero.
        instance.get_directional_derivative(&OUTPUTS, &[], &[], &mut derivative);
        assert_eq!(derivative, [0.0; 3]);
    }

    #[test]
    fn directional_derivative_refuses_parameters_outputs_and_bad_rates_by_name() {
        let (mut instance, log) = at_a_general_point();
        let mut out = [0.0];
        let cases: [(&[u32], &[u32], f64, &str); 5] = [
            (
                &[vr::FORCE_LATERAL],
                &[vr::SHEAR_MODULUS],
                1.0,
                "fmi2GetDirectionalDerivative: shear_modulus (value reference 100) cannot be a known: derivatives are \
                 taken with respect to the continuous Real inputs only",
            ),
            (
                &[vr::FORCE_LATERAL],
                &[vr::FORCE_LONGITUDINAL],
                1.0,
                "fmi2GetDirectionalDerivative: force_longitudinal (value reference 200) cannot be a known: \
                 derivatives are taken with respect to the continuous Real inputs only",
            ),
            (
                &[vr::NORMAL_FORCE],
                &[vr::SEMI_AXIS_A],
                1.0,
                "fmi2GetDirectionalDerivative: normal_force (value reference 3) cannot be an unknown: not an output",
            ),
            (
                &[vr::FORCE_LATERAL],
                &[vr::SEMI_AXIS_A],
                f64::INFINITY,
                "fmi2GetDirectionalDerivative: dvKnown = inf for semi_axis_a is invalid: must be finite",
            ),
            (&[999], &[vr::SEMI_AXIS_A], 1.0, "fmi2GetDirectionalDerivative: unknown value reference 999"),
        ];
        for (unknowns, knowns, rate, expected) in cases {
            assert_eq!(instance.get_directional_derivative(unknowns, knowns, &[rate], &mut out), Status::Error);
            assert_eq!(last_message(&log), expected);
        }
        // At an invalid point the variable is named, as for DoStep.
        instance.set_real(&[vr::SEMI_AXIS_B], &[-1.0]);
        assert_eq!(
            instance.get_directional_derivative(&OUTPUTS[..1], &[vr::SEMI_AXIS_A], &[1.0], &mut out),
            Status::Error
        );
        assert_eq!(
            last_message(&log),
            "fmi2GetDirectionalDerivative: semi_axis_b = -1 is invalid: must be finite and > 0"
        );
    }

    /// `<ModelStructure>` dependencies and the Jacobian agree: for each smooth model, at a
    /// general point, every non-zero derivative is along a declared dependency. (The declared
    /// lists hold what can change an output under some model or option; that each declared input
    /// does change its output somewhere is tested in `scene.rs` by perturbation.)
    #[test]
    fn every_non_zero_derivative_is_a_declared_dependency() {
        use crate::model_description::Model;
        for model in [Model::Polach, Model::KalkerLinear, Model::ShenHedrickElkins] {
            let (mut instance, _) = new_instance();
            assert_eq!(instance.set_integer(&[vr::CREEP_FORCE_MODEL], &[model as i32]), Status::Ok);
            assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
            assert_eq!(instance.enter_initialization_mode(), Status::Ok);
            assert_eq!(instance.exit_initialization_mode(), Status::Ok);
            instance.set_real(&[vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE], &[-0.6e-3, 0.3]);
            assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
            let mut non_zero = 0;
            for input in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
                for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
                    let mut derivative = [f64::NAN];
                    let status = instance.get_directional_derivative(
                        &[output.value_reference],
                        &[input.value_reference],
                        &[1.0],
                        &mut derivative,
                    );
                    assert_eq!(status, Status::Ok);
                    if derivative[0] != 0.0 {
                        non_zero += 1;
                        let declared = output.dependencies.contains(&input.value_reference);
                        assert!(
                            declared,
                            "{model:?}: d {} / d {} = {} undeclared",
                            output.name, input.name, derivative[0]
                        );
                    }
                }
            }
            assert!(non_zero > 30, "{model:?}: only {non_zero} non-zero derivatives");
        }
    }

    #[test]
    fn an_fmu_state_restores_mode_time_and_every_value() {
        let (mut instance, _) = at_a_general_point();
        let saved = instance.get_fmu_state().unwrap();
        let before = (instance.state(), *instance.values(), instance.get_real_status(StatusKind::LastSuccessfulTime));
        instance.set_real(&[vr::NORMAL_FORCE, vr::SHEAR_MODULUS], &[20e3, 70e9]);
        instance.set_integer(&[vr::STIFFNESS_SOURCE], &[StiffnessSourceValue::MEASURED]);
        instance.do_step(0.1, 0.2);
        instance.terminate();
        assert_eq!(instance.set_fmu_state(&saved), Status::Ok);
        let after = (instance.state(), *instance.values(), instance.get_real_status(StatusKind::LastSuccessfulTime));
        assert_eq!(after, before);
        // Through bytes, into an instance in another mode: the same.
        let mut bytes = vec![0; instance.serialized_fmu_state_size(&saved).unwrap()];
        assert_eq!(instance.serialize_fmu_state(&saved, &mut bytes), Status::Ok);
        let (mut fresh, _) = new_instance();
        let restored = fresh.deserialize_fmu_state(&bytes).unwrap();
        assert_eq!(restored, saved);
        fresh.set_fmu_state(&restored);
        assert_eq!((fresh.state(), *fresh.values()), (before.0, before.1));
        // The master's settings are not part of the state.
        assert_eq!(fresh.name(), "wheel 1");
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
        assert_eq!(instance.deserialize_fmu_state(b"WRCst").unwrap_err(), Status::Error);
        let expected =
            "fmi2DeSerializeFMUstate: serializedState rejected: truncated: 5 bytes, the state needs at least 19";
        assert_eq!(last_message(&log), expected);
    }

    #[test]
    fn an_overflowing_coulomb_limit_is_an_error_and_keeps_the_last_valid_values() {
        // Found by the fuzz harness: finite μ and Q whose product overflows. The core rejects it
        // by name; the finite-outputs check behind it stays as a backstop.
        let (mut instance, log) = stepping();
        let before = instance.values().outputs;
        instance.set_real(&[vr::FRICTION_COEFFICIENT], &[f64::MAX]);
        assert_eq!(instance.do_step(0.0, 0.1), Status::Error);
        assert_eq!(
            last_message(&log),
            "fmi2DoStep: friction_coefficient = 1.7976931348623157e308 is invalid: times normal_force \
             (the Coulomb limit μQ) must be finite"
        );
        assert_eq!(instance.values().outputs, before);
    }

    #[test]
    fn a_panic_becomes_fatal_and_only_freeing_remains() {
        let (mut instance, log) = stepping();
        let status = instance.guarded("fmi2DoStep", |_| panic!("a bug"));
        assert_eq!(status, Status::Fatal);
        assert_eq!(instance.state(), State::Fatal);
        let (status, category, message) = log.borrow().last().cloned().unwrap();
        assert_eq!((status, category.as_str()), (Status::Fatal, "logStatusFatal"));
        assert_eq!(message, "fmi2DoStep: internal error (a bug); this instance can only be freed");
        assert_eq!(instance.guarded("fmi2Reset", Instance::reset), Status::Error);
        assert_eq!(last_message(&log), "fmi2Reset: illegal call in state fatal");
    }
}
