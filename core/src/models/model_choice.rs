//! One type for "whichever rung of the ladder the user picked": enum dispatch, so a caller (the
//! FMU) holds one value, pays one `match` per evaluation and nothing for the models not chosen.

use crate::models::exact::ExactTheory;
use crate::models::ModelChoice;
use crate::{InvalidInput, LargeCreepage, Polach, Polach2005, Rung};

/// Defines [`ModelChoice`] from the list of rungs in `src/models/mod.rs` (one line per rung:
/// variant, model type, module declaring its `RUNG`): the enum, [`ModelChoice::RUNGS`],
/// [`ModelChoice::rung`] and the dispatch of [`CreepForceModel`], so that registering a rung is
/// that one line.
macro_rules! ladder {
    ($($(#[$doc:meta])* $variant:ident($model:ty) = $module:ident,)*) => {
        /// The selected creep-force model with its options.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum ModelChoice {
            $($(#[$doc])* $variant($model),)*
        }

        impl ModelChoice {
            /// Every rung, in the order of their FMU values: the one list the FMU's enumeration,
            /// its documentation, the ladder table of docs/library.md, the tests and the benchmarks are
            /// made from or checked against.
            pub const RUNGS: &'static [&'static $crate::Rung] = &[$(&$module::RUNG),*];

            /// The rung this model is.
            pub fn rung(&self) -> &'static $crate::Rung {
                match self {
                    $(Self::$variant(_) => &$module::RUNG,)*
                }
            }
        }

        /// What the models carry from one evaluation of a sequence to the next that can change
        /// the next result: each rung's [`SequenceModel::Memory`](crate::models::sequence::SequenceModel)
        /// (the exact theory's warm start: its last tractions, from which the next solve ends
        /// within the solver's tolerance of a cold solve, not bit for bit on it). It is state, not
        /// cache: an FMU state saves it, so that a restored run continues bit for bit.
        #[derive(Debug, Clone, PartialEq, Default)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        pub struct ModelMemory {
            $($module: <$model as $crate::models::sequence::SequenceModel>::Memory,)*
        }

        impl ModelMemory {
            /// Checks a memory that did not come from an evaluation (one read back from a saved
            /// state).
            ///
            /// ```
            /// # use wheel_rail_contact::ModelMemory;
            /// assert!(ModelMemory::default().validate().is_ok());
            /// ```
            pub fn validate(&self) -> Result<(), $crate::InvalidInput> {
                $(<$model as $crate::models::sequence::SequenceModel>::validate_memory(&self.$module)?;)*
                Ok(())
            }
        }

        /// What the models keep between evaluations for speed only — results are bit-identical
        /// without it: each rung's [`SequenceModel::Cache`](crate::models::sequence::SequenceModel)
        /// (Polach's shape factors for the last a/b and ν). Never saved.
        #[derive(Debug, Clone, Default)]
        pub struct ModelCache {
            $($module: <$model as $crate::models::sequence::SequenceModel>::Cache,)*
        }

        impl ModelChoice {
            /// The forces of one evaluation of a sequence (a co-simulation's steps): the chosen
            /// rung's [`SequenceModel::creep_forces_in_sequence`](crate::models::sequence::SequenceModel::creep_forces_in_sequence)
            /// from its part of `memory` (read here; its successor is returned, so that a failed
            /// evaluation leaves the caller's memory as it was) and of `cache` (updated).
            ///
            /// ```
            /// use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTheory, ModelCache, ModelChoice, ModelMemory};
            /// let model = ModelChoice::Exact(ExactTheory::new(24, 24));
            /// let contact = |xi: f64| ContactInput {
            ///     creepage_longitudinal: xi, creepage_lateral: 0.0, spin_creepage: 0.0,
            ///     normal_force: 100e3, semi_axis_a: 7.2e-3, semi_axis_b: 5.4e-3,
            ///     friction_coefficient: 0.3, shear_modulus: 82e9, poisson_ratio: 0.28,
            /// };
            /// let mut cache = ModelCache::default();
            /// let first = model.creep_forces_in_sequence(&contact(1e-3), &ModelMemory::default(), &mut cache).unwrap();
            /// // The next step starts from the first one's tractions: the same forces as a cold solve,
            /// // to the solver's tolerance (10⁻⁹ μQ), not bit for bit.
            /// let next = model.creep_forces_in_sequence(&contact(1.1e-3), &first.memory, &mut cache).unwrap();
            /// let cold = model.creep_forces(&contact(1.1e-3)).unwrap();
            /// assert!((next.forces.force_longitudinal - cold.force_longitudinal).abs() < 1e-9 * 0.3 * 100e3);
            /// assert_ne!(next.memory, first.memory);
            /// assert!(next.unconverged_grid.is_none());
            /// ```
            #[inline]
            pub fn creep_forces_in_sequence(
                &self,
                input: &$crate::ContactInput,
                memory: &ModelMemory,
                cache: &mut ModelCache,
            ) -> Result<$crate::SequenceStep, $crate::InvalidInput> {
                use $crate::models::sequence::SequenceModel;
                match self {
                    $(Self::$variant(model) => {
                        let step = model.creep_forces_in_sequence(input, &memory.$module, &mut cache.$module)?;
                        Ok($crate::SequenceStep {
                            forces: step.forces,
                            memory: ModelMemory { $module: step.memory, ..ModelMemory::default() },
                            unconverged_grid: step.unconverged_grid,
                        })
                    })*
                }
            }
        }

        impl $crate::CreepForceModel for ModelChoice {
            #[inline]
            fn creep_forces(
                &self,
                input: &$crate::ContactInput,
            ) -> Result<$crate::CreepForces, $crate::InvalidInput> {
                match self {
                    $(Self::$variant(model) => model.creep_forces(input),)*
                }
            }

            /// The chosen model's own derivative (each model's: exact by dual numbers where it
            /// has one, a central difference where it has not). Without this the trait's default
            /// (a central difference) would replace the exact ones.
            #[inline]
            fn directional_derivative(
                &self,
                input: &$crate::ContactInput,
                direction: &$crate::ContactInput,
            ) -> Result<$crate::CreepForces, $crate::InvalidInput> {
                match self {
                    $(Self::$variant(model) => model.directional_derivative(input, direction),)*
                }
            }
        }
    };
}
pub(crate) use ladder;

