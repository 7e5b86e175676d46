use wheel_rail_contact::*;
fn main() {
    let text = include_str!("../data/kalker_c33.csv");
    let rows: Vec<(String, f64, [f64; 3])> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("branch"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[0].to_string(),
                f[1].parse().unwrap(),
                [f[2].parse().unwrap(), f[3].parse().unwrap(), f[4].parse().unwrap()],
            )
        })
        .collect();
    let n: usize = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(80);
    for (branch, g, recalled) in rows {
        let a_over_b = if branch == "a/b" { g } else { 1.0 / g };
        let mut out = vec![];
        for (k, nu) in [0.0, 0.25, 0.5].into_iter().enumerate() {
            let b = (32e-6 / a_over_b).sqrt();
            let a = a_over_b * b;
            let model = ExactTheory { grid: GridSize { longitudinal: n, lateral: n } };
            let phi = 1e-5;
            let input = ContactInput {
                creepage_longitudinal: 0.0,
                creepage_lateral: 0.0,
                spin_creepage: phi,
                normal_force: 1e5,
                semi_axis_a: a,
                semi_axis_b: b,
                friction_coefficient: 0.3,
                shear_modulus: 8e10,
                poisson_ratio: nu,
            };
            let f = model.creep_forces(&input).unwrap();
            let c4 = (a * b) * (a * b);
            let c33 = -f.spin_moment.unwrap() / (8e10 * c4 * phi);
            out.push(format!("{c33:.4} ({:+.1}%)", (c33 / recalled[k] - 1.0) * 100.0));
        }
        println!("{branch} {g}: {}", out.join("  "));
    }
}
