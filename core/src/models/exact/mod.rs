//! Kalker's exact theory of steady rolling contact, as in the CONTACT program: the top rung of
//! the ladder, the reference every cheaper model is measured against.
//!
//! Problem (Kalker 1990, *Three-dimensional elastic bodies in rolling contact*, ch. 2 and 5;
//! Vollebregt, CONTACT user guide): two quasi-identical elastic half-spaces roll in steady state
//! over a Hertzian contact ellipse with semi-axes a (rolling direction x) × b. Quasi-identity
//! decouples the normal problem from the tangential one, so the pressure is Hertz's,
//! p_n = p₀ √(1 − x²/a² − y²/b²) with p₀ = 3Q/(2πab), and the tangential tractions solve
//!
//! ```text
//! s = w + (u(x) − u(x + δx))/δx,   w = (ξ − φ y, η + φ x),
//! |p| ≤ μ p_n;  s = 0 where |p| < μ p_n (adhesion);  p = −μ p_n s/|s| where s ≠ 0 (slip),
//! ```
//!
//! (with CONTACT's evaluation of the spin term at x + δx/6, see `rigid_slip`), discretised
//! with piecewise-constant tractions on a rectangular grid (`grid.rs`) and Love's influence
//! coefficients (`influence.rs`), applied as FFT convolutions (`convolution.rs`) inside an
//! active-set Newton–GMRES solver (`tangential.rs`). CONTACT's non-linear Gauss–Seidel
//! method on the same discretisation (`gauss_seidel.rs`) stays as the test oracle
//! ([`ExactTheory::solve_by_gauss_seidel`]).
//!
//! Sign convention: tractions and forces act on the wheel (body 1) and oppose the creepages;
//! M_z = Σ (x p_y − y p_x) δA about the contact centre.
//!
//! Cost: O(N log N) per iteration for N elements (four 2-D FFTs of the zero-padded grid per
//! operator product, as many per preconditioner application), 40–120 products per cold solve
//! on 40 × 40 … 160 × 160. The time per solve, cold and warm-started, one thread, is measured by
//! `cargo bench --bench exact` (CONTACT's spin case, pure ξ in partial slip, a slowly varying
//! co-simulation) and per grid over the trade report's cases in docs/trade/README.md. Every solve is bounded ([`MAX_ITERATIONS`]
//! Newton steps, [`MAX_PRODUCTS`] products; twice that for a warm start and the cold solve
//! racing it), and a warm-started one by about twice a cold solve (see below).
//!
//! Grid: the grid error is first order in the element size and comes almost entirely from the
//! element length δx along the rolling direction (n_x × n_y = 320 × 40 is within 0.0005 μQ of
//! 320 × 320 on CONTACT's spin case, pure ξ and a/b = 10), so grids with more elements along x
//! are the cheap way to accuracy: the trade report (docs/trade/README.md) gives each grid's error
//! against the converged solution over its cases, spin included, 200 × 50 among them.
//!
//! Warm starts: a solution's tractions, kept by the caller as a [`WarmStart`] and passed to
//! [`ExactTheory::solve_from`], start the next solve. They are stored in units of μp₀ on a grid
//! that scales with the ellipse, so they carry over to a new load, friction coefficient and
//! ellipse; a poor start costs iterations, never accuracy (the solution is the same to the
//! solver's tolerance). A start that has not converged after [`WARM_ALONE_PRODUCTS`] operator
//! products is raced by a cold solve, so a step after an abrupt change costs at most about
//! twice a cold solve (on 200 × 50: 1.1–2.4 × its products over 24 random jumps, `cargo bench
//! --bench exact -- worst_jump`, where a warm start alone cycled for up to 4000 products, 5 s).

mod coefficients;
mod convolution;
mod element;
mod gauss_seidel;
mod grid;
mod influence;
mod tangential;

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::models::rung::Rung;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, ModelChoice};
pub use coefficients::LinearCoefficients;
use grid::ContactGrid;
pub use grid::GridSize;
use influence::InfluenceTable;
use tangential::TangentialSolution;
pub use tangential::{MAX_ITERATIONS, MAX_PRODUCTS, WARM_ALONE_PRODUCTS};

/// Whether an element carries traction, and if so whether it adheres or slips.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementState {
    /// Outside the contact ellipse: no pressure, no traction.
    Exterior,
    /// Inside the contact, |p| < μ p_n and zero slip.
    Adhesion,
    /// Inside the contact, |p| = μ p_n, traction opposing the slip.
    Slip,
}

