//! `contact_geometry = profiles` through the C ABI: the String parameters, the profiles read at
//! initialisation (errors naming the variable, the file and the reason), the wheel's outputs
//! against the core's own evaluation, lift-off, the left wheel as the right one mirrored, and
//! no directional derivatives.

use std::ffi::CString;

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use wheel_rail_contact::geometry::{WheelOnRail, WheelSide, WheelsetPosition};
use wheel_rail_contact::scene::{CreepageSource, Evaluation, Scene};
use wheel_rail_contact::wheel::{
    VerticalContact, WheelCache, WheelInput, WheelRailContact, WheelState, WheelsetVelocity,
};
use wheel_rail_contact::{ModelChoice, Polach};
use wheel_rail_contact_fmu::ffi::{
    fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2GetInteger, fmi2GetReal, fmi2SetString,
    fmi2SetupExperiment,
};
use wheel_rail_contact_fmu::fmi2::fmi2Status;
use wheel_rail_contact_fmu::model_description::{
    value_reference as vr, variable, ContactGeometry, ContactMethod, Model, VerticalContact as VerticalChoice,
    WheelSide as SideChoice,
};

/// The wheelset's inputs, in this order.
const WHEELSET: [u32; 9] = [
    vr::WHEELSET_LATERAL_DISPLACEMENT,
    vr::WHEELSET_VERTICAL_POSITION,
    vr::WHEELSET_ROLL_ANGLE,
    vr::WHEELSET_YAW_ANGLE,
    vr::VERTICAL_FORCE,
    vr::ROLLING_SPEED,
    vr::WHEEL_ANGULAR_SPEED,
    vr::WHEELSET_LATERAL_VELOCITY,
    vr::WHEELSET_YAW_RATE,
];

/// Every output of the wheel, in this order: the totals, then patch 1's and patch 2's.
const WHEEL_OUTPUTS: [u32; 30] = [
    vr::TRACK_FORCE_X,
    vr::TRACK_FORCE_Y,
    vr::TRACK_FORCE_Z,
    vr::TRACK_MOMENT_X,
    vr::TRACK_MOMENT_Y,
    vr::TRACK_MOMENT_Z,
    vr::CONTACT_PATCH_COUNT,
    vr::WHEELSET_VERTICAL_POSITION_SOLVED,
    vr::PATCH1_CONTACT_ANGLE,
    vr::PATCH1_RAIL_LATERAL_POSITION,
    vr::PATCH1_ROLLING_RADIUS,
    vr::PATCH1_NORMAL_FORCE,
    vr::PATCH1_FORCE_LONGITUDINAL,
    vr::PATCH1_FORCE_LATERAL,
    vr::PATCH1_CREEPAGE_LONGITUDINAL,
    vr::PATCH1_CREEPAGE_LATERAL,
    vr::PATCH1_SPIN_CREEPAGE,
    vr::PATCH1_SEMI_AXIS_A,
    vr::PATCH1_SEMI_AXIS_B,
    vr::PATCH2_CONTACT_ANGLE,
    vr::PATCH2_RAIL_LATERAL_POSITION,
    vr::PATCH2_ROLLING_RADIUS,
    vr::PATCH2_NORMAL_FORCE,
    vr::PATCH2_FORCE_LONGITUDINAL,
    vr::PATCH2_FORCE_LATERAL,
    vr::PATCH2_CREEPAGE_LONGITUDINAL,
    vr::PATCH2_CREEPAGE_LATERAL,
    vr::PATCH2_SPIN_CREEPAGE,
    vr::PATCH2_SEMI_AXIS_A,
    vr::PATCH2_SEMI_AXIS_B,
];

/// case 11 of the Manchester benchmark (5 mm to the right, yawed and rolled: tread and
/// flange both in contact on the right wheel), braking slightly, moving sideways and yawing.
const CASE_11: [f64; 9] = [5e-3, 0.0, -3.554e-4, 0.012, 10e3, 2.0, 4.3353637 * 0.999, 0.01, 0.005];

/// An instance with profiles on `side` and Hertz's patches (`contact_method = hertz`: the tests
/// that use it check them against the core's Hertz wheel and at its patches' changes; the
/// non-Hertzian patches' own tests set `non_hertzian`, the start value), its inputs set,
/// initialised (logging into `log`).
fn profiles(side: SideChoice, inputs: &[f64; 9], log: &MessageLog) -> Fmu {
    let fmu = Fmu::instantiate_logged("profiles", log);
    let choices = [ContactGeometry::Profiles as i32, side as i32, ContactMethod::Hertz as i32];
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::WHEEL_SIDE, vr::CONTACT_METHOD], &choices), OK);
    assert_eq!(fmu.set_real(&WHEELSET, inputs), OK);
    fmu.initialise(0.0);
    fmu
}

/// fmi2ExitInitializationMode's status after setting up.
fn exit_initialisation(fmu: &Fmu) -> fmi2Status {
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        fmi2ExitInitializationMode(fmu.c)
    }
}

