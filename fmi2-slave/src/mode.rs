//! The FMI 2.0 state machines, Co-Simulation (FMI 2.0.4, section 4.2.4) and Model Exchange
//! (section 3.2.3), in one: the modes an instance can be in (a Co-Simulation instance never
//! enters `eventMode` or `continuousTimeMode`, a Model Exchange one never `stepComplete`), which
//! modes allow which call, as bit masks (membership is one bit test), and which interface a call
//! belongs to.

use serde::{Deserialize, Serialize};

/// The states of the two state machines that this FMU can be in (the discriminants are the
/// mode byte of a serialized FMU state: new modes go at the end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mode {
    Instantiated,
    InitializationMode,
    StepComplete,
    Terminated,
    Fatal,
    /// Model Exchange: after initialization and at events.
    EventMode,
    /// Model Exchange: between events, while the master integrates.
    ContinuousTimeMode,
}

impl Mode {
    /// The state's name as the standard writes it.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Instantiated => "instantiated",
            Mode::InitializationMode => "initializationMode",
            Mode::StepComplete => "stepComplete",
            Mode::Terminated => "terminated",
            Mode::Fatal => "fatal",
            Mode::EventMode => "eventMode",
            Mode::ContinuousTimeMode => "continuousTimeMode",
        }
    }
}

use Mode::{ContinuousTimeMode, EventMode, InitializationMode, Instantiated, StepComplete, Terminated};

/// A set of states as a bit mask: membership is one bit test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Modes(u8);

impl Modes {
    pub const fn of(modes: &[Mode]) -> Modes {
        let mut mask = 0;
        let mut i = 0;
        while i < modes.len() {
            mask |= 1 << modes[i] as u8;
            i += 1;
        }
        Modes(mask)
    }

    #[inline]
    pub fn contains(self, mode: Mode) -> bool {
        self.0 & (1 << mode as u8) != 0
    }
}

/// Where SetDebugLogging, Reset and the FMU-state functions are allowed.
pub const LIVE: Modes =
    Modes::of(&[Instantiated, InitializationMode, StepComplete, EventMode, ContinuousTimeMode, Terminated]);
/// Where values may be read (and directional derivatives taken).
pub const READABLE: Modes = Modes::of(&[InitializationMode, StepComplete, EventMode, ContinuousTimeMode, Terminated]);
/// Where values may be written (which ones: the variable's causality and variability decide).
pub const WRITABLE: Modes = Modes::of(&[Instantiated, InitializationMode, StepComplete, EventMode, ContinuousTimeMode]);
/// Where the step status may be inquired.
pub const STEPPED: Modes = Modes::of(&[StepComplete, Terminated]);
/// Where initialization is over and the instance is running or has run: the modes after
/// fmi2ExitInitializationMode, of either interface.
pub const INITIALIZED: Modes = Modes::of(&[StepComplete, EventMode, ContinuousTimeMode, Terminated]);
/// Where the continuous states, their derivatives and the event indicators may be read (Model
/// Exchange; the states are computed in initialization mode on demand).
pub const STATES_READABLE: Modes = Modes::of(&[InitializationMode, EventMode, ContinuousTimeMode, Terminated]);
/// Nowhere.
pub const NEVER: Modes = Modes::of(&[]);

/// The interface an instance was instantiated for (fmi2Instantiate's `fmuType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    ModelExchange,
    CoSimulation,
}

impl Interface {
    pub fn name(self) -> &'static str {
        match self {
            Interface::ModelExchange => "Model Exchange",
            Interface::CoSimulation => "Co-Simulation",
        }
    }

    pub fn other(self) -> Interface {
        match self {
            Interface::ModelExchange => Interface::CoSimulation,
            Interface::CoSimulation => Interface::ModelExchange,
        }
    }

    /// The mode fmi2ExitInitializationMode leaves an instance of this interface in.
    pub fn after_initialization(self) -> Mode {
        match self {
            Interface::ModelExchange => EventMode,
            Interface::CoSimulation => StepComplete,
        }
    }

    /// The modes only an instance of this interface is ever in.
    pub fn own_modes(self) -> Modes {
        match self {
            Interface::ModelExchange => Modes::of(&[EventMode, ContinuousTimeMode]),
            Interface::CoSimulation => Modes::of(&[StepComplete]),
        }
    }
}

