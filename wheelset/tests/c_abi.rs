//! The wheelset FMU through its C exports, called in-process as a master calls the shared
//! library: the life cycle, the pointer checks, errors that name the variable, the time and the
//! value, FMU states, a free oscillation against its closed form, and a seeded fuzz of calls.

use std::ffi::{CStr, CString};
use std::ptr::{null, null_mut};

use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::fmi2::*;
use wheelset::ffi::*;
use wheelset::model_description::{value_reference as vr, GUID};

const OK: fmi2Status = fmi2Status_fmi2OK;
const ERROR: fmi2Status = fmi2Status_fmi2Error;

/// One instance, freed on drop.
struct Wheelset {
    c: fmi2Component,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Wheelset {
    fn instantiate(log: &MessageLog) -> Wheelset {
        let callbacks = Box::new(log.callbacks());
        let guid = CString::new(GUID).unwrap();
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe {
            fmi2Instantiate(c"ws".as_ptr(), fmi2Type_fmi2CoSimulation, guid.as_ptr(), null(), &*callbacks, 0, 0)
        };
        assert!(!c.is_null(), "{}", log.last_text());
        Wheelset { c, _callbacks: callbacks }
    }

    /// `parameters` set, then initialised at t = 0.
    fn stepping(log: &MessageLog, parameters: &[(u32, f64)]) -> Wheelset {
        let fmu = Wheelset::instantiate(log);
        // SAFETY: `c` is live.
        unsafe {
            assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        }
        for &(reference, value) in parameters {
            assert_eq!(fmu.set(&[reference], &[value]), OK, "{}", log.last_text());
        }
        // SAFETY: `c` is live.
        assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK, "{}", log.last_text());
        fmu
    }

    fn set(&self, references: &[u32], values: &[f64]) -> fmi2Status {
        // SAFETY: `c` is live; the slices have the same length.
        unsafe { fmi2SetReal(self.c, references.as_ptr(), references.len(), values.as_ptr()) }
    }

    fn get(&self, references: &[u32]) -> Vec<f64> {
        let mut values = vec![f64::NAN; references.len()];
        // SAFETY: `c` is live; the slices have the same length.
        let status = unsafe { fmi2GetReal(self.c, references.as_ptr(), references.len(), values.as_mut_ptr()) };
        assert_eq!(status, OK);
        values
    }

    fn do_step(&self, time: f64, step: f64) -> fmi2Status {
        // SAFETY: `c` is live.
        unsafe { fmi2DoStep(self.c, time, step, 0) }
    }
}

impl Drop for Wheelset {
    fn drop(&mut self) {
        // SAFETY: freed once.
        unsafe { fmi2FreeInstance(self.c) }
    }
}

const STATE: [u32; 6] = [
    vr::WHEELSET_LATERAL_DISPLACEMENT,
    vr::WHEELSET_YAW_ANGLE,
    vr::WHEELSET_LATERAL_VELOCITY,
    vr::WHEELSET_YAW_RATE,
    vr::ROLLING_SPEED,
    vr::WHEEL_ANGULAR_SPEED,
];

#[test]
fn life_cycle_outputs_start_rolling_on_the_centred_radius() {
    let log = MessageLog::default();
    let fmu = Wheelset::stepping(&log, &[(vr::FORWARD_SPEED, 30.0)]);
    assert_eq!(fmu.get(&STATE), [0.0, 0.0, 0.0, 0.0, 30.0, 30.0 / 0.45990634083]);
    // At rest, centred, the wheels' loads only: nothing moves.
    for k in 0..10 {
        assert_eq!(fmu.do_step(k as f64 * 1e-3, 1e-3), OK, "{}", log.last_text());
    }
    assert_eq!(fmu.get(&STATE), [0.0, 0.0, 0.0, 0.0, 30.0, 30.0 / 0.45990634083]);
    let mut time = 0.0;
    // SAFETY: `c` is live; valid out-pointers.
    unsafe {
        assert_eq!(fmi2GetRealStatus(fmu.c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut time), OK);
        assert!((time - 0.01).abs() < 1e-15, "{time}");
        assert_eq!(fmi2Terminate(fmu.c), OK);
        assert_eq!(fmi2Reset(fmu.c), OK);
    }
    assert!(log.0.lock().unwrap().is_empty());
}

