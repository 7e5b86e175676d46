//! What the FMU accepts as a profile file and what it refuses, through the C ABI as a hostile
//! or careless master drives it (the defects of the second independent review, issue 40): a
//! far-off point, a wrong length unit, a spike, a device, FIFO or huge file behind a profile's
//! name, a wheel file given as the rail, bytes that are not UTF-8 in a file or in a file name, a
//! path of megabytes, a file changed on disk under a saved FMU state. Every refusal is
//! fmi2Error at once, naming the variable, the file and (where one is to blame) the line; the
//! instance then carries on with a corrected value.

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use fmu_test_master::{Fmu, MessageLog, ERROR, OK};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use wheel_rail_contact_fmu::ffi::{
    fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2SetString, fmi2SetupExperiment,
};
use wheel_rail_contact_fmu::fmi2::fmi2Status;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, ContactGeometry};

const WHEEL_FILE: &str = include_str!("../../../data/profiles/MBench_S1002_v3.prw");
const RAIL_BAN: &[u8] = include_bytes!("../../../data/profiles/MBench_UIC60_v3.ban");

/// A directory of this test's own (removed at the end of each test that makes one).
fn scratch(name: &str) -> PathBuf {
    let directory = std::env::temp_dir().join(format!("wrc-profile-files-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    directory
}

/// An instance with profiles in initialisation mode, `reference` set to `value`.
fn with_profile(log: &MessageLog, reference: u32, value: &str) -> Fmu {
    let fmu = Fmu::instantiate_logged("profile files", log);
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
    assert_eq!(fmu.set_string(&[reference], &[value]), OK);
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    fmu
}

fn exit_initialisation(fmu: &Fmu) -> fmi2Status {
    // SAFETY: a live instance in initialisation mode.
    unsafe { fmi2ExitInitializationMode(fmu.c) }
}

fn variable_name(reference: u32) -> &'static str {
    if reference == vr::WHEEL_PROFILE {
        "wheel_profile"
    } else {
        "rail_profile"
    }
}

/// `value` as `reference` is refused at fmi2ExitInitializationMode within a second (no
/// allocation sized by the file, no blocking read), with a message naming the variable and the
/// value and containing each of `reasons`; corrected to the built-in profile, the instance
/// carries on. Returns the message.
fn refused(reference: u32, value: &str, reasons: &[&str]) -> String {
    let log = MessageLog::default();
    let fmu = with_profile(&log, reference, value);
    let start = Instant::now();
    assert_eq!(exit_initialisation(&fmu), ERROR, "{value}");
    assert!(start.elapsed() < Duration::from_secs(1), "{value}: refused after {:?}", start.elapsed());
    let (status, message) = log.last().unwrap();
    assert_eq!(status, ERROR);
    let prefix = format!("fmi2ExitInitializationMode: {} = \"{value}\"", variable_name(reference));
    assert!(message.starts_with(&prefix), "{message}");
    for reason in reasons {
        assert!(message.contains(reason), "{reason:?} not in {message}");
    }
    let builtin = if reference == vr::WHEEL_PROFILE { "MBench_S1002" } else { "MBench_UIC60" };
    assert_eq!(fmu.set_string(&[reference], &[builtin]), OK);
    assert_eq!(exit_initialisation(&fmu), OK, "{value}: the instance carries on");
    message
}

/// The built-in S1002 file with one more point line `extra` before its first point; the line
/// number of the extra point.
fn wheel_with_point(extra: &str) -> (String, usize) {
    let begin = WHEEL_FILE.find("point.begin").unwrap();
    let line_start = begin + WHEEL_FILE[begin..].find('\n').unwrap() + 1;
    let line = WHEEL_FILE[..line_start].lines().count() + 1;
    (format!("{}{extra}\n{}", &WHEEL_FILE[..line_start], &WHEEL_FILE[line_start..]), line)
}

fn write(directory: &Path, name: &str, content: impl AsRef<[u8]>) -> String {
    let path = directory.join(name);
    std::fs::write(&path, content).unwrap();
    path.to_str().unwrap().to_owned()
}

#[test]
fn a_far_off_point_a_wrong_unit_or_a_spike_is_refused_with_its_line_at_once() {
    // The review's defect 1: one point at y = −1e9 mm (a mistyped exponent) aborted the host
    // (an allocation of 320 GB); 1e18 mm or ±1e300 gave fmi2Fatal; 0.1–1 km took seconds.
    let directory = scratch("far");
    // The file's first point lies at y = 69.6 mm (−69.6 mm once `mirror.y = 1` mirrors it); a
    // point before it at y ≫ 69.6 mm keeps the order, so only its distance is wrong (the others
    // are refused for their distance before the order is checked).
    for far in ["-1e9 0", "-1e15 0", "-1e18 0", "-1e300 0", "-1e5 0", "-1000000 5"] {
        let (text, line) = wheel_with_point(far);
        let path = write(&directory, "far.prw", text);
        refused(vr::WHEEL_PROFILE, &path, &[&format!("line {line}: the point (y, z)"), "more than 1 m"]);
    }
    // A spike of 1 km in z, the mm read as m (defect 4: a 130 m wide wheel gave plausible
    // forces; with both files so, 81 s and a solved height of −3.78 m).
    let (spike, line) = wheel_with_point("-70 1000000");
    let path = write(&directory, "spike.prw", spike);
    refused(vr::WHEEL_PROFILE, &path, &[&format!("line {line}:"), "more than 1 m"]);
    let metres = WHEEL_FILE.replace("units.len.f    = +1.000000000000000e+03", "units.len.f    = 1");
    assert_ne!(metres, WHEEL_FILE);
    let path = write(&directory, "metres.prw", metres);
    refused(vr::WHEEL_PROFILE, &path, &["more than 1 m", "units.len.f = 1 file units per metre"]);
    // Read in micrometres: 0.13 mm wide, refused by its width.
    let micrometres = WHEEL_FILE.replace("units.len.f    = +1.000000000000000e+03", "units.len.f    = 1e6");
    let path = write(&directory, "micrometres.prw", micrometres);
    refused(vr::WHEEL_PROFILE, &path, &["the wheel profile is 0.129613 mm wide"]);
    // A spike inside the 1 m bound: 300 mm tall.
    let (tall, _) = wheel_with_point("75 300");
    let path = write(&directory, "tall.prw", tall);
    refused(vr::WHEEL_PROFILE, &path, &["the wheel profile is 3", "mm tall"]);
    std::fs::remove_dir_all(&directory).unwrap();
}

#[cfg(unix)]
#[test]
fn only_regular_files_of_bounded_size_are_read() {
    // Defect 3: /dev/zero behind a .prw name read until memory ran out, a FIFO never returned,
    // a link to /dev/stdin read the master's stdin.
    let directory = scratch("kinds");
    let link = |target: &str, name: &str| {
        let path = directory.join(name);
        std::os::unix::fs::symlink(target, &path).unwrap();
        path.to_str().unwrap().to_owned()
    };
    for (target, name) in [("/dev/zero", "zero.prw"), ("/dev/urandom", "random.prr")] {
        let path = link(target, name);
        let reference = if name.ends_with(".prw") { vr::WHEEL_PROFILE } else { vr::RAIL_PROFILE };
        refused(reference, &path, &["the file cannot be read", "not a regular file"]);
    }
    // The test's stdin is a terminal, a pipe, /dev/null or closed (then the link leads nowhere):
    // refused, and not read, in every case.
    refused(vr::WHEEL_PROFILE, &link("/dev/stdin", "stdin.prw"), &["the file cannot be read"]);
    let fifo = directory.join("fifo.prw");
    let fifo_name = CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(fifo_name.as_ptr(), 0o600) }, 0);
    refused(vr::WHEEL_PROFILE, fifo.to_str().unwrap(), &["not a regular file"]);
    let folder = directory.join("folder.prw");
    std::fs::create_dir(&folder).unwrap();
    refused(vr::WHEEL_PROFILE, folder.to_str().unwrap(), &["not a regular file"]);
    // 17 MiB (sparse: nothing written), past the 16 MiB a profile file may have.
    let huge = directory.join("huge.prw");
    std::fs::File::create(&huge).unwrap().set_len(17 << 20).unwrap();
    refused(vr::WHEEL_PROFILE, huge.to_str().unwrap(), &["it has 17825792 bytes; this file may have at most 16777216"]);
    std::fs::remove_dir_all(&directory).unwrap();
}

