//! A whole scene as the FMU evaluates it, each option on in turn: Hertz's ellipse from the
//! profile curvatures, creepages from the wheel's velocities through standstill, Polach 2005's
//! falling friction, and creep relaxation over a braking transient.
//! `cargo run --release --example scene_options`

use wheel_rail_contact::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use wheel_rail_contact::scene::kinematics::WheelKinematics;
use wheel_rail_contact::scene::{
    CreepageSource, EllipseSource, Evaluation, Relaxation, Scene, SceneCache, SceneInput, SceneState, TractionLaw,
};
use wheel_rail_contact::{ModelChoice, Polach, Polach2005};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let radius = 0.46;
    // Hertz: a 920 mm wheel with a conical tread (no lateral curvature) on a 300 mm rail crown.
    let curvature = RelativeCurvature::from_profile_curvatures(radius, 0.0, 1.0 / 0.3)?;
    let hertz = HertzContact::solve(100e3, &curvature, contact_modulus(82e9, 0.28)?)?;
    println!(
        "Hertz: a = {:.2} mm, b = {:.2} mm, p0 = {:.0} MPa, approach {:.1} µm",
        hertz.semi_axis_a * 1e3,
        hertz.semi_axis_b * 1e3,
        hertz.max_pressure / 1e6,
        hertz.approach * 1e6
    );
    // Hertz's p0 = 3Q/(2πab).
    let p0 = 3.0 * 100e3 / (2.0 * std::f64::consts::PI * hertz.semi_axis_a * hertz.semi_axis_b);
    assert!((hertz.max_pressure / p0 - 1.0).abs() < 1e-12);

    // Kinematics: a wheel braked 0.5 % at 20 m/s, and the same slip velocity at walking pace and
    // at standstill, where the regularisation speed v_c keeps the creepage finite.
    for speed in [20.0, 1.0, 0.0] {
        let wheel = WheelKinematics {
            rolling_speed: speed,
            wheel_angular_speed: (speed - 0.1) / radius,
            wheel_rolling_radius: radius,
            lateral_slip_velocity: 0.0,
            spin_angular_velocity: 0.0,
        };
        let creepages = wheel.creepages(0.01)?;
        println!("V = {speed:4} m/s, slip 0.1 m/s: ξ = {:.4}", creepages.longitudinal);
        assert!(creepages.longitudinal.is_finite());
    }

    // The scene: Polach 2005 (dry), Hertz's ellipse, creepages from the kinematics, relaxation.
    let scene = Scene {
        creepages: CreepageSource::Kinematics { regularisation_speed: 0.01 },
        ellipse: EllipseSource::Hertz { wheel_profile_curvature: 0.0, rail_profile_curvature: 1.0 / 0.3 },
        traction_law: TractionLaw::Polach2005(Polach2005::DRY),
        relaxation: Relaxation::On { length: 0.0 },
        ..Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28)
    };
    let rolling = SceneInput {
        normal_force: 100e3,
        friction_coefficient: 0.4,
        rolling_speed: 20.0,
        wheel_angular_speed: 20.0 / radius,
        wheel_rolling_radius: radius,
        ..SceneInput::default()
    };
    let mut cache = SceneCache::default();
    let (_, mut state) = scene.evaluate(&rolling, &SceneState::default(), &mut cache, Evaluation::Initialise)?;
    let braking = SceneInput { wheel_angular_speed: 0.99 * 20.0 / radius, ..rolling };
    println!("braking 1 %: t [ms]  F_x [kN]  μ(w)");
    let mut previous = 0.0_f64;
    for step in 1..=8 {
        let output;
        (output, state) = scene.evaluate(&braking, &state, &mut cache, Evaluation::Step(1e-4))?;
        println!(
            "{:17.1} {:9.2} {:6.3}",
            step as f64 * 0.1,
            output.force_longitudinal / 1e3,
            output.current_friction_coefficient
        );
        // The force builds up monotonically, never beyond μ(w)·Q.
        assert!(output.force_longitudinal.abs() >= previous.abs());
        assert!(output.adhesion_utilisation <= 1.0);
        previous = output.force_longitudinal;
    }
    Ok(())
}
