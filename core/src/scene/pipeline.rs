//! One scene, end to end: where the creepages come from → where the contact ellipse comes from →
//! the creep-force model → the traction law → creep relaxation. The FMU, the packaging tool's
//! reference outputs and Rust users all evaluate a scene through [`Scene::evaluate`].
//!
//! Per evaluation, in order (each option only when the scene selects it; an option that is off
//! costs a branch and nothing else, and its inputs are not read):
//! 1. creepages: the inputs, or from the kinematics ([`super::kinematics`]);
//! 2. contact ellipse: the inputs, or Hertz's ([`crate::hertz`]; Q ≤ 0 is lift-off and gives
//!    zero forces before any Hertz computation);
//! 3. forces: the chosen [`ModelChoice`], with Polach's 2005 traction law applied at this
//!    evaluation's speed when selected;
//! 4. relaxation ([`super::relaxation`]): the relaxed forces advanced exactly over the step from
//!    the steady-state forces of step 3, at the speed that renews the contact (|V|, or
//!    (|V| + |ωr|)/2 with the kinematics: a wheel spinning at standstill builds up its force, a
//!    contact at rest holds it), and never beyond this evaluation's friction limit μQ.
//!
//! What carries over from one evaluation to the next is [`SceneState`] (the relaxed forces and
//! the model's memory: save it and a restored run continues bit for bit) and [`SceneCache`]
//! (derived data for speed only).
//!
//! ```
//! use wheel_rail_contact::scene::{CreepageSource, Evaluation, Relaxation, Scene, SceneCache, SceneInput, SceneState};
//! use wheel_rail_contact::{ModelChoice, Polach};
//! // Polach's model, creepages from the wheel's velocities, creep relaxation over 10 mm.
//! let scene = Scene {
//!     creepages: CreepageSource::Kinematics { regularisation_speed: 0.01 },
//!     relaxation: Relaxation::On { length: 0.01 },
//!     ..Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28)
//! };
//! let rolling = SceneInput {
//!     normal_force: 100e3, semi_axis_a: 7.2e-3, semi_axis_b: 5.4e-3, friction_coefficient: 0.3,
//!     rolling_speed: 20.0, wheel_angular_speed: 20.0 / 0.46, wheel_rolling_radius: 0.46,
//!     ..SceneInput::default()
//! };
//! let mut cache = SceneCache::default();
//! let (start, state) = scene.evaluate(&rolling, &SceneState::default(), &mut cache, Evaluation::Initialise).unwrap();
//! assert!(start.force_longitudinal.abs() < 1e-6, "free rolling: no creep force");
//! // Braking: the wheel turns 0.2 % slower; the force builds up over the relaxation length.
//! let braking = SceneInput { wheel_angular_speed: 0.998 * 20.0 / 0.46, ..rolling };
//! let (after_1_ms, _) = scene.evaluate(&braking, &state, &mut cache, Evaluation::Step(1e-3)).unwrap();
//! let steady = Scene { relaxation: Relaxation::Off, ..scene }
//!     .evaluate(&braking, &SceneState::default(), &mut cache, Evaluation::Initialise)
//!     .unwrap()
//!     .0;
//! // 20 mm travelled over L = 10 mm: 1 − e⁻² of the way to the steady force (which opposes the creepage).
//! let expected = steady.force_longitudinal * -(-2.0_f64).exp_m1();
//! assert!((after_1_ms.force_longitudinal / expected - 1.0).abs() < 1e-3);
//! ```
//!
//! Derivatives, the contact input a scene hands its model, and states read back:
//!
//! ```
//! use wheel_rail_contact::scene::{CreepageSource, Scene, SceneError, SceneInput, SceneState};
//! use wheel_rail_contact::{KalkerLinear, ModelChoice};
//!
//! // Kalker's linear theory, a = 8 mm, b = 4 mm, ν = 0.25: dF_x/dξ = −G ab C11, C11 = 5.10.
//! let scene = Scene::of_model(ModelChoice::KalkerLinear(KalkerLinear), 82e9, 0.25);
//! let input = SceneInput {
//!     creepage_longitudinal: 1e-3,
//!     normal_force: 82e3,
//!     semi_axis_a: 8e-3,
//!     semi_axis_b: 4e-3,
//!     friction_coefficient: 0.3,
//!     ..SceneInput::default()
//! };
//! let contact = scene.contact_input(&input);
//! assert_eq!((contact.creepage_longitudinal, contact.shear_modulus, contact.poisson_ratio), (1e-3, 82e9, 0.25));
//! let along_xi = SceneInput { creepage_longitudinal: 1.0, ..SceneInput::default() };
//! assert_eq!(scene.option_without_derivatives(), None);
//! let rates = scene.directional_derivative(&input, &along_xi).unwrap();
//! assert!((rates.force_longitudinal + 82e9 * 32e-6 * 5.10).abs() < 1e-3);
//! assert_eq!(rates.effective_creepage_longitudinal, 1.0, "the creepage output passes the input through");
//! // With the creepages from the kinematics the outputs are not the model's forces of the
//! // inputs: no derivative, and the error says why.
//! let kinematic = Scene { creepages: CreepageSource::Kinematics { regularisation_speed: 0.01 }, ..scene };
//! assert!(kinematic.option_without_derivatives().is_some());
//! assert!(matches!(kinematic.directional_derivative(&input, &along_xi), Err(SceneError::NoDerivativeWith(_))));
//! // A state read back from a file is checked before use.
//! assert!(SceneState::with_relaxed_forces([100.0, -50.0]).validate().is_ok());
//! let error = SceneState::with_relaxed_forces([f64::NAN, 0.0]).validate().unwrap_err();
//! assert_eq!(error.variable, "relaxed_force_longitudinal");
//! ```

