//! A seeded, randomised fuzz harness of the C ABI: random sequences of every FMI 2.0 call an
//! instance accepts, on Co-Simulation and Model Exchange instances (each also called with the
//! other interface's functions), with random value references (valid and not), random values (NaN, ±Inf,
//! ±1e±300, ±0, negatives, subnormals, realistic ones), NULL pointers with n = 0 (and with
//! n > 0), random state transitions, and FMU states taken, set, freed, serialised, corrupted and
//! deserialised. Every call must return a valid fmi2Status (never fmi2Fatal: that would be a
//! panic caught at the boundary, i.e. a bug), no panic may escape (it would abort the test
//! process), outputs read after a successful step are finite, and every log message is
//! well-formed (see `fmu_test_master::count_message`).
//!
//! Budget: `FMU_FUZZ_CALLS` calls (default 1 000 000, about a second) from seed
//! `FMU_FUZZ_SEED` (default fixed, so CI is reproducible). A failure prints the seed and the
//! call number; rerun with that seed to reproduce. Longer runs: see docs/testing.md.

use std::collections::BTreeMap;
use std::ffi::{c_char, CString};
use std::ptr::{null, null_mut};

use fmu_test_master::{callbacks, LogCounter};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::fmi2::*;
use wheel_rail_contact_fmu::model_description::{Causality, GUID, VARIABLES};

const DEFAULT_SEED: u64 = 0x5EED_2026_0006;
const DEFAULT_CALLS: usize = 1_000_000;

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Values a master might send, from sensible to hostile.
const SPECIAL: [f64; 16] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    1e-300,
    -1e-300,
    0.0,
    -0.0,
    -1.0,
    f64::MIN_POSITIVE,
    5e-324,
    f64::MAX,
    f64::MIN,
    1.0,
    1e-3,
];

struct Fuzzer {
    rng: StdRng,
    calls: usize,
    /// Per function: how often it answered each status (OK, Warning, Discard, Error, Fatal).
    statuses: BTreeMap<&'static str, [usize; 5]>,
    counter: Box<LogCounter>,
    instances: Vec<fmi2Component>,
    states: Vec<fmi2FMUstate>,
    blobs: Vec<Vec<u8>>,
    /// Keeps the callbacks structures alive for the instances, at fixed addresses (FMI 2.0 lets
    /// an FMU keep the pointer it was given, so a master must not move them).
    #[allow(clippy::vec_box)]
    callbacks: Vec<Box<fmi2CallbackFunctions>>,
}

impl Fuzzer {
    fn real(&mut self) -> f64 {
        match self.rng.random_range(0..4) {
            0 => SPECIAL[self.rng.random_range(0..SPECIAL.len())],
            // Around a variable's start value: mostly valid, sometimes out of range.
            1 | 2 => {
                let variable = &VARIABLES[self.rng.random_range(0..VARIABLES.len())];
                let start = match variable.kind {
                    wheel_rail_contact_fmu::model_description::Kind::Real { start: Some(s) } => s,
                    _ => 1e-3,
                };
                start * self.rng.random_range(-2.0..3.0)
            }
            _ => self.rng.random_range(-1e6..1e6),
        }
    }

    fn value_reference(&mut self) -> u32 {
        if self.rng.random_bool(0.85) {
            VARIABLES[self.rng.random_range(0..VARIABLES.len())].value_reference
        } else {
            [7, 99, 106, 203, 299, 4095, 4096, 65_535, u32::MAX][self.rng.random_range(0..9)]
        }
    }

    fn value_references(&mut self) -> Vec<u32> {
        let n = self.rng.random_range(0..5);
        (0..n).map(|_| self.value_reference()).collect()
    }

    /// A pointer to `values` — or NULL, which is legal only for n = 0.
    fn pointer<T>(&mut self, values: &[T]) -> *const T {
        if values.is_empty() && self.rng.random_bool(0.5) || self.rng.random_bool(0.02) {
            null()
        } else {
            values.as_ptr()
        }
    }

    fn pointer_mut<T>(&mut self, values: &mut [T]) -> *mut T {
        self.pointer(values).cast_mut()
    }

    fn check(&mut self, status: fmi2Status, call: &'static str) {
        self.calls += 1;
        assert!(
            (fmi2Status_fmi2OK..=fmi2Status_fmi2Error).contains(&status),
            "call {} ({call}) returned status {status}",
            self.calls
        );
        self.statuses.entry(call).or_default()[status as usize] += 1;
    }

