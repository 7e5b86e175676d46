//! What every creep-force model returns.

use crate::numerics::magnitude;

/// Tangential contact forces on the wheel, in SI units.
///
/// Sign convention (Kalker, CONTACT; ERRATA E4): forces act on the wheel and oppose the
/// creepages, so in the linear range F_x = −G·ab·C11·ξ.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepForces {
    /// Longitudinal force F_x [N].
    pub force_longitudinal: f64,
    /// Lateral force F_y [N].
    pub force_lateral: f64,
    /// Spin moment M_z [N·m] about the contact normal; `None` for models that do not compute it
    /// (Polach's method neglects it, see the paper's discussion before eq. 16).
    pub spin_moment: Option<f64>,
    /// Adhesion utilisation |F|/(μQ) [1]; 0 when μQ = 0.
    pub adhesion_utilisation: f64,
}

impl CreepForces {
    /// Forces with their utilisation of the Coulomb limit `friction_limit` = μQ.
    pub fn new(force_longitudinal: f64, force_lateral: f64, spin_moment: Option<f64>, friction_limit: f64) -> Self {
        let adhesion_utilisation =
            if friction_limit > 0.0 { magnitude(force_longitudinal, force_lateral) / friction_limit } else { 0.0 };
        Self { force_longitudinal, force_lateral, spin_moment, adhesion_utilisation }
    }
}
