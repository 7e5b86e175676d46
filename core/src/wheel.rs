//! A wheel on its rail, from profiles to forces: the contact patches of [`WheelOnRail`], each
//! patch's creepages from the wheelset's motion, its creep forces by any rung of the ladder (one
//! [`Scene`] evaluation per patch), and their sum on the wheel in track coordinates.
//!
//! A wheel with its profiles, the Manchester benchmark's case A-2.2 no. 3 (right wheel: the
//! wheelset 1 mm to the right, yawed 2.4 mrad, 10 kN on the wheel, V = 2 m/s, μ = 0.3), against
//! CONTACT's published full solution (rail y −18.54 mm, contact angle −0.0696 rad, N = 9827 N,
//! creep forces on the wheel 814 N and 2832 N, `core/tests/data/mbench_a22_contact_ref_out.csv`):
//!
//! ```
//! use wheel_rail_contact::geometry::{builtin_profile, SmoothProfile, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition};
//! use wheel_rail_contact::wheel::{VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity};
//! use wheel_rail_contact::scene::{Evaluation, Scene};
//! use wheel_rail_contact::{ModelChoice, Polach};
//!
//! let profile = |name| SmoothProfile::new(&builtin_profile(name).unwrap()).unwrap();
//! let (wheel, rail) = (profile("MBench_S1002"), profile("MBench_UIC60"));
//! let placed = WheelOnRail::new(wheel, rail, TrackDimensions::MANCHESTER_BENCHMARK, WheelSide::Right, 82e9, 0.28);
//! let contact = WheelRailContact::new(placed.unwrap(), Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28));
//! let input = WheelInput {
//!     position: WheelsetPosition { lateral: 1e-3, vertical: 0.0, roll: -5.049e-5, yaw: 2.4e-3 },
//!     velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3465752, ..WheelsetVelocity::default() },
//!     vertical: VerticalContact::PrescribedForce(10e3),
//!     friction_coefficient: 0.3,
//! };
//! let (output, _next_state) =
//!     contact.evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise).unwrap();
//! let patch = &output.patches[0];
//! assert_eq!(output.patches.len(), 1);
//! let point = patch.patch.point;
//! // Our Hertz point against the centre of CONTACT's non-elliptic patch: within 0.35 mm.
//! assert!((point.rail_lateral + 18.54e-3).abs() < 0.35e-3, "rail y {}", point.rail_lateral);
//! assert!((point.contact_angle + 0.0696).abs() < 0.002, "contact angle {}", point.contact_angle);
//! assert!((patch.patch.normal_force / 9827.0 - 1.0).abs() < 0.005, "N {}", patch.patch.normal_force);
//! // Polach on the tread: within 0.06 μN of CONTACT's exact theory on the real patch.
//! let within = |ours: f64, theirs: f64| (ours - theirs).abs() < 0.06 * 0.3 * 9827.0;
//! let (f_x, f_y) = (patch.output.force_longitudinal, patch.output.force_lateral);
//! assert!(within(f_x, 814.3) && within(f_y, 2832.0), "F_x {f_x}, F_y {f_y}");
//! // The wheel carries the prescribed 10 kN (z downward: the rail pushes up, −z).
//! assert!((output.track_force[2] + 10e3).abs() < 1e-6);
//! ```
//!
//! Frames (CONTACT's module 1): track x along the track in the rolling direction, y lateral to
//! the right, z down. A patch at contact angle δ has its own axes x (the track's), s = (0, cos δ,
//! sin δ) along the surfaces and n = (0, −sin δ, cos δ) into the rail. The wheelset's centre c
//! is on its axle at (0, y_ws, z_ws − r0); it moves at (V, ẏ_ws, 0) and turns at ω = ψ̇·e_z −
//! Ω·a, with a = R_z(ψ)R_x(φ)·e_y its axle (Ω > 0 rolls forward; CONTACT's VPITCH is −Ω).
//!
//! Creepages. The rail is at rest, so the slip of the wheel's point at the patch centre p is its
//! velocity v = v_c + ω × (p − c): ξ, η from v·e_x and v·s, φ from ω·n, each over the rolling
//! speed regularised through standstill ([`crate::scene::kinematics`]) — the wheel minus the
//! rail, as every creepage of this crate (CONTACT's CKSI, CETA, CPHI are the rail minus the
//! wheel, over its VELOC). The scene evaluates each patch with its creepages from these slip
//! velocities and its ellipse from the geometry (Hertz, [`WheelOnRail`]).
//!
//! Forces. A patch's creep forces F_x, F_s act on the wheel in its tangent plane (the negative of
//! CONTACT's FX, FS on the rail), its normal force N on the wheel along −n: in track axes
//! F = F_x·e_x + F_s·s − N·n. The wheel's totals are their sums, with the moments about c
//! (including each patch's spin moment M_z about n).
//!
//! Vertical balance. With a prescribed vertical force F_z, the rail carries the wheel through
//! both the normal and the creep forces: Σ (N cos δ − F_s sin δ) = F_z. On the flange (δ ≈ −1)
//! the creep force carries a third of the load. The normal problem is solved for the shares
//! s_i = cos δ_i − (F_s/N)_i sin δ_i of the last creep forces, the creep forces again for its
//! patches, until they carry F_z within [`BALANCE_TOLERANCE`], by secant steps on z_ws (three
//! rounds on the tread, four or five on the flange on A-2.2; [`VERTICAL_ROUNDS`] at most).
//!
//! Contact method ([`ContactMethod`]). The patches above are Hertz ellipses, one per minimum of
//! the undeformed gap ([`ContactCandidates`]). With [`ContactMethod::NonHertzian`] they are the
//! contact regions of the two profiles' interpenetration instead (Kik–Piotrowski,
//! [`crate::geometry::non_hertzian`]), each with its pressure centroid as the contact point and an
//! equivalent ellipse for the creep-force models; a prescribed vertical force is balanced by one
//! root search on z_ws whose every evaluation is a round as above (the patches at z_ws, their
//! creep forces, the vertical force both carry), started from the last step's z_ws. Where its
//! last two rounds nearly meet the force (the product of their relative misses below 1e-12)
//! the answer is interpolated between them at the search's next secant
//! step, the creep forces computed again there, instead of a round solved there: the normal
//! problem is most of a round's cost, and the interpolation's error is of the order of that
//! product (`WheelRailContact::interpolated_round`).
//!
//! Creep relaxation and the exact theory's warm start carry over per patch: a patch takes the
//! state of the last evaluation's patch nearest to it on the rail within [`PATCH_MATCH_DISTANCE`];
//! a new patch (a flange that comes into contact) starts from rest.

use std::fmt;

use crate::geometry::non_hertzian::{rising, Regions, Root};
use crate::geometry::{
    ContactCandidates, ContactPatch, ContactPoint, ProfileError, SwitchingFunctions, WheelOnRail, WheelsetPosition,
};
use crate::scene::kinematics::DEFAULT_REGULARISATION_SPEED;
use crate::scene::{
    CreepageSource, EllipseSource, Evaluation, Scene, SceneCache, SceneError, SceneInput, SceneOutput, SceneState,
};
use crate::InvalidInput;

/// How many rounds of normal problem and creep forces settle the vertical balance at most.
pub const VERTICAL_ROUNDS: usize = 12;

/// The vertical balance settles when the patches carry the prescribed force within this
/// fraction of it.
pub const BALANCE_TOLERANCE: f64 = 1e-10;

/// The non-Hertzian balance takes its answer between its last two rounds where the product of
/// their relative misses of the force is below this ([`WheelRailContact::interpolated_round`]):
/// the interpolation's error, of that order, stays below [`BALANCE_TOLERANCE`].
const INTERPOLATION_LIMIT: f64 = 1e-12;