#[test]
fn strings_are_copied_in_and_read_back() {
    let fmu = Fmu::instantiate("strings", None);
    // SAFETY: a live instance (Get is legal from initialisation mode on).
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    let profiles = [vr::WHEEL_PROFILE, vr::RAIL_PROFILE];
    assert_eq!(fmu.get_string(&profiles), ["MBench_S1002", "MBench_UIC60"], "the start values");
    // The caller's buffer is changed after the call: the FMU kept its own copy.
    let mut text = CString::new("profiles/worn wheel.prw").unwrap().into_bytes_with_nul();
    // SAFETY: a live instance; `text` is NUL-terminated and outlives the call.
    let status = unsafe { fmi2SetString(fmu.c, &vr::WHEEL_PROFILE, 1, &text.as_ptr().cast()) };
    assert_eq!(status, OK);
    text[0] = b'X';
    assert_eq!(fmu.set_string(&[vr::RAIL_PROFILE], &["rail ü.ban"]), OK);
    assert_eq!(fmu.get_string(&profiles), ["profiles/worn wheel.prw", "rail ü.ban"]);
    // The pointers of one call stay valid while the master reads them.
    let (status, pointers) = fmu.get_string_pointers(&[vr::RAIL_PROFILE, vr::WHEEL_PROFILE, vr::RAIL_PROFILE]);
    assert_eq!(status, OK);
    // SAFETY: the FMU's strings, valid until its next call.
    let texts: Vec<&str> = pointers.iter().map(|&p| unsafe { std::ffi::CStr::from_ptr(p) }.to_str().unwrap()).collect();
    assert_eq!(texts, ["rail ü.ban", "profiles/worn wheel.prw", "rail ü.ban"]);
    // Not a String, or not a variable: nothing is set.
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::SHEAR_MODULUS], &["a.prw", "b"]), ERROR);
    assert_eq!(fmu.get_string(&[vr::WHEEL_PROFILE]), ["profiles/worn wheel.prw"]);
    assert_eq!(fmu.get_string_pointers(&[vr::TRACK_FORCE_X]).0, ERROR);
    // Fixed parameters: not after initialisation.
    // SAFETY: a live instance in initialisation mode (contact_geometry = ellipse: the profiles
    // are not read).
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK);
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE], &["MBench_S1002"]), ERROR);
}

#[test]
fn a_missing_or_malformed_profile_is_an_error_naming_the_file_and_the_reason() {
    let directory = std::env::temp_dir().join(format!("wrc-profiles-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let malformed = directory.join("malformed.ban");
    std::fs::write(&malformed, "0.0 0.0\n1.0 oops\n").unwrap();
    let missing = directory.join("missing.prw");
    let cases = [
        (vr::WHEEL_PROFILE, missing.to_str().unwrap().to_owned(), "the file cannot be read"),
        (vr::RAIL_PROFILE, malformed.to_str().unwrap().to_owned(), "line 2"),
        (vr::WHEEL_PROFILE, "S1002".to_owned(), "neither a built-in profile (MBench_S1002, MBench_UIC60)"),
    ];
    for (reference, path, reason) in cases {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged("bad profile", &log);
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
        assert_eq!(fmu.set_string(&[reference], &[&path]), OK);
        assert_eq!(exit_initialisation(&fmu), ERROR, "{path}");
        let (status, message) = log.last().unwrap();
        assert_eq!(status, ERROR);
        let variable = if reference == vr::WHEEL_PROFILE { "wheel_profile" } else { "rail_profile" };
        assert!(message.starts_with(&format!("fmi2ExitInitializationMode: {variable} = \"{path}\"")), "{message}");
        assert!(message.contains(reason), "{message}");
        // Corrected, the instance carries on.
        let builtin = if reference == vr::WHEEL_PROFILE { "MBench_S1002" } else { "MBench_UIC60" };
        assert_eq!(fmu.set_string(&[reference], &[builtin]), OK);
        // SAFETY: a live instance, still in initialisation mode.
        assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK);
    }
    std::fs::remove_dir_all(&directory).unwrap();
}

#[test]
fn a_relative_profile_path_is_read_from_the_fmus_resources() {
    // An FMU unzipped into a directory with a space, as masters do, its wheel profile packed
    // under resources/profiles/: the master passes the location as a percent-encoded file URI.
    let root = std::env::temp_dir().join(format!("wrc unzipped {}", std::process::id()));
    let resources = root.join("resources");
    std::fs::create_dir_all(resources.join("profiles")).unwrap();
    std::fs::write(resources.join("profiles/wheel.prw"), include_str!("../../../data/profiles/MBench_S1002_v3.prw"))
        .unwrap();
    // Beside the table every FMU's resources hold, which fmi2Instantiate checks.
    std::fs::copy(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin"), resources.join("exact_table.bin"))
        .unwrap();
    let location = format!("file://{}/", resources.to_str().unwrap().replace(' ', "%20"));
    let outputs = |wheel: &str, location: Option<&str>| {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged_at("packed", &log, location);
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
        assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE], &[wheel]), OK);
        assert_eq!(fmu.set_real(&WHEELSET, &CASE_11), OK);
        let status = exit_initialisation(&fmu);
        let message = log.last().map(|(_, message)| message).unwrap_or_default();
        let forces = if status == OK { fmu.get_real(&[vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z]) } else { Vec::new() };
        (status, forces, message)
    };
    let (status, packed, _) = outputs("profiles/wheel.prw", Some(&location));
    assert_eq!(status, OK);
    // The same profile as the built-in one: the same wheel, bit for bit.
    assert_eq!(packed, outputs("MBench_S1002", None).1);
    // Without the resource location, the relative path is the working directory's: not there.
    let (status, _, message) = outputs("profiles/wheel.prw", None);
    assert_eq!(status, ERROR);
    assert!(message.contains("the file cannot be read") && !message.contains("resources"), "{message}");
    // Not packed either: the message says where it looked.
    let (status, _, message) = outputs("profiles/other.prw", Some(&location));
    assert_eq!(status, ERROR);
    assert!(message.contains("looked in the FMU's resources") && message.contains("working directory"), "{message}");
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn the_outputs_are_the_cores_wheel_on_its_rail() {
    let log = MessageLog::default();
    let fmu = profiles(SideChoice::Right, &CASE_11, &log);
    let outputs = fmu.get_real(&WHEEL_OUTPUTS);
    let geometry = WheelOnRail::manchester_benchmark(WheelSide::Right);
    let scene = Scene {
        creepages: CreepageSource::Kinematics { regularisation_speed: 0.01 },
        ..Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28)
    };
    let input = WheelInput {
        position: WheelsetPosition { lateral: 5e-3, vertical: 0.0, roll: -3.554e-4, yaw: 0.012 },
        velocity: WheelsetVelocity {
            rolling_speed: 2.0,
            wheel_angular_speed: 4.3353637 * 0.999,
            lateral_velocity: 0.01,
            yaw_rate: 0.005,
        },
        vertical: VerticalContact::PrescribedForce(10e3),
        friction_coefficient: 0.3,
    };
    let (wheel, _) = WheelRailContact::new(geometry, scene)
        .evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise)
        .unwrap();
    assert_eq!(wheel.patches.len(), 2, "tread and flange");
    let mut expected = vec![];
    expected.extend(wheel.track_force);
    expected.extend(wheel.track_moment);
    expected.extend([2.0, wheel.wheelset_vertical_position]);
    for patch in &wheel.patches {
        let (point, output) = (&patch.patch.point, &patch.output);
        expected.extend([
            point.contact_angle,
            point.rail_lateral,
            point.rolling_radius,
            patch.patch.normal_force,
            output.force_longitudinal,
            output.force_lateral,
            output.effective_creepage_longitudinal,
            output.effective_creepage_lateral,
            output.effective_spin_creepage,
            patch.patch.ellipse.semi_axis_a,
            patch.patch.ellipse.semi_axis_b,
        ]);
    }
    assert_eq!(outputs, expected);
    // Tread first: the flange patch is further towards the gauge side and steeper.
    assert!(outputs[9] > outputs[20] && outputs[19] < outputs[8] && outputs[8] < 0.0, "{outputs:?}");
    // The rail carries the prescribed load: F_z on the wheel is −10 kN.
    assert!((outputs[2] + 10e3).abs() < 1e-6 * 10e3, "{}", outputs[2]);
    // The single patch's outputs are not computed with profiles.
    let single = fmu.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::CONTACT_SEMI_AXIS_A]);
    assert_eq!(single, [0.0; 3]);
}

