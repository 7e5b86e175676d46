//! The rungs of the speed–accuracy ladder, one model per file, all behind
//! [`crate::CreepForceModel`], each declaring its [`Rung`](rung::Rung) (FMU item, parameters,
//! documentation) beside its code; registered below, once.

pub mod exact;
pub mod exact_table;
pub mod fastsim;
pub mod kalker_linear;
pub mod measured_curve;
pub mod model_choice;
pub mod polach;
pub mod polach2005;
pub mod rung;
pub mod sequence;
pub mod shen_hedrick_elkins;

// The ladder, in the order of the FMU's `creep_force_model` values: variant of `ModelChoice`,
// model type, module with its `RUNG`.
model_choice::ladder! {
    /// Polach's method (no spin moment: `spin_moment` is `None`).
    Polach(polach::Polach) = polach,
    /// Kalker's linear theory (not friction-limited).
    KalkerLinear(kalker_linear::KalkerLinear) = kalker_linear,
    /// Shen–Hedrick–Elkins cubic saturation of the linear theory.
    ShenHedrickElkins(shen_hedrick_elkins::ShenHedrickElkins) = shen_hedrick_elkins,
    /// Kalker's FASTSIM with its grid and options.
    Fastsim(fastsim::Fastsim) = fastsim,
    /// Kalker's exact theory on its grid (slow: offline or low-rate use; see [`exact::ExactTheory`]).
    Exact(exact::ExactTheory) = exact,
    /// Kalker's exact theory interpolated from its table (see [`exact_table::ExactTable`]).
    ExactTable(exact_table::ExactTable) = exact_table,
}
