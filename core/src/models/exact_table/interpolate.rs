//! Evaluation: from a contact to the table's cell, and the multilinear blend of its 32 nodes.

use super::coordinates::{fold, kink_fitted, IDENTITY_END};
use super::table::{AxisMap, Table, A_OVER_B_RANGE};
use super::zero_forces;
use crate::models::kalker_linear::linear_forces;
use crate::numerics::{magnitude, moves_negative, value, Scalar};
use crate::{ContactInput, CreepForces, InvalidInput};

/// Exact power of two the direction is scaled by before it is formed, so that creepages up to
/// f64::MAX times the scale factors (≤ 5) stay finite; undone in the size.
const DIRECTION_SCALE: f64 = 1.0 / 1024.0;

/// The forces for a validated input.
pub(crate) fn forces<D: Scalar>(table: &Table, input: &ContactInput<D>) -> Result<CreepForces<D>, InvalidInput> {
    if input.transmits_no_force() {
        return Ok(zero_forces());
    }
    let a_over_b = input.semi_axis_a / input.semi_axis_b;
    // The range's ends are accepted up to the rounding of a/b; `cell` keeps such values in the
    // end cell.
    if !table.covers_a_over_b(value(a_over_b)) {
        // (The message is static: the shipped table's range, or where another table's is.)
        let requirement = if table.axes.a_over_b == A_OVER_B_RANGE {
            "over semi_axis_b must lie in the exact_table's a/b range [0.1, 31.62] (10^-1 to 10^1.5)"
        } else {
            "over semi_axis_b must lie in the a/b range of the exact_table's table (Table::axes)"
        };
        return Err(InvalidInput::new("semi_axis_a", value(input.semi_axis_a), requirement)
            .involving([Some(("semi_axis_b", value(input.semi_axis_b))), None]));
    }
    let [ab_map, nu_map, beta_map, alpha_map, t_map] = &table.maps;
    let (i_ab, w_ab) = cell(a_over_b.ln(), ab_map);
    let (i_nu, w_nu) = cell(D::from(value(input.poisson_ratio)), nu_map);

    // Scale factors k, bilinear over the (a/b, ν) cell like the values.
    let n_nu = nu_map.nodes;
    let [lower_ab, upper_ab] = [i_ab, i_ab + 1].map(|i| adjacent(&table.scales, i * n_nu + i_nu));
    let blend2 = |[low, high]: [[f64; 3]; 2], c: usize| w_nu * (high[c] - low[c]) + low[c];
    let k: [D; 3] = std::array::from_fn(|c| {
        let (lower, upper) = (blend2(lower_ab, c), blend2(upper_ab, c));
        (upper - lower) * w_ab + lower
    });
    let c = (input.semi_axis_a * input.semi_axis_b).sqrt();
    let bounded = |x: D| if value(x).abs() <= 1e300 { x } else { D::from(1e300_f64.copysign(value(x))) };
    let direction = [
        bounded(input.creepage_longitudinal * DIRECTION_SCALE * k[0]),
        bounded(input.creepage_lateral * DIRECTION_SCALE * k[1]),
        bounded(input.spin_creepage * DIRECTION_SCALE * k[2] * c),
    ];
    // G/(μp₀) = 2πabG/(3μQ), the similarity scale of the creepages, over DIRECTION_SCALE.
    let size_factor = input.shear_modulus * (input.semi_axis_a * input.semi_axis_b)
        / (input.friction_coefficient * input.normal_force)
        * (2.0 * std::f64::consts::PI / 3.0 / DIRECTION_SCALE);
    let folded = fold(direction, size_factor);

    let (i_beta, w_beta) = cell(folded.beta, beta_map);
    let (i_alpha, w_alpha) = cell(folded.alpha, alpha_map);

    // The 16 corner rays of the (a/b, ν, β, α) cell: 8 pairs of rays adjacent along α.
    let [stride_ab, stride_nu, stride_beta, _] = table.ray_strides;
    let first_ray = i_ab * stride_ab + i_nu * stride_nu + i_beta * stride_beta + i_alpha;
    let weights = corner_weights(w_ab, w_nu, w_beta, w_alpha);
    // The query's collapse, interpolated like the values, and its kink-fitted size τ: every
    // corner's collapse sits on the node τ_c, and so does the query's (`coordinates.rs`).
    // Below IDENTITY_END τ = t whatever the collapse.
    let tau = if value(folded.t) <= IDENTITY_END {
        folded.t
    } else {
        // Four partial sums (by β side, then α side): independent chains instead of one of 16
        // additions.
        let mut partial = [[D::from(0.0); 2]; 2];
        for (pair, (&offset, pair_weights)) in table.alpha_pairs.iter().zip(&weights).enumerate() {
            let collapse = adjacent(&table.collapse, first_ray + offset);
            for ((sum, &f), t_c) in partial[pair % 2].iter_mut().zip(pair_weights).zip(collapse) {
                *sum += f * f64::from(t_c);
            }
        }
        kink_fitted(folded.t, (partial[0][0] + partial[0][1]) + (partial[1][0] + partial[1][1]))
    };
    let (i_t, w_t) = cell(tau, t_map);
    // In the first cell (inside the identity piece, τ = t) the forces are linear in s (see
    // `small_creepage`): it needs the node t₁ alone.
    let w_t = if i_t == 0 { D::from(1.0) } else { w_t };
    let sum = blend(table, first_ray, &weights, i_t, w_t);
    let (resize, utilisation) = chord_correction(sum[0], sum[1], sum[3]);
    let limit = input.friction_limit() * folded.sign_all;
    let lateral_limit = limit * folded.sign_lateral;
    let forces = [sum[0] * resize * limit, sum[1] * resize * lateral_limit, sum[2] * lateral_limit * c];
    if let Some(forces) = small_creepage(input, forces, folded.t, i_t == 0, t_map.nodes) {
        return Ok(CreepForces::new(forces[0], forces[1], Some(forces[2]), input.friction_limit()));
    }
    // |F|/(μQ) is known: the corrected length.
    Ok(CreepForces {
        force_longitudinal: forces[0],
        force_lateral: forces[1],
        spin_moment: Some(forces[2]),
        adhesion_utilisation: utilisation,
    })
}

