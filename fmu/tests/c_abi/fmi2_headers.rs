//! The adapter's own FMI 2.0 C types (`src/fmi2.rs`) against the standard's headers (bindgen's
//! `fmi2*TYPE` from fmi-sys, a test-only dependency): every export's signature must coerce to
//! the header's function type, so a mismatch does not compile; the two exports with a struct in
//! their signature (fmi2Instantiate, fmi2NewDiscreteStates) are checked field by field.

use std::mem::{align_of, offset_of, size_of};

use fmi_sys::fmi2 as headers;
use headers::*;
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::fmi2 as own;

/// The size and alignment of the struct `$type` and the offset of each field, own against the
/// headers'.
macro_rules! same_layout {
    ($type:ident; $($field:ident),* $(,)?) => {
        assert_eq!(size_of::<own::$type>(), size_of::<headers::$type>());
        assert_eq!(align_of::<own::$type>(), align_of::<headers::$type>());
        $(assert_eq!(offset_of!(own::$type, $field), offset_of!(headers::$type, $field), stringify!($field));)*
    };
}

/// Every export but fmi2Instantiate and fmi2NewDiscreteStates, by its header type.
const _: () = {
    let _: fmi2GetTypesPlatformTYPE = Some(fmi2GetTypesPlatform);
    let _: fmi2GetVersionTYPE = Some(fmi2GetVersion);
    let _: fmi2SetDebugLoggingTYPE = Some(fmi2SetDebugLogging);
    let _: fmi2FreeInstanceTYPE = Some(fmi2FreeInstance);
    let _: fmi2SetupExperimentTYPE = Some(fmi2SetupExperiment);
    let _: fmi2EnterInitializationModeTYPE = Some(fmi2EnterInitializationMode);
    let _: fmi2ExitInitializationModeTYPE = Some(fmi2ExitInitializationMode);
    let _: fmi2TerminateTYPE = Some(fmi2Terminate);
    let _: fmi2ResetTYPE = Some(fmi2Reset);
    let _: fmi2GetRealTYPE = Some(fmi2GetReal);
    let _: fmi2GetIntegerTYPE = Some(fmi2GetInteger);
    let _: fmi2GetBooleanTYPE = Some(fmi2GetBoolean);
    let _: fmi2GetStringTYPE = Some(fmi2GetString);
    let _: fmi2SetRealTYPE = Some(fmi2SetReal);
    let _: fmi2SetIntegerTYPE = Some(fmi2SetInteger);
    let _: fmi2SetBooleanTYPE = Some(fmi2SetBoolean);
    let _: fmi2SetStringTYPE = Some(fmi2SetString);
    let _: fmi2GetFMUstateTYPE = Some(fmi2GetFMUstate);
    let _: fmi2SetFMUstateTYPE = Some(fmi2SetFMUstate);
    let _: fmi2FreeFMUstateTYPE = Some(fmi2FreeFMUstate);
    let _: fmi2SerializedFMUstateSizeTYPE = Some(fmi2SerializedFMUstateSize);
    let _: fmi2SerializeFMUstateTYPE = Some(fmi2SerializeFMUstate);
    let _: fmi2DeSerializeFMUstateTYPE = Some(fmi2DeSerializeFMUstate);
    let _: fmi2GetDirectionalDerivativeTYPE = Some(fmi2GetDirectionalDerivative);
    let _: fmi2SetRealInputDerivativesTYPE = Some(fmi2SetRealInputDerivatives);
    let _: fmi2GetRealOutputDerivativesTYPE = Some(fmi2GetRealOutputDerivatives);
    let _: fmi2DoStepTYPE = Some(fmi2DoStep);
    let _: fmi2CancelStepTYPE = Some(fmi2CancelStep);
    let _: fmi2GetStatusTYPE = Some(fmi2GetStatus);
    let _: fmi2GetRealStatusTYPE = Some(fmi2GetRealStatus);
    let _: fmi2GetIntegerStatusTYPE = Some(fmi2GetIntegerStatus);
    let _: fmi2GetBooleanStatusTYPE = Some(fmi2GetBooleanStatus);
    let _: fmi2GetStringStatusTYPE = Some(fmi2GetStringStatus);
    let _: fmi2EnterEventModeTYPE = Some(fmi2EnterEventMode);
    let _: fmi2EnterContinuousTimeModeTYPE = Some(fmi2EnterContinuousTimeMode);
    let _: fmi2CompletedIntegratorStepTYPE = Some(fmi2CompletedIntegratorStep);
    let _: fmi2SetTimeTYPE = Some(fmi2SetTime);
    let _: fmi2SetContinuousStatesTYPE = Some(fmi2SetContinuousStates);
    let _: fmi2GetDerivativesTYPE = Some(fmi2GetDerivatives);
    let _: fmi2GetEventIndicatorsTYPE = Some(fmi2GetEventIndicators);
    let _: fmi2GetContinuousStatesTYPE = Some(fmi2GetContinuousStates);
    let _: fmi2GetNominalsOfContinuousStatesTYPE = Some(fmi2GetNominalsOfContinuousStates);
};

