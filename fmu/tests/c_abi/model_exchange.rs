//! The contact FMU as FMI 2.0 Model Exchange: algebraic in its inputs (its event indicators are
//! `event_indicators.rs`'), its outputs, read at any point of the event and continuous-time
//! modes, those a Co-Simulation
//! step computes at the same inputs; two continuous states, the relaxed forces of creep
//! relaxation, whose derivative is the relaxation law and which a step event projects onto the
//! friction limit; creep relaxation with profiles refused at fmi2ExitInitializationMode.

use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::fmi2::*;
use fmu_test_master::{Fmu, ERROR, OK};
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, ContactGeometry, ContactMethod, Model, Switch};

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

/// The same inputs in both interfaces give the same outputs, bit for bit (within `tolerance` of
/// the largest where it is not 0): in Model Exchange as soon as they are set (event or
/// continuous-time mode), in Co-Simulation after a step.
fn agree(integers: &[(u32, i32)], inputs: &[(u32, f64)], outputs: &[u32], tolerance: f64) {
    let log = MessageLog::default();
    let me = Fmu::model_exchange_logged("me", &log);
    let cs = Fmu::instantiate_logged("cs", &log);
    initialised(&me, integers);
    initialised(&cs, integers);
    // SAFETY: `me.c` is live.
    unsafe {
        let mut info = fmi2EventInfo::default();
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(me.c), OK);
    }
    // Without relaxation the relaxed forces are inert: 0, and so are their derivatives.
    assert_eq!(states(&me), [0.0; 2]);
    assert_eq!(derivatives(&me), [0.0; 2]);
    for (step, &(reference, value)) in inputs.iter().enumerate() {
        for fmu in [&me, &cs] {
            assert_eq!(fmu.set_real(&[reference], &[value]), OK, "{}", log.last_text());
        }
        // SAFETY: `me.c` is live.
        assert_eq!(unsafe { fmi2SetTime(me.c, (step + 1) as f64 * 1e-3) }, OK);
        assert_eq!(cs.do_step(step as f64 * 1e-3, 1e-3), OK, "{}", log.last_text());
        let (a, b) = (me.get_real(outputs), cs.get_real(outputs));
        if tolerance == 0.0 {
            assert_eq!(a, b, "after {reference} = {value}");
        } else {
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let apart = a.iter().zip(&b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(apart <= tolerance * scale, "after {reference} = {value}: {a:?} against {b:?}");
        }
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
        agree(&[(vr::CREEP_FORCE_MODEL, model as i32)], &inputs, &OUTPUTS, 0.0);
    }
}

#[test]
fn a_wheel_on_its_profiles_in_model_exchange_is_the_co_simulation_step_at_the_same_position() {
    let inputs = [(vr::WHEELSET_LATERAL_DISPLACEMENT, 4e-3), (vr::WHEELSET_YAW_ANGLE, 1e-3)];
    let profiles = (vr::CONTACT_GEOMETRY, ContactGeometry::Profiles as i32);
    agree(&[profiles, (vr::CONTACT_METHOD, ContactMethod::Hertz as i32)], &inputs, &TRACK, 0.0);
    // The non-Hertzian balance starts its search where the state's last one settled: a
    // Co-Simulation step moves that start, a Model Exchange evaluation does not (its state is
    // the master's), so the two meet the load within the balance's 1e-10 from different starts.
    agree(&[profiles, (vr::CONTACT_METHOD, ContactMethod::NonHertzian as i32)], &inputs, &TRACK, 1e-8);
}

/// The continuous states (the relaxed forces).
fn states(fmu: &Fmu) -> [f64; 2] {
    let mut x = [f64::NAN; 2];
    // SAFETY: `fmu.c` is live; `x` holds the FMU's 2 states.
    assert_eq!(unsafe { fmi2GetContinuousStates(fmu.c, x.as_mut_ptr(), 2) }, OK);
    x
}

/// The state derivatives at the states and inputs set.
fn derivatives(fmu: &Fmu) -> [f64; 2] {
    let mut dx = [f64::NAN; 2];
    // SAFETY: `fmu.c` is live; `dx` holds the FMU's 2 derivatives.
    assert_eq!(unsafe { fmi2GetDerivatives(fmu.c, dx.as_mut_ptr(), 2) }, OK);
    dx
}

fn set_states(fmu: &Fmu, x: [f64; 2]) {
    // SAFETY: `fmu.c` is live; `x` holds 2 states.
    assert_eq!(unsafe { fmi2SetContinuousStates(fmu.c, x.as_ptr(), 2) }, OK);
}