#[test]
fn guid_and_pointers_are_checked() {
    let log = MessageLog::default();
    let functions = log.callbacks();
    // SAFETY: NULL pointers and a wrong GUID are what is being tested.
    unsafe {
        let wrong = c"{00000000-0000-0000-0000-000000000000}";
        assert!(fmi2Instantiate(c"ws".as_ptr(), 1, wrong.as_ptr(), null(), &functions, 0, 0).is_null());
        assert!(log.last_text().contains("does not match this FMU's GUID"), "{}", log.last_text());
        assert!(fmi2Instantiate(c"ws".as_ptr(), 1, wrong.as_ptr(), null(), null(), 0, 0).is_null());
        assert_eq!(fmi2DoStep(null_mut(), 0.0, 1e-3, 0), ERROR);
        assert_eq!(fmi2GetReal(null_mut(), &vr::MASS, 1, &mut 0.0), ERROR);
        fmi2FreeInstance(null_mut());
    }
    let fmu = Wheelset::stepping(&log, &[]);
    // SAFETY: NULL arrays with n > 0 must be refused; with n = 0 they are legal.
    unsafe {
        assert_eq!(fmi2SetReal(fmu.c, &vr::LEFT_TRACK_FORCE_Y, 1, null()), ERROR);
        assert_eq!(log.last_text(), "fmi2SetReal: NULL array pointer with n > 0");
        assert_eq!(fmi2GetReal(fmu.c, null(), 0, null_mut()), OK);
        assert_eq!(fmi2GetFMUstate(fmu.c, null_mut()), ERROR);
        assert_eq!(log.last_text(), "fmi2GetFMUstate: FMUstate is NULL");
        assert_eq!(fmi2GetDirectionalDerivative(fmu.c, null(), 0, null(), 0, null(), null_mut()), ERROR);
        assert_eq!(log.last_text(), "fmi2GetDirectionalDerivative: not supported (providesDirectionalDerivative = false in modelDescription.xml)");
        let mut value = 0;
        assert_eq!(fmi2GetInteger(fmu.c, &vr::MASS, 1, &mut value), ERROR);
        assert_eq!(log.last_text(), "fmi2GetInteger: value reference 100 (mass) is not a Integer");
    }
}

#[test]
fn bad_values_are_errors_naming_variable_time_and_value() {
    let log = MessageLog::default();
    let fmu = Wheelset::stepping(&log, &[]);
    assert_eq!(fmu.do_step(0.0, 0.5), OK);
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Y], &[f64::NAN]), OK);
    assert_eq!(fmu.do_step(0.5, 1e-3), ERROR);
    assert_eq!(log.last_text(), "fmi2DoStep: left_track_force_y = NaN N at t = 0.5 s is invalid: must be finite");
    // The instance kept its state: a good value and it carries on.
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Y], &[0.0]), OK);
    assert_eq!(fmu.do_step(0.5, 1e-3), OK);
    assert_eq!(fmu.set(&[vr::RIGHT_TRACK_FORCE_Z], &[0.0]), OK);
    assert_eq!(fmu.do_step(0.501, 1e-3), ERROR);
    assert!(log
        .last_text()
        .starts_with("fmi2DoStep: the wheel lifts off the rail at t = 0.501 s: right_track_force_z = 0 N"));
    assert_eq!(fmu.set(&[vr::RIGHT_TRACK_FORCE_Z], &[-5e4]), OK);
    // A fixed parameter after initialisation, an output: refused.
    assert_eq!(fmu.set(&[vr::MASS], &[1.0]), ERROR);
    assert_eq!(log.last_text(), "fmi2SetReal: mass is a fixed parameter and cannot be set after initialization");
    assert_eq!(fmu.set(&[vr::ROLLING_SPEED], &[1.0]), ERROR);
    assert_eq!(log.last_text(), "fmi2SetReal: rolling_speed is an output and cannot be set");
    // 60 kN to the right on a suspension of 2 × 3.884 MN/m: 7.7 mm static, up to twice that in
    // the first swing, beyond the 10 mm bound.
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Y], &[60e3]), OK);
    // The refused step did not advance the time.
    let mut time = 0.501;
    let status = loop {
        let status = fmu.do_step(time, 1e-3);
        if status != OK || time > 1.0 {
            break status;
        }
        time += 1e-3;
    };
    assert_eq!(status, ERROR);
    let message = log.last_text();
    assert!(message.starts_with("fmi2DoStep: the wheelset derails at t = 0.5"), "{message}");
    // At the refused step's end, the master's time summed step by step, to 12 significant
    // digits: whole milliseconds.
    let milliseconds = ((time + 1e-3) * 1e3).round() / 1e3;
    assert!(message.contains(&format!("derails at t = {milliseconds} s:")), "{time}: {message}");
    assert!(message.ends_with("m is beyond derailment_displacement = 0.01 m"), "{message}");
}