use std::fmt;

use num_dual::Dual64;

use super::kinematics::WheelKinematics;
use super::relaxation::{renewal_speed, RelaxationLengths};
use crate::contact_input::hertz_max_pressure;
use crate::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use crate::models::exact::GridSize;
use crate::models::polach::resulting_creepage_at;
use crate::{
    ContactInput, CreepForceModel, CreepForces, InvalidInput, ModelCache, ModelChoice, ModelMemory, Polach, Polach2005,
};

/// Where the creepages ξ, η, φ come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CreepageSource {
    /// The creepage inputs, as given.
    Inputs,
    /// From the wheel's velocities ([`WheelKinematics`]), smooth through standstill with the
    /// regularisation speed v_c [m/s].
    Kinematics { regularisation_speed: f64 },
}

/// Where the contact ellipse comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EllipseSource {
    /// The semi-axis inputs a, b, with Hertz's p₀ = 3Q/(2πab) and no approach.
    Inputs,
    /// Hertz's ellipse from the load, the wheel's rolling radius and the signed profile
    /// curvatures [1/m] (0 = straight; a concave profile is negative).
    Hertz { wheel_profile_curvature: f64, rail_profile_curvature: f64 },
}

/// The friction law of the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TractionLaw {
    /// Constant friction coefficient μ (the input).
    Coulomb,
    /// Polach 2005: μ falls with the slip velocity from μ₀ (the input), with reduced stiffness
    /// ([`Polach2005`]). Polach's model only.
    Polach2005(Polach2005),
}

/// Creep relaxation of F_x, F_y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Relaxation {
    /// The forces follow the creepages at once.
    Off,
    /// The forces relax over `length` \[m\] of rolling (0: derived from the contact,
    /// [`RelaxationLengths::from_contact`]).
    On { length: f64 },
}

/// A scene: the model and every option, with the material constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    pub model: ModelChoice,
    pub creepages: CreepageSource,
    pub ellipse: EllipseSource,
    pub traction_law: TractionLaw,
    pub relaxation: Relaxation,
    /// Combined shear modulus G \[Pa\].
    pub shear_modulus: f64,
    /// Combined Poisson's ratio ν \[1\].
    pub poisson_ratio: f64,
}