    fn instantiate(&mut self) {
        let logging = self.rng.random_bool(0.3);
        let callbacks = Box::new(callbacks(logging.then_some(&*self.counter)));
        let name = CString::new(format!("fuzz {}", self.instances.len())).unwrap();
        let guid = CString::new(GUID).unwrap();
        let debug = fmi2Boolean::from(self.rng.random_bool(0.3));
        let fmu_type = if self.rng.random_bool(0.6) { fmi2Type_fmi2CoSimulation } else { fmi2Type_fmi2ModelExchange };
        // SAFETY: valid strings and callbacks.
        let c = unsafe { fmi2Instantiate(name.as_ptr(), fmu_type, guid.as_ptr(), null(), &*callbacks, 0, debug) };
        assert!(!c.is_null());
        self.calls += 1;
        self.instances.push(c);
        self.callbacks.push(callbacks);
    }

    /// One random call on a random instance.
    fn call(&mut self) {
        let c = self.instances[self.rng.random_range(0..self.instances.len())];
        // SAFETY: `c` is live; every pointer is NULL or valid for its n; states come from this FMU
        // and are not freed (a freed one is removed from the pool).
        unsafe {
            match self.rng.random_range(0..40) {
                0..=5 => {
                    let references = self.value_references();
                    let values: Vec<f64> = references.iter().map(|_| self.real()).collect();
                    let (r, v) = (self.pointer(&references), self.pointer(&values));
                    self.check(fmi2SetReal(c, r, references.len(), v), "fmi2SetReal");
                }
                6..=8 => {
                    let references = self.value_references();
                    let mut values = vec![0.0; references.len()];
                    let (r, v) = (self.pointer(&references), self.pointer_mut(&mut values));
                    let status = fmi2GetReal(c, r, references.len(), v);
                    self.check(status, "fmi2GetReal");
                    let outputs =
                        |r: &u32| VARIABLES.iter().any(|v| v.value_reference == *r && v.causality == Causality::Output);
                    if status == fmi2Status_fmi2OK {
                        for (reference, value) in references.iter().zip(&values) {
                            assert!(!outputs(reference) || value.is_finite(), "output {reference} = {value}");
                        }
                    }
                }
                9 => {
                    let references = self.value_references();
                    let values: Vec<i32> = references
                        .iter()
                        .map(|_| [1, 2, 0, -1, 3, i32::MAX, i32::MIN][self.rng.random_range(0..7)])
                        .collect();
                    let (r, v) = (self.pointer(&references), self.pointer(&values));
                    self.check(fmi2SetInteger(c, r, references.len(), v), "fmi2SetInteger");
                    let mut read = vec![0; references.len()];
                    let w = self.pointer_mut(&mut read);
                    self.check(fmi2GetInteger(c, r, references.len(), w), "fmi2GetInteger");
                }
                10 => {
                    let references = self.value_references();
                    let flags = vec![1; references.len()];
                    let text = c"x".as_ptr();
                    let strings = vec![text; references.len()];
                    let r = self.pointer(&references);
                    let (f, s) = (self.pointer(&flags), self.pointer(&strings));
                    self.check(fmi2SetBoolean(c, r, references.len(), f), "fmi2SetBoolean");
                    self.check(fmi2SetString(c, r, references.len(), s), "fmi2SetString");
                    let (mut flags, mut strings) = (flags, strings);
                    let (f, s) = (self.pointer_mut(&mut flags), self.pointer_mut(&mut strings));
                    self.check(fmi2GetBoolean(c, r, references.len(), f), "fmi2GetBoolean");
                    self.check(fmi2GetString(c, r, references.len(), s), "fmi2GetString");
                }
                11..=15 => {
                    let time = self.current_time(c);
                    let step = if self.rng.random_bool(0.8) { self.rng.random_range(1e-6..0.1) } else { self.real() };
                    let at = if self.rng.random_bool(0.9) { time } else { self.real() };
                    let no_set_prior = self.rng.random_range(0..2);
                    self.check(fmi2DoStep(c, at, step, no_set_prior), "fmi2DoStep");
                }
                16 => {
                    let (start, stop) = (self.real(), self.real());
                    let status = fmi2SetupExperiment(c, 1, self.real(), start, self.rng.random_range(0..2), stop);
                    self.check(status, "fmi2SetupExperiment");
                }
                17 => self.check(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode"),
                18 => self.check(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode"),
                19 => match self.rng.random_range(0..3) {
                    0 => self.check(fmi2Terminate(c), "fmi2Terminate"),
                    1 => self.check(fmi2Reset(c), "fmi2Reset"),
                    _ => self.check(fmi2CancelStep(c), "fmi2CancelStep"),
                },
                20 => {
                    let kind = [0, 1, 2, 3, 17, u32::MAX][self.rng.random_range(0..6)];
                    let (mut status, mut real, mut integer, mut boolean, mut string) = (0, 0.0, 0, 0, null());
                    let null_value = self.rng.random_bool(0.2);
                    fn pick<T>(null_value: bool, p: &mut T) -> *mut T {
                        if null_value {
                            null_mut()
                        } else {
                            p
                        }
                    }
                    self.check(fmi2GetStatus(c, kind, pick(null_value, &mut status)), "fmi2GetStatus");
                    self.check(fmi2GetRealStatus(c, kind, pick(null_value, &mut real)), "fmi2GetRealStatus");
                    self.check(fmi2GetIntegerStatus(c, kind, pick(null_value, &mut integer)), "fmi2GetIntegerStatus");
                    self.check(fmi2GetBooleanStatus(c, kind, pick(null_value, &mut boolean)), "fmi2GetBooleanStatus");
                    self.check(fmi2GetStringStatus(c, kind, pick(null_value, &mut string)), "fmi2GetStringStatus");
                }
                21 => {
                    let names = [c"logAll", c"logStatusError", c"logCalls", c"noSuchCategory", c""];
                    let n = self.rng.random_range(0..3);
                    let categories: Vec<fmi2String> =
                        (0..n).map(|_| names[self.rng.random_range(0..names.len())].as_ptr()).collect();
                    let p = self.pointer(&categories);
                    let logging_on = self.rng.random_range(0..2);
                    self.check(fmi2SetDebugLogging(c, logging_on, n, p), "fmi2SetDebugLogging");
                }
                22..=23 => {
                    let mut slot: fmi2FMUstate = null_mut();
                    let reuse = !self.states.is_empty() && self.rng.random_bool(0.3);
                    let index = self.rng.random_range(0..self.states.len().max(1));
                    if reuse {
                        slot = self.states[index];
                    }
                    let target = if self.rng.random_bool(0.03) { null_mut() } else { &mut slot as *mut _ };
                    let status = fmi2GetFMUstate(c, target);
                    self.check(status, "fmi2GetFMUstate");
                    if status == fmi2Status_fmi2OK && !reuse {
                        self.states.push(slot);
                    }
                }
                24..=25 => {
                    let state = self.some_state();
                    self.check(fmi2SetFMUstate(c, state), "fmi2SetFMUstate");
                }
                26 => {
                    if !self.states.is_empty() {
                        let index = self.rng.random_range(0..self.states.len());
                        let mut state = self.states[index];
                        let status = fmi2FreeFMUstate(c, &mut state);
                        self.check(status, "fmi2FreeFMUstate");
                        if status == fmi2Status_fmi2OK {
                            assert!(state.is_null());
                            self.states.swap_remove(index);
                        }
                    } else {
                        self.check(fmi2FreeFMUstate(c, null_mut()), "fmi2FreeFMUstate");
                    }
                }
                27..=28 => {
                    let state = self.some_state();
                    let mut size = 0usize;
                    let status = fmi2SerializedFMUstateSize(c, state, &mut size);
                    self.check(status, "fmi2SerializedFMUstateSize");
                    if status == fmi2Status_fmi2OK {
                        let wrong = self.rng.random_bool(0.1);
                        let length = if wrong { size + self.rng.random_range(0..3) - 1 } else { size };
                        let mut bytes = vec![0u8; length];
                        let p = self.pointer_mut(&mut bytes);
                        let status = fmi2SerializeFMUstate(c, state, p.cast::<c_char>(), length);
                        self.check(status, "fmi2SerializeFMUstate");
                        if status == fmi2Status_fmi2OK {
                            assert_eq!(length, size);
                            self.blobs.push(bytes);
                        }
                    }
                }
                29..=30 => {
                    let blob = self.damaged_blob();
                    let mut slot: fmi2FMUstate = null_mut();
                    let p = self.pointer(&blob);
                    let status = fmi2DeSerializeFMUstate(c, p.cast::<c_char>(), blob.len(), &mut slot);
                    self.check(status, "fmi2DeSerializeFMUstate");
                    if status == fmi2Status_fmi2OK {
                        self.states.push(slot);
                    } else {
                        assert!(slot.is_null());
                    }
                }
                31..=32 => {
                    let (unknowns, knowns) = (self.value_references(), self.value_references());
                    let rates: Vec<f64> = knowns.iter().map(|_| self.real()).collect();
                    let mut results = vec![0.0; unknowns.len()];
                    let (u, k, r) = (self.pointer(&unknowns), self.pointer(&knowns), self.pointer(&rates));
                    let d = self.pointer_mut(&mut results);
                    let status = fmi2GetDirectionalDerivative(c, u, unknowns.len(), k, knowns.len(), r, d);
                    self.check(status, "fmi2GetDirectionalDerivative");
                }
                34 => match self.rng.random_range(0..3) {
                    0 => self.check(fmi2EnterEventMode(c), "fmi2EnterEventMode"),
                    1 => self.check(fmi2EnterContinuousTimeMode(c), "fmi2EnterContinuousTimeMode"),
                    _ => {
                        let mut info = fmi2EventInfo::default();
                        let target = if self.rng.random_bool(0.05) { null_mut() } else { &mut info as *mut _ };
                        self.check(fmi2NewDiscreteStates(c, target), "fmi2NewDiscreteStates");
                    }
                },
                35 => {
                    let (mut enter, mut terminate) = (0, 0);
                    let target = if self.rng.random_bool(0.05) { null_mut() } else { &mut enter as *mut _ };
                    let status = fmi2CompletedIntegratorStep(c, 1, target, &mut terminate);
                    self.check(status, "fmi2CompletedIntegratorStep");
                }
                36 => {
                    let time = self.real();
                    self.check(fmi2SetTime(c, time), "fmi2SetTime");
                }
                37 => {
                    // The contact FMU has no states: n = 0 is right, anything else an error.
                    let states: Vec<f64> = (0..self.rng.random_range(0..3)).map(|_| self.real()).collect();
                    let p = self.pointer(&states);
                    self.check(fmi2SetContinuousStates(c, p, states.len()), "fmi2SetContinuousStates");
                }
                38 => {
                    let mut values = vec![0.0; self.rng.random_range(0..3)];
                    let (n, p) = (values.len(), self.pointer_mut(&mut values));
                    self.check(fmi2GetDerivatives(c, p, n), "fmi2GetDerivatives");
                    // The event indicators' count, now and then (their values: anything).
                    let mut indicators = vec![0.0; if self.rng.random_bool(0.5) { 18 } else { n }];
                    let (m, q) = (indicators.len(), self.pointer_mut(&mut indicators));
                    self.check(fmi2GetEventIndicators(c, q, m), "fmi2GetEventIndicators");
                    self.check(fmi2GetContinuousStates(c, p, n), "fmi2GetContinuousStates");
                    self.check(fmi2GetNominalsOfContinuousStates(c, p, n), "fmi2GetNominalsOfContinuousStates");
                }
                _ => {
                    let references = self.value_references();
                    let orders = vec![1; references.len()];
                    let mut values = vec![0.0; references.len()];
                    let r = self.pointer(&references);
                    let status = fmi2SetRealInputDerivatives(c, r, references.len(), orders.as_ptr(), values.as_ptr());
                    self.check(status, "fmi2SetRealInputDerivatives");
                    let status =
                        fmi2GetRealOutputDerivatives(c, r, references.len(), orders.as_ptr(), values.as_mut_ptr());
                    self.check(status, "fmi2GetRealOutputDerivatives");
                }
            }
        }
    }

    /// The instance's time if it has one to report, else 0.
    fn current_time(&mut self, c: fmi2Component) -> f64 {
        let mut time = 0.0;
        // SAFETY: live instance, valid pointer.
        let status = unsafe { fmi2GetRealStatus(c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut time) };
        self.check(status, "fmi2GetRealStatus");
        time
    }

    /// A state from the pool, or NULL.
    fn some_state(&mut self) -> fmi2FMUstate {
        if self.states.is_empty() || self.rng.random_bool(0.05) {
            null_mut()
        } else {
            self.states[self.rng.random_range(0..self.states.len())]
        }
    }

    /// A serialised state, intact or damaged (bit flip, truncation, extension, random bytes).
    fn damaged_blob(&mut self) -> Vec<u8> {
        if self.blobs.is_empty() || self.rng.random_bool(0.1) {
            let n = self.rng.random_range(0..200);
            return (0..n).map(|_| self.rng.random()).collect();
        }
        let mut blob = self.blobs[self.rng.random_range(0..self.blobs.len())].clone();
        match self.rng.random_range(0..5) {
            0 => {}
            1 => {
                let position = self.rng.random_range(0..blob.len());
                blob[position] ^= 1 << self.rng.random_range(0..8);
            }
            2 => blob.truncate(self.rng.random_range(0..blob.len())),
            3 => blob.push(self.rng.random()),
            _ => {
                let position = self.rng.random_range(0..blob.len());
                blob[position] = self.rng.random();
            }
        }
        blob
    }

    /// Frees every state and instance of the episode.
    fn finish_episode(&mut self) {
        let c = self.instances[0];
        for mut state in self.states.drain(..) {
            // SAFETY: live instance, each state freed once. fmi2Reset first: freeing is legal in
            // every live state, and an instance this harness drove is always live.
            let status = unsafe { fmi2FreeFMUstate(c, &mut state) };
            assert_eq!(status, fmi2Status_fmi2OK);
        }
        for c in self.instances.drain(..) {
            // SAFETY: freed once.
            unsafe { fmi2FreeInstance(c) };
        }
        self.callbacks.clear();
        self.blobs.truncate(8);
    }
}

#[test]
fn random_call_sequences_through_the_c_abi_never_crash_and_always_answer_a_valid_status() {
    let seed = env_or("FMU_FUZZ_SEED", DEFAULT_SEED);
    let budget = env_or("FMU_FUZZ_CALLS", DEFAULT_CALLS);
    let mut fuzzer = Fuzzer {
        rng: StdRng::seed_from_u64(seed),
        calls: 0,
        statuses: BTreeMap::new(),
        counter: Box::new(LogCounter(0.into())),
        instances: Vec::new(),
        states: Vec::new(),
        blobs: Vec::new(),
        callbacks: Vec::new(),
    };
    let mut episodes = 0;
    while fuzzer.calls < budget {
        episodes += 1;
        for _ in 0..fuzzer.rng.random_range(1..4) {
            fuzzer.instantiate();
        }
        let length = fuzzer.rng.random_range(1..600);
        for _ in 0..length {
            fuzzer.call();
        }
        fuzzer.finish_episode();
    }
    let messages = fuzzer.counter.0.load(std::sync::atomic::Ordering::Relaxed);
    let total = fuzzer.statuses.values().fold([0; 5], |sum, s| std::array::from_fn(|k| sum[k] + s[k]));
    println!(
        "fuzz: seed {seed:#x}, {episodes} episodes, {} calls; status OK {}, Warning {}, Discard {}, Error {}, \
         Fatal {}; {messages} log messages",
        fuzzer.calls, total[0], total[1], total[2], total[3], total[4],
    );
    for (call, [ok, warning, discard, error, fatal]) in &fuzzer.statuses {
        println!("  {call:32} OK {ok:7} Warning {warning:5} Discard {discard:5} Error {error:7} Fatal {fatal}");
    }
    // The harness reaches the interesting paths: every export is called often, the central
    // ones both succeed and refuse, and messages reach the logger.
    assert_eq!(fuzzer.statuses.len(), 40, "every export but Instantiate/FreeInstance/GetVersion/GetTypesPlatform");
    for (call, counts) in &fuzzer.statuses {
        assert!(counts.iter().sum::<usize>() > budget / 200, "{call} called too rarely: {counts:?}");
    }
    for call in [
        "fmi2SetReal",
        "fmi2DoStep",
        "fmi2GetReal",
        "fmi2GetDirectionalDerivative",
        "fmi2SetFMUstate",
        "fmi2SerializeFMUstate",
        "fmi2DeSerializeFMUstate",
        "fmi2SetTime",
        "fmi2EnterContinuousTimeMode",
        "fmi2CompletedIntegratorStep",
        "fmi2GetDerivatives",
    ] {
        let [ok, _, _, error, _] = fuzzer.statuses[call];
        assert!(ok > 0 && error > 0, "{call} was not exercised both ways");
    }
    assert!(messages > budget / 20, "{messages} log messages");
}
