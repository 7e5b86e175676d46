//! The tangential problem of steady rolling with Coulomb friction, solved by an active-set
//! Newton method whose linear steps are solved by GMRES with FFT products: O(N log N) per
//! iteration for N elements.
//!
//! Units: lengths in a, tractions in μp₀ (so the Coulomb bound of an element is its normalised
//! pressure g = p_n/p₀), slip in the creepage scale μp₀/G.
//!
//! Discretisation (Kalker 1990 §2.2; CONTACT's steady rolling), the same as the Gauss–Seidel
//! reference (`gauss_seidel.rs`): material flows from the leading edge (+x) towards −x, one
//! element δx per time step, and the slip of element I is
//!
//! ```text
//! s_I = w_I + Σ_J (A_IJ/δx) Δp_J,    Δp_J = p_J − p_{J+x̂}   (p = 0 outside the contact),
//! ```
//!
//! evaluated for all elements at once as an FFT convolution (`convolution.rs`). Coulomb's law:
//! |p_I| ≤ g_I; s_I = 0 where |p_I| < g_I (adhesion); s_I = −|s_I| p_I/g_I (slip).
//!
//! Method (the classical active-set treatment of Kalker's KOMBI and CONTACT's outer loops,
//! with a Newton step for the slip directions): for the current division into adhesion and
//! slip, the unknowns are both traction components of an adhesion element and the direction
//! θ of the traction g (cos θ, sin θ) of a slip element; the equations are s = 0 in adhesion
//! and n·s = 0 in slip (n ⊥ p: slip parallel to the traction). Linearised, the slip equation
//! gains the term |s| δθ from the turning of n (∂n/∂θ = −t, −t·s = |s|), which makes it
//! better conditioned the faster the element slips. Each linear step is solved by restarted,
//! right-preconditioned GMRES (Saad & Schultz 1986; Saad 1993 for the flexible variant that
//! keeps the preconditioned vectors). After each step, adhesion elements pushed over their
//! bound are projected onto it and start slipping; before the next, slip elements whose slip
//! is not nearly opposite to their traction are solved locally again (`Newton::release`):
//! those whose slip has turned along their traction return to adhesion.
//!
//! Preconditioner: the steady-rolling operator is the product of the symmetric positive
//! definite influence operator A/δx and the difference Δ along the rolling direction, a
//! transport operator whose symbol (∼ i k_x/|k|) puts eigenvalues along the imaginary axis,
//! where Krylov methods stall. Its approximate inverse is the FFT-circulant inverse of A/δx
//! (`SlipConvolution::apply_inverse`) followed by the exact inverse of the difference: a
//! change of an element's traction carried downstream through the adhesion elements of its
//! row up to the first slip element, as in the Gauss–Seidel step of the reference solver.
//! Slip elements blend the two: slow slip (turning coefficient c ≪ self influence k) turns
//! like an adhesion element constrained to the normal direction (carried and circulant part),
//! fast slip is dominated by its own turning term (local inverse), weights k : c. The slip
//! rows are scaled by 1/(k + c), so every residual is in units of traction and fast slip at
//! extreme creepage does not dominate GMRES's norm. Measured products on 80 × 80 (CONTACT's
//! spin case): 511 with the local inverse alone, 165 blended.
//!
//! Start: a warm start, or the solution on a grid with half as many elements along one or both
//! axes (`ExactTheory::solve_from`; a cold solve races a warm start that does not converge
//! soon, [`solve_warm_or_cold`]): the Newton solver moves the boundary between adhesion and slip by about one
//! element layer per step, so a start with the right division saves most steps (spin case on
//! 80 × 80: 21 → 8).
//!
//! Bounded cost: at most [`MAX_ITERATIONS`] Newton steps and [`MAX_PRODUCTS`] operator products
//! per solve; a solve that hits either limit returns its last iterate with `converged = false`.

use super::convolution::SlipConvolution;
use super::element::local_traction;
use super::grid::ContactGrid;
use super::influence::InfluenceTable;
use super::ElementState;
use crate::InvalidInput;

