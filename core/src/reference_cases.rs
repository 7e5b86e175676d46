//! CONTACT's published reference cases as data, in SI units, to check a model choice against:
//! the one definition the tests, the benchmarks and the lab's trade report use (and, not published,
//! the scene two benchmarks share, [`BENCHMARK_WITH_SPIN`]).
//! Source and the full tables: `core/tests/data/contact_published_cases.md` (open-source CONTACT, <https://github.com/eve70a/CONTACT>, `examples/tractcurv`
//! and `examples/fastsim`, Apache-2.0).

use crate::{ContactInput, TractionBound};

/// Case 1 (`examples/tractcurv`, Eurosprinter): a/b = 0.5, N = 106.7 kN, μ = 0.33; pure ξ, which
/// each point sets.
pub const TRACTCURV_CONTACT: ContactInput = ContactInput {
    creepage_longitudinal: 0.0,
    creepage_lateral: 0.0,
    spin_creepage: 0.0,
    normal_force: 106.7e3,
    semi_axis_a: 6.304e-3,
    semi_axis_b: 12.61e-3,
    friction_coefficient: 0.33,
    shear_modulus: 82e9,
    poisson_ratio: 0.28,
};

/// Case 1, Kalker's exact theory: (ξ [%], F_x/(μN)), the whole published curve.
pub const TRACTCURV_EXACT: [(f64, f64); 30] = [
    (0.001, -0.0070),
    (0.04, -0.2588),
    (0.08, -0.4743),
    (0.12, -0.6481),
    (0.16, -0.7830),
    (0.2, -0.8815),
    (0.24, -0.9466),
    (0.28, -0.9832),
    (0.32, -0.9977),
    (0.36, -0.9991),
    (0.4, -0.9991),
    (0.44, -0.9994),
    (0.48, -0.9994),
    (0.52, -0.9997),
    (0.56, -0.9997),
    (0.6, -0.9997),
    (0.8, -0.9997),
    (1.0, -1.0),
    (2.0, -1.0),
    (3.0, -1.0),
    (4.0, -1.0),
    (5.0, -1.0),
    (7.5, -1.0),
    (10.0, -1.0),
    (12.5, -1.0),
    (15.0, -1.0),
    (17.5, -1.0),
    (20.0, -1.0),
    (22.5, -1.0),
    (25.0, -1.0),
];

/// Case 2 (`examples/fastsim`): a = 8 mm, b = 4 mm, N = 82 kN, G = 82 GPa, ν = 0.28, μ = 0.3,
/// ξ = 0, η = −6.25e-4, φ = 6.25e-4 /mm.
pub const FASTSIM_CASE: ContactInput = ContactInput {
    creepage_longitudinal: 0.0,
    creepage_lateral: -6.25e-4,
    spin_creepage: 0.625,
    normal_force: 82e3,
    semi_axis_a: 8e-3,
    semi_axis_b: 4e-3,
    friction_coefficient: 0.3,
    shear_modulus: 82e9,
    poisson_ratio: 0.28,
};

/// One published result for case 2: F_y/(μN) and M_z [N·m].
#[derive(Debug, Clone, Copy)]
pub struct Published {
    pub force_lateral_ratio: f64,
    pub spin_moment: f64,
}

/// Case 2, Kalker's exact theory (CONTACT, 44 × 44 grid).
pub const FASTSIM_CASE_EXACT: Published = Published { force_lateral_ratio: -0.6074, spin_moment: -48.21 };

/// Case 2 solved by CONTACT's FASTSIM (material model M = 3: three flexibilities as blended by
/// CONTACT's `simpflex`) on its rectangular grid over 1.1 × the contact: 44 × 44 elements
/// (`elements_in_contact` = 40) or 220 × 220 (200).
#[derive(Debug, Clone, Copy)]
pub struct PublishedFastsim {
    pub bound: TractionBound,
    pub elements_in_contact: usize,
    pub result: Published,
}

/// Case 2, CONTACT's FASTSIM results as published.
pub const FASTSIM_CASE_CONTACT_FASTSIM: [PublishedFastsim; 4] = [
    contact_fastsim(TractionBound::Parabolic, 40, -0.6118, -39.00),
    contact_fastsim(TractionBound::Elliptic, 40, -0.6016, -48.29),
    contact_fastsim(TractionBound::Parabolic, 200, -0.6359, -37.98),
    contact_fastsim(TractionBound::Elliptic, 200, -0.5956, -45.30),
];

const fn contact_fastsim(
    bound: TractionBound,
    elements_in_contact: usize,
    force_lateral_ratio: f64,
    spin_moment: f64,
) -> PublishedFastsim {
    PublishedFastsim { bound, elements_in_contact, result: Published { force_lateral_ratio, spin_moment } }
}

/// Not a published case: issue 2's evaluation with spin (combined ξ, η and spin in partial slip),
/// the one scene the Polach benchmark (`benches/polach.rs`) and the FMU's C-ABI step benchmark
/// (`fmu/benches/fmu_step.rs`) share, so that their figures compare.
pub const BENCHMARK_WITH_SPIN: ContactInput = ContactInput {
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
