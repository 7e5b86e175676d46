//! A small master over the FMU's C exports (the `extern "C"` functions of
//! `wheel_rail_contact_fmu::ffi`, called in-process exactly as a master calls the shared
//! library), shared by the adapter's C-ABI integration tests, its leak-check example and its
//! step benchmark. A workspace crate (not published) so that each of them depends on it instead
//! of including its source.

use std::ffi::{c_char, CStr, CString};
use std::ptr::{null, null_mut};
use std::sync::atomic::{AtomicUsize, Ordering};

pub use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::ffi::variadic_logger;
pub use fmu_master::binary::file_uri;
use wheel_rail_contact_fmu::ffi::*;
use wheel_rail_contact_fmu::fmi2::*;
use wheel_rail_contact_fmu::model_description::{value_reference as vr, GUID};

pub const OK: fmi2Status = fmi2Status_fmi2OK;
pub const ERROR: fmi2Status = fmi2Status_fmi2Error;

/// The seven continuous inputs, in value-reference order.
pub const INPUTS: [u32; 7] = [
    vr::CREEPAGE_LONGITUDINAL,
    vr::CREEPAGE_LATERAL,
    vr::SPIN_CREEPAGE,
    vr::NORMAL_FORCE,
    vr::SEMI_AXIS_A,
    vr::SEMI_AXIS_B,
    vr::FRICTION_COEFFICIENT,
];
pub const OUTPUTS: [u32; 3] = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION];

/// Counts the logger's calls and checks each one as a master would rely on it: the format is
/// `"%s"` and every string is a valid, NUL-terminated pointer.
pub struct LogCounter(pub AtomicUsize);

/// The logger of [`LogCounter`] (a named parameter for the variadic one:
/// [`fmi2_slave::ffi::NamedLogger`]). It allocates nothing, so that the leak check counts the
/// FMU's allocations only; [`MessageLog`] records the texts.
extern "C" fn count_message(
    environment: fmi2ComponentEnvironment,
    instance_name: fmi2String,
    status: fmi2Status,
    category: fmi2String,
    format: fmi2String,
    text: fmi2String,
) {
    // SAFETY: the environment is the `LogCounter` given at instantiation; the FMU passes
    // NUL-terminated strings.
    unsafe {
        assert!(status <= fmi2Status_fmi2Fatal, "status {status}");
        assert_eq!(CStr::from_ptr(format), c"%s");
        for text in [instance_name, category, text] {
            assert!(!text.is_null());
            CStr::from_ptr(text).to_str().expect("UTF-8 message");
        }
        (*environment.cast::<LogCounter>()).0.fetch_add(1, Ordering::Relaxed);
    }
}

/// Callbacks whose logger counts into `counter` (`None`: no logger).
pub fn callbacks(counter: Option<&LogCounter>) -> fmi2CallbackFunctions {
    fmi2CallbackFunctions {
        logger: counter.and_then(|_| variadic_logger(count_message)),
        allocateMemory: None,
        freeMemory: None,
        stepFinished: None,
        componentEnvironment: counter.map_or(null_mut(), |c| (c as *const LogCounter).cast_mut().cast()),
    }
}

/// The repository's `data/` directory as a file URI (RFC 8089, percent-encoded): it holds
/// `exact_table.bin` as the packaged FMU's `resources/` does, so the `exact_table` model reads
/// the same table in-process as in the FMU.
pub fn repository_resources() -> String {
    let directory = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data"));
    file_uri(&directory.canonicalize().expect("the repository's data/ directory exists"))
}

