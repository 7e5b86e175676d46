//! Kalker's coefficients: the table reproduced at its nodes, Kalker's ν interpolation rule,
//! the thin-ellipse asymptotes, and continuity over a/b = 1e-3 … 1e3.

use crate::common;

use common::relative_difference;
use std::f64::consts::PI;
use wheel_rail_contact::KalkerCoefficients;

/// The rows of data/kalker_coefficients.csv, parsed here independently of build.rs:
/// (a/b, [[C11; 3], [C22; 3], [C23; 3]] at ν = 0, 0.25, 0.5).
fn table() -> Vec<(f64, [[f64; 3]; 3])> {
    include_str!("../../../data/kalker_coefficients.csv")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("branch"))
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            let n: Vec<f64> = f[1..].iter().map(|x| x.parse().unwrap()).collect();
            let a_over_b = if f[0] == "a/b" { n[0] } else { 1.0 / n[0] };
            (a_over_b, [[n[1], n[2], n[3]], [n[4], n[5], n[6]], [n[7], n[8], n[9]]])
        })
        .collect()
}

fn as_array(c: KalkerCoefficients) -> [f64; 3] {
    [c.c11, c.c22, c.c23]
}

#[test]
fn table_nodes_are_reproduced() {
    let rows = table();
    assert_eq!(rows.len(), 19);
    for (a_over_b, values) in rows {
        for (nu_index, nu) in [0.0, 0.25, 0.5].into_iter().enumerate() {
            let got = as_array(KalkerCoefficients::new(a_over_b, nu));
            for (coefficient, got) in got.into_iter().enumerate() {
                let expected = values[coefficient][nu_index];
                assert!(
                    relative_difference(got, expected) < 4.0 * f64::EPSILON,
                    "C{} at a/b = {a_over_b}, nu = {nu}: {got} vs table {expected}",
                    ["11", "22", "23"][coefficient]
                );
            }
        }
    }
}

#[test]
fn poisson_zero_gives_c11_equal_c22() {
    for a_over_b in [1e-3, 0.05, 0.1, 0.37, 1.0, 2.5, 10.0, 47.0, 1e3] {
        let c = KalkerCoefficients::new(a_over_b, 0.0);
        assert!(relative_difference(c.c11, c.c22) < 1e-14, "a/b = {a_over_b}: {c:?}");
    }
}

#[test]
fn poisson_interpolation_is_quadratic_in_the_reciprocal() {
    // Hand evaluation of the CSV header's rule at a/b = 0.5, ν = 0.28:
    // weights 8(ν−¼)(ν−½) = −0.0528, −16(ν−½)ν = 0.9856, 8ν(ν−¼) = 0.0672.
    let expected_c11 = 1.0 / (-0.0528 / 2.88 + 0.9856 / 3.62 + 0.0672 / 4.83);
    let expected_c23 = 1.0 / (-0.0528 / 0.827 + 0.9856 / 0.929 + 0.0672 / 1.07);
    let c = KalkerCoefficients::new(0.5, 0.28);
    assert!(relative_difference(c.c11, expected_c11) < 1e-14, "{} vs {expected_c11}", c.c11);
    assert!(relative_difference(c.c23, expected_c23) < 1e-14, "{} vs {expected_c23}", c.c23);
    // Between rows, as in CONTACT's linrol: linear in g at each tabulated ν first, then the rule
    // in ν. a/b = 0.55 lies half-way between the rows 0.5 and 0.6.
    let node = |c_0_5: f64, c_0_6: f64| (c_0_5 + c_0_6) / 2.0;
    let expected_c11 = 1.0 / (-0.0528 / node(2.88, 2.98) + 0.9856 / node(3.62, 3.72) + 0.0672 / node(4.83, 4.91));
    let c = KalkerCoefficients::new(0.55, 0.28);
    assert!(relative_difference(c.c11, expected_c11) < 1e-14, "{} vs {expected_c11}", c.c11);
    let mid = KalkerCoefficients::new(0.55, 0.0);
    assert!(relative_difference(mid.c22, (2.88 + 2.98) / 2.0) < 1e-14, "{mid:?}");
    // b/a = 0.45 (a/b = 1/0.45) lies half-way between the b/a rows 0.5 and 0.4.
    let mid = KalkerCoefficients::new(1.0 / 0.45, 0.5);
    assert!(relative_difference(mid.c23, (2.96 + 3.70) / 2.0) < 1e-13, "{mid:?}");
}

