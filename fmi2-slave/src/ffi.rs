//! The 25 common, 9 Co-Simulation and 10 Model Exchange functions of FMI 2.0, generic over the [`Slave`] that
//! implements them, and [`export_fmi2!`](crate::export_fmi2), which expands to one cdylib's
//! `#[no_mangle] extern "C"` exports calling them. The only file of the crate with `unsafe`.
//!
//! Each function does exactly three things: check the pointers it got (NULL with n = 0 is legal,
//! NULL with n > 0 is an `fmi2Error`), turn them into slices and strings, and run the safe
//! [`Slave`] method inside [`Slave::guarded`], which catches panics (`fmi2Fatal`).
//!
//! Contract with the master (FMI 2.0): `c` is NULL or a pointer returned by [`instantiate`] for
//! the same slave type and not yet given to [`free_instance`]; an `fmi2FMUstate` is NULL or one
//! this FMU returned (fmi2GetFMUstate, fmi2DeSerializeFMUstate) and not yet given to
//! [`free_fmu_state`]; array pointers are valid for their n elements; strings are
//! NUL-terminated. Calls on one instance are not concurrent; different instances may run on
//! different threads (there is no global mutable state).

// The C boundary: the only module of the crate allowed `unsafe` (the crate denies it).
#![allow(unsafe_code)]
#![allow(non_snake_case, non_upper_case_globals, clippy::missing_safety_doc)]
#![deny(unsafe_op_in_unsafe_fn)]

use std::borrow::Cow;
use std::ffi::{c_char, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr::null_mut;

use crate::fmi2::*;
use crate::logging::{LogSink, Status};
use crate::mode::{Call, Interface};
use crate::{InstantiateArguments, Slave, StatusKind, Unsupported};

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
unsafe fn string_argument<'a>(text: fmi2String) -> Option<Cow<'a, str>> {
    // SAFETY: by the caller's contract.
    (!text.is_null()).then(|| unsafe { CStr::from_ptr(text) }.to_string_lossy())
}

/// A string argument that must be UTF-8: the text, or why not (NULL, or the position of its
/// first byte that is not UTF-8, with the bytes around it escaped).
/// SAFETY: `text` is NULL or NUL-terminated.
unsafe fn utf8_argument<'a>(text: fmi2String) -> Result<Cow<'a, str>, String> {
    if text.is_null() {
        return Err("a value is a NULL string".to_owned());
    }
    // SAFETY: by the caller's contract.
    let bytes = unsafe { CStr::from_ptr(text) }.to_bytes();
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(Cow::Borrowed(text)),
        Err(error) => {
            let at = error.valid_up_to();
            let around = &bytes[at.saturating_sub(16)..(at + 16).min(bytes.len())];
            Err(format!(
                "a value is not UTF-8 (byte {at} of {}, near \"{}\"): FMI 2.0 strings are UTF-8, so a file name \
                 must be passed in UTF-8",
                bytes.len(),
                around.escape_ascii()
            ))
        }
    }
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
/// SAFETY: `c` is NULL or a live instance of `S` from [`instantiate`].
#[inline]
unsafe fn with_instance<S: Slave>(c: fmi2Component, call: Call, body: impl FnOnce(&mut S) -> Status) -> fmi2Status {
    // SAFETY: by the caller's contract; the master does not call into one instance concurrently.
    match unsafe { c.cast::<S>().as_mut() } {
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
fn status_arguments<S: Slave, T>(
    instance: &mut S,
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

pub fn get_types_platform() -> *const c_char {
    fmi2TypesPlatform.as_ptr().cast()
}

pub fn get_version() -> *const c_char {
    fmi2Version.as_ptr().cast()
}

pub unsafe fn instantiate<S: Slave>(
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
            interface: match fmuType {
                fmi2Type_fmi2CoSimulation => Ok(Interface::CoSimulation),
                fmi2Type_fmi2ModelExchange => Ok(Interface::ModelExchange),
                other => Err(other),
            },
            guid: guid.as_deref().unwrap_or(""),
            resource_location: resources.as_deref(),
            logging_on: loggingOn != 0,
        };
        S::instantiate(arguments, Box::new(sink))
    };
    match catch_unwind(instantiate) {
        Ok(Some(instance)) => Box::into_raw(Box::new(instance)).cast::<c_void>(),
        _ => null_mut(),
    }
}

pub unsafe fn free_instance<S: Slave>(c: fmi2Component) {
    if c.is_null() {
        return;
    }
    // SAFETY: `c` came from `instantiate::<S>` (Box::into_raw) and is freed exactly once.
    let instance = unsafe { Box::from_raw(c.cast::<S>()) };
    // A panic while dropping must not unwind into C; the memory is released either way.
    let _ = catch_unwind(AssertUnwindSafe(move || drop(instance)));
}

pub unsafe fn set_debug_logging<S: Slave>(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::SetDebugLogging;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
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

pub unsafe fn setup_experiment<S: Slave>(
    c: fmi2Component,
    _toleranceDefined: fmi2Boolean,
    _tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    let stop_time = (stopTimeDefined != 0).then_some(stopTime);
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, Call::SetupExperiment, |instance: &mut S| instance.setup_experiment(startTime, stop_time))
    }
}

pub unsafe fn enter_initialization_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::EnterInitializationMode, S::enter_initialization_mode) }
}

