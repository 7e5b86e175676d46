//! The `exact_table` rung: held-out accuracy against the exact solver, continuity across cell
//! edges, the problem's symmetries, the Coulomb bound, Kalker's linear limit, derivatives, and
//! the refusal of corrupted tables.

use crate::common;

use common::{contact, moved, NO_RATES};
use wheel_rail_contact::models::exact_table::{Table, TableAxes};
use wheel_rail_contact::{
    ContactInput, CreepForceModel, CreepForces, ExactTable, ExactTheory, KalkerCoefficients, KalkerLinear,
};

fn model() -> ExactTable {
    ExactTable::new().expect("the compiled-in table is valid")
}

/// A small seeded generator (the points must not depend on the test order).
struct Points(u64);

impl Points {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A random contact over issue 11's domain: a/b log-uniform in [0.1, 10], ν in [0, 0.5],
    /// creepages as `level` × Kalker's characteristic creepages (the linear force reaches μQ:
    /// ξ* = μQ/(G c² C11), η* likewise, φ* = μQ/(G c³ C23)) in a random direction.
    fn contact(&mut self, level: f64) -> ContactInput {
        self.contact_over(level, (-1.0, 1.0))
    }

    /// The held-out sample: `per_level` contacts at each level from the linear range to full
    /// sliding, a/b log-uniform in [10^`low`, 10^`high`].
    fn held_out(&mut self, per_level: usize, exponents: (f64, f64)) -> Vec<ContactInput> {
        let levels = [0.05, 0.3, 0.7, 1.0, 1.5, 2.5, 4.0, 8.0];
        levels
            .iter()
            .flat_map(|&level| vec![level; per_level])
            .map(|level| self.contact_over(level, exponents))
            .collect()
    }

    /// [`Points::contact`] with a/b log-uniform in [10^`low`, 10^`high`].
    fn contact_over(&mut self, level: f64, (low, high): (f64, f64)) -> ContactInput {
        let a_over_b = 10f64.powf(low + (high - low) * self.next());
        let nu = 0.5 * self.next();
        let base = contact(a_over_b, nu, 0.0, 0.0, 0.0);
        let c2 = base.semi_axis_a * base.semi_axis_b;
        let k = KalkerCoefficients::new(a_over_b, nu);
        let unit = base.friction_coefficient * base.normal_force / (base.shear_modulus * c2);
        let (z, angle) = (2.0 * self.next() - 1.0, 2.0 * std::f64::consts::PI * self.next());
        let planar = (1.0 - z * z).sqrt();
        ContactInput {
            creepage_longitudinal: level * planar * angle.cos() * unit / k.c11,
            creepage_lateral: level * planar * angle.sin() * unit / k.c22,
            spin_creepage: level * z * unit / (c2.sqrt() * k.c23),
            ..base
        }
    }
}

fn limit(input: &ContactInput) -> f64 {
    input.friction_coefficient * input.normal_force
}

fn c(input: &ContactInput) -> f64 {
    (input.semi_axis_a * input.semi_axis_b).sqrt()
}

/// The contact with all three creepages times `factor`.
fn scaled(input: &ContactInput, factor: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: input.creepage_longitudinal * factor,
        creepage_lateral: input.creepage_lateral * factor,
        spin_creepage: input.spin_creepage * factor,
        ..*input
    }
}

/// max(|ΔF_x|, |ΔF_y|)/(μQ) and |ΔM_z|/(μQc).
fn deviation(input: &ContactInput, a: &CreepForces, b: &CreepForces) -> (f64, f64) {
    let force = (a.force_longitudinal - b.force_longitudinal).abs().max((a.force_lateral - b.force_lateral).abs());
    let moment = (a.spin_moment.unwrap() - b.spin_moment.unwrap()).abs();
    (force / limit(input), moment / (limit(input) * c(input)))
}

