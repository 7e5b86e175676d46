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

use num_dual::Dual64;

use super::model_description::{Inputs, Outputs, Parameters, Switch, TractionLaw, Values};
use super::scene::{contact_input, creep_force_model, ModelCache};
use crate::models::polach::resulting_creepage_at;
use crate::CreepForceModel;

/// The option, if any, under which the outputs are not the model's forces of the inputs, so
/// that J·v by the core's derivative would be wrong: then the FMU answers fmi2Error
/// "directional derivatives are not available with <option> on".
///
/// The one place to extend: every parameter is listed (no `..`), so a parameter added to
/// modelDescription.xml stops the build here until it is classified. A parameter that
/// transforms the inputs (kinematics → creepages, Hertz → semi-axes, creep relaxation → lagged
/// forces) or makes the friction depend on an input the core does not differentiate (Polach
/// 2005: μ of the slip velocity) returns its name when on; one that only selects or tunes the
/// model is `_`.
pub(crate) fn option_without_derivatives(parameters: &Parameters) -> Option<&'static str> {
    let Parameters {
        shear_modulus: _,
        poisson_ratio: _,
        stiffness_source: _,
        measured_peak_adhesion: _,
        measured_creepage_at_peak: _,
        measured_kinetic_friction: _,
        creep_force_model: _,
        fastsim_strips: _,
        fastsim_elements: _,
        fastsim_traction_bound: _,
        fastsim_flexibility: _,
        exact_elements_longitudinal: _,
        exact_elements_lateral: _,
        traction_law,
        adhesion_reduction_factor: _,
        slip_reduction_factor: _,
        friction_limit_ratio: _,
        friction_decay_rate: _,
        hertz_contact,
        wheel_profile_curvature: _,
        rail_profile_curvature: _,
        creepages_from_kinematics,
        regularisation_speed: _,
        creep_relaxation,
        relaxation_length: _,
    } = parameters;
    let on = |switch: i32| switch == Switch::On as i32;
    if *traction_law != TractionLaw::Coulomb as i32 {
        Some("traction_law (Polach 2005)")
    } else if on(*hertz_contact) {
        Some("hertz_contact")
    } else if on(*creepages_from_kinematics) {
        Some("creepages_from_kinematics")
    } else if on(*creep_relaxation) {
        Some("creep_relaxation")
    } else {
        None
    }
}

/// d(outputs) along `direction` (one rate per continuous input) at `values`, or why not
/// (an option without derivatives, an invalid value, naming the variable).
///
/// With no option on, the forces and M_z are the model's ([`CreepForceModel::directional_derivative`]);
/// the other outputs pass inputs through (friction, creepages, semi-axes), or are
/// p0 = 3Q/(2πab) (so dp0 = p0·(dQ/Q − da/a − db/b)), the approach (0, no Hertz), and the slip
/// velocity s_C·|V| (s_C of Polach's eqs. 21, 22, differentiated with dual numbers).
pub(crate) fn directional_derivative(
    values: &Values,
    cache: &mut ModelCache,
    direction: &Inputs,
) -> Result<Outputs, String> {
    if let Some(option) = option_without_derivatives(&values.parameters) {
        return Err(format!("directional derivatives are not available with {option} on"));
    }
    let model = creep_force_model(&values.parameters, cache)?;
    let mut rates = contact_input(&Values { inputs: *direction, ..*values });
    // Parameters are never knowns: their rates are zero.
    rates.shear_modulus = 0.0;
    rates.poisson_ratio = 0.0;
    let input = contact_input(values);
    let forces = model.directional_derivative(&input, &rates).map_err(|e| e.to_string())?;

    let (x, d) = (&values.inputs, direction);
    let dual = |value: f64, rate: f64| Dual64::new(value, rate);
    let resulting_creepage = resulting_creepage_at(
        dual(x.creepage_longitudinal, d.creepage_longitudinal),
        dual(x.creepage_lateral, d.creepage_lateral),
        dual(x.spin_creepage, d.spin_creepage),
        dual(x.semi_axis_a, d.semi_axis_a),
    );
    let speed = dual(x.rolling_speed, d.rolling_speed);
    // |V|: at V = 0 the rate of the positive side (the slip velocity grows either way).
    let slip_velocity = resulting_creepage * if x.rolling_speed < 0.0 { -speed } else { speed };
    let max_pressure = if x.normal_force > 0.0 {
        values.outputs.max_pressure
            * (d.normal_force / x.normal_force - d.semi_axis_a / x.semi_axis_a - d.semi_axis_b / x.semi_axis_b)
    } else {
        0.0
    };
    Ok(Outputs {
        force_longitudinal: forces.force_longitudinal,
        force_lateral: forces.force_lateral,
        adhesion_utilisation: forces.adhesion_utilisation,
        spin_moment: forces.spin_moment.unwrap_or(0.0),
        current_friction_coefficient: d.friction_coefficient,
        slip_velocity: slip_velocity.eps,
        effective_creepage_longitudinal: d.creepage_longitudinal,
        effective_creepage_lateral: d.creepage_lateral,
        effective_spin_creepage: d.spin_creepage,
        contact_semi_axis_a: d.semi_axis_a,
        contact_semi_axis_b: d.semi_axis_b,
        max_pressure,
        approach: 0.0,
    })
}
