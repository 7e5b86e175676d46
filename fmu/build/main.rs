//! Build script: generates the adapter's interface from the FMU's single source of truth,
//! `modelDescription.xml` at the workspace root: the value structs, value references, Get/Set
//! mapping, variable table, GUID, `<ModelStructure>` indices and the FMU-state layout tag
//! (`src/model_description.rs` includes the result).

mod model_description;

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    model_description::generate("../modelDescription.xml", &out_dir.join("model_description.rs"));
    // The FMU exports the 34 fmi2* functions and nothing else: rustc's export list for a cdylib
    // holds only its `#[no_mangle]` functions, and no C library is linked in (packaging checks
    // every binary's export table, `packaging::fmu::check_library`).
}
