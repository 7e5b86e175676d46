//! One contact: `exact_table` against the exact solver on the table's node grid (80 × 20) and on
//! finer grids, to tell the node grid's error from the interpolation's (docs/exact_table.md,
//! "Accuracy"). The contact is the trade report's: Q = 80 kN, μ = 0.3, G = 82 GPa, c = √(ab) = 5 mm.
//!
//! Run: `cargo run --release -p lab --bin exact_table_at_point -- <a/b> <ν> <ξ> <η> <φ [1/m]>`,
//! e.g. `-- 3.787 0.080 1.551e-3 8.044e-3 -1.220`.

use wheel_rail_contact::{ContactInput, CreepForceModel, CreepForces, ExactTable, ExactTheory};

const NORMAL_FORCE: f64 = 80e3;
const FRICTION: f64 = 0.3;
const SHEAR_MODULUS: f64 = 82e9;
const MEAN_SEMI_AXIS: f64 = 5e-3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = std::env::args().skip(1).map(|a| a.parse::<f64>()).collect::<Result<Vec<_>, _>>()?;
    let [a_over_b, poisson_ratio, xi, eta, phi] = args[..] else {
        return Err("arguments: <a/b> <ν> <ξ> <η> <φ [1/m]>".into());
    };
    // a/b about c = √(ab).
    let (semi_axis_a, semi_axis_b) = (MEAN_SEMI_AXIS * a_over_b.sqrt(), MEAN_SEMI_AXIS / a_over_b.sqrt());
    let (normal_force, friction_coefficient, shear_modulus) = (NORMAL_FORCE, FRICTION, SHEAR_MODULUS);
    let (creepage_longitudinal, creepage_lateral, spin_creepage) = (xi, eta, phi);
    let input = ContactInput {
        creepage_longitudinal,
        creepage_lateral,
        spin_creepage,
        normal_force,
        semi_axis_a,
        semi_axis_b,
        friction_coefficient,
        shear_modulus,
        poisson_ratio,
    };
    let limit = FRICTION * NORMAL_FORCE;
    let row = |name: &str, f: &CreepForces| {
        println!(
            "{name:>16}: F_x/(μQ) {:+.4}  F_y/(μQ) {:+.4}  M_z/(μQc) {:+.4}",
            f.force_longitudinal / limit,
            f.force_lateral / limit,
            f.spin_moment.unwrap_or(0.0) / (limit * MEAN_SEMI_AXIS)
        );
    };
    row("exact_table", &ExactTable::new()?.creep_forces(&input)?);
    let mut along_x = Vec::new();
    for (longitudinal, lateral) in [(80, 20), (120, 30), (160, 160), (320, 400), (400, 400)] {
        let forces = ExactTheory::new(longitudinal, lateral).creep_forces(&input)?;
        row(&format!("exact {longitudinal}x{lateral}"), &forces);
        if lateral == 400 {
            along_x.push((longitudinal as f64, forces));
        }
    }
    // F(n_x) = F∞ + C/n_x on two grids of equal n_y.
    let [(n1, f1), (n2, f2)] = [along_x[0], along_x[1]];
    let extrapolate = |a: f64, b: f64| (n2 * b - n1 * a) / (n2 - n1);
    row(
        "n_x → ∞",
        &CreepForces {
            force_longitudinal: extrapolate(f1.force_longitudinal, f2.force_longitudinal),
            force_lateral: extrapolate(f1.force_lateral, f2.force_lateral),
            spin_moment: Some(extrapolate(f1.spin_moment.unwrap_or(0.0), f2.spin_moment.unwrap_or(0.0))),
            adhesion_utilisation: f2.adhesion_utilisation,
        },
    );
    Ok(())
}