/// Issue 11 allowed the table 20 MB over a/b ∈ [0.1, 10]; its 29 nodes there take that share,
/// and the 7 nodes on to 10^1.5 (a flange's long patches) the rest (docs/exact_table.md, "Long
/// patches": in the FMU the table is zipped, and the FMU stays within issue 29's 12 MB).
#[test]
fn the_compiled_in_table_says_how_it_was_made_and_fits_in_20_mb_up_to_a_over_b_10() {
    let table = model().table();
    assert!(table.provenance.contains("exact_table generator v"), "{}", table.provenance);
    assert!(table.provenance.contains("ExactTheory"), "{}", table.provenance);
    assert_eq!(table.axes.a_over_b, (0.1, 10f64.powf(1.5)));
    assert_eq!(table.axes.counts[0], 36);
    assert!((table.axes.a_over_b_node(28) - 10.0).abs() < 1e-12, "a/b = 10 is a node");
    assert_eq!(table.axes.poisson_ratio, (0.0, 0.5));
    let bytes = table.to_bytes();
    assert!(bytes.len() * 29 / 36 <= 20_000_000 && bytes.len() <= 23_000_000, "{} bytes", bytes.len());
    assert_eq!(Table::from_bytes(&bytes).as_ref(), Ok(table));
    // The writer's bytes are the file's, whose value coding was made by an independent converter
    // from the v2 file (every count identical) and is decoded here independently of the reader.
    let file = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin")).unwrap();
    assert!(bytes == file, "the table writer's bytes differ from data/exact_table.bin");
    let counts = file_counts(&table.axes, &file[file.len() - 4 - 6 * table.axes.len()..file.len() - 4]);
    assert_eq!(file_value_bytes(&table.axes, &counts), file[file.len() - 4 - 6 * table.axes.len()..file.len() - 4]);
}

/// Random held-out points (never nodes) from the linear range to full sliding, spin included,
/// against the exact solver on 120 × 30 elements (its grid error, against the converged theory,
/// reaches 0.009 μQ at the worst of the trade report's points; docs/exact_table.md). The full
/// set (1000 points, against the same solver, its worst re-checked against the converged
/// theory) is in the trade report.
#[test]
fn held_out_points_match_the_exact_theory() {
    let cases = Points(20261122).held_out(4, (-1.0, 1.0));
    let (median, max, moment_max) = held_out_errors(&cases, ExactTheory::new(120, 30));
    // Issue 11's goals (measured on this sample: median 0.0017, max 0.0055, M_z max 0.0058;
    // with the second table, uniform in t: 0.0026, 0.0085, 0.0092).
    assert!(median <= 0.003 && max <= 0.02, "F: median {median}, max {max}");
    assert!(moment_max <= 0.02, "M_z: max {moment_max}");
}

/// The table against `reference` at `cases`: the median and largest max(|ΔF_x|, |ΔF_y|)/(μQ)
/// and the largest |ΔM_z|/(μQc).
fn held_out_errors(cases: &[ContactInput], reference: ExactTheory) -> (f64, f64, f64) {
    let mut forces = Vec::new();
    let mut moments = Vec::new();
    for (input, solved) in cases.iter().zip(reference.creep_forces_many(cases)) {
        let (force, moment) = deviation(input, &model().creep_forces(input).unwrap(), &solved.unwrap());
        forces.push(force);
        moments.push(moment);
    }
    forces.sort_by(f64::total_cmp);
    (forces[forces.len() / 2], forces[forces.len() - 1], moments.into_iter().fold(0.0, f64::max))
}

/// The same goals on a flange's long patches, a/b ∈ [10, 10^1.5], against the exact solver on
/// 160 × 30 elements (long patches need more along x; docs/exact_table.md, "Long patches", has
/// 400 points and the worst re-checked against the converged theory).
#[test]
fn held_out_points_on_long_patches_match_the_exact_theory() {
    let cases = Points(20261126).held_out(3, (1.0, 1.5));
    let (median, max, moment_max) = held_out_errors(&cases, ExactTheory::new(160, 30));
    assert!(median <= 0.003 && max <= 0.02, "F: median {median}, max {max}");
    assert!(moment_max <= 0.02, "M_z: max {moment_max}");
}

