//! Wheel–rail contact from profiles: from wheel and rail profiles and the wheelset's position and
//! motion to the contact patches and the forces on the wheel.
//!
//! - [`profile_file`]: the SIMPACK (`.prw`, `.prr`) and MiniProf (`.whl`, `.ban`) readers, with
//!   errors naming the line and the reason;
//! - [`builtin`]: the Manchester contact benchmark's S1002 wheel and UIC60 rail profiles, compiled
//!   in and selectable by name (`MBench_S1002`, `MBench_UIC60`; `data/profiles/README.md` gives
//!   their provenance);
//! - [`smooth_profile`]: a profile's smooth representation (parametric cubic spline) with its
//!   slope and curvature;
//! - [`contact`]: a wheel placed on its rail, right or left (gauge, cant, flange back, roll, yaw), its
//!   contact points (tread and flange), the normal problem in both modes (prescribed vertical
//!   position or force) with a Hertz ellipse per patch;
//! - [`conicity`]: the wheelset's rolling-radius difference Δr(y) and its equivalent conicity
//!   tan γ_e(A) by EN 15302's principle (the kinematic wavelength of the nonlinear motion);
//! - [`wheel_forces`]: each patch's creepages from the wheelset's motion, its creep forces by
//!   any rung of the ladder, their sum and moment on the wheel, the vertical balance with the
//!   creep forces' share.
//!
//! Conventions are CONTACT's module 1: profile coordinates y lateral, z downward, in metres; the
//! profiles are given for the right side (a left wheel and rail use them mirrored).

pub mod builtin;
pub mod conicity;
pub mod contact;
pub mod normal_problem;
pub mod profile_file;
mod sampled_profile;
pub mod smooth_profile;
pub mod wheel_forces;

pub use builtin::{builtin_profile, BUILTIN_PROFILE_NAMES};
pub use conicity::{first_touch, ConicityError, RollingRadiusDifference};
pub use contact::{ContactPatch, ContactPoint, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition};
pub use normal_problem::ContactCandidates;
pub use profile_file::{parse_profile, ProfileError, ProfileFormat, ProfilePoints};
pub use smooth_profile::{ProfilePoint, SmoothProfile};
pub use wheel_forces::{
    PatchForces, PatchState, VerticalContact, WheelCache, WheelContactError, WheelInput, WheelOutput, WheelRailContact,
    WheelState, WheelsetVelocity,
};
