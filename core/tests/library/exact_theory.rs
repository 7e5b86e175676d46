//! Kalker's exact theory (`ExactTheory`) against Kalker's linear coefficients, CONTACT's
//! published cases, and the invariants of the contact problem.

use rayon::prelude::*;
use wheel_rail_contact::{ContactInput, CreepForceModel, ElementState, ExactTheory, KalkerCoefficients, WarmStart};

const SHEAR_MODULUS: f64 = 82e9;

fn input(a: f64, b: f64, normal_force: f64, mu: f64, nu: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: 0.0,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        normal_force,
        semi_axis_a: a,
        semi_axis_b: b,
        friction_coefficient: mu,
        shear_modulus: SHEAR_MODULUS,
        poisson_ratio: nu,
    }
}

fn relative_error(value: f64, reference: f64) -> f64 {
    (value / reference - 1.0).abs()
}

/// CONTACT's `examples/fastsim` case (values from the example output shipped with the
/// open-source CONTACT program, Vollebregt & Kalker, Apache-2.0): a = 8 mm, b = 4 mm, N = 82 kN, μ = 0.3, ν = 0.28,
/// η = −6.25e-4, φ = 6.25e-4 /mm.
fn contact_spin_case() -> ContactInput {
    ContactInput { creepage_lateral: -6.25e-4, spin_creepage: 0.625, ..input(8e-3, 4e-3, 82e3, 0.3, 0.28) }
}

/// Full adhesion: with tiny creepages nothing slips and the forces are Kalker's linear theory,
/// F_x = −G ab C11 ξ, F_y = −G ab C22 η − G (ab)^{3/2} C23 φ (Kalker 1990, table E.3).
///
/// Grid 80 × 40 (80 along the rolling direction): the discretisation error of steady rolling is
/// first order and dominated by δx. Measured worst cases on this grid: C11 +0.84 % (a/b = 0.5,
/// ν = 0.5), C23 −0.71 % (a/b = 0.2, ν = 0.5); on 40 × 40 errors reach 2 %.
#[test]
fn full_adhesion_reproduces_kalkers_coefficients() {
    let model = ExactTheory::new(80, 40);
    let b = 5e-3;
    for a_over_b in [0.2, 0.5, 1.0, 2.0] {
        for nu in [0.0, 0.25, 0.5] {
            let a = a_over_b * b;
            let kalker = KalkerCoefficients::new(a_over_b, nu);
            let (creepage, spin) = (1e-7, 1e-5);
            let base = input(a, b, 1e5, 0.3, nu);
            // ξ and η together: by the symmetry y → −y neither drives the other's force.
            let creep = ContactInput { creepage_longitudinal: creepage, creepage_lateral: creepage, ..base };
            let spinning = ContactInput { spin_creepage: spin, ..base };
            for case in [creep, spinning] {
                let solution = model.solve(&case).unwrap();
                assert!(
                    solution.converged && solution.slip_area == 0.0,
                    "a/b {a_over_b}, ν {nu}: not in full adhesion"
                );
            }
            let creep_forces = model.creep_forces(&creep).unwrap();
            let spin_forces = model.creep_forces(&spinning).unwrap();
            let c11 = -creep_forces.force_longitudinal / (SHEAR_MODULUS * a * b * creepage);
            let c22 = -creep_forces.force_lateral / (SHEAR_MODULUS * a * b * creepage);
            let c23 = -spin_forces.force_lateral / (SHEAR_MODULUS * (a * b).powf(1.5) * spin);
            for (name, value, reference) in
                [("C11", c11, kalker.c11), ("C22", c22, kalker.c22), ("C23", c23, kalker.c23)]
            {
                assert!(
                    relative_error(value, reference) < 0.01,
                    "a/b {a_over_b}, ν {nu}: {name} = {value:.4}, Kalker {reference:.4}"
                );
            }
        }
    }
}