/// Target accuracy of the tractions, relative to the largest. The iteration stops after an
/// accurately solved Newton step (to [`SETTLED_TOLERANCE`]) that changed no element's state and
/// no traction by more than [`RELATIVE_TOLERANCE`] / [`SETTLED_TOLERANCE`] × the largest
/// traction, if the slip then releases no element: the error left after such a step is about
/// the step times the linear tolerance. (1e-7 rather than tighter: forces to ≈ 1e-7 μQ, and a
/// warm-started step of a co-simulation needs one accurate linear solve instead of two; on
/// 40 × 40, 30 instead of 43 products per step.)
pub(crate) const RELATIVE_TOLERANCE: f64 = 1e-7;
/// Most Newton steps per solve (the tested cases take 4–15, the extremes of the tests up to 35).
pub const MAX_ITERATIONS: usize = 200;
/// Newton steps solved to [`UNSETTLED_TOLERANCE`] at most; every later step is solved to
/// [`SETTLED_TOLERANCE`] (`Newton::run`). Above the 4–15 steps the tested and benchmarked
/// cases converge in, so it changes none of them.
pub(crate) const LOOSE_STEPS: usize = 16;
/// Most operator products (FFT convolutions) per solve, summed over all linear steps.
pub const MAX_PRODUCTS: usize = 4000;
/// Slip elements whose slip direction is further than arccos(0.9) ≈ 26° from opposite to their
/// traction are re-solved locally before a Newton step (see `Newton::release`). Needed at
/// extreme creepage, where a loosely solved first step leaves slip directions far off; at the
/// solution every slip element has the cosine 1 exactly.
const RESOLVE_ALIGNMENT: f64 = 0.9;
/// GMRES restart length: Krylov vectors kept (twice: plain and preconditioned).
const RESTART: usize = 30;
/// Relative residual to which a linear step is solved while the division into adhesion and
/// slip still changes, and once it has settled. Measured products to convergence on 40 × 40
/// with the first preconditioner (adhesion, ξ partial slip, CONTACT's spin case, a/b = 10):
/// 47, 117, 323, 150 with (0.1, 1e-4); (0.3, 1e-4): 57, 106, 348, 164; (0.1, 1e-6): 62, 154,
/// 430, 200; a fixed 1e-3: 53, 205, 563, 277.
const UNSETTLED_TOLERANCE: f64 = 0.1;
const SETTLED_TOLERANCE: f64 = 1e-4;
/// Operator products a warm start spends alone before a cold solve races it
/// ([`ExactTheory::solve_from`](super::ExactTheory::solve_from)): about a cold solve's (on
/// 200 × 50, 31–75 products for random contacts, a/b 0.06–16), so that the warm attempt and the
/// race after it stay within about twice a cold solve. A step of a slowly varying
/// co-simulation converges within it (on 200 × 50, 27–46 products with the creepages changing
/// by 0.1–0.3 % per step), so it never pays for the race; with changes of 0.5–1.5 % per step
/// warm solves take 33–78 products, and the race costs 4 % more over 40 such steps (2085
/// products against 1999 without a race; cold solves 2320).
pub const WARM_ALONE_PRODUCTS: usize = 50;

/// Tractions (units μp₀) and element states, row-major (index i + j·nx).
pub(crate) struct TangentialSolution {
    pub traction_x: Vec<f64>,
    pub traction_y: Vec<f64>,
    pub state: Vec<ElementState>,
    pub iterations: usize,
    pub products: usize,
    pub converged: bool,
}

/// Solves the steady-rolling problem on `grid` for the rigid slip `rigid_slip` (units of the
/// creepage scale, one value per element, row-major), starting from `start` (tractions in
/// units of μp₀ on the same grid; clipped to the bound) or from zero.
pub(crate) fn solve(
    grid: &ContactGrid,
    table: &InfluenceTable,
    rigid_slip: [&[f64]; 2],
    start: Option<[&[f64]; 2]>,
) -> TangentialSolution {
    let mut work = Workspace::new(table);
    let mut solver = Newton::new(grid, table, rigid_slip, start);
    let converged = solver.run(&mut work);
    solver.into_solution(converged, (0, 0))
}

