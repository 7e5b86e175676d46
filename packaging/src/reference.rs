//! The core library's outputs for rows of inputs and parameters: the reference the fmpy tests
//! compare the FMU with. The column-to-field mapping and the composition of the options (Hertz,
//! kinematics, Polach 2005, relaxation) are written here on purpose, independently of the
//! adapter's (`src/fmi/scene.rs`), from the core's public API, so that a mistake in the adapter
//! cannot hide in its own reference.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::io::{BufRead, Write};

use wheel_rail_contact::scene::hertz::{contact_modulus, HertzContact, RelativeCurvature};
use wheel_rail_contact::scene::kinematics::WheelKinematics;
use wheel_rail_contact::scene::relaxation::RelaxationLengths;
use wheel_rail_contact::{
    ContactInput, CreepForceModel, CreepForces, ExactTheory, Fastsim, Flexibility, KalkerLinear, LargeCreepage,
    MeasuredCurve, Polach, Polach2005, ShenHedrickElkins, StiffnessSource, TractionBound,
};

/// The columns written, in this order (the FMU's output names).
pub const OUTPUT_COLUMNS: [&str; 13] = [
    "force_longitudinal",
    "force_lateral",
    "adhesion_utilisation",
    "spin_moment",
    "current_friction_coefficient",
    "slip_velocity",
    "effective_creepage_longitudinal",
    "effective_creepage_lateral",
    "effective_spin_creepage",
    "contact_semi_axis_a",
    "contact_semi_axis_b",
    "max_pressure",
    "approach",
];

/// The integer-valued columns that may be left out, with the value they then take: the plain
/// scene (Polach with Kalker's stiffness, every option off).
const INTEGER_DEFAULTS: [(&str, f64); 6] = [
    ("creep_force_model", 1.0),
    ("stiffness_source", 1.0),
    ("traction_law", 1.0),
    ("hertz_contact", 0.0),
    ("creepages_from_kinematics", 0.0),
    ("creep_relaxation", 0.0),
];

/// One row: column name → value. A missing real column reads as NaN (an error where it is used).
struct Row(HashMap<String, f64>);

impl Row {
    fn get(&self, column: &str) -> f64 {
        let default = INTEGER_DEFAULTS.iter().find(|(name, _)| *name == column).map_or(f64::NAN, |(_, v)| *v);
        self.0.get(column).copied().unwrap_or(default)
    }

    fn on(&self, column: &str) -> bool {
        self.get(column) == 1.0
    }

    fn count(&self, column: &str) -> usize {
        self.get(column) as usize
    }
}

fn model(row: &Row, speed: f64) -> Result<Box<dyn CreepForceModel>, String> {
    let law = match row.get("traction_law") as i32 {
        1 => None,
        2 => Some(Polach2005::DRY),
        3 => Some(Polach2005::WET),
        4 => Some(
            Polach2005::new(
                row.get("adhesion_reduction_factor"),
                row.get("slip_reduction_factor"),
                row.get("friction_limit_ratio"),
                row.get("friction_decay_rate"),
            )
            .map_err(|e| e.to_string())?,
        ),
        other => return Err(format!("traction_law = {other}")),
    };
    let polach = || -> Result<Polach, String> {
        let stiffness = if row.get("stiffness_source") == 2.0 {
            let curve = MeasuredCurve::from_peak(
                row.get("measured_peak_adhesion"),
                row.get("measured_creepage_at_peak"),
                row.get("measured_kinetic_friction"),
            );
            StiffnessSource::MeasuredCurve(curve.map_err(|e| e.to_string())?)
        } else {
            StiffnessSource::Kalker
        };
        let large_creepage = law.map(|law| LargeCreepage::new(law, speed)).transpose().map_err(|e| e.to_string())?;
        Ok(Polach { stiffness, large_creepage })
    };
    Ok(match row.get("creep_force_model") as i32 {
        1 => Box::new(polach()?),
        2 => Box::new(KalkerLinear),
        3 => Box::new(ShenHedrickElkins),
        4 => {
            let item = |column: &str, count: usize| row.count(column).wrapping_sub(1).min(count);
            let bounds = [TractionBound::Parabolic, TractionBound::Elliptic];
            let bound = *bounds.get(item("fastsim_traction_bound", 2)).ok_or("fastsim_traction_bound")?;
            let flexibilities = [Flexibility::ThreeBlended, Flexibility::Three, Flexibility::SingleWeighted];
            let flexibility = *flexibilities.get(item("fastsim_flexibility", 3)).ok_or("fastsim_flexibility")?;
            let fastsim = Fastsim::new(row.count("fastsim_strips"), row.count("fastsim_elements"), bound, flexibility);
            Box::new(fastsim.map_err(|e| e.to_string())?)
        }
        5 => Box::new(ExactTheory::new(row.count("exact_elements_longitudinal"), row.count("exact_elements_lateral"))),
        other => return Err(format!("creep_force_model = {other}")),
    })
}

