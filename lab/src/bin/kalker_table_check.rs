//! Compares Kalker's table of C11, C22, C23 (data/kalker_coefficients.csv, Kalker 1990 table
//! E.3) at its own rows with the coefficients of this project's exact solver in full adhesion
//! ([`ExactTheory::linear_coefficients`]) on two grids fitted to the ellipse.
//!
//! Grids for a level n: n elements along the longer semi-axis' direction, n/2 along the shorter
//! one's for a < b; for a > b, max(n b/a, 0.4 n) across (thin ellipses need the lateral
//! resolution too). The convergence is first order but irregular (the staircase edge of the
//! ellipse moves with the grid), so the two levels are shown rather than extrapolated.
//!
//! `cargo run --release -p lab --bin kalker_table_check -- 200 400` (about two minutes); its
//! output is kept in docs/reference/kalker-table-check.txt.

use wheel_rail_contact::{ExactTheory, LinearCoefficients};

fn grid(a_over_b: f64, n: usize) -> ExactTheory {
    let longitudinal = if a_over_b >= 1.0 { n } else { n / 2 };
    let lateral = if a_over_b <= 1.0 { n } else { (n as f64 / a_over_b).max(0.4 * n as f64) as usize };
    ExactTheory::new(longitudinal, lateral)
}

fn main() {
    let levels: Vec<usize> = std::env::args().skip(1).map(|n| n.parse().expect("grid levels n1 n2")).collect();
    let [n1, n2] = [levels.first().copied().unwrap_or(200), levels.get(1).copied().unwrap_or(400)];
    println!("row        nu    coefficient  table   n={n1:<4}   n={n2:<4}  n={n2} vs table");
    for line in include_str!("../../../data/kalker_coefficients.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("branch"))
    {
        let fields: Vec<&str> = line.split(',').collect();
        let (branch, g) = (fields[0], fields[1]);
        let g: f64 = g.parse().expect("ratio");
        let a_over_b = if branch == "a/b" { g } else { 1.0 / g };
        for (k, nu) in [0.0, 0.25, 0.5].into_iter().enumerate() {
            let solve = |n| grid(a_over_b, n).linear_coefficients(a_over_b, nu).expect("valid grid and ellipse");
            let (coarse, fine): (LinearCoefficients, LinearCoefficients) = (solve(n1), solve(n2));
            for (name, column, v1, v2) in
                [("C11", 0, coarse.c11, fine.c11), ("C22", 1, coarse.c22, fine.c22), ("C23", 2, coarse.c23, fine.c23)]
            {
                let table: f64 = fields[2 + 3 * column + k].parse().expect("coefficient");
                println!(
                    "{branch}={g:<5} {nu:<5} {name:<12} {table:6.3} {v1:9.4} {v2:9.4} {:+10.2} %",
                    (v2 / table - 1.0) * 100.0
                );
            }
        }
    }
}
