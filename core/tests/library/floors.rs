//! The core's floors (ARCHITECTURE.md): each module imports only modules on its own floor or
//! below — the basic types, then `hertz`, `models`, `geometry`, `scene`, `wheel`, and on top
//! `reference_cases` (published cases for tests and users, in the models' terms) — so
//! that no import runs up a floor and no two floors import each other. Read from the source: every
//! `crate::module` path and every name re-exported at the crate's root (`use crate::{Polach, …}`),
//! outside comments and unit tests.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The floors, bottom up; a module not listed is on the ground floor with the basic types.
const FLOORS: [&str; 6] = ["hertz", "models", "geometry", "scene", "wheel", "reference_cases"];

fn floor(module: &str) -> usize {
    FLOORS.iter().position(|&m| m == module).map_or(0, |index| index + 1)
}

fn source_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level module a source file belongs to (`geometry/contact.rs` → `geometry`).
fn module_of(file: &Path) -> String {
    let relative = file.strip_prefix(source_root()).unwrap();
    let first = relative.components().next().unwrap().as_os_str().to_str().unwrap();
    first.trim_end_matches(".rs").to_owned()
}

fn rust_files(directory: &Path, files: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(directory).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
}

/// The names `lib.rs` re-exports, with the module each comes from (`Polach` → `models`).
fn root_names() -> HashMap<String, String> {
    let lib = std::fs::read_to_string(source_root().join("lib.rs")).unwrap();
    let mut names = HashMap::new();
    for line in lib.lines().filter_map(|l| l.strip_prefix("pub use ")) {
        let module = line.split("::").next().unwrap().to_owned();
        let list = line.split_once("::").unwrap().1;
        let items = list.rsplit("::").next().unwrap().trim_matches(|c| "{};".contains(c));
        for name in items.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            names.insert(name.to_owned(), module.clone());
        }
    }
    names
}

/// The modules a file's code names through `crate::`, with the line (comments and the unit tests
/// after `#[cfg(test)]` left out).
fn imports(text: &str, root: &HashMap<String, String>) -> Vec<(String, String)> {
    let code = text.lines().take_while(|l| l.trim() != "#[cfg(test)]").filter(|l| !l.trim_start().starts_with("//"));
    let mut found = Vec::new();
    for line in code {
        for (at, _) in line.match_indices("crate::") {
            let rest = &line[at + "crate::".len()..];
            let names: Vec<&str> = if let Some(list) = rest.strip_prefix('{') {
                list.split('}').next().unwrap().split(',').map(|n| n.trim().split("::").next().unwrap()).collect()
            } else {
                vec![rest.split(|c: char| !(c.is_alphanumeric() || c == '_')).next().unwrap()]
            };
            for name in names.into_iter().filter(|n| !n.is_empty()) {
                let module = root.get(name).cloned().unwrap_or_else(|| name.to_owned());
                found.push((module, line.trim().to_owned()));
            }
        }
    }
    found
}

#[test]
fn no_import_runs_up_a_floor() {
    let root = root_names();
    assert_eq!(root.get("Polach").map(String::as_str), Some("models"), "lib.rs's re-exports read");
    let mut files = Vec::new();
    rust_files(&source_root(), &mut files);
    let mut upward = Vec::new();
    for file in files.iter().filter(|f| f.file_name().unwrap() != "lib.rs") {
        let module = module_of(file);
        for (imported, line) in imports(&std::fs::read_to_string(file).unwrap(), &root) {
            if floor(&imported) > floor(&module) {
                upward.push(format!("{} ({module}) imports {imported}: {line}", file.display()));
            }
        }
    }
    assert!(upward.is_empty(), "imports that run up a floor:\n{}", upward.join("\n"));
}

/// The reader finds what it must: an upward import written each way is caught.
#[test]
fn the_reader_sees_paths_and_root_names() {
    let root = root_names();
    let seen = |text: &str| imports(text, &root).into_iter().map(|(m, _)| m).collect::<Vec<_>>();
    assert_eq!(seen("use crate::scene::Scene;"), ["scene"]);
    assert_eq!(seen("use crate::{ExactTheory, InvalidInput};"), ["models", "invalid_input"]);
    assert_eq!(seen("    crate::hertz::table::prepare();"), ["hertz"]);
    assert!(seen("// use crate::wheel::WheelState;").is_empty());
    assert!(seen("#[cfg(test)]\nmod tests {\n    use crate::wheel::WheelState;\n}").is_empty());
    assert!(
        floor("wheel") > floor("scene") && floor("scene") > floor("geometry") && floor("hertz") > floor("numerics")
    );
}
