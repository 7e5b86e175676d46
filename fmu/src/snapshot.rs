//! The contact FMU's part of an FMU state (fmi2GetFMUstate, fmi2SerializeFMUstate, …): what the
//! slave layer's [`FmuState`] holds beside the mode, time and stop time, as plain values, and its
//! byte encoding.
//!
//! What is saved is a [`Snapshot`]: the state-machine mode, time and stop time (the slave
//! layer's), every variable's value (the generated [`Values`], whole, and the String parameters,
//! [`Strings`]), the scene's state (relaxed forces, the exact theory's warm start:
//! [`SceneState`]) and the wheel's with profiles (each patch's, [`WheelState`]): a
//! [`ContactState`]. A field added to any of these is saved and restored with no change here.
//! Not saved, because they are the master's settings for this instance rather than its state:
//! the instance name, the resource location, the logger and the debug-logging selection.
//!
//! Byte format: the slave layer's ([`fmi2_slave::state_format`]: magic `WRCstate`, version
//! [`FORMAT_VERSION`], the variable-layout tag, the GUID, a CRC-32) around the [`Snapshot`]
//! encoded by postcard (serde). [`decode`] checks every part before it builds anything, then
//! the snapshot's sense (the slave layer's: a live mode, the times; then `check_state`).

use fmi2_slave::instance::FmuState;
use serde::{Deserialize, Serialize};

use crate::mode::Mode;
use crate::model::Instance;
use crate::model_description::{Causality, Strings, Values, VARIABLES};
use crate::profiles::ProfileDigest;
use wheel_rail_contact::scene::SceneState;
use wheel_rail_contact::wheel::WheelState;

/// First bytes of every serialized state of this FMU.
pub const MAGIC: [u8; 8] = *b"WRCstate";
/// The layout of the header and payload described in the module documentation.
pub const FORMAT_VERSION: u16 = 7;

/// Everything an instance computes with beside its mode and times.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactState {
    /// Every variable: inputs, parameters and the last outputs.
    pub values: Values,
    /// The String parameters (the profiles).
    pub strings: Strings,
    /// The scene's state carried from step to step: the relaxed forces (`creep_relaxation =
    /// on`) and the model's memory (the exact theory's warm start), so that a restored instance
    /// continues bit for bit ([`SceneState`]).
    pub scene: SceneState,
    /// The wheel's state with `contact_geometry = profiles`: each patch's scene state and where
    /// it was on the rail ([`WheelState`]).
    pub wheel: WheelState,
    /// The digest of the profiles the outputs were computed with (`contact_geometry =
    /// profiles`, once evaluated): restored where a profile file's content has since changed,
    /// the state is refused at the next evaluation rather than continued with other profiles.
    pub profiles: Option<ProfileDigest>,
}

impl ContactState {
    /// A freshly instantiated instance's: the start values.
    pub fn start() -> ContactState {
        ContactState {
            values: Values::default(),
            strings: Strings::default(),
            scene: SceneState::default(),
            wheel: WheelState::default(),
            profiles: None,
        }
    }
}

/// What an FMU state of this FMU holds: the mode, time and stop time, then the [`ContactState`]
/// (encoded in this order: postcard writes a struct as its fields one after the other).
pub type Snapshot = FmuState<ContactState>;

/// The serialized bytes of `state` (their length is exactly what fmi2SerializedFMUstateSize
/// reports: the encoding is deterministic).
pub fn encode(state: &Snapshot) -> Vec<u8> {
    Instance::encode_state(state)
}

/// The state in `bytes`, or why they are not a state this FMU wrote.
pub fn decode(bytes: &[u8]) -> Result<Snapshot, String> {
    Instance::decode_state(bytes)
}

/// The payload of `state` ([`crate::model::ContactModel`]'s `Model::encode`).
pub(crate) fn encode_payload(state: &Snapshot) -> Vec<u8> {
    postcard::to_stdvec(state).expect("plain values always encode")
}

/// The inverse of [`encode_payload`], every byte used.
pub(crate) fn decode_payload(payload: &[u8]) -> Result<Snapshot, String> {
    match postcard::take_from_bytes(payload) {
        Ok((state, [])) => Ok(state),
        Ok(_) => Err("corrupted: the payload has bytes after the state".to_owned()),
        Err(error) => Err(format!("corrupted: the payload does not decode ({error})")),
    }
}

