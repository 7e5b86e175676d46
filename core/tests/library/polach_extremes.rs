//! Polach's method at the extremes: every valid input gives finite forces within the Coulomb
//! limit, and invalid inputs give a typed error naming the variable.

use crate::common;

use common::contact_case;
use proptest::prelude::*;
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

/// Every input below is valid, so the result must exist, be finite and respect |F| ≤ μQ
/// (see core/tests/library/polach_invariants.rs for why spin does not break that bound).
fn assert_finite_and_bounded(input: &ContactInput) {
    let f = Polach::default().creep_forces(input).unwrap_or_else(|e| panic!("{e} for {input:?}"));
    let limit = input.friction_limit();
    // Rounding: 1e-12 relative, plus the absolute spacing of subnormal numbers (a few 5e-324),
    // which dominates when μQ itself is subnormal.
    let bound = limit * (1.0 + 1e-12) + 1e-321;
    assert!(f.force_longitudinal.is_finite() && f.force_lateral.is_finite(), "{f:?} for {input:?}");
    assert!(f.force_longitudinal.abs() <= bound, "{f:?} for {input:?}");
    assert!(f.force_lateral.abs() <= bound, "{f:?} for {input:?}");
    assert!(f.adhesion_utilisation.is_finite(), "{f:?} for {input:?}");
    assert!(f.adhesion_utilisation * limit <= bound, "{f:?} for {input:?}");
}

fn signed(magnitudes: &[f64]) -> Vec<f64> {
    magnitudes.iter().flat_map(|&m| if m == 0.0 { vec![0.0] } else { vec![m, -m] }).collect()
}

#[test]
fn extremes_grid() {
    let creepages = signed(&[0.0, 1e-300, 1e-12, 1e-6, 1e-3, 1.0, 1e3, 1e6]);
    let mut evaluated = 0_u64;
    for a_over_b in [1e-3_f64, 1e-2, 0.1, 0.5, 1.0, 2.0, 10.0, 1e2, 1e3] {
        // Semi-axes around √(ab) = 5 mm.
        let b = 5e-3 / a_over_b.sqrt();
        for normal_force in [0.0, 1e-12, 1.0, 1e3, 1e5, 1e7] {
            for friction_coefficient in [0.0, 1e-12, 1e-6, 0.3, 1.0] {
                for &xi in &creepages {
                    for &eta in &creepages {
                        for &phi in &creepages {
                            assert_finite_and_bounded(&ContactInput {
                                creepage_longitudinal: xi,
                                creepage_lateral: eta,
                                spin_creepage: phi,
                                normal_force,
                                semi_axis_a: a_over_b * b,
                                semi_axis_b: b,
                                friction_coefficient,
                                ..contact_case()
                            });
                            evaluated += 1;
                        }
                    }
                }
            }
        }
    }
    assert_eq!(evaluated, 9 * 6 * 5 * 15 * 15 * 15);
}

/// A finite value spread over all magnitudes 1e-300 … 1e300, either sign, or zero.
fn any_magnitude() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-300.0..300.0_f64, any::<bool>()).prop_map(|(e, neg)| if neg { -(10f64.powf(e)) } else { 10f64.powf(e) })
    ]
}

fn positive(log10_min: f64, log10_max: f64) -> impl Strategy<Value = f64> {
    (log10_min..log10_max).prop_map(|e| 10f64.powf(e))
}

/// Either sign of a magnitude spread log-uniformly over 10^log10_min … 10^log10_max.
fn signed_magnitude(log10_min: f64, log10_max: f64) -> impl Strategy<Value = f64> {
    (positive(log10_min, log10_max), any::<bool>()).prop_map(|(m, negative)| if negative { -m } else { m })
}

/// Realistic values (weight 6 of 10: wheel–rail creepages 1e-5 … 1e-1, spin 1e-3 … 1e2 /m),
/// exactly 0 (1 of 10) or any magnitude (3 of 10). So ξ, η and Φ are all realistic together
/// in ~22 % of the cases (and the contact's other inputs in 60 % each), not in < 1 %.
fn creepage(log10_min: f64, log10_max: f64) -> impl Strategy<Value = f64> {
    prop_oneof![6 => signed_magnitude(log10_min, log10_max), 1 => Just(0.0), 3 => any_magnitude()]
}