/// A patch inherits the state of the last evaluation's patch within this distance on the rail
/// \[m\]: beyond a patch's half-width, closer than tread and flange are to each other.
pub const PATCH_MATCH_DISTANCE: f64 = 5e-3;

/// How the normal problem finds the patches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactMethod {
    /// One Hertz ellipse per minimum of the undeformed gap (2–4 µs a wheel step).
    #[default]
    Hertz,
    /// One patch per contact region of the profiles' virtual interpenetration (Kik–Piotrowski;
    /// CONTACT's accuracy where the gap is flat or conformal). A wheel step takes 21–180 µs with
    /// the exact strips, 5–22 µs with the strip table ([`WheelRailContact::with_strip_table`])
    /// where the step starts from the last one's z_ws, 17–83 µs from a cold start (Polach or
    /// `exact_table`, the benchmark's four poses; Hertz 3–5 µs in the same run;
    /// `crate::geometry::non_hertzian`, module doc, "Cost").
    NonHertzian,
}

/// The wheelset's velocities in track axes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelsetVelocity {
    /// V [m/s]: the wheelset centre's speed along the track.
    pub rolling_speed: f64,
    /// Ω [rad/s]: about the axle, positive when rolling forward (Ω r = V in pure rolling).
    pub wheel_angular_speed: f64,
    /// ẏ_ws [m/s].
    pub lateral_velocity: f64,
    /// ψ̇ [rad/s].
    pub yaw_rate: f64,
}

/// How the wheel's vertical contact is set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VerticalContact {
    /// The wheel carries this vertical force \[N\]; the wheelset's vertical position is solved
    /// for (the position's `vertical` is not read). ≤ 0 lifts the wheel off.
    PrescribedForce(f64),
    /// The wheelset is at its position's `vertical`; the forces follow from the penetration.
    PrescribedPosition,
}

/// What a wheel's evaluation reads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelInput {
    pub position: WheelsetPosition,
    pub velocity: WheelsetVelocity,
    pub vertical: VerticalContact,
    /// μ \[1\] (μ₀ under Polach 2005).
    pub friction_coefficient: f64,
}

/// One loaded patch: its geometry, normal force and ellipse, and the scene's outputs (its creep
/// forces on the wheel in the patch's tangent plane, creepages, spin moment).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchForces {
    pub patch: ContactPatch,
    pub output: SceneOutput,
}

impl PatchForces {
    /// The patch's force on the wheel in track axes \[N\] (module doc).
    pub fn track_force(&self) -> [f64; 3] {
        let (sin, cos) = self.patch.point.contact_angle_sin_cos();
        self.track_force_at(sin, cos)
    }

    /// [`Self::track_force`] with sin δ, cos δ known.
    fn track_force_at(&self, sin: f64, cos: f64) -> [f64; 3] {
        let (lateral, normal) = (self.output.force_lateral, self.patch.normal_force);
        [self.output.force_longitudinal, lateral * cos + normal * sin, lateral * sin - normal * cos]
    }
}

/// What a wheel's evaluation gives.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelOutput {
    /// The loaded patches, tread first (from the rail's field side to its gauge side).
    pub patches: Vec<PatchForces>,
    /// z_ws \[m\]: the prescribed one, or the one that carries the prescribed force.
    pub wheelset_vertical_position: f64,
    /// The sum of the patches' forces on the wheel, track axes \[N\].
    pub track_force: [f64; 3],
    /// Their moment about the wheelset's centre, track axes [N·m].
    pub track_moment: [f64; 3],
    /// The switching functions of the patches at this pose (`geometry/switching.rs`): their signs
    /// change where the patches jump.
    pub switching: SwitchingFunctions,
}

/// What a patch carries to the next evaluation.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PatchState {
    /// Where the patch was, y in the rail profile's coordinates \[m\].
    pub rail_lateral: f64,
    pub scene: SceneState,
}

/// What a wheel carries to the next evaluation: its patches' states, where its last
/// non-Hertzian vertical balance settled, and that balance's answer where it was interpolated.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WheelState {
    pub patches: Vec<PatchState>,
    pub balance: Option<BalanceStart>,
    /// (Boxed: unboxed, its 160 bytes, moved with every state, cost a Hertz wheel step 500
    /// instructions.)
    pub interpolated: Option<Box<InterpolatedBalance>>,
}

/// A non-Hertzian balance's answer interpolated between its last two rounds (the wheel's
/// `interpolated_round`, module doc, "Contact method"), kept so that an evaluation repeated at the same
/// pose and load gives it again, bit for bit: its patches with their creep forces computed
/// again (a round solved at its z_ws meets the force too, within the balance's tolerance, but
/// not at the same bits; reading an FMU's outputs at other inputs and back must give them as
/// the step did).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct InterpolatedBalance {
    /// The pose it is the answer at: y_ws \[m\], roll and yaw \[rad\].
    pub pose: [f64; 3],
    /// The vertical force it carries \[N\].
    pub vertical_force: f64,
    /// Its patches (their creep forces follow from the inputs and the state).
    pub patches: Vec<ContactPatch>,
    /// Its switching functions.
    pub switching: SwitchingFunctions,
}

impl WheelState {
    /// Checks a state read back from a saved one.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        for patch in &self.patches {
            if !patch.rail_lateral.is_finite() {
                return Err(InvalidInput::new("patch_rail_lateral_position", patch.rail_lateral, "must be finite"));
            }
            patch.scene.validate()?;
        }
        if let Some(balance) = &self.balance {
            for (name, value) in [("balance_vertical_position", balance.vertical), ("balance_touch", balance.touch)] {
                if !value.is_finite() {
                    return Err(InvalidInput::new(name, value, "must be finite"));
                }
            }
            if let Some(slope) = balance.slope.filter(|&slope| rising(slope).is_none()) {
                return Err(InvalidInput::new("balance_slope", slope, "must be finite and positive"));
            }
        }
        if let Some(answer) = &self.interpolated {
            let values = answer.pose.iter().chain([&answer.vertical_force]).chain(answer.switching.values().iter());
            if let Some(value) = values.copied().find(|value| !value.is_finite()) {
                return Err(InvalidInput::new("interpolated_balance", value, "must be finite"));
            }
            for patch in &answer.patches {
                let sizes = [patch.normal_force, patch.ellipse.semi_axis_a, patch.ellipse.semi_axis_b];
                if let Some(value) = sizes.into_iter().find(|value| !(value.is_finite() && *value > 0.0)) {
                    return Err(InvalidInput::new("interpolated_balance_patch", value, "must be finite and > 0"));
                }
                if let Some(value) = patch.point.values().into_iter().find(|value| !value.is_finite()) {
                    return Err(InvalidInput::new("interpolated_balance_point", value, "must be finite"));
                }
            }
        }
        Ok(())
    }
}

/// Where a non-Hertzian vertical balance settled ([`ContactMethod::NonHertzian`] with a
/// prescribed force), where the next one's root search starts: at the same depth below its
/// pose's touch (a step moves the wheelset little, and the depth that carries the load changes
/// less than z_ws, which follows the touch as the pose moves: on the flange by micrometres per
/// micrometre of y_ws), its first step along the same slope of the search's residual. Part of the
/// state, not of the [`WheelCache`], so that an evaluation is a function of its input and state
/// alone: the search meets the force within [`BALANCE_TOLERANCE`] wherever it starts, but not at
/// the same bits, and a step rolled back to a saved state, or inputs read back after others were
/// tried, must give the outputs they gave. At the same pose (the same touch) it starts at the
/// z_ws itself, so that an evaluation repeated from the state it left gives its outputs again
/// (bit for bit: a round's own answer by solving that round again, one interpolated between the
/// last two rounds by the [`InterpolatedBalance`] the state keeps).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BalanceStart {
    /// z_ws where the balance settled \[m\].
    pub vertical: f64,
    /// z_ws where the wheel first touched the rail at that pose \[m\].
    pub touch: f64,
    /// The slope of the search's residual there \[N^(2/3)/m\], where known.
    pub slope: Option<f64>,
}

