//! The `exact_table` model's table in the FMU's `resources/` (issue 29), through the C ABI: read
//! from there (the same forces as the core's model on the same file, bit for bit), and a missing,
//! corrupted, truncated or foreign table refused at fmi2Instantiate with a message naming the
//! file and what is wrong — never a wrong force. Without a resource location the instance
//! still works, and selecting the model is the error, saying why.

use std::path::{Path, PathBuf};

use fmu_test_master::{file_uri, Fmu, MessageLog, ERROR, INPUTS, OK};
use wheel_rail_contact::models::exact_table::Table;
use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTable};
use wheel_rail_contact_fmu::ffi::{fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2SetupExperiment};
use wheel_rail_contact_fmu::fmi2::fmi2Status;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Model};

const SHIPPED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin");

/// A fresh directory standing for an unzipped FMU's `resources/` (a space in its name, as
/// masters' temporary folders have), holding `table` as `exact_table.bin` if given.
fn resources(name: &str, table: Option<&[u8]>) -> PathBuf {
    let directory = std::env::temp_dir().join(format!("wrc table {name} {}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    if let Some(bytes) = table {
        std::fs::write(directory.join("exact_table.bin"), bytes).unwrap();
    }
    directory
}

fn exit_initialisation(fmu: &Fmu) -> fmi2Status {
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        fmi2ExitInitializationMode(fmu.c)
    }
}

/// A contact well inside the table, partly sliding, with spin.
const CONTACT: [f64; 7] = [1.5e-3, -0.8e-3, 0.4, 90e3, 6e-3, 4.5e-3, 0.35];

/// fmi2Instantiate at `location` refused: the one message logged, for `file`.
fn refusal(location: &str) -> String {
    let log = MessageLog::default();
    assert!(Fmu::try_instantiate_logged_at("damaged", &log, Some(location)).is_none(), "{location}");
    let (status, message) = log.last().unwrap();
    assert_eq!(status, ERROR);
    assert_eq!(log.texts().len(), 1, "{:?}", log.texts());
    message
}

#[test]
fn the_model_reads_the_table_in_the_resources_as_the_core_reads_the_same_file() {
    let shipped = std::fs::read(SHIPPED).unwrap();
    let directory = resources("good", Some(&shipped));
    // file:/… (one slash), as some masters write it: the same directory.
    let location = file_uri(&directory).replacen("file://", "file:", 1);
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged_at("exact_table", &log, Some(&location));
    assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL], &[Model::ExactTable as i32]), OK);
    assert_eq!(fmu.set_real(&INPUTS, &CONTACT), OK);
    assert_eq!(exit_initialisation(&fmu), OK, "{:?}", log.texts());
    assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    let outputs = fmu.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT]);

    let table: &'static Table = Box::leak(Box::new(Table::from_bytes(&shipped).unwrap()));
    let [xi, eta, phi, q, a, b, mu] = CONTACT;
    let expected = ExactTable::with_table(table)
        .creep_forces(&ContactInput {
            creepage_longitudinal: xi,
            creepage_lateral: eta,
            spin_creepage: phi,
            normal_force: q,
            semi_axis_a: a,
            semi_axis_b: b,
            friction_coefficient: mu,
            shear_modulus: 82e9,
            poisson_ratio: 0.28,
        })
        .unwrap();
    assert_eq!(outputs, [expected.force_longitudinal, expected.force_lateral, expected.spin_moment.unwrap()]);
    // Partly sliding with spin: a real force, not a zero that would match anything.
    assert!(expected.force_longitudinal < -0.1 * mu * q && expected.spin_moment.unwrap() != 0.0, "{expected:?}");
    drop(fmu);
    std::fs::remove_dir_all(directory).unwrap();
}

