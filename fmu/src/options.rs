//! Which variables each model choice and scene option uses — declared once: the options here,
//! the models in their rungs (`wheel_rail_contact::ModelChoice::RUNGS`). The FMU's
//! documentation prints this table (`packaging/src/documentation.rs`), docs/fmu.md carries the
//! same table (checked by `packaging/tests/readme_tables.rs`), and the tests check it against the
//! model description: every name is a variable of the stated causality, and every input listed
//! for an output is among that output's declared dependencies.

use std::borrow::Cow;

use wheel_rail_contact::ModelChoice;

/// One row: what a model choice or option reads and what it sets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OptionUse {
    /// The choice or option, as a user selects it (`parameter = item`).
    pub option: Cow<'static, str>,
    /// The inputs it reads.
    pub inputs: &'static [&'static str],
    /// The inputs it makes unused (replaced by what it computes).
    pub replaces: &'static [&'static str],
    /// The parameters it reads.
    pub parameters: &'static [&'static str],
    /// The outputs it sets (beyond the forces every scene gives).
    pub outputs: &'static [&'static str],
}

/// What every scene uses, whichever model and options.
const EVERY_SCENE: &[OptionUse] = &[
    OptionUse {
        option: Cow::Borrowed("every scene"),
        inputs: &["normal_force", "friction_coefficient", "rolling_speed"],
        replaces: &[],
        parameters: &["shear_modulus", "poisson_ratio", "creep_force_model"],
        outputs: &["force_longitudinal", "force_lateral", "adhesion_utilisation", "spin_moment"],
    },
    OptionUse {
        option: Cow::Borrowed("creepages as inputs (default)"),
        inputs: &["creepage_longitudinal", "creepage_lateral", "spin_creepage"],
        replaces: &[],
        parameters: &[],
        outputs: &["effective_creepage_longitudinal", "effective_creepage_lateral", "effective_spin_creepage"],
    },
    OptionUse {
        option: Cow::Borrowed("ellipse as inputs (default)"),
        inputs: &["semi_axis_a", "semi_axis_b"],
        replaces: &[],
        parameters: &[],
        outputs: &["contact_semi_axis_a", "contact_semi_axis_b", "max_pressure"],
    },
];

