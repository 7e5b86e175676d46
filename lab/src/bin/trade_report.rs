//! The speed–accuracy trade, measured: evaluates every model of the ladder over the fixed case
//! set of docs/trade.md against the reference, Kalker's exact theory (`ExactTheory`) on two grids
//! extrapolated in the grid size (Richardson, solved in parallel with
//! `ExactTheory::creep_forces_many`), checks the reference against CONTACT's published values,
//! and writes tables and SVG plots under docs/trade/.
//!
//! Run: `cargo run --release -p lab --bin trade_report` (or `-- --quick` for the reduced CI set).

use plotters::prelude::*;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;
use wheel_rail_contact::{
    ContactInput, CreepForceModel, CreepForces, Discretisation, ExactTable, ExactTheory, Fastsim, Flexibility,
    KalkerCoefficients, TractionBound,
};

use lab::random_contacts::{random_contact_over, Uniform, FRICTION, MEAN_SEMI_AXIS, NORMAL_FORCE, SHEAR_MODULUS};
use wheel_rail_contact::geometry::{WheelOnRail, WheelSide};
use wheel_rail_contact::models::{fastsim, polach};
use wheel_rail_contact::reference_cases::{manchester_a22, ManchesterA22};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{ContactMethod, WheelCache, WheelRailContact, WheelState};
use wheel_rail_contact::ModelChoice;

/// CONTACT's published cases, the same definitions the tests use.
use wheel_rail_contact::reference_cases::{
    FASTSIM_CASE, FASTSIM_CASE_CONTACT_FASTSIM, FASTSIM_CASE_EXACT, TRACTCURV_CONTACT, TRACTCURV_EXACT,
};

const POISSON: f64 = 0.28;
/// Points per creep-force curve (the exact theory's curves use every fourth).
const CURVE_POINTS: usize = 96;

struct Settings {
    quick: bool,
    ratios: &'static [f64],
    levels: &'static [f64],
    /// The exact theory's coarse and fine grids (n × n); the reference is 2 F_fine − F_coarse.
    exact_grids: (usize, usize),
    /// Further exact-theory grids (longitudinal × lateral) timed and compared, one case at a
    /// time on one thread.
    exact_rows: &'static [(usize, usize)],
    fastsim_grids: &'static [usize],
    /// Random held-out points for `exact_table`, and the exact grid they are checked against.
    held_out: (usize, (usize, usize)),
    /// Their a/b range, as powers of ten.
    held_out_exponents: (f64, f64),
    /// The worst held-out points re-checked against the converged theory: two grids that differ
    /// only along x, extrapolated to n_x → ∞ (first order, as the solver converges along x).
    held_out_recheck: Option<(usize, [(usize, usize); 2])>,
    repetitions: usize,
    out_dir: &'static str,
}

type Model = (String, Box<dyn CreepForceModel>);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let started = Instant::now();
    let quick = std::env::args().any(|a| a == "--quick");
    let settings = if quick {
        Settings {
            quick,
            ratios: &[0.5, 2.0],
            levels: &[0.1, 1.0, 5.0],
            exact_grids: (10, 20),
            exact_rows: &[(40, 10)],
            fastsim_grids: &[5, 10, 20],
            held_out: (40, (80, 20)),
            held_out_exponents: (-1.0, 1.5),
            held_out_recheck: None,
            repetitions: 3,
            out_dir: "target/trade-quick",
        }
    } else {
        Settings {
            quick,
            ratios: &[0.2, 0.5, 1.0, 2.0, 5.0],
            levels: &[0.02, 0.1, 0.3, 0.6, 1.0, 1.5, 2.5, 5.0, 20.0],
            exact_grids: (80, 160),
            exact_rows: &[(40, 40), (200, 50)],
            fastsim_grids: &[5, 10, 20, 40, 70, 100],
            held_out: (1000, (120, 30)),
            held_out_exponents: (-1.0, 1.0),
            held_out_recheck: Some((12, [(320, 400), (400, 400)])),
            repetitions: 15,
            out_dir: "docs/trade",
        }
    };
    if std::env::args().any(|a| a == "--held-out-long") {
        // The table's nodes beyond a/b = 10, added for a flange's long patches
        // (docs/exact_table.md, "Long patches"): only this section, on stdout. Long patches
        // need more elements along x than across for the converged reference.
        let settings = Settings {
            held_out: (400, (160, 30)),
            held_out_exponents: (1.0, 1.5),
            held_out_recheck: Some((10, [(240, 60), (320, 60)])),
            ..settings
        };
        let mut report = String::new();
        write_held_out(&mut report, &settings);
        println!("{report}");
        return Ok(());
    }
    std::fs::create_dir_all(settings.out_dir)?;
    let cases = case_set(&settings);
    let (coarse, fine) = settings.exact_grids;
    // The coarse grid is timed one case at a time (it is a row of the table); the fine one only
    // serves the reference and runs on every core.
    let exact_coarse = evaluate(&exact(coarse), &cases, 1);
    let exact_fine: Vec<CreepForces> =
        exact(fine).creep_forces_many(&cases).into_iter().collect::<Result<_, _>>().expect("valid cases");
    let reference: Vec<CreepForces> = exact_coarse.0.iter().zip(&exact_fine).map(|(c, f)| richardson(c, f)).collect();

    let mut rows = Vec::new();
    for (name, model) in ladder(settings.fastsim_grids) {
        let (results, nanoseconds) = evaluate(model.as_ref(), &cases, settings.repetitions);
        rows.push(Row::new(name, &results, &reference, nanoseconds));
    }
    for &(longitudinal, lateral) in settings.exact_rows {
        let (results, nanoseconds) = evaluate(&ExactTheory::new(longitudinal, lateral), &cases, 1);
        rows.push(Row::new(format!("exact_{longitudinal}x{lateral}"), &results, &reference, nanoseconds));
    }
    rows.push(Row::new(format!("exact_{coarse}x{coarse}"), &exact_coarse.0, &reference, exact_coarse.1));
    let polach_time = rows[0].nanoseconds;
    let finest_fastsim =
        ladder_results(&rows, &format!("fastsim_elliptic_{0}x{0}", settings.fastsim_grids.last().unwrap()));
    let reference_accuracy = deviations(&exact_fine, &reference);
    let mut report = String::new();
    write_header(&mut report, &settings, cases.len(), reference_accuracy);
    write_trade_table(&mut report, &rows, polach_time);
    write_convergence(&mut report, &rows, &finest_fastsim);
    write_held_out(&mut report, &settings);
    write_contact_comparison(&mut report, &settings)?;
    write_wheel_comparison(&mut report, &settings);
    std::fs::write(format!("{}/README.md", settings.out_dir), report)?;
    plot_pareto(&format!("{}/pareto.svg", settings.out_dir), &rows)?;
    for (file, title, direction) in [
        ("curve_xi.svg", "pure longitudinal creepage, a/b = 1: F_x/(μQ)", Direction::Xi),
        ("curve_eta.svg", "pure lateral creepage, a/b = 1: F_y/(μQ)", Direction::Eta),
        ("curve_spin.svg", "pure spin, a/b = 1: F_y/(μQ)", Direction::Spin),
    ] {
        plot_curves(&format!("{}/{file}", settings.out_dir), title, direction, &settings)?;
    }
    println!("wrote {}/README.md and plots in {:.0} s", settings.out_dir, started.elapsed().as_secs_f64());
    Ok(())
}

