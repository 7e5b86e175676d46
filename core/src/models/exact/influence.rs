//! Influence coefficients of two quasi-identical elastic half-spaces for uniform tangential
//! tractions on rectangles, and the steady-rolling kernel built from them.
//!
//! A tangential point force Q on the surface of a half-space displaces the surface by Cerruti's
//! solution (Johnson, *Contact Mechanics*, 1985, eq. 3.86a–b). For two bodies with the same
//! elastic constants up to the combination 1/G = ½(1/G₁+1/G₂), ν/G = ½(ν₁/G₁+ν₂/G₂)
//! (quasi-identity, Kalker 1990 §1.5), traction p on body 1 and −p on body 2 give the
//! displacement difference u = u₁ − u₂ with the kernel
//!
//! ```text
//! K_xx = [(1−ν)/r + ν x²/r³] / (πG),   K_xy = ν x y / r³ / (πG),   K_yy = [(1−ν)/r + ν y²/r³] / (πG),
//! ```
//!
//! and no coupling to the normal direction. Integrating over a rectangle with uniform traction
//! gives Love's closed forms (Love 1929, *Phil. Trans. R. Soc. A* 228; Kalker 1990 §5.2;
//! CONTACT's `m_inflcf`). With the corner function
//!
//! ```text
//! F_xx(x, y) = (1−ν) x asinh(y/|x|) + y asinh(x/|y|)     (∂²F_xx/∂x∂y = (1−ν)/r + ν x²/r³)
//! F_yy(x, y) = x asinh(y/|x|) + (1−ν) y asinh(x/|y|)
//! F_xy(x, y) = −ν r
//! ```
//!
//! the displacement at offset (X, Y) from the centre of a δx × δy rectangle is
//! Σ ± F(X ± δx/2, Y ± δy/2) / (πG), the sign being the product of the two ± signs. The
//! textbook form uses ln(x + r); asinh(x/|y|) = ln((x + r)/|y|) differs from it by a term in y
//! alone, which the four-corner sum cancels, and asinh does not lose digits when x < 0.
//!
//! Everything here is dimensionless: lengths in units of the semi-axis a, tractions in units of
//! the creepage scale (see `tangential.rs`), so the 1/(πG) factor becomes 1/π.

use std::f64::consts::PI;

/// x·asinh(y/|x|), with its limit 0 at x = 0.
fn x_asinh_y_over_x(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    }
}

/// The three independent components of a symmetric 2 × 2 tangential influence matrix.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct TangentialInfluence {
    pub xx: f64,
    pub xy: f64,
    pub yy: f64,
}

/// The corner function (F_xx, F_xy, F_yy) at (x, y), times π (see the module documentation).
fn corner(x: f64, y: f64, poisson_ratio: f64) -> TangentialInfluence {
    let along_x = x_asinh_y_over_x(x, y);
    let along_y = x_asinh_y_over_x(y, x);
    TangentialInfluence {
        xx: (1.0 - poisson_ratio) * along_x + along_y,
        xy: -poisson_ratio * x.hypot(y),
        yy: along_x + (1.0 - poisson_ratio) * along_y,
    }
}

/// Σ ± F over the four corners (the sign is the product of the corners' ± signs), divided by
/// π: corners given as [(+, +), (+, −), (−, +), (−, −)].
fn four_corner_sum(corners: [TangentialInfluence; 4]) -> TangentialInfluence {
    let [pp, pm, mp, mm] = corners;
    TangentialInfluence {
        xx: (pp.xx - pm.xx - mp.xx + mm.xx) / PI,
        xy: (pp.xy - pm.xy - mp.xy + mm.xy) / PI,
        yy: (pp.yy - pm.yy - mp.yy + mm.yy) / PI,
    }
}