/// Largest number of elements along either axis (the "[1, 400]" of the validation message):
/// bounds the memory (the Newton solver keeps 60 vectors of the grid's size: 215 MB peak at
/// 400 × 400) and the time of a solve (at most [`MAX_PRODUCTS`] operator products; CONTACT's spin
/// case cold at 400 × 400 takes 203). Raised from
/// 200 with the FFT solver, for reference solutions on 320 × 320 and 400 × 400.
pub const MAX_ELEMENTS_PER_AXIS: usize = 400;
/// Smallest number of elements along an axis for which a solve without a start begins with the
/// solution on a grid of half as many along it ([`ExactTheory::solve_from`]). Below, a cold
/// solve is cheap. (Where only one axis has that many, the nesting can cost more than it saves,
/// 80 × 20 started from 40 × 20 and 20 × 20: 40 % slower over 300 random contacts, no fewer
/// Newton steps; but 39 × 200 at a/b = 11.5 cycled cold and converges nested.)
pub const NESTED_START_MINIMUM: usize = 40;
/// Ratio of an element's sides from which the nested start halves only the axis of its shorter
/// side ([`ExactTheory::nested_start_grid`]).
const NESTED_START_ASPECT: f64 = 3.0;
/// Offset of the point where the spin part φx of the rigid slip is taken, in element lengths
/// from the centre towards the leading edge; see [`rigid_slip`].
const SPIN_SLIP_OFFSET: f64 = 1.0 / 6.0;
/// Rigid slip in units of the creepage scale μp₀/G is clamped here: far beyond it every element
/// slips in the direction of w to within 1e-100, and the clamp keeps the arithmetic finite.
const RIGID_SLIP_MAX: f64 = 1e100;

/// Kalker's exact theory on a grid of `grid` elements over the potential contact area
/// 2.2 a × 2.2 b (CONTACT's default layout).
///
/// CONTACT's published spin case (`examples/fastsim`: a = 8 mm, b = 4 mm, η = −6.25e-4, φ =
/// 0.625 /m, μN = 24.6 kN) on CONTACT's own grid, 44 × 44 elements of 0.4 × 0.2 mm: CONTACT
/// gives F_y/(μN) = −0.6074 and M_z = −48.21 N·m (this solver: within 0.4 %):
///
/// ```
/// use wheel_rail_contact::reference_cases::{FASTSIM_CASE, FASTSIM_CASE_EXACT};
/// use wheel_rail_contact::{ElementState, ExactTheory};
///
/// let exact = ExactTheory::new(44, 44);
/// assert_eq!(exact, ExactTheory::default());
/// assert!(exact.validate().is_ok() && ExactTheory::new(0, 44).validate().is_err());
/// let solution = exact.solve(&FASTSIM_CASE).unwrap().converged().unwrap();
/// let ratio = solution.forces.force_lateral / FASTSIM_CASE.friction_limit();
/// assert!((ratio / FASTSIM_CASE_EXACT.force_lateral_ratio - 1.0).abs() < 0.005, "{ratio}");
/// assert!((solution.forces.spin_moment.unwrap() / FASTSIM_CASE_EXACT.spin_moment - 1.0).abs() < 0.005);
/// // The fields: partial slip; element (0, 0) is the corner one, outside the ellipse.
/// let count = |wanted: ElementState| solution.element_state.iter().filter(|&&state| state == wanted).count();
/// assert!(count(ElementState::Adhesion) > 0 && count(ElementState::Slip) > 0);
/// let (x, y) = solution.element_centre(0, 0);
/// assert!((x + 8.6e-3).abs() < 1e-12 && (y + 4.3e-3).abs() < 1e-12);
/// assert_eq!(solution.element_state[0], ElementState::Exterior);
/// // A warm start from this solution: the same answer in fewer operator products.
/// let warm = exact.solve_from(&FASTSIM_CASE, Some(&solution.warm_start())).unwrap();
/// assert!(warm.warm_start().validate().is_ok() && warm.operator_products < solution.operator_products);
/// assert!((warm.forces.force_lateral / solution.forces.force_lateral - 1.0).abs() < 1e-6);
/// // Many cases at once (rayon), in order; the Gauss–Seidel oracle agrees.
/// let both = exact.creep_forces_many(&[FASTSIM_CASE, FASTSIM_CASE]);
/// assert_eq!(both[0].as_ref().unwrap(), both[1].as_ref().unwrap());
/// let oracle = ExactTheory::new(12, 12).solve_by_gauss_seidel(&FASTSIM_CASE, 1e-9).unwrap();
/// let newton = ExactTheory::new(12, 12).solve(&FASTSIM_CASE).unwrap();
/// assert!((oracle.forces.force_lateral / newton.forces.force_lateral - 1.0).abs() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExactTheory {
    /// Elements over the potential contact area.
    pub grid: GridSize,
}

