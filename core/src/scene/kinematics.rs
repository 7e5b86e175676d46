//! Creepages from the velocities a vehicle model knows, safe down to and through standstill.
//!
//! Axes are the track's: x forward along the track, y lateral, z along the contact normal (as in
//! [`crate::ContactInput`]). Kalker defines creepages as rigid slip velocities (wheel minus rail
//! at the contact point) over the rolling speed, in axes whose x points in the rolling
//! direction (Kalker, *Three-dimensional elastic bodies in rolling contact*, 1990, ch. 1).
//! Rolling backwards turns those axes by 180° about z; the models are odd in (ξ, η, φ)
//! jointly, so the forces in track axes follow from track-axis creepages
//!
//! ```text
//! ξ = (V − ωr)/|V|,   η = v_y/|V|,   φ = ω_z/V   (signed V: the spin term reverses).
//! ```
//!
//! **Regularisation.** |V| is replaced by the smooth D = √(V² + v_c²) ≥ v_c, and 1/V in φ by the
//! odd V/D², the usual smooth-max remedy for the 1/V singularity of slip definitions (compare
//! Pacejka, *Tire and Vehicle Dynamics*, on slip at low speed: |V_cx| + ε in the denominator). So:
//! - nothing divides by zero: at V = 0 the creepages are (−ωr, v_y)/v_c and φ = 0;
//! - the creepages, and hence the forces of any continuous model, are continuous and smooth in
//!   V through 0, and bounded by μQ because the models are;
//! - a slip velocity at standstill (a spinning wheel) gives a creepage of slip/v_c, so the
//!   force saturates at μQ against the slip, as it physically does;
//! - the spin's lateral force, a rolling effect, fades to 0 at standstill and reverses with the
//!   direction of travel;
//! - for |V| ≫ v_c the creepages equal Kalker's to a relative v_c²/(2V²) (φ: v_c²/V²).
//!
//! The default v_c = 0.01 m/s keeps that error below 1e-4 from 1 m/s up and below 1 % from
//! 0.1 m/s up. Below v_c the contact acts as a stiff viscous damper (slope G·ab·C11/v_c); a
//! larger v_c softens it at the cost of accuracy at low speed. At standstill the real contact is
//! an elastic spring, not a damper: for low-speed transients switch on the relaxation
//! ([`super::relaxation`]), whose rate |V|/L bounds the force's rate of change.
//!
//! The rolling speed is the wheel centre's V, as in Polach's papers; Kalker's exact definition
//! uses the mean of the two surface speeds, (V + ωr)/2. The two differ by a factor 1 − ξ/2 on ξ,
//! negligible in the creep range and irrelevant once saturated.

use crate::InvalidInput;

/// Default regularisation speed v_c [m/s]; see the module documentation.
pub const DEFAULT_REGULARISATION_SPEED: f64 = 0.01;

/// The velocities at one wheel–rail contact, SI units, track axes.
///
/// ```
/// use wheel_rail_contact::scene::kinematics::{WheelKinematics, DEFAULT_REGULARISATION_SPEED};
///
/// // Braking at 20 m/s: ωr = 19.96 m/s, 0.1 m/s sideways, spinning at 0.5 rad/s.
/// let braking = WheelKinematics {
///     rolling_speed: 20.0,
///     wheel_angular_speed: 19.96 / 0.46,
///     wheel_rolling_radius: 0.46,
///     lateral_slip_velocity: 0.1,
///     spin_angular_velocity: 0.5,
/// };
/// assert!((braking.longitudinal_slip_velocity() - 0.04).abs() < 1e-12);
/// let creepages = braking.creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
/// // ξ = (V − ωr)/V, η = v_y/V, φ = ω_z/V, to a relative v_c²/(2V²) (φ: v_c²/V²) at speed.
/// assert!((creepages.longitudinal / 0.002 - 1.0).abs() < 1e-6);
/// assert!((creepages.lateral / 0.005 - 1.0).abs() < 1e-6);
/// assert!((creepages.spin / 0.025 - 1.0).abs() < 1e-6);
/// // At standstill nothing divides by zero: a spinning wheel's creepage is −ωr/v_c.
/// let spinning = WheelKinematics { rolling_speed: 0.0, lateral_slip_velocity: 0.0, ..braking };
/// let at_rest = spinning.creepages(DEFAULT_REGULARISATION_SPEED).unwrap();
/// assert!((at_rest.longitudinal + 19.96 / 0.01).abs() < 1e-9 && at_rest.spin == 0.0);
/// assert_eq!(braking.creepages(0.0).unwrap_err().variable, "regularisation_speed");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelKinematics {
    /// Rolling speed V: the wheel centre's speed along the track [m/s], negative when the wheel
    /// travels backwards.
    pub rolling_speed: f64,
    /// Wheel angular speed ω about its axle [rad/s], positive when rolling forwards (ωr = V in
    /// pure rolling).
    pub wheel_angular_speed: f64,
    /// Rolling radius r at the contact point \[m\], > 0.
    pub wheel_rolling_radius: f64,
    /// Lateral slip velocity v_y of the wheel relative to the rail at the contact point [m/s].
    pub lateral_slip_velocity: f64,
    /// Spin angular velocity ω_z of the wheel relative to the rail about the contact normal
    /// [rad/s].
    pub spin_angular_velocity: f64,
}

