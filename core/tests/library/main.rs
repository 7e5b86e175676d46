//! The library's integration tests: one program, so that they compile and link once (each file of
//! tests/ would be a program of its own, linking the library and its embedded table again). One module
//! per subject; `cargo test --test library <module>` runs one, e.g. `geometry_benchmark`.

mod common;
mod derivative_properties;
mod derivatives;
mod exact_step_cost;
mod exact_table;
mod exact_theory;
mod floors;
mod geometry_benchmark;
mod geometry_conicity;
mod geometry_invariants;
mod geometry_measured;
mod geometry_non_hertzian;
mod geometry_profiles;
mod geometry_wheel_forces;
mod kalker_coefficients;
mod kalker_table_exact;
mod ladder_contact_case;
mod ladder_invariants;
mod ladder_linear_limit;
mod measured_curve;
mod paper_hand_values;
mod polach2005;
mod polach_extremes;
mod polach_invariants;
mod polach_linear_limit;
mod polach_shape_cache;
mod polach_worked_cases;
mod public_api_examples;
mod scene_exact_warm_start;
mod scene_sequences;
mod strip_table;
mod wheel_non_hertzian;
mod wheel_rolling_sweep;
mod wheel_worn;
