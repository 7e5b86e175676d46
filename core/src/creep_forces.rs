//! What every creep-force model returns.

use crate::numerics::{magnitude, value, Scalar};

/// Tangential contact forces on the wheel, in SI units.
///
/// Sign convention (Kalker, CONTACT; ERRATA E4): forces act on the wheel and oppose the
/// creepages, so in the linear range F_x = −G·ab·C11·ξ.
///
/// `T` is `f64` for forces; [`crate::CreepForceModel::directional_derivative`] returns the same
/// structure holding derivatives.
///
/// ```
/// use wheel_rail_contact::CreepForces;
///
/// // 3 kN and 4 kN under μQ = 10 kN: half the Coulomb limit used.
/// let forces = CreepForces::new(-3e3, 4e3, None, 10e3);
/// assert_eq!(forces.adhesion_utilisation, 0.5);
/// assert_eq!(CreepForces::new(0.0, 0.0, Some(0.0), 0.0).adhesion_utilisation, 0.0, "no limit, no utilisation");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepForces<T = f64> {
    /// Longitudinal force F_x \[N\].
    pub force_longitudinal: T,
    /// Lateral force F_y \[N\].
    pub force_lateral: T,
    /// Spin moment M_z [N·m] about the contact normal; `None` for models that do not compute it
    /// (Polach's method neglects it, see the paper's discussion before eq. 16).
    pub spin_moment: Option<T>,
    /// Adhesion utilisation |F|/(μQ) \[1\]; 0 when μQ = 0.
    pub adhesion_utilisation: T,
}

impl<T: Scalar> CreepForces<T> {
    /// Forces with their utilisation of the Coulomb limit `friction_limit` = μQ.
    pub fn new(force_longitudinal: T, force_lateral: T, spin_moment: Option<T>, friction_limit: T) -> Self {
        let adhesion_utilisation = if value(friction_limit) > 0.0 {
            magnitude(force_longitudinal, force_lateral) / friction_limit
        } else {
            T::from(0.0)
        };
        Self { force_longitudinal, force_lateral, spin_moment, adhesion_utilisation }
    }

    /// No force at all (lift-off, no friction, no creepage).
    pub(crate) fn zero() -> Self {
        let zero = T::from(0.0);
        Self { force_longitudinal: zero, force_lateral: zero, spin_moment: None, adhesion_utilisation: zero }
    }
}
