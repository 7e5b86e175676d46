//! The packaged `.fmu`, imported with rust-fmi (the `fmi` crate) as a Rust master would, must
//! reproduce the core library bit for bit. Builds its own FMU (dev profile: cheaper than the
//! release build of `cargo fmu`, same code) so that `cargo test --workspace` needs no prior step.

use fmi::fmi2::import::Fmi2Import;
use fmi::fmi2::instance::{CoSimulation, Common};
use fmi::schema::fmi2::Causality;
use fmi::traits::{FmiImport, FmiInstance};
use packaging::default_scene::{default_creepages, sweep};
use packaging::documentation::default_contact_input;
use packaging::fmu::{package, Profile, Reach, CONTACT};
use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, GUID, VARIABLES};

fn packaged_fmu() -> (tempfile::TempDir, std::path::PathBuf) {
    let directory = tempfile::tempdir().unwrap();
    let fmu = package(&CONTACT, Profile::Dev, Reach::ThisMachine, directory.path()).unwrap().fmu;
    (directory, fmu)
}

#[test]
#[ignore = "slow tier: scripts/test-all runs it (cargo test --workspace -- --include-ignored)"]
fn rust_fmi_imports_the_fmu_and_runs_scenes_equal_to_the_core() {
    let (_directory, fmu) = packaged_fmu();
    let import: Fmi2Import = fmi::import::from_path(&fmu).unwrap();
    let description = import.model_description();
    assert_eq!(description.guid, GUID);
    let names: Vec<&str> = description.model_variables.variables.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, VARIABLES.iter().map(|v| v.name).collect::<Vec<_>>());
    let outputs = description.model_variables.variables.iter().filter(|v| v.causality == Causality::Output).count();
    assert_eq!(
        outputs,
        13 + 8 + 2 * 11,
        "one patch: forces, utilisation, spin moment, friction, slip velocity, 3 creepages, a, b, p0, approach; \
         a wheel on profiles: 3 forces, 3 moments, patch count, z_ws, and 11 per patch for two patches"
    );

    // The default scene's creepage sweep (the README's first command).
    let rows = sweep(&fmu, &default_creepages()).unwrap();
    for row in &rows {
        let input = ContactInput { creepage_longitudinal: row.creepage_longitudinal, ..default_contact_input() };
        let expected = Polach::default().creep_forces(&input).unwrap();
        assert_eq!(row.force_longitudinal, expected.force_longitudinal, "ξ = {}", row.creepage_longitudinal);
        assert_eq!(row.force_lateral, expected.force_lateral);
        assert_eq!(row.adhesion_utilisation, expected.adhesion_utilisation);
    }
    assert!(rows.windows(2).all(|pair| pair[1].force_longitudinal < pair[0].force_longitudinal), "saturating");

    // A combined scene with a load step and a friction drop, stepped with varying step sizes.
    let mut instance = import.instantiate_cs("combined", false, true).unwrap();
    FmiInstance::enter_initialization_mode(&mut instance, None, 0.0, Some(1.0)).unwrap();
    FmiInstance::exit_initialization_mode(&mut instance).unwrap();
    let references = [vr::CREEPAGE_LATERAL, vr::SPIN_CREEPAGE, vr::NORMAL_FORCE, vr::FRICTION_COEFFICIENT];
    let mut time = 0.0;
    for (step, values) in
        [(0.1, [1e-3, 0.5, 100e3, 0.3]), (0.25, [1e-3, 0.5, 120e3, 0.3]), (0.05, [2e-3, -0.2, 120e3, 0.15])]
    {
        Common::set_real(&mut instance, &references, &values).unwrap();
        instance.do_step(time, step, true).unwrap();
        time += step;
        let mut forces = [0.0; 3];
        Common::get_real(
            &mut instance,
            &[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION],
            &mut forces,
        )
        .unwrap();
        let [creepage_lateral, spin_creepage, normal_force, friction_coefficient] = values;
        let input = ContactInput {
            creepage_lateral,
            spin_creepage,
            normal_force,
            friction_coefficient,
            ..default_contact_input()
        };
        let expected = Polach::default().creep_forces(&input).unwrap();
        assert_eq!(forces, [expected.force_longitudinal, expected.force_lateral, expected.adhesion_utilisation]);
    }
    // Past the stop time: refused, and the instance still answers.
    assert!(instance.do_step(time, 1.0, true).is_err());
    FmiInstance::terminate(&mut instance).unwrap();
}
