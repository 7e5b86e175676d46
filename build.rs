//! Build script: generates Rust source from the project's single sources of truth.
//!
//! - `data/kalker_coefficients.csv` and `data/kalker_c33.csv` (Kalker's table E.3) become the
//!   coefficient tables used by `src/kalker_coefficients.rs`, so the numbers are written in
//!   exactly one place.
//! - `modelDescription.xml` (the FMU's interface) becomes the FMI adapter's variable table, value
//!   storage and GUID (`src/fmi/model_description.rs`), so the interface is written in exactly one place.

#[path = "build/kalker_table.rs"]
mod kalker_table;
#[path = "build/model_description.rs"]
mod model_description;

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    kalker_table::generate(&out_dir.join("kalker_table.rs"));
    model_description::generate("modelDescription.xml", &out_dir.join("model_description.rs"));
    // The FMU exports the 34 fmi2* functions and nothing else: fmi-sys (used for the headers'
    // types) carries a `#[no_mangle]` logger helper that would otherwise leak into the exports.
    // zig's linker (the old-glibc linux64 build, packaging::fmu) rejects the flag: there the helper
    // stays exported (packaging/tests/platforms.rs names it) until the adapter drops fmi-sys.
    let linker_is_zig = std::env::var("RUSTC_LINKER").is_ok_and(|linker| linker.contains("zig"));
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") && !linker_is_zig {
        println!("cargo:rustc-cdylib-link-arg=-Wl,--exclude-libs,ALL");
    }
}
