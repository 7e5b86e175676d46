//! Would a kink-fitted size coordinate remove `exact_table`'s largest errors? An experiment for
//! the next table (docs/exact_table.md, "Why the maxima sit where they do").
//!
//! Along a ray of growing creepage the exact theory's adhesion area can collapse within a tiny
//! step of t (29 % → 2.7 % of the contact), a kink that multilinear interpolation smears. The
//! candidate: per ray (a/b, ν, β, α) find t_c, where the adhesion fraction falls below 15 %, and
//! place the ray's nodes uniformly in τ, a piecewise-linear map of t sending t_c to the fixed
//! node τ_c = 27/48; evaluate a query at τ(t; t_c interpolated from its 16 corner rays), where
//! every corner's kink sits on the same node.
//!
//! For each query point this solves the 16 corner rays of the second table's (a/b, ν, β, α)
//! cell directly (80 × 20 elements, the table's grid; 49 nodes in t or τ) and prints the error
//! of both interpolants against the solver at the point itself, in μQ (max of F_x, F_y):
//! `cargo run --release -p lab --bin kink_alignment_experiment -- 60` (random points, ≈ 80 s), or
//! `-- 0 worst` (the nine largest errors of the second table on 1000 held-out points); with
//! `--a-over-b-nodes 29` on the third table's a/b nodes (`-- 300 worst --a-over-b-nodes 29`,
//! ≈ 10 min). The third table is built on this experiment (docs/exact_table.md).

use rayon::prelude::*;
use wheel_rail_contact::{ContactInput, ExactTheory, KalkerCoefficients};

use lab::random_contacts::{Uniform, FRICTION, MEAN_SEMI_AXIS, NORMAL_FORCE, SHEAR_MODULUS};

/// The second table's node counts along ln(a/b), ν, β, α, and t (the a/b count can be changed:
/// `--a-over-b-nodes 29` is the third table's).
const COUNTS: [usize; 5] = [15, 4, 41, 13, 49];
/// Adhesion fraction below which a ray counts as past its collapse.
const COLLAPSED: f64 = 0.15;
/// The node every ray's collapse is mapped to.
const TAU_C: f64 = 27.0 / 48.0;

/// A point in the table's coordinates (a/b, ν, α, β, t).
type Point = [f64; 5];

/// The contact at a point, with the table's scaling u = k · creepage · G/(μp₀).
fn contact([a_over_b, nu, alpha, beta, t]: Point) -> ContactInput {
    let (shear_modulus, c) = (SHEAR_MODULUS, MEAN_SEMI_AXIS);
    let size = (t / (1.0 - t)).powi(2);
    let u = [(1.0 - alpha) * (1.0 - beta.abs()) * size, alpha * (1.0 - beta.abs()) * size, beta * size];
    let (a, b) = (c * a_over_b.sqrt(), c / a_over_b.sqrt());
    let p0 = 3.0 * NORMAL_FORCE / (2.0 * std::f64::consts::PI * a * b);
    let k = KalkerCoefficients::new(a_over_b, nu);
    let c33 = KalkerCoefficients::spin_moment_c33(a_over_b, nu);
    let unit = 2.0 * std::f64::consts::PI / 3.0 * FRICTION * p0 / shear_modulus;
    ContactInput {
        creepage_longitudinal: u[0] * unit / k.c11,
        creepage_lateral: u[1] * unit / k.c22,
        spin_creepage: u[2] * unit / ((k.c23 + c33) * c),
        normal_force: NORMAL_FORCE,
        semi_axis_a: a,
        semi_axis_b: b,
        friction_coefficient: FRICTION,
        shear_modulus,
        poisson_ratio: nu,
    }
}

/// (F_x, F_y)/(μQ) and the adhesion fraction of the contact area.
fn solve(point: Point) -> ([f64; 2], f64) {
    let solution = ExactTheory::new(80, 20).solve(&contact(point)).expect("valid contact");
    let f = solution.forces;
    let limit = FRICTION * NORMAL_FORCE;
    let adhesion = solution.adhesion_area / (solution.adhesion_area + solution.slip_area);
    ([f.force_longitudinal / limit, f.force_lateral / limit], adhesion)
}

/// t of the ray's collapse (bisection to 6e-5), 0.97 where it never falls below 15 %.
fn collapse(ray: [f64; 4]) -> f64 {
    let at = |t: f64| solve([ray[0], ray[1], ray[2], ray[3], t]).1;
    let (mut below, mut above) = (0.05, 0.97);
    if at(above) >= COLLAPSED {
        return above;
    }
    for _ in 0..14 {
        let middle = 0.5 * (below + above);
        if at(middle) >= COLLAPSED {
            below = middle;
        } else {
            above = middle;
        }
    }
    0.5 * (below + above)
}

fn tau_of(t: f64, t_c: f64) -> f64 {
    if t <= t_c {
        t / t_c * TAU_C
    } else {
        1.0 - (1.0 - t) / (1.0 - t_c) * (1.0 - TAU_C)
    }
}

fn t_of(tau: f64, t_c: f64) -> f64 {
    if tau <= TAU_C {
        tau / TAU_C * t_c
    } else {
        1.0 - (1.0 - tau) / (1.0 - TAU_C) * (1.0 - t_c)
    }
}

