//! `contact_geometry = profiles`: the FMU's values ↔ the core's [`WheelRailContact`] (one wheel
//! on its rail, from its profiles). Here, and only here, the adapter reads files: the core has no
//! I/O, so a profile given as a path is read into text and handed to the core's reader
//! ([`parse_profile`], the format from the extension); a built-in name goes to
//! [`builtin_profile`]. Errors name the variable, the file and the reason (the core's
//! [`ProfileError`](wheel_rail_contact::geometry::ProfileError) gives the line).
//!
//! Outputs: the totals on the wheel in track axes, the solved vertical position and, for the
//! first two patches (tread first, as the core orders them), their geometry, forces and
//! creepages. A third patch, rare, is in the totals only.

use super::model_description::{
    Inputs, Parameters, Strings, VerticalContact as VerticalChoice, WheelSide as SideChoice,
};
use super::resources::file_path;
use super::scene::enumeration;
use std::path::Path;
use wheel_rail_contact::geometry::{
    builtin_profile, parse_profile, PatchForces, ProfileFormat, ProfilePoints, SmoothProfile, TrackDimensions,
    VerticalContact, WheelInput, WheelOnRail, WheelOutput, WheelRailContact, WheelSide, WheelsetPosition,
    WheelsetVelocity, BUILTIN_PROFILE_NAMES,
};
use wheel_rail_contact::scene::Scene;

/// How many patches have their own outputs (`patch1_*`, `patch2_*`).
pub const REPORTED_PATCHES: usize = 2;

/// A wheel on its rail as the parameters place it, and how its vertical contact is set.
#[derive(Debug, Clone)]
pub struct ProfileContact {
    contact: WheelRailContact,
    vertical: VerticalChoice,
}

/// The points of the profile `variable` names: a built-in one, or the file at that path (a
/// relative one in the FMU's `resources` first, then in the working directory).
fn profile_points(variable: &str, value: &str, resources: Option<&Path>) -> Result<ProfilePoints, String> {
    if BUILTIN_PROFILE_NAMES.contains(&value) {
        return builtin_profile(value).map_err(|e| format!("{variable} = \"{value}\": {e}"));
    }
    let Some(format) = ProfileFormat::from_file_name(value) else {
        return Err(format!(
            "{variable} = \"{value}\" is invalid: neither a built-in profile ({}) nor a file named .prw, .prr \
             (SIMPACK), .whl or .ban (MiniProf)",
            BUILTIN_PROFILE_NAMES.join(", ")
        ));
    };
    let path = file_path(value, resources);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        let looked_in = match resources {
            Some(directory) if Path::new(value).is_relative() => {
                format!(" (looked in the FMU's resources {} and the working directory)", directory.display())
            }
            _ => String::new(),
        };
        format!("{variable} = \"{value}\": the file cannot be read ({e}){looked_in}")
    })?;
    parse_profile(&text, format).map_err(|e| format!("{variable} = \"{value}\": {e}"))
}

fn smooth_profile(variable: &str, value: &str, resources: Option<&Path>) -> Result<SmoothProfile, String> {
    SmoothProfile::new(&profile_points(variable, value, resources)?)
        .map_err(|e| format!("{variable} = \"{value}\": {e}"))
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
        let geometry = WheelOnRail::new(
            smooth_profile("wheel_profile", &strings.wheel_profile, resources)?,
            smooth_profile("rail_profile", &strings.rail_profile, resources)?,
            dimensions,
            side,
            scene.shear_modulus,
            scene.poisson_ratio,
        )
        .map_err(|e| e.to_string())?;
        Ok(Self { contact: WheelRailContact::new(geometry, scene), vertical })
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
