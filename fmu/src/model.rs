//! The contact FMU as a model on the slave layer's generic instance
//! ([`fmi2_slave::instance::Instance`], which holds the lifecycle, Get/Set, the step's checks,
//! FMU states and logging): what is this FMU's own. Its state is a [`ContactState`] (values,
//! profile names, the scene's and the wheel's state); beside it the model keeps what is not
//! state: the [`ContactCache`] derived from the parameters, and the resources directory.
//!
//! - evaluation: `crate::scene::update_outputs`, in place (the hot path of a co-simulation
//!   step), with a warning when an exact solve stopped at its limits;
//! - instantiation: refused with a missing or corrupted `exact_table` table in the resources
//!   directory ([`crate::exact_table::check`]);
//! - the cache: forgotten when a parameter is written, when an FMU state with other parameters
//!   is restored, and on fmi2Reset;
//! - directional derivatives: `derivative.rs` (the arguments) and
//!   `crate::scene::directional_derivative` (the mathematics);
//! - the FMU state's payload and sense checks: [`crate::snapshot`].
//!
//! Unit tests of the instance through this model sit beside it, in `model/*_tests.rs`.

use std::path::PathBuf;

use fmi2_slave::instance::{Evaluation, FmuState, Model};
use wheel_rail_contact::geometry::{SwitchingFunctions, NO_SWITCH, SWITCHING_FUNCTIONS};
use wheel_rail_contact::scene::Evaluation as SceneEvaluation;

use crate::mode::Mode;
use crate::model_description::{self, access_of, ContactGeometry, Switch, Variable, VARIABLES};
use crate::resources::resource_directory;
use crate::scene::{update_outputs, ContactCache};
use crate::snapshot::{self, ContactState};

mod derivative;

pub use fmi2_slave::{InstantiateArguments, Slave, StatusKind, Unsupported};

/// One instance of the contact FMU.
pub type Instance = fmi2_slave::instance::Instance<ContactModel>;

/// What an instance keeps beside its state.
pub struct ContactModel {
    /// The directory the resource location names, if it names one: where relative profile
    /// paths are looked up first.
    resources: Option<PathBuf>,
    /// Derived from the parameters (not state: it is rebuilt whenever they differ).
    cache: ContactCache,
    /// The switching functions of the last evaluation (the event indicators): not state, as the
    /// outputs they go with are recomputed before they are read again after a restored state.
    switching: SwitchingFunctions,
}

// The event indicators are the wheel's switching functions, one for one.
const _: () = assert!(model_description::EVENT_INDICATORS == SWITCHING_FUNCTIONS);

impl Model for ContactModel {
    type State = ContactState;

