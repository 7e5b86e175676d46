//! One type for "whichever rung of the ladder the user picked": enum dispatch, so a caller (the
//! FMU) holds one value, pays one `match` per evaluation and nothing for the models not chosen.

use crate::models::exact::ExactTheory;
use crate::models::exact_table::ExactTable;
use crate::models::fastsim::Fastsim;
use crate::models::kalker_linear::KalkerLinear;
use crate::models::shen_hedrick_elkins::ShenHedrickElkins;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, Polach};

/// The selected creep-force model with its options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModelChoice {
    /// Polach's method (no spin moment: `spin_moment` is `None`).
    Polach(Polach),
    /// Kalker's linear theory (not friction-limited).
    KalkerLinear(KalkerLinear),
    /// Shen–Hedrick–Elkins cubic saturation of the linear theory.
    ShenHedrickElkins(ShenHedrickElkins),
    /// Kalker's FASTSIM with its grid and options.
    Fastsim(Fastsim),
    /// Kalker's exact theory on its grid (slow: offline or low-rate use; see [`ExactTheory`]).
    Exact(ExactTheory),
    /// Kalker's exact theory interpolated from its table (see [`ExactTable`]).
    ExactTable(ExactTable),
}

impl ModelChoice {
    /// Short name, as in the FMU's `model` enumeration and the trade report.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Polach(_) => "polach",
            Self::KalkerLinear(_) => "kalker_linear",
            Self::ShenHedrickElkins(_) => "shen_hedrick_elkins",
            Self::Fastsim(_) => "fastsim",
            Self::Exact(_) => "exact",
            Self::ExactTable(_) => "exact_table",
        }
    }
}

impl CreepForceModel for ModelChoice {
    #[inline]
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        match self {
            Self::Polach(model) => model.creep_forces(input),
            Self::KalkerLinear(model) => model.creep_forces(input),
            Self::ShenHedrickElkins(model) => model.creep_forces(input),
            Self::Fastsim(model) => model.creep_forces(input),
            Self::Exact(model) => model.creep_forces(input),
            Self::ExactTable(model) => model.creep_forces(input),
        }
    }

    /// The chosen model's own derivative: exact (dual numbers) for Polach, Kalker's linear
    /// theory, Shen–Hedrick–Elkins and the exact theory's table, FASTSIM's central difference. Without this the trait's
    /// default (a central difference) would replace the exact ones.
    #[inline]
    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        match self {
            Self::Polach(model) => model.directional_derivative(input, direction),
            Self::KalkerLinear(model) => model.directional_derivative(input, direction),
            Self::ShenHedrickElkins(model) => model.directional_derivative(input, direction),
            Self::Fastsim(model) => model.directional_derivative(input, direction),
            Self::Exact(model) => model.directional_derivative(input, direction),
            Self::ExactTable(model) => model.directional_derivative(input, direction),
        }
    }
}