/// ```
/// use wheel_rail_contact::{KalkerLinear, ModelChoice, Polach};
///
/// // The ladder in the FMU's order: polach = 1 … exact_table = 6.
/// let names: Vec<&str> = ModelChoice::RUNGS.iter().map(|rung| rung.name).collect();
/// assert_eq!(names, ["polach", "kalker_linear", "shen_hedrick_elkins", "fastsim", "exact", "exact_table"]);
/// let linear = ModelChoice::KalkerLinear(KalkerLinear);
/// assert_eq!((linear.name(), linear.rung().fmu_value, linear.rung().friction_limited), ("kalker_linear", 2, false));
/// assert_eq!(ModelChoice::rung_of_fmu_value(1).unwrap().name, ModelChoice::Polach(Polach::default()).name());
/// assert!(ModelChoice::rung_of_fmu_value(7).is_none());
/// ```
impl ModelChoice {
    /// The rung of this value of the FMU's `creep_force_model`, if any.
    pub fn rung_of_fmu_value(value: i32) -> Option<&'static Rung> {
        Self::RUNGS.iter().copied().find(|rung| rung.fmu_value == value)
    }

    /// Short name, as in the FMU's `model` enumeration and the trade report.
    pub fn name(&self) -> &'static str {
        self.rung().name
    }
}