/// The exact theory's rung of the ladder: the top one, the reference of the others.
pub const RUNG: Rung = Rung {
    name: "exact",
    fmu_value: 5,
    type_name: "ExactTheory",
    fmu_parameters: &["exact_elements_longitudinal", "exact_elements_lateral"],
    spin_moment: true,
    friction_limited: true,
    offline: true,
    summary: "Kalker's exact theory of steady rolling on half-spaces (Love's influence coefficients as FFT convolutions, active-set Newton–GMRES; Gauss–Seidel kept as the test oracle), forces, M_z, traction field, adhesion/slip areas; its own linear coefficients C11 … C33 (`linear_coefficients`, checked against Kalker's table row by row)",
    source: "Kalker 1990; CONTACT",
    documentation: "Kalker's exact theory of steady rolling (Kalker 1990; as in Vollebregt's CONTACT): Love's
influence coefficients on a rectangular grid of <code>exact_elements_longitudinal</code> ×
<code>exact_elements_lateral</code> elements over the potential contact area 2.2a × 2.2b, Hertzian pressure,
Coulomb's law; solved by an active-set Newton method whose linear steps (GMRES) apply the influence coefficients
as FFT convolutions, O(N log N) per product. Gives M<sub>z</sub>. Each step starts from the previous step's
tractions (scaled to the new μp<sub>0</sub> and ellipse), so a co-simulation with slowly varying creepage needs
a few iterations per step. The default 200 × 50 spends its elements along the rolling direction, where almost
all of the error comes from; its error against the converged theory and its time per evaluation, and those of
other grids, are measured in docs/trade/README.md in the source repository (<code>cargo run --release -p lab --bin trade_report</code>).
<b>For offline or low-rate use.</b>",
    default_model: || {
        let exact = ExactTheory::new(200, 50);
        exact.validate()?;
        Ok(ModelChoice::Exact(exact))
    },
};

impl Default for ExactTheory {
    /// CONTACT's published grid: 44 × 44 elements, 40 × 40 of them inside the ellipse.
    fn default() -> Self {
        Self { grid: GridSize { longitudinal: 44, lateral: 44 } }
    }
}

/// The full solution: forces, and the fields behind them.
///
/// Fields are row-major over the grid: element (i, j) (i along x, from −x to +x; j along y)
/// is at index i + j·`grid.longitudinal`; see [`ExactSolution::element_centre`].
#[derive(Debug, Clone, PartialEq)]
pub struct ExactSolution {
    /// F_x, F_y and M_z (always `Some`) on the wheel.
    pub forces: CreepForces,
    /// The grid the problem was solved on.
    pub grid: GridSize,
    /// Element size along x \[m\].
    pub element_length: f64,
    /// Element size along y \[m\].
    pub element_width: f64,
    /// Normal pressure per element \[Pa\] (0 outside the contact ellipse).
    pub pressure: Vec<f64>,
    /// Longitudinal traction p_x per element \[Pa\].
    pub traction_longitudinal: Vec<f64>,
    /// Lateral traction p_y per element \[Pa\].
    pub traction_lateral: Vec<f64>,
    /// Exterior, adhesion or slip per element.
    pub element_state: Vec<ElementState>,
    /// Area of the adhesion elements \[m²\].
    pub adhesion_area: f64,
    /// Area of the slip elements \[m²\].
    pub slip_area: f64,
    /// The friction coefficient μ of the solve: the Coulomb bound of element I is
    /// μ × `pressure[I]`.
    pub friction_coefficient: f64,
    /// Newton steps used (Gauss–Seidel sweeps for [`ExactTheory::solve_by_gauss_seidel`]); a
    /// warm start and the cold solve that raced it count together.
    pub iterations: usize,
    /// Operator products (FFT convolutions) used on this grid, over all Newton steps (the
    /// half-grid start of a cold solve not included; a warm start's and the cold solve's that
    /// raced it together).
    pub operator_products: usize,
    /// Whether the iteration met its tolerance (tractions to ≈ 1e-7 × the largest: an accurate
    /// Newton step that changed no element's state and no traction by more than 1e-3 × the
    /// largest traction, then no element released) within the limits [`MAX_ITERATIONS`] and
    /// [`MAX_PRODUCTS`]. Otherwise the tractions and forces are the last iterate, which
    /// [`ExactSolution::converged`] refuses to pass on as forces.
    pub converged: bool,
}

