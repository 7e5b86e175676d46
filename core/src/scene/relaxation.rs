//! Creep-force relaxation: the force builds up over a rolling distance instead of instantly,
//!
//! ```text
//! dF/dt = (V_r/L)·(F_ss − F),
//! ```
//!
//! with F_ss the steady-state force of a creep-force model, L the relaxation length and V_r
//! the speed at which the contact's material is renewed (below). This is the first-order
//! "relaxation length" model of rolling contact (Pacejka, *Tire and Vehicle Dynamics*,
//! transient slip; for wheel and rail Knothe & Gross-Thebing, VSD 15, 1986).
//!
//! **Renewal speed.** The contact patch stands still in the track frame (to first order) while
//! the material of both bodies passes through it: the rail's at |V| (the wheel centre's speed
//! along the track), the wheel's at its circumferential speed |ωr|. Kalker's theory of
//! quasi-identical bodies gives each body half of the tangential elastic displacement
//! difference (equal compliances, opposite tractions), and each half is carried out of the
//! contact by its own body: the rail's relaxes at |V|/L, the wheel's at |ωr|/L. Their sum
//! relaxes at the mean rate, so
//!
//! ```text
//! V_r = (|V| + |ωr|)/2,
//! ```
//!
//! the magnitude form of Kalker's rolling speed (V + ωr)/2 (Kalker, *Three-dimensional elastic
//! bodies in rolling contact*, 1990, ch. 1; see also [`super::kinematics`]). It is the one the
//! kinematics' regularisation needs ([`renewal_speed`]):
//! - rolling with creepage ξ it is |V|·(1 − ξ/2): the |V| of the creepage's denominator to
//!   within the creepage, as at speed the regularised D = √(V² + v_c²) is;
//! - a wheel spinning or braking at standstill (V = 0, ω ≠ 0) renews the contact at |ωr|/2,
//!   so the force reaches the saturated steady state μQ after a few relaxation lengths of
//!   the wheel's own rolling (e^{−x} of the gap is left after a travel of 2xL of the wheel's
//!   surface), not never (which a law in |V| alone gives) and not over the regularisation's
//!   artificial time scale L/v_c;
//! - a locked wheel (ω = 0) sliding at V relaxes at |V|/2, over the rail's renewal;
//! - a contact at rest (V = ω = 0) is not renewed at all: V_r = 0 and the force is held, the
//!   stuck contact's elastic spring keeping its load (dF/dt = 0, no decay).
//!
//! Without kinematics (creepages given) ω is not known and V_r = |V|.
//!
//! **Exact update.** With V_r and F_ss held over a step h (the co-simulation's zero-order
//! hold), the solution is F(t + h) = F_ss + (F − F_ss)·e^{−V_r h/L}. It is evaluated as the
//! convex combination F·e^{−x} + F_ss·(1 − e^{−x}), x = V_r h/L, with 1 − e^{−x} from `exp_m1`
//! (exact for tiny x), and clamped to [F, F_ss]: unconditionally stable, never overshooting,
//! the same after one step of h as after n steps of h/n (e^{−x} multiplies), and frozen at
//! V_r = 0.
//!
//! **Default length.** At low speed in the linear range the relaxed law must reproduce the
//! elastic contact: with F_ss = C·s/V (s the slip velocity) and V_r ≈ |V|, dF/dt = (C/L)·s −
//! (V/L)·F → (C/L)·(slip displacement rate) as V → 0, a spring of stiffness C/L. Setting C/L to the tangential stiffness k of the stuck
//! contact gives Pacejka's relaxation length L = C/k, with C = G·ab·C_jj Kalker's creep stiffness
//! and, for two bodies of one material, Mindlin's k = 4Gc/(2 − ν) of a circle of radius
//! c = √(ab) (Mindlin 1949; Johnson, *Contact Mechanics*, ch. 7). G cancels:
//!
//! ```text
//! L_x = √(ab)·C11·(2 − ν)/4,   L_y = √(ab)·C22·(2 − ν)/4.
//! ```
//!
//! For a circle and ν = 0.28 that is L_x ≈ 1.8a and L_y ≈ 1.6a, comparable to the contact
//! length 2a, the rolling distance over which the material in the contact is renewed. The
//! equivalent circle is an approximation for slender ellipses; a measured or preferred length
//! can be set with [`RelaxationLengths::uniform`].

