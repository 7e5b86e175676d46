//! Kalker's linear-theory creepage coefficients C11, C22, C23 as continuous functions of the
//! semi-axis ratio a/b and Poisson's ratio ν.
//!
//! Sources: Kalker (1990), *Three-dimensional elastic bodies in rolling contact*, Table E.3
//! (`data/kalker_coefficients.csv`, turned into a constant by `build.rs`), and Kalker's
//! asymptotic formulas for thin ellipses (g < 0.1, docs/reference/kalker-asymptotes.md).
//!
//! Interpolation (Kalker's CONTACT rule): at each table row, 1/C is quadratic (Lagrange) in ν
//! through ν = 0, 0.25, 0.5; between rows C is linear in g = smaller/larger semi-axis.
//!
//! Below g = 0.1 the asymptotes differ from the table's g = 0.1 row by a few per cent, so a hard
//! switch would make the forces jump. We blend multiplicatively:
//!
//! ```text
//! C(g) = C_asym(g) · [1 + (C_table(0.1)/C_asym(0.1) − 1) · g/0.1],   g < 0.1,
//! ```
//!
//! which equals the table at g = 0.1 and tends to the asymptote (relative correction → 0) as
//! g → 0: continuous in a/b over the whole range, with both published limits honoured.

use std::f64::consts::PI;

/// One table row: the reciprocals 1/C at ν = 0, 0.25, 0.5.
pub(crate) struct KalkerRow {
    inv_c11: [f64; 3],
    inv_c22: [f64; 3],
    inv_c23: [f64; 3],
}

include!(concat!(env!("OUT_DIR"), "/kalker_table.rs"));

/// Index of the table row with a/b = 1 (rows before it are a/b = 0.1 … 0.9, after it b/a = 0.9 … 0.1).
const ROW_ROUND: usize = 9;
/// Smallest tabulated ratio g; below it the asymptotes apply.
const G_TABLE_MIN: f64 = 0.1;
/// Numerical floor of g: keeps g^{3/2} and 1/g far from underflow/overflow for absurd ratios.
/// Physical contacts never come near it; below it the coefficients are held constant.
const G_FLOOR: f64 = 1e-100;

/// Kalker's creepage coefficients for one ellipse shape and material [1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KalkerCoefficients {
    /// Longitudinal creepage coefficient C11.
    pub c11: f64,
    /// Lateral creepage coefficient C22.
    pub c22: f64,
    /// Lateral force from spin, C23 (= −C32 for quasi-identical bodies).
    pub c23: f64,
}

impl KalkerCoefficients {
    /// Coefficients for semi-axis ratio `a_over_b` = a/b (a in the rolling direction) and
    /// Poisson's ratio `poisson_ratio` in [0, 0.5]. `a_over_b` must be > 0 (not checked here:
    /// callers validate their inputs first).
    pub fn new(a_over_b: f64, poisson_ratio: f64) -> Self {
        let weights = lagrange_weights(poisson_ratio);
        let (g, a_is_shorter) = if a_over_b <= 1.0 { (a_over_b, true) } else { (1.0 / a_over_b, false) };
        if g >= G_TABLE_MIN {
            return interpolate_table(g, a_is_shorter, &weights);
        }
        let edge_row = if a_is_shorter { 0 } else { KALKER_TABLE.len() - 1 };
        let table_edge = row_coefficients(&KALKER_TABLE[edge_row], &weights);
        let asymptote_edge = asymptotes(G_TABLE_MIN, a_is_shorter, poisson_ratio);
        let asymptote = asymptotes(g.max(G_FLOOR), a_is_shorter, poisson_ratio);
        let weight = g / G_TABLE_MIN;
        let blend = |asym: f64, table: f64, asym_edge: f64| asym * (1.0 + (table / asym_edge - 1.0) * weight);
        Self {
            c11: blend(asymptote.c11, table_edge.c11, asymptote_edge.c11),
            c22: blend(asymptote.c22, table_edge.c22, asymptote_edge.c22),
            c23: blend(asymptote.c23, table_edge.c23, asymptote_edge.c23),
        }
    }
}

/// Lagrange weights of the nodes ν = 0, 0.25, 0.5 (CSV header):
/// 1/C(ν) = 8(ν−¼)(ν−½)/C(0) − 16(ν−½)ν/C(¼) + 8ν(ν−¼)/C(½).
fn lagrange_weights(nu: f64) -> [f64; 3] {
    [8.0 * (nu - 0.25) * (nu - 0.5), -16.0 * (nu - 0.5) * nu, 8.0 * nu * (nu - 0.25)]
}

fn row_coefficients(row: &KalkerRow, weights: &[f64; 3]) -> KalkerCoefficients {
    let at_nu = |inv: &[f64; 3]| 1.0 / (weights[0] * inv[0] + weights[1] * inv[1] + weights[2] * inv[2]);
    KalkerCoefficients { c11: at_nu(&row.inv_c11), c22: at_nu(&row.inv_c22), c23: at_nu(&row.inv_c23) }
}

/// Linear interpolation in g between the two rows that bracket it (g in [0.1, 1]).
fn interpolate_table(g: f64, a_is_shorter: bool, weights: &[f64; 3]) -> KalkerCoefficients {
    // Position in rows: a/b branch row i at g = 0.1(i+1); b/a branch row 9+j at g = 1 − 0.1 j.
    let position = if a_is_shorter { g * 10.0 - 1.0 } else { ROW_ROUND as f64 + (1.0 - g) * 10.0 };
    let lower = (position as usize).min(KALKER_TABLE.len() - 2);
    let fraction = position - lower as f64;
    let low = row_coefficients(&KALKER_TABLE[lower], weights);
    if fraction == 0.0 {
        return low;
    }
    let high = row_coefficients(&KALKER_TABLE[lower + 1], weights);
    let mix = |l: f64, h: f64| l + (h - l) * fraction;
    KalkerCoefficients { c11: mix(low.c11, high.c11), c22: mix(low.c22, high.c22), c23: mix(low.c23, high.c23) }
}

/// Kalker's asymptotic coefficients for a thin ellipse, g = smaller/larger semi-axis → 0.
fn asymptotes(g: f64, a_is_shorter: bool, nu: f64) -> KalkerCoefficients {
    let ln_4 = 4.0_f64.ln();
    if a_is_shorter {
        // a ≪ b: the contact is a thin strip across the rail.
        KalkerCoefficients {
            c11: PI * PI / (4.0 * (1.0 - nu)),
            c22: PI * PI / 4.0,
            c23: PI * g.sqrt() / (3.0 * (1.0 - nu)) * (1.0 + nu * ((16.0 / g).ln() - 5.0)),
        }
    } else {
        // a ≫ b, with Λ = ln(16/g²) written as ln 16 − 2 ln g so that g² cannot underflow.
        let lambda = 16.0_f64.ln() - 2.0 * g.ln();
        let c11 = 2.0 * PI / ((lambda - 2.0 * nu) * g) * (1.0 + (3.0 - ln_4) / (lambda - 2.0 * nu));
        let d22 = (1.0 - nu) * lambda + 2.0 * nu;
        let c22 = 2.0 * PI / g * (1.0 + (1.0 - nu) * (3.0 - ln_4) / d22) / d22;
        let c23 = 2.0 * PI / (3.0 * g * g.sqrt() * ((1.0 - nu) * lambda - 2.0 + 4.0 * nu));
        KalkerCoefficients { c11, c22, c23 }
    }
}
