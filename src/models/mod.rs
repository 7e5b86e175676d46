//! The rungs of the speed–accuracy ladder, one model per file, all behind
//! [`crate::CreepForceModel`].

pub mod exact;
pub mod exact_table;
pub mod fastsim;
pub mod kalker_linear;
pub mod measured_curve;
pub mod model_choice;
pub mod polach;
pub mod polach2005;
pub mod shen_hedrick_elkins;