#[test]
fn lift_off_gives_zeros_and_no_patch() {
    let log = MessageLog::default();
    let mut inputs = CASE_11;
    inputs[4] = 0.0;
    let fmu = profiles(SideChoice::Right, &inputs, &log);
    let outputs = fmu.get_real(&WHEEL_OUTPUTS);
    // All zero but the height at which the wheel just touches.
    for (position, value) in outputs.iter().enumerate().filter(|(position, _)| *position != 7) {
        assert_eq!(*value, 0.0, "output {position}");
    }
    assert!(outputs[7].is_finite());
    // Loaded again: two patches.
    assert_eq!(fmu.set_real(&[vr::VERTICAL_FORCE], &[10e3]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    assert_eq!(fmu.get_real(&[vr::CONTACT_PATCH_COUNT]), [2.0]);
    assert_eq!(fmu.set_real(&[vr::VERTICAL_FORCE], &[-5.0]), OK);
    assert_eq!(fmu.do_step(1e-3, 1e-3), OK);
    assert_eq!(fmu.get_real(&[vr::CONTACT_PATCH_COUNT, vr::TRACK_FORCE_Z, vr::PATCH2_NORMAL_FORCE]), [0.0; 3]);
}

#[test]
fn an_invalid_position_is_an_error_naming_it_and_the_instance_carries_on() {
    let log = MessageLog::default();
    let fmu = profiles(SideChoice::Right, &CASE_11, &log);
    let before = fmu.get_real(&WHEEL_OUTPUTS);
    for (reference, name) in [
        (vr::WHEELSET_LATERAL_DISPLACEMENT, "wheelset_lateral_displacement = NaN"),
        (vr::WHEELSET_YAW_RATE, "wheelset_yaw_rate = NaN"),
    ] {
        assert_eq!(fmu.set_real(&[reference], &[f64::NAN]), OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
        let (_, message) = log.last().unwrap();
        assert!(message.starts_with(&format!("fmi2DoStep: {name}")), "{message}");
        // Read at the invalid input, the outputs are the same error (direct feedthrough) …
        let mut values = [0.0; WHEEL_OUTPUTS.len()];
        // SAFETY: a live instance; the arrays have the length passed.
        let status = unsafe { fmi2GetReal(fmu.c, WHEEL_OUTPUTS.as_ptr(), WHEEL_OUTPUTS.len(), values.as_mut_ptr()) };
        assert_eq!(status, ERROR);
        let (_, message) = log.last().unwrap();
        assert!(message.starts_with(&format!("fmi2GetReal: {name}")), "{message}");
        // … and back at the good value they are the ones before: the failed step kept nothing.
        let index = WHEELSET.iter().position(|r| *r == reference).unwrap();
        assert_eq!(fmu.set_real(&[reference], &[CASE_11[index]]), OK);
        assert_eq!(fmu.get_real(&WHEEL_OUTPUTS), before, "the outputs are kept");
    }
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    // The vertical position is not read with a prescribed force.
    assert_eq!(fmu.set_real(&[vr::WHEELSET_VERTICAL_POSITION], &[f64::NAN]), OK);
    assert_eq!(fmu.do_step(1e-3, 1e-3), OK);
    assert_eq!(fmu.get_real(&WHEEL_OUTPUTS), before);
}

/// The left wheel at (−y, −roll, −yaw), moving at (−ẏ, −ψ̇), is the right wheel at (y, roll,
/// yaw) mirrored in y: lateral forces, positions, angles, lateral and spin creepages and the
/// moments about x and z change sign; the rest is the same.
#[test]
fn the_left_wheel_is_the_right_one_mirrored() {
    let mirror = [-1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0, -1.0, -1.0];
    let patch = [-1.0, -1.0, 1.0, 1.0, 1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0];
    let mut signs = vec![1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, 1.0];
    signs.extend(patch);
    signs.extend(patch);
    // The cant turns each rail towards the track's centre, mirrored on the left (here −0.01 rad,
    // less inclined than the built-in 1:40, and +0.05, which drops the lower gauge-side flank).
    for (lateral, cant) in [(5e-3, 0.0), (-2e-3, 0.0), (7e-3, 0.0), (3e-3, -0.01), (4e-3, 0.05)] {
        let mut right_inputs = CASE_11;
        right_inputs[0] = lateral;
        let left_inputs: [f64; 9] = std::array::from_fn(|i| right_inputs[i] * mirror[i]);
        let log = MessageLog::default();
        let canted = |side, inputs: &[f64; 9]| {
            let fmu = Fmu::instantiate_logged("mirror", &log);
            let integers = [ContactGeometry::Profiles as i32, side as i32];
            assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::WHEEL_SIDE], &integers), OK);
            assert_eq!(fmu.set_real(&[vr::RAIL_CANT], &[cant]), OK);
            assert_eq!(fmu.set_real(&WHEELSET, inputs), OK);
            assert_eq!(exit_initialisation(&fmu), OK, "{:?}", log.last());
            fmu.get_real(&WHEEL_OUTPUTS)
        };
        let right = canted(SideChoice::Right, &right_inputs);
        let left = canted(SideChoice::Left, &left_inputs);
        if cant != 0.0 {
            let uncanted = profiles(SideChoice::Right, &right_inputs, &log).get_real(&WHEEL_OUTPUTS);
            // On the tread the contact angle follows the rail's turn, less the wheel's own slope change.
            assert!((right[8] - uncanted[8]).abs() > 0.005, "{} vs {}", right[8], uncanted[8]);
        }
        assert!(right[6] >= 1.0, "in contact at y = {lateral}");
        for (i, ((r, l), sign)) in right.iter().zip(&left).zip(&signs).enumerate() {
            let name = variable(WHEEL_OUTPUTS[i]).unwrap().name;
            assert!((l - sign * r).abs() <= 1e-9 * r.abs() + 1e-15, "y = {lateral}, {name}: {l} vs {sign} × {r}");
        }
    }
}