/// Love's coefficients: displacement difference at offset (x, y) from the centre of a
/// `length` × `width` rectangle carrying unit uniform traction, times G (dimensionless).
#[cfg(test)]
fn rectangle_influence(x: f64, y: f64, length: f64, width: f64, poisson_ratio: f64) -> TangentialInfluence {
    let (half_length, half_width) = (0.5 * length, 0.5 * width);
    four_corner_sum([
        corner(x + half_length, y + half_width, poisson_ratio),
        corner(x + half_length, y - half_width, poisson_ratio),
        corner(x - half_length, y + half_width, poisson_ratio),
        corner(x - half_length, y - half_width, poisson_ratio),
    ])
}

/// Love's coefficients between all pairs of elements of a grid of `elements_x` × `elements_y`
/// rectangles of size `length` × `width`, divided by `length` as the steady-rolling slip needs
/// them (see `tangential.rs`): entry (dx, dy) is A(dx·δx, dy·δy)/δx for offsets
/// −nx ≤ dx ≤ nx (one more than the grid, for the element just behind each row's trailing
/// edge) and −(ny−1) ≤ dy ≤ ny−1.
///
/// A is even under (x, y) → (−x, −y) in every component (xy/r³ included), so the table serves
/// both A(I − J) and A(J − I).
pub(crate) struct InfluenceTable {
    pub elements_x: usize,
    pub elements_y: usize,
    /// Components, row-major over offsets: index (dx + nx) + (dy + ny − 1)(2nx + 1).
    pub xx: Vec<f64>,
    pub xy: Vec<f64>,
    pub yy: Vec<f64>,
}

impl InfluenceTable {
    pub fn new(elements_x: usize, elements_y: usize, length: f64, width: f64, poisson_ratio: f64) -> Self {
        let size = (2 * elements_x + 1) * (2 * elements_y - 1);
        let mut table = Self {
            elements_x,
            elements_y,
            xx: Vec::with_capacity(size),
            xy: Vec::with_capacity(size),
            yy: Vec::with_capacity(size),
        };
        // The corners of every rectangle lie on one lattice of (2nx + 2) × 2ny nodes: the corner
        // function is evaluated once per node, not four times per entry.
        let (nodes_x, nodes_y) = (2 * elements_x + 2, 2 * elements_y);
        let node_x = |m: usize| (m as f64 - elements_x as f64 - 0.5) * length;
        let node_y = |m: usize| (m as f64 - elements_y as f64 + 0.5) * width;
        let mut lattice = Vec::with_capacity(nodes_x * nodes_y);
        for m_y in 0..nodes_y {
            for m_x in 0..nodes_x {
                lattice.push(corner(node_x(m_x), node_y(m_y), poisson_ratio));
            }
        }
        // Entry (dx, dy): corners x = (dx ± ½)δx at nodes dx + nx + 1 and dx + nx, y = (dy ± ½)δy
        // at nodes dy + ny and dy + ny − 1.
        for lower_y in 0..nodes_y - 1 {
            for lower_x in 0..nodes_x - 1 {
                let node = |m_x: usize, m_y: usize| lattice[m_x + m_y * nodes_x];
                let a = four_corner_sum([
                    node(lower_x + 1, lower_y + 1),
                    node(lower_x + 1, lower_y),
                    node(lower_x, lower_y + 1),
                    node(lower_x, lower_y),
                ]);
                table.xx.push(a.xx / length);
                table.xy.push(a.xy / length);
                table.yy.push(a.yy / length);
            }
        }
        table
    }

    /// Index of the offset (`offset_x`, `offset_y`) into the component tables.
    pub fn index(&self, offset_x: isize, offset_y: isize) -> usize {
        let row = 2 * self.elements_x + 1;
        (offset_x + self.elements_x as isize) as usize + (offset_y + self.elements_y as isize - 1) as usize * row
    }

