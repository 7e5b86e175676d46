//! The potential contact area: a rectangular grid of equal elements over the contact ellipse,
//! carrying the Hertzian pressure.

use std::f64::consts::PI;

/// Half-size of the potential contact area in units of the semi-axes: 1.1 a × 1.1 b, as in
/// CONTACT's examples (44 elements of 0.4 mm over 17.6 mm for a = 8 mm puts 40 inside).
pub const POTENTIAL_AREA_HALF_SIZE: f64 = 1.1;

/// Number of elements of the grid over the potential contact area
/// 2.2 a (rolling direction) × 2.2 b (lateral).
///
/// ```
/// use wheel_rail_contact::GridSize;
///
/// // CONTACT's grid for a = 8 mm, b = 4 mm: 44 × 44 elements of 0.4 × 0.2 mm over 17.6 × 8.8 mm.
/// let grid = GridSize { longitudinal: 44, lateral: 44 };
/// let (length, width) = grid.element_sides(8e-3, 4e-3);
/// assert!((length - 0.4e-3).abs() < 1e-15 && (width - 0.2e-3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GridSize {
    /// Elements along x, the rolling direction.
    pub longitudinal: usize,
    /// Elements along y, the lateral direction.
    pub lateral: usize,
}

impl GridSize {
    /// Length (along x) and width (along y) of this grid's elements over the ellipse with
    /// semi-axes `semi_axis_a` × `semi_axis_b` (in their unit).
    pub fn element_sides(&self, semi_axis_a: f64, semi_axis_b: f64) -> (f64, f64) {
        let side = 2.0 * POTENTIAL_AREA_HALF_SIZE;
        (side * semi_axis_a / self.longitudinal as f64, side * semi_axis_b / self.lateral as f64)
    }
}

/// The grid in the solver's units (lengths in units of a) with the Hertzian traction bound.
pub(crate) struct ContactGrid {
    pub elements_x: usize,
    pub elements_y: usize,
    /// Element length δx and width δy, in units of a.
    pub length: f64,
    pub width: f64,
    /// Normalised pressure p_n / p₀ per element, row-major (index i + j·nx), 0 outside the
    /// ellipse. Scaled so that Σ p_n δx δy equals the Hertzian load exactly (see [`Self::new`]).
    pub pressure: Vec<f64>,
    /// For every lateral row j, the range of longitudinal indices i inside the ellipse.
    /// The ellipse is convex, so each row's contact elements are contiguous.
    pub rows_in_contact: Vec<Option<(usize, usize)>>,
}

impl ContactGrid {
    /// Grid for the ellipse with semi-axes 1 × `b_over_a` (units of a).
    ///
    /// An element is in contact when its centre lies inside the ellipse; it carries the Hertz
    /// pressure p₀ √(1 − x²/a² − y²/b²) at its centre (Johnson 1985, eq. 7.49), rescaled by a
    /// common factor (→ 1 as the grid is refined) so that the discrete resultant equals the
    /// continuous one, (2π/3) a b p₀ = Q. Then Coulomb's bound sums to μQ exactly and full
    /// slip gives |F| = μQ on every grid.
    pub(crate) fn new(size: GridSize, b_over_a: f64) -> Self {
        let (elements_x, elements_y) = (size.longitudinal, size.lateral);
        let (length, width) = size.element_sides(1.0, b_over_a);
        let mut pressure = vec![0.0; elements_x * elements_y];
        let mut rows_in_contact = vec![None; elements_y];
        for (j, row) in rows_in_contact.iter_mut().enumerate() {
            let y = centre(j, elements_y) * POTENTIAL_AREA_HALF_SIZE;
            for i in 0..elements_x {
                let x = centre(i, elements_x) * POTENTIAL_AREA_HALF_SIZE;
                let depth = 1.0 - x * x - y * y;
                if depth > 0.0 {
                    pressure[i + j * elements_x] = depth.sqrt();
                    *row = Some(row.map_or((i, i), |(first, _)| (first, i)));
                }
            }
        }
        // Continuous resultant of √(1 − x² − y²/β²) over the ellipse: (2π/3) β, β = b/a.
        let discrete_resultant: f64 = pressure.iter().sum::<f64>() * length * width;
        let scale = 2.0 * PI / 3.0 * b_over_a / discrete_resultant;
        pressure.iter_mut().for_each(|p| *p *= scale);
        Self { elements_x, elements_y, length, width, pressure, rows_in_contact }
    }

    /// Centre of element (i, j) in units of a.
    pub(crate) fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (
            centre(i, self.elements_x) * POTENTIAL_AREA_HALF_SIZE,
            centre(j, self.elements_y) * POTENTIAL_AREA_HALF_SIZE * self.width_scale(),
        )
    }

    /// b/a, recovered from the element width.
    fn width_scale(&self) -> f64 {
        self.width * self.elements_y as f64 / (2.0 * POTENTIAL_AREA_HALF_SIZE)
    }

    pub(crate) fn element_area(&self) -> f64 {
        self.length * self.width
    }
}

/// Centre of element k of n equal elements over [−1, 1], in units of the half-size.
fn centre(k: usize, n: usize) -> f64 {
    -1.0 + (2.0 * k as f64 + 1.0) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CONTACT's published grid: 44 × 44 elements over 1.1 a × 1.1 b put 40 × 40 inside.
    #[test]
    fn contacts_grid_has_forty_elements_across() {
        let grid = ContactGrid::new(GridSize { longitudinal: 44, lateral: 44 }, 0.5);
        let middle_row = grid.rows_in_contact[22].unwrap();
        assert_eq!(middle_row, (2, 41));
        assert_eq!(grid.rows_in_contact.iter().filter(|row| row.is_some()).count(), 40);
        assert!((grid.length - 0.05).abs() < 1e-15 && (grid.width - 0.025).abs() < 1e-15);
        let (x, y) = grid.centre(43, 0);
        assert!((x - 1.075).abs() < 1e-12 && (y + 0.5375).abs() < 1e-12);
    }

    /// The resultant of the pressure is the Hertzian load, and the rescaling is small.
    #[test]
    fn pressure_resultant_is_exact() {
        let grid = ContactGrid::new(GridSize { longitudinal: 40, lateral: 30 }, 2.0);
        let resultant: f64 = grid.pressure.iter().sum::<f64>() * grid.element_area();
        assert!((resultant - 4.0 * PI / 3.0).abs() < 1e-12);
        let peak = grid.pressure.iter().cloned().fold(0.0, f64::max);
        assert!((peak - 1.0).abs() < 0.02, "peak {peak}");
    }
}
