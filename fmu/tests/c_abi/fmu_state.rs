//! FMU state through the C ABI: rolled-back runs repeat bit for bit, serialised states continue
//! bit for bit in a fresh instance, and damaged byte strings are rejected without effect.

use fmu_test_master::{bits, run_scene, Fmu, MessageLog, ERROR, OK, OUTPUTS};
use wheel_rail_contact::wheel::BalanceStart;
use wheel_rail_contact::ModelMemory;
use wheel_rail_contact_fmu::ffi::{
    fmi2EnterInitializationMode, fmi2ExitInitializationMode, fmi2GetFMUstate, fmi2SetupExperiment, fmi2Terminate,
};
use wheel_rail_contact_fmu::fmi2::fmi2FMUstate;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, ContactMethod, Model, Switch};
use wheel_rail_contact_fmu::snapshot::{decode, encode, Snapshot};

const STEP: f64 = 1e-3;

/// A run 250 steps in, where the creepage ramp is well into partial slip.
fn mid_run() -> Fmu {
    let fmu = Fmu::stepping("rolled back", 0.0);
    run_scene(&fmu, 0, 250, 0.0, STEP);
    fmu
}

#[test]
fn get_state_run_100_steps_set_state_run_again_is_bit_identical() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let time = 250.0 * STEP;
    let first = run_scene(&fmu, 250, 100, time, STEP);
    assert_eq!(fmu.set_state(state), OK);
    let second = run_scene(&fmu, 250, 100, time, STEP);
    assert_eq!(bits(&first), bits(&second));
    // The run really moved: the outputs vary along it.
    assert!(first.iter().any(|row| row[0] != first[0][0]));
    fmu.free_state(state);
}

#[test]
fn a_serialised_state_continues_bit_identically_in_a_fresh_instance() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    fmu.free_state(state);
    let expected = run_scene(&fmu, 250, 100, 250.0 * STEP, STEP);

    // A fresh instance that has never stepped, still in `instantiated`.
    let fresh = Fmu::instantiate("fresh", None);
    let restored = fresh.deserialize(&bytes).unwrap();
    assert_eq!(fresh.set_state(restored), OK);
    assert_eq!(fresh.get_real(&OUTPUTS), fmu_outputs_at_250());
    let continued = run_scene(&fresh, 250, 100, 250.0 * STEP, STEP);
    assert_eq!(bits(&expected), bits(&continued));
    // Serialising the restored state again gives the same bytes.
    assert_eq!(fresh.serialize(restored), bytes);
    fresh.free_state(restored);
}

fn fmu_outputs_at_250() -> Vec<f64> {
    mid_run().get_real(&OUTPUTS)
}

#[test]
fn corrupted_truncated_and_foreign_byte_strings_are_fmi2_error_and_change_nothing() {
    let fmu = mid_run();
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    let outputs = fmu.get_real(&OUTPUTS);
    let mut rejected =
        vec![Vec::new(), bytes[..bytes.len() - 1].to_vec(), bytes[..20].to_vec(), b"{\"state\": 1}".to_vec()];
    for position in [0, 9, 12, bytes.len() / 2, bytes.len() - 1] {
        let mut corrupted = bytes.clone();
        corrupted[position] ^= 0x20;
        rejected.push(corrupted);
    }
    let mut longer = bytes.clone();
    longer.extend_from_slice(&[0; 8]);
    rejected.push(longer);
    for blob in &rejected {
        assert_eq!(fmu.deserialize(blob), Err(ERROR), "{blob:?}");
    }
    // Nothing changed: same outputs, and the run continues as the original would.
    assert_eq!(fmu.get_real(&OUTPUTS), outputs);
    let after_rejections = run_scene(&fmu, 250, 20, 250.0 * STEP, STEP);
    assert_eq!(fmu.set_state(state), OK);
    assert_eq!(bits(&after_rejections), bits(&run_scene(&fmu, 250, 20, 250.0 * STEP, STEP)));
    fmu.free_state(state);
}