pub unsafe fn exit_initialization_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::ExitInitializationMode, S::exit_initialization_mode) }
}

pub unsafe fn terminate<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::Terminate, S::terminate) }
}

pub unsafe fn reset<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::Reset, S::reset) }
}

pub unsafe fn get_real<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    const CALL: Call = Call::GetReal;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => instance.get_real(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn get_integer<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    const CALL: Call = Call::GetInteger;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => instance.get_integer(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn get_boolean<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::GetBoolean;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice_mut(value, nvr)) {
            (Some(vr), Some(value)) => instance.get_boolean(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn get_string<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::GetString;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice_mut(value, nvr)) {
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

pub unsafe fn set_real<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    const CALL: Call = Call::SetReal;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => instance.set_real(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn set_integer<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    const CALL: Call = Call::SetInteger;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => instance.set_integer(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn set_boolean<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::SetBoolean;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => instance.set_boolean(vr, value),
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

pub unsafe fn set_string<S: Slave>(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    const CALL: Call = Call::SetString;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (slice(vr, nvr), slice(value, nvr)) {
            (Some(vr), Some(value)) => {
                // Copied now: the master's strings need not outlive the call. FMI 2.0 strings
                // are UTF-8 (as the model description's XML); one that is not is refused whole
                // rather than converted lossily, which would change a file name's bytes (the
                // file then could not be opened, and fmi2GetString would return other bytes).
                match value.iter().map(|&text| utf8_argument(text)).collect::<Result<Vec<_>, _>>() {
                    Ok(texts) => instance.set_string(vr, &texts),
                    Err(reason) => instance.invalid_argument(CALL, &reason),
                }
            }
            _ => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

/// The FMU state behind an `fmi2FMUstate` the master got from this FMU (NULL: `None`).
/// SAFETY: `state` is NULL or from [`get_fmu_state`]/[`deserialize_fmu_state`] for the same
/// slave type and not freed.
unsafe fn fmu_state<'a, S: Slave>(state: fmi2FMUstate) -> Option<&'a mut S::FmuState> {
    // SAFETY: by the caller's contract.
    unsafe { state.cast::<S::FmuState>().as_mut() }
}

/// Stores `state` in `*slot`: into the FMU state already there (the standard lets the master
/// pass one back for reuse) or a new allocation.
/// SAFETY: `*slot` is NULL or an FMU state of this FMU that has not been freed.
unsafe fn store_fmu_state<S: Slave>(slot: &mut fmi2FMUstate, state: S::FmuState) {
    // SAFETY: by the caller's contract.
    match unsafe { fmu_state::<S>(*slot) } {
        Some(existing) => *existing = state,
        None => *slot = Box::into_raw(Box::new(state)).cast(),
    }
}

pub unsafe fn get_fmu_state<S: Slave>(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::GetFMUstate;
    // SAFETY: see the module's contract; `FMUstate` is NULL or points to the master's slot.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match FMUstate.as_mut() {
            None => instance.invalid_argument(CALL, "FMUstate is NULL"),
            Some(slot) => match instance.get_fmu_state() {
                Ok(state) => {
                    store_fmu_state::<S>(slot, state);
                    Status::Ok
                }
                Err(status) => status,
            },
        })
    }
}

pub unsafe fn set_fmu_state<S: Slave>(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::SetFMUstate;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match fmu_state::<S>(FMUstate) {
            None => instance.invalid_argument(CALL, "FMUstate is NULL"),
            Some(state) => instance.set_fmu_state(state),
        })
    }
}

pub unsafe fn free_fmu_state<S: Slave>(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status {
    const CALL: Call = Call::FreeFMUstate;
    // SAFETY: see the module's contract; `*FMUstate` came from Box::into_raw in this file and is
    // released once: the slot is set to NULL.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
            let status = instance.free_fmu_state();
            if status == Status::Ok {
                if let Some(slot) = FMUstate.as_mut() {
                    if !slot.is_null() {
                        drop(Box::from_raw(slot.cast::<S::FmuState>()));
                        *slot = null_mut();
                    }
                }
            }
            status
        })
    }
}

