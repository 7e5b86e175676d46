//! The C exports of the FMU: all 25 common and 9 Co-Simulation functions of FMI 2.0. The only
//! file of the crate with `unsafe`.
//!
//! Each export does exactly three things: check the pointers it got (NULL with n = 0 is legal,
//! NULL with n > 0 is an `fmi2Error`), turn them into slices and strings, and run the safe
//! [`Instance`] method inside [`Instance::guarded`], which catches panics (`fmi2Fatal`).
//!
//! Contract with the master (FMI 2.0): `c` is NULL or a pointer returned by [`fmi2Instantiate`]
//! and not yet given to [`fmi2FreeInstance`]; an `fmi2FMUstate` is NULL or one this FMU returned
//! (fmi2GetFMUstate, fmi2DeSerializeFMUstate) and not yet given to [`fmi2FreeFMUstate`]; array
//! pointers are valid for their n elements; strings are NUL-terminated. Calls on one instance are not concurrent; different instances may
//! run on different threads (there is no global mutable state).

// The FMI adapter's C boundary: the only module allowed `unsafe` (the crate denies it).
#![allow(unsafe_code)]
#![allow(non_snake_case, non_upper_case_globals, clippy::missing_safety_doc)]
#![deny(unsafe_op_in_unsafe_fn)]

use std::ffi::{c_char, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr::null_mut;

use crate::fmi2::*;

use crate::instance::{FmuState, Instance, InstantiateArguments, StatusKind, Unsupported, ValueType};
use crate::logging::{LogSink, Status};
use crate::mode::Call;

#[cfg(not(panic = "unwind"))]
compile_error!("the FMU must be built with panic = \"unwind\": every export turns a panic into fmi2Fatal");

const NULL_ARRAY: &str = "NULL array pointer with n > 0";

fn to_c(status: Status) -> fmi2Status {
    match status {
        Status::Ok => fmi2Status_fmi2OK,
        Status::Warning => fmi2Status_fmi2Warning,
        Status::Discard => fmi2Status_fmi2Discard,
        Status::Error => fmi2Status_fmi2Error,
        Status::Fatal => fmi2Status_fmi2Fatal,
    }
}

/// The master's logger, called as the standard asks: `"%s"` and the text, with the
/// environment pointer the master gave and a copy of the instance name.
struct CallbackLogger {
    logger: fmi2CallbackLogger,
    environment: fmi2ComponentEnvironment,
    instance_name: CString,
}

impl LogSink for CallbackLogger {
    fn log(&mut self, status: Status, category: &str, message: &str) {
        let Some(logger) = self.logger else { return };
        let (category, message) = (c_string(category), c_string(message));
        // SAFETY: the master gave this callback for this instance; every pointer passed is a
        // NUL-terminated string that outlives the call, and "%s" consumes exactly one of them.
        unsafe {
            logger(
                self.environment,
                self.instance_name.as_ptr(),
                to_c(status),
                category.as_ptr(),
                c"%s".as_ptr(),
                message.as_ptr(),
            )
        }
    }
}

/// A C copy of `text` (an interior NUL would cut it short, so it is spelled out).
fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', "\\0")).unwrap_or_default()
}

/// SAFETY: `text` is NULL or NUL-terminated.
unsafe fn string_argument<'a>(text: fmi2String) -> Option<std::borrow::Cow<'a, str>> {
    // SAFETY: by the caller's contract.
    (!text.is_null()).then(|| unsafe { CStr::from_ptr(text) }.to_string_lossy())
}

/// SAFETY: `pointer` is NULL or valid for `n` reads.
unsafe fn slice<'a, T>(pointer: *const T, n: usize) -> Option<&'a [T]> {
    match (n, pointer.is_null()) {
        (0, _) => Some(&[]),
        (_, true) => None,
        // SAFETY: by the caller's contract.
        _ => Some(unsafe { std::slice::from_raw_parts(pointer, n) }),
    }
}

/// SAFETY: `pointer` is NULL or valid for `n` writes.
unsafe fn slice_mut<'a, T>(pointer: *mut T, n: usize) -> Option<&'a mut [T]> {
    match (n, pointer.is_null()) {
        (0, _) => Some(&mut []),
        (_, true) => None,
        // SAFETY: by the caller's contract.
        _ => Some(unsafe { std::slice::from_raw_parts_mut(pointer, n) }),
    }
}

