//! The FMU's values ↔ the core's [`Scene`] (`contact_geometry = ellipse`) or the core's wheel on
//! its rail ([`crate::profiles`], `contact_geometry = profiles`): decodes the parameters into a
//! typed scene (model choice and options, validated once when a parameter changes, errors naming
//! the FMU's variables and values), the inputs into a `SceneInput`, and the core's outputs into
//! the outputs. The evaluation itself is the core's ([`Scene::evaluate`],
//! [`WheelRailContact::evaluate`](wheel_rail_contact::wheel::WheelRailContact::evaluate)).
//!
//! The parameters and inputs are destructured without `..` (unused fields bound to `_`
//! explicitly) and the outputs built by one struct literal without `..` ([`outputs`]), so a
//! variable added to or removed from `modelDescription.xml` stops the build until it is mapped here.

use std::path::{Path, PathBuf};

use super::model_description::{
    enumeration, Causality, ContactGeometry, Flexibility as FlexibilityChoice, Inputs, Kind, Model, Outputs,
    Parameters, StiffnessSource as StiffnessChoice, Strings, Switch, TractionBound as TractionBoundChoice,
    TractionLaw as TractionLawChoice, Values, Variability, VARIABLES,
};
use super::profiles::{ProfileContact, ProfileDigest, WheelOutputs};
use wheel_rail_contact::geometry::SwitchingFunctions;
use wheel_rail_contact::models::exact::{MAX_ITERATIONS, MAX_PRODUCTS};
use wheel_rail_contact::scene::{
    CreepageSource, EllipseSource, Evaluation, Relaxation, Scene, SceneCache, SceneError, SceneInput, SceneOutput,
    SceneState, TractionLaw,
};
use wheel_rail_contact::wheel::{WheelCache, WheelState};
use wheel_rail_contact::{
    ContactInput, ExactTable, ExactTheory, Fastsim, Flexibility, InvalidInput, MeasuredCurve, ModelChoice, Polach,
    Polach2005, StiffnessSource, TractionBound,
};

/// What the parameters select: one patch from the inputs, or a wheel on its rail from profiles.
#[derive(Debug, Clone)]
enum Contact {
    Ellipse(Scene),
    Profiles(Box<ProfileContact>),
}

/// The contact the parameters select, built (the measured-curve fit, FASTSIM's load
/// normalisation, the profiles read and placed, every check of the parameters) when first
/// needed and again only after [`ContactCache::parameters_changed`] — the instance calls it
/// whenever a parameter is written or an FMU state is set — so a step pays no comparison of the
/// parameters; and the scene's [`SceneCache`] (Polach's shape factors for the last ellipse shape)
/// or the wheel's. Derived data, so not part of the FMU's state (the scene's [`SceneState`] and
/// the wheel's [`WheelState`] are, in the instance's snapshot).
#[derive(Debug, Clone, Default)]
pub struct ContactCache {
    /// The parameters it was built for (checked against the current ones in debug builds: a
    /// missed `parameters_changed` fails every test) and the contact or why there is none.
    built: Option<(Parameters, Strings, Result<Contact, String>)>,
    /// The scene's derived data (Polach's shape factors).
    scene_cache: SceneCache,
    /// The same per patch of the wheel.
    wheel_cache: WheelCache,
    /// The FMU's resources directory, where relative profile paths are looked up first.
    resources: Option<PathBuf>,
    /// The profiles' digest of a restored FMU state: the next build must read the same content.
    expected_profiles: Option<ProfileDigest>,
}

impl ContactCache {
    /// An empty cache whose profiles are looked up in `resources` first (see
    /// [`crate::resources::file_path`]).
    pub fn new(resources: Option<PathBuf>) -> Self {
        Self { resources, ..Self::default() }
    }

    /// Forgets the scene: the next evaluation builds it from the parameters it is given.
    #[inline]
    pub fn parameters_changed(&mut self) {
        self.built = None;
    }

    /// The digest of the profiles built from, if a contact from profiles is built.
    #[inline]
    pub fn profile_digest(&self) -> Option<ProfileDigest> {
        match &self.built {
            Some((_, _, Ok(Contact::Profiles(wheel)))) => Some(wheel.digest()),
            _ => None,
        }
    }

    /// An FMU state computed with profiles of `digest` is restored: a contact built from other
    /// content is rebuilt, and the rebuild must read the same content, else it is an error.
    pub fn restored(&mut self, digest: Option<ProfileDigest>) {
        if digest.is_some() && digest != self.profile_digest() {
            self.built = None;
        }
        self.expected_profiles = digest;
    }

    /// The contact for these parameters, the caches, and whether the contact was built by this
    /// call (after [`ContactCache::parameters_changed`]); the error names the parameter.
    #[inline]
    fn plan(
        &mut self,
        parameters: &Parameters,
        strings: &Strings,
    ) -> Result<(&Contact, &mut SceneCache, &mut WheelCache, bool), String> {
        let rebuilt = self.built.is_none();
        let resources = self.resources.as_deref();
        let expected = &mut self.expected_profiles;
        let (built_for, built_strings, contact) = self.built.get_or_insert_with(|| {
            let saved = expected.take();
            let contact = contact_of(parameters, strings, resources).and_then(|contact| match (&contact, saved) {
                (Contact::Profiles(wheel), Some(saved)) if wheel.digest() != saved => {
                    Err(changed_profiles(wheel.digest(), saved))
                }
                _ => Ok(contact),
            });
            (*parameters, strings.clone(), contact)
        });
        // A NaN parameter never equals itself (`parameters != parameters`): such a scene is an
        // error, reported alike whether cached or rebuilt.
        #[allow(clippy::eq_op)]
        let unchanged_or_nan = (built_for == parameters || parameters != parameters) && built_strings == strings;
        debug_assert!(unchanged_or_nan, "a parameter changed without ContactCache::parameters_changed");
        match contact {
            Ok(contact) => Ok((contact, &mut self.scene_cache, &mut self.wheel_cache, rebuilt)),
            Err(reason) => Err(reason.clone()),
        }
    }
}