pub unsafe fn serialized_fmu_state_size<S: Slave>(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    const CALL: Call = Call::SerializedFMUstateSize;
    // SAFETY: see the module's contract; `size` is NULL or writable.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match (fmu_state::<S>(FMUstate), size.as_mut()) {
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

pub unsafe fn serialize_fmu_state<S: Slave>(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    const CALL: Call = Call::SerializeFMUstate;
    // SAFETY: see the module's contract; `serializedState` is valid for `size` writes.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
            match (fmu_state::<S>(FMUstate), slice_mut(serializedState.cast::<u8>(), size)) {
                (Some(state), Some(bytes)) => instance.serialize_fmu_state(state, bytes),
                (None, _) => instance.invalid_argument(CALL, "FMUstate is NULL"),
                (_, None) => instance.invalid_argument(CALL, NULL_ARRAY),
            }
        })
    }
}

pub unsafe fn deserialize_fmu_state<S: Slave>(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    const CALL: Call = Call::DeSerializeFMUstate;
    // SAFETY: see the module's contract; `serializedState` is valid for `size` reads, `FMUstate`
    // is NULL or points to the master's slot (NULL or an FMU state of this FMU).
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
            match (slice(serializedState.cast::<u8>(), size), FMUstate.as_mut()) {
                (Some(bytes), Some(slot)) => match instance.deserialize_fmu_state(bytes) {
                    Ok(state) => {
                        store_fmu_state::<S>(slot, state);
                        Status::Ok
                    }
                    Err(status) => status,
                },
                (None, _) => instance.invalid_argument(CALL, NULL_ARRAY),
                (_, None) => instance.invalid_argument(CALL, "FMUstate is NULL"),
            }
        })
    }
}

pub unsafe fn get_directional_derivative<S: Slave>(
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
        with_instance(c, CALL, |instance: &mut S| {
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

/// fmi2SetRealInputDerivatives and fmi2GetRealOutputDerivatives: declared unsupported.
pub unsafe fn unsupported<S: Slave>(c: fmi2Component, capability: Unsupported) -> fmi2Status {
    let (call, _) = capability.describe();
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, call, |instance: &mut S| instance.unsupported(capability)) }
}

pub unsafe fn do_step<S: Slave>(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, Call::DoStep, |instance: &mut S| {
            instance.do_step(currentCommunicationPoint, communicationStepSize)
        })
    }
}

pub unsafe fn cancel_step<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::CancelStep, S::cancel_step) }
}

pub unsafe fn get_status<S: Slave>(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status {
    const CALL: Call = Call::GetStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_status(kind),
            Err(status) => status,
        })
    }
}

pub unsafe fn get_real_status<S: Slave>(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status {
    const CALL: Call = Call::GetRealStatus;
    // SAFETY: see the module's contract; `value` was checked for NULL.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match status_arguments(instance, CALL, s, value) {
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

pub unsafe fn get_integer_status<S: Slave>(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status {
    const CALL: Call = Call::GetIntegerStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_integer_status(kind),
            Err(status) => status,
        })
    }
}

