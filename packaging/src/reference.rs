//! The core library's forces for rows of inputs: the reference the fmpy tests compare the
//! FMU with. The column-to-field mapping is written here on purpose, independently of the
//! adapter's, so that a mapping mistake in the adapter cannot hide in its own reference.

use std::io::{BufRead, Write};

use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

fn set(input: &mut ContactInput, column: &str, value: f64) -> Result<(), String> {
    let field = match column {
        "creepage_longitudinal" => &mut input.creepage_longitudinal,
        "creepage_lateral" => &mut input.creepage_lateral,
        "spin_creepage" => &mut input.spin_creepage,
        "normal_force" => &mut input.normal_force,
        "semi_axis_a" => &mut input.semi_axis_a,
        "semi_axis_b" => &mut input.semi_axis_b,
        "friction_coefficient" => &mut input.friction_coefficient,
        "shear_modulus" => &mut input.shear_modulus,
        "poisson_ratio" => &mut input.poisson_ratio,
        other => return Err(format!("unknown column {other}")),
    };
    *field = value;
    Ok(())
}

/// Reads CSV with a header of input names (all nine of [`ContactInput`]) and writes
/// `force_longitudinal,force_lateral,adhesion_utilisation` per row, with every digit
/// (Polach's method, Kalker stiffness).
pub fn forces_csv(input: impl BufRead, mut output: impl Write) -> Result<(), String> {
    let mut lines = input.lines();
    let header = lines.next().ok_or("empty input")?.map_err(|e| e.to_string())?;
    let columns: Vec<String> = header.split(',').map(|c| c.trim().to_owned()).collect();
    writeln!(output, "force_longitudinal,force_lateral,adhesion_utilisation").map_err(|e| e.to_string())?;
    for line in lines {
        let line = line.map_err(|e| e.to_string())?;
        let mut contact = ContactInput {
            creepage_longitudinal: f64::NAN,
            creepage_lateral: f64::NAN,
            spin_creepage: f64::NAN,
            normal_force: f64::NAN,
            semi_axis_a: f64::NAN,
            semi_axis_b: f64::NAN,
            friction_coefficient: f64::NAN,
            shear_modulus: f64::NAN,
            poisson_ratio: f64::NAN,
        };
        let values: Vec<&str> = line.split(',').collect();
        if values.len() != columns.len() {
            return Err(format!("`{line}` has {} fields, the header {}", values.len(), columns.len()));
        }
        for (column, value) in columns.iter().zip(values) {
            let value = value.trim().parse().map_err(|e| format!("{column} = `{value}`: {e}"))?;
            set(&mut contact, column, value)?;
        }
        let forces = Polach::default().creep_forces(&contact).map_err(|e| e.to_string())?;
        writeln!(
            output,
            "{:?},{:?},{:?}",
            forces.force_longitudinal, forces.force_lateral, forces.adhesion_utilisation
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_limit_row() {
        let text = "creepage_longitudinal,creepage_lateral,spin_creepage,normal_force,semi_axis_a,semi_axis_b,\
                    friction_coefficient,shear_modulus,poisson_ratio\n1e-9,0,0,1e5,6e-3,6e-3,0.3,8e10,0.28\n";
        let mut output = Vec::new();
        forces_csv(text.as_bytes(), &mut output).unwrap();
        let output = String::from_utf8(output).unwrap();
        let row: Vec<f64> = output.lines().nth(1).unwrap().split(',').map(|v| v.parse().unwrap()).collect();
        // Kalker's linear limit F_x = −G a b C11 ξ, C11(a/b = 1, ν = 0.28) from the core's table.
        let c11 = wheel_rail_contact::KalkerCoefficients::new(1.0, 0.28).c11;
        let linear = -8e10 * 6e-3 * 6e-3 * c11 * 1e-9;
        assert!((row[0] / linear - 1.0).abs() < 1e-6, "{row:?} vs {linear}");
        assert_eq!(row[1], 0.0);
    }

    #[test]
    fn a_missing_column_is_an_error() {
        let error = forces_csv("creepage_longitudinal\n0.001\n".as_bytes(), Vec::new()).unwrap_err();
        assert_eq!(error, "creepage_lateral = NaN is invalid: must be finite");
    }
}
