//! The wheelset FMU as FMI 2.0 Model Exchange, through its C exports in-process: the state
//! machine of section 3.2.3 (which calls each mode allows, which interface a call belongs to),
//! the continuous states and their nominals, the derivatives against the equations of motion
//! written out here from the parameters, a free oscillation integrated by this test's own RK4
//! against its closed form, and the errors (wrong length, a state not finite, derailment at an
//! accepted point, a fixed parameter in continuous-time mode).

use std::ffi::CString;
use std::ptr::{null, null_mut};

use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::fmi2::*;
use wheelset::ffi::*;
use wheelset::model_description::{value_reference as vr, GUID};

const OK: fmi2Status = fmi2Status_fmi2OK;
const ERROR: fmi2Status = fmi2Status_fmi2Error;

// The start values of modelDescription.xml (Manchester benchmark vehicle 1).
const MASS: f64 = 1813.0;
const YAW_INERTIA: f64 = 1120.0;
const SPIN_INERTIA: f64 = 112.0;
const K_X: f64 = 31.391e6;
const C_X: f64 = 15e3;
const K_Y: f64 = 3.884e6;
const C_Y: f64 = 2e3;
const B1: f64 = 1.0;
const SPEED: f64 = 20.0;
const RADIUS: f64 = 0.45990634083;
const HALF_LOAD: f64 = -54546.05;

