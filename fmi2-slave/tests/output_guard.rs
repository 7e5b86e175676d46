//! The generic instance's last guard, through the C exports of a minimal FMU built on it: an
//! output that initialize or a step computes non-finite (finite values whose arithmetic
//! overflows, which the model itself does not check) is fmi2Error naming the output, its value
//! and what it was computed from, and the instance keeps its previous values (the review's
//! defect 8: `wheel_angular_speed = inf` with fmi2OK).
//!
//! The FMU: `quotient` = `numerator` / `denominator` (inputs, direct feedthrough) and `integral`,
//! a state that grows by `gain` × step (a parameter, no input acts on it).

use std::ffi::CString;
use std::ptr::null;

use fmi2_slave::ffi::message_log::MessageLog;
use fmi2_slave::fmi2::*;
use fmi2_slave::instance::{decode_run, encode_run, keep_if_finite, Evaluation, FmuState, Model};
use fmi2_slave::mode::Mode;
use fmi2_slave::variables::{Causality, Kind, Variability, Variable};

const NUMERATOR: u32 = 0;
const DENOMINATOR: u32 = 1;
const GAIN: u32 = 10;
const QUOTIENT: u32 = 20;
const INTEGRAL: u32 = 21;

const fn real(name: &'static str, value_reference: u32, causality: Causality, start: Option<f64>) -> Variable {
    let variability = match causality {
        Causality::Parameter => Variability::Fixed,
        _ => Variability::Continuous,
    };
    let dependencies: &[u32] = if value_reference == QUOTIENT { &[NUMERATOR, DENOMINATOR] } else { &[] };
    Variable {
        name,
        value_reference,
        causality,
        variability,
        kind: Kind::Real { start },
        unit: None,
        display_unit: None,
        description: "",
        dependencies,
    }
}

static VARIABLES: [Variable; 5] = [
    real("numerator", NUMERATOR, Causality::Input, Some(1.0)),
    real("denominator", DENOMINATOR, Causality::Input, Some(1.0)),
    real("gain", GAIN, Causality::Parameter, Some(1.0)),
    real("quotient", QUOTIENT, Causality::Output, None),
    real("integral", INTEGRAL, Causality::Output, None),
];

const GUID: &str = "{output-guard}";

/// The values in `VARIABLES`' order.
#[derive(Debug, Clone, PartialEq)]
struct Ratio([f64; 5]);

impl Default for Ratio {
    fn default() -> Self {
        Ratio([1.0, 1.0, 1.0, 1.0, 0.0])
    }
}

fn index(value_reference: u32) -> Option<usize> {
    VARIABLES.iter().position(|v| v.value_reference == value_reference)
}

/// The gain that makes a step panic: a bug inside an export, to see it become fmi2Fatal.
const PANICKING_GAIN: f64 = 13.0;

/// The model: no checks of its own, so every non-finite output below reaches the slave layer's
/// guard ([`keep_if_finite`]).
struct RatioModel;

impl Model for RatioModel {
    type State = Ratio;

