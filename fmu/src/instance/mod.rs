//! One FMU instance: its lifecycle through the FMI 2.0 Co-Simulation state machine
//! ([`crate::mode`]), logging, status inquiries; by concern in the sibling files: `values.rs`
//! (Get/Set), `step.rs` (DoStep, the outputs), `fmu_state.rs` (FMU states), `derivative.rs`
//! (directional derivatives). Unit tests sit beside each, in `*_tests.rs`.
//!
//! Safe code only: `ffi` turns C arguments into slices and strings and calls these methods, so
//! unit tests drive every rule here without the C boundary.
//!
//! Rules (FMI 2.0.4, section 4.2.4, Co-Simulation state machine), the argument checks and their
//! messages shared with the slave layer's generic instance (`fmi2_slave::instance`):
//! - a call outside the states that allow it returns `Error` and logs
//!   `fmi2XXX: illegal call in state YYY`; the state does not change;
//! - an invalid value (NaN, a ≤ 0, …) is reported where outputs are computed
//!   (ExitInitializationMode, DoStep, GetReal of an output in Mode::InitializationMode) as `Error`
//!   naming the variable and value. The instance keeps its state, so the master can set a good
//!   value and carry on (this FMU never enters the standard's `error` state);
//! - a panic inside a call (a bug) is caught by [`Instance::guarded`]: `Fatal`, logged, and the
//!   instance accepts nothing but fmi2FreeInstance afterwards.
//!
//! The hot path (fmi2SetReal/DoStep/GetReal) does no allocation, no string comparison and no
//! search: one dense-table lookup per value reference, a bit test for the state, and a log
//! filter decided once per fmi2SetDebugLogging.

use std::borrow::Cow;
use std::ffi::CString;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

mod derivative;
mod fmu_state;
mod step;
mod values;

pub use fmi2_slave::{InstantiateArguments, StatusKind, Unsupported};
pub use fmu_state::FmuState;
pub use values::ValueType;

use crate::logging::{LogFilter, LogSink, Logger, Status};
use crate::mode::{Call, Mode, Modes, LIVE};
use crate::model_description::{self, Values, LOG_CATEGORIES};
use crate::resources::resource_directory;
use crate::scene::ModelCache;
use crate::snapshot::Snapshot;
use fmi2_slave::instance as rules;
use wheel_rail_contact::scene::Evaluation;

/// Under `cfg(test)` only: a log category that makes fmi2SetDebugLogging panic, so that a test
/// can drive a real panic through an export and see it become fmi2Fatal. Not in any FMU binary.
#[cfg(test)]
pub(crate) const PANIC_CATEGORY_FOR_TESTS: &str = "panicForTests";

/// One instance of the FMU.
pub struct Instance {
    name: String,
    resource_location: Option<String>,
    /// The directory it names, if it names one: where relative profile paths are looked up first.
    resources: Option<PathBuf>,
    /// Mode, time, values and model state: exactly what an FMU state saves and restores.
    run: Snapshot,
    /// A cache derived from the parameters (not state: it is refitted whenever they differ).
    model: ModelCache,
    /// What the last fmi2GetString returned: the master's pointers point into these.
    returned_strings: Vec<CString>,
    /// The master's logger behind the log filter.
    log: Logger,
}