/// The contact at a point of the table's coordinates (a/b, ν, α, β, t) (docs/exact_table.md):
/// u = k · (ξ, η, cφ) · G/(μp₀) with k from Kalker's coefficients, s = (t/(1 − t))².
fn at_table_point([a_over_b, nu, alpha, beta, t]: [f64; 5]) -> ContactInput {
    let base = contact(a_over_b, nu, 0.0, 0.0, 0.0);
    let (a, b) = (base.semi_axis_a, base.semi_axis_b);
    let size = (t / (1.0 - t)).powi(2);
    let u = [(1.0 - alpha) * (1.0 - beta.abs()) * size, alpha * (1.0 - beta.abs()) * size, beta * size];
    let max_pressure = 3.0 * base.normal_force / (2.0 * std::f64::consts::PI * a * b);
    let unit = 2.0 * std::f64::consts::PI / 3.0 * base.friction_coefficient * max_pressure / base.shear_modulus;
    let k = KalkerCoefficients::new(a_over_b, nu);
    let c33 = KalkerCoefficients::spin_moment_c33(a_over_b, nu);
    ContactInput {
        creepage_longitudinal: u[0] * unit / k.c11,
        creepage_lateral: u[1] * unit / k.c22,
        spin_creepage: u[2] * unit / ((k.c23 + c33) * (a * b).sqrt()),
        ..base
    }
}

/// Where the adhesion zone collapses along a ray (a kink of the forces), the table with uniform
/// t nodes was off by up to 0.029 μQ: the six worst points of its held-out sets. The kink-fitted
/// size puts every ray's collapse on one node (docs/exact_table.md).
#[test]
fn the_adhesion_collapse_kink_is_resolved() {
    let points = [
        [2.007, 0.43, 0.527, -0.564, 0.617],
        [2.018, 0.16, 0.502, -0.661, 0.589],
        [0.670, 0.13, 0.793, -0.816, 0.633],
        [4.993, 0.27, 0.047, -0.722, 0.550],
        [5.869, 0.12, 0.021, 0.922, 0.509],
        [6.166, 0.12, 0.347, -0.378, 0.597],
    ];
    let cases: Vec<ContactInput> = points.iter().map(|&point| at_table_point(point)).collect();
    let exact = ExactTheory::new(120, 30).creep_forces_many(&cases);
    for ((input, reference), point) in cases.iter().zip(exact).zip(points) {
        let (force, moment) = deviation(input, &model().creep_forces(input).unwrap(), &reference.unwrap());
        assert!(force <= 0.015 && moment <= 0.015, "{point:?}: F off by {force} μQ, M_z by {moment} μQc");
    }
}

/// Dense sweeps through every coordinate of the table (and across its fold edges ξ = 0, η = 0,
/// φ = 0): neighbouring samples never differ by more than the force's slope allows.
#[test]
fn continuous_across_every_cell_edge() {
    let model = model();
    let base = Points(7).contact(1.2);
    let sweep = |name: &str, samples: usize, at: &dyn Fn(f64) -> ContactInput| {
        let mut previous: Option<CreepForces> = None;
        for i in 0..=samples {
            let input = at(i as f64 / samples as f64);
            let f = model.creep_forces(&input).unwrap();
            if let Some(p) = previous {
                let (force, moment) = deviation(&input, &f, &p);
                assert!(force < 2e-3 && moment < 2e-3, "{name} at sample {i}: jump {force} / {moment}");
            }
            previous = Some(f);
        }
    };
    let (xi, eta, phi) = (base.creepage_longitudinal, base.creepage_lateral, base.spin_creepage);
    sweep("xi", 20_000, &|s| ContactInput { creepage_longitudinal: xi * (6.0 * s - 3.0), ..base });
    sweep("eta", 20_000, &|s| ContactInput { creepage_lateral: eta * (6.0 * s - 3.0), ..base });
    sweep("phi", 20_000, &|s| ContactInput { spin_creepage: phi * (6.0 * s - 3.0), ..base });
    sweep("size", 20_000, &|s| scaled(&base, 10f64.powf(12.0 * s - 6.0)));
    sweep("nu", 5_000, &|s| ContactInput { poisson_ratio: 0.5 * s, ..base });
    let area = base.semi_axis_a * base.semi_axis_b;
    sweep("a/b", 20_000, &|s| {
        let a_over_b = 10f64.powf(2.0 * s - 1.0);
        ContactInput { semi_axis_a: (area * a_over_b).sqrt(), semi_axis_b: (area / a_over_b).sqrt(), ..base }
    });
}