impl ExactSolution {
    /// The solution, if its iteration converged; otherwise an error naming the grid, for
    /// callers that must not use an unconverged iterate (references, studies). An iterate's
    /// forces are usually close (wide contacts on 200 × 50 elements that stop at the limits:
    /// within 2e-4 μQ, M_z within 2 %) but can be far off (0.3 μQ in the case `tangential.rs`
    /// cites); [`CreepForceModel::creep_forces`] returns the last iterate (a total function, as
    /// every model's), and the scene reports it (`SceneOutput::unconverged_grid`, the FMU's
    /// fmi2Warning).
    pub fn converged(self) -> Result<Self, InvalidInput> {
        if self.converged {
            return Ok(self);
        }
        Err(InvalidInput::new(
            "grid_elements_longitudinal",
            self.grid.longitudinal as f64,
            "the exact theory did not converge on this grid for this contact within its limits \
             (200 Newton steps, 4000 operator products); choose another grid or model",
        )
        .involving([Some(("grid_elements_lateral", self.grid.lateral as f64)), None]))
    }

    /// Centre of element (i, j) \[m\] relative to the contact centre.
    pub fn element_centre(&self, i: usize, j: usize) -> (f64, f64) {
        let x = (i as f64 + 0.5 - 0.5 * self.grid.longitudinal as f64) * self.element_length;
        let y = (j as f64 + 0.5 - 0.5 * self.grid.lateral as f64) * self.element_width;
        (x, y)
    }

    /// This solution's tractions as the start of the next solve ([`ExactTheory::solve_from`]).
    pub fn warm_start(&self) -> WarmStart {
        let relative = |traction: &[f64]| -> Vec<f64> {
            traction
                .iter()
                .zip(&self.pressure)
                .map(|(&p, &pressure)| {
                    let bound = self.friction_coefficient * pressure;
                    if bound > 0.0 && (p / bound).is_finite() {
                        p / bound
                    } else {
                        0.0
                    }
                })
                .collect()
        };
        WarmStart {
            grid: Some(self.grid),
            relative_longitudinal: relative(&self.traction_longitudinal),
            relative_lateral: relative(&self.traction_lateral),
        }
    }
}

/// A previous solution's tangential tractions relative to their Coulomb bound μ p_n, per
/// element of its grid: the start of the next solve ([`ExactTheory::solve_from`]).
///
/// The grid spans 2.2 a × 2.2 b whatever the ellipse, so an element keeps its relative position
/// when the semi-axes change, and a traction relative to its bound keeps adhesion inside the
/// bound and slip on it when the load, μ or the ellipse change: the start is the previous
/// solution scaled to the new μp₀ and ellipse. On another grid size each element takes the
/// value of the stored element that contains its centre. `WarmStart::default()` starts from
/// zero traction.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WarmStart {
    grid: Option<GridSize>,
    relative_longitudinal: Vec<f64>,
    relative_lateral: Vec<f64>,
}