use crate::scene::kinematics::WheelKinematics;
use crate::{InvalidInput, KalkerCoefficients};

/// The renewal speed V_r = (|V| + |ωr|)/2 [m/s] of the contact under `kinematics` (module
/// documentation): the speed to pass to [`RelaxationLengths::advance`] when the creepages come
/// from the kinematics. 0 exactly at rest (V = ω = 0).
pub fn renewal_speed(kinematics: &WheelKinematics) -> f64 {
    // Halves first: no overflow for any finite speeds.
    0.5 * kinematics.rolling_speed.abs()
        + 0.5 * (kinematics.wheel_angular_speed * kinematics.wheel_rolling_radius).abs()
}

/// Relaxation lengths of the longitudinal and lateral force \[m\].
///
/// ```
/// use wheel_rail_contact::scene::kinematics::WheelKinematics;
/// use wheel_rail_contact::scene::relaxation::{relax, renewal_speed, RelaxationLengths};
///
/// // 1 ms at 20 m/s over L = 10 mm: 2 lengths travelled, 1 − e⁻² of the way to the steady force.
/// let lengths = RelaxationLengths::uniform(0.01).unwrap();
/// let [f_x, f_y] = lengths.advance([0.0, 100.0], [1000.0, -500.0], 20.0, 1e-3).unwrap();
/// let progress = 1.0 - (-2.0_f64).exp();
/// assert!((f_x - 1000.0 * progress).abs() < 1e-9 && (f_y - (100.0 - 600.0 * progress)).abs() < 1e-9);
/// // The law an integrator follows, of which `advance` is the solution: (V/L)(F_ss − F) [N/s].
/// assert_eq!(lengths.rate([0.0, 100.0], [1000.0, -500.0], 20.0), [2e6, -1.2e6]);
/// assert_eq!(relax(100.0, -500.0, f64::INFINITY), -500.0);
/// // The contact's own lengths, L = √(ab)·C(2 − ν)/4: a circle of 6 mm at ν = 0.25, with
/// // Kalker's C11 = 4.12, C22 = 3.67 (Table E.3).
/// let circle = RelaxationLengths::from_contact(6e-3, 6e-3, 0.25).unwrap();
/// assert!((circle.longitudinal - 6e-3 * 4.12 * 1.75 / 4.0).abs() < 1e-12);
/// assert!((circle.lateral - 6e-3 * 3.67 * 1.75 / 4.0).abs() < 1e-12);
/// // The renewal speed (|V| + |ωr|)/2: a wheel spinning at standstill renews the contact.
/// let spinning = WheelKinematics {
///     rolling_speed: 0.0,
///     wheel_angular_speed: 2.0 / 0.5,
///     wheel_rolling_radius: 0.5,
///     lateral_slip_velocity: 0.0,
///     spin_angular_velocity: 0.0,
/// };
/// assert_eq!(renewal_speed(&spinning), 1.0);
/// assert_eq!(RelaxationLengths::uniform(0.0).unwrap_err().variable, "relaxation_length");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationLengths {
    /// L_x, for the longitudinal force \[m\].
    pub longitudinal: f64,
    /// L_y, for the lateral force (creepage and spin parts together) \[m\].
    pub lateral: f64,
}

impl RelaxationLengths {
    /// The same length L \[m\] (> 0) in both directions.
    pub fn uniform(length: f64) -> Result<Self, InvalidInput> {
        if !(length > 0.0 && length.is_finite()) {
            return Err(InvalidInput::new("relaxation_length", length, "must be finite and > 0"));
        }
        Ok(Self { longitudinal: length, lateral: length })
    }