fn exact(n: usize) -> ExactTheory {
    ExactTheory::new(n, n)
}

/// Richardson extrapolation for a first-order grid error, from grids n and 2n: 2 F_2n − F_n.
fn richardson(coarse: &CreepForces, fine: &CreepForces) -> CreepForces {
    let extrapolate = |c: f64, f: f64| 2.0 * f - c;
    CreepForces::new(
        extrapolate(coarse.force_longitudinal, fine.force_longitudinal),
        extrapolate(coarse.force_lateral, fine.force_lateral),
        Some(extrapolate(coarse.spin_moment.unwrap(), fine.spin_moment.unwrap())),
        FRICTION * NORMAL_FORCE,
    )
}

/// FASTSIM with CONTACT's blended flexibilities (the default, which reproduces CONTACT).
fn fastsim(n: usize, bound: TractionBound) -> Fastsim {
    Fastsim::new(n, n, bound, Flexibility::ThreeBlended).expect("valid grid")
}

fn bound_name(bound: TractionBound) -> &'static str {
    if bound == TractionBound::Parabolic {
        "parabolic"
    } else {
        "elliptic"
    }
}

/// Every model measured: each real-time rung at its default (`ModelChoice::RUNGS`, Polach first:
/// the speed ratios refer to it) but FASTSIM, which is measured on `grids` with both bounds.
fn ladder(grids: &[usize]) -> Vec<Model> {
    let mut models: Vec<Model> = ModelChoice::RUNGS
        .iter()
        .filter(|rung| !rung.offline && rung.name != fastsim::RUNG.name)
        .map(|rung| {
            let model = (rung.default_model)().unwrap_or_else(|e| panic!("{}: {e}", rung.name));
            (rung.name.to_owned(), Box::new(model) as Box<dyn CreepForceModel>)
        })
        .collect();
    assert_eq!(models[0].0, polach::RUNG.name, "the speed ratios refer to Polach's");
    for bound in [TractionBound::Parabolic, TractionBound::Elliptic] {
        for &n in grids {
            models.push((format!("fastsim_{}_{n}x{n}", bound_name(bound)), Box::new(fastsim(n, bound))));
        }
        // CONTACT's own discretisation on CONTACT's grid (40 × 40 elements in the contact).
        let contact_grid = fastsim(44, bound).with_discretisation(Discretisation::ContactGrid);
        models.push((format!("fastsim_contact_grid_{}_44x44", bound_name(bound)), Box::new(contact_grid)));
    }
    models
}

#[derive(Clone, Copy)]
enum Direction {
    Xi,
    Eta,
    Spin,
}

fn contact(a_over_b: f64, xi: f64, eta: f64, phi: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: phi,
        normal_force: NORMAL_FORCE,
        semi_axis_a: MEAN_SEMI_AXIS * a_over_b.sqrt(),
        semi_axis_b: MEAN_SEMI_AXIS / a_over_b.sqrt(),
        friction_coefficient: FRICTION,
        shear_modulus: SHEAR_MODULUS,
        poisson_ratio: POISSON,
    }
}

/// Characteristic creepages (CONTACT's `simpflex`): the linear force reaches μQ at ξ*, η*, φ*.
fn characteristic(a_over_b: f64) -> (f64, f64, f64) {
    let k = KalkerCoefficients::new(a_over_b, POISSON);
    let c = MEAN_SEMI_AXIS;
    let load = FRICTION * NORMAL_FORCE / SHEAR_MODULUS;
    (load / (c * c * k.c11), load / (c * c * k.c22), load / (c * c * c * k.c23))
}

