//! `contact_geometry = profiles`: the FMU's values ↔ the core's [`WheelRailContact`] (one wheel
//! on its rail, from its profiles). Here, and only here, the adapter reads files: the core has no
//! I/O, so a profile given as a path is read into text and handed to the core's reader
//! ([`parse_profile_as`], the format and the kind, wheel or rail, from the extension); a built-in
//! name goes to [`builtin_profile`]. Only regular files of at most [`MAX_PROFILE_FILE_SIZE`]
//! bytes are read. Errors name the variable, the file and the reason (the core's
//! [`ProfileError`](wheel_rail_contact::geometry::ProfileError) gives the line); a value is
//! repeated in a message up to its first 200 characters.
//!
//! Outputs: the totals on the wheel in track axes, the solved vertical position and, for the
//! first two patches (tread first, as the core orders them), their geometry, forces and
//! creepages. A third patch, rare, is in the totals only.

use super::files::read_regular_file;
use super::model_description::{
    enumeration, ContactMethod as MethodChoice, Inputs, Parameters, Strings, VerticalContact as VerticalChoice,
    WheelSide as SideChoice,
};
use super::resources::file_path;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::path::Path;
use wheel_rail_contact::geometry::{
    builtin_profile, parse_profile_as, read_measured_profile, MeasuredOptions, ProfileFormat, ProfileKind,
    ProfilePoints, SmoothProfile, TrackDimensions, WheelOnRail, WheelSide, WheelsetPosition, BUILTIN_PROFILE_NAMES,
};
use wheel_rail_contact::scene::Scene;
use wheel_rail_contact::wheel::{
    ContactMethod, PatchForces, VerticalContact, WheelContactError, WheelInput, WheelOutput, WheelRailContact,
    WheelsetVelocity,
};

/// How many patches have their own outputs (`patch1_*`, `patch2_*`).
pub const REPORTED_PATCHES: usize = 2;

/// A wheel on its rail as the parameters place it, and how its vertical contact is set.
#[derive(Debug, Clone)]
pub struct ProfileContact {
    contact: WheelRailContact,
    vertical: VerticalChoice,
    /// What the profiles were read from, for the messages of the geometry's errors.
    sources: String,
    /// Their content's fingerprint: an FMU state saved with it refuses another content.
    digest: ProfileDigest,
}

/// A fingerprint of the wheel's and the rail's profile as read (CRC-32 of the file's bytes, or
/// of a built-in profile's name): an FMU state carries it, so that a state restored after its
/// profile file changed on disk is refused rather than continued with other profiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ProfileDigest {
    pub wheel: u32,
    pub rail: u32,
}

/// The largest profile file read \[bytes\]: measured profiles hold hundreds to a few thousand
/// points (MiniProf's 50–200 kB); a file beyond 16 MiB is not a profile, and reading it whole
/// would size the FMU's memory by a user's file.
pub const MAX_PROFILE_FILE_SIZE: u64 = 16 << 20;

/// The longest filter wavelength for measured profiles \[m\]: 0.1 m smooths a rail head's whole
/// width into one arc.
const MAX_FILTER_WAVELENGTH: f64 = 0.1;

/// The longest path a profile parameter may hold \[bytes\] (PATH_MAX on Linux; Windows' is shorter).
const MAX_PATH_LENGTH: usize = 4096;

/// How much of a parameter's value a message repeats \[characters\].
const SHOWN_LENGTH: usize = 200;

/// `value` as a message shows it: whole, or its first [`SHOWN_LENGTH`] characters and its length.
fn shown(value: &str) -> Cow<'_, str> {
    match value.char_indices().nth(SHOWN_LENGTH) {
        None => Cow::Borrowed(value),
        Some((end, _)) => Cow::Owned(format!("{}… ({} bytes)", &value[..end], value.len())),
    }
}

/// `wheel_profile = "…"` or `rail_profile = "…"`: how a message names the variable and its value.
fn named(kind: ProfileKind, value: &str) -> String {
    format!("{}_profile = \"{}\"", kind.name(), shown(value))
}