/// Interpolating the components of forces of different direction shortens the result (the
/// chord of an arc): in full slip without spin, where |F| = μQ exactly, by 0.3 % of μQ between α
/// nodes. Where the 32 interpolated nodes' forces are nearly parallel — the interpolated force
/// at least 99 % as long as the interpolated lengths (`size`) — its length is taken from the
/// interpolated lengths instead; below 95 % (forces of opposing directions, where the force
/// passes through zero between nodes) the components are left alone; between, the two blend
/// linearly, so the result is continuous. Returns the factor for both components and the
/// corrected length. The length never exceeds `size`, a convex combination of node lengths ≤ 1,
/// so |F| ≤ μQ still holds.
///
/// Where the interpolated lengths themselves nearly vanish (below 2 % of μQ; 1 % and less gets
/// no correction, between the two it fades in linearly) the correction is left out: there it
/// is worth at most 0.3 % of 0.02 μQ, but it divides by a vanishing length. At pure spin in full
/// sliding (F ≈ 1e-9 μQ, every node's force nearly 0 but those off pure spin) that ratio turned
/// the cell's first-order change of node lengths into ∂F_y/∂ξ ≈ ∂F_x/∂ξ, 350 μQ per unit ξ,
/// over a bump 1e-9 μQ high and 1e-11 wide in ξ: the exact derivative of a feature no
/// difference sees.
fn chord_correction<D: Scalar>(x: D, y: D, size: D) -> (D, D) {
    let length = magnitude(x, y);
    let (l, s) = (value(length), value(size));
    // s = l (every node's force parallel, e.g. pure spin, where all α rays are one contact) and
    // s at the start of the fade: the branch is the side the derivative's direction moves to,
    // consistent with the value.
    if !(l > CHORD_BLEND_START * s && moves_negative(length - size) && !moves_negative(size - CHORD_SIZE_START)) {
        return (D::from(1.0), length);
    }
    if l >= CHORD_BLEND_END * s && s >= CHORD_SIZE_END {
        return (size / length, size);
    }
    let one = D::from(1.0);
    let by_ratio = if l >= CHORD_BLEND_END * s {
        one
    } else {
        (length / size - CHORD_BLEND_START) / (CHORD_BLEND_END - CHORD_BLEND_START)
    };
    let by_size =
        if s >= CHORD_SIZE_END { one } else { (size - CHORD_SIZE_START) / (CHORD_SIZE_END - CHORD_SIZE_START) };
    let corrected = length + (size - length) * (by_ratio * by_size);
    (corrected / length, corrected)
}

/// The ratio |Σ w F_i| / Σ w |F_i| from which [`chord_correction`] starts, and where it is full.
const CHORD_BLEND_START: f64 = 0.95;
const CHORD_BLEND_END: f64 = 0.99;
/// The interpolated length Σ w |F_i| / μQ from which [`chord_correction`] starts, and where it
/// is full.
const CHORD_SIZE_START: f64 = 0.01;
const CHORD_SIZE_END: f64 = 0.02;