impl WarmStart {
    /// Checks a start that did not come from [`ExactSolution::warm_start`] (one read back from
    /// a saved state): empty, or a valid grid with one finite relative traction per element and
    /// axis. Any such start is safe: it only chooses where the Newton iteration begins.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        let elements = match self.grid {
            None => 0,
            Some(grid) => {
                ExactTheory { grid }.validate()?;
                grid.longitudinal * grid.lateral
            }
        };
        for (variable, relative) in
            [("warm_start_longitudinal", &self.relative_longitudinal), ("warm_start_lateral", &self.relative_lateral)]
        {
            if relative.len() != elements {
                return Err(InvalidInput::new(variable, relative.len() as f64, "must hold one value per element"));
            }
            if let Some(&value) = relative.iter().find(|value| !value.is_finite()) {
                return Err(InvalidInput::new(variable, value, "must be finite"));
            }
        }
        Ok(())
    }

    /// The start on `grid` in the solver's units (μp₀), or `None` for an empty start.
    fn tractions(&self, grid: &ContactGrid) -> Option<[Vec<f64>; 2]> {
        let stored = self.grid?;
        // Element k of n covers [k/n, (k+1)/n) of the axis; the stored element holding the
        // centre (k + ½)/n.
        let source = |k: usize, n: usize, m: usize| ((2 * k + 1) * m / (2 * n)).min(m - 1);
        let mut tractions = [vec![0.0; grid.pressure.len()], vec![0.0; grid.pressure.len()]];
        for j in 0..grid.elements_y {
            let stored_j = source(j, grid.elements_y, stored.lateral);
            for i in 0..grid.elements_x {
                let element = i + j * grid.elements_x;
                let stored_element = source(i, grid.elements_x, stored.longitudinal) + stored_j * stored.longitudinal;
                let bound = grid.pressure[element];
                tractions[0][element] = bound * self.relative_longitudinal[stored_element];
                tractions[1][element] = bound * self.relative_lateral[stored_element];
            }
        }
        Some(tractions)
    }
}

impl ExactTheory {
    /// A model on `longitudinal` × `lateral` elements over the potential contact area.
    pub fn new(longitudinal: usize, lateral: usize) -> Self {
        Self { grid: GridSize { longitudinal, lateral } }
    }

