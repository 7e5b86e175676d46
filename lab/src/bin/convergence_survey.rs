//! Does the exact solver converge? Cold solves of random contacts on one grid: how many stop at
//! the iteration limits, Newton steps (median, 99th percentile, max) and the time. The
//! contacts: a/b log-uniform in [10^−S, 10^S], ν uniform in [0, 0.5], the creepage direction
//! uniform on the sphere of (ξ/ξ*, η/η*, φ/φ*), its size log-uniform from 0.01 to 30 × the
//! characteristic creepage (the same kind as the trade report's held-out points).
//!
//! Run: `cargo run --release -p lab --bin convergence_survey -- N NX NY [SEED] [S]` (defaults:
//! seed 77, S = 1.2). Prints the summary line and every contact that did not converge.
use rayon::prelude::*;
use std::time::Instant;
use wheel_rail_contact::ExactTheory;

use lab::random_contacts::{random_contact, Uniform};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let argument = |i: usize, name: &str, default: Option<&str>| -> String {
        args.get(i)
            .map(String::as_str)
            .or(default)
            .unwrap_or_else(|| panic!("{name} missing: N NX NY [SEED] [S]"))
            .to_owned()
    };
    let count: usize = argument(0, "N", None).parse().expect("N");
    assert!(count > 0, "N must be at least 1");
    let longitudinal: usize = argument(1, "NX", None).parse().expect("NX");
    let lateral: usize = argument(2, "NY", None).parse().expect("NY");
    let mut uniform = Uniform::new(argument(3, "SEED", Some("77")).parse().expect("SEED"));
    let span: f64 = argument(4, "S", Some("1.2")).parse().expect("S");
    let cases: Vec<_> = (0..count).map(|_| random_contact(&mut uniform, span)).collect();
    let model = ExactTheory::new(longitudinal, lateral);
    let started = Instant::now();
    let solutions: Vec<_> = cases.par_iter().map(|input| model.solve(input).expect("a valid contact")).collect();
    let seconds = started.elapsed().as_secs_f64();
    let mut steps: Vec<usize> = solutions.iter().map(|solution| solution.iterations).collect();
    steps.sort_unstable();
    let unconverged: Vec<usize> = (0..count).filter(|&i| !solutions[i].converged).collect();
    println!(
        "{longitudinal} x {lateral}: {count} contacts (a/b 10^±{span}) in {seconds:.1} s on all cores; {} unconverged; \
         Newton steps median {}, 99th percentile {}, max {}",
        unconverged.len(),
        steps[count / 2],
        steps[count * 99 / 100],
        steps[count - 1]
    );
    for i in unconverged {
        println!("  not converged: {:?}", cases[i]);
    }
}
