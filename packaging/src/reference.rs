//! The core library's outputs for rows of inputs and parameters: the reference the fmpy tests
//! compare the FMU with. Each row is decoded into the core's typed scene by the adapter's decoder
//! ([`wheel_rail_contact_fmu::scene::scene_of`], the enumerations' numbers generated from
//! `modelDescription.xml`) and evaluated by the core's [`Scene::evaluate`] — the one pipeline the
//! FMU runs too — without the C ABI, the instance's state machine or its value storage, which
//! the fmpy tests thereby check. (The pipeline's composition itself is checked against the core's
//! parts one by one in the adapter's `scene` tests.)

use std::io::{BufRead, Write};

use wheel_rail_contact::scene::{Evaluation, Scene, SceneCache, SceneState};
use wheel_rail_contact_fmu::model_description::Outputs;
use wheel_rail_contact_fmu::model_description::{Causality, Kind, Values, VARIABLES};
use wheel_rail_contact_fmu::profiles::WheelOutputs;
use wheel_rail_contact_fmu::scene::{outputs, scene_input, scene_of};

/// The columns written, in this order (the FMU's output names).
pub fn output_columns() -> Vec<&'static str> {
    VARIABLES.iter().filter(|v| v.causality == Causality::Output).map(|v| v.name).collect()
}

/// The values of one row: a variable not given keeps its start value, as in an FMU instance
/// whose master does not set it (so the plain scene: Polach with Kalker's stiffness, every
/// option off).
fn values_of(columns: &[String], row: &[f64]) -> Result<Values, String> {
    let mut values = Values::default();
    for (column, &value) in columns.iter().zip(row) {
        if column == "step_size" {
            continue;
        }
        let variable = VARIABLES
            .iter()
            .find(|v| v.name == column && v.causality != Causality::Output)
            .ok_or_else(|| format!("`{column}` is not an input or parameter of the FMU"))?;
        match variable.kind {
            Kind::Real { .. } => *values.real_mut(variable.value_reference).expect("a Real variable") = value,
            Kind::Integer { .. } | Kind::Enumeration { .. } => {
                *values.integer_mut(variable.value_reference).expect("an Integer variable") = value as i32
            }
            Kind::String { .. } => return Err(format!("`{column}` is a String: a numeric table cannot set it")),
        }
    }
    Ok(values)
}

/// One row's outputs; `state` carries the scene's state (the relaxed force, the exact theory's
/// warm start) from row to row, advanced over the row's `step_size` (0 or absent: set to the
/// steady state, as at initialisation).
fn outputs_of(values: &Values, step_size: f64, state: &mut SceneState) -> Result<Vec<f64>, String> {
    // The repository's data/ holds the exact_table model's table, as the FMU's resources/ does.
    let scene: Scene = scene_of(&values.parameters, Some(&crate::fmu::workspace_root().join("data")))?;
    let evaluation = if step_size > 0.0 { Evaluation::Step(step_size) } else { Evaluation::Initialise };
    let (output, next_state) = scene
        .evaluate(&scene_input(&values.inputs), state, &mut SceneCache::default(), evaluation)
        .map_err(|e| e.to_string())?;
    *state = next_state;
    let outputs: Outputs = outputs(&output, &WheelOutputs::default());
    Ok(VARIABLES
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| Values { outputs, ..Values::default() }.real(v.value_reference).expect("a Real output"))
        .collect())
}

/// Reads CSV whose header names FMU inputs and parameters (Enumerations as their integer
/// values) plus an optional `step_size` \[s\] for creep relaxation, and writes the outputs
/// ([`output_columns`]) per row with every digit. Rows are a sequence: the relaxed force carries
/// from one row to the next.
pub fn outputs_csv(input: impl BufRead, mut output: impl Write) -> Result<(), String> {
    let mut lines = input.lines();
    let header = lines.next().ok_or("empty input")?.map_err(|e| e.to_string())?;
    let columns: Vec<String> = header.split(',').map(|c| c.trim().to_owned()).collect();
    writeln!(output, "{}", output_columns().join(",")).map_err(|e| e.to_string())?;
    let mut state = SceneState::default();
    for line in lines {
        let line = line.map_err(|e| e.to_string())?;
        let texts: Vec<&str> = line.split(',').collect();
        if texts.len() != columns.len() {
            return Err(format!("`{line}` has {} fields, the header {}", texts.len(), columns.len()));
        }
        let row = columns
            .iter()
            .zip(texts)
            .map(|(column, text)| text.trim().parse().map_err(|e| format!("{column} = `{text}`: {e}")))
            .collect::<Result<Vec<f64>, String>>()?;
        let step_size = columns.iter().position(|c| c == "step_size").map_or(0.0, |i| row[i]);
        let values = outputs_of(&values_of(&columns, &row)?, step_size, &mut state)?;
        let texts: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
        writeln!(output, "{}", texts.join(",")).map_err(|e| e.to_string())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use wheel_rail_contact::{ContactInput, CreepForceModel, Polach};

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
        assert_eq!(&row[9..13], &[6e-3, 6e-3, 3.0 * 1e5 / (2.0 * PI * 6e-3) / 6e-3, 0.0]);
        // The wheel's outputs (contact_geometry = profiles) are not computed here: zero.
        assert!(row[13..].iter().all(|x| *x == 0.0), "{row:?}");
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
    fn a_missing_column_keeps_its_start_value_and_an_unknown_one_is_an_error() {
        // The default scene at ξ = 0.2 %: the core's Polach with the FMU's start values.
        let row = &rows("creepage_longitudinal\n0.002\n")[0];
        let input = ContactInput { creepage_longitudinal: 2e-3, ..crate::documentation::default_contact_input() };
        assert_eq!(row[0], Polach::default().creep_forces(&input).unwrap().force_longitudinal);
        let error = outputs_csv("creepage\n0.001\n".as_bytes(), Vec::new()).unwrap_err();
        assert_eq!(error, "`creepage` is not an input or parameter of the FMU");
    }
}
