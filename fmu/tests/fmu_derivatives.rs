//! fmi2GetDirectionalDerivative through the C ABI: refused with its message for every option
//! that transforms the inputs, and, for the exact theory, confined to the declared
//! `<ModelStructure>` dependencies.

mod c_abi;

use c_abi::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact_fmu::model_description::{
    value_reference as vr, Causality, Model, Switch, TractionLaw, VARIABLES,
};

fn initialise(fmu: &Fmu) {
    // SAFETY: `fmu.c` is live.
    unsafe {
        use wheel_rail_contact_fmu::fmi2::*;
        use wheel_rail_contact_fmu::ffi::*;
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
