//! # fmi2-slave
//!
//! The model-independent half of an FMI 2.0 FMU (Co-Simulation and Model Exchange in one binary), shared by every FMU of this
//! workspace so that none copies another's C boundary:
//!
//! - [`fmi2`]: the FMI 2.0 C types;
//! - [`ffi`]: the 44 `fmi2*` functions as generic Rust (pointer checks, C strings and slices,
//!   panic catching, FMU-state boxing) over a [`Slave`], and [`export_fmi2!`], which expands to
//!   the `#[no_mangle] extern "C"` exports of one cdylib for its slave type; for in-process
//!   masters (tests), a logger callback from a Rust function and, behind the `message-log`
//!   feature, the one recording logger (`ffi::message_log`). The only file with `unsafe`;
//! - [`mode`]: the Co-Simulation and Model Exchange state machines: modes and the call table saying which modes
//!   allow each call;
//! - [`instance`]: the generic instance (lifecycle, Get/Set of Real, Integer, Enumeration and
//!   String variables, step checks, evaluation warnings, FMU states, directional derivatives)
//!   around an [`instance::Model`] (its values, its evaluation, what it keeps that is not state),
//!   implementing [`Slave`];
//! - [`logging`]: statuses, the logger sink and the log filter;
//! - [`state_format`]: the byte format of a serialized FMU state (magic, version, layout tag,
//!   GUID, CRC-32 around the FMU's payload), the same for every FMU;
//! - [`variables`]: the types of the variable tables generated from a `modelDescription.xml`, and
//!   `build` (feature `build`, for build scripts): the generator itself, which also checks the
//!   XML against the rules of the standard that masters rely on.
//!
//! A model crate implements [`instance::Model`] (safe code only) and writes
//! `export_fmi2!(fmi2_slave::instance::Instance<MyModel>);` in one module.

#![deny(unsafe_code)]

#[cfg(feature = "build")]
pub mod build;
pub mod ffi;
pub mod fmi2;
pub mod instance;
pub mod logging;
pub mod mode;
pub mod state_format;
pub mod variables;

use std::borrow::Cow;
use std::ffi::CString;

use logging::{LogSink, Status};
use mode::Call;

/// The FMI 2.0 functions (`fmi2Functions.h`: the common ones with the FMU-state and derivative
/// functions, the 9 of Co-Simulation and the 10 of Model Exchange): what [`export_fmi2!`] exports, and all a
/// binary of this layer may export (`build::export_only_fmi2_functions` holds a win64 DLL to it).
pub const FMI2_FUNCTIONS: [&str; 44] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
    "fmi2EnterEventMode",
    "fmi2NewDiscreteStates",
    "fmi2EnterContinuousTimeMode",
    "fmi2CompletedIntegratorStep",
    "fmi2SetTime",
    "fmi2SetContinuousStates",
    "fmi2GetDerivatives",
    "fmi2GetEventIndicators",
    "fmi2GetContinuousStates",
    "fmi2GetNominalsOfContinuousStates",
];

/// `fmi2StatusKind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusKind {
    DoStepStatus,
    PendingStatus,
    LastSuccessfulTime,
    Terminated,
}

/// What fmi2Instantiate received, decoded.
pub struct InstantiateArguments<'a> {
    pub instance_name: &'a str,
    /// The interface asked for, or the `fmuType` value that is neither.
    pub interface: Result<mode::Interface, u32>,
    pub guid: &'a str,
    pub resource_location: Option<&'a str>,
    pub logging_on: bool,
}

/// The optional capabilities an FMU of this workspace may declare false.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unsupported {
    RealInputDerivatives,
    RealOutputDerivatives,
    DirectionalDerivative,
}

impl Unsupported {
    /// The call that asks for the capability, and the capability flag in `modelDescription.xml`
    /// that says it is absent.
    pub fn describe(self) -> (Call, &'static str) {
        match self {
            Unsupported::RealInputDerivatives => (Call::SetRealInputDerivatives, "canInterpolateInputs = false"),
            Unsupported::RealOutputDerivatives => (Call::GetRealOutputDerivatives, "maxOutputDerivativeOrder = 0"),
            Unsupported::DirectionalDerivative => {
                (Call::GetDirectionalDerivative, "providesDirectionalDerivative = false")
            }
        }
    }
}

/// One FMU instance as the C exports see it: one safe method per FMI 2.0 call, after [`ffi`] has
/// checked the pointers and turned them into slices and strings.
///
/// Contract: a method checks the state machine itself (an illegal call is `Error`, logged as
/// `fmi2XXX: illegal call in state YYY`) and logs every non-OK status it returns through the
/// sink it was instantiated with; [`Slave::guarded`] runs each call (except fmi2Instantiate and
/// fmi2FreeInstance, which [`ffi`] guards itself) and turns a panic into `Fatal`.
pub trait Slave: Sized {
    /// The object behind an `fmi2FMUstate` pointer (boxed by [`ffi`]).
    type FmuState;