/// One Model Exchange instance, freed on drop.
struct Me {
    c: fmi2Component,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Me {
    fn instantiate(log: &MessageLog, fmu_type: fmi2Type) -> Me {
        let callbacks = Box::new(log.callbacks());
        let guid = CString::new(GUID).unwrap();
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe { fmi2Instantiate(c"ws".as_ptr(), fmu_type, guid.as_ptr(), null(), &*callbacks, 0, 0) };
        assert!(!c.is_null(), "{}", log.last_text());
        Me { c, _callbacks: callbacks }
    }

    /// `parameters` set in initialization mode, then in continuous-time mode at t = 0 after
    /// the event iteration fmpy and OMSimulator run.
    fn running(log: &MessageLog, parameters: &[(u32, f64)]) -> Me {
        let fmu = Me::instantiate(log, fmi2Type_fmi2ModelExchange);
        // SAFETY: `c` is live; valid out-pointers.
        unsafe {
            assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
            for &(reference, value) in parameters {
                assert_eq!(fmi2SetReal(fmu.c, &reference, 1, &value), OK, "{}", log.last_text());
            }
            assert_eq!(fmi2ExitInitializationMode(fmu.c), OK, "{}", log.last_text());
            let mut info = fmi2EventInfo { newDiscreteStatesNeeded: 1, nextEventTimeDefined: 1, ..Default::default() };
            assert_eq!(fmi2NewDiscreteStates(fmu.c, &mut info), OK);
            assert_eq!((info.newDiscreteStatesNeeded, info.terminateSimulation, info.nextEventTimeDefined), (0, 0, 0));
            assert_eq!((info.nominalsOfContinuousStatesChanged, info.valuesOfContinuousStatesChanged), (0, 0));
            assert_eq!(fmi2EnterContinuousTimeMode(fmu.c), OK);
        }
        fmu
    }

    fn set(&self, references: &[u32], values: &[f64]) -> fmi2Status {
        // SAFETY: `c` is live; the slices have the same length.
        unsafe { fmi2SetReal(self.c, references.as_ptr(), references.len(), values.as_ptr()) }
    }

    fn states(&self) -> Vec<f64> {
        let mut x = vec![f64::NAN; 5];
        // SAFETY: `c` is live; 5 slots.
        assert_eq!(unsafe { fmi2GetContinuousStates(self.c, x.as_mut_ptr(), 5) }, OK);
        x
    }

    fn set_states(&self, x: &[f64]) -> fmi2Status {
        // SAFETY: `c` is live; `x` has x.len() values.
        unsafe { fmi2SetContinuousStates(self.c, x.as_ptr(), x.len()) }
    }

    fn derivatives(&self) -> Vec<f64> {
        let mut dx = vec![f64::NAN; 5];
        // SAFETY: `c` is live; 5 slots.
        assert_eq!(unsafe { fmi2GetDerivatives(self.c, dx.as_mut_ptr(), 5) }, OK);
        dx
    }
}

impl Drop for Me {
    fn drop(&mut self) {
        // SAFETY: freed once.
        unsafe { fmi2FreeInstance(self.c) }
    }
}

/// The equations of motion of the wheelset (docs/wheelset.md), written out for the test:
/// ẍ of (y, ψ, ẏ, ψ̇, Ω) under the summed lateral force, yaw moment and axle moment.
fn equations_of_motion(x: &[f64], lateral_force: f64, yaw_moment: f64, axle_moment: f64) -> [f64; 5] {
    let [y, psi, y_dot, psi_dot, _] = x.try_into().unwrap();
    [
        y_dot,
        psi_dot,
        (lateral_force - 2.0 * K_Y * y - 2.0 * C_Y * y_dot) / MASS,
        (yaw_moment - 2.0 * K_X * B1 * B1 * psi - 2.0 * C_X * B1 * B1 * psi_dot) / YAW_INERTIA,
        -axle_moment / SPIN_INERTIA,
    ]
}

#[test]
fn states_nominals_and_derivatives_are_the_equations_of_motion() {
    let log = MessageLog::default();
    let fmu = Me::running(&log, &[(vr::INITIAL_LATERAL_DISPLACEMENT, 1e-3), (vr::INITIAL_YAW_RATE, -0.01)]);
    let x = fmu.states();
    assert_eq!(x, [1e-3, 0.0, 0.0, -0.01, SPEED / RADIUS]);
    let mut nominals = [0.0; 5];
    // SAFETY: `c` is live; 5 slots.
    assert_eq!(unsafe { fmi2GetNominalsOfContinuousStates(fmu.c, nominals.as_mut_ptr(), 5) }, OK);
    assert_eq!(nominals, [1e-3, 1e-3, 1e-2, 1e-2, 10.0]);
    // At the start values' loads (vertical only).
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(a, b)| (a - b).abs() <= 1e-12 * b.abs().max(1e-9));
    let expected = equations_of_motion(&x, 0.0, 0.0, 0.0);
    assert!(close(&fmu.derivatives(), &expected), "{:?} against {expected:?}", fmu.derivatives());
    // New loads (both wheels) and new states: the derivatives follow both.
    let loads = [vr::LEFT_TRACK_FORCE_Y, vr::RIGHT_TRACK_FORCE_Y, vr::LEFT_TRACK_MOMENT_Z, vr::RIGHT_TRACK_MOMENT_Z];
    assert_eq!(fmu.set(&loads, &[1500.0, -400.0, 300.0, 50.0]), OK);
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_MOMENT_Y, vr::RIGHT_TRACK_MOMENT_Y], &[-20.0, -4.0]), OK);
    let moved = [2e-3, -1e-3, 0.03, 0.02, 44.0];
    assert_eq!(fmu.set_states(&moved), OK);
    let expected = equations_of_motion(&moved, 1100.0, 350.0, -24.0);
    assert!(close(&fmu.derivatives(), &expected), "{:?} against {expected:?}", fmu.derivatives());
    // The derivatives are also variables (der(...)), and the states are the outputs.
    let mut der = [0.0; 5];
    let der_refs = [
        vr::DER_WHEELSET_LATERAL_DISPLACEMENT,
        vr::DER_WHEELSET_YAW_ANGLE,
        vr::DER_WHEELSET_LATERAL_VELOCITY,
        vr::DER_WHEELSET_YAW_RATE,
        vr::DER_WHEEL_ANGULAR_SPEED,
    ];
    // SAFETY: `c` is live; 5 slots.
    assert_eq!(unsafe { fmi2GetReal(fmu.c, der_refs.as_ptr(), 5, der.as_mut_ptr()) }, OK);
    assert!(close(&der, &expected), "{der:?}");
    assert_eq!(fmu.states(), moved);
    // SAFETY: `c` is live; no event indicators.
    unsafe {
        let mut enter = 1;
        let mut terminate = 1;
        assert_eq!(fmi2CompletedIntegratorStep(fmu.c, 1, &mut enter, &mut terminate), OK);
        assert_eq!((enter, terminate), (0, 0));
        assert_eq!(fmi2GetEventIndicators(fmu.c, null_mut(), 0), OK);
        assert_eq!(fmi2EnterEventMode(fmu.c), OK);
        assert_eq!(fmi2Terminate(fmu.c), OK);
    }
    assert!(log.0.lock().unwrap().is_empty(), "{:?}", log.texts());
}