/// One instance, freed on drop.
pub struct Fmu {
    pub c: fmi2Component,
    /// Kept alive as long as the instance: the FMU holds no pointer into it, but the master's
    /// callbacks structure must outlive fmi2Instantiate.
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Fmu {
    /// An instance whose resource location is [`repository_resources`], as every instance below
    /// but [`Self::instantiate_logged_at`]'s.
    pub fn instantiate(name: &str, counter: Option<&LogCounter>) -> Fmu {
        Self::with_callbacks(name, callbacks(counter), Some(&repository_resources()))
            .expect("fmi2Instantiate returned NULL")
    }

    /// An instance whose messages are recorded in `log` (which must outlive it).
    pub fn instantiate_logged(name: &str, log: &MessageLog) -> Fmu {
        Self::instantiate_logged_at(name, log, Some(&repository_resources()))
    }

    /// [`Self::instantiate_logged`] with `resource_location` passed to fmi2Instantiate.
    pub fn instantiate_logged_at(name: &str, log: &MessageLog, resource_location: Option<&str>) -> Fmu {
        Self::try_instantiate_logged_at(name, log, resource_location).expect("fmi2Instantiate returned NULL")
    }

    /// [`Self::instantiate_logged_at`], `None` where fmi2Instantiate returns NULL.
    pub fn try_instantiate_logged_at(name: &str, log: &MessageLog, resource_location: Option<&str>) -> Option<Fmu> {
        Self::with_callbacks(name, log.callbacks(), resource_location)
    }

    /// [`Self::instantiate_logged`] for Model Exchange.
    pub fn model_exchange_logged(name: &str, log: &MessageLog) -> Fmu {
        Self::of_type(fmi2Type_fmi2ModelExchange, name, log.callbacks(), Some(&repository_resources()))
            .expect("fmi2Instantiate returned NULL")
    }

    fn with_callbacks(name: &str, callbacks: fmi2CallbackFunctions, resource_location: Option<&str>) -> Option<Fmu> {
        Self::of_type(fmi2Type_fmi2CoSimulation, name, callbacks, resource_location)
    }

    fn of_type(
        fmu_type: fmi2Type,
        name: &str,
        callbacks: fmi2CallbackFunctions,
        resource_location: Option<&str>,
    ) -> Option<Fmu> {
        let callbacks = Box::new(callbacks);
        let (name, guid) = (CString::new(name).unwrap(), CString::new(GUID).unwrap());
        let location = resource_location.map(|location| CString::new(location).unwrap());
        let location_pointer = location.as_ref().map_or(null(), |location| location.as_ptr());
        // SAFETY: valid strings (or NULL for the location) and callbacks.
        let c = unsafe { fmi2Instantiate(name.as_ptr(), fmu_type, guid.as_ptr(), location_pointer, &*callbacks, 0, 0) };
        (!c.is_null()).then_some(Fmu { c, _callbacks: callbacks })
    }

    /// Setup from `start_time`, initialisation entered and left.
    pub fn initialise(&self, start_time: f64) {
        // SAFETY: `self.c` is live.
        unsafe {
            assert_eq!(fmi2SetupExperiment(self.c, 0, 0.0, start_time, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(self.c), OK);
            assert_eq!(fmi2ExitInitializationMode(self.c), OK);
        }
    }

    pub fn set_debug_logging(&self, on: bool, categories: &[&str]) -> fmi2Status {
        let owned: Vec<CString> = categories.iter().map(|c| CString::new(*c).unwrap()).collect();
        let pointers: Vec<fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        // SAFETY: live instance; `pointers` valid for its length, strings NUL-terminated.
        unsafe { fmi2SetDebugLogging(self.c, on as fmi2Boolean, pointers.len(), pointers.as_ptr()) }
    }

    pub fn set_integer(&self, references: &[u32], values: &[i32]) -> fmi2Status {
        assert_eq!(references.len(), values.len());
        // SAFETY: live instance, matching lengths.
        unsafe { fmi2SetInteger(self.c, references.as_ptr(), references.len(), values.as_ptr()) }
    }

    /// J·seed for `unknowns` with respect to `knowns`, with the call's status.
    pub fn directional_derivative(&self, unknowns: &[u32], knowns: &[u32], seed: &[f64]) -> (fmi2Status, Vec<f64>) {
        assert_eq!(knowns.len(), seed.len());
        let mut rates = vec![f64::NAN; unknowns.len()];
        // SAFETY: live instance; every array valid for its length.
        let status = unsafe {
            fmi2GetDirectionalDerivative(
                self.c,
                unknowns.as_ptr(),
                unknowns.len(),
                knowns.as_ptr(),
                knowns.len(),
                seed.as_ptr(),
                rates.as_mut_ptr(),
            )
        };
        (status, rates)
    }

    /// Instantiated, initialised from `start_time` on, in step mode.
    pub fn stepping(name: &str, start_time: f64) -> Fmu {
        let fmu = Fmu::instantiate(name, None);
        // SAFETY: `fmu.c` is live.
        unsafe {
            assert_eq!(fmi2SetupExperiment(fmu.c, 0, 0.0, start_time, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(fmu.c), OK);
            assert_eq!(fmi2ExitInitializationMode(fmu.c), OK);
        }
        fmu
    }

    /// fmi2SetString from Rust texts (the C copies are dropped after the call: the FMU must
    /// have copied them).
    pub fn set_string(&self, references: &[u32], values: &[&str]) -> fmi2Status {
        assert_eq!(references.len(), values.len());
        let owned: Vec<CString> = values.iter().map(|v| CString::new(*v).unwrap()).collect();
        let pointers: Vec<fmi2String> = owned.iter().map(|c| c.as_ptr()).collect();
        // SAFETY: live instance, matching lengths, NUL-terminated strings.
        unsafe { fmi2SetString(self.c, references.as_ptr(), references.len(), pointers.as_ptr()) }
    }

    /// fmi2GetString's pointers (valid until the instance's next call) and the call's status.
    pub fn get_string_pointers(&self, references: &[u32]) -> (fmi2Status, Vec<fmi2String>) {
        let mut pointers = vec![null(); references.len()];
        // SAFETY: live instance, matching lengths.
        let status = unsafe { fmi2GetString(self.c, references.as_ptr(), references.len(), pointers.as_mut_ptr()) };
        (status, pointers)
    }

    /// fmi2GetString, copied into Rust texts.
    pub fn get_string(&self, references: &[u32]) -> Vec<String> {
        let (status, pointers) = self.get_string_pointers(references);
        assert_eq!(status, OK);
        // SAFETY: the FMU's NUL-terminated strings, read before any other call on the instance.
        pointers.iter().map(|&p| unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_owned()).collect()
    }

    pub fn set_real(&self, references: &[u32], values: &[f64]) -> fmi2Status {
        assert_eq!(references.len(), values.len());
        // SAFETY: live instance, matching lengths.
        unsafe { fmi2SetReal(self.c, references.as_ptr(), references.len(), values.as_ptr()) }
    }

    pub fn get_real(&self, references: &[u32]) -> Vec<f64> {
        let mut values = vec![f64::NAN; references.len()];
        // SAFETY: live instance, matching lengths.
        let status = unsafe { fmi2GetReal(self.c, references.as_ptr(), references.len(), values.as_mut_ptr()) };
        assert_eq!(status, OK);
        values
    }

    pub fn do_step(&self, time: f64, step: f64) -> fmi2Status {
        // SAFETY: live instance.
        unsafe { fmi2DoStep(self.c, time, step, 0) }
    }

    pub fn get_state(&self) -> fmi2FMUstate {
        let mut state: fmi2FMUstate = null_mut();
        // SAFETY: live instance; a NULL slot asks for a new state.
        assert_eq!(unsafe { fmi2GetFMUstate(self.c, &mut state) }, OK);
        assert!(!state.is_null());
        state
    }

    // Safe on purpose, as the C ABI a master calls is: the FMU must check the state it is given
    // (the tests hand it states of other instances and freed ones), not trust the caller.
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn set_state(&self, state: fmi2FMUstate) -> fmi2Status {
        // SAFETY: live instance; `state` from this FMU.
        unsafe { fmi2SetFMUstate(self.c, state) }
    }

    pub fn free_state(&self, mut state: fmi2FMUstate) {
        // SAFETY: live instance; `state` from this FMU, freed once (the slot is cleared).
        assert_eq!(unsafe { fmi2FreeFMUstate(self.c, &mut state) }, OK);
        assert!(state.is_null());
    }

    // Safe on purpose, as the C ABI a master calls is: the FMU must check the state it is given
    // (the tests hand it states of other instances and freed ones), not trust the caller.
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn serialize(&self, state: fmi2FMUstate) -> Vec<u8> {
        let mut size = 0;
        // SAFETY: live instance and state; the buffer has the size the FMU asked for.
        unsafe {
            assert_eq!(fmi2SerializedFMUstateSize(self.c, state, &mut size), OK);
            let mut bytes = vec![0u8; size];
            assert_eq!(fmi2SerializeFMUstate(self.c, state, bytes.as_mut_ptr().cast::<c_char>(), size), OK);
            bytes
        }
    }

    /// The state in `bytes` (`Err(status)` if the FMU rejects them).
    pub fn deserialize(&self, bytes: &[u8]) -> Result<fmi2FMUstate, fmi2Status> {
        let mut state: fmi2FMUstate = null_mut();
        // SAFETY: live instance; `bytes` valid for its length.
        let status =
            unsafe { fmi2DeSerializeFMUstate(self.c, bytes.as_ptr().cast::<c_char>(), bytes.len(), &mut state) };
        if status == OK {
            Ok(state)
        } else {
            assert!(state.is_null(), "a rejected byte string gives no state");
            Err(status)
        }
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        // SAFETY: freed once.
        unsafe { fmi2FreeInstance(self.c) }
    }
}

/// Inputs of step `k` of a scene that sweeps every input through its range (creepage ramp
/// through saturation and sign change, spin, load steps down to lift-off, ellipse shape,
/// friction drop).
pub fn scene_inputs(k: usize) -> [f64; 7] {
    let t = k as f64;
    [
        4e-3 * (0.05 * t).sin(),
        -2e-3 * (0.031 * t).cos(),
        0.6 * (0.017 * t).sin(),
        if k % 97 == 50 { -10.0 } else { 60e3 + 40e3 * (0.011 * t).cos() },
        6e-3 + 2e-3 * (0.007 * t).sin(),
        4.5e-3 + 1.5e-3 * (0.013 * t).cos(),
        if k % 200 < 150 { 0.35 } else { 0.15 },
    ]
}

/// Runs steps `first..first + count` of [`scene_inputs`] from `fmu`'s current time, returning
/// the three outputs after every step.
pub fn run_scene(fmu: &Fmu, first: usize, count: usize, start_time: f64, step: f64) -> Vec<[f64; 3]> {
    (first..first + count)
        .map(|k| {
            assert_eq!(fmu.set_real(&INPUTS, &scene_inputs(k)), OK);
            let time = start_time + (k - first) as f64 * step;
            assert_eq!(fmu.do_step(time, step), OK, "step {k}");
            let outputs = fmu.get_real(&OUTPUTS);
            [outputs[0], outputs[1], outputs[2]]
        })
        .collect()
}

/// Bit patterns, so that equality is exact (and NaN-safe).
pub fn bits(rows: &[[f64; 3]]) -> Vec<[u64; 3]> {
    rows.iter().map(|row| row.map(f64::to_bits)).collect()
}