#[test]
fn event_info_has_the_headers_layout_and_new_discrete_states_its_signature() {
    same_layout!(
        fmi2EventInfo;
        newDiscreteStatesNeeded,
        terminateSimulation,
        nominalsOfContinuousStatesChanged,
        valuesOfContinuousStatesChanged,
        nextEventTimeDefined,
        nextEventTime
    );
    let own = own::fmi2EventInfo::default();
    let _: headers::fmi2EventInfo = headers::fmi2EventInfo {
        newDiscreteStatesNeeded: own.newDiscreteStatesNeeded,
        terminateSimulation: own.terminateSimulation,
        nominalsOfContinuousStatesChanged: own.nominalsOfContinuousStatesChanged,
        valuesOfContinuousStatesChanged: own.valuesOfContinuousStatesChanged,
        nextEventTimeDefined: own.nextEventTimeDefined,
        nextEventTime: own.nextEventTime,
    };
    type OwnNewDiscreteStates =
        unsafe extern "C" fn(headers::fmi2Component, *mut own::fmi2EventInfo) -> headers::fmi2Status;
    let _: OwnNewDiscreteStates = fmi2NewDiscreteStates;
}

#[test]
fn callback_functions_have_the_headers_layout() {
    same_layout!(fmi2CallbackFunctions; logger, allocateMemory, freeMemory, stepFinished, componentEnvironment);
    // The field types, as the headers declare them.
    let own = own::fmi2CallbackFunctions {
        logger: None,
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: std::ptr::null_mut(),
    };
    let _: headers::fmi2CallbackFunctions = headers::fmi2CallbackFunctions {
        logger: own.logger,
        allocateMemory: own.allocateMemory,
        freeMemory: own.freeMemory,
        stepFinished: own.stepFinished,
        componentEnvironment: own.componentEnvironment,
    };
}

#[test]
fn instantiate_has_the_headers_signature_but_for_the_callback_struct() {
    type OwnInstantiate = unsafe extern "C" fn(
        headers::fmi2String,
        headers::fmi2Type,
        headers::fmi2String,
        headers::fmi2String,
        *const own::fmi2CallbackFunctions,
        headers::fmi2Boolean,
        headers::fmi2Boolean,
    ) -> headers::fmi2Component;
    let _: OwnInstantiate = fmi2Instantiate;
}

#[test]
fn status_and_kind_values_are_the_headers() {
    let pairs = [
        (own::fmi2Status_fmi2OK, fmi2Status_fmi2OK),
        (own::fmi2Status_fmi2Warning, fmi2Status_fmi2Warning),
        (own::fmi2Status_fmi2Discard, fmi2Status_fmi2Discard),
        (own::fmi2Status_fmi2Error, fmi2Status_fmi2Error),
        (own::fmi2Status_fmi2Fatal, fmi2Status_fmi2Fatal),
        (own::fmi2Status_fmi2Pending, fmi2Status_fmi2Pending),
        (own::fmi2Type_fmi2ModelExchange, fmi2Type_fmi2ModelExchange),
        (own::fmi2Type_fmi2CoSimulation, fmi2Type_fmi2CoSimulation),
        (own::fmi2StatusKind_fmi2DoStepStatus, fmi2StatusKind_fmi2DoStepStatus),
        (own::fmi2StatusKind_fmi2PendingStatus, fmi2StatusKind_fmi2PendingStatus),
        (own::fmi2StatusKind_fmi2LastSuccessfulTime, fmi2StatusKind_fmi2LastSuccessfulTime),
        (own::fmi2StatusKind_fmi2Terminated, fmi2StatusKind_fmi2Terminated),
    ];
    for (own, header) in pairs {
        assert_eq!(own, header);
    }
    assert_eq!((own::fmi2True as u32, own::fmi2False as u32), (fmi2True, fmi2False));
}
