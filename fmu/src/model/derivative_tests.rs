//! Unit tests of fmi2GetDirectionalDerivative.

use super::test_support::*;
use super::Slave;
use crate::logging::Status;
use crate::model_description::{value_reference as vr, Causality, VARIABLES};

const OUTPUTS: [u32; 3] = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];

#[test]
fn directional_derivative_is_the_core_models_along_the_given_rates() {
    let (mut instance, _) = at_a_general_point();
    let knowns = [vr::CREEPAGE_LONGITUDINAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE, vr::CREEPAGE_LONGITUDINAL];
    let rates = [1.0, -0.5, 2e3, 0.25];
    let mut derivative = [f64::NAN; 3];
    assert_eq!(instance.get_directional_derivative(&OUTPUTS, &knowns, &rates, &mut derivative), Status::Ok);
    let input = crate::scene::contact_input(&instance.model_state().values);
    let direction = wheel_rail_contact::ContactInput {
        creepage_longitudinal: 1.25, // a known given twice adds its rates
        creepage_lateral: 0.0,
        spin_creepage: -0.5,
        normal_force: 2e3,
        semi_axis_a: 0.0,
        semi_axis_b: 0.0,
        friction_coefficient: 0.0,
        shear_modulus: 0.0,
        poisson_ratio: 0.0,
    };
    use wheel_rail_contact::CreepForceModel;
    let expected = wheel_rail_contact::Polach::default().directional_derivative(&input, &direction).unwrap();
    assert_eq!(derivative, [expected.force_longitudinal, expected.force_lateral, expected.adhesion_utilisation]);
    // Unknowns in any order and subset.
    let mut lateral = [f64::NAN];
    instance.get_directional_derivative(&[vr::FORCE_LATERAL], &knowns, &rates, &mut lateral);
    assert_eq!(lateral[0], derivative[1]);
    // The continuous states (the relaxed forces, inert with creep_relaxation off) add nothing,
    // and the state derivatives' rates are 0.
    let with_states = [&knowns[..], &[vr::RELAXED_FORCE_LONGITUDINAL, vr::RELAXED_FORCE_LATERAL]].concat();
    let with_state_rates = [&rates[..], &[5e3, -7e3]].concat();
    let unknowns =
        [OUTPUTS[0], OUTPUTS[1], OUTPUTS[2], vr::DER_RELAXED_FORCE_LONGITUDINAL, vr::DER_RELAXED_FORCE_LATERAL];
    let mut full = [f64::NAN; 5];
    assert_eq!(instance.get_directional_derivative(&unknowns, &with_states, &with_state_rates, &mut full), Status::Ok);
    assert_eq!(full, [derivative[0], derivative[1], derivative[2], 0.0, 0.0]);
    // No knowns: zero.
    instance.get_directional_derivative(&OUTPUTS, &[], &[], &mut derivative);
    assert_eq!(derivative, [0.0; 3]);
}

#[test]
fn directional_derivative_refuses_parameters_outputs_and_bad_rates_by_name() {
    let (mut instance, log) = at_a_general_point();
    let mut out = [0.0];
    let cases: [(&[u32], &[u32], f64, &str); 6] = [
        (
            &[vr::FORCE_LATERAL],
            &[vr::SHEAR_MODULUS],
            1.0,
            "fmi2GetDirectionalDerivative: shear_modulus (value reference 100) cannot be a known: derivatives are \
             taken with respect to the continuous Real inputs and the continuous states only",
        ),
        (
            &[vr::FORCE_LATERAL],
            &[vr::FORCE_LONGITUDINAL],
            1.0,
            "fmi2GetDirectionalDerivative: force_longitudinal (value reference 200) cannot be a known: \
             derivatives are taken with respect to the continuous Real inputs and the continuous states only",
        ),
        (
            &[vr::NORMAL_FORCE],
            &[vr::SEMI_AXIS_A],
            1.0,
            "fmi2GetDirectionalDerivative: normal_force (value reference 3) cannot be an unknown: not an output or a \
             state derivative",
        ),
        (
            &[vr::RELAXED_FORCE_LATERAL],
            &[vr::SEMI_AXIS_A],
            1.0,
            "fmi2GetDirectionalDerivative: relaxed_force_lateral (value reference 301) cannot be an unknown: not an \
             output or a state derivative",
        ),
        (
            &[vr::FORCE_LATERAL],
            &[vr::SEMI_AXIS_A],
            f64::INFINITY,
            "fmi2GetDirectionalDerivative: dvKnown = inf for semi_axis_a is invalid: must be finite",
        ),
        (&[999], &[vr::SEMI_AXIS_A], 1.0, "fmi2GetDirectionalDerivative: unknown value reference 999"),
    ];
    for (unknowns, knowns, rate, expected) in cases {
        assert_eq!(instance.get_directional_derivative(unknowns, knowns, &[rate], &mut out), Status::Error);
        assert_eq!(last_message(&log), expected);
    }
    // At an invalid point the variable is named, as for DoStep.
    instance.set_real(&[vr::SEMI_AXIS_B], &[-1.0]);
    assert_eq!(instance.get_directional_derivative(&OUTPUTS[..1], &[vr::SEMI_AXIS_A], &[1.0], &mut out), Status::Error);
    assert_eq!(last_message(&log), "fmi2GetDirectionalDerivative: semi_axis_b = -1 is invalid: must be finite and > 0");
}

