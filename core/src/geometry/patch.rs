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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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

    /// Every number of the point (a state read back is checked for them all).
    pub(crate) fn values(&self) -> [f64; 12] {
        [
            self.track_longitudinal,
            self.track_lateral,
            self.track_vertical,
            self.rail_lateral,
            self.wheel_lateral,
            self.contact_angle,
            self.rolling_radius,
            self.gap_at_zero,
            self.curvature_rolling,
            self.curvature_lateral,
            self.contact_angle_sin_cos.0,
            self.contact_angle_sin_cos.1,
        ]
    }
}

/// A loaded patch: its contact point, normal penetration, normal force and Hertz ellipse.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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

impl ContactPatch {
    /// The patch a fraction `t` of the way from `self` to `other` (t outside [0, 1]: beyond
    /// them on their line), every quantity linear in t, the contact angle's sine and cosine
    /// taken from it: the patch solved between two z_ws by linear interpolation in z_ws
    /// (`crate::wheel`'s non-Hertzian balance; error ½ P'' (z − z₀)(z − z₁)).
    pub(crate) fn interpolated(&self, other: &Self, t: f64) -> Self {
        let at = |a: f64, b: f64| a + t * (b - a);
        let (p, q) = (&self.point, &other.point);
        let contact_angle = at(p.contact_angle, q.contact_angle);
        let point = ContactPoint {
            track_longitudinal: at(p.track_longitudinal, q.track_longitudinal),
            track_lateral: at(p.track_lateral, q.track_lateral),
            track_vertical: at(p.track_vertical, q.track_vertical),
            rail_lateral: at(p.rail_lateral, q.rail_lateral),
            wheel_lateral: at(p.wheel_lateral, q.wheel_lateral),
            contact_angle,
            rolling_radius: at(p.rolling_radius, q.rolling_radius),
            gap_at_zero: at(p.gap_at_zero, q.gap_at_zero),
            curvature_rolling: at(p.curvature_rolling, q.curvature_rolling),
            curvature_lateral: at(p.curvature_lateral, q.curvature_lateral),
            contact_angle_sin_cos: contact_angle.sin_cos(),
        };
        let (e, f) = (&self.ellipse, &other.ellipse);
        let ellipse = HertzContact {
            semi_axis_a: at(e.semi_axis_a, f.semi_axis_a),
            semi_axis_b: at(e.semi_axis_b, f.semi_axis_b),
            max_pressure: at(e.max_pressure, f.max_pressure),
            approach: at(e.approach, f.approach),
        };
        Self {
            point,
            penetration: at(self.penetration, other.penetration),
            normal_force: at(self.normal_force, other.normal_force),
            ellipse,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{ContactPatch, ContactPoint, HertzContact};

    fn patch(scale: f64, angle: f64) -> ContactPatch {
        let point = ContactPoint {
            track_longitudinal: scale,
            track_lateral: 2.0 * scale,
            track_vertical: 3.0 * scale,
            rail_lateral: 4.0 * scale,
            wheel_lateral: 5.0 * scale,
            contact_angle: angle,
            rolling_radius: 6.0 * scale,
            gap_at_zero: 7.0 * scale,
            curvature_rolling: 8.0 * scale,
            curvature_lateral: 9.0 * scale,
            contact_angle_sin_cos: angle.sin_cos(),
        };
        let ellipse = HertzContact {
            semi_axis_a: 10.0 * scale,
            semi_axis_b: 11.0 * scale,
            max_pressure: 12.0 * scale,
            approach: 13.0 * scale,
        };
        ContactPatch { point, penetration: 14.0 * scale, normal_force: 15.0 * scale, ellipse }
    }

    /// Every quantity of an interpolated patch lies on the line through the two patches' (here
    /// each one a multiple of the scale, so the patch at t is the one of scale 1 + t), its
    /// angle's sine and cosine taken from its angle.
    #[test]
    fn a_patch_is_interpolated_linearly_in_every_quantity() {
        let (from, to) = (patch(1.0, -0.2), patch(2.0, -1.0));
        assert_eq!(from.interpolated(&to, 0.0), from);
        for t in [0.25, 1.0, 1.5, -0.5] {
            let between = from.interpolated(&to, t);
            let expected = patch(1.0 + t, -0.2 - 0.8 * t);
            let (p, q) = (between.point, expected.point);
            let pairs = [
                (p.track_longitudinal, q.track_longitudinal),
                (p.track_lateral, q.track_lateral),
                (p.track_vertical, q.track_vertical),
                (p.rail_lateral, q.rail_lateral),
                (p.wheel_lateral, q.wheel_lateral),
                (p.contact_angle, q.contact_angle),
                (p.rolling_radius, q.rolling_radius),
                (p.gap_at_zero, q.gap_at_zero),
                (p.curvature_rolling, q.curvature_rolling),
                (p.curvature_lateral, q.curvature_lateral),
                (p.contact_angle_sin_cos.0, q.contact_angle_sin_cos.0),
                (p.contact_angle_sin_cos.1, q.contact_angle_sin_cos.1),
                (between.ellipse.semi_axis_a, expected.ellipse.semi_axis_a),
                (between.ellipse.semi_axis_b, expected.ellipse.semi_axis_b),
                (between.ellipse.max_pressure, expected.ellipse.max_pressure),
                (between.ellipse.approach, expected.ellipse.approach),
                (between.penetration, expected.penetration),
                (between.normal_force, expected.normal_force),
            ];
            for (k, (got, want)) in pairs.into_iter().enumerate() {
                assert!((got - want).abs() <= 1e-14 * want.abs().max(1.0), "t {t}, quantity {k}: {got} against {want}");
            }
        }
    }
}
