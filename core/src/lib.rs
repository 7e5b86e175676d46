//! # wheel-rail-contact
//!
//! Tangential wheel–rail contact forces (creep forces) of one contact patch, from its
//! creepages, spin, normal load, contact ellipse and friction: a pure, safe physics core in SI
//! units, under an FMI 2.0 Co-Simulation adapter.
//!
//! The core method is Polach's fast analytical solution ([`Polach`]). Around it a ladder of models
//! trades speed for accuracy — [`KalkerLinear`], [`ShenHedrickElkins`], [`Polach`], [`Fastsim`]
//! at any grid, [`ExactTheory`] — each in its own file under [`models`], all implementing
//! [`CreepForceModel`] (forces and exact or finite-difference directional derivatives);
//! [`ModelChoice`] selects one at run time. [`scene`] holds what a scene may add — the contact
//! ellipse by Hertz ([`hertz`]), creepages from kinematics through standstill, creep relaxation —
//! and [`scene::Scene`], the whole pipeline with one evaluation, which the FMU (the
//! `wheel-rail-contact-fmu` crate, the FMI 2.0 adapter that holds all `unsafe` code) calls too.
//! [`geometry`] finds a wheel's contact patches on its rail from their profiles, and [`wheel`]
//! evaluates a scene per patch and sums the forces on the wheel. This crate forbids `unsafe` code
//! and has no FFI.
//!
//! **Sign convention** (Kalker, CONTACT): forces act on the wheel and oppose the creepages; in
//! the linear range F_x = −G·ab·C11·ξ and F_y = −G·ab·C22·η − G·(ab)^{3/2}·C23·φ.
//!
//! ```
//! use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};
//! let input = ContactInput {
//!     creepage_longitudinal: 1e-3, creepage_lateral: 0.0, spin_creepage: 0.0,
//!     normal_force: 100e3, semi_axis_a: 6e-3, semi_axis_b: 4e-3,
//!     friction_coefficient: 0.3, shear_modulus: 8e10, poisson_ratio: 0.28,
//! };
//! let forces = Polach::default().creep_forces(&input).unwrap();
//! assert!(forces.force_longitudinal < 0.0 && forces.adhesion_utilisation < 1.0);
//! ```

#![forbid(unsafe_code)]
// The errors name the variable, its value and the rule it breaks (what a user's log needs);
// they are returned on the error path only, where their size costs nothing measurable.
#![allow(clippy::result_large_err)]

mod contact_input;
mod creep_force_model;
mod creep_forces;
pub mod geometry;
pub mod hertz;
mod invalid_input;
mod kalker_coefficients;
pub mod models;
mod numerics;
pub mod reference_cases;
pub mod scene;
pub mod wheel;

pub use contact_input::ContactInput;
pub use creep_force_model::{central_difference, CreepForceModel};
pub use creep_forces::CreepForces;
pub use invalid_input::InvalidInput;
pub use kalker_coefficients::KalkerCoefficients;
pub use models::exact::{ElementState, ExactSolution, ExactTheory, GridSize, LinearCoefficients, WarmStart};
pub use models::exact_table::{ExactTable, TableError};
pub use models::fastsim::{Discretisation, Fastsim, FastsimResult, Flexibility, TractionBound};
pub use models::kalker_linear::KalkerLinear;
pub use models::measured_curve::{MeasuredCurve, MeasuredCurveError};
pub use models::polach::{spin_moment_factor, Polach, PolachShape, ShapeCache, StiffnessSource};
pub use models::polach2005::{LargeCreepage, Polach2005};
pub use models::rung::Rung;
pub use models::sequence::{SequenceModel, SequenceStep};
pub use models::shen_hedrick_elkins::ShenHedrickElkins;
pub use models::ModelChoice;
pub use models::{ModelCache, ModelMemory};
