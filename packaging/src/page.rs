//! What every FMU's `documentation/index.html` shares: the style, the table of variables and the
//! list of output dependencies generated from a model description's variable table (so neither
//! can drift from the interface), and the Platforms section read off the binaries the FMU carries.

use std::fmt::Write as _;

use fmi2_slave::variables::{Causality, Kind, Variable};

use crate::plot::escape;

/// `<UnitDefinitions>` as the interface generator writes it: each unit's name and its display
/// units (name, factor: display = factor · value).
pub type UnitDefinitions<'a> = &'a [(&'a str, &'a [(&'a str, f64)])];

/// The pages' style sheet.
pub const STYLE: &str = "body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.45}\
table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:0.25em 0.5em;vertical-align:top}\
pre{background:#f5f5f5;padding:0.5em}";

fn display_unit_text(variable: &Variable, units: UnitDefinitions) -> String {
    let Some(unit) = variable.unit else { return String::new() };
    match variable.display_unit {
        Some(display) => {
            let factor =
                units.iter().find(|(u, _)| *u == unit).and_then(|(_, d)| d.iter().find(|(n, _)| *n == display));
            let factor = factor.map_or(1.0, |(_, f)| *f);
            format!("{unit} (shown in {display}: 1 {unit} = {factor} {display})")
        }
        None => unit.to_owned(),
    }
}

/// Every variable of `variables` as an HTML table: name, value reference, causality,
/// variability, unit (with its display unit from `units`), start value and meaning (the
/// description, and an Enumeration's items).
pub fn variables_table(variables: &[Variable], units: UnitDefinitions) -> String {
    let mut html = String::from(
        "<table>\n<tr><th>name</th><th>value reference</th><th>causality</th><th>variability</th>\
         <th>unit</th><th>start</th><th>meaning</th></tr>\n",
    );
    for variable in variables {
        let start = match variable.kind {
            Kind::Real { start } => start.map(|s| format!("{s}")).unwrap_or_else(|| "(computed)".into()),
            Kind::Integer { start } => start.map(|s| s.to_string()).unwrap_or_else(|| "(computed)".into()),
            Kind::Enumeration { items, start, .. } => {
                let name = items.iter().find(|(_, value, _)| *value == start).map_or("?", |(name, _, _)| name);
                format!("{start} ({name})")
            }
            Kind::String { start } => format!("\"{}\"", escape(start)),
        };
        let mut meaning = escape(variable.description);
        if let Kind::Enumeration { declared_type, items, .. } = variable.kind {
            write!(meaning, "<br>Enumeration {declared_type}:").unwrap();
            for (name, value, description) in items {
                write!(meaning, "<br>{value} = <code>{name}</code>: {}", escape(description)).unwrap();
            }
        }
        writeln!(
            html,
            "<tr><td><code>{}</code></td><td>{}</td><td>{:?}</td><td>{:?}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            variable.name,
            variable.value_reference,
            variable.causality,
            variable.variability,
            escape(&display_unit_text(variable, units)),
            start,
            meaning
        )
        .unwrap();
    }
    html.push_str("</table>\n");
    html
}

/// Each output of `variables` with the inputs it depends on (`<ModelStructure>`'s `<Outputs>`),
/// as a list; an output that depends on none (a state) says so.
pub fn dependencies_list(variables: &[Variable]) -> String {
    let mut html = String::from("<ul>\n");
    for output in variables.iter().filter(|v| v.causality == Causality::Output) {
        let names: Vec<String> = output
            .dependencies
            .iter()
            .filter_map(|r| variables.iter().find(|v| v.value_reference == *r))
            .map(|v| format!("<code>{}</code>", v.name))
            .collect();
        let names = if names.is_empty() { "no input".to_owned() } else { names.join(", ") };
        writeln!(html, "<li><code>{}</code> depends on {names}</li>", output.name).unwrap();
    }
    html.push_str("</ul>\n");
    html
}

/// One binary of the FMU, as its documentation describes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryNote {
    /// linux64, needing glibc ≥ `glibc` (read off the binary), built against the baseline or not.
    Linux64 { glibc: (u32, u32), baseline_applied: bool },
    /// win64, linked by zig (cargo-zigbuild) or else by mingw-w64.
    Win64 { linked_by_zig: bool },
}

/// The Platforms section: what each binary in this FMU needs, read off the binaries (a linux64
/// binary built without cargo-zigbuild needs the building machine's glibc, and says so);
/// `win64_tested` is the FMU's own sentence on how its win64 binary was tested.
pub fn platforms_section(binaries: &[BinaryNote], win64_tested: &str) -> String {
    let mut items: Vec<String> = binaries
        .iter()
        .map(|binary| match *binary {
            BinaryNote::Linux64 { glibc: (major, minor), baseline_applied } => {
                let how = if baseline_applied {
                    "built against that glibc with cargo-zigbuild"
                } else {
                    "built with plain cargo, so it needs the glibc of the machine that packaged it (`cargo fmu` \
                     builds against glibc 2.28 with cargo-zigbuild, which it installs from PyPI into .venv \
                     when Python's venv is available)"
                };
                format!(
                    "<li><b>linux64</b> (x86-64): needs glibc ≥ {major}.{minor} (the newest glibc symbol version it \
                     uses; {how}); besides glibc it needs only libm, libpthread and libdl. glibc 2.28 is Debian 10, \
                     Ubuntu 18.10, RHEL/Rocky 8; 2.31 Ubuntu 20.04, 2.34 RHEL/Rocky 9, 2.35 Ubuntu 22.04, 2.36 \
                     Debian 12.</li>"
                )
            }
            BinaryNote::Win64 { linked_by_zig } => format!(
                "<li><b>win64</b> (x86-64, Windows 10 or later): {}, so it needs only DLLs that Windows ships. \
                 {win64_tested}</li>",
                if linked_by_zig {
                    "linked by zig (cargo-zigbuild) against Windows' Universal C Runtime"
                } else {
                    "built with mingw-w64, the C runtime and libgcc linked statically"
                }
            ),
        })
        .collect();
    if !binaries.iter().any(|binary| matches!(binary, BinaryNote::Win64 { .. })) {
        items.push(
            "<li>No win64 binary in this build (its toolchain was missing where it was packaged).</li>".to_owned(),
        );
    }
    if !binaries.iter().any(|binary| matches!(binary, BinaryNote::Linux64 { .. })) {
        items.push("<li>No linux64 binary in this build.</li>".to_owned());
    }
    format!("<h2>Platforms</h2>\n<ul>\n{}\n<li>No darwin64 binary yet.</li>\n</ul>", items.join("\n"))
}
