//! Every rung of the ladder on one contact with creepage and spin, cheapest first: Kalker's
//! linear theory, Shen–Hedrick–Elkins, Polach, the exact theory's table, FASTSIM and the exact
//! theory itself, side by side with the time of one call (an illustration: the benchmarks,
//! `cargo bench --bench models`, measure it). `cargo run --release --example ladder`

use std::time::Instant;

use wheel_rail_contact::{
    ContactInput, CreepForceModel, ExactTable, ExactTheory, Fastsim, Flexibility, KalkerLinear, ModelChoice, Polach,
    ShenHedrickElkins, TractionBound,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let contact = ContactInput {
        creepage_longitudinal: 1e-3,
        creepage_lateral: -5e-4,
        spin_creepage: 0.5,
        normal_force: 100e3,
        semi_axis_a: 7.2e-3,
        semi_axis_b: 5.4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    };
    let ladder = [
        ModelChoice::KalkerLinear(KalkerLinear),
        ModelChoice::ShenHedrickElkins(ShenHedrickElkins),
        ModelChoice::Polach(Polach::default()),
        ModelChoice::ExactTable(ExactTable::new()?),
        ModelChoice::Fastsim(Fastsim::new(20, 20, TractionBound::Parabolic, Flexibility::ThreeBlended)?),
        ModelChoice::Exact(ExactTheory::new(200, 50)),
    ];
    let limit = contact.friction_limit();
    let reference = ExactTheory::new(200, 50).creep_forces(&contact)?;
    println!(
        "{:<20} {:>9} {:>9} {:>11} {:>12} {:>12}",
        "model", "F_x/μQ", "F_y/μQ", "M_z [N·m]", "|ΔF|/μQ", "one call [µs]"
    );
    for model in ladder {
        let started = Instant::now();
        let forces = model.creep_forces(&contact)?;
        let micros = started.elapsed().as_secs_f64() * 1e6;
        let error = (forces.force_longitudinal - reference.force_longitudinal)
            .hypot(forces.force_lateral - reference.force_lateral)
            / limit;
        let spin_moment = forces.spin_moment.map_or("—".to_owned(), |m| format!("{m:.2}"));
        println!(
            "{:<20} {:>9.4} {:>9.4} {:>11} {:>12.4} {:>12.1}",
            model.name(),
            forces.force_longitudinal / limit,
            forces.force_lateral / limit,
            spin_moment,
            error,
            micros
        );
        // Every friction-limited rung stays inside the Coulomb disc.
        if !matches!(model, ModelChoice::KalkerLinear(_)) {
            assert!(forces.adhesion_utilisation <= 1.0);
        }
    }
    // The table reproduces the theory it was made from to about 0.01 μQ.
    let table = ExactTable::new()?.creep_forces(&contact)?;
    assert!((table.force_lateral - reference.force_lateral).abs() < 0.01 * limit);
    Ok(())
}