#[test]
fn bad_parameters_keep_it_in_initialization_mode() {
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmu.set(&[vr::SPIN_INERTIA], &[-112.0]), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), ERROR);
        assert_eq!(
            log.last_text(),
            "fmi2ExitInitializationMode: spin_inertia = -112 is invalid: must be finite and > 0"
        );
        assert_eq!(fmu.set(&[vr::SPIN_INERTIA], &[112.0]), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
}

/// The free lateral oscillation through the exports: y(t) of the damped oscillator with
/// ω² = 2 k_y/m, damping 2 c_y/m, from y(0) = 2 mm (the physics' own tests check it finer).
#[test]
fn free_lateral_oscillation_through_the_exports() {
    let log = MessageLog::default();
    let fmu = Wheelset::stepping(&log, &[(vr::INITIAL_LATERAL_DISPLACEMENT, 2e-3)]);
    let (k, c) = (2.0 * 3.884e6 / 1813.0, 2.0 * 2.0e3 / 1813.0);
    let omega_d = (k - c * c / 4.0_f64).sqrt();
    for step in 0..100 {
        assert_eq!(fmu.do_step(step as f64 * 1e-3, 1e-3), OK);
    }
    let t = 0.1;
    let expected = 2e-3 * (-c / 2.0 * t).exp() * ((omega_d * t).cos() + c / 2.0 / omega_d * (omega_d * t).sin());
    let y = fmu.get(&[vr::WHEELSET_LATERAL_DISPLACEMENT])[0];
    assert!((y - expected).abs() < 1e-6 * 2e-3, "{y} against {expected}");
}

/// An FMU state taken, serialised, read back and restored: the run continues bit for bit.
#[test]
fn fmu_states_round_trip() {
    let log = MessageLog::default();
    let fmu = Wheelset::stepping(&log, &[(vr::INITIAL_YAW_ANGLE, 1e-3)]);
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_MOMENT_Y], &[-100.0]), OK);
    assert_eq!(fmu.do_step(0.0, 0.01), OK);
    let mut state: fmi2FMUstate = null_mut();
    let mut size = 0;
    // SAFETY: `c` is live; `state` is this FMU's until freed; the buffer has `size` bytes.
    unsafe {
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), OK);
        assert_eq!(fmi2SerializedFMUstateSize(fmu.c, state, &mut size), OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr().cast(), size), OK);
        assert_eq!(fmu.do_step(0.01, 0.01), OK);
        let first = fmu.get(&STATE);
        let mut restored: fmi2FMUstate = null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), size, &mut restored), OK);
        assert_eq!(fmi2SetFMUstate(fmu.c, restored), OK);
        assert_eq!(fmu.do_step(0.01, 0.01), OK);
        assert_eq!(fmu.get(&STATE), first);
        bytes[0] ^= 1;
        let mut rejected: fmi2FMUstate = null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), size, &mut rejected), ERROR);
        assert_eq!(
            log.last_text(),
            "fmi2DeSerializeFMUstate: serializedState rejected: not a serialized state of this FMU (wrong magic bytes)"
        );
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut restored), OK);
        assert!(state.is_null() && restored.is_null());
    }
}

