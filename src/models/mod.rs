//! The rungs of the speed–accuracy ladder, one model per file, all behind
//! [`crate::CreepForceModel`].

pub mod measured_curve;
pub mod polach;
pub mod polach2005;