/// On fine grids the solver reproduces Kalker's table (Kalker 1990, table E.3) at the table's
/// own rows (no interpolation between rows, which alone is worth 2 % in C23 at a/b = 3) within
/// 0.5 % over a/b = 0.1 … 2 and ν = 0, 0.25, 0.5, with two exceptions; at a/b = 5 and 10 it is
/// within 0.5 % for C23 and above the table for C11 and C22. Every entry beyond 0.5 % is held to
/// its measured deviation (± 0.2 %). All rows: docs/reference/kalker-table-check.txt
/// (`cargo run --release -p lab --bin kalker_table_check`).
/// - C11 at a/b = 0.5, ν = 0.5, +1.0 %: a table outlier. The solver is 0.4 % above the table at
///   a/b = 0.3, 0.4, 0.6 and 0.7; its values 4.819, 4.839, 4.877, 4.929, 4.991 run smoothly
///   where the table's 4.80, 4.82, 4.83, 4.91, 4.97 do not.
/// - C23 at a/b = 0.1, ν = 0.5, −0.9 % (−0.85 % on 200 × 400; refining either axis moves it
///   towards the table by ≈ 0.1 %).
/// - a > b: C11 and C22 above the table by an amount growing with a/b (C22 at ν = 0.25: +0.3 %
///   at 2, +0.6 % at 5, +1.2 % at 10). Refining along y raises them (a/b = 10, C22 on 400 × 40,
///   80, 160, 320: +0.94, +1.22, +1.32, +1.39 %), along x lowers them (−0.3 % from 200 to 400
///   elements), so the converged solver stays ≈ 0.6 % (C11) and ≈ 1.1 % (C22) above the
///   table's three digits at a/b = 10. Whether the table (computed in 1967 with a truncated
///   polynomial method, least accurate for slender ellipses) or the solver is off there is open:
///   no independent converged value is at hand.
#[test]
#[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
fn fine_grids_reproduce_kalkers_table_at_its_rows() {
    // a/b, and the grid: 300 elements along the longer semi-axis, at least 120 across.
    let rows: [(f64, usize, usize); 7] = [
        (0.1, 150, 300),
        (0.2, 150, 300),
        (0.5, 150, 300),
        (1.0, 300, 300),
        (2.0, 300, 150),
        (5.0, 300, 120),
        (10.0, 300, 120),
    ];
    // (a/b, ν, coefficient, measured deviation from the table).
    let known = [
        (0.1, 0.5, "C23", -0.0089),
        (0.5, 0.5, "C11", 0.0100),
        (5.0, 0.0, "C11", 0.0053),
        (5.0, 0.0, "C22", 0.0053),
        (5.0, 0.25, "C22", 0.0061),
        (5.0, 0.5, "C22", 0.0081),
        (10.0, 0.0, "C11", 0.0092),
        (10.0, 0.0, "C22", 0.0092),
        (10.0, 0.25, "C11", 0.0073),
        (10.0, 0.25, "C22", 0.0118),
        (10.0, 0.5, "C11", 0.0054),
        (10.0, 0.5, "C22", 0.0109),
    ];
    let cases: Vec<(f64, usize, usize, f64)> =
        rows.iter().flat_map(|&(r, nx, ny)| [0.0, 0.25, 0.5].map(|nu| (r, nx, ny, nu))).collect();
    let solved: Vec<_> = cases
        .par_iter()
        .map(|&(a_over_b, nx, ny, nu)| ExactTheory::new(nx, ny).linear_coefficients(a_over_b, nu).unwrap())
        .collect();
    for (&(a_over_b, _, _, nu), solver) in cases.iter().zip(&solved) {
        let table = KalkerCoefficients::new(a_over_b, nu);
        for (name, value, reference) in
            [("C11", solver.c11, table.c11), ("C22", solver.c22, table.c22), ("C23", solver.c23, table.c23)]
        {
            let deviation = value / reference - 1.0;
            let expected = known.iter().find(|k| (k.0, k.1, k.2) == (a_over_b, nu, name)).map(|k| k.3);
            let within = match expected {
                Some(measured) => (deviation - measured).abs() <= 0.002,
                None => deviation.abs() <= 0.005,
            };
            assert!(within, "a/b {a_over_b}, ν {nu}: {name} = {value:.4}, Kalker {reference:.4} ({deviation:+.4})");
        }
    }
}

