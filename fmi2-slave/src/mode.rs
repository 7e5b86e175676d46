//! The FMI 2.0 Co-Simulation state machine (FMI 2.0.4, section 4.2.4): the modes an instance can
//! be in, and which modes allow which call, as bit masks (membership is one bit test).

use serde::{Deserialize, Serialize};

/// The states of the Co-Simulation state machine that this FMU can be in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mode {
    Instantiated,
    InitializationMode,
    StepComplete,
    Terminated,
    Fatal,
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
        }
    }
}

use Mode::{InitializationMode, Instantiated, StepComplete, Terminated};

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
pub const LIVE: Modes = Modes::of(&[Instantiated, InitializationMode, StepComplete, Terminated]);
/// Where values may be read (and directional derivatives taken).
pub const READABLE: Modes = Modes::of(&[InitializationMode, StepComplete, Terminated]);
/// Where values may be written (which ones: the variable's causality and variability decide).
pub const WRITABLE: Modes = Modes::of(&[Instantiated, InitializationMode, StepComplete]);
/// Where the step status may be inquired.
pub const STEPPED: Modes = Modes::of(&[StepComplete, Terminated]);
/// Nowhere.
pub const NEVER: Modes = Modes::of(&[]);

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
        }
    }

    /// The modes in which the call is legal (fmi2Instantiate and fmi2FreeInstance need no
    /// instance mode: always).
    pub fn allowed(self) -> Modes {
        match self {
            Call::Instantiate | Call::FreeInstance => {
                Modes::of(&[Instantiated, InitializationMode, StepComplete, Terminated, Mode::Fatal])
            }
            Call::SetDebugLogging => LIVE,
            Call::SetupExperiment => Modes::of(&[Instantiated]),
            Call::EnterInitializationMode => Modes::of(&[Instantiated]),
            Call::ExitInitializationMode => Modes::of(&[InitializationMode]),
            Call::Terminate => Modes::of(&[StepComplete]),
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
        }
    }
}

impl std::fmt::Display for Call {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
