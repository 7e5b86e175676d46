//! The FMU state (fmi2GetFMUstate, fmi2SerializeFMUstate, …): a copy of everything an instance
//! computes with, as plain values, and its byte encoding.
//!
//! What is saved is [`RunState`]: the state-machine mode, time and stop time, every variable's
//! value (the generated [`Values`], whole) and the model's internal state ([`ModelState`]). A
//! field added to any of these is saved and restored with no change here. Not saved, because
//! they are the master's settings for this instance rather than its state: the instance name,
//! the resource location, the logger and the debug-logging selection.
//!
//! Byte format (all integers little-endian), version [`FORMAT_VERSION`]:
//!
//! ```text
//! offset        size  content
//! 0             8     magic "WRCstate"
//! 8             2     format version (u16)
//! 10            1     length g of the GUID
//! 11            g     the GUID of the FMU that wrote it (modelDescription.xml)
//! 11 + g        4     payload length p (u32)
//! 15 + g        4     CRC-32 (IEEE) of bytes 0 .. 15 + g and of the payload
//! 19 + g        p     payload: RunState encoded by postcard (serde)
//! ```
//!
//! [`decode`] checks every part before it builds anything: a truncated, corrupted, foreign or
//! other-version byte string, or one from another FMU (GUID), is an error that says which.

use serde::{Deserialize, Serialize};

use super::instance::State;
use super::model_description::{Values, GUID};
use super::scene::ModelState;

/// First bytes of every serialized state of this FMU.
pub const MAGIC: [u8; 8] = *b"WRCstate";
/// The layout of the header and payload described in the module documentation.
pub const FORMAT_VERSION: u16 = 1;

/// Everything an instance computes with: what an FMU state holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunState {
    /// The state-machine mode (never `Fatal`: a fatal instance gives no state).
    pub mode: State,
    /// The instance's time: the end of the last step.
    pub time: f64,
    /// fmi2SetupExperiment's stop time, if one was given.
    pub stop_time: Option<f64>,
    /// Every variable: inputs, parameters and the last outputs.
    pub values: Values,
    /// The model's internal state carried from step to step.
    pub model_state: ModelState,
}

impl RunState {
    /// A freshly instantiated instance's: start values, time 0.
    pub fn instantiated() -> RunState {
        RunState {
            mode: State::Instantiated,
            time: 0.0,
            stop_time: None,
            values: Values::default(),
            model_state: ModelState::default(),
        }
    }
}

/// The opaque object behind an `fmi2FMUstate` pointer.
#[derive(Debug, Clone, PartialEq)]
pub struct FmuState(pub RunState);

/// Bytes before the GUID: magic, version, GUID length.
const PREFIX: usize = MAGIC.len() + 2 + 1;
/// Bytes between the GUID and the payload: payload length, CRC-32.
const LENGTHS: usize = 4 + 4;

/// The serialized bytes of `state` (their length is exactly what fmi2SerializedFMUstateSize
/// reports: the encoding is deterministic).
pub fn encode(state: &RunState) -> Vec<u8> {
    let payload = postcard::to_stdvec(state).expect("plain values always encode");
    let guid = GUID.as_bytes();
    let mut bytes = Vec::with_capacity(PREFIX + guid.len() + LENGTHS + payload.len());
    bytes.extend_from_slice(&MAGIC);
    bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    bytes.push(u8::try_from(guid.len()).expect("a GUID is short"));
    bytes.extend_from_slice(guid);
    bytes.extend_from_slice(&u32::try_from(payload.len()).expect("a state is small").to_le_bytes());
    let checksum = checksum(&bytes, &payload);
    bytes.extend_from_slice(&checksum.to_le_bytes());
    bytes.extend_from_slice(&payload);
    bytes
}

fn checksum(header: &[u8], payload: &[u8]) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(header);
    hasher.update(payload);
    hasher.finalize()
}

/// The state in `bytes`, or why they are not a state this FMU wrote.
pub fn decode(bytes: &[u8]) -> Result<RunState, String> {
    let size = bytes.len();
    let truncated = |needed: usize| format!("truncated: {size} bytes, the state needs at least {needed}");
    if !MAGIC.starts_with(&bytes[..size.min(MAGIC.len())]) {
        return Err("not a serialized state of this FMU (wrong magic bytes)".to_owned());
    }
    if size < PREFIX {
        return Err(truncated(PREFIX));
    }
    let version = u16::from_le_bytes([bytes[8], bytes[9]]);
    if version != FORMAT_VERSION {
        return Err(format!("format version {version}; this FMU reads version {FORMAT_VERSION}"));
    }
    let guid_end = PREFIX + usize::from(bytes[10]);
    let payload_start = guid_end + LENGTHS;
    if size < payload_start {
        return Err(truncated(payload_start));
    }
    let guid = String::from_utf8_lossy(&bytes[PREFIX..guid_end]);
    if guid != GUID {
        return Err(format!("written by an FMU with GUID {guid}, not by this one ({GUID})"));
    }
    let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let payload_length = usize::try_from(word(guid_end)).unwrap_or(usize::MAX);
    let expected_size = payload_start.saturating_add(payload_length);
    if size < expected_size {
        return Err(truncated(expected_size));
    }
    if size > expected_size {
        return Err(format!("{size} bytes, but the header announces {expected_size}: trailing bytes"));
    }
    let payload = &bytes[payload_start..];
    if checksum(&bytes[..guid_end + 4], payload) != word(guid_end + 4) {
        return Err("corrupted: the CRC-32 checksum does not match".to_owned());
    }
    let state: RunState = match postcard::take_from_bytes(payload) {
        Ok((state, [])) => state,
        Ok(_) => return Err("corrupted: the payload has bytes after the state".to_owned()),
        Err(error) => return Err(format!("corrupted: the payload does not decode ({error})")),
    };
    if state.mode == State::Fatal {
        return Err("corrupted: a state cannot be in mode fatal".to_owned());
    }
    Ok(state)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stepping_state() -> RunState {
        let mut state = RunState::instantiated();
        state.mode = State::StepComplete;
        state.time = 0.125;
        state.stop_time = Some(2.0);
        state.values.inputs.creepage_lateral = -1.5e-3;
        state.values.inputs.spin_creepage = f64::from_bits(0x7ff8_0000_dead_beef); // a NaN payload
        state.values.outputs.force_longitudinal = -1234.5;
        state
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let state = stepping_state();
        let bytes = encode(&state);
        let decoded = decode(&bytes).unwrap();
        assert_eq!(decoded.values.inputs.spin_creepage.to_bits(), 0x7ff8_0000_dead_beef);
        assert_eq!(encode(&decoded), bytes, "re-encoding gives the same bytes");
        assert_eq!(&bytes[..8], b"WRCstate");
        assert_eq!(bytes[10] as usize, GUID.len());
        // Compact: postcard writes each Real in 8 bytes and each Integer as a varint (≤ 5), plus
        // the header (≤ 64 bytes with the GUID) and the run data (time, stop time, mode, the
        // relaxed forces: ≤ 48 bytes).
        let bound = 8 * crate::fmi::model_description::VARIABLES.len() + 64 + 48;
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
        assert_eq!(decode(&version).unwrap_err(), "format version 2; this FMU reads version 1");
        let mut guid = bytes.clone();
        guid[12] = b'0';
        let error = decode(&guid).unwrap_err();
        assert!(error.starts_with("written by an FMU with GUID {0"), "{error}");
        let mut trailing = bytes.clone();
        trailing.push(0);
        assert!(decode(&trailing).unwrap_err().contains("trailing bytes"));
    }
}
