//! Making the table: every ray's collapse t_c (bisection on the adhesion fraction), every
//! node's forces from the exact solver (τ < 1) or the full-sliding quadrature (τ = 1), one
//! (a/b, ν) slice at a time so that a generator can save slices as they finish and resume after
//! an interruption (`cargo fmu exact-table` does).
//!
//! The generator's steps on a small table (two nodes along a/b and ν; three along β and α, so
//! that no spin, β = 0, is a node; five along τ) and coarse grids — the shipped table is the same steps on 29 × 6 × 17 × 17 × 47
//! nodes and 80 × 20 / 40 × 20 elements (docs/exact_table.md):
//!
//! ```
//! use wheel_rail_contact::models::exact_table::generation::{
//!     assemble, extrapolate, refresh_full_slip, scales, slice_values, slices_of,
//! };
//! use wheel_rail_contact::models::exact_table::{TableAxes, A_OVER_B_RANGE};
//! use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTable, ExactTheory};
//!
//! let axes = TableAxes { counts: [2, 2, 3, 3, 5], a_over_b: A_OVER_B_RANGE, poisson_ratio: (0.0, 0.5) };
//! assert_eq!(scales(&axes).len(), 4); // one set of scale factors per (a/b, ν) node
//! let (grid, half_grid) = (ExactTheory::new(16, 8), ExactTheory::new(8, 8));
//! let mut slices = Vec::new();
//! for i_ab in 0..2 {
//!     for i_nu in 0..2 {
//!         let (slice, statistics) = slice_values(&axes, i_ab, i_nu, &grid, None).unwrap();
//!         assert!(statistics.solves > 0 && statistics.iterations >= statistics.solves);
//!         // Only the solver's nodes are expensive: the full-sliding ones are made again as they were.
//!         assert_eq!(refresh_full_slip(&axes, i_ab, i_nu, &slice), slice);
//!         // The half grid at the same nodes (its rays take this slice's collapse), then Richardson.
//!         let (coarse, _) = slice_values(&axes, i_ab, i_nu, &half_grid, Some(&slice)).unwrap();
//!         assert_eq!(coarse.collapse, slice.collapse);
//!         slices.push(extrapolate(&slice, &coarse));
//!     }
//! }
//! let table = assemble("example: 16 × 8 and 8 × 8 elements".into(), axes, slices).unwrap();
//! // A table's slices assemble into the same table up to a count of its 16-bit values (μQ/32767;
//! // their units, the largest value per τ node, move by the values' f32 rounding):
//! // `cargo fmu exact-table --extend-from` reuses a table's nodes so.
//! let again = assemble(table.provenance.clone(), table.axes.clone(), slices_of(&table)).unwrap();
//! assert_eq!((&again.axes, again.to_bytes().len()), (&table.axes, table.to_bytes().len()));
//! let again = ExactTable::with_table(Box::leak(Box::new(again)));
//! let model = ExactTable::with_table(Box::leak(Box::new(table)));
//! // Full sliding is analytic in any table: |F| = μQ against the creepage.
//! let input = ContactInput {
//!     creepage_longitudinal: 0.05,
//!     creepage_lateral: 0.0,
//!     spin_creepage: 0.0,
//!     normal_force: 80e3,
//!     semi_axis_a: 6e-3,
//!     semi_axis_b: 4e-3,
//!     friction_coefficient: 0.3,
//!     shear_modulus: 82e9,
//!     poisson_ratio: 0.25,
//! };
//! let forces = model.creep_forces(&input).unwrap();
//! assert!((forces.force_longitudinal + 0.3 * 80e3).abs() < 1e-3 * 0.3 * 80e3, "{forces:?}");
//! let partial = ContactInput { creepage_longitudinal: 4e-4, creepage_lateral: -3e-4, spin_creepage: 0.2, ..input };
//! let (first, second) = (model.creep_forces(&partial).unwrap(), again.creep_forces(&partial).unwrap());
//! assert!(first.force_lateral.abs() > 1e3 && (first.force_lateral - second.force_lateral).abs() < 0.3 * 80e3 / 32767.0);
//! // A node below full sliding is the solver's, extrapolated as the table's are, 2F(16 × 8) −
//! // F(8 × 8): a/b = 0.1, ν = 0, at t = 1/4 (τ = 1/4, the identity piece; s = 1/9), along ξ
//! // (β = 0, α = 0) and along −φ (β = −1, a ray mirrored from +φ by y → −y).
//! let (a, b) = (5e-3 * 0.1f64.sqrt(), 5e-3 / 0.1f64.sqrt());
//! let node = ContactInput { semi_axis_a: a, semi_axis_b: b, poisson_ratio: 0.0, ..input };
//! let creepage_unit = 0.3 * 3.0 * 80e3 / (2.0 * std::f64::consts::PI * a * b) / 82e9; // μp₀/G
//! let c = wheel_rail_contact::KalkerCoefficients::new(0.1, 0.0);
//! let c33 = wheel_rail_contact::KalkerCoefficients::spin_moment_c33(0.1, 0.0);
//! let k = [c.c11, c.c23 + c33].map(|c| 3.0 * c / (2.0 * std::f64::consts::PI));
//! let along_xi = ContactInput { creepage_longitudinal: creepage_unit / (9.0 * k[0]), ..node };
//! let along_spin = ContactInput { creepage_longitudinal: 0.0, spin_creepage: -creepage_unit / (9.0 * k[1] * (a * b).sqrt()), ..node };
//! let solved = |input: &ContactInput| {
//!     let (fine, coarse) = (grid.creep_forces(input).unwrap(), half_grid.creep_forces(input).unwrap());
//!     (2.0 * fine.force_longitudinal - coarse.force_longitudinal, 2.0 * fine.spin_moment.unwrap() - coarse.spin_moment.unwrap())
//! };
//! let (limit, lever) = (0.3 * 80e3, (a * b).sqrt());
//! let (f_x, _) = solved(&along_xi);
//! let table_x = model.creep_forces(&along_xi).unwrap().force_longitudinal;
//! assert!(f_x < -0.1 * limit && (table_x - f_x).abs() < 1e-4 * limit, "F_x {table_x} against {f_x}");
//! let (_, m_z) = solved(&along_spin);
//! let table_m = model.creep_forces(&along_spin).unwrap().spin_moment.unwrap();
//! assert!(m_z.abs() > 1e-3 * limit * lever && (table_m - m_z).abs() < 1e-4 * limit * lever, "M_z {table_m} against {m_z}");
//! ```