#[test]
fn a_wheel_file_is_not_taken_for_a_rail() {
    // Defect 4: a SIMPACK wheel file (`type = 1`) given as rail_profile was accepted.
    let directory = scratch("kind");
    let path = write(&directory, "wheel_as_rail.prr", WHEEL_FILE);
    let type_line = WHEEL_FILE.lines().position(|l| l.trim_start().starts_with("type")).unwrap() + 1;
    refused(
        vr::RAIL_PROFILE,
        &path,
        &[&format!("line {type_line}: the header's `type = 1` says a wheel profile, not a rail profile")],
    );
    // By its extension: a rail's name given as the wheel.
    let path = write(&directory, "rail.ban", RAIL_BAN);
    refused(vr::WHEEL_PROFILE, &path, &["the extension names a rail profile; wheel_profile needs a wheel profile"]);
    std::fs::remove_dir_all(&directory).unwrap();
}

/// The wheel's outputs after one step at the default inputs with these profiles.
fn wheel_outputs(wheel: &str, rail: &str) -> Vec<f64> {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("outputs", &log);
    assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
    assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE, vr::RAIL_PROFILE], &[wheel, rail]), OK);
    fmu.initialise(0.0);
    assert_eq!(fmu.do_step(0.0, 1e-3), OK, "{:?}", log.last());
    fmu.get_real(&[vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z, vr::PATCH1_RAIL_LATERAL_POSITION])
}