pub unsafe fn get_boolean_status<S: Slave>(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status {
    const CALL: Call = Call::GetBooleanStatus;
    // SAFETY: see the module's contract; `value` was checked for NULL.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match status_arguments(instance, CALL, s, value) {
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

pub unsafe fn get_string_status<S: Slave>(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status {
    const CALL: Call = Call::GetStringStatus;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match status_arguments(instance, CALL, s, value) {
            Ok(kind) => instance.get_string_status(kind),
            Err(status) => status,
        })
    }
}

pub unsafe fn enter_event_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::EnterEventMode, S::enter_event_mode) }
}

pub unsafe fn new_discrete_states<S: Slave>(c: fmi2Component, fmi2eventInfo: *mut fmi2EventInfo) -> fmi2Status {
    const CALL: Call = Call::NewDiscreteStates;
    // SAFETY: see the module's contract; `fmi2eventInfo` is checked for NULL before the write.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
            let Some(out) = fmi2eventInfo.as_mut() else {
                return instance.invalid_argument(CALL, "fmi2eventInfo is NULL");
            };
            match instance.new_discrete_states() {
                Ok(info) => {
                    *out = fmi2EventInfo {
                        newDiscreteStatesNeeded: info.new_discrete_states_needed.into(),
                        terminateSimulation: info.terminate_simulation.into(),
                        nominalsOfContinuousStatesChanged: info.nominals_of_continuous_states_changed.into(),
                        valuesOfContinuousStatesChanged: info.values_of_continuous_states_changed.into(),
                        nextEventTimeDefined: info.next_event_time.is_some().into(),
                        nextEventTime: info.next_event_time.unwrap_or(0.0),
                    };
                    Status::Ok
                }
                Err(status) => status,
            }
        })
    }
}

pub unsafe fn enter_continuous_time_mode<S: Slave>(c: fmi2Component) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::EnterContinuousTimeMode, S::enter_continuous_time_mode) }
}

pub unsafe fn completed_integrator_step<S: Slave>(
    c: fmi2Component,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
    enterEventMode: *mut fmi2Boolean,
    terminateSimulation: *mut fmi2Boolean,
) -> fmi2Status {
    const CALL: Call = Call::CompletedIntegratorStep;
    // SAFETY: see the module's contract; both flags are checked for NULL before the writes.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| {
            if enterEventMode.is_null() || terminateSimulation.is_null() {
                return instance.invalid_argument(CALL, "enterEventMode or terminateSimulation is NULL");
            }
            match instance.completed_integrator_step() {
                Ok((enter, terminate)) => {
                    *enterEventMode = enter.into();
                    *terminateSimulation = terminate.into();
                    Status::Ok
                }
                Err(status) => status,
            }
        })
    }
}

pub unsafe fn set_time<S: Slave>(c: fmi2Component, time: fmi2Real) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { with_instance(c, Call::SetTime, |instance: &mut S| instance.set_time(time)) }
}

pub unsafe fn set_continuous_states<S: Slave>(c: fmi2Component, x: *const fmi2Real, nx: usize) -> fmi2Status {
    const CALL: Call = Call::SetContinuousStates;
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, CALL, |instance: &mut S| match slice(x, nx) {
            Some(states) => instance.set_continuous_states(states),
            None => instance.invalid_argument(CALL, NULL_ARRAY),
        })
    }
}

/// The four Model Exchange functions that fill an array of the master's.
/// SAFETY: see the module's contract.
unsafe fn fill<S: Slave>(
    c: fmi2Component,
    call: Call,
    values: *mut fmi2Real,
    n: usize,
    body: impl FnOnce(&mut S, &mut [f64]) -> Status,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe {
        with_instance(c, call, |instance: &mut S| match slice_mut(values, n) {
            Some(values) => body(instance, values),
            None => instance.invalid_argument(call, NULL_ARRAY),
        })
    }
}

pub unsafe fn get_derivatives<S: Slave>(c: fmi2Component, derivatives: *mut fmi2Real, nx: usize) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { fill(c, Call::GetDerivatives, derivatives, nx, S::get_derivatives) }
}

pub unsafe fn get_event_indicators<S: Slave>(
    c: fmi2Component,
    eventIndicators: *mut fmi2Real,
    ni: usize,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { fill(c, Call::GetEventIndicators, eventIndicators, ni, S::get_event_indicators) }
}