use rayon::prelude::*;

use super::coordinates::{scale_factors, size_of, unfold, COLLAPSE_RANGE, IDENTITY_END};
use super::full_slip::full_slip_forces;
use super::table::{Table, TableAxes, TableError};
use crate::{ContactInput, ExactSolution, ExactTheory, WarmStart};

/// A representative contact for the solves: by similarity only a/b, ν and u matter.
const NORMAL_FORCE: f64 = 80e3;
const FRICTION: f64 = 0.3;
const SHEAR_MODULUS: f64 = 82e9;
const MEAN_SEMI_AXIS: f64 = 5e-3;
/// A ray's collapse t_c is where its adhesion area falls below this fraction of the contact
/// (docs/exact_table.md: the zone collapses from ≈ 30 % to ≈ 3 % within Δt ≈ 0.003).
const COLLAPSED: f64 = 0.15;
/// Bisection steps for t_c: 0.55/2¹⁰ = 5e-4, a fortieth of a node spacing.
const BISECTION_STEPS: usize = 10;

/// One (a/b, ν) slice: the values (3 per node over β, α, τ) and each ray's collapse t_c (over β, α).
#[derive(Debug, Clone, PartialEq)]
pub struct Slice {
    pub values: Vec<f32>,
    pub collapse: Vec<f32>,
}

/// The scale factors of every (a/b, ν) node, in the table's order.
pub fn scales(axes: &TableAxes) -> Vec<[f64; 3]> {
    let mut scales = Vec::with_capacity(axes.counts[0] * axes.counts[1]);
    for i in 0..axes.counts[0] {
        for j in 0..axes.counts[1] {
            scales.push(scale_factors(axes.a_over_b_node(i), axes.poisson_node(j)));
        }
    }
    scales
}