/// Near zero the forces are tiny, so the sweeps above, in units of μQ, cannot see a jump there.
/// Through the first t cell and the blend into Kalker's linear theory (creepages from 1e-5 to
/// 1e-1 of the characteristic ones), a step of 0.1 % in the creepages changes the forces by
/// about 0.1 % of themselves, never by a jump (the solver's and Kalker's coefficients differ by
/// up to 1.2 %).
#[test]
fn continuous_through_the_small_creepages() {
    let model = model();
    let mut points = Points(31);
    for _ in 0..8 {
        let base = points.contact(1.0);
        let mut previous: Option<CreepForces> = None;
        // 1.001^9212 ≈ 1e4.
        for i in 0..=9212 {
            let input = scaled(&base, 1e-5 * 1.001f64.powi(i));
            let f = model.creep_forces(&input).unwrap();
            if let Some(p) = previous {
                let size = p.force_longitudinal.hypot(p.force_lateral);
                let change = (f.force_longitudinal - p.force_longitudinal).hypot(f.force_lateral - p.force_lateral);
                let (moment, moment_change) = (p.spin_moment.unwrap(), f.spin_moment.unwrap() - p.spin_moment.unwrap());
                assert!(
                    change <= 0.003 * size && moment_change.abs() <= 0.003 * moment.abs().max(0.01 * size * c(&input)),
                    "step {i} at {input:?}: {p:?} → {f:?}"
                );
            }
            previous = Some(f);
        }
    }
}

#[test]
fn the_symmetries_hold_exactly() {
    let model = model();
    let mut points = Points(11);
    for level in [1e-4, 0.01, 0.5, 1.0, 3.0, 30.0] {
        for _ in 0..20 {
            let input = points.contact(level);
            let f = model.creep_forces(&input).unwrap();
            // S1 reverses every creepage and every output; S2 (the mirror y → −y) reverses η, φ
            // and F_y, M_z.
            for (creepage_signs, [sx, sy]) in [([-1.0, -1.0, -1.0], [-1.0, -1.0]), ([1.0, -1.0, -1.0], [1.0, -1.0])] {
                let [cx, cy, cphi] = creepage_signs;
                let image = ContactInput {
                    creepage_longitudinal: cx * input.creepage_longitudinal,
                    creepage_lateral: cy * input.creepage_lateral,
                    spin_creepage: cphi * input.spin_creepage,
                    ..input
                };
                let g = model.creep_forces(&image).unwrap();
                assert_eq!(
                    (g.force_longitudinal, g.force_lateral, g.spin_moment),
                    (sx * f.force_longitudinal, sy * f.force_lateral, f.spin_moment.map(|m| sy * m)),
                    "{creepage_signs:?} at {input:?}"
                );
            }
        }
    }
}

