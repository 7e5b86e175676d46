//! The README's tables that are declared elsewhere, word for word: what each model choice and
//! option uses (`fmu/src/options.rs` and the rungs) and the ladder (the rungs,
//! `wheel_rail_contact::ModelChoice::RUNGS`). `UPDATE_README=1 cargo test -p packaging --test
//! readme_tables` rewrites them after a change there.

use wheel_rail_contact::ModelChoice;

/// Checks (or with `UPDATE_README` rewrites) the README's text between `start` and `end`.
fn check_readme_section(start_marker: &str, end_marker: &str, declared: &str) {
    let path = packaging::fmu::workspace_root().join("README.md");
    let readme = std::fs::read_to_string(&path).unwrap();
    let start = readme.find(start_marker).unwrap_or_else(|| panic!("README has {start_marker}")) + start_marker.len();
    let end = start + readme[start..].find(end_marker).unwrap_or_else(|| panic!("README has {end_marker}"));
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, format!("{}{declared}{}", &readme[..start], &readme[end..])).unwrap();
        return;
    }
    assert_eq!(&readme[start..end], declared, "README.md's section after {start_marker} differs from its declaration");
}

#[test]
fn the_readme_options_table_is_the_declared_one() {
    check_readme_section(
        "<!-- options table: generated from fmu/src/options.rs -->\n",
        "<!-- end of options table -->",
        &wheel_rail_contact_fmu::options::markdown_table(),
    );
}

#[test]
fn the_readme_ladder_is_the_registered_rungs() {
    let mut table = String::from("| model | FMU `creep_force_model` | what it is | source |\n|---|---|---|---|\n");
    for rung in ModelChoice::RUNGS {
        table.push_str(&format!(
            "| `{}` | {} (`{}`) | {} | {} |\n",
            rung.type_name, rung.fmu_value, rung.name, rung.summary, rung.source
        ));
    }
    check_readme_section(
        "<!-- ladder table: generated from ModelChoice::RUNGS -->\n",
        "<!-- end of ladder table -->",
        &table,
    );
}
