//! A rigid wheelset on its primary suspension, driven by the forces and moments of its two
//! wheel–rail contacts: the equations of motion and their integration over one communication
//! step. Pure and safe: no FFI, no I/O.
//!
//! # Model
//!
//! Axes and signs are the contact unit's (`src/wheel.rs`, the FMU's README):
//! track x forward, y to the right, z down; ψ about z (positive turns the heading towards +y).
//! The wheelset (mass m, yaw inertia I, spin inertia I_s about its axle) is held by a primary
//! suspension at two axleboxes, ±b₁ from its centre, each with a longitudinal (k_x, c_x) and a
//! lateral (k_y, c_y) spring and damper, to a frame that moves straight along the track at the
//! forward speed V. Its degrees of freedom are the lateral displacement y, the yaw angle ψ and
//! the wheels' common angular speed Ω about the axle (positive rolling forward, Ω r = V in pure
//! rolling); the linear wheelset of Wickens (*Fundamentals of Rail Vehicle Dynamics*, 2003,
//! ch. 2) and Garg & Dukkipati (*Dynamics of Railway Vehicle Systems*, 1984, ch. 6), with the
//! contact forces taken as they come from the contact units instead of linearised:
//!
//! ```text
//! m ÿ   = F_y − 2 k_y y − 2 c_y ẏ
//! I ψ̈   = M_z − 2 k_x b₁² ψ − 2 c_x b₁² ψ̇
//! I_s Ω̇ = −M_y
//! ```
//!
//! F_y, M_y, M_z: the sums over both wheels of the contact units' `track_force_y`,
//! `track_moment_y` and `track_moment_z` — forces on the wheel, moments about the wheelset centre
//! on its axle (`WheelOutput::track_moment`), so they add without transport. A yaw ψ moves the
//! axleboxes by ∓b₁ψ along the track, hence the yaw stiffness 2 k_x b₁². Ω turns about −y (the
//! contact unit's wheel angular velocity is −Ω times the axle's direction), so a moment M_y about
//! +y decelerates it: a creep force F_x < 0 at the contact, a radius r below the centre, gives
//! M_y = r F_x < 0 and spins the wheel up, towards Ω r = V.
//!
//! Ω is a state, not V/r imposed: a wheelset whose Ω is fixed must creep on both wheels whenever
//! their rolling radii change unequally, which lowers its kinematic (Klingel) frequency by 3–5 %
//! (docs/wheelset.md, "The wheel's spin"); free to spin it settles where the longitudinal creep
//! forces cancel. No drive or brake torque.
//!
//! Left out: the longitudinal displacement (the forces F_x deflect the longitudinal springs
//! statically by F_x/(2 k_x), which changes no contact input), the vertical motion and roll (the
//! contact units each carry their prescribed wheel load), and the gyroscopic moment I_s Ω ψ̇,
//! which acts about the roll axis and is carried by the rails.
//!
//! # Integration
//!
//! Over a communication step the contact forces are held (zero-order hold: the values the master
//! set before fmi2DoStep), so within the step the system is linear with constant coefficients
//! and a constant load. It is integrated by the classical fourth-order Runge–Kutta method on
//! equal substeps no longer than [`RATE_STEP`] / ρ, ρ = ω + 2ζω (for each of the lateral and yaw
//! oscillators, the largest eigenvalue magnitude, bounded from above): ρ h ≤ 0.2 keeps RK4 far
//! inside its stability interval (|λ h| < 2.78 on the real axis, < 2.83 on the imaginary one)
//! and its per-substep amplitude error (ρh)⁶/144 ≈ 4·10⁻⁷, phase error (ρh)⁵/120 ≈ 3·10⁻⁶ rad.
//! The cited suspension's fastest mode (yaw, 237 rad/s) needs a substep of 0.8 ms; a free
//! wheelset (no springs) has ρ = 0 and is integrated in one substep, exactly (a constant load
//! gives a polynomial motion of degree 2, which RK4 reproduces). An explicit method is enough
//! because the stiff part of the coupled system, the creep forces, is not inside this model: it
//! is held over the step by the master.

use std::fmt;

/// Largest ρ h of a substep (module doc).
pub const RATE_STEP: f64 = 0.2;

/// At most this many substeps per communication step: a step that would need more (a step of
/// hours, or stiffness far beyond any wheelset's) is refused rather than run for minutes.
pub const MAX_SUBSTEPS: usize = 10_000_000;