#[test]
fn a_state_is_reused_when_passed_back_and_restores_the_mode() {
    let fmu = mid_run();
    let mut state: fmi2FMUstate = fmu.get_state();
    let first = state;
    run_scene(&fmu, 250, 10, 250.0 * STEP, STEP);
    // SAFETY: live instance; `state` is this FMU's and is overwritten in place.
    assert_eq!(unsafe { fmi2GetFMUstate(fmu.c, &mut state) }, OK);
    assert_eq!(state, first, "the same allocation, updated");
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2Terminate(fmu.c) }, OK);
    assert_eq!(fmu.do_step(260.0 * STEP, STEP), ERROR, "terminated");
    assert_eq!(fmu.set_state(state), OK);
    assert_eq!(run_scene(&fmu, 260, 5, 260.0 * STEP, STEP).len(), 5, "stepping again from t = 0.26");
    fmu.free_state(state);
}

/// Relaxation on (L = 0.02 m, V = 5 m/s: τ = 4 ms), initialised at the steady state of ξ = 1e-3,
/// then a creepage step to ξ = 4e-3 and one step of 1 ms: the relaxed force, the FMU's only
/// internal state, is a quarter-τ into its transient (e^{−1/4} of the gap left), not at either
/// steady state. Returns the instance and the time reached.
fn relaxing_mid_transient(name: &str) -> (Fmu, f64) {
    let fmu = Fmu::instantiate(name, None);
    assert_eq!(fmu.set_integer(&[vr::CREEP_RELAXATION], &[Switch::On as i32]), OK);
    assert_eq!(fmu.set_real(&[vr::RELAXATION_LENGTH, vr::ROLLING_SPEED], &[0.02, 5.0]), OK);
    initialise(&fmu);
    assert_eq!(fmu.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[4e-3]), OK);
    assert_eq!(fmu.do_step(0.0, STEP), OK);
    (fmu, STEP)
}

fn initialise(fmu: &Fmu) {
    // SAFETY: live instance.
    unsafe {
        assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
        assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
    }
}

/// `count` steps of 1 ms from `time` with the inputs left as they are; the outputs after each.
fn hold_inputs(fmu: &Fmu, time: f64, count: usize) -> Vec<[f64; 3]> {
    (0..count)
        .map(|k| {
            assert_eq!(fmu.do_step(time + k as f64 * STEP, STEP), OK);
            let outputs = fmu.get_real(&OUTPUTS);
            [outputs[0], outputs[1], outputs[2]]
        })
        .collect()
}

/// Issue 16: the FMU-state tests above run with relaxation off, where the outputs depend on the
/// inputs alone, so a state without its relaxed force passed them. Here the state is taken
/// mid-transient; rolling back to it repeats the run bit for bit, and that run differs from
/// one that starts at the steady state, so a state that lost (or a set-state that ignored)
/// the relaxed force fails.
#[test]
fn a_state_taken_mid_transient_restores_the_relaxed_force() {
    let (fmu, time) = relaxing_mid_transient("relaxing");
    let state = fmu.get_state();
    let first = hold_inputs(&fmu, time, 10);
    // The transient is under way: F_x still moves by more than 1 % of its value per step.
    assert!((first[1][0] - first[0][0]).abs() > 1e-2 * first[0][0].abs(), "{first:?}");
    assert_eq!(fmu.set_state(state), OK);
    let second = hold_inputs(&fmu, time, 10);
    assert_eq!(bits(&first), bits(&second));

    // The same inputs from the steady state of ξ = 4e-3 (what a lost relaxed force would give
    // after initialisation) stay at that steady state: a different run.
    let (steady, _) = relaxing_mid_transient("steady");
    assert_eq!(steady.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[4e-3]), OK);
    let settled = hold_inputs(&steady, time, 2000);
    assert_ne!(bits(&settled[1990..]), bits(&first));
    assert!((settled[1999][0] - first[0][0]).abs() > 0.05 * settled[1999][0].abs(), "{:?} vs {first:?}", settled[1999]);
    fmu.free_state(state);
}

