//! Creep relaxation through the C ABI: a wheel spinning at standstill builds up its force, a
//! contact at rest holds it, and the relaxed force never exceeds the friction limit μQ of the
//! current friction coefficient and load — after a drop of μ or Q, and at rest (each of those
//! cases gave |F| > μQ before the bound: μ 0.3 → 0.05, F_x = −25051 N against μQ = 5000 N).

use fmu_test_master::{Fmu, OK};
use wheel_rail_contact_fmu::ffi::{fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2SetupExperiment};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Switch};

const STEP: f64 = 1e-4;

/// Default scene with creep relaxation on (length from the contact), rolling at `speed`, braked
/// into saturation (ξ = 1 %, |F| ≈ 0.9 μQ), initialised at the steady state.
fn saturated(speed: f64) -> Fmu {
    let fmu = Fmu::instantiate("relaxation", None);
    assert_eq!(fmu.set_integer(&[vr::CREEP_RELAXATION], &[Switch::On as i32]), OK);
    assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::ROLLING_SPEED], &[1e-2, speed]), OK);
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
    let [fx, fy, utilisation] = forces(&fmu);
    assert!(utilisation > 0.8 && fx < -0.8 * 0.3 * 100e3 && fy == 0.0, "{fx}, {utilisation}");
    fmu
}

fn forces(fmu: &Fmu) -> [f64; 3] {
    let values = fmu.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION]);
    [values[0], values[1], values[2]]
}

/// Steps `count` times from step `first`, asserting |F| ≤ μQ and the utilisation ≤ 1 after
/// every step; returns the last forces.
fn step_within_limit(fmu: &Fmu, first: usize, count: usize, friction_limit: f64) -> [f64; 3] {
    let mut last = [0.0; 3];
    for k in first..first + count {
        assert_eq!(fmu.do_step(k as f64 * STEP, STEP), OK, "step {k}");
        last = forces(fmu);
        let magnitude = last[0].hypot(last[1]);
        assert!(magnitude <= friction_limit * (1.0 + 1e-12), "step {k}: |F| = {magnitude} > μQ = {friction_limit}");
        assert!(last[2] <= 1.0 + 1e-12, "step {k}: utilisation {}", last[2]);
    }
    last
}

#[test]
fn a_drop_of_friction_limits_the_relaxed_force_at_once() {
    let fmu = saturated(20.0);
    assert_eq!(fmu.set_real(&[vr::FRICTION_COEFFICIENT], &[0.05]), OK);
    // The first step after the drop: the contact slides down to μQ (it cannot hold more), in
    // the force's own direction.
    let [fx, fy, utilisation] = step_within_limit(&fmu, 0, 1, 0.05 * 100e3);
    assert!((fx + 0.05 * 100e3).abs() < 1e-9 * 5e3 && fy == 0.0 && (utilisation - 1.0).abs() < 1e-12, "{fx}");
    // It then relaxes towards the new steady state, inside the limit throughout.
    step_within_limit(&fmu, 1, 200, 0.05 * 100e3);
}

#[test]
fn a_drop_of_load_limits_the_relaxed_force_at_once() {
    let fmu = saturated(20.0);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[10e3]), OK);
    step_within_limit(&fmu, 0, 200, 0.3 * 10e3);
}

#[test]
fn a_contact_at_rest_holds_no_more_than_the_friction_limit_of_its_load() {
    // At rest the contact is not renewed (V_r = 0) and holds its force: after Q 100 → 5 kN
    // it holds μQ = 1.5 kN, not the 25 kN it held before.
    let fmu = saturated(0.0);
    assert_eq!(fmu.set_real(&[vr::NORMAL_FORCE], &[5e3]), OK);
    let [fx, _, _] = step_within_limit(&fmu, 0, 100, 0.3 * 5e3);
    assert!((fx + 0.3 * 5e3).abs() < 1e-9 * 1.5e3, "held {fx}");
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

/// A wheel spun up at standstill (V = 0, ω = 5 rad/s, r = 0.46 m: slip 2.3 m/s) builds up
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

/// The other side: a contact at rest (V = ω = 0) keeps its force like a spring.
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