/// Regularised creepages in track axes, ready for [`crate::ContactInput`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Creepages {
    /// Longitudinal creepage ξ \[1\].
    pub longitudinal: f64,
    /// Lateral creepage η \[1\].
    pub lateral: f64,
    /// Spin creepage φ [1/m].
    pub spin: f64,
    /// The denominator D = √(V² + v_c²) [m/s]: ξ·D and η·D are the slip velocities exactly,
    /// so a slip-velocity-dependent friction law can use creepage × D at any speed.
    pub reference_speed: f64,
}

impl WheelKinematics {
    /// Longitudinal slip velocity V − ωr of the wheel relative to the rail [m/s].
    pub fn longitudinal_slip_velocity(&self) -> f64 {
        self.rolling_speed - self.wheel_angular_speed * self.wheel_rolling_radius
    }

    /// The creepages with regularisation speed v_c [m/s] (> 0; usually
    /// [`DEFAULT_REGULARISATION_SPEED`]).
    pub fn creepages(&self, regularisation_speed: f64) -> Result<Creepages, InvalidInput> {
        self.validate(regularisation_speed)?;
        let speed = self.rolling_speed;
        let reference_speed = speed.hypot(regularisation_speed);
        let creepages = Creepages {
            longitudinal: self.longitudinal_slip_velocity() / reference_speed,
            lateral: self.lateral_slip_velocity / reference_speed,
            // ω_z·V/D²: the odd, bounded stand-in for ω_z/V (|V/D| ≤ 1, so no overflow from V).
            spin: self.spin_angular_velocity * (speed / reference_speed) / reference_speed,
            reference_speed,
        };
        // Finite inputs can still overflow (huge slip over a tiny v_c): name the culprit.
        for (variable, value, creepage) in [
            ("wheel_angular_speed", self.wheel_angular_speed, creepages.longitudinal),
            ("lateral_slip_velocity", self.lateral_slip_velocity, creepages.lateral),
            ("spin_angular_velocity", self.spin_angular_velocity, creepages.spin),
        ] {
            if !creepage.is_finite() {
                return Err(InvalidInput::new(variable, value, "gives a creepage beyond f64 range"));
            }
        }
        Ok(creepages)
    }

