//! The documentation's tables that are declared elsewhere, word for word: what each model choice
//! and option uses (`fmu/src/options.rs` and the rungs), in `docs/fmu.md`, and the ladder (the
//! rungs, `wheel_rail_contact::ModelChoice::RUNGS`), in `docs/library.md` (both were the README's
//! until the README became a first page; the test keeps its name). `UPDATE_README=1 cargo test -p
//! packaging --test readme_tables` rewrites them after a change there.

use wheel_rail_contact::ModelChoice;

/// Checks (or with `UPDATE_README` rewrites) the text of `file` (relative to the workspace root)
/// between `start` and `end`. The declarations write their links relative to the workspace root
/// (`[…](docs/exact_table.md)`); in a file under `docs/` those links are rebased onto it
/// (`[…](exact_table.md)`), and nothing else changes.
fn check_doc_section(file: &str, start_marker: &str, end_marker: &str, declared: &str) {
    let rebased;
    let declared = match file.strip_prefix("docs/") {
        Some(_) => {
            rebased = declared.replace("](docs/", "](");
            rebased.as_str()
        }
        None => declared,
    };
    let path = packaging::fmu::workspace_root().join(file);
    let doc = std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{file}: {error}"));
    let start = doc.find(start_marker).unwrap_or_else(|| panic!("{file} has {start_marker}")) + start_marker.len();
    let end = start + doc[start..].find(end_marker).unwrap_or_else(|| panic!("{file} has {end_marker}"));
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, format!("{}{declared}{}", &doc[..start], &doc[end..])).unwrap();
        return;
    }
    assert_eq!(&doc[start..end], declared, "{file}'s section after {start_marker} differs from its declaration");
}

#[test]
fn the_fmu_guide_options_table_is_the_declared_one() {
    check_doc_section(
        "docs/fmu.md",
        "<!-- options table: generated from fmu/src/options.rs -->\n",
        "<!-- end of options table -->",
        &wheel_rail_contact_fmu::options::markdown_table(),
    );
}

#[test]
fn the_library_guide_ladder_is_the_registered_rungs() {
    let mut table = String::from("| model | FMU `creep_force_model` | what it is | source |\n|---|---|---|---|\n");
    for rung in ModelChoice::RUNGS {
        table.push_str(&format!(
            "| `{}` | {} (`{}`) | {} | {} |\n",
            rung.type_name, rung.fmu_value, rung.name, rung.summary, rung.source
        ));
    }
    check_doc_section(
        "docs/library.md",
        "<!-- ladder table: generated from ModelChoice::RUNGS -->\n",
        "<!-- end of ladder table -->",
        &table,
    );
}
