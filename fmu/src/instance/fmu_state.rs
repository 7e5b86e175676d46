//! fmi2GetFMUstate … fmi2DeSerializeFMUstate: an FMU state is a [`Snapshot`] of the instance;
//! its byte format is [`crate::snapshot`]'s.

use super::Instance;
use crate::logging::Status;
use crate::mode::Call;
use crate::snapshot::{decode, encode, Snapshot};
use fmi2_slave::instance as rules;

/// The opaque object behind an `fmi2FMUstate` pointer.
#[derive(Debug, Clone, PartialEq)]
pub struct FmuState(pub Snapshot);

impl Instance {
    /// fmi2GetFMUstate: a copy of the instance's mode, time, values and model state.
    pub fn get_fmu_state(&mut self) -> Result<FmuState, Status> {
        const CALL: Call = Call::GetFMUstate;
        self.require(CALL)?;
        let (mode, time) = (self.run.mode, self.run.time);
        self.log.trace(|| format!("{CALL}: state {}, time {time}", mode.name()));
        Ok(FmuState(self.run.clone()))
    }

    /// fmi2SetFMUstate: from here on the instance behaves exactly as when `state` was taken.
    pub fn set_fmu_state(&mut self, state: &FmuState) -> Status {
        const CALL: Call = Call::SetFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        self.log.trace(|| format!("{CALL}: state {}, time {}", state.0.mode.name(), state.0.time));
        // The model (with profiles: the profiles read and placed, tens of ms) is rebuilt only if
        // the state's parameters differ: a master that restores a state every step (a
        // finite-difference Jacobian, a retried step) would otherwise pay that each time.
        let parameters_differ =
            self.run.values.parameters != state.0.values.parameters || self.run.strings != state.0.strings;
        self.run.clone_from(&state.0);
        if parameters_differ {
            self.model.parameters_changed();
        }
        // A state computed with profiles of other content than the cache's (a file changed on
        // disk since it was saved, here or in the process that serialized it) is not continued
        // with the content read now: the next evaluation rereads the files and compares.
        self.model.restored(state.0.profiles);
        Status::Ok
    }

    /// fmi2FreeFMUstate: whether the call is legal now (the C layer releases the memory).
    pub fn free_fmu_state(&mut self) -> Status {
        const CALL: Call = Call::FreeFMUstate;
        match self.require(CALL) {
            Ok(()) => Status::Ok,
            Err(status) => status,
        }
    }

    /// fmi2SerializedFMUstateSize: the exact length fmi2SerializeFMUstate writes.
    pub fn serialized_fmu_state_size(&mut self, state: &FmuState) -> Result<usize, Status> {
        self.require(Call::SerializedFMUstateSize)?;
        Ok(encode(&state.0).len())
    }

    /// fmi2SerializeFMUstate: `bytes` must have exactly the serialized size.
    pub fn serialize_fmu_state(&mut self, state: &FmuState, bytes: &mut [u8]) -> Status {
        const CALL: Call = Call::SerializeFMUstate;
        if let Err(status) = self.require(CALL) {
            return status;
        }
        match rules::copy_serialized(&encode(&state.0), bytes) {
            Ok(()) => Status::Ok,
            Err(reason) => self.log.fail(CALL, &reason),
        }
    }

    /// fmi2DeSerializeFMUstate: the state in `bytes`, after checking all of them (see
    /// [`decode`]); the instance itself is not changed.
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<FmuState, Status> {
        const CALL: Call = Call::DeSerializeFMUstate;
        self.require(CALL)?;
        decode(bytes)
            .map(FmuState)
            .map_err(|reason| self.log.fail(CALL, &format!("serializedState rejected: {reason}")))
    }
}
