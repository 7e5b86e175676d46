//! Build script: generates Rust source from the project's single sources of truth.
//!
//! - `data/kalker_coefficients.csv` and `data/kalker_c33.csv` (Kalker's table E.3) become the
//!   coefficient tables used by `src/kalker_coefficients.rs`, so the numbers are written in
//!   exactly one place.

#[path = "build/kalker_table.rs"]
mod kalker_table;

fn main() {
    let out_dir = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    kalker_table::generate(&out_dir.join("kalker_table.rs"));
}
