//! One scene: the instance's values → the core's input and model → the outputs.
//!
//! Inputs and parameters are destructured without `..` (unused fields bound to `_` explicitly)
//! and the outputs are built with a struct literal, so a variable added to or removed from `modelDescription.xml` stops the build here
//! until it is mapped.

use super::model_description::{Inputs, Outputs, Parameters, StiffnessSource as StiffnessChoice, Values};
use crate::{ContactInput, CreepForceModel, CreepForces, MeasuredCurve, MeasuredCurveError, Polach, StiffnessSource};

/// The measured curve fitted to the last parameter values it was asked for: the fit (a root
/// search) runs once when the parameters are first needed (ExitInitializationMode) and again
/// only when they change, not at every step.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct MeasuredCurveFit {
    fitted: Option<([u64; 3], Result<MeasuredCurve, MeasuredCurveError>)>,
}

impl MeasuredCurveFit {
    fn get(
        &mut self,
        peak_adhesion: f64,
        creepage_at_peak: f64,
        kinetic_friction: f64,
    ) -> Result<MeasuredCurve, MeasuredCurveError> {
        // Compared bit for bit, so that a NaN parameter never matches and is always reported.
        let key = [peak_adhesion.to_bits(), creepage_at_peak.to_bits(), kinetic_friction.to_bits()];
        match self.fitted {
            Some((fitted_key, result)) if fitted_key == key => result,
            _ => {
                let result = MeasuredCurve::from_peak(peak_adhesion, creepage_at_peak, kinetic_friction);
                self.fitted = Some((key, result));
                result
            }
        }
    }
}

/// The core's input for the instance's values.
pub fn contact_input(values: &Values) -> ContactInput {
    let Inputs {
        creepage_longitudinal,
        creepage_lateral,
        spin_creepage,
        normal_force,
        semi_axis_a,
        semi_axis_b,
        friction_coefficient,
    } = values.inputs;
    ContactInput {
        creepage_longitudinal,
        creepage_lateral,
        spin_creepage,
        normal_force,
        semi_axis_a,
        semi_axis_b,
        friction_coefficient,
        shear_modulus: values.parameters.shear_modulus,
        poisson_ratio: values.parameters.poisson_ratio,
    }
}

/// The stiffness source the parameters select (the measured curve fitted if needed).
fn stiffness(parameters: &Parameters, fit: &mut MeasuredCurveFit) -> Result<StiffnessSource, String> {
    let Parameters {
        shear_modulus: _,
        poisson_ratio: _,
        stiffness_source,
        measured_peak_adhesion,
        measured_creepage_at_peak,
        measured_kinetic_friction,
    } = *parameters;
    match StiffnessChoice::from_value(stiffness_source) {
        Some(StiffnessChoice::Kalker) => Ok(StiffnessSource::Kalker),
        Some(StiffnessChoice::MeasuredCurve) => fit
            .get(measured_peak_adhesion, measured_creepage_at_peak, measured_kinetic_friction)
            .map(StiffnessSource::MeasuredCurve)
            .map_err(|e| e.to_string()),
        None => {
            let items: Vec<String> =
                StiffnessChoice::ITEMS.iter().map(|(name, value, _)| format!("{value} ({name})")).collect();
            Err(format!("stiffness_source = {stiffness_source} is invalid: must be one of {}", items.join(", ")))
        }
    }
}

/// The creep-force model the parameters select (also what fmi2GetDirectionalDerivative
/// differentiates).
#[inline]
pub(crate) fn creep_force_model(parameters: &Parameters, fit: &mut MeasuredCurveFit) -> Result<Polach, String> {
    Ok(Polach { stiffness: stiffness(parameters, fit)?, ..Polach::default() })
}

/// The outputs holding `forces` (or their rates, for directional derivatives).
#[inline]
pub(crate) fn outputs(forces: &CreepForces) -> Outputs {
    Outputs {
        force_longitudinal: forces.force_longitudinal,
        force_lateral: forces.force_lateral,
        adhesion_utilisation: forces.adhesion_utilisation,
    }
}

/// The outputs for `values`, or the reason they cannot be computed (names the variable and value).
#[inline]
pub(crate) fn compute_outputs(values: &Values, fit: &mut MeasuredCurveFit) -> Result<Outputs, String> {
    let forces = creep_force_model(&values.parameters, fit)?.creep_forces(&contact_input(values));
    Ok(outputs(&forces.map_err(|e| e.to_string())?))
}

// --- FMU state (fmu-master branch): the model's internal state, saved with the FMU state ---

