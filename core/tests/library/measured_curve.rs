//! Stiffness from a measured creep curve (Polach eqs. 33–36, ERRATA E7).

use crate::common;

use common::{contact_case, relative_difference};
use std::f64::consts::{FRAC_1_PI, PI};
use wheel_rail_contact::{ContactInput, CreepForceModel, MeasuredCurve, MeasuredCurveError, Polach, StiffnessSource};

/// Eq. (34) normalised by Q f_k, written independently of the library.
fn normalised_law(k: f64, epsilon: f64) -> f64 {
    2.0 / PI * (k * epsilon / (k * k + epsilon * epsilon) + epsilon.atan())
}

fn longitudinal_force(curve: MeasuredCurve, input: &ContactInput, xi: f64) -> f64 {
    let model = Polach { stiffness: StiffnessSource::MeasuredCurve(curve), ..Polach::default() };
    model.creep_forces(&ContactInput { creepage_longitudinal: xi, ..*input }).unwrap().force_longitudinal
}

#[test]
fn eq_35_is_the_maximum_of_eq_34() {
    // Independent check of the printed eq. (35): the gradient it gives maximises eq. (34).
    for peak in [0.3001, 0.31, 0.35, 0.39] {
        let curve = MeasuredCurve::from_peak(peak, 4e-3, 0.3).unwrap();
        let (k, e) = (curve.friction_ratio(), curve.gradient_at_peak());
        let h = 1e-4 * e;
        let slope = (normalised_law(k, e + h) - normalised_law(k, e - h)) / (2.0 * h);
        let curvature = (normalised_law(k, e + h) - 2.0 * normalised_law(k, e) + normalised_law(k, e - h)) / (h * h);
        assert!(slope.abs() < 1e-7 * curvature.abs() * e, "slope {slope} at ε_max = {e}");
        assert!(curvature < 0.0);
        assert!(relative_difference(normalised_law(k, e), peak / 0.3) < 1e-12, "peak of eq. 34");
    }
}

#[test]
fn recovers_a_known_friction_ratio() {
    // k = 2: eq. (35) gives ε² = (2/2)(7 + √73); the peak value follows from eq. (34).
    let e = (7.0 + 73f64.sqrt()).sqrt();
    let peak_ratio = normalised_law(2.0, e);
    let curve = MeasuredCurve::from_peak(0.25 * peak_ratio, 1e-2, 0.25).unwrap();
    assert!(relative_difference(curve.friction_ratio(), 2.0) < 1e-12, "{curve:?}");
    assert!(relative_difference(curve.gradient_at_peak(), e) < 1e-12, "{curve:?}");
}

#[test]
fn the_fitted_curve_peaks_at_the_measurement_and_falls_to_kinetic_friction() {
    let base = contact_case();
    for (peak, s_max, f_k) in [(0.4, 0.01, 0.35), (0.33, 2e-3, 0.3), (0.2001, 5e-3, 0.2), (0.45, 0.03, 0.36)] {
        let input = ContactInput { friction_coefficient: f_k, ..base };
        let curve = MeasuredCurve::from_peak(peak, s_max, f_k).unwrap();
        let f_max = peak * input.normal_force;
        let at_peak = -longitudinal_force(curve, &input, s_max);
        assert!(relative_difference(at_peak, f_max) < 1e-9, "F(s_max) = {at_peak}, F_max = {f_max}");
        for factor in [0.9, 0.999, 1.001, 1.1] {
            assert!(-longitudinal_force(curve, &input, s_max * factor) < at_peak, "not a maximum at {factor}·s_max");
        }
        // Towards large creepage eq. (34) falls to Q f_k from above like (2/π)(k − 1)/ε.
        let far = -longitudinal_force(curve, &input, 1e4 * s_max);
        let excess = far / (f_k * input.normal_force) - 1.0;
        let asymptote = 2.0 / PI * (curve.friction_ratio() - 1.0) / (1e4 * curve.gradient_at_peak());
        assert!(
            excess > 0.0 && relative_difference(excess, asymptote) < 1e-3,
            "F/(Q f_k) − 1 = {excess} vs {asymptote}"
        );
        // Eq. (36) in eq. (7): ε(s_max) = (2/3) C π a² b s_max / (Q f_k) = ε_max.
        let c = curve.contact_stiffness(input.normal_force, input.semi_axis_a, input.semi_axis_b);
        let epsilon =
            2.0 / 3.0 * c * PI * input.semi_axis_a.powi(2) * input.semi_axis_b * s_max / (input.normal_force * f_k);
        assert!(relative_difference(epsilon, curve.gradient_at_peak()) < 1e-14);
    }
}

