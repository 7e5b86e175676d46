//! The steady-rolling influence operator as an FFT convolution, and its circulant inverse.
//!
//! The slip of every element is a discrete convolution of the traction steps with Love's
//! coefficients (`influence.rs`): s_I = Σ_J T(J − I) Δp_J with T = A/δx, the same sum the
//! Gauss–Seidel reference evaluates element by element. On a zero-padded grid of Mx × My
//! points with Mx ≥ 2 nx + 1 and My ≥ 2 ny − 1 the circular convolution equals the linear one for
//! every element (no wrap-around), so one product costs four 2-D real FFTs, O(N log N),
//! instead of the O(N²) direct sum, with the same result to rounding.
//!
//! The same padded grid carries a preconditioner: the inverse of the 2 × 2 symbol of T
//! (T placed evenly on the periodic grid, so its symbol is real), which maps a
//! slip field to the traction steps that would cancel it if the contact filled the plane.
//! Restricted to the contact it is an approximate inverse (Strang's circulant preconditioner
//! for Toeplitz systems, as in Vollebregt's FFT-preconditioned normal solver, J. Optim. Theory
//! Appl. 162, 2014).

use std::cell::RefCell;
use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use super::influence::InfluenceTable;

thread_local! {
    /// FFT planners kept per thread: they cache their plans, so solves on grids of sizes met
    /// before skip the planning.
    static PLANNERS: RefCell<(RealFftPlanner<f64>, FftPlanner<f64>)> =
        RefCell::new((RealFftPlanner::new(), FftPlanner::new()));
}