/// fmi2CompletedIntegratorStep's enterEventMode (terminateSimulation is never set).
fn completed_step_asks_for_an_event(fmu: &Fmu) -> bool {
    let (mut enter, mut terminate) = (7, 7);
    // SAFETY: `fmu.c` is live; valid out-pointers.
    assert_eq!(unsafe { fmi2CompletedIntegratorStep(fmu.c, 1, &mut enter, &mut terminate) }, OK);
    assert_eq!(terminate, 0);
    enter != 0
}

const RELAXATION_LENGTH: f64 = 0.01;

/// One patch (polach, the start values: Q = 100 kN, μ = 0.3, V = 20 m/s) with creep relaxation
/// over `RELAXATION_LENGTH` and creepages ξ, η, initialised (Model Exchange in eventMode).
fn relaxing(fmu: &Fmu, creepages: [f64; 2]) {
    assert_eq!(fmu.set_integer(&[vr::CREEP_RELAXATION], &[Switch::On as i32]), OK);
    assert_eq!(fmu.set_real(&[vr::RELAXATION_LENGTH], &[RELAXATION_LENGTH]), OK);
    assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL], &creepages), OK);
    fmu.initialise(0.0);
}

fn enter_continuous_time_mode(me: &Fmu) {
    let mut info = fmi2EventInfo::default();
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(me.c), OK);
    }
}

/// The relaxed forces start at the steady state; after a creepage step their derivative is the
/// relaxation law (V/L)(F_ss − F) with the steady force of an instance without relaxation, and
/// integrated over one relaxation length of travel (RK4, 50 steps) they land where the
/// Co-Simulation step's exact update does, F_ss + (F₀ − F_ss)/e.
#[test]
fn the_relaxed_forces_are_continuous_states_following_the_relaxation_law() {
    let log = MessageLog::default();
    let (me, cs, steady) = (
        Fmu::model_exchange_logged("me", &log),
        Fmu::instantiate_logged("cs", &log),
        Fmu::instantiate_logged("ss", &log),
    );
    let (before, after) = ([1e-3, -0.5e-3], [3e-3, 0.4e-3]);
    relaxing(&me, before);
    relaxing(&cs, before);
    enter_continuous_time_mode(&me);
    let forces = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL];
    let start = states(&me);
    assert_eq!(start.to_vec(), me.get_real(&forces), "the states start at the steady forces");
    assert!(start[0] < -1e3 && start[1] > 1e2, "forces oppose the creepages: {start:?}");
    assert_eq!(derivatives(&me), [0.0; 2]);
    // The new steady state, from an instance without relaxation.
    assert_eq!(steady.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL], &after), OK);
    steady.initialise(0.0);
    let target = steady.get_real(&forces);
    for fmu in [&me, &cs] {
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL], &after), OK);
    }
    assert_eq!(me.get_real(&forces), start.to_vec(), "the state has not moved yet");
    let rate = 20.0 / RELAXATION_LENGTH;
    let law = |x: [f64; 2]| [rate * (target[0] - x[0]), rate * (target[1] - x[1])];
    let dx = derivatives(&me);
    for k in 0..2 {
        assert!((dx[k] - law(start)[k]).abs() <= 1e-12 * law(start)[k].abs(), "{dx:?} against {:?}", law(start));
    }
    // One relaxation length, L/V = 0.5 ms, in 50 classical Runge–Kutta steps of the FMU's derivatives.
    let (steps, h) = (50, RELAXATION_LENGTH / 20.0 / 50.0);
    let mut x = start;
    let f = |x: [f64; 2]| {
        set_states(&me, x);
        derivatives(&me)
    };
    for _ in 0..steps {
        let k1 = f(x);
        let k2 = f([x[0] + 0.5 * h * k1[0], x[1] + 0.5 * h * k1[1]]);
        let k3 = f([x[0] + 0.5 * h * k2[0], x[1] + 0.5 * h * k2[1]]);
        let k4 = f([x[0] + h * k3[0], x[1] + h * k3[1]]);
        x = [0, 1].map(|k| x[k] + h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]));
        set_states(&me, x);
        assert!(!completed_step_asks_for_an_event(&me), "within the friction limit: no event");
    }
    assert_eq!(cs.do_step(0.0, RELAXATION_LENGTH / 20.0), OK);
    let stepped = cs.get_real(&forces);
    // RK4's global error, (Vh/L)⁴/120 per unit of travel ≈ 1e-9 of the force's change.
    let change = (start[0] - target[0]).hypot(start[1] - target[1]);
    for k in 0..2 {
        let exact = target[k] + (start[k] - target[k]) * (-1.0_f64).exp();
        assert!((stepped[k] - exact).abs() <= 1e-12 * change, "{stepped:?}");
        assert!((x[k] - exact).abs() <= 1e-8 * change, "RK4 {x:?} against {exact}");
    }
    assert_eq!(me.get_real(&forces), x.to_vec(), "the outputs are the states within the friction limit");
    assert_eq!(cs.get_real(&[vr::RELAXED_FORCE_LONGITUDINAL, vr::RELAXED_FORCE_LATERAL]), stepped, "CS: the state");
    assert!(log.0.lock().unwrap().is_empty(), "{:?}", log.texts());
}

