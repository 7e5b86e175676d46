//! The FMI 2.0 C types the exports use, as declared in the standard's `fmi2TypesPlatform.h` and
//! `fmi2FunctionTypes.h` (names as bindgen spells them). Written here rather than generated, so
//! that building the FMU needs nothing but cargo (bindgen needs libclang); `fmu/tests/c_abi/fmi2_headers.rs`
//! checks every export's signature and the callback struct's layout against the headers
//! themselves (fmi-sys, a test-only dependency).
#![allow(non_camel_case_types, non_upper_case_globals, non_snake_case)]

use std::ffi::{c_char, c_int, c_uint, c_void};

pub type fmi2Component = *mut c_void;
pub type fmi2ComponentEnvironment = *mut c_void;
pub type fmi2FMUstate = *mut c_void;
pub type fmi2ValueReference = c_uint;
pub type fmi2Real = f64;
pub type fmi2Integer = c_int;
pub type fmi2Boolean = c_int;
pub type fmi2Char = c_char;
pub type fmi2String = *const fmi2Char;
pub type fmi2Byte = c_char;

pub const fmi2True: fmi2Boolean = 1;
pub const fmi2False: fmi2Boolean = 0;

pub type fmi2Status = c_uint;
pub const fmi2Status_fmi2OK: fmi2Status = 0;
pub const fmi2Status_fmi2Warning: fmi2Status = 1;
pub const fmi2Status_fmi2Discard: fmi2Status = 2;
pub const fmi2Status_fmi2Error: fmi2Status = 3;
pub const fmi2Status_fmi2Fatal: fmi2Status = 4;
pub const fmi2Status_fmi2Pending: fmi2Status = 5;

pub type fmi2Type = c_uint;
pub const fmi2Type_fmi2ModelExchange: fmi2Type = 0;
pub const fmi2Type_fmi2CoSimulation: fmi2Type = 1;

pub type fmi2StatusKind = c_uint;
pub const fmi2StatusKind_fmi2DoStepStatus: fmi2StatusKind = 0;
pub const fmi2StatusKind_fmi2PendingStatus: fmi2StatusKind = 1;
pub const fmi2StatusKind_fmi2LastSuccessfulTime: fmi2StatusKind = 2;
pub const fmi2StatusKind_fmi2Terminated: fmi2StatusKind = 3;

pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        componentEnvironment: fmi2ComponentEnvironment,
        instanceName: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        message: fmi2String,
        ...
    ),
>;
pub type fmi2CallbackAllocateMemory = Option<unsafe extern "C" fn(nobj: usize, size: usize) -> *mut c_void>;
pub type fmi2CallbackFreeMemory = Option<unsafe extern "C" fn(obj: *mut c_void)>;
pub type fmi2StepFinished =
    Option<unsafe extern "C" fn(componentEnvironment: fmi2ComponentEnvironment, status: fmi2Status)>;

/// `fmi2CallbackFunctions` of `fmi2FunctionTypes.h`.
#[repr(C)]
#[derive(Debug, Copy, Clone)]
pub struct fmi2CallbackFunctions {
    pub logger: fmi2CallbackLogger,
    pub allocateMemory: fmi2CallbackAllocateMemory,
    pub freeMemory: fmi2CallbackFreeMemory,
    pub stepFinished: fmi2StepFinished,
    pub componentEnvironment: fmi2ComponentEnvironment,
}

/// `fmi2EventInfo` of `fmi2FunctionTypes.h`.
#[repr(C)]
#[derive(Debug, Copy, Clone, Default)]
pub struct fmi2EventInfo {
    pub newDiscreteStatesNeeded: fmi2Boolean,
    pub terminateSimulation: fmi2Boolean,
    pub nominalsOfContinuousStatesChanged: fmi2Boolean,
    pub valuesOfContinuousStatesChanged: fmi2Boolean,
    pub nextEventTimeDefined: fmi2Boolean,
    pub nextEventTime: fmi2Real,
}

/// `fmi2TypesPlatform`, NUL-terminated.
pub const fmi2TypesPlatform: &[u8; 8] = b"default\0";
/// `fmi2Version`, NUL-terminated.
pub const fmi2Version: &[u8; 4] = b"2.0\0";
