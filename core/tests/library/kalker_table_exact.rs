//! Every row of Kalker's Table E.3 as the code holds it (`KalkerCoefficients`, built from
//! `data/kalker_coefficients.csv` and `data/kalker_c33.csv`) against the exact theory in full
//! adhesion: the reference is the solver, not the table, so a mistyped entry fails here.
//!
//! Linear theory: F_x = −G c² C11 ξ, F_y = −G c² C22 η − G c³ C23 φ, M_z = G c³ C23 η − G c⁴ C33 φ
//! with c = √(ab). Creepages 1e-7 and φ = 1e-5 /m leave every element in adhesion (asserted).
//!
//! **Grids and tolerances (measured, release build, all 19 rows × ν = 0, 0.25, 0.5).** On 40 × 20
//! elements (40 along the rolling direction, whose first-order error dominates) C11 and C22 lie
//! within 1.3 % of the table and C23 within 1.5 %: checked at 3 %, so an entry off by 8 % (e.g.
//! C23 at a/b = 0.8, ν = 0.25 typed 1.15 instead of 1.25) fails with a margin of 3.5 %. C33
//! converges much more slowly (the spin moment weights the contact's edges, +450 % at a/b = 10,
//! ν = 0.5 on 40 × 20); the first-order Richardson extrapolation 2·C(40 × 20) − C(20 × 20) lies
//! within 4.6 % of the table everywhere (the table's C33 is the project's transcription, see
//! `data/kalker_c33.csv`): checked at 6 %, which catches an entry off by more than ~10 %
//! anywhere and by 8 % where the solver's gap is small. A finer C33 check (80 × 40 and
//! 40 × 40 extrapolated, ~1 s per row and ν) is `full_table_c33_on_finer_grids`, ignored by default.

use wheel_rail_contact::{ContactInput, ExactTheory, KalkerCoefficients};

const SHEAR_MODULUS: f64 = 82e9;

/// The 19 rows of Table E.3 as a/b: g = a/b = 0.1 … 1 on the a ≤ b branch, then b/a = 0.9 … 0.1.
fn table_rows() -> Vec<f64> {
    let g: Vec<f64> = (1..=10).map(|i| f64::from(i) / 10.0).collect();
    g.iter().copied().chain(g.iter().rev().skip(1).map(|b_over_a| 1.0 / b_over_a)).collect()
}

/// (C11, C22, C23, C33) of the exact theory on `grid` (elements along x, along y).
fn solver_coefficients(grid: (usize, usize), a_over_b: f64, nu: f64) -> [f64; 4] {
    let model = ExactTheory::new(grid.0, grid.1);
    let b = 5e-3;
    let a = a_over_b * b;
    let base = ContactInput {
        creepage_longitudinal: 0.0,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        normal_force: 1e5,
        semi_axis_a: a,
        semi_axis_b: b,
        friction_coefficient: 0.3,
        shear_modulus: SHEAR_MODULUS,
        poisson_ratio: nu,
    };
    let (creepage, spin) = (1e-7, 1e-5);
    // ξ and η together: by the symmetry y → −y neither drives the other's force.
    let creep =
        model.solve(&ContactInput { creepage_longitudinal: creepage, creepage_lateral: creepage, ..base }).unwrap();
    let spinning = model.solve(&ContactInput { spin_creepage: spin, ..base }).unwrap();
    for solution in [&creep, &spinning] {
        assert!(solution.converged && solution.slip_area == 0.0, "a/b {a_over_b}, ν {nu}: not in full adhesion");
    }
    let area = a * b;
    let g = SHEAR_MODULUS;
    [
        -creep.forces.force_longitudinal / (g * area * creepage),
        -creep.forces.force_lateral / (g * area * creepage),
        -spinning.forces.force_lateral / (g * area.powf(1.5) * spin),
        -spinning.forces.spin_moment.unwrap() / (g * area * area * spin),
    ]
}

fn table(a_over_b: f64, nu: f64) -> [f64; 4] {
    let c = KalkerCoefficients::new(a_over_b, nu);
    [c.c11, c.c22, c.c23, KalkerCoefficients::spin_moment_c33(a_over_b, nu)]
}

const NAMES: [&str; 4] = ["C11", "C22", "C23", "C33"];

#[test]
fn every_row_of_table_e3_matches_the_exact_theory() {
    let mut failures = Vec::new();
    for a_over_b in table_rows() {
        for nu in [0.0, 0.25, 0.5] {
            let fine = solver_coefficients((40, 20), a_over_b, nu);
            let coarse = solver_coefficients((20, 20), a_over_b, nu);
            let expected = table(a_over_b, nu);
            for k in 0..4 {
                let (solver, tolerance) = if k < 3 { (fine[k], 0.03) } else { (2.0 * fine[k] - coarse[k], 0.06) };
                let error = expected[k] / solver - 1.0;
                if error.abs() > tolerance {
                    failures.push(format!(
                        "a/b {a_over_b:.4}, ν {nu}: {} table {} vs solver {solver:.4} ({:+.1} %)",
                        NAMES[k],
                        expected[k],
                        100.0 * error
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// C33 on finer grids: 2·C(80 × 40) − C(40 × 40). About a minute in release; run with
/// `cargo test --release --test library kalker_table_exact -- --ignored`.
#[test]
#[ignore = "about a minute: finer-grid C33 check"]
fn full_table_c33_on_finer_grids() {
    let mut failures = Vec::new();
    for a_over_b in table_rows() {
        for nu in [0.0, 0.25, 0.5] {
            let fine = solver_coefficients((80, 40), a_over_b, nu)[3];
            let coarse = solver_coefficients((40, 40), a_over_b, nu)[3];
            let solver = 2.0 * fine - coarse;
            let expected = table(a_over_b, nu)[3];
            if (expected / solver - 1.0).abs() > 0.06 {
                failures.push(format!("a/b {a_over_b:.4}, ν {nu}: C33 table {expected} vs solver {solver:.4}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