/// What a scene reads per evaluation (SI units); the option inputs are read only by their option.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SceneInput {
    /// ξ \[1\] (creepages from the inputs).
    pub creepage_longitudinal: f64,
    /// η \[1\].
    pub creepage_lateral: f64,
    /// φ [1/m].
    pub spin_creepage: f64,
    /// Q \[N\]; Q ≤ 0 is lift-off (zero forces).
    pub normal_force: f64,
    /// a \[m\] (ellipse from the inputs).
    pub semi_axis_a: f64,
    /// b \[m\].
    pub semi_axis_b: f64,
    /// μ, or μ₀ under Polach 2005 \[1\].
    pub friction_coefficient: f64,
    /// V [m/s]: the kinematics' rolling speed; with creepages from the inputs, the speed that
    /// turns creepage into slip velocity (Polach 2005, relaxation).
    pub rolling_speed: f64,
    /// ω [rad/s] (kinematics).
    pub wheel_angular_speed: f64,
    /// r \[m\] (kinematics, Hertz).
    pub wheel_rolling_radius: f64,
    /// v_y [m/s] (kinematics).
    pub lateral_slip_velocity: f64,
    /// ω_z [rad/s] (kinematics).
    pub spin_angular_velocity: f64,
}

/// What a scene gives per evaluation (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SceneOutput {
    /// F_x \[N\] on the wheel.
    pub force_longitudinal: f64,
    /// F_y \[N\].
    pub force_lateral: f64,
    /// |F|/(μQ) with the friction applied \[1\].
    pub adhesion_utilisation: f64,
    /// M_z [N·m] (0 for the models that have none).
    pub spin_moment: f64,
    /// The friction coefficient applied (μ(w) under Polach 2005) \[1\].
    pub current_friction_coefficient: f64,
    /// s_C·speed [m/s] (Polach's eqs. 21, 22).
    pub slip_velocity: f64,
    /// The creepages the model used.
    pub effective_creepage_longitudinal: f64,
    pub effective_creepage_lateral: f64,
    pub effective_spin_creepage: f64,
    /// The ellipse the model used \[m\] (0 after a Hertzian lift-off).
    pub contact_semi_axis_a: f64,
    pub contact_semi_axis_b: f64,
    /// Hertz's p₀ \[Pa\].
    pub max_pressure: f64,
    /// Hertz's approach δ \[m\] (0 with the ellipse from the inputs).
    pub approach: f64,
    /// d[F_x, F_y]/dt of the relaxed forces at the state this evaluation leaves, (V_r/L)(F_ss − F)
    /// [N/s] ([`super::relaxation`]): Model Exchange's state derivative. 0 without creep
    /// relaxation, at the start (F = F_ss) and where the contact transmits no force.
    pub relaxation_rate: [f64; 2],
    /// The exact theory's grid when its iteration stopped at its limits
    /// ([`crate::models::exact::MAX_ITERATIONS`] Newton steps or
    /// [`crate::models::exact::MAX_PRODUCTS`] products) without converging: the outputs are
    /// its last iterate. `None` for every other evaluation.
    pub unconverged_grid: Option<GridSize>,
}

/// What a scene carries from one evaluation to the next that changes the next result: the
/// relaxed forces (the physical state of creep relaxation) and the model's memory (the exact
/// theory's warm start, [`ModelMemory`]). Save it whole and a restored run continues bit for
/// bit (the FMU state does, with the `serde` feature).
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SceneState {
    /// The relaxed forces [F_x, F_y] \[N\] (with creep relaxation on; zero otherwise).
    pub relaxed_forces: [f64; 2],
    /// What the model carries to its next evaluation.
    pub model: ModelMemory,
}

impl SceneState {
    /// A state with these relaxed forces and an empty model memory.
    pub fn with_relaxed_forces(relaxed_forces: [f64; 2]) -> Self {
        Self { relaxed_forces, ..Self::default() }
    }

    /// Checks a state that did not come from an evaluation (one read back from a saved state):
    /// finite relaxed forces and a valid model memory.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        for (variable, force) in
            [("relaxed_force_longitudinal", self.relaxed_forces[0]), ("relaxed_force_lateral", self.relaxed_forces[1])]
        {
            if !force.is_finite() {
                return Err(InvalidInput::new(variable, force, "must be finite"));
            }
        }
        self.model.validate()
    }
}

/// What a scene keeps between evaluations for speed only (results are bit-identical without
/// it, so it is never saved): the model's [`ModelCache`].
#[derive(Debug, Clone, Default)]
pub struct SceneCache {
    model: ModelCache,
}