/// One row's outputs; `relaxed` is the relaxed force carried from row to row, advanced over the
/// row's `step_size` (0 or absent: set to the steady state, as at initialisation).
fn outputs(row: &Row, relaxed: &mut [f64; 2]) -> Result<[f64; 13], String> {
    let speed_input = row.get("rolling_speed");
    let (xi, eta, phi, speed) = if row.on("creepages_from_kinematics") {
        let kinematics = WheelKinematics {
            rolling_speed: speed_input,
            wheel_angular_speed: row.get("wheel_angular_speed"),
            wheel_rolling_radius: row.get("wheel_rolling_radius"),
            lateral_slip_velocity: row.get("lateral_slip_velocity"),
            spin_angular_velocity: row.get("spin_angular_velocity"),
        };
        let c = kinematics.creepages(row.get("regularisation_speed")).map_err(|e| e.to_string())?;
        (c.longitudinal, c.lateral, c.spin, c.reference_speed)
    } else {
        (row.get("creepage_longitudinal"), row.get("creepage_lateral"), row.get("spin_creepage"), speed_input.abs())
    };
    let q = row.get("normal_force");
    let (g, nu) = (row.get("shear_modulus"), row.get("poisson_ratio"));
    let (a, b, p0, approach) = if !row.on("hertz_contact") {
        let (a, b) = (row.get("semi_axis_a"), row.get("semi_axis_b"));
        (a, b, if q > 0.0 { 3.0 * q / (2.0 * PI * a * b) } else { 0.0 }, 0.0)
    } else if q <= 0.0 {
        (0.0, 0.0, 0.0, 0.0)
    } else {
        let radius = |curvature: f64| if curvature == 0.0 { f64::INFINITY } else { 1.0 / curvature };
        let curvature = RelativeCurvature::from_radii(
            row.get("wheel_rolling_radius"),
            radius(row.get("wheel_profile_curvature")),
            radius(row.get("rail_profile_curvature")),
        )
        .map_err(|e| e.to_string())?;
        let modulus = contact_modulus(g, nu).map_err(|e| e.to_string())?;
        let hertz = HertzContact::solve(q, &curvature, modulus).map_err(|e| e.to_string())?;
        (hertz.semi_axis_a, hertz.semi_axis_b, hertz.max_pressure, hertz.approach)
    };
    let contact = ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: phi,
        normal_force: q,
        // Lift-off under Hertz: no ellipse, and every model gives zero force for Q ≤ 0.
        semi_axis_a: if a > 0.0 { a } else { 1.0 },
        semi_axis_b: if b > 0.0 { b } else { 1.0 },
        friction_coefficient: row.get("friction_coefficient"),
        shear_modulus: g,
        poisson_ratio: nu,
    };
    let steady = model(row, speed)?.creep_forces(&contact).map_err(|e| e.to_string())?;
    // Polach's eqs. (21), (22): s_yC = η + aφ where that enlarges |η|; w = s_C times the speed.
    let s_yc = if (eta + a * phi).abs() > eta.abs() { eta + a * phi } else { eta };
    let slip_velocity = (xi * xi + s_yc * s_yc).sqrt() * speed;
    let mu0 = contact.friction_coefficient;
    let friction = match row.get("traction_law") as i32 {
        1 => mu0,
        2 => Polach2005::DRY.friction(mu0, slip_velocity),
        3 => Polach2005::WET.friction(mu0, slip_velocity),
        _ => Polach2005::new(
            row.get("adhesion_reduction_factor"),
            row.get("slip_reduction_factor"),
            row.get("friction_limit_ratio"),
            row.get("friction_decay_rate"),
        )
        .map_err(|e| e.to_string())?
        .friction(mu0, slip_velocity),
    };
    let forces = if row.on("creep_relaxation") {
        let steady_forces = [steady.force_longitudinal, steady.force_lateral];
        let step = row.0.get("step_size").copied().unwrap_or(0.0);
        *relaxed = if q <= 0.0 || mu0 == 0.0 {
            [0.0; 2]
        } else if step == 0.0 {
            steady_forces
        } else {
            let length = row.get("relaxation_length");
            let lengths = if length == 0.0 {
                RelaxationLengths::from_contact(a, b, nu)
            } else {
                RelaxationLengths::uniform(length)
            };
            let lengths = lengths.map_err(|e| e.to_string())?;
            lengths.advance(*relaxed, steady_forces, speed_input, step).map_err(|e| e.to_string())?
        };
        let limit = if q <= 0.0 || mu0 == 0.0 { 0.0 } else { q * friction };
        CreepForces::new(relaxed[0], relaxed[1], steady.spin_moment, limit)
    } else {
        steady
    };
    Ok([
        forces.force_longitudinal,
        forces.force_lateral,
        forces.adhesion_utilisation,
        forces.spin_moment.unwrap_or(0.0),
        friction,
        slip_velocity,
        xi,
        eta,
        phi,
        a,
        b,
        p0,
        approach,
    ])
}

