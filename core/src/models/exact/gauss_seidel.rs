//! The reference solver of the tangential problem (the test oracle of `tangential.rs`): the
//! non-linear block Gauss–Seidel method for steady rolling of Vollebregt's CONTACT ("SteadyGS":
//! Vollebregt 2014, "Numerical modeling of measured railway creep versus creep-force curves
//! with CONTACT", §2; Kalker 1990 §5.3). Written from the description, not from the source.
//!
//! Units: lengths in a, tractions in μp₀ (so the Coulomb bound of an element is its normalised
//! pressure g = p_n/p₀), slip in the creepage scale μp₀/G.
//!
//! Discretisation (Kalker 1990 §2.2; CONTACT's steady rolling): material flows through the
//! contact from the leading edge (+x) towards −x, one element δx per time step, so the slip of
//! element I is the rigid slip plus the change of the displacement difference since the
//! particle left element I + x̂ (a backward difference against the flow):
//!
//! ```text
//! s_I = w_I + (u_I − u_{I+x̂})/δx = w_I + Σ_J (A_IJ/δx) Δp_J,    Δp_J = p_J − p_{J+x̂},
//! ```
//!
//! with A Love's influence matrix (`influence.rs`) and p = 0 outside the contact, so Δp is
//! non-zero on the contact and on the element just behind each row's trailing edge. Written in
//! the traction *steps* Δp the operator is the symmetric positive definite A/δx; in the
//! tractions p themselves it would be A·D with the difference operator D, which is far from
//! diagonally dominant (a Gauss–Seidel sweep on p diverges on fine grids).
//!
//! Coulomb's law, per element: |p| ≤ g; s = 0 where |p| < g (adhesion); s = −|s| p/g (slip).
//!
//! One Gauss–Seidel step changes the traction of element I by δ while keeping the traction
//! steps Δp of the adhesion elements downstream (their tractions shift with it, as in the
//! adhered state the step is what the slip equation fixes) and the tractions of the first slip
//! or exterior element downstream, J. In Δp that is +δ at I and −δ at J, which changes s_I by
//! C δ with C = [A(0) − A(I − J)]/δx, diagonal and positive. The element's two equations are
//! then solved exactly for δ (`local_traction`). Adhesion elements downstream that the shift
//! pushes over their bound are clipped to it. Rows are swept from the trailing to the leading
//! edge. For a fixed adhesion area this is Gauss–Seidel on a symmetric positive definite system
//! in the directions e_I − e_J, which converges.
//!
//! Cost: each step evaluates s_I afresh by direct summation over all traction steps, O(N) for
//! N contact elements, so O(N²) per sweep. FFT convolution does not fit Gauss–Seidel: each step
//! needs the newest field at one element, which an FFT cannot give cheaper than this O(N)
//! sum. The sum runs over contiguous row segments of a precomputed table and vectorises.
//! Adhesion steps are under-relaxed (`ADHESION_RELAXATION`), which saves up to half the sweeps.
//! Tried without gain: starting from the solution on the half grid (the sweeps after the first
//! few are spent on slowly decaying smooth error, which a better start does not remove).

use super::element::local_traction;
use super::grid::ContactGrid;
use super::influence::InfluenceTable;
use super::tangential::TangentialSolution;
use super::ElementState;

/// Safety limit on the number of sweeps.
const MAX_SWEEPS: usize = 20_000;
/// Relaxation factor of the adhesion steps. The plain step overshoots (each step also shifts
/// the element's adhesion row downstream, and the neighbours' corrections add up);
/// under-relaxation damps that. Measured sweeps to the
/// tolerance on 44 × 44 / 80 × 80 with 1 (plain Gauss–Seidel) → 0.6: pure ξ in partial slip
/// 53 → 36 / 78 → 43, full adhesion 61 → 33 / 89 → 48, η with spin 67 → 60 / 104 → 100;
/// factors above 1 (over-relaxation) raise the count, 0.5 is no better than 0.6. The fixed
/// point, and so the solution, is the same.
const ADHESION_RELAXATION: f64 = 0.6;