/// CONTACT's published exact-theory result on its own grid (44 × 44 elements of 0.4 × 0.2 mm):
/// F_y/(μN) = −0.6074, M_z = −48.21 N·m. Measured: −0.6097 (+0.38 %), −48.39 N·m (+0.37 %).
#[test]
fn reproduces_contacts_published_spin_case() {
    let case = contact_spin_case();
    let solution = ExactTheory::new(44, 44).solve(&case).unwrap();
    assert!(solution.converged);
    assert!((solution.element_length - 0.4e-3).abs() < 1e-12 && (solution.element_width - 0.2e-3).abs() < 1e-12);
    let forces = solution.forces;
    let normalised_lateral = forces.force_lateral / case.friction_limit();
    assert!(relative_error(normalised_lateral, -0.6074) < 0.01, "F_y/(μN) = {normalised_lateral}");
    let moment = forces.spin_moment.unwrap();
    assert!(relative_error(moment, -48.21) < 0.01, "M_z = {moment}");
    // No longitudinal creepage, and the problem is symmetric in y: F_x vanishes.
    assert!(forces.force_longitudinal.abs() < 1e-6 * case.friction_limit());
    // Partial slip: both areas present, adding up to the contact area.
    assert!(solution.adhesion_area > 0.0 && solution.slip_area > 0.0);
    let contact_elements = solution.element_state.iter().filter(|&&state| state != ElementState::Exterior).count();
    let ellipse_elements = std::f64::consts::PI * 8.0 * 4.0 / (0.4 * 0.2);
    assert!(relative_error(contact_elements as f64, ellipse_elements) < 0.01, "{contact_elements} elements inside");
    let contact_area = contact_elements as f64 * solution.element_length * solution.element_width;
    assert!(relative_error(solution.adhesion_area + solution.slip_area, contact_area) < 1e-12);
    // CONTACT's grid is centred on the contact: 22 elements either side of each axis.
    for ((i, j), (x, y)) in [((0, 0), (-8.6e-3, -4.3e-3)), ((43, 43), (8.6e-3, 4.3e-3)), ((22, 21), (0.2e-3, -0.1e-3))]
    {
        let (centre_x, centre_y) = solution.element_centre(i, j);
        assert!((centre_x - x).abs() < 1e-15 && (centre_y - y).abs() < 1e-15, "({i}, {j}): ({centre_x}, {centre_y})");
    }
}

/// The exact-theory creep curve of CONTACT's Eurosprinter example (`core/tests/data`), on CONTACT's
/// grid of 48 × 44 elements. Measured differences in F_x/(μN): +0.0002, +0.0001, −0.0005,
/// −0.0008, +0.0001 at ξ = 0.04, 0.12, 0.2, 0.28, 1 %.
#[test]
fn reproduces_contacts_eurosprinter_creep_curve() {
    let data = include_str!("../data/contact_tractcurv_eurosprinter.csv");
    let curve: Vec<(f64, f64)> = data
        .lines()
        .filter(|line| !line.starts_with('#') && !line.starts_with("creepage"))
        .map(|line| {
            let (creepage, force) = line.split_once(',').unwrap();
            (creepage.parse::<f64>().unwrap() / 100.0, force.parse().unwrap())
        })
        .collect();
    assert_eq!(curve.len(), 30);
    let model = ExactTheory::new(48, 44);
    let base = input(6.304e-3, 12.61e-3, 106.7e3, 0.33, 0.28);
    for &(creepage, published) in
        curve.iter().filter(|(creepage, _)| [0.0004, 0.0012, 0.002, 0.0028, 0.01].contains(creepage))
    {
        let forces = model.creep_forces(&ContactInput { creepage_longitudinal: creepage, ..base }).unwrap();
        let normalised = forces.force_longitudinal / base.friction_limit();
        assert!(
            (normalised - published).abs() < 0.01,
            "ξ = {creepage}: F_x/(μN) = {normalised:.4}, CONTACT {published}"
        );
    }
}

/// Large creepage: every element slips and the force is the Coulomb limit μQ, in the
/// direction opposite to the creepage. (Measured |F|/(μQ) = 0.999996: the elastic part of the
/// slip still turns the slip directions by ~1e-3 rad at 10 % creepage.)
#[test]
fn full_slip_gives_the_coulomb_limit() {
    let model = ExactTheory::new(24, 24);
    let base = input(6e-3, 4e-3, 90e3, 0.35, 0.28);
    for (xi, eta) in [(0.1, 0.0), (0.0, -0.1), (0.06, 0.08)] {
        let case = ContactInput { creepage_longitudinal: xi, creepage_lateral: eta, ..base };
        let solution = model.solve(&case).unwrap();
        assert_eq!(solution.adhesion_area, 0.0, "ξ {xi}, η {eta}: adhesion left");
        let forces = solution.forces;
        assert!((forces.adhesion_utilisation - 1.0).abs() < 1e-5, "|F|/(μQ) = {}", forces.adhesion_utilisation);
        let along_creepage = (forces.force_longitudinal * xi + forces.force_lateral * eta) / xi.hypot(eta);
        assert!((along_creepage + case.friction_limit()).abs() < 1e-5 * case.friction_limit());
    }
}

