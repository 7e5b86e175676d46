//! One scene: the instance's values → the options a scene switches on → the core's model → the
//! outputs.
//!
//! Per evaluation, in order (each option only when its parameter is `on`; an option that is off
//! costs a branch and nothing else, and its inputs and parameters are not checked):
//! 1. creepages: the inputs, or from the kinematics ([`crate::scene::kinematics`]);
//! 2. contact ellipse: the inputs, or Hertz's ([`crate::scene::hertz`]; Q ≤ 0 is lift-off and
//!    gives zero forces before any Hertz computation);
//! 3. forces: the model the parameters select ([`ModelChoice`]), built once by [`ModelCache`]
//!    when the parameters change, with Polach's 2005 traction law applied at this step's speed;
//! 4. relaxation ([`crate::scene::relaxation`]): the relaxed forces, the instance's only state,
//!    advanced exactly over the step from the steady-state forces of step 3.
//!
//! Inputs and parameters are destructured without `..` (unused fields bound to `_` explicitly)
//! and the outputs are built with a struct literal, so a variable added to or removed from
//! `modelDescription.xml` stops the build here until it is mapped.

use std::f64::consts::PI;

use super::model_description::{
    Flexibility as FlexibilityChoice, Inputs, Model, Outputs, Parameters, StiffnessSource as StiffnessChoice, Switch,
    TractionBound as TractionBoundChoice, TractionLaw, Values,
};
use crate::numerics::magnitude;
use crate::scene::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use crate::scene::kinematics::WheelKinematics;
use crate::scene::relaxation::RelaxationLengths;
use crate::{
    ContactInput, CreepForceModel, CreepForces, ExactTheory, Fastsim, Flexibility, InvalidInput, KalkerLinear,
    LargeCreepage, MeasuredCurve, ModelChoice, Polach, Polach2005, ShenHedrickElkins, StiffnessSource, TractionBound,
};

/// The relaxed forces [F_x, F_y] [N]: the FMU's one state (used when `creep_relaxation = on`),
/// in the layout of [`RelaxationLengths::advance`].
pub type RelaxedForces = [f64; 2];

/// What an evaluation is for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Evaluation {
    /// Initialization mode (ExitInitializationMode, GetReal of an output): the relaxed forces
    /// start at the steady state.
    Initialise,
    /// fmi2DoStep of this size [s] (> 0): the relaxed forces advance over it.
    Step(f64),
}

/// What the parameters select, validated: the model and the options that are on.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Plan {
    model: ModelChoice,
    /// Polach 2005 (only with model = polach); the rolling speed is applied per evaluation.
    traction: Option<Polach2005>,
    hertz_contact: bool,
    creepages_from_kinematics: bool,
    creep_relaxation: bool,
}

/// The plan for the last parameter values it was asked for: built (the measured-curve fit, FASTSIM's
/// load normalisation, every check of the parameters) once when the parameters are first needed
/// and again only when one changes, not at every step. Derived from the parameters alone, so it
/// is not part of the FMU's state.
#[derive(Debug, Clone, Default)]
pub struct ModelCache {
    built: Option<(Parameters, Result<Plan, String>)>,
}

impl ModelCache {
    fn plan(&mut self, parameters: &Parameters) -> Result<Plan, String> {
        // A NaN parameter never equals itself, so it is rebuilt and reported every time.
        match &self.built {
            Some((built_for, plan)) if built_for == parameters => plan.clone(),
            _ => {
                let plan = build_plan(parameters);
                self.built = Some((*parameters, plan.clone()));
                plan
            }
        }
    }
}

/// "name = value is invalid: must be one of 1 (a), 2 (b)".
fn enumeration<T>(
    name: &str,
    value: i32,
    from_value: fn(i32) -> Option<T>,
    items: &[(&str, i32, &str)],
) -> Result<T, String> {
    from_value(value).ok_or_else(|| {
        let items: Vec<String> = items.iter().map(|(item, value, _)| format!("{value} ({item})")).collect();
        format!("{name} = {value} is invalid: must be one of {}", items.join(", "))
    })
}