/// Directional derivatives with profiles (central differences of the core's wheel, one-sided
/// where the patches change), against the FMU's own outputs read back after moving an input
/// (direct feedthrough) by a step of its own (30 µm, 30 µrad, 30 N), on the tread (y_ws =
/// 2 mm: one patch), on the flange (7 mm) and with tread and flange in contact (case 11). Two
/// rates known without differences: the rail carries the prescribed force whatever the pose,
/// so ∂F_z/∂y_ws = 0 and ∂F_z/∂(vertical_force) = −1.
#[test]
fn directional_derivatives_with_profiles_are_the_outputs_differences() {
    let unknowns =
        [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z, vr::TRACK_MOMENT_Z, vr::PATCH1_NORMAL_FORCE];
    let knowns =
        [(vr::WHEELSET_LATERAL_DISPLACEMENT, 3e-5), (vr::WHEELSET_YAW_ANGLE, 3e-5), (vr::VERTICAL_FORCE, 30.0)];
    // The differences at 3× the derivative's own step differ from it by their truncation: within
    // 0.1 % on the tread and the flange; 1.1 % where tread and flange share the load at 5 mm,
    // where the forces bend sharply with y_ws.
    for (lateral, tolerance) in [(2e-3, 2e-3), (7e-3, 2e-3), (5e-3, 2e-2)] {
        let log = MessageLog::default();
        let mut inputs = CASE_11;
        inputs[0] = lateral;
        let fmu = profiles(SideChoice::Right, &inputs, &log);
        let base = fmu.get_real(&unknowns);
        for (known, step) in knowns {
            let (status, rates) = fmu.directional_derivative(&unknowns, &[known], &[1.0]);
            assert_eq!(status, OK, "{:?}", log.last());
            let value = fmu.get_real(&[known])[0];
            let at = |x: f64| {
                assert_eq!(fmu.set_real(&[known], &[x]), OK);
                fmu.get_real(&unknowns)
            };
            let (ahead, behind) = (at(value + step), at(value - step));
            assert_eq!(at(value), base, "back at the input, the outputs are the same");
            for (i, rate) in rates.iter().enumerate() {
                let difference = (ahead[i] - behind[i]) / (2.0 * step);
                let scale = rates.iter().chain([&difference]).fold(0.0f64, |m, r| m.max(r.abs()));
                assert!(
                    (rate - difference).abs() <= tolerance * scale,
                    "y {lateral}: d(output {i})/d({known}) = {rate}, differences {difference}"
                );
            }
            if known == vr::WHEELSET_LATERAL_DISPLACEMENT {
                assert!(rates[0].abs() > 1e3 || rates[1].abs() > 1e3, "y {lateral}: the forces move with y_ws");
                assert!(rates[2].abs() <= 1e-3 * rates[1].abs().max(1.0), "y {lateral}: ∂F_z/∂y = {}", rates[2]);
            }
            if known == vr::VERTICAL_FORCE {
                assert!((rates[2] + 1.0).abs() < 1e-4, "y {lateral}: ∂F_z/∂(vertical_force) = {}", rates[2]);
            }
        }
    }
}

#[test]
fn a_rail_cant_beyond_its_range_is_an_error_naming_it() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("cant", &log);
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
    assert_eq!(fmu.set_real(&[vr::RAIL_CANT], &[0.2]), OK);
    assert_eq!(exit_initialisation(&fmu), ERROR);
    let (_, message) = log.last().unwrap();
    assert!(message.starts_with("fmi2ExitInitializationMode: rail_cant = 0.2"), "{message}");
    // Defect 10 of the review: the documented ±0.1 rad was mostly refused on the built-in rail
    // (1:40 = 0.025 "turns a flank … past the vertical"). Every cant of the range places it and
    // steps: first the same instance, corrected, then fresh ones.
    assert_eq!(fmu.set_real(&[vr::RAIL_CANT], &[0.025]), OK);
    // SAFETY: a live instance, still in initialisation mode.
    assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK, "{:?}", log.last());
    assert_eq!(fmu.do_step(0.0, 1e-3), OK, "{:?}", log.last());
    for cant in [0.1, -0.1, 0.05] {
        let fmu = Fmu::instantiate_logged("cant", &log);
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
        assert_eq!(fmu.set_real(&[vr::RAIL_CANT], &[cant]), OK);
        assert_eq!(exit_initialisation(&fmu), OK, "rail_cant {cant}: {:?}", log.last());
        assert_eq!(fmu.do_step(0.0, 1e-3), OK, "rail_cant {cant}: {:?}", log.last());
        assert_eq!(fmu.get_real(&[vr::CONTACT_PATCH_COUNT])[0], 1.0, "rail_cant {cant}");
    }
}