/// What an evaluation is for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Evaluation {
    /// The start: the relaxed forces are set to the steady state.
    Initialise,
    /// A step of this size \[s\] (> 0): the relaxed forces advance over it.
    Step(f64),
}

/// Why a scene cannot be evaluated or differentiated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneError {
    /// An input or parameter outside the models' domain (names it).
    Invalid(InvalidInput),
    /// Polach 2005 with another model than Polach's.
    TractionLawNeedsPolach,
    /// A directional derivative was asked with an option on that transforms the inputs in a way
    /// not differentiated (named).
    NoDerivativeWith(&'static str),
    /// The model refused the ellipse that Hertz's theory gave (`hertz_contact`): the semi-axes
    /// are not inputs then, so the error names what they came from.
    HertzEllipseRefused {
        /// Hertz's semi-axes a, b \[m\].
        semi_axis_a: f64,
        semi_axis_b: f64,
        /// What Hertz's ellipse was computed from: r \[m\] and the profile curvatures [1/m].
        wheel_rolling_radius: f64,
        wheel_profile_curvature: f64,
        rail_profile_curvature: f64,
        /// The model's refusal (it names a semi-axis and its rule).
        refusal: InvalidInput,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(error) => error.fmt(f),
            Self::TractionLawNeedsPolach => f.write_str("the Polach 2005 traction law needs Polach's model"),
            Self::NoDerivativeWith(option) => write!(f, "directional derivatives are not available with {option} on"),
            Self::HertzEllipseRefused {
                semi_axis_a: a,
                semi_axis_b: b,
                wheel_rolling_radius,
                wheel_profile_curvature,
                rail_profile_curvature,
                refusal,
            } => write!(
                f,
                "hertz_contact = on: Hertz's ellipse from wheel_rolling_radius = {wheel_rolling_radius} m, \
                 wheel_profile_curvature = {wheel_profile_curvature} 1/m and rail_profile_curvature = \
                 {rail_profile_curvature} 1/m has a/b = {:.4} (a = {:.4} mm, b = {:.4} mm), which the model cannot \
                 take ({} {})",
                a / b,
                a * 1e3,
                b * 1e3,
                refusal.variable,
                refusal.requirement
            ),
        }
    }
}

impl std::error::Error for SceneError {}

impl From<InvalidInput> for SceneError {
    fn from(error: InvalidInput) -> Self {
        Self::Invalid(error)
    }
}

/// The creepages the model uses and the speed that turns creepage into slip velocity.
struct Creepages {
    longitudinal: f64,
    lateral: f64,
    spin: f64,
    /// |V|, or D = √(V² + v_c²) from the kinematics (ξ·D is then the slip velocity exactly).
    speed: f64,
    /// The speed at which the contact's material is renewed, for creep relaxation: |V|, or
    /// (|V| + |ωr|)/2 from the kinematics ([`super::relaxation::renewal_speed`]).
    renewal: f64,
}

impl Scene {
    /// A scene of `model` with every option off.
    pub fn of_model(model: ModelChoice, shear_modulus: f64, poisson_ratio: f64) -> Self {
        Self {
            model,
            creepages: CreepageSource::Inputs,
            ellipse: EllipseSource::Inputs,
            traction_law: TractionLaw::Coulomb,
            relaxation: Relaxation::Off,
            shear_modulus,
            poisson_ratio,
        }
    }