impl ModelChoice {
    /// This model under Polach's 2005 traction law (friction falling with the slip velocity,
    /// reduced stiffness) at the speed `speed` [m/s]: Polach's method only, `None` for every
    /// other model.
    ///
    /// ```
    /// use wheel_rail_contact::{KalkerLinear, ModelChoice, Polach, Polach2005};
    /// let polach = ModelChoice::Polach(Polach::default());
    /// let Some(ModelChoice::Polach(under)) = polach.under_polach2005(Polach2005::DRY, 20.0).unwrap() else {
    ///     unreachable!()
    /// };
    /// assert!(under.large_creepage.is_some());
    /// assert_eq!(ModelChoice::KalkerLinear(KalkerLinear).under_polach2005(Polach2005::DRY, 20.0), Ok(None));
    /// // The speed must be finite.
    /// assert!(polach.under_polach2005(Polach2005::DRY, f64::NAN).is_err());
    /// ```
    pub fn under_polach2005(self, law: Polach2005, speed: f64) -> Result<Option<Self>, InvalidInput> {
        Ok(match self {
            Self::Polach(polach) => {
                Some(Self::Polach(Polach { large_creepage: Some(LargeCreepage::new(law, speed)?), ..polach }))
            }
            _ => None,
        })
    }

    /// The rung that evaluates a contact patch whose semi-axes are in the ratio `a_over_b`: this
    /// one, except that `exact_table` beyond its table's a/b range (the shipped one's
    /// [0.1, 10^1.5] holds a flange's long Hertz ellipse, a/b = 16–22 on A-2.2) hands the patch to
    /// the theory the table interpolates, the exact theory on CONTACT's grid (slower, as accurate).
    ///
    /// ```
    /// use wheel_rail_contact::{ExactTable, ExactTheory, ModelChoice};
    /// let table = ModelChoice::ExactTable(ExactTable::new().unwrap());
    /// assert_eq!(table.for_ellipse(20.0), table); // a flange's patch, within the table
    /// assert_eq!(table.for_ellipse(40.0), ModelChoice::Exact(ExactTheory::default()));
    /// ```
    pub fn for_ellipse(self, a_over_b: f64) -> Self {
        match self {
            Self::ExactTable(table) if !table.table().covers_a_over_b(a_over_b) => Self::Exact(ExactTheory::default()),
            model => model,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CreepForceModel;

    /// The FMU's values are 1, 2, … in the list's order, and each rung's default model is that
    /// rung (a rung registered in `RUNGS` but answered by another `rung()` arm fails here).
    #[test]
    fn every_rung_is_listed_once_in_the_order_of_its_value() {
        for (index, rung) in ModelChoice::RUNGS.iter().enumerate() {
            assert_eq!(rung.fmu_value, index as i32 + 1, "{}", rung.name);
            let model = (rung.default_model)().unwrap_or_else(|e| panic!("{}: {e}", rung.name));
            assert_eq!((model.rung().name, model.rung().fmu_value), (rung.name, rung.fmu_value));
            assert_eq!(model.name(), rung.name);
            assert_eq!(ModelChoice::rung_of_fmu_value(rung.fmu_value).map(|r| r.name), Some(rung.name));
            assert_eq!(
                model.creep_forces(&crate::reference_cases::FASTSIM_CASE).map(|f| f.spin_moment.is_some()),
                Ok(rung.spin_moment),
                "{}",
                rung.name
            );
        }
        assert!(ModelChoice::rung_of_fmu_value(0).is_none());
        let mut names: Vec<_> = ModelChoice::RUNGS.iter().map(|rung| rung.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), ModelChoice::RUNGS.len());
    }

    #[test]
    fn a_patch_beyond_the_tables_a_over_b_goes_to_the_exact_theory() {
        let table = ModelChoice::ExactTable(crate::ExactTable::new().unwrap());
        // A flange's (a/b = 20), one near the table's end (31 < 10^1.5), beyond it (40), and wide
        // ones (1/9 within, 1/20 below the table's 0.1).
        for (a_over_b, beyond) in [(20.0, false), (31.0, false), (40.0, true), (1.0 / 9.0, false), (0.05, true)] {
            let model = table.for_ellipse(a_over_b);
            assert_eq!(matches!(model, ModelChoice::Exact(_)), beyond, "a/b = {a_over_b}");
            if beyond {
                assert_eq!(model, ModelChoice::Exact(ExactTheory::default()), "CONTACT's grid");
            } else {
                assert_eq!(model, table);
            }
        }
        // Other rungs are kept whatever the shape.
        let polach = ModelChoice::Polach(Polach::default());
        assert_eq!(polach.for_ellipse(40.0), polach);
    }
}