/// The master integrates: this test's classical RK4 on 0.1 ms steps through fmi2SetTime,
/// fmi2SetContinuousStates and fmi2GetDerivatives, against the damped oscillator's closed form
/// y(t) with ω² = 2 k_y/m, damping 2 c_y/m, from y(0) = 2 mm.
#[test]
fn a_master_integrating_the_derivatives_gets_the_free_oscillation() {
    let log = MessageLog::default();
    let fmu = Me::running(&log, &[(vr::INITIAL_LATERAL_DISPLACEMENT, 2e-3)]);
    let h = 1e-4;
    let mut x = fmu.states();
    let rate = |time: f64, x: &[f64]| -> Vec<f64> {
        // SAFETY: `c` is live.
        assert_eq!(unsafe { fmi2SetTime(fmu.c, time) }, OK);
        assert_eq!(fmu.set_states(x), OK);
        fmu.derivatives()
    };
    let plus =
        |x: &[f64], factor: f64, k: &[f64]| -> Vec<f64> { x.iter().zip(k).map(|(x, k)| x + factor * k).collect() };
    for step in 0..1000 {
        let t = step as f64 * h;
        let k1 = rate(t, &x);
        let k2 = rate(t + h / 2.0, &plus(&x, h / 2.0, &k1));
        let k3 = rate(t + h / 2.0, &plus(&x, h / 2.0, &k2));
        let k4 = rate(t + h, &plus(&x, h, &k3));
        x = (0..5).map(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])).collect();
        assert_eq!(fmu.set_states(&x), OK);
        let (mut enter, mut terminate) = (0, 0);
        // SAFETY: `c` is live; valid out-pointers.
        assert_eq!(unsafe { fmi2CompletedIntegratorStep(fmu.c, 1, &mut enter, &mut terminate) }, OK);
    }
    let (k, c) = (2.0 * K_Y / MASS, 2.0 * C_Y / MASS);
    let omega_d = (k - c * c / 4.0_f64).sqrt();
    let t = 0.1;
    let expected = 2e-3 * (-c / 2.0 * t).exp() * ((omega_d * t).cos() + c / 2.0 / omega_d * (omega_d * t).sin());
    assert!((x[0] - expected).abs() < 1e-8 * 2e-3, "{} against {expected}", x[0]);
    assert_eq!(x[4], SPEED / RADIUS, "no axle moment: the wheels keep turning at V/r_c");
}

