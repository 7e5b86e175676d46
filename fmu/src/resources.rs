//! The FMU's `resources/` directory from the resource location a master passes to
//! fmi2Instantiate, and the files a parameter names relative to it.
//!
//! FMI 2.0 (section 2.1.5, fmi2Instantiate) passes `fmuResourceLocation` as a URI (RFC 3986)
//! with the `file` scheme. Masters write it in every form RFC 8089 allows and some it does not:
//! `file:///home/u/x/resources`, `file:/home/u/x/resources`, `file://localhost/…`, percent-encoded
//! characters (`%20`), Windows drive letters (`file:///C:/x`, `file:/C:/x`, and `file://C:/x`,
//! where the drive letter stands in the host's place), with or without a trailing slash. The
//! [`url`] crate reads RFC 8089 and turns it into a path of the platform the binary runs on; the
//! drive letter in the host's place is repaired first.
//!
//! A relative file name in a parameter (a profile) is looked up in the resources directory
//! first, so that files packed into the FMU are found wherever the master runs, then in the
//! master's working directory, as before.

use std::path::{Path, PathBuf};

/// The directory `location` names, or why it names none.
pub fn resource_directory(location: &str) -> Result<PathBuf, String> {
    let repaired = drive_letter_as_host(location);
    let url = url::Url::parse(repaired.as_deref().unwrap_or(location))
        .map_err(|e| format!("the resource location \"{location}\" is not a URI ({e})"))?;
    if url.scheme() != "file" {
        return Err(format!("the resource location \"{location}\" is not a file URI"));
    }
    url.to_file_path().map_err(|()| format!("the resource location \"{location}\" names no local directory"))
}

/// `file://C:/x` → `file:///C:/x`: a drive letter where the host belongs (RFC 8089 appendix E.2
/// lists it among the forms in use).
fn drive_letter_as_host(location: &str) -> Option<String> {
    let rest = location.get(..7).filter(|scheme| scheme.eq_ignore_ascii_case("file://")).map(|_| &location[7..])?;
    let bytes = rest.as_bytes();
    let drive = bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && (bytes[1] == b':' || bytes[1] == b'|');
    (drive && (bytes.len() == 2 || bytes[2] == b'/' || bytes[2] == b'\\')).then(|| format!("file:///{rest}"))
}

/// Where to read the file a parameter names: an absolute path as it is; a relative one in the
/// resources directory if it exists there, else relative to the working directory.
pub fn file_path(name: &str, resources: Option<&Path>) -> PathBuf {
    let path = Path::new(name);
    if path.is_absolute() {
        return path.to_path_buf();
    }
    match resources.map(|directory| directory.join(path)) {
        Some(packed) if packed.is_file() => packed,
        _ => path.to_path_buf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn every_file_uri_form_masters_pass_names_the_directory() {
        let expected = Path::new("/home/u/my model/resources");
        for location in [
            "file:///home/u/my%20model/resources",
            "file:///home/u/my%20model/resources/",
            "file:/home/u/my%20model/resources",
            "file://localhost/home/u/my%20model/resources",
            "FILE:///home/u/my%20model/resources",
        ] {
            let directory = resource_directory(location).unwrap();
            assert_eq!(
                directory.components().collect::<Vec<_>>(),
                expected.components().collect::<Vec<_>>(),
                "{location}"
            );
        }
        // A drive letter in the host's place is read as a path (on Unix it stays a path
        // component; on Windows it is the drive).
        assert_eq!(resource_directory("file://C:/fmu/resources").unwrap(), Path::new("/C:/fmu/resources"));
    }

    #[cfg(windows)]
    #[test]
    fn every_file_uri_form_masters_pass_names_the_directory() {
        let expected = Path::new(r"C:\Users\u\my model\resources");
        for location in [
            "file:///C:/Users/u/my%20model/resources",
            "file:/C:/Users/u/my%20model/resources/",
            "file://C:/Users/u/my%20model/resources",
            "file:///C|/Users/u/my%20model/resources",
            "file://localhost/C:/Users/u/my%20model/resources",
        ] {
            let directory = resource_directory(location).unwrap();
            assert_eq!(
                directory.components().collect::<Vec<_>>(),
                expected.components().collect::<Vec<_>>(),
                "{location}"
            );
        }
        assert_eq!(
            resource_directory(r"file://server/share/resources").unwrap(),
            Path::new(r"\\server\share\resources")
        );
    }

    #[test]
    fn other_locations_are_errors_naming_them() {
        for (location, reason) in [
            ("/home/u/resources", "is not a URI"),
            ("http://example.com/resources", "is not a file URI"),
            ("", "is not a URI"),
        ] {
            let error = resource_directory(location).unwrap_err();
            assert!(error.contains(&format!("\"{location}\"")) && error.contains(reason), "{error}");
        }
        #[cfg(unix)]
        assert!(resource_directory("file://server/share").unwrap_err().contains("names no local directory"));
    }

    #[test]
    fn a_relative_name_is_read_from_the_resources_first() {
        let resources = std::env::temp_dir().join(format!("wheel_rail_contact_resources_{}", std::process::id()));
        std::fs::create_dir_all(resources.join("profiles")).unwrap();
        std::fs::write(resources.join("profiles/worn.prw"), "").unwrap();
        assert_eq!(file_path("profiles/worn.prw", Some(&resources)), resources.join("profiles/worn.prw"));
        // Not packed: relative to the working directory, as without resources.
        assert_eq!(file_path("other.prw", Some(&resources)), Path::new("other.prw"));
        assert_eq!(file_path("profiles/worn.prw", None), Path::new("profiles/worn.prw"));
        let absolute = resources.join("profiles/worn.prw");
        assert_eq!(file_path(absolute.to_str().unwrap(), Some(Path::new("/elsewhere"))), absolute);
        std::fs::remove_dir_all(&resources).unwrap();
    }
}
