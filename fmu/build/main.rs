//! Build script: generates the adapter's interface from the FMU's single source of truth,
//! `modelDescription.xml` beside this crate's Cargo.toml: the value structs, value references, Get/Set
//! mapping, variable table, GUID, `<ModelStructure>` indices and the FMU-state layout tag
//! (`src/model_description.rs` includes the result), by the slave layer's generator
//! (`fmi2_slave::build`, shared with the wheelset FMU).

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fmi2_slave::build::generate("modelDescription.xml", &out_dir.join("model_description.rs"));
    // The FMU exports the 44 fmi2* functions and nothing else: rustc's export list for a cdylib
    // holds only its `#[no_mangle]` functions, and no C library is linked in; for a win64 DLL
    // linked by zig, a module-definition file says it (packaging checks every binary's export
    // table, `packaging::fmu::check_library`).
    fmi2_slave::build::export_only_fmi2_functions(&out_dir);
}
