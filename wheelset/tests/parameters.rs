//! The FMU's start values are the cited parameters: every wheelset and suspension entry of
//! data/wheelset/passenger_coach.toml, the half axle load as the vertical forces' start, and the
//! centred rolling radius of data/wheelset/contact_data.json.

use wheelset::model_description::{value_reference as vr, variable, Kind};

fn start(value_reference: u32) -> f64 {
    match variable(value_reference).expect("a variable").kind {
        Kind::Real { start: Some(start) } => start,
        other => panic!("{other:?}"),
    }
}

fn read(path: &str) -> String {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    std::fs::read_to_string(format!("{root}/{path}")).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn start_values_are_the_passenger_coach_toml() {
    let document: toml_edit::DocumentMut = read("data/wheelset/passenger_coach.toml").parse().unwrap();
    let entry = |table: &str, key: &str| {
        let item = &document[table][key];
        let value = item["value"].as_float().unwrap_or_else(|| panic!("{table}.{key}"));
        (value, item["unit"].as_str().unwrap().to_owned())
    };
    let pairs = [
        (vr::MASS, "wheelset", "mass"),
        (vr::YAW_INERTIA, "wheelset", "yaw_inertia"),
        (vr::SPIN_INERTIA, "wheelset", "spin_inertia"),
        (vr::LONGITUDINAL_STIFFNESS, "primary_suspension", "longitudinal_stiffness"),
        (vr::LONGITUDINAL_DAMPING, "primary_suspension", "longitudinal_damping"),
        (vr::LATERAL_STIFFNESS, "primary_suspension", "lateral_stiffness"),
        (vr::LATERAL_DAMPING, "primary_suspension", "lateral_damping"),
        (vr::LATERAL_SEMI_SPACING, "primary_suspension", "lateral_semi_spacing"),
    ];
    for (value_reference, table, key) in pairs {
        let (value, unit) = entry(table, key);
        let v = variable(value_reference).unwrap();
        assert_eq!(start(value_reference), value, "{}", v.name);
        // The XML spells products with a dot and powers without a caret (FMI's unit names).
        let xml_unit = unit.replace(' ', ".");
        assert_eq!(v.unit, Some(xml_unit.as_str()), "{}", v.name);
    }
    let (axle_load, _) = entry("wheelset", "axle_load");
    assert_eq!(start(vr::LEFT_TRACK_FORCE_Z), -axle_load / 2.0);
    assert_eq!(start(vr::RIGHT_TRACK_FORCE_Z), -axle_load / 2.0);
}

#[test]
fn the_wheels_start_on_the_contact_data_centred_radius() {
    let json = read("data/wheelset/contact_data.json");
    let after = json.split("\"centred_radius\":").nth(1).expect("centred_radius in contact_data.json");
    let radius: f64 = after.split(',').next().unwrap().trim().parse().unwrap();
    assert_eq!(start(vr::CENTRED_ROLLING_RADIUS), radius);
}
