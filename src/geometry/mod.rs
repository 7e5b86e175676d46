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
//!
//! A wheel with its profiles, the Manchester benchmark's case A-2.2 no. 3 (right wheel: the
//! wheelset 1 mm to the right, yawed 2.4 mrad, 10 kN on the wheel, V = 2 m/s, μ = 0.3), against
//! CONTACT's published full solution (rail y −18.54 mm, contact angle −0.0696 rad, N = 9827 N,
//! creep forces on the wheel 814 N and 2832 N, `tests/data/mbench_a22_contact_ref_out.csv`):
//!
//! ```
//! use wheel_rail_contact::geometry::{
//!     builtin_profile, SmoothProfile, TrackDimensions, VerticalContact, WheelCache, WheelInput, WheelOnRail,
//!     WheelRailContact, WheelSide, WheelState, WheelsetPosition, WheelsetVelocity,
//! };
//! use wheel_rail_contact::scene::{Evaluation, Scene};
//! use wheel_rail_contact::{ModelChoice, Polach};
//!
//! let profile = |name| SmoothProfile::new(&builtin_profile(name).unwrap()).unwrap();
//! let (wheel, rail) = (profile("MBench_S1002"), profile("MBench_UIC60"));
//! let placed = WheelOnRail::new(wheel, rail, TrackDimensions::MANCHESTER_BENCHMARK, WheelSide::Right, 82e9, 0.28);
//! let contact = WheelRailContact::new(placed.unwrap(), Scene::of_model(ModelChoice::Polach(Polach::default()), 82e9, 0.28));
//! let input = WheelInput {
//!     position: WheelsetPosition { lateral: 1e-3, vertical: 0.0, roll: -5.049e-5, yaw: 2.4e-3 },
//!     velocity: WheelsetVelocity { rolling_speed: 2.0, wheel_angular_speed: 4.3465752, ..WheelsetVelocity::default() },
//!     vertical: VerticalContact::PrescribedForce(10e3),
//!     friction_coefficient: 0.3,
//! };
//! let (output, _next_state) =
//!     contact.evaluate(&input, &WheelState::default(), &mut WheelCache::default(), Evaluation::Initialise).unwrap();
//! let patch = &output.patches[0];
//! assert_eq!(output.patches.len(), 1);
//! let point = patch.patch.point;
//! // Our Hertz point against the centre of CONTACT's non-elliptic patch: within 0.35 mm.
//! assert!((point.rail_lateral + 18.54e-3).abs() < 0.35e-3, "rail y {}", point.rail_lateral);
//! assert!((point.contact_angle + 0.0696).abs() < 0.002, "contact angle {}", point.contact_angle);
//! assert!((patch.patch.normal_force / 9827.0 - 1.0).abs() < 0.005, "N {}", patch.patch.normal_force);
//! // Polach on the tread: within 0.06 μN of CONTACT's exact theory on the real patch.
//! let within = |ours: f64, theirs: f64| (ours - theirs).abs() < 0.06 * 0.3 * 9827.0;
//! let (f_x, f_y) = (patch.output.force_longitudinal, patch.output.force_lateral);
//! assert!(within(f_x, 814.3) && within(f_y, 2832.0), "F_x {f_x}, F_y {f_y}");
//! // The wheel carries the prescribed 10 kN (z downward: the rail pushes up, −z).
//! assert!((output.track_force[2] + 10e3).abs() < 1e-6);
//! ```

pub mod builtin;
pub mod conicity;
pub mod contact;
mod hertz_table;
pub mod normal_problem;
pub mod profile_file;
mod sampled_profile;
pub mod smooth_profile;
pub mod wheel_forces;

pub use builtin::{builtin_profile, BUILTIN_PROFILE_NAMES};
pub use conicity::{first_touch, ConicityError, RollingRadiusDifference};
pub use contact::{ContactPatch, ContactPoint, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition};
pub use normal_problem::{ContactCandidates, MAX_PENETRATION};
pub use profile_file::{
    parse_profile, parse_profile_as, ProfileError, ProfileFormat, ProfileKind, ProfilePoints, MAX_COORDINATE,
};
pub use smooth_profile::{ProfilePoint, SmoothProfile};
pub use wheel_forces::{
    PatchForces, PatchState, VerticalContact, WheelCache, WheelContactError, WheelInput, WheelOutput, WheelRailContact,
    WheelState, WheelsetVelocity,
};
