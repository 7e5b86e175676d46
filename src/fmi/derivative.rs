//! fmi2GetDirectionalDerivative's mathematics: J·v of the outputs with respect to the
//! continuous inputs at the instance's current values, by the core's
//! [`CreepForceModel::directional_derivative`] — exact forward-mode dual numbers for Polach,
//! Kalker's linear theory and Shen–Hedrick–Elkins (exact to rounding; 1e-6 relative against
//! central finite differences away from kinks, tests/fmpy/test_master.py); for FASTSIM a central
//! difference whose step moves each input by 1e-6 of its size
//! (`creep_force_model::central_difference`). FASTSIM's forces are piecewise smooth on its grid
//! (an element switching between adhesion and slip inside a step is a kink), so its derivative
//! is a secant slope: documented tolerance 1e-2 relative on each output's scale against a
//! central difference with a 100 times larger step, on 10² to 100² grids away from zero
//! creepages (measured worst 4e-3, tests/derivatives.rs).

use super::model_description::{Inputs, Outputs, Parameters, Values};
use super::scene::{contact_input, creep_force_model, outputs, MeasuredCurveFit};
use crate::CreepForceModel;

/// The option, if any, under which the outputs are not the model's forces of the inputs, so
/// that J·v by the core's derivative would be wrong: then the FMU answers fmi2Error
/// "directional derivatives are not available with <option> on".
///
/// The one place to extend: every parameter is listed (no `..`), so a parameter added to
/// modelDescription.xml stops the build here until it is classified. A parameter that
/// transforms the inputs (kinematics → creepages, Hertz → semi-axes, creep relaxation → lagged
/// forces) returns its name when on; one that only selects or tunes the model is `_`.
pub(crate) fn option_without_derivatives(parameters: &Parameters) -> Option<&'static str> {
    let Parameters {
        shear_modulus: _,
        poisson_ratio: _,
        stiffness_source: _,
        measured_peak_adhesion: _,
        measured_creepage_at_peak: _,
        measured_kinetic_friction: _,
    } = parameters;
    None
}

/// d(outputs) along `direction` (one rate per continuous input) at `values`, or why not
/// (an option without derivatives, an invalid value, naming the variable).
pub(crate) fn directional_derivative(
    values: &Values,
    fit: &mut MeasuredCurveFit,
    direction: &Inputs,
) -> Result<Outputs, String> {
    if let Some(option) = option_without_derivatives(&values.parameters) {
        return Err(format!("directional derivatives are not available with {option} on"));
    }
    let model = creep_force_model(&values.parameters, fit)?;
    let mut rates = contact_input(&Values { inputs: *direction, ..*values });
    // Parameters are never knowns: their rates are zero.
    rates.shear_modulus = 0.0;
    rates.poisson_ratio = 0.0;
    let derivative = model.directional_derivative(&contact_input(values), &rates).map_err(|e| e.to_string())?;
    Ok(outputs(&derivative))
}