/// The `kind` profile `value` names — a built-in one, or the file at that path (a relative one
/// in the FMU's `resources` first, then in the working directory) — its points, and their
/// digest.
fn profile_points(kind: ProfileKind, value: &str, resources: Option<&Path>) -> Result<(ProfilePoints, u32), String> {
    if BUILTIN_PROFILE_NAMES.contains(&value) {
        let points = builtin_profile(value).map_err(|e| format!("{}: {e}", named(kind, value)))?;
        return Ok((points, crc32fast::hash(value.as_bytes())));
    }
    let Some(format) = ProfileFormat::from_file_name(value) else {
        return Err(format!(
            "{} is invalid: neither a built-in profile ({}) nor a file named .prw, .prr (SIMPACK), .whl or .ban \
             (MiniProf)",
            named(kind, value),
            BUILTIN_PROFILE_NAMES.join(", ")
        ));
    };
    // (Every extension of a format names a kind.)
    if let Some(other) = ProfileKind::from_file_name(value).filter(|named_kind| *named_kind != kind) {
        return Err(format!(
            "{} is invalid: the extension names a {} profile; {}_profile needs a {} profile (.prw or .whl for a \
             wheel, .prr or .ban for a rail)",
            named(kind, value),
            other.name(),
            kind.name(),
            kind.name()
        ));
    }
    if value.len() > MAX_PATH_LENGTH {
        return Err(format!("{} is invalid: a path is at most {MAX_PATH_LENGTH} bytes long", named(kind, value)));
    }
    let path = file_path(value, resources);
    let bytes = read_regular_file(&path, MAX_PROFILE_FILE_SIZE).map_err(|reason| {
        let looked_in = match resources {
            Some(directory) if Path::new(value).is_relative() => {
                format!(" (looked in the FMU's resources {} and the working directory)", directory.display())
            }
            _ => String::new(),
        };
        format!("{}: the file cannot be read: {reason}{looked_in}", named(kind, value))
    })?;
    // Only the numbers matter: a comment or header in Windows-1252 or Latin-1 (MiniProf's
    // `Chars=Win`) is read with its other bytes replaced.
    let text = String::from_utf8_lossy(&bytes);
    let points = match format {
        // What instruments write: read and cleaned as measured points (every header form,
        // zig-zags, back-steps, overhangs, side and z direction detected).
        ProfileFormat::MiniProf => {
            read_measured_profile(&text, format, kind, &MeasuredOptions::default()).map(|measured| measured.points)
        }
        ProfileFormat::Simpack => parse_profile_as(&text, format, kind),
    }
    .map_err(|e| format!("{}: {e}", named(kind, value)))?;
    Ok((points, crc32fast::hash(&bytes)))
}

/// [`profile_points`] as a smooth profile of a wheel's or rail's extent: a measured (MiniProf)
/// one smoothed with filter wavelength `wavelength` (CONTACT's weighted smoothing spline;
/// 0 interpolates), the others interpolated.
fn smooth_profile(
    kind: ProfileKind,
    value: &str,
    resources: Option<&Path>,
    wavelength: f64,
) -> Result<(SmoothProfile, u32), String> {
    let (points, digest) = profile_points(kind, value, resources)?;
    // (A built-in name has no file extension.)
    let measured = ProfileFormat::from_file_name(value) == Some(ProfileFormat::MiniProf);
    let profile = if measured { SmoothProfile::smoothed(&points, wavelength) } else { SmoothProfile::new(&points) };
    let profile = profile
        .and_then(|profile| profile.check_extent(kind.name()).map(|()| profile))
        .map_err(|e| format!("{}: {e}", named(kind, value)))?;
    Ok((profile, digest))
}

impl ProfileContact {
    /// Reads and places the profiles and builds the wheel with `scene` (its model, traction
    /// law, relaxation and material); the error names the variable and value.
    pub fn new(
        parameters: &Parameters,
        strings: &Strings,
        scene: Scene,
        resources: Option<&Path>,
    ) -> Result<Self, String> {
        let side = match enumeration("wheel_side", parameters.wheel_side, SideChoice::from_value, SideChoice::ITEMS)? {
            SideChoice::Right => WheelSide::Right,
            SideChoice::Left => WheelSide::Left,
        };
        let method = match enumeration(
            "contact_method",
            parameters.contact_method,
            MethodChoice::from_value,
            MethodChoice::ITEMS,
        )? {
            MethodChoice::Hertz => ContactMethod::Hertz,
            MethodChoice::NonHertzian => ContactMethod::NonHertzian,
        };
        let vertical = enumeration(
            "vertical_contact",
            parameters.vertical_contact,
            VerticalChoice::from_value,
            VerticalChoice::ITEMS,
        )?;
        let dimensions = TrackDimensions {
            gauge: parameters.track_gauge,
            gauge_measuring_height: parameters.gauge_measuring_height,
            flange_back_distance: parameters.flange_back_distance,
            flange_back_position: parameters.flange_back_position,
            nominal_radius: parameters.wheel_nominal_radius,
            rail_cant: parameters.rail_cant,
        };
        let wavelength = parameters.profile_filter_wavelength;
        if !(0.0..=MAX_FILTER_WAVELENGTH).contains(&wavelength) {
            return Err(format!(
                "profile_filter_wavelength = {wavelength} is invalid: must lie in [0, {MAX_FILTER_WAVELENGTH}] m"
            ));
        }
        let (wheel, wheel_digest) = smooth_profile(ProfileKind::Wheel, &strings.wheel_profile, resources, wavelength)?;
        let (rail, rail_digest) = smooth_profile(ProfileKind::Rail, &strings.rail_profile, resources, wavelength)?;
        let sources = format!(
            "wheel_profile = \"{}\", rail_profile = \"{}\"",
            shown(&strings.wheel_profile),
            shown(&strings.rail_profile)
        );
        let geometry = WheelOnRail::new(wheel, rail, dimensions, side, scene.shear_modulus, scene.poisson_ratio)
            .map_err(|e| format!("{e} ({sources})"))?;
        // The non-Hertzian strips' table (under half a millisecond to build on S1002, several times faster
        // steps within 2 nm of the exact gap) serves that method alone: built where it is chosen.
        let contact = WheelRailContact::new(geometry, scene).with_method(method);
        let contact = if method == ContactMethod::NonHertzian { contact.with_strip_table() } else { contact };
        Ok(Self { contact, vertical, sources, digest: ProfileDigest { wheel: wheel_digest, rail: rail_digest } })
    }