/// The mid-transient state serialised, deserialised into a fresh instance that has never
/// stepped (its relaxed force at the default) and set there: the run continues bit for bit.
#[test]
fn a_serialised_mid_transient_state_continues_bit_identically_in_a_fresh_instance() {
    let (fmu, time) = relaxing_mid_transient("relaxing");
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    fmu.free_state(state);
    let expected = hold_inputs(&fmu, time, 10);

    let fresh = Fmu::instantiate("fresh", None);
    let restored = fresh.deserialize(&bytes).unwrap();
    assert_eq!(fresh.set_state(restored), OK);
    let continued = hold_inputs(&fresh, time, 10);
    assert_eq!(bits(&expected), bits(&continued));
    fresh.free_state(restored);

    // A fresh instance stepped into its own, different transient first (ξ = 1e-3 held, so its
    // relaxed force sits at the other steady state): setting the state must replace it.
    let (other, _) = relaxing_mid_transient("other");
    assert_eq!(other.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[1e-3]), OK);
    hold_inputs(&other, time, 50);
    let restored = other.deserialize(&bytes).unwrap();
    assert_eq!(other.set_state(restored), OK);
    assert_eq!(bits(&expected), bits(&hold_inputs(&other, time, 10)));
    other.free_state(restored);
}

/// The exact theory on 40 × 24 elements (small, so the test is quick; every grid warm-starts
/// alike), stepped 20 times through the sweeping scene: its warm start (the last tractions) is
/// now part of the instance's state.
fn exact_mid_run(name: &str) -> Fmu {
    let fmu = Fmu::instantiate(name, None);
    assert_eq!(
        fmu.set_integer(
            &[vr::CREEP_FORCE_MODEL, vr::EXACT_ELEMENTS_LONGITUDINAL, vr::EXACT_ELEMENTS_LATERAL],
            &[Model::Exact as i32, 40, 24]
        ),
        OK
    );
    initialise(&fmu);
    run_scene(&fmu, 0, 20, 0.0, STEP);
    fmu
}

/// Issue 27.4: with the exact theory a step starts from the previous step's tractions, which
/// changes its result within the solver's tolerance (≈ 1e-11 relative): a state without the
/// warm start repeated the steps only to that tolerance (F_x …4.88510734648 vs …647), and a
/// state deserialised into a fresh instance never continued bit for bit. Both do now.
#[test]
fn an_exact_theory_state_restores_its_warm_start_bit_for_bit() {
    let fmu = exact_mid_run("exact");
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    let first = run_scene(&fmu, 20, 5, 20.0 * STEP, STEP);
    assert_eq!(fmu.set_state(state), OK);
    assert_eq!(bits(&first), bits(&run_scene(&fmu, 20, 5, 20.0 * STEP, STEP)), "rolled back in place");
    fmu.free_state(state);

    // A fresh instance, and one that has stepped elsewhere (its own warm start replaced).
    let fresh = Fmu::instantiate("fresh", None);
    let other = exact_mid_run("other");
    run_scene(&other, 300, 7, 20.0 * STEP, STEP);
    for instance in [&fresh, &other] {
        let restored = instance.deserialize(&bytes).unwrap();
        assert_eq!(instance.set_state(restored), OK);
        assert_eq!(bits(&first), bits(&run_scene(instance, 20, 5, 20.0 * STEP, STEP)), "deserialised");
        instance.free_state(restored);
    }
    // The saved tractions are 2 × 40 × 24 values of 8 bytes beyond a state without them.
    assert!(bytes.len() > 2 * 40 * 24 * 8, "{} bytes", bytes.len());
}

/// A state whose bytes are intact (valid checksum) but whose content this FMU can never be in.
fn forged(bytes: &[u8], forge: impl FnOnce(&mut Snapshot)) -> Vec<u8> {
    let mut snapshot = decode(bytes).unwrap();
    forge(&mut snapshot);
    encode(&snapshot)
}

/// Issue 27.7: deserialisation applies the checks of the setters and of the state machine. A
/// forged state with a NaN output was returned by fmi2GetReal with fmi2OK; a NaN time left the
/// instance stuck; a NaN stop time, or one the time has passed, was accepted although
/// fmi2SetupExperiment refuses both. Each is fmi2Error naming the value, and nothing changes.
/// A change made to a saved state.
type Forgery = Box<dyn Fn(&mut Snapshot)>;