    /// fmi2Instantiate: `None` (after logging why through `sink`) when the arguments are refused.
    fn instantiate(arguments: InstantiateArguments, sink: Box<dyn LogSink>) -> Option<Self>;
    /// Runs one FMI call; a panic inside `body` becomes `Fatal`, is logged, and leaves the
    /// instance accepting nothing but fmi2FreeInstance.
    fn guarded(&mut self, call: Call, body: impl FnOnce(&mut Self) -> Status) -> Status;
    /// An argument [`ffi`] found unusable (a NULL pointer with n > 0, an unknown enum value).
    fn invalid_argument(&mut self, call: Call, reason: &str) -> Status;
    /// A capability the FMU declares false.
    fn unsupported(&mut self, capability: Unsupported) -> Status;

    fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status;
    fn setup_experiment(&mut self, start_time: f64, stop_time: Option<f64>) -> Status;
    fn enter_initialization_mode(&mut self) -> Status;
    fn exit_initialization_mode(&mut self) -> Status;
    fn terminate(&mut self) -> Status;
    fn reset(&mut self) -> Status;

    fn get_real(&mut self, value_references: &[u32], values: &mut [f64]) -> Status;
    fn get_integer(&mut self, value_references: &[u32], values: &mut [i32]) -> Status;
    fn get_boolean(&mut self, value_references: &[u32], values: &mut [i32]) -> Status;
    /// The texts as C strings, kept by the instance until its next fmi2GetString.
    fn get_string(&mut self, value_references: &[u32]) -> Result<&[CString], Status>;
    fn set_real(&mut self, value_references: &[u32], values: &[f64]) -> Status;
    fn set_integer(&mut self, value_references: &[u32], values: &[i32]) -> Status;
    fn set_boolean(&mut self, value_references: &[u32], values: &[i32]) -> Status;
    fn set_string(&mut self, value_references: &[u32], values: &[Cow<'_, str>]) -> Status;

    fn get_fmu_state(&mut self) -> Result<Self::FmuState, Status>;
    fn set_fmu_state(&mut self, state: &Self::FmuState) -> Status;
    /// Whether fmi2FreeFMUstate is legal now ([`ffi`] releases the memory).
    fn free_fmu_state(&mut self) -> Status;
    fn serialized_fmu_state_size(&mut self, state: &Self::FmuState) -> Result<usize, Status>;
    /// `bytes` must have exactly the serialized size.
    fn serialize_fmu_state(&mut self, state: &Self::FmuState, bytes: &mut [u8]) -> Status;
    fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<Self::FmuState, Status>;

    /// `unknown_rates` = J·`known_rates`, J = ∂(unknowns)/∂(knowns).
    fn get_directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Status;

    fn do_step(&mut self, current_communication_point: f64, communication_step_size: f64) -> Status;
    fn cancel_step(&mut self) -> Status;
    fn get_status(&mut self, kind: StatusKind) -> Status;
    fn get_real_status(&mut self, kind: StatusKind) -> Result<f64, Status>;
    fn get_integer_status(&mut self, kind: StatusKind) -> Status;
    fn get_boolean_status(&mut self, kind: StatusKind) -> Result<bool, Status>;
    fn get_string_status(&mut self, kind: StatusKind) -> Status;

    // Model Exchange (FMI 2.0, section 3.2).
    fn enter_event_mode(&mut self) -> Status;
    fn new_discrete_states(&mut self) -> Result<EventInfo, Status>;
    fn enter_continuous_time_mode(&mut self) -> Status;
    /// `(enterEventMode, terminateSimulation)`.
    fn completed_integrator_step(&mut self) -> Result<(bool, bool), Status>;
    fn set_time(&mut self, time: f64) -> Status;
    fn set_continuous_states(&mut self, states: &[f64]) -> Status;
    fn get_derivatives(&mut self, derivatives: &mut [f64]) -> Status;
    fn get_event_indicators(&mut self, indicators: &mut [f64]) -> Status;
    fn get_continuous_states(&mut self, states: &mut [f64]) -> Status;
    fn get_nominals_of_continuous_states(&mut self, nominals: &mut [f64]) -> Status;
}

/// `fmi2EventInfo`, decoded: what fmi2NewDiscreteStates reports.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EventInfo {
    pub new_discrete_states_needed: bool,
    pub terminate_simulation: bool,
    pub nominals_of_continuous_states_changed: bool,
    pub values_of_continuous_states_changed: bool,
    /// The time of the next time event, if there is one.
    pub next_event_time: Option<f64>,
}
