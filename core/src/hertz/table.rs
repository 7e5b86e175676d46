//! Hertz's solution under 1 N read from a table over the curvature ratio, for the normal
//! problem's candidates (`normal_problem.rs`): solving Hertz's shape equation costs five
//! residuals of two Carlson integrals each (≈ 4 700 instructions, a sixth of a wheel step with
//! two patches); the table's read costs two logarithms and three exponentials.
//!
//! Why a table over one variable suffices: Hertz's solution under the load Q, the relative
//! curvatures A, B = r·A and the contact modulus E* is ([`crate::hertz`])
//!
//! ```text
//! a = a₁(r)·(Q/(E* A))^{1/3},   b = k(r)·a,   δ = d(r)·a²·A,   p₀ = 3Q/(2π a b),
//! ```
//!
//! with a₁ = (R_D(0, k², 1)/(2π))^{1/3} and d = 3 R_F(0, 1, k²)/R_D(0, k², 1) functions of the
//! shape k = b/a alone, itself the root of the shape equation in r. So ln a₁, ln k and ln d are
//! smooth functions of u = ln r (nearly linear: k ≈ r^{−2/3}), tabulated every [`STEP`] from
//! [`HertzContact::solve`] with Q = A = E* = 1 and read by four-point Lagrange interpolation
//! (error O(h⁴)): within 4e-11 of the solved a, b, δ and p₀ (`tests` below). Beyond the table
//! (|u| > [`LOG_RATIO_REACH`], a/b beyond 400 — no wheel–rail patch) the shape equation is solved.

use std::sync::OnceLock;

use super::{HertzContact, RelativeCurvature};
use crate::contact_input::hertz_max_pressure;
use crate::InvalidInput;

/// The table's step in u = ln(B/A).
const STEP: f64 = 1.0 / 64.0;
/// The table covers |ln(B/A)| ≤ this (B/A within 1.2·10⁻⁴ … 8.1·10³).
const LOG_RATIO_REACH: f64 = 9.0;

/// ln a₁, ln k, ln d (module doc) at u = −[`LOG_RATIO_REACH`] + (j − 1)·[`STEP`]: one node
/// beyond each end, for the interpolation's outer points.
struct ShapeTable {
    nodes: Vec<[f64; 3]>,
}

impl ShapeTable {
    fn new() -> Self {
        let intervals = (2.0 * LOG_RATIO_REACH / STEP).round() as usize;
        let nodes = (0..=intervals + 2)
            .map(|j| {
                let u = -LOG_RATIO_REACH + (j as f64 - 1.0) * STEP;
                let curvature = RelativeCurvature::new(1.0, u.exp()).expect("ratios within 1e±4 are valid");
                let unit = HertzContact::solve(1.0, &curvature, 1.0).expect("Q = A = E* = 1 is representable");
                let a = unit.semi_axis_a;
                [a.ln(), (unit.semi_axis_b / a).ln(), (unit.approach / (a * a)).ln()]
            })
            .collect();
        Self { nodes }
    }

    /// The shared table, built on first use (≈ 1 200 solutions, a millisecond).
    fn get() -> &'static Self {
        static TABLE: OnceLock<ShapeTable> = OnceLock::new();
        TABLE.get_or_init(Self::new)
    }

    /// ln a₁, ln k, ln d at u by four-point Lagrange interpolation; `None` beyond the table
    /// (NaN too).
    fn at(&self, u: f64) -> Option<[f64; 3]> {
        if !(-LOG_RATIO_REACH..LOG_RATIO_REACH).contains(&u) {
            return None;
        }
        let position = (u + LOG_RATIO_REACH) / STEP;
        let j = position as usize;
        let t = position - j as f64;
        // The weights of the nodes at t = −1, 0, 1, 2 (node j + 1 of `nodes` is at t = 0).
        let (before, after, further) = (t + 1.0, t - 1.0, t - 2.0);
        let weights = [
            -t * after * further / 6.0,
            before * after * further / 2.0,
            -before * t * further / 2.0,
            before * t * after / 6.0,
        ];
        let stencil = &self.nodes[j..j + 4];
        Some(std::array::from_fn(|i| stencil.iter().zip(&weights).map(|(node, weight)| node[i] * weight).sum()))
    }
}

/// Builds the table if no placement has yet (`WheelOnRail::new` calls this: a millisecond then,
/// not in a wheel's first step).
pub(crate) fn prepare() {
    ShapeTable::get();
}