/// a/b × level × direction: pure ξ, η, φ; (ξ, η) at 45°; (η, φ); (ξ, η, φ).
fn case_set(settings: &Settings) -> Vec<ContactInput> {
    let mut cases = Vec::new();
    for &ratio in settings.ratios {
        let (xs, es, ps) = characteristic(ratio);
        for &level in settings.levels {
            let d = std::f64::consts::FRAC_1_SQRT_2;
            let s3 = 1.0 / 3.0_f64.sqrt();
            for (x, e, p) in
                [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (d, d, 0.0), (0.0, d, d), (s3, -s3, s3)]
            {
                cases.push(contact(ratio, level * x * xs, level * e * es, level * p * ps));
            }
        }
    }
    cases
}

struct Row {
    name: String,
    /// Median and max over the cases of |ΔF_x|/(μQ), |ΔF_y|/(μQ), |ΔM_z|/(μQ c) (None: no M_z).
    fx: (f64, f64),
    fy: (f64, f64),
    mz: Option<(f64, f64)>,
    nanoseconds: f64,
    results: Vec<CreepForces>,
}

impl Row {
    fn new(name: String, results: &[CreepForces], reference: &[CreepForces], nanoseconds: f64) -> Self {
        let errors = deviations(results, reference);
        Row { name, fx: errors.0, fy: errors.1, mz: errors.2, nanoseconds, results: results.to_vec() }
    }
}

fn ladder_results(rows: &[Row], name: &str) -> Vec<CreepForces> {
    rows.iter().find(|r| r.name == name).map(|r| r.results.clone()).unwrap_or_default()
}

/// Median and max over the cases of |ΔF_x|/(μQ), |ΔF_y|/(μQ) and |ΔM_z|/(μQ c).
type Deviations = ((f64, f64), (f64, f64), Option<(f64, f64)>);

fn deviations(results: &[CreepForces], reference: &[CreepForces]) -> Deviations {
    let limit = FRICTION * NORMAL_FORCE;
    let err = |f: &dyn Fn(&CreepForces) -> Option<f64>, scale: f64| -> Option<(f64, f64)> {
        let mut e: Vec<f64> = results
            .iter()
            .zip(reference)
            .map(|(r, re)| Some((f(r)? - f(re)?).abs() / scale))
            .collect::<Option<Vec<f64>>>()?;
        e.sort_by(f64::total_cmp);
        Some((e[e.len() / 2], e[e.len() - 1]))
    };
    (
        err(&|f| Some(f.force_longitudinal), limit).unwrap(),
        err(&|f| Some(f.force_lateral), limit).unwrap(),
        err(&|f| f.spin_moment, limit * MEAN_SEMI_AXIS),
    )
}

/// The model's forces on every case, and the time per evaluation: the median over `reps`
/// passes through all cases in this process.
fn evaluate(model: &dyn CreepForceModel, cases: &[ContactInput], reps: usize) -> (Vec<CreepForces>, f64) {
    let mut results = Vec::new();
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            results = cases.iter().map(|case| black_box(model.creep_forces(black_box(case)).unwrap())).collect();
            start.elapsed().as_secs_f64() * 1e9 / cases.len() as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (results, times[times.len() / 2])
}

fn write_header(report: &mut String, settings: &Settings, case_count: usize, accuracy: Deviations) {
    let mode = if settings.quick { " (quick mode: reduced set, not the committed report)" } else { "" };
    let (coarse, fine) = settings.exact_grids;
    writeln!(report, "# The speed–accuracy trade, measured{mode}\n").unwrap();
    writeln!(
        report,
        "Generated by `cargo run --release -p lab --bin trade_report` (see [../trade.md](../trade.md) for the \
         case set and the method). {case_count} cases: a/b ∈ {:?}, ν = {POISSON}, Q = {} kN, μ = {FRICTION}, \
         G = {} GPa, c = √(ab) = {} mm; creepage levels {:?} × the characteristic creepage (linear force = μQ) \
         along pure ξ, pure η, pure φ, (ξ, η), (η, φ) and (ξ, −η, φ).\n",
        settings.ratios,
        NORMAL_FORCE / 1e3,
        SHEAR_MODULUS / 1e9,
        MEAN_SEMI_AXIS * 1e3,
        settings.levels
    )
    .unwrap();
    let max = |d: (f64, f64)| d.1;
    writeln!(
        report,
        "Reference: Kalker's exact theory (`ExactTheory`, CONTACT's steady-rolling problem) on {coarse} × {coarse} \
         and {fine} × {fine} elements over 1.1 a × 1.1 b, extrapolated to the zero grid size assuming its \
         first-order grid error (Richardson: F = 2 F_{fine} − F_{coarse}). The extrapolation moves the \
         {fine} × {fine} forces by median {:.4} / max {:.4} (F_x), {:.4} / {:.4} (F_y), max {:.4} (M_z) in \
         the units below. Accuracy of the reference, checked against the 160/320 and 120/240 \
         extrapolations on four cases ([../trade.md](../trade.md)): ≈ 0.0005 μQ in pure creepage, ≈ 0.001 μQ \
         with spin. Every FASTSIM row uses CONTACT's blended flexibilities. Errors are \
         |Δ F|/(μQ) for forces and |Δ M_z|/(μQ·c) for the spin moment (\"—\": the model has no M_z). Time: \
         median over {} passes through all cases in one process, per evaluation (exact theory: one pass); \
         ratio = time / Polach's time.\n",
        accuracy.0 .0,
        max(accuracy.0),
        accuracy.1 .0,
        max(accuracy.1),
        accuracy.2.map_or(f64::NAN, max),
        settings.repetitions
    )
    .unwrap();
}