#[test]
fn the_patch_count_and_patch_one_follow_the_load_and_are_declared_to() {
    // Unyawed at 5 mm, S1002 on UIC60 touches on the tread and the flange root: under 10 kN two
    // patches, under 100 kN their interpenetrations join into one, the deeper kept (the core's
    // normal problem, module doc). The count, and with it which candidate is patch 1 or 2,
    // change with the load, so `<ModelStructure>` lists vertical_force (and every input of the
    // balance) for them.
    let log = MessageLog::default();
    let mut inputs = [5e-3, 0.0, 0.0, 0.0, 10e3, 2.0, 2.0 / 0.46, 0.0, 0.0];
    let fmu = profiles(SideChoice::Right, &inputs, &log);
    let outputs = [vr::CONTACT_PATCH_COUNT, vr::PATCH1_CONTACT_ANGLE, vr::PATCH2_RAIL_LATERAL_POSITION];
    let light = fmu.get_real(&outputs);
    inputs[4] = 100e3;
    assert_eq!(fmu.set_real(&WHEELSET, &inputs), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    let heavy = fmu.get_real(&outputs);
    assert_eq!((light[0], heavy[0]), (2.0, 1.0), "{light:?} {heavy:?}");
    assert!(light[2] != 0.0 && heavy[2] == 0.0, "patch 2 joins patch 1: {light:?} {heavy:?}");
    for output in outputs {
        let declared = variable(output).unwrap();
        for input in
            [vr::VERTICAL_FORCE, vr::WHEELSET_VERTICAL_POSITION, vr::WHEELSET_ROLL_ANGLE, vr::FRICTION_COEFFICIENT]
        {
            assert!(declared.dependencies.contains(&input), "{} must list {input}", declared.name);
        }
    }
}

/// One instance with profiles and `model`, stepping at 10 kN (default inputs) as y_ws changes:
/// each step's status, patch count and vertical force.
struct Sweep {
    fmu: Fmu,
    /// Boxed: the FMU's logger keeps its address.
    log: Box<MessageLog>,
    time: std::cell::Cell<f64>,
}

impl Sweep {
    fn new(model: i32) -> Sweep {
        let log = Box::new(MessageLog::default());
        let fmu = Fmu::instantiate_logged("balance", &log);
        // Hertz's patches, whose join near y_ws = −0.248 mm this sweeps.
        let integers = [ContactGeometry::Profiles as i32, model, ContactMethod::Hertz as i32];
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::CREEP_FORCE_MODEL, vr::CONTACT_METHOD], &integers), OK);
        fmu.initialise(0.0);
        Sweep { fmu, log, time: std::cell::Cell::new(0.0) }
    }

    fn at(&self, lateral: f64) -> (fmi2Status, f64, f64) {
        assert_eq!(self.fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[lateral]), OK);
        let status = self.fmu.do_step(self.time.get(), 1e-3);
        if status != OK {
            // Read at this position the outputs would be the same error (direct feedthrough).
            return (status, f64::NAN, f64::NAN);
        }
        self.time.set(self.time.get() + 1e-3);
        let [count, force] = self.fmu.get_real(&[vr::CONTACT_PATCH_COUNT, vr::TRACK_FORCE_Z])[..] else {
            unreachable!()
        };
        (status, count, force)
    }
}

#[test]
fn the_vertical_balance_settles_where_tread_and_flange_patches_join() {
    // The review's defect 7: at 10 kN the balance "did not settle in 12 rounds" in a window
    // some 1e-15 m wide near y_ws = −0.24798 mm (SHE, FASTSIM, exact_table), where two
    // patches join and the carried force jumps, so no height carries the load exactly. Found
    // here as the patch count's change (bisected to adjacent floats), then stepped through
    // ±4e-15 m around it every 2e-17 m: every step settles, within 1 % of the load (the jump's
    // side that carries it more closely). The worst miss is printed (`-- --nocapture`).
    let mut worst = 0.0f64;
    let mut boundaries = 0;
    for model in [Model::ShenHedrickElkins, Model::Fastsim, Model::ExactTable, Model::Polach] {
        let sweep = Sweep::new(model as i32);
        let mut previous = None;
        for k in 0..=100 {
            let lateral = -0.3e-3 + f64::from(k) * 1e-6;
            let (status, count, _) = sweep.at(lateral);
            assert_eq!(status, OK, "{model:?} at {lateral}: {:?}", sweep.log.last());
            let Some((before, before_count)) = previous.replace((lateral, count)) else { continue };
            if before_count == count {
                continue;
            }
            let (mut low, mut high) = (before, lateral);
            while let Some(middle) = Some(0.5 * (low + high)).filter(|&m| m > low && m < high) {
                if sweep.at(middle).1 == before_count {
                    low = middle;
                } else {
                    high = middle;
                }
            }
            boundaries += 1;
            for step in -200..=200 {
                let lateral = high + f64::from(step) * 2e-17;
                let (status, _, force) = sweep.at(lateral);
                assert_eq!(status, OK, "{model:?} at y_ws = {lateral:e}: {:?}", sweep.log.last());
                let miss = (force + 10e3).abs() / 10e3;
                worst = worst.max(miss);
                assert!(miss < 0.01, "{model:?} at y_ws = {lateral:e}: F_z = {force}");
            }
        }
    }
    eprintln!("WORST {worst} over {boundaries} boundaries");
    assert!(boundaries >= 3, "the joins of tread and flange patches were not found");
}