/// Random calls with random (finite, infinite, NaN) values in random states: every call returns a
/// status (no panic crosses the C ABI, which would abort the test), and an instance never
/// reports a non-finite output after a successful step.
#[test]
fn seeded_fuzz_is_panic_free() {
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // A 64-bit linear congruential generator (Knuth's MMIX constants): reproducible, no crate.
    let mut seed: u64 = 0x5eed;
    let mut next = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        seed >> 33
    };
    let values = [0.0, 1.0, -1.0, 1e-3, 5e4, -5e4, 1e300, f64::NAN, f64::INFINITY, -f64::INFINITY];
    let references: Vec<u32> =
        wheelset::model_description::VARIABLES.iter().map(|v| v.value_reference).chain([999]).collect();
    for _ in 0..20_000 {
        let reference = references[next() as usize % references.len()];
        let value = values[next() as usize % values.len()];
        // SAFETY: `c` is live; one reference, one value.
        let status = unsafe {
            match next() % 8 {
                0 => fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0),
                1 => fmi2EnterInitializationMode(fmu.c),
                2 => fmi2ExitInitializationMode(fmu.c),
                3 => fmi2SetReal(fmu.c, &reference, 1, &value),
                4 => fmi2GetReal(fmu.c, &reference, 1, &mut 0.0),
                5 => {
                    // At the instance's time where it has one (an error in the other states).
                    let mut time = 0.0;
                    fmi2GetRealStatus(fmu.c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut time);
                    let status = fmi2DoStep(fmu.c, time, value.abs().min(0.01), 0);
                    if status == OK {
                        assert!(fmu.get(&STATE).iter().all(|v| v.is_finite()));
                    }
                    status
                }
                6 => fmi2Reset(fmu.c),
                _ => fmi2Terminate(fmu.c),
            }
        };
        assert!(status <= fmi2Status_fmi2Error, "status {status}: {}", log.last_text());
    }
}

/// The two wheels' loads add: the free wheelset (no suspension) under different left and right
/// lateral forces, axle moments and yaw moments accelerates uniformly by their sums — ÿ = ΣF_y/m,
/// ψ̈ = ΣM_z/I, Ω̇ = −ΣM_y/I_s — exactly, over one step (RK4 is exact for a constant rate).
#[test]
fn the_two_wheels_loads_add() {
    let log = MessageLog::default();
    let free = [
        (vr::LATERAL_STIFFNESS, 0.0),
        (vr::LATERAL_DAMPING, 0.0),
        (vr::LONGITUDINAL_STIFFNESS, 0.0),
        (vr::LONGITUDINAL_DAMPING, 0.0),
    ];
    let fmu = Wheelset::stepping(&log, &free);
    let before = fmu.get(&STATE);
    let loads = [
        (vr::LEFT_TRACK_FORCE_Y, 3e3),
        (vr::RIGHT_TRACK_FORCE_Y, 5e3),
        (vr::LEFT_TRACK_MOMENT_Y, 100.0),
        (vr::RIGHT_TRACK_MOMENT_Y, 200.0),
        (vr::LEFT_TRACK_MOMENT_Z, 30.0),
        (vr::RIGHT_TRACK_MOMENT_Z, 50.0),
    ];
    for (reference, value) in loads {
        assert_eq!(fmu.set(&[reference], &[value]), OK);
    }
    let h = 0.01;
    assert_eq!(fmu.do_step(0.0, h), OK, "{}", log.last_text());
    let after = fmu.get(&STATE);
    let (lateral, yaw, spin) = (8e3 / 1813.0, 80.0 / 1120.0, -300.0 / 112.0);
    let expected = [lateral * h * h / 2.0, yaw * h * h / 2.0, lateral * h, yaw * h, before[4], before[5] + spin * h];
    for (k, (value, expected)) in after.iter().zip(expected).enumerate() {
        assert!((value - expected).abs() <= 1e-12 * expected.abs(), "{}: {value} against {expected}", STATE_NAMES[k]);
    }
}

const STATE_NAMES: [&str; 6] = ["y", "ψ", "ẏ", "ψ̇", "V", "Ω"];

/// The initial state is the parameters' (the lateral velocity among them), and an initial
/// displacement exactly at the derailment bound is still within it.
#[test]
fn the_initial_state_is_the_parameters() {
    let log = MessageLog::default();
    let initial = [
        (vr::INITIAL_LATERAL_DISPLACEMENT, 0.01),
        (vr::INITIAL_YAW_ANGLE, -2e-3),
        (vr::INITIAL_LATERAL_VELOCITY, 0.05),
        (vr::INITIAL_YAW_RATE, 0.02),
    ];
    let fmu = Wheelset::stepping(&log, &initial);
    assert_eq!(fmu.get(&STATE)[..4], [0.01, -2e-3, 0.05, 0.02]);
    let refused = [
        (
            vr::INITIAL_LATERAL_DISPLACEMENT,
            -0.0100001,
            "initial_lateral_displacement = -0.0100001 is invalid: must be within derailment_displacement = 0.01",
        ),
        (vr::CENTRED_ROLLING_RADIUS, 0.0, "centred_rolling_radius = 0 is invalid: must be finite and > 0"),
        (vr::CENTRED_ROLLING_RADIUS, f64::INFINITY, "centred_rolling_radius = inf is invalid: must be finite and > 0"),
    ];
    for (reference, value, message) in refused {
        let log = MessageLog::default();
        let fmu = Wheelset::instantiate(&log);
        // SAFETY: `c` is live.
        unsafe {
            assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
            assert_eq!(fmu.set(&[reference], &[value]), OK);
            assert_eq!(fmi2ExitInitializationMode(fmu.c), ERROR);
        }
        assert_eq!(log.last_text(), format!("fmi2ExitInitializationMode: {message}"));
    }
}