fn write_trade_table(report: &mut String, rows: &[Row], polach_time: f64) {
    report.push_str("## Trade table (errors against the exact theory)\n\n| model | F_x median | F_x max | F_y median | F_y max | M_z median | M_z max | ns / evaluation | time / Polach |\n|---|---|---|---|---|---|---|---|---|\n");
    for row in rows {
        let mz = row.mz.map_or(("—".to_owned(), "—".to_owned()), |(m, x)| (format!("{m:.4}"), format!("{x:.4}")));
        writeln!(
            report,
            "| {} | {:.4} | {:.4} | {:.4} | {:.4} | {} | {} | {:.0} | {:.2} |",
            row.name,
            row.fx.0,
            row.fx.1,
            row.fy.0,
            row.fy.1,
            mz.0,
            mz.1,
            row.nanoseconds,
            row.nanoseconds / polach_time
        )
        .unwrap();
    }
    report.push_str(
        "\nThe linear theory is not friction-limited, so its error grows without bound beyond the linear range \
         (its max is the largest level of the set). The `exact_n×n` rows are the exact theory on one grid: their \
         error is its grid error.\n\n![error vs time](pareto.svg)\n\n",
    );
}

fn write_convergence(report: &mut String, rows: &[Row], finest: &[CreepForces]) {
    report.push_str(
        "## FASTSIM grid convergence (elliptic bound)\n\nError against the exact theory (the model error plus the \
         grid error), and the change against FASTSIM's own finest grid (the grid error alone).\n\n\
         | grid | vs exact: median | vs exact: max | vs finest FASTSIM: median | vs finest FASTSIM: max | ns / evaluation | ns / element |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for row in rows.iter().filter(|r| r.name.starts_with("fastsim_elliptic")) {
        let n: f64 = row.name.rsplit('x').next().unwrap().parse().unwrap();
        let own = deviations(&row.results, finest);
        writeln!(
            report,
            "| {} | {:.5} | {:.5} | {:.5} | {:.5} | {:.0} | {:.1} |",
            row.name.trim_start_matches("fastsim_elliptic_"),
            row.fx.0.max(row.fy.0),
            row.fx.1.max(row.fy.1),
            own.0 .0.max(own.1 .0),
            own.0 .1.max(own.1 .1),
            row.nanoseconds,
            row.nanoseconds / (n * n)
        )
        .unwrap();
    }
    report.push_str("\n(max over F_x and F_y of the median and max errors / (μQ).)\n\n");
}

/// `exact_table` on random points over its domain (never its nodes) against the exact
/// solver: a/b log-uniform over `Settings::held_out_exponents`, ν uniform in [0, 0.5], the creepage direction uniform
/// on the sphere of (ξ/ξ*, η/η*, φ/φ*) and its size log-uniform over [0.01, 30] × the
/// characteristic creepage.
fn write_held_out(report: &mut String, settings: &Settings) {
    let (count, (longitudinal, lateral)) = settings.held_out;
    let mut uniform = Uniform::new(0x5eed);
    let mut cases = Vec::with_capacity(count);
    for _ in 0..count {
        cases.push(random_contact_over(&mut uniform, settings.held_out_exponents));
    }
    let started = Instant::now();
    let exact: Vec<CreepForces> = ExactTheory::new(longitudinal, lateral)
        .creep_forces_many(&cases)
        .into_iter()
        .collect::<Result<_, _>>()
        .expect("valid cases");
    let solve_time = started.elapsed().as_secs_f64();
    let table = ExactTable::new().expect("the compiled-in table is valid");
    let results: Vec<CreepForces> = cases.iter().map(|c| table.creep_forces(c).expect("inside the table")).collect();
    let limit = FRICTION * NORMAL_FORCE;
    let quantiles = |mut e: Vec<f64>| {
        e.sort_by(f64::total_cmp);
        let at = |q: f64| e[((e.len() - 1) as f64 * q).round() as usize];
        (at(0.5), at(0.95), at(1.0))
    };
    let component = |f: &dyn Fn(&CreepForces) -> f64, scale: f64| {
        quantiles(results.iter().zip(&exact).map(|(r, e)| (f(r) - f(e)).abs() / scale).collect())
    };
    let fx = component(&|f| f.force_longitudinal, limit);
    let fy = component(&|f| f.force_lateral, limit);
    let mz = component(&|f| f.spin_moment.unwrap(), limit * MEAN_SEMI_AXIS);
    writeln!(
        report,
        "## `exact_table` on held-out points\n\n{count} random points over the table's domain (never its \
         nodes): a/b log-uniform in [{:.4}, {:.4}], ν uniform in [0, 0.5], the creepage direction uniform on the \
         sphere of (ξ/ξ*, η/η*, φ/φ*) (φ* with C23), its size log-uniform in [0.01, 30] × the characteristic \
         creepage. Reference: the exact solver on {longitudinal} × {lateral} elements ({solve_time:.0} s on all \
         cores; its own grid error reaches 0.009 μQ at the worst points, see the re-check below). Table: {}.\n\n\
         | output | median | 95th percentile | max |\n|---|---|---|---|\n\
         | F_x/(μQ) | {:.4} | {:.4} | {:.4} |\n| F_y/(μQ) | {:.4} | {:.4} | {:.4} |\n\
         | M_z/(μQc) | {:.4} | {:.4} | {:.4} |\n",
        10f64.powf(settings.held_out_exponents.0),
        10f64.powf(settings.held_out_exponents.1),
        table.table().provenance,
        fx.0,
        fx.1,
        fx.2,
        fy.0,
        fy.1,
        fy.2,
        mz.0,
        mz.1,
        mz.2
    )
    .unwrap();
    if let Some((worst, grids)) = settings.held_out_recheck {
        write_held_out_recheck(report, (&cases, &exact, &results), (longitudinal, lateral), (worst, grids));
    }
}