/// The checks the setters apply to what a state holds, for a state whose bytes are intact but
/// whose content did not come from this FMU (a forged or hand-edited one), after the slave
/// layer's of its mode and times: finite outputs (an instance only ever keeps finite ones) and
/// a valid scene state. Inputs and parameters may hold any value, as after
/// fmi2SetReal/fmi2SetInteger: an invalid one is reported by the next evaluation, naming it.
pub(crate) fn check_state(state: &ContactState, _mode: Mode) -> Result<(), String> {
    // The outputs, and the locals (the relaxed forces and their rates).
    for variable in
        VARIABLES.iter().filter(|variable| matches!(variable.causality, Causality::Output | Causality::Local))
    {
        if let Some(value) = state.values.real(variable.value_reference).filter(|value| !value.is_finite()) {
            return Err(format!("{} = {value} is invalid: an output or local is always finite", variable.name));
        }
    }
    state.scene.validate().map_err(|error| error.to_string())?;
    state.wheel.validate().map_err(|error| error.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::model_description::GUID;

    fn stepping_state() -> Snapshot {
        let mut state = Snapshot::instantiated(ContactState::start());
        state.mode = Mode::StepComplete;
        state.time = 0.125;
        state.stop_time = Some(2.0);
        state.model.values.inputs.creepage_lateral = -1.5e-3;
        state.model.values.inputs.spin_creepage = f64::from_bits(0x7ff8_0000_dead_beef); // a NaN payload
        state.model.values.outputs.force_longitudinal = -1234.5;
        state
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let state = stepping_state();
        let bytes = encode(&state);
        let decoded = decode(&bytes).unwrap();
        assert_eq!(decoded.model.values.inputs.spin_creepage.to_bits(), 0x7ff8_0000_dead_beef);
        assert_eq!(encode(&decoded), bytes, "re-encoding gives the same bytes");
        assert_eq!(&bytes[..8], b"WRCstate");
        assert_eq!(bytes[18] as usize, GUID.len());
        // Compact: postcard writes each Real in 8 bytes and each Integer as a varint (≤ 5), plus
        // the header (≤ 72 bytes with the GUID) and the run data (time, stop time, mode, the
        // relaxed forces: ≤ 48 bytes).
        let bound = 8 * crate::model_description::VARIABLES.len() + 72 + 48;
        assert!(bytes.len() <= bound, "{} > {bound}", bytes.len());
    }

    #[test]
    fn every_truncation_and_every_single_bit_flip_is_rejected() {
        let bytes = encode(&stepping_state());
        for length in 0..bytes.len() {
            let error = decode(&bytes[..length]).unwrap_err();
            assert!(error.starts_with("truncated: "), "{length}: {error}");
        }
        for position in 0..bytes.len() {
            for bit in 0..8 {
                let mut corrupted = bytes.clone();
                corrupted[position] ^= 1 << bit;
                assert!(decode(&corrupted).is_err(), "flip of bit {bit} of byte {position} accepted");
            }
        }
    }

    #[test]
    fn foreign_version_guid_and_trailing_bytes_are_named() {
        let bytes = encode(&stepping_state());
        assert_eq!(
            decode(b"PK\x03\x04 a zip file").unwrap_err(),
            "not a serialized state of this FMU (wrong magic bytes)"
        );
        let mut version = bytes.clone();
        version[8] = 2;
        assert_eq!(decode(&version).unwrap_err(), "format version 2; this FMU reads version 7");
        let mut layout = bytes.clone();
        layout[10] ^= 1;
        let error = decode(&layout).unwrap_err();
        assert!(error.starts_with("variable-layout tag 0x") && error.contains("this FMU's variables have tag"));
        let mut guid = bytes.clone();
        guid[20] = b'0';
        let error = decode(&guid).unwrap_err();
        assert!(error.starts_with("written by an FMU with GUID {0"), "{error}");
        let mut trailing = bytes.clone();
        trailing.push(0);
        assert!(decode(&trailing).unwrap_err().contains("trailing bytes"));
    }
}