/// Solves the steady-rolling problem on `grid` for the rigid slip `rigid_slip_x/y` (units of
/// the creepage scale, one value per element, row-major). Sweeps stop when no traction
/// changed by more than `relative_tolerance` × the largest traction.
pub(crate) fn solve(
    grid: &ContactGrid,
    table: &InfluenceTable,
    rigid_slip_x: &[f64],
    rigid_slip_y: &[f64],
    relative_tolerance: f64,
) -> TangentialSolution {
    let count = grid.elements_x * grid.elements_y;
    let steps = (grid.elements_x + 1) * grid.elements_y;
    let mut solver = Solver {
        grid,
        table,
        rigid_slip_x,
        rigid_slip_y,
        traction_x: vec![0.0; count],
        traction_y: vec![0.0; count],
        step_x: vec![0.0; steps],
        step_y: vec![0.0; steps],
        state: grid
            .pressure
            .iter()
            .map(|&p| if p > 0.0 { ElementState::Adhesion } else { ElementState::Exterior })
            .collect(),
    };
    let mut sweeps = 0;
    let mut converged = false;
    while sweeps < MAX_SWEEPS && !converged {
        sweeps += 1;
        let previous_x = solver.traction_x.clone();
        let previous_y = solver.traction_y.clone();
        for (j, row) in grid.rows_in_contact.iter().enumerate() {
            let Some((first, last)) = *row else { continue };
            // Trailing to leading edge: the other orders (tried: reversed, alternating) fail to
            // converge in partial slip.
            for i in first..=last {
                solver.relax(i, j, first);
            }
        }
        let mut largest_change: f64 = 0.0;
        let mut largest_traction: f64 = 0.0;
        for element in 0..count {
            let (p_x, p_y) = (solver.traction_x[element], solver.traction_y[element]);
            largest_change = largest_change.max((p_x - previous_x[element]).hypot(p_y - previous_y[element]));
            largest_traction = largest_traction.max(p_x.hypot(p_y));
        }
        converged = largest_change <= relative_tolerance * largest_traction;
    }
    TangentialSolution {
        traction_x: solver.traction_x,
        traction_y: solver.traction_y,
        state: solver.state,
        iterations: sweeps,
        // Direct sums, not FFT products.
        products: 0,
        converged,
    }
}

struct Solver<'a> {
    grid: &'a ContactGrid,
    table: &'a InfluenceTable,
    rigid_slip_x: &'a [f64],
    rigid_slip_y: &'a [f64],
    /// Tractions p per element, index i + j·nx.
    traction_x: Vec<f64>,
    traction_y: Vec<f64>,
    /// Traction steps Δp = p_I − p_{I+x̂}, index (i + 1) + j·(nx + 1): column 0 is the element
    /// i = −1, behind a row that reaches the edge of the grid.
    step_x: Vec<f64>,
    step_y: Vec<f64>,
    state: Vec<ElementState>,
}

