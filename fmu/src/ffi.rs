//! The C exports of the FMU: all 25 common and 9 Co-Simulation functions of FMI 2.0, generated
//! by [`fmi2_slave::export_fmi2!`] for [`Instance`](crate::model::Instance) (its
//! [`fmi2_slave::Slave`] implementation). Pointer checks, C strings, panic catching and
//! FMU-state boxing are the slave layer's ([`fmi2_slave::ffi`], with its contract with the
//! master); this file only instantiates them, and holds the tests of the exports.

// The expansion declares `#[no_mangle] unsafe extern "C"` functions: the only module of the crate
// allowed `unsafe` (the crate denies it).
#![allow(unsafe_code)]

fmi2_slave::export_fmi2!(crate::model::Instance);

#[cfg(test)]
mod tests {
    //! The exports themselves, called in-process as a master would.
    use super::*;
    use crate::fmi2::*;
    use crate::model_description::{value_reference as vr, GUID};
    use fmi2_slave::ffi::message_log::MessageLog;
    use std::ffi::{CStr, CString};
    use std::ptr::null_mut;

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
        let messages = MessageLog::default();
        assert!(instantiate(c"wheel", c"{00000000-0000-0000-0000-000000000000}", &messages.callbacks()).is_null());
        // The format ("%s") and every string: the MessageLog's logger checks them.
        let (status, category, message) = messages.0.lock().unwrap()[0].clone();
        assert_eq!((status, category.as_str()), (fmi2Status_fmi2Error, "logStatusError"));
        assert!(message.contains("does not match this FMU's GUID"), "{message}");
        // SAFETY: NULL callbacks and strings are what is being tested.
        unsafe {
            let no_functions = null_mut();
            assert!(fmi2Instantiate(c"w".as_ptr(), 1, guid().as_ptr(), null_mut(), no_functions, 0, 0).is_null());
            let functions = messages.callbacks();
            assert!(fmi2Instantiate(null_mut(), 1, guid().as_ptr(), null_mut(), &functions, 0, 0).is_null());
            assert!(fmi2Instantiate(c"w".as_ptr(), 1, null_mut(), null_mut(), &functions, 0, 0).is_null());
        }
    }

    #[test]
    fn pointers_are_checked() {
        let messages = MessageLog::default();
        let c = stepping(&messages.callbacks());
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
            assert_eq!(messages.last_text(), "fmi2SetReal: NULL array pointer with n > 0");
            assert_eq!(fmi2GetRealStatus(c, fmi2StatusKind_fmi2LastSuccessfulTime, null_mut()), fmi2Status_fmi2Error);
            assert_eq!(fmi2GetStatus(c, 17, &mut 0), fmi2Status_fmi2Error);
            assert_eq!(messages.last_text(), "fmi2GetStatus: unknown fmi2StatusKind 17");
            fmi2FreeInstance(c);
        }
    }

    #[test]
    fn status_functions_through_the_exports() {
        let messages = MessageLog::default();
        let c = stepping(&messages.callbacks());
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
            assert_eq!(messages.last_text(), "fmi2CancelStep: illegal call in state stepComplete");
            fmi2FreeInstance(c);
        }
    }

    #[test]
    fn instances_are_independent() {
        let (first_log, second_log) = (MessageLog::default(), MessageLog::default());
        let (first_callbacks, second_callbacks) = (first_log.callbacks(), second_log.callbacks());
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
        assert!(first_log.texts().is_empty());
        assert_eq!(second_log.texts()[0], "fmi2DoStep: semi_axis_b = NaN is invalid: must be finite and > 0");
        // SAFETY: freed once each.
        unsafe {
            fmi2FreeInstance(first);
            fmi2FreeInstance(second);
        }
    }
}
