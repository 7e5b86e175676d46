//! The contact FMU as FMI 2.0 Model Exchange: an algebraic model (no continuous states, no
//! event indicators) whose outputs, read at any point of the event and continuous-time modes,
//! are those a Co-Simulation step computes at the same inputs; the creep relaxation, whose
//! forces advance only over steps, refused at fmi2ExitInitializationMode.

use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::fmi2::*;
use fmu_test_master::{Fmu, ERROR, OK};
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, ContactGeometry, Model, Switch};

const OUTPUTS: [u32; 4] =
    [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT, vr::EFFECTIVE_CREEPAGE_LONGITUDINAL];
const TRACK: [u32; 4] = [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z, vr::TRACK_MOMENT_Z];

/// An instance of `fmu_type` with `integers` set, initialised; Model Exchange left in eventMode.
fn initialised(fmu: &Fmu, integers: &[(u32, i32)]) {
    for &(reference, value) in integers {
        assert_eq!(fmu.set_integer(&[reference], &[value]), OK);
    }
    fmu.initialise(0.0);
}

/// The same inputs in both interfaces give the same outputs, bit for bit: in Model Exchange as
/// soon as they are set (event or continuous-time mode), in Co-Simulation after a step.
fn agree(integers: &[(u32, i32)], inputs: &[(u32, f64)], outputs: &[u32]) {
    let log = MessageLog::default();
    let me = Fmu::model_exchange_logged("me", &log);
    let cs = Fmu::instantiate_logged("cs", &log);
    initialised(&me, integers);
    initialised(&cs, integers);
    // SAFETY: `me.c` is live; no states, so n = 0 with NULL arrays is legal.
    unsafe {
        let mut info = fmi2EventInfo::default();
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(me.c), OK);
        assert_eq!(fmi2GetContinuousStates(me.c, std::ptr::null_mut(), 0), OK);
        assert_eq!(fmi2GetDerivatives(me.c, std::ptr::null_mut(), 0), OK);
        assert_eq!(fmi2GetEventIndicators(me.c, std::ptr::null_mut(), 0), OK);
    }
    for (step, &(reference, value)) in inputs.iter().enumerate() {
        for fmu in [&me, &cs] {
            assert_eq!(fmu.set_real(&[reference], &[value]), OK, "{}", log.last_text());
        }
        // SAFETY: `me.c` is live.
        assert_eq!(unsafe { fmi2SetTime(me.c, (step + 1) as f64 * 1e-3) }, OK);
        assert_eq!(cs.do_step(step as f64 * 1e-3, 1e-3), OK, "{}", log.last_text());
        let (a, b) = (me.get_real(outputs), cs.get_real(outputs));
        assert_eq!(a, b, "after {reference} = {value}");
        let (mut enter, mut terminate) = (1, 1);
        // SAFETY: `me.c` is live; valid out-pointers.
        assert_eq!(unsafe { fmi2CompletedIntegratorStep(me.c, 1, &mut enter, &mut terminate) }, OK);
        assert_eq!((enter, terminate), (0, 0));
    }
    // SAFETY: `me.c` is live.
    assert_eq!(unsafe { fmi2Terminate(me.c) }, OK);
    assert!(log.0.lock().unwrap().is_empty(), "{:?}", log.texts());
}

#[test]
fn one_patch_in_model_exchange_is_the_co_simulation_step_at_the_same_inputs() {
    for model in [Model::Polach, Model::ExactTable, Model::Fastsim] {
        let inputs = [(vr::CREEPAGE_LONGITUDINAL, 2e-3), (vr::CREEPAGE_LATERAL, -1e-3), (vr::SPIN_CREEPAGE, 0.3)];
        agree(&[(vr::CREEP_FORCE_MODEL, model as i32)], &inputs, &OUTPUTS);
    }
}

#[test]
fn a_wheel_on_its_profiles_in_model_exchange_is_the_co_simulation_step_at_the_same_position() {
    let inputs = [(vr::WHEELSET_LATERAL_DISPLACEMENT, 4e-3), (vr::WHEELSET_YAW_ANGLE, 1e-3)];
    agree(&[(vr::CONTACT_GEOMETRY, ContactGeometry::Profiles as i32)], &inputs, &TRACK);
}

#[test]
fn creep_relaxation_is_refused_in_model_exchange_and_the_instance_stays_correctable() {
    let log = MessageLog::default();
    let me = Fmu::model_exchange_logged("me", &log);
    assert_eq!(me.set_integer(&[vr::CREEP_RELAXATION], &[Switch::On as i32]), OK);
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(me.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(me.c), OK);
        assert_eq!(fmi2ExitInitializationMode(me.c), ERROR);
    }
    assert_eq!(
        log.last_text(),
        "fmi2ExitInitializationMode: creep_relaxation = 1 is not available in Model Exchange: its relaxed forces \
         advance over Co-Simulation steps, and Model Exchange evaluates the contact algebraically (no continuous \
         states); set creep_relaxation = 0 (off) or instantiate for Co-Simulation"
    );
    assert_eq!(me.set_integer(&[vr::CREEP_RELAXATION], &[Switch::Off as i32]), OK);
    // SAFETY: `me.c` is live.
    assert_eq!(unsafe { fmi2ExitInitializationMode(me.c) }, OK);
    assert_eq!(me.do_step(0.0, 1e-3), ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2DoStep: a Co-Simulation function, but this instance was instantiated for Model Exchange"
    );
}