    const GUID: &'static str = GUID;
    const MODEL_IDENTIFIER: &'static str = "ratio";
    const LOG_CATEGORIES: &'static [&'static str] = &[];
    const STATE_LAYOUT_TAG: u64 = 1;
    const STATE_MAGIC: [u8; 8] = *b"RATstate";
    const STATE_FORMAT_VERSION: u16 = 1;

    fn instantiate(_resource_location: Option<&str>) -> Result<(Self, Option<String>), String> {
        Ok((RatioModel, None))
    }

    fn reset(&mut self) {}

    fn start() -> Ratio {
        Ratio::default()
    }

    fn variable(value_reference: u32) -> Option<&'static Variable> {
        index(value_reference).map(|i| &VARIABLES[i])
    }

    fn variables() -> &'static [Variable] {
        &VARIABLES
    }

    fn real(state: &Ratio, value_reference: u32) -> Option<f64> {
        index(value_reference).map(|i| state.0[i])
    }

    fn real_mut(state: &mut Ratio, value_reference: u32) -> Option<&mut f64> {
        index(value_reference).map(|i| &mut state.0[i])
    }

    fn evaluate(&mut self, state: &mut Ratio, evaluation: Evaluation) -> Result<Option<String>, String> {
        keep_if_finite::<Self>(state, |ratio| {
            ratio.0[3] = ratio.0[0] / ratio.0[1];
            match evaluation {
                Evaluation::Initialise => ratio.0[4] = 0.0,
                Evaluation::Step { size, .. } => {
                    assert!(ratio.0[2] != PANICKING_GAIN, "forced by a test");
                    ratio.0[4] += ratio.0[2] * size;
                }
                // The ratio at the new inputs; the integral is state and stays.
                Evaluation::Feedthrough { .. } => {}
            }
            Ok(())
        })?;
        Ok(None)
    }

    fn encode(state: &FmuState<Ratio>) -> Vec<u8> {
        let bytes: Vec<u8> = state.model.0.iter().flat_map(|x| x.to_le_bytes()).collect();
        encode_run(state, &bytes)
    }

    fn decode(payload: &[u8]) -> Result<FmuState<Ratio>, String> {
        let run = decode_run(payload)?;
        let values: Vec<f64> = run.model.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
        let model = values.try_into().map(Ratio).map_err(|_| format!("{} bytes of values", run.model.len()))?;
        Ok(FmuState { mode: run.mode, time: run.time, stop_time: run.stop_time, model })
    }

    fn check_state(_state: &Ratio, _mode: Mode) -> Result<(), String> {
        Ok(())
    }
}

fmi2_slave::export_fmi2!(fmi2_slave::instance::Instance<crate::RatioModel>);

const OK: fmi2Status = fmi2Status_fmi2OK;
const ERROR: fmi2Status = fmi2Status_fmi2Error;

/// One instance, freed on drop.
struct Fmu {
    c: fmi2Component,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Fmu {
    /// Instantiated, in initialization mode at t = 0.
    fn initializing(log: &MessageLog) -> Fmu {
        let callbacks = Box::new(log.callbacks());
        let guid = CString::new(GUID).unwrap();
        // SAFETY: valid strings and callbacks that outlive the instance.
        let c = unsafe {
            fmi2Instantiate(c"ratio".as_ptr(), fmi2Type_fmi2CoSimulation, guid.as_ptr(), null(), &*callbacks, 0, 0)
        };
        assert!(!c.is_null(), "{}", log.last_text());
        // SAFETY: `c` is live.
        unsafe {
            assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi2EnterInitializationMode(c), OK);
        }
        Fmu { c, _callbacks: callbacks }
    }

    fn set(&self, reference: u32, value: f64) {
        // SAFETY: `c` is live; one reference, one value.
        assert_eq!(unsafe { fmi2SetReal(self.c, &reference, 1, &value) }, OK);
    }

    fn get(&self, references: &[u32]) -> (fmi2Status, Vec<f64>) {
        let mut values = vec![f64::NAN; references.len()];
        // SAFETY: `c` is live; the slices have the same length.
        let status = unsafe { fmi2GetReal(self.c, references.as_ptr(), references.len(), values.as_mut_ptr()) };
        (status, values)
    }

    fn exit_initialization(&self) -> fmi2Status {
        // SAFETY: `c` is live.
        unsafe { fmi2ExitInitializationMode(self.c) }
    }

    fn do_step(&self, time: f64, step: f64) -> fmi2Status {
        // SAFETY: `c` is live.
        unsafe { fmi2DoStep(self.c, time, step, 0) }
    }

    fn last_successful_time(&self) -> f64 {
        let mut time = f64::NAN;
        // SAFETY: `c` is live.
        assert_eq!(unsafe { fmi2GetRealStatus(self.c, fmi2StatusKind_fmi2LastSuccessfulTime, &mut time) }, OK);
        time
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        // SAFETY: freed once.
        unsafe { fmi2FreeInstance(self.c) }
    }
}

const OUTPUTS: [u32; 2] = [QUOTIENT, INTEGRAL];