/// The forces converge as the grid is refined: on doubling the grid the change shrinks.
///
/// Partial slip under pure ξ (F ≈ 0.47 μQ). Measured F_x/(μN): −0.4806 (16²), −0.4707 (32²),
/// −0.4693 (64²). Element-boundary staircase effects make single refinements non-monotone by
/// up to 1 % in spin cases (CONTACT's spin case: −0.5947, −0.6097, −0.6178 on 22², 44², 88²,
/// but −0.6153 on 64²), so the test uses doubling, which keeps the staircase similar.
#[test]
fn forces_converge_with_grid_refinement() {
    let case = ContactInput { creepage_longitudinal: 1e-3, ..input(8e-3, 4e-3, 82e3, 0.3, 0.28) };
    let longitudinal =
        |n: usize| ExactTheory::new(n, n).creep_forces(&case).unwrap().force_longitudinal / case.friction_limit();
    let (coarse, medium, fine) = (longitudinal(16), longitudinal(32), longitudinal(64));
    assert!((fine - medium).abs() < 0.5 * (medium - coarse).abs(), "{coarse} {medium} {fine}");
    assert!((fine - medium).abs() < 0.005, "{medium} {fine}");
}

/// Forces oppose the creepages, are odd in (ξ, η, φ) together, and never exceed μQ.
#[test]
fn invariants_sign_oddness_and_coulomb_bound() {
    let model = ExactTheory::new(20, 20);
    let base = input(7e-3, 5e-3, 80e3, 0.3, 0.25);
    for (xi, eta, phi) in [(5e-4, 0.0, 0.0), (0.0, 8e-4, 0.0), (1e-3, -2e-3, 0.5), (3e-3, 1e-3, -2.0), (0.0, 0.0, 1.5)]
    {
        let case = ContactInput { creepage_longitudinal: xi, creepage_lateral: eta, spin_creepage: phi, ..base };
        let mirrored = ContactInput { creepage_longitudinal: -xi, creepage_lateral: -eta, spin_creepage: -phi, ..base };
        let forces = model.creep_forces(&case).unwrap();
        let opposite = model.creep_forces(&mirrored).unwrap();
        let limit = case.friction_limit();
        assert!(forces.adhesion_utilisation <= 1.0 + 1e-12, "|F| > μQ: {forces:?}");
        assert!((forces.force_longitudinal + opposite.force_longitudinal).abs() < 1e-5 * limit);
        assert!((forces.force_lateral + opposite.force_lateral).abs() < 1e-5 * limit);
        let moment = forces.spin_moment.unwrap();
        assert!((moment + opposite.spin_moment.unwrap()).abs() < 1e-5 * limit * case.semi_axis_a);
        // Pure creepage: the force opposes it; pure spin: the moment opposes it.
        if phi == 0.0 {
            assert!(forces.force_longitudinal * xi + forces.force_lateral * eta < 0.0);
        }
        if xi == 0.0 && eta == 0.0 {
            assert!(moment * phi < 0.0 && forces.force_lateral * phi < 0.0);
        }
    }
    // Monotone saturation in ξ.
    let mut previous = 0.0;
    for xi in [1e-4, 5e-4, 1e-3, 2e-3, 5e-3, 2e-2] {
        let fx = model.creep_forces(&ContactInput { creepage_longitudinal: xi, ..base }).unwrap().force_longitudinal;
        assert!(fx < previous, "not increasing in magnitude at ξ = {xi}");
        previous = fx;
    }
}

