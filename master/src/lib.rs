//! A C-ABI master for the FMU's binaries: the binary loaded with libloading and driven through
//! the FMI 2.0 C types declared here, sharing no code with the adapter it drives. The
//! `fmu-master` program compares platforms with it (`scripts/test-platforms`); `cargo fmu` runs
//! the default scene through it; the lab's coupling stability map couples the wheelset FMU and
//! two contact units with it (lab/src/coupling.rs).

pub mod binary;
pub mod compare;
pub mod description;