#[test]
fn bounded_by_coulomb_and_finite_at_the_extremes() {
    let model = model();
    let mut points = Points(5);
    for level in [0.0_f64, 1e-300, 1e-6, 1.0, 10.0, 1e6, 1e300] {
        for _ in 0..50 {
            let input = points.contact(level.min(1.0));
            let input = ContactInput {
                creepage_longitudinal: input.creepage_longitudinal * level.max(1.0),
                creepage_lateral: input.creepage_lateral * level.max(1.0),
                spin_creepage: input.spin_creepage * level.max(1.0),
                ..input
            };
            let f = model.creep_forces(&input).unwrap();
            assert!(f.force_longitudinal.hypot(f.force_lateral) <= limit(&input) * (1.0 + 1e-12), "{input:?}: {f:?}");
            // |M_z| = |∫ r × p dA| ≤ max(a, b) ∫ |p| dA ≤ max(a, b) μQ.
            let radius = input.semi_axis_a.max(input.semi_axis_b);
            assert!(f.spin_moment.unwrap().abs() <= limit(&input) * radius, "{input:?}: {f:?}");
        }
    }
    // Absurd magnitudes: creepages near f64::MAX, no friction to speak of, lift-off.
    let base = contact(1.0, 0.28, 0.0, 0.0, 0.0);
    for input in [
        ContactInput { creepage_longitudinal: f64::MAX, creepage_lateral: -f64::MAX, spin_creepage: f64::MAX, ..base },
        ContactInput { creepage_longitudinal: 1e-3, friction_coefficient: 1e-300, ..base },
        ContactInput { spin_creepage: 1.0, normal_force: 1e-300, ..base },
        ContactInput { creepage_lateral: 1e-3, shear_modulus: f64::MAX, ..base },
        ContactInput { creepage_lateral: 1e-3, normal_force: -5.0, ..base },
    ] {
        let f = model.creep_forces(&input).unwrap();
        assert!(f.force_longitudinal.is_finite() && f.force_lateral.is_finite(), "{input:?}: {f:?}");
        assert!(f.spin_moment.unwrap().is_finite() && f.adhesion_utilisation <= 1.0 + 1e-12, "{input:?}: {f:?}");
    }
    // Far beyond saturation: full sliding, |F| = μQ against the creepage.
    let sliding = model.creep_forces(&ContactInput { creepage_longitudinal: 1.0, ..base }).unwrap();
    assert!((sliding.force_longitudinal / limit(&base) + 1.0).abs() < 1e-6, "{sliding:?}");
}

#[test]
fn outside_the_tabulated_ellipses_the_error_names_the_semi_axes() {
    for a_over_b in [0.099, 32.0] {
        let input = contact(a_over_b, 0.28, 1e-3, 0.0, 0.0);
        let error = model().creep_forces(&input).unwrap_err().to_string();
        assert!(error.starts_with("semi_axis_a = ") && error.contains("with semi_axis_b = "), "{error}");
        assert!(error.contains("[0.1, 31.62] (10^-1 to 10^1.5)"), "{error}");
    }
    // The ends themselves are inside, also when a/b rounds to just beyond them.
    for a_over_b in [0.1, 10f64.powf(1.5)] {
        let c = 5e-3;
        let input = ContactInput {
            semi_axis_a: c * f64::sqrt(a_over_b),
            semi_axis_b: c / f64::sqrt(a_over_b),
            ..contact(1.0, 0.28, 1e-3, 0.0, 0.0)
        };
        assert!(model().creep_forces(&input).is_ok(), "a/b = {}", input.semi_axis_a / input.semi_axis_b);
    }
}

/// Kalker's linear theory (his table's coefficients, an independent source) at small creepage.
#[test]
fn the_linear_limit_is_kalkers_linear_theory() {
    let model = model();
    for a_over_b in [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0] {
        for nu in [0.0, 0.25, 0.28, 0.5] {
            for (xi, eta, phi) in [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 100.0), (0.6, -0.8, 50.0)] {
                for scale in [1e-12, 1e-9, 1e-7] {
                    let input = contact(a_over_b, nu, xi * scale, eta * scale, phi * scale);
                    let table = model.creep_forces(&input).unwrap();
                    let linear = KalkerLinear.creep_forces(&input).unwrap();
                    let close = |a: f64, b: f64, size: f64| (a - b).abs() <= 0.01 * size;
                    let size = linear.force_longitudinal.hypot(linear.force_lateral);
                    let moment = linear.spin_moment.unwrap().abs().max(size * c(&input));
                    assert!(
                        close(table.force_longitudinal, linear.force_longitudinal, size)
                            && close(table.force_lateral, linear.force_lateral, size)
                            && close(table.spin_moment.unwrap(), linear.spin_moment.unwrap(), moment),
                        "a/b {a_over_b}, ν {nu}, {input:?}: {table:?} vs {linear:?}"
                    );
                }
            }
        }
    }
}