/// The FMI 2.0 calls an instance answers, each with the modes that allow it: the standard's
/// state-machine table (FMI 2.0.4, section 4.2.4) in one place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    Instantiate,
    FreeInstance,
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    GetReal,
    GetInteger,
    GetBoolean,
    GetString,
    SetReal,
    SetInteger,
    SetBoolean,
    SetString,
    GetFMUstate,
    SetFMUstate,
    FreeFMUstate,
    SerializedFMUstateSize,
    SerializeFMUstate,
    DeSerializeFMUstate,
    GetDirectionalDerivative,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
    DoStep,
    CancelStep,
    GetStatus,
    GetRealStatus,
    GetIntegerStatus,
    GetBooleanStatus,
    GetStringStatus,
    EnterEventMode,
    NewDiscreteStates,
    EnterContinuousTimeMode,
    CompletedIntegratorStep,
    SetTime,
    SetContinuousStates,
    GetDerivatives,
    GetEventIndicators,
    GetContinuousStates,
    GetNominalsOfContinuousStates,
}

impl Call {
    /// The C function's name, as messages name the call.
    pub fn name(self) -> &'static str {
        match self {
            Call::Instantiate => "fmi2Instantiate",
            Call::FreeInstance => "fmi2FreeInstance",
            Call::SetDebugLogging => "fmi2SetDebugLogging",
            Call::SetupExperiment => "fmi2SetupExperiment",
            Call::EnterInitializationMode => "fmi2EnterInitializationMode",
            Call::ExitInitializationMode => "fmi2ExitInitializationMode",
            Call::Terminate => "fmi2Terminate",
            Call::Reset => "fmi2Reset",
            Call::GetReal => "fmi2GetReal",
            Call::GetInteger => "fmi2GetInteger",
            Call::GetBoolean => "fmi2GetBoolean",
            Call::GetString => "fmi2GetString",
            Call::SetReal => "fmi2SetReal",
            Call::SetInteger => "fmi2SetInteger",
            Call::SetBoolean => "fmi2SetBoolean",
            Call::SetString => "fmi2SetString",
            Call::GetFMUstate => "fmi2GetFMUstate",
            Call::SetFMUstate => "fmi2SetFMUstate",
            Call::FreeFMUstate => "fmi2FreeFMUstate",
            Call::SerializedFMUstateSize => "fmi2SerializedFMUstateSize",
            Call::SerializeFMUstate => "fmi2SerializeFMUstate",
            Call::DeSerializeFMUstate => "fmi2DeSerializeFMUstate",
            Call::GetDirectionalDerivative => "fmi2GetDirectionalDerivative",
            Call::SetRealInputDerivatives => "fmi2SetRealInputDerivatives",
            Call::GetRealOutputDerivatives => "fmi2GetRealOutputDerivatives",
            Call::DoStep => "fmi2DoStep",
            Call::CancelStep => "fmi2CancelStep",
            Call::GetStatus => "fmi2GetStatus",
            Call::GetRealStatus => "fmi2GetRealStatus",
            Call::GetIntegerStatus => "fmi2GetIntegerStatus",
            Call::GetBooleanStatus => "fmi2GetBooleanStatus",
            Call::GetStringStatus => "fmi2GetStringStatus",
            Call::EnterEventMode => "fmi2EnterEventMode",
            Call::NewDiscreteStates => "fmi2NewDiscreteStates",
            Call::EnterContinuousTimeMode => "fmi2EnterContinuousTimeMode",
            Call::CompletedIntegratorStep => "fmi2CompletedIntegratorStep",
            Call::SetTime => "fmi2SetTime",
            Call::SetContinuousStates => "fmi2SetContinuousStates",
            Call::GetDerivatives => "fmi2GetDerivatives",
            Call::GetEventIndicators => "fmi2GetEventIndicators",
            Call::GetContinuousStates => "fmi2GetContinuousStates",
            Call::GetNominalsOfContinuousStates => "fmi2GetNominalsOfContinuousStates",
        }
    }

    /// The interface the call belongs to, `None` for the common functions.
    #[inline]
    pub fn interface(self) -> Option<Interface> {
        match self {
            Call::DoStep
            | Call::CancelStep
            | Call::GetStatus
            | Call::GetRealStatus
            | Call::GetIntegerStatus
            | Call::GetBooleanStatus
            | Call::GetStringStatus
            | Call::SetRealInputDerivatives
            | Call::GetRealOutputDerivatives => Some(Interface::CoSimulation),
            Call::EnterEventMode
            | Call::NewDiscreteStates
            | Call::EnterContinuousTimeMode
            | Call::CompletedIntegratorStep
            | Call::SetTime
            | Call::SetContinuousStates
            | Call::GetDerivatives
            | Call::GetEventIndicators
            | Call::GetContinuousStates
            | Call::GetNominalsOfContinuousStates => Some(Interface::ModelExchange),
            _ => None,
        }
    }

    /// The modes in which the call is legal (fmi2Instantiate and fmi2FreeInstance need no
    /// instance mode: always). The Model Exchange rows are the standard's table of section
    /// 3.2.3 (without its `error` state, which this FMU never enters).
    #[inline]
    pub fn allowed(self) -> Modes {
        match self {
            Call::Instantiate | Call::FreeInstance => Modes::of(&[
                Instantiated,
                InitializationMode,
                StepComplete,
                EventMode,
                ContinuousTimeMode,
                Terminated,
                Mode::Fatal,
            ]),
            Call::SetDebugLogging => LIVE,
            Call::SetupExperiment => Modes::of(&[Instantiated]),
            Call::EnterInitializationMode => Modes::of(&[Instantiated]),
            Call::ExitInitializationMode => Modes::of(&[InitializationMode]),
            Call::Terminate => Modes::of(&[StepComplete, EventMode, ContinuousTimeMode]),
            Call::Reset => LIVE,
            Call::GetReal => READABLE,
            Call::GetInteger => READABLE,
            Call::GetBoolean => READABLE,
            Call::GetString => READABLE,
            Call::SetReal => WRITABLE,
            Call::SetInteger => WRITABLE,
            Call::SetBoolean => WRITABLE,
            Call::SetString => WRITABLE,
            Call::GetFMUstate => LIVE,
            Call::SetFMUstate => LIVE,
            Call::FreeFMUstate => LIVE,
            Call::SerializedFMUstateSize => LIVE,
            Call::SerializeFMUstate => LIVE,
            Call::DeSerializeFMUstate => LIVE,
            Call::GetDirectionalDerivative => READABLE,
            Call::SetRealInputDerivatives => WRITABLE,
            Call::GetRealOutputDerivatives => STEPPED,
            Call::DoStep => Modes::of(&[StepComplete]),
            Call::CancelStep => NEVER,
            Call::GetStatus => STEPPED,
            Call::GetRealStatus => STEPPED,
            Call::GetIntegerStatus => STEPPED,
            Call::GetBooleanStatus => STEPPED,
            Call::GetStringStatus => STEPPED,
            Call::EnterEventMode => Modes::of(&[EventMode, ContinuousTimeMode]),
            Call::NewDiscreteStates => Modes::of(&[EventMode]),
            Call::EnterContinuousTimeMode => Modes::of(&[EventMode]),
            Call::CompletedIntegratorStep => Modes::of(&[ContinuousTimeMode]),
            Call::SetTime => Modes::of(&[EventMode, ContinuousTimeMode]),
            Call::SetContinuousStates => Modes::of(&[ContinuousTimeMode]),
            Call::GetDerivatives => Modes::of(&[EventMode, ContinuousTimeMode, Terminated]),
            Call::GetEventIndicators | Call::GetContinuousStates => STATES_READABLE,
            Call::GetNominalsOfContinuousStates => {
                Modes::of(&[Instantiated, EventMode, ContinuousTimeMode, Terminated])
            }
        }
    }
}

impl std::fmt::Display for Call {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