/// The generic slave's inquiries and checks (`fmi2_slave::instance`, which the wheelset runs on):
/// platform and version, the status inquiries, String and Integer access to a model of Reals,
/// an output read in initialization mode, states that do not fit, and the log: categories by
/// status, calls traced only when asked, illegal calls named with the state.
#[test]
fn the_generic_slaves_inquiries_and_checks() {
    // SAFETY: static strings.
    unsafe {
        assert_eq!(CStr::from_ptr(fmi2GetTypesPlatform()), c"default");
        assert_eq!(CStr::from_ptr(fmi2GetVersion()), c"2.0");
    }
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live; every pointer is valid or deliberately NULL.
    unsafe {
        // An illegal call names the state; an error is logged in its status's category.
        assert_eq!(fmi2DoStep(fmu.c, 0.0, 1e-3, 0), ERROR);
        assert_eq!(log.last_text(), "fmi2DoStep: illegal call in state instantiated");
        assert_eq!(log.0.lock().unwrap().last().unwrap().1, "logStatusError");
        // An output read in initialization mode is computed from the parameters set.
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmu.set(&[vr::INITIAL_LATERAL_DISPLACEMENT], &[2e-3]), OK);
        assert_eq!(fmu.get(&[vr::WHEELSET_LATERAL_DISPLACEMENT]), [2e-3]);
        // No String or Integer variables: a reference to a Real is refused by type, both ways.
        let (reference, mut string, mut integer) = (vr::MASS, null(), 0);
        assert_eq!(fmi2GetString(fmu.c, &reference, 1, &mut string), ERROR);
        assert_eq!(log.last_text(), "fmi2GetString: value reference 100 (mass) is not a String");
        assert_eq!(fmi2SetInteger(fmu.c, &reference, 1, &integer), ERROR);
        assert_eq!(log.last_text(), "fmi2SetInteger: value reference 100 (mass) is not a Integer");
        assert_eq!(fmi2GetInteger(fmu.c, &reference, 0, &mut integer), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
        // The status inquiries: nothing pending, never asks to stop.
        let mut boolean = 1;
        assert_eq!(fmi2GetBooleanStatus(fmu.c, fmi2StatusKind_fmi2Terminated, &mut boolean), OK);
        assert_eq!(boolean, 0);
        let mut status = OK;
        for kind in [fmi2StatusKind_fmi2DoStepStatus, fmi2StatusKind_fmi2PendingStatus] {
            assert_eq!(fmi2GetStatus(fmu.c, kind, &mut status), fmi2Status_fmi2Discard);
        }
        assert!(log.last_text().starts_with("fmi2GetStatus: no PendingStatus to report"), "{}", log.last_text());
        assert_eq!(fmi2GetBooleanStatus(fmu.c, fmi2StatusKind_fmi2DoStepStatus, &mut boolean), fmi2Status_fmi2Discard);
        assert!(log.last_text().starts_with("fmi2GetBooleanStatus: no DoStepStatus to report"), "{}", log.last_text());
        assert_eq!(fmi2GetStatus(fmu.c, fmi2StatusKind_fmi2DoStepStatus, null_mut()), ERROR);
        assert_eq!(fmi2GetStatus(fmu.c, 7, &mut status), ERROR);
        // Calls are traced in logCalls only when that category is on.
        let logged = || log.0.lock().unwrap().len();
        assert_eq!(fmi2SetDebugLogging(fmu.c, 1, 1, [c"logStatusError".as_ptr()].as_ptr()), OK);
        let before = logged();
        assert_eq!(fmu.do_step(0.0, 1e-3), OK);
        assert_eq!(logged(), before);
        assert_eq!(fmi2SetDebugLogging(fmu.c, 1, 1, [c"logCalls".as_ptr()].as_ptr()), OK);
        assert_eq!(fmu.do_step(1e-3, 1e-3), OK);
        let (status, category, text) = log.0.lock().unwrap().last().unwrap().clone();
        assert_eq!((status, category.as_str()), (OK, "logCalls"));
        assert!(text.starts_with("fmi2DoStep"), "{text}");
        // A state shorter than its header, or holding no state's mode, is refused.
        let mut state: fmi2FMUstate = null_mut();
        let mut size = 0;
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), OK);
        assert_eq!(fmi2SerializedFMUstateSize(fmu.c, state, &mut size), OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr().cast(), size), OK);
        let mut rejected: fmi2FMUstate = null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), 24, &mut rejected), ERROR);
        assert!(log.last_text().ends_with("truncated: 24 bytes, the state needs at least 65"), "{}", log.last_text());
        let mut restored: fmi2FMUstate = null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), size, &mut restored), OK);
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut restored), OK);
        // A mode byte no state holds, behind a valid header and checksum.
        let format = fmi2_slave::instance::Instance::<wheelset::model::WheelsetModel>::state_format();
        let mut payload = format.decode(&bytes).unwrap().to_vec();
        payload[0] = 200;
        let bytes = format.encode(&payload);
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), size, &mut rejected), ERROR);
        assert!(log.last_text().ends_with("mode byte 200 is not a state an FMU state can hold"), "{}", log.last_text());
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
    }
}