/// The `worst` held-out points (largest |ΔF| or |ΔM_z| against the held-out grid) against the
/// converged theory: F(n_x) = F∞ + C/n_x on two grids of equal n_y gives F∞.
fn write_held_out_recheck(
    report: &mut String,
    (cases, exact, results): (&[ContactInput], &[CreepForces], &[CreepForces]),
    held_out_grid: (usize, usize),
    (worst, grids): (usize, [(usize, usize); 2]),
) {
    let limit = FRICTION * NORMAL_FORCE;
    let scaled = |f: &CreepForces| {
        [f.force_longitudinal / limit, f.force_lateral / limit, f.spin_moment.unwrap() / (limit * MEAN_SEMI_AXIS)]
    };
    // max(|ΔF_x|, |ΔF_y|) and |ΔM_z|.
    let errors = |a: [f64; 3], b: [f64; 3]| [(a[0] - b[0]).abs().max((a[1] - b[1]).abs()), (a[2] - b[2]).abs()];
    let held_out_error = |i: usize| errors(scaled(&results[i]), scaled(&exact[i]));
    let mut order: Vec<usize> = (0..cases.len()).collect();
    order.sort_by(|&i, &j| {
        let largest = |i: usize| held_out_error(i).into_iter().fold(0.0, f64::max);
        largest(j).total_cmp(&largest(i))
    });
    order.truncate(worst);
    let chosen: Vec<ContactInput> = order.iter().map(|&i| cases[i]).collect();
    // A reference solve that does not converge (`ExactSolution::converged`) leaves its point
    // out, said in its row, rather than comparing against an unconverged iterate.
    let solve = |(longitudinal, lateral): (usize, usize)| -> Vec<Option<CreepForces>> {
        let model = ExactTheory::new(longitudinal, lateral);
        chosen.par_iter().map(|input| Some(model.solve(input).ok()?.converged().ok()?.forces)).collect()
    };
    let (coarse, fine) = (solve(grids[0]), solve(grids[1]));
    let [(n1, lateral), (n2, _)] = grids;
    let (w1, w2) = (n1 as f64 / (n2 - n1) as f64, n2 as f64 / (n2 - n1) as f64);
    writeln!(
        report,
        "\nThe {worst} worst of these points against the converged theory (the solver converges along x as \
         1/n_x: F∞ = (n₂F(n₂) − n₁F(n₁))/(n₂ − n₁) from {n1} and {n2} × {lateral} elements), as \
         max(|ΔF_x|, |ΔF_y|)/(μQ) / |ΔM_z|/(μQc):\n\n\
         | a/b | ν | ξ | η | φ [1/m] | table vs {0}×{1} | table vs converged | {0}×{1} vs converged |\n\
         |---|---|---|---|---|---|---|---|",
        held_out_grid.0, held_out_grid.1
    )
    .unwrap();
    let mut largest = [0.0f64; 2];
    for (k, &i) in order.iter().enumerate() {
        let input = &cases[i];
        let held_out = held_out_error(i);
        write!(
            report,
            "| {:.3} | {:.3} | {:.2e} | {:.2e} | {:.2e} | {:.4} / {:.4} |",
            input.semi_axis_a / input.semi_axis_b,
            input.poisson_ratio,
            input.creepage_longitudinal,
            input.creepage_lateral,
            input.spin_creepage,
            held_out[0],
            held_out[1],
        )
        .unwrap();
        let (Some(coarse), Some(fine)) = (&coarse[k], &fine[k]) else {
            writeln!(report, " the reference did not converge | |").unwrap();
            continue;
        };
        let converged = [0, 1, 2].map(|m| w2 * scaled(fine)[m] - w1 * scaled(coarse)[m]);
        let table = errors(scaled(&results[i]), converged);
        let reference = errors(scaled(&exact[i]), converged);
        largest = [largest[0].max(table[0]), largest[1].max(table[1])];
        writeln!(report, " {:.4} / {:.4} | {:.4} / {:.4} |", table[0], table[1], reference[0], reference[1]).unwrap();
    }
    writeln!(
        report,
        "\nLargest table error against the converged theory among them: {:.4} μQ (F), {:.4} μQc (M_z).\n",
        largest[0], largest[1]
    )
    .unwrap();
}