impl BalanceStart {
    /// Where a search at a pose touching at `touch` starts.
    fn start(&self, touch: f64) -> Root {
        let vertical = if touch == self.touch { self.vertical } else { touch + (self.vertical - self.touch) };
        Root { vertical, slope: self.slope }
    }
}

/// Derived data for speed only: one scene cache per patch.
#[derive(Debug, Clone, Default)]
pub struct WheelCache {
    patches: Vec<SceneCache>,
    /// The non-Hertzian normal problems solved so far (each round of a balance solves one): what
    /// a balance costs, counted (the tests' measure of it).
    normal_solves: usize,
}

/// Why a wheel cannot be evaluated.
#[derive(Debug, Clone, PartialEq)]
pub enum WheelContactError {
    /// The geometry: the profiles, the position, the normal problem.
    Geometry(ProfileError),
    /// A patch's creep forces.
    Scene(SceneError),
}

impl fmt::Display for WheelContactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Geometry(error) => error.fmt(f),
            Self::Scene(error) => error.fmt(f),
        }
    }
}

impl std::error::Error for WheelContactError {}

impl From<ProfileError> for WheelContactError {
    fn from(error: ProfileError) -> Self {
        Self::Geometry(error)
    }
}

impl From<SceneError> for WheelContactError {
    fn from(error: SceneError) -> Self {
        Self::Scene(error)
    }
}

impl From<InvalidInput> for WheelContactError {
    fn from(error: InvalidInput) -> Self {
        Self::Scene(SceneError::Invalid(error))
    }
}

/// A wheel on its rail with the scene that gives each patch's creep forces.
///
/// The right wheel 5 mm to the right under 10 kN: a tread patch and one at the flange root, whose forces
/// (on the wheel, in track axes) sum to the wheel's; both vertical modes give the same wheel;
/// a state carries each patch's relaxation to the next step (see the module example in
/// [`crate::geometry`] for a case against CONTACT):
///
/// ```
/// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
/// use wheel_rail_contact::wheel::{VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity};
/// use wheel_rail_contact::scene::{Evaluation, Relaxation, Scene};
/// use wheel_rail_contact::{ModelChoice, Polach};
///
/// let placed = WheelOnRail::manchester_benchmark(WheelSide::Right);
/// let scene = Scene { relaxation: Relaxation::On { length: 0.01 }, ..Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28) };
/// let contact = WheelRailContact::new(placed, scene);
/// let input = WheelInput {
///     position: WheelsetPosition { lateral: 5e-3, yaw: 2e-3, ..WheelsetPosition::default() },
///     velocity: WheelsetVelocity { rolling_speed: 20.0, wheel_angular_speed: 20.0 / 0.46, ..WheelsetVelocity::default() },
///     vertical: VerticalContact::PrescribedForce(10e3),
///     friction_coefficient: 0.3,
/// };
/// let mut cache = WheelCache::default();
/// let (output, state) = contact.evaluate(&input, &WheelState::default(), &mut cache, Evaluation::Initialise).unwrap();
/// assert_eq!(output.patches.len(), 2, "tread and flange root");
/// let angles = output.patches.iter().map(|patch| patch.patch.point.contact_angle).collect::<Vec<_>>();
/// assert!(angles[0] > -0.15 && angles[1] < -0.25, "contact angles {angles:?}");
/// for axis in 0..3 {
///     let sum: f64 = output.patches.iter().map(|patch| patch.track_force()[axis]).sum();
///     assert!((sum - output.track_force[axis]).abs() < 1e-6);
/// }
/// assert!((output.track_force[2] + 10e3).abs() < 10e3 * 1e-10, "the balance carries 10 kN");
/// // The same wheel at the height the balance found, with the height prescribed.
/// let at_height = WheelInput {
///     position: WheelsetPosition { vertical: output.wheelset_vertical_position, ..input.position },
///     vertical: VerticalContact::PrescribedPosition,
///     ..input
/// };
/// let (same, _) = contact.evaluate(&at_height, &state, &mut cache, Evaluation::Initialise).unwrap();
/// assert!((same.track_force[1] - output.track_force[1]).abs() < 1e-3);
/// // A step of 1 ms from the relaxed state: finite forces, a state that validates.
/// let (_, next) = contact.evaluate(&input, &state, &mut cache, Evaluation::Step(1e-3)).unwrap();
/// assert!(next.validate().is_ok() && next.patches.len() == 2);
/// assert!(contact.geometry().contact_points(&input.position).unwrap().len() >= 2);
/// // Bad motion is an error naming the variable.
/// let spinning = WheelInput { velocity: WheelsetVelocity { yaw_rate: f64::NAN, ..input.velocity }, ..input };
/// let error = contact.evaluate(&spinning, &state, &mut cache, Evaluation::Step(1e-3)).unwrap_err();
/// assert!(error.to_string().contains("wheelset_yaw_rate"), "{error}");
/// ```
#[derive(Debug, Clone)]
pub struct WheelRailContact {
    geometry: WheelOnRail,
    scene: Scene,
    method: ContactMethod,
}

impl WheelRailContact {
    /// `scene` gives the model, the traction law, the relaxation and the material; its
    /// creepages come from the patch's slip velocities (with its regularisation speed, or the
    /// default one) and its ellipse from the geometry, whatever it selects.
    pub fn new(geometry: WheelOnRail, scene: Scene) -> Self {
        let regularisation_speed = match scene.creepages {
            CreepageSource::Kinematics { regularisation_speed } => regularisation_speed,
            CreepageSource::Inputs => DEFAULT_REGULARISATION_SPEED,
        };
        let scene = Scene {
            creepages: CreepageSource::Kinematics { regularisation_speed },
            ellipse: EllipseSource::Inputs,
            ..scene
        };
        Self { geometry, scene, method: ContactMethod::Hertz }
    }

    /// The same contact with its patches found by `method` (Hertz unless told).
    ///
    /// The centred wheelset of the Manchester benchmark (A-2.2 case 1, 10 kN): the Hertz ellipse
    /// sits at the gap's minimum, 1.4 mm from the middle of CONTACT's wide patch (rail
    /// y = −8.66 mm); the non-Hertzian patch's pressure centroid within 0.2 mm of it.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide};
    /// use wheel_rail_contact::scene::{Evaluation, Scene};
    /// use wheel_rail_contact::wheel::{ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity};
    /// use wheel_rail_contact::{ModelChoice, Polach};
    ///
    /// let rail_y = |method| {
    ///     let scene = Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28);
    ///     let contact = WheelRailContact::new(WheelOnRail::manchester_benchmark(WheelSide::Right), scene).with_method(method);
    ///     let input = WheelInput {
    ///         position: Default::default(),
    ///         velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3478, ..Default::default() },
    ///         vertical: VerticalContact::PrescribedForce(10e3),
    ///         friction_coefficient: 0.3,
    ///     };
    ///     let (output, _) =
    ///         contact.evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise).unwrap();
    ///     output.patches[0].patch.point.rail_lateral
    /// };
    /// assert!((rail_y(ContactMethod::Hertz) + 8.66e-3).abs() > 1e-3);
    /// assert!((rail_y(ContactMethod::NonHertzian) + 8.66e-3).abs() < 0.2e-3);
    /// ```
    pub fn with_method(self, method: ContactMethod) -> Self {
        Self { method, ..self }
    }