pub unsafe fn get_continuous_states<S: Slave>(c: fmi2Component, x: *mut fmi2Real, nx: usize) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { fill(c, Call::GetContinuousStates, x, nx, S::get_continuous_states) }
}

pub unsafe fn get_nominals_of_continuous_states<S: Slave>(
    c: fmi2Component,
    x_nominal: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    // SAFETY: see the module's contract.
    unsafe { fill(c, Call::GetNominalsOfContinuousStates, x_nominal, nx, S::get_nominals_of_continuous_states) }
}

/// Expands to the 44 `#[no_mangle] extern "C"` functions of FMI 2.0 (25 common, 9
/// Co-Simulation, 10 Model Exchange) for the [`Slave`] type given, each forwarding its arguments to its generic
/// twin in this module. Invoke it once per cdylib, in a module that allows `unsafe_code` (the
/// expansion declares `unsafe extern "C"` functions and `#[no_mangle]`), with a path that
/// resolves from a child module (e.g. `crate::instance::Instance`): the functions are defined in
/// a hidden child module `fmi2_exports` and re-exported from the invoking one. Requires
/// `panic = "unwind"`: every export turns a panic into `fmi2Fatal`.
#[macro_export]
macro_rules! export_fmi2 {
    ($slave:ty) => {
        #[cfg(not(panic = "unwind"))]
        compile_error!("the FMU must be built with panic = \"unwind\": every export turns a panic into fmi2Fatal");

        pub use fmi2_exports::*;

        #[doc(hidden)]
        #[allow(non_snake_case)]
        pub mod fmi2_exports {
            use $crate::fmi2::*;

            $crate::export_fmi2! { @forward $slave,
                fn fmi2Instantiate(instanceName: fmi2String, fmuType: fmi2Type, fmuGUID: fmi2String,
                    fmuResourceLocation: fmi2String, functions: *const fmi2CallbackFunctions,
                    visible: fmi2Boolean, loggingOn: fmi2Boolean) -> fmi2Component = instantiate;
                fn fmi2FreeInstance(c: fmi2Component) -> () = free_instance;
                fn fmi2SetDebugLogging(c: fmi2Component, loggingOn: fmi2Boolean, nCategories: usize,
                    categories: *const fmi2String) -> fmi2Status = set_debug_logging;
                fn fmi2SetupExperiment(c: fmi2Component, toleranceDefined: fmi2Boolean, tolerance: fmi2Real,
                    startTime: fmi2Real, stopTimeDefined: fmi2Boolean, stopTime: fmi2Real) -> fmi2Status
                    = setup_experiment;
                fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status = enter_initialization_mode;
                fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status = exit_initialization_mode;
                fn fmi2Terminate(c: fmi2Component) -> fmi2Status = terminate;
                fn fmi2Reset(c: fmi2Component) -> fmi2Status = reset;
                fn fmi2GetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *mut fmi2Real) -> fmi2Status = get_real;
                fn fmi2GetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *mut fmi2Integer) -> fmi2Status = get_integer;
                fn fmi2GetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *mut fmi2Boolean) -> fmi2Status = get_boolean;
                fn fmi2GetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *mut fmi2String) -> fmi2Status = get_string;
                fn fmi2SetReal(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *const fmi2Real) -> fmi2Status = set_real;
                fn fmi2SetInteger(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *const fmi2Integer) -> fmi2Status = set_integer;
                fn fmi2SetBoolean(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *const fmi2Boolean) -> fmi2Status = set_boolean;
                fn fmi2SetString(c: fmi2Component, vr: *const fmi2ValueReference, nvr: usize,
                    value: *const fmi2String) -> fmi2Status = set_string;
                fn fmi2GetFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status = get_fmu_state;
                fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status = set_fmu_state;
                fn fmi2FreeFMUstate(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status = free_fmu_state;
                fn fmi2SerializedFMUstateSize(c: fmi2Component, FMUstate: fmi2FMUstate, size: *mut usize)
                    -> fmi2Status = serialized_fmu_state_size;
                fn fmi2SerializeFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate, serializedState: *mut fmi2Byte,
                    size: usize) -> fmi2Status = serialize_fmu_state;
                fn fmi2DeSerializeFMUstate(c: fmi2Component, serializedState: *const fmi2Byte, size: usize,
                    FMUstate: *mut fmi2FMUstate) -> fmi2Status = deserialize_fmu_state;
                fn fmi2GetDirectionalDerivative(c: fmi2Component, vUnknown_ref: *const fmi2ValueReference,
                    nUnknown: usize, vKnown_ref: *const fmi2ValueReference, nKnown: usize, dvKnown: *const fmi2Real,
                    dvUnknown: *mut fmi2Real) -> fmi2Status = get_directional_derivative;
                fn fmi2CancelStep(c: fmi2Component) -> fmi2Status = cancel_step;
                fn fmi2GetStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status
                    = get_status;
                fn fmi2GetRealStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status
                    = get_real_status;
                fn fmi2GetIntegerStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status
                    = get_integer_status;
                fn fmi2GetBooleanStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status
                    = get_boolean_status;
                fn fmi2GetStringStatus(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status
                    = get_string_status;
                fn fmi2EnterEventMode(c: fmi2Component) -> fmi2Status = enter_event_mode;
                fn fmi2NewDiscreteStates(c: fmi2Component, fmi2eventInfo: *mut fmi2EventInfo) -> fmi2Status
                    = new_discrete_states;
                fn fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status = enter_continuous_time_mode;
                fn fmi2CompletedIntegratorStep(c: fmi2Component, noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
                    enterEventMode: *mut fmi2Boolean, terminateSimulation: *mut fmi2Boolean) -> fmi2Status
                    = completed_integrator_step;
                fn fmi2SetTime(c: fmi2Component, time: fmi2Real) -> fmi2Status = set_time;
                fn fmi2SetContinuousStates(c: fmi2Component, x: *const fmi2Real, nx: usize) -> fmi2Status
                    = set_continuous_states;
                fn fmi2GetDerivatives(c: fmi2Component, derivatives: *mut fmi2Real, nx: usize) -> fmi2Status
                    = get_derivatives;
                fn fmi2GetEventIndicators(c: fmi2Component, eventIndicators: *mut fmi2Real, ni: usize) -> fmi2Status
                    = get_event_indicators;
                fn fmi2GetContinuousStates(c: fmi2Component, x: *mut fmi2Real, nx: usize) -> fmi2Status
                    = get_continuous_states;
                fn fmi2GetNominalsOfContinuousStates(c: fmi2Component, x_nominal: *mut fmi2Real, nx: usize)
                    -> fmi2Status = get_nominals_of_continuous_states;
            }

            #[no_mangle]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const ::std::ffi::c_char {
                $crate::ffi::get_types_platform()
            }

            #[no_mangle]
            pub extern "C" fn fmi2GetVersion() -> *const ::std::ffi::c_char {
                $crate::ffi::get_version()
            }

            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
                c: fmi2Component,
                _vr: *const fmi2ValueReference,
                _nvr: usize,
                _order: *const fmi2Integer,
                _value: *const fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the FMI 2.0 contract of `fmi2_slave::ffi`, which the master keeps.
                unsafe { $crate::ffi::unsupported::<$slave>(c, $crate::Unsupported::RealInputDerivatives) }
            }

            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
                c: fmi2Component,
                _vr: *const fmi2ValueReference,
                _nvr: usize,
                _order: *const fmi2Integer,
                _value: *mut fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the FMI 2.0 contract of `fmi2_slave::ffi`, which the master keeps.
                unsafe { $crate::ffi::unsupported::<$slave>(c, $crate::Unsupported::RealOutputDerivatives) }
            }

            #[no_mangle]
            pub unsafe extern "C" fn fmi2DoStep(
                c: fmi2Component,
                currentCommunicationPoint: fmi2Real,
                communicationStepSize: fmi2Real,
                _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the FMI 2.0 contract of `fmi2_slave::ffi`, which the master keeps.
                unsafe { $crate::ffi::do_step::<$slave>(c, currentCommunicationPoint, communicationStepSize) }
            }
        }
    };
    // One export per line: its C signature (FMI 2.0 names and types) and the generic function
    // it forwards its arguments to, in order.
    (@forward $slave:ty, $(fn $name:ident($($argument:ident: $type:ty),* $(,)?) -> $result:ty = $target:ident;)*) => {
        $(
            #[no_mangle]
            pub unsafe extern "C" fn $name($($argument: $type),*) -> $result {
                // SAFETY: the FMI 2.0 contract of `fmi2_slave::ffi`, which the master keeps.
                unsafe { $crate::ffi::$target::<$slave>($($argument),*) }
            }
        )*
    };
}

