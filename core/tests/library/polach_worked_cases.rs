//! Polach's method against cases computed independently from the paper's literal formulas by
//! core/tests/data/polach_worked_cases.py (Python, plain floats, eq. (20) as printed).

use crate::common;

use common::relative_difference;
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

#[test]
fn matches_the_independent_worked_cases() {
    let text = include_str!("../data/polach_worked_cases.csv");
    let mut cases = 0;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let input = ContactInput {
            creepage_longitudinal: v[0],
            creepage_lateral: v[1],
            spin_creepage: v[2],
            normal_force: v[3],
            semi_axis_a: v[4],
            semi_axis_b: v[5],
            friction_coefficient: v[6],
            shear_modulus: v[7],
            poisson_ratio: v[8],
        };
        let forces = Polach::default().creep_forces(&input).unwrap();
        for (got, expected) in [(forces.force_longitudinal, v[9]), (forces.force_lateral, v[10])] {
            // Relative to μQ where the expected component is exactly zero.
            let error = if expected == 0.0 { got.abs() / (v[3] * v[6]) } else { relative_difference(got, expected) };
            assert!(error < 1e-12, "case {line}: {got} vs {expected}");
        }
        cases += 1;
    }
    assert_eq!(cases, 5);
}