    /// The default L = C/k (module documentation) of the contact ellipse with semi-axes a
    /// (rolling) and b \[m\] and Poisson's ratio ν.
    pub fn from_contact(semi_axis_a: f64, semi_axis_b: f64, poisson_ratio: f64) -> Result<Self, InvalidInput> {
        for (variable, value) in [("semi_axis_a", semi_axis_a), ("semi_axis_b", semi_axis_b)] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(InvalidInput::new(variable, value, "must be finite and > 0"));
            }
        }
        if !(0.0..=0.5).contains(&poisson_ratio) {
            return Err(InvalidInput::new("poisson_ratio", poisson_ratio, "must lie in [0, 0.5]"));
        }
        let coefficients = KalkerCoefficients::new(semi_axis_a / semi_axis_b, poisson_ratio);
        // √a·√b: no overflow or underflow of the product for any finite positive semi-axes.
        let per_coefficient = semi_axis_a.sqrt() * semi_axis_b.sqrt() * (2.0 - poisson_ratio) / 4.0;
        Ok(Self { longitudinal: per_coefficient * coefficients.c11, lateral: per_coefficient * coefficients.c22 })
    }

    /// dF/dt = (V_r/L)(F_ss − F) [N/s] of the relaxed forces `[F_x, F_y]` \[N\] at renewal speed
    /// `renewal_speed` (its magnitude is used, as in [`RelaxationLengths::advance`]): the
    /// derivative a Model Exchange integrator follows, of which `advance` is the exact solution
    /// over a step with F_ss and V_r held.
    pub fn rate(&self, forces: [f64; 2], steady_state: [f64; 2], renewal_speed: f64) -> [f64; 2] {
        let speed = renewal_speed.abs();
        [
            speed * ((steady_state[0] - forces[0]) / self.longitudinal),
            speed * ((steady_state[1] - forces[1]) / self.lateral),
        ]
    }

    /// Advances the relaxed forces `[F_x, F_y]` \[N\] towards the steady-state forces over a step
    /// of `step` seconds (≥ 0) at renewal speed `renewal_speed` V_r [m/s] (its magnitude is
    /// used: [`renewal_speed`] with kinematics, |V| with given creepages), both held over the
    /// step.
    pub fn advance(
        &self,
        forces: [f64; 2],
        steady_state: [f64; 2],
        renewal_speed: f64,
        step: f64,
    ) -> Result<[f64; 2], InvalidInput> {
        for (variable, value) in [
            ("force_longitudinal", forces[0]),
            ("force_lateral", forces[1]),
            ("steady_force_longitudinal", steady_state[0]),
            ("steady_force_lateral", steady_state[1]),
            ("renewal_speed", renewal_speed),
        ] {
            if !value.is_finite() {
                return Err(InvalidInput::new(variable, value, "must be finite"));
            }
        }
        if !(step >= 0.0 && step.is_finite()) {
            return Err(InvalidInput::new("step", step, "must be finite and >= 0"));
        }
        // V_r·h may overflow to +inf: then the force has fully relaxed, which `relax` handles.
        let distance = renewal_speed.abs() * step;
        Ok([
            relax(forces[0], steady_state[0], distance / self.longitudinal),
            relax(forces[1], steady_state[1], distance / self.lateral),
        ])
    }
}