/// A realistic range (weight 6 of 10) or the extreme one.
fn realistic_or(
    realistic: impl Strategy<Value = f64>,
    extreme: impl Strategy<Value = f64>,
) -> impl Strategy<Value = f64> {
    prop_oneof![6 => realistic, 4 => extreme]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn any_finite_valid_input_gives_finite_bounded_forces(
        xi in creepage(-5.0, -1.0), eta in creepage(-5.0, -1.0), phi in creepage(-3.0, 2.0),
        normal_force in realistic_or(1e3..2e5_f64, any_magnitude()),
        friction_coefficient in realistic_or(0.05..0.6_f64, positive(-300.0, 1.0)),
        semi_axis_a in realistic_or(positive(-3.0, -1.7), positive(-150.0, 150.0)),
        semi_axis_b in realistic_or(positive(-3.0, -1.7), positive(-150.0, 150.0)),
        shear_modulus in realistic_or(7e10..9e10_f64, positive(-100.0, 100.0)), poisson_ratio in 0.0..=0.5_f64,
    ) {
        assert_finite_and_bounded(&ContactInput {
            creepage_longitudinal: xi, creepage_lateral: eta, spin_creepage: phi, normal_force,
            semi_axis_a, semi_axis_b, friction_coefficient, shear_modulus, poisson_ratio,
        });
    }
}

#[test]
fn huge_creepages_keep_their_direction() {
    // ξ : η = 1 : 3 at 1e200 and at 1e3 (ε ≈ 1e7): both saturated to rounding, so equal forces.
    let direction = |scale: f64| {
        let input = ContactInput { creepage_longitudinal: scale, creepage_lateral: 3.0 * scale, ..contact_case() };
        Polach::default().creep_forces(&input).unwrap()
    };
    let (huge, saturated) = (direction(1e200), direction(1e3));
    assert!((huge.force_longitudinal / saturated.force_longitudinal - 1.0).abs() < 1e-12, "{huge:?} vs {saturated:?}");
    assert!((huge.force_lateral / saturated.force_lateral - 1.0).abs() < 1e-12, "{huge:?} vs {saturated:?}");
}

#[test]
fn invalid_inputs_name_the_variable_and_value() {
    let valid = contact_case();
    let cases: [(ContactInput, &str, f64); 10] = [
        (ContactInput { creepage_longitudinal: f64::NAN, ..valid }, "creepage_longitudinal", f64::NAN),
        (ContactInput { creepage_lateral: f64::INFINITY, ..valid }, "creepage_lateral", f64::INFINITY),
        (ContactInput { spin_creepage: f64::NEG_INFINITY, ..valid }, "spin_creepage", f64::NEG_INFINITY),
        (ContactInput { normal_force: f64::NAN, ..valid }, "normal_force", f64::NAN),
        (ContactInput { semi_axis_a: 0.0, ..valid }, "semi_axis_a", 0.0),
        (ContactInput { semi_axis_b: -1e-3, ..valid }, "semi_axis_b", -1e-3),
        (ContactInput { friction_coefficient: -0.1, ..valid }, "friction_coefficient", -0.1),
        (ContactInput { shear_modulus: 0.0, ..valid }, "shear_modulus", 0.0),
        (ContactInput { poisson_ratio: 0.51, ..valid }, "poisson_ratio", 0.51),
        (ContactInput { poisson_ratio: f64::NAN, ..valid }, "poisson_ratio", f64::NAN),
    ];
    // Finite values whose Coulomb limit μQ overflows (found by the FMU's fuzz harness).
    let overflow = ContactInput { friction_coefficient: f64::MAX, normal_force: 1e5, ..valid };
    let error = Polach::default().creep_forces(&overflow).unwrap_err();
    assert_eq!((error.variable, error.value), ("friction_coefficient", f64::MAX));
    for (input, variable, value) in cases {
        let error = Polach::default().creep_forces(&input).unwrap_err();
        assert_eq!(error.variable, variable);
        assert!(error.value.to_bits() == value.to_bits(), "{error}");
        assert!(error.to_string().starts_with(&format!("{variable} = {value} is invalid: ")), "{error}");
    }
}
