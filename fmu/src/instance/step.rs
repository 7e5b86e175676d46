//! fmi2DoStep and the evaluation of the outputs: the core's scene over the step, kept only if
//! every output is finite.

use super::Instance;
use crate::logging::Status;
use crate::mode::Call;
use crate::model_description::Outputs;
use crate::scene::compute_outputs;
use wheel_rail_contact::scene::Evaluation;

impl Instance {
    /// Brings the outputs up to date: `Ok(Status::Ok)`, or `Ok(Status::Warning)` after logging
    /// why the outputs are to be used with care (an exact solve that stopped at its limits).
    #[inline]
    pub(super) fn update_outputs(&mut self, call: Call, evaluation: Evaluation) -> Result<Status, Status> {
        // The scene's next state is kept only if the outputs are good.
        let states = (&self.run.scene, &self.run.wheel);
        let outputs = compute_outputs(&self.run.values, &self.run.strings, &mut self.model, states, evaluation)
            .and_then(|(outputs, states, warning)| finite(&outputs).map(|_| (outputs, states, warning)));
        match outputs {
            Ok((outputs, (scene, wheel), warning)) => {
                self.run.values.outputs = outputs;
                self.run.scene = scene;
                self.run.wheel = wheel;
                self.run.profiles = self.model.profile_digest();
                Ok(match warning {
                    Some(warning) => {
                        self.log.emit(Status::Warning, &format!("{call}: {warning}"));
                        Status::Warning
                    }
                    None => Status::Ok,
                })
            }
            Err(reason) => Err(self.log.fail(call, &reason)),
        }
    }

    /// fmi2DoStep: outputs at t + h from the inputs set before the step (the model is algebraic).
    #[inline]
    pub fn do_step(&mut self, current_communication_point: f64, communication_step_size: f64) -> Status {
        const CALL: Call = Call::DoStep;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        let (t, h) = (current_communication_point, communication_step_size);
        self.log.trace(|| format!("{CALL}: currentCommunicationPoint = {t}, communicationStepSize = {h}"));
        let end = match fmi2_slave::instance::step_end(self.run.time, self.run.stop_time, t, h) {
            Ok(end) => end,
            Err(problem) => return self.log.fail(CALL, &problem),
        };
        match self.update_outputs(CALL, Evaluation::Step(h)) {
            Ok(status) => {
                self.run.time = end;
                status
            }
            Err(status) => status,
        }
    }

    /// fmi2CancelStep: DoStep never returns fmi2Pending, so there is never a step to cancel.
    pub fn cancel_step(&mut self) -> Status {
        match self.require(Call::CancelStep) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }
}

/// Every output finite, or why not: the last guard of "never NaN or Inf out", for finite
/// inputs so large that a model's arithmetic overflows. A few compares on the hot path; the
/// message is built only on failure.
pub(super) fn finite(outputs: &Outputs) -> Result<(), String> {
    let reals = outputs.reals();
    // x·0 is ±0 for a finite x and NaN for ±Inf or NaN: one branch-free sum tells.
    if reals.iter().fold(0.0, |sum, x| sum + x * 0.0) == 0.0 {
        return Ok(());
    }
    let overflowing: Vec<String> = Outputs::NAMES
        .iter()
        .zip(reals)
        .filter(|(_, x)| !x.is_finite())
        .map(|(name, x)| format!("{name} = {x}"))
        .collect();
    Err(format!(
        "{} for these values: an input or parameter is too large for the model's floating-point range",
        overflowing.join(", ")
    ))
}
