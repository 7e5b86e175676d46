//! The scene the Polach and C-ABI benchmarks share: issue 2's evaluation with spin (combined
//! ξ, η and spin in partial slip), so that their figures compare.

use wheel_rail_contact::ContactInput;

pub const WITH_SPIN: ContactInput = ContactInput {
    creepage_longitudinal: 1.5e-3,
    creepage_lateral: -0.8e-3,
    spin_creepage: 0.4,
    normal_force: 80e3,
    semi_axis_a: 6.3e-3,
    semi_axis_b: 4.1e-3,
    friction_coefficient: 0.35,
    shear_modulus: 82e9,
    poisson_ratio: 0.28,
};