    const GUID: &'static str = model_description::GUID;
    const MODEL_IDENTIFIER: &'static str = model_description::MODEL_IDENTIFIER;
    const LOG_CATEGORIES: &'static [&'static str] = model_description::LOG_CATEGORIES;
    const STATE_LAYOUT_TAG: u64 = model_description::STATE_LAYOUT_TAG;
    const STATE_MAGIC: [u8; 8] = snapshot::MAGIC;
    const STATE_FORMAT_VERSION: u16 = snapshot::FORMAT_VERSION;
    const PROVIDES_DIRECTIONAL_DERIVATIVE: bool = true;
    const MODEL_EXCHANGE: bool = model_description::MODEL_EXCHANGE;
    const EVENT_INDICATORS: usize = model_description::EVENT_INDICATORS;
    const CONTINUOUS_STATES: &'static [(u32, u32, f64)] = model_description::CONTINUOUS_STATES;

    /// Refused with a missing or corrupted `exact_table` table in the resources directory. A
    /// resource location that names no directory is not an error: only a relative profile path
    /// needs the directory, and is then also looked up in the working directory (the trace
    /// says so).
    fn instantiate(resource_location: Option<&str>) -> Result<(Self, Option<String>), String> {
        let resources = resource_location.map(resource_directory);
        crate::exact_table::check(resources.as_ref().and_then(|r| r.as_deref().ok()))?;
        let note = match &resources {
            Some(Err(reason)) => Some(format!("{reason}; relative profile paths are read from the working directory")),
            _ => None,
        };
        let resources = resources.and_then(Result::ok);
        let model = ContactModel {
            cache: ContactCache::new(resources.clone()),
            resources,
            switching: SwitchingFunctions::default(),
        };
        Ok((model, note))
    }

    fn reset(&mut self) {
        self.cache = ContactCache::new(self.resources.clone());
        self.switching = SwitchingFunctions::default();
    }

    fn start() -> ContactState {
        ContactState::start()
    }

    #[inline]
    fn variable(value_reference: u32) -> Option<&'static Variable> {
        model_description::variable(value_reference)
    }

    fn variables() -> &'static [Variable] {
        &VARIABLES
    }

    #[inline]
    fn access(value_reference: u32) -> u8 {
        access_of(value_reference)
    }

    #[inline]
    fn real(state: &ContactState, value_reference: u32) -> Option<f64> {
        state.values.real(value_reference)
    }

    #[inline]
    fn real_mut(state: &mut ContactState, value_reference: u32) -> Option<&mut f64> {
        state.values.real_mut(value_reference)
    }

    fn integer(state: &ContactState, value_reference: u32) -> Option<i32> {
        state.values.integer(value_reference)
    }

    fn integer_mut(state: &mut ContactState, value_reference: u32) -> Option<&mut i32> {
        state.values.integer_mut(value_reference)
    }

    fn string(state: &ContactState, value_reference: u32) -> Option<&str> {
        state.strings.string(value_reference).map(String::as_str)
    }

    /// A String is a parameter, so the contact is rebuilt (the profiles read again) at the
    /// next evaluation.
    fn string_mut(state: &mut ContactState, value_reference: u32) -> Option<&mut String> {
        state.strings.string_mut(value_reference)
    }

    /// The outputs at the start or at the step's end from the inputs set before it (the model is
    /// algebraic in them; the step size matters to the relaxed forces), in place; the outputs
    /// and the contact's state change only if every output is finite. Direct feedthrough (new
    /// inputs read back before the next step) is a step of zero length whose state is dropped:
    /// the outputs at the new inputs, with the relaxed forces and the exact theory's warm start
    /// as the last step left them. So is every evaluation of Model Exchange, at the continuous
    /// states the master set: the relaxed forces' rate is the state derivative.
    ///
    /// The relaxed forces are the locals `relaxed_force_*` (Model Exchange's continuous states):
    /// the scene starts from them and, when a step or the start moves them, they take the
    /// scene's.
    #[inline]
    fn evaluate(&mut self, state: &mut ContactState, evaluation: Evaluation) -> Result<Option<String>, String> {
        let ContactState { values, strings, scene, wheel, profiles } = state;
        scene.relaxed_forces = [values.locals.relaxed_force_longitudinal, values.locals.relaxed_force_lateral];
        let switching = &mut self.switching;
        let warning = match evaluation {
            Evaluation::Initialise => {
                update_outputs(values, strings, &mut self.cache, scene, wheel, switching, SceneEvaluation::Initialise)?
            }
            Evaluation::Step { size, .. } => {
                update_outputs(values, strings, &mut self.cache, scene, wheel, switching, SceneEvaluation::Step(size))?
            }
            Evaluation::Feedthrough { .. } => {
                let (mut scene, mut wheel) = (scene.clone(), wheel.clone());
                let feedthrough = SceneEvaluation::Step(0.0);
                update_outputs(values, strings, &mut self.cache, &mut scene, &mut wheel, switching, feedthrough)?
            }
        };
        // The scene's relaxed forces are the state after the start or a step; a feedthrough
        // dropped its own.
        [values.locals.relaxed_force_longitudinal, values.locals.relaxed_force_lateral] = scene.relaxed_forces;
        *profiles = self.cache.profile_digest();
        Ok(warning)
    }

    /// The switching functions of the wheel's patches (`wheel_rail_contact::geometry::switching`)
    /// as event indicators: with `contact_geometry = profiles` their signs change where the
    /// patches join, part or pass to another gap minimum (or region), where the outputs jump;
    /// with one patch (`ellipse`, whose evaluation leaves them alone) they are [`NO_SWITCH`].
    fn event_indicators(&self, state: &ContactState, indicators: &mut [f64]) {
        if state.values.parameters.contact_geometry == ContactGeometry::Profiles as i32 {
            indicators.copy_from_slice(self.switching.values());
        } else {
            indicators.fill(NO_SWITCH);
        }
    }

    /// With profiles each patch relaxes on its own, and patches come and go: not continuous
    /// states of a fixed number.
    fn model_exchange_problem(state: &ContactState) -> Option<String> {
        let parameters = &state.values.parameters;
        (parameters.creep_relaxation != Switch::Off as i32
            && parameters.contact_geometry == ContactGeometry::Profiles as i32)
            .then(|| {
                format!(
                    "creep_relaxation = {} with contact_geometry = {} (profiles) is not available in Model \
                     Exchange: each patch's relaxed forces are its own, and patches appear, merge and vanish as \
                     the wheelset moves, so they are no fixed set of continuous states; set creep_relaxation = 0 \
                     (off), use contact_geometry = 1 (ellipse), or instantiate for Co-Simulation",
                    parameters.creep_relaxation, parameters.contact_geometry
                )
            })
    }

    /// A step event where the relaxed forces (the continuous states) lie beyond the friction
    /// limit μQ of the accepted point: the outputs are already their projection onto it (the
    /// scene's [`within_friction_limit`](wheel_rail_contact::scene)), and the event moves the
    /// states there, as a Co-Simulation step does at its end.
    fn completed_integrator_step(&mut self, state: &ContactState, _time: f64) -> Result<bool, String> {
        Ok(beyond_friction_limit(state))
    }

    /// The relaxed forces set to their projection onto the friction limit (the outputs).
    fn new_discrete_states(&mut self, state: &mut ContactState) -> bool {
        let beyond = beyond_friction_limit(state);
        if beyond {
            let values = &mut state.values;
            values.locals.relaxed_force_longitudinal = values.outputs.force_longitudinal;
            values.locals.relaxed_force_lateral = values.outputs.force_lateral;
        }
        beyond
    }

    #[inline]
    fn parameters_changed(&mut self) {
        self.cache.parameters_changed();
    }

    /// The model (with profiles: the profiles read and placed, tens of ms) is rebuilt only if
    /// the state's parameters differ: a master that restores a state every step (a
    /// finite-difference Jacobian, a retried step) would otherwise pay that each time. A state
    /// computed with profiles of other content than the cache's (a file changed on disk since
    /// it was saved, here or in the process that serialized it) is not continued with the
    /// content read now: the next evaluation rereads the files and compares.
    fn restoring(&mut self, current: &ContactState, restored: &ContactState) {
        if current.values.parameters != restored.values.parameters || current.strings != restored.strings {
            self.cache.parameters_changed();
        }
        self.cache.restored(restored.profiles);
    }

    fn directional_derivative(
        &mut self,
        state: &ContactState,
        unknowns: &[u32],
        knowns: &[u32],
        known_rates: &[f64],
        unknown_rates: &mut [f64],
    ) -> Result<(), String> {
        derivative::directional_derivative(&mut self.cache, state, unknowns, knowns, known_rates, unknown_rates)
    }

    fn encode(state: &FmuState<ContactState>) -> Vec<u8> {
        snapshot::encode_payload(state)
    }

    fn decode(payload: &[u8]) -> Result<FmuState<ContactState>, String> {
        snapshot::decode_payload(payload)
    }

    fn check_state(state: &ContactState, mode: Mode) -> Result<(), String> {
        snapshot::check_state(state, mode)
    }
}

/// Whether the relaxed forces (relaxation on) differ from the output forces, their projection
/// onto the friction limit: bit for bit equal within the limit (a step of zero length leaves them
/// exactly), so any difference is the projection (or a lift-off, which zeroes them). (With
/// profiles, which Model Exchange refuses with relaxation on, both stay 0.)
fn beyond_friction_limit(state: &ContactState) -> bool {
    let ContactState { values, .. } = state;
    values.parameters.creep_relaxation != Switch::Off as i32
        && (values.locals.relaxed_force_longitudinal != values.outputs.force_longitudinal
            || values.locals.relaxed_force_lateral != values.outputs.force_lateral)
}

#[cfg(test)]
mod derivative_tests;
#[cfg(test)]
mod fmu_state_tests;
#[cfg(test)]
mod instance_tests;
#[cfg(test)]
mod step_tests;
#[cfg(test)]
mod test_support;
#[cfg(test)]
mod values_tests;
