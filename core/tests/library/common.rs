//! Shared fixtures for the integration tests.

use wheel_rail_contact::geometry::{
    read_measured_profile, MeasuredOptions, MeasuredProfile, ProfileError, ProfileFormat, ProfileKind,
};
use wheel_rail_contact::scene::SceneOutput;
use wheel_rail_contact::{ContactInput, Fastsim, Flexibility, ModelChoice, TractionBound};

pub use wheel_rail_contact::reference_cases as published;

/// The published CONTACT case 2 contact (a = 8 mm, b = 4 mm, N = 82 kN, G = 82 GPa, ν = 0.28,
/// μ = 0.3) with no creepage; tests set the creepages they need.
pub fn contact_case() -> ContactInput {
    ContactInput { creepage_lateral: 0.0, spin_creepage: 0.0, ..published::FASTSIM_CASE }
}

/// `contact_case()` with semi-axes for ratio a/b around a fixed area ab = 32 mm², Poisson ratio ν
/// and creepages (ξ, η, φ).
pub fn contact(a_over_b: f64, nu: f64, xi: f64, eta: f64, phi: f64) -> ContactInput {
    let area = 32e-6;
    let b = (area / a_over_b).sqrt();
    ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: phi,
        semi_axis_a: a_over_b * b,
        semi_axis_b: b,
        poisson_ratio: nu,
        ..contact_case()
    }
}

/// Relative difference |x − y| / max(|x|, |y|) (0 when both are 0).
pub fn relative_difference(x: f64, y: f64) -> f64 {
    let scale = x.abs().max(y.abs());
    if scale == 0.0 {
        0.0
    } else {
        (x - y).abs() / scale
    }
}

/// A typical wheel–rail contact (a/b = 1.5) with the given creepages.
pub fn typical_contact(xi: f64, eta: f64, phi: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: phi,
        normal_force: 80e3,
        semi_axis_a: 6e-3,
        semi_axis_b: 4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 8e10,
        poisson_ratio: 0.28,
    }
}

/// FASTSIM on n × n with CONTACT's blended flexibilities (the default).
pub fn fastsim(n: usize, bound: TractionBound) -> Fastsim {
    Fastsim::new(n, n, bound, Flexibility::ThreeBlended).unwrap()
}

/// Every rung for real-time use at its default (`ModelChoice::RUNGS`; the exact theory's default
/// grid is for offline use, so the tests that include it choose a small grid themselves), and
/// FASTSIM with its other bound and flexibilities.
pub fn all_models() -> Vec<ModelChoice> {
    let mut models: Vec<ModelChoice> = ModelChoice::RUNGS
        .iter()
        .filter(|rung| !rung.offline)
        .map(|rung| (rung.default_model)().unwrap_or_else(|e| panic!("{}: {e}", rung.name)))
        .collect();
    models.extend([
        ModelChoice::Fastsim(fastsim(20, TractionBound::Elliptic)),
        ModelChoice::Fastsim(Fastsim::new(20, 20, TractionBound::Parabolic, Flexibility::Three).unwrap()),
        ModelChoice::Fastsim(Fastsim::new(15, 25, TractionBound::Parabolic, Flexibility::SingleWeighted).unwrap()),
    ]);
    models
}

/// The models of [`all_models`] whose forces are bounded by μQ.
pub fn saturating_models() -> Vec<ModelChoice> {
    all_models().into_iter().filter(|model| model.rung().friction_limited).collect()
}

/// A direction with no rate at all; tests set the rates they need.
pub const NO_RATES: ContactInput = ContactInput {
    creepage_longitudinal: 0.0,
    creepage_lateral: 0.0,
    spin_creepage: 0.0,
    normal_force: 0.0,
    semi_axis_a: 0.0,
    semi_axis_b: 0.0,
    friction_coefficient: 0.0,
    shear_modulus: 0.0,
    poisson_ratio: 0.0,
};

/// The input moved by `t` along `direction`.
pub fn moved(x: &ContactInput, d: &ContactInput, t: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: x.creepage_longitudinal + t * d.creepage_longitudinal,
        creepage_lateral: x.creepage_lateral + t * d.creepage_lateral,
        spin_creepage: x.spin_creepage + t * d.spin_creepage,
        normal_force: x.normal_force + t * d.normal_force,
        semi_axis_a: x.semi_axis_a + t * d.semi_axis_a,
        semi_axis_b: x.semi_axis_b + t * d.semi_axis_b,
        friction_coefficient: x.friction_coefficient + t * d.friction_coefficient,
        shear_modulus: x.shear_modulus + t * d.shear_modulus,
        poisson_ratio: x.poisson_ratio,
    }
}

/// A scene's outputs as one vector: every field the FMU outputs, in its order.
pub fn scene_outputs(o: &SceneOutput) -> [f64; 13] {
    [
        o.force_longitudinal,
        o.force_lateral,
        o.adhesion_utilisation,
        o.spin_moment,
        o.current_friction_coefficient,
        o.slip_velocity,
        o.effective_creepage_longitudinal,
        o.effective_creepage_lateral,
        o.effective_spin_creepage,
        o.contact_semi_axis_a,
        o.contact_semi_axis_b,
        o.max_pressure,
        o.approach,
    ]
}

/// The text of a measured profile of `core/tests/data/profiles/measured/` (its README).
pub fn measured_text(name: &str) -> String {
    std::fs::read_to_string(format!("{}/tests/data/profiles/measured/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// `text` read as the file `name` is, its format and kind from the name, default options (as
/// the FMU reads a profile file).
pub fn read_measured_as(text: &str, name: &str) -> Result<MeasuredProfile, ProfileError> {
    let (format, kind) = (ProfileFormat::from_file_name(name).unwrap(), ProfileKind::from_file_name(name).unwrap());
    read_measured_profile(text, format, kind, &MeasuredOptions::default())
}

/// The measured profile `name`, read ([`read_measured_as`]).
pub fn read_measured(name: &str) -> MeasuredProfile {
    read_measured_as(&measured_text(name), name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// One contact patch of CONTACT's full solution as `core/tests/data/contact_worn_right.py`
/// extracts it (the worn-profile and the rolling references), in our units and signs (forces on
/// the wheel).
pub struct ContactPatchRow {
    pub case: u32,
    /// y_ws \[m\].
    pub lateral: f64,
    /// The prescribed F_z \[N\] (NaN where CONTACT found no solution).
    pub vertical_force: f64,
    /// The patch's contact reference on the rail \[m\].
    pub rail_lateral: f64,
    pub contact_angle: f64,
    pub normal_force: f64,
    /// F_x, F_s on the wheel \[N\].
    pub creep_forces: [f64; 2],
    /// The totals on the wheel in track coordinates \[N\].
    pub track_force: [f64; 3],
}

/// The rows of such a CSV file: case, y_ws, z_ws, fz_tr, fx_tr, fy_tr, patches, patch, ycp_r,
/// deltcp, cksi, ceta, cphi, fn, fx, fs (CONTACT's mm, N; forces on the rail).
pub fn contact_patch_rows(csv: &str) -> Vec<ContactPatchRow> {
    csv.lines()
        .filter(|line| !line.starts_with('#') && !line.starts_with("case"))
        .map(|line| {
            let f: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
            ContactPatchRow {
                case: f[0] as u32,
                lateral: f[1] * 1e-3,
                vertical_force: f[3],
                rail_lateral: f[8] * 1e-3,
                contact_angle: f[9],
                normal_force: f[13],
                creep_forces: [-f[14], -f[15]],
                track_force: [-f[4], -f[5], -f[3]],
            }
        })
        .collect()
}
