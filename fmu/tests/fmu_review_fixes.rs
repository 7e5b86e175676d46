//! Defects found by an independent review of the packaged FMU (issue 14), each reproduced
//! through the C ABI as a master meets it; every test here failed before its fix.

mod c_abi;

use std::f64::consts::PI;

use c_abi::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::value_reference as vr;

const FATAL: u32 = wheel_rail_contact_fmu::fmi2::fmi2Status_fmi2Fatal;

/// 14.1: d(max_pressure) is taken at the current inputs, not from the last step's output:
/// p₀ = 3Q/(2πab), so dp₀/dQ = 3/(2πab) whatever Q is, and dp₀/da = −p₀/a at the current Q.
#[test]
fn max_pressure_derivative_is_at_the_current_inputs() {
    let fmu = Fmu::stepping("max_pressure", 0.0);
    let (a, b) = (7.2e-3, 5.4e-3);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[100e3]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    // A new load, no step: the derivative is of the outputs at 50 kN.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[50e3]), OK);
    let (status, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert_eq!(status, OK);
    let per_newton = 3.0 / (2.0 * PI * a * b); // 12280.47 Pa/N
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{} vs {per_newton}", rates[0]);
    // A new semi-axis: dp₀/da = −3Q/(2πa²b) at Q = 50 kN and the new a.
    let a_new = 9e-3;
    assert_eq!(fmu.set_real(&[vr::SEMI_AXIS_A], &[a_new]), OK);
    let (_, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::SEMI_AXIS_A], &[1.0]);
    let expected = -3.0 * 50e3 / (2.0 * PI * a_new * a_new * b);
    assert!((rates[0] / expected - 1.0).abs() < 1e-12, "{} vs {expected}", rates[0]);
    // After a lift-off step, loaded again without a step: the loaded rate, not 0.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE, vr::SEMI_AXIS_A], &[-1.0, a]), OK);
    assert_eq!(fmu.do_step(1e-3, 1e-3), OK);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[80e3]), OK);
    let (_, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{}", rates[0]);
}

/// 14.1, in initialisation mode before any output was computed: the rate at the start values.
#[test]
fn max_pressure_derivative_in_initialisation_mode() {
    let fmu = Fmu::instantiate("initialisation", None);
    // SAFETY: a live instance.
    unsafe {
        use wheel_rail_contact_fmu::ffi::{fmi2EnterInitializationMode, fmi2SetupExperiment};
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    let (status, rates) = fmu.directional_derivative(&[vr::MAX_PRESSURE], &[vr::NORMAL_FORCE], &[1.0]);
    assert_eq!(status, OK);
    let per_newton = 3.0 / (2.0 * PI * 7.2e-3 * 5.4e-3);
    assert!((rates[0] / per_newton - 1.0).abs() < 1e-12, "{}", rates[0]);
}

/// 14.3: a category selection filters the call traces, never the message of a failing call.
#[test]
fn errors_and_warnings_reach_the_logger_whatever_the_selection() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("logging", &log);
    fmu.initialise(0.0);
    assert_eq!(fmu.set_debug_logging(true, &["logCalls"]), OK);
    // A bad input: the step that uses it fails, with its reason in the log.
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[f64::NAN]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    let texts = log.texts();
    assert_eq!(texts.last().unwrap(), "fmi2DoStep: normal_force = NaN is invalid: must be finite", "{texts:?}");
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[1e5]), OK);
    // An error of DoStep's own arguments (not at the instance's time).
    assert_eq!(fmu.do_step(5.0, 1e-3), ERROR);
    assert_eq!(log.texts().last().unwrap(), "fmi2DoStep: currentCommunicationPoint = 5 is not the instance's time 0");
    // An unknown category alone: the call's own warning is logged.
    log.0.lock().unwrap().clear();
    assert_eq!(fmu.set_debug_logging(true, &["bogus"]), 1, "fmi2Warning");
    let texts = log.texts();
    assert_eq!(texts.len(), 1, "{texts:?}");
    assert!(texts[0].starts_with("fmi2SetDebugLogging: unknown log categories [\"bogus\"] ignored"), "{texts:?}");
    // With that selection, a successful call's trace is filtered, an error is not.
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    assert_eq!(log.texts().len(), 2);
    assert!(log.0.lock().unwrap().iter().all(|(status, _, _)| *status != FATAL));
}