/// CONTACT's published values (core/tests/data/contact_published_cases.md): the exact theory, and
/// CONTACT's own FASTSIM on the `fastsim` case; an independent check of the reference.
fn write_contact_comparison(report: &mut String, settings: &Settings) -> std::io::Result<()> {
    let published = FASTSIM_CASE_EXACT;
    let (coarse, fine) = settings.exact_grids;
    writeln!(
        report,
        "## Against CONTACT (published examples)\n\n`tractcurv`: a/b = 0.5, pure ξ, the {} published exact-theory \
         points from 0.001 % to 25 % (core/tests/data/contact_published_cases.md, case 1; CONTACT's grid 48 × 44). \
         `fastsim`: a = 8 mm, b = 4 mm, η = −6.25e-4, φ = 0.625 /m (case 2): CONTACT's exact theory on its \
         44 × 44 grid gives F_y/(μN) = {}, M_z = {} N·m.\n\n\
         | model | tractcurv max abs ΔF_x/(μN) | fastsim F_y/(μN) | fastsim M_z [N·m] |\n|---|---|---|---|",
        TRACTCURV_EXACT.len(),
        published.force_lateral_ratio,
        published.spin_moment
    )
    .unwrap();
    let mut models = ladder(settings.fastsim_grids);
    let finest = format!("_{0}x{0}", settings.fastsim_grids.last().unwrap());
    models.retain(|(name, _)| {
        !name.starts_with("fastsim")
            || name.ends_with("_20x20")
            || name.ends_with(&finest)
            || name.contains("contact_grid")
    });
    models.push(("exact, CONTACT's grids (48 × 44, 44 × 44)".to_owned(), Box::new(exact(44))));
    for (name, model) in &models {
        let tractcurv_model: &dyn CreepForceModel =
            if name.starts_with("exact") { &ExactTheory::new(48, 44) } else { model.as_ref() };
        let max_error = tractcurv_error(tractcurv_model);
        let f = model.creep_forces(&FASTSIM_CASE).unwrap();
        let mz = f.spin_moment.map_or("—".to_owned(), |m| format!("{m:.2}"));
        writeln!(report, "| {name} | {max_error:.4} | {:.4} | {mz} |", f.force_lateral / FASTSIM_CASE.friction_limit())
            .unwrap();
    }
    let mut inputs: Vec<ContactInput> = TRACTCURV_EXACT
        .iter()
        .map(|&(xi_percent, _)| ContactInput { creepage_longitudinal: xi_percent / 100.0, ..TRACTCURV_CONTACT })
        .collect();
    inputs.push(FASTSIM_CASE);
    let solve_all = |n: usize| -> Vec<CreepForces> {
        exact(n).creep_forces_many(&inputs).into_iter().collect::<Result<_, _>>().expect("valid cases")
    };
    let extrapolated: Vec<CreepForces> =
        solve_all(coarse).iter().zip(&solve_all(fine)).map(|(c, f)| richardson(c, f)).collect();
    let tractcurv_reference = TRACTCURV_EXACT
        .iter()
        .zip(&extrapolated)
        .map(|(&(_, published), forces)| {
            (forces.force_longitudinal / TRACTCURV_CONTACT.friction_limit() - published).abs()
        })
        .fold(0.0, f64::max);
    let f = extrapolated[TRACTCURV_EXACT.len()];
    writeln!(
        report,
        "| the reference: exact, {coarse}/{fine} extrapolated | {tractcurv_reference:.4} | {:.4} | {:.2} |",
        f.force_lateral / FASTSIM_CASE.friction_limit(),
        f.spin_moment.unwrap()
    )
    .unwrap();
    for published in FASTSIM_CASE_CONTACT_FASTSIM {
        let n = published.elements_in_contact;
        writeln!(
            report,
            "| CONTACT's FASTSIM, {}, {n} × {n} in the contact | — | {:.4} | {:.2} |",
            bound_name(published.bound),
            published.result.force_lateral_ratio,
            published.result.spin_moment
        )
        .unwrap();
    }
    writeln!(
        report,
        "| CONTACT exact theory (44 × 44) | 0 | {:.4} | {:.2} |\n\n\
         CONTACT's published exact values carry its grid's first-order error like our `exact` rows on the same \
         grids; the extrapolated reference differs from them by that error. `fastsim_contact_grid` is CONTACT's \
         FASTSIM discretisation (`Discretisation::ContactGrid`) and reproduces CONTACT's own FASTSIM rows.\n\n\
         ![pure ξ](curve_xi.svg)\n![pure η](curve_eta.svg)\n![pure spin](curve_spin.svg)",
        published.force_lateral_ratio, published.spin_moment
    )
    .unwrap();
    Ok(())
}

