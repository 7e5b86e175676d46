//! Creep-force relaxation: the force builds up over a rolling distance instead of instantly,
//!
//! ```text
//! dF/dt = (|V|/L)·(F_ss − F),
//! ```
//!
//! with F_ss the steady-state force of a creep-force model and L the relaxation length (the
//! first-order "relaxation length" model of rolling contact; Pacejka, *Tire and Vehicle
//! Dynamics*, transient slip; for wheel and rail Knothe & Gross-Thebing, VSD 15, 1986).
//!
//! **Exact update.** With V and F_ss held over a step h (the co-simulation's zero-order hold),
//! the solution is F(t + h) = F_ss + (F − F_ss)·e^{−|V|h/L}. It is evaluated as the convex
//! combination F·e^{−x} + F_ss·(1 − e^{−x}), x = |V|h/L, with 1 − e^{−x} from `exp_m1` (exact
//! for tiny x), and clamped to [F, F_ss]: unconditionally stable, never overshooting, the same
//! after one step of h as after n steps of h/n (e^{−x} multiplies), and frozen at V = 0 (no
//! rolling, no renewal of the contact). Backwards travel relaxes with |V|.
//!
//! **Default length.** At standstill the relaxed law must reproduce the elastic contact: with
//! F_ss = C·s/V in the linear range, dF/dt = (C/L)·s − (V/L)·F → (C/L)·(slip displacement rate)
//! at V = 0, a spring of stiffness C/L. Setting C/L to the tangential stiffness k of the stuck
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

use crate::{InvalidInput, KalkerCoefficients};

/// Relaxation lengths of the longitudinal and lateral force \[m\].
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

    /// Advances the relaxed forces `[F_x, F_y]` \[N\] towards the steady-state forces over a step
    /// of `step` seconds (≥ 0) at rolling speed `rolling_speed` [m/s], both held over the step.
    pub fn advance(
        &self,
        forces: [f64; 2],
        steady_state: [f64; 2],
        rolling_speed: f64,
        step: f64,
    ) -> Result<[f64; 2], InvalidInput> {
        for (variable, value) in [
            ("force_longitudinal", forces[0]),
            ("force_lateral", forces[1]),
            ("steady_force_longitudinal", steady_state[0]),
            ("steady_force_lateral", steady_state[1]),
            ("rolling_speed", rolling_speed),
        ] {
            if !value.is_finite() {
                return Err(InvalidInput::new(variable, value, "must be finite"));
            }
        }
        if !(step >= 0.0 && step.is_finite()) {
            return Err(InvalidInput::new("step", step, "must be finite and >= 0"));
        }
        // |V|·h may overflow to +inf: then the force has fully relaxed, which `relax` handles.
        let distance = rolling_speed.abs() * step;
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

    #[test]
    fn bad_values_are_named() {
        assert_eq!(RelaxationLengths::uniform(0.0).unwrap_err().variable, "relaxation_length");
        assert_eq!(RelaxationLengths::from_contact(1e-3, -1.0, 0.3).unwrap_err().variable, "semi_axis_b");
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