#[test]
fn bytes_that_are_not_utf8_in_a_file_are_read_around() {
    // Defect 5: MiniProf writes Windows-1252 (`Chars=Win`): `Line=Köln` as one byte 0xF6, or a
    // Latin-1 comment in a SIMPACK file, was "stream did not contain valid UTF-8".
    let directory = scratch("encoding");
    let mut rail = b"Line=K\xf6ln\r\n".to_vec();
    rail.extend_from_slice(RAIL_BAN);
    let rail = write(&directory, "koeln.ban", rail);
    let mut wheel = b"! Gemessen in K\xf6ln, Stra\xdfe 3\n".to_vec();
    wheel.extend_from_slice(WHEEL_FILE.as_bytes());
    let wheel = write(&directory, "koeln.prw", wheel);
    let plain_rail = write(&directory, "plain.ban", RAIL_BAN);
    let reference = wheel_outputs("MBench_S1002", &plain_rail);
    assert_eq!(wheel_outputs(&wheel, &plain_rail), reference, "the same points as the built-in wheel");
    assert_eq!(wheel_outputs(&wheel, &rail), reference, "the same points as the rail without its Latin-1 line");
    std::fs::remove_dir_all(&directory).unwrap();
}

#[test]
fn a_file_name_that_is_not_utf8_is_refused_not_mangled() {
    // Defect 13: fmi2SetString converted lossily, so fmi2GetString returned other bytes.
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("latin-1", &log);
    let latin = CString::new(b"/tmp/rail_\xe9.ban".to_vec()).unwrap();
    // SAFETY: a live instance; a NUL-terminated string that outlives the call.
    let status = unsafe { fmi2SetString(fmu.c, &vr::RAIL_PROFILE, 1, &latin.as_ptr()) };
    assert_eq!(status, ERROR);
    let (_, message) = log.last().unwrap();
    assert!(
        message.starts_with("fmi2SetString: a value is not UTF-8 (byte 10 of 15, near \"/tmp/rail_\\xe9.ban\")"),
        "{message}"
    );
    // SAFETY: a live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
    }
    assert_eq!(fmu.get_string(&[vr::RAIL_PROFILE]), ["MBench_UIC60"], "nothing was set");
}

#[test]
fn a_path_of_megabytes_is_not_echoed_whole() {
    // Defect 9: a 50 MiB path was echoed whole into a 52 MB log message.
    let long = format!("{}.prw", "x".repeat(50 << 20));
    let log = MessageLog::default();
    let fmu = with_profile(&log, vr::WHEEL_PROFILE, &long);
    assert_eq!(exit_initialisation(&fmu), ERROR);
    let (_, message) = log.last().unwrap();
    assert!(message.len() < 1000, "{} bytes", message.len());
    assert!(message.contains("… (52428804 bytes)") && message.contains("a path is at most 4096 bytes"), "{message}");
    // A path of 4096 bytes is a path (here one that names no file); 4097 is not.
    for (length, reason) in [(4096, "the file cannot be read"), (4097, "a path is at most 4096 bytes")] {
        let path = format!("/{}.prw", "x".repeat(length - 5));
        assert_eq!(path.len(), length);
        let log = MessageLog::default();
        let fmu = with_profile(&log, vr::WHEEL_PROFILE, &path);
        assert_eq!(exit_initialisation(&fmu), ERROR);
        let (_, message) = log.last().unwrap();
        assert!(message.contains(reason), "{length}: {message}");
    }
}

