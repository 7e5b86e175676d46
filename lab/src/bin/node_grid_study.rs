//! The exact_table nodes' grid error: candidate solver grids for the table's nodes against the
//! converged theory, on random contacts near the knee of saturation with spin (where the
//! table's largest errors are; docs/exact_table.md, "How it was made"). The converged values
//! are extrapolated along x from 320 and 400 × 400 elements (the solver converges as 1/n_x). A
//! candidate `NXxNY` is the solver on that grid; `NXxNY,MXxMY` is the extrapolation along x
//! from the two, 2F(MX) − F(NX) for MX = 2 NX (the rule `cargo fmu exact-table` builds with).
//! A contact whose solve (reference or candidate) does not converge is left out and counted.
//!
//! Run: `cargo run --release -p lab --bin node_grid_study -- N SEED LOG10_LOW LOG10_HIGH GRIDS…`:
//! N contacts with a/b log-uniform between 10^LOG10_LOW and 10^LOG10_HIGH (≈ 10 s per contact
//! on two cores, most of it the reference). Without arguments: `40 4660 -1 1 80x20 40x20,80x20
//! 20x40,40x40`. Prints, per candidate and a/b band, max |ΔF|/(μQ) / max |ΔM_z|/(μQc), and the
//! median |ΔF|.
use rayon::prelude::*;
use wheel_rail_contact::{CreepForces, ExactTheory};

use lab::random_contacts::{contact_along, Uniform, FRICTION, MEAN_SEMI_AXIS, NORMAL_FORCE};

/// F_x/(μQ), F_y/(μQ), M_z/(μQc).
fn scaled(f: &CreepForces, l: f64, c: f64) -> [f64; 3] {
    [f.force_longitudinal / l, f.force_lateral / l, f.spin_moment.unwrap() / (l * c)]
}

fn grid(text: &str) -> (usize, usize) {
    let counts: Vec<usize> = text.split('x').map(|n| n.parse().expect("a grid NXxNY")).collect();
    (counts[0], counts[1])
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() {
        args = "40 4660 -1 1 80x20 40x20,80x20 20x40,40x40".split(' ').map(String::from).collect();
    }
    let n: usize = args[0].parse().expect("N");
    let mut uniform = Uniform::new(args[1].parse().expect("SEED"));
    let (low, high): (f64, f64) = (args[2].parse().expect("LOG10_LOW"), args[3].parse().expect("LOG10_HIGH"));
    let (l, c) = (FRICTION * NORMAL_FORCE, MEAN_SEMI_AXIS);
    let mut cases = Vec::new();
    for i in 0..n {
        let a_over_b = 10f64.powf(low + (high - low) * (i as f64 + uniform.sample()) / n as f64);
        let poisson_ratio = 0.5 * uniform.sample();
        let level = 0.4 + 1.6 * uniform.sample();
        let z = (0.3 + 0.7 * uniform.sample()) * if uniform.sample() < 0.5 { -1.0 } else { 1.0 };
        let angle = 2.0 * std::f64::consts::PI * uniform.sample();
        cases.push(contact_along(a_over_b, poisson_ratio, level, z, angle));
    }
    let solve = |(nx, ny): (usize, usize)| -> Vec<Option<[f64; 3]>> {
        let model = ExactTheory::new(nx, ny);
        cases.par_iter().map(|input| Some(scaled(&model.solve(input).ok()?.converged().ok()?.forces, l, c))).collect()
    };
    let extrapolate = |coarse: &[Option<[f64; 3]>], fine: &[Option<[f64; 3]>], n1: f64, n2: f64| {
        let combine = |a: &Option<[f64; 3]>, b: &Option<[f64; 3]>| {
            let (a, b) = ((*a)?, (*b)?);
            Some([0, 1, 2].map(|k| (n2 * b[k] - n1 * a[k]) / (n2 - n1)))
        };
        coarse.iter().zip(fine).map(|(a, b)| combine(a, b)).collect::<Vec<_>>()
    };
    let reference = extrapolate(&solve((320, 400)), &solve((400, 400)), 320.0, 400.0);
    let left_out = reference.iter().filter(|r| r.is_none()).count();
    let bands: &[(f64, f64)] = if high <= 0.0 {
        &[(0.1, 0.15), (0.15, 0.22), (0.22, 1.0 / 3.0), (1.0 / 3.0, 1.0)]
    } else {
        &[(0.1, 0.3), (0.3, 1.0), (1.0, 3.0), (3.0, 10.01)]
    };
    let band_names: Vec<String> = bands.iter().map(|(lo, hi)| format!("[{lo:.2}, {hi:.2})")).collect();
    println!(
        "{n} contacts ({left_out} left out: reference not converged; a candidate's own unconverged solves are \
         left out of its line); per a/b band {}: max F / max M_z; median F",
        band_names.join(" ")
    );
    for candidate in &args[4..] {
        let grids: Vec<(usize, usize)> = candidate.split(',').map(grid).collect();
        let values = match grids[..] {
            [single] => solve(single),
            [coarse, fine] => extrapolate(&solve(coarse), &solve(fine), coarse.0 as f64, fine.0 as f64),
            _ => panic!("{candidate}: one grid, or two to extrapolate along x"),
        };
        let mut line = format!("{candidate:>16}:");
        let mut all = Vec::new();
        for &(lo, hi) in bands {
            let (mut f, mut m) = (0.0f64, 0.0f64);
            for (i, input) in cases.iter().enumerate() {
                let a_over_b = input.semi_axis_a / input.semi_axis_b;
                let (Some(value), Some(reference)) = (values[i], reference[i]) else { continue };
                if a_over_b >= lo && a_over_b < hi {
                    let e = [0, 1, 2].map(|k| (value[k] - reference[k]).abs());
                    f = f.max(e[0].max(e[1]));
                    m = m.max(e[2]);
                    all.push(e[0].max(e[1]));
                }
            }
            line += &format!("  {f:.4}/{m:.4}");
        }
        all.sort_by(f64::total_cmp);
        line += &format!("  median {:.4}", all.get(all.len() / 2).copied().unwrap_or(f64::NAN));
        println!("{line}");
    }
}