#[test]
fn a_non_finite_output_at_initialization_is_an_error_naming_it_and_its_inputs() {
    let log = MessageLog::default();
    let fmu = Fmu::initializing(&log);
    // 1 / 5e-324 overflows: finite values, an infinite output.
    fmu.set(DENOMINATOR, 5e-324);
    let message = "quotient = inf is not finite, computed from numerator = 1.0, denominator = 5e-324: a value beyond \
                   the floating-point range; the previous values are kept";
    assert_eq!(fmu.exit_initialization(), ERROR);
    assert_eq!(log.last_text(), format!("fmi2ExitInitializationMode: {message}"));
    // Still in initialization mode: reading an output computes them again, with the same error,
    // and hands out nothing.
    assert_eq!(fmu.get(&OUTPUTS).0, ERROR);
    assert_eq!(log.last_text(), format!("fmi2GetReal: {message}"));
    // Corrected, it starts.
    fmu.set(DENOMINATOR, 4.0);
    assert_eq!(fmu.exit_initialization(), OK, "{}", log.last_text());
    assert_eq!(fmu.get(&OUTPUTS), (OK, vec![0.25, 0.0]));
}

#[test]
fn a_non_finite_output_after_a_step_is_an_error_and_the_previous_values_stay() {
    let log = MessageLog::default();
    let fmu = Fmu::initializing(&log);
    fmu.set(GAIN, 1e308);
    assert_eq!(fmu.exit_initialization(), OK, "{}", log.last_text());
    assert_eq!(fmu.do_step(0.0, 1.0), OK);
    let before = fmu.get(&OUTPUTS);
    assert_eq!(before, (OK, vec![1.0, 1e308]));
    // An output with inputs: they are named with their values.
    fmu.set(NUMERATOR, 1e308);
    fmu.set(DENOMINATOR, 1e-308);
    assert_eq!(fmu.do_step(1.0, 1.0), ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2DoStep: quotient = inf is not finite, computed from numerator = 1e308, denominator = 1e-308: a value \
         beyond the floating-point range; the previous values are kept"
    );
    // Read at these inputs, the quotient is the same error (direct feedthrough) …
    assert_eq!(fmu.get(&OUTPUTS).0, ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2GetReal: quotient = inf is not finite, computed from numerator = 1e308, denominator = 1e-308: a value \
         beyond the floating-point range; the previous values are kept"
    );
    assert_eq!(fmu.last_successful_time(), 1.0);
    // … and back at the previous inputs the previous values are there: nothing of the failed
    // step was kept.
    fmu.set(NUMERATOR, 1.0);
    fmu.set(DENOMINATOR, 1.0);
    assert_eq!(fmu.get(&OUTPUTS), before);
    // A state no input acts on: the parameters and the state are to blame (1e308 + 1e308).
    assert_eq!(fmu.do_step(1.0, 1.0), ERROR);
    assert_eq!(
        log.last_text(),
        "fmi2DoStep: integral = inf is not finite, computed from the parameters and the state (no input acts on it \
         directly): a value beyond the floating-point range; the previous values are kept"
    );
    assert_eq!(fmu.get(&OUTPUTS), before);
    assert_eq!(fmu.last_successful_time(), 1.0);
    // A step that stays in range still succeeds from the kept values.
    assert_eq!(fmu.do_step(1.0, 0.5), OK, "{}", log.last_text());
    assert_eq!(fmu.get(&OUTPUTS), (OK, vec![1.0, 1.5e308]));
    assert_eq!(fmu.last_successful_time(), 1.5);
}

/// A panic inside an export (a bug; here forced by the model's step) is caught at the C
/// boundary: fmi2Fatal, a fatal message through the master's logger, and the instance refuses
/// every further call but can be freed.
#[test]
fn a_panic_in_an_export_becomes_fmi2_fatal_and_only_freeing_remains() {
    let log = MessageLog::default();
    let fmu = Fmu::initializing(&log);
    fmu.set(GAIN, PANICKING_GAIN);
    assert_eq!(fmu.exit_initialization(), OK, "{}", log.last_text());
    assert_eq!(fmu.do_step(0.0, 1.0), fmi2Status_fmi2Fatal);
    let message = log.last_text();
    assert!(message.starts_with("fmi2DoStep: internal error (forced by a test"), "{message}");
    assert!(message.ends_with("); this instance can only be freed"), "{message}");
    assert_eq!(fmu.do_step(0.0, 1.0), ERROR);
    assert_eq!(log.last_text(), "fmi2DoStep: illegal call in state fatal");
    // SAFETY: `c` is live.
    assert_eq!(unsafe { fmi2Reset(fmu.c) }, ERROR);
    assert_eq!(log.last_text(), "fmi2Reset: illegal call in state fatal");
}
