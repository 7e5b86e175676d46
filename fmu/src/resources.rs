//! The FMU's `resources/` directory from the resource location a master passes to
//! fmi2Instantiate, and the files a parameter names relative to it.
//!
//! FMI 2.0 (section 2.1.5, fmi2Instantiate) passes `fmuResourceLocation` as a URI (RFC 3986)
//! with the `file` scheme. Masters write it in every form RFC 8089 allows and some it does not:
//! `file:///home/u/x/resources`, `file:/home/u/x/resources`, `file://localhost/…`, percent-encoded
//! characters (`%20`), Windows drive letters (`file:///C:/x`, `file:/C:/x`, and `file://C:/x`,
//! where the drive letter stands in the host's place), with or without a trailing slash. They are read
//! here as RFC 8089 describes them (its appendix E lists the non-standard forms), into a path of
//! the platform the binary runs on; the percent-encoding is undone by the `percent-encoding`
//! crate. (The `url` crate would parse them too, but brings Unicode host names' tables into the
//! binary for a job that has no host name.)
//!
//! A relative file name in a parameter (a profile) is looked up in the resources directory
//! first, so that files packed into the FMU are found wherever the master runs, then in the
//! master's working directory, as before.

use std::path::{Path, PathBuf};

/// The directory `location` names, or why it names none.
pub fn resource_directory(location: &str) -> Result<PathBuf, String> {
    let Some(rest) = location.get(..5).filter(|scheme| scheme.eq_ignore_ascii_case("file:")).map(|_| &location[5..])
    else {
        return Err(if has_scheme(location) {
            format!("the resource location \"{location}\" is not a file URI")
        } else {
            format!("the resource location \"{location}\" is not a URI (no scheme)")
        });
    };
    let path = match rest.strip_prefix("//") {
        Some(authority_and_path) => {
            let (authority, path) =
                authority_and_path.split_at(authority_and_path.find('/').unwrap_or(authority_and_path.len()));
            if authority.is_empty() || authority.eq_ignore_ascii_case("localhost") {
                path.to_owned()
            } else if is_drive(authority) {
                // `file://C:/x`: the drive letter in the host's place (RFC 8089, E.2).
                format!("/{authority}{path}")
            } else {
                return remote(location, authority, path);
            }
        }
        None if rest.starts_with('/') => rest.to_owned(),
        None => return Err(format!("the resource location \"{location}\" has no absolute path")),
    };
    Ok(local_path(&decoded(location, &path)?))
}

/// `path` with its percent-encoding undone; an error naming `location` if that is not UTF-8.
fn decoded(location: &str, path: &str) -> Result<String, String> {
    percent_encoding::percent_decode_str(path)
        .decode_utf8()
        .map(|text| text.into_owned())
        .map_err(|_| format!("the resource location \"{location}\" is not UTF-8 once percent-decoded"))
}

/// `scheme:` at the start (RFC 3986: a letter, then letters, digits, `+`, `-`, `.`).
fn has_scheme(text: &str) -> bool {
    let Some((scheme, _)) = text.split_once(':') else { return false };
    let mut characters = scheme.chars();
    characters.next().is_some_and(|c| c.is_ascii_alphabetic())
        && characters.all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
}

/// `C:` or `C|` (a drive letter as RFC 8089's appendix E writes it).
fn is_drive(text: &str) -> bool {
    let bytes = text.as_bytes();
    bytes.len() == 2 && bytes[0].is_ascii_alphabetic() && (bytes[1] == b':' || bytes[1] == b'|')
}

/// A host other than this machine: a UNC path on Windows, no local directory elsewhere.
#[cfg(windows)]
fn remote(location: &str, host: &str, path: &str) -> Result<PathBuf, String> {
    Ok(PathBuf::from(format!(r"\\{host}{}", decoded(location, path)?.replace('/', r"\"))))
}

#[cfg(not(windows))]
fn remote(location: &str, _host: &str, _path: &str) -> Result<PathBuf, String> {
    Err(format!("the resource location \"{location}\" names no local directory (a remote host)"))
}

/// The decoded URI path as this platform's path: on Windows `/C:/x` and `/C|/x` become `C:\x`.
#[cfg(windows)]
fn local_path(path: &str) -> PathBuf {
    let trimmed = path.strip_prefix('/').filter(|rest| rest.get(..2).is_some_and(is_drive)).unwrap_or(path);
    let mut text = trimmed.replace('/', r"\");
    if text.as_bytes().get(1) == Some(&b'|') {
        text.replace_range(1..2, ":");
    }
    PathBuf::from(text)
}

#[cfg(not(windows))]
fn local_path(path: &str) -> PathBuf {
    PathBuf::from(path)
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
            ("file:resources", "has no absolute path"),
            ("file:///home/u/%FF", "is not UTF-8"),
        ] {
            let error = resource_directory(location).unwrap_err();
            assert!(error.contains(&format!("\"{location}\"")) && error.contains(reason), "{error}");
        }
        #[cfg(unix)]
        for remote in ["file://server/share", "file://ab/share", "file://h:8080/share"] {
            // Two letters or a letter and a port are hosts, not drive letters.
            assert!(resource_directory(remote).unwrap_err().contains("names no local directory"), "{remote}");
        }
        // A scheme starts with a letter: "1http:" is no scheme at all.
        assert!(resource_directory("1http://x").unwrap_err().contains("is not a URI"));
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
