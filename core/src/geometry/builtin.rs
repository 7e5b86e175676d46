//! The built-in profiles: the Manchester contact benchmark's files, compiled into the library so
//! that users need no file to run the benchmark (provenance: `data/profiles/README.md`).

use super::profile_file::{parse_profile, ProfileError, ProfileFormat, ProfilePoints};

/// The names [`builtin_profile`] knows, with their files' text.
const BUILTINS: [(&str, &str); 2] = [
    ("MBench_S1002", include_str!("../../../data/profiles/MBench_S1002_v3.prw")),
    ("MBench_UIC60", include_str!("../../../data/profiles/MBench_UIC60_v3.prr")),
];

/// The names of the built-in profiles: S1002 wheel, UIC60 rail (canted 1:40).
pub const BUILTIN_PROFILE_NAMES: [&str; 2] = [BUILTINS[0].0, BUILTINS[1].0];

/// The built-in profile `name`'s points; an unknown name is an error listing the known ones.
///
/// ```
/// use wheel_rail_contact::geometry::{builtin_profile, BUILTIN_PROFILE_NAMES};
///
/// assert_eq!(BUILTIN_PROFILE_NAMES, ["MBench_S1002", "MBench_UIC60"]);
/// // S1002 (EN 13715): y from the flange back (−70 mm) to the field side, z = 0 on the running circle.
/// let wheel = builtin_profile("MBench_S1002").unwrap();
/// let (first, last) = (wheel.lateral[0], wheel.lateral[wheel.lateral.len() - 1]);
/// assert!(first < -0.069 && last >= 0.06, "{first} … {last}");
/// let error = builtin_profile("S1002").unwrap_err();
/// assert_eq!(error.to_string(), "no built-in profile `S1002` (known: MBench_S1002, MBench_UIC60)");
/// ```
pub fn builtin_profile(name: &str) -> Result<ProfilePoints, ProfileError> {
    let (_, text) = BUILTINS.iter().find(|(known, _)| *known == name).ok_or_else(|| {
        ProfileError::whole(format!("no built-in profile `{name}` (known: {})", BUILTIN_PROFILE_NAMES.join(", ")))
    })?;
    parse_profile(text, ProfileFormat::Simpack)
}