/// State the model carries from one step to the next (e.g. creep relaxation), held by the
/// instance and saved and restored whole with the FMU state (`fmi::fmu_state::RunState`) and
/// reset to `Default` by fmi2Reset. Plain values only (no pointers), serde-serialisable. Empty
/// while the scene is algebraic.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct ModelState {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::model_description::{value_reference as vr, Causality, VARIABLES};

    fn default_outputs(values: &Values) -> Outputs {
        compute_outputs(values, &mut MeasuredCurveFit::default()).unwrap()
    }

    #[test]
    fn default_scene_equals_the_core_with_the_start_values() {
        let values = Values::default();
        let input = ContactInput {
            creepage_longitudinal: 1e-3,
            creepage_lateral: 0.0,
            spin_creepage: 0.0,
            normal_force: 100e3,
            semi_axis_a: 7.2e-3,
            semi_axis_b: 5.4e-3,
            friction_coefficient: 0.3,
            shear_modulus: 82e9,
            poisson_ratio: 0.28,
        };
        let expected = Polach::default().creep_forces(&input).unwrap();
        let outputs = default_outputs(&values);
        assert_eq!(outputs.force_longitudinal, expected.force_longitudinal);
        assert_eq!(outputs.force_lateral, 0.0);
        assert_eq!(outputs.adhesion_utilisation, expected.adhesion_utilisation);
        // A loaded wheel with a small creepage: braking force, partly saturated, well below μQ.
        assert!(outputs.force_longitudinal < -5e3 && outputs.adhesion_utilisation < 0.9, "{outputs:?}");
    }

    /// `<ModelStructure>` declares every output to depend on exactly the inputs it lists: at a
    /// scene where every input matters, perturbing a declared input changes the output and
    /// perturbing anything else does not.
    #[test]
    fn declared_output_dependencies_are_the_true_ones() {
        let mut base = Values::default();
        base.inputs.creepage_lateral = 0.4e-3;
        base.inputs.spin_creepage = 0.3;
        let reference = Values { outputs: default_outputs(&base), ..base };
        let inputs = VARIABLES.iter().filter(|v| v.causality == Causality::Input);
        for input in inputs {
            let mut perturbed = base;
            let value = perturbed.real_mut(input.value_reference).unwrap();
            *value = *value * 1.01 + 1e-5;
            let outputs = Values { outputs: default_outputs(&perturbed), ..perturbed };
            for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
                let changed = outputs.real(output.value_reference) != reference.real(output.value_reference);
                let declared = output.dependencies.contains(&input.value_reference);
                assert_eq!(changed, declared, "{} on {}", output.name, input.name);
            }
        }
    }

    #[test]
    fn invalid_values_are_named_with_their_value() {
        let mut values = Values::default();
        values.inputs.semi_axis_a = f64::NAN;
        let message = compute_outputs(&values, &mut MeasuredCurveFit::default()).unwrap_err();
        assert_eq!(message, "semi_axis_a = NaN is invalid: must be finite and > 0");
        let mut values = Values::default();
        values.parameters.stiffness_source = 7;
        let message = compute_outputs(&values, &mut MeasuredCurveFit::default()).unwrap_err();
        assert_eq!(message, "stiffness_source = 7 is invalid: must be one of 1 (kalker), 2 (measured_curve)");
    }

    #[test]
    fn measured_curve_reproduces_its_peak_at_the_kinetic_friction() {
        let mut values = Values::default();
        values.parameters.stiffness_source = StiffnessChoice::MeasuredCurve as i32;
        values.inputs.friction_coefficient = values.parameters.measured_kinetic_friction;
        values.inputs.creepage_longitudinal = values.parameters.measured_creepage_at_peak;
        let at_peak = default_outputs(&values);
        let peak = values.parameters.measured_peak_adhesion * values.inputs.normal_force;
        assert!((at_peak.force_longitudinal + peak).abs() < 1e-9 * peak, "{at_peak:?}");
        for factor in [0.9, 1.1] {
            values.inputs.creepage_longitudinal = values.parameters.measured_creepage_at_peak * factor;
            assert!(default_outputs(&values).force_longitudinal.abs() < peak);
        }
    }

    #[test]
    fn measured_curve_is_refitted_when_its_parameters_change() {
        let mut values = Values::default();
        values.parameters.stiffness_source = StiffnessChoice::MeasuredCurve as i32;
        let mut fit = MeasuredCurveFit::default();
        let before = compute_outputs(&values, &mut fit).unwrap();
        *values.real_mut(vr::MEASURED_PEAK_ADHESION).unwrap() = 0.36;
        let after = compute_outputs(&values, &mut fit).unwrap();
        assert_ne!(before, after);
        assert_eq!(after, compute_outputs(&values, &mut MeasuredCurveFit::default()).unwrap());
        values.parameters.measured_peak_adhesion = 0.29;
        let message = compute_outputs(&values, &mut fit).unwrap_err();
        assert!(message.starts_with("measured_peak_adhesion = 0.29 is invalid"), "{message}");
    }
}