/// The derivative is the interpolant's: central differences agree inside a cell.
#[test]
fn derivatives_match_finite_differences() {
    let model = model();
    let mut points = Points(99);
    for level in [0.02, 0.4, 1.0, 2.0, 6.0] {
        for _ in 0..10 {
            let input = points.contact(level);
            let directions = [
                ContactInput { creepage_longitudinal: input.creepage_longitudinal.abs() + 1e-6, ..NO_RATES },
                ContactInput { creepage_lateral: input.creepage_lateral.abs() + 1e-6, ..NO_RATES },
                ContactInput { spin_creepage: input.spin_creepage.abs() + 1e-4, ..NO_RATES },
                ContactInput { normal_force: input.normal_force, ..NO_RATES },
                ContactInput { semi_axis_a: input.semi_axis_a, friction_coefficient: 0.1, ..NO_RATES },
            ];
            for direction in directions {
                let derivative = model.directional_derivative(&input, &direction).unwrap();
                let h = 1e-7;
                let at = |s: f64| model.creep_forces(&moved(&input, &direction, s)).unwrap();
                let (plus, minus) = (at(h), at(-h));
                let difference = |p: f64, m: f64| (p - m) / (2.0 * h);
                let size = limit(&input);
                for (exact, approximate) in [
                    (derivative.force_longitudinal, difference(plus.force_longitudinal, minus.force_longitudinal)),
                    (derivative.force_lateral, difference(plus.force_lateral, minus.force_lateral)),
                ] {
                    assert!(
                        (exact - approximate).abs() <= 1e-5 * size,
                        "{input:?} along {direction:?}: {exact} vs {approximate}"
                    );
                }
            }
        }
    }
}

/// At pure spin in full sliding the forces nearly vanish (F_y ≈ 2e-9 μQ at a normalised spin of
/// 1e9), and the chord correction, which divides by their length, is left out there: ∂F_y/∂ξ is
/// the differences' (≈ 1.5e-6 μQ per unit ξ), not the 350 μQ of a bump 1e-9 μQ high and 1e-11
/// wide that the correction made (it came out equal to ∂F_x/∂ξ).
#[test]
fn at_pure_spin_in_full_sliding_the_lateral_derivative_is_the_differences() {
    let model = model();
    for a_over_b in [0.1, 3.0, 31.6] {
        let input = ContactInput {
            friction_coefficient: 1.4e-7,
            normal_force: 2.5e-5,
            ..contact(a_over_b, 0.0, 0.0, 0.0, 1.0)
        };
        let along_xi = |sign: f64| ContactInput { creepage_longitudinal: sign, ..NO_RATES };
        let size = limit(&input);
        let at = |xi: f64| model.creep_forces(&ContactInput { creepage_longitudinal: xi, ..input }).unwrap();
        let h = 1e-9;
        for sign in [1.0, -1.0] {
            let derivative = model.directional_derivative(&input, &along_xi(sign)).unwrap();
            // The one-sided difference of the side the direction moves to (F_y is even in ξ).
            let difference = (at(sign * h).force_lateral - at(0.0).force_lateral) / h;
            assert!(
                derivative.force_longitudinal.abs() > 10.0 * size,
                "a/b {a_over_b}: ∂F_x/∂ξ {}",
                derivative.force_longitudinal / size
            );
            assert!(
                (derivative.force_lateral - difference).abs() <= 1e-5 * size,
                "a/b {a_over_b}, along {sign}ξ: ∂F_y/∂ξ {} μQ against {} μQ",
                derivative.force_lateral / size,
                difference / size
            );
        }
    }
}

