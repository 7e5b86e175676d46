//! Kalker's exact theory on one contact: the forces, the traction field, the areas of adhesion
//! and slip, and a co-simulation's steps warm-started from the previous step's tractions.
//! `cargo run --release --example exact_theory`

use wheel_rail_contact::{ContactInput, ElementState, ExactTheory};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let contact = |xi: f64| ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: 0.0,
        spin_creepage: 0.3,
        normal_force: 100e3,
        semi_axis_a: 7.2e-3,
        semi_axis_b: 5.4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    };
    let theory = ExactTheory::new(80, 40);
    let solution = theory.solve(&contact(1e-3))?.converged()?;
    let forces = solution.forces;
    println!(
        "F_x = {:.0} N, F_y = {:.0} N, M_z = {:.2} N·m after {} Newton steps",
        forces.force_longitudinal,
        forces.force_lateral,
        forces.spin_moment.unwrap_or(0.0),
        solution.iterations
    );
    let contact_area = solution.adhesion_area + solution.slip_area;
    println!("adhesion: {:.0} % of the contact area", 100.0 * solution.adhesion_area / contact_area);
    // Coulomb's law everywhere: |p| ≤ μ p_n, with equality where the element slips.
    for (k, state) in solution.element_state.iter().enumerate() {
        let traction = solution.traction_longitudinal[k].hypot(solution.traction_lateral[k]);
        let bound = solution.friction_coefficient * solution.pressure[k];
        assert!(traction <= bound * (1.0 + 1e-9) + 1e-9);
        if *state == ElementState::Slip {
            assert!((traction - bound).abs() <= 1e-6 * bound);
        }
    }
    // Along the middle row: adhesion from the leading edge (x = +a, the rolling direction is
    // +x), slip towards the trailing edge.
    let (middle_row, columns) = (solution.grid.lateral / 2, solution.grid.longitudinal);
    let row: Vec<ElementState> = (0..columns)
        .map(|i| solution.element_state[i + middle_row * columns])
        .filter(|state| *state != ElementState::Exterior)
        .collect();
    println!("middle row, trailing to leading edge: {:?} … {:?}", row[0], row[row.len() - 1]);
    assert_eq!((row[0], row[row.len() - 1]), (ElementState::Slip, ElementState::Adhesion));

    // A co-simulation: each step starts from the last one's tractions.
    let mut start = solution.warm_start();
    for step in 1..=5 {
        let next = theory.solve_from(&contact(1e-3 + 1e-5 * step as f64), Some(&start))?.converged()?;
        println!("step {step}: F_x = {:.1} N in {} Newton steps", next.forces.force_longitudinal, next.iterations);
        start = next.warm_start();
    }
    Ok(())
}