/// An FMU state keeps the experiment's stop time: restored, a step beyond it is still refused.
#[test]
fn a_restored_state_keeps_the_stop_time() {
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 1, 0.01), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.do_step(0.0, 0.005), OK);
    let bytes = serialized(&fmu);
    assert_eq!(restore(&fmu, &bytes), OK);
    assert_eq!(fmu.do_step(0.005, 0.01), ERROR);
    assert_eq!(log.last_text(), "fmi2DoStep: the step would end at 0.015, after stopTime = 0.01");
    assert_eq!(fmu.do_step(0.005, 0.005), OK);
}

/// A serialized state of a wheelset at y = 2 mm after a step, and the instance.
fn serialized_stepping_state(log: &MessageLog) -> (Wheelset, Vec<u8>) {
    let fmu = Wheelset::stepping(log, &[(vr::INITIAL_LATERAL_DISPLACEMENT, 2e-3)]);
    assert_eq!(fmu.do_step(0.0, 0.01), OK);
    let bytes = serialized(&fmu);
    (fmu, bytes)
}

/// The instance's state now, serialized (the state itself freed).
fn serialized(fmu: &Wheelset) -> Vec<u8> {
    let mut state: fmi2FMUstate = null_mut();
    let mut size = 0;
    // SAFETY: `c` is live; the buffer has `size` bytes; the state is freed.
    unsafe {
        assert_eq!(fmi2GetFMUstate(fmu.c, &mut state), OK);
        assert_eq!(fmi2SerializedFMUstateSize(fmu.c, state, &mut size), OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(fmi2SerializeFMUstate(fmu.c, state, bytes.as_mut_ptr().cast(), size), OK);
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
        bytes
    }
}

/// `bytes` deserialized and set as the instance's state (the state then freed).
fn restore(fmu: &Wheelset, bytes: &[u8]) -> fmi2Status {
    let mut state: fmi2FMUstate = null_mut();
    // SAFETY: `c` is live; `bytes` is readable; the state is freed.
    unsafe {
        assert_eq!(fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), bytes.len(), &mut state), OK);
        let status = fmi2SetFMUstate(fmu.c, state);
        assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
        status
    }
}

fn deserialize(fmu: &Wheelset, bytes: &[u8]) -> fmi2Status {
    let mut state: fmi2FMUstate = null_mut();
    // SAFETY: `c` is live; `bytes` is readable.
    unsafe {
        let status = fmi2DeSerializeFMUstate(fmu.c, bytes.as_ptr().cast(), bytes.len(), &mut state);
        if !state.is_null() {
            assert_eq!(fmi2FreeFMUstate(fmu.c, &mut state), OK);
        }
        status
    }
}