#[test]
fn corrupted_or_missing_tables_are_refused_with_a_message() {
    let bytes = model().table().to_bytes();
    let refused = |bytes: &[u8]| Table::from_bytes(bytes).unwrap_err().to_string();
    assert!(refused(&[]).contains("0 bytes is too short for a table"), "{}", refused(&[]));
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 0x10;
    assert!(refused(&flipped).contains("checksum mismatch"), "{}", refused(&flipped));
    assert!(refused(&bytes[..bytes.len() - 100]).contains("checksum mismatch"));
    assert!(refused(&bytes[..10]).contains("magic"), "{}", refused(&bytes[..10]));
    let mut magic = bytes.clone();
    magic[0] = b'X';
    assert!(refused(&magic).contains("magic"));
    // Only the magic bytes and their checksum: a table file cut short, not a foreign file.
    let mut cut = bytes[..16].to_vec();
    cut.extend_from_slice(&crc32(&cut).to_le_bytes());
    assert!(refused(&cut).contains("truncated"), "{}", refused(&cut));
    // Well-formed files (checksum recomputed) whose values break the Coulomb bound, or whose
    // ray has its collapse outside the range the kink-fitted size is built for.
    let table = model().table();
    let rewritten = |offset_from_values: isize, replacement: &[u8]| {
        let mut bytes = table.to_bytes();
        let value_start = bytes.len() - 4 - 2 * 3 * table.axes.len();
        let at = (value_start as isize + offset_from_values) as usize;
        bytes[at..at + replacement.len()].copy_from_slice(replacement);
        let body = bytes.len() - 4;
        let checksum = crc32(&bytes[..body]);
        bytes[body..].copy_from_slice(&checksum.to_le_bytes());
        refused(&bytes)
    };
    // Node 5's F_x and F_y at full scale: |F| = √2 μQ (the values re-encoded as the format says).
    let mut counts = file_counts(&table.axes, &bytes[bytes.len() - 4 - 2 * 3 * table.axes.len()..bytes.len() - 4]);
    counts[3 * 5..3 * 5 + 2].copy_from_slice(&[i16::MAX; 2]);
    let outside = rewritten(0, &file_value_bytes(&table.axes, &counts));
    assert!(outside.contains("node 5") && outside.contains("|F| > μQ"), "{outside}");
    // The last τ node's force unit (just before the values, then its moment unit) at 2/32767:
    // 32767 counts would be 2 μQ.
    let n_t = table.axes.counts[4];
    let unit = rewritten(-16, &(2.0f64 / 32767.0).to_le_bytes());
    assert!(unit.contains(&format!("τ node {}: value units", n_t - 1)), "{unit}");
    // The last ray's collapse (just before the value units, 2 per τ node) at t = 0.1.
    let collapse = rewritten(-16 * n_t as isize - 4, &0.1f32.to_le_bytes());
    assert!(collapse.contains("collapse at t = 0.1"), "{collapse}");
    // A table made with a node outside the disc.
    let axes = TableAxes { counts: [2, 2, 3, 2, 5], a_over_b: (0.1, 10.0), poisson_ratio: (0.0, 0.5) };
    let mut values = vec![0.0; 3 * 120];
    values[3 * 7] = 1.001;
    let error = Table::new("test".into(), axes, vec![[1.0; 3]; 4], vec![0.6; 24], values).unwrap_err().to_string();
    assert!(error.contains("node 7") && error.contains("|F| > μQ"), "{error}");
}

