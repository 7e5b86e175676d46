//! The exact_table nodes' grid error: candidate solver grids for the table's nodes against the
//! converged theory, on random contacts near the knee of saturation with spin (where the third
//! table's largest errors are; docs/exact_table.md, "What is not there yet"). The converged
//! values are extrapolated along x from 320 and 400 × 400 elements (the solver converges as
//! 1/n_x); "R(n₁,n₂)" is the same extrapolation from two candidate grids, "adapt" puts
//! 20·√(b/a) elements across a contact wider than long.
//!
//! Run: `cargo run --release --example node_grid_study -- 40` (the number of contacts; ≈ 5 min).
use wheel_rail_contact::{ContactInput, CreepForceModel, CreepForces, ExactTheory, KalkerCoefficients};

/// F_x/(μQ), F_y/(μQ), M_z/(μQc).
fn scaled(f: &CreepForces, l: f64, c: f64) -> [f64; 3] {
    [f.force_longitudinal / l, f.force_lateral / l, f.spin_moment.unwrap() / (l * c)]
}

fn main() {
    let n: usize = std::env::args().nth(1).map(|a| a.parse().unwrap()).unwrap_or(40);
    let mut state = 0x1234_u64;
    let mut next = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (q, mu, g, c) = (80e3, 0.3, 82e9, 5e-3);
    let l = mu * q;
    let mut cases = Vec::new();
    for i in 0..n {
        let a_over_b = 10f64.powf(-1.0 + 2.0 * (i as f64 + next()) / n as f64);
        let poisson_ratio = 0.5 * next();
        let level = 0.4 + 1.6 * next();
        let z = (0.3 + 0.7 * next()) * if next() < 0.5 { -1.0 } else { 1.0 };
        let angle = 2.0 * std::f64::consts::PI * next();
        let planar = (1.0 - z * z).sqrt();
        let k = KalkerCoefficients::new(a_over_b, poisson_ratio);
        let unit = mu * q / g / (c * c);
        cases.push(ContactInput {
            creepage_longitudinal: level * planar * angle.cos() * unit / k.c11,
            creepage_lateral: level * planar * angle.sin() * unit / k.c22,
            spin_creepage: level * z * unit / (c * k.c23),
            normal_force: q,
            semi_axis_a: c * a_over_b.sqrt(),
            semi_axis_b: c / a_over_b.sqrt(),
            friction_coefficient: mu,
            shear_modulus: g,
            poisson_ratio,
        });
    }
    let solve_one = |input: &ContactInput, grid: (usize, usize)| {
        scaled(&ExactTheory::new(grid.0, grid.1).creep_forces(input).unwrap(), l, c)
    };
    let solve = |grid: (usize, usize)| -> Vec<[f64; 3]> {
        ExactTheory::new(grid.0, grid.1)
            .creep_forces_many(&cases)
            .into_iter()
            .map(|f| scaled(&f.unwrap(), l, c))
            .collect()
    };
    let extrapolate = |a: &[[f64; 3]], b: &[[f64; 3]], n1: f64, n2: f64| -> Vec<[f64; 3]> {
        a.iter().zip(b).map(|(a, b)| [0, 1, 2].map(|k| (n2 * b[k] - n1 * a[k]) / (n2 - n1))).collect()
    };
    let reference = extrapolate(&solve((320, 400)), &solve((400, 400)), 320.0, 400.0);
    let ny_adapted = |input: &ContactInput, nx: usize| {
        let b_over_a = input.semi_axis_b / input.semi_axis_a;
        (nx, (20.0 * b_over_a.max(1.0).sqrt()).round() as usize)
    };
    let mut rules: Vec<(String, Vec<[f64; 3]>)> = Vec::new();
    let f80 = solve((80, 20));
    let f160 = solve((160, 20));
    rules.push(("80x20".into(), f80.clone()));
    rules.push(("160x20".into(), f160.clone()));
    rules.push(("R(80,160)x20".into(), extrapolate(&f80, &f160, 80.0, 160.0)));
    let f80_40 = solve((80, 40));
    let f160_40 = solve((160, 40));
    rules.push(("80x40".into(), f80_40.clone()));
    rules.push(("R(80,160)x40".into(), extrapolate(&f80_40, &f160_40, 80.0, 160.0)));
    let a80: Vec<[f64; 3]> = cases.iter().map(|i| solve_one(i, ny_adapted(i, 80))).collect();
    let a160: Vec<[f64; 3]> = cases.iter().map(|i| solve_one(i, ny_adapted(i, 160))).collect();
    rules.push(("80xadapt".into(), a80.clone()));
    rules.push(("R(80,160)xadapt".into(), extrapolate(&a80, &a160, 80.0, 160.0)));
    let bands = [(0.1, 0.3), (0.3, 1.0), (1.0, 3.0), (3.0, 10.01)];
    println!("rule: per a/b band [0.1,0.3) [0.3,1) [1,3) [3,10]: max F / max M_z; overall median F");
    for (name, values) in &rules {
        let mut line = format!("{name:>16}:");
        let mut all = Vec::new();
        for (lo, hi) in bands {
            let (mut f, mut m) = (0.0f64, 0.0f64);
            for (i, input) in cases.iter().enumerate() {
                let ab = input.semi_axis_a / input.semi_axis_b;
                if ab >= lo && ab < hi {
                    let e = [0, 1, 2].map(|k| (values[i][k] - reference[i][k]).abs());
                    f = f.max(e[0].max(e[1]));
                    m = m.max(e[2]);
                    all.push(e[0].max(e[1]));
                }
            }
            line += &format!("  {f:.4}/{m:.4}");
        }
        all.sort_by(f64::total_cmp);
        line += &format!("  median {:.4}", all[all.len() / 2]);
        println!("{line}");
    }
}
