//! Cross-checks the C33 column of data/kalker_c33.csv against this project's exact-theory solver.
//!
//! In full adhesion under pure spin Kalker's linear theory gives M_z = −G c⁴ C33 φ (c = √(ab)),
//! so the solver's moment at a tiny spin creepage yields C33. The solver's grid error is first
//! order, so two grids n1 < n2 are extrapolated: C33 ≈ v(n2) − (v(n1) − v(n2))·n1/(n2 − n1).
//!
//! `cargo run --release -p lab --bin kalker_c33_check -- 80 120 [branch=g …]`
//! (e.g. `b/a=0.1`; all rows by default). The full table at 80² and 120² takes tens of minutes.

use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTheory, GridSize};

fn c33_from_exact_theory(a_over_b: f64, poisson_ratio: f64, grid: usize) -> f64 {
    let (shear_modulus, spin) = (8e10, 1e-5);
    let b = (32e-6 / a_over_b).sqrt();
    let a = a_over_b * b;
    let input = ContactInput {
        creepage_longitudinal: 0.0,
        creepage_lateral: 0.0,
        spin_creepage: spin,
        normal_force: 1e5,
        semi_axis_a: a,
        semi_axis_b: b,
        friction_coefficient: 0.3,
        shear_modulus,
        poisson_ratio,
    };
    let model = ExactTheory { grid: GridSize { longitudinal: grid, lateral: grid } };
    let moment = model.creep_forces(&input).expect("valid input").spin_moment.expect("exact theory has M_z");
    -moment / (shear_modulus * (a * b).powi(2) * spin)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let grids: Vec<usize> = args.iter().take(2).map(|g| g.parse().expect("grid sizes n1 n2")).collect();
    let [n1, n2] = [grids.first().copied().unwrap_or(80), grids.get(1).copied().unwrap_or(120)];
    let rows: Vec<&String> = args.iter().skip(2).collect();
    println!("row          nu    table   n={n1:<4}  n={n2:<4}  extrapolated  table vs extrapolated");
    for line in
        include_str!("../../../data/kalker_c33.csv").lines().filter(|l| !l.starts_with('#') && !l.starts_with("branch"))
    {
        let fields: Vec<&str> = line.split(',').collect();
        let (branch, g) = (fields[0], fields[1]);
        if !rows.is_empty() && !rows.iter().any(|r| **r == format!("{branch}={g}")) {
            continue;
        }
        let g: f64 = g.parse().unwrap();
        let a_over_b = if branch == "a/b" { g } else { 1.0 / g };
        for (k, nu) in [0.0, 0.25, 0.5].into_iter().enumerate() {
            let table: f64 = fields[2 + k].parse().unwrap();
            let (v1, v2) = (c33_from_exact_theory(a_over_b, nu, n1), c33_from_exact_theory(a_over_b, nu, n2));
            let extrapolated = v2 - (v1 - v2) * n1 as f64 / (n2 - n1) as f64;
            println!(
                "{branch}={g:<5} {nu:<5} {table:7.4} {v1:8.4} {v2:8.4} {extrapolated:11.4} {:+10.1} %",
                (table / extrapolated - 1.0) * 100.0
            );
        }
    }
}
