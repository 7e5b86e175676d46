//! What a rung carries from one evaluation of a sequence (a co-simulation's steps) to the next,
//! declared in the rung's own file by its [`SequenceModel`] implementation: its memory (state:
//! it can change the next result, so an FMU state saves it) and its cache (derived data for speed
//! only: the results are bit-identical without it; never saved). A rung that keeps neither writes
//! `type Memory = (); type Cache = ();`. The ladder (`model_choice.rs`) holds one memory and one
//! cache per rung, [`ModelMemory`](crate::ModelMemory) and [`ModelCache`](crate::ModelCache), and
//! dispatches to the chosen rung.

use std::fmt::Debug;

use crate::models::exact::GridSize;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput};

/// A type an FMU state can save: serde data with the `serde` feature, any type without it.
#[cfg(feature = "serde")]
pub trait Saved: serde::Serialize + serde::de::DeserializeOwned {}
#[cfg(feature = "serde")]
impl<T: serde::Serialize + serde::de::DeserializeOwned> Saved for T {}
/// A type an FMU state can save: serde data with the `serde` feature, any type without it.
#[cfg(not(feature = "serde"))]
pub trait Saved {}
#[cfg(not(feature = "serde"))]
impl<T> Saved for T {}

/// One evaluation of a sequence: the forces, the memory the next evaluation starts from, and
/// whether the evaluation stopped short of converging.
#[derive(Debug, Clone, PartialEq)]
pub struct SequenceStep<M = crate::ModelMemory> {
    pub forces: CreepForces,
    /// The memory the next evaluation starts from.
    pub memory: M,
    /// The exact theory's grid when its iteration stopped at its limits without converging (the
    /// forces are its last iterate); `None` for every other evaluation.
    pub unconverged_grid: Option<GridSize>,
}

/// A creep-force model evaluated step after step.
pub trait SequenceModel: CreepForceModel {
    /// What changes the next result (the exact theory's warm start); `()` for most rungs.
    type Memory: Clone + PartialEq + Default + Debug + Saved;
    /// What saves work only (Polach's shape factors); `()` for most rungs.
    type Cache: Clone + Default + Debug;

    /// The forces of `input` continuing from `memory`, with `cache` updated; by default those of
    /// [`CreepForceModel::creep_forces`], with nothing carried over.
    fn creep_forces_in_sequence(
        &self,
        input: &ContactInput,
        _memory: &Self::Memory,
        _cache: &mut Self::Cache,
    ) -> Result<SequenceStep<Self::Memory>, InvalidInput> {
        Ok(SequenceStep { forces: self.creep_forces(input)?, memory: Self::Memory::default(), unconverged_grid: None })
    }

    /// Checks a memory that did not come from an evaluation (one read back from a saved state).
    fn validate_memory(_memory: &Self::Memory) -> Result<(), InvalidInput> {
        Ok(())
    }
}
