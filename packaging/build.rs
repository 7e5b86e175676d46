//! Build script: generates the wheelset FMU's interface from `wheelset/modelDescription.xml`
//! (with `fmi2_slave::build`, as the wheelset crate's own build script does), for
//! `wheelset_interface`: packaging cannot link the wheelset crate beside the contact adapter,
//! since both define the fmi2* symbols.

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fmi2_slave::build::generate("../wheelset/modelDescription.xml", &out_dir.join("wheelset_interface.rs"));
}
