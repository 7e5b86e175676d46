//! The linearly implicit master with the contact units' directional derivatives against the
//! same master probing FMU states (issue 43, item 3; docs/coupling-stability.md): per speed and
//! communication step, whether the run stays bounded, its distance from the Gauss–Seidel run at
//! 10 µs (max |y − y_ref|/y0 over t = 10 ms, 20 ms, …), and the wall time per communication
//! step, one run after the other in one process. `polach`, creep relaxation off (where the
//! derivatives are the J the master needs), the coupling map's system and start.
//!
//! Run after `cargo build --release -p wheel-rail-contact-fmu -p wheelset`:
//! `cargo run --release -p lab --bin derivative_master`.

use std::time::Instant;

use lab::coupling::{release_fmus, run, Case, Master, Run};
use lab::wheelset_parameters::{document, number};

const SPEEDS: [f64; 3] = [1.0, 20.0, 80.0];
const STEPS: [f64; 4] = [1e-3, 2e-3, 5e-3, 10e-3];
const DURATION: f64 = 0.5;
const INITIAL_DISPLACEMENT: f64 = 3e-3;

fn main() -> Result<(), String> {
    let (wheelset, contact) = release_fmus()?;
    let wheel_load = 0.5 * number(&document(), "wheelset", "axle_load");
    let case = |speed, master, step| Case {
        rung: "polach",
        relaxation: false,
        master,
        speed,
        step,
        duration: DURATION,
        initial_displacement: INITIAL_DISPLACEMENT,
    };
    let distance = |run: &Run, reference: &Run| {
        run.displacements
            .iter()
            .zip(&reference.displacements)
            .map(|(y, y_ref)| (y - y_ref).abs() / INITIAL_DISPLACEMENT)
            .fold(0.0, f64::max)
    };
    println!("| speed [m/s] | step [ms] | master | bounded | distance | ms / step |\n|---|---|---|---|---|---|");
    for speed in SPEEDS {
        let reference = run(&wheelset, &contact, &case(speed, Master::GaussSeidel, 1e-5), wheel_load)?;
        for step in STEPS {
            for master in [Master::LinearlyImplicit, Master::LinearlyImplicitDerivatives] {
                let started = Instant::now();
                let result = run(&wheelset, &contact, &case(speed, master, step), wheel_load)?;
                let per_step = started.elapsed().as_secs_f64() / (DURATION / step) * 1e3;
                let (bounded, away) = match &result.unbounded {
                    None => ("yes".to_owned(), format!("{:.2e}", distance(&result, &reference))),
                    Some(end) => (format!("no ({end})"), "—".to_owned()),
                };
                println!("| {speed} | {} | {} | {bounded} | {away} | {per_step:.3} |", step * 1e3, master.name());
            }
        }
    }
    Ok(())
}