/// What one slice cost.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SliceStatistics {
    /// Exact-theory solves.
    pub solves: usize,
    /// Solves that stopped at the solver's iteration limits instead of its tolerance.
    pub unconverged: usize,
    /// Newton steps and operator products over all solves.
    pub iterations: usize,
    pub operator_products: usize,
}

impl std::ops::AddAssign for SliceStatistics {
    fn add_assign(&mut self, other: Self) {
        self.solves += other.solves;
        self.unconverged += other.unconverged;
        self.iterations += other.iterations;
        self.operator_products += other.operator_products;
    }
}

/// Slice (`i_ab`, `i_nu`), solved by `solver` on rayon's thread pool, one ray (fixed β, α;
/// t rising, each solve warm-started from a previous one) per task; the τ = 1 nodes by the
/// full-sliding quadrature. Each ray's collapse is found by bisection on `solver`'s grid, or,
/// with `collapse_of` (another slice of the same nodes), taken from that slice, so that both
/// slices hold the same t at every node (as [`extrapolate`] needs).
pub fn slice_values(
    axes: &TableAxes,
    i_ab: usize,
    i_nu: usize,
    solver: &ExactTheory,
    collapse_of: Option<&Slice>,
) -> Result<(Slice, SliceStatistics), crate::InvalidInput> {
    let a_over_b = axes.a_over_b_node(i_ab);
    let poisson_ratio = axes.poisson_node(i_nu);
    let scale = scale_factors(a_over_b, poisson_ratio);
    let solved = solved_rays(axes);
    let n_alpha = axes.counts[3];
    let rays: Vec<(Ray, SliceStatistics)> = solved
        .par_iter()
        .map(|&(k, l)| {
            let known = collapse_of.map(|slice| f64::from(slice.collapse[k * n_alpha + l]));
            ray(axes, k, l, a_over_b, poisson_ratio, scale, solver, known)
        })
        .collect::<Result<_, _>>()?;
    let mut statistics = SliceStatistics::default();
    let mut values = Vec::with_capacity(rays.len());
    for (ray_values, stats) in rays {
        statistics += stats;
        values.push(ray_values);
    }
    Ok((fill_slice(axes, i_ab, i_nu, &solved, values), statistics))
}

/// A saved slice (as [`slice_values`] made it) with its τ = 1 nodes made again by the current
/// quadrature: the solver's nodes are the expensive part, and only they are kept.
pub fn refresh_full_slip(axes: &TableAxes, i_ab: usize, i_nu: usize, saved: &Slice) -> Slice {
    let [_, _, _, n_alpha, n_t] = axes.counts;
    let solved = solved_rays(axes);
    let rays = solved
        .iter()
        .map(|&(k, l)| {
            let start = 3 * n_t * (k * n_alpha + l);
            let values = saved.values[start..start + 3 * n_t]
                .chunks_exact(3)
                .map(|v| [v[0], v[1], v[2]].map(f64::from))
                .collect();
            Ray { collapse: f64::from(saved.collapse[k * n_alpha + l]), values }
        })
        .collect();
    fill_slice(axes, i_ab, i_nu, &solved, rays)
}

/// The rays that are solved: all but the mirror images (β < 0 at α = 0) and one ray per pole.
fn solved_rays(axes: &TableAxes) -> Vec<(usize, usize)> {
    let [_, _, n_beta, n_alpha, _] = axes.counts;
    (0..n_beta)
        .flat_map(|k| (0..n_alpha).map(move |l| (k, l)))
        .filter(|&(k, l)| {
            let (beta, alpha, _) = axes.direction_node(k, l, 0);
            let pole = beta.abs() == 1.0;
            !(pole && (l > 0 || beta < 0.0)) && !(alpha == 0.0 && beta < 0.0)
        })
        .collect()
}

/// A solved ray: its collapse and its nodes' values.
#[derive(Clone)]
struct Ray {
    collapse: f64,
    values: Vec<[f64; 3]>,
}