    /// Diagonal part of A(0) − A(offset_x, 0)/δx: the change of an element's slip per unit
    /// traction step that ends `offset_x` elements downstream. The off-diagonal term vanishes
    /// on the x axis (xy/r³ is odd in y).
    pub fn step_response(&self, offset_x: isize) -> (f64, f64) {
        let (centre, end) = (self.index(0, 0), self.index(offset_x, 0));
        (self.xx[centre] - self.xx[end], self.yy[centre] - self.yy[end])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The normal-direction analogue of Love's formula, (1−ν)/r integrated, at the centre of a
    /// square of side h gives 4 h asinh(1) (Johnson 1985, eq. 3.20 with c = h/2, both bodies).
    #[test]
    fn centre_of_square_matches_love() {
        let h = 0.3;
        let influence = rectangle_influence(0.0, 0.0, h, h, 0.0);
        let expected = 4.0 * h * 1.0_f64.asinh() / PI;
        assert!((influence.xx - expected).abs() < 1e-14, "{} vs {expected}", influence.xx);
        assert!((influence.yy - expected).abs() < 1e-14);
        assert!(influence.xy.abs() < 1e-15);
    }

    /// Far from the rectangle its traction acts like a point force of the same resultant:
    /// Cerruti's kernel times the area, to O((h/r)²).
    #[test]
    fn far_field_is_the_point_force_kernel() {
        let (h, w, nu) = (0.01, 0.02, 0.3);
        let (x, y): (f64, f64) = (1.3, -0.7);
        let r = x.hypot(y);
        let area = h * w;
        let expected_xx = ((1.0 - nu) / r + nu * x * x / r.powi(3)) * area / PI;
        let expected_xy = nu * x * y / r.powi(3) * area / PI;
        let expected_yy = ((1.0 - nu) / r + nu * y * y / r.powi(3)) * area / PI;
        let influence = rectangle_influence(x, y, h, w, nu);
        for (got, want) in [(influence.xx, expected_xx), (influence.xy, expected_xy), (influence.yy, expected_yy)] {
            assert!((got - want).abs() < 1e-3 * want.abs(), "{got} vs {want}");
        }
    }

    /// Swapping the axes swaps xx and yy (isotropy), and xy is odd in each coordinate.
    #[test]
    fn symmetries() {
        let a = rectangle_influence(0.4, 0.25, 0.1, 0.05, 0.28);
        let swapped = rectangle_influence(0.25, 0.4, 0.05, 0.1, 0.28);
        assert!((a.xx - swapped.yy).abs() < 1e-15 && (a.yy - swapped.xx).abs() < 1e-15);
        assert!((a.xy - swapped.xy).abs() < 1e-15);
        let mirrored = rectangle_influence(-0.4, 0.25, 0.1, 0.05, 0.28);
        assert!((a.xy + mirrored.xy).abs() < 1e-15 && (a.xx - mirrored.xx).abs() < 1e-15);
        assert!(a.xy > 0.0, "ν x y / r³ > 0 in the first quadrant");
    }

    /// The table holds A/δx at every offset, is even under point reflection, and a step that
    /// ends downstream raises the slip (A decreases with distance).
    #[test]
    fn table_entries_and_step_response() {
        let (dx, dy, nu) = (0.1, 0.07, 0.25);
        let table = InfluenceTable::new(5, 4, dx, dy, nu);
        for (i, j) in [(0, 0), (-5, 3), (5, -3), (2, 1)] {
            let k = table.index(i, j);
            let a = rectangle_influence(i as f64 * dx, j as f64 * dy, dx, dy, nu);
            assert!((table.xx[k] - a.xx / dx).abs() < 1e-14 && (table.yy[k] - a.yy / dx).abs() < 1e-14);
            assert!((table.xy[k] - a.xy / dx).abs() < 1e-14);
            let mirrored = table.index(-i, -j);
            assert!(
                (table.xy[k] - table.xy[mirrored]).abs() < 1e-14 && (table.xx[k] - table.xx[mirrored]).abs() < 1e-14
            );
        }
        let (near_x, near_y) = table.step_response(1);
        let (far_x, far_y) = table.step_response(4);
        assert!(0.0 < near_x && near_x < far_x && 0.0 < near_y && near_y < far_y);
        assert_eq!(table.xy[table.index(3, 0)], 0.0);
    }
}
