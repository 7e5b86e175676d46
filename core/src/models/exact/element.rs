//! One element's Coulomb problem: the traction that makes its slip vanish or oppose the
//! traction, given how its slip responds to its own traction (shared by the Newton solver's
//! release step and the Gauss–Seidel reference).

/// Newton iterations on the slip multiplier λ; convergence is monotone and takes a handful.
const MAX_NEWTON_STEPS: usize = 60;

/// Exact solution of one element's equations: traction p with |p| ≤ `bound` for the slip
/// s = r + diag(b) p, returning (p, slips).
///
/// Adhesion (s = 0) if p = −r/b fits the bound. Otherwise s = −λ p with λ > 0 gives
/// p = −r/(b + λ), and λ solves |p(λ)| = g. Writing r = ρ e (|e| = 1), the function
/// φ(λ) = (Σ e_k²/(b_k + λ)²)^(−1/2) − ρ/g is increasing and concave (a power mean of
/// b_k + λ with exponent −2), so Newton's method from a start with φ ≤ 0 climbs monotonically
/// to the root. λ₀ = max(0, ρ/g − max b) has φ(λ₀) ≤ 0.
pub(crate) fn local_traction(residual: (f64, f64), own: (f64, f64), bound: f64) -> ((f64, f64), bool) {
    let (b_x, b_y) = own;
    let adhesion = (-residual.0 / b_x, -residual.1 / b_y);
    if adhesion.0.hypot(adhesion.1) <= bound {
        return (adhesion, false);
    }
    let rho = residual.0.hypot(residual.1);
    let (e_x, e_y) = (residual.0 / rho, residual.1 / rho);
    let target = rho / bound;
    let mut lambda = (target - b_x.max(b_y)).max(0.0);
    for _ in 0..MAX_NEWTON_STEPS {
        let (q_x, q_y) = (e_x / (b_x + lambda), e_y / (b_y + lambda));
        let sum_sq = q_x * q_x + q_y * q_y;
        let phi = 1.0 / sum_sq.sqrt() - target;
        // φ' = (Σ e_k²/(b_k+λ)³) / (Σ e_k²/(b_k+λ)²)^(3/2)
        let slope = (q_x * q_x / (b_x + lambda) + q_y * q_y / (b_y + lambda)) / (sum_sq * sum_sq.sqrt());
        let step = -phi / slope;
        // Stops at convergence, and on a NaN step (cannot occur for finite r ≠ 0, g > 0).
        if step.is_nan() || step <= 1e-15 * (lambda + b_x.min(b_y)) {
            break;
        }
        lambda += step;
    }
    let traction = (-rho * e_x / (b_x + lambda), -rho * e_y / (b_y + lambda));
    // Rounding can leave |p| a hair off g; put it exactly on the bound, direction unchanged.
    let scale = bound / traction.0.hypot(traction.1);
    ((traction.0 * scale, traction.1 * scale), true)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// In slip the traction sits on the bound and the resulting slip opposes it.
    #[test]
    fn local_slip_opposes_traction() {
        let own = (2.0, 3.0);
        let residual = (5.0, -4.0);
        let bound = 0.7;
        let ((p_x, p_y), slips) = local_traction(residual, own, bound);
        assert!(slips);
        assert!((p_x.hypot(p_y) - bound).abs() < 1e-14);
        let (s_x, s_y) = (residual.0 + own.0 * p_x, residual.1 + own.1 * p_y);
        // s = −λ p with λ > 0: parallel and opposite.
        assert!((s_x * p_y - s_y * p_x).abs() < 1e-12, "not parallel");
        assert!(s_x * p_x + s_y * p_y < 0.0, "not opposite");
    }

    #[test]
    fn local_adhesion_cancels_slip() {
        let ((p_x, p_y), slips) = local_traction((0.2, -0.3), (2.0, 3.0), 1.0);
        assert!(!slips);
        assert!((0.2 + 2.0 * p_x).abs() < 1e-15 && (-0.3 + 3.0 * p_y).abs() < 1e-15);
    }

    /// Huge residuals (full slip at enormous creepage) still give a finite traction on the bound.
    #[test]
    fn local_solution_survives_extreme_residuals() {
        let ((p_x, p_y), slips) = local_traction((1e300, -1e300), (1.0, 2.0), 1e-3);
        assert!(slips && p_x.is_finite() && p_y.is_finite());
        assert!((p_x + 1e-3 / 2f64.sqrt()).abs() < 1e-12);
    }
}