    fn validate(&self, regularisation_speed: f64) -> Result<(), InvalidInput> {
        for (variable, value) in [
            ("rolling_speed", self.rolling_speed),
            ("wheel_angular_speed", self.wheel_angular_speed),
            ("lateral_slip_velocity", self.lateral_slip_velocity),
            ("spin_angular_velocity", self.spin_angular_velocity),
        ] {
            if !value.is_finite() {
                return Err(InvalidInput::new(variable, value, "must be finite"));
            }
        }
        for (variable, value) in
            [("wheel_rolling_radius", self.wheel_rolling_radius), ("regularisation_speed", regularisation_speed)]
        {
            if !(value > 0.0 && value.is_finite()) {
                return Err(InvalidInput::new(variable, value, "must be finite and > 0"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ContactInput, CreepForceModel, CreepForces, KalkerCoefficients, Polach};
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const V_C: f64 = DEFAULT_REGULARISATION_SPEED;
    const RADIUS: f64 = 0.46;
    const FRICTION_LIMIT: f64 = 0.3 * 80e3;

    fn kinematics(speed: f64, circumferential_speed: f64, lateral: f64, spin: f64) -> WheelKinematics {
        WheelKinematics {
            rolling_speed: speed,
            wheel_angular_speed: circumferential_speed / RADIUS,
            wheel_rolling_radius: RADIUS,
            lateral_slip_velocity: lateral,
            spin_angular_velocity: spin,
        }
    }

    fn contact(creepages: Creepages) -> ContactInput {
        ContactInput {
            creepage_longitudinal: creepages.longitudinal,
            creepage_lateral: creepages.lateral,
            spin_creepage: creepages.spin,
            normal_force: 80e3,
            semi_axis_a: 6.3e-3,
            semi_axis_b: 4.1e-3,
            friction_coefficient: 0.3,
            shear_modulus: 8.2e10,
            poisson_ratio: 0.28,
        }
    }

    fn polach(kinematics: WheelKinematics) -> CreepForces {
        Polach::default().creep_forces(&contact(kinematics.creepages(V_C).unwrap())).unwrap()
    }

    /// Kalker's longitudinal creep stiffness G·ab·C11 of the contact above \[N\].
    fn creep_stiffness() -> f64 {
        let input = contact(Creepages { longitudinal: 0.0, lateral: 0.0, spin: 0.0, reference_speed: 1.0 });
        let c11 = KalkerCoefficients::new(input.semi_axis_a / input.semi_axis_b, input.poisson_ratio).c11;
        input.shear_modulus * input.semi_axis_a * input.semi_axis_b * c11
    }

    #[test]
    fn at_speed_the_creepages_are_kalkers() {
        let k = kinematics(30.0, 30.0 * 0.998, 0.015, 0.9).creepages(V_C).unwrap();
        let tolerance = V_C * V_C / (30.0 * 30.0);
        assert_relative_eq!(k.longitudinal, 0.002, max_relative = tolerance);
        assert_relative_eq!(k.lateral, 0.015 / 30.0, max_relative = tolerance);
        assert_relative_eq!(k.spin, 0.9 / 30.0, max_relative = tolerance);
        // Backwards: the spin creepage reverses with the rolling direction.
        assert_relative_eq!(
            kinematics(-30.0, 0.0, 0.0, 0.9).creepages(V_C).unwrap().spin,
            -0.9 / 30.0,
            max_relative = tolerance
        );
    }

    #[test]
    fn at_exact_standstill_everything_is_finite_and_a_spinning_wheel_saturates() {
        let at_rest = kinematics(0.0, 0.0, 0.0, 0.0).creepages(V_C).unwrap();
        assert_eq!((at_rest.longitudinal, at_rest.lateral, at_rest.spin), (0.0, 0.0, 0.0));
        assert_eq!(polach(kinematics(0.0, 0.0, 0.0, 0.0)), CreepForces::default());

        // Driven wheel spinning on the spot at 0.5 m/s: creepage −0.5/v_c, traction ≈ +μQ.
        let spinning = kinematics(0.0, 0.5, 0.0, 2.0);
        let k = spinning.creepages(V_C).unwrap();
        assert_eq!((k.longitudinal, k.spin, k.reference_speed), (-0.5 / V_C, 0.0, V_C));
        assert_relative_eq!(k.longitudinal * k.reference_speed, spinning.longitudinal_slip_velocity());
        let forces = polach(spinning);
        assert!(forces.force_longitudinal > 0.99 * FRICTION_LIMIT && forces.force_longitudinal <= FRICTION_LIMIT);
        assert_eq!(forces.force_lateral, 0.0);
    }

    /// Locked wheel (ω = 0) sliding through V = 0: F_x is Lipschitz with Kalker's stiffness
    /// G·ab·C11 times |dξ/dV| ≤ 1/v_c, so no step between samples can exceed that slope.
    #[test]
    fn longitudinal_force_is_continuous_through_standstill() {
        let slope = creep_stiffness() / V_C;
        let step = 1e-7;
        let samples: Vec<f64> =
            (-1000..=1000).map(|i| polach(kinematics(f64::from(i) * step, 0.0, 0.0, 0.0)).force_longitudinal).collect();
        for pair in samples.windows(2) {
            assert!((pair[1] - pair[0]).abs() <= slope * step * (1.0 + 1e-9), "jump {pair:?}");
        }
        assert_eq!(samples[1000], 0.0);
        // Sliding forwards the force points backwards, and the other way round; saturated at the ends.
        assert!(samples[2000] < -0.9 * FRICTION_LIMIT && samples[0] > 0.9 * FRICTION_LIMIT);
    }

    /// Spin, lateral and longitudinal slip together, V swept through 0: every step of the force
    /// shrinks in proportion to the step of V (continuity), and nothing exceeds μQ.
    #[test]
    fn combined_forces_are_continuous_and_bounded_through_standstill() {
        let sweep = |samples: i32| {
            let step = 0.02 / f64::from(samples);
            let mut largest_jump: f64 = 0.0;
            let mut previous = polach(kinematics(-0.01, 1e-4, 2e-5, 3.0));
            for i in 1..=samples {
                let speed = -0.01 + f64::from(i) * step;
                let forces = polach(kinematics(speed, 1e-4, 2e-5, 3.0));
                assert!(forces.adhesion_utilisation <= 1.0 + 1e-12);
                let jump = (forces.force_longitudinal - previous.force_longitudinal)
                    .hypot(forces.force_lateral - previous.force_lateral);
                largest_jump = largest_jump.max(jump);
                previous = forces;
            }
            largest_jump
        };
        let (coarse, fine) = (sweep(2_000), sweep(20_000));
        // A jump would stay the same size under refinement; a continuous force's steps shrink ~10×.
        assert!(fine < 0.15 * coarse, "coarse {coarse}, fine {fine}");
    }

    #[test]
    fn braking_force_opposes_travel_in_both_directions() {
        let forwards = polach(kinematics(20.0, 20.0 * 0.995, 0.0, 0.0));
        let backwards = polach(kinematics(-20.0, -20.0 * 0.995, 0.0, 0.0));
        assert!(forwards.force_longitudinal < 0.0);
        assert_relative_eq!(backwards.force_longitudinal, -forwards.force_longitudinal, max_relative = 1e-12);
    }

    #[test]
    fn bad_values_are_named() {
        let good = kinematics(1.0, 1.0, 0.0, 0.0);
        assert_eq!(good.creepages(0.0).unwrap_err().variable, "regularisation_speed");
        let flat = WheelKinematics { wheel_rolling_radius: -1.0, ..good };
        assert_eq!(flat.creepages(V_C).unwrap_err().variable, "wheel_rolling_radius");
        let nan = WheelKinematics { rolling_speed: f64::NAN, ..good };
        assert_eq!(nan.creepages(V_C).unwrap_err().variable, "rolling_speed");
        let overflow = WheelKinematics { rolling_speed: 0.0, lateral_slip_velocity: 1e300, ..good };
        assert_eq!(overflow.creepages(1e-10).unwrap_err().variable, "lateral_slip_velocity");
    }

    proptest! {
        /// The same motion seen travelling the other way (turned 180° about z: V, ω, v_y change
        /// sign, ω_z does not) gives the opposite forces in track axes.
        #[test]
        fn reversing_the_direction_of_travel_reverses_the_forces(
            speed in -40.0..40.0_f64, slip in -1.0..1.0_f64, lateral in -0.5..0.5_f64, spin in -5.0..5.0_f64,
        ) {
            let ahead = polach(kinematics(speed, speed + slip, lateral, spin));
            let behind = polach(kinematics(-speed, -(speed + slip), -lateral, spin));
            prop_assert!((ahead.force_longitudinal + behind.force_longitudinal).abs() <= 1e-9 * FRICTION_LIMIT);
            prop_assert!((ahead.force_lateral + behind.force_lateral).abs() <= 1e-9 * FRICTION_LIMIT);
        }

        /// Finite creepages and forces within μQ for any speed, including exactly 0.
        #[test]
        fn forces_are_finite_and_bounded(
            speed in prop_oneof![Just(0.0), -50.0..50.0_f64], circumferential in -50.0..50.0_f64,
            lateral in -5.0..5.0_f64, spin in -50.0..50.0_f64,
        ) {
            let forces = polach(kinematics(speed, circumferential, lateral, spin));
            prop_assert!(forces.force_longitudinal.is_finite() && forces.force_lateral.is_finite());
            prop_assert!(forces.adhesion_utilisation <= 1.0 + 1e-12);
        }
    }
}
