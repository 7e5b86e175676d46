//! Invariants of Polach's method: saturation, monotonicity, symmetry, continuity, bounds.

use crate::common;

use common::published::{TRACTCURV_CONTACT, TRACTCURV_EXACT};
use common::{contact, contact_case, relative_difference};
use std::f64::consts::PI;
use wheel_rail_contact::{ContactInput, CreepForceModel, CreepForces, Polach};

fn forces(input: &ContactInput) -> CreepForces {
    Polach::default().creep_forces(input).unwrap()
}

fn with_creepages(xi: f64, eta: f64, phi: f64) -> ContactInput {
    ContactInput { creepage_longitudinal: xi, creepage_lateral: eta, spin_creepage: phi, ..contact_case() }
}

/// Log-spaced creepage magnitudes from the linear range to deep full slip.
fn creepage_sweep() -> impl Iterator<Item = f64> {
    (0..=120).map(|i| 1e-7 * 10f64.powf(i as f64 / 15.0))
}

#[test]
fn saturates_to_the_coulomb_limit_from_below_monotonically_on_every_ray() {
    for a_over_b in [0.2, 1.0, 5.0] {
        for angle_degrees in [0.0, 30.0, 60.0, 90.0, 135.0, 200.0, 290.0] {
            let (sin, cos) = (angle_degrees * PI / 180.0_f64).sin_cos();
            let mut previous = 0.0;
            for s in creepage_sweep() {
                let input = contact(a_over_b, 0.28, s * cos, s * sin, 0.0);
                let f = forces(&input);
                let magnitude = f.force_longitudinal.hypot(f.force_lateral);
                let limit = input.friction_limit();
                assert!(magnitude <= limit, "|F| = {magnitude} > μQ at s = {s}");
                assert!(magnitude >= previous, "not monotone at s = {s}, ray {angle_degrees}°");
                previous = magnitude;
            }
            // F = μQ (1 − (4/3π) ε⁻³ + …); at s = 1e3 the gradient ε is ~4e5, so F = μQ to rounding.
            let far = forces(&contact(a_over_b, 0.28, 1e3 * cos, 1e3 * sin, 0.0));
            assert!((far.adhesion_utilisation - 1.0).abs() < 1e-12, "{far:?}");
        }
    }
}

#[test]
fn forces_oppose_creepage_and_are_odd() {
    for s in creepage_sweep().step_by(7) {
        for (xi, eta, phi) in [(s, 0.3 * s, 40.0 * s), (-s, 2.0 * s, -90.0 * s), (0.5 * s, -s, 300.0 * s)] {
            let f = forces(&with_creepages(xi, eta, phi));
            assert!(f.force_longitudinal * xi <= 0.0, "F_x·ξ > 0 at {xi}, {eta}, {phi}");
            let mirrored_x = forces(&with_creepages(-xi, eta, phi));
            assert_eq!(mirrored_x.force_longitudinal, -f.force_longitudinal, "F_x not odd in ξ");
            assert_eq!(mirrored_x.force_lateral, f.force_lateral, "F_y not even in ξ");
            let mirrored_y = forces(&with_creepages(xi, -eta, -phi));
            assert_eq!(mirrored_y.force_lateral, -f.force_lateral, "F_y(−η, −φ) ≠ −F_y(η, φ)");
            assert_eq!(mirrored_y.force_longitudinal, f.force_longitudinal);
        }
    }
}

#[test]
fn pure_spin_opposes_spin_and_fades_beyond_its_peak() {
    // K_M ∝ −ε_s/(1+ε_s²)² peaks at ε_s = 1/√3 and then falls to 0 (ERRATA E5's check).
    let mut previous_magnitude = f64::INFINITY;
    let mut past_peak = false;
    let mut last = 0.0;
    for phi in (0..=150).map(|i| 1e-3 * 10f64.powf(i as f64 / 15.0)) {
        let f = forces(&with_creepages(0.0, 0.0, phi));
        assert!(f.force_lateral < 0.0, "F_y must oppose φ > 0 at φ = {phi}");
        assert_eq!(f.force_longitudinal, 0.0);
        let magnitude = f.force_lateral.abs();
        if past_peak {
            assert!(magnitude <= previous_magnitude, "|F_yS| rises again at φ = {phi}");
        }
        past_peak |= magnitude < previous_magnitude && previous_magnitude.is_finite();
        previous_magnitude = magnitude;
        last = magnitude;
    }
    assert!(past_peak);
    assert!(last < 1e-12 * contact_case().friction_limit(), "|F_yS| = {last} at φ = 1e7 /m");
}