/// The slice from its solved rays, with each τ = 1 node replaced by full sliding and the fold
/// edges tabulated with the symmetries they must have (`coordinates.rs`): the rays at β = ±1
/// (pure spin) are one ray for every α with F_x = 0; at α = 0 the ray at −β is the mirror
/// (F_y, M_z reversed, the same collapse) of the ray at β; at α = 1 (no ξ) F_x = 0.
fn fill_slice(axes: &TableAxes, i_ab: usize, i_nu: usize, solved: &[(usize, usize)], rays: Vec<Ray>) -> Slice {
    let [_, _, n_beta, n_alpha, n_t] = axes.counts;
    let a_over_b = axes.a_over_b_node(i_ab);
    let scale = scale_factors(a_over_b, axes.poisson_node(i_nu));
    let mut by_direction = vec![None; n_beta * n_alpha];
    for (&(k, l), mut ray) in solved.iter().zip(rays) {
        let (beta, alpha, _) = axes.direction_node(k, l, n_t - 1);
        ray.values[n_t - 1] = full_slip_forces(unfold(alpha, beta, 0.5), a_over_b, scale);
        by_direction[k * n_alpha + l] = Some(ray);
    }
    let mirrored =
        |ray: &Ray| Ray { collapse: ray.collapse, values: ray.values.iter().map(|v| [v[0], -v[1], -v[2]]).collect() };
    let mut slice = Slice {
        values: Vec::with_capacity(3 * n_beta * n_alpha * n_t),
        collapse: Vec::with_capacity(n_beta * n_alpha),
    };
    for k in 0..n_beta {
        for l in 0..n_alpha {
            let (beta, alpha, _) = axes.direction_node(k, l, 0);
            let ray = if beta.abs() == 1.0 {
                let plus = by_direction[(n_beta - 1) * n_alpha].as_ref().expect("pole ray solved");
                let pure_spin =
                    Ray { collapse: plus.collapse, values: plus.values.iter().map(|v| [0.0, v[1], v[2]]).collect() };
                if beta > 0.0 {
                    pure_spin
                } else {
                    mirrored(&pure_spin)
                }
            } else if alpha == 0.0 && beta < 0.0 {
                mirrored(by_direction[(n_beta - 1 - k) * n_alpha].as_ref().expect("mirror ray solved"))
            } else {
                by_direction[k * n_alpha + l].clone().expect("ray solved")
            };
            slice.collapse.push(ray.collapse as f32);
            for v in ray.values {
                let x = if alpha == 1.0 { 0.0 } else { v[0] };
                slice.values.extend([x, v[1], v[2]].map(|x| x as f32));
            }
        }
    }
    slice
}

/// One ray: τ = 0 (no force); the solver at the nodes 0 < τ ≤ `IDENTITY_END` (where τ = t);
/// the collapse t_c by bisection (unless `known`); the solver at the nodes above, at
/// t = size_of(τ, t_c); τ = 1 is left at zero for [`fill_slice`].
#[allow(clippy::too_many_arguments)]
fn ray(
    axes: &TableAxes,
    k: usize,
    l: usize,
    a_over_b: f64,
    poisson_ratio: f64,
    scale: [f64; 3],
    solver: &ExactTheory,
    known: Option<f64>,
) -> Result<(Ray, SliceStatistics), crate::InvalidInput> {
    let n_t = axes.counts[4];
    let (a, b) = (MEAN_SEMI_AXIS * a_over_b.sqrt(), MEAN_SEMI_AXIS / a_over_b.sqrt());
    let max_pressure = 3.0 * NORMAL_FORCE / (2.0 * std::f64::consts::PI * a * b);
    let creepage_unit = FRICTION * max_pressure / SHEAR_MODULUS;
    let limit = FRICTION * NORMAL_FORCE;
    let mut statistics = SliceStatistics::default();
    let (beta, alpha, _) = axes.direction_node(k, l, 0);
    let mut solve = |t: f64, start: Option<&WarmStart>| -> Result<ExactSolution, crate::InvalidInput> {
        let u = unfold(alpha, beta, t);
        let input = ContactInput {
            creepage_longitudinal: u[0] * creepage_unit / scale[0],
            creepage_lateral: u[1] * creepage_unit / scale[1],
            spin_creepage: u[2] * creepage_unit / (scale[2] * MEAN_SEMI_AXIS),
            normal_force: NORMAL_FORCE,
            semi_axis_a: a,
            semi_axis_b: b,
            friction_coefficient: FRICTION,
            shear_modulus: SHEAR_MODULUS,
            poisson_ratio,
        };
        let solution = solver.solve_from(&input, start)?;
        statistics.solves += 1;
        statistics.unconverged += usize::from(!solution.converged);
        statistics.iterations += solution.iterations;
        statistics.operator_products += solution.operator_products;
        Ok(solution)
    };
    let forces = |solution: &ExactSolution| {
        let f = &solution.forces;
        [f.force_longitudinal / limit, f.force_lateral / limit, f.spin_moment.unwrap_or(0.0) / (limit * MEAN_SEMI_AXIS)]
    };
    let collapsed =
        |solution: &ExactSolution| solution.adhesion_area < COLLAPSED * (solution.adhesion_area + solution.slip_area);
    let tau = |m: usize| m as f64 / (n_t - 1) as f64;
    let mut values = vec![[0.0; 3]];
    let mut start: Option<WarmStart> = None;
    let mut m = 1;
    while m < n_t - 1 && tau(m) <= IDENTITY_END {
        let solution = solve(tau(m), start.as_ref())?;
        values.push(forces(&solution));
        start = Some(solution.warm_start());
        m += 1;
    }
    let collapse = match known {
        Some(collapse) => collapse,
        None => find_collapse(&mut solve, start.as_ref(), collapsed)?,
    };
    while m < n_t - 1 {
        let solution = solve(size_of(tau(m), collapse), start.as_ref())?;
        values.push(forces(&solution));
        start = Some(solution.warm_start());
        m += 1;
    }
    values.push([0.0; 3]);
    Ok((Ray { collapse, values }, statistics))
}