    /// The core's contact input with every option off (creepages and ellipse as given).
    pub fn contact_input(&self, input: &SceneInput) -> ContactInput {
        ContactInput {
            creepage_longitudinal: input.creepage_longitudinal,
            creepage_lateral: input.creepage_lateral,
            spin_creepage: input.spin_creepage,
            normal_force: input.normal_force,
            semi_axis_a: input.semi_axis_a,
            semi_axis_b: input.semi_axis_b,
            friction_coefficient: input.friction_coefficient,
            shear_modulus: self.shear_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }

    /// The outputs for `input` from `state`, and the state after this evaluation (advanced over
    /// the step, or initialised): the caller keeps it for the next evaluation, or drops it to
    /// repeat this one. `cache` holds derived data only (any cache, even a fresh one, gives the
    /// same outputs).
    pub fn evaluate(
        &self,
        input: &SceneInput,
        state: &SceneState,
        cache: &mut SceneCache,
        evaluation: Evaluation,
    ) -> Result<(SceneOutput, SceneState), SceneError> {
        if !input.rolling_speed.is_finite() {
            return Err(InvalidInput::new("rolling_speed", input.rolling_speed, "must be finite").into());
        }
        let creepages = self.creepages_of(input)?;
        // Lift-off with Hertz on: no contact, zero forces, and nothing of Hertz's is computed.
        let hertz_lift_off = matches!(self.ellipse, EllipseSource::Hertz { .. }) && input.normal_force <= 0.0;
        let ellipse = match self.ellipse {
            _ if hertz_lift_off => {
                HertzContact { semi_axis_a: 0.0, semi_axis_b: 0.0, max_pressure: 0.0, approach: 0.0 }
            }
            EllipseSource::Hertz { wheel_profile_curvature, rail_profile_curvature } => {
                let curvature = RelativeCurvature::from_profile_curvatures(
                    input.wheel_rolling_radius,
                    wheel_profile_curvature,
                    rail_profile_curvature,
                )?;
                let modulus = contact_modulus(self.shear_modulus, self.poisson_ratio)?;
                HertzContact::solve(input.normal_force, &curvature, modulus)?
            }
            EllipseSource::Inputs => {
                let given = self.contact_input(input);
                HertzContact {
                    semi_axis_a: input.semi_axis_a,
                    semi_axis_b: input.semi_axis_b,
                    max_pressure: given.max_pressure().min(f64::MAX),
                    approach: 0.0,
                }
            }
        };
        let contact = ContactInput {
            creepage_longitudinal: creepages.longitudinal,
            creepage_lateral: creepages.lateral,
            spin_creepage: creepages.spin,
            normal_force: input.normal_force,
            // After a Hertzian lift-off any valid ellipse will do: every model checks the other
            // values and returns zero force for Q ≤ 0 before using the ellipse.
            semi_axis_a: if hertz_lift_off { 1.0 } else { ellipse.semi_axis_a },
            semi_axis_b: if hertz_lift_off { 1.0 } else { ellipse.semi_axis_b },
            friction_coefficient: input.friction_coefficient,
            shear_modulus: self.shear_modulus,
            poisson_ratio: self.poisson_ratio,
        };
        // The slip velocity: the resulting creepage s_C times the speed (Polach's eqs. 21, 22).
        let s_c =
            Polach::resulting_creepage(creepages.longitudinal, creepages.lateral, creepages.spin, ellipse.semi_axis_a);
        let slip_velocity = s_c * creepages.speed;
        // The scene's own model unless the traction law adapts it: borrowed, since a model can be
        // large (the exact theory's grid) and this is the hot path of a step.
        let adapted;
        let (model, friction) = match self.traction_law {
            TractionLaw::Coulomb => (&self.model, input.friction_coefficient),
            TractionLaw::Polach2005(law) => {
                adapted =
                    self.model.under_polach2005(law, creepages.speed)?.ok_or(SceneError::TractionLawNeedsPolach)?;
                (&adapted, law.friction(input.friction_coefficient, slip_velocity))
            }
        };
        let step = model
            .creep_forces_in_sequence(&contact, &state.model, &mut cache.model)
            .map_err(|refusal| self.attributed(refusal, input, &ellipse))?;
        let (forces, relaxed_forces, relaxation_rate) = match self.relaxation {
            Relaxation::On { length } => relax_forces(
                &contact,
                &step.forces,
                friction,
                state.relaxed_forces,
                creepages.renewal,
                length,
                evaluation,
            )?,
            Relaxation::Off => (step.forces, state.relaxed_forces, [0.0; 2]),
        };
        let output = SceneOutput {
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
            relaxation_rate,
            unconverged_grid: step.unconverged_grid,
        };
        Ok((output, SceneState { relaxed_forces, model: step.memory }))
    }

    /// The option, if any, under which the outputs are not the model's forces of the inputs, so
    /// that J·v by the model's derivative would be wrong: kinematics → creepages, Hertz →
    /// semi-axes, relaxation → lagged forces, Polach 2005 → μ of the slip velocity.
    pub fn option_without_derivatives(&self) -> Option<&'static str> {
        if matches!(self.traction_law, TractionLaw::Polach2005(_)) {
            Some("traction_law (Polach 2005)")
        } else if matches!(self.ellipse, EllipseSource::Hertz { .. }) {
            Some("hertz_contact")
        } else if matches!(self.creepages, CreepageSource::Kinematics { .. }) {
            Some("creepages_from_kinematics")
        } else if matches!(self.relaxation, Relaxation::On { .. }) {
            Some("creep_relaxation")
        } else {
            None
        }
    }

