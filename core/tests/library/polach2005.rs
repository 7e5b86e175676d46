//! Polach's 2005 extension (ERRATA E8): falling friction and reduced stiffness.

use crate::common;

use common::{contact_case, relative_difference};
use std::f64::consts::E;
use wheel_rail_contact::{ContactInput, CreepForceModel, CreepForces, LargeCreepage, Polach, Polach2005};

fn extended(extension: Polach2005, rolling_speed: f64) -> Polach {
    Polach { large_creepage: Some(LargeCreepage::new(extension, rolling_speed).unwrap()), ..Polach::default() }
}

fn longitudinal(model: &Polach, input: &ContactInput, xi: f64) -> f64 {
    model.creep_forces(&ContactInput { creepage_longitudinal: xi, ..*input }).unwrap().force_longitudinal
}

#[test]
fn neutral_parameters_reproduce_the_base_model_exactly() {
    let neutral = Polach2005::new(1.0, 1.0, 1.0, 0.6).unwrap();
    for speed in [0.0, 3.0, -40.0, 1e4] {
        for (xi, eta, phi) in [(1e-4, 0.0, 0.0), (2e-3, -1e-3, 0.7), (0.0, 0.0, -3.0), (0.2, 0.1, 10.0)] {
            let input =
                ContactInput { creepage_longitudinal: xi, creepage_lateral: eta, spin_creepage: phi, ..contact_case() };
            let base: CreepForces = Polach::default().creep_forces(&input).unwrap();
            assert_eq!(extended(neutral, speed).creep_forces(&input).unwrap(), base, "V = {speed}, {input:?}");
        }
    }
}

#[test]
fn friction_falls_with_slip_velocity() {
    let law = Polach2005::new(1.0, 0.4, 0.4, 0.6).unwrap();
    assert_eq!(law.friction(0.55, 0.0), 0.55);
    // w = 1/B: μ0((1 − A)/e + A).
    assert!(relative_difference(law.friction(0.55, 1.0 / 0.6), 0.55 * (0.6 / E + 0.4)) < 1e-15);
    assert!(relative_difference(law.friction(0.55, 1e3), 0.55 * 0.4) < 1e-15);
}

#[test]
fn dry_and_wet_curves_rise_peak_fall_and_settle_at_the_sliding_friction() {
    let speed = 20.0;
    let presets = [
        (Polach2005::DRY, Polach2005::DRY_MAXIMUM_FRICTION, 0.6),
        (Polach2005::WET, Polach2005::WET_MAXIMUM_FRICTION, 0.2),
    ];
    for (preset, mu0, decay) in presets {
        let model = extended(preset, speed);
        let input = ContactInput { friction_coefficient: mu0, ..contact_case() };
        let curve: Vec<(f64, f64)> = (0..=96)
            .map(|i| 1e-5 * 10f64.powf(i as f64 / 16.0))
            .map(|s| (s, -longitudinal(&model, &input, s)))
            .collect();
        let peak = curve.iter().enumerate().max_by(|a, b| a.1 .1.total_cmp(&b.1 .1)).unwrap().0;
        assert!(peak > 5 && peak < 70, "peak at s = {} for {preset:?}", curve[peak].0);
        assert!(curve[..=peak].windows(2).all(|w| w[1].1 > w[0].1), "not rising before the peak");
        // Falls while friction still decays: e^{−B w} > 1e-2, i.e. B·s·V < ln 100.
        let decaying = curve.iter().take_while(|(s, _)| decay * s * speed < 100f64.ln()).count();
        assert!(curve[peak..decaying].windows(2).all(|w| w[1].1 < w[0].1), "not falling after the peak");
        // Far out μ = A·μ0 and the law's factor → 1 − (2/π)(1/k_S − 1/k_A)/ε: F → Q·A·μ0.
        let sliding = 0.4 * mu0 * input.normal_force;
        let last = curve.last().unwrap().1;
        assert!(relative_difference(last, sliding) < 1e-2, "{last} vs {sliding}");
    }
}

#[test]
fn initial_slope_is_reduced_by_the_mean_reduction_factor() {
    let input = contact_case();
    let tiny = 1e-9;
    let base_slope = longitudinal(&Polach::default(), &input, tiny) / tiny;
    for (k_a, k_s) in [(1.0, 0.4), (0.3, 0.1), (0.7, 0.7)] {
        let model = extended(Polach2005::new(k_a, k_s, 0.4, 0.6).unwrap(), 30.0);
        let slope = longitudinal(&model, &input, tiny) / tiny;
        assert!(relative_difference(slope / base_slope, (k_a + k_s) / 2.0) < 1e-6, "k_A = {k_a}, k_S = {k_s}");
    }
}

#[test]
fn bad_parameters_are_named() {
    let cases = [
        (Polach2005::new(0.0, 0.0, 0.4, 0.6), "adhesion_reduction_factor"),
        (Polach2005::new(1.2, 0.4, 0.4, 0.6), "adhesion_reduction_factor"),
        (Polach2005::new(0.3, 0.4, 0.4, 0.6), "slip_reduction_factor"),
        (Polach2005::new(1.0, 0.4, 1.5, 0.6), "friction_limit_ratio"),
        (Polach2005::new(1.0, 0.4, 0.4, -1.0), "friction_decay_rate"),
        (Polach2005::new(1.0, 0.4, 0.4, f64::NAN), "friction_decay_rate"),
    ];
    for (result, variable) in cases {
        assert_eq!(result.unwrap_err().variable, variable);
    }
    assert_eq!(LargeCreepage::new(Polach2005::DRY, f64::NAN).unwrap_err().variable, "rolling_speed");
    assert_eq!(LargeCreepage::new(Polach2005::DRY, f64::INFINITY).unwrap_err().variable, "rolling_speed");
}

#[test]
fn stays_finite_at_extreme_speeds_and_creepages() {
    for speed in [0.0, 1e-300, 1e300, -1e300] {
        for s in [0.0, 1e-300, 1e-6, 1.0, 1e6] {
            let input = ContactInput {
                creepage_longitudinal: s,
                creepage_lateral: -s,
                spin_creepage: 3.0 * s,
                ..contact_case()
            };
            let f = extended(Polach2005::WET, speed).creep_forces(&input).unwrap();
            assert!(
                f.force_longitudinal.is_finite()
                    && f.force_lateral.is_finite()
                    && f.adhesion_utilisation <= 1.0 + 1e-12
            );
        }
    }
}