/// [`solve`] from a warm start `warm` with the cost of a step bounded by a cold solve's: the
/// warm start's iteration runs alone for [`WARM_ALONE_PRODUCTS`] operator products; if it has
/// not converged by then, the cold solve (from `cold_start`, the nested start, computed only then)
/// races it, the iteration that has used fewer operator products taking the next Newton step,
/// until either converges. The counts are both iterations'.
///
/// Why a race: a start far from the solution (a contact that jumped between steps) can leave
/// the Newton iteration cycling between adhesion and slip for hundreds of steps (200 × 50,
/// full slip → ξ = 1e-7: 203 steps, 3434 products, 3.5 s where a cold solve takes 36 products),
/// while a start that converges slowly is not cycling (320 × 400 from the 160 × 200 solution:
/// 40 steps, see `LOOSE_STEPS`); no test on the first steps tells them apart, and the cold
/// solve's cost is unknown until it is done. Racing bounds the step by twice the cost of the
/// cheaper of the two plus the one Newton step either may be ahead, or the warm start's
/// products alone and a cold solve: products ≤ max(2·cold + one warm step,
/// [`WARM_ALONE_PRODUCTS`] + cold) and ≤ max(2·warm + one cold step, warm).
pub(crate) fn solve_warm_or_cold(
    grid: &ContactGrid,
    table: &InfluenceTable,
    rigid_slip: [&[f64]; 2],
    warm: [&[f64]; 2],
    cold_start: impl FnOnce() -> Result<Option<[Vec<f64>; 2]>, InvalidInput>,
) -> Result<TangentialSolution, InvalidInput> {
    let mut work = Workspace::new(table);
    let mut warm = Newton::new(grid, table, rigid_slip, Some(warm));
    let mut warm_finished = warm.check(&mut work);
    while warm_finished.is_none() && warm.products < WARM_ALONE_PRODUCTS {
        warm.advance(&mut work);
        warm_finished = warm.check(&mut work);
    }
    if warm_finished == Some(true) {
        return Ok(warm.into_solution(true, (0, 0)));
    }
    let cold_start = cold_start()?;
    let mut cold = Newton::new(grid, table, rigid_slip, cold_start.as_ref().map(|[x, y]| [x.as_slice(), y.as_slice()]));
    let mut cold_finished = cold.check(&mut work);
    loop {
        match (warm_finished, cold_finished) {
            (Some(true), _) => {
                let other = (cold.iterations, cold.products);
                return Ok(warm.into_solution(true, other));
            }
            (_, Some(converged)) if converged || warm_finished.is_some() => {
                // Both at their limits: the cold iterate, as a solve without a start gives.
                let other = (warm.iterations, warm.products);
                return Ok(cold.into_solution(converged, other));
            }
            _ => {}
        }
        // Ties go to the cold solve: its cost is the bound.
        if cold_finished.is_some() || (warm_finished.is_none() && warm.products < cold.products) {
            warm.advance(&mut work);
            warm_finished = warm.check(&mut work);
        } else {
            cold.advance(&mut work);
            cold_finished = cold.check(&mut work);
        }
    }
}

/// Vectors of the linear steps: x components in the first half, y components in the second.
type Field = Vec<f64>;

/// What the Newton iterations on one grid share: the FFT convolution and GMRES's Krylov vectors
/// (kept between solves: allocating them anew each iteration costs page faults on large grids).
struct Workspace {
    convolution: SlipConvolution,
    krylov_basis: Vec<Field>,
    krylov_preconditioned: Vec<Field>,
}

impl Workspace {
    fn new(table: &InfluenceTable) -> Self {
        Self { convolution: SlipConvolution::new(table), krylov_basis: Vec::new(), krylov_preconditioned: Vec::new() }
    }
}

