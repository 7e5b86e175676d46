//! Build script: generates the wheelset FMU's interface (value structs, value references, Get/Set
//! mapping, variable table, GUID, the packaged `<ModelStructure>`, the FMU-state layout tag) from
//! its single source of truth, `modelDescription.xml`, with the slave layer's generator
//! (`fmi2_slave::build`, the contact FMU's too). `src/model_description.rs` includes the result.

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fmi2_slave::build::generate("modelDescription.xml", &out_dir.join("model_description.rs"));
    // Only the fmi2* functions exported, also from a win64 DLL linked by zig.
    fmi2_slave::build::export_only_fmi2_functions(&out_dir);
}