    /// The profiles' fingerprint.
    pub fn digest(&self) -> ProfileDigest {
        self.digest
    }

    /// An evaluation's error as the master reads it: one of the geometry (no contact, Hertz
    /// inapplicable, …) names the profiles it was found with; one of the scene names its input.
    pub fn describe(&self, error: WheelContactError) -> String {
        match error {
            WheelContactError::Geometry(error) => format!("{error} ({})", self.sources),
            other => other.to_string(),
        }
    }

    /// The wheel.
    pub fn contact(&self) -> &WheelRailContact {
        &self.contact
    }

    /// The core's input from the FMU's inputs; the vertical one the mode does not use is not read.
    pub fn input(&self, inputs: &Inputs) -> WheelInput {
        let (vertical, position_vertical) = match self.vertical {
            VerticalChoice::PrescribedForce => (VerticalContact::PrescribedForce(inputs.vertical_force), 0.0),
            VerticalChoice::PrescribedPosition => {
                (VerticalContact::PrescribedPosition, inputs.wheelset_vertical_position)
            }
        };
        WheelInput {
            position: WheelsetPosition {
                lateral: inputs.wheelset_lateral_displacement,
                vertical: position_vertical,
                roll: inputs.wheelset_roll_angle,
                yaw: inputs.wheelset_yaw_angle,
            },
            velocity: WheelsetVelocity {
                rolling_speed: inputs.rolling_speed,
                wheel_angular_speed: inputs.wheel_angular_speed,
                lateral_velocity: inputs.wheelset_lateral_velocity,
                yaw_rate: inputs.wheelset_yaw_rate,
            },
            vertical,
            friction_coefficient: inputs.friction_coefficient,
        }
    }
}

/// One patch's outputs (`patchK_*`): all zero for an absent patch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PatchOutputs {
    pub contact_angle: f64,
    pub rail_lateral_position: f64,
    pub rolling_radius: f64,
    pub normal_force: f64,
    pub force_longitudinal: f64,
    pub force_lateral: f64,
    pub creepage_longitudinal: f64,
    pub creepage_lateral: f64,
    pub spin_creepage: f64,
    pub semi_axis_a: f64,
    pub semi_axis_b: f64,
}

impl PatchOutputs {
    fn of(patch: &PatchForces) -> Self {
        let PatchForces { patch, output } = patch;
        Self {
            contact_angle: patch.point.contact_angle,
            rail_lateral_position: patch.point.rail_lateral,
            rolling_radius: patch.point.rolling_radius,
            normal_force: patch.normal_force,
            force_longitudinal: output.force_longitudinal,
            force_lateral: output.force_lateral,
            creepage_longitudinal: output.effective_creepage_longitudinal,
            creepage_lateral: output.effective_creepage_lateral,
            spin_creepage: output.effective_spin_creepage,
            semi_axis_a: patch.ellipse.semi_axis_a,
            semi_axis_b: patch.ellipse.semi_axis_b,
        }
    }
}

/// The wheel's outputs: all zero with `contact_geometry = ellipse`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WheelOutputs {
    pub track_force: [f64; 3],
    pub track_moment: [f64; 3],
    pub contact_patch_count: f64,
    pub wheelset_vertical_position_solved: f64,
    pub patches: [PatchOutputs; REPORTED_PATCHES],
}

impl WheelOutputs {
    pub fn of(output: &WheelOutput) -> Self {
        let mut patches = [PatchOutputs::default(); REPORTED_PATCHES];
        for (slot, patch) in patches.iter_mut().zip(&output.patches) {
            *slot = PatchOutputs::of(patch);
        }
        Self {
            track_force: output.track_force,
            track_moment: output.track_moment,
            contact_patch_count: output.patches.len() as f64,
            wheelset_vertical_position_solved: output.wheelset_vertical_position,
            patches,
        }
    }
}