    /// d(outputs) along `direction` (one rate per input) at `input`, of the outputs at `input`
    /// itself — never of a stored output.
    ///
    /// With no option on, the forces and M_z are the model's
    /// ([`CreepForceModel::directional_derivative`]); the other outputs pass inputs through
    /// (friction, creepages, semi-axes), or are p₀ = 3Q/(2πab) and the slip velocity s_C·|V|
    /// (Polach's eqs. 21, 22), both differentiated with dual numbers; the approach is 0. At the
    /// kinks Q = 0 and V = 0 the rate of the positive side is given.
    pub fn directional_derivative(
        &self,
        input: &SceneInput,
        direction: &SceneInput,
    ) -> Result<SceneOutput, SceneError> {
        if let Some(option) = self.option_without_derivatives() {
            return Err(SceneError::NoDerivativeWith(option));
        }
        let mut rates = self.contact_input(direction);
        // Material constants are parameters, never knowns: their rates are zero.
        rates.shear_modulus = 0.0;
        rates.poisson_ratio = 0.0;
        let at = self.contact_input(input);
        let forces = self.model.directional_derivative(&at, &rates)?;

        let (x, d) = (input, direction);
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
        // At Q = 0 the rate of the loaded side, 3/(2πab)·dQ: p₀ is taken at the smallest Q > 0.
        let max_pressure = hertz_max_pressure(
            dual(if x.normal_force == 0.0 { f64::MIN_POSITIVE } else { x.normal_force }, d.normal_force),
            dual(x.semi_axis_a, d.semi_axis_a),
            dual(x.semi_axis_b, d.semi_axis_b),
        );
        Ok(SceneOutput {
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
            max_pressure: max_pressure.eps,
            approach: 0.0,
            relaxation_rate: [0.0; 2],
            unconverged_grid: None,
        })
    }

    /// The model's refusal of `input`, with a refused semi-axis of Hertz's ellipse attributed to
    /// what the ellipse came from (the semi-axis inputs are ignored with `hertz_contact` on).
    fn attributed(&self, refusal: InvalidInput, input: &SceneInput, ellipse: &HertzContact) -> SceneError {
        match self.ellipse {
            EllipseSource::Hertz { wheel_profile_curvature, rail_profile_curvature }
                if matches!(refusal.variable, "semi_axis_a" | "semi_axis_b") =>
            {
                SceneError::HertzEllipseRefused {
                    semi_axis_a: ellipse.semi_axis_a,
                    semi_axis_b: ellipse.semi_axis_b,
                    wheel_rolling_radius: input.wheel_rolling_radius,
                    wheel_profile_curvature,
                    rail_profile_curvature,
                    refusal,
                }
            }
            _ => refusal.into(),
        }
    }

    fn creepages_of(&self, input: &SceneInput) -> Result<Creepages, InvalidInput> {
        Ok(match self.creepages {
            CreepageSource::Kinematics { regularisation_speed } => {
                let kinematics = WheelKinematics {
                    rolling_speed: input.rolling_speed,
                    wheel_angular_speed: input.wheel_angular_speed,
                    wheel_rolling_radius: input.wheel_rolling_radius,
                    lateral_slip_velocity: input.lateral_slip_velocity,
                    spin_angular_velocity: input.spin_angular_velocity,
                };
                let computed = kinematics.creepages(regularisation_speed)?;
                Creepages {
                    longitudinal: computed.longitudinal,
                    lateral: computed.lateral,
                    spin: computed.spin,
                    speed: computed.reference_speed,
                    renewal: renewal_speed(&kinematics),
                }
            }
            CreepageSource::Inputs => Creepages {
                longitudinal: input.creepage_longitudinal,
                lateral: input.creepage_lateral,
                spin: input.spin_creepage,
                speed: input.rolling_speed.abs(),
                renewal: input.rolling_speed.abs(),
            },
        })
    }
}