#[test]
fn each_interface_refuses_the_others_functions_and_the_modes_are_checked() {
    let log = MessageLog::default();
    let me = Me::running(&log, &[]);
    // SAFETY: `c` is live; valid pointers.
    unsafe {
        assert_eq!(fmi2DoStep(me.c, 0.0, 1e-3, 0), ERROR);
        assert_eq!(
            log.last_text(),
            "fmi2DoStep: a Co-Simulation function, but this instance was instantiated for Model Exchange"
        );
        // Continuous-time mode: no event iteration, no fixed parameter.
        let mut info = fmi2EventInfo::default();
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), ERROR);
        assert_eq!(log.last_text(), "fmi2NewDiscreteStates: illegal call in state continuousTimeMode");
        assert_eq!(me.set(&[vr::MASS], &[1000.0]), ERROR);
        assert_eq!(log.last_text(), "fmi2SetReal: mass is a fixed parameter and cannot be set after initialization");
        assert_eq!(fmi2NewDiscreteStates(me.c, null_mut()), ERROR);
        assert_eq!(fmi2EnterEventMode(me.c), OK);
        assert_eq!(fmi2NewDiscreteStates(me.c, null_mut()), ERROR);
        assert_eq!(log.last_text(), "fmi2NewDiscreteStates: fmi2eventInfo is NULL");
        assert_eq!(fmi2SetContinuousStates(me.c, [0.0; 5].as_ptr(), 5), ERROR);
        assert_eq!(log.last_text(), "fmi2SetContinuousStates: illegal call in state eventMode");
        assert_eq!(fmi2SetTime(me.c, f64::NAN), ERROR);
        assert_eq!(log.last_text(), "fmi2SetTime: time = NaN is invalid: must be finite and within ±1e12 s");
    }
    let cs = Me::instantiate(&log, fmi2Type_fmi2CoSimulation);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2SetTime(cs.c, 1.0), ERROR);
        assert_eq!(
            log.last_text(),
            "fmi2SetTime: a Model Exchange function, but this instance was instantiated for Co-Simulation"
        );
        assert!(fmi2Instantiate(
            c"ws".as_ptr(),
            7,
            CString::new(GUID).unwrap().as_ptr(),
            null(),
            &log.callbacks(),
            0,
            0
        )
        .is_null());
        assert_eq!(
            log.last_text(),
            "fmi2Instantiate: fmuType = 7 is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)"
        );
    }
}

/// The states read in initialization mode follow the initial values set there; the loads alone
/// (no state written) change the derivatives; the derivatives cannot be written; on the
/// derailment bound itself the wheelset is still on the track (as initialization allows).
#[test]
fn states_follow_initial_values_and_derivatives_the_loads_alone() {
    let log = MessageLog::default();
    let fmu = Me::instantiate(&log, fmi2Type_fmi2ModelExchange);
    // SAFETY: `c` is live.
    unsafe { assert_eq!(fmi2EnterInitializationMode(fmu.c), OK) };
    assert_eq!(fmu.set(&[vr::INITIAL_LATERAL_DISPLACEMENT, vr::INITIAL_YAW_ANGLE], &[1e-3, -2e-3]), OK);
    assert_eq!(fmu.states(), [1e-3, -2e-3, 0.0, 0.0, SPEED / RADIUS]);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(fmu.c), OK);
    }
    let x = fmu.states();
    assert_eq!(fmu.set(&[vr::RIGHT_TRACK_FORCE_Y, vr::LEFT_TRACK_MOMENT_Y], &[2500.0, 30.0]), OK);
    let expected = equations_of_motion(&x, 2500.0, 0.0, 30.0);
    let derivatives = fmu.derivatives();
    let close = derivatives.iter().zip(&expected).all(|(a, b)| (a - b).abs() <= 1e-12 * b.abs().max(1e-9));
    assert!(close, "{derivatives:?} against {expected:?}");
    assert_eq!(fmu.set(&[vr::DER_WHEELSET_LATERAL_VELOCITY], &[0.0]), ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2SetReal: der(wheelset_lateral_velocity) is computed by the model and cannot be set"
    );
    assert_eq!(fmu.set_states(&[0.01, 0.0, 0.0, 0.0, 40.0]), OK);
    let (mut enter, mut terminate) = (0, 0);
    // SAFETY: `c` is live; valid out-pointers.
    assert_eq!(unsafe { fmi2CompletedIntegratorStep(fmu.c, 1, &mut enter, &mut terminate) }, OK);
}

