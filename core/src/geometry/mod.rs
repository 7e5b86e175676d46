//! Wheel–rail contact from profiles: from wheel and rail profiles and the wheelset's position to
//! the contact patches, each with its Hertz ellipse.
//!
//! - [`profile_file`]: the SIMPACK (`.prw`, `.prr`) and MiniProf (`.whl`, `.ban`) readers, with
//!   errors naming the line and the reason;
//! - [`builtin`]: the Manchester contact benchmark's S1002 wheel and UIC60 rail profiles, compiled
//!   in and selectable by name (`MBench_S1002`, `MBench_UIC60`; `data/profiles/README.md` gives
//!   their provenance);
//! - [`measured_profile`]: measured, worn profiles (MiniProf, SIMPACK) read and cleaned into
//!   their running surface: header forms, zig-zags, back-steps and overhangs, either side, z up
//!   or down;
//! - [`smooth_profile`]: a profile's smooth representation (parametric cubic spline, interpolating
//!   or smoothing) with its slope and curvature;
//! - [`contact`]: a wheel placed on its rail, right or left (gauge, cant, flange back, roll, yaw), its
//!   contact points (tread and flange), the normal problem in both modes (prescribed vertical
//!   position or force) with a Hertz ellipse per patch;
//! - [`non_hertzian`]: the normal problem per contact region instead of per gap minimum
//!   (Kik–Piotrowski's virtual penetration, strip by strip), both modes;
//! - [`conicity`]: the wheelset's rolling-radius difference Δr(y) and its equivalent conicity
//!   tan γ_e(A) by EN 15302's principle (the kinematic wavelength of the nonlinear motion);
//! - [`switching`]: the switching functions whose signs change where a wheel's patches jump
//!   (joining, parting, or passing to another gap minimum), for integrators' event detection;
//! - `patch`: what the search and the normal problem find: the side, a contact point, a
//!   loaded patch.
//!
//! Geometry stands below the creep-force models and the scene; the wheel's forces from its patches
//! ([`crate::wheel`]) stand above all three.
//!
//! Conventions are CONTACT's module 1: profile coordinates y lateral, z downward, in metres; the
//! profiles are given for the right side (a left wheel and rail use them mirrored).

pub mod builtin;
pub mod conicity;
pub mod contact;
pub mod measured_profile;
pub mod non_hertzian;
pub mod normal_problem;
mod patch;
pub mod profile_file;
mod sampled_profile;
pub mod smooth_profile;
mod strip_grid;
mod strip_kernel;
mod strip_table;
pub mod switching;

pub use builtin::{builtin_profile, BUILTIN_PROFILE_NAMES};
pub use conicity::{first_touch, ConicityError, RollingRadiusDifference};
pub use contact::{TrackDimensions, WheelOnRail, WheelsetPosition};
pub use measured_profile::{
    read_measured_profile, MeasuredOptions, MeasuredProfile, Orientation, MEASURED_FILTER_WAVELENGTH,
};
pub use non_hertzian::{NonHertzianContact, NonHertzianPatch, NonHertzianPose, Strip};
pub use normal_problem::{ContactCandidates, MAX_PENETRATION};
pub use patch::{ContactPatch, ContactPoint, WheelSide};
pub use profile_file::{
    parse_profile, parse_profile_as, ProfileError, ProfileFormat, ProfileKind, ProfilePoints, MAX_COORDINATE,
};
pub use smooth_profile::{ProfilePoint, SmoothProfile};
pub use switching::{SwitchingFunctions, NO_SWITCH, SWITCHING_CONTACTS, SWITCHING_FUNCTIONS, SWITCHING_PAIRS};
