//! The table's coordinates: where a contact sits in the five-dimensional table, by Kalker's
//! similarity law and the symmetries of the steady rolling problem.
//!
//! **Similarity.** With Hertz's pressure p_n = p₀√(1 − x²/a² − y²/b²) the tangential problem,
//! written in x/a, y/b and tractions in units of μp₀, depends on a/b, ν and the creepages
//! scaled by μp₀/G (spin also by the size c = √(ab) of the ellipse) only (Kalker 1990, §2.3;
//! the exact solver is written in exactly these units). So F/(μQ) and M_z/(μQc) are functions of
//!
//! ```text
//! u = (k_x ξ, k_y η, k_φ c φ) · G/(μp₀),   k_x = 3C11/(2π), k_y = 3C22/(2π),
//! k_φ = 3(C23 + C33)/(2π),
//! ```
//!
//! a/b and ν. The factors k put the linear theory's saturation, F_x = μQ at u_x = 1 (and F_y
//! alike), at the same place for every a/b and ν, so the features of the force surface (the
//! onset of full slip near |u| ≈ 3) line up across the table's a/b and ν nodes. Spin acts
//! through F_y (C23, dominant for a > b: 8.3 against C33 = 0.59 at a/b = 5.6, ν = 0.25) and
//! through M_z (C33, dominant for a < b): scaled by their sum, u_φ = 1 is where the larger of
//! its linear effects reaches about μQ (or μQc) for every ellipse, and the force surface has no
//! steep band in the spin share β (with C33 alone it had one, 0.1 wide, at a/b > 3).
//!
//! **Symmetries** (exact in the continuous problem and on the solver's symmetric grid):
//! S1: (ξ, η, φ) → −(ξ, η, φ) reverses every force; S2: (ξ, η, φ) → (ξ, −η, −φ) (the mirror
//! y → −y) reverses F_y and M_z. They fold every u onto u_x ≥ 0, u_y ≥ 0.
//!
//! **Direction and size** without trigonometry: with the L1 size s = u_x + u_y + |u_φ|,
//! α = u_y/(u_x + u_y) ∈ [0, 1] (the creepage direction; undefined, and unused, for pure spin),
//! β = u_φ/s ∈ [−1, 1] (the share of spin) and t = √s/(1 + √s) ∈ [0, 1): t = 0 is rest,
//! t → 1 is full sliding, reached continuously and tabulated analytically (`full_slip.rs`).
//! The square root spreads the nodes over the range where the forces bend most: the knee of
//! saturation (s ≈ 1…3) and, with spin, the last approach to full sliding (s ≈ 5…20, where
//! F_x and M_z turn within Δs ≈ 2); with t = s/(1 + s) those got 3 of 32 intervals, errors up
//! to 0.06 μQ.

use crate::numerics::{moves_negative, value, Scalar};

/// **Kink-fitted size coordinate τ.** Along a ray of growing creepage with spin the exact
/// theory's adhesion zone collapses within a tiny step of t (29 % → 2.7 % of the area within
/// Δt = 0.003), and the forces kink there; the kink's t_c moves with a/b, ν and the direction
/// (0.51 … 0.75 on 4800 rays). Each ray's nodes are uniform in τ, a piecewise-linear map of t
/// that is the identity up to `IDENTITY_END` and sends the ray's own t_c to `KINK_NODE`, so every
/// ray's kink sits on the same τ node; a query is evaluated at τ(t; t_c) with t_c interpolated
/// from its cell's corner rays, so the corners' kinks and the query's coincide. With 49 t nodes
/// both ends of the middle piece are nodes (12 and 27).
pub(crate) const IDENTITY_END: f64 = 0.25;
/// τ of every ray's collapse.
pub(crate) const KINK_NODE: f64 = 0.5625;
/// The range a ray's t_c is kept in (a ray whose adhesion never collapses gets the upper end).
pub(crate) const COLLAPSE_RANGE: (f64, f64) = (0.35, 0.9);