/// A ray's collapse t_c: bisection in `COLLAPSE_RANGE` on whether the adhesion area has
/// `collapsed`, each solve warm-started from the nearest one below it.
fn find_collapse(
    solve: &mut impl FnMut(f64, Option<&WarmStart>) -> Result<ExactSolution, crate::InvalidInput>,
    start: Option<&WarmStart>,
    collapsed: impl Fn(&ExactSolution) -> bool,
) -> Result<f64, crate::InvalidInput> {
    let (mut below, mut above) = COLLAPSE_RANGE;
    let low = solve(below, start)?;
    Ok(if collapsed(&low) {
        below
    } else if !collapsed(&solve(above, start)?) {
        above
    } else {
        let mut nearest = low.warm_start();
        for _ in 0..BISECTION_STEPS {
            let middle = 0.5 * (below + above);
            let solution = solve(middle, Some(&nearest))?;
            if collapsed(&solution) {
                above = middle;
            } else {
                below = middle;
                nearest = solution.warm_start();
            }
        }
        0.5 * (below + above)
    })
}

/// Richardson extrapolation along x of two slices solved at the same nodes (the coarse one
/// with `collapse_of` the fine one, [`slice_values`]) on grids of n_x and n_x/2 elements: the
/// solver's error is first order in the element length along the rolling direction, so
/// F∞ ≈ 2 F(n_x) − F(n_x/2) (docs/exact_table.md, "How it was made"). A force the extrapolation
/// puts outside the Coulomb disc, which the converged theory never leaves, is scaled back onto
/// it. τ = 1 (full sliding, the same quadrature in both) and the fold edges' symmetries are kept.
pub fn extrapolate(fine: &Slice, coarse: &Slice) -> Slice {
    assert!(
        fine.collapse == coarse.collapse && fine.values.len() == coarse.values.len(),
        "extrapolate: the coarse slice must be solved at the fine slice's nodes"
    );
    let mut values = Vec::with_capacity(fine.values.len());
    for (f, c) in fine.values.chunks_exact(3).zip(coarse.values.chunks_exact(3)) {
        let v: [f64; 3] = std::array::from_fn(|k| 2.0 * f64::from(f[k]) - f64::from(c[k]));
        let length = v[0].hypot(v[1]);
        let inside = if length > 1.0 { 1.0 / length } else { 1.0 };
        values.extend([v[0] * inside, v[1] * inside, v[2]].map(|x| x as f32));
    }
    Slice { values, collapse: fine.collapse.clone() }
}