    /// The same contact with the non-Hertzian strips' geometry from tables
    /// ([`WheelOnRail::with_strip_table`]; under half a millisecond to build on S1002): worth it with
    /// [`ContactMethod::NonHertzian`] alone, which it makes several times faster within 2 nm
    /// of the exact gap.
    ///
    /// ```
    /// use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    /// use wheel_rail_contact::scene::{Evaluation, Scene};
    /// use wheel_rail_contact::wheel::{ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity};
    /// use wheel_rail_contact::{ModelChoice, Polach};
    ///
    /// let scene = Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28);
    /// let exact = WheelRailContact::new(WheelOnRail::manchester_benchmark(WheelSide::Right), scene)
    ///     .with_method(ContactMethod::NonHertzian);
    /// let tabled = exact.clone().with_strip_table();
    /// let input = WheelInput {
    ///     position: WheelsetPosition { lateral: 2e-3, yaw: 4.8e-3, ..Default::default() },
    ///     velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3478, ..Default::default() },
    ///     vertical: VerticalContact::PrescribedForce(10e3),
    ///     friction_coefficient: 0.3,
    /// };
    /// let step = |contact: &WheelRailContact| {
    ///     contact.evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise).unwrap().0
    /// };
    /// let (a, b) = (step(&exact), step(&tabled));
    /// // The same wheel within a nanometre and a millinewton.
    /// assert!((a.wheelset_vertical_position - b.wheelset_vertical_position).abs() < 1e-9);
    /// for axis in 0..3 {
    ///     assert!((a.track_force[axis] - b.track_force[axis]).abs() < 1e-3, "{:?} {:?}", a.track_force, b.track_force);
    /// }
    /// ```
    pub fn with_strip_table(self) -> Self {
        Self { geometry: self.geometry.with_strip_table(), ..self }
    }

    /// The wheel's placed profiles.
    pub fn geometry(&self) -> &WheelOnRail {
        &self.geometry
    }