fn switch(name: &str, value: i32) -> Result<bool, String> {
    enumeration(name, value, Switch::from_value, Switch::ITEMS).map(|switch| switch == Switch::On)
}

/// An Integer parameter as a count: a negative value becomes 0, which every count rejects, and
/// [`reported`] puts the original value back into the message.
fn count(value: i32) -> usize {
    usize::try_from(value).unwrap_or(0)
}

/// The core's error for one of `counts`, renamed to the FMU's variable and with its value.
fn reported(error: InvalidInput, counts: &[(&'static str, &'static str, i32)]) -> String {
    match counts.iter().find(|(core_name, _, _)| *core_name == error.variable) {
        Some(&(_, variable, value)) => InvalidInput { variable, value: value as f64, ..error }.to_string(),
        None => error.to_string(),
    }
}

fn build_plan(parameters: &Parameters) -> Result<Plan, String> {
    let Parameters {
        shear_modulus: _,
        poisson_ratio: _,
        stiffness_source,
        measured_peak_adhesion,
        measured_creepage_at_peak,
        measured_kinetic_friction,
        model,
        fastsim_strips,
        fastsim_elements,
        fastsim_traction_bound,
        fastsim_flexibility,
        exact_elements_longitudinal,
        exact_elements_lateral,
        traction_law,
        adhesion_reduction_factor,
        slip_reduction_factor,
        friction_limit_ratio,
        friction_decay_rate,
        hertz_contact,
        wheel_profile_curvature: _,
        rail_profile_curvature: _,
        creepages_from_kinematics,
        regularisation_speed: _,
        creep_relaxation,
        relaxation_length: _,
    } = *parameters;
    let selected = enumeration("model", model, Model::from_value, Model::ITEMS)?;
    let stiffness =
        match enumeration("stiffness_source", stiffness_source, StiffnessChoice::from_value, StiffnessChoice::ITEMS)? {
            StiffnessChoice::Kalker => StiffnessSource::Kalker,
            StiffnessChoice::MeasuredCurve => {
                MeasuredCurve::from_peak(measured_peak_adhesion, measured_creepage_at_peak, measured_kinetic_friction)
                    .map(StiffnessSource::MeasuredCurve)
                    .map_err(|e| e.to_string())?
            }
        };
    let traction = match enumeration("traction_law", traction_law, TractionLaw::from_value, TractionLaw::ITEMS)? {
        TractionLaw::Coulomb => None,
        TractionLaw::Polach2005Dry => Some(Polach2005::DRY),
        TractionLaw::Polach2005Wet => Some(Polach2005::WET),
        TractionLaw::Polach2005User => Some(
            Polach2005::new(
                adhesion_reduction_factor,
                slip_reduction_factor,
                friction_limit_ratio,
                friction_decay_rate,
            )
            .map_err(|e| e.to_string())?,
        ),
    };
    // Both are Polach's: rejected rather than silently ignored with another model.
    if selected != Model::Polach {
        let name = Model::ITEMS.iter().find(|(_, value, _)| *value == model).map_or("?", |(name, _, _)| name);
        let model_text = format!("model = {model} ({name})");
        if traction.is_some() {
            return Err(format!(
                "traction_law = {traction_law} is invalid: Polach 2005 needs model = 1 (polach), not {model_text}"
            ));
        }
        if stiffness != StiffnessSource::Kalker {
            return Err(format!(
                "stiffness_source = {stiffness_source} is invalid: a measured curve needs model = 1 (polach), not {model_text}"
            ));
        }
    }
    let model = match selected {
        Model::Polach => ModelChoice::Polach(Polach { stiffness, large_creepage: None }),
        Model::KalkerLinear => ModelChoice::KalkerLinear(KalkerLinear),
        Model::ShenHedrickElkins => ModelChoice::ShenHedrickElkins(ShenHedrickElkins),
        Model::Fastsim => {
            let bound = match enumeration(
                "fastsim_traction_bound",
                fastsim_traction_bound,
                TractionBoundChoice::from_value,
                TractionBoundChoice::ITEMS,
            )? {
                TractionBoundChoice::Parabolic => TractionBound::Parabolic,
                TractionBoundChoice::Elliptic => TractionBound::Elliptic,
            };
            let flexibility = match enumeration(
                "fastsim_flexibility",
                fastsim_flexibility,
                FlexibilityChoice::from_value,
                FlexibilityChoice::ITEMS,
            )? {
                FlexibilityChoice::ThreeBlended => Flexibility::ThreeBlended,
                FlexibilityChoice::Three => Flexibility::Three,
                FlexibilityChoice::SingleWeighted => Flexibility::SingleWeighted,
            };
            let counts = [
                ("fastsim_strips", "fastsim_strips", fastsim_strips),
                ("fastsim_elements", "fastsim_elements", fastsim_elements),
            ];
            Fastsim::new(count(fastsim_strips), count(fastsim_elements), bound, flexibility)
                .map(ModelChoice::Fastsim)
                .map_err(|e| reported(e, &counts))?
        }
        Model::Exact => {
            let exact = ExactTheory::new(count(exact_elements_longitudinal), count(exact_elements_lateral));
            let counts = [
                ("grid_elements_longitudinal", "exact_elements_longitudinal", exact_elements_longitudinal),
                ("grid_elements_lateral", "exact_elements_lateral", exact_elements_lateral),
            ];
            exact.validate().map_err(|e| reported(e, &counts))?;
            ModelChoice::Exact(exact)
        }
    };
    Ok(Plan {
        model,
        traction,
        hertz_contact: switch("hertz_contact", hertz_contact)?,
        creepages_from_kinematics: switch("creepages_from_kinematics", creepages_from_kinematics)?,
        creep_relaxation: switch("creep_relaxation", creep_relaxation)?,
    })
}