#[test]
fn geometry_errors_name_the_profiles() {
    // Defect 9: "the rail profile does not reach 0.014 m below its top on its inner side" and
    // the contact search's errors named neither the variable nor the file.
    let directory = scratch("geometry");
    // A rail head 20 mm wide and 5 mm tall: no gauge face 14 mm below its top.
    let flat = "ColumnDef=X,Y\n-10 5\n-8 1\n-4 0.1\n0 0\n4 0.1\n8 1\n10 5\n";
    let rail = write(&directory, "flat.ban", flat);
    let log = MessageLog::default();
    let fmu = with_profile(&log, vr::RAIL_PROFILE, &rail);
    assert_eq!(exit_initialisation(&fmu), ERROR);
    let (_, message) = log.last().unwrap();
    assert!(message.starts_with("fmi2ExitInitializationMode: the rail profile does not reach 0.014 m below its top"));
    assert!(message.ends_with(&format!("(wheel_profile = \"MBench_S1002\", rail_profile = \"{rail}\")")), "{message}");
    // The wheelset half a metre aside: the profiles do not overlap (at a step).
    let log = MessageLog::default();
    let fmu = with_profile(&log, vr::RAIL_PROFILE, "MBench_UIC60");
    assert_eq!(exit_initialisation(&fmu), OK);
    assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[0.5]), OK);
    assert_eq!(fmu.do_step(0.0, 1e-3), ERROR);
    let (_, message) = log.last().unwrap();
    assert!(message.contains("do not overlap laterally at wheelset_lateral_displacement = 0.5 m"), "{message}");
    assert!(message.ends_with("(wheel_profile = \"MBench_S1002\", rail_profile = \"MBench_UIC60\")"), "{message}");
    std::fs::remove_dir_all(&directory).unwrap();
}

#[test]
fn a_state_saved_with_other_profile_content_is_refused() {
    // Defect 12: change the file on disk, restore a saved state: it went on silently with the
    // new profile.
    let directory = scratch("state");
    let wheel = write(&directory, "wheel.prw", WHEEL_FILE);
    let inputs = [vr::WHEELSET_LATERAL_DISPLACEMENT];
    let run = |log: &MessageLog| {
        let fmu = Fmu::instantiate_logged("state", log);
        assert_eq!(fmu.set_integer(&[vr::CONTACT_GEOMETRY], &[ContactGeometry::Profiles as i32]), OK);
        assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE], &[&wheel]), OK);
        assert_eq!(fmu.set_real(&inputs, &[2e-3]), OK);
        fmu.initialise(0.0);
        fmu
    };
    let log = MessageLog::default();
    let saving = run(&log);
    assert_eq!(saving.do_step(0.0, 1e-3), OK);
    let state = saving.get_state();
    let bytes = saving.serialize(state);
    let saved_outputs = saving.get_real(&[vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y]);
    // The wheel profile worn by 0.2 mm on its tread: another content, another contact.
    let worn = WHEEL_FILE.replace("shift.z        = +0.000000000000000e+00", "shift.z        = +2.000000000000000e-01");
    assert_ne!(worn, WHEEL_FILE);
    std::fs::write(directory.join("wheel.prw"), &worn).unwrap();
    // Restored into the same instance, whose wheel was built from the saved content: it goes on
    // as the saved run did.
    assert_eq!(saving.set_state(state), OK);
    assert_eq!(saving.do_step(1e-3, 1e-3), OK);
    assert_eq!(saving.get_real(&[vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y]), saved_outputs);
    saving.free_state(state);
    // Restored into a new instance (another process's, as after fmi2DeSerializeFMUstate), which
    // reads the files as they are now: refused, naming the file, and again until the master acts.
    let log = MessageLog::default();
    let restoring = run(&log);
    assert_eq!(restoring.do_step(0.0, 1e-3), OK, "the new instance reads the worn wheel");
    let restored = restoring.deserialize(&bytes).unwrap();
    assert_eq!(restoring.set_state(restored), OK);
    for _ in 0..2 {
        assert_eq!(restoring.do_step(1e-3, 1e-3), ERROR);
        let (_, message) = log.last().unwrap();
        assert!(
            message.starts_with(
                "fmi2DoStep: the restored FMU state was computed with other profiles: the content of \
                 wheel_profile (CRC-32"
            ),
            "{message}"
        );
    }
    // The file put back: the state goes on as saved.
    std::fs::write(directory.join("wheel.prw"), WHEEL_FILE).unwrap();
    assert_eq!(restoring.set_state(restored), OK);
    assert_eq!(restoring.do_step(1e-3, 1e-3), OK, "{:?}", log.last());
    restoring.free_state(restored);
    std::fs::remove_dir_all(&directory).unwrap();
}