#[test]
fn bad_states_and_lengths_are_errors_that_change_nothing() {
    let log = MessageLog::default();
    let fmu = Me::running(&log, &[]);
    let start = fmu.states();
    assert_eq!(fmu.set_states(&[0.0; 4]), ERROR);
    assert_eq!(log.last_text(), "fmi2SetContinuousStates: n = 4 is not this FMU's number of continuous states 5");
    assert_eq!(fmu.set_states(&[0.0, f64::INFINITY, 0.0, 0.0, 1.0]), ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2SetContinuousStates: wheelset_yaw_angle = inf is invalid: a continuous state must be finite"
    );
    assert_eq!(fmu.states(), start);
    let mut two = [0.0; 2];
    // SAFETY: `c` is live; the arrays hold what n says (or n is the wrong count being tested).
    unsafe {
        assert_eq!(fmi2GetDerivatives(fmu.c, two.as_mut_ptr(), 2), ERROR);
        assert_eq!(log.last_text(), "fmi2GetDerivatives: n = 2 is not this FMU's number of continuous states 5");
        assert_eq!(fmi2GetEventIndicators(fmu.c, two.as_mut_ptr(), 1), ERROR);
        assert_eq!(log.last_text(), "fmi2GetEventIndicators: n = 1 is not this FMU's numberOfEventIndicators 0");
        assert_eq!(fmi2GetDerivatives(fmu.c, null_mut(), 5), ERROR);
        assert_eq!(log.last_text(), "fmi2GetDerivatives: NULL array pointer with n > 0");
    }
    // A load the equations cannot take: the derivatives are refused, naming it.
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Z], &[10.0]), OK);
    let mut dx = [0.0; 5];
    // SAFETY: `c` is live; 5 slots.
    assert_eq!(unsafe { fmi2GetDerivatives(fmu.c, dx.as_mut_ptr(), 5) }, ERROR);
    assert!(log
        .last_text()
        .starts_with("fmi2GetDerivatives: the wheel lifts off the rail at t = 0 s: left_track_force_z = 10 N"));
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Z], &[HALF_LOAD]), OK);
    // An accepted point beyond the derailment bound ends the run with an error.
    assert_eq!(fmu.set_states(&[0.011, 0.0, 0.0, 0.0, 40.0]), OK);
    // SAFETY: `c` is live.
    unsafe { assert_eq!(fmi2SetTime(fmu.c, 0.25), OK) };
    let (mut enter, mut terminate) = (0, 0);
    // SAFETY: `c` is live; valid out-pointers.
    assert_eq!(unsafe { fmi2CompletedIntegratorStep(fmu.c, 1, &mut enter, &mut terminate) }, ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2CompletedIntegratorStep: the wheelset derails at t = 0.25 s: wheelset_lateral_displacement = 0.011 m is \
         beyond derailment_displacement = 0.01 m"
    );
}

/// An FMU state of Model Exchange restores the continuous states; a Co-Simulation instance
/// cannot take it (it never is in eventMode or continuousTimeMode).
#[test]
fn a_model_exchange_state_restores_only_into_model_exchange() {
    let log = MessageLog::default();
    let fmu = Me::running(&log, &[]);
    let moved = [1e-3, 2e-3, 3e-3, 4e-3, 40.0];
    assert_eq!(fmu.set_states(&moved), OK);
    let mut state: fmi2FMUstate = null_mut();
    // SAFETY: `c` is live; `state` is this FMU's until freed.
    unsafe {
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), OK);
        assert_eq!(fmu.set_states(&[0.0, 0.0, 0.0, 0.0, 1.0]), OK);
        assert_eq!(fmi2SetFMUstate(fmu.c, state), OK);
        assert_eq!(fmu.states(), moved);
        let cs = Me::instantiate(&log, fmi2Type_fmi2CoSimulation);
        assert_eq!(fmi2SetFMUstate(cs.c, state), ERROR);
        assert_eq!(
            log.last_text(),
            "fmi2SetFMUstate: FMUstate was taken in state continuousTimeMode, which an instance of Co-Simulation never \
             is in"
        );
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
    }
}