/// The end of the blend into Kalker's linear theory, in t: s_lin = (1/31)² ≈ 1.04e-3, about
/// 0.1 % of saturation. Fixed, so that the small-creepage behaviour does not depend on the t
/// grid; compared in t, so that larger creepages pay no division for it.
const LINEAR_BLEND_END: f64 = 1.0 / 32.0;

/// The small creepages, where the forces are linear in the creepages to within 1e-3 of
/// themselves: `None` above both the first t cell (0 < s < s₁) and s_lin. Multilinear in t the
/// first cell would be √s-shaped (s ∝ t² near 0); it is linear instead, F_table = (s/s₁) F(t₁).
/// Below s_lin the table blends into Kalker's linear theory ([`crate::KalkerLinear`]), the exact
/// theory's own small-creepage limit:
///
/// ```text
/// F = (s/s_lin) F_table + (1 − s/s_lin) F_Kalker(ξ, η, φ),
/// ```
///
/// continuous at s_lin and with Kalker's slope at zero. Our solver's nodes are within 0.2–1.5 %
/// of Kalker's C11, C22 and C23 (docs/exact_table.md), a difference of < 2e-5 μQ at s_lin.
fn small_creepage<D: Scalar>(
    input: &ContactInput<D>,
    interpolated: [D; 3],
    t: D,
    first_cell: bool,
    t_nodes: usize,
) -> Option<[D; 3]> {
    if !first_cell && value(t) >= LINEAR_BLEND_END {
        return None;
    }
    // s = (t/(1 − t))², the L1 size of the scaled creepages.
    let size = |t: f64| (t / (1.0 - t)).powi(2);
    let root = t / (-t + 1.0);
    let s = root * root;
    let table =
        if first_cell { interpolated.map(|f| f * (s / size(1.0 / (t_nodes - 1) as f64))) } else { interpolated };
    if value(t) >= LINEAR_BLEND_END {
        return Some(table);
    }
    let linear = linear_forces(input);
    let linear = [linear.force_longitudinal, linear.force_lateral, linear.spin_moment.unwrap_or(D::from(0.0))];
    let weight = s / size(LINEAR_BLEND_END);
    Some(std::array::from_fn(|k| table[k] * weight + linear[k] * (-weight + 1.0)))
}

/// The weights of the 16 corner rays of an (a/b, ν, β, α) cell, in the order of
/// [`Table::alpha_pairs`]: for each (a/b, ν, β) corner, its rays at the lower and the upper α node.
fn corner_weights<D: Scalar>(w_ab: D, w_nu: D, w_beta: D, w_alpha: D) -> [[D; 2]; 8] {
    let across = |w: D| [D::from(1.0) - w, w];
    std::array::from_fn(|pair| {
        let f_spin = across(w_ab)[pair / 4] * across(w_nu)[pair / 2 % 2] * across(w_beta)[pair % 2];
        across(w_alpha).map(|f_alpha| f_spin * f_alpha)
    })
}

/// The weighted sum of the 32 nodes of a cell: its 16 corner rays (the pairs of
/// [`Table::alpha_pairs`] from `first_ray` on, weighted by [`corner_weights`]), each at its
/// nodes `i_t` and `i_t` + 1, the upper one weighted by `w_t`.
fn blend<D: Scalar>(table: &Table, first_ray: usize, weights: &[[D; 2]; 8], i_t: usize, w_t: D) -> [D; 4] {
    let n_t = table.maps[4].nodes;
    // Two sums, over the lower and the upper α rays: two independent chains of 8 additions
    // instead of one of 16.
    let mut sums = [[[D::from(0.0); 4]; 2]; 2];
    for (&offset, pair_weights) in table.alpha_pairs.iter().zip(weights) {
        let lower_ray = (first_ray + offset) * n_t + i_t;
        for ((sum, &weight), node) in sums.iter_mut().zip(pair_weights).zip([lower_ray, lower_ray + n_t]) {
            let [low, high] = adjacent(&table.nodes, node);
            for k in 0..4 {
                sum[0][k] += weight * f64::from(low[k]);
                sum[1][k] += weight * f64::from(high[k]);
            }
        }
    }
    std::array::from_fn(|k| {
        let (below, above) = (sums[0][0][k] + sums[1][0][k], sums[0][1][k] + sums[1][1][k]);
        (above - below) * w_t + below
    })
}

/// `values[index]` and `values[index + 1]`, with one range check for both.
fn adjacent<T: Copy>(values: &[T], index: usize) -> [T; 2] {
    let pair: &[T; 2] = values[index..index + 2].try_into().expect("a range of two");
    *pair
}

