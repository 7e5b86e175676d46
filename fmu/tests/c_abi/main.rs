//! The contact FMU driven through its C ABI by an in-process master (fmu_test_master): one program,
//! so that the tests compile and link once. `fmu_memory` stays a program of its own: its counting
//! global allocator must see only its own instance. `cargo test -p wheel-rail-contact-fmu --test
//! c_abi <module>` runs one module, e.g. `fmu_fuzz`.

mod creep_relaxation;
mod event_indicators;
mod exact_table_fold_derivatives;
mod exact_table_resources;
mod feedthrough;
mod fmi2_headers;
mod fmu_derivatives;
mod fmu_fuzz;
mod fmu_state;
mod fmu_threads;
mod hertz_contact;
mod logging;
mod model_exchange;
mod profile_files;
mod profiles;
mod stepping;