/// τ of size t on a ray (or at a query) whose collapse is at `collapse`.
pub(crate) fn kink_fitted<D: Scalar>(t: D, collapse: D) -> D {
    if value(t) <= IDENTITY_END {
        t
    } else if value(t) <= value(collapse) {
        (t - IDENTITY_END) / (collapse - IDENTITY_END) * (KINK_NODE - IDENTITY_END) + IDENTITY_END
    } else {
        -((-t + 1.0) / (-collapse + 1.0) * (1.0 - KINK_NODE)) + 1.0
    }
}

/// t of τ on a ray whose collapse is at `collapse`: the inverse of [`kink_fitted`].
pub(crate) fn size_of(tau: f64, collapse: f64) -> f64 {
    if tau <= IDENTITY_END {
        tau
    } else if tau <= KINK_NODE {
        IDENTITY_END + (tau - IDENTITY_END) / (KINK_NODE - IDENTITY_END) * (collapse - IDENTITY_END)
    } else {
        1.0 - (1.0 - tau) / (1.0 - KINK_NODE) * (1.0 - collapse)
    }
}

/// The creepage scale factors k = (k_x, k_y, k_φ) of one ellipse shape and material.
pub(crate) fn scale_factors(a_over_b: f64, poisson_ratio: f64) -> [f64; 3] {
    let k = crate::KalkerCoefficients::new(a_over_b, poisson_ratio);
    let c33 = crate::KalkerCoefficients::spin_moment_c33(a_over_b, poisson_ratio);
    [k.c11, k.c22, k.c23 + c33].map(|c| 3.0 * c / (2.0 * std::f64::consts::PI))
}

/// A contact folded onto the table's octant u_x ≥ 0, u_y ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Folded<D> {
    /// Creepage direction α ∈ [0, 1].
    pub alpha: D,
    /// Share of spin β ∈ [−1, 1].
    pub beta: D,
    /// Size t ∈ [0, 1].
    pub t: D,
    /// −1 when S1 was applied (every output reverses), else 1.
    pub sign_all: f64,
    /// −1 when S2 was applied (F_y and M_z reverse), else 1.
    pub sign_lateral: f64,
}

/// Largest size s kept with its derivative: beyond it t = 1/(1 + 1/√s) rounds to 1 anyway.
const SIZE_MAX: f64 = 1e300;

/// Folds a contact into (α, β, t) and the signs that undo the folding. `direction` is the
/// scaled creepage u up to a positive factor (finite components), `size_factor` that factor,
/// u = direction × size_factor (may be +∞: full sliding).
///
/// On a fold plane (u_x = 0, u_y = 0 or u_φ = 0, where a symmetry or the L1 size |u_φ| has a
/// kink) the side is the one the derivative's direction moves to ([`moves_negative`]), so the
/// derivative is the one-sided derivative of the interpolant along the direction,
/// lim (F(u + h·du) − F(u))/h for h → 0⁺, consistent with the value (which is the same from
/// both sides). At pure spin (u_x = u_y = 0) α is undefined at the point but constant along
/// the ray u + h·du: du_y/(du_x + du_y) after the folding; taking it with no rate keeps the
/// planar creepage's rate, which moves β off ±1 (a constant α there, as before, gave the
/// derivative of the creepage direction α = 0 whatever the direction's).
pub(crate) fn fold<D: Scalar>(direction: [D; 3], size_factor: D) -> Folded<D> {
    let [mut ux, mut uy, mut uphi] = direction;
    let mut sign_all = 1.0;
    if moves_negative(ux) {
        (ux, uy, uphi) = (-ux, -uy, -uphi);
        sign_all = -1.0;
    }
    let mut sign_lateral = 1.0;
    if moves_negative(uy) {
        (uy, uphi) = (-uy, -uphi);
        sign_lateral = -1.0;
    }
    let planar = ux + uy;
    let length = planar + if moves_negative(uphi) { -uphi } else { uphi };
    if value(length) == 0.0 {
        let zero = D::from(0.0);
        return Folded { alpha: zero, beta: zero, t: zero, sign_all, sign_lateral };
    }
    let alpha = if value(planar) > 0.0 {
        uy / planar
    } else if planar.rate() > 0.0 {
        D::from(uy.rate() / planar.rate())
    } else {
        D::from(0.0)
    };
    let beta = uphi / length;
    let size = length * size_factor;
    let size = if value(size) <= SIZE_MAX { size } else { D::from(SIZE_MAX) };
    if value(size) == 0.0 {
        // Underflowed (no load to speak of against the stiffness): rest, without √'s infinite slope.
        return Folded { alpha, beta, t: D::from(0.0), sign_all, sign_lateral };
    }
    // t = √s/(1 + √s): 0 at s = 0, 1 − 1e-150 at the largest s.
    let root = size.sqrt();
    let t = root / (root + 1.0);
    Folded { alpha, beta, t, sign_all, sign_lateral }
}

