//! The passenger-coach wheelset's parameter file, data/wheelset/passenger_coach.toml (every
//! entry `{ value, unit, source }`, SI units), compiled in.

const PARAMETERS: &str = include_str!("../../data/wheelset/passenger_coach.toml");

/// The parameter file, parsed.
pub fn document() -> toml_edit::DocumentMut {
    PARAMETERS.parse().expect("data/wheelset/passenger_coach.toml parses")
}

/// `[table].name.value` of the parameter file.
fn parameter<'a>(document: &'a toml_edit::DocumentMut, table: &str, name: &str) -> &'a toml_edit::Item {
    &document[table][name]["value"]
}

pub fn number(document: &toml_edit::DocumentMut, table: &str, name: &str) -> f64 {
    parameter(document, table, name).as_float().unwrap_or_else(|| panic!("{table}.{name}.value must be a float"))
}

pub fn text<'a>(document: &'a toml_edit::DocumentMut, table: &str, name: &str) -> &'a str {
    parameter(document, table, name).as_str().unwrap_or_else(|| panic!("{table}.{name}.value must be a string"))
}
