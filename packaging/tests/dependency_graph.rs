//! What building needs: the core (a Rust user's dependency), the FMUs' cdylibs (the contact
//! unit's and the wheelset's) and the packaging tool (`cargo fmu`, the README's first command)
//! must build with cargo alone — no bindgen, so no libclang, and no crate that compiles C. Read from `cargo tree` over normal and build
//! dependencies (dev-dependencies, which only the tests build, are allowed them).

use std::process::Command;

/// Crates that need a C toolchain or libclang at build time.
const FORBIDDEN: [&str; 4] = ["bindgen", "clang-sys", "cc", "fmi-sys"];

fn build_graph(package: &str) -> Vec<String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args(["tree", "-p", package, "-e", "normal,build", "--prefix", "none", "--format", "{p}"])
        .current_dir(packaging::fmu::workspace_root())
        .output()
        .expect("cargo runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .filter_map(|line| line.split_whitespace().next().map(str::to_owned))
        .collect()
}

#[test]
fn the_core_the_cdylib_and_cargo_fmu_build_with_cargo_alone() {
    for package in ["wheel-rail-contact", "wheel-rail-contact-fmu", "wheelset", "packaging"] {
        let graph = build_graph(package);
        assert!(graph.iter().any(|name| name == package), "{package}: {graph:?}");
        let forbidden: Vec<&String> = graph.iter().filter(|name| FORBIDDEN.contains(&name.as_str())).collect();
        assert!(forbidden.is_empty(), "{package} builds {forbidden:?}");
    }
}

#[test]
fn the_core_has_no_ffi_and_only_numeric_dependencies() {
    let graph = build_graph("wheel-rail-contact");
    for name in ["libloading", "serde", "zip", "libc", "wheel-rail-contact-fmu"] {
        assert!(!graph.iter().any(|n| n == name), "the core depends on {name}");
    }
}

/// The test itself would pass vacuously if `cargo tree` printed nothing useful: the test-only
/// header bindings must show up once dev-dependencies are included.
#[test]
fn the_check_sees_the_test_only_bindings() {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args(["tree", "-p", "wheel-rail-contact-fmu", "-e", "normal,build,dev", "--prefix", "none"])
        .current_dir(packaging::fmu::workspace_root())
        .output()
        .expect("cargo runs");
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(text.contains("bindgen") && text.contains("fmi-sys"), "{text}");
}
