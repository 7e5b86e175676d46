//! The contact data of the passenger-coach wheelset (data/wheelset/passenger_coach.toml) on its
//! track, from the library's geometry, as JSON for the linear stability reference
//! (wheelset/tests/system/linear_stability.py, docs/wheelset.md):
//!
//! - the equivalent conicity tan γ_e(A) by EN 15302's principle and its harmonic linearisation,
//!   for amplitudes A = 0.25 … 6 mm every 0.25 mm (`RollingRadiusDifference`, Δr every 0.1 mm);
//! - per lateral displacement y = −6 … 6 mm every 0.05 mm (zero roll and yaw) and per wheel, the
//!   patches that carry half the axle load vertically (prescribed vertical force, vertical share
//!   cos δ: the normal problem without creep forces): normal force N, contact angle δ, rolling
//!   radius, track y of the contact, Hertz semi-axes a, b and Kalker's C11, C22, C23, C33 for a/b
//!   and ν. Kalker's linear stiffnesses follow as f11 = G a b C11, f22 = G a b C22,
//!   f23 = G (ab)^{3/2} C23, f33 = G (ab)² C33;
//! - per displacement and wheel, what the contact unit's own computation gives for the wheelset
//!   at rest in yaw and lateral motion, rolling at V = 10 m/s with Ω = V/r_c (r_c the centred
//!   wheelset's rolling radius), `kalker_linear`, half the axle load prescribed: the lateral
//!   force and the yaw moment on the wheelset [N, N m] (`WheelRailContact`), against which the
//!   linear reference's force model is checked (wheelset/tests/system/test_linear_stability.py).
//!
//! `cargo run --release -p lab --bin wheelset_contact_data > data/wheelset/contact_data.json`

use std::fmt::Write;

