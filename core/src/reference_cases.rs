//! CONTACT's published reference cases as data, in SI units, to check a model choice against:
//! the one definition the tests, the benchmarks and the lab's trade report use (and, not published,
//! the scene two benchmarks share, [`BENCHMARK_WITH_SPIN`]); and the Manchester contact
//! benchmark's case A-2.2 with CONTACT's full solution for a wheel from profiles
//! ([`manchester_a22`]).
//! Source and the full tables: `core/tests/data/contact_published_cases.md` (open-source CONTACT, <https://github.com/eve70a/CONTACT>, `examples/tractcurv`
//! and `examples/fastsim`, Apache-2.0).

use crate::geometry::{WheelSide, WheelsetPosition};
use crate::wheel::{VerticalContact, WheelInput, WheelsetVelocity};
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

/// One case of the Manchester contact benchmark A-2.2 (S1002 on UIC60 1:40 on the benchmark's
/// track, 10 kN per wheel, V = 2 m/s, μ = 0.3; both wheels, 21 cases each) with CONTACT's
/// published full solution (rev. 2707, `examples/mbench_a22_{right,left}.ref_out`, Apache-2.0;
/// `core/tests/data/mbench_a22_contact_ref_out.csv` and `manchester_a22_inputs.csv`), in this
/// crate's terms: SI units, forces on the wheel (the negatives of CONTACT's on the rail).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ManchesterA22 {
    pub side: WheelSide,
    /// The case number, 1–21.
    pub case: u32,
    /// The wheelset's pose and motion, the prescribed 10 kN and μ.
    pub input: WheelInput,
    /// CONTACT's contact reference point on the rail (rail profile y) \[m\].
    pub rail_lateral: f64,
    /// CONTACT's contact angle there \[rad\].
    pub contact_angle: f64,
    /// CONTACT's normal force \[N\].
    pub normal_force: f64,
    /// CONTACT's creep forces on the wheel in the patch's tangent plane, F_x and F_s \[N\].
    pub creep_forces: [f64; 2],
    /// CONTACT's total force on the wheel in track axes \[N\].
    pub track_force: [f64; 3],
}

/// Every A-2.2 case, the right wheel's first.
///
/// ```
/// use wheel_rail_contact::geometry::WheelSide;
/// use wheel_rail_contact::reference_cases::manchester_a22;
///
/// let cases = manchester_a22();
/// assert_eq!(cases.len(), 42);
/// // Right wheel, case 3: y_ws = 1 mm, CONTACT's patch at rail y = −18.54 mm carrying 9827 N.
/// let case = cases.iter().find(|c| c.side == WheelSide::Right && c.case == 3).unwrap();
/// assert_eq!(case.input.position.lateral, 1e-3);
/// assert!((case.rail_lateral + 18.5418e-3).abs() < 1e-9 && case.normal_force == 9827.0);
/// ```
pub fn manchester_a22() -> Vec<ManchesterA22> {
    let numbers = |line: &str| -> Vec<f64> { line.split(',').skip(1).map(|v| v.parse().expect("a number")).collect() };
    let inputs = include_str!("../tests/data/manchester_a22_inputs.csv");
    let outputs = include_str!("../tests/data/mbench_a22_contact_ref_out.csv");
    let mut cases = Vec::new();
    for (name, side) in [("right", WheelSide::Right), ("left", WheelSide::Left)] {
        let prefix = format!("{name},");
        for line in outputs.lines().filter(|l| l.starts_with(&prefix)) {
            // case, y_ws, z_ws, roll, yaw, fx_tr … fz_tr, xcp … deltcp_tr, ycp_r, …, fn, fx, fs (CONTACT's units: mm, N).
            let f = numbers(line);
            let case = f[0] as u32;
            let pitch = inputs
                .lines()
                .find(|l| l.starts_with(&format!("{prefix}{case},")))
                .and_then(|l| l.rsplit(',').next())
                .and_then(|v| v.parse::<f64>().ok())
                .expect("the case's inputs");
            cases.push(ManchesterA22 {
                side,
                case,
                input: WheelInput {
                    position: WheelsetPosition { lateral: f[1] * 1e-3, vertical: 0.0, roll: f[3], yaw: f[4] },
                    // CONTACT's VPITCH is −Ω.
                    velocity: WheelsetVelocity {
                        rolling_speed: 2.0,
                        wheel_angular_speed: -pitch,
                        ..Default::default()
                    },
                    vertical: VerticalContact::PrescribedForce(10e3),
                    friction_coefficient: 0.3,
                },
                rail_lateral: f[12] * 1e-3,
                contact_angle: f[11],
                normal_force: f[21],
                creep_forces: [-f[22], -f[23]],
                track_force: [-f[5], -f[6], -f[7]],
            });
        }
    }
    cases
}