#[test]
fn tiny_loads_settle() {
    // Defect 7: 0 < vertical_force ≲ 2e-3 N "did not settle in 12 rounds" for every model (the
    // balance's tolerance, 1e-10 of the load, finer than a penetration of nanometres resolves).
    for model in [Model::Polach, Model::ShenHedrickElkins, Model::Fastsim, Model::ExactTable, Model::KalkerLinear] {
        let sweep = Sweep::new(model as i32);
        for (k, load) in [1e-6, 1e-4, 1e-3, 2e-3, 0.1, 1.0, 1e3].into_iter().enumerate() {
            assert_eq!(sweep.fmu.set_real(&[vr::VERTICAL_FORCE], &[load]), OK);
            let (status, count, force) = sweep.at(2e-3 * (k as f64 - 3.0));
            assert_eq!(status, OK, "{model:?}, {load} N: {:?}", sweep.log.last());
            assert!(count >= 1.0);
            assert!((force + load).abs() <= 1e-6 * load, "{model:?}, {load} N: F_z = {force}");
        }
    }
}

#[test]
fn a_huge_lateral_displacement_is_a_clean_error() {
    // Defect 2: y_ws ≥ 2e15 m (|yaw| ≤ 0.025) panicked in the contact table (an index sum
    // wrapped): fmi2Fatal and a Rust panic report on the host's stderr.
    let sweep = Sweep::new(Model::Polach as i32);
    for lateral in [2e15, 1e16, 1.8e19, 1e300, f64::MAX, -2e15, -f64::MAX] {
        for yaw in [0.0, 0.02] {
            assert_eq!(sweep.fmu.set_real(&[vr::WHEELSET_YAW_ANGLE], &[yaw]), OK);
            let (status, _, _) = sweep.at(lateral);
            assert_eq!(status, ERROR, "y_ws = {lateral}");
            let (_, message) = sweep.log.last().unwrap();
            assert!(message.contains("do not overlap laterally at wheelset_lateral_displacement"), "{message}");
        }
    }
    assert_eq!(sweep.fmu.set_real(&[vr::WHEELSET_YAW_ANGLE], &[0.0]), OK);
    assert_eq!(sweep.at(1e-3).0, OK, "the instance carries on");
}

#[test]
fn a_prescribed_position_inside_the_rail_is_refused() {
    // Defect 11: z_ws = 1e6 m gave N = 1.4e20 N and 1.2 km semi-axes with fmi2OK; z_ws = 1e300
    // blamed normal_force, an input profile mode does not read.
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("position", &log);
    let integers = [ContactGeometry::Profiles as i32, VerticalChoice::PrescribedPosition as i32];
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::VERTICAL_CONTACT], &integers), OK);
    fmu.initialise(0.0);
    for vertical in [1e6, 1e300, f64::MAX, 0.2] {
        assert_eq!(fmu.set_real(&[vr::WHEELSET_VERTICAL_POSITION], &[vertical]), OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), ERROR, "z_ws = {vertical}");
        let (_, message) = log.last().unwrap();
        assert!(
            message.starts_with(&format!("fmi2DoStep: wheelset_vertical_position = {vertical} m puts the wheel"))
                && message.contains("more than 0.1 m of penetration"),
            "{message}"
        );
    }
    // The instance carries on at a real height.
    assert_eq!(fmu.set_real(&[vr::WHEELSET_VERTICAL_POSITION], &[0.0]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK, "{:?}", log.last());
}

/// `contact_method = non_hertzian` through the C ABI: the centred wheelset (Manchester
/// case 1, 10 kN) has its one wide patch where CONTACT's full solution has it, rail y = −8.66 mm
/// and δ = −0.0290 rad (CONTACT rev. 2707, `core/tests/data/mbench_a22_contact_ref_out.csv`),
/// within the 1 mm and 0.01 rad of CONTACT's fast methods; `hertz` puts its ellipse at the gap's
/// minimum, 1.4 mm off. Case 11 (5 mm, yawed: Hertz finds a tread and a flange patch) gives
/// CONTACT's one patch at −33.45 mm, δ = −0.2905 rad, within 2 mm and 0.05 rad. `non_hertzian`
/// is the start value.
#[test]
fn non_hertzian_patches_are_where_contact_finds_them() {
    let fresh = Fmu::instantiate("start value", None);
    fresh.initialise(0.0);
    let mut method = [0];
    // SAFETY: a live instance (Get is legal from initialisation mode on); one reference, one value.
    assert_eq!(unsafe { fmi2GetInteger(fresh.c, [vr::CONTACT_METHOD].as_ptr(), 1, method.as_mut_ptr()) }, OK);
    assert_eq!(method, [ContactMethod::NonHertzian as i32]);
    let centred = [0.0, 0.0, 0.0, 0.0, 10e3, 2.0, 4.3478, 0.0, 0.0];
    let case_11 = [5e-3, 0.0, -3.554e-4, 0.012, 10e3, 2.0, 4.3353637, 0.0, 0.0];
    let patches = |inputs: &[f64; 9], method: ContactMethod| {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged("contact method", &log);
        let integers = [ContactGeometry::Profiles as i32, method as i32];
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::CONTACT_METHOD], &integers), OK);
        assert_eq!(fmu.set_real(&WHEELSET, inputs), OK);
        fmu.initialise(0.0);
        let [count, angle, rail_y, force_z] = fmu
            .get_real(&[
                vr::CONTACT_PATCH_COUNT,
                vr::PATCH1_CONTACT_ANGLE,
                vr::PATCH1_RAIL_LATERAL_POSITION,
                vr::TRACK_FORCE_Z,
            ])
            .try_into()
            .unwrap();
        assert!((force_z + 10e3).abs() < 1e-6 * 10e3, "{method:?}: F_z {force_z}");
        (count, angle, rail_y)
    };
    let (count, angle, rail_y) = patches(&centred, ContactMethod::NonHertzian);
    assert_eq!(count, 1.0);
    assert!((rail_y + 8.66e-3).abs() < 1e-3 && (angle + 0.0290).abs() < 0.01, "rail y {rail_y}, δ {angle}");
    let (_, _, hertz_rail_y) = patches(&centred, ContactMethod::Hertz);
    assert!((hertz_rail_y + 8.66e-3).abs() > 1e-3, "Hertz at the gap's minimum: {hertz_rail_y}");
    let (count, angle, rail_y) = patches(&case_11, ContactMethod::NonHertzian);
    assert_eq!(count, 1.0);
    assert!((rail_y + 33.447e-3).abs() < 2e-3 && (angle + 0.2905).abs() < 0.05, "rail y {rail_y}, δ {angle}");
    assert_eq!(patches(&case_11, ContactMethod::Hertz).0, 2.0, "Hertz: tread and flange");
}