    /// The forces for `input` from `state`, and the state after this evaluation (as
    /// [`Scene::evaluate`]).
    pub fn evaluate(
        &self,
        input: &WheelInput,
        state: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<(WheelOutput, WheelState), WheelContactError> {
        check_velocity(&input.velocity)?;
        let (vertical, patches, states, switching) = match input.vertical {
            VerticalContact::PrescribedPosition => {
                let vertical = input.position.vertical;
                let (patches, switching) = match self.method {
                    ContactMethod::Hertz => {
                        let candidates = self.geometry.candidates(&input.position)?;
                        (candidates.patches_at(vertical)?, candidates.switching_functions(vertical))
                    }
                    ContactMethod::NonHertzian => {
                        let mut pose = self.geometry.non_hertzian_pose(&input.position)?;
                        let (patches, regions) = pose.summaries_at(vertical)?;
                        (patches, pose.switching_functions(vertical, &regions)?)
                    }
                };
                let no_hints = WheelState::default();
                let (forces, states) =
                    self.patch_forces(input, &input.position, &patches, state, &no_hints, cache, evaluation)?;
                (vertical, forces, states, switching)
            }
            VerticalContact::PrescribedForce(force) => match self.method {
                ContactMethod::Hertz => {
                    let candidates = self.geometry.candidates(&input.position)?;
                    let (vertical, forces, states) =
                        self.balance_vertical_force(&candidates, force, input, state, cache, evaluation)?;
                    (vertical, forces, states, candidates.switching_functions(vertical))
                }
                ContactMethod::NonHertzian => self.balance_non_hertzian(force, input, state, cache, evaluation)?,
            },
        };
        let centre = self.geometry.wheelset_centre(&WheelsetPosition { vertical, ..input.position });
        let mut track_force = [0.0; 3];
        let mut track_moment = [0.0; 3];
        for patch in &patches {
            let point = &patch.patch.point;
            let (sin, cos) = point.contact_angle_sin_cos();
            let force = patch.track_force_at(sin, cos);
            let arm = [
                point.track_longitudinal - centre[0],
                point.track_lateral - centre[1],
                point.track_vertical - centre[2],
            ];
            let moment = cross(arm, force);
            let normal = patch_normal(sin, cos);
            for axis in 0..3 {
                track_force[axis] += force[axis];
                track_moment[axis] += moment[axis] + patch.output.spin_moment * normal[axis];
            }
        }
        let output =
            WheelOutput { patches, wheelset_vertical_position: vertical, track_force, track_moment, switching };
        Ok((output, states))
    }

    /// Prescribed vertical force: rounds of normal problem and creep forces (module doc). A
    /// round maps z_ws to the normal problem's z_ws under its creep forces' shares, G(z_ws);
    /// plain rounds z ← G(z) converge linearly, by a factor of about 0.001 a round on the tread
    /// and 0.1 on the flange. From the second round on, the next z_ws is the secant step on
    /// G(z) − z through the last two rounds (superlinear; the first is Aitken's Δ²), where it
    /// keeps the same patches and moves no further than a plain round would by much.
    ///
    /// Settled when the patches carry the force within [`BALANCE_TOLERANCE`], or when a round
    /// moves z_ws by no more than its rounding (a load of millinewtons penetrates nanometres,
    /// which z_ws resolves to some 1e-10 of the load). Where the rounds do not settle — G jumps
    /// where two patches join or part, and the fixed point can lie in the jump — a bisection on
    /// G(z) − z between rounds of opposite sign closes in on it, and the side that carries the
    /// force more closely is the answer.
    fn balance_vertical_force(
        &self,
        candidates: &ContactCandidates,
        force: f64,
        input: &WheelInput,
        state: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<(f64, Vec<PatchForces>, WheelState), WheelContactError> {
        // The first round without creep forces: each patch's share is cos δ.
        let (mut vertical, mut patches) =
            candidates.patches_for_force(force, |point| point.contact_angle_sin_cos().1)?;
        let touch = candidates.touch();
        // What z_ws resolves near here: a few of its ulps.
        let resolution = |z: f64| 4.0 * f64::EPSILON * z.abs().max(touch.abs());
        // Each round's model memory starts the next round's (the exact theory's warm start: the
        // rounds differ by little); the relaxed forces always start from `state`.
        let mut hints = WheelState::default();
        // The last round's z_ws and its residual G(z_ws) − z_ws.
        let mut last: Option<(f64, f64)> = None;
        // The rounds' z_ws with a residual ≥ 0 and < 0, closest to each other: the bracket.
        let (mut below, mut above): (Option<f64>, Option<f64>) = (None, None);
        for _ in 0..VERTICAL_ROUNDS {
            let round = self.round(candidates, force, input, vertical, &patches, state, &hints, cache, evaluation)?;
            let Round { forces, states, next, .. } = round;
            // Settled when the rail carries F_z through these normal and creep forces.
            let Some((next, next_patches)) = next else { return Ok((vertical, forces, states)) };
            // The secant step on the round's residual r(z) = G(z) − z through this round and the
            // last: the root of the line through them (from a plain round's two, Aitken's Δ²).
            let residual = next - vertical;
            if residual.abs() <= resolution(vertical) {
                return Ok((vertical, forces, states));
            }
            hints = states;
            if residual >= 0.0 {
                below = Some(below.map_or(vertical, |b: f64| b.max(vertical)));
            } else {
                above = Some(above.map_or(vertical, |a: f64| a.min(vertical)));
            }
            let same = |patches: &[ContactPatch]| patches.len() == next_patches.len();
            let secant = last
                .and_then(|last| secant_root(last, (vertical, residual)))
                .and_then(|root| candidates.patches_at(root).ok().filter(|p| same(p)).map(|patches| (root, patches)));
            last = Some((vertical, residual));
            (vertical, patches) = secant.unwrap_or((next, next_patches));
        }
        let unsettled = || -> WheelContactError {
            ProfileError::whole(format!(
                "vertical_force = {force} N: the vertical balance with the creep forces did not settle in \
                 {VERTICAL_ROUNDS} rounds"
            ))
            .into()
        };
        let (Some(mut low), Some(mut high)) = (below, above) else { return Err(unsettled()) };
        if low > high {
            // G(z) − z falls through zero between them (it rises with z nowhere a round saw).
            return Err(unsettled());
        }
        // Bisection of r(z) = G(z) − z on [low, high] to z_ws's rounding (≤ 64 halvings), each
        // end's round kept; the end whose patches carry the force more closely is the answer.
        let mut best: Option<(f64, f64, Vec<PatchForces>, WheelState)> = None;
        for _ in 0..64 {
            let middle = 0.5 * (low + high);
            if high - low <= resolution(middle) || middle <= low || middle >= high {
                break;
            }
            let patches = candidates.patches_at(middle)?;
            let round = self.round(candidates, force, input, middle, &patches, state, &hints, cache, evaluation)?;
            let Some((next, _)) = round.next else { return Ok((middle, round.forces, round.states)) };
            let miss = (round.carried - force).abs();
            if next >= middle {
                low = middle;
            } else {
                high = middle;
            }
            if best.as_ref().is_none_or(|(_, best_miss, _, _)| miss < *best_miss) {
                best = Some((middle, miss, round.forces, round.states));
            }
        }
        best.map(|(vertical, _, forces, states)| (vertical, forces, states)).ok_or_else(unsettled)
    }

    /// Prescribed vertical force with non-Hertzian patches: z_ws where the rail carries F_z
    /// through the normal and the creep forces of the patches at z_ws within
    /// [`BALANCE_TOLERANCE`] (module doc), found by the non-Hertzian problem's own root search
    /// ([`crate::geometry::NonHertzianPose`]: secant steps on the carried force's 2/3 power,
    /// then a bracket) with each evaluation a round — the patches at z_ws, their creep forces,
    /// the vertical force they carry together — started at the last step's depth below the
    /// touch, its first step along the last search's slope ([`BalanceStart`], in `state`). The
    /// carried force is nearly the normal forces' alone, whose 2/3 power the search's secants
    /// nearly meet: 2–6 rounds, where solving the frictionless problem to 1e-12 for each
    /// corrected load took 16–34.
    ///
    /// Where the carried force is not smooth the rounds close in on a step: on a narrow flange
    /// patch the equivalent ellipse's width moves by a strip (0.1 mm of some 0.5 mm) as a strip
    /// enters, and with it the creep forces' share by some 100 N. Then the bracket closes on the
    /// step and the round that carries F_z more closely is the answer (as the Hertz balance does
    /// where patches join).
    ///
    /// Where the carried force is not monotonic in z_ws the balance can have two roots, and the
    /// start picks one: at the tread-to-flange transition (right wheel, y_ws 6.42 mm, roll
    /// 1.9 mrad, yaw −4.0 mrad, 58.7 kN, V 19.3 m/s) two z_ws 1.4 µm apart both carry F_z within
    /// 1e-10, with the patch's F_s −3956 N and −8606 N. From a cold cache (10 µm into the rail)
    /// the search finds the root the former rounds found (on 240 sampled poses, and there); from
    /// the Hertz patches' z_ws it found the other; from the last step's z_ws it starts at the
    /// root the last step found (a sweep through such a pose is not tested).
    fn balance_non_hertzian(
        &self,
        force: f64,
        input: &WheelInput,
        state: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<Balanced, WheelContactError> {
        let position = &input.position;
        let at = [position.lateral, position.roll, position.yaw];
        if let Some(replay) = self.replay(force, input, at, state, cache, evaluation)? {
            return Ok(replay);
        }
        let mut pose = self.geometry.non_hertzian_pose(&input.position)?;
        // Each round's model memory starts the next round's (the exact theory's warm start: the
        // rounds differ by little); the relaxed forces always start from `state`.
        let mut hints = WheelState::default();
        // Per round: its z_ws, its answer (its own, or one between it and the round before,
        // `interpolated_round`), its regions.
        let mut rounds: Vec<(f64, RoundAnswer, Regions)> = Vec::new();
        let mut last: Option<(f64, f64, Vec<ContactPatch>)> = None;
        let touch = pose.touch();
        let start = state.balance.map(|balance| balance.start(touch));
        let root = pose.vertical_for_force(force, start, BALANCE_TOLERANCE, |pose, vertical| {
            let (patches, regions) = pose.summaries_at(vertical)?;
            cache.normal_solves += 1;
            let position = WheelsetPosition { vertical, ..input.position };
            let (forces, states) = self.patch_forces(input, &position, &patches, state, &hints, cache, evaluation)?;
            let carried = carried_by(&forces);
            hints = states.clone();
            let between = match &last {
                Some((last_vertical, last_carried, last_patches)) => self.interpolated_round(
                    force,
                    input,
                    [(*last_vertical, *last_carried, last_patches), (vertical, carried, &patches)],
                    state,
                    &hints,
                    cache,
                    evaluation,
                )?,
                None => None,
            };
            last = Some((vertical, carried, patches));
            let answer = between.unwrap_or(RoundAnswer { vertical, forces, states, carried });
            let carried = answer.carried;
            rounds.push((vertical, answer, regions));
            Ok::<_, WheelContactError>(carried)
        })?;
        // The answer is a round's, but at lift-off (the touch, no patch); the next search starts
        // at its z_ws.
        match rounds.into_iter().rev().find(|round| round.0 == root.vertical) {
            Some((vertical, RoundAnswer { vertical: answer, forces, states, .. }, regions)) => {
                let switching = pose.switching_functions(vertical, &regions)?;
                let balance = Some(BalanceStart { vertical: answer, touch, slope: root.slope });
                let interpolated = (answer != vertical).then(|| {
                    Box::new(InterpolatedBalance {
                        pose: at,
                        vertical_force: force,
                        patches: forces.iter().map(|patch| patch.patch).collect(),
                        switching,
                    })
                });
                Ok((answer, forces, WheelState { balance, interpolated, ..states }, switching))
            }
            None => {
                let balance = Some(BalanceStart { vertical: root.vertical, touch, slope: root.slope });
                let state = WheelState { patches: Vec::new(), balance, interpolated: None };
                Ok((root.vertical, Vec::new(), state, SwitchingFunctions::default()))
            }
        }
    }

    /// The answer `state` keeps from an interpolated balance ([`InterpolatedBalance`]) where this
    /// evaluation is at its pose and load, bit for bit: its patches at its z_ws, their creep
    /// forces computed again, if they carry the load within [`BALANCE_TOLERANCE`] (they do
    /// unless the velocities or the friction changed the creep forces' share); `None` otherwise.
    fn replay(
        &self,
        force: f64,
        input: &WheelInput,
        at: [f64; 3],
        state: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<Option<Balanced>, WheelContactError> {
        let (Some(answer), Some(balance)) = (&state.interpolated, state.balance) else { return Ok(None) };
        if answer.pose != at || answer.vertical_force != force {
            return Ok(None);
        }
        let position = WheelsetPosition { vertical: balance.vertical, ..input.position };
        let no_hints = WheelState::default();
        let (forces, states) =
            self.patch_forces(input, &position, &answer.patches, state, &no_hints, cache, evaluation)?;
        if !meets(carried_by(&forces), force) {
            return Ok(None);
        }
        let state = WheelState { balance: Some(balance), interpolated: Some(answer.clone()), ..states };
        Ok(Some((balance.vertical, forces, state, answer.switching)))
    }

    /// The balance between the last two rounds of the non-Hertzian root search, where they
    /// nearly meet F_z (`force`): at the root z* of the line through their residuals (the
    /// search's own next secant step, on the carried force's 2/3 power) each patch interpolated
    /// linearly in z_ws between the two rounds' ([`ContactPatch::interpolated`]; the same
    /// patches in both), their creep forces again. Interpolation misses the patches solved at z*
    /// by ½ P'' (z* − z₀)(z* − z₁), of the order of the product of the two rounds' misses of F_z
    /// (relative to the depth below the touch, which grows as F_z^(2/3)): taken where that
    /// product is below [`INTERPOLATION_LIMIT`] and the carried force then meets F_z within
    /// [`BALANCE_TOLERANCE`]. The last round of a search (misses of, say, 1e-5 then 1e-8 of
    /// F_z before a round that meets it) costs the moving centred wheelset's step some 60 000
    /// instructions of 234 000; the creep forces a few hundred a patch. `None` otherwise (the
    /// search goes on). The answer: z*, its forces and states, the force they carry.
    #[allow(clippy::too_many_arguments)]
    fn interpolated_round(
        &self,
        force: f64,
        input: &WheelInput,
        [(vertical_0, carried_0, patches_0), (vertical_1, carried_1, patches_1)]: [(f64, f64, &[ContactPatch]); 2],
        state: &WheelState,
        hints: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<Option<RoundAnswer>, WheelContactError> {
        let misses = [carried_0, carried_1].map(|carried| (carried - force) / force);
        if misses[1].abs() <= BALANCE_TOLERANCE
            || (misses[0] * misses[1]).abs() > INTERPOLATION_LIMIT
            || patches_0.len() != patches_1.len()
            || patches_1.is_empty()
        {
            return Ok(None);
        }
        let target = force.powf(2.0 / 3.0);
        let [residual_0, residual_1] = [carried_0, carried_1].map(|carried| carried.powf(2.0 / 3.0) - target);
        let t = residual_0 / (residual_0 - residual_1);
        let vertical = vertical_0 + t * (vertical_1 - vertical_0);
        if !vertical.is_finite() {
            return Ok(None);
        }
        let patches: Vec<ContactPatch> = patches_0.iter().zip(patches_1).map(|(p, q)| p.interpolated(q, t)).collect();
        let position = WheelsetPosition { vertical, ..input.position };
        let (forces, states) = self.patch_forces(input, &position, &patches, state, hints, cache, evaluation)?;
        let carried = carried_by(&forces);
        Ok(meets(carried, force).then_some(RoundAnswer { vertical, forces, states, carried }))
    }

    /// One round of the vertical balance at z_ws = `vertical` with these `patches`: their creep
    /// forces, the force the rail carries through them, and, unless these settle the balance
    /// (the rail carries F_z within [`BALANCE_TOLERANCE`]), the normal problem's z_ws (with its
    /// patches) under the shares of these creep forces, G(z_ws).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn round(
        &self,
        candidates: &ContactCandidates,
        force: f64,
        input: &WheelInput,
        vertical: f64,
        patches: &[ContactPatch],
        state: &WheelState,
        hints: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<Round, WheelContactError> {
        let position = WheelsetPosition { vertical, ..input.position };
        let (forces, states) = self.patch_forces(input, &position, patches, state, hints, cache, evaluation)?;
        let carried = carried_by(&forces);
        if forces.is_empty() || meets(carried, force) {
            return Ok(Round { forces, states, carried, next: None });
        }
        let share = |point: &ContactPoint| {
            let (sin, cos) = point.contact_angle_sin_cos();
            let traction = forces
                .iter()
                .find(|p| p.patch.point.track_lateral == point.track_lateral)
                .map_or(0.0, |p| p.output.force_lateral / p.patch.normal_force);
            cos - traction * sin
        };
        let next = candidates.patches_for_force_near(force, share, Some(vertical))?;
        Ok(Round { forces, states, carried, next: Some(next) })
    }

    /// Each patch's creep forces (module doc), with the state of the nearest last patch, its
    /// model memory from the nearest patch of `hints` if there is one.
    #[allow(clippy::too_many_arguments)]
    fn patch_forces(
        &self,
        input: &WheelInput,
        position: &WheelsetPosition,
        patches: &[ContactPatch],
        state: &WheelState,
        hints: &WheelState,
        cache: &mut WheelCache,
        evaluation: Evaluation,
    ) -> Result<(Vec<PatchForces>, WheelState), WheelContactError> {
        cache.patches.resize_with(patches.len().max(cache.patches.len()), SceneCache::default);
        let centre = self.geometry.wheelset_centre(position);
        let axle = wheelset_axle(position);
        let mut forces = Vec::with_capacity(patches.len());
        let mut states = Vec::with_capacity(patches.len());
        for (patch, patch_cache) in patches.iter().zip(&mut cache.patches) {
            let scene_input = patch_scene_input(patch, &centre, &axle, &input.velocity, input.friction_coefficient);
            let mut last = nearest(state, patch).map(|last| last.scene.clone()).unwrap_or_default();
            if let Some(hint) = nearest(hints, patch) {
                last.model = hint.scene.model.clone();
            }
            let scene = self.patch_scene(patch);
            let (output, scene_state) = scene.evaluate(&scene_input, &last, patch_cache, evaluation)?;
            forces.push(PatchForces { patch: *patch, output });
            states.push(PatchState { rail_lateral: patch.point.rail_lateral, scene: scene_state });
        }
        Ok((forces, WheelState { patches: states, balance: None, interpolated: None }))
    }
}

impl WheelRailContact {
    /// The scene for one patch: the chosen rung, or the one the ladder hands a patch of this
    /// shape to ([`crate::ModelChoice::for_ellipse`]).
    fn patch_scene(&self, patch: &ContactPatch) -> Scene {
        let a_over_b = patch.ellipse.semi_axis_a / patch.ellipse.semi_axis_b;
        Scene { model: self.scene.model.for_ellipse(a_over_b), ..self.scene }
    }
}

/// A balanced wheel: z_ws, its patches' forces, its state, its switching functions.
type Balanced = (f64, Vec<PatchForces>, WheelState, SwitchingFunctions);

/// A non-Hertzian round's answer ([`WheelRailContact::interpolated_round`]): z_ws, the patches'
/// forces and states there, the vertical force they carry \[N\].
struct RoundAnswer {
    vertical: f64,
    forces: Vec<PatchForces>,
    states: WheelState,
    carried: f64,
}

/// Whether the rail carries the prescribed `force` within [`BALANCE_TOLERANCE`].
fn meets(carried: f64, force: f64) -> bool {
    (carried - force).abs() <= BALANCE_TOLERANCE * force
}

/// The vertical force the rail carries through these patches \[N\].
fn carried_by(forces: &[PatchForces]) -> f64 {
    forces.iter().map(|patch| -patch.track_force()[2]).sum()
}

/// One round of the vertical balance ([`WheelRailContact::round`]).
struct Round {
    forces: Vec<PatchForces>,
    states: WheelState,
    /// The vertical force the rail carries through `forces` \[N\].
    carried: f64,
    /// G(z_ws) and its patches; `None` when `forces` settle the balance.
    next: Option<(f64, Vec<ContactPatch>)>,
}

/// The secant step on a residual r(z): the root of the line through (z₀, r₀) and (z₁, r₁), if
/// it lies no further from z₁ than |z₁ − z₀| + |r₁| (the last step and a plain round together);
/// `None` where the line is flat or the root further off.
fn secant_root((last_vertical, last_residual): (f64, f64), (vertical, residual): (f64, f64)) -> Option<f64> {
    let root = vertical - residual * (vertical - last_vertical) / (residual - last_residual);
    let near = (root - vertical).abs() < (vertical - last_vertical).abs() + residual.abs();
    (root.is_finite() && near).then_some(root)
}

/// The patch of `state` nearest to `patch` on the rail, within [`PATCH_MATCH_DISTANCE`].
fn nearest<'a>(state: &'a WheelState, patch: &ContactPatch) -> Option<&'a PatchState> {
    let distance = |last: &PatchState| (last.rail_lateral - patch.point.rail_lateral).abs();
    state
        .patches
        .iter()
        .filter(|last| distance(last) < PATCH_MATCH_DISTANCE)
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
}

/// The scene's input for one patch: its slip velocities (module doc) as the kinematics option
/// reads them — the circumferential speed Ω_eff·r that leaves V − Ω_eff·r = v·e_x, the lateral
/// slip v·s and the spin ω·n — with its load and ellipse.
fn patch_scene_input(
    patch: &ContactPatch,
    centre: &[f64; 3],
    axle: &[f64; 3],
    velocity: &WheelsetVelocity,
    friction_coefficient: f64,
) -> SceneInput {
    let point = &patch.point;
    let spin = velocity.wheel_angular_speed;
    let angular = [-spin * axle[0], -spin * axle[1], velocity.yaw_rate - spin * axle[2]];
    let arm = [point.track_longitudinal - centre[0], point.track_lateral - centre[1], point.track_vertical - centre[2]];
    let turning = cross(angular, arm);
    let slip = [velocity.rolling_speed + turning[0], velocity.lateral_velocity + turning[1], turning[2]];
    let (sin, cos) = point.contact_angle_sin_cos();
    let normal = patch_normal(sin, cos);
    SceneInput {
        normal_force: patch.normal_force,
        semi_axis_a: patch.ellipse.semi_axis_a,
        semi_axis_b: patch.ellipse.semi_axis_b,
        friction_coefficient,
        rolling_speed: velocity.rolling_speed,
        wheel_angular_speed: (velocity.rolling_speed - slip[0]) / point.rolling_radius,
        wheel_rolling_radius: point.rolling_radius,
        lateral_slip_velocity: slip[1] * cos + slip[2] * sin,
        spin_angular_velocity: dot(angular, normal),
        ..SceneInput::default()
    }
}

/// The wheelset's axle a = R_z(ψ)R_x(φ)·e_y in track axes.
fn wheelset_axle(position: &WheelsetPosition) -> [f64; 3] {
    let (sin_roll, cos_roll) = position.roll.sin_cos();
    let (sin_yaw, cos_yaw) = position.yaw.sin_cos();
    [-cos_roll * sin_yaw, cos_roll * cos_yaw, sin_roll]
}

/// A patch's normal n = (0, −sin δ, cos δ), into the rail, from sin δ and cos δ.
fn patch_normal(sin: f64, cos: f64) -> [f64; 3] {
    [0.0, -sin, cos]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn check_velocity(velocity: &WheelsetVelocity) -> Result<(), InvalidInput> {
    for (variable, value) in [
        ("rolling_speed", velocity.rolling_speed),
        ("wheel_angular_speed", velocity.wheel_angular_speed),
        ("wheelset_lateral_velocity", velocity.lateral_velocity),
        ("wheelset_yaw_rate", velocity.yaw_rate),
    ] {
        if !value.is_finite() {
            return Err(InvalidInput::new(variable, value, "must be finite"));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{
        secant_root, BalanceStart, ContactMethod, VerticalContact, WheelCache, WheelInput, WheelRailContact,
        WheelState, WheelsetVelocity,
    };
    use crate::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
    use crate::scene::{Evaluation, Scene};
    use crate::{ModelChoice, Polach};

    /// The right wheel on S1002/UIC60 with the non-Hertzian patches, Polach.
    fn non_hertzian_wheel() -> WheelRailContact {
        let scene = Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28);
        WheelRailContact::new(WheelOnRail::manchester_benchmark(WheelSide::Right), scene)
            .with_method(ContactMethod::NonHertzian)
            .with_strip_table()
    }

    /// Rolling at 20 m/s, yaw 2 mrad, at y_ws = `lateral` under `load`.
    fn rolling(lateral: f64, load: f64) -> WheelInput {
        WheelInput {
            position: WheelsetPosition { lateral, vertical: 0.0, roll: 0.0, yaw: 0.002 },
            velocity: WheelsetVelocity { rolling_speed: 20.0, wheel_angular_speed: 43.48, ..Default::default() },
            vertical: VerticalContact::PrescribedForce(load),
            friction_coefficient: 0.3,
        }
    }

    /// The first step of a wheelset moving 1 µm a step from y_ws = 2 mm under 50 kN whose
    /// balance is interpolated: its input, its state before, its output and the state it left.
    fn first_interpolated_step(
        contact: &WheelRailContact,
        cache: &mut WheelCache,
    ) -> (WheelInput, WheelState, super::WheelOutput, WheelState) {
        let mut state = WheelState::default();
        for k in 0..20 {
            let input = rolling(2e-3 + 1e-6 * f64::from(k), 50e3);
            let (output, next) = contact.evaluate(&input, &state, cache, Evaluation::Initialise).unwrap();
            if next.interpolated.is_some() {
                return (input, state, output, next);
            }
            state = next;
        }
        panic!("no interpolated balance in 20 steps");
    }

    /// An interpolated answer is kept in the state ([`super::InterpolatedBalance`]) and given
    /// again, bit for bit and without a normal problem solved, by an evaluation from that state
    /// at its pose and load; at another load, or with another friction (the creep forces' share
    /// of the load changed), the search runs and meets the load.
    #[test]
    fn an_interpolated_balance_is_given_again_at_its_pose_and_load() {
        let contact = non_hertzian_wheel();
        let mut cache = WheelCache::default();
        let (input, state, output, left) = first_interpolated_step(&contact, &mut cache);
        let kept = left.interpolated.clone().unwrap();
        assert_eq!((kept.pose, kept.vertical_force), ([input.position.lateral, 0.0, 0.002], 50e3));
        // What is kept is an answer no round solved: the patches solved at its z_ws are within
        // about the balance's tolerance of it, not the same bits.
        let placed = WheelInput {
            position: WheelsetPosition { vertical: output.wheelset_vertical_position, ..input.position },
            vertical: VerticalContact::PrescribedPosition,
            ..input
        };
        let (solved, _) =
            contact.evaluate(&placed, &state, &mut WheelCache::default(), Evaluation::Initialise).unwrap();
        let (p, q) = (&solved.patches[0].patch, &output.patches[0].patch);
        assert_ne!(p, q);
        assert!((p.normal_force / q.normal_force - 1.0).abs() < 1e-9, "{p:?} against {q:?}");
        assert!((p.ellipse.semi_axis_a / q.ellipse.semi_axis_a - 1.0).abs() < 1e-9, "{p:?} against {q:?}");
        let solves = cache.normal_solves;
        let (again, after) = contact.evaluate(&input, &left, &mut cache, Evaluation::Initialise).unwrap();
        assert_eq!(again, output);
        assert_eq!(after, left);
        assert_eq!(cache.normal_solves, solves, "given again without a normal problem solved");
        let heavier = WheelInput { vertical: VerticalContact::PrescribedForce(50.5e3), ..input };
        let (other, _) = contact.evaluate(&heavier, &left, &mut cache, Evaluation::Initialise).unwrap();
        assert!(cache.normal_solves > solves);
        assert!((other.track_force[2] / -50.5e3 - 1.0).abs() <= super::BALANCE_TOLERANCE);
        // At its pose and load but with less friction the kept patches' creep forces carry
        // another share of the load: not given again, the search meets the load.
        let solves = cache.normal_solves;
        let slippery = WheelInput { friction_coefficient: 0.2, ..input };
        let (other, _) = contact.evaluate(&slippery, &left, &mut cache, Evaluation::Initialise).unwrap();
        assert!(cache.normal_solves > solves);
        assert!((other.track_force[2] / -50e3 - 1.0).abs() <= super::BALANCE_TOLERANCE);
    }

    /// A wheelset moving 1 µm a step over 0.1 mm from `lateral` under `load`, each step from the
    /// last one's state: the mean number of normal problems solved a step; and each step's
    /// answer against the same pose's from no state (a search from 10 µm into the rail, which
    /// ends elsewhere): the largest difference of the totals over F_z, and of the patches' normal
    /// forces and semi-axes, relative.
    fn a_moving_wheel(lateral: f64, load: f64) -> (f64, f64, f64) {
        let contact = non_hertzian_wheel();
        let (mut state, mut cache) = (WheelState::default(), WheelCache::default());
        let (mut totals, mut patches) = (0.0f64, 0.0f64);
        let steps = 100;
        for k in 0..=steps {
            let input = rolling(lateral + 1e-6 * f64::from(k), load);
            let (warm, next) = contact.evaluate(&input, &state, &mut cache, Evaluation::Initialise).unwrap();
            state = next;
            // The first step, from no state, is not counted.
            if k == 0 {
                cache.normal_solves = 0;
            }
            let cold =
                contact.evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise);
            let cold = cold.unwrap().0;
            for axis in 0..3 {
                totals = totals.max((warm.track_force[axis] - cold.track_force[axis]).abs() / load);
            }
            assert_eq!(warm.patches.len(), cold.patches.len());
            for (p, q) in warm.patches.iter().zip(&cold.patches) {
                let (p, q) = (&p.patch, &q.patch);
                for (x, y) in [
                    (p.normal_force, q.normal_force),
                    (p.ellipse.semi_axis_a, q.ellipse.semi_axis_a),
                    (p.ellipse.semi_axis_b, q.ellipse.semi_axis_b),
                ] {
                    patches = patches.max((x / y - 1.0).abs());
                }
            }
        }
        (cache.normal_solves as f64 / f64::from(steps), totals, patches)
    }

    /// A moving step's balance takes its answer between its last two rounds
    /// ([`WheelRailContact::interpolated_round`]) where they nearly meet the force: on the tread
    /// (2 mm, 50 kN) 2.2 normal problems a step (3.0 when each round had to meet it), near the
    /// centred wheelset (0.1 mm, 10 kN) 3.0 (3.88); and the answer is the one a search from no
    /// state finds, within about the balance's tolerance (measured: 7e-11 and 1.3e-10 of F_z in
    /// the totals, the same relative in the patches, as before). (From 0 mm the warm and the
    /// cold search settle on different roots beyond y_ws = 56 µm, with or without the
    /// interpolation: docs/geometry.md, "Known limits".)
    #[test]
    fn a_moving_steps_balance_interpolates_its_last_rounds() {
        for (lateral, load, most) in [(2e-3, 50e3, 2.4), (0.1e-3, 10e3, 3.3)] {
            let (solves, totals, patches) = a_moving_wheel(lateral, load);
            assert!(solves <= most, "y_ws {lateral}: {solves} normal problems a step");
            assert!(totals < 5e-10 && patches < 5e-10, "y_ws {lateral}: totals {totals:e}, patches {patches:e}");
        }
    }

    /// A balance's start: at the same pose (the same touch) its own z_ws, bit for bit; at
    /// another, the same depth below the new touch; its slope as kept.
    #[test]
    fn a_balance_starts_at_its_z_ws_or_at_its_depth_below_a_moved_touch() {
        let balance = BalanceStart { vertical: 0.1 + 0.2, touch: 0.1, slope: Some(3.0) };
        let same = balance.start(0.1);
        assert_eq!((same.vertical.to_bits(), same.slope), ((0.1f64 + 0.2).to_bits(), Some(3.0)));
        let moved = balance.start(0.5);
        assert_eq!((moved.vertical, moved.slope), (0.5 + (0.1 + 0.2 - 0.1), Some(3.0)));
        assert!((moved.vertical - 0.7).abs() < 1e-15);
    }

    /// A state read back with a balance that is not finite, or a slope that does not rise, is
    /// refused with the quantity named; a sound one, or none, is accepted.
    /// A kept interpolated answer with a number that is not finite (or a size not > 0) is
    /// refused, its name given.
    #[test]
    fn a_state_with_an_unsound_interpolated_balance_is_refused() {
        let (.., sound) = first_interpolated_step(&non_hertzian_wheel(), &mut WheelCache::default());
        assert!(sound.validate().is_ok());
        let spoilt = |spoil: &dyn Fn(&mut super::InterpolatedBalance)| {
            let mut state = sound.clone();
            spoil(state.interpolated.as_mut().unwrap());
            state.validate().unwrap_err().to_string()
        };
        assert!(spoilt(&|a| a.pose[0] = f64::NAN).contains("interpolated_balance"));
        assert!(spoilt(&|a| a.vertical_force = f64::INFINITY).contains("interpolated_balance"));
        assert!(spoilt(&|a| a.patches[0].normal_force = 0.0).contains("interpolated_balance_patch"));
        assert!(spoilt(&|a| a.patches[0].ellipse.semi_axis_b = -1e-3).contains("interpolated_balance_patch"));
        assert!(spoilt(&|a| a.patches[0].point.track_vertical = f64::NAN).contains("interpolated_balance_point"));
    }

    #[test]
    fn a_state_with_an_unsound_balance_is_refused() {
        let sound = BalanceStart { vertical: 2e-5, touch: 1e-6, slope: Some(4e7) };
        let state = |balance| WheelState { balance, ..WheelState::default() };
        assert!(state(Some(sound)).validate().is_ok());
        assert!(state(Some(BalanceStart { slope: None, ..sound })).validate().is_ok());
        assert!(state(None).validate().is_ok());
        for (balance, name) in [
            (BalanceStart { vertical: f64::NAN, ..sound }, "balance_vertical_position"),
            (BalanceStart { touch: f64::INFINITY, ..sound }, "balance_touch"),
            (BalanceStart { slope: Some(0.0), ..sound }, "balance_slope"),
            (BalanceStart { slope: Some(-4e7), ..sound }, "balance_slope"),
            (BalanceStart { slope: Some(f64::INFINITY), ..sound }, "balance_slope"),
        ] {
            let error = state(Some(balance)).validate().unwrap_err();
            assert!(error.to_string().contains(name), "{error} for {balance:?}");
        }
    }

    #[test]
    fn the_secant_step_finds_a_linear_residuals_root_and_refuses_far_or_flat_lines() {
        // r(z) = −0.3 (z − 2): through (0, 0.6) and (1, 0.3) the root 2, one plain round and the
        // last step away at most (|2 − 1| = 1 < 1 + 0.3).
        assert_eq!(secant_root((0.0, 0.6), (1.0, 0.3)), Some(2.0));
        // r(z) = 0.5 (z − 1) from the other side: through (3, 1) and (2, 0.5) the root 1.
        assert_eq!(secant_root((3.0, 1.0), (2.0, 0.5)), Some(1.0));
        // Nearly parallel to the axis: the root 60 lies beyond 1 + 0.59.
        assert_eq!(secant_root((0.0, 0.6), (1.0, 0.59)), None);
        // Flat: no root.
        assert_eq!(secant_root((0.0, 0.6), (1.0, 0.6)), None);
        // A root inside the reach |z₁ − z₀| + |r₁| (1 against 1.5) and one outside (2.33 against
        // 1.7).
        assert_eq!(secant_root((0.0, 1.0), (1.0, 0.5)), Some(2.0));
        assert_eq!(secant_root((0.0, 1.0), (1.0, 0.7)), None);
        // Away from the origin and with a step of 2: r(z) = −0.25 (z − 5) through (2, 0.75) and
        // (4, 0.25) has its root at 5; the same far line as above shifted to z₀ = 2 is refused.
        assert_eq!(secant_root((2.0, 0.75), (4.0, 0.25)), Some(5.0));
        assert_eq!(secant_root((2.0, 1.0), (3.0, 0.7)), None);
    }
}