/// The wheelset's parameters (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameters {
    /// m \[kg\].
    pub mass: f64,
    /// I about the vertical axis \[kg m²\].
    pub yaw_inertia: f64,
    /// I_s about the axle \[kg m²\].
    pub spin_inertia: f64,
    /// k_x per axlebox \[N/m\].
    pub longitudinal_stiffness: f64,
    /// c_x per axlebox \[N s/m\].
    pub longitudinal_damping: f64,
    /// k_y per axlebox \[N/m\].
    pub lateral_stiffness: f64,
    /// c_y per axlebox \[N s/m\].
    pub lateral_damping: f64,
    /// b₁, half the lateral distance between the axleboxes \[m\].
    pub lateral_semi_spacing: f64,
    /// V, the frame's speed along the track \[m/s\].
    pub forward_speed: f64,
    /// |y| beyond which the wheelset has derailed \[m\].
    pub derailment_displacement: f64,
}

/// The wheelset's state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct State {
    /// y \[m\].
    pub lateral_displacement: f64,
    /// ψ \[rad\].
    pub yaw_angle: f64,
    /// ẏ \[m/s\].
    pub lateral_velocity: f64,
    /// ψ̇ \[rad/s\].
    pub yaw_rate: f64,
    /// Ω \[rad/s\].
    pub wheel_angular_speed: f64,
}

/// The contact loads on the wheelset, summed over both wheels, in track axes, moments about the
/// wheelset centre on its axle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    /// F_y \[N\].
    pub lateral_force: f64,
    /// M_y, about the axle (+y) \[N m\].
    pub axle_moment: f64,
    /// M_z \[N m\].
    pub yaw_moment: f64,
}

/// Why a step cannot be taken.
#[derive(Debug, Clone, PartialEq)]
pub enum WheelsetError {
    /// A parameter is out of its range: its name, value and the range.
    Parameter { name: &'static str, value: f64, requirement: &'static str },
    /// The wheelset has left the rails: |y| beyond the derailment displacement.
    Derailed { lateral_displacement: f64, limit: f64 },
    /// The step needs more than [`MAX_SUBSTEPS`] substeps.
    StepTooLong { step: f64, substeps: f64 },
    /// The step is not finite and ≥ 0.
    InvalidStep { step: f64 },
    /// The state at the step's end is not finite: a load was not (the caller checks its inputs
    /// by name; this is the last guard).
    NotFinite { state: State },
}

impl fmt::Display for WheelsetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WheelsetError::Parameter { name, value, requirement } => {
                write!(f, "{name} = {value} is invalid: must be {requirement}")
            }
            WheelsetError::Derailed { lateral_displacement, limit } => write!(
                f,
                "the wheelset derails: lateral_displacement = {lateral_displacement} m is beyond \
                 derailment_displacement = {limit} m"
            ),
            WheelsetError::StepTooLong { step, substeps } => write!(
                f,
                "communicationStepSize = {step} s would need {substeps:e} substeps (at most {MAX_SUBSTEPS:e}): \
                 take shorter steps"
            ),
            WheelsetError::InvalidStep { step } => {
                write!(f, "communicationStepSize = {step} s is invalid: must be finite and >= 0")
            }
            WheelsetError::NotFinite { state } => {
                write!(f, "the state is not finite ({state:?}): every load must be finite")
            }
        }
    }
}

impl Parameters {
    /// Every parameter in its range: inertias and the derailment bound finite and > 0,
    /// stiffnesses, dampings and b₁ finite and ≥ 0, V finite.
    pub fn check(&self) -> Result<(), WheelsetError> {
        let positive = [
            ("mass", self.mass),
            ("yaw_inertia", self.yaw_inertia),
            ("spin_inertia", self.spin_inertia),
            ("derailment_displacement", self.derailment_displacement),
        ];
        let non_negative = [
            ("longitudinal_stiffness", self.longitudinal_stiffness),
            ("longitudinal_damping", self.longitudinal_damping),
            ("lateral_stiffness", self.lateral_stiffness),
            ("lateral_damping", self.lateral_damping),
            ("lateral_semi_spacing", self.lateral_semi_spacing),
        ];
        let bad = positive
            .iter()
            .filter(|(_, value)| !(value.is_finite() && *value > 0.0))
            .map(|&(name, value)| (name, value, "finite and > 0"))
            .chain(
                non_negative
                    .iter()
                    .filter(|(_, value)| !(value.is_finite() && *value >= 0.0))
                    .map(|&(name, value)| (name, value, "finite and >= 0")),
            )
            .chain((!self.forward_speed.is_finite()).then_some(("forward_speed", self.forward_speed, "finite")))
            .next();
        match bad {
            Some((name, value, requirement)) => Err(WheelsetError::Parameter { name, value, requirement }),
            None => Ok(()),
        }
    }