/// At a change of the patches (case 11's pose at y_ws = 4.7395 mm: one patch, a second within
/// 0.5 µm further out; found by a 1 µm sweep), the derivative along y_ws is the one-sided
/// difference on the side with the patches of the inputs themselves (over the derivative's step,
/// 10 µm), not a central one across the change.
#[test]
fn at_a_change_of_the_patches_the_derivative_is_one_sided() {
    let log = MessageLog::default();
    let mut inputs = CASE_11;
    inputs[0] = 4.7395e-3;
    let fmu = profiles(SideChoice::Right, &inputs, &log);
    let forces = [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_MOMENT_Z];
    let (status, rates) = fmu.directional_derivative(&forces, &[vr::WHEELSET_LATERAL_DISPLACEMENT], &[1.0]);
    assert_eq!(status, OK);
    let step = 1e-5;
    let at = |y: f64| {
        assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[y]), OK);
        let count = fmu.get_real(&[vr::CONTACT_PATCH_COUNT])[0];
        (count, fmu.get_real(&forces))
    };
    let (y, (here, base), (ahead, f_ahead), (behind, f_behind)) =
        (inputs[0], at(inputs[0]), at(inputs[0] + step), at(inputs[0] - step));
    assert_eq!((here, behind), (1.0, 1.0));
    assert_eq!(ahead, 2.0, "the flange comes into contact within the step");
    for i in 0..3 {
        let one_sided = (base[i] - f_behind[i]) / step;
        let central = (f_ahead[i] - f_behind[i]) / (2.0 * step);
        assert!((rates[i] - one_sided).abs() <= 1e-9 * one_sided.abs(), "y {y}: {} vs {one_sided}", rates[i]);
        assert!((rates[i] - central).abs() > 1e-3 * one_sided.abs(), "the central difference would straddle the jump");
    }
}

/// Measured MiniProf profiles through the FMU (issue 39): a measured wheel and high rail from
/// CONTACT's test bank (`core/tests/data/profiles/measured/`, its README) read, cleaned and
/// smoothed (`profile_filter_wavelength`, 5 mm by default); the MiniProf wheel's y runs from its
/// flange back (`flange_back_position = 0`) and the rail is measured in its own axes (1:40
/// inclination by `rail_cant`). Centred, with 10 kN: the wheel carries the load on one patch on
/// its tread (CONTACT's own search on these files smooths them too); interpolated (wavelength 0)
/// the noise's minima give more candidates, and the answer still carries the load. A negative
/// wavelength is refused naming it.
#[test]
fn measured_miniprof_profiles_are_read_cleaned_and_smoothed() {
    let measured = concat!(env!("CARGO_MANIFEST_DIR"), "/../core/tests/data/profiles/measured/");
    let wheel = format!("{measured}right-wheel-v1-pre-dry.whl");
    let rail = format!("{measured}avg_HR.BAN");
    let run = |wavelength: f64| {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged("measured", &log);
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
        assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE], &[&wheel, &rail]), OK);
        let reals = [0.0, (1.0f64 / 40.0).atan(), wavelength];
        assert_eq!(fmu.set_real(&[vr::FLANGE_BACK_POSITION, vr::RAIL_CANT, vr::PROFILE_FILTER_WAVELENGTH], &reals), OK);
        assert_eq!(fmu.set_real(&WHEELSET, &[0.0, 0.0, 0.0, 0.0, 10e3, 2.0, 4.3478, 0.0, 0.0]), OK);
        let status = exit_initialisation(&fmu);
        (status, fmu, log)
    };
    let (status, fmu, log) = run(5e-3);
    assert_eq!(status, OK, "{:?}", log.last());
    let [count, force_z, angle, rail_y] = fmu
        .get_real(&[
            vr::CONTACT_PATCH_COUNT,
            vr::TRACK_FORCE_Z,
            vr::PATCH1_CONTACT_ANGLE,
            vr::PATCH1_RAIL_LATERAL_POSITION,
        ])
        .try_into()
        .unwrap();
    assert_eq!(count, 1.0);
    assert!((force_z + 10e3).abs() < 1e-6 * 10e3, "F_z {force_z}");
    assert!(angle.abs() < 0.1 && rail_y.abs() < 20e-3, "on the tread: δ {angle}, rail y {rail_y}");
    let (status, fmu, log) = run(0.0);
    assert_eq!(status, OK, "{:?}", log.last());
    assert!((fmu.get_real(&[vr::TRACK_FORCE_Z])[0] + 10e3).abs() < 1e-6 * 10e3);
    let (status, _, log) = run(-1e-3);
    assert_eq!(status, ERROR);
    let (_, message) = log.last().unwrap();
    assert!(message.contains("profile_filter_wavelength = -0.001 is invalid"), "{message}");
}