    /// Checks the grid: 1 … [`MAX_ELEMENTS_PER_AXIS`] elements along each axis.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        for (variable, count) in
            [("grid_elements_longitudinal", self.grid.longitudinal), ("grid_elements_lateral", self.grid.lateral)]
        {
            if !(1..=MAX_ELEMENTS_PER_AXIS).contains(&count) {
                return Err(InvalidInput::new(variable, count as f64, "must lie in [1, 400]"));
            }
        }
        Ok(())
    }

    /// Solves the contact problem and returns the forces with the traction field and the
    /// adhesion and slip areas.
    ///
    /// Lift-off (Q ≤ 0) gives no contact (every element exterior); μ = 0 gives zero traction
    /// with every contact element slipping.
    pub fn solve(&self, input: &ContactInput) -> Result<ExactSolution, InvalidInput> {
        self.solve_from(input, None)
    }

    /// [`Self::solve`] starting from a previous solution's tractions (`start`, see
    /// [`WarmStart`]). Per step of a co-simulation:
    /// `let solution = model.solve_from(&input, Some(&start))?; start = solution.warm_start();`.
    ///
    /// Without a start (`None` or an empty one), a grid with at least [`NESTED_START_MINIMUM`]
    /// elements along an axis starts from the solution on a grid of half as many along it
    /// (nested iteration, recursively; not along the longer side of elements whose sides differ
    /// three times or more): it puts the division into adhesion and slip close to the final one,
    /// which the Newton solver otherwise finds one element layer per step. A warm start that
    /// has not converged after [`WARM_ALONE_PRODUCTS`] operator products is raced by the solve without
    /// it (each taking the next Newton step in turn, the one that has used fewer operator
    /// products first) until either converges: a step costs at most about twice a cold solve
    /// (`tangential::solve_warm_or_cold`), where a start from a contact that jumped could cycle
    /// for 200 steps (3.5–5 s on 200 × 50 instead of 0.1 s).
    pub fn solve_from(&self, input: &ContactInput, start: Option<&WarmStart>) -> Result<ExactSolution, InvalidInput> {
        let Some(start) = start.filter(|start| start.grid.is_some()) else {
            return self.solve_cold(input);
        };
        self.solve_with(input, |grid, table, rigid_slip| {
            let Some([warm_x, warm_y]) = start.tractions(grid) else {
                return Ok(tangential::solve(grid, table, rigid_slip, None));
            };
            tangential::solve_warm_or_cold(grid, table, rigid_slip, [&warm_x, &warm_y], || {
                Ok(self.nested_start(input)?.and_then(|start| start.tractions(grid)))
            })
        })
    }

    /// The solve without a start: nested on grids large enough ([`Self::solve_from`]).
    fn solve_cold(&self, input: &ContactInput) -> Result<ExactSolution, InvalidInput> {
        // Refused before any coarse solve (a grid of 1000 × 1000 would otherwise solve the
        // nested 250 × 250 first).
        input.validate()?;
        self.validate()?;
        let start = self.nested_start(input)?;
        self.solve_with(input, |grid, table, rigid_slip| {
            let field = start.as_ref().and_then(|start| start.tractions(grid));
            let field = field.as_ref().map(|[x, y]| [x.as_slice(), y.as_slice()]);
            Ok(tangential::solve(grid, table, rigid_slip, field))
        })
    }

    /// The start of a solve without one: the solution on the grid of
    /// [`Self::nested_start_grid`], if any.
    fn nested_start(&self, input: &ContactInput) -> Result<Option<WarmStart>, InvalidInput> {
        match self.nested_start_grid(input.semi_axis_b / input.semi_axis_a) {
            Some(coarse) => Ok(Some(ExactTheory { grid: coarse }.solve(input)?.warm_start())),
            None => Ok(None),
        }
    }

    /// The grid of the nested start, if any: half as many elements along each axis that has at
    /// least [`NESTED_START_MINIMUM`] elements, except the axis of an element's longer side when
    /// its sides differ [`NESTED_START_ASPECT`] times or more. Halving both axes of elements far
    /// from square coarsens the short side too: 200 × 50 elements at a/b = 0.16 (elements 25
    /// times longer across than along) started from 100 × 25, from which the Newton iteration
    /// cycled between adhesion and slip at the lateral edges until its limits (on 200 × 50, 22
    /// of 1000 random contacts, `lab/src/bin/convergence_survey.rs`, none now); 320 × 400 at
    /// a/b = 9.8 needed 40 steps from 160 × 200, 7 from 320 × 200. And 39 × 200 at a/b = 11.5, not nested when both axes needed 40 elements,
    /// cycled cold; from 39 × 100 it converges in 8.
    fn nested_start_grid(&self, b_over_a: f64) -> Option<GridSize> {
        let (along, across) = self.grid.element_sides(1.0, b_over_a);
        let halve = |elements: usize, side: f64, other_side: f64| {
            if elements >= NESTED_START_MINIMUM && side < NESTED_START_ASPECT * other_side {
                elements.div_ceil(2)
            } else {
                elements
            }
        };
        let GridSize { longitudinal, lateral } = self.grid;
        let coarse =
            GridSize { longitudinal: halve(longitudinal, along, across), lateral: halve(lateral, across, along) };
        (coarse != self.grid).then_some(coarse)
    }

    /// The forces of many cases, solved in parallel on rayon's thread pool (each case on one
    /// thread, as [`CreepForceModel::creep_forces`]); results in the order of `inputs`. For
    /// report and table generation; a single case is never split across threads.
    pub fn creep_forces_many(&self, inputs: &[ContactInput]) -> Vec<Result<CreepForces, InvalidInput>> {
        inputs.par_iter().map(|input| self.creep_forces(input)).collect()
    }

    /// The reference solution by CONTACT's non-linear Gauss–Seidel method (SteadyGS) on the
    /// same discretisation, swept until no traction changes by more than `relative_tolerance`
    /// × the largest traction (at most 20 000 sweeps). O(N²) per sweep: the test oracle of
    /// [`Self::solve`], not meant for production use.
    pub fn solve_by_gauss_seidel(
        &self,
        input: &ContactInput,
        relative_tolerance: f64,
    ) -> Result<ExactSolution, InvalidInput> {
        self.solve_with(input, |grid, table, [slip_x, slip_y]| {
            Ok(gauss_seidel::solve(grid, table, slip_x, slip_y, relative_tolerance))
        })
    }

    /// The problem set-up and the resultants around a tangential solver.
    fn solve_with(
        &self,
        input: &ContactInput,
        tangential: impl FnOnce(&ContactGrid, &InfluenceTable, [&[f64]; 2]) -> Result<TangentialSolution, InvalidInput>,
    ) -> Result<ExactSolution, InvalidInput> {
        input.validate()?;
        self.validate()?;
        let a = input.semi_axis_a;
        let b_over_a = input.semi_axis_b / a;
        let grid = ContactGrid::new(self.grid, b_over_a);
        let count = grid.elements_x * grid.elements_y;
        let element_length = grid.length * a;
        let element_width = grid.width * a;
        let mut solution = ExactSolution {
            forces: CreepForces::new(0.0, 0.0, Some(0.0), input.friction_limit()),
            grid: self.grid,
            element_length,
            element_width,
            pressure: vec![0.0; count],
            traction_longitudinal: vec![0.0; count],
            traction_lateral: vec![0.0; count],
            element_state: vec![ElementState::Exterior; count],
            adhesion_area: 0.0,
            slip_area: 0.0,
            friction_coefficient: input.friction_coefficient,
            iterations: 0,
            operator_products: 0,
            converged: true,
        };
        if input.normal_force <= 0.0 {
            return Ok(solution);
        }
        let peak_pressure = 3.0 / (2.0 * PI) * input.normal_force / a / input.semi_axis_b;
        for (pressure, normalised) in solution.pressure.iter_mut().zip(&grid.pressure) {
            *pressure = peak_pressure * normalised;
        }
        if input.friction_coefficient == 0.0 {
            for (state, &pressure) in solution.element_state.iter_mut().zip(&grid.pressure) {
                if pressure > 0.0 {
                    *state = ElementState::Slip;
                }
            }
            solution.slip_area = contact_area(&grid) * a * a;
            return Ok(solution);
        }

        // Creepage scale: tractions are solved in units of μp₀, slips in units of μp₀/G.
        let traction_scale = input.friction_coefficient * peak_pressure;
        let creepage_scale = traction_scale / input.shear_modulus;
        let (rigid_slip_x, rigid_slip_y) = rigid_slip(input, &grid, creepage_scale);
        let table = InfluenceTable::new(grid.elements_x, grid.elements_y, grid.length, grid.width, input.poisson_ratio);
        let tangential = tangential(&grid, &table, [&rigid_slip_x, &rigid_slip_y])?;

        // Resultants in units of μQ (Σ bound·δA = (2π/3) b/a, see `grid.rs`) and μQa.
        let (mut force_x, mut force_y, mut moment) = (0.0, 0.0, 0.0);
        for j in 0..grid.elements_y {
            for i in 0..grid.elements_x {
                let element = i + j * grid.elements_x;
                let (x, y) = grid.centre(i, j);
                let (p_x, p_y) = (tangential.traction_x[element], tangential.traction_y[element]);
                force_x += p_x;
                force_y += p_y;
                moment += x * p_y - y * p_x;
            }
        }
        let to_friction_limit = grid.element_area() / (2.0 * PI / 3.0 * b_over_a);
        let friction_limit = input.friction_limit();
        solution.forces = CreepForces::new(
            friction_limit * force_x * to_friction_limit,
            friction_limit * force_y * to_friction_limit,
            Some(friction_limit * a * moment * to_friction_limit),
            friction_limit,
        );
        let element_area = element_length * element_width;
        for (state, &new_state) in solution.element_state.iter_mut().zip(&tangential.state) {
            *state = new_state;
            match new_state {
                ElementState::Adhesion => solution.adhesion_area += element_area,
                ElementState::Slip => solution.slip_area += element_area,
                ElementState::Exterior => {}
            }
        }
        for (traction, normalised) in solution.traction_longitudinal.iter_mut().zip(&tangential.traction_x) {
            *traction = traction_scale * normalised;
        }
        for (traction, normalised) in solution.traction_lateral.iter_mut().zip(&tangential.traction_y) {
            *traction = traction_scale * normalised;
        }
        solution.iterations = tangential.iterations;
        solution.operator_products = tangential.products;
        solution.converged = tangential.converged;
        Ok(solution)
    }
}