#[test]
fn a_missing_corrupted_truncated_or_foreign_table_fails_the_instantiation_naming_the_file() {
    let shipped = std::fs::read(SHIPPED).unwrap();
    let mut flipped = shipped.clone();
    flipped[shipped.len() / 2] ^= 0x10;
    let foreign = include_bytes!("../../../data/profiles/MBench_S1002_v3.prw");
    let cases: [(&str, Option<&[u8]>, &str); 5] = [
        ("missing", None, "cannot read the exact_table model's table"),
        ("flipped", Some(&flipped), "checksum mismatch"),
        ("truncated", Some(&shipped[..shipped.len() - 1000]), "checksum mismatch"),
        ("empty", Some(&[]), "0 bytes is too short for a table"),
        ("foreign", Some(foreign), "not a table file (wrong magic bytes)"),
    ];
    for (name, table, reason) in cases {
        let directory = resources(name, table);
        let message = refusal(&file_uri(&directory));
        let file = directory.join("exact_table.bin");
        assert!(message.starts_with("fmi2Instantiate: "), "{name}: {message}");
        assert!(message.contains(&file.display().to_string()) && message.contains(reason), "{name}: {message}");
        std::fs::remove_dir_all(directory).unwrap();
    }
}

/// Without a resource location (NULL, or one naming no directory) nothing can be checked at
/// fmi2Instantiate: the instance works with every other model, and selecting exact_table is
/// refused at fmi2ExitInitializationMode, saying where the table was looked for.
#[test]
fn without_resources_only_selecting_the_model_is_an_error() {
    let nowhere = Path::new("/nonexistent/wrc/resources");
    for (location, reason) in [
        (None, "the master passed no usable resource location to fmi2Instantiate".to_owned()),
        (
            Some(file_uri(nowhere)),
            format!("cannot read the exact_table model's table {}", nowhere.join("exact_table.bin").display()),
        ),
    ] {
        let log = MessageLog::default();
        let fmu = Fmu::instantiate_logged_at("no resources", &log, location.as_deref());
        assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL], &[Model::ExactTable as i32]), OK);
        assert_eq!(exit_initialisation(&fmu), ERROR);
        let message = log.last().unwrap().1;
        assert!(
            message.starts_with("fmi2ExitInitializationMode: creep_force_model = 6 (exact_table): ")
                && message.contains(&reason),
            "{message}"
        );
        // Another model, and the instance carries on.
        assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL], &[Model::Polach as i32]), OK);
        // SAFETY: a live instance, still in initialisation mode.
        assert_eq!(unsafe { fmi2ExitInitializationMode(fmu.c) }, OK);
        assert_eq!(fmu.do_step(0.0, 1e-3), OK);
    }
}

#[cfg(unix)]
#[test]
fn a_table_that_is_not_a_regular_file_or_too_large_is_refused_at_once() {
    // Every file the FMU opens is bounded (issue 40's class search): resources/exact_table.bin
    // as a FIFO would block fmi2Instantiate for ever, as /dev/zero it would read until memory
    // runs out.
    let root = std::env::temp_dir().join(format!("wrc-table-kinds-{}", std::process::id()));
    for (name, make) in [
        (
            "fifo",
            &(|path: &std::path::Path| {
                let name = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
                // SAFETY: a NUL-terminated path.
                assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
            }) as &dyn Fn(&std::path::Path),
        ),
        ("zero", &|path: &std::path::Path| std::os::unix::fs::symlink("/dev/zero", path).unwrap()),
        ("huge", &|path: &std::path::Path| std::fs::File::create(path).unwrap().set_len(65 << 20).unwrap()),
    ] {
        let resources = root.join(name);
        std::fs::create_dir_all(&resources).unwrap();
        make(&resources.join("exact_table.bin"));
        let log = MessageLog::default();
        let location = format!("file://{}/", resources.to_str().unwrap());
        let start = std::time::Instant::now();
        assert!(Fmu::try_instantiate_logged_at("table", &log, Some(&location)).is_none(), "{name}");
        assert!(start.elapsed() < std::time::Duration::from_secs(2), "{name}: {:?}", start.elapsed());
        let (_, message) = log.last().unwrap();
        let reason = if name == "huge" { "this file may have at most 67108864" } else { "not a regular file" };
        assert!(message.contains("cannot read the exact_table model's table") && message.contains(reason), "{message}");
    }
    std::fs::remove_dir_all(&root).unwrap();
}