#[test]
fn every_truncation_and_single_bit_flip_of_a_state_is_refused() {
    // The review's defect 6: 2 242 of 2 312 single-bit flips were accepted (no checksum).
    let log = MessageLog::default();
    let (fmu, bytes) = serialized_stepping_state(&log);
    assert_eq!(deserialize(&fmu, &bytes), OK);
    for length in 0..bytes.len() {
        assert_eq!(deserialize(&fmu, &bytes[..length]), ERROR, "truncated to {length}");
    }
    for position in 0..bytes.len() {
        for bit in 0..8 {
            let mut flipped = bytes.clone();
            flipped[position] ^= 1 << bit;
            assert_eq!(deserialize(&fmu, &flipped), ERROR, "bit {bit} of byte {position}");
            assert!(
                log.last_text().starts_with("fmi2DeSerializeFMUstate: serializedState rejected: "),
                "{}",
                log.last_text()
            );
        }
    }
}

#[test]
fn a_forged_state_with_a_valid_checksum_is_refused_by_its_sense() {
    // Defect 6: a forged wheelset_lateral_displacement = NaN was accepted and fmi2GetReal then
    // returned NaN with fmi2OK; so were mass = −1, a stop time before the time, time = −1e300.
    // The forgeries below carry a correct header and CRC (the layer's own format), so only the
    // sense checks stand between them and the instance.
    let log = MessageLog::default();
    let (fmu, bytes) = serialized_stepping_state(&log);
    let format = fmi2_slave::instance::Instance::<wheelset::model::WheelsetModel>::state_format();
    let payload = format.decode(&bytes).unwrap().to_vec();
    // Payload: mode (1 byte), time (8), stop time (8), then every variable in VARIABLES' order.
    let variable_at = |reference: u32| {
        17 + 8 * wheelset::model_description::VARIABLES.iter().position(|v| v.value_reference == reference).unwrap()
    };
    let forged = |at: usize, value: f64| {
        let mut payload = payload.clone();
        payload[at..at + 8].copy_from_slice(&value.to_le_bytes());
        format.encode(&payload)
    };
    for (at, value, reason) in [
        (variable_at(vr::WHEELSET_LATERAL_DISPLACEMENT), f64::NAN, "wheelset_lateral_displacement = NaN is invalid"),
        (variable_at(vr::WHEELSET_LATERAL_DISPLACEMENT), 0.5, "wheelset_lateral_displacement = 0.5 is invalid: beyond"),
        (variable_at(vr::WHEEL_ANGULAR_SPEED), f64::INFINITY, "wheel_angular_speed = inf is invalid"),
        (variable_at(vr::MASS), -1.0, "mass = -1"),
        (variable_at(vr::CENTRED_ROLLING_RADIUS), 0.0, "centred_rolling_radius = 0 is invalid"),
        (1, -1e300, "time = -1e300 is invalid"),
        (1, f64::NAN, "time = NaN is invalid"),
        (9, -1.0, "stopTime = -1 is invalid: must be >= time"),
    ] {
        assert_eq!(deserialize(&fmu, &forged(at, value)), ERROR, "{reason}");
        let message = log.last_text();
        assert!(
            message.starts_with("fmi2DeSerializeFMUstate: serializedState rejected: not a state this FMU can be in: ")
                && message.contains(reason),
            "{message}"
        );
    }
    // An input may hold any value, as after fmi2SetReal: the next step reports it.
    assert_eq!(deserialize(&fmu, &forged(variable_at(vr::LEFT_TRACK_FORCE_Y), f64::NAN)), OK);
    // On the derailment bound itself is still on the track (initialize allows |y| = the bound).
    assert_eq!(
        deserialize(&fmu, &forged(variable_at(vr::WHEELSET_LATERAL_DISPLACEMENT), -0.01)),
        OK,
        "{}",
        log.last_text()
    );
    // A payload shorter than its run data (mode, time, stop time: 17 bytes), or with the run
    // data and no values, behind a valid header: each refused with its reason.
    assert_eq!(deserialize(&fmu, &format.encode(&payload[..16])), ERROR);
    assert!(
        log.last_text().ends_with("corrupted: a payload of 16 bytes, shorter than its 17-byte run data"),
        "{}",
        log.last_text()
    );
    assert_eq!(deserialize(&fmu, &format.encode(&payload[..17])), ERROR);
    assert!(log.last_text().ends_with("0 bytes of values, not the 304 of this FMU's variables"), "{}", log.last_text());
    // The refusals changed nothing: the instance steps on from its own values, all finite, and
    // the unforged state still restores.
    let outputs = fmu.get(&STATE);
    assert!(outputs.iter().all(|x| x.is_finite()), "{outputs:?}");
    assert_eq!(fmu.do_step(0.01, 0.01), OK, "{}", log.last_text());
    assert!(fmu.get(&STATE).iter().all(|x| x.is_finite()));
    assert_eq!(restore(&fmu, &bytes), OK);
    assert_eq!(fmu.get(&STATE), outputs);
    assert_eq!(fmu.do_step(0.01, 0.01), OK, "{}", log.last_text());
}