/// A table must cover a/b ∈ [0.1, 10] (issue 11's domain; a table's own range may reach further,
/// and the model's error names the range of the table it has) and all of ν ∈ [0, 0.5]
/// (otherwise valid inputs would be clamped silently).
#[test]
fn tables_over_other_ranges_are_refused() {
    let table = |a_over_b: (f64, f64), poisson_ratio: (f64, f64)| {
        let axes = TableAxes { counts: [2, 2, 3, 2, 5], a_over_b, poisson_ratio };
        Table::new("test".into(), axes, vec![[1.0; 3]; 4], vec![0.6; 24], vec![0.0; 3 * 120])
    };
    let first = table((0.1, 10.0), (0.0, 0.5)).unwrap();
    assert!(table((0.1, 10f64.powf(1.5)), (0.0, 0.5)).is_ok() && table((0.05, 20.0), (0.0, 0.5)).is_ok());
    let error = table((0.1, 10.0), (0.0, 0.4)).unwrap_err().to_string();
    assert!(error.contains("ν range (0.0, 0.4)"), "{error}");
    for (range, text) in [((0.2, 10.0), "(0.2, 10.0)"), ((0.1, 9.5), "(0.1, 9.5)"), ((0.0, 10.0), "(0.0, 10.0)")] {
        let error = table(range, (0.0, 0.5)).unwrap_err().to_string();
        assert!(error.contains(&format!("a/b range {text}")) && error.contains("covering (0.1, 10.0)"), "{error}");
    }
    let error = table((0.1, f64::INFINITY), (0.0, 0.5)).unwrap_err().to_string();
    assert!(error.contains("a/b range (0.1, inf)"), "{error}");
    // Another table's range is not the shipped one's: the model's error says where it is.
    let model = ExactTable::with_table(Box::leak(Box::new(first)));
    let error = model.creep_forces(&contact(12.0, 0.28, 1e-3, 0.0, 0.0)).unwrap_err().to_string();
    assert!(error.contains("the a/b range of the exact_table's table (Table::axes)"), "{error}");
    assert!(model.creep_forces(&contact(9.0, 0.28, 1e-3, 0.0, 0.0)).is_ok());
}

/// CRC-32 (IEEE), bit by bit: the test's own, independent of the library's crate.
/// The value counts of a table file (node-major, 3 per node), decoded as its format states
/// (`table.rs`), independently of the reader: per component, the low-byte plane then the
/// high-byte plane of the differences along τ and then ν; summed back along ν, then τ.
fn file_counts(axes: &TableAxes, values: &[u8]) -> Vec<i16> {
    let n = axes.len();
    let [_, n_nu, n_beta, n_alpha, n_t] = axes.counts;
    let mut counts = vec![0i16; 3 * n];
    for c in 0..3 {
        let mut v: Vec<i16> =
            (0..n).map(|i| i16::from_le_bytes([values[2 * c * n + i], values[(2 * c + 1) * n + i]])).collect();
        let nu_stride = n_beta * n_alpha * n_t;
        for i in (0..n).filter(|i| (i / nu_stride) % n_nu != 0) {
            v[i] = v[i].wrapping_add(v[i - nu_stride]);
        }
        for i in 0..n {
            if i % n_t != 0 {
                v[i] = v[i].wrapping_add(v[i - 1]);
            }
            counts[3 * i + c] = v[i];
        }
    }
    counts
}

/// The inverse of `file_counts`.
fn file_value_bytes(axes: &TableAxes, counts: &[i16]) -> Vec<u8> {
    let n = axes.len();
    let [_, n_nu, n_beta, n_alpha, n_t] = axes.counts;
    let nu_stride = n_beta * n_alpha * n_t;
    let mut bytes = vec![0u8; 6 * n];
    for c in 0..3 {
        let tau_difference = |i: usize| {
            if i % n_t != 0 {
                counts[3 * i + c].wrapping_sub(counts[3 * (i - 1) + c])
            } else {
                counts[3 * i + c]
            }
        };
        for i in 0..n {
            let d = if (i / nu_stride) % n_nu != 0 {
                tau_difference(i).wrapping_sub(tau_difference(i - nu_stride))
            } else {
                tau_difference(i)
            };
            bytes[2 * c * n + i] = d.to_le_bytes()[0];
            bytes[(2 * c + 1) * n + i] = d.to_le_bytes()[1];
        }
    }
    bytes
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}