#[test]
fn spin_never_pushes_the_force_past_the_coulomb_limit() {
    // Analytically |K_M| ≤ √3/8 and |a·Φ/s_C| ≤ 2 (eq. 21) only give |F_yS| ≤ (9√3/64)·K_S·μQ, but
    // where |a·Φ/s_C| approaches 2 the spin opposes η and F_yS opposes the creep force. Over
    // every combination below (and 3·10⁶ random ones tried while writing this test) the total
    // stays within μQ; spin and creep sharing the sign come closest.
    let mut largest: f64 = 0.0;
    for a_over_b in [0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0] {
        for eta in creepage_sweep().step_by(2) {
            for spin_to_eta in [-1.99, -1.0, -0.5, 0.5, 2.0, 10.0, 1e3] {
                for xi_to_eta in [0.0, 0.3, -2.0] {
                    let base = contact(a_over_b, 0.28, xi_to_eta * eta, eta, 0.0);
                    let input = ContactInput { spin_creepage: spin_to_eta * eta / base.semi_axis_a, ..base };
                    let utilisation = forces(&input).adhesion_utilisation;
                    assert!(utilisation <= 1.0 + 1e-12, "|F|/μQ = {utilisation} for {input:?}");
                    largest = largest.max(utilisation);
                }
            }
        }
    }
    assert!(largest > 1.0 - 1e-9, "the sweep must reach full slip: {largest}");
}

#[test]
fn continuous_across_the_spin_switch_of_eq_21() {
    // Eq. (21) switches s_yC between η and η + aΦ where |η + aΦ| = |η|, i.e. aΦ = −2η.
    for eta in [1e-5, 3e-4, 2e-3, 0.05] {
        for xi in [0.0, 1e-4, 3e-3] {
            let base = contact(2.0, 0.28, xi, eta, 0.0);
            let phi_switch = -2.0 * eta / base.semi_axis_a;
            let at = |phi: f64| forces(&ContactInput { spin_creepage: phi, ..base });
            let (below, above) = (at(phi_switch * (1.0 - 1e-12)), at(phi_switch * (1.0 + 1e-12)));
            let scale = base.friction_limit();
            assert!((below.force_lateral - above.force_lateral).abs() < 1e-9 * scale, "{below:?} vs {above:?}");
            assert!((below.force_longitudinal - above.force_longitudinal).abs() < 1e-9 * scale);
        }
    }
}

#[test]
fn continuous_across_zero_creepages() {
    let scale = contact_case().friction_limit();
    for phi in [0.0, 0.3, -2.0] {
        for other in [0.0, 1e-4, -2e-3] {
            for tiny in [1e-15, 1e-30] {
                // Through ξ = 0 with η fixed, and through η = 0 with ξ fixed.
                let across_xi = [-tiny, 0.0, tiny].map(|xi| forces(&with_creepages(xi, other, phi)));
                let across_eta = [-tiny, 0.0, tiny].map(|eta| forces(&with_creepages(other, eta, phi)));
                for side in [0, 2] {
                    for f in [&across_xi, &across_eta] {
                        assert!((f[side].force_longitudinal - f[1].force_longitudinal).abs() < 1e-9 * scale);
                        assert!((f[side].force_lateral - f[1].force_lateral).abs() < 1e-9 * scale);
                    }
                }
            }
        }
    }
}

#[test]
fn lift_off_and_no_friction_give_zero_force_continuously() {
    let loaded = with_creepages(2e-3, -1e-3, 0.5);
    for (q, mu) in [(0.0, 0.3), (-5e3, 0.3), (82e3, 0.0), (1e-9, 0.3), (82e3, 1e-15)] {
        let f = forces(&ContactInput { normal_force: q, friction_coefficient: mu, ..loaded });
        let limit = if q > 0.0 { q * mu } else { 0.0 };
        assert!(
            f.force_longitudinal.abs() <= limit && f.force_lateral.abs() <= 3.0 * limit,
            "Q = {q}, μ = {mu}: {f:?}"
        );
        if limit == 0.0 {
            assert_eq!(f, CreepForces::default());
        }
    }
}

#[test]
fn eurosprinter_curve_stays_close_to_kalkers_exact_theory() {
    // CONTACT examples/tractcurv (contact_published_cases.md, case 1): exact-theory F_x/(μN).
    let base = TRACTCURV_CONTACT;
    let mut largest_error: f64 = 0.0;
    for (xi_percent, fx_exact) in TRACTCURV_EXACT {
        let input = ContactInput { creepage_longitudinal: xi_percent / 100.0, ..base };
        let fx = forces(&input).force_longitudinal / input.friction_limit();
        largest_error = largest_error.max((fx - fx_exact).abs());
    }
    // Polach's knee is rounder than the exact theory's: the largest gap, 0.0614 μN, is at
    // ξ = 0.28 % (Polach −0.9218, exact −0.9832); the linear range agrees.
    assert!(largest_error < 0.065, "largest |ΔF_x|/(μN) = {largest_error}");
    let linear = forces(&ContactInput { creepage_longitudinal: 1e-5, ..base });
    assert!(relative_difference(linear.force_longitudinal / base.friction_limit(), -0.0070) < 0.02);
}