#[test]
fn a_forged_state_with_a_valid_checksum_is_refused_with_its_reason() {
    let log = MessageLog::default();
    let fmu = Fmu::instantiate_logged("forged", &log);
    initialise(&fmu);
    run_scene(&fmu, 0, 10, 0.0, STEP);
    let state = fmu.get_state();
    let bytes = fmu.serialize(state);
    fmu.free_state(state);
    let outputs = fmu.get_real(&OUTPUTS);
    let cases: [(Forgery, &str); 7] = [
        (Box::new(|s| s.model.values.outputs.force_longitudinal = f64::NAN), "force_longitudinal = NaN is invalid"),
        (Box::new(|s| s.model.values.outputs.max_pressure = f64::INFINITY), "max_pressure = inf is invalid"),
        (Box::new(|s| s.time = f64::NAN), "time = NaN is invalid: must be finite"),
        (Box::new(|s| s.time = f64::NEG_INFINITY), "time = -inf is invalid: must be finite"),
        (Box::new(|s| s.stop_time = Some(f64::NAN)), "stopTime = NaN is invalid: must be >= time = 0.01"),
        (Box::new(|s| s.stop_time = Some(0.005)), "stopTime = 0.005 is invalid: must be >= time = 0.01"),
        (
            Box::new(|s| s.model.scene.relaxed_forces[1] = f64::NAN),
            "relaxed_force_lateral = NaN is invalid: must be finite",
        ),
    ];
    for (forge, reason) in cases {
        let blob = forged(&bytes, forge);
        assert_eq!(fmu.deserialize(&blob), Err(ERROR), "{reason}");
        let message = log.texts().pop().unwrap();
        assert!(
            message.starts_with("fmi2DeSerializeFMUstate: serializedState rejected: not a state this FMU can be in: ")
                && message.contains(reason),
            "{message}"
        );
    }
    // An exact theory's warm start with a NaN traction, and one with too few values for its grid.
    let exact = exact_mid_run("exact");
    let state = exact.get_state();
    let exact_bytes = exact.serialize(state);
    exact.free_state(state);
    let memory = decode(&exact_bytes).unwrap().model.scene.model;
    let mut encoded = postcard::to_stdvec(&memory).unwrap();
    let last = encoded.len() - 8;
    encoded[last..].copy_from_slice(&f64::NAN.to_le_bytes());
    let with_nan: ModelMemory = postcard::from_bytes(&encoded).unwrap();
    let blob = forged(&exact_bytes, |s| s.model.scene.model = with_nan.clone());
    assert_eq!(fmu.deserialize(&blob), Err(ERROR));
    assert!(log.texts().pop().unwrap().ends_with("warm_start_lateral = NaN is invalid: must be finite"));
    // The lateral values' count (a varint of 960 = 2 bytes) one less.
    let count = encoded.len() - 8 * 960 - 2;
    assert_eq!(&encoded[count..count + 2], &[0xc0, 0x07]);
    encoded[count] = 0xbf;
    encoded.truncate(encoded.len() - 8);
    let short: ModelMemory = postcard::from_bytes(&encoded).unwrap();
    assert_eq!(fmu.deserialize(&forged(&exact_bytes, |s| s.model.scene.model = short.clone())), Err(ERROR));
    assert!(log
        .texts()
        .pop()
        .unwrap()
        .ends_with("warm_start_lateral = 959 is invalid: must hold one value per element"));

    // Nothing changed, and a state with a legal stop time (after the time) is accepted.
    assert_eq!(fmu.get_real(&OUTPUTS), outputs);
    let legal = fmu.deserialize(&forged(&bytes, |s| s.stop_time = Some(1.0))).unwrap();
    assert_eq!(fmu.set_state(legal), OK);
    fmu.free_state(legal);
}

