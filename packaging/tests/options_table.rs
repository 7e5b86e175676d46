//! The README's table of what each model choice and option uses is the adapter's declaration
//! (`fmu/src/options.rs`), word for word. `UPDATE_README=1 cargo test -p packaging --test
//! options_table` rewrites it after a change there.

const START: &str = "<!-- options table: generated from fmu/src/options.rs -->\n";
const END: &str = "<!-- end of options table -->";

#[test]
fn the_readme_table_is_the_declared_one() {
    let path = packaging::fmu::workspace_root().join("README.md");
    let readme = std::fs::read_to_string(&path).unwrap();
    let start = readme.find(START).expect("README has the options-table marker") + START.len();
    let end = start + readme[start..].find(END).expect("README has the end marker");
    let declared = wheel_rail_contact_fmu::options::markdown_table();
    if std::env::var_os("UPDATE_README").is_some() {
        std::fs::write(&path, format!("{}{declared}{}", &readme[..start], &readme[end..])).unwrap();
        return;
    }
    assert_eq!(&readme[start..end], declared, "README.md's options table differs from fmu/src/options.rs");
}