/// The 16 corner rays (a/b, ν, α, β) of the point's cell and their multilinear weights.
fn corners([a_over_b, nu, alpha, beta, _]: Point, a_over_b_nodes: usize) -> Vec<(f64, [f64; 4])> {
    let counts = [a_over_b_nodes, COUNTS[1], COUNTS[2], COUNTS[3]];
    let low = [0.1f64.ln(), 0.0, -1.0, 0.0];
    let high = [10f64.ln(), 0.5, 1.0, 1.0];
    let coordinates = [a_over_b.ln(), nu, beta, alpha];
    let node = |d: usize, i: usize| low[d] + i as f64 * (high[d] - low[d]) / (counts[d] - 1) as f64;
    let cell: Vec<(usize, f64)> = (0..4)
        .map(|d| {
            let position = (coordinates[d] - low[d]) / (high[d] - low[d]) * (counts[d] - 1) as f64;
            let index = (position.floor() as usize).min(counts[d] - 2);
            (index, position - index as f64)
        })
        .collect();
    (0..16)
        .map(|corner| {
            let mut weight = 1.0;
            let mut at = [0.0; 4];
            for (d, &(index, fraction)) in cell.iter().enumerate() {
                let upper = (corner >> d) & 1;
                weight *= if upper == 1 { fraction } else { 1.0 - fraction };
                at[d] = node(d, index + upper);
            }
            (weight, [at[0].exp(), at[1], at[3], at[2]])
        })
        .collect()
}

/// Errors of the uniform-t and the kink-fitted interpolants at one point.
fn errors(point: Point, a_over_b_nodes: usize) -> (f64, f64) {
    let rays = corners(point, a_over_b_nodes);
    let collapses: Vec<f64> = rays.iter().map(|&(_, ray)| collapse(ray)).collect();
    let query_collapse: f64 = rays.iter().zip(&collapses).map(|((w, _), t_c)| w * t_c).sum();
    let step = 1.0 / (COUNTS[4] - 1) as f64;
    let bracket = |x: f64| ((x / step).floor(), x / step - (x / step).floor());
    let ((i_t, w_t), (i_tau, w_tau)) = (bracket(point[4]), bracket(tau_of(point[4], query_collapse)));
    let (mut uniform, mut fitted) = ([0.0; 2], [0.0; 2]);
    for (&(weight, [a_over_b, nu, alpha, beta]), &t_c) in rays.iter().zip(&collapses) {
        let at = |t: f64| solve([a_over_b, nu, alpha, beta, t]).0;
        let (u0, u1) = (at(i_t * step), at((i_t + 1.0) * step));
        let (f0, f1) = (at(t_of(i_tau * step, t_c)), at(t_of((i_tau + 1.0) * step, t_c)));
        for k in 0..2 {
            uniform[k] += weight * (u0[k] * (1.0 - w_t) + u1[k] * w_t);
            fitted[k] += weight * (f0[k] * (1.0 - w_tau) + f1[k] * w_tau);
        }
    }
    let exact = solve(point).0;
    let error = |v: [f64; 2]| (v[0] - exact[0]).abs().max((v[1] - exact[1]).abs());
    let spread =
        collapses.iter().copied().fold(f64::MIN, f64::max) - collapses.iter().copied().fold(f64::MAX, f64::min);
    println!(
        "a/b {:.3} ν {:.2} α {:.3} β {:+.3} t {:.3}: t_c {query_collapse:.3} (spread over corners {spread:.3}); \
         uniform t {:.4}, kink-fitted {:.4}",
        point[0],
        point[1],
        point[2],
        point[3],
        point[4],
        error(uniform),
        error(fitted)
    );
    (error(uniform), error(fitted))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let random: usize = args.first().map_or(60, |n| n.parse().expect("number of random points"));
    let a_over_b_nodes = args
        .iter()
        .position(|a| a == "--a-over-b-nodes")
        .map_or(COUNTS[0], |i| args[i + 1].parse().expect("--a-over-b-nodes N"));
    let mut points: Vec<Point> = if args.get(1).map(String::as_str) == Some("worst") {
        vec![
            [2.007, 0.43, 0.527, -0.564, 0.617],
            [2.018, 0.16, 0.502, -0.661, 0.589],
            [0.670, 0.13, 0.793, -0.816, 0.633],
            [5.869, 0.12, 0.021, 0.922, 0.509],
            [6.166, 0.12, 0.347, -0.378, 0.597],
            [0.245, 0.34, 0.402, -0.525, 0.798],
            [0.323, 0.44, 0.601, 0.595, 0.938],
            [0.106, 0.29, 0.009, -0.580, 0.840],
            [6.146, 0.46, 0.494, -0.749, 0.674],
        ]
    } else {
        Vec::new()
    };
    let mut uniform = Uniform::new(4242);
    let mut next = || uniform.sample();
    for _ in 0..random {
        points.push([10f64.powf(2.0 * next() - 1.0), 0.5 * next(), next(), 2.0 * next() - 1.0, 0.3 + 0.6 * next()]);
    }
    let results: Vec<(f64, f64)> = points.par_iter().map(|&point| errors(point, a_over_b_nodes)).collect();
    let summary = |mut e: Vec<f64>| {
        e.sort_by(f64::total_cmp);
        format!("median {:.4}, max {:.4}", e[e.len() / 2], e[e.len() - 1])
    };
    println!(
        "{} points: uniform t {}; kink-fitted {}",
        results.len(),
        summary(results.iter().map(|r| r.0).collect()),
        summary(results.iter().map(|r| r.1).collect())
    );
}
