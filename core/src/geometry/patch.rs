//! The contact's result types, apart from the search that finds them ([`super::contact`]) and the
//! normal problem that loads them ([`super::normal_problem`]): which wheel, where a contact point
//! is and what its surfaces' curvatures are, and a loaded patch with its Hertz ellipse.

use crate::hertz::HertzContact;

/// Which wheel of the wheelset, on which rail.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WheelSide {
    /// y > 0: the profiles as given.
    Right,
    /// y < 0: the profiles mirrored in y, as CONTACT does.
    Left,
}

impl WheelSide {
    /// A right-side point seen on this side: lateral positions (track and both profiles', as
    /// CONTACT reports them for the left side) and the contact angle change sign.
    pub(super) fn mirror_point(self, point: &ContactPoint) -> ContactPoint {
        match self {
            Self::Right => *point,
            Self::Left => ContactPoint {
                track_lateral: -point.track_lateral,
                rail_lateral: -point.rail_lateral,
                wheel_lateral: -point.wheel_lateral,
                contact_angle: -point.contact_angle,
                contact_angle_sin_cos: (-point.contact_angle_sin_cos.0, point.contact_angle_sin_cos.1),
                ..*point
            },
        }
    }

    pub(super) fn mirror_patches(self, mut patches: Vec<ContactPatch>) -> Vec<ContactPatch> {
        if self == Self::Left {
            for patch in &mut patches {
                patch.point = self.mirror_point(&patch.point);
            }
        }
        patches
    }
}

/// One contact point's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Track x \[m\]: ahead of the wheelset's centre (non-zero with yaw).
    pub track_longitudinal: f64,
    /// Track y \[m\].
    pub track_lateral: f64,
    /// Track z of the rail surface \[m\].
    pub track_vertical: f64,
    /// y in the rail profile's coordinates \[m\].
    pub rail_lateral: f64,
    /// y in the wheel profile's coordinates \[m\].
    pub wheel_lateral: f64,
    /// The surfaces' inclination atan(dz/dy) in track coordinates \[rad\] (CONTACT's DELTCP).
    pub contact_angle: f64,
    /// The wheel's rolling radius at the contact point \[m\]: its depth below the axle in the
    /// wheel's plane (r0 + z_wheel without yaw; with yaw the point lies ahead of or behind the
    /// axle, and this is r cos θ, as CONTACT's r0 + ZCP(W)).
    pub rolling_radius: f64,
    /// The undeformed vertical gap at the contact point with z_ws = 0 \[m\].
    pub gap_at_zero: f64,
    /// Relative curvature along x, A \[1/m\] (module doc, "Ellipse"; cos γ/(2 r) without yaw).
    pub curvature_rolling: f64,
    /// Relative curvature along the patch's lateral axis, B \[1/m\] ((κ_rail − κ_wheel)/2 without
    /// yaw).
    pub curvature_lateral: f64,
    /// sin δ and cos δ of `contact_angle`, taken once with the point: a wheel step reads them
    /// in every round of its vertical balance, per patch, three times.
    pub(super) contact_angle_sin_cos: (f64, f64),
}

impl ContactPoint {
    /// sin δ and cos δ of the contact angle.
    pub(crate) fn contact_angle_sin_cos(&self) -> (f64, f64) {
        self.contact_angle_sin_cos
    }
}

/// A loaded patch: its contact point, normal penetration, normal force and Hertz ellipse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPatch {
    /// Where it is.
    pub point: ContactPoint,
    /// Penetration along the contact normal \[m\].
    pub penetration: f64,
    /// Normal force \[N\].
    pub normal_force: f64,
    /// Hertz's ellipse for that force.
    pub ellipse: HertzContact,
}