/// The relaxation lengths: `length` > 0, or (0) the module's default from the contact.
fn relaxation_lengths(contact: &ContactInput, length: f64) -> Result<RelaxationLengths, InvalidInput> {
    if length == 0.0 {
        RelaxationLengths::from_contact(contact.semi_axis_a, contact.semi_axis_b, contact.poisson_ratio)
    } else if length > 0.0 {
        RelaxationLengths::uniform(length)
    } else {
        Err(InvalidInput::new("relaxation_length", length, "must be finite and >= 0 (0: derived from the contact)"))
    }
}

/// The relaxed forces at the end of this evaluation, the output forces from them, and their rate
/// there: F_x and F_y relaxed, M_z the steady state's, the utilisation against the friction
/// `friction` applied; the rate (V_r/L)(F_ss − F) of [`RelaxationLengths::rate`].
///
/// The relaxed force never exceeds the friction limit μQ of this evaluation's μ and Q
/// ([`within_friction_limit`]): relaxation lags the build-up of the elastic deformation, but no
/// stored deformation can hold a force beyond what Coulomb's law lets the tractions carry. (A
/// model without a friction limit, Kalker's linear theory, is bounded by its steady force
/// instead where that is larger.)
fn relax_forces(
    contact: &ContactInput,
    steady: &CreepForces,
    friction: f64,
    relaxed_forces: [f64; 2],
    renewal_speed: f64,
    relaxation_length: f64,
    evaluation: Evaluation,
) -> Result<(CreepForces, [f64; 2], [f64; 2]), InvalidInput> {
    if contact.transmits_no_force() {
        // Lift-off or no friction: the contact holds no elastic deformation to relax.
        return Ok((CreepForces { spin_moment: steady.spin_moment, ..CreepForces::default() }, [0.0; 2], [0.0; 2]));
    }
    let steady_forces = [steady.force_longitudinal, steady.force_lateral];
    // Checked at initialisation too, so that a bad length is reported at the start.
    let lengths = relaxation_lengths(contact, relaxation_length)?;
    let relaxed = match evaluation {
        // Initialised at the steady state: the outputs are the model's, exactly.
        Evaluation::Initialise => return Ok((*steady, steady_forces, [0.0; 2])),
        Evaluation::Step(step) => lengths.advance(relaxed_forces, steady_forces, renewal_speed, step)?,
    };
    let friction_limit = contact.normal_force * friction;
    // Kalker's linear theory has no friction limit: its forces may exceed μQ, and the relaxed
    // force is then bounded by the steady force it relaxes towards.
    let limit = friction_limit.max(steady.force_longitudinal.hypot(steady.force_lateral));
    let relaxed = within_friction_limit(relaxed, limit);
    let rate = lengths.rate(relaxed, steady_forces, renewal_speed);
    Ok((CreepForces::new(relaxed[0], relaxed[1], steady.spin_moment, friction_limit), relaxed, rate))
}

/// `forces` scaled onto the circle |F| = `friction_limit` if they lie outside it, unchanged
/// otherwise.
///
/// Why this bound: every traction of the contact obeys Coulomb's law |p| ≤ μ p_n, so the force
/// |F| = |∫p dA| ≤ ∫μ p_n dA = μQ whatever the history — a relaxed force above the limit (μ or Q
/// dropped within a step) is a deformation the contact cannot hold. The excess slides off at
/// once: the contact is then in full slip, where every traction is μ p_n along the slip, and the
/// slip that releases a stored elastic deformation runs along that deformation's own force, so the
/// force keeps its direction and takes the magnitude μQ — the radial projection. What calls for
/// it is a drop of μ or Q within a step: the relaxed law moves the force from where it was
/// towards a steady state inside the new, smaller disc, and only over the relaxation length.
fn within_friction_limit(forces: [f64; 2], friction_limit: f64) -> [f64; 2] {
    let magnitude = forces[0].hypot(forces[1]);
    if magnitude > friction_limit {
        let scale = friction_limit / magnitude;
        [forces[0] * scale, forces[1] * scale]
    } else {
        forces
    }
}