/// The error of a restored FMU state whose profile files hold other content than when it was saved.
#[cold]
fn changed_profiles(read: ProfileDigest, saved: ProfileDigest) -> String {
    let changed: Vec<String> = [("wheel_profile", read.wheel, saved.wheel), ("rail_profile", read.rail, saved.rail)]
        .iter()
        .filter(|(_, read, saved)| read != saved)
        .map(|(name, read, saved)| format!("{name} (CRC-32 {read:08x}, the state's {saved:08x})"))
        .collect();
    format!(
        "the restored FMU state was computed with other profiles: the content of {} changed since the state was \
         saved; restore the files, or set the profile parameters again to start from the files as they are",
        changed.join(" and ")
    )
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

/// The core's scene the parameters select, validated; the error names the FMU variable and
/// its value. `resources`: the FMU's resources directory, where `exact_table` reads its table.
pub fn scene_of(parameters: &Parameters, resources: Option<&Path>) -> Result<Scene, String> {
    let Parameters {
        shear_modulus,
        poisson_ratio,
        stiffness_source,
        measured_peak_adhesion,
        measured_creepage_at_peak,
        measured_kinetic_friction,
        creep_force_model,
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
        wheel_profile_curvature,
        rail_profile_curvature,
        creepages_from_kinematics,
        regularisation_speed,
        creep_relaxation,
        relaxation_length,
        // The wheel on its rail's (`contact_of`, `crate::profiles`).
        contact_geometry: _,
        wheel_side: _,
        track_gauge: _,
        gauge_measuring_height: _,
        rail_cant: _,
        flange_back_distance: _,
        flange_back_position: _,
        wheel_nominal_radius: _,
        vertical_contact: _,
        contact_method: _,
        profile_filter_wavelength: _,
    } = *parameters;
    let selected = enumeration("creep_force_model", creep_force_model, Model::from_value, Model::ITEMS)?;
    let stiffness =
        match enumeration("stiffness_source", stiffness_source, StiffnessChoice::from_value, StiffnessChoice::ITEMS)? {
            StiffnessChoice::Kalker => StiffnessSource::Kalker,
            StiffnessChoice::MeasuredCurve => {
                MeasuredCurve::from_peak(measured_peak_adhesion, measured_creepage_at_peak, measured_kinetic_friction)
                    .map(StiffnessSource::MeasuredCurve)
                    .map_err(|e| e.to_string())?
            }
        };
    let traction =
        match enumeration("traction_law", traction_law, TractionLawChoice::from_value, TractionLawChoice::ITEMS)? {
            TractionLawChoice::Coulomb => None,
            TractionLawChoice::Polach2005Dry => Some(Polach2005::DRY),
            TractionLawChoice::Polach2005Wet => Some(Polach2005::WET),
            TractionLawChoice::Polach2005User => Some(
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
        let name = ModelChoice::rung_of_fmu_value(creep_force_model).map_or("?", |rung| rung.name);
        let model_text = format!("creep_force_model = {creep_force_model} ({name})");
        if traction.is_some() {
            return Err(format!(
                "traction_law = {traction_law} is invalid: Polach 2005 needs creep_force_model = 1 (polach), not {model_text}"
            ));
        }
        if stiffness != StiffnessSource::Kalker {
            return Err(format!(
                "stiffness_source = {stiffness_source} is invalid: a measured curve needs creep_force_model = 1 (polach), not {model_text}"
            ));
        }
    }
    // The rungs with FMU parameters of their own are built from them here; every other rung is
    // its registered default (`ModelChoice::RUNGS`).
    let model = match selected {
        Model::Polach => ModelChoice::Polach(Polach { stiffness, large_creepage: None }),
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
        // Not the rung's default model: that is the table compiled into the core, which the
        // FMU's binary leaves out for the one copy in its resources.
        Model::ExactTable => crate::exact_table::table(resources)
            .map(|table| ModelChoice::ExactTable(ExactTable::with_table(table)))
            .map_err(|e| format!("creep_force_model = {creep_force_model} (exact_table): {e}"))?,
        _ => {
            let rung = ModelChoice::rung_of_fmu_value(creep_force_model)
                .expect("the Model enumeration is the registry's (model_description tests)");
            (rung.default_model)()
                .map_err(|e| format!("creep_force_model = {creep_force_model} ({}): {e}", rung.name))?
        }
    };
    Ok(Scene {
        model,
        creepages: if switch("creepages_from_kinematics", creepages_from_kinematics)? {
            CreepageSource::Kinematics { regularisation_speed }
        } else {
            CreepageSource::Inputs
        },
        ellipse: if switch("hertz_contact", hertz_contact)? {
            EllipseSource::Hertz { wheel_profile_curvature, rail_profile_curvature }
        } else {
            EllipseSource::Inputs
        },
        traction_law: traction.map_or(TractionLaw::Coulomb, TractionLaw::Polach2005),
        relaxation: if switch("creep_relaxation", creep_relaxation)? {
            Relaxation::On { length: relaxation_length }
        } else {
            Relaxation::Off
        },
        shear_modulus,
        poisson_ratio,
    })
}

/// The contact the parameters select: the scene, or the wheel on its rail with that scene's
/// model, traction law, relaxation, material and regularisation speed (its creepages always
/// from the wheelset's motion, its ellipses from the profiles).
fn contact_of(parameters: &Parameters, strings: &Strings, resources: Option<&Path>) -> Result<Contact, String> {
    let scene = scene_of(parameters, resources)?;
    let geometry = parameters.contact_geometry;
    Ok(match enumeration("contact_geometry", geometry, ContactGeometry::from_value, ContactGeometry::ITEMS)? {
        ContactGeometry::Ellipse => Contact::Ellipse(scene),
        ContactGeometry::Profiles => {
            let regularisation_speed = parameters.regularisation_speed;
            let scene = Scene { creepages: CreepageSource::Kinematics { regularisation_speed }, ..scene };
            Contact::Profiles(Box::new(ProfileContact::new(parameters, strings, scene, resources)?))
        }
    })
}

/// Evaluates the contact the parameters select at `values` from the states of the last
/// evaluation (`scene` with `ellipse`, `wheel` with `profiles`) and, only if every output it
/// computes is finite, writes the outputs into `values` and the state after this evaluation
/// (advanced or initialised) into the contact's own; on error nothing is changed. `Ok` holds a
/// warning for the master when the outputs are an unconverged exact solve's last iterate; the
/// error names the variable and value. With profiles the wheel's switching functions go to
/// `switching` (one patch has none, and does not pay for them: it leaves them alone).
///
/// The one-patch path is the hot path of a co-simulation step: it writes the patch's outputs in
/// place (the wheel's stay zero) and moves no state it does not advance.
pub(crate) fn update_outputs(
    values: &mut Values,
    strings: &Strings,
    cache: &mut ContactCache,
    scene_state: &mut SceneState,
    wheel_state: &mut WheelState,
    switching: &mut SwitchingFunctions,
    evaluation: Evaluation,
) -> Result<Option<String>, String> {
    let (contact, scene_cache, wheel_cache, rebuilt) = cache.plan(&values.parameters, strings)?;
    match contact {
        Contact::Ellipse(scene) => {
            let (output, next_state) = scene
                .evaluate(&scene_input(&values.inputs), scene_state, scene_cache, evaluation)
                .map_err(|e| e.to_string())?;
            if !patch_outputs_finite(&output) {
                return Err(non_finite(&outputs(&output, &WheelOutputs::default())));
            }
            if rebuilt {
                // The last outputs may be a wheel's, of the contact the parameters selected before.
                values.outputs = outputs(&SceneOutput::default(), &WheelOutputs::default());
            }
            write_patch_outputs(&mut values.outputs, &output);
            [values.locals.der_relaxed_force_longitudinal, values.locals.der_relaxed_force_lateral] =
                output.relaxation_rate.map(|rate| rate + 0.0);
            *scene_state = next_state;
            Ok(unconverged_warning(&output))
        }
        Contact::Profiles(wheel) => {
            let input = wheel.input(&values.inputs);
            let (output, next_state) = wheel
                .contact()
                .evaluate(&input, wheel_state, wheel_cache, evaluation)
                .map_err(|e| wheel.describe(e))?;
            let warning = output.patches.iter().find_map(|patch| unconverged_warning(&patch.output));
            let outputs = outputs(&SceneOutput::default(), &WheelOutputs::of(&output));
            finite(&outputs)?;
            values.outputs = outputs;
            // The patches' relaxed forces are in the wheel's state, not continuous states.
            [values.locals.der_relaxed_force_longitudinal, values.locals.der_relaxed_force_lateral] = [0.0; 2];
            *wheel_state = next_state;
            *switching = output.switching;
            Ok(warning)
        }
    }
}

/// Whether every value is finite. Each value is tested on its own and the answers combined by a
/// bitwise and: no value waits for another (a running sum of x·0 made one chain of dependent
/// additions, 13 additions' latency at the end of every step).
#[inline]
fn all_finite(reals: &[f64]) -> bool {
    reals.iter().fold(true, |all, x| all & x.is_finite())
}

/// Whether every output of one patch is finite.
#[inline]
fn patch_outputs_finite(scene: &SceneOutput) -> bool {
    let SceneOutput {
        force_longitudinal,
        force_lateral,
        adhesion_utilisation,
        spin_moment,
        current_friction_coefficient,
        slip_velocity,
        effective_creepage_longitudinal,
        effective_creepage_lateral,
        effective_spin_creepage,
        contact_semi_axis_a,
        contact_semi_axis_b,
        max_pressure,
        approach,
        relaxation_rate: [rate_longitudinal, rate_lateral],
        unconverged_grid: _,
    } = *scene;
    all_finite(&[
        force_longitudinal,
        force_lateral,
        adhesion_utilisation,
        spin_moment,
        current_friction_coefficient,
        slip_velocity,
        effective_creepage_longitudinal,
        effective_creepage_lateral,
        effective_spin_creepage,
        contact_semi_axis_a,
        contact_semi_axis_b,
        max_pressure,
        approach,
        rate_longitudinal,
        rate_lateral,
    ])
}

/// Every output finite, or why not: the last guard of "never NaN or Inf out", for finite
/// inputs so large that a model's arithmetic overflows. A few compares on the hot path; the
/// message is built only on failure.
pub(crate) fn finite(outputs: &Outputs) -> Result<(), String> {
    if all_finite(&outputs.reals()) {
        Ok(())
    } else {
        Err(non_finite(outputs))
    }
}

/// The message of outputs of which one is not finite.
#[cold]
fn non_finite(outputs: &Outputs) -> String {
    let overflowing: Vec<String> = Outputs::NAMES
        .iter()
        .zip(outputs.reals())
        .filter(|(_, x)| !x.is_finite())
        .map(|(name, x)| format!("{name} = {x}"))
        .collect();
    format!(
        "{} for these values: an input or parameter is too large for the model's floating-point range",
        overflowing.join(", ")
    )
}

/// The master's warning when `output` is an exact solve that stopped at its limits.
fn unconverged_warning(output: &SceneOutput) -> Option<String> {
    output.unconverged_grid.map(|grid| {
        let (length, width) = grid.element_sides(output.contact_semi_axis_a, output.contact_semi_axis_b);
        format!(
            "creep_force_model = {} (exact): the exact theory did not converge on exact_elements_longitudinal × \
             exact_elements_lateral = {} × {} elements ({:.3} mm long × {:.3} mm wide) within its limits \
             ({MAX_ITERATIONS} Newton steps, {MAX_PRODUCTS} operator products); the outputs are its last \
             iterate, which can be off by several percent of μQ: elements closer to square, or \
             creep_force_model = {} (exact_table), avoid it",
            Model::Exact as i32,
            grid.longitudinal,
            grid.lateral,
            length * 1e3,
            width * 1e3,
            Model::ExactTable as i32,
        )
    })
}

/// d(outputs) along `direction` (one rate per continuous input) at the current `values` — of
/// the outputs at these inputs, never of the last step's — or why not (an option without
/// derivatives, an invalid value, naming the variable). One patch: the core's
/// [`Scene::directional_derivative`] (exact). A wheel from profiles: [`profile_derivative`].
pub(crate) fn directional_derivative(
    values: &Values,
    strings: &Strings,
    cache: &mut ContactCache,
    wheel_state: &WheelState,
    direction: &Inputs,
) -> Result<Outputs, String> {
    match cache.plan(&values.parameters, strings)? {
        (Contact::Ellipse(scene), ..) => {
            let rates = scene
                .directional_derivative(&scene_input(&values.inputs), &scene_input(direction))
                .map_err(|e: SceneError| e.to_string())?;
            Ok(outputs(&rates, &WheelOutputs::default()))
        }
        (Contact::Profiles(wheel), _, wheel_cache, _) => {
            profile_derivative(wheel, wheel_cache, &values.inputs, wheel_state, direction)
        }
    }
}

/// How far [`profile_derivative`] moves an input of this unit: 10 µm, 10 µrad, 10 µm/s or µrad/s,
/// 1e-5 of μ, 10 N of load. Measured on the tread (S1002/UIC60, y_ws = 2 mm, Polach): the wheel's
/// forces carry some 1e-4 N of rounding from the contact search and the vertical balance, so
/// that ∂F_x/∂y_ws by central differences scatters by 60 % at 1 nm, 1.6 % at 10 nm and 0.07 %
/// at 1 µm, and agrees to 0.006 % between 1 and 10 µm: at 10 µm that rounding is some 1e-5 of
/// the difference, and the creepage moves by a few 1e-6, where the creep-force curve is nearly
/// straight.
fn derivative_step(unit: &str) -> f64 {
    match unit {
        "N" => 10.0,
        _ => 1e-5,
    }
}

/// d(outputs) of a wheel from profiles along `direction`, by central differences of the core's
/// wheel evaluated at the inputs moved by ±t·direction (t from [`derivative_step`]; each
/// evaluation a zero-length step from the wheel's current state, as a feedthrough read, the
/// state itself untouched): the geometry's contact search and vertical balance have no
/// derivative of their own. Where the patches change between the two sides (a flange that
/// comes into contact) the difference is taken one-sided, on the side with the patches of the
/// inputs themselves, as the one-patch mode gives its folds.
fn profile_derivative(
    wheel: &ProfileContact,
    cache: &mut WheelCache,
    inputs: &Inputs,
    state: &WheelState,
    direction: &Inputs,
) -> Result<Outputs, String> {
    let direction = Values { inputs: *direction, ..Values::default() };
    // Each continuous Real input with its rate, and that rate over its unit's step.
    let continuous: Vec<(u32, f64, f64)> = VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Input && v.variability == Variability::Continuous)
        .filter(|v| matches!(v.kind, Kind::Real { .. }))
        .filter_map(|v| {
            let rate = direction.real(v.value_reference)?;
            Some((v.value_reference, rate, rate / derivative_step(v.unit.unwrap_or(""))))
        })
        .collect();
    let largest = continuous.iter().fold(0.0f64, |m, (_, _, relative)| m.max(relative.abs()));
    if largest == 0.0 {
        return Ok(outputs(&SceneOutput::default(), &WheelOutputs::default()));
    }
    // No input moves by more than its step.
    let t = 1.0 / largest;
    let mut at = |multiple: f64| -> Result<(Outputs, usize), String> {
        let mut moved = Values { inputs: *inputs, ..Values::default() };
        for &(value_reference, rate, _) in &continuous {
            if let Some(value) = moved.real_mut(value_reference) {
                *value += multiple * t * rate;
            }
        }
        let input = wheel.input(&moved.inputs);
        let (output, _) =
            wheel.contact().evaluate(&input, state, cache, Evaluation::Step(0.0)).map_err(|e| wheel.describe(e))?;
        Ok((outputs(&SceneOutput::default(), &WheelOutputs::of(&output)), output.patches.len()))
    };
    let ((ahead, ahead_patches), (behind, behind_patches)) = (at(1.0)?, at(-1.0)?);
    let (high, low, span) = if ahead_patches == behind_patches {
        (ahead, behind, 2.0 * t)
    } else {
        let (here, here_patches) = at(0.0)?;
        if ahead_patches == here_patches {
            (ahead, here, t)
        } else {
            (here, behind, t)
        }
    };
    let (high, low) = (Values { outputs: high, ..Values::default() }, Values { outputs: low, ..Values::default() });
    let mut rates = Values::default();
    for output in VARIABLES.iter().filter(|v| v.causality == Causality::Output) {
        let r = output.value_reference;
        if let (Some(h), Some(l), Some(slot)) = (high.real(r), low.real(r), rates.real_mut(r)) {
            *slot = (h - l) / span;
        }
    }
    Ok(rates.outputs)
}

/// The core's input for the instance's values with every option off (the creepage and ellipse
/// inputs as given): the default scene of the documentation.
pub fn contact_input(values: &Values) -> ContactInput {
    let parameters = &values.parameters;
    Scene::of_model(ModelChoice::Polach(Polach::default()), parameters.shear_modulus, parameters.poisson_ratio)
        .contact_input(&scene_input(&values.inputs))
}

/// The inputs as the core's scene input: each of its fields is the input of the same name, listed
/// once; the wheelset's inputs (profiles only) are bound to `_`, so an input added to
/// `modelDescription.xml` stops the build here until it is mapped.
pub fn scene_input(inputs: &Inputs) -> SceneInput {
    macro_rules! scene_input_of {
        ($($field:ident),*; unused: $($unused:ident),*) => {{
            let Inputs { $($field,)* $($unused: _,)* } = *inputs;
            SceneInput { $($field),* }
        }};
    }
    scene_input_of!(
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
        spin_angular_velocity;
        unused: wheelset_lateral_displacement,
        wheelset_vertical_position,
        wheelset_roll_angle,
        wheelset_yaw_angle,
        vertical_force,
        wheelset_lateral_velocity,
        wheelset_yaw_rate
    )
}

/// The outputs from one patch's scene output and a wheel's outputs (the one not computed all
/// zero), every zero written as +0 (`x + 0.0` changes nothing else; masters print −0 as `-0`).
pub fn outputs(scene: &SceneOutput, wheel: &WheelOutputs) -> Outputs {
    let [patch1, patch2] = &wheel.patches;
    let mut outputs = Outputs {
        force_longitudinal: 0.0,
        force_lateral: 0.0,
        adhesion_utilisation: 0.0,
        spin_moment: 0.0,
        current_friction_coefficient: 0.0,
        slip_velocity: 0.0,
        effective_creepage_longitudinal: 0.0,
        effective_creepage_lateral: 0.0,
        effective_spin_creepage: 0.0,
        contact_semi_axis_a: 0.0,
        contact_semi_axis_b: 0.0,
        max_pressure: 0.0,
        approach: 0.0,
        track_force_x: wheel.track_force[0] + 0.0,
        track_force_y: wheel.track_force[1] + 0.0,
        track_force_z: wheel.track_force[2] + 0.0,
        track_moment_x: wheel.track_moment[0] + 0.0,
        track_moment_y: wheel.track_moment[1] + 0.0,
        track_moment_z: wheel.track_moment[2] + 0.0,
        contact_patch_count: wheel.contact_patch_count,
        wheelset_vertical_position_solved: wheel.wheelset_vertical_position_solved + 0.0,
        patch1_contact_angle: patch1.contact_angle + 0.0,
        patch1_rail_lateral_position: patch1.rail_lateral_position + 0.0,
        patch1_rolling_radius: patch1.rolling_radius + 0.0,
        patch1_normal_force: patch1.normal_force + 0.0,
        patch1_force_longitudinal: patch1.force_longitudinal + 0.0,
        patch1_force_lateral: patch1.force_lateral + 0.0,
        patch1_creepage_longitudinal: patch1.creepage_longitudinal + 0.0,
        patch1_creepage_lateral: patch1.creepage_lateral + 0.0,
        patch1_spin_creepage: patch1.spin_creepage + 0.0,
        patch1_semi_axis_a: patch1.semi_axis_a + 0.0,
        patch1_semi_axis_b: patch1.semi_axis_b + 0.0,
        patch2_contact_angle: patch2.contact_angle + 0.0,
        patch2_rail_lateral_position: patch2.rail_lateral_position + 0.0,
        patch2_rolling_radius: patch2.rolling_radius + 0.0,
        patch2_normal_force: patch2.normal_force + 0.0,
        patch2_force_longitudinal: patch2.force_longitudinal + 0.0,
        patch2_force_lateral: patch2.force_lateral + 0.0,
        patch2_creepage_longitudinal: patch2.creepage_longitudinal + 0.0,
        patch2_creepage_lateral: patch2.creepage_lateral + 0.0,
        patch2_spin_creepage: patch2.spin_creepage + 0.0,
        patch2_semi_axis_a: patch2.semi_axis_a + 0.0,
        patch2_semi_axis_b: patch2.semi_axis_b + 0.0,
    };
    write_patch_outputs(&mut outputs, scene);
    outputs
}

/// Writes one patch's outputs (the scene's) into `outputs`, every zero as +0; the wheel's
/// outputs are left as they are.
#[inline]
fn write_patch_outputs(outputs: &mut Outputs, scene: &SceneOutput) {
    outputs.force_longitudinal = scene.force_longitudinal + 0.0;
    outputs.force_lateral = scene.force_lateral + 0.0;
    outputs.adhesion_utilisation = scene.adhesion_utilisation + 0.0;
    outputs.spin_moment = scene.spin_moment + 0.0;
    outputs.current_friction_coefficient = scene.current_friction_coefficient + 0.0;
    outputs.slip_velocity = scene.slip_velocity + 0.0;
    outputs.effective_creepage_longitudinal = scene.effective_creepage_longitudinal + 0.0;
    outputs.effective_creepage_lateral = scene.effective_creepage_lateral + 0.0;
    outputs.effective_spin_creepage = scene.effective_spin_creepage + 0.0;
    outputs.contact_semi_axis_a = scene.contact_semi_axis_a + 0.0;
    outputs.contact_semi_axis_b = scene.contact_semi_axis_b + 0.0;
    outputs.max_pressure = scene.max_pressure + 0.0;
    outputs.approach = scene.approach + 0.0;
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::model_description::{
        value_reference as vr, Causality, ContactMethod as MethodChoice, TractionLaw,
        VerticalContact as VerticalChoice, VARIABLES,
    };
    use wheel_rail_contact::hertz::{contact_modulus, HertzContact, RelativeCurvature};
    use wheel_rail_contact::scene::kinematics::WheelKinematics;
    use wheel_rail_contact::scene::kinematics::DEFAULT_REGULARISATION_SPEED;
    use wheel_rail_contact::scene::relaxation::RelaxationLengths;
    use wheel_rail_contact::{CreepForceModel, LargeCreepage};

    /// Every zero an output carries is written as +0 (masters print −0 as `-0`): a scene's and a
    /// wheel's outputs that are all −0 come out all +0, field by field.
    #[test]
    fn every_zero_output_is_written_as_positive_zero() {
        let z = -0.0;
        let scene = SceneOutput {
            force_longitudinal: z,
            force_lateral: z,
            adhesion_utilisation: z,
            spin_moment: z,
            current_friction_coefficient: z,
            slip_velocity: z,
            effective_creepage_longitudinal: z,
            effective_creepage_lateral: z,
            effective_spin_creepage: z,
            contact_semi_axis_a: z,
            contact_semi_axis_b: z,
            max_pressure: z,
            approach: z,
            ..SceneOutput::default()
        };
        let patch = crate::profiles::PatchOutputs {
            contact_angle: z,
            rail_lateral_position: z,
            rolling_radius: z,
            normal_force: z,
            force_longitudinal: z,
            force_lateral: z,
            creepage_longitudinal: z,
            creepage_lateral: z,
            spin_creepage: z,
            semi_axis_a: z,
            semi_axis_b: z,
        };
        // (A patch count is a whole number, never −0.)
        let wheel = WheelOutputs {
            track_force: [z; 3],
            track_moment: [z; 3],
            contact_patch_count: 0.0,
            wheelset_vertical_position_solved: z,
            patches: [patch; 2],
        };
        let written = super::outputs(&scene, &wheel).reals();
        for (name, value) in Outputs::NAMES.iter().zip(written) {
            assert!(value == 0.0 && value.is_sign_positive(), "{name} = {value:?}");
        }
    }

    /// The repository's `data/`, which holds `exact_table.bin` as the FMU's `resources/` does.
    const TEST_RESOURCES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data");

    fn test_cache() -> ContactCache {
        ContactCache::new(Some(PathBuf::from(TEST_RESOURCES)))
    }

    /// A rung's model with its default parameters, `exact_table`'s from the test resources.
    fn default_model(rung: &wheel_rail_contact::models::rung::Rung) -> ModelChoice {
        match Model::from_value(rung.fmu_value).unwrap() {
            Model::ExactTable => ModelChoice::ExactTable(ExactTable::with_table(
                crate::exact_table::table(Some(Path::new(TEST_RESOURCES))).unwrap(),
            )),
            _ => (rung.default_model)().unwrap(),
        }
    }

    fn outputs_of(values: &Values) -> Result<Outputs, String> {
        evaluate_relaxed(values, &mut test_cache(), &mut [0.0; 2], Evaluation::Initialise)
    }

    /// [`update_outputs`] from a state of these relaxed forces (and no model memory), which
    /// advance on success.
    fn evaluate_relaxed(
        values: &Values,
        cache: &mut ContactCache,
        relaxed_forces: &mut [f64; 2],
        evaluation: Evaluation,
    ) -> Result<Outputs, String> {
        let mut state = SceneState::with_relaxed_forces(*relaxed_forces);
        let mut values = *values;
        let strings = Strings::default();
        let mut switching = SwitchingFunctions::default();
        update_outputs(
            &mut values,
            &strings,
            cache,
            &mut state,
            &mut WheelState::default(),
            &mut switching,
            evaluation,
        )?;
        *relaxed_forces = state.relaxed_forces;
        Ok(values.outputs)
    }

    fn outputs(values: &Values) -> Outputs {
        outputs_of(values).unwrap()
    }

    fn on() -> i32 {
        Switch::On as i32
    }

    /// A scene where every input matters: combined creepages with spin, and kinematics that give
    /// similar creepages.
    fn rich_scene() -> Values {
        let mut values = Values::default();
        values.inputs.creepage_lateral = 0.4e-3;
        values.inputs.spin_creepage = 0.3;
        values.inputs.lateral_slip_velocity = 0.008;
        values.inputs.spin_angular_velocity = 6.0;
        // A wheelset at the Manchester benchmark's case 11 (5 mm right, where tread and
        // flange both carry 10 kN), yawing, moving sideways, about that load's vertical position.
        values.inputs.wheelset_lateral_displacement = 5e-3;
        values.inputs.wheelset_yaw_angle = 0.012;
        values.inputs.wheelset_roll_angle = -3.554e-4;
        values.inputs.wheelset_vertical_position = 1e-5;
        values.inputs.wheelset_lateral_velocity = 0.05;
        values.inputs.wheelset_yaw_rate = 0.02;
        values
    }

    /// The `creep_force_model` enumeration of `modelDescription.xml` is the core's list of rungs:
    /// the same names with the same values, in the same order.
    #[test]
    fn the_model_enumeration_is_the_registry_of_rungs() {
        let registered: Vec<(&str, i32)> = ModelChoice::RUNGS.iter().map(|rung| (rung.name, rung.fmu_value)).collect();
        let declared: Vec<(&str, i32)> = Model::ITEMS.iter().map(|&(name, value, _)| (name, value)).collect();
        assert_eq!(declared, registered);
    }

    /// With the start values, each choice of `creep_force_model` is its rung's default model.
    #[test]
    fn each_model_choice_at_the_start_values_is_its_rungs_default() {
        for rung in ModelChoice::RUNGS {
            let mut parameters = Values::default().parameters;
            parameters.creep_force_model = rung.fmu_value;
            let scene = scene_of(&parameters, Some(Path::new(TEST_RESOURCES))).unwrap();
            assert_eq!(scene.model, default_model(rung), "{}", rung.name);
        }
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
        assert_eq!(contact_input(&values), input);
        let expected = Polach::default().creep_forces(&input).unwrap();
        let outputs = outputs(&values);
        assert_eq!(outputs.force_longitudinal, expected.force_longitudinal);
        assert_eq!(outputs.force_lateral, 0.0);
        assert_eq!(outputs.adhesion_utilisation, expected.adhesion_utilisation);
        assert_eq!(outputs.spin_moment, 0.0, "Polach has no spin moment");
        // A loaded wheel with a small creepage: braking force, partly saturated, well below μQ.
        assert!(outputs.force_longitudinal < -5e3 && outputs.adhesion_utilisation < 0.9, "{outputs:?}");
        // The echoes: creepages and ellipse as given, p0 = 3Q/(2πab), μ as given, w = ξ|V|.
        assert_eq!(outputs.effective_creepage_longitudinal, 1e-3);
        assert_eq!((outputs.contact_semi_axis_a, outputs.contact_semi_axis_b), (7.2e-3, 5.4e-3));
        // To rounding of the order of the operations.
        let p0 = 3.0 * 100e3 / (2.0 * PI * 7.2e-3) / 5.4e-3;
        assert!((outputs.max_pressure - p0).abs() <= 4.0 * f64::EPSILON * p0, "{} against {p0}", outputs.max_pressure);
        assert_eq!((outputs.approach, outputs.current_friction_coefficient), (0.0, 0.3));
        assert!((outputs.slip_velocity - 1e-3 * 20.0).abs() < 1e-18);
    }

    /// With every option off, the Polach path gives exactly the forces of the core's plain
    /// `Polach::default()`, as before the options existed.
    #[test]
    fn polach_with_options_off_is_bit_identical_to_plain_polach() {
        let mut cases = 0;
        for xi in [-2e-2, -1e-3, 0.0, 3e-4, 5e-3] {
            for eta in [-1e-3, 0.0, 2e-3] {
                for phi in [-0.5, 0.0, 1.2] {
                    for (q, a, b, mu) in
                        [(100e3, 7.2e-3, 5.4e-3, 0.3), (40e3, 3e-3, 9e-3, 0.45), (-5.0, 7e-3, 5e-3, 0.3)]
                    {
                        let mut values = Values::default();
                        let inputs = &mut values.inputs;
                        (inputs.creepage_longitudinal, inputs.creepage_lateral, inputs.spin_creepage) = (xi, eta, phi);
                        (inputs.normal_force, inputs.semi_axis_a, inputs.semi_axis_b) = (q, a, b);
                        inputs.friction_coefficient = mu;
                        let expected = Polach::default().creep_forces(&contact_input(&values)).unwrap();
                        let outputs = outputs(&values);
                        // Bit for bit, but a zero is always +0 in the outputs.
                        let bits = |x: f64| (x + 0.0).to_bits();
                        assert_eq!(outputs.force_longitudinal.to_bits(), bits(expected.force_longitudinal));
                        assert_eq!(outputs.force_lateral.to_bits(), bits(expected.force_lateral));
                        assert_eq!(outputs.adhesion_utilisation.to_bits(), bits(expected.adhesion_utilisation));
                        for output in [outputs.force_longitudinal, outputs.force_lateral, outputs.spin_moment] {
                            assert!(output != 0.0 || output.is_sign_positive(), "−0 in {outputs:?}");
                        }
                        cases += 1;
                    }
                }
            }
        }
        assert_eq!(cases, 135);
    }

    /// Every `model` item evaluates the core's model with the grid and options of the parameters.
    #[test]
    fn every_model_is_the_cores_model() {
        let mut values = rich_scene();
        values.parameters.fastsim_strips = 7;
        values.parameters.fastsim_elements = 9;
        values.parameters.fastsim_traction_bound = TractionBoundChoice::Elliptic as i32;
        values.parameters.fastsim_flexibility = FlexibilityChoice::SingleWeighted as i32;
        values.parameters.exact_elements_longitudinal = 12;
        values.parameters.exact_elements_lateral = 10;
        let input = contact_input(&values);
        // The rungs with parameters of their own at the parameters above, every other at its default.
        for rung in ModelChoice::RUNGS {
            let model = match Model::from_value(rung.fmu_value).unwrap() {
                Model::Fastsim => ModelChoice::Fastsim(
                    Fastsim::new(7, 9, TractionBound::Elliptic, Flexibility::SingleWeighted).unwrap(),
                ),
                Model::Exact => ModelChoice::Exact(ExactTheory::new(12, 10)),
                _ => default_model(rung),
            };
            values.parameters.creep_force_model = rung.fmu_value;
            let expected = model.creep_forces(&input).unwrap();
            let outputs = outputs(&values);
            let name = rung.name;
            assert_eq!(outputs.force_longitudinal, expected.force_longitudinal, "{name}");
            assert_eq!(outputs.force_lateral, expected.force_lateral, "{name}");
            assert_eq!(outputs.adhesion_utilisation, expected.adhesion_utilisation, "{name}");
            assert_eq!(outputs.spin_moment, expected.spin_moment.unwrap_or(0.0), "{name}");
            // A rung with a spin moment opposes the spin (φ > 0 → M_z < 0 here); the others give 0.
            if rung.spin_moment {
                assert!(outputs.spin_moment < 0.0, "{name}: {}", outputs.spin_moment);
            } else {
                assert_eq!(outputs.spin_moment, 0.0, "{name}");
            }
        }
    }

    #[test]
    fn invalid_parameters_are_named_with_their_value() {
        use Model::{Exact, Fastsim as FastsimModel, KalkerLinear as Linear, Polach as PolachModel};
        use TractionLaw::{Coulomb, Polach2005Dry as Dry, Polach2005User as User};
        type Change = fn(&mut Parameters);
        let cases: [(Model, TractionLaw, Change, &str); 14] = [
            (PolachModel, Coulomb, |p| p.creep_force_model = 9, "creep_force_model = 9 is invalid: must be one of 1 (polach), 2 (kalker_linear), 3 (shen_hedrick_elkins), 4 (fastsim), 5 (exact), 6 (exact_table)"),
            (PolachModel, Coulomb, |p| p.stiffness_source = 7, "stiffness_source = 7 is invalid: must be one of 1 (kalker), 2 (measured_curve)"),
            (PolachModel, Coulomb, |p| p.hertz_contact = 2, "hertz_contact = 2 is invalid: must be one of 0 (off), 1 (on)"),
            (PolachModel, Coulomb, |p| p.creepages_from_kinematics = -1, "creepages_from_kinematics = -1 is invalid: must be one of 0 (off), 1 (on)"),
            (PolachModel, User, |p| p.adhesion_reduction_factor = 0.0, "adhesion_reduction_factor = 0 is invalid: k_A must lie in (0, 1]"),
            (PolachModel, User, |p| p.slip_reduction_factor = 1.5, "slip_reduction_factor = 1.5 is invalid: k_S must lie in (0, k_A]"),
            (PolachModel, User, |p| p.friction_decay_rate = f64::NAN, "friction_decay_rate = NaN is invalid: B must be finite and >= 0 [s/m]"),
            (FastsimModel, Dry, |_| {}, "traction_law = 2 is invalid: Polach 2005 needs creep_force_model = 1 (polach), not creep_force_model = 4 (fastsim)"),
            (Linear, Coulomb, |p| p.stiffness_source = 2, "stiffness_source = 2 is invalid: a measured curve needs creep_force_model = 1 (polach), not creep_force_model = 2 (kalker_linear)"),
            (FastsimModel, Coulomb, |p| p.fastsim_strips = 0, "fastsim_strips = 0 is invalid: must be an integer in 1..=10000"),
            (FastsimModel, Coulomb, |p| p.fastsim_elements = -3, "fastsim_elements = -3 is invalid: must be an integer in 1..=10000"),
            (FastsimModel, Coulomb, |p| p.fastsim_flexibility = 0, "fastsim_flexibility = 0 is invalid: must be one of 1 (three_blended), 2 (three), 3 (single_weighted)"),
            (Exact, Coulomb, |p| p.exact_elements_longitudinal = 0, "exact_elements_longitudinal = 0 is invalid: must lie in [1, 400]"),
            (Exact, Coulomb, |p| p.exact_elements_lateral = 401, "exact_elements_lateral = 401 is invalid: must lie in [1, 400]"),
        ];
        for (model, law, change, expected) in cases {
            let mut values = Values::default();
            (values.parameters.creep_force_model, values.parameters.traction_law) = (model as i32, law as i32);
            change(&mut values.parameters);
            assert_eq!(outputs_of(&values).unwrap_err(), expected);
        }
    }

    /// Parameters and inputs of an option that is off are not used, so not checked.
    #[test]
    fn options_that_are_off_check_nothing_of_theirs() {
        let mut values = Values::default();
        values.parameters.adhesion_reduction_factor = -1.0;
        values.parameters.fastsim_strips = 0;
        values.parameters.exact_elements_lateral = 0;
        values.parameters.regularisation_speed = -1.0;
        values.parameters.wheel_profile_curvature = f64::NAN;
        values.parameters.relaxation_length = -1.0;
        values.inputs.wheel_angular_speed = f64::NAN;
        values.inputs.wheel_rolling_radius = 0.0;
        assert_eq!(outputs(&values), outputs(&Values::default()));
    }

    #[test]
    fn invalid_option_values_are_named_with_their_value() {
        type Change = fn(&mut Values);
        let cases: [(Change, &str); 8] = [
            (|v| v.inputs.rolling_speed = f64::INFINITY, "rolling_speed = inf is invalid: must be finite"),
            (
                |v| {
                    v.parameters.creepages_from_kinematics = on();
                    v.parameters.regularisation_speed = -0.01;
                },
                "regularisation_speed = -0.01 is invalid: must be finite and > 0",
            ),
            (
                |v| {
                    v.parameters.creepages_from_kinematics = on();
                    v.inputs.spin_angular_velocity = f64::NAN;
                },
                "spin_angular_velocity = NaN is invalid: must be finite",
            ),
            (
                |v| {
                    v.parameters.hertz_contact = on();
                    v.inputs.wheel_rolling_radius = 0.0;
                },
                "wheel_rolling_radius = 0 is invalid: must be finite and > 0",
            ),
            (
                |v| {
                    v.parameters.hertz_contact = on();
                    v.parameters.rail_profile_curvature = f64::INFINITY;
                },
                "rail_profile_curvature = inf is invalid: must be finite",
            ),
            (
                |v| {
                    // A hollow wheel more curved than the rail head: a conformal, non-Hertzian contact.
                    v.parameters.hertz_contact = on();
                    v.parameters.wheel_profile_curvature = -5.0;
                },
                "wheel_profile_curvature = -5 is invalid with rail_profile_curvature = 3.3333333333333335: gives no \
                 contact ellipse: a concave wheel profile must be flatter than the rail head \
                 (wheel_profile_curvature + rail_profile_curvature > 0), otherwise the contact is conformal, outside \
                 Hertz's theory",
            ),
            (
                |v| {
                    v.parameters.hertz_contact = on();
                    v.parameters.poisson_ratio = 0.7;
                },
                "poisson_ratio = 0.7 is invalid: must lie in [0, 0.5]",
            ),
            (
                |v| {
                    v.parameters.creep_relaxation = on();
                    v.parameters.relaxation_length = -0.01;
                },
                "relaxation_length = -0.01 is invalid: must be finite and >= 0 (0: derived from the contact)",
            ),
        ];
        for (change, expected) in cases {
            let mut values = Values::default();
            change(&mut values);
            let mut cache = test_cache();
            let mut relaxed = [1.0, 2.0];
            let result = evaluate_relaxed(&values, &mut cache, &mut relaxed, Evaluation::Step(1e-3));
            assert_eq!(result.unwrap_err(), expected);
            assert_eq!(relaxed, [1.0, 2.0], "the state is kept on an error");
        }
    }

    #[test]
    fn hertz_contact_replaces_the_ellipse_inputs() {
        let mut values = rich_scene();
        values.parameters.hertz_contact = on();
        (values.inputs.semi_axis_a, values.inputs.semi_axis_b) = (f64::NAN, -1.0); // ignored
        let outputs = outputs(&values);
        // A conical tread (straight) on a 300 mm rail crown, r = 0.46 m: A = 1/(2r), B = 1/(2·0.3 m).
        let curvature = RelativeCurvature::from_radii(0.46, f64::INFINITY, 0.3).unwrap();
        let hertz = HertzContact::solve(100e3, &curvature, contact_modulus(82e9, 0.28).unwrap()).unwrap();
        assert_eq!(outputs.contact_semi_axis_a, hertz.semi_axis_a);
        assert_eq!(outputs.contact_semi_axis_b, hertz.semi_axis_b);
        assert_eq!((outputs.max_pressure, outputs.approach), (hertz.max_pressure, hertz.approach));
        // The default scene's a = 7.2 mm, b = 5.4 mm are this contact's, to the 0.1 mm given.
        assert!((hertz.semi_axis_a - 7.2e-3).abs() < 1e-4 && (hertz.semi_axis_b - 5.4e-3).abs() < 1e-4, "{hertz:?}");
        let input =
            ContactInput { semi_axis_a: hertz.semi_axis_a, semi_axis_b: hertz.semi_axis_b, ..contact_input(&values) };
        let expected = Polach::default().creep_forces(&input).unwrap();
        assert_eq!(
            (outputs.force_longitudinal, outputs.force_lateral),
            (expected.force_longitudinal, expected.force_lateral)
        );
        // Lift-off: zero forces and no contact, no error.
        values.inputs.normal_force = -10.0;
        let lifted = super::tests::outputs(&values);
        assert_eq!([lifted.force_longitudinal, lifted.force_lateral, lifted.adhesion_utilisation], [0.0; 3]);
        assert_eq!(
            [lifted.contact_semi_axis_a, lifted.contact_semi_axis_b, lifted.max_pressure, lifted.approach],
            [0.0; 4]
        );
    }

    #[test]
    fn creepages_from_kinematics_replace_the_creepage_inputs() {
        let mut values = rich_scene();
        values.parameters.creepages_from_kinematics = on();
        values.inputs.creepage_longitudinal = f64::NAN; // ignored
        let kinematics = WheelKinematics {
            rolling_speed: 20.0,
            wheel_angular_speed: values.inputs.wheel_angular_speed,
            wheel_rolling_radius: 0.46,
            lateral_slip_velocity: 0.008,
            spin_angular_velocity: 6.0,
        };
        let creepages = kinematics.creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
        let outputs = outputs(&values);
        assert_eq!(outputs.effective_creepage_longitudinal, creepages.longitudinal);
        assert_eq!(outputs.effective_creepage_lateral, creepages.lateral);
        assert_eq!(outputs.effective_spin_creepage, creepages.spin);
        // The start values roll purely (ω r = V: ξ = 0 to rounding), with η = 0.4e-3 and
        // φ ≈ 0.3 /m from the slip velocities.
        assert!(creepages.longitudinal.abs() < 1e-15, "{creepages:?}");
        assert!((creepages.lateral / 0.4e-3 - 1.0).abs() < 1e-6, "{creepages:?}");
        let input = ContactInput {
            creepage_longitudinal: creepages.longitudinal,
            creepage_lateral: creepages.lateral,
            spin_creepage: creepages.spin,
            ..contact_input(&values)
        };
        let expected = Polach::default().creep_forces(&input).unwrap();
        assert_eq!(
            (outputs.force_longitudinal, outputs.force_lateral),
            (expected.force_longitudinal, expected.force_lateral)
        );
        // Standstill with a spinning wheel: finite, saturated against the slip.
        values.inputs.rolling_speed = 0.0;
        let standstill = super::tests::outputs(&values);
        assert!(standstill.force_longitudinal > 0.0 && standstill.adhesion_utilisation > 0.99, "{standstill:?}");
        assert_eq!(standstill.effective_spin_creepage, 0.0);
        let slip = (-values.inputs.wheel_angular_speed * 0.46).hypot(0.008);
        assert!((standstill.slip_velocity / slip - 1.0).abs() < 1e-12, "w = |(V − ωr, v_y)| at V = 0");
    }

    /// Polach 2005 with creepages from kinematics: w = s_C·D with D the kinematics' reference
    /// speed, μ(w) from the core's law, and the forces of Polach's 2005 model at that speed.
    #[test]
    fn polach_2005_uses_the_slip_velocity_of_the_kinematics() {
        for law in [TractionLaw::Polach2005Dry, TractionLaw::Polach2005Wet] {
            let mut values = rich_scene();
            values.parameters.traction_law = law as i32;
            values.parameters.creepages_from_kinematics = on();
            values.inputs.friction_coefficient = 0.55;
            values.inputs.wheel_angular_speed = 19.0 / 0.46; // 5 % slip: beyond the peak
            let outputs = outputs(&values);
            let creepages = WheelKinematics {
                rolling_speed: 20.0,
                wheel_angular_speed: values.inputs.wheel_angular_speed,
                wheel_rolling_radius: 0.46,
                lateral_slip_velocity: 0.008,
                spin_angular_velocity: 6.0,
            }
            .creepages(DEFAULT_REGULARISATION_SPEED)
            .unwrap();
            let extension = if law == TractionLaw::Polach2005Dry { Polach2005::DRY } else { Polach2005::WET };
            let eta_c = creepages.lateral + creepages.spin * 7.2e-3;
            let s_c = creepages.longitudinal.hypot(eta_c);
            assert!((outputs.slip_velocity / (s_c * creepages.reference_speed) - 1.0).abs() < 1e-14);
            let friction = extension.friction(0.55, outputs.slip_velocity);
            assert_eq!(outputs.current_friction_coefficient, friction);
            assert!(friction < 0.5 && friction > 0.4 * 0.55, "friction falls with slip: {friction}");
            let model = Polach {
                large_creepage: Some(LargeCreepage::new(extension, creepages.reference_speed).unwrap()),
                ..Polach::default()
            };
            let input = ContactInput {
                creepage_longitudinal: creepages.longitudinal,
                creepage_lateral: creepages.lateral,
                spin_creepage: creepages.spin,
                ..contact_input(&values)
            };
            let expected = model.creep_forces(&input).unwrap();
            assert_eq!(outputs.force_longitudinal, expected.force_longitudinal);
            assert_eq!(outputs.adhesion_utilisation, expected.adhesion_utilisation);
            // The utilisation is against μ(w)Q: the FMU's μ(w) is the model's to rounding.
            let magnitude = expected.force_longitudinal.hypot(expected.force_lateral);
            let model_friction = magnitude / expected.adhesion_utilisation / 100e3;
            assert!((model_friction / friction - 1.0).abs() < 1e-14, "{model_friction} vs {friction}");
        }
    }

    /// The relaxed forces start at the steady state, follow the core's exact update over each
    /// step, give the same result for one step of h as for two of h/2, and are kept per evaluation.
    #[test]
    fn relaxation_advances_the_state_exactly() {
        let mut values = rich_scene();
        values.parameters.creep_relaxation = on();
        let mut cache = test_cache();
        let mut state = [0.0; 2];
        let initial = evaluate_relaxed(&values, &mut cache, &mut state, Evaluation::Initialise).unwrap();
        let steady = Polach::default().creep_forces(&contact_input(&values)).unwrap();
        assert_eq!(state, [steady.force_longitudinal, steady.force_lateral]);
        assert_eq!(
            (initial.force_longitudinal, initial.adhesion_utilisation),
            (steady.force_longitudinal, steady.adhesion_utilisation)
        );
        // A creepage step: the force relaxes towards the new steady state.
        let before = state;
        values.inputs.creepage_longitudinal = 3e-3;
        let new_steady = Polach::default().creep_forces(&contact_input(&values)).unwrap();
        let lengths = RelaxationLengths::from_contact(7.2e-3, 5.4e-3, 0.28).unwrap();
        let mut one_step = before;
        let after = evaluate_relaxed(&values, &mut cache, &mut one_step, Evaluation::Step(4e-4)).unwrap();
        let steady_forces = [new_steady.force_longitudinal, new_steady.force_lateral];
        assert_eq!(one_step, lengths.advance(before, steady_forces, 20.0, 4e-4).unwrap());
        assert_eq!([after.force_longitudinal, after.force_lateral], one_step);
        // 63 % of the way after travelling L_x (L_x/V = 0.64 ms here: 4e-4 s is 8 mm of 12.8 mm).
        let progress = (one_step[0] - before[0]) / (steady_forces[0] - before[0]);
        assert!((progress - (1.0 - (-20.0 * 4e-4 / lengths.longitudinal).exp())).abs() < 1e-12, "{progress}");
        let mut two_steps = before;
        evaluate_relaxed(&values, &mut cache, &mut two_steps, Evaluation::Step(2e-4)).unwrap();
        evaluate_relaxed(&values, &mut cache, &mut two_steps, Evaluation::Step(2e-4)).unwrap();
        for (one, two) in one_step.iter().zip(two_steps) {
            assert!((one - two).abs() <= 1e-12 * one.abs(), "{one_step:?} vs {two_steps:?}");
        }
        let magnitude = one_step[0].hypot(one_step[1]);
        assert!((after.adhesion_utilisation - magnitude / (0.3 * 100e3)).abs() < 1e-15);
        // A given length is used in both directions; lift-off clears the state.
        values.parameters.relaxation_length = 0.05;
        cache.parameters_changed();
        let mut state = before;
        evaluate_relaxed(&values, &mut cache, &mut state, Evaluation::Step(1e-3)).unwrap();
        let uniform = RelaxationLengths::uniform(0.05).unwrap();
        assert_eq!(state, uniform.advance(before, steady_forces, 20.0, 1e-3).unwrap());
        values.inputs.normal_force = 0.0;
        let lifted = evaluate_relaxed(&values, &mut cache, &mut state, Evaluation::Step(1e-3)).unwrap();
        assert_eq!((state, lifted.force_longitudinal, lifted.adhesion_utilisation), ([0.0; 2], 0.0, 0.0));
    }

    #[test]
    fn the_scene_is_rebuilt_after_parameters_changed() {
        let mut values = Values::default();
        values.parameters.stiffness_source = StiffnessChoice::MeasuredCurve as i32;
        let mut cache = test_cache();
        let mut state = [0.0; 2];
        let mut evaluate = |values: &Values| {
            cache.parameters_changed();
            evaluate_relaxed(values, &mut cache, &mut state, Evaluation::Step(1e-3))
        };
        let before = evaluate(&values).unwrap();
        values.parameters.measured_peak_adhesion = 0.36;
        let after = evaluate(&values).unwrap();
        assert_ne!(before, after);
        assert_eq!(after, outputs(&values));
        values.parameters.measured_peak_adhesion = 0.29;
        let message = evaluate(&values).unwrap_err();
        assert!(message.starts_with("measured_peak_adhesion = 0.29 is invalid"), "{message}");
        values.parameters.creep_force_model = Model::KalkerLinear as i32;
        values.parameters.stiffness_source = StiffnessChoice::Kalker as i32;
        assert_eq!(evaluate(&values).unwrap(), outputs(&values));
    }

    /// `<ModelStructure>` declares each output to depend on the inputs that can change it under
    /// some choice of model and options: perturbing a declared input changes the output in at
    /// least one of the scenes below, perturbing an undeclared one in none.
    #[test]
    fn declared_output_dependencies_are_the_true_ones() {
        type Configure = fn(&mut Parameters);
        let scenes: [(Configure, Evaluation); 13] = [
            (|_| {}, Evaluation::Initialise),
            (|p| p.hertz_contact = on(), Evaluation::Initialise),
            (|p| p.creepages_from_kinematics = on(), Evaluation::Initialise),
            (|p| p.traction_law = TractionLaw::Polach2005Dry as i32, Evaluation::Initialise),
            (|p| p.creep_relaxation = on(), Evaluation::Step(1e-4)),
            (
                |p| {
                    p.creep_force_model = Model::Fastsim as i32;
                    (p.fastsim_strips, p.fastsim_elements) = (6, 6);
                },
                Evaluation::Initialise,
            ),
            (
                |p| {
                    p.creep_force_model = Model::Fastsim as i32;
                    (p.fastsim_strips, p.fastsim_elements) = (6, 6);
                    p.creepages_from_kinematics = on();
                },
                Evaluation::Initialise,
            ),
            (
                |p| {
                    p.creep_force_model = Model::KalkerLinear as i32;
                    (p.hertz_contact, p.creepages_from_kinematics, p.creep_relaxation) = (on(), on(), on());
                },
                Evaluation::Step(1e-4),
            ),
            (
                |p| {
                    p.traction_law = TractionLaw::Polach2005Wet as i32;
                    (p.hertz_contact, p.creepages_from_kinematics, p.creep_relaxation) = (on(), on(), on());
                },
                Evaluation::Step(1e-4),
            ),
            // Profiles: the non-Hertzian patches (the start value), and Hertz's, which have a
            // second patch (the flange) at this pose.
            (|p| p.contact_geometry = ContactGeometry::Profiles as i32, Evaluation::Initialise),
            (
                |p| {
                    p.contact_geometry = ContactGeometry::Profiles as i32;
                    p.contact_method = MethodChoice::Hertz as i32;
                },
                Evaluation::Initialise,
            ),
            (
                |p| {
                    p.contact_geometry = ContactGeometry::Profiles as i32;
                    p.contact_method = MethodChoice::Hertz as i32;
                    p.vertical_contact = VerticalChoice::PrescribedPosition as i32;
                },
                Evaluation::Initialise,
            ),
            (
                |p| {
                    p.contact_geometry = ContactGeometry::Profiles as i32;
                    p.contact_method = MethodChoice::Hertz as i32;
                    p.creep_relaxation = on();
                },
                Evaluation::Step(1e-4),
            ),
        ];
        let run = |values: &Values, evaluation| {
            let mut state = [-2e3, 1e3];
            let outputs = evaluate_relaxed(values, &mut test_cache(), &mut state, evaluation).unwrap();
            Values { outputs, ..*values }
        };
        let inputs: Vec<_> = VARIABLES.iter().filter(|v| v.causality == Causality::Input).collect();
        let outputs: Vec<_> = VARIABLES.iter().filter(|v| v.causality == Causality::Output).collect();
        let mut changed = vec![vec![false; inputs.len()]; outputs.len()];
        for (configure, evaluation) in scenes {
            let mut base = rich_scene();
            configure(&mut base.parameters);
            let reference = run(&base, evaluation);
            for (i, input) in inputs.iter().enumerate() {
                let mut perturbed = base;
                let value = perturbed.real_mut(input.value_reference).unwrap();
                *value = *value * 1.01 + 1e-5;
                let result = run(&perturbed, evaluation);
                for (o, output) in outputs.iter().enumerate() {
                    changed[o][i] |= result.real(output.value_reference) != reference.real(output.value_reference);
                }
            }
        }
        // Which candidates of a wheel on profiles are loaded, and so the patch count and each
        // patch's place, changes with every input of the vertical balance, but only where a
        // patch appears or two join (`fmu/tests/c_abi/profiles.rs`): no 1 % change here moves them.
        // For these outputs a declared input need not change them here.
        let place_of_patches = |name: &str| {
            name == "contact_patch_count"
                || ["contact_angle", "rail_lateral_position", "rolling_radius", "spin_creepage"]
                    .iter()
                    .any(|quantity| name.starts_with("patch") && name.ends_with(quantity))
        };
        for (o, output) in outputs.iter().enumerate() {
            for (i, input) in inputs.iter().enumerate() {
                let declared = output.dependencies.contains(&input.value_reference);
                if place_of_patches(output.name) {
                    assert!(declared || !changed[o][i], "{} on {}", output.name, input.name);
                } else {
                    assert_eq!(changed[o][i], declared, "{} on {}", output.name, input.name);
                }
            }
        }
        assert_eq!(outputs.iter().find(|o| o.value_reference == vr::APPROACH).unwrap().dependencies.len(), 2);
    }
}