impl Solver<'_> {
    /// One Gauss–Seidel step at element (i, j) of a row whose trailing contact element is `first`.
    fn relax(&mut self, i: usize, j: usize, first: usize) {
        let nx = self.grid.elements_x;
        let element = i + j * nx;
        // The first slip or exterior element downstream absorbs the change of Δp.
        let absorber = (first..i).rev().find(|&k| self.state[k + j * nx] == ElementState::Slip);
        let distance = i as isize - absorber.map_or(first as isize - 1, |k| k as isize);
        let response = self.table.step_response(distance);
        let (s_x, s_y) = self.slip(i, j);
        let residual = (s_x - response.0 * self.traction_x[element], s_y - response.1 * self.traction_y[element]);
        let bound = self.grid.pressure[element];
        let (mut traction, slips) = local_traction(residual, response, bound);
        if !slips {
            // Under-relaxed adhesion step, clipped to the bound (see `ADHESION_RELAXATION`).
            let old = (self.traction_x[element], self.traction_y[element]);
            traction = (
                old.0 + ADHESION_RELAXATION * (traction.0 - old.0),
                old.1 + ADHESION_RELAXATION * (traction.1 - old.1),
            );
            let magnitude = traction.0.hypot(traction.1);
            if magnitude > bound {
                traction = (traction.0 * bound / magnitude, traction.1 * bound / magnitude);
            }
        }
        self.traction_x[element] = traction.0;
        self.traction_y[element] = traction.1;
        self.state[element] = if slips { ElementState::Slip } else { ElementState::Adhesion };
        self.restore_steps(i, j, first);
    }

    /// Slip s_I = w_I + Σ_J (A_IJ/δx) Δp_J by direct summation over the non-zero steps.
    fn slip(&self, i: usize, j: usize) -> (f64, f64) {
        let nx = self.grid.elements_x;
        let element = i + j * nx;
        let (mut s_x, mut s_y) = (self.rigid_slip_x[element], self.rigid_slip_y[element]);
        for (row_j, row) in self.grid.rows_in_contact.iter().enumerate() {
            let Some((first, last)) = *row else { continue };
            // Sources i' = first − 1 … last; step column i' + 1.
            let len = last - first + 2;
            let k = self.table.index(first as isize - 1 - i as isize, row_j as isize - j as isize);
            let s = first + row_j * (nx + 1);
            let (row_x, row_y) = row_slip(
                [&self.table.xx[k..k + len], &self.table.xy[k..k + len], &self.table.yy[k..k + len]],
                [&self.step_x[s..s + len], &self.step_y[s..s + len]],
            );
            s_x += row_x;
            s_y += row_y;
        }
        (s_x, s_y)
    }

    /// Re-establishes Δp along row j from element `i` down to the trailing edge: adhesion
    /// elements keep their step (their traction follows the one upstream, clipped to the
    /// bound), slip elements keep their traction.
    fn restore_steps(&mut self, i: usize, j: usize, first: usize) {
        let nx = self.grid.elements_x;
        let upstream = |solver: &Self, k: usize| {
            if k + 1 < nx {
                (solver.traction_x[k + 1 + j * nx], solver.traction_y[k + 1 + j * nx])
            } else {
                (0.0, 0.0)
            }
        };
        for k in (first..=i).rev() {
            let element = k + j * nx;
            let step = k + 1 + j * (nx + 1);
            let (up_x, up_y) = upstream(self, k);
            if k < i && self.state[element] == ElementState::Adhesion {
                let (mut p_x, mut p_y) = (up_x + self.step_x[step], up_y + self.step_y[step]);
                let (magnitude, bound) = (p_x.hypot(p_y), self.grid.pressure[element]);
                if magnitude > bound {
                    p_x *= bound / magnitude;
                    p_y *= bound / magnitude;
                }
                self.traction_x[element] = p_x;
                self.traction_y[element] = p_y;
            }
            self.step_x[step] = self.traction_x[element] - up_x;
            self.step_y[step] = self.traction_y[element] - up_y;
        }
        // The element behind the trailing edge carries no traction: its step is −p_first.
        let trailing = first + j * (nx + 1);
        self.step_x[trailing] = -self.traction_x[first + j * nx];
        self.step_y[trailing] = -self.traction_y[first + j * nx];
    }
}

/// Independent partial sums in [`row_slip`]: a single chain of dependent additions would make
/// the sum latency-bound; four lanes let the compiler vectorise it.
const LANES: usize = 4;

/// One row segment's share of the slip: Σ_k (xx_k Δp_x,k + xy_k Δp_y,k, xy_k Δp_x,k + yy_k Δp_y,k)
/// for `influence` = [xx, xy, yy] and `steps` = [Δp_x, Δp_y], all of one length.
fn row_slip([xx, xy, yy]: [&[f64]; 3], [dp_x, dp_y]: [&[f64]; 2]) -> (f64, f64) {
    let (mut lanes_x, mut lanes_y) = ([0.0; LANES], [0.0; LANES]);
    let chunks = <[f64]>::chunks_exact;
    let influence = chunks(xx, LANES).zip(chunks(xy, LANES)).zip(chunks(yy, LANES));
    for (((xx, xy), yy), (dx, dy)) in influence.zip(chunks(dp_x, LANES).zip(chunks(dp_y, LANES))) {
        for lane in 0..LANES {
            lanes_x[lane] += xx[lane] * dx[lane] + xy[lane] * dy[lane];
            lanes_y[lane] += xy[lane] * dx[lane] + yy[lane] * dy[lane];
        }
    }
    let (mut s_x, mut s_y) = (lanes_x.iter().sum::<f64>(), lanes_y.iter().sum::<f64>());
    for k in xx.len() - xx.len() % LANES..xx.len() {
        s_x += xx[k] * dp_x[k] + xy[k] * dp_y[k];
        s_y += xy[k] * dp_x[k] + yy[k] * dp_y[k];
    }
    (s_x, s_y)
}
