//! The table's t = 1 nodes: full sliding, where the traction is μp_n against the rigid slip
//! everywhere in the contact, so the forces follow from quadrature over the Hertzian pressure
//! instead of the solver (Kalker 1990, §5.2: the limit of the exact theory for large creepage).
//!
//! In units X = x/a, Y = y/b, c = √(ab) = 1, the rigid slip of the scaled creepage u is
//! w = (u_x/k_x − (u_φ/k_φ) b Y, u_y/k_y + (u_φ/k_φ) a X) (only its direction matters), and
//!
//! ```text
//! F/(μQ)      = −(3/2π) ∫∫_{X²+Y²<1} √(1 − X² − Y²) ŵ dX dY,
//! M_z/(μQc)   = −(3/2π) ∫∫ √(1 − X² − Y²) (a X ŵ_y − b Y ŵ_x) dX dY.
//! ```
//!
//! Polar coordinates with X + iY = sin θ e^{iϑ} turn the weight √(1 − ρ²) ρ dρ into
//! cos²θ sin θ dθ, smooth over θ ∈ [0, π/2] (the centre and the edge included); the midpoint rule
//! in θ and ϑ then converges at second order, except near the spin's centre of rotation, where
//! ŵ jumps (on a set of vanishing measure). The sums are divided by the same rule's sum of the
//! weight (2π/3 in the limit), so a uniform slip gives |F| = μQ to rounding, as it must.

use std::f64::consts::PI;

/// Midpoints in σ and in ϑ: the quadrature error is below 1e-5 for every table direction
/// (halving both changes the forces by less than that; `tests::converged`).
const RADIAL_POINTS: usize = 320;
const ANGULAR_POINTS: usize = 640;

/// [F_x/(μQ), F_y/(μQ), M_z/(μQc)] in full sliding, for the scaled creepage direction `u`
/// (not all zero) of an ellipse with semi-axis ratio `a_over_b` and scale factors `scale`.
pub(crate) fn full_slip_forces(u: [f64; 3], a_over_b: f64, scale: [f64; 3]) -> [f64; 3] {
    full_slip_with(u, a_over_b, scale, RADIAL_POINTS, ANGULAR_POINTS)
}

fn full_slip_with(u: [f64; 3], a_over_b: f64, scale: [f64; 3], radial: usize, angular: usize) -> [f64; 3] {
    let (a, b) = (a_over_b.sqrt(), 1.0 / a_over_b.sqrt());
    let [xi, eta, spin] = [u[0] / scale[0], u[1] / scale[1], u[2] / scale[2]];
    let mut sum = [0.0; 3];
    let mut total_weight = 0.0;
    let angles: Vec<(f64, f64)> =
        (0..angular).map(|m| (2.0 * PI * (m as f64 + 0.5) / angular as f64).sin_cos()).collect();
    for n in 0..radial {
        let (rho, cos_theta) = (std::f64::consts::FRAC_PI_2 * (n as f64 + 0.5) / radial as f64).sin_cos();
        let weight = cos_theta * cos_theta * rho;
        total_weight += weight * angular as f64;
        for &(sin, cos) in &angles {
            let (x, y) = (a * rho * cos, b * rho * sin);
            let (wx, wy) = (xi - spin * y, eta + spin * x);
            let length = wx.hypot(wy);
            if length > 0.0 {
                let (sx, sy) = (wx / length, wy / length);
                sum[0] += weight * sx;
                sum[1] += weight * sy;
                sum[2] += weight * (x * sy - y * sx);
            }
        }
    }
    // −(3/2π) ∫ … with ∫ cos²θ sin θ dθ dϑ = 2π/3 replaced by the rule's own value of it.
    sum.map(|s| -s / total_weight)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pure_creepage_slides_at_the_coulomb_limit() {
        // ŵ is constant: F = −μQ ŵ exactly, no moment.
        let f = full_slip_forces([3.0, 4.0, 0.0], 2.0, [1.0, 1.0, 1.0]);
        assert!((f[0] + 0.6).abs() < 1e-12 && (f[1] + 0.8).abs() < 1e-12 && f[2].abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn pure_spin_on_a_circle_gives_the_sliding_moment_only() {
        // Circle, rotation about the centre: M_z = −μ ∫ p_n r dA = −(3π/16) μQc (Johnson 1985,
        // eq. 5.68 with the Hertz pressure), no force.
        let f = full_slip_forces([0.0, 0.0, 1.0], 1.0, [1.0, 1.0, 1.0]);
        assert!(f[0].abs() < 1e-12 && f[1].abs() < 1e-12, "{f:?}");
        assert!((f[2] + 3.0 * PI / 16.0).abs() < 1e-5, "{f:?}");
    }

    #[test]
    fn converged() {
        for (u, ab) in [([1.0, 0.5, 2.0], 0.3), ([0.2, 0.1, -1.0], 5.0), ([0.0, 1.0, 0.4], 1.0)] {
            let fine = full_slip_with(u, ab, [1.0, 1.2, 0.7], 2 * RADIAL_POINTS, 2 * ANGULAR_POINTS);
            let ours = full_slip_forces(u, ab, [1.0, 1.2, 0.7]);
            for k in 0..3 {
                assert!((fine[k] - ours[k]).abs() < 1e-5, "{u:?} {ab}: {ours:?} vs {fine:?}");
            }
            let magnitude = ours[0].hypot(ours[1]);
            assert!(magnitude < 1.0, "|F| ≤ μQ: {magnitude}");
        }
    }
}
