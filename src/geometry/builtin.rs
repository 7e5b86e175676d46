//! The built-in profiles: the Manchester contact benchmark's files, compiled into the library so
//! that users need no file to run the benchmark (provenance: `data/profiles/README.md`).

use super::profile_file::{parse_profile, ProfileError, ProfileFormat, ProfilePoints};

/// The names [`builtin_profile`] knows, with their files' text.
const BUILTINS: [(&str, &str); 2] = [
    ("MBench_S1002", include_str!("../../data/profiles/MBench_S1002_v3.prw")),
    ("MBench_UIC60", include_str!("../../data/profiles/MBench_UIC60_v3.prr")),
];

/// The names of the built-in profiles: S1002 wheel, UIC60 rail (canted 1:40).
pub const BUILTIN_PROFILE_NAMES: [&str; 2] = [BUILTINS[0].0, BUILTINS[1].0];

/// The built-in profile `name`'s points; an unknown name is an error listing the known ones.
pub fn builtin_profile(name: &str) -> Result<ProfilePoints, ProfileError> {
    let (_, text) = BUILTINS.iter().find(|(known, _)| *known == name).ok_or_else(|| {
        ProfileError::whole(format!("no built-in profile `{name}` (known: {})", BUILTIN_PROFILE_NAMES.join(", ")))
    })?;
    parse_profile(text, ProfileFormat::Simpack)
}