/// The scaled creepage u of a table node (α, β, t) with t < 1: the inverse of [`fold`].
pub(crate) fn unfold(alpha: f64, beta: f64, t: f64) -> [f64; 3] {
    let size = (t / (1.0 - t)).powi(2);
    let planar = (1.0 - beta.abs()) * size;
    [(1.0 - alpha) * planar, alpha * planar, beta * size]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Folding then unfolding gives the table's point, and the signs map it back to the input.
    #[test]
    fn fold_inverts_unfold_and_applies_the_symmetries() {
        for (alpha, beta, t) in [(0.0, 0.0, 0.5), (0.25, -0.5, 0.1), (1.0, 0.75, 0.9), (0.5, 1.0, 0.3)] {
            let u = unfold(alpha, beta, t);
            for flip in [[1.0, 1.0, 1.0], [-1.0, -1.0, -1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, 1.0]] {
                let input = [u[0] * flip[0], u[1] * flip[1], u[2] * flip[2]];
                let folded = fold(input, 1.0);
                assert!((folded.t - t).abs() < 1e-15, "{folded:?}");
                let table_point = unfold(folded.alpha, folded.beta, folded.t);
                let lateral = folded.sign_all * folded.sign_lateral;
                let back = [table_point[0] * folded.sign_all, table_point[1] * lateral, table_point[2] * lateral];
                for k in 0..3 {
                    assert!((back[k] - input[k]).abs() < 1e-12 * (1.0 + input[k].abs()), "{input:?}: {folded:?}");
                }
                assert!(table_point[0] >= 0.0 && table_point[1] >= 0.0, "{folded:?}");
            }
        }
    }

    /// The size map is continuous, increasing, inverted by `size_of`, and sends t_c to τ_c.
    #[test]
    fn kink_fitted_size_inverts_and_aligns_the_collapse() {
        for collapse in [COLLAPSE_RANGE.0, 0.514, 0.6, 0.748, COLLAPSE_RANGE.1] {
            assert!((kink_fitted(collapse, collapse) - KINK_NODE).abs() < 1e-15);
            let mut previous = -1.0;
            for i in 0..=1000 {
                let t = i as f64 / 1000.0;
                let tau = kink_fitted(t, collapse);
                assert!(tau > previous, "t {t}, t_c {collapse}: τ {tau} after {previous}");
                assert!((size_of(tau, collapse) - t).abs() < 1e-14, "t {t}, t_c {collapse}");
                previous = tau;
            }
            assert_eq!((kink_fitted(0.0, collapse), kink_fitted(1.0, collapse)), (0.0, 1.0));
        }
    }

    #[test]
    fn huge_and_zero_creepage_stay_finite() {
        let folded = fold([1e300, -1e300, 0.0], f64::INFINITY);
        assert_eq!(folded.t, 1.0);
        assert_eq!((folded.alpha, folded.beta), (0.5, 0.0));
        assert_eq!((folded.sign_all, folded.sign_lateral), (1.0, -1.0));
        let rest = fold([0.0, -0.0, 0.0], f64::INFINITY);
        assert_eq!((rest.alpha, rest.beta, rest.t), (0.0, 0.0, 0.0));
    }
}