/// 14.4: a step whose end time overflows is an error naming the values, and changes nothing.
#[test]
fn an_overflowing_step_end_is_an_error_and_changes_nothing() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("overflow", &log);
    fmu.initialise(1e308);
    let before = fmu.get_real(&[vr::FORCE_LONGITUDINAL]);
    assert_eq!(fmu.do_step(1e308, 1e308), ERROR);
    assert_eq!(
        log.texts().last().unwrap(),
        "fmi2DoStep: the step would end at inf: currentCommunicationPoint = 1e308 plus communicationStepSize = 1e308 is not finite"
    );
    // The instance's time is still 1e308: a good step from there succeeds.
    assert_eq!(fmu.do_step(1e308, 1e292), OK);
    assert_eq!(fmu.get_real(&[vr::FORCE_LONGITUDINAL]), before);
}

/// A zero output is +0, never −0 (masters print `-0` into their result files).
#[test]
fn zero_outputs_are_positive_zeros() {
    // ξ = ±0 (the core's F_x = −k·ξ is −0 for ξ = +0) and lift-off: zero forces.
    for (xi, q) in [(0.0, 1e5), (-0.0, 1e5), (1e-3, -5.0)] {
        let fmu = Fmu::stepping("zeros", 0.0);
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::NORMAL_FORCE], &[xi, q]), OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), OK);
        let outputs = fmu.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT, vr::SLIP_VELOCITY]);
        assert!(outputs.contains(&0.0));
        for value in outputs.iter().filter(|v| **v == 0.0) {
            assert!(value.is_sign_positive(), "ξ = {xi}, Q = {q}: {outputs:?}");
        }
    }
}

/// One step of the FMU with creepages from the kinematics and creep relaxation (length 10 mm)
/// on, from a contact at rest, with the wheel then turning at `angular_speed` while the vehicle
/// moves at `rolling_speed`: the longitudinal force after each of `steps` steps of `step`, and
/// the steady-state force of the same inputs without relaxation.
fn spin_up(rolling_speed: f64, angular_speed: f64, step: f64, steps: usize) -> (Vec<f64>, f64) {
    use wheel_rail_contact_fmu::model_description::Switch;
    let on = Switch::On as i32;
    let run = |relaxation: i32| {
        let fmu = Fmu::instantiate("standstill", None);
        let switches = [vr::CREEPAGES_FROM_KINEMATICS, vr::CREEP_RELAXATION];
        assert_eq!(fmu.set_integer(&switches, &[on, relaxation]), OK);
        assert_eq!(fmu.set_real(&[vr::RELAXATION_LENGTH], &[0.01]), OK);
        // At rest: no slip, no force.
        assert_eq!(fmu.set_real(&[vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED], &[0.0, 0.0]), OK);
        fmu.initialise(0.0);
        assert_eq!(fmu.get_real(&[vr::FORCE_LONGITUDINAL]), [0.0]);
        assert_eq!(fmu.set_real(&[vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED], &[rolling_speed, angular_speed]), OK);
        (0..steps)
            .map(|k| {
                assert_eq!(fmu.do_step(k as f64 * step, step), OK);
                fmu.get_real(&[vr::FORCE_LONGITUDINAL])[0]
            })
            .collect::<Vec<f64>>()
    };
    let steady = run(Switch::Off as i32);
    (run(on), *steady.last().unwrap())
}