/// Degenerate but valid inputs give zero force; invalid ones are named.
#[test]
fn degenerate_and_invalid_inputs() {
    let model = ExactTheory::new(10, 10);
    let base = ContactInput { creepage_longitudinal: 1e-3, spin_creepage: 0.3, ..input(6e-3, 4e-3, 80e3, 0.3, 0.28) };
    let no_creepage = model.creep_forces(&input(6e-3, 4e-3, 80e3, 0.3, 0.28)).unwrap();
    assert_eq!(
        (no_creepage.force_longitudinal, no_creepage.force_lateral, no_creepage.spin_moment),
        (0.0, 0.0, Some(0.0))
    );
    let lifted = model.solve(&ContactInput { normal_force: -5.0, ..base }).unwrap();
    assert_eq!(lifted.forces.force_longitudinal, 0.0);
    assert!(lifted.element_state.iter().all(|&state| state == ElementState::Exterior));
    let frictionless = model.solve(&ContactInput { friction_coefficient: 0.0, ..base }).unwrap();
    assert_eq!((frictionless.forces.force_longitudinal, frictionless.adhesion_area), (0.0, 0.0));
    // Without friction every element in contact slides.
    let in_contact = frictionless.element_state.iter().filter(|&&state| state == ElementState::Slip).count();
    let element_area = frictionless.element_length * frictionless.element_width;
    assert!(in_contact > 50 && relative_error(frictionless.slip_area, in_contact as f64 * element_area) < 1e-12);
    let error = ExactTheory::new(0, 10).creep_forces(&base).unwrap_err();
    assert_eq!(error.to_string(), "grid_elements_longitudinal = 0 is invalid: must lie in [1, 400]");
    assert!(ExactTheory::new(400, 400).validate().is_ok());
    let error = ExactTheory::new(400, 401).validate().unwrap_err();
    assert_eq!(error.to_string(), "grid_elements_lateral = 401 is invalid: must lie in [1, 400]");
    // Refused as such, not through the nested start's coarser (valid) grids.
    let error = ExactTheory::new(1000, 1000).solve(&base).unwrap_err();
    assert_eq!(error.to_string(), "grid_elements_longitudinal = 1000 is invalid: must lie in [1, 400]");
    let error = ExactTheory::new(1000, 40).solve(&ContactInput { semi_axis_b: f64::NAN, ..base }).unwrap_err();
    assert_eq!(error.variable, "semi_axis_b");
    let error = model.creep_forces(&ContactInput { poisson_ratio: 0.7, ..base }).unwrap_err();
    assert_eq!(error.variable, "poisson_ratio");
    // One element, and absurd magnitudes: finite results on the Coulomb bound.
    for case in [
        ContactInput { creepage_longitudinal: 1e300, spin_creepage: -1e300, ..base },
        ContactInput { shear_modulus: 1e-300, ..base },
        ContactInput { friction_coefficient: 1e-300, ..base },
    ] {
        for grid in [ExactTheory::new(1, 1), ExactTheory::new(3, 5)] {
            let forces = grid.creep_forces(&case).unwrap();
            assert!(forces.force_longitudinal.is_finite() && forces.force_lateral.is_finite());
            assert!(forces.spin_moment.unwrap().is_finite());
            assert!(forces.adhesion_utilisation <= 1.0 + 1e-12, "{case:?}: {forces:?}");
        }
    }
}

/// Cases of every regime: full adhesion, partial slip under ξ, full slip, pure spin, CONTACT's
/// spin case, and thin ellipses (a/b = 0.1 and 10) with creepage and spin.
fn regime_cases() -> Vec<(&'static str, ContactInput)> {
    let base = input(8e-3, 4e-3, 82e3, 0.3, 0.28);
    vec![
        ("full adhesion", ContactInput { creepage_longitudinal: 1e-7, creepage_lateral: -1e-7, ..base }),
        ("partial slip", ContactInput { creepage_longitudinal: 1e-3, ..base }),
        ("full slip", ContactInput { creepage_longitudinal: 0.05, creepage_lateral: 0.03, ..base }),
        ("pure spin", ContactInput { spin_creepage: 1.0, ..base }),
        ("spin case", contact_spin_case()),
        (
            "a/b = 0.1",
            ContactInput {
                creepage_longitudinal: 5e-4,
                creepage_lateral: 5e-4,
                spin_creepage: 0.3,
                ..input(2e-3, 20e-3, 82e3, 0.3, 0.28)
            },
        ),
        (
            "a/b = 10",
            ContactInput {
                creepage_longitudinal: 5e-4,
                creepage_lateral: 5e-4,
                spin_creepage: 0.3,
                ..input(20e-3, 2e-3, 82e3, 0.3, 0.28)
            },
        ),
    ]
}