/// The creepages the model uses and the speed that turns creepage into slip velocity.
struct Creepages {
    longitudinal: f64,
    lateral: f64,
    spin: f64,
    /// |V|, or D = √(V² + v_c²) from the kinematics (ξ·D is then the slip velocity exactly).
    speed: f64,
}

fn from_kinematics(kinematics: &WheelKinematics, regularisation_speed: f64) -> Result<Creepages, InvalidInput> {
    let computed = kinematics.creepages(regularisation_speed)?;
    Ok(Creepages {
        longitudinal: computed.longitudinal,
        lateral: computed.lateral,
        spin: computed.spin,
        speed: computed.reference_speed,
    })
}

/// The relative curvatures from the FMU's signed profile curvatures (0 = straight), with errors
/// named after the FMU's variables.
fn relative_curvature(wheel_rolling_radius: f64, parameters: &Parameters) -> Result<RelativeCurvature, InvalidInput> {
    let curvatures = [
        ("wheel_profile_curvature", parameters.wheel_profile_curvature),
        ("rail_profile_curvature", parameters.rail_profile_curvature),
    ];
    for (variable, value) in curvatures {
        if !value.is_finite() {
            return Err(InvalidInput::new(variable, value, "must be finite"));
        }
    }
    // 1/0 = ∞: a straight profile, as `from_radii` takes it.
    let [(_, wheel), (_, rail)] = curvatures;
    RelativeCurvature::from_radii(wheel_rolling_radius, 1.0 / wheel, 1.0 / rail).map_err(|e| match e.variable {
        "wheel_profile_radius" => InvalidInput { variable: "wheel_profile_curvature", value: wheel, ..e },
        "rail_profile_radius" => InvalidInput { variable: "rail_profile_curvature", value: rail, ..e },
        _ => e,
    })
}

/// Hertz's ellipse for normal force Q > 0 (Johnson 1985, ch. 3 and §4.2; see
/// [`crate::scene::hertz`]).
fn hertz_ellipse(
    normal_force: f64,
    wheel_rolling_radius: f64,
    parameters: &Parameters,
) -> Result<HertzContact, InvalidInput> {
    let curvature = relative_curvature(wheel_rolling_radius, parameters)?;
    let modulus = contact_modulus(parameters.shear_modulus, parameters.poisson_ratio)?;
    HertzContact::solve(normal_force, &curvature, modulus)
}

