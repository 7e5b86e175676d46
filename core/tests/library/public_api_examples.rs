//! Every public function of the core is called in a doc example of its own file (issue 31: doc
//! examples cover the public API, with asserted values). A function no example calls fails
//! here, named with its file; the modules not yet covered are listed in `NOT_YET_COVERED`.

use std::path::{Path, PathBuf};

/// Source files (relative to `src/`) without examples yet. Empty: every file is covered; it stays
/// so.
const NOT_YET_COVERED: [&str; 0] = [];

fn source_files(directory: &Path, files: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(directory).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            source_files(&path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
}

/// The code of the file's doc examples (```` ``` ```` or ```` ```rust ```` blocks of `///` and
/// `//!` comments; `text` blocks are not code).
fn example_code(source: &str) -> String {
    let mut code = String::new();
    let mut block: Option<bool> = None;
    for line in source.lines() {
        let line = line.trim_start();
        let Some(body) = line.strip_prefix("///").or_else(|| line.strip_prefix("//!")) else { continue };
        let body = body.trim();
        if let Some(language) = body.strip_prefix("```") {
            block = match block {
                Some(_) => None,
                None => Some(language.is_empty() || language == "rust"),
            };
        } else if block == Some(true) {
            code.push_str(body);
            code.push('\n');
        }
    }
    code
}

/// The names of the file's public functions, up to its test module.
fn public_functions(source: &str) -> Vec<&str> {
    source
        .lines()
        .take_while(|line| !line.trim_start().starts_with("#[cfg(test)]"))
        .filter_map(|line| {
            let line = line.trim_start();
            let rest = line.strip_prefix("pub fn ").or_else(|| line.strip_prefix("pub const fn "))?;
            Some(rest.split(|c: char| !(c.is_alphanumeric() || c == '_')).next().unwrap())
        })
        .collect()
}

fn is_called(name: &str, code: &str) -> bool {
    code.match_indices(name).any(|(at, _)| {
        let before = code[..at].chars().next_back();
        let after = code[at + name.len()..].chars().next();
        let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
        !word(before) && !word(after)
    })
}

#[test]
fn every_public_function_is_called_in_a_doc_example() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&root, &mut files);
    let mut missing = Vec::new();
    let mut covered = 0;
    for file in &files {
        let relative = file.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
        let source = std::fs::read_to_string(file).unwrap();
        let code = example_code(&source);
        let functions = public_functions(&source);
        if NOT_YET_COVERED.contains(&relative.as_str()) {
            continue;
        }
        covered += functions.len();
        missing.extend(functions.into_iter().filter(|f| !is_called(f, &code)).map(|f| format!("{relative}: {f}")));
    }
    for listed in NOT_YET_COVERED {
        assert!(root.join(listed).is_file(), "NOT_YET_COVERED lists {listed}, which is not a source file");
    }
    assert!(covered > 50, "the scan found {covered} public functions in the covered files");
    assert!(missing.is_empty(), "public functions no doc example of their file calls:\n{}", missing.join("\n"));
}

#[test]
fn the_scan_reads_examples_and_functions() {
    let source = "//! ```text\n//! f(x)\n//! ```\n/// ```\n/// let y = shown(1);\n/// ```\npub fn shown() {}\npub fn hidden() {}\n#[cfg(test)]\npub fn in_tests() {}\n";
    let code = example_code(source);
    assert_eq!(code, "let y = shown(1);\n");
    assert_eq!(public_functions(source), ["shown", "hidden"]);
    assert!(is_called("shown", &code) && !is_called("hidden", &code) && !is_called("show", &code));
}