/// A wheel from profiles, per contact method and rung, against CONTACT's full solution of the
/// Manchester benchmark A-2.2 (both wheels, all 42 cases, 10 kN, μ = 0.3): the worst errors of
/// the contact point, the angle, the normal force, each patch's creep forces and the wheel's
/// totals, and the time of one wheel step (prescribed force, from rest), the least over a few
/// passes through every case. Every rung but the offline exact theory; FASTSIM on 20 × 20.
fn write_wheel_comparison(report: &mut String, settings: &Settings) {
    report.push_str(
        "\n\n## From profiles: contact method × rung against CONTACT (Manchester A-2.2)\n\n\
         A wheel from the S1002 and UIC60 profiles (`contact_geometry = profiles`), both wheels, all 42 cases of \
         case A-2.2 (10 kN, μ = 0.3, V = 2 m/s), against CONTACT's published full solution (non-Hertzian patch, \
         exact theory; `wheel_rail_contact::reference_cases::manchester_a22`). Errors: the contact point on the \
         rail [mm] and its angle [rad] against CONTACT's contact reference, the normal force relative, each \
         patch's creep forces F_x, F_s over μN and the wheel's total forces over μF_z (cases with one patch, as \
         CONTACT; with `hertz` the cases where it finds two are counted apart; refused: the vertical balance did not settle, an error \
         naming it). Time: one wheel step with the \
         vertical balance from a cold cache (no last step to start from), each case's least over the passes, their \
         mean and the slowest case; \
         `non_hertzian` with its strip table, as the FMU builds it.\n\n\
         | contact method | rung | cases with CONTACT's one patch | rail y max [mm] | angle max [rad] | N max | \
         creep max [μN] | totals max [μF_z] | µs / wheel step | slowest case [µs] |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let cases = manchester_a22();
    let mut rungs: Vec<(String, ModelChoice)> = ModelChoice::RUNGS
        .iter()
        .filter(|rung| !rung.offline && rung.name != fastsim::RUNG.name)
        .map(|rung| (rung.name.to_owned(), (rung.default_model)().unwrap_or_else(|e| panic!("{}: {e}", rung.name))))
        .collect();
    rungs.push(("fastsim_elliptic_20x20".to_owned(), ModelChoice::Fastsim(fastsim(20, TractionBound::Elliptic))));
    for (method, method_name) in [(ContactMethod::Hertz, "hertz"), (ContactMethod::NonHertzian, "non_hertzian")] {
        for (rung, model) in &rungs {
            let contact = |side| {
                let scene = Scene::of_model(*model, SHEAR_MODULUS, POISSON);
                let contact = WheelRailContact::new(WheelOnRail::manchester_benchmark(side), scene).with_method(method);
                // As the FMU evaluates it: the non-Hertzian strips from the strip table.
                match method {
                    ContactMethod::NonHertzian => contact.with_strip_table(),
                    ContactMethod::Hertz => contact,
                }
            };
            let (right, left) = (contact(WheelSide::Right), contact(WheelSide::Left));
            let wheel = |case: &ManchesterA22| if case.side == WheelSide::Right { &right } else { &left };
            let step = |case: &ManchesterA22| {
                wheel(case)
                    .evaluate(&case.input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise)
                    .map(|(output, _)| output)
                    .map_err(|e| e.to_string())
            };
            let mut worst = [0.0f64; 5];
            let (mut single, mut failed) = (0, 0);
            for case in &cases {
                let Ok(output) = step(case) else {
                    failed += 1;
                    continue;
                };
                if output.patches.len() != 1 {
                    continue;
                }
                single += 1;
                let patch = &output.patches[0];
                let limit = case.input.friction_coefficient * case.normal_force;
                let errors = [
                    (patch.patch.point.rail_lateral - case.rail_lateral).abs() * 1e3,
                    (patch.patch.point.contact_angle - case.contact_angle).abs(),
                    (patch.patch.normal_force / case.normal_force - 1.0).abs(),
                    (patch.output.force_longitudinal - case.creep_forces[0])
                        .abs()
                        .max((patch.output.force_lateral - case.creep_forces[1]).abs())
                        / limit,
                    (0..3).map(|i| (output.track_force[i] - case.track_force[i]).abs()).fold(0.0, f64::max) / 3e3,
                ];
                for (w, e) in worst.iter_mut().zip(errors) {
                    *w = w.max(e);
                }
            }
            let passes = if settings.quick { 2 } else { 5 };
            // Each case's least time over the passes: their mean, and the slowest case.
            let times: Vec<f64> = cases
                .iter()
                .map(|case| {
                    (0..passes)
                        .map(|_| {
                            let started = Instant::now();
                            let _ = black_box(step(black_box(case)));
                            started.elapsed().as_secs_f64()
                        })
                        .fold(f64::INFINITY, f64::min)
                })
                .collect();
            let microseconds = times.iter().sum::<f64>() / cases.len() as f64 * 1e6;
            let (slowest, slowest_seconds) =
                cases.iter().zip(&times).max_by(|a, b| a.1.total_cmp(b.1)).expect("the A-2.2 cases");
            let side = if slowest.side == WheelSide::Right { "right" } else { "left" };
            let slowest = format!("{:.0} ({side} {})", slowest_seconds * 1e6, slowest.case);
            writeln!(
                report,
                "| {method_name} | {rung} | {single} of {}{} | {:.2} | {:.4} | {:.3} | {:.3} | {:.3} | {microseconds:.1} | {slowest} |",
                cases.len(),
                if failed > 0 { format!(" ({failed} refused)") } else { String::new() },
                worst[0],
                worst[1],
                worst[2],
                worst[3],
                worst[4]
            )
            .unwrap();
        }
    }
    report.push_str(
        "\nThe issue's tolerances (CONTACT's own fast methods against its full solution): 1 mm and 0.01 rad on the \
         tread (2 mm, 0.05 rad on the flange), 3 % in N, 0.12 μN in the forces (0.17 on the flange). `hertz` finds \
         two patches where CONTACT finds one on the right wheel's case 11, and its point is off the flat gap's \
         wide patch at y_ws = 0 and 0.5 mm; `polach` is short of full slip under the flange's large spin \
         (docs/geometry.md). Per case and method: `core/tests/library/wheel_non_hertzian.rs`, \
         `core/tests/library/geometry_wheel_forces.rs`.\n",
    );
}

/// Largest |ΔF_x|/(μN) over CONTACT's published `tractcurv` exact-theory curve.
fn tractcurv_error(model: &dyn CreepForceModel) -> f64 {
    TRACTCURV_EXACT
        .iter()
        .map(|&(xi_percent, published)| {
            let input = ContactInput { creepage_longitudinal: xi_percent / 100.0, ..TRACTCURV_CONTACT };
            (model.creep_forces(&input).unwrap().force_longitudinal / input.friction_limit() - published).abs()
        })
        .fold(0.0, f64::max)
}

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(127, 127, 127),
];