/// The given ellipse with Hertz's p0 = 3Q/(2πab) (0 for Q ≤ 0); no approach without curvatures.
fn given_ellipse(normal_force: f64, semi_axis_a: f64, semi_axis_b: f64) -> HertzContact {
    let max_pressure = if normal_force > 0.0 {
        (3.0 * normal_force / (2.0 * PI * semi_axis_a) / semi_axis_b).min(f64::MAX)
    } else {
        0.0
    };
    HertzContact { semi_axis_a, semi_axis_b, max_pressure, approach: 0.0 }
}

/// Polach's resulting creepage s_C (eqs. 21, 22): spin counts towards the lateral creepage only
/// where it enlarges it. The slip velocity of his 2005 friction law is s_C times the speed.
fn resulting_creepage(creepages: &Creepages, semi_axis_a: f64) -> f64 {
    let eta_with_spin = creepages.lateral + creepages.spin * semi_axis_a;
    let lateral = if eta_with_spin.abs() > creepages.lateral.abs() { eta_with_spin } else { creepages.lateral };
    magnitude(creepages.longitudinal, lateral)
}

/// The relaxation lengths: the parameter, or (0) the module's default from the contact.
fn relaxation_lengths(contact: &ContactInput, length: f64) -> Result<RelaxationLengths, InvalidInput> {
    if length == 0.0 {
        RelaxationLengths::from_contact(contact.semi_axis_a, contact.semi_axis_b, contact.poisson_ratio)
    } else if length > 0.0 {
        RelaxationLengths::uniform(length)
    } else {
        Err(InvalidInput::new("relaxation_length", length, "must be finite and >= 0 (0: derived from the contact)"))
    }
}

/// The outputs for `values`, or the reason they cannot be computed (names the variable and
/// value). `relaxed_forces` is read and, on success only, advanced (or initialised).
pub(crate) fn compute_outputs(
    values: &Values,
    cache: &mut ModelCache,
    relaxed_forces: &mut RelaxedForces,
    evaluation: Evaluation,
) -> Result<Outputs, String> {
    let plan = cache.plan(&values.parameters)?;
    let (outputs, relaxed) = evaluate(values, &plan, *relaxed_forces, evaluation).map_err(|e| e.to_string())?;
    *relaxed_forces = relaxed;
    Ok(outputs)
}