use lab::wheelset_parameters::{document, number, text};
use wheel_rail_contact::geometry::{
    builtin_profile, RollingRadiusDifference, SmoothProfile, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition,
};
use wheel_rail_contact::scene::{Evaluation, Scene};
use wheel_rail_contact::wheel::{
    VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{KalkerCoefficients, KalkerLinear, ModelChoice};

/// The rolling speed of the at-rest evaluations \[m/s\] (any speed well above the
/// regularisation speed gives the same creepages).
const SPEED: f64 = 10.0;

fn main() {
    let document = document();
    let wheel_load = 0.5 * number(&document, "wheelset", "axle_load");
    let shear_modulus = number(&document, "contact", "shear_modulus");
    let poisson_ratio = number(&document, "contact", "poisson_ratio");
    let (wheel_name, rail_name) =
        (text(&document, "contact", "wheel_profile"), text(&document, "contact", "rail_profile"));
    let dimensions = TrackDimensions::MANCHESTER_BENCHMARK;
    assert_eq!(dimensions.nominal_radius, number(&document, "wheelset", "nominal_rolling_radius"));
    let profile = |name| SmoothProfile::new(&builtin_profile(name).expect("built-in profile")).expect("profile");
    let wheel = |side| {
        WheelOnRail::new(profile(wheel_name), profile(rail_name), dimensions, side, shear_modulus, poisson_ratio)
            .expect("placed wheel")
    };
    let (right, left) = (wheel(WheelSide::Right), wheel(WheelSide::Left));

    let difference = RollingRadiusDifference::from_wheelset(&right, &left, 0.010, 1e-4).expect("Δr");
    let mut conicity = String::new();
    for k in 1..=24 {
        let amplitude = 0.25e-3 * f64::from(k);
        let equivalent = difference.equivalent_conicity(amplitude).expect("tan γ_e");
        let harmonic = difference.harmonic_conicity(amplitude).expect("tan γ_h");
        let separator = if k == 1 { "" } else { ",\n" };
        write!(conicity, "{separator}    [{amplitude:.5e}, {equivalent:.8e}, {harmonic:.8e}]").unwrap();
    }

    let centred = WheelsetPosition::default();
    let centred_radius = 0.5
        * [&right, &left]
            .map(|wheel| {
                let (_, patches) =
                    wheel.patches_for_force(wheel_load, &centred, |p| p.contact_angle.cos()).expect("centred");
                patches[0].point.rolling_radius
            })
            .iter()
            .sum::<f64>();
    let scene = Scene::of_model(ModelChoice::KalkerLinear(KalkerLinear), shear_modulus, poisson_ratio);
    let contacts = [WheelRailContact::new(right.clone(), scene), WheelRailContact::new(left.clone(), scene)];
    let velocity = WheelsetVelocity {
        rolling_speed: SPEED,
        wheel_angular_speed: SPEED / centred_radius,
        lateral_velocity: 0.0,
        yaw_rate: 0.0,
    };

    let mut samples = String::new();
    for k in -120..=120 {
        let lateral = 0.05e-3 * f64::from(k);
        let position = WheelsetPosition { lateral, ..WheelsetPosition::default() };
        let mut wheels = Vec::new();
        for ((name, wheel), contact) in [("right", &right), ("left", &left)].into_iter().zip(&contacts) {
            let input = WheelInput {
                position,
                velocity,
                vertical: VerticalContact::PrescribedForce(wheel_load),
                friction_coefficient: 0.3,
            };
            let (output, _) = contact
                .evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise)
                .unwrap_or_else(|e| panic!("{name} wheel at rest at y = {lateral} m: {e}"));
            wheels.push(format!(
                "\"{name}_at_rest\": {{\"force_lateral\": {:.8e}, \"moment_yaw\": {:.8e}}}",
                output.track_force[1], output.track_moment[2]
            ));
            let (_, patches) = wheel
                .patches_for_force(wheel_load, &position, |point| point.contact_angle.cos())
                .unwrap_or_else(|e| panic!("{name} wheel at y = {lateral} m: {e}"));
            let patches: Vec<String> = patches
                .iter()
                .map(|patch| {
                    let (a, b) = (patch.ellipse.semi_axis_a, patch.ellipse.semi_axis_b);
                    let c = KalkerCoefficients::new(a / b, poisson_ratio);
                    let c33 = KalkerCoefficients::spin_moment_c33(a / b, poisson_ratio);
                    let p = &patch.point;
                    format!(
                        "{{\"normal_force\": {:.8e}, \"contact_angle\": {:.8e}, \"rolling_radius\": {:.10e}, \
                         \"track_lateral\": {:.8e}, \"semi_axis_a\": {a:.8e}, \"semi_axis_b\": {b:.8e}, \
                         \"c11\": {:.8e}, \"c22\": {:.8e}, \"c23\": {:.8e}, \"c33\": {c33:.8e}}}",
                        patch.normal_force, p.contact_angle, p.rolling_radius, p.track_lateral, c.c11, c.c22, c.c23
                    )
                })
                .collect();
            wheels.push(format!("\"{name}\": [{}]", patches.join(", ")));
        }
        let separator = if k == -120 { "" } else { ",\n" };
        write!(samples, "{separator}    {{\"lateral\": {lateral:.5e}, {}}}", wheels.join(", ")).unwrap();
    }

    println!("{{");
    println!(
        "  \"made_by\": \"cargo run --release -p lab --bin wheelset_contact_data > data/wheelset/contact_data.json\","
    );
    println!("  \"wheel_profile\": \"{wheel_name}\", \"rail_profile\": \"{rail_name}\",");
    println!("  \"wheel_load\": {wheel_load:.8e}, \"shear_modulus\": {shear_modulus:.8e}, \"poisson_ratio\": {poisson_ratio},");
    println!("  \"nominal_radius\": {}, \"track_gauge\": {},", dimensions.nominal_radius, dimensions.gauge);
    println!("  \"centred_radius\": {centred_radius:.10e}, \"at_rest_speed\": {SPEED},");
    println!("  \"conicity_columns\": [\"amplitude\", \"equivalent\", \"harmonic\"],");
    println!("  \"conicity\": [\n{conicity}\n  ],");
    println!("  \"samples\": [\n{samples}\n  ]");
    println!("}}");
}
