//! The byte format of a serialized FMU state (fmi2SerializeFMUstate), one for every FMU of the
//! workspace: a header that says whose state it is and a CRC-32 over it and the payload, which
//! the FMU encodes as it likes. Decoding checks every part before the payload is read, so a
//! truncated, corrupted (any single flipped bit), foreign, other-version, other-layout or
//! other-FMU byte string is an error that says which; what the payload means is checked by the
//! FMU after (its sense checks).
//!
//! ```text
//! offset        size  content (integers little-endian)
//! 0             8     magic: the FMU's own 8 bytes (`b"WRCstate"`, `b"WSTstate"`)
//! 8             2     format version (u16): the layout of this header and of the FMU's payload
//! 10            8     variable-layout tag (u64): a hash of every variable's name, value
//!                     reference, causality and type, generated from modelDescription.xml, so a
//!                     state written with another variable layout is never read as this one's
//! 18            1     length g of the GUID
//! 19            g     the GUID of the FMU that wrote it
//! 19 + g        4     payload length p (u32)
//! 23 + g        4     CRC-32 (IEEE) of bytes 0 .. 23 + g and of the payload
//! 27 + g        p     payload
//! ```

/// What identifies the states of one FMU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateFormat {
    pub magic: [u8; 8],
    pub version: u16,
    pub layout_tag: u64,
    pub guid: &'static str,
}

/// Bytes before the GUID: magic, version, layout tag, GUID length.
const PREFIX: usize = 8 + 2 + 8 + 1;
/// Bytes between the GUID and the payload: payload length, CRC-32.
const LENGTHS: usize = 4 + 4;

impl StateFormat {
    /// `payload` behind this FMU's header.
    pub fn encode(&self, payload: &[u8]) -> Vec<u8> {
        let guid = self.guid.as_bytes();
        let mut bytes = Vec::with_capacity(PREFIX + guid.len() + LENGTHS + payload.len());
        bytes.extend_from_slice(&self.magic);
        bytes.extend_from_slice(&self.version.to_le_bytes());
        bytes.extend_from_slice(&self.layout_tag.to_le_bytes());
        bytes.push(u8::try_from(guid.len()).expect("a GUID is short"));
        bytes.extend_from_slice(guid);
        bytes.extend_from_slice(&u32::try_from(payload.len()).expect("a state is small").to_le_bytes());
        let checksum = checksum(&bytes, payload);
        bytes.extend_from_slice(&checksum.to_le_bytes());
        bytes.extend_from_slice(payload);
        bytes
    }

    /// The payload of `bytes`, or why they are not a state this FMU wrote.
    pub fn decode<'a>(&self, bytes: &'a [u8]) -> Result<&'a [u8], String> {
        let size = bytes.len();
        let truncated = |needed: usize| format!("truncated: {size} bytes, the state needs at least {needed}");
        if !self.magic.starts_with(&bytes[..size.min(self.magic.len())]) {
            return Err("not a serialized state of this FMU (wrong magic bytes)".to_owned());
        }
        if size < PREFIX {
            return Err(truncated(PREFIX));
        }
        let version = u16::from_le_bytes([bytes[8], bytes[9]]);
        if version != self.version {
            return Err(format!("format version {version}; this FMU reads version {}", self.version));
        }
        let tag = u64::from_le_bytes(bytes[10..18].try_into().expect("8 bytes"));
        if tag != self.layout_tag {
            return Err(format!(
                "variable-layout tag {tag:#018x}; this FMU's variables have tag {:#018x}",
                self.layout_tag
            ));
        }
        let guid_end = PREFIX + usize::from(bytes[18]);
        let payload_start = guid_end + LENGTHS;
        if size < payload_start {
            return Err(truncated(payload_start));
        }
        let guid = String::from_utf8_lossy(&bytes[PREFIX..guid_end]);
        if guid != self.guid {
            return Err(format!("written by an FMU with GUID {guid}, not by this one ({})", self.guid));
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
        Ok(payload)
    }
}

fn checksum(header: &[u8], payload: &[u8]) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(header);
    hasher.update(payload);
    hasher.finalize()
}

#[cfg(test)]
mod tests {
    use super::StateFormat;

    const FORMAT: StateFormat =
        StateFormat { magic: *b"TSTstate", version: 3, layout_tag: 0x0123_4567_89ab_cdef, guid: "{guid-1}" };

    #[test]
    fn the_payload_comes_back_and_every_truncation_and_bit_flip_is_refused() {
        let bytes = FORMAT.encode(b"some payload");
        assert_eq!(FORMAT.decode(&bytes).unwrap(), b"some payload");
        // An empty payload is a payload; cut at the GUID's length byte, the whole header's
        // length is what is missing.
        assert_eq!(FORMAT.decode(&FORMAT.encode(b"")).unwrap(), b"");
        assert_eq!(FORMAT.decode(&bytes[..19]).unwrap_err(), "truncated: 19 bytes, the state needs at least 35");
        assert_eq!(bytes.len(), 19 + 8 + 8 + 12);
        assert_eq!(&bytes[..8], b"TSTstate");
        for length in 0..bytes.len() {
            let error = FORMAT.decode(&bytes[..length]).unwrap_err();
            assert!(error.starts_with("truncated: ") || length < 8 && error.contains("magic"), "{length}: {error}");
        }
        for position in 0..bytes.len() {
            for bit in 0..8 {
                let mut corrupted = bytes.clone();
                corrupted[position] ^= 1 << bit;
                assert!(FORMAT.decode(&corrupted).is_err(), "flip of bit {bit} of byte {position} accepted");
            }
        }
    }

    #[test]
    fn another_fmus_version_layout_or_guid_is_named() {
        let bytes = FORMAT.encode(b"x");
        let other = |format: StateFormat| format.decode(&bytes).unwrap_err();
        assert_eq!(
            other(StateFormat { magic: *b"WRCstate", ..FORMAT }),
            "not a serialized state of this FMU (wrong magic bytes)"
        );
        assert_eq!(other(StateFormat { version: 4, ..FORMAT }), "format version 3; this FMU reads version 4");
        assert!(other(StateFormat { layout_tag: 1, ..FORMAT }).starts_with("variable-layout tag 0x0123456789abcdef;"));
        assert_eq!(
            other(StateFormat { guid: "{guid-2}", ..FORMAT }),
            "written by an FMU with GUID {guid-1}, not by this one ({guid-2})"
        );
        let mut trailing = bytes.clone();
        trailing.push(0);
        assert!(FORMAT.decode(&trailing).unwrap_err().contains("trailing bytes"));
    }
}