fn evaluate(
    values: &Values,
    plan: &Plan,
    relaxed_forces: RelaxedForces,
    evaluation: Evaluation,
) -> Result<(Outputs, RelaxedForces), InvalidInput> {
    let Inputs {
        creepage_longitudinal,
        creepage_lateral,
        spin_creepage,
        normal_force,
        semi_axis_a,
        semi_axis_b,
        friction_coefficient,
        rolling_speed,
        wheel_angular_speed,
        wheel_rolling_radius,
        lateral_slip_velocity,
        spin_angular_velocity,
    } = values.inputs;
    let parameters = &values.parameters;
    if !rolling_speed.is_finite() {
        return Err(InvalidInput::new("rolling_speed", rolling_speed, "must be finite"));
    }
    let creepages = if plan.creepages_from_kinematics {
        let kinematics = WheelKinematics {
            rolling_speed,
            wheel_angular_speed,
            wheel_rolling_radius,
            lateral_slip_velocity,
            spin_angular_velocity,
        };
        from_kinematics(&kinematics, parameters.regularisation_speed)?
    } else {
        let speed = rolling_speed.abs();
        Creepages { longitudinal: creepage_longitudinal, lateral: creepage_lateral, spin: spin_creepage, speed }
    };
    // Lift-off with Hertz on: no contact, zero forces, and nothing of Hertz's is computed.
    let hertz_lift_off = plan.hertz_contact && normal_force <= 0.0;
    let ellipse = if hertz_lift_off {
        HertzContact { semi_axis_a: 0.0, semi_axis_b: 0.0, max_pressure: 0.0, approach: 0.0 }
    } else if plan.hertz_contact {
        hertz_ellipse(normal_force, wheel_rolling_radius, parameters)?
    } else {
        given_ellipse(normal_force, semi_axis_a, semi_axis_b)
    };
    let contact = ContactInput {
        creepage_longitudinal: creepages.longitudinal,
        creepage_lateral: creepages.lateral,
        spin_creepage: creepages.spin,
        normal_force,
        // After a Hertzian lift-off any valid ellipse will do: every model checks the other
        // values and returns zero force for Q ≤ 0 before using the ellipse.
        semi_axis_a: if hertz_lift_off { 1.0 } else { ellipse.semi_axis_a },
        semi_axis_b: if hertz_lift_off { 1.0 } else { ellipse.semi_axis_b },
        friction_coefficient,
        shear_modulus: parameters.shear_modulus,
        poisson_ratio: parameters.poisson_ratio,
    };
    let slip_velocity = resulting_creepage(&creepages, ellipse.semi_axis_a) * creepages.speed;
    let (steady, friction) = match (plan.traction, plan.model) {
        (Some(extension), ModelChoice::Polach(polach)) => {
            let model = Polach { large_creepage: Some(LargeCreepage::new(extension, creepages.speed)?), ..polach };
            (model.creep_forces(&contact)?, extension.friction(friction_coefficient, slip_velocity))
        }
        _ => (plan.model.creep_forces(&contact)?, friction_coefficient),
    };
    let (forces, relaxed) = if plan.creep_relaxation {
        relax_forces(
            &contact,
            &steady,
            friction,
            relaxed_forces,
            rolling_speed,
            parameters.relaxation_length,
            evaluation,
        )?
    } else {
        (steady, relaxed_forces)
    };
    let outputs = Outputs {
        force_longitudinal: forces.force_longitudinal,
        force_lateral: forces.force_lateral,
        adhesion_utilisation: forces.adhesion_utilisation,
        spin_moment: forces.spin_moment.unwrap_or(0.0),
        current_friction_coefficient: friction,
        slip_velocity,
        effective_creepage_longitudinal: creepages.longitudinal,
        effective_creepage_lateral: creepages.lateral,
        effective_spin_creepage: creepages.spin,
        contact_semi_axis_a: ellipse.semi_axis_a,
        contact_semi_axis_b: ellipse.semi_axis_b,
        max_pressure: ellipse.max_pressure,
        approach: ellipse.approach,
    };
    Ok((outputs, relaxed))
}

/// The relaxed forces at the end of this evaluation, and the output forces from them: F_x and
/// F_y relaxed, M_z the steady state's, the utilisation against the friction `friction` applied.
fn relax_forces(
    contact: &ContactInput,
    steady: &CreepForces,
    friction: f64,
    relaxed_forces: RelaxedForces,
    rolling_speed: f64,
    relaxation_length: f64,
    evaluation: Evaluation,
) -> Result<(CreepForces, RelaxedForces), InvalidInput> {
    if contact.transmits_no_force() {
        // Lift-off or no friction: the contact holds no elastic deformation to relax.
        return Ok((CreepForces { spin_moment: steady.spin_moment, ..CreepForces::default() }, [0.0; 2]));
    }
    let steady_forces = [steady.force_longitudinal, steady.force_lateral];
    let relaxed = match evaluation {
        Evaluation::Initialise => steady_forces,
        Evaluation::Step(step) => relaxation_lengths(contact, relaxation_length)?.advance(
            relaxed_forces,
            steady_forces,
            rolling_speed,
            step,
        )?,
    };
    let friction_limit = contact.normal_force * friction;
    Ok((CreepForces::new(relaxed[0], relaxed[1], steady.spin_moment, friction_limit), relaxed))
}

/// The core's input for the instance's values with every option off (the creepage and ellipse
/// inputs as given): the default scene of the documentation.
pub fn contact_input(values: &Values) -> ContactInput {
    ContactInput {
        creepage_longitudinal: values.inputs.creepage_longitudinal,
        creepage_lateral: values.inputs.creepage_lateral,
        spin_creepage: values.inputs.spin_creepage,
        normal_force: values.inputs.normal_force,
        semi_axis_a: values.inputs.semi_axis_a,
        semi_axis_b: values.inputs.semi_axis_b,
        friction_coefficient: values.inputs.friction_coefficient,
        shear_modulus: values.parameters.shear_modulus,
        poisson_ratio: values.parameters.poisson_ratio,
    }
}