/// The slices of a table (in the order i_ab, then i_ν), as [`assemble`] takes them, with the
/// values as stored (16-bit): to make a table over a longer a/b axis from a shorter one at the
/// same node spacing without solving its nodes again (`cargo fmu exact-table --extend-from`).
pub fn slices_of(table: &Table) -> Vec<Slice> {
    let [n_ab, n_nu, n_beta, n_alpha, n_t] = table.axes.counts;
    let rays = n_beta * n_alpha;
    (0..n_ab * n_nu)
        .map(|slice| Slice {
            values: table.nodes[slice * rays * n_t..(slice + 1) * rays * n_t]
                .iter()
                .flat_map(|node| [node[0], node[1], node[2]])
                .collect(),
            collapse: table.collapse[slice * rays..(slice + 1) * rays].to_vec(),
        })
        .collect()
}

/// `earlier` extended along a/b: its slices, then `new_slices` (the next a/b nodes of `axes`,
/// whose first nodes must be `earlier`'s), assembled, with `earlier`'s force counts kept where
/// the units allow (`Table::keeping_force_counts_of`, within the crate): counts not moved by a
/// second rounding.
pub fn extend(
    earlier: &Table,
    provenance: String,
    axes: TableAxes,
    new_slices: Vec<Slice>,
) -> Result<Table, TableError> {
    let mut slices = slices_of(earlier);
    slices.extend(new_slices);
    assemble(provenance, axes, slices)?.keeping_force_counts_of(earlier)
}