/// Reads CSV whose header names FMU inputs and parameters (Enumerations as their integer
/// values; `creep_force_model`, `stiffness_source`, `traction_law` and the three option switches may be
/// left out: plain Polach, options off) plus an optional `step_size` \[s\] for creep relaxation,
/// and writes [`OUTPUT_COLUMNS`] per row with every digit. Rows are a sequence: the relaxed
/// force carries from one row to the next.
pub fn outputs_csv(input: impl BufRead, mut output: impl Write) -> Result<(), String> {
    let mut lines = input.lines();
    let header = lines.next().ok_or("empty input")?.map_err(|e| e.to_string())?;
    let columns: Vec<String> = header.split(',').map(|c| c.trim().to_owned()).collect();
    writeln!(output, "{}", OUTPUT_COLUMNS.join(",")).map_err(|e| e.to_string())?;
    let mut relaxed = [0.0; 2];
    for line in lines {
        let line = line.map_err(|e| e.to_string())?;
        let values: Vec<&str> = line.split(',').collect();
        if values.len() != columns.len() {
            return Err(format!("`{line}` has {} fields, the header {}", values.len(), columns.len()));
        }
        let mut row = HashMap::new();
        for (column, value) in columns.iter().zip(values) {
            let value: f64 = value.trim().parse().map_err(|e| format!("{column} = `{value}`: {e}"))?;
            row.insert(column.clone(), value);
        }
        let row = outputs(&Row(row), &mut relaxed)?;
        let texts: Vec<String> = row.iter().map(|v| format!("{v:?}")).collect();
        writeln!(output, "{}", texts.join(",")).map_err(|e| e.to_string())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(text: &str) -> Vec<Vec<f64>> {
        let mut output = Vec::new();
        outputs_csv(text.as_bytes(), &mut output).unwrap();
        let output = String::from_utf8(output).unwrap();
        output.lines().skip(1).map(|line| line.split(',').map(|v| v.parse().unwrap()).collect()).collect()
    }

    #[test]
    fn linear_limit_row() {
        let text = "creepage_longitudinal,creepage_lateral,spin_creepage,normal_force,semi_axis_a,semi_axis_b,\
                    friction_coefficient,shear_modulus,poisson_ratio,rolling_speed\n\
                    1e-9,0,0,1e5,6e-3,6e-3,0.3,8e10,0.28,10\n";
        let row = &rows(text)[0];
        // Kalker's linear limit F_x = −G a b C11 ξ, C11(a/b = 1, ν = 0.28) from the core's table.
        let c11 = wheel_rail_contact::KalkerCoefficients::new(1.0, 0.28).c11;
        let linear = -8e10 * 6e-3 * 6e-3 * c11 * 1e-9;
        assert!((row[0] / linear - 1.0).abs() < 1e-6, "{row:?} vs {linear}");
        assert_eq!((row[1], row[3], row[4]), (0.0, 0.0, 0.3));
        assert_eq!(row[5], 1e-8, "w = ξ|V|");
        assert_eq!(&row[9..], &[6e-3, 6e-3, 3.0 * 1e5 / (2.0 * PI * 36e-6), 0.0]);
    }

    #[test]
    fn relaxation_rows_carry_the_state() {
        let header = "creepage_longitudinal,creepage_lateral,spin_creepage,normal_force,semi_axis_a,semi_axis_b,\
                      friction_coefficient,shear_modulus,poisson_ratio,rolling_speed,creep_relaxation,\
                      relaxation_length,step_size";
        let text = format!(
            "{header}\n1e-3,0,0,1e5,6e-3,6e-3,0.3,8e10,0.28,10,1,0.01,0\n3e-3,0,0,1e5,6e-3,6e-3,0.3,8e10,0.28,10,1,0.01,1e-3\n"
        );
        let rows = rows(&text);
        let steady = |xi: f64| {
            let input = ContactInput {
                creepage_longitudinal: xi,
                creepage_lateral: 0.0,
                spin_creepage: 0.0,
                normal_force: 1e5,
                semi_axis_a: 6e-3,
                semi_axis_b: 6e-3,
                friction_coefficient: 0.3,
                shear_modulus: 8e10,
                poisson_ratio: 0.28,
            };
            Polach::default().creep_forces(&input).unwrap().force_longitudinal
        };
        assert_eq!(rows[0][0], steady(1e-3));
        // 10 mm travelled over L = 10 mm: 1 − 1/e of the way to the new steady state.
        let expected = steady(3e-3) + (steady(1e-3) - steady(3e-3)) * (-1.0f64).exp();
        assert!((rows[1][0] / expected - 1.0).abs() < 1e-14, "{} vs {expected}", rows[1][0]);
    }

    #[test]
    fn a_missing_column_is_an_error() {
        let error = outputs_csv("creepage_longitudinal\n0.001\n".as_bytes(), Vec::new()).unwrap_err();
        assert_eq!(error, "creepage_lateral = NaN is invalid: must be finite");
    }
}