#[test]
fn lower_friction_keeps_the_stiffness_and_saturates_earlier() {
    let input = ContactInput { friction_coefficient: 0.35, ..contact_case() };
    let curve = MeasuredCurve::from_peak(0.4, 0.01, 0.35).unwrap();
    let wet = ContactInput { friction_coefficient: 0.1, ..input };
    // The initial slope is the stiffness: the same for both friction levels (eq. 7 with fixed C).
    let tiny = 1e-9;
    let slope_dry = longitudinal_force(curve, &input, tiny) / tiny;
    let slope_wet = longitudinal_force(curve, &wet, tiny) / tiny;
    assert!(relative_difference(slope_dry, slope_wet) < 1e-6, "{slope_dry} vs {slope_wet}");
    // and the wet peak sits at s_max·μ/f_k.
    let wet_peak = -longitudinal_force(curve, &wet, 0.01 * 0.1 / 0.35);
    assert!(relative_difference(wet_peak, 0.4 / 0.35 * 0.1 * wet.normal_force) < 1e-9);
}

#[test]
fn a_peak_barely_above_kinetic_friction_stays_finite() {
    // k → 1⁺: ε_max → ∞ like √(2/(k−1)); everything must stay finite and the peak still match.
    let base = ContactInput { friction_coefficient: 0.3, ..contact_case() };
    let mut previous_ratio = f64::INFINITY;
    for excess in [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let curve = MeasuredCurve::from_peak(0.3 * (1.0 + excess), 1e-2, 0.3).unwrap();
        let k = curve.friction_ratio();
        assert!(k > 1.0 && k < previous_ratio && curve.gradient_at_peak().is_finite(), "{curve:?}");
        previous_ratio = k;
        let at_peak = -longitudinal_force(curve, &base, 1e-2) / (0.3 * base.normal_force);
        assert!(at_peak.is_finite() && (at_peak - (1.0 + excess)).abs() < 1e-9, "{excess}: {at_peak}");
    }
}

#[test]
fn impossible_curves_get_a_typed_error() {
    use MeasuredCurveError::*;
    assert_eq!(
        MeasuredCurve::from_peak(0.3, 1e-2, 0.3),
        Err(PeakNotAboveKineticFriction { peak_adhesion: 0.3, kinetic_friction: 0.3 })
    );
    assert_eq!(
        MeasuredCurve::from_peak(0.2, 1e-2, 0.3),
        Err(PeakNotAboveKineticFriction { peak_adhesion: 0.2, kinetic_friction: 0.3 })
    );
    let ceiling = (1.0 + FRAC_1_PI) * 0.3;
    assert_eq!(
        MeasuredCurve::from_peak(ceiling, 1e-2, 0.3),
        Err(PeakTooHigh { peak_adhesion: ceiling, largest_possible: ceiling })
    );
    assert!(MeasuredCurve::from_peak(0.99 * ceiling, 1e-2, 0.3).is_ok());
    assert_eq!(
        MeasuredCurve::from_peak(0.4, 0.0, 0.3),
        Err(NotPositive { variable: "measured_creepage_at_peak", value: 0.0 })
    );
    assert_eq!(
        MeasuredCurve::from_peak(0.4, 1e-2, -0.3),
        Err(NotPositive { variable: "measured_kinetic_friction", value: -0.3 })
    );
    assert!(matches!(
        MeasuredCurve::from_peak(f64::NAN, 1e-2, 0.3),
        Err(NotPositive { variable: "measured_peak_adhesion", .. })
    ));
    let message = MeasuredCurve::from_peak(0.2, 1e-2, 0.3).unwrap_err().to_string();
    assert!(message.starts_with("measured_peak_adhesion = 0.2 is invalid"), "{message}");
}