#[test]
fn a_state_saved_before_initialization_may_hold_any_parameter() {
    // The fixed parameters can be set to anything until ExitInitializationMode checks them, so
    // a state saved then restores (the sense checks apply to them once initialized).
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.set(&[vr::MASS], &[-1.0]), OK);
    let bytes = serialized(&fmu);
    assert_eq!(deserialize(&fmu, &bytes), OK, "{}", log.last_text());
    // SAFETY: `c` is live.
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, ERROR);
    assert!(log.last_text().contains("mass = -1 is invalid"), "{}", log.last_text());
}

#[test]
fn an_output_that_overflows_is_an_error_and_the_outputs_are_kept() {
    // Defect 8: centred_rolling_radius = 5e-324 gave wheel_angular_speed = inf with fmi2OK.
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.set(&[vr::CENTRED_ROLLING_RADIUS], &[5e-324]), OK);
    // SAFETY: `c` is live.
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, ERROR);
    assert!(
        log.last_text()
            .starts_with("fmi2ExitInitializationMode: centred_rolling_radius = 5e-324 m is invalid: forward_speed"),
        "{}",
        log.last_text()
    );
    // Still in initialization mode: a read of an output computes them again and hands out no
    // infinity either.
    let mut omega = 0.0;
    // SAFETY: `c` is live; one reference, one value.
    assert_eq!(unsafe { fmi2GetReal(fmu.c, &vr::WHEEL_ANGULAR_SPEED, 1, &mut omega) }, ERROR);
    assert!(
        log.last_text().starts_with("fmi2GetReal: centred_rolling_radius = 5e-324 m is invalid"),
        "{}",
        log.last_text()
    );
    // Corrected, it starts; every output finite.
    assert_eq!(fmu.set(&[vr::CENTRED_ROLLING_RADIUS], &[0.46]), OK);
    // SAFETY: `c` is live.
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK, "{}", log.last_text());
    assert!(fmu.get(&STATE).iter().all(|x| x.is_finite()));
}

#[test]
fn a_step_that_cannot_advance_the_time_is_refused() {
    // A time of 1e12 s (the bound of fmi2SetupExperiment's startTime) plus 1e-6 s is the same
    // float: the step would leave the time where it is.
    let log = MessageLog::default();
    let fmu = Wheelset::instantiate(&log);
    // SAFETY: `c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, -1e300, 0, 0.0), ERROR);
        assert!(
            log.last_text().contains("startTime = -1e300 is invalid: must be finite and within ±1e12 s"),
            "{}",
            log.last_text()
        );
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 1e12, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.do_step(1e12, 1e-6), ERROR);
    assert!(log.last_text().contains("is below the resolution of the time"), "{}", log.last_text());
}

#[test]
fn loads_whose_sum_overflows_are_an_error_and_the_outputs_are_kept() {
    // Each wheel's lateral force is finite, their sum is not: the physics refuses the state it
    // would reach (before the slave layer's output guard, which output_guard.rs tests).
    let log = MessageLog::default();
    let fmu = Wheelset::stepping(&log, &[]);
    let before = fmu.get(&STATE);
    assert_eq!(fmu.set(&[vr::LEFT_TRACK_FORCE_Y, vr::RIGHT_TRACK_FORCE_Y], &[f64::MAX, f64::MAX]), OK);
    assert_eq!(fmu.do_step(0.0, 0.01), ERROR);
    assert!(log.last_text().starts_with("fmi2DoStep: the state is not finite"), "{}", log.last_text());
    assert_eq!(fmu.get(&STATE), before, "the outputs are kept");
}