/// The cell of `x` along `axis` and the fraction across it, both kept in the cell (rounding
/// only: callers bring x into the axis's range).
fn cell<D: Scalar>(x: D, axis: &AxisMap) -> (usize, D) {
    let position = (x - axis.origin) * axis.inverse_step;
    // Truncation is the floor here (≥ 0), without a libm call; NaN cannot occur (finite inputs).
    // u32: its conversion to f64 is one instruction (usize's is several on x86-64).
    let index = (value(position).max(0.0) as u32).min(axis.nodes as u32 - 2);
    let fraction = position - f64::from(index);
    // The value is kept in the cell, the rate is not dropped: at the ends of an axis (a/b at
    // the table's edge, α = 1 where ξ = 0) the derivative is the end cell's, the one-sided
    // derivative from inside, like the value (a constant here gave a/b's derivative of the
    // values but not of the weights: ∂M_z/∂a 0.709 at a/b = 0.1 against 0.404 just inside).
    let clamped = value(fraction).clamp(0.0, 1.0);
    let fraction = fraction.with_value(clamped);
    // On a node the cell is the one the derivative's direction moves into (the cell above for
    // a plain value): the same side as the folds take (`coordinates::fold`), so that where a
    // node and a fold coincide (β = 0 and |u_φ|) the derivative is one side's, not a mix.
    if clamped == 0.0 && index > 0 && fraction.rate() < 0.0 {
        return (index as usize - 1, fraction + 1.0);
    }
    (index as usize, fraction)
}

#[cfg(test)]
mod tests {
    use num_dual::Dual64;

    use super::*;

    /// The chord correction works at every size of the interpolated lengths, not only in full
    /// slip (s = 1): nearly parallel forces (l ≥ 0.99 s) get the interpolated length, opposing
    /// ones (l ≤ 0.95 s) are left alone, and between, the blend is continuous.
    #[test]
    fn the_chord_correction_restores_the_interpolated_length_at_any_size() {
        for size in [0.2, 0.5, 1.0] {
            let (x, y) = (0.6 * 0.995 * size, 0.8 * 0.995 * size); // l = 0.995 s
            assert_eq!(chord_correction(x, y, size), (size / (0.995 * size), size));
            let (x, y) = (0.6 * 0.9 * size, 0.8 * 0.9 * size); // l = 0.9 s
            assert_eq!(chord_correction(x, y, size), (1.0, 0.9 * size));
            for (at, weight) in [(0.95, 0.0), (0.97, 0.5), (0.99, 1.0)] {
                let l = at * size;
                let (factor, length) = chord_correction(0.6 * l, 0.8 * l, size);
                let expected = l + (size - l) * weight;
                assert!((length - expected).abs() < 1e-12 && (factor * l - expected).abs() < 1e-12, "{size} {at}");
            }
        }
    }

    /// Where the interpolated lengths nearly vanish the correction fades out: none at 1 % of μQ
    /// and below, half at 1.5 %, full from 2 %, continuous through both ends.
    #[test]
    fn the_chord_correction_fades_out_where_the_forces_vanish() {
        for (size, weight) in [(1e-9, 0.0), (0.005, 0.0), (0.01, 0.0), (0.015, 0.5), (0.02, 1.0), (0.03, 1.0)] {
            let l = 0.995 * size;
            let (factor, length) = chord_correction(0.6 * l, 0.8 * l, size);
            let expected = l + (size - l) * weight;
            assert!((length - expected).abs() < 1e-15 * size, "{size}: {length} against {expected}");
            assert!((factor * l - expected).abs() < 1e-15 * size, "{size}: factor {factor}");
        }
        // Half-way through both blends: the weights multiply.
        let (size, l) = (0.015, 0.97 * 0.015);
        let (_, length) = chord_correction(0.6 * l, 0.8 * l, size);
        assert!((length - (l + (size - l) * 0.25)).abs() < 1e-15, "{length}");
    }

    /// On a node the cell is the one the direction moves into: the rate decides, the value
    /// stays on the node.
    #[test]
    fn on_a_node_the_direction_picks_the_cell() {
        let axis = AxisMap { origin: 0.0, inverse_step: 4.0, nodes: 5 };
        let (up, fraction_up) = cell(Dual64::new(0.5, 1.0), &axis);
        let (down, fraction_down) = cell(Dual64::new(0.5, -1.0), &axis);
        assert_eq!((up, fraction_up.re, fraction_up.eps), (2, 0.0, 4.0));
        assert_eq!((down, fraction_down.re, fraction_down.eps), (1, 1.0, -4.0));
        // A value a rounding below the axis stays in the first cell at 0, its rate kept.
        let (first, fraction) = cell(Dual64::new(-1e-17, 1.0), &axis);
        assert_eq!((first, fraction.re, fraction.eps), (0, 0.0, 4.0));
    }
}