/// A row's model family and grid: "fastsim_elliptic_20x20" → ("fastsim_elliptic", "20x20").
fn family_and_grid(name: &str) -> (&str, &str) {
    match name.rsplit_once('_') {
        Some((family, grid)) if grid.contains('x') && grid.starts_with(|c: char| c.is_ascii_digit()) => (family, grid),
        _ => (name, ""),
    }
}

/// Error against time, the median (left) and the maximum (right) over the cases of
/// max(|ΔF_x|, |ΔF_y|)/(μQ): the median alone hides the large errors with spin.
fn plot_pareto(path: &str, rows: &[Row]) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (1400, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(700);
    draw_pareto(&left, rows, "median", &|r: &Row| r.fx.0.max(r.fy.0))?;
    draw_pareto(&right, rows, "max", &|r: &Row| r.fx.1.max(r.fy.1))?;
    root.present()?;
    Ok(())
}

fn draw_pareto<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[Row],
    statistic: &str,
    error: &dyn Fn(&Row) -> f64,
) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let error = |r: &Row| error(r).max(1e-6);
    let (t_min, t_max) =
        rows.iter().fold((f64::MAX, 0.0_f64), |(lo, hi), r| (lo.min(r.nanoseconds), hi.max(r.nanoseconds)));
    let (e_min, e_max) = rows.iter().fold((f64::MAX, 0.0_f64), |(lo, hi), r| (lo.min(error(r)), hi.max(error(r))));
    let mut chart = ChartBuilder::on(area)
        .caption(format!("{statistic} error max(F_x, F_y)/(μQ) vs time"), ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((t_min * 0.5..t_max * 3.0).log_scale(), (e_min * 0.5..e_max * 4.0).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("ns per evaluation")
        .y_desc(format!("{statistic} error / (μQ)"))
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    // One colour and one legend entry per model family; a family's grids are joined by a line
    // and labelled at their points.
    let mut families: Vec<&str> = Vec::new();
    for row in rows {
        let (family, _) = family_and_grid(&row.name);
        if !families.contains(&family) {
            families.push(family);
        }
    }
    for (i, family) in families.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let members: Vec<(f64, f64, &str)> = rows
            .iter()
            .filter(|r| family_and_grid(&r.name).0 == *family)
            .map(|r| (r.nanoseconds, error(r), family_and_grid(&r.name).1))
            .collect();
        chart.draw_series(LineSeries::new(members.iter().map(|&(t, e, _)| (t, e)), color.mix(0.6)))?;
        chart
            .draw_series(members.iter().map(|&(t, e, _)| Circle::new((t, e), 5, color.filled())))?
            .label(family.to_string())
            .legend(move |(x, y)| Circle::new((x, y), 5, color.filled()));
        chart.draw_series(
            members
                .iter()
                .filter(|(_, _, grid)| !grid.is_empty())
                .map(|&(t, e, grid)| Text::new(grid.to_owned(), (t * 1.08, e * 1.12), ("sans-serif", 11).into_font())),
        )?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

fn plot_curves(
    path: &str,
    title: &str,
    direction: Direction,
    settings: &Settings,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let (xs, es, ps) = characteristic(1.0);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..4.0, -1.3..0.05)?;
    chart.configure_mesh().x_desc("creepage / characteristic creepage").y_desc("force / (μQ)").draw()?;
    let mut models = ladder(settings.fastsim_grids);
    models.retain(|(name, _)| !name.starts_with("fastsim") || name.ends_with("_5x5") || name.ends_with("_20x20"));
    let (coarse, _) = settings.exact_grids;
    models.push((format!("exact ({coarse} × {coarse})"), Box::new(exact(coarse))));
    for (i, (name, model)) in models.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        // The exact theory costs ≈ 0.1 s per point: every fourth point.
        let stride = if name.starts_with("exact") { 4 } else { 1 };
        let curve: Vec<(f64, f64)> = (0..=CURVE_POINTS)
            .step_by(stride)
            .map(|k| {
                let level = 4.0 * k as f64 / CURVE_POINTS as f64;
                let input = match direction {
                    Direction::Xi => contact(1.0, level * xs, 0.0, 0.0),
                    Direction::Eta => contact(1.0, 0.0, level * es, 0.0),
                    Direction::Spin => contact(1.0, 0.0, 0.0, level * ps),
                };
                let f = model.creep_forces(&input).unwrap();
                let force = if matches!(direction, Direction::Xi) { f.force_longitudinal } else { f.force_lateral };
                (level, (force / input.friction_limit()).max(-1.3))
            })
            .collect();
        chart
            .draw_series(LineSeries::new(curve, color.stroke_width(2)))?
            .label(name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
    root.present()?;
    Ok(())
}