/// One mutation of a profile file's lines: a number replaced by an extreme or a non-number, a
/// line deleted, repeated or swapped with the next, bytes flipped, a header line inserted.
fn mutate(rng: &mut StdRng, text: &[u8]) -> Vec<u8> {
    const VALUES: [&str; 14] =
        ["1e300", "-1e9", "1e18", "0", "-0", "NaN", "inf", "x", "1e-300", "999", "-70", "", "1,5", "\u{00e9}"];
    let mut lines: Vec<Vec<u8>> = text.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    for _ in 0..rng.random_range(1..4) {
        let at = rng.random_range(0..lines.len());
        match rng.random_range(0..7) {
            0 => {
                let line = String::from_utf8_lossy(&lines[at]).into_owned();
                let mut fields: Vec<&str> = line.split_whitespace().collect();
                if !fields.is_empty() {
                    let field = rng.random_range(0..fields.len());
                    fields[field] = VALUES[rng.random_range(0..VALUES.len())];
                }
                lines[at] = fields.join(" ").into_bytes();
            }
            1 => {
                lines.remove(at);
            }
            2 => {
                let copy = lines[at].clone();
                lines.insert(at, copy);
            }
            3 if at + 1 < lines.len() => lines.swap(at, at + 1),
            4 => {
                if let Some(byte) = lines[at].first_mut() {
                    *byte ^= 1 << rng.random_range(0..8);
                }
            }
            5 => lines.insert(at, b"MINIPROF 101 148 1994 3 24 \xf6".to_vec()),
            _ => lines.truncate(at.max(1)),
        }
        if lines.is_empty() {
            break;
        }
    }
    lines.join(&b'\n')
}

/// The process's peak resident memory \[kB\] (Linux `VmHWM`), if the platform tells.
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status.lines().find_map(|l| l.strip_prefix("VmHWM:")).and_then(|v| v.trim().trim_end_matches(" kB").parse().ok())
}

#[test]
fn mutated_real_profile_files_never_crash_hang_or_grow_the_host() {
    // The class of defects 1 to 5: 400 seeded mutations of the shipped wheel and rail files
    // (SIMPACK and MiniProf), each given to a fresh instance and, where accepted, stepped at
    // three poses. Every call returns within seconds, never fmi2Fatal (no panic crosses the
    // boundary; an abort would end the test process), every refusal is fmi2Error naming the
    // variable and the file, and the peak memory grows by less than 200 MB over the run.
    let directory = scratch("fuzz");
    let mut rng = StdRng::seed_from_u64(0x05ee_d0ff_11e5);
    let sources: [(&[u8], &str, u32); 3] = [
        (WHEEL_FILE.as_bytes(), "wheel.prw", vr::WHEEL_PROFILE),
        (include_bytes!("../../../data/profiles/MBench_UIC60_v3.prr"), "rail.prr", vr::RAIL_PROFILE),
        (RAIL_BAN, "rail.ban", vr::RAIL_PROFILE),
    ];
    let before = peak_memory();
    let (mut accepted, mut refused) = (0, 0);
    for case in 0..400 {
        let (text, name, reference) = sources[case % sources.len()];
        let path = write(&directory, &format!("{case}-{name}"), mutate(&mut rng, text));
        let log = MessageLog::default();
        let fmu = with_profile(&log, reference, &path);
        let start = Instant::now();
        let status = exit_initialisation(&fmu);
        assert!(start.elapsed() < Duration::from_secs(5), "case {case}: {:?}", start.elapsed());
        if status == ERROR {
            refused += 1;
            let (_, message) = log.last().unwrap();
            let named = message
                .starts_with(&format!("fmi2ExitInitializationMode: {} = \"{path}\"", variable_name(reference)))
                || message.contains(&format!("{} = \"{path}\")", variable_name(reference)));
            assert!(named, "case {case}: {message}");
            continue;
        }
        assert_eq!(status, OK, "case {case}: {:?}", log.last());
        accepted += 1;
        let mut time = 0.0;
        for lateral in [-4e-3, 0.0, 6e-3] {
            assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[lateral]), OK);
            let status = fmu.do_step(time, 1e-3);
            assert!(status == OK || status == ERROR, "case {case}, y_ws {lateral}: {status} {:?}", log.last());
            if status == OK {
                time += 1e-3;
            }
        }
    }
    eprintln!("{accepted} accepted, {refused} refused");
    assert!(accepted > 40 && refused > 40, "{accepted} accepted, {refused} refused: the mutations test little");
    if let (Some(before), Some(after)) = (before, peak_memory()) {
        assert!(after - before < 200_000, "peak memory grew by {} kB", after - before);
    }
    std::fs::remove_dir_all(&directory).unwrap();
}
