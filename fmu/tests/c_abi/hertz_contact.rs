//! Hertz's contact (`hertz_contact = on`) through the C ABI: its errors name the FMU's
//! variables and the cause. The semi-axis inputs are ignored then, so a model's refusal of the
//! ellipse must name what the ellipse came from — the curvatures, the rolling radius and the a/b
//! that Hertz's theory gave — not the ignored inputs. Before (issue 27.5), exact_table's refusal
//! of a/b = 20 blamed `semi_axis_a`/`semi_axis_b`, printed Hertz's values as theirs and never
//! stated a/b.

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Model, Switch};

#[test]
fn a_hertz_ellipse_outside_exact_tables_range_is_reported_as_hertzs() {
    // A 1 mm rail crown under a 460 mm wheel: a long, narrow ellipse, longer than a flange's.
    let (radius, rail_curvature) = (0.46, 1000.0);
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("hertz", &log);
    assert_eq!(
        fmu.set_integer(&[vr::CREEP_FORCE_MODEL, vr::HERTZ_CONTACT], &[Model::ExactTable as i32, Switch::On as i32]),
        OK
    );
    assert_eq!(fmu.set_real(&[vr::RAIL_PROFILE_CURVATURE, vr::WHEEL_ROLLING_RADIUS], &[rail_curvature, radius]), OK);
    // SAFETY: a live instance.
    unsafe {
        use wheel_rail_contact_fmu::ffi::{
            fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2SetupExperiment,
        };
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), ERROR);
    }
    let message = log.texts().pop().unwrap();
    // Hertz's ellipse of the same curvatures (the default load 100 kN, G = 82 GPa, ν = 0.28).
    let curvature = RelativeCurvature::from_profile_curvatures(radius, 0.0, rail_curvature).unwrap();
    let ellipse = HertzContact::solve(100e3, &curvature, contact_modulus(82e9, 0.28).unwrap()).unwrap();
    let a_over_b = ellipse.semi_axis_a / ellipse.semi_axis_b;
    assert!(a_over_b > 10f64.powf(1.5), "{a_over_b}");
    let expected = format!(
        "fmi2ExitInitializationMode: hertz_contact = on: Hertz's ellipse from wheel_rolling_radius = 0.46 m, \
         wheel_profile_curvature = 0 1/m and rail_profile_curvature = 1000 1/m has a/b = {a_over_b:.4} (a = {:.4} mm, \
         b = {:.4} mm), which the model cannot take (semi_axis_a over semi_axis_b must lie in the exact_table's a/b \
         range [0.1, 31.62] (10^-1 to 10^1.5))",
        ellipse.semi_axis_a * 1e3,
        ellipse.semi_axis_b * 1e3
    );
    assert_eq!(message, expected);
    // A refusal of anything but the ellipse keeps its own name: a negative μ is the input's.
    assert_eq!(fmu.set_real(&[vr::FRICTION_COEFFICIENT], &[-0.1]), OK);
    // SAFETY: a live instance.
    assert_eq!(unsafe { wheel_rail_contact_fmu::ffi::fmi2ExitInitializationMode(fmu.c) }, ERROR);
    let message = log.texts().pop().unwrap();
    assert!(message.starts_with("fmi2ExitInitializationMode: friction_coefficient = -0.1 is invalid"), "{message}");
    assert_eq!(fmu.set_real(&[vr::FRICTION_COEFFICIENT], &[0.3]), OK);
    // The instance stays usable: a rail crown of 300 mm gives a/b ≈ 1.3, inside the table.
    assert_eq!(fmu.set_real(&[vr::RAIL_PROFILE_CURVATURE], &[1.0 / 0.3]), OK);
    // SAFETY: a live instance.
    assert_eq!(unsafe { wheel_rail_contact_fmu::ffi::fmi2ExitInitializationMode(fmu.c) }, OK);
}

/// The message of a DoStep with Hertz on and these profile curvatures (wheel, rail) [1/m].
fn hertz_message(wheel: f64, rail: f64) -> String {
    use wheel_rail_contact_fmu::model_description::Switch;
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("hertz", &log);
    assert_eq!(fmu.set_integer(&[vr::HERTZ_CONTACT], &[Switch::On as i32]), OK);
    fmu.initialise(0.0);
    assert_eq!(fmu.set_real(&[vr::WHEEL_PROFILE_CURVATURE, vr::RAIL_PROFILE_CURVATURE], &[wheel, rail]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    log.texts().last().unwrap().clone()
}

/// Hertz's errors name the FMU's variables with their values and the actual reason, never
/// an internal quantity (the combined curvature B) nor a concave profile that is not there.
#[test]
fn hertz_errors_name_the_fmu_variables_and_the_cause() {
    for (wheel, rail, named) in [
        (0.0, 1e-20, ["rail_profile_curvature = 1e-20", "wheel_profile_curvature = 0"]),
        (0.0, 0.0, ["rail_profile_curvature = 0", "wheel_profile_curvature = 0"]),
        (0.0, -1.0, ["rail_profile_curvature = -1", "wheel_profile_curvature = 0"]),
    ] {
        let message = hertz_message(wheel, rail);
        assert!(message.starts_with("fmi2DoStep: "), "{message}");
        for text in named {
            assert!(message.contains(text), "{text} not in {message}");
        }
        assert!(!message.contains("curvature_lateral") && !message.contains("concave wheel"), "{message}");
    }
    // A concave wheel flatter than nothing: that cause, named.
    let message = hertz_message(-5.0, 3.0);
    assert!(message.contains("wheel_profile_curvature = -5") && message.contains("concave wheel"), "{message}");
}
