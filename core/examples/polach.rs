//! Polach's method on one contact: with Kalker's stiffness, with a measured creep curve's, and
//! with Polach's 2005 falling friction. `cargo run --release --example polach`

use wheel_rail_contact::{
    ContactInput, CreepForceModel, KalkerCoefficients, LargeCreepage, MeasuredCurve, Polach, Polach2005,
    StiffnessSource,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A new 920 mm wheel on a 300 mm rail crown under 100 kN (the FMU's default scene).
    let contact = |xi: f64| ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: 0.0,
        spin_creepage: 0.0,
        normal_force: 100e3,
        semi_axis_a: 7.2e-3,
        semi_axis_b: 5.4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 82e9,
        poisson_ratio: 0.28,
    };
    let kalker = Polach::default();
    println!("creepage   F_x [kN]   |F|/(μQ)");
    for xi in [1e-4, 1e-3, 3e-3, 1e-2, 1e-1] {
        let forces = kalker.creep_forces(&contact(xi))?;
        println!("{xi:8.0e} {:10.2} {:10.3}", forces.force_longitudinal / 1e3, forces.adhesion_utilisation);
    }
    // In the linear range Polach's force is Kalker's: F_x = −G·a·b·C11·ξ.
    let c11 = KalkerCoefficients::new(7.2e-3 / 5.4e-3, 0.28).c11;
    let linear = -82e9 * 7.2e-3 * 5.4e-3 * c11 * 1e-6;
    let small = kalker.creep_forces(&contact(1e-6))?.force_longitudinal;
    assert!((small / linear - 1.0).abs() < 1e-3, "{small} vs {linear}");

    // A measured curve: peak adhesion 0.33 at 0.3 % creepage, 0.3 at large creepage.
    let measured = Polach {
        stiffness: StiffnessSource::MeasuredCurve(MeasuredCurve::from_peak(0.33, 3e-3, 0.3)?),
        large_creepage: None,
    };
    let at_peak = measured.creep_forces(&contact(3e-3))?;
    println!("measured curve at its peak creepage: |F|/Q = {:.3}", at_peak.force_longitudinal.abs() / 100e3);
    assert!((at_peak.force_longitudinal.abs() / 100e3 - 0.33).abs() < 0.01);

    // Polach 2005 (dry rail): friction falls with the slip velocity at 20 m/s.
    let falling = Polach { large_creepage: Some(LargeCreepage::new(Polach2005::DRY, 20.0)?), ..kalker };
    let sliding = falling.creep_forces(&contact(0.1))?;
    println!("Polach 2005, ξ = 10 % at 20 m/s: |F|/(μ₀Q) = {:.3}", sliding.force_longitudinal.abs() / 30e3);
    assert!(sliding.force_longitudinal.abs() < kalker.creep_forces(&contact(0.1))?.force_longitudinal.abs());
    Ok(())
}