/// 14.2: a wheel spun up at standstill (V = 0, ω = 5 rad/s, r = 0.46 m: slip 2.3 m/s) builds up
/// its force over the relaxation length of its own rolling — the renewal speed
/// V_r = (|V| + |ωr|)/2 = 1.15 m/s — instead of staying at 0: after one step of 1 ms,
/// F = F_ss·(1 − e^{−V_r h/L}) exactly; after 0.1 s (11.5 lengths) it is the steady force.
#[test]
fn a_wheel_spinning_at_standstill_builds_up_its_force() {
    let (forces, steady) = spin_up(0.0, 5.0, 1e-3, 100);
    // Full slip at μ = 0.3, Q = 100 kN: the steady force is μQ (in Kalker's convention, opposing
    // the negative creepage of a wheel turning faster than it travels).
    assert!((steady - 0.3 * 100e3).abs() < 0.01 * 0.3 * 100e3, "{steady}");
    let first = steady * -(-(1.15e-3 / 0.01_f64)).exp_m1();
    assert!((forces[0] / first - 1.0).abs() < 1e-12, "{} vs {first}", forces[0]);
    assert!((forces[99] / steady - 1.0).abs() < 1e-4, "{} vs {steady}", forces[99]);
    // Creeping vehicles: V = 1 mm/s and 10 mm/s build up just as fast (V_r ≈ |ωr|/2).
    for rolling_speed in [1e-3, 1e-2] {
        let (forces, steady) = spin_up(rolling_speed, 5.0, 1e-3, 100);
        assert!((forces[99] / steady - 1.0).abs() < 1e-4, "V = {rolling_speed}: {} vs {steady}", forces[99]);
    }
}

/// 14.2, the other side: a contact at rest (V = ω = 0) keeps its force like a spring.
#[test]
fn a_contact_at_rest_holds_its_force() {
    use wheel_rail_contact_fmu::model_description::Switch;
    let on = Switch::On as i32;
    let fmu = Fmu::instantiate("holding", None);
    assert_eq!(fmu.set_integer(&[vr::CREEPAGES_FROM_KINEMATICS, vr::CREEP_RELAXATION], &[on, on]), OK);
    assert_eq!(fmu.set_real(&[vr::ROLLING_SPEED, vr::WHEEL_ANGULAR_SPEED], &[0.0, 5.0]), OK);
    fmu.initialise(0.0);
    let loaded = fmu.get_real(&[vr::FORCE_LONGITUDINAL])[0];
    assert!(loaded > 1e4, "{loaded}");
    assert_eq!(fmu.set_real(&[vr::WHEEL_ANGULAR_SPEED], &[0.0]), OK);
    for k in 0..100 {
        assert_eq!(fmu.do_step(k as f64 * 0.01, 0.01), OK);
    }
    assert_eq!(fmu.get_real(&[vr::FORCE_LONGITUDINAL])[0], loaded);
}

/// The message of a DoStep with Hertz on and these profile curvatures (wheel, rail) [1/m].
fn hertz_message(wheel: f64, rail: f64) -> String {
    use wheel_rail_contact_fmu::model_description::Switch;
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("hertz", &log);
    assert_eq!(fmu.set_integer(&[vr::HERTZ_CONTACT], &[Switch::On as i32]), OK);
    fmu.initialise(0.0);
    assert_eq!(fmu.set_real(&[vr::WHEEL_PROFILE_CURVATURE, vr::RAIL_PROFILE_CURVATURE], &[wheel, rail]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    log.texts().last().unwrap().clone()
}

/// 14.6: Hertz's errors name the FMU's variables with their values and the actual reason, never
/// an internal quantity (the combined curvature B) nor a concave profile that is not there.
#[test]
fn hertz_errors_name_the_fmu_variables_and_the_cause() {
    for (wheel, rail, named) in [
        (0.0, 1e-20, ["rail_profile_curvature = 1e-20", "wheel_profile_curvature = 0"]),
        (0.0, 0.0, ["rail_profile_curvature = 0", "wheel_profile_curvature = 0"]),
        (0.0, -1.0, ["rail_profile_curvature = -1", "wheel_profile_curvature = 0"]),
    ] {
        let message = hertz_message(wheel, rail);
        assert!(message.starts_with("fmi2DoStep: "), "{message}");
        for text in named {
            assert!(message.contains(text), "{text} not in {message}");
        }
        assert!(!message.contains("curvature_lateral") && !message.contains("concave wheel"), "{message}");
    }
    // A concave wheel flatter than nothing: that cause, named.
    let message = hertz_message(-5.0, 3.0);
    assert!(message.contains("wheel_profile_curvature = -5") && message.contains("concave wheel"), "{message}");
}