    /// The lateral and yaw oscillators as (stiffness/inertia, damping/inertia): ẍ = −k x − c ẋ + …
    fn oscillators(&self) -> [(f64, f64); 2] {
        let yaw_arm = self.lateral_semi_spacing * self.lateral_semi_spacing;
        [
            (2.0 * self.lateral_stiffness / self.mass, 2.0 * self.lateral_damping / self.mass),
            (
                2.0 * self.longitudinal_stiffness * yaw_arm / self.yaw_inertia,
                2.0 * self.longitudinal_damping * yaw_arm / self.yaw_inertia,
            ),
        ]
    }

    /// ρ: a bound of the largest eigenvalue magnitude, ω + 2ζω = √k + c per oscillator (module
    /// doc; for the overdamped oscillator |λ| ≤ c, for the underdamped |λ| = ω).
    pub fn fastest_rate(&self) -> f64 {
        self.oscillators().iter().map(|&(k, c)| k.sqrt() + c).fold(0.0, f64::max)
    }

    /// The rates of the state under `loads`: the equations of motion (module doc), what Model
    /// Exchange's master integrates.
    pub fn rates(&self, state: &State, loads: &Loads) -> State {
        let [(k_y, c_y), (k_psi, c_psi)] = self.oscillators();
        State {
            lateral_displacement: state.lateral_velocity,
            yaw_angle: state.yaw_rate,
            lateral_velocity: loads.lateral_force / self.mass
                - k_y * state.lateral_displacement
                - c_y * state.lateral_velocity,
            yaw_rate: loads.yaw_moment / self.yaw_inertia - k_psi * state.yaw_angle - c_psi * state.yaw_rate,
            wheel_angular_speed: -loads.axle_moment / self.spin_inertia,
        }
    }
}

impl State {
    /// At rest on the track centre line, the wheels turning at `forward_speed / rolling_radius`.
    pub fn rolling(forward_speed: f64, rolling_radius: f64) -> State {
        State { wheel_angular_speed: forward_speed / rolling_radius, ..State::default() }
    }

    fn as_array(&self) -> [f64; 5] {
        [self.lateral_displacement, self.yaw_angle, self.lateral_velocity, self.yaw_rate, self.wheel_angular_speed]
    }

    fn from_array(x: [f64; 5]) -> State {
        State {
            lateral_displacement: x[0],
            yaw_angle: x[1],
            lateral_velocity: x[2],
            yaw_rate: x[3],
            wheel_angular_speed: x[4],
        }
    }

    /// `self + factor · rate`, component by component.
    fn plus(&self, factor: f64, rate: &State) -> State {
        let (x, r) = (self.as_array(), rate.as_array());
        State::from_array(std::array::from_fn(|i| x[i] + factor * r[i]))
    }
}

/// The state after `step` seconds under `loads` held constant (module doc), or why not: bad
/// parameters, a step needing too many substeps, a load that is not finite, or a derailment (|y| beyond the bound at the
/// step's end).
pub fn advance(parameters: &Parameters, state: &State, loads: &Loads, step: f64) -> Result<State, WheelsetError> {
    parameters.check()?;
    if !(step.is_finite() && step >= 0.0) {
        return Err(WheelsetError::InvalidStep { step });
    }
    let substeps = (step * parameters.fastest_rate() / RATE_STEP).ceil().max(1.0);
    if substeps > MAX_SUBSTEPS as f64 {
        return Err(WheelsetError::StepTooLong { step, substeps });
    }
    let h = step / substeps;
    let mut x = *state;
    for _ in 0..substeps as usize {
        let k1 = parameters.rates(&x, loads);
        let k2 = parameters.rates(&x.plus(h / 2.0, &k1), loads);
        let k3 = parameters.rates(&x.plus(h / 2.0, &k2), loads);
        let k4 = parameters.rates(&x.plus(h, &k3), loads);
        x = x.plus(h / 6.0, &k1).plus(h / 3.0, &k2).plus(h / 3.0, &k3).plus(h / 6.0, &k4);
    }
    if !x.as_array().iter().all(|v| v.is_finite()) {
        return Err(WheelsetError::NotFinite { state: x });
    }
    if x.lateral_displacement.abs() > parameters.derailment_displacement {
        return Err(WheelsetError::Derailed {
            lateral_displacement: x.lateral_displacement,
            limit: parameters.derailment_displacement,
        });
    }
    Ok(x)
}

#[cfg(test)]
mod tests;