impl CreepForceModel for ExactTheory {
    /// The forces of [`ExactTheory::solve`]: of its last iterate when the iteration stopped at
    /// its limits ([`ExactSolution::converged`] tells, and refuses such a solution).
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        self.solve(input).map(|solution| solution.forces)
    }
}

/// Area of the contact elements in units of a².
fn contact_area(grid: &ContactGrid) -> f64 {
    grid.pressure.iter().filter(|&&p| p > 0.0).count() as f64 * grid.element_area()
}

/// Kalker's rigid slip w = (ξ − φy, η + φ(x + δx/6)) at every element, in units of
/// `creepage_scale` and clamped to ±[`RIGID_SLIP_MAX`].
///
/// The lateral spin term is taken δx/6 off the element centre (towards the leading edge), as
/// CONTACT does by default for rolling (its `facphi` = 1/6). The offset is a first-order term
/// that vanishes as δx → 0, but at practical grids it matters for spin: with it our 44 × 44
/// solution of CONTACT's published spin case is within 0.4 % of CONTACT's; at the element
/// centre (offset 0) F_y is 1.9 % low, at the midpoint of the difference quotient (1/2) 4.7 %
/// high (both measured; the tests pin the 1/6 result).
fn rigid_slip(input: &ContactInput, grid: &ContactGrid, creepage_scale: f64) -> (Vec<f64>, Vec<f64>) {
    let a = input.semi_axis_a;
    let scaled = |creepage: f64| {
        if creepage == 0.0 {
            0.0
        } else {
            (creepage / creepage_scale).clamp(-RIGID_SLIP_MAX, RIGID_SLIP_MAX)
        }
    };
    // A zero coordinate contributes no spin term (avoids ∞·0 for absurd φ·a).
    let plus_spin = |creepage: f64, spin_arm: f64| {
        if spin_arm == 0.0 {
            creepage
        } else {
            creepage + input.spin_creepage * (a * spin_arm)
        }
    };
    let count = grid.elements_x * grid.elements_y;
    let (mut slip_x, mut slip_y) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for j in 0..grid.elements_y {
        for i in 0..grid.elements_x {
            let (x, y) = grid.centre(i, j);
            slip_x.push(scaled(plus_spin(input.creepage_longitudinal, -y)));
            slip_y.push(scaled(plus_spin(input.creepage_lateral, x + SPIN_SLIP_OFFSET * grid.length)));
        }
    }
    (slip_x, slip_y)
}

