//! fmi2GetDirectionalDerivative through the C ABI: refused with its message for every option
//! that transforms the inputs; for the exact theory, confined to the declared
//! `<ModelStructure>` dependencies; taken at the current inputs, never of a stored output.

use std::f64::consts::PI;

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::{
    value_reference as vr, Causality, Model, Switch, TractionLaw, VARIABLES,
};

fn initialise(fmu: &Fmu) {
    // SAFETY: `fmu.c` is live.
    unsafe {
        use wheel_rail_contact_fmu::ffi::*;
        use wheel_rail_contact_fmu::fmi2::*;
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), fmi2Status_fmi2OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), fmi2Status_fmi2OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), fmi2Status_fmi2OK);
    }
}

/// README: directional derivatives are "not available with hertz_contact, creepages_from_kinematics,
/// creep_relaxation or a Polach 2005 traction law on". Each option alone: fmi2Error with the
/// option's name in the logged message, after a step that succeeds (the scene itself is valid);
/// the same instance's derivative is fmi2OK and non-zero once the option is off again.
#[test]
fn each_option_refuses_derivatives_with_its_message() {
    let options: [(u32, i32, i32, &str); 4] = [
        (vr::HERTZ_CONTACT, Switch::On as i32, Switch::Off as i32, "hertz_contact"),
        (vr::CREEPAGES_FROM_KINEMATICS, Switch::On as i32, Switch::Off as i32, "creepages_from_kinematics"),
        (vr::CREEP_RELAXATION, Switch::On as i32, Switch::Off as i32, "creep_relaxation"),
        (
            vr::TRACTION_LAW,
            TractionLaw::Polach2005Dry as i32,
            TractionLaw::Coulomb as i32,
            "traction_law (Polach 2005)",
        ),
    ];
    for (reference, on, off, name) in options {
        let recorder = MessageLog::default();
        let fmu = Fmu::instantiate_logged("options", &recorder);
        assert_eq!(fmu.set_integer(&[reference], &[on]), OK, "{name}");
        initialise(&fmu);
        assert_eq!(fmu.do_step(0.0, 1e-3), OK, "{name}: the scene with the option on steps");
        let (status, _) = fmu.directional_derivative(&[vr::FORCE_LONGITUDINAL], &[vr::CREEPAGE_LONGITUDINAL], &[1.0]);
        assert_eq!(status, ERROR, "{name}");
        let (logged_status, text) = recorder.last().expect("a message");
        assert_eq!(logged_status, ERROR, "{name}: {text}");
        assert!(text.contains(&format!("directional derivatives are not available with {name} on")), "{name}: {text}");
        // Control: the refusal is the option's. Switched off (parameters are tunable only before
        // initialisation, so in a fresh instance), the same call succeeds.
        let plain = Fmu::instantiate_logged("plain", &recorder);
        assert_eq!(plain.set_integer(&[reference], &[off]), OK);
        initialise(&plain);
        let (status, rates) =
            plain.directional_derivative(&[vr::FORCE_LONGITUDINAL], &[vr::CREEPAGE_LONGITUDINAL], &[1.0]);
        assert_eq!(status, OK, "{name} off");
        assert!(rates[0] < 0.0, "{name} off: {rates:?}");
    }
}

/// Model exact (20 × 20 elements, a general point with lateral creepage and spin): every
/// non-zero derivative of every output is along a dependency `<ModelStructure>` declares, and
/// the forces do depend on every contact input (so the test sees the pattern, not zeros).
#[test]
fn exact_theorys_derivatives_stay_within_the_declared_dependencies() {
    let fmu = Fmu::instantiate("exact", None);
    assert_eq!(
        fmu.set_integer(
            &[vr::CREEP_FORCE_MODEL, vr::EXACT_ELEMENTS_LONGITUDINAL, vr::EXACT_ELEMENTS_LATERAL],
            &[Model::Exact as i32, 20, 20]
        ),
        OK
    );
    initialise(&fmu);
    assert_eq!(fmu.set_real(&[vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE], &[-0.6e-3, 0.3]), OK);
    assert_eq!(fmu.do_step(0.0, 0.1), OK);
    let outputs: Vec<_> = VARIABLES.iter().filter(|v| v.causality == Causality::Output).collect();
    let output_references: Vec<u32> = outputs.iter().map(|o| o.value_reference).collect();
    let mut non_zero = 0;
    for input in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        let (status, rates) = fmu.directional_derivative(&output_references, &[input.value_reference], &[1.0]);
        assert_eq!(status, OK, "d/d {}", input.name);
        for (output, rate) in outputs.iter().zip(&rates) {
            assert!(rate.is_finite(), "d {} / d {} = {rate}", output.name, input.name);
            if *rate != 0.0 {
                non_zero += 1;
                assert!(
                    output.dependencies.contains(&input.value_reference),
                    "exact: d {} / d {} = {rate} undeclared",
                    output.name,
                    input.name
                );
            }
        }
    }
    // F_x, F_y, M_z, |F|/μQ on the seven contact inputs, plus the echoes and p0.
    assert!(non_zero > 30, "only {non_zero} non-zero derivatives");
    for input in [vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE, vr::SEMI_AXIS_A, vr::FRICTION_COEFFICIENT]
    {
        let (_, rates) = fmu.directional_derivative(&[vr::FORCE_LATERAL, vr::SPIN_MOMENT], &[input], &[1.0]);
        assert!(rates.iter().all(|r| *r != 0.0), "input {input}: {rates:?}");
    }
}

/// d(max_pressure) is taken at the current inputs, not from the last step's output:
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

/// In initialisation mode before any output was computed: the rate at the start values.
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
