//! Direct feedthrough through the C ABI (FMI 2.0, §4.2.1): in step mode an output read after an
//! input it depends on (`<ModelStructure>`) was written is the output at the new input, while the
//! time, the relaxed forces and the exact theory's warm start stay as the last step left them. A
//! master solving the algebraic loop between a wheelset and its contacts relies on this; without
//! it every master applies the contact forces one step late.

use fmu_test_master::{Fmu, OK};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, ContactGeometry, Model, Switch};

const STEP: f64 = 1e-3;
const OUTPUTS: [u32; 3] = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::EFFECTIVE_CREEPAGE_LONGITUDINAL];

fn instance(name: &str, integers: &[(u32, i32)]) -> Fmu {
    let fmu = Fmu::instantiate(name, None);
    for &(reference, value) in integers {
        assert_eq!(fmu.set_integer(&[reference], &[value]), OK);
    }
    fmu.initialise(0.0);
    assert_eq!(fmu.do_step(0.0, STEP), OK);
    fmu
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// One patch, each rung that keeps no state: the forces read after ξ is written are, bit for
/// bit, those a step at that ξ computes (the patch is algebraic in its inputs).
#[test]
fn the_forces_read_after_a_creepage_is_written_are_the_forces_at_that_creepage() {
    for model in [Model::Polach, Model::KalkerLinear, Model::Fastsim, Model::ExactTable] {
        let setting = [(vr::CREEP_FORCE_MODEL, model as i32)];
        let (read, stepped) = (instance("read", &setting), instance("stepped", &setting));
        let before = read.get_real(&OUTPUTS);
        for fmu in [&read, &stepped] {
            assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL, vr::CREEPAGE_LATERAL], &[2e-3, -1e-3]), OK);
        }
        let after = read.get_real(&OUTPUTS);
        assert_eq!(after[2], 2e-3, "{model:?}");
        assert!(after[0] < before[0] && after[1] > 0.0, "{model:?}: {before:?} → {after:?}");
        assert_eq!(stepped.do_step(STEP, STEP), OK);
        assert_eq!(stepped.get_real(&OUTPUTS), after, "{model:?}");
    }
}

/// With creep relaxation the force is a state: read at a new creepage it is the last step's
/// (over no distance it relaxes by nothing) while the creepage it relaxes towards is the new one;
/// and the read changes nothing of what follows: the next step's outputs are bit for bit those
/// of an instance that was not read.
#[test]
fn a_relaxed_force_read_within_the_step_is_the_last_steps_and_the_next_step_is_unchanged() {
    let setting = [(vr::CREEP_RELAXATION, Switch::On as i32)];
    let (read, unread) = (instance("read", &setting), instance("unread", &setting));
    for fmu in [&read, &unread] {
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[5e-3]), OK);
        assert_eq!(fmu.do_step(STEP, STEP), OK);
    }
    let before = read.get_real(&OUTPUTS);
    for fmu in [&read, &unread] {
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[8e-3]), OK);
    }
    let within = read.get_real(&OUTPUTS);
    assert!(close(within[0], before[0]), "{before:?} → {within:?}");
    assert_eq!(within[2], 8e-3);
    for fmu in [&read, &unread] {
        assert_eq!(fmu.do_step(2.0 * STEP, STEP), OK);
    }
    let next = read.get_real(&OUTPUTS);
    assert_eq!(next, unread.get_real(&OUTPUTS));
    assert!(next[0] < within[0], "the force builds up towards ξ = 0.8 %: {within:?} → {next:?}");
}

/// The exact theory's warm start is state too: a read within the step leaves the next step's
/// solve starting where the last one ended, bit for bit.
#[test]
fn the_exact_theorys_warm_start_is_kept_through_a_read() {
    let setting = [
        (vr::CREEP_FORCE_MODEL, Model::Exact as i32),
        (vr::EXACT_ELEMENTS_LONGITUDINAL, 24),
        (vr::EXACT_ELEMENTS_LATERAL, 24),
    ];
    let (read, unread) = (instance("read", &setting), instance("unread", &setting));
    for fmu in [&read, &unread] {
        assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[3e-3]), OK);
    }
    let within = read.get_real(&OUTPUTS);
    assert_eq!(within[2], 3e-3);
    for fmu in [&read, &unread] {
        assert_eq!(fmu.do_step(STEP, STEP), OK);
    }
    let next = read.get_real(&OUTPUTS);
    assert_eq!(next, unread.get_real(&OUTPUTS));
    // Both solve the same contact: the same forces within the solver's tolerance (1e-9 μQ).
    assert!((next[0] - within[0]).abs() < 1e-8 * 0.3 * 100e3, "{within:?} against {next:?}");
}

/// A wheel on its profiles: the track forces read after the wheelset moves are those at the new
/// position (within the vertical balance's tolerance of a step there).
#[test]
fn the_track_forces_read_after_the_wheelset_moves_are_those_at_the_new_position() {
    let setting = [(vr::CONTACT_GEOMETRY, ContactGeometry::Profiles as i32)];
    let (read, stepped) = (instance("read", &setting), instance("stepped", &setting));
    let forces = [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::TRACK_FORCE_Z, vr::PATCH1_CONTACT_ANGLE];
    let before = read.get_real(&forces);
    for fmu in [&read, &stepped] {
        assert_eq!(fmu.set_real(&[vr::WHEELSET_LATERAL_DISPLACEMENT], &[4e-3]), OK);
    }
    let after = read.get_real(&forces);
    assert!((after[3] - before[3]).abs() > 1e-3, "the patch moved: {before:?} → {after:?}");
    assert_eq!(stepped.do_step(STEP, STEP), OK);
    let stepped = stepped.get_real(&forces);
    for (a, b) in after.iter().zip(&stepped) {
        assert!((a - b).abs() <= 1e-9 * 10e3, "{after:?} against a step there {stepped:?}");
    }
}
