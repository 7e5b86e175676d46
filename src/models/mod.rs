//! The rungs of the speed–accuracy ladder, one model per file, all behind
//! [`crate::CreepForceModel`].

pub mod exact;
pub mod measured_curve;
pub mod polach;