impl Instance {
    /// fmi2Instantiate: `None` (after logging why) for a wrong GUID, an empty name, Model
    /// Exchange, or a missing or corrupted `exact_table` table in the resources directory.
    pub fn instantiate(arguments: InstantiateArguments, sink: Box<dyn LogSink>) -> Option<Instance> {
        let problem =
            rules::instantiate_problem(&arguments, model_description::GUID, model_description::MODEL_IDENTIFIER);
        let InstantiateArguments { instance_name, resource_location, logging_on, .. } = arguments;
        let mut log = Logger::new(logging_on, sink);
        let resources = resource_location.map(resource_directory);
        let problem =
            problem.or_else(|| crate::exact_table::check(resources.as_ref().and_then(|r| r.as_deref().ok())).err());
        if let Some(problem) = problem {
            log.fail(Call::Instantiate, &problem);
            return None;
        }
        let mut instance = Instance {
            name: instance_name.to_owned(),
            resource_location: resource_location.map(str::to_owned),
            resources: resources.clone().and_then(Result::ok),
            run: Snapshot::instantiated(),
            model: ModelCache::new(resources.clone().and_then(Result::ok)),
            returned_strings: Vec::new(),
            log,
        };
        instance.log.trace(|| format!("fmi2Instantiate: resourceLocation = {}", resource_location.unwrap_or("NULL")));
        if let Some(Err(reason)) = resources {
            // Not an error: only a relative profile path needs the directory, and is then also
            // looked up in the working directory.
            instance.log.trace(|| {
                format!("fmi2Instantiate: {reason}; relative profile paths are read from the working directory")
            });
        }
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

    pub fn state(&self) -> Mode {
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
    pub fn guarded(&mut self, call: Call, body: impl FnOnce(&mut Instance) -> Status) -> Status {
        match catch_unwind(AssertUnwindSafe(|| body(self))) {
            Ok(status) => status,
            Err(payload) => self.panicked(call, payload.as_ref()),
        }
    }

    #[cold]
    fn panicked(&mut self, call: Call, payload: &(dyn std::any::Any + Send)) -> Status {
        self.run.mode = Mode::Fatal;
        self.log.emit(Status::Fatal, &rules::panic_message(call, payload));
        Status::Fatal
    }

    #[inline]
    fn require(&mut self, call: Call) -> Result<(), Status> {
        self.require_in(call, call.allowed())
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

    /// fmi2SetDebugLogging. Unknown categories are ignored with a warning.
    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        const CALL: Call = Call::SetDebugLogging;
        #[cfg(test)]
        if categories.contains(&PANIC_CATEGORY_FOR_TESTS) {
            panic!("forced by a test through the category {PANIC_CATEGORY_FOR_TESTS}");
        }
        if let Err(status) = self.require(CALL) {
            return status;
        }
        let selection = if categories.is_empty() { None } else { Some(categories) };
        self.log.select(LogFilter::new(logging_on, selection));
        self.log.trace(|| format!("{CALL}: loggingOn = {logging_on}, categories = {categories:?}"));
        match rules::unknown_categories_message(categories, LOG_CATEGORIES) {
            None => Status::Ok,
            Some(message) => {
                self.log.emit(Status::Warning, &message);
                Status::Warning
            }
        }
    }

    /// fmi2SetupExperiment. The tolerance is not used: the outputs are algebraic in the inputs.
    pub fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Status {
        const CALL: Call = Call::SetupExperiment;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: startTime = {start_time}, stopTime = {stop_time:?}"));
        if let Some(problem) = rules::experiment_problem(start_time, stop_time) {
            return self.log.fail(CALL, &problem);
        }
        self.run.time = start_time;
        self.run.stop_time = stop_time;
        Status::Ok
    }

    pub fn enter_initialization_mode(&mut self) -> Status {
        const CALL: Call = Call::EnterInitializationMode;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run.mode = Mode::InitializationMode;
        Status::Ok
    }

    /// fmi2ExitInitializationMode: computes the outputs; with an invalid value it stays in
    /// initialization mode so that the master can correct it.
    pub fn exit_initialization_mode(&mut self) -> Status {
        const CALL: Call = Call::ExitInitializationMode;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        match self.update_outputs(CALL, Evaluation::Initialise) {
            Ok(status) => {
                self.run.mode = Mode::StepComplete;
                status
            }
            Err(status) => status,
        }
    }

    pub fn terminate(&mut self) -> Status {
        const CALL: Call = Call::Terminate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run.mode = Mode::Terminated;
        Status::Ok
    }

    /// fmi2Reset: back to the start values and the `instantiated` state (the log settings stay).
    pub fn reset(&mut self) -> Status {
        const CALL: Call = Call::Reset;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| CALL.name().to_owned());
        self.run = Snapshot::instantiated();
        self.model = ModelCache::new(self.resources.clone());
        Status::Ok
    }

    fn discard_status(&mut self, call: Call, kind: StatusKind) -> Status {
        self.log.emit(Status::Discard, &rules::discard_message(call, kind));
        Status::Discard
    }

    /// fmi2GetStatus: nothing to report (steps are synchronous and never discarded).
    pub fn get_status(&mut self, kind: StatusKind) -> Status {
        const CALL: Call = Call::GetStatus;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// fmi2GetRealStatus: `fmi2LastSuccessfulTime` is the end of the last completed step.
    pub fn get_real_status(&mut self, kind: StatusKind) -> Result<f64, Status> {
        const CALL: Call = Call::GetRealStatus;
        self.require(CALL)?;
        match kind {
            StatusKind::LastSuccessfulTime => Ok(self.run.time),
            _ => Err(self.discard_status(CALL, kind)),
        }
    }

    /// fmi2GetIntegerStatus: the standard defines no integer status.
    pub fn get_integer_status(&mut self, kind: StatusKind) -> Status {
        const CALL: Call = Call::GetIntegerStatus;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// fmi2GetBooleanStatus: `fmi2Terminated` is false: this FMU never asks to stop.
    pub fn get_boolean_status(&mut self, kind: StatusKind) -> Result<bool, Status> {
        const CALL: Call = Call::GetBooleanStatus;
        self.require(CALL)?;
        match kind {
            StatusKind::Terminated => Ok(false),
            _ => Err(self.discard_status(CALL, kind)),
        }
    }

    /// fmi2GetStringStatus: `fmi2PendingStatus` has nothing to report (no pending step).
    pub fn get_string_status(&mut self, kind: StatusKind) -> Status {
        const CALL: Call = Call::GetStringStatus;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.discard_status(CALL, kind)
    }

    /// An unsupported capability: `Error` with the capability flag that says so.
    pub fn unsupported(&mut self, capability: Unsupported) -> Status {
        let (call, flag) = capability.describe();
        if let Err(status) = self.require(call) {
            return status;
        }
        self.log.fail(call, &format!("not supported ({flag} in modelDescription.xml)"))
    }

    /// An argument the C layer found unusable (a NULL pointer with n > 0, an unknown enum value).
    pub fn invalid_argument(&mut self, call: Call, reason: &str) -> Status {
        if let Err(status) = self.require_in(call, LIVE) {
            return status;
        }
        self.log.fail(call, reason)
    }
}

/// The C exports' view of the instance (see [`crate::ffi`]): each call is the inherent method
/// of the same name.
impl fmi2_slave::Slave for Instance {
    type FmuState = FmuState;

    fn instantiate(arguments: InstantiateArguments, sink: Box<dyn LogSink>) -> Option<Self> {
        Instance::instantiate(arguments, sink)
    }
    #[inline]
    fn guarded(&mut self, call: Call, body: impl FnOnce(&mut Self) -> Status) -> Status {
        Instance::guarded(self, call, body)
    }
    fn invalid_argument(&mut self, call: Call, reason: &str) -> Status {
        Instance::invalid_argument(self, call, reason)
    }
    fn unsupported(&mut self, capability: Unsupported) -> Status {
        Instance::unsupported(self, capability)
    }
    fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        Instance::set_debug_logging(self, logging_on, categories)
    }
    fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Status {
        Instance::setup_experiment(self, start_time, stop_time)
    }
    fn enter_initialization_mode(&mut self) -> Status {
        Instance::enter_initialization_mode(self)
    }
    fn exit_initialization_mode(&mut self) -> Status {
        Instance::exit_initialization_mode(self)
    }
    fn terminate(&mut self) -> Status {
        Instance::terminate(self)
    }
    fn reset(&mut self) -> Status {
        Instance::reset(self)
    }
    #[inline]
    fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status {
        Instance::get_real(self, value_references, values)
    }
    fn get_integer(&mut self, value_references: &[u32], values: &mut [i32]) -> Status {
        Instance::get_integer(self, value_references, values)
    }
    fn get_boolean(&mut self, value_references: &[u32], _values: &mut [i32]) -> Status {
        self.get_absent_type(Call::GetBoolean, ValueType::Boolean, value_references)
    }
    fn get_string(&mut self, value_references: &[u32]) -> Result<&[CString], Status> {
        Instance::get_string(self, value_references)
    }
    #[inline]
    fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status {
        Instance::set_real(self, value_references, values)
    }
    fn set_integer(&mut self, value_references: &[u32], values: &[i32]) -> Status {
        Instance::set_integer(self, value_references, values)
    }
    fn set_boolean(&mut self, value_references: &[u32], _values: &[i32]) -> Status {
        self.set_absent_type(Call::SetBoolean, ValueType::Boolean, value_references)
    }
    fn set_string(&mut self, value_references: &[u32], values: &[Cow<'_, str>]) -> Status {
        Instance::set_string(self, value_references, values)
    }
    fn get_fmu_state(&mut self) -> Result<FmuState, Status> {
        Instance::get_fmu_state(self)
    }
    fn set_fmu_state(&mut self, state: &FmuState) -> Status {
        Instance::set_fmu_state(self, state)
    }
    fn free_fmu_state(&mut self) -> Status {
        Instance::free_fmu_state(self)
    }
    fn serialized_fmu_state_size(&mut self, state: &FmuState) -> Result<usize, Status> {
        Instance::serialized_fmu_state_size(self, state)
    }
    fn serialize_fmu_state(&mut self, state: &FmuState, bytes: &mut [u8]) -> Status {
        Instance::serialize_fmu_state(self, state, bytes)
    }
    fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<FmuState, Status> {
        Instance::deserialize_fmu_state(self, bytes)
    }
    fn get_directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Status {
        Instance::get_directional_derivative(self, unknowns, knowns, known_rates, unknown_rates)
    }
    #[inline]
    fn do_step(&mut self, current_communication_point: f64, communication_step_size: f64) -> Status {
        Instance::do_step(self, current_communication_point, communication_step_size)
    }
    fn cancel_step(&mut self) -> Status {
        Instance::cancel_step(self)
    }
    fn get_status(&mut self, kind: StatusKind) -> Status {
        Instance::get_status(self, kind)
    }
    fn get_real_status(&mut self, kind: StatusKind) -> Result<f64, Status> {
        Instance::get_real_status(self, kind)
    }
    fn get_integer_status(&mut self, kind: StatusKind) -> Status {
        Instance::get_integer_status(self, kind)
    }
    fn get_boolean_status(&mut self, kind: StatusKind) -> Result<bool, Status> {
        Instance::get_boolean_status(self, kind)
    }
    fn get_string_status(&mut self, kind: StatusKind) -> Status {
        Instance::get_string_status(self, kind)
    }
}

#[cfg(test)]
mod derivative_tests;
#[cfg(test)]
mod fmu_state_tests;
#[cfg(test)]
mod instance_tests;
#[cfg(test)]
mod step_tests;
#[cfg(test)]
mod test_support;
#[cfg(test)]
mod values_tests;