/// What each option uses.
const OPTIONS: &[OptionUse] = &[
    OptionUse {
        option: Cow::Borrowed("traction_law = polach2005_*"),
        inputs: &["rolling_speed"],
        replaces: &[],
        parameters: &[
            "traction_law",
            "adhesion_reduction_factor",
            "slip_reduction_factor",
            "friction_limit_ratio",
            "friction_decay_rate",
        ],
        outputs: &["current_friction_coefficient", "slip_velocity"],
    },
    OptionUse {
        option: Cow::Borrowed("hertz_contact = on"),
        inputs: &["wheel_rolling_radius"],
        replaces: &["semi_axis_a", "semi_axis_b"],
        parameters: &["hertz_contact", "wheel_profile_curvature", "rail_profile_curvature"],
        outputs: &["contact_semi_axis_a", "contact_semi_axis_b", "max_pressure", "approach"],
    },
    OptionUse {
        option: Cow::Borrowed("creepages_from_kinematics = on"),
        inputs: &[
            "rolling_speed",
            "wheel_angular_speed",
            "wheel_rolling_radius",
            "lateral_slip_velocity",
            "spin_angular_velocity",
        ],
        replaces: &["creepage_longitudinal", "creepage_lateral", "spin_creepage"],
        parameters: &["creepages_from_kinematics", "regularisation_speed"],
        outputs: &[
            "effective_creepage_longitudinal",
            "effective_creepage_lateral",
            "effective_spin_creepage",
            "slip_velocity",
        ],
    },
    OptionUse {
        option: Cow::Borrowed("creep_relaxation = on"),
        // The renewal speed: |V|, or (|V| + |ωr|)/2 with the kinematics.
        inputs: &["rolling_speed", "wheel_angular_speed", "wheel_rolling_radius"],
        replaces: &[],
        parameters: &["creep_relaxation", "relaxation_length"],
        outputs: &["force_longitudinal", "force_lateral", "adhesion_utilisation"],
    },
    OptionUse {
        option: Cow::Borrowed("contact_geometry = profiles"),
        inputs: &[
            "wheelset_lateral_displacement",
            "wheelset_vertical_position",
            "wheelset_roll_angle",
            "wheelset_yaw_angle",
            "vertical_force",
            "rolling_speed",
            "wheel_angular_speed",
            "wheelset_lateral_velocity",
            "wheelset_yaw_rate",
            "friction_coefficient",
        ],
        // Each patch's creepages come from the wheelset's motion, its load and ellipse from the
        // profiles.
        replaces: &[
            "creepage_longitudinal",
            "creepage_lateral",
            "spin_creepage",
            "normal_force",
            "semi_axis_a",
            "semi_axis_b",
            "wheel_rolling_radius",
            "lateral_slip_velocity",
            "spin_angular_velocity",
        ],
        parameters: &[
            "contact_geometry",
            "wheel_profile",
            "rail_profile",
            "wheel_side",
            "track_gauge",
            "gauge_measuring_height",
            "rail_cant",
            "flange_back_distance",
            "flange_back_position",
            "wheel_nominal_radius",
            "vertical_contact",
            "contact_method",
            "profile_filter_wavelength",
            "regularisation_speed",
        ],
        outputs: &[
            "track_force_x",
            "track_force_y",
            "track_force_z",
            "track_moment_x",
            "track_moment_y",
            "track_moment_z",
            "contact_patch_count",
            "wheelset_vertical_position_solved",
            "patch1_contact_angle",
            "patch1_rail_lateral_position",
            "patch1_rolling_radius",
            "patch1_normal_force",
            "patch1_force_longitudinal",
            "patch1_force_lateral",
            "patch1_creepage_longitudinal",
            "patch1_creepage_lateral",
            "patch1_spin_creepage",
            "patch1_semi_axis_a",
            "patch1_semi_axis_b",
            "patch2_contact_angle",
            "patch2_rail_lateral_position",
            "patch2_rolling_radius",
            "patch2_normal_force",
            "patch2_force_longitudinal",
            "patch2_force_lateral",
            "patch2_creepage_longitudinal",
            "patch2_creepage_lateral",
            "patch2_spin_creepage",
            "patch2_semi_axis_a",
            "patch2_semi_axis_b",
        ],
    },
];

/// Every scene, then each model that has parameters or a spin moment (its rung), then each option.
pub fn option_uses() -> Vec<OptionUse> {
    let models =
        ModelChoice::RUNGS.iter().filter(|rung| !rung.fmu_parameters.is_empty() || rung.spin_moment).map(|rung| {
            OptionUse {
                option: Cow::Owned(format!("creep_force_model = {}", rung.name)),
                inputs: &[],
                replaces: &[],
                parameters: rung.fmu_parameters,
                outputs: if rung.spin_moment { &["spin_moment"] } else { &[] },
            }
        });
    EVERY_SCENE.iter().cloned().chain(models).chain(OPTIONS.iter().cloned()).collect()
}

/// The table's header cells.
pub const COLUMNS: [&str; 5] =
    ["choice or option", "inputs used", "inputs it replaces", "parameters used", "outputs it sets"];

/// The table's rows as cells, each name formatted by `code` (`—` for none): what docs/fmu.md's
/// Markdown and the documentation's HTML are written from.
pub fn rows(code: impl Fn(&str) -> String) -> Vec<[String; 5]> {
    let list = |names: &[&str]| {
        if names.is_empty() {
            "—".to_owned()
        } else {
            names.iter().map(|name| code(name)).collect::<Vec<_>>().join(", ")
        }
    };
    option_uses()
        .into_iter()
        .map(|row| {
            [row.option.into_owned(), list(row.inputs), list(row.replaces), list(row.parameters), list(row.outputs)]
        })
        .collect()
}