struct Newton<'a> {
    grid: &'a ContactGrid,
    rigid_slip: [&'a [f64]; 2],
    count: usize,
    traction: [Vec<f64>; 2],
    state: Vec<ElementState>,
    slip: [Vec<f64>; 2],
    /// Per slip element: the unit traction direction t and the slip speed over the bound,
    /// |s|/g (the coefficient of the turning term).
    direction: Vec<(f64, f64)>,
    turning: Vec<f64>,
    /// Self-influence of a unit traction step: with the turning term, the diagonal of a slip
    /// element's equation, which the preconditioner inverts locally.
    self_influence: f64,
    /// Slip response of an element to its own traction alone (diagonal, x and y).
    own_response: (f64, f64),
    steps: [Vec<f64>; 2],
    product: [Vec<f64>; 2],
    unscaled: [Vec<f64>; 2],
    right_side: Field,
    iterations: usize,
    products: usize,
    /// The last step was accurate and changed nothing: converged if the slip releases nothing.
    converging: bool,
    /// The last step changed no element's state.
    settled: bool,
    /// The last check released elements.
    released: bool,
}

impl<'a> Newton<'a> {
    fn new(
        grid: &'a ContactGrid,
        table: &InfluenceTable,
        rigid_slip: [&'a [f64]; 2],
        start: Option<[&[f64]; 2]>,
    ) -> Self {
        let count = grid.elements_x * grid.elements_y;
        let steps = (grid.elements_x + 1) * grid.elements_y;
        let centre = table.index(0, 0);
        let mut solver = Self {
            grid,
            rigid_slip,
            count,
            traction: [vec![0.0; count], vec![0.0; count]],
            state: vec![ElementState::Exterior; count],
            slip: [vec![0.0; count], vec![0.0; count]],
            direction: vec![(0.0, 0.0); count],
            turning: vec![0.0; count],
            self_influence: 0.5 * (table.xx[centre] + table.yy[centre]),
            own_response: table.step_response(1),
            steps: [vec![0.0; steps], vec![0.0; steps]],
            product: [vec![0.0; count], vec![0.0; count]],
            unscaled: [vec![0.0; count], vec![0.0; count]],
            right_side: vec![0.0; 2 * count],
            iterations: 0,
            products: 0,
            converging: false,
            settled: false,
            released: false,
        };
        for element in 0..count {
            let bound = grid.pressure[element];
            if bound <= 0.0 {
                continue;
            }
            solver.state[element] = ElementState::Adhesion;
            if let Some([start_x, start_y]) = start {
                let (p_x, p_y) = (start_x[element], start_y[element]);
                let magnitude = p_x.hypot(p_y);
                if magnitude.is_finite() {
                    solver.traction[0][element] = p_x;
                    solver.traction[1][element] = p_y;
                    // A start on the bound, up to the rounding of its units, slips.
                    if magnitude >= bound * (1.0 - 1e-9) {
                        solver.project_onto_bound(element);
                    }
                }
            }
        }
        solver
    }

    /// Puts element `element`'s traction on its bound (same direction) and marks it slipping.
    fn project_onto_bound(&mut self, element: usize) {
        let (p_x, p_y) = (self.traction[0][element], self.traction[1][element]);
        let scale = self.grid.pressure[element] / p_x.hypot(p_y);
        self.traction[0][element] = p_x * scale;
        self.traction[1][element] = p_y * scale;
        self.state[element] = ElementState::Slip;
    }

    /// Newton iteration; returns whether it converged.
    fn run(&mut self, work: &mut Workspace) -> bool {
        loop {
            if let Some(converged) = self.check(work) {
                return converged;
            }
            self.advance(work);
        }
    }

    /// The slip of the current iterate, released slip elements, and the stopping test:
    /// `Some(converged)` when the iteration is finished (converged, or at its limits).
    fn check(&mut self, work: &mut Workspace) -> Option<bool> {
        self.evaluate_slip(&mut work.convolution);
        self.released = self.release();
        if self.released {
            self.evaluate_slip(&mut work.convolution);
        }
        self.linearise();
        if self.converging && !self.released {
            return Some(true);
        }
        if self.iterations == MAX_ITERATIONS || self.products >= MAX_PRODUCTS {
            return Some(false);
        }
        None
    }

    /// One Newton step from the iterate of the last [`Self::check`].
    fn advance(&mut self, work: &mut Workspace) {
        self.iterations += 1;
        let mut right_side = std::mem::take(&mut self.right_side);
        self.right_side(&mut right_side);
        // Solving accurately pays only once the division into adhesion and slip has settled,
        // or once it has failed to settle for long: loose steps can make elements trade
        // places between adhesion and slip forever (a/b = 9.8 with spin on 320 × 400 from
        // the 160 × 200 solution: 200 steps without settling, the adhesion area left at 6 %
        // of the solution's and F_x off by 0.3 μQ; with accurate steps after the 16th it
        // converges in 41).
        let accurate = self.settled && !self.released;
        let tolerance = if accurate || self.iterations > LOOSE_STEPS { SETTLED_TOLERANCE } else { UNSETTLED_TOLERANCE };
        let update = self.gmres(work, &right_side, tolerance);
        self.right_side = right_side;
        let (relative_step, changed) = self.update(&update);
        self.settled = !changed;
        self.converging = accurate && !changed && relative_step <= RELATIVE_TOLERANCE / SETTLED_TOLERANCE;
    }

    /// The solution of this iteration, its counts plus `other`'s (iterations, products): those
    /// of an iteration that raced it.
    fn into_solution(self, converged: bool, other: (usize, usize)) -> TangentialSolution {
        let [traction_x, traction_y] = self.traction;
        TangentialSolution {
            traction_x,
            traction_y,
            state: self.state,
            iterations: self.iterations + other.0,
            products: self.products + other.1,
            converged,
        }
    }

    /// slip ← w + (A/δx) Δp for the current tractions.
    fn evaluate_slip(&mut self, convolution: &mut SlipConvolution) {
        let [traction_x, traction_y] = &self.traction;
        let (nx, ny) = (self.grid.elements_x, self.grid.elements_y);
        let [steps_x, steps_y] = &mut self.steps;
        steps_of([traction_x, traction_y], [steps_x, steps_y], nx, ny);
        let [slip_x, slip_y] = &mut self.slip;
        convolution.apply([&self.steps[0], &self.steps[1]], [slip_x, slip_y]);
        self.products += 1;
        for component in 0..2 {
            for (slip, rigid) in self.slip[component].iter_mut().zip(self.rigid_slip[component]) {
                *slip += rigid;
            }
        }
    }

    /// Slip elements whose slip is not nearly opposite to their traction (cosine of the angle
    /// between −s and p below [`RESOLVE_ALIGNMENT`], s·p > 0 included) are solved locally again,
    /// as a Gauss–Seidel step would (`local_traction`, with the response of the element's own
    /// traction): they return to adhesion, or slip in a new direction. The Newton step's
    /// linearisation in the slip direction holds for small turns only. Returns whether any
    /// element was solved again.
    fn release(&mut self) -> bool {
        let mut released = false;
        for element in 0..self.count {
            if self.state[element] != ElementState::Slip {
                continue;
            }
            let (p_x, p_y) = (self.traction[0][element], self.traction[1][element]);
            let (s_x, s_y) = (self.slip[0][element], self.slip[1][element]);
            if s_x * p_x + s_y * p_y <= -RESOLVE_ALIGNMENT * s_x.hypot(s_y) * p_x.hypot(p_y) {
                continue;
            }
            let (b_x, b_y) = self.own_response;
            let residual = (s_x - b_x * p_x, s_y - b_y * p_y);
            let (traction, slips) = local_traction(residual, self.own_response, self.grid.pressure[element]);
            self.traction[0][element] = traction.0;
            self.traction[1][element] = traction.1;
            if !slips {
                self.state[element] = ElementState::Adhesion;
            }
            released = true;
        }
        released
    }

    /// The slip elements' directions t = p/g and turning coefficients |s|/g.
    fn linearise(&mut self) {
        for element in 0..self.count {
            if self.state[element] != ElementState::Slip {
                continue;
            }
            let bound = self.grid.pressure[element];
            let t = (self.traction[0][element] / bound, self.traction[1][element] / bound);
            let along = self.slip[0][element] * t.0 + self.slip[1][element] * t.1;
            self.direction[element] = t;
            self.turning[element] = (-along).max(0.0) / bound;
        }
    }

    /// The slip equations' row scale 1/(k + c): their residual in units of traction, as the
    /// adhesion equations' residual is in units of slip; balances the rows of fast slip
    /// (c → ∞ at extreme creepage) against the others in GMRES's residual norm.
    fn row_scale(&self, element: usize) -> f64 {
        1.0 / (self.self_influence + self.turning[element])
    }

    /// The Newton step's right side: −s in adhesion, −n(n·s)/(k + c) in slip, 0 outside.
    fn right_side(&self, out: &mut [f64]) {
        let n = self.count;
        for element in 0..n {
            let (s_x, s_y) = (self.slip[0][element], self.slip[1][element]);
            let (r_x, r_y) = match self.state[element] {
                ElementState::Exterior => (0.0, 0.0),
                ElementState::Adhesion => (-s_x, -s_y),
                ElementState::Slip => {
                    let (t_x, t_y) = self.direction[element];
                    let normal = (-t_y * s_x + t_x * s_y) * self.row_scale(element);
                    (t_y * normal, -t_x * normal)
                }
            };
            out[element] = r_x;
            out[n + element] = r_y;
        }
    }

    /// The linearised operator: for adhesion elements the slip change, for slip elements the
    /// normal component of the slip change plus the turning term (normal direction) and the
    /// tangential component of the input (an identity that fixes the unused unknown).
    fn apply_operator(&mut self, convolution: &mut SlipConvolution, input: &[f64], out: &mut [f64]) {
        let n = self.count;
        let (nx, ny) = (self.grid.elements_x, self.grid.elements_y);
        let (input_x, input_y) = input.split_at(n);
        // The admissible change: slip elements only turn.
        for element in 0..n {
            let (v_x, v_y) = (input_x[element], input_y[element]);
            let (d_x, d_y) = match self.state[element] {
                ElementState::Exterior => (0.0, 0.0),
                ElementState::Adhesion => (v_x, v_y),
                ElementState::Slip => {
                    let (t_x, t_y) = self.direction[element];
                    let normal = -t_y * v_x + t_x * v_y;
                    (-t_y * normal, t_x * normal)
                }
            };
            self.product[0][element] = d_x;
            self.product[1][element] = d_y;
        }
        let [change_x, change_y] = &self.product;
        let [steps_x, steps_y] = &mut self.steps;
        steps_of([change_x, change_y], [steps_x, steps_y], nx, ny);
        let (out_x, out_y) = out.split_at_mut(n);
        convolution.apply([&self.steps[0], &self.steps[1]], [out_x, out_y]);
        self.products += 1;
        for element in 0..n {
            match self.state[element] {
                ElementState::Exterior => {
                    out_x[element] = 0.0;
                    out_y[element] = 0.0;
                }
                ElementState::Adhesion => {}
                ElementState::Slip => {
                    let (t_x, t_y) = self.direction[element];
                    let (v_x, v_y) = (input_x[element], input_y[element]);
                    let normal = (-t_y * out_x[element]
                        + t_x * out_y[element]
                        + self.turning[element] * (-t_y * v_x + t_x * v_y))
                        * self.row_scale(element);
                    let tangential = t_x * v_x + t_y * v_y;
                    out_x[element] = -t_y * normal + t_x * tangential;
                    out_y[element] = t_x * normal + t_y * tangential;
                }
            }
        }
    }

    /// The preconditioner (see the module documentation): circulant inverse, then the row
    /// scan from the leading edge that carries each change downstream through adhesion; slip
    /// elements by their own coefficient.
    fn precondition(&mut self, convolution: &mut SlipConvolution, input: &[f64], out: &mut [f64]) {
        let n = self.count;
        let nx = self.grid.elements_x;
        let (input_x, input_y) = input.split_at(n);
        // The circulant inverse acts on slip: slip rows back in slip units, normal part only.
        for element in 0..n {
            let (r_x, r_y) = (input_x[element], input_y[element]);
            let (u_x, u_y) = match self.state[element] {
                ElementState::Slip => {
                    let (t_x, t_y) = self.direction[element];
                    let normal = (-t_y * r_x + t_x * r_y) / self.row_scale(element);
                    (-t_y * normal, t_x * normal)
                }
                _ => (r_x, r_y),
            };
            self.unscaled[0][element] = u_x;
            self.unscaled[1][element] = u_y;
        }
        {
            let [steps_x, steps_y] = &mut self.product;
            let [unscaled_x, unscaled_y] = &self.unscaled;
            convolution.apply_inverse([unscaled_x, unscaled_y], [steps_x, steps_y]);
        }
        let (out_x, out_y) = out.split_at_mut(n);
        out_x.iter_mut().for_each(|v| *v = 0.0);
        out_y.iter_mut().for_each(|v| *v = 0.0);
        for (j, row) in self.grid.rows_in_contact.iter().enumerate() {
            let Some((first, last)) = *row else { continue };
            let mut carry = (0.0, 0.0);
            for i in (first..=last).rev() {
                let element = i + j * nx;
                let (z_x, z_y) = (self.product[0][element], self.product[1][element]);
                match self.state[element] {
                    ElementState::Exterior => carry = (0.0, 0.0),
                    ElementState::Adhesion => {
                        carry = (carry.0 + z_x, carry.1 + z_y);
                        out_x[element] = carry.0;
                        out_y[element] = carry.1;
                    }
                    ElementState::Slip => {
                        let (t_x, t_y) = self.direction[element];
                        // Slow slip (c ≪ k) behaves like adhesion across the direction of
                        // the traction, fast slip is dominated by its own turning term.
                        let (k, c) = (self.self_influence, self.turning[element]);
                        let carried = -t_y * (z_x + carry.0) + t_x * (z_y + carry.1);
                        let own = -t_y * input_x[element] + t_x * input_y[element];
                        let normal = (k * carried + c * own) / (k + c);
                        let tangential = t_x * input_x[element] + t_y * input_y[element];
                        carry = (-t_y * normal, t_x * normal);
                        out_x[element] = carry.0 + t_x * tangential;
                        out_y[element] = carry.1 + t_y * tangential;
                    }
                }
            }
        }
    }

    /// Flexible restarted GMRES with right preconditioning for the Newton step, from zero.
    fn gmres(&mut self, work: &mut Workspace, right_side: &[f64], tolerance: f64) -> Field {
        let size = right_side.len();
        let mut solution = vec![0.0; size];
        let mut residual = right_side.to_vec();
        let target = tolerance * norm(right_side);
        let Workspace { convolution, krylov_basis: basis, krylov_preconditioned: preconditioned } = work;
        basis.resize_with(RESTART + 1, || vec![0.0; size]);
        preconditioned.resize_with(RESTART, || vec![0.0; size]);
        let mut image = vec![0.0; size];
        loop {
            let beta = norm(&residual);
            if beta <= target || !beta.is_finite() || self.products >= MAX_PRODUCTS {
                break;
            }
            basis[0].iter_mut().zip(&residual).for_each(|(v, r)| *v = r / beta);
            // Hessenberg columns, Givens rotations (c, s), and the rotated right side.
            let mut hessenberg: Vec<Vec<f64>> = Vec::with_capacity(RESTART);
            let mut rotations: Vec<(f64, f64)> = Vec::with_capacity(RESTART);
            let mut rotated = vec![beta];
            for k in 0..RESTART {
                self.precondition(convolution, &basis[k], &mut preconditioned[k]);
                self.apply_operator(convolution, &preconditioned[k], &mut image);
                // Modified Gram–Schmidt.
                let mut column = Vec::with_capacity(k + 2);
                for vector in &basis[..=k] {
                    let h = dot(&image, vector);
                    image.iter_mut().zip(vector).for_each(|(w, v)| *w -= h * v);
                    column.push(h);
                }
                let next_norm = norm(&image);
                column.push(next_norm);
                for (i, &(c, s)) in rotations.iter().enumerate() {
                    let (a, b) = (column[i], column[i + 1]);
                    column[i] = c * a + s * b;
                    column[i + 1] = -s * a + c * b;
                }
                let (a, b) = (column[k], column[k + 1]);
                let radius = a.hypot(b);
                let (c, s) = if radius == 0.0 { (1.0, 0.0) } else { (a / radius, b / radius) };
                column[k] = radius;
                column[k + 1] = 0.0;
                rotations.push((c, s));
                rotated.push(-s * rotated[k]);
                rotated[k] *= c;
                hessenberg.push(column);
                let estimate = rotated[k + 1].abs();
                if estimate <= target || next_norm == 0.0 || self.products >= MAX_PRODUCTS {
                    break;
                }
                basis[k + 1].iter_mut().zip(&image).for_each(|(v, w)| *v = w / next_norm);
            }
            // Back substitution for the coefficients, then the update from the preconditioned
            // vectors.
            let used = hessenberg.len();
            let mut coefficients = vec![0.0; used];
            for i in (0..used).rev() {
                let mut sum = rotated[i];
                for (m, coefficient) in coefficients.iter().enumerate().skip(i + 1) {
                    sum -= hessenberg[m][i] * coefficient;
                }
                coefficients[i] = if hessenberg[i][i] == 0.0 { 0.0 } else { sum / hessenberg[i][i] };
            }
            for (coefficient, vector) in coefficients.iter().zip(preconditioned.iter()) {
                solution.iter_mut().zip(vector).for_each(|(x, z)| *x += coefficient * z);
            }
            if rotated[used].abs() <= target || self.products >= MAX_PRODUCTS {
                break;
            }
            // Restart from the true residual.
            self.apply_operator(convolution, &solution, &mut image);
            residual.iter_mut().zip(right_side.iter().zip(&image)).for_each(|(r, (b, w))| *r = b - w);
        }
        solution
    }

    /// Applies the Newton step; adhesion elements pushed over their bound start slipping.
    /// Returns the largest traction change relative to the largest traction, and whether any
    /// element started slipping.
    fn update(&mut self, step: &[f64]) -> (f64, bool) {
        let n = self.count;
        let (step_x, step_y) = step.split_at(n);
        let (mut largest_step, mut largest_traction): (f64, f64) = (0.0, 0.0);
        let mut changed = false;
        for element in 0..n {
            let (mut d_x, mut d_y) = (step_x[element], step_y[element]);
            match self.state[element] {
                ElementState::Exterior => continue,
                ElementState::Adhesion => {}
                ElementState::Slip => {
                    let (t_x, t_y) = self.direction[element];
                    let normal = -t_y * d_x + t_x * d_y;
                    (d_x, d_y) = (-t_y * normal, t_x * normal);
                }
            }
            let (old_x, old_y) = (self.traction[0][element], self.traction[1][element]);
            self.traction[0][element] = old_x + d_x;
            self.traction[1][element] = old_y + d_y;
            let magnitude = self.traction[0][element].hypot(self.traction[1][element]);
            let bound = self.grid.pressure[element];
            if self.state[element] == ElementState::Slip || magnitude > bound {
                changed |= self.state[element] == ElementState::Adhesion;
                if magnitude > 0.0 {
                    self.project_onto_bound(element);
                } else {
                    self.traction[0][element] = old_x;
                    self.traction[1][element] = old_y;
                }
            }
            let (new_x, new_y) = (self.traction[0][element], self.traction[1][element]);
            largest_step = largest_step.max((new_x - old_x).hypot(new_y - old_y));
            largest_traction = largest_traction.max(new_x.hypot(new_y));
        }
        let relative_step = if largest_traction > 0.0 { largest_step / largest_traction } else { 0.0 };
        (relative_step, changed)
    }
}

/// Traction steps Δp_i = p_i − p_{i+1} along every row, for i = −1 … nx − 1 (step column
/// i + 1), with p = 0 outside the grid.
fn steps_of(field: [&[f64]; 2], steps: [&mut [f64]; 2], nx: usize, ny: usize) {
    for (values, out) in field.into_iter().zip(steps) {
        for j in 0..ny {
            let row = &values[j * nx..(j + 1) * nx];
            let out_row = &mut out[j * (nx + 1)..(j + 1) * (nx + 1)];
            out_row[0] = -row[0];
            for i in 0..nx {
                let upstream = if i + 1 < nx { row[i + 1] } else { 0.0 };
                out_row[i + 1] = row[i] - upstream;
            }
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}
