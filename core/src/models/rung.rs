//! What the ladder, the FMU and the documentation need to know about one rung, declared once
//! beside the rung's code (each model file's `RUNG`) and registered once, by one line of the
//! ladder in `src/models/mod.rs` (which defines [`ModelChoice`] and its
//! [`RUNGS`](ModelChoice::RUNGS)). From that list the FMU's adapter checks its `creep_force_model`
//! enumeration, builds the rungs without parameters of their own and writes its options table;
//! the packaging tool writes the FMU's documentation and the ladder table of docs/library.md; the tests,
//! benchmarks and the trade report take their models. Adding a rung without FMU parameters of
//! its own therefore takes its model file (with its `RUNG`), its line in the ladder, its tests
//! and its item in `modelDescription.xml` (checked against the list by the adapter's tests); one
//! with FMU parameters also declares them in `modelDescription.xml` and maps them in
//! `fmu/src/scene.rs`.

use crate::ModelChoice;

/// One rung of the speed–accuracy ladder as others see it.
#[derive(Debug, Clone, Copy)]
pub struct Rung {
    /// Its item of the FMU's `creep_force_model` enumeration (and its name in reports).
    pub name: &'static str,
    /// That item's value: part of the FMU's interface (a master stores it), never reused.
    pub fmu_value: i32,
    /// The library type that implements it.
    pub type_name: &'static str,
    /// The FMU parameters only this rung reads (every rung reads those of every scene).
    pub fmu_parameters: &'static [&'static str],
    /// Whether it computes the spin moment M_z (without it the FMU's `spin_moment` is 0).
    pub spin_moment: bool,
    /// Whether its forces are bounded by μQ (Kalker's linear theory's are not, by definition).
    pub friction_limited: bool,
    /// Whether it is for offline or low-rate use only (the exact theory: milliseconds per step).
    pub offline: bool,
    /// What it is, one line of Markdown (the ladder table of docs/library.md).
    pub summary: &'static str,
    /// Where it comes from, Markdown (the ladder table of docs/library.md).
    pub source: &'static str,
    /// Its paragraph of the FMU's documentation, HTML: the equations, the FMU parameters it reads
    /// and where its accuracy and cost are measured.
    pub documentation: &'static str,
    /// The model with the FMU's start values for its parameters, or why it is unavailable (the
    /// exact table when the library was built without its data).
    pub default_model: fn() -> Result<ModelChoice, Box<dyn std::error::Error + Send + Sync>>,
}