/// Runs `body` on the instance behind `c` (NULL: `fmi2Error`, nothing to log to).
/// SAFETY: `c` is NULL or a live instance from [`fmi2Instantiate`].
#[inline]
unsafe fn with_instance(c: fmi2Component, call: Call, body: impl FnOnce(&mut Instance) -> Status) -> fmi2Status {
    // SAFETY: by the caller's contract; the master does not call into one instance concurrently.
    match unsafe { c.cast::<Instance>().as_mut() } {
        Some(instance) => to_c(instance.guarded(call, body)),
        None => fmi2Status_fmi2Error,
    }
}

fn status_kind(kind: fmi2StatusKind) -> Option<StatusKind> {
    match kind {
        fmi2StatusKind_fmi2DoStepStatus => Some(StatusKind::DoStepStatus),
        fmi2StatusKind_fmi2PendingStatus => Some(StatusKind::PendingStatus),
        fmi2StatusKind_fmi2LastSuccessfulTime => Some(StatusKind::LastSuccessfulTime),
        fmi2StatusKind_fmi2Terminated => Some(StatusKind::Terminated),
        _ => None,
    }
}

/// Common checks of the fmi2GetXXXStatus functions: a known kind and a value pointer.
fn status_arguments<T>(
    instance: &mut Instance,
    call: Call,
    kind: fmi2StatusKind,
    value: *mut T,
) -> Result<StatusKind, Status> {
    match status_kind(kind) {
        _ if value.is_null() => Err(instance.invalid_argument(call, "value is NULL")),
        None => Err(instance.invalid_argument(call, &format!("unknown fmi2StatusKind {kind}"))),
        Some(kind) => Ok(kind),
    }
}

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    fmi2TypesPlatform.as_ptr().cast()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    fmi2Version.as_ptr().cast()
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    let instantiate = || {
        // SAFETY: `functions` is NULL or points to the master's callbacks (FMI 2.0 contract).
        let functions = unsafe { functions.as_ref() }?;
        // SAFETY: the strings are NULL or NUL-terminated (FMI 2.0 contract).
        let (name, guid, resources) =
            unsafe { (string_argument(instanceName), string_argument(fmuGUID), string_argument(fmuResourceLocation)) };
        let name = name.unwrap_or_default();
        let sink = CallbackLogger {
            logger: functions.logger,
            environment: functions.componentEnvironment,
            instance_name: c_string(&name),
        };
        let arguments = InstantiateArguments {
            instance_name: &name,
            co_simulation: fmuType == fmi2Type_fmi2CoSimulation,
            guid: guid.as_deref().unwrap_or(""),
            resource_location: resources.as_deref(),
            logging_on: loggingOn != 0,
        };
        Instance::instantiate(arguments, Box::new(sink))
    };
    match catch_unwind(instantiate) {
        Ok(Some(instance)) => Box::into_raw(Box::new(instance)).cast::<c_void>(),
        _ => null_mut(),
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if c.is_null() {
        return;
    }
    // SAFETY: `c` came from `fmi2Instantiate` (Box::into_raw) and is freed exactly once.
    let instance = unsafe { Box::from_raw(c.cast::<Instance>()) };
    // A panic while dropping must not unwind into C; the memory is released either way.
    let _ = catch_unwind(AssertUnwindSafe(move || drop(instance)));
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::SetDebugLogging;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| {
            let Some(pointers) = slice(categories, nCategories) else {
                return instance.invalid_argument(CALL, NULL_ARRAY);
            };
            let Some(names) = pointers.iter().map(|&p| string_argument(p)).collect::<Option<Vec<_>>>() else {
                return instance.invalid_argument(CALL, "a category is NULL");
            };
            let names: Vec<&str> = names.iter().map(|n| n.as_ref()).collect();
            instance.set_debug_logging(loggingOn != 0, &names)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    _toleranceDefined: fmi2Boolean,
    _tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    let stop_time = (stopTimeDefined != 0).then_some(stopTime);
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::SetupExperiment, |instance| instance.setup_experiment(startTime, stop_time)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::EnterInitializationMode, Instance::enter_initialization_mode) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::ExitInitializationMode, Instance::exit_initialization_mode) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::Terminate, Instance::terminate) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::Reset, Instance::reset) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    const CALL: Call = Call::GetReal;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => instance.get_real(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    const CALL: Call = Call::GetInteger;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => instance.get_integer(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::GetBoolean;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(_)) => instance.get_absent_type(CALL, ValueType::Boolean, vr),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::GetString;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => match instance.get_string(vr) {
                Ok(texts) => {
                    // The instance keeps the texts until its next fmi2GetString.
                    for (slot, text) in value.iter_mut().zip(texts) {
                        *slot = text.as_ptr();
                    }
                    Status::Ok
                }
                Err(status) => status,
            },
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    const CALL: Call = Call::SetReal;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => instance.set_real(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    const CALL: Call = Call::SetInteger;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => instance.set_integer(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::SetBoolean;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(_)) => instance.set_absent_type(CALL, ValueType::Boolean, vr),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::SetString;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => {
                // Copied now: the master's strings need not outlive the call.
                match value.iter().map(|&text| string_argument(text)).collect::<Option<Vec<_>>>() {
                    Some(texts) => instance.set_string(vr, &texts),
                    None => instance.invalid_argument(CALL, "a value is a NULL string"),
                }
            }
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

/// SAFETY: see the module's contract.
unsafe fn unsupported(c: fmi2Component, capability: Unsupported, call: Call) -> fmi2Status {
    // SAFETY: by the caller's contract.
    unsafe { with_instance(c, call, |instance| instance.unsupported(capability)) }
}

/// The FMU state behind an `fmi2FMUstate` the master got from this FMU (NULL: `None`).
/// SAFETY: `state` is NULL or from [`fmi2GetFMUstate`]/[`fmi2DeSerializeFMUstate`] and not freed.
unsafe fn fmu_state<'a>(state: fmi2FMUstate) -> Option<&'a mut FmuState> {
    // SAFETY: by the caller's contract.
    unsafe { state.cast::<FmuState>().as_mut() }
}

/// Stores `state` in `*slot`: into the FMU state already there (the standard lets the master
/// pass one back for reuse) or a new allocation.
/// SAFETY: `*slot` is NULL or an FMU state of this FMU that has not been freed.
unsafe fn store_fmu_state(slot: &mut fmi2FMUstate, state: FmuState) {
    // SAFETY: by the caller's contract.
    match unsafe { fmu_state(*slot) } {
        Some(existing) => *existing = state,
        None => *slot = Box::into_raw(Box::new(state)).cast(),
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::GetFMUstate;
    // SAFETY: see the module's contract; `FMUstate` is NULL or points to the master's slot.
    unsafe {
        with_instance(c, CALL, |instance| match FMUstate.as_mut() {
            None => instance.invalid_argument(CALL, "FMUstate is NULL"),
            Some(slot) => match instance.get_fmu_state() {
                Ok(state) => {
                    store_fmu_state(slot, state);
                    Status::Ok
                }
                Err(status) => status,
            },
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::SetFMUstate;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match fmu_state(FMUstate) {
            None => instance.invalid_argument(CALL, "FMUstate is NULL"),
            Some(state) => instance.set_fmu_state(state),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::FreeFMUstate;
    // SAFETY: see the module's contract; `*FMUstate` came from Box::into_raw in this file and is
    // released once: the slot is set to NULL.
    unsafe {
        with_instance(c, CALL, |instance| {
            let status = instance.free_fmu_state();
            if status == Status::Ok {
                if let Some(slot) = FMUstate.as_mut() {
                    if !slot.is_null() {
                        drop(Box::from_raw(slot.cast::<FmuState>()));
                        *slot = null_mut();
                    }
                }
            }
            status
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    const CALL: Call = Call::SerializedFMUstateSize;
    // SAFETY: see the module's contract; `size` is NULL or writable.
    unsafe {
        with_instance(c, CALL, |instance| match (fmu_state(FMUstate), size.as_mut()) {
            (Some(state), Some(size)) => match instance.serialized_fmu_state_size(state) {
                Ok(bytes) => {
                    *size = bytes;
                    Status::Ok
                }
                Err(status) => status,
            },
            _ => instance.invalid_argument(CALL, "FMUstate or size is NULL"),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    const CALL: Call = Call::SerializeFMUstate;
    // SAFETY: see the module's contract; `serializedState` is valid for `size` writes.
    unsafe {
        with_instance(c, CALL, |instance| match (fmu_state(FMUstate), slice_mut(serializedState.cast::<u8>(), size)) {
            (Some(state), Some(bytes)) => instance.serialize_fmu_state(state, bytes),
            (None, _) => instance.invalid_argument(CALL, "FMUstate is NULL"),
            (_, None) => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    const CALL: Call = Call::DeSerializeFMUstate;
    // SAFETY: see the module's contract; `serializedState` is valid for `size` reads, `FMUstate`
    // is NULL or points to the master's slot (NULL or an FMU state of this FMU).
    unsafe {
        with_instance(c, CALL, |instance| match (slice(serializedState.cast::<u8>(), size), FMUstate.as_mut()) {
            (Some(bytes), Some(slot)) => match instance.deserialize_fmu_state(bytes) {
                Ok(state) => {
                    store_fmu_state(slot, state);
                    Status::Ok
                }
                Err(status) => status,
            },
            (None, _) => instance.invalid_argument(CALL, NULL_ARRAY),
            (_, None) => instance.invalid_argument(CALL, "FMUstate is NULL"),
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    vUnknown_ref: *const fmi2ValueReference,
    nUnknown: usize,
    vKnown_ref: *const fmi2ValueReference,
    nKnown: usize,
    dvKnown: *const fmi2Real,
    dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    const CALL: Call = Call::GetDirectionalDerivative;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| {
            let unknowns = (slice(vUnknown_ref, nUnknown), slice_mut(dvUnknown, nUnknown));
            let knowns = (slice(vKnown_ref, nKnown), slice(dvKnown, nKnown));
            match (unknowns, knowns) {
                ((Some(unknowns), Some(rates)), (Some(knowns), Some(known_rates))) => {
                    instance.get_directional_derivative(unknowns, knowns, known_rates, rates)
                }
                _ => instance.invalid_argument(CALL, NULL_ARRAY),
            }
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *const fmi2Real,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { unsupported(c, Unsupported::RealInputDerivatives, Call::SetRealInputDerivatives) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { unsupported(c, Unsupported::RealOutputDerivatives, Call::GetRealOutputDerivatives) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, Call::DoStep, |instance| instance.do_step(currentCommunicationPoint, communicationStepSize))
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::CancelStep, Instance::cancel_step) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status {
    const CALL: Call = Call::GetStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_status(kind),
            Err(status) => status,
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status {
    const CALL: Call = Call::GetRealStatus;
    // SAFETY: see the module's contract; `value` was checked for NULL.
    unsafe {
        with_instance(c, CALL, |instance| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => match instance.get_real_status(kind) {
                Ok(time) => {
                    *value = time;
                    Status::Ok
                }
                Err(status) => status,
            },
            Err(status) => status,
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Integer,
) -> fmi2Status {
    const CALL: Call = Call::GetIntegerStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_integer_status(kind),
            Err(status) => status,
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::GetBooleanStatus;
    // SAFETY: see the module's contract; `value` was checked for NULL.
    unsafe {
        with_instance(c, CALL, |instance| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => match instance.get_boolean_status(kind) {
                Ok(flag) => {
                    *value = fmi2Boolean::from(flag);
                    Status::Ok
                }
                Err(status) => status,
            },
            Err(status) => status,
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::GetStringStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_string_status(kind),
            Err(status) => status,
        })
    }
}

#[cfg(test)]
mod tests {
    //! The exports themselves, called in-process as a master would.
    use super::*;
    use crate::instance::PANIC_CATEGORY_FOR_TESTS;
    use crate::model_description::{value_reference as vr, GUID};
    use std::cell::RefCell;

    /// (status, category, format, message) of every logger call.
    type Messages = RefCell<Vec<(fmi2Status, String, String, String)>>;

    /// A logger for the tests. Stable Rust cannot define a C-variadic function, so it takes the
    /// one argument that `"%s"` announces as a named parameter; on the platforms the FMU is
    /// built for (x86-64 System V, AArch64 Linux) a variadic pointer argument is passed exactly
    /// like a named one, which is also how fmpy's ctypes logger receives it.
    extern "C" fn record(
        environment: fmi2ComponentEnvironment,
        _instance_name: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        format: fmi2String,
        text: fmi2String,
    ) {
        // SAFETY: the tests pass a `Messages` as environment; the strings are the FMU's C strings.
        unsafe {
            let messages = &*environment.cast::<Messages>();
            let string = |p: fmi2String| CStr::from_ptr(p).to_string_lossy().into_owned();
            messages.borrow_mut().push((status, string(category), string(format), string(text)));
        }
    }

    fn callbacks(messages: &Messages) -> fmi2CallbackFunctions {
        type Named =
            extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, fmi2String);
        type Variadic =
            unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
        // SAFETY: see `record`.
        let logger = unsafe { std::mem::transmute::<Named, Variadic>(record) };
        fmi2CallbackFunctions {
            logger: Some(logger),
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: (messages as *const Messages).cast_mut().cast(),
        }
    }

    fn instantiate(name: &std::ffi::CStr, guid: &std::ffi::CStr, functions: &fmi2CallbackFunctions) -> fmi2Component {
        // SAFETY: valid strings and callbacks.
        unsafe { fmi2Instantiate(name.as_ptr(), fmi2Type_fmi2CoSimulation, guid.as_ptr(), null_mut(), functions, 0, 0) }
    }

    fn guid() -> CString {
        CString::new(GUID).unwrap()
    }

    /// Instantiated and initialised, in step mode.
    fn stepping(functions: &fmi2CallbackFunctions) -> fmi2Component {
        let c = instantiate(c"wheel", &guid(), functions);
        assert!(!c.is_null());
        // SAFETY: `c` is live.
        unsafe {
            assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), fmi2Status_fmi2OK);
            assert_eq!(fmi2EnterInitializationMode(c), fmi2Status_fmi2OK);
            assert_eq!(fmi2ExitInitializationMode(c), fmi2Status_fmi2OK);
        }
        c
    }

    fn force_longitudinal(c: fmi2Component) -> f64 {
        let mut value = f64::NAN;
        // SAFETY: `c` is live; one reference, one value.
        assert_eq!(unsafe { fmi2GetReal(c, &vr::FORCE_LONGITUDINAL, 1, &mut value) }, fmi2Status_fmi2OK);
        value
    }

    #[test]
    fn version_and_platform() {
        // SAFETY: static NUL-terminated strings.
        unsafe {
            assert_eq!(CStr::from_ptr(fmi2GetVersion()), c"2.0");
            assert_eq!(CStr::from_ptr(fmi2GetTypesPlatform()), c"default");
        }
    }

    #[test]
    fn guid_mismatch_and_missing_callbacks_give_null() {
        let messages = Messages::default();
        assert!(instantiate(c"wheel", c"{00000000-0000-0000-0000-000000000000}", &callbacks(&messages)).is_null());
        let (status, category, format, message) = messages.borrow()[0].clone();
        assert_eq!((status, category.as_str(), format.as_str()), (fmi2Status_fmi2Error, "logStatusError", "%s"));
        assert!(message.contains("does not match this FMU's GUID"), "{message}");
        // SAFETY: NULL callbacks and strings are what is being tested.
        unsafe {
            let no_functions = null_mut();
            assert!(fmi2Instantiate(c"w".as_ptr(), 1, guid().as_ptr(), null_mut(), no_functions, 0, 0).is_null());
            let functions = callbacks(&messages);
            assert!(fmi2Instantiate(null_mut(), 1, guid().as_ptr(), null_mut(), &functions, 0, 0).is_null());
            assert!(fmi2Instantiate(c"w".as_ptr(), 1, null_mut(), null_mut(), &functions, 0, 0).is_null());
        }
    }

    #[test]
    fn pointers_are_checked() {
        let messages = Messages::default();
        let c = stepping(&callbacks(&messages));
        // SAFETY: NULL pointers are what is being tested; n = 0 makes them legal.
        unsafe {
            assert_eq!(fmi2GetReal(null_mut(), &vr::FORCE_LATERAL, 1, &mut 0.0), fmi2Status_fmi2Error);
            assert_eq!(fmi2DoStep(null_mut(), 0.0, 1.0, 0), fmi2Status_fmi2Error);
            fmi2FreeInstance(null_mut());
            assert_eq!(fmi2SetReal(c, std::ptr::null(), 0, std::ptr::null()), fmi2Status_fmi2OK);
            assert_eq!(fmi2GetReal(c, std::ptr::null(), 0, null_mut()), fmi2Status_fmi2OK);
            assert_eq!(fmi2GetString(c, std::ptr::null(), 0, null_mut()), fmi2Status_fmi2OK);
            assert_eq!(fmi2SetDebugLogging(c, 1, 0, std::ptr::null()), fmi2Status_fmi2OK);
            assert_eq!(fmi2SetReal(c, &vr::NORMAL_FORCE, 1, std::ptr::null()), fmi2Status_fmi2Error);
            assert_eq!(messages.borrow().last().unwrap().3, "fmi2SetReal: NULL array pointer with n > 0");
            assert_eq!(fmi2GetRealStatus(c, fmi2StatusKind_fmi2LastSuccessfulTime, null_mut()), fmi2Status_fmi2Error);
            assert_eq!(fmi2GetStatus(c, 17, &mut 0), fmi2Status_fmi2Error);
            assert_eq!(messages.borrow().last().unwrap().3, "fmi2GetStatus: unknown fmi2StatusKind 17");
            fmi2FreeInstance(c);
        }
    }

    #[test]
    fn status_functions_through_the_exports() {
        let messages = Messages::default();
        let c = stepping(&callbacks(&messages));
        // SAFETY: `c` is live; the value pointers are valid.
        unsafe {
            assert_eq!(fmi2DoStep(c, 0.0, 0.5, 1), fmi2Status_fmi2OK);
            let mut time = 0.0;
            assert_eq!(fmi2GetRealStatus(c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut time), fmi2Status_fmi2OK);
            assert_eq!(time, 0.5);
            let mut terminated = 7;
            assert_eq!(fmi2GetBooleanStatus(c, fmi2StatusKind_fmi2Terminated, &mut terminated), fmi2Status_fmi2OK);
            assert_eq!(terminated, 0);
            let mut status = 7;
            assert_eq!(fmi2GetStatus(c, fmi2StatusKind_fmi2DoStepStatus, &mut status), fmi2Status_fmi2Discard);
            let mut text: fmi2String = std::ptr::null();
            assert_eq!(fmi2GetStringStatus(c, fmi2StatusKind_fmi2PendingStatus, &mut text), fmi2Status_fmi2Discard);
            assert_eq!(fmi2CancelStep(c), fmi2Status_fmi2Error);
            assert_eq!(messages.borrow().last().unwrap().3, "fmi2CancelStep: illegal call in state stepComplete");
            fmi2FreeInstance(c);
        }
    }

    #[test]
    fn instances_are_independent() {
        let (first_log, second_log) = (Messages::default(), Messages::default());
        let (first_callbacks, second_callbacks) = (callbacks(&first_log), callbacks(&second_log));
        let first = stepping(&first_callbacks);
        let second = stepping(&second_callbacks);
        let start = force_longitudinal(first);
        // SAFETY: both instances are live.
        unsafe {
            assert_eq!(fmi2SetReal(second, &vr::CREEPAGE_LONGITUDINAL, 1, &-1e-3), fmi2Status_fmi2OK);
            assert_eq!(fmi2SetReal(second, &vr::SEMI_AXIS_B, 1, &f64::NAN), fmi2Status_fmi2OK);
            assert_eq!(fmi2DoStep(second, 0.0, 1.0, 0), fmi2Status_fmi2Error);
            assert_eq!(fmi2DoStep(first, 0.0, 1.0, 0), fmi2Status_fmi2OK);
            assert_eq!(fmi2SetReal(second, &vr::SEMI_AXIS_B, 1, &5.4e-3), fmi2Status_fmi2OK);
            assert_eq!(fmi2DoStep(second, 0.0, 1.0, 0), fmi2Status_fmi2OK);
        }
        assert_eq!(force_longitudinal(first), start);
        assert_eq!(force_longitudinal(second), -start);
        assert!(first_log.borrow().is_empty());
        assert_eq!(second_log.borrow()[0].3, "fmi2DoStep: semi_axis_b = NaN is invalid: must be finite and > 0");
        // SAFETY: freed once each.
        unsafe {
            fmi2FreeInstance(first);
            fmi2FreeInstance(second);
        }
    }

    /// A panic inside an export (forced by the test-only log category) is caught at the C
    /// boundary: fmi2Fatal, a fatal message through the master's logger, and the instance
    /// refuses further calls but can be freed.
    #[test]
    fn a_panic_in_an_export_becomes_fmi2_fatal() {
        let messages = Messages::default();
        let c = stepping(&callbacks(&messages));
        let category = CString::new(PANIC_CATEGORY_FOR_TESTS).unwrap();
        // SAFETY: `c` is live; one category string.
        unsafe {
            assert_eq!(fmi2SetDebugLogging(c, 1, 1, &category.as_ptr()), fmi2Status_fmi2Fatal);
            let (status, log_category, format, message) = messages.borrow().last().cloned().unwrap();
            assert_eq!(
                (status, log_category.as_str(), format.as_str()),
                (fmi2Status_fmi2Fatal, "logStatusFatal", "%s")
            );
            assert!(message.starts_with("fmi2SetDebugLogging: internal error (forced by a test"), "{message}");
            assert_eq!(fmi2DoStep(c, 0.0, 1.0, 0), fmi2Status_fmi2Error);
            assert_eq!(messages.borrow().last().unwrap().3, "fmi2DoStep: illegal call in state fatal");
            fmi2FreeInstance(c);
        }
    }
}
