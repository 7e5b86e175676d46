//! fmi2DoStep and the evaluation of the outputs: the core's scene over the step, kept only if
//! every output is finite ([`crate::scene::update_outputs`]).

use super::Instance;
use crate::logging::Status;
use crate::mode::Call;
use crate::scene::update_outputs;
use wheel_rail_contact::scene::Evaluation;

impl Instance {
    /// Brings the outputs up to date: `Ok(Status::Ok)`, or `Ok(Status::Warning)` after logging
    /// why the outputs are to be used with care (an exact solve that stopped at its limits).
    /// The outputs and the contact's state change only if every output is finite.
    #[inline]
    pub(super) fn update_outputs(&mut self, call: Call, evaluation: Evaluation) -> Result<Status, Status> {
        let run = &mut self.run;
        let updated =
            update_outputs(&mut run.values, &run.strings, &mut self.model, &mut run.scene, &mut run.wheel, evaluation);
        match updated {
            Ok(warning) => {
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