/// Largest difference of the forces in units of μQ (the moment in μQa).
fn force_difference(
    case: &ContactInput,
    a: &wheel_rail_contact::CreepForces,
    b: &wheel_rail_contact::CreepForces,
) -> f64 {
    let limit = case.friction_limit();
    let moment = (a.spin_moment.unwrap() - b.spin_moment.unwrap()).abs() / (limit * case.semi_axis_a);
    ((a.force_longitudinal - b.force_longitudinal).abs() / limit)
        .max((a.force_lateral - b.force_lateral).abs() / limit)
        .max(moment)
}

/// Same grid, same answer: the FFT Newton solver equals CONTACT's Gauss–Seidel method
/// (swept to a 1e-11 relative change) to 1e-6 μQ, with the same adhesion and slip areas.
#[test]
fn newton_solver_equals_gauss_seidel() {
    for grid in [ExactTheory::new(24, 24), ExactTheory::new(30, 18)] {
        for (name, case) in regime_cases() {
            let fast = grid.solve(&case).unwrap();
            let reference = grid.solve_by_gauss_seidel(&case, 1e-11).unwrap();
            assert!(fast.converged && reference.converged, "{name}: not converged");
            let difference = force_difference(&case, &fast.forces, &reference.forces);
            assert!(difference < 1e-6, "{name} on {:?}: differs by {difference:.2e} μQ", grid.grid);
            assert_eq!(fast.element_state, reference.element_state, "{name}: other adhesion/slip division");
        }
    }
}

/// Warm starts: from the solution of another creepage sign, of another ellipse, or from zero,
/// the solve reaches the same answer as from zero traction (to the solver's tolerance), and a
/// start from the answer itself needs no more than the two Newton steps of the stopping test
/// (a loose one, then an accurate one that changes nothing).
#[test]
fn warm_starts_converge_to_the_same_answer() {
    let model = ExactTheory::new(32, 32);
    let case = contact_spin_case();
    let cold = model.solve(&case).unwrap();
    let mirrored = ContactInput {
        creepage_lateral: -case.creepage_lateral,
        spin_creepage: -case.spin_creepage,
        creepage_longitudinal: 1e-3,
        ..case
    };
    let other_ellipse = ContactInput { semi_axis_a: 3e-3, semi_axis_b: 9e-3, friction_coefficient: 0.1, ..mirrored };
    let starts = [
        ("other creepage sign", model.solve(&mirrored).unwrap().warm_start()),
        ("other ellipse and μ", model.solve(&other_ellipse).unwrap().warm_start()),
        ("zero", WarmStart::default()),
        ("other grid", ExactTheory::new(20, 20).solve(&case).unwrap().warm_start()),
        ("the answer", cold.warm_start()),
    ];
    for (name, start) in starts {
        let warm = model.solve_from(&case, Some(&start)).unwrap();
        assert!(warm.converged, "{name}");
        let difference = force_difference(&case, &warm.forces, &cold.forces);
        assert!(difference < 1e-8, "{name}: differs by {difference:.2e} μQ");
        assert_eq!(warm.element_state, cold.element_state, "{name}");
    }
    let restarted = model.solve_from(&case, Some(&cold.warm_start())).unwrap();
    assert!(restarted.iterations <= 2, "restart from the answer took {} Newton steps", restarted.iterations);
}

/// Extremes stay finite, within the Coulomb bound, and return: creepage 1e300, a/b = 1e-3 and
/// 1e3, μ → 0, each with spin, on a coarse and a fine grid. (The iteration limits bound the
/// time of every call; these converge well within them.)
#[test]
fn extremes_are_finite_and_bounded() {
    let base = ContactInput { creepage_longitudinal: 1e-3, spin_creepage: 0.3, ..input(6e-3, 4e-3, 80e3, 0.3, 0.28) };
    let cases = [
        ContactInput { creepage_longitudinal: 1e300, creepage_lateral: -1e300, spin_creepage: 1e300, ..base },
        ContactInput { semi_axis_a: 0.4e-3, semi_axis_b: 0.4, ..base },
        ContactInput { semi_axis_a: 0.4, semi_axis_b: 0.4e-3, ..base },
        ContactInput { friction_coefficient: 1e-300, ..base },
        ContactInput { friction_coefficient: 1e-12, ..base },
    ];
    for model in [ExactTheory::new(12, 12), ExactTheory::new(60, 60)] {
        for case in cases {
            let solution = model.solve(&case).unwrap();
            let forces = solution.forces;
            assert!(forces.force_longitudinal.is_finite() && forces.force_lateral.is_finite(), "{case:?}");
            assert!(forces.spin_moment.unwrap().is_finite(), "{case:?}");
            assert!(forces.adhesion_utilisation <= 1.0 + 1e-12, "{case:?}: {forces:?}");
            assert!(solution.converged, "{case:?}: not converged");
        }
    }
}

