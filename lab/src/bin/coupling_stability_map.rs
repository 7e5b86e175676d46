//! The coupling stability map of issue 28 (docs/coupling-stability.md): the wheelset FMU on the
//! cited primary suspension (data/wheelset/passenger_coach.toml) and two contact units
//! (S1002/UIC60, half the axle load each), started y0 = 3 mm off centre and run for
//! [`DURATION`] with a fixed communication step, per creep-force rung, creep relaxation off/on,
//! master ([`Master`]), speed and step. Written as CSV to stdout, one line per run:
//!
//! - `bounded`: the run reached the end with every FMU call OK, |y| ≤ 2 y0 and the spin
//!   creepage |Ω r_c/V − 1| ≤ 10 % throughout (`lab::coupling`); the cited suspension makes the
//!   wheelset stable at every speed here (no critical speed below 400 m/s, docs/wheelset.md),
//!   so an unbounded run is the coupling's doing;
//! - `distance`: max over t = 10 ms, 20 ms, … of |y(t) − y_ref(t)| / y0, y_ref the run of the
//!   same rung, option and speed at the reference step [`REFERENCE_STEP`] with the Gauss–Seidel
//!   master (bounded runs only);
//! - `peak_spin_creepage`: max |Ω r_c/V − 1| over the run;
//! - `end`: why and when an unbounded run stopped.
//!
//! The reference runs are lines too (step 1e-5 s, distance 0). An optional argument, a rung's
//! name, maps that rung only.
//!
//! The binaries are the ones `cargo fmu package` zips (target/release, with the repository's
//! model descriptions and data/ as the contact FMU's resources/): `cargo build --release -p wheel-rail-contact-fmu -p wheelset`, then
//! `cargo run --release -p lab --bin coupling_stability_map > docs/coupling-stability/map.csv`.
//! `RAYON_NUM_THREADS` bounds the threads.

use std::time::Instant;

use lab::coupling::{release_fmus, run, Case, Master, Run};
use lab::wheelset_parameters::{document, number};
use rayon::prelude::*;

const SPEEDS: [f64; 7] = [1.0, 2.0, 5.0, 10.0, 20.0, 40.0, 80.0];
/// Communication steps \[s\]: 0.05–10 ms, each dividing `lab::coupling::SAMPLE_INTERVAL`.
const STEPS: [f64; 8] = [0.05e-3, 0.1e-3, 0.2e-3, 0.5e-3, 1e-3, 2e-3, 5e-3, 10e-3];
const RUNGS: [&str; 3] = ["kalker_linear", "polach", "exact_table"];
/// The reference run's step \[s\]: a fifth of the smallest creep time constant at 1 m/s
/// (the spin's, I_s V/Σ f11 r² ≈ 27 µs, docs/coupling-stability.md).
const REFERENCE_STEP: f64 = 0.01e-3;
/// Simulated time \[s\].
const DURATION: f64 = 0.5;
/// The start off centre \[m\].
const INITIAL_DISPLACEMENT: f64 = 3e-3;

fn distance(run: &Run, reference: &Run) -> f64 {
    run.displacements
        .iter()
        .zip(&reference.displacements)
        .map(|(y, y_ref)| (y - y_ref).abs() / INITIAL_DISPLACEMENT)
        .fold(0.0, f64::max)
}

fn main() -> Result<(), String> {
    let (wheelset, contact) = release_fmus()?;
    let wheel_load = 0.5 * number(&document(), "wheelset", "axle_load");
    let only = std::env::args().nth(1);

    let settings: Vec<(&str, bool, f64)> = RUNGS
        .iter()
        .filter(|rung| only.as_deref().is_none_or(|only| only == **rung))
        .flat_map(|&rung| {
            [false, true].into_iter().flat_map(move |relaxation| SPEEDS.map(|speed| (rung, relaxation, speed)))
        })
        .collect();
    let case = |(rung, relaxation, speed): (&'static str, bool, f64), master, step| Case {
        rung,
        relaxation,
        master,
        speed,
        step,
        duration: DURATION,
        initial_displacement: INITIAL_DISPLACEMENT,
    };
    let started = Instant::now();
    let references: Vec<Run> = settings
        .par_iter()
        .map(|&setting| {
            let reference = run(&wheelset, &contact, &case(setting, Master::GaussSeidel, REFERENCE_STEP), wheel_load)?;
            eprintln!("{:6.0} s reference {setting:?}: {:?}", started.elapsed().as_secs_f64(), reference.unbounded);
            Ok(reference)
        })
        .collect::<Result<_, String>>()?;
    let runs: Vec<(usize, Case)> = (0..settings.len())
        .flat_map(|s| Master::ALL.into_iter().flat_map(move |master| STEPS.map(|step| (s, master, step))))
        .map(|(s, master, step)| (s, case(settings[s], master, step)))
        .collect();
    let results: Vec<(usize, Case, Run)> = runs
        .into_par_iter()
        .map(|(s, case)| {
            let result = run(&wheelset, &contact, &case, wheel_load)?;
            eprintln!("{:6.0} s {case:?}: {:?}", started.elapsed().as_secs_f64(), result.unbounded);
            Ok((s, case, result))
        })
        .collect::<Result<_, String>>()?;

    println!("rung,relaxation,master,speed_m_per_s,step_s,bounded,distance,peak_spin_creepage,end");
    let reference_rows = references
        .iter()
        .enumerate()
        .map(|(s, reference)| (s, case(settings[s], Master::GaussSeidel, REFERENCE_STEP), reference.clone()));
    for (s, case, result) in reference_rows.chain(results) {
        let (bounded, distance) = match &result.unbounded {
            None => ("true", format!("{:.4e}", distance(&result, &references[s]))),
            Some(_) => ("false", String::new()),
        };
        println!(
            "{},{},{},{},{:e},{bounded},{distance},{:.4e},{}",
            case.rung,
            if case.relaxation { "on" } else { "off" },
            case.master.name(),
            case.speed,
            case.step,
            result.peak_spin_creepage,
            result.unbounded.unwrap_or_default().replace(',', ";")
        );
    }
    for (setting, reference) in settings.iter().zip(&references) {
        if let Some(reason) = &reference.unbounded {
            return Err(format!("the reference run {setting:?} is not bounded: {reason}"));
        }
    }
    Ok(())
}