/// `<ModelStructure>` dependencies and the Jacobian agree: for each smooth model, at a
/// general point, every non-zero derivative is along a declared dependency. (The declared
/// lists hold what can change an output under some model or option; that each declared input
/// does change its output somewhere is tested in `scene.rs` by perturbation.)
#[test]
fn every_non_zero_derivative_is_a_declared_dependency() {
    use crate::model_description::Model;
    for model in [Model::Polach, Model::KalkerLinear, Model::ShenHedrickElkins] {
        let (mut instance, _) = new_instance();
        assert_eq!(instance.set_integer(&[vr::CREEP_FORCE_MODEL], &[model as i32]), Status::Ok);
        assert_eq!(instance.setup_experiment(0.0, None), Status::Ok);
        assert_eq!(instance.enter_initialization_mode(), Status::Ok);
        assert_eq!(instance.exit_initialization_mode(), Status::Ok);
        instance.set_real(&[vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE], &[-0.6e-3, 0.3]);
        assert_eq!(instance.do_step(0.0, 0.1), Status::Ok);
        let mut non_zero = 0;
        for input in VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
            for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
                let mut derivative = [f64::NAN];
                let status = instance.get_directional_derivative(
                    &[output.value_reference],
                    &[input.value_reference],
                    &[1.0],
                    &mut derivative,
                );
                assert_eq!(status, Status::Ok);
                if derivative[0] != 0.0 {
                    non_zero += 1;
                    let declared = output.dependencies.contains(&input.value_reference);
                    assert!(declared, "{model:?}: d {} / d {} = {} undeclared", output.name, input.name, derivative[0]);
                }
            }
        }
        assert!(non_zero > 30, "{model:?}: only {non_zero} non-zero derivatives");
    }
}

/// A rate so large that J·v overflows (the slip velocity's rate s_C'·V·10³⁰⁸; the forces' in dual
/// arithmetic, ∞ − ∞) is an error naming the outputs, not an infinite or NaN derivative.
#[test]
fn a_derivative_beyond_the_floating_point_range_is_an_error_naming_the_output() {
    let (mut instance, log) = at_a_general_point();
    let mut derivative = [f64::NAN; 3];
    let status = instance.get_directional_derivative(&OUTPUTS, &[vr::CREEPAGE_LONGITUDINAL], &[1e308], &mut derivative);
    assert_eq!(status, Status::Error);
    let message = last_message(&log);
    assert!(message.starts_with("fmi2GetDirectionalDerivative: force_longitudinal = "), "{message}");
    assert!(message.contains("slip_velocity = inf"), "{message}");
    assert!(message.ends_with("too large for the model's floating-point range"), "{message}");
    // A rate in range still works.
    assert_eq!(
        instance.get_directional_derivative(&OUTPUTS, &[vr::CREEPAGE_LONGITUDINAL], &[1.0], &mut derivative),
        Status::Ok
    );
    assert!(derivative.iter().all(|d| d.is_finite()));
}