/// Relaxed forces beyond μQ (30 kN here) give outputs projected onto the friction limit along
/// their own direction, the derivative from there; the accepted point asks for an event, at
/// which the states move onto the limit (and once there, no second change, no second event).
#[test]
fn relaxed_forces_beyond_the_friction_limit_are_projected_at_a_step_event() {
    let log = MessageLog::default();
    let me = Fmu::model_exchange_logged("me", &log);
    relaxing(&me, [1e-3, 0.0]);
    enter_continuous_time_mode(&me);
    let forces = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL];
    let steady = me.get_real(&forces);
    let limit = 1e5 * 0.3;
    let mut info = fmi2EventInfo::default();
    // Beyond the limit along x alone: F_y stays 0, and the event is asked all the same.
    set_states(&me, [-5e4, 0.0]);
    assert_eq!(me.get_real(&forces), [-limit, 0.0]);
    // The model's steady F_y of η = 0 is −0 (−(0 + 0); the output shows +0), the state +0: their
    // difference is −0, and the derivative is written as +0 like every zero output (masters
    // print −0 as `-0`).
    assert_eq!(derivatives(&me)[1].to_bits(), 0.0_f64.to_bits());
    assert!(completed_step_asks_for_an_event(&me));
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2EnterEventMode(me.c), OK);
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(me.c), OK);
    }
    assert_eq!(states(&me), [-limit, 0.0]);
    let beyond = [-4e4, 3e4]; // |F| = 50 kN
    set_states(&me, beyond);
    let projected = me.get_real(&forces);
    for k in 0..2 {
        assert!((projected[k] - beyond[k] * limit / 5e4).abs() <= 1e-12 * limit, "{projected:?}");
    }
    let dx = derivatives(&me);
    for k in 0..2 {
        let law = 20.0 / RELAXATION_LENGTH * (steady[k] - projected[k]);
        assert!((dx[k] - law).abs() <= 1e-12 * law.abs(), "{dx:?}");
    }
    assert!(completed_step_asks_for_an_event(&me));
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2EnterEventMode(me.c), OK);
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
    }
    assert_eq!(
        (info.valuesOfContinuousStatesChanged, info.newDiscreteStatesNeeded, info.terminateSimulation),
        (1, 0, 0)
    );
    assert_eq!(states(&me).to_vec(), projected);
    // SAFETY: `me.c` is live.
    assert_eq!(unsafe { fmi2NewDiscreteStates(me.c, &mut info) }, OK);
    assert_eq!(info.valuesOfContinuousStatesChanged, 0, "already on the limit");
    // SAFETY: `me.c` is live.
    assert_eq!(unsafe { fmi2EnterContinuousTimeMode(me.c) }, OK);
    assert_eq!(me.get_real(&forces), projected);
    assert!(!completed_step_asks_for_an_event(&me));
    // A lift-off (Q = 0) leaves no force to relax: the outputs 0, an event, the states 0.
    assert_eq!(me.set_real(&[vr::NORMAL_FORCE], &[0.0]), OK);
    assert_eq!(me.get_real(&forces), [0.0; 2]);
    assert!(completed_step_asks_for_an_event(&me));
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2EnterEventMode(me.c), OK);
        assert_eq!(fmi2NewDiscreteStates(me.c, &mut info), OK);
    }
    assert_eq!(states(&me), [0.0; 2]);
    assert!(log.0.lock().unwrap().is_empty(), "{:?}", log.texts());
}

#[test]
fn creep_relaxation_with_profiles_is_refused_in_model_exchange_and_the_instance_stays_correctable() {
    let log = MessageLog::default();
    let me = Fmu::model_exchange_logged("me", &log);
    let options = [vr::CREEP_RELAXATION, vr::CONTACT_GEOMETRY];
    assert_eq!(me.set_integer(&options, &[Switch::On as i32, ContactGeometry::Profiles as i32]), OK);
    // SAFETY: `me.c` is live.
    unsafe {
        assert_eq!(fmi2SetupExperiment(me.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(me.c), OK);
        assert_eq!(fmi2ExitInitializationMode(me.c), ERROR);
    }
    assert_eq!(
        log.last_text(),
        "fmi2ExitInitializationMode: creep_relaxation = 1 with contact_geometry = 2 (profiles) is not available in \
         Model Exchange: each patch's relaxed forces are its own, and patches appear, merge and vanish as the \
         wheelset moves, so they are no fixed set of continuous states; set creep_relaxation = 0 (off), use \
         contact_geometry = 1 (ellipse), or instantiate for Co-Simulation"
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