/// The table from its slices (in the order i_ab, then i_ν), with its provenance text.
pub fn assemble(provenance: String, axes: TableAxes, slices: Vec<Slice>) -> Result<Table, TableError> {
    let scales = scales(&axes);
    let collapse = slices.iter().flat_map(|slice| slice.collapse.iter().copied()).collect();
    let values = slices.into_iter().flat_map(|slice| slice.values).collect();
    Table::new(provenance, axes, scales, collapse, values)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slice(values: &[[f32; 3]]) -> Slice {
        Slice { values: values.iter().flatten().copied().collect(), collapse: vec![0.6] }
    }

    /// Values with an error A/n_x (the solver's first-order error along x) extrapolate to their
    /// limit; one the extrapolation puts outside the Coulomb disc is scaled back onto it, its
    /// direction and its moment kept; full sliding, the same on both grids, is unchanged.
    #[test]
    fn extrapolation_removes_a_first_order_error_and_stays_in_the_disc() {
        let limit = [[0.25, -0.5, 0.125], [0.75, 0.5, -0.25], [0.6, 0.8, 0.0]];
        let error = [[0.5, 0.25, -1.0], [1.0, 1.0, 0.5], [0.0, 0.0, 0.0]];
        let on =
            |n: f32| slice(&std::array::from_fn::<_, 3, _>(|i| std::array::from_fn(|k| limit[i][k] + error[i][k] / n)));
        let extrapolated = extrapolate(&on(80.0), &on(40.0));
        assert_eq!(extrapolated.collapse, vec![0.6]);
        for (node, expected) in extrapolated.values.chunks_exact(3).zip(limit) {
            for k in 0..3 {
                assert!((node[k] - expected[k]).abs() < 1e-6, "{node:?} against {expected:?}");
            }
        }
        // 2·(0.8, 0.7) − (0.7, 0.6) = (0.9, 0.8), |F| = 1.204: scaled back to length 1.
        let outside = extrapolate(&slice(&[[0.8, 0.7, 0.3]]), &slice(&[[0.7, 0.6, 0.1]]));
        let length = 0.9f64.hypot(0.8);
        let expected = [0.9 / length, 0.8 / length, 0.5];
        for (value, expected) in outside.values.iter().zip(expected) {
            assert!((f64::from(*value) - expected).abs() < 1e-6, "{:?}", outside.values);
        }
    }

    /// Extending keeps the earlier table's force counts wherever a τ node's force unit stays
    /// (quantizing its decoded values again moves some by a count), quantizes again where the
    /// new slices' forces make a unit grow, and refuses a table whose nodes are not the first.
    #[test]
    fn extending_keeps_the_earlier_counts_where_the_units_stay() {
        let axes = |n_ab: usize, high: f64| TableAxes {
            counts: [n_ab, 2, 3, 2, 5],
            a_over_b: (0.1, high),
            poisson_ratio: (0.0, 0.5),
        };
        // Per slice 30 nodes (β 3 × α 2 × τ 5); node i of a slice is at τ node i % 5.
        // Each τ node's largest |F| is 0.25 (exact in f32, so its unit decodes to itself); the
        // others are lengths a second rounding can move.
        let earlier_values: Vec<f32> = (0..120)
            .flat_map(|node| {
                let x = 0.009 * (node % 17) as f32 + 0.0004 * (node % 5) as f32;
                if node % 30 < 5 {
                    [0.25, 0.0, 0.01]
                } else {
                    [x, 0.7 * x + 0.001 * (node % 3) as f32, 0.01]
                }
            })
            .collect();
        let earlier =
            Table::new("earlier".into(), axes(2, 10.0), scales(&axes(2, 10.0)), vec![0.6; 24], earlier_values).unwrap();
        // The new slices: small forces, but at τ node 3 one larger than any earlier one there.
        let new_slice = |grow: bool| Slice {
            values: (0..30)
                .flat_map(|node| if grow && node == 8 { [0.5f32, 0.5, 0.0] } else { [0.01, 0.0, 0.0] })
                .collect(),
            collapse: vec![0.6; 6],
        };
        let longer = axes(3, 1000.0);
        let extended =
            extend(&earlier, "extended".into(), longer.clone(), vec![new_slice(true), new_slice(false)]).unwrap();
        let again = assemble(
            "again".into(),
            longer.clone(),
            [slices_of(&earlier), vec![new_slice(true), new_slice(false)]].concat(),
        )
        .unwrap();
        assert_eq!((slices_of(&extended).len(), slices_of(&earlier).len()), (6, 4));
        let unit = |table: &Table, m: usize| table.units[m][0];
        assert!(
            unit(&extended, 3) > unit(&earlier, 3)
                && (0..5).filter(|&m| m != 3).all(|m| unit(&extended, m) == unit(&earlier, m))
        );
        let (mut kept, mut moved_by_assembly) = (0, 0);
        for (node, (old, new)) in earlier.nodes.iter().zip(&extended.nodes).enumerate() {
            if node % 5 == 3 {
                // Quantized in the grown unit: within 2 of its counts (`quantize_force`).
                assert!((old[0] - new[0]).abs() as f64 <= 2.0 * unit(&extended, 3) + 1e-7, "node {node}");
                continue;
            }
            assert_eq!((old[0], old[1]), (new[0], new[1]), "node {node}: the earlier counts");
            kept += 1;
            moved_by_assembly += usize::from(again.nodes[node][..2] != old[..2]);
        }
        assert_eq!(kept, 96);
        assert!(moved_by_assembly > 0, "the test's values must be ones a second rounding moves");
        // The new a/b node's values are the new slices'.
        assert!((extended.nodes[120 + 8][0] - 0.5).abs() < 1e-4 && (extended.nodes[121][0] - 0.01).abs() < 1e-4);
        // Nodes that are not the first of the new axes are refused.
        let other = TableAxes { counts: [3, 2, 5, 2, 5], ..longer };
        let error = extend(&earlier, "x".into(), other.clone(), vec![]).unwrap_err().to_string();
        assert!(error.contains("are not the first of [3, 2, 5, 2, 5]") || error.contains("values for"), "{error}");
        let refused = again.keeping_force_counts_of(&Table { axes: other, ..earlier.clone() }).unwrap_err().to_string();
        assert!(refused.contains("nodes [3, 2, 5, 2, 5] are not the first of [3, 2, 3, 2, 5]"), "{refused}");
        // A table is its own prefix: its counts kept, itself again.
        assert_eq!(earlier.clone().keeping_force_counts_of(&earlier).unwrap().nodes, earlier.nodes);
        let shorter = earlier.clone().keeping_force_counts_of(&extended).unwrap_err().to_string();
        assert!(shorter.contains("nodes [3, 2, 3, 2, 5] are not the first of [2, 2, 3, 2, 5]"), "{shorter}");
    }

    #[test]
    #[should_panic(expected = "solved at the fine slice's nodes")]
    fn extrapolation_refuses_slices_of_different_nodes() {
        let mut other = slice(&[[0.1, 0.2, 0.3]]);
        other.collapse = vec![0.7];
        extrapolate(&slice(&[[0.1, 0.2, 0.3]]), &other);
    }
}