/// With `contact_geometry = profiles` and creep relaxation, the state carries each patch's
/// relaxed forces and where it was: a rolled-back run and a deserialised one in a fresh
/// instance continue bit for bit, the String parameters included.
#[test]
fn a_wheel_on_profiles_continues_bit_identically() {
    use wheel_rail_contact_fmu::model_description::ContactGeometry;
    let outputs = [vr::TRACK_FORCE_X, vr::TRACK_FORCE_Y, vr::PATCH1_FORCE_LATERAL];
    // The wheelset sways across the tread towards the flange, braking.
    let run = |fmu: &Fmu, first: usize, count: usize| -> Vec<[f64; 3]> {
        (first..first + count)
            .map(|k| {
                let lateral = 4e-3 * (0.05 * k as f64).sin();
                let inputs = [lateral, 2.0, 2.0 / 0.46 * 0.998, 0.2 * (0.05 * k as f64).cos()];
                let references = [
                    vr::WHEELSET_LATERAL_DISPLACEMENT,
                    vr::ROLLING_SPEED,
                    vr::WHEEL_ANGULAR_SPEED,
                    vr::WHEELSET_LATERAL_VELOCITY,
                ];
                assert_eq!(fmu.set_real(&references, &inputs), OK);
                assert_eq!(fmu.do_step(k as f64 * STEP, STEP), OK, "step {k}");
                let values = fmu.get_real(&outputs);
                [values[0], values[1], values[2]]
            })
            .collect()
    };
    // With non_hertzian the vertical balance's search starts where the last one settled, which
    // the state holds (`WheelState::balance`): a state restored continues from there.
    for method in [ContactMethod::Hertz, ContactMethod::NonHertzian] {
        let fmu = Fmu::instantiate("profiles", None);
        let parameters = [vr::CONTACT_GEOMETRY, vr::CREEP_RELAXATION, vr::WHEEL_SIDE, vr::CONTACT_METHOD];
        let choices = [ContactGeometry::Profiles as i32, Switch::On as i32, 0, method as i32];
        assert_eq!(fmu.set_integer(&parameters, &choices), OK);
        assert_eq!(fmu.set_string(&[vr::WHEEL_PROFILE], &["MBench_S1002"]), OK);
        fmu.initialise(0.0);
        run(&fmu, 0, 30);
        let state = fmu.get_state();
        let first = run(&fmu, 30, 40);
        assert_eq!(fmu.set_state(state), OK);
        assert_eq!(bits(&first), bits(&run(&fmu, 30, 40)), "{method:?}: rolled back");
        // Relaxation matters here: the forces lag behind the steady ones.
        let snapshot = decode(&fmu.serialize(state)).unwrap();
        assert!(
            !snapshot.model.wheel.patches.is_empty()
                && snapshot.model.wheel.patches.iter().all(|p| p.scene.relaxed_forces != [0.0; 2])
        );
        assert_eq!(snapshot.model.wheel.balance.is_some(), method == ContactMethod::NonHertzian, "{method:?}");
        assert_eq!(snapshot.model.strings.wheel_profile, "MBench_S1002");
        let bytes = fmu.serialize(state);
        fmu.free_state(state);
        let fresh = Fmu::instantiate("fresh", None);
        let restored = fresh.deserialize(&bytes).unwrap();
        assert_eq!(fresh.set_state(restored), OK);
        assert_eq!(bits(&first), bits(&run(&fresh, 30, 40)), "{method:?}: deserialised");
        fresh.free_state(restored);
        // A state whose wheel holds a non-finite patch position, or balance, is refused.
        let mut forged_state = snapshot.clone();
        forged_state.model.wheel.patches[0].rail_lateral = f64::NAN;
        assert_eq!(fresh.deserialize(&encode(&forged_state)), Err(ERROR));
        if let Some(balance) = snapshot.model.wheel.balance {
            for forged_balance in [
                BalanceStart { vertical: f64::INFINITY, ..balance },
                BalanceStart { touch: f64::NAN, ..balance },
                BalanceStart { slope: Some(-1.0), ..balance },
            ] {
                let mut forged_state = snapshot.clone();
                forged_state.model.wheel.balance = Some(forged_balance);
                assert_eq!(fresh.deserialize(&encode(&forged_state)), Err(ERROR), "{forged_balance:?}");
            }
        }
    }
}