/// The operator on a grid of nx × ny elements, with its FFT plans and work space.
pub(crate) struct SlipConvolution {
    elements_x: usize,
    elements_y: usize,
    /// Padded sizes.
    size_x: usize,
    size_y: usize,
    /// Spectrum length along x (real FFT): Mx/2 + 1.
    half_x: usize,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
    /// Symbols (real spectra) of T (xx, xy, yy), scaled by 1/(Mx My) for the unnormalised
    /// inverse transform. Layout column-major over the spectrum: index y + h·My.
    kernel: [Vec<f64>; 3],
    /// The preconditioner's 2 × 2 inverse symbol (xx, xy, yy), same layout and scaling.
    inverse: [Vec<f64>; 3],
    spectra: [Vec<Complex<f64>>; 2],
    row: Vec<f64>,
    row_spectrum: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

/// Smallest even n ≥ `minimum` whose prime factors are 2, 3 and 5 (fast FFT lengths; real
/// transforms of even length take half a complex transform, of odd length a whole one).
fn fast_length(minimum: usize) -> usize {
    (minimum.max(2)..)
        .find(|&n| {
            n % 2 == 0 && {
                let mut m = n;
                for factor in [2, 3, 5] {
                    while m % factor == 0 {
                        m /= factor;
                    }
                }
                m == 1
            }
        })
        .expect("an FFT-friendly length exists above any bound")
}

impl SlipConvolution {
    pub(crate) fn new(table: &InfluenceTable) -> Self {
        let (nx, ny) = (table.elements_x, table.elements_y);
        // One more than the wrap-free minimum 2 nx along x, so the kernel can be placed evenly.
        let size_x = fast_length(2 * nx + 1);
        let size_y = fast_length(2 * ny - 1);
        let half_x = size_x / 2 + 1;
        let (row_forward, row_inverse, column_forward, column_inverse) = PLANNERS.with_borrow_mut(|(real, complex)| {
            (
                real.plan_fft_forward(size_x),
                real.plan_fft_inverse(size_x),
                complex.plan_fft_forward(size_y),
                complex.plan_fft_inverse(size_y),
            )
        });
        let scratch_length = [
            row_forward.get_scratch_len(),
            row_inverse.get_scratch_len(),
            column_forward.get_inplace_scratch_len(),
            column_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        let spectrum = || vec![Complex::new(0.0, 0.0); half_x * size_y];
        let real = || vec![0.0; half_x * size_y];
        let mut convolution = Self {
            elements_x: nx,
            elements_y: ny,
            size_x,
            size_y,
            half_x,
            row_forward,
            row_inverse,
            column_forward,
            column_inverse,
            kernel: Default::default(),
            inverse: [real(), real(), real()],
            spectra: [spectrum(), spectrum()],
            row: vec![0.0; size_x],
            row_spectrum: vec![Complex::new(0.0, 0.0); half_x],
            scratch: vec![Complex::new(0.0, 0.0); scratch_length],
        };
        let normalisation = 1.0 / (size_x * size_y) as f64;
        let (nx, ny) = (nx as isize, ny as isize);
        let wrap = |offset: isize, size: usize| offset.rem_euclid(size as isize) as usize;
        // The product needs offsets −(nx−1) … nx along x (target minus source, the source grid
        // starting one element behind) and −(ny−1) … ny−1 along y. The kernel is placed at
        // −nx … nx (the extra offset −nx meets no pair of target and source): T is even under
        // point reflection, so the placed kernel is even and its symbol real. The same symbol,
        // inverted, is the preconditioner's.
        let mut field = vec![0.0; size_x * size_y];
        let mut symbols = Vec::new();
        for values in [&table.xx, &table.xy, &table.yy] {
            field.iter_mut().for_each(|v| *v = 0.0);
            for dy in -(ny - 1)..ny {
                for dx in -nx..=nx {
                    field[wrap(dx, size_x) + wrap(dy, size_y) * size_x] = values[table.index(dx, dy)];
                }
            }
            convolution.forward(&field, 0);
            symbols.push(convolution.spectra[0].iter().map(|c| c.re).collect::<Vec<f64>>());
        }
        for (kernel, symbol) in convolution.kernel.iter_mut().zip(&symbols) {
            *kernel = symbol.iter().map(|value| value * normalisation).collect();
        }
        // The 2 × 2 symbol is inverted per frequency. Love's kernel is positive definite, but
        // truncation can leave a few symbols near zero or negative: those frequencies are
        // floored at a small fraction of the largest eigenvalue, so the preconditioner stays
        // bounded and positive.
        let largest = symbols[0].iter().chain(&symbols[2]).map(|value| value.abs()).fold(0.0, f64::max);
        let floor = 1e-3 * largest;
        let [inverse_xx, inverse_xy, inverse_yy] = &mut convolution.inverse;
        let symbol_matrices = symbols[0].iter().zip(&symbols[1]).zip(&symbols[2]);
        for (k, ((xx, xy), yy)) in symbol_matrices.enumerate() {
            let (xx, xy, yy) = (*xx, *xy, *yy);
            // Eigen-decomposition of the symmetric 2 × 2 symbol, eigenvalues floored.
            let mean = 0.5 * (xx + yy);
            let radius = (0.25 * (xx - yy) * (xx - yy) + xy * xy).sqrt();
            let (large, small) = ((mean + radius).max(floor), (mean - radius).max(floor));
            let angle = 0.5 * (2.0 * xy).atan2(xx - yy);
            let (c, s) = (angle.cos(), angle.sin());
            let (inv_large, inv_small) = (normalisation / large, normalisation / small);
            inverse_xx[k] = c * c * inv_large + s * s * inv_small;
            inverse_xy[k] = c * s * (inv_large - inv_small);
            inverse_yy[k] = s * s * inv_large + c * c * inv_small;
        }
        convolution
    }

    /// Slip increments on the nx × ny elements from traction steps on (nx + 1) × ny elements
    /// (column 0 is the element i = −1): out_I = Σ_J T(J − I) Δp_J.
    pub(crate) fn apply(&mut self, steps: [&[f64]; 2], out: [&mut [f64]; 2]) {
        let (nx, ny) = (self.elements_x, self.elements_y);
        self.transform_input(steps, nx + 1);
        let kernel = std::mem::take(&mut self.kernel);
        self.multiply(&kernel);
        self.kernel = kernel;
        // The source grid starts one element behind the target grid: target i is index i + 1.
        self.transform_output(out, 1, nx, ny);
    }

    /// The preconditioner: traction steps on the nx × ny elements that would cancel the slip
    /// field `slip` (nx × ny) in an unbounded contact.
    pub(crate) fn apply_inverse(&mut self, slip: [&[f64]; 2], out: [&mut [f64]; 2]) {
        let (nx, ny) = (self.elements_x, self.elements_y);
        self.transform_input(slip, nx);
        let inverse = std::mem::take(&mut self.inverse);
        self.multiply(&inverse);
        self.inverse = inverse;
        self.transform_output(out, 0, nx, ny);
    }

    /// Both components of a field with rows of `width` values (ny rows) into `spectra`.
    fn transform_input(&mut self, field: [&[f64]; 2], width: usize) {
        let mut padded = std::mem::take(&mut self.row);
        for (component, values) in field.into_iter().enumerate() {
            for column in self.spectra[component].iter_mut() {
                *column = Complex::new(0.0, 0.0);
            }
            for j in 0..self.elements_y {
                padded.iter_mut().for_each(|v| *v = 0.0);
                padded[..width].copy_from_slice(&values[j * width..(j + 1) * width]);
                self.row_forward
                    .process_with_scratch(&mut padded, &mut self.row_spectrum, &mut self.scratch)
                    .expect("buffer lengths come from the plan");
                for (h, &value) in self.row_spectrum.iter().enumerate() {
                    self.spectra[component][j + h * self.size_y] = value;
                }
            }
            self.column_forward.process_with_scratch(&mut self.spectra[component], &mut self.scratch);
        }
        self.row = padded;
    }

    /// Forward transform of one padded real field (Mx × My, row-major) into `spectra[slot]`.
    fn forward(&mut self, field: &[f64], slot: usize) {
        let mut row = std::mem::take(&mut self.row);
        for j in 0..self.size_y {
            row.copy_from_slice(&field[j * self.size_x..(j + 1) * self.size_x]);
            self.row_forward
                .process_with_scratch(&mut row, &mut self.row_spectrum, &mut self.scratch)
                .expect("buffer lengths come from the plan");
            for (h, &value) in self.row_spectrum.iter().enumerate() {
                self.spectra[slot][j + h * self.size_y] = value;
            }
        }
        self.column_forward.process_with_scratch(&mut self.spectra[slot], &mut self.scratch);
        self.row = row;
    }

    /// spectra ← [[k_xx, k_xy], [k_xy, k_yy]] · spectra, per frequency.
    fn multiply(&mut self, [xx, xy, yy]: &[Vec<f64>; 3]) {
        let [first, second] = &mut self.spectra;
        for k in 0..first.len() {
            let (u, v) = (first[k], second[k]);
            first[k] = xx[k] * u + xy[k] * v;
            second[k] = xy[k] * u + yy[k] * v;
        }
    }

    /// Inverse transform of both spectra, keeping nx columns from `offset` on the first ny rows.
    fn transform_output(&mut self, out: [&mut [f64]; 2], offset: usize, nx: usize, ny: usize) {
        let mut row = std::mem::take(&mut self.row);
        for (component, values) in out.into_iter().enumerate() {
            self.column_inverse.process_with_scratch(&mut self.spectra[component], &mut self.scratch);
            for j in 0..ny {
                for (h, value) in self.row_spectrum.iter_mut().enumerate() {
                    *value = self.spectra[component][j + h * self.size_y];
                }
                // The field is real: the first (and, for even Mx, last) coefficients are real
                // up to rounding, which the real inverse transform requires exactly.
                self.row_spectrum[0].im = 0.0;
                if self.size_x % 2 == 0 {
                    self.row_spectrum[self.half_x - 1].im = 0.0;
                }
                self.row_inverse
                    .process_with_scratch(&mut self.row_spectrum, &mut row, &mut self.scratch)
                    .expect("buffer lengths come from the plan");
                values[j * nx..(j + 1) * nx].copy_from_slice(&row[offset..offset + nx]);
            }
        }
        self.row = row;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FFT product equals the direct sum over the table, element by element.
    #[test]
    fn product_equals_the_direct_sum() {
        let (nx, ny) = (7, 5);
        let table = InfluenceTable::new(nx, ny, 0.3, 0.2, 0.28);
        let mut convolution = SlipConvolution::new(&table);
        let steps_x: Vec<f64> = (0..(nx + 1) * ny).map(|k| ((k * 37 % 11) as f64 - 5.0) * 0.1).collect();
        let steps_y: Vec<f64> = (0..(nx + 1) * ny).map(|k| ((k * 17 % 13) as f64 - 6.0) * 0.07).collect();
        let (mut out_x, mut out_y) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        convolution.apply([&steps_x, &steps_y], [&mut out_x, &mut out_y]);
        for j in 0..ny {
            for i in 0..nx {
                let (mut sx, mut sy) = (0.0, 0.0);
                for jj in 0..ny {
                    for ii in 0..=nx {
                        // Step column ii is the element i' = ii − 1.
                        let k = table.index(ii as isize - 1 - i as isize, jj as isize - j as isize);
                        let (qx, qy) = (steps_x[ii + jj * (nx + 1)], steps_y[ii + jj * (nx + 1)]);
                        sx += table.xx[k] * qx + table.xy[k] * qy;
                        sy += table.xy[k] * qx + table.yy[k] * qy;
                    }
                }
                assert!((out_x[i + j * nx] - sx).abs() < 1e-12, "({i}, {j}): {} vs {sx}", out_x[i + j * nx]);
                assert!((out_y[i + j * nx] - sy).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn fast_lengths() {
        assert_eq!(fast_length(7), 8);
        assert_eq!(fast_length(81), 90);
        assert_eq!(fast_length(161), 162);
        assert_eq!(fast_length(401), 432);
    }
}