/// The table as Markdown (docs/fmu.md's copy).
pub fn markdown_table() -> String {
    let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
    let mut table = line(&COLUMNS.map(str::to_owned));
    table.push_str("|---|---|---|---|---|\n");
    for row in rows(|name| format!("`{name}`")) {
        table.push_str(&line(&row));
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model_description::{Causality, VARIABLES};

    fn variable(name: &str) -> &'static crate::model_description::Variable {
        VARIABLES.iter().find(|v| v.name == name).unwrap_or_else(|| panic!("{name} is not a variable"))
    }

    #[test]
    fn every_name_is_a_variable_of_its_causality() {
        for row in option_uses() {
            for name in row.inputs.iter().chain(row.replaces) {
                assert_eq!(variable(name).causality, Causality::Input, "{}: {name}", row.option);
            }
            for name in row.parameters {
                assert_eq!(variable(name).causality, Causality::Parameter, "{}: {name}", row.option);
            }
            for name in row.outputs {
                assert_eq!(variable(name).causality, Causality::Output, "{}: {name}", row.option);
            }
        }
    }

    /// What an option reads can change what it sets: every input of a row is a declared
    /// dependency (`<ModelStructure>`, itself checked against perturbations by the scene tests)
    /// of some output of the row, and every output of the row depends on some input of it.
    #[test]
    fn the_inputs_and_outputs_of_a_row_are_declared_dependencies() {
        for row in option_uses().iter().filter(|row| !row.inputs.is_empty() && !row.outputs.is_empty()) {
            let depends =
                |output: &str, input: &str| variable(output).dependencies.contains(&variable(input).value_reference);
            for input in row.inputs {
                assert!(row.outputs.iter().any(|o| depends(o, input)), "{}: nothing depends on {input}", row.option);
            }
            for output in row.outputs {
                assert!(row.inputs.iter().any(|i| depends(output, i)), "{}: {output} depends on none", row.option);
            }
        }
    }

    /// Every input and parameter that only some choices or options use says so, naming each of
    /// them (its "used when"): an option added to a row cannot leave a variable's description
    /// silent on it. What every scene uses needs no condition; an option's own selector is not
    /// used "when" itself; an option with a wildcard (`polach2005_*`) may be named by one of its
    /// items.
    #[test]
    fn every_variable_names_the_options_that_use_it() {
        let rows = option_uses();
        let (every, options): (Vec<_>, Vec<_>) = rows.iter().partition(|row| EVERY_SCENE.contains(row));
        let used_by_every =
            |name: &str| every.iter().any(|row| row.inputs.contains(&name) || row.parameters.contains(&name));
        let mut silent = Vec::new();
        for row in options {
            let selector = row.option.split(" = ").next().unwrap_or_default();
            let named = row.option.trim_end_matches('*');
            for name in row.inputs.iter().chain(row.parameters).filter(|&&n| n != selector && !used_by_every(n)) {
                let description = variable(name).description;
                if !description.contains(named) {
                    silent.push(format!("{name} does not name `{}`: \"{description}\"", row.option));
                }
            }
        }
        assert!(silent.is_empty(), "descriptions in modelDescription.xml:\n{}", silent.join("\n"));
    }

    /// Every parameter and input appears in some row: nothing the FMU has is left undocumented.
    #[test]
    fn every_input_and_parameter_is_listed() {
        for v in VARIABLES.iter().filter(|v| matches!(v.causality, Causality::Input | Causality::Parameter)) {
            let listed = option_uses().iter().any(|row| {
                row.inputs.contains(&v.name) || row.replaces.contains(&v.name) || row.parameters.contains(&v.name)
            });
            assert!(listed, "{} is in no row of option_uses()", v.name);
        }
    }
}