/// A long ellipse (a/b = 9.8) with spin near the collapse of adhesion, on 320 × 400 elements
/// (eight times longer than wide).
fn long_contact_near_the_collapse() -> ContactInput {
    ContactInput {
        creepage_longitudinal: 7.641165e-4,
        creepage_lateral: -9.891905e-4,
        spin_creepage: 0.1249448,
        poisson_ratio: 0.4644424,
        ..input(15.671075e-3, 1.5952958e-3, 80e3, 0.3, 0.4644424)
    }
}

/// The forces of [`long_contact_near_the_collapse`] on 320 × 400 elements: those of the 300 ×
/// 400 grid (F_x = −0.56187 μQ, F_y = 0.08123 μQ, converged in 9 steps) within 0.002 μQ.
fn assert_long_contact_forces(solution: &wheel_rail_contact::models::exact::ExactSolution) {
    assert!(solution.converged, "{} steps, {} products", solution.iterations, solution.operator_products);
    let limit = 0.3 * 80e3;
    let forces = solution.forces;
    assert!((forces.force_longitudinal / limit + 0.56187).abs() < 2e-3, "{forces:?}");
    assert!((forces.force_lateral / limit - 0.08123).abs() < 2e-3, "{forces:?}");
}

/// Elements far from square are started from the grid halved across their short side only:
/// halving both axes started 320 × 400 from 160 × 200, from which the Newton iteration needed
/// 40 steps (and, before accurate steps after sixteen loose ones, cycled for 200 and returned
/// F_x = −0.258 μQ). From 320 × 200 (and so on down) it converges within the loose steps.
#[test]
#[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
fn a_long_contact_on_long_elements_starts_from_a_grid_halved_across_only() {
    let solution = ExactTheory::new(320, 400).solve(&long_contact_near_the_collapse()).unwrap();
    assert!(solution.iterations <= 16, "{} Newton steps", solution.iterations);
    assert_long_contact_forces(&solution);
}

/// From the 160 × 200 solution the warm Newton iteration needs 40 steps (≈ 1300 products; the
/// unit test `a_division_that_does_not_settle_is_solved_accurately_until_it_converges` in
/// `src/models/exact/mod.rs` runs it alone): the cold solve racing it converges first, so the
/// step gives the converged forces for at most twice a cold solve's products (+ one Newton step
/// of the warm iteration, which can be ahead when the cold one converges: 30 products allowed).
#[test]
#[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
fn a_slow_warm_start_is_overtaken_by_the_cold_solve() {
    let case = long_contact_near_the_collapse();
    let start = ExactTheory::new(160, 200).solve(&case).unwrap().warm_start();
    let model = ExactTheory::new(320, 400);
    let solution = model.solve_from(&case, Some(&start)).unwrap();
    assert_long_contact_forces(&solution);
    let cold = model.solve(&case).unwrap();
    assert!(
        solution.operator_products <= 2 * cold.operator_products + 30,
        "{} products, cold {}",
        solution.operator_products,
        cold.operator_products
    );
}

/// An iterate that did not converge is never passed on as forces: the error names the grid and
/// the solver's limits.
#[test]
fn an_unconverged_solution_is_refused_with_the_grid_named() {
    let case = ContactInput { creepage_longitudinal: 1e-3, spin_creepage: 0.3, ..input(6e-3, 4e-3, 80e3, 0.3, 0.28) };
    let mut solution = ExactTheory::new(20, 16).solve(&case).unwrap();
    assert!(solution.clone().converged().is_ok());
    solution.converged = false;
    let message = solution.converged().unwrap_err().to_string();
    for part in [
        "grid_elements_longitudinal = 20",
        "grid_elements_lateral = 16",
        "did not converge",
        &format!("{} Newton steps", wheel_rail_contact::models::exact::MAX_ITERATIONS),
        &format!("{} operator products", wheel_rail_contact::models::exact::MAX_PRODUCTS),
    ] {
        assert!(message.contains(part), "{message}: no {part:?}");
    }
}