/// A logger callback of the master's, from a Rust function. Stable Rust cannot define a
/// C-variadic function, so `logger` takes the one argument that `"%s"` announces (the only
/// format this layer passes, [`Slave`]'s messages being preformatted) as a named parameter: on
/// the platforms the FMUs are built for (x86-64 System V, AArch64 Linux) a variadic pointer
/// argument is passed exactly like a named one, which is also how fmpy's ctypes logger receives
/// it. For in-process masters (the workspace's tests and benchmarks).
pub type NamedLogger =
    extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, fmi2String);

/// `logger` as the `fmi2CallbackLogger` of `fmi2CallbackFunctions` (see [`NamedLogger`]).
pub fn variadic_logger(logger: NamedLogger) -> fmi2CallbackLogger {
    type Variadic = unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
    // SAFETY: the calling conventions agree for the one variadic argument, see `NamedLogger`.
    Some(unsafe { std::mem::transmute::<NamedLogger, Variadic>(logger) })
}

/// The one recording logger of the workspace's in-process masters (the FMUs' C-ABI tests, the
/// contact FMU's test master): every message an FMU logs, checked as a master relies on it.
#[cfg(feature = "message-log")]
pub mod message_log {
    use std::ffi::CStr;
    use std::sync::Mutex;

    use super::{variadic_logger, NamedLogger};
    use crate::fmi2::*;