/// Worn, measured profiles through the FMU with `contact_method = non_hertzian` (issue 39): the
/// averaged worn wheel on the averaged worn high rail (MiniProf, CONTACT's test bank), on their
/// North American track, at y_ws = 12.5 mm, 80 kN, yaw 2 mrad, μ = 0.3, `exact_table`: CONTACT's
/// full solution (`core/tests/data/contact_worn_right.csv`, case 14) has two patches, the tread's
/// at rail y −20.80 mm (FN 67.87 kN) and the worn gauge corner's at −36.92 mm (11.15 kN); the FMU
/// reports both, tread first, within 1 mm and 2 mm, their normal forces within 3 % and 5 %
/// (the gauge corner's angle is CONTACT's planar mean, `wheel_worn.rs`), its totals within
/// 0.12 μF_z of CONTACT's (FX, FY on the rail −18.01, −3.405 kN).
#[test]
fn worn_measured_profiles_give_contacts_two_patches() {
    use wheel_rail_contact_fmu::model_description::ContactMethod;
    let measured = concat!(env!("CARGO_MANIFEST_DIR"), "/../core/tests/data/profiles/measured/");
    let (wheel, rail) = (format!("{measured}avg_wheel.whl"), format!("{measured}avg_HR.BAN"));
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("worn", &log);
    let integers = [ContactGeometry::Profiles as i32, ContactMethod::NonHertzian as i32, Model::ExactTable as i32];
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY, vr::CONTACT_METHOD, vr::CREEP_FORCE_MODEL], &integers), OK);
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE], &[&wheel, &rail]), OK);
    let track = [
        (vr::TRACK_GAUGE, 1.4351),
        (vr::GAUGE_MEASURING_HEIGHT, 0.015875),
        (vr::FLANGE_BACK_DISTANCE, 1.3522),
        (vr::FLANGE_BACK_POSITION, 0.0),
        (vr::WHEEL_NOMINAL_RADIUS, 0.4191),
        (vr::FRICTION_COEFFICIENT, 0.3),
    ];
    for (reference, value) in track {
        assert_eq!(fmu.set_real(&[reference], &[value]), OK);
    }
    assert_eq!(fmu.set_real(&WHEELSET, &[12.5e-3, 0.0, 0.0, 0.002, 80e3, 2.0, 2.0 / 0.4191, 0.0, 0.0]), OK);
    assert_eq!(exit_initialisation(&fmu), OK, "{:?}", log.last());
    let [count, fx, fy, fz, y1, n1, y2, n2] = fmu
        .get_real(&[
            vr::CONTACT_PATCH_COUNT,
            vr::TRACK_FORCE_X,
            vr::TRACK_FORCE_Y,
            vr::TRACK_FORCE_Z,
            vr::PATCH1_RAIL_LATERAL_POSITION,
            vr::PATCH1_NORMAL_FORCE,
            vr::PATCH2_RAIL_LATERAL_POSITION,
            vr::PATCH2_NORMAL_FORCE,
        ])
        .try_into()
        .unwrap();
    assert_eq!(count, 2.0);
    assert!((y1 + 20.80e-3).abs() < 1e-3 && (n1 / 67.87e3 - 1.0).abs() < 0.03, "tread: y {y1}, N {n1}");
    assert!((y2 + 36.92e-3).abs() < 2e-3 && (n2 / 11.15e3 - 1.0).abs() < 0.05, "gauge corner: y {y2}, N {n2}");
    // On the wheel: the negatives of CONTACT's totals on the rail.
    for (ours, contact) in [(fx, 18.01e3), (fy, 3.405e3)] {
        assert!((ours - contact).abs() < 0.12 * 0.3 * 80e3, "{ours} against {contact}");
    }
    assert!((fz + 80e3).abs() < 1e-6 * 80e3, "F_z {fz}");
}

/// With `contact_method = non_hertzian` and a prescribed load the vertical balance's search
/// starts where the last one settled, which is part of the wheel's state (a warm start: it
/// meets the load within 1e-10 from anywhere, but not at the same bits). So the outputs are a
/// function of the inputs and the state alone: after a step, reading them at other inputs and
/// back, a directional derivative (its evaluations move the inputs by ±10 µm), and a failed step
/// leave the outputs at the step's own inputs as the step gave them, bit for bit — on the tread,
/// the centred wheelset and where tread and flange root share the load. (Started from a cache
/// instead of the state, each of these moved them by some 1e-10.)
#[test]
fn non_hertzian_outputs_are_a_function_of_the_inputs_and_the_state() {
    let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
    for lateral in [2e-3, 0.0, 5e-3] {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged("non_hertzian", &log);
        let parameters = [vr::CONTACT_GEOMETRY, vr::WHEEL_SIDE, vr::CONTACT_METHOD];
        let choices = [ContactGeometry::Profiles as i32, SideChoice::Right as i32, ContactMethod::NonHertzian as i32];
        assert_eq!(fmu.set_integer(&parameters, &choices), OK);
        let mut inputs = CASE_11;
        inputs[0] = lateral;
        assert_eq!(fmu.set_real(&WHEELSET, &inputs), OK);
        fmu.initialise(0.0);
        // A step from the initial state to a moved pose, whose search starts away from its root.
        assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[lateral + 2e-5]), OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), OK, "{:?}", log.last());
        let step = fmu.get_real(&WHEEL_OUTPUTS);
        assert!(step[vr_index(vr::CONTACT_PATCH_COUNT)] >= 1.0, "y_ws {lateral}: {step:?}");
        let at = |y: f64| {
            assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[y]), OK);
            fmu.get_real(&WHEEL_OUTPUTS)
        };
        at(lateral + 5e-5);
        assert_eq!(bits(&at(lateral + 2e-5)), bits(&step), "y_ws {lateral}: read at other inputs and back");
        let (status, _) =
            fmu.directional_derivative(&[vr::TRACK_FORCE_X], &[vr::WHEELSET_LATERAL_DISPLACEMENT], &[1.0]);
        assert_eq!(status, OK, "{:?}", log.last());
        assert_eq!(bits(&fmu.get_real(&WHEEL_OUTPUTS)), bits(&step), "y_ws {lateral}: after a directional derivative");
        assert_eq!(fmu.set_real(&[vr::VERTICAL_FORCE], &[f64::NAN]), OK);
        assert_eq!(fmu.do_step(1e-3, 1e-3), ERROR);
        assert_eq!(fmu.set_real(&[vr::VERTICAL_FORCE], &[inputs[4]]), OK);
        assert_eq!(bits(&fmu.get_real(&WHEEL_OUTPUTS)), bits(&step), "y_ws {lateral}: after a failed step");
    }
}

/// The position of value reference `reference` in [`WHEEL_OUTPUTS`].
fn vr_index(reference: u32) -> usize {
    WHEEL_OUTPUTS.iter().position(|&r| r == reference).expect("a wheel output")
}