/// The exact solution of dF/ds = (F_ss − F)/L after a travelled distance s, given as
/// `distance_over_length` = s/L ≥ 0 (+inf allowed): F·e^{−s/L} + F_ss·(1 − e^{−s/L}), clamped
/// to the interval between F and F_ss so that rounding can never overshoot.
pub fn relax(force: f64, steady_state: f64, distance_over_length: f64) -> f64 {
    let remaining = (-distance_over_length).exp();
    let progress = -(-distance_over_length).exp_m1();
    (force * remaining + steady_state * progress).clamp(force.min(steady_state), force.max(steady_state))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::kinematics::DEFAULT_REGULARISATION_SPEED;
    use crate::{ContactInput, CreepForceModel, Polach};
    use approx::assert_relative_eq;
    use proptest::prelude::*;
    use std::f64::consts::E;

    fn lengths() -> RelaxationLengths {
        RelaxationLengths::uniform(0.012).unwrap()
    }

    /// After travelling L (t = L/V) a step response has covered 1 − 1/e ≈ 63.2 %.
    #[test]
    fn step_response_reaches_one_minus_one_over_e_after_one_length() {
        let (speed, length) = (12.5, 0.012);
        let relaxed = lengths().advance([0.0, 2e3], [1e4, -3e3], speed, length / speed).unwrap();
        assert_relative_eq!(relaxed[0], 1e4 * (1.0 - 1.0 / E), max_relative = 1e-15);
        assert_relative_eq!(relaxed[1], -3e3 + 5e3 / E, max_relative = 1e-14);
        // Backwards travel relaxes the same; standstill and h = 0 leave the force untouched.
        assert_eq!(lengths().advance([0.0, 2e3], [1e4, -3e3], -speed, length / speed).unwrap(), relaxed);
        assert_eq!(lengths().advance([1.0, 2.0], [1e4, -3e3], 0.0, 10.0).unwrap(), [1.0, 2.0]);
        assert_eq!(lengths().advance([1.0, 2.0], [1e4, -3e3], 30.0, 0.0).unwrap(), [1.0, 2.0]);
    }

    #[test]
    fn one_big_step_equals_many_small_ones() {
        let (speed, step) = (7.0, 3e-3);
        let big = lengths().advance([-4e3, 1e3], [2.5e4, -8e3], speed, step).unwrap();
        let mut small = [-4e3, 1e3];
        for _ in 0..1000 {
            small = lengths().advance(small, [2.5e4, -8e3], speed, step / 1000.0).unwrap();
        }
        assert!((big[0] - small[0]).abs() <= 1e-12 * 2.9e4, "{big:?} vs {small:?}");
        assert!((big[1] - small[1]).abs() <= 1e-12 * 9e3, "{big:?} vs {small:?}");
    }

    /// The rate is the ODE's right-hand side (V_r/L)(F_ss − F), by hand: 20 m/s over 10 mm is
    /// 2000 1/s; backwards travel relaxes the same; and it is the slope of the exact update at
    /// h = 0 (central differences of `advance` over ±1 µs of travel, the second-order error
    /// (V/L)²h²/6 ≈ 1e-6 relative).
    #[test]
    fn the_rate_is_the_slope_of_the_exact_update() {
        let lengths = RelaxationLengths { longitudinal: 0.01, lateral: 0.02 };
        let (forces, steady) = ([0.0, 100.0], [1000.0, -500.0]);
        assert_eq!(lengths.rate(forces, steady, 20.0), [2e6, -6e5]);
        assert_eq!(lengths.rate(forces, steady, -20.0), [2e6, -6e5]);
        assert_eq!(lengths.rate(steady, steady, 20.0), [0.0, 0.0]);
        let h = 1e-6;
        // advance(−h) is the backward solution: advance takes |V|·h ≥ 0, so integrate backwards by hand.
        let ahead = lengths.advance(forces, steady, 20.0, h).unwrap();
        let behind = [
            steady[0] + (forces[0] - steady[0]) * (20.0 * h / 0.01_f64).exp(),
            steady[1] + (forces[1] - steady[1]) * (20.0 * h / 0.02_f64).exp(),
        ];
        let rate = lengths.rate(forces, steady, 20.0);
        for k in 0..2 {
            assert_relative_eq!((ahead[k] - behind[k]) / (2.0 * h), rate[k], max_relative = 1e-5);
        }
    }

    #[test]
    fn huge_steps_land_exactly_on_the_steady_state() {
        assert_eq!(lengths().advance([1e308, -1e308], [-1e308, 1e308], 1e300, 1e300).unwrap(), [-1e308, 1e308]);
    }

    /// Circle, ν = 0.28: L = a·C(1, 0.28)·(2 − ν)/4, with C11 ≠ C22 giving two lengths of the
    /// order of the contact length 2a.
    #[test]
    fn default_lengths_follow_creep_over_mindlin_stiffness() {
        let a = 5e-3;
        let lengths = RelaxationLengths::from_contact(a, a, 0.28).unwrap();
        let c = KalkerCoefficients::new(1.0, 0.28);
        assert_relative_eq!(lengths.longitudinal, a * c.c11 * 1.72 / 4.0, max_relative = 1e-15);
        assert_relative_eq!(lengths.lateral, a * c.c22 * 1.72 / 4.0, max_relative = 1e-15);
        assert!(lengths.longitudinal > a && lengths.longitudinal < 3.0 * a);
        // Doubling the contact doubles the lengths (C depends on a/b only).
        let doubled = RelaxationLengths::from_contact(2.0 * a, 2.0 * a, 0.28).unwrap();
        assert_relative_eq!(doubled.longitudinal, 2.0 * lengths.longitudinal, max_relative = 1e-15);
    }

    /// The kinematics of the issue: a wheel of radius 0.46 m spun up to ω = 5 rad/s on a rail at
    /// rest (slip 2.3 m/s), optionally creeping forwards at `speed`.
    fn spinning_wheel(speed: f64) -> WheelKinematics {
        WheelKinematics {
            rolling_speed: speed,
            wheel_angular_speed: 5.0,
            wheel_rolling_radius: 0.46,
            lateral_slip_velocity: 0.0,
            spin_angular_velocity: 0.0,
        }
    }

    /// V_r = (|V| + |ωr|)/2 by hand for rolling, spinning at rest, sliding locked and backwards.
    #[test]
    fn renewal_speed_is_the_mean_surface_speed() {
        assert_relative_eq!(renewal_speed(&spinning_wheel(0.0)), 1.15, max_relative = 1e-15); // (0 + 5·0.46)/2
        assert_relative_eq!(renewal_speed(&spinning_wheel(0.01)), 1.155, max_relative = 1e-15);
        let rolling = WheelKinematics { rolling_speed: 20.0, wheel_angular_speed: 19.9 / 0.46, ..spinning_wheel(0.0) };
        assert_relative_eq!(renewal_speed(&rolling), 19.95, max_relative = 1e-15);
        let locked_backwards = WheelKinematics { rolling_speed: -3.0, wheel_angular_speed: 0.0, ..rolling };
        assert_eq!(renewal_speed(&locked_backwards), 1.5);
        let at_rest = WheelKinematics { rolling_speed: 0.0, wheel_angular_speed: 0.0, ..rolling };
        assert_eq!(renewal_speed(&at_rest), 0.0);
    }

    /// The default scene (Q = 100 kN, 7.2 × 5.4 mm, μ = 0.3) under [`spinning_wheel`]: the
    /// steady force (Polach, creepages regularised with v_c = 0.01 m/s) and the contact.
    fn spinning_contact(speed: f64) -> (ContactInput, f64) {
        let creepages = spinning_wheel(speed).creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
        let contact = ContactInput {
            creepage_longitudinal: creepages.longitudinal,
            creepage_lateral: creepages.lateral,
            spin_creepage: creepages.spin,
            normal_force: 100e3,
            semi_axis_a: 7.2e-3,
            semi_axis_b: 5.4e-3,
            friction_coefficient: 0.3,
            shear_modulus: 82e9,
            poisson_ratio: 0.28,
        };
        (contact, Polach::default().creep_forces(&contact).unwrap().force_longitudinal)
    }

    /// Issue 14: at V = 0 a wheel spun to ω = 5 rad/s must build up its traction (it stayed at 0
    /// when the law used |V|). With L = 12 mm and V_r = 1.15 m/s the time constant is
    /// τ = L/V_r = 10.43 ms: one step of τ covers 1 − 1/e of the way; after a renewal travel of
    /// 5L (52 ms, 1 ms steps) F_x is within e^{−5} of the steady state, and that is μQ = 30 kN
    /// to 0.1 % (creepage −230: fully saturated).
    #[test]
    fn a_wheel_spinning_at_standstill_reaches_the_friction_limit_within_a_few_lengths() {
        let friction_limit = 0.3 * 100e3;
        let (_, steady) = spinning_contact(0.0);
        assert!(steady > 0.999 * friction_limit && steady <= friction_limit, "{steady}");
        let length = 0.012;
        let lengths = RelaxationLengths::uniform(length).unwrap();
        let speed = renewal_speed(&spinning_wheel(0.0));
        let time_constant = length / 1.15;
        let one_tau = lengths.advance([0.0; 2], [steady, 0.0], speed, time_constant).unwrap();
        assert_relative_eq!(one_tau[0], steady * (1.0 - 1.0 / E), max_relative = 1e-14);

        let step = 1e-3;
        let mut forces = [0.0; 2];
        let mut time = 0.0;
        while 1.15 * time < 5.0 * length {
            forces = lengths.advance(forces, [steady, 0.0], speed, step).unwrap();
            time += step;
            // The exponential of the law, F = F_ss·(1 − e^{−t/τ}), step after step.
            assert_relative_eq!(forces[0], steady * -(-time / time_constant).exp_m1(), max_relative = 1e-12);
        }
        assert!(time < 0.0531, "{time}");
        assert!(forces[0] > (1.0 - (-5.0_f64).exp()) * 0.999 * friction_limit, "{forces:?} after {time} s");
        assert_eq!(forces[1], 0.0);

        // Creeping forwards at 1 cm/s (where |V| alone gave 2.4 kN after 0.1 s): V_r = 1.155 m/s
        // and the default length of this contact; 0.1 s is over 9 lengths of renewal travel.
        let (contact, steady) = spinning_contact(0.01);
        let lengths = RelaxationLengths::from_contact(contact.semi_axis_a, contact.semi_axis_b, 0.28).unwrap();
        assert!(lengths.longitudinal < 0.0125, "{lengths:?}");
        let mut forces = [0.0; 2];
        for _ in 0..100 {
            forces = lengths.advance(forces, [steady, 0.0], renewal_speed(&spinning_wheel(0.01)), 1e-3).unwrap();
        }
        assert!(forces[0] > 0.999 * steady && steady > 0.999 * friction_limit, "{forces:?}, {steady}");
    }

    /// V = ω = 0: nothing rolls through the contact, so its force is held for any step, even
    /// where the steady state (a lateral slip at rest) differs: the stuck contact is a spring.
    #[test]
    fn a_contact_at_rest_holds_its_force_like_a_spring() {
        let at_rest = WheelKinematics {
            rolling_speed: 0.0,
            wheel_angular_speed: 0.0,
            wheel_rolling_radius: 0.46,
            lateral_slip_velocity: 1e-3,
            spin_angular_velocity: 0.0,
        };
        let held = [-1.2e4, 7.5e3];
        let lengths = RelaxationLengths::from_contact(7.2e-3, 5.4e-3, 0.28).unwrap();
        for step in [1e-3, 1.0, 1e6] {
            assert_eq!(lengths.advance(held, [0.0, -3e4], renewal_speed(&at_rest), step).unwrap(), held);
        }
    }

    #[test]
    fn bad_values_are_named() {
        assert_eq!(RelaxationLengths::uniform(0.0).unwrap_err().variable, "relaxation_length");
        assert_eq!(RelaxationLengths::from_contact(1e-3, -1.0, 0.3).unwrap_err().variable, "semi_axis_b");
        assert_eq!(RelaxationLengths::from_contact(0.0, 1e-3, 0.3).unwrap_err().variable, "semi_axis_a");
        assert_eq!(RelaxationLengths::from_contact(1e-3, 1e-3, 0.7).unwrap_err().variable, "poisson_ratio");
        assert_eq!(lengths().advance([0.0; 2], [0.0; 2], 1.0, -1.0).unwrap_err().variable, "step");
        assert_eq!(
            lengths().advance([0.0; 2], [f64::NAN, 0.0], 1.0, 1.0).unwrap_err().variable,
            "steady_force_longitudinal"
        );
    }

    proptest! {
        /// For any step the force moves towards the steady state and never past it.
        #[test]
        fn never_overshoots(
            force in -1e6..1e6_f64, steady in -1e6..1e6_f64, speed in -100.0..100.0_f64,
            log_step in -12.0..6.0_f64, length in 1e-4..1.0_f64,
        ) {
            let relaxed = RelaxationLengths::uniform(length).unwrap()
                .advance([force, steady], [steady, force], speed, 10f64.powf(log_step)).unwrap();
            prop_assert!(relaxed[0] >= force.min(steady) && relaxed[0] <= force.max(steady));
            prop_assert!((relaxed[0] - steady).abs() <= (force - steady).abs());
            prop_assert!((relaxed[1] - force).abs() <= (steady - force).abs());
        }
    }
}