    /// Every message an FMU logged through [`MessageLog::callbacks`], as (status, category,
    /// text). Shared between threads: an instance may run on another thread than its master's.
    #[derive(Debug, Default)]
    pub struct MessageLog(pub Mutex<Vec<(fmi2Status, String, String)>>);

    impl MessageLog {
        /// Callbacks whose logger records into this log, which must outlive every instance
        /// given them (it is their component environment).
        pub fn callbacks(&self) -> fmi2CallbackFunctions {
            fmi2CallbackFunctions {
                logger: variadic_logger(record as NamedLogger),
                allocateMemory: None,
                freeMemory: None,
                stepFinished: None,
                componentEnvironment: (self as *const MessageLog).cast_mut().cast(),
            }
        }

        /// The texts, in the order logged.
        pub fn texts(&self) -> Vec<String> {
            self.0.lock().unwrap().iter().map(|(_, _, text)| text.clone()).collect()
        }

        /// The last message's status and text.
        pub fn last(&self) -> Option<(fmi2Status, String)> {
            self.0.lock().unwrap().last().map(|(status, _, text)| (*status, text.clone()))
        }

        /// The last message's text ("" if there is none).
        pub fn last_text(&self) -> String {
            self.last().map(|(_, text)| text).unwrap_or_default()
        }
    }

    /// The logger of [`MessageLog`]: the format is `"%s"` and every string a valid,
    /// NUL-terminated UTF-8 text, or the test fails here (an abort: a panic cannot leave an
    /// `extern "C"` function).
    extern "C" fn record(
        environment: fmi2ComponentEnvironment,
        instance_name: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        format: fmi2String,
        text: fmi2String,
    ) {
        assert!(!environment.is_null(), "a MessageLog's logger without its log");
        // SAFETY: the environment is the `MessageLog` whose callbacks the instance was given,
        // and it outlives the instance; the FMU passes NUL-terminated strings.
        unsafe {
            assert!(status <= fmi2Status_fmi2Fatal, "status {status}");
            assert_eq!(CStr::from_ptr(format), c"%s");
            let [_, category, text] = [instance_name, category, text].map(|s| {
                assert!(!s.is_null());
                CStr::from_ptr(s).to_str().expect("UTF-8 message").to_owned()
            });
            (*environment.cast::<MessageLog>()).0.lock().unwrap().push((status, category, text));
        }
    }
}