/// The exact theory carries its last tractions from one evaluation to the next ([`WarmStart`]):
/// each solve starts there and ends within the solver's tolerance of a cold solve. That is state:
/// an FMU state saves it.
impl crate::models::sequence::SequenceModel for ExactTheory {
    type Memory = WarmStart;
    type Cache = ();

    fn creep_forces_in_sequence(
        &self,
        input: &ContactInput,
        memory: &WarmStart,
        _cache: &mut (),
    ) -> Result<crate::SequenceStep<WarmStart>, InvalidInput> {
        let solution = self.solve_from(input, Some(memory))?;
        Ok(crate::SequenceStep {
            forces: solution.forces,
            memory: solution.warm_start(),
            unconverged_grid: (!solution.converged).then_some(solution.grid),
        })
    }

    fn validate_memory(memory: &WarmStart) -> Result<(), InvalidInput> {
        memory.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From the 160 × 200 solution, loosely solved Newton steps keep trading ≈ 250 elements
    /// between adhesion and slip of a long ellipse (a/b = 9.8) with spin near the collapse of
    /// adhesion on 320 × 400 (after 200 steps the iterate had 6 % of the adhesion area and
    /// F_x = −0.258 μQ). After sixteen loose steps every step is solved accurately, and it
    /// converges to the forces of the 300 × 400 grid (F_x = −0.56187 μQ, F_y = 0.08123 μQ)
    /// within 0.002 μQ. The warm iteration alone, without the cold solve that races it in
    /// [`ExactTheory::solve_from`].
    #[test]
    #[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
    fn a_division_that_does_not_settle_is_solved_accurately_until_it_converges() {
        let case = ContactInput {
            creepage_longitudinal: 7.641165e-4,
            creepage_lateral: -9.891905e-4,
            spin_creepage: 0.1249448,
            normal_force: 80e3,
            semi_axis_a: 15.671075e-3,
            semi_axis_b: 1.5952958e-3,
            friction_coefficient: 0.3,
            shear_modulus: 82e9,
            poisson_ratio: 0.4644424,
        };
        let start = ExactTheory::new(160, 200).solve(&case).unwrap().warm_start();
        let solution = ExactTheory::new(320, 400)
            .solve_with(&case, |grid, table, rigid_slip| {
                let field = start.tractions(grid);
                let field = field.as_ref().map(|[x, y]| [x.as_slice(), y.as_slice()]);
                Ok(tangential::solve(grid, table, rigid_slip, field))
            })
            .unwrap();
        assert!(solution.converged, "{} steps, {} products", solution.iterations, solution.operator_products);
        assert!(
            solution.iterations > tangential::LOOSE_STEPS,
            "{} Newton steps: the loose steps settled",
            solution.iterations
        );
        let limit = 0.3 * 80e3;
        let forces = solution.forces;
        assert!((forces.force_longitudinal / limit + 0.56187).abs() < 2e-3, "{forces:?}");
        assert!((forces.force_lateral / limit - 0.08123).abs() < 2e-3, "{forces:?}");
    }
}