/// Hertz's solution under 1 N for `curvature` and the contact modulus E* \[Pa\]: from the table
/// (module doc), or [`HertzContact::solve`] where [`from_table`] has none (its error, then, is the
/// solver's).
pub(crate) fn unit_solution(curvature: &RelativeCurvature, contact_modulus: f64) -> Result<HertzContact, InvalidInput> {
    from_table(curvature, contact_modulus).map_or_else(|| HertzContact::solve(1.0, curvature, contact_modulus), Ok)
}

/// The table's solution under 1 N (module doc); `None` beyond the table and wherever its numbers
/// would not be finite and positive.
fn from_table(curvature: &RelativeCurvature, contact_modulus: f64) -> Option<HertzContact> {
    let rolling = curvature.rolling();
    let [log_a, log_k, log_d] = ShapeTable::get().at((curvature.lateral() / rolling).ln())?;
    // a = a₁ (E* A)^{−1/3} under Q = 1.
    let semi_axis_a = (log_a - (contact_modulus * rolling).ln() / 3.0).exp();
    let semi_axis_b = semi_axis_a * log_k.exp();
    let approach = log_d.exp() * semi_axis_a * (semi_axis_a * rolling);
    let max_pressure = hertz_max_pressure(1.0, semi_axis_a, semi_axis_b);
    let values = [semi_axis_a, semi_axis_b, max_pressure, approach];
    values.iter().all(|value| value.is_finite() && *value > 0.0).then_some(HertzContact {
        semi_axis_a,
        semi_axis_b,
        max_pressure,
        approach,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest relative difference of a, b, p₀, δ between the table and the solver.
    fn difference(curvature: &RelativeCurvature, modulus: f64) -> f64 {
        let (table, solved) =
            (from_table(curvature, modulus).unwrap(), HertzContact::solve(1.0, curvature, modulus).unwrap());
        [
            (table.semi_axis_a, solved.semi_axis_a),
            (table.semi_axis_b, solved.semi_axis_b),
            (table.max_pressure, solved.max_pressure),
            (table.approach, solved.approach),
        ]
        .iter()
        .map(|(ours, theirs)| (ours / theirs - 1.0).abs())
        .fold(0.0, f64::max)
    }

    /// Over the whole table, between and on its nodes (u every 0.00123, 14 600 ratios), for
    /// wheel-like and extreme rolling curvatures and moduli: within 4e-11 (measured 2.6e-11:
    /// the interpolation's O(h⁴) with h = 1/64 on these smooth functions, plus the solver's
    /// own 1e-14).
    #[test]
    fn the_table_gives_the_solved_contact_within_4e_11() {
        let mut worst = 0.0f64;
        for i in 0..14_600 {
            let u = -LOG_RATIO_REACH + 0.001_23 * f64::from(i);
            for (rolling, modulus) in [(1.087, 82e9 / 0.72), (1.0, 1.0), (37.0, 2e11), (1e-3, 1e6)] {
                worst = worst.max(difference(&RelativeCurvature::new(rolling, rolling * u.exp()).unwrap(), modulus));
            }
        }
        assert!(worst < 4e-11, "{worst:e}");
    }

    /// Beyond the table the solver answers, as it does for curvatures no table can read.
    #[test]
    fn beyond_the_table_the_solver_answers() {
        for ratio in [1e-5, 9e3, 1e12, 1e-12] {
            let curvature = RelativeCurvature::new(2.0, 2.0 * ratio).unwrap();
            assert_eq!(from_table(&curvature, 1e11), None);
            assert_eq!(unit_solution(&curvature, 1e11), HertzContact::solve(1.0, &curvature, 1e11));
        }
        assert!(ShapeTable::get().at(f64::NAN).is_none());
        assert!(ShapeTable::get().at(LOG_RATIO_REACH).is_none() && ShapeTable::get().at(-LOG_RATIO_REACH).is_some());
        // Where the table's numbers overflow, the solver's error.
        let huge = RelativeCurvature::new(1e-300, 1e-300).unwrap();
        assert_eq!(from_table(&huge, 1e-300), None);
        assert!(unit_solution(&huge, 1e-300).is_err());
        assert_eq!(unit_solution(&huge, 1e-300), HertzContact::solve(1.0, &huge, 1e-300));
    }
}