/// Kalker's thin-ellipse asymptotes (kalker_asymptotes.md), written out independently.
fn asymptote(a_over_b: f64, nu: f64) -> [f64; 3] {
    if a_over_b < 1.0 {
        let g = a_over_b;
        [
            PI * PI / (4.0 * (1.0 - nu)),
            PI * PI / 4.0,
            PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
        ]
    } else {
        let g = 1.0 / a_over_b;
        let l = (16.0 / (g * g)).ln();
        let c11 = 2.0 * PI / ((l - 2.0 * nu) * g) * (1.0 + (3.0 - 4f64.ln()) / (l - 2.0 * nu));
        let d = (1.0 - nu) * l + 2.0 * nu;
        let c22 = 2.0 * PI / g * (1.0 + (1.0 - nu) * (3.0 - 4f64.ln()) / d) / d;
        let c23 = 2.0 * PI / (3.0 * g.powf(1.5) * ((1.0 - nu) * l - 2.0 + 4.0 * nu));
        [c11, c22, c23]
    }
}

#[test]
fn thin_ellipses_approach_kalkers_asymptotes() {
    for nu in [0.0, 0.25, 0.28, 0.5] {
        for a_over_b in [0.05, 20.0] {
            // The blend removes the table/asymptote mismatch linearly in g: halving g halves it.
            let got = as_array(KalkerCoefficients::new(a_over_b, nu));
            let finer = if a_over_b < 1.0 { a_over_b / 2.0 } else { a_over_b * 2.0 };
            let got_finer = as_array(KalkerCoefficients::new(finer, nu));
            let (asym, asym_finer) = (asymptote(a_over_b, nu), asymptote(finer, nu));
            for i in 0..3 {
                let error = got[i] / asym[i] - 1.0;
                let error_finer = got_finer[i] / asym_finer[i] - 1.0;
                assert!(
                    (error_finer / error - 0.5).abs() < 1e-6,
                    "coefficient {i}, nu = {nu}, a/b = {a_over_b}: {error} then {error_finer}"
                );
            }
        }
        // At g = 1e-3 exactly g/0.1 = 1 % of the mismatch at the table edge remains, and that
        // mismatch is a few per cent (kalker_asymptotes.md; the largest, 6.4 %, is C23 at ν = 0.5).
        for (a_over_b, edge) in [(1e-3, 0.1), (1e3, 10.0)] {
            let got = as_array(KalkerCoefficients::new(a_over_b, nu));
            let at_edge = as_array(KalkerCoefficients::new(edge, nu));
            for i in 0..3 {
                let edge_mismatch = at_edge[i] / asymptote(edge, nu)[i] - 1.0;
                assert!(edge_mismatch.abs() < 0.065, "C{i}, nu = {nu}: table vs asymptote {edge_mismatch}");
                let remaining = got[i] / asymptote(a_over_b, nu)[i] - 1.0;
                assert!(
                    (remaining - 0.01 * edge_mismatch).abs() < 1e-12,
                    "C{i} a/b = {a_over_b}, nu = {nu}: {remaining}"
                );
            }
        }
    }
}

#[test]
fn continuous_across_table_edges_and_the_round_contact() {
    for nu in [0.0, 0.25, 0.28, 0.5] {
        for edge in [0.1, 1.0, 10.0] {
            let below = as_array(KalkerCoefficients::new(edge - 1e-12, nu));
            let at = as_array(KalkerCoefficients::new(edge, nu));
            let above = as_array(KalkerCoefficients::new(edge + 1e-12, nu));
            for i in 0..3 {
                for neighbour in [below[i], above[i]] {
                    let jump = relative_difference(neighbour, at[i]);
                    assert!(jump < 1e-9, "coefficient {i} jumps by {jump} at a/b = {edge}, nu = {nu}");
                }
            }
        }
    }
}

#[test]
fn continuous_and_positive_over_the_whole_range() {
    // Log-spaced sweep 1e-3 … 1e3: neighbouring values differ only by the local slope, never by
    // a jump. The steepest logarithmic slope |d ln C / d ln(a/b)| is C23's between the b/a rows
    // 0.2 and 0.1: (12.2 − 5.72)/0.1 · 0.2/5.72 = 2.27; the bound uses 3. A step is 2.3e-5 in
    // ln(a/b), so the bound (6.9e-5) is far below the table/asymptote mismatch (~1e-2).
    let steps = 600_000;
    let ratio = (1e6f64).powf(1.0 / steps as f64);
    for nu in [0.0, 0.28, 0.5] {
        let mut previous = as_array(KalkerCoefficients::new(1e-3, nu));
        for step in 1..=steps {
            let a_over_b = 1e-3 * ratio.powi(step);
            let current = as_array(KalkerCoefficients::new(a_over_b, nu));
            for i in 0..3 {
                assert!(current[i] > 0.0 && current[i].is_finite(), "C{i} at a/b = {a_over_b}");
                let change = relative_difference(current[i], previous[i]);
                assert!(change < 3.0 * (ratio - 1.0), "C{i} changes by {change} at a/b = {a_over_b}, nu = {nu}");
            }
            previous = current;
        }
    }
}
