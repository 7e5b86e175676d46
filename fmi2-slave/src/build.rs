//! Turns `modelDescription.xml` (the FMU's interface, written once) into Rust.
//!
//! Generated, per variable: a value-reference constant, a field of a plain struct (`Inputs`,
//! `Parameters`, `Outputs` or `Locals`, by causality; start values are their `Default`; a
//! state derivative `der(x)` is the field `der_x`), the Get/Set
//! mapping from value reference to field, and a row of the `VARIABLES` table (name, causality,
//! variability, start, unit, description) that the documentation is generated from. Also: the
//! GUID, the model identifier, the log categories, one Rust enum per Enumeration type, the
//! output and state-derivative dependencies declared by name in `<ModelStructure>`, the
//! continuous states of Model Exchange (state, derivative, nominal), the packaged model description
//! (that `<ModelStructure>` in the standard's by-index form, so adding a variable touches one
//! place) and the FMU-state layout tag (a hash of the variable layout).
//!
//! Why this makes drift impossible: the adapter builds `Outputs` with a struct literal and
//! destructures `Inputs` and `Parameters` without `..`, so a variable added to or removed from
//! the XML breaks the build until the adapter maps it. The XML is also checked here against the
//! rules of the standard that fmpy and other masters rely on (unique names and value references,
//! start values where required, defined units, a `<ModelStructure>` entry for exactly the outputs); any violation
//! fails the build with the reason.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Causality {
    Input,
    Parameter,
    Output,
    /// A state derivative, or a continuous state that is neither input nor output (the only
    /// locals this generator accepts).
    Local,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum BaseType {
    Real,
    Integer,
    Enumeration,
    /// Parameters only; kept out of the `Copy` value structs, in [`Strings`].
    String,
}

struct Variable {
    /// 1-based position in `<ModelVariables>`: how `<ModelStructure>` refers to it.
    index: usize,
    name: String,
    /// The Rust name of its field and (upper-cased) constant: the name, `der(x)` as `der_x`.
    ident: String,
    value_reference: u32,
    causality: Causality,
    variability: String,
    description: String,
    base_type: BaseType,
    declared_type: Option<String>,
    unit: Option<String>,
    display_unit: Option<String>,
    start: Option<String>,
    /// A state derivative's state: its `derivative` attribute (a 1-based index).
    derivative: Option<usize>,
    /// The `nominal` attribute (a state's, for fmi2GetNominalsOfContinuousStates).
    nominal: Option<f64>,
}

/// What `<ModelStructure>` declares by name: per output and per state derivative (in the order
/// of the variables), the indices of what it depends on.
struct Dependencies {
    outputs: Vec<Vec<usize>>,
    derivatives: Vec<Vec<usize>>,
}

struct EnumerationType {
    name: String,
    description: String,
    items: Vec<(String, i32, String)>,
}

/// For a Windows GNU target: makes the cdylib export the [`crate::FMI2_FUNCTIONS`] and nothing
/// else, by a module-definition file in `out_dir` handed to the linker as an input file. With
/// mingw-w64's ld, rustc's own export list already does that; zig's linker (cargo-zigbuild, the
/// win64 build that needs no root) ignores rustc's list, passed as `-Wl,<file>`, and exported
/// every global symbol (2 233 of them) — a positional `.def` it honours. Other targets: nothing.
pub fn export_only_fmi2_functions(out_dir: &Path) {
    let target = |key: &str| std::env::var(key).unwrap_or_default();
    if target("CARGO_CFG_TARGET_OS") != "windows" || target("CARGO_CFG_TARGET_ENV") != "gnu" {
        return;
    }
    let definitions = out_dir.join("fmi2_exports.def");
    let text: String = std::iter::once("EXPORTS\n".to_owned())
        .chain(crate::FMI2_FUNCTIONS.iter().map(|name| format!("    {name}\n")))
        .collect();
    std::fs::write(&definitions, text).unwrap_or_else(|e| panic!("cannot write {}: {e}", definitions.display()));
    println!("cargo:rustc-cdylib-link-arg={}", definitions.display());
}

pub fn generate(xml_path: &str, out_path: &Path) {
    println!("cargo:rerun-if-changed={xml_path}");
    let text = std::fs::read_to_string(xml_path).unwrap_or_else(|e| panic!("cannot read {xml_path}: {e}"));
    let document = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{xml_path}: {e}"));
    let root = document.root_element();
    if root.tag_name().name() != "fmiModelDescription" || root.attribute("fmiVersion") != Some("2.0") {
        fail("the root must be <fmiModelDescription fmiVersion=\"2.0\">".into());
    }
    if root.namespaces().any(|ns| ns.name() == Some("xsi")) {
        fail("no xmlns:xsi on the root element: rust-fmi's importer rejects it".into());
    }
    let guid = root.attribute("guid").unwrap_or_else(|| fail("the root has no guid".into()));
    let co_simulation = child(root, "CoSimulation").unwrap_or_else(|| fail("no <CoSimulation> element".into()));
    let model_identifier = co_simulation
        .attribute("modelIdentifier")
        .unwrap_or_else(|| fail("<CoSimulation> has no modelIdentifier".into()));
    let model_exchange = child(root, "ModelExchange");
    if model_exchange.is_some_and(|me| me.attribute("modelIdentifier") != Some(model_identifier)) {
        fail("<ModelExchange> must have <CoSimulation>'s modelIdentifier: one binary holds both interfaces".into());
    }
    let event_indicators: usize = root
        .attribute("numberOfEventIndicators")
        .map(|n| n.parse().unwrap_or_else(|_| fail(format!("numberOfEventIndicators = {n} is not a count"))))
        .unwrap_or(0);

    let units = read_units(root);
    let enumerations = read_enumerations(root);
    let variables = read_variables(root, &units, &enumerations);
    let dependencies = read_model_structure(root, &variables);
    if model_exchange.is_none() && !dependencies.derivatives.is_empty() {
        fail("state derivatives need <ModelExchange>".into());
    }
    let packaged = packaged_xml(&text, &standard_model_structure(&variables, &dependencies));
    let packaged_path = out_path.with_file_name("modelDescription.xml");
    std::fs::write(&packaged_path, &packaged).unwrap_or_else(|e| panic!("{}: {e}", packaged_path.display()));
    let log_categories: Vec<&str> = child(root, "LogCategories")
        .map(|c| elements(c, "Category").map(|e| e.attribute("name").unwrap_or_default()).collect())
        .unwrap_or_default();

    let mut source = format!("// Generated by build.rs from {xml_path}. Do not edit.\n\n");
    writeln!(source, "/// The model description as packaged in the FMU (`<ModelStructure>` by index).").unwrap();
    writeln!(source, "pub const MODEL_DESCRIPTION_XML: &str = include_str!({:?});", packaged_path.display()).unwrap();
    writeln!(source, "/// The FMU-state format tag: a hash of the variable layout.").unwrap();
    writeln!(source, "pub const STATE_LAYOUT_TAG: u64 = {:#018x};", layout_tag(&variables)).unwrap();
    writeln!(source, "/// The GUID that `fmi2Instantiate` requires.\npub const GUID: &str = {guid:?};").unwrap();
    writeln!(source, "/// Names the shared library and its C symbols' prefix-free exports.").unwrap();
    writeln!(source, "pub const MODEL_IDENTIFIER: &str = {model_identifier:?};").unwrap();
    writeln!(source, "/// The log categories of `<LogCategories>`.").unwrap();
    writeln!(source, "pub const LOG_CATEGORIES: &[&str] = &{log_categories:?};").unwrap();
    writeln!(source, "/// Whether the model description declares `<ModelExchange>`.").unwrap();
    writeln!(source, "pub const MODEL_EXCHANGE: bool = {};", model_exchange.is_some()).unwrap();
    writeln!(source, "/// `numberOfEventIndicators`.\npub const EVENT_INDICATORS: usize = {event_indicators};")
        .unwrap();
    write_continuous_states(&mut source, &variables);
    write_units(&mut source, &units);
    for enumeration in &enumerations {
        write_enumeration(&mut source, enumeration);
    }
    write_value_references(&mut source, &variables);
    write_structs(&mut source, &variables);
    write_accessors(&mut source, &variables);
    write_table(&mut source, &variables, &dependencies);
    std::fs::write(out_path, source).unwrap_or_else(|e| panic!("cannot write {}: {e}", out_path.display()));
}

/// Stops the build with what is wrong in the model description.
fn fail(message: String) -> ! {
    panic!("modelDescription.xml: {message}")
}

fn child<'a, 'input>(node: roxmltree::Node<'a, 'input>, name: &str) -> Option<roxmltree::Node<'a, 'input>> {
    node.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

fn elements<'a, 'input: 'a>(
    node: roxmltree::Node<'a, 'input>,
    name: &'a str,
) -> impl Iterator<Item = roxmltree::Node<'a, 'input>> + 'a {
    node.children().filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// Unit name → its display units with their factors.
fn read_units(root: roxmltree::Node) -> BTreeMap<String, Vec<(String, f64)>> {
    let mut units = BTreeMap::new();
    if let Some(definitions) = child(root, "UnitDefinitions") {
        for unit in elements(definitions, "Unit") {
            let display_units = elements(unit, "DisplayUnit")
                .map(|d| {
                    let factor = d.attribute("factor").map_or(1.0, |f| f.parse().expect("DisplayUnit factor"));
                    (d.attribute("name").unwrap_or_default().to_owned(), factor)
                })
                .collect();
            units.insert(unit.attribute("name").unwrap_or_default().to_owned(), display_units);
        }
    }
    units
}

fn read_enumerations(root: roxmltree::Node) -> Vec<EnumerationType> {
    let Some(definitions) = child(root, "TypeDefinitions") else { return Vec::new() };
    let mut enumerations = Vec::new();
    for simple_type in elements(definitions, "SimpleType") {
        let name = simple_type.attribute("name").unwrap_or_default().to_owned();
        let Some(enumeration) = child(simple_type, "Enumeration") else {
            fail(format!("SimpleType {name}: only Enumeration types are supported by fmi2_slave::build"))
        };
        let items = elements(enumeration, "Item")
            .map(|item| {
                let value = item.attribute("value").and_then(|v| v.parse().ok());
                let value = value.unwrap_or_else(|| fail(format!("SimpleType {name}: an Item lacks an integer value")));
                let item_name = item.attribute("name").unwrap_or_default().to_owned();
                (item_name, value, item.attribute("description").unwrap_or_default().to_owned())
            })
            .collect();
        let description = simple_type.attribute("description").unwrap_or_default().to_owned();
        enumerations.push(EnumerationType { name, description, items });
    }
    enumerations
}

fn read_variables(
    root: roxmltree::Node,
    units: &BTreeMap<String, Vec<(String, f64)>>,
    enumerations: &[EnumerationType],
) -> Vec<Variable> {
    let model_variables = child(root, "ModelVariables").unwrap_or_else(|| fail("no <ModelVariables>".into()));
    let mut variables = Vec::new();
    let mut names = BTreeSet::new();
    let mut value_references = BTreeSet::new();
    for (position, scalar) in elements(model_variables, "ScalarVariable").enumerate() {
        let name = scalar.attribute("name").unwrap_or_default().to_owned();
        // `der(x)`, the structured naming convention's state derivative, is the field `der_x`.
        let ident = match name.strip_prefix("der(").and_then(|rest| rest.strip_suffix(')')) {
            Some(state) => format!("der_{state}"),
            None => name.clone(),
        };
        let is_identifier = ident.chars().next().is_some_and(|c| c.is_ascii_lowercase())
            && ident.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
        if !is_identifier {
            fail(format!(
                "variable `{name}`: names must be snake_case identifiers or der(identifier) (they become Rust fields)"
            ));
        }
        if !names.insert(name.clone()) {
            fail(format!("variable name `{name}` is not unique"));
        }
        let value_reference: u32 = scalar
            .attribute("valueReference")
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| fail(format!("variable {name}: missing or invalid valueReference")));
        // One namespace for all types keeps the generated accessors simple and masters unconfused.
        if !value_references.insert(value_reference) {
            fail(format!("variable {name}: valueReference {value_reference} is not unique"));
        }
        let causality = match scalar.attribute("causality") {
            Some("input") => Causality::Input,
            Some("parameter") => Causality::Parameter,
            Some("output") => Causality::Output,
            Some("local") => Causality::Local,
            other => {
                fail(format!("variable {name}: causality {other:?} is not supported (input, parameter, output, local)"))
            }
        };
        let variability = scalar.attribute("variability").unwrap_or("continuous").to_owned();
        if scalar.attribute("initial").is_some() {
            fail(format!(
                "variable {name}: leave `initial` at its default (exact for inputs/parameters, calculated for outputs)"
            ));
        }
        let type_element =
            scalar.children().find(|c| c.is_element()).unwrap_or_else(|| fail(format!("{name}: no type")));
        let base_type = match type_element.tag_name().name() {
            "Real" => BaseType::Real,
            "Integer" => BaseType::Integer,
            "Enumeration" => BaseType::Enumeration,
            "String" => BaseType::String,
            other => fail(format!("variable {name}: type {other} is not supported yet by fmi2_slave::build")),
        };
        if base_type == BaseType::String && causality != Causality::Parameter {
            fail(format!("variable {name}: only parameters can be Strings (fmi2_slave::build)"));
        }
        let declared_type = type_element.attribute("declaredType").map(str::to_owned);
        if base_type == BaseType::Enumeration && !enumerations.iter().any(|e| Some(&e.name) == declared_type.as_ref()) {
            fail(format!("variable {name}: declaredType {declared_type:?} is not an Enumeration in <TypeDefinitions>"));
        }
        let unit = type_element.attribute("unit").map(str::to_owned);
        let display_unit = type_element.attribute("displayUnit").map(str::to_owned);
        if let Some(unit) = &unit {
            let Some(display_units) = units.get(unit) else {
                fail(format!("variable {name}: unit {unit} is not defined"))
            };
            if let Some(display) = &display_unit {
                if !display_units.iter().any(|(d, _)| d == display) {
                    fail(format!("variable {name}: display unit {display} is not defined for unit {unit}"));
                }
            }
        } else if base_type == BaseType::Real {
            fail(format!("variable {name}: every Real needs a unit"));
        }
        let start = type_element.attribute("start").map(str::to_owned);
        let derivative = type_element.attribute("derivative").map(|index| {
            index
                .parse::<usize>()
                .unwrap_or_else(|_| fail(format!("variable {name}: derivative = {index} is not an index")))
        });
        if derivative.is_some() && causality != Causality::Local {
            fail(format!("variable {name}: only locals can be state derivatives (with `derivative`)"));
        }
        let nominal = type_element.attribute("nominal").map(|nominal| match nominal.parse::<f64>() {
            Ok(value) if value.is_finite() && value > 0.0 => value,
            _ => fail(format!("variable {name}: nominal = {nominal} must be finite and > 0")),
        });
        match (causality, &start) {
            (Causality::Output, Some(_)) => {
                fail(format!("output {name}: initial=\"calculated\" forbids a start value"))
            }
            (Causality::Local, Some(_)) => fail(format!("local {name}: initial=\"calculated\" forbids a start value")),
            (Causality::Input | Causality::Parameter, None) => {
                fail(format!("{name}: inputs and parameters need a start"))
            }
            _ => {}
        }
        if let Some(start) = &start {
            let parses = match base_type {
                BaseType::Real => start.parse::<f64>().is_ok_and(f64::is_finite),
                BaseType::Integer | BaseType::Enumeration => start.parse::<i32>().is_ok(),
                BaseType::String => true,
            };
            if !parses {
                fail(format!("variable {name}: start value `{start}` does not parse as its type"));
            }
        }
        let description = scalar.attribute("description").unwrap_or_default().to_owned();
        variables.push(Variable {
            index: position + 1,
            name,
            ident,
            value_reference,
            causality,
            variability,
            description,
            base_type,
            declared_type,
            unit,
            display_unit,
            start,
            derivative,
            nominal,
        });
    }
    for v in &variables {
        let Some(state) = v.derivative else { continue };
        match variables.get(state.wrapping_sub(1)) {
            Some(x)
                if v.name == format!("der({})", x.name)
                    && x.base_type == BaseType::Real
                    && x.variability == "continuous" => {}
            _ => fail(format!(
                "{}: derivative = {state} must be the index of the continuous Real it is named after",
                v.name
            )),
        }
    }
    for v in variables.iter().filter(|v| v.causality == Causality::Local && v.derivative.is_none()) {
        if !variables.iter().any(|d| d.derivative == Some(v.index)) {
            fail(format!(
                "local {}: a local is a state derivative (with `derivative`) or the continuous state of one",
                v.name
            ));
        }
    }
    variables
}

/// The continuous states of Model Exchange as (state, derivative, nominal) value references,
/// in the order of the derivatives.
fn write_continuous_states(source: &mut String, variables: &[Variable]) {
    let rows: Vec<String> = variables
        .iter()
        .filter_map(|v| {
            let state = &variables[v.derivative? - 1];
            Some(format!("({}, {}, {:?})", state.value_reference, v.value_reference, state.nominal.unwrap_or(1.0)))
        })
        .collect();
    writeln!(
        source,
        "/// The continuous states of Model Exchange: (state, its derivative, nominal value) value references."
    )
    .unwrap();
    writeln!(source, "pub const CONTINUOUS_STATES: &[(u32, u32, f64)] = &[{}];\n", rows.join(", ")).unwrap();
}

/// The dependencies declared by name in `<ModelStructure>`: one `<Output name dependsOn>` per
/// output, in the order of the outputs, each on inputs, parameters and continuous states; one `<Derivative name
/// dependsOn>` per state derivative, in order, each on inputs and continuous states. Unknown
/// names, an entry missing or out of order, or a dependency of another kind stop the build.
fn read_model_structure(root: roxmltree::Node, variables: &[Variable]) -> Dependencies {
    let structure = child(root, "ModelStructure").unwrap_or_else(|| fail("no <ModelStructure>".into()));
    let by_name: BTreeMap<&str, &Variable> = variables.iter().map(|v| (v.name.as_str(), v)).collect();
    let states: BTreeSet<usize> = variables.iter().filter_map(|v| v.derivative).collect();
    let declared =
        |element: &str, selected: &dyn Fn(&Variable) -> bool, known: &dyn Fn(&Variable) -> bool, kinds: &str| {
            let expected: Vec<&str> = variables.iter().filter(|v| selected(v)).map(|v| v.name.as_str()).collect();
            let entries: Vec<(&str, Vec<usize>)> = elements(structure, element)
                .map(|entry| {
                    let name =
                        entry.attribute("name").unwrap_or_else(|| fail(format!("an <{element}> lacks its name")));
                    let depends_on = entry
                        .attribute("dependsOn")
                        .unwrap_or_else(|| fail(format!("<{element} name=\"{name}\"> must list what it dependsOn")));
                    let mut indices: Vec<usize> = depends_on
                        .split_whitespace()
                        .map(|dependency| match by_name.get(dependency) {
                            Some(v) if known(v) => v.index,
                            _ => fail(format!("{name} cannot depend on `{dependency}`: not {kinds}")),
                        })
                        .collect();
                    indices.sort_unstable();
                    indices.dedup();
                    (name, indices)
                })
                .collect();
            if entries.iter().map(|(name, _)| *name).collect::<Vec<_>>() != expected {
                fail(format!("<ModelStructure> must declare exactly the {element}s {expected:?}, in order"));
            }
            entries.into_iter().map(|(_, indices)| indices).collect()
        };
    Dependencies {
        outputs: declared(
            "Output",
            &|v| v.causality == Causality::Output,
            &|v| matches!(v.causality, Causality::Input | Causality::Parameter) || states.contains(&v.index),
            "an input, parameter or continuous state",
        ),
        derivatives: declared(
            "Derivative",
            &|v| v.derivative.is_some(),
            &|v| v.causality == Causality::Input || states.contains(&v.index),
            "an input or continuous state",
        ),
    }
}

/// The standard's `<ModelStructure>` (FMI 2.0, §2.2.8) from the declared dependencies: under
/// `<Outputs>` each output's inputs and continuous states (an output that is a continuous state:
/// that state, what it is in Model Exchange), under `<Derivatives>` each state derivative's
/// inputs and states, under `<InitialUnknowns>` (the outputs, derivatives and local states: all
/// have initial="calculated", in index order) an output's inputs and parameters (its states are
/// calculated too, so not knowns there), a derivative's or local state's everything (no list).
fn standard_model_structure(variables: &[Variable], dependencies: &Dependencies) -> String {
    let by_index: BTreeMap<usize, &Variable> = variables.iter().map(|v| (v.index, v)).collect();
    let states: BTreeSet<usize> = variables.iter().filter_map(|v| v.derivative).collect();
    let outputs: Vec<&Variable> = variables.iter().filter(|v| v.causality == Causality::Output).collect();
    let derivatives: Vec<&Variable> = variables.iter().filter(|v| v.derivative.is_some()).collect();
    let local_states = variables.iter().filter(|v| v.causality == Causality::Local && v.derivative.is_none());
    let unknown = |xml: &mut String, index: usize, on: &[usize]| {
        let on: Vec<String> = on.iter().map(usize::to_string).collect();
        let kinds = vec!["dependent"; on.len()].join(" ");
        writeln!(
            xml,
            "      <Unknown index=\"{index}\" dependencies=\"{}\" dependenciesKind=\"{kinds}\"/>",
            on.join(" ")
        )
        .unwrap();
    };
    let mut xml = String::from("<ModelStructure>\n    <Outputs>\n");
    for (output, all) in outputs.iter().zip(&dependencies.outputs) {
        let on: Vec<usize> = if states.contains(&output.index) {
            vec![output.index]
        } else {
            all.iter().copied().filter(|i| by_index[i].causality == Causality::Input || states.contains(i)).collect()
        };
        unknown(&mut xml, output.index, &on);
    }
    xml.push_str("    </Outputs>\n");
    if !derivatives.is_empty() {
        xml.push_str("    <Derivatives>\n");
        for (derivative, on) in derivatives.iter().zip(&dependencies.derivatives) {
            unknown(&mut xml, derivative.index, on);
        }
        xml.push_str("    </Derivatives>\n");
    }
    xml.push_str("    <InitialUnknowns>\n");
    let mut initial: Vec<(usize, Option<&Vec<usize>>)> =
        outputs.iter().zip(&dependencies.outputs).map(|(v, all)| (v.index, Some(all))).collect();
    initial.extend(derivatives.iter().map(|v| (v.index, None)));
    initial.extend(local_states.map(|v| (v.index, None)));
    initial.sort_unstable_by_key(|(index, _)| *index);
    for (index, all) in initial {
        match all {
            Some(all) => {
                let all: Vec<String> = all.iter().filter(|i| !states.contains(i)).map(usize::to_string).collect();
                writeln!(xml, "      <Unknown index=\"{index}\" dependencies=\"{}\"/>", all.join(" ")).unwrap();
            }
            None => writeln!(xml, "      <Unknown index=\"{index}\"/>").unwrap(),
        }
    }
    xml.push_str("    </InitialUnknowns>\n  </ModelStructure>");
    xml
}

/// The packaged model description: the source with its by-name `<ModelStructure>` (and the
/// comment before it) replaced by the standard form.
fn packaged_xml(text: &str, model_structure: &str) -> String {
    let start = text.find("<ModelStructure>").unwrap_or_else(|| fail("no <ModelStructure>".into()));
    let end = text.find("</ModelStructure>").expect("closed") + "</ModelStructure>".len();
    let comment = text[..start].rfind("<!--").filter(|c| text[*c..start].trim_end().ends_with("-->"));
    let start_of_comment = comment.unwrap_or(start);
    format!("{}{model_structure}{}", &text[..start_of_comment], &text[end..])
}

/// A 64-bit FNV-1a hash of the variable layout (names, value references, causalities and types
/// in order): the FMU-state format tag, so that a state written by an FMU with another layout
/// is never read as this one's.
fn layout_tag(variables: &[Variable]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for v in variables {
        let row = format!("{}|{}|{:?}|{:?};", v.name, v.value_reference, v.causality, v.base_type);
        for byte in row.bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

fn rust_type(variable: &Variable) -> &'static str {
    match variable.base_type {
        BaseType::Real => "f64",
        BaseType::Integer | BaseType::Enumeration => "i32",
        BaseType::String => "String",
    }
}

fn constant_name(name: &str) -> String {
    name.to_ascii_uppercase()
}

fn camel_case(name: &str) -> String {
    name.split('_').map(|word| word[..1].to_ascii_uppercase() + &word[1..]).collect()
}

fn write_units(source: &mut String, units: &BTreeMap<String, Vec<(String, f64)>>) {
    writeln!(
        source,
        "/// `<UnitDefinitions>`: unit name and its display units (name, factor: display = factor · value)."
    )
    .unwrap();
    writeln!(source, "pub const UNITS: &[(&str, &[(&str, f64)])] = &[").unwrap();
    for (unit, display_units) in units {
        writeln!(source, "    ({unit:?}, &{display_units:?}),").unwrap();
    }
    writeln!(source, "];\n").unwrap();
}

fn write_enumeration(source: &mut String, enumeration: &EnumerationType) {
    let EnumerationType { name, description, items } = enumeration;
    writeln!(source, "/// {description}").unwrap();
    writeln!(source, "#[derive(Debug, Clone, Copy, PartialEq, Eq)]\npub enum {name} {{").unwrap();
    for (item, value, item_description) in items {
        writeln!(source, "    /// {item_description}\n    {} = {value},", camel_case(item)).unwrap();
    }
    writeln!(source, "}}\n\nimpl {name} {{").unwrap();
    writeln!(source, "    /// The items as (name, value, description), in XML order.").unwrap();
    writeln!(source, "    pub const ITEMS: &[(&str, i32, &str)] = &{items:?};").unwrap();
    writeln!(source, "    /// The item with this integer value, if any.").unwrap();
    writeln!(source, "    pub fn from_value(value: i32) -> Option<Self> {{\n        match value {{").unwrap();
    for (item, value, _) in items {
        writeln!(source, "            {value} => Some(Self::{}),", camel_case(item)).unwrap();
    }
    writeln!(source, "            _ => None,\n        }}\n    }}\n}}\n").unwrap();
}

fn write_value_references(source: &mut String, variables: &[Variable]) {
    writeln!(source, "/// Value references, one constant per variable.\npub mod value_reference {{").unwrap();
    for v in variables {
        writeln!(
            source,
            "    /// `{}`: {}\n    pub const {}: u32 = {};",
            v.name,
            v.description,
            constant_name(&v.ident),
            v.value_reference
        )
        .unwrap();
    }
    writeln!(source, "}}\n").unwrap();
}

fn write_structs(source: &mut String, variables: &[Variable]) {
    let groups = [
        ("Inputs", Causality::Input, "The inputs (causality = input)."),
        ("Parameters", Causality::Parameter, "The parameters (causality = parameter)."),
        ("Outputs", Causality::Output, "The outputs (causality = output), as last computed."),
        (
            "Locals",
            Causality::Local,
            "The state derivatives and the continuous states that are neither inputs nor outputs (causality = \
             local), as last computed.",
        ),
    ];
    for (struct_name, causality, doc) in groups {
        writeln!(
            source,
            "/// {doc}\n#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]\npub struct \
             {struct_name} {{"
        )
        .unwrap();
        for v in variables.iter().filter(|v| v.causality == causality && v.base_type != BaseType::String) {
            // Escaped: rustdoc would read "[m]" as a link.
            let unit = v.unit.as_deref().map(|u| format!(" \\[{u}\\]")).unwrap_or_default();
            writeln!(source, "    /// {}{unit}\n    pub {}: {},", v.description, v.ident, rust_type(v)).unwrap();
        }
        writeln!(source, "}}\n\nimpl Default for {struct_name} {{\n    /// The start values.").unwrap();
        writeln!(source, "    fn default() -> Self {{\n        Self {{").unwrap();
        for v in variables.iter().filter(|v| v.causality == causality && v.base_type != BaseType::String) {
            let value = match (&v.start, v.base_type) {
                (Some(start), BaseType::Real) => format!("{:?}", start.parse::<f64>().unwrap()),
                (Some(start), _) => start.parse::<i32>().unwrap().to_string(),
                // Outputs have no start value; they are computed before any master can read them.
                (None, BaseType::Real) => "0.0".into(),
                (None, _) => "0".into(),
            };
            writeln!(source, "            {}: {value},", v.ident).unwrap();
        }
        writeln!(source, "        }}\n    }}\n}}\n").unwrap();
    }
    // The outputs (all Real) as an array with their names: the adapter checks them all at
    // every step, and that must cost a few compares, not a lookup per value reference.
    let outputs: Vec<&Variable> = variables.iter().filter(|v| v.causality == Causality::Output).collect();
    assert!(outputs.iter().all(|v| v.base_type == BaseType::Real), "every output must be a Real");
    let names: Vec<String> = outputs.iter().map(|v| format!("\"{}\"", v.name)).collect();
    let fields: Vec<String> = outputs.iter().map(|v| format!("self.{}", v.name)).collect();
    writeln!(
        source,
        "impl Outputs {{\n    /// The outputs' names, in the order of [`Outputs::reals`].\n    pub const NAMES: [&str; {n}] = \
         [{names}];\n\n    /// Every output's value.\n    #[inline]\n    pub fn reals(&self) -> [f64; {n}] {{\n        \
         [{fields}]\n    }}\n}}\n",
        n = outputs.len(),
        names = names.join(", "),
        fields = fields.join(", ")
    )
    .unwrap();
    write_strings(source, variables);
    let strings =
        if variables.iter().any(|v| v.base_type == BaseType::String) { " but the Strings ([`Strings`])" } else { "" };
    writeln!(source, "/// Every value of one instance{strings}: plain data, no pointers.").unwrap();
    writeln!(source, "#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]")
        .unwrap();
    writeln!(
        source,
        "pub struct Values {{\n    pub inputs: Inputs,\n    pub parameters: Parameters,\n    pub outputs: Outputs,\n    pub \
         locals: Locals,\n}}\n"
    )
        .unwrap();
}

/// The String variables (parameters only) in their own struct: owned text is not `Copy`, and
/// the value structs are (the instance compares and copies them on the hot path).
/// Nothing for a model without String variables.
fn write_strings(source: &mut String, variables: &[Variable]) {
    let strings: Vec<&Variable> = variables.iter().filter(|v| v.base_type == BaseType::String).collect();
    if strings.is_empty() {
        return;
    }
    writeln!(
        source,
        "/// The String parameters (owned copies of what fmi2SetString gave).\n#[derive(Debug, Clone, PartialEq, \
         serde::Serialize, serde::Deserialize)]\npub struct Strings {{"
    )
    .unwrap();
    for v in &strings {
        writeln!(source, "    /// {}\n    pub {}: String,", v.description, v.name).unwrap();
    }
    writeln!(
        source,
        "}}\n\nimpl Default for Strings {{\n    /// The start values.\n    fn default() -> Self {{\n        Self {{"
    )
    .unwrap();
    for v in &strings {
        writeln!(source, "            {}: {:?}.to_owned(),", v.name, v.start.as_deref().unwrap_or_default()).unwrap();
    }
    writeln!(source, "        }}\n    }}\n}}\n\nimpl Strings {{").unwrap();
    for (suffix, doc, receiver, reference) in [("", "", "&self", "&"), ("_mut", ", for writing", "&mut self", "&mut ")]
    {
        writeln!(source, "    /// The String behind a value reference{doc}.").unwrap();
        writeln!(source, "    pub fn string{suffix}({receiver}, value_reference: u32) -> Option<{reference}String> {{")
            .unwrap();
        writeln!(source, "        match value_reference {{").unwrap();
        for v in &strings {
            writeln!(
                source,
                "            value_reference::{} => Some({reference}self.{}),",
                constant_name(&v.name),
                v.name
            )
            .unwrap();
        }
        writeln!(source, "            _ => None,\n        }}\n    }}\n").unwrap();
    }
    writeln!(source, "}}\n").unwrap();
}

fn field_path(v: &Variable) -> String {
    let group = match v.causality {
        Causality::Input => "inputs",
        Causality::Parameter => "parameters",
        Causality::Output => "outputs",
        Causality::Local => "locals",
    };
    debug_assert!(v.base_type != BaseType::String, "Strings are not in Values");
    format!("{group}.{}", v.ident)
}

fn write_accessors(source: &mut String, variables: &[Variable]) {
    writeln!(source, "impl Values {{").unwrap();
    for (kind, types) in [("real", &[BaseType::Real][..]), ("integer", &[BaseType::Integer, BaseType::Enumeration][..])]
    {
        let rust = if kind == "real" { "f64" } else { "i32" };
        let matching: Vec<&Variable> = variables.iter().filter(|v| types.contains(&v.base_type)).collect();
        // A model without variables of the kind gets no accessors (no code that can only say None).
        if matching.is_empty() {
            continue;
        }
        // The reading accessor and the writing one differ only in their references.
        for (suffix, doc, receiver, reference) in
            [("", "", "&self", ""), ("_mut", ", for writing", "&mut self", "&mut ")]
        {
            writeln!(source, "    /// The field behind a {kind} value reference{doc}.").unwrap();
            writeln!(source, "    #[inline]").unwrap();
            writeln!(
                source,
                "    pub fn {kind}{suffix}({receiver}, value_reference: u32) -> Option<{reference}{rust}> {{"
            )
            .unwrap();
            writeln!(source, "        match value_reference {{").unwrap();
            for v in &matching {
                writeln!(
                    source,
                    "            value_reference::{} => Some({reference}self.{}),",
                    constant_name(&v.ident),
                    field_path(v)
                )
                .unwrap();
            }
            writeln!(source, "            _ => None,\n        }}\n    }}\n").unwrap();
        }
    }
    writeln!(source, "}}\n").unwrap();
}

fn write_table(source: &mut String, variables: &[Variable], dependencies: &Dependencies) {
    let output_dependencies = &dependencies.outputs;
    let by_index: BTreeMap<usize, &Variable> = variables.iter().map(|v| (v.index, v)).collect();
    writeln!(source, "/// Every variable, in `<ModelVariables>` order.").unwrap();
    writeln!(source, "pub const VARIABLES: [Variable; {}] = [", variables.len()).unwrap();
    for v in variables {
        let causality = format!("{:?}", v.causality);
        let variability = camel_case(&v.variability);
        let kind = match v.base_type {
            BaseType::Real => {
                format!("Kind::Real {{ start: {:?} }}", v.start.as_ref().map(|s| s.parse::<f64>().unwrap()))
            }
            BaseType::Integer => {
                format!("Kind::Integer {{ start: {:?} }}", v.start.as_ref().map(|s| s.parse::<i32>().unwrap()))
            }
            BaseType::String => format!("Kind::String {{ start: {:?} }}", v.start.as_deref().unwrap_or_default()),
            BaseType::Enumeration => format!(
                "Kind::Enumeration {{ declared_type: {:?}, items: {}::ITEMS, start: {} }}",
                v.declared_type.as_deref().unwrap(),
                v.declared_type.as_deref().unwrap(),
                v.start.as_deref().unwrap()
            ),
        };
        let dependencies: Vec<u32> = if v.causality == Causality::Output {
            let position =
                variables.iter().filter(|o| o.causality == Causality::Output).position(|o| o.index == v.index);
            // The inputs (`<Outputs>`); the parameters are for the initial unknowns only.
            output_dependencies[position.unwrap()]
                .iter()
                .filter(|i| by_index[*i].causality == Causality::Input)
                .map(|i| by_index[i].value_reference)
                .collect()
        } else if v.derivative.is_some() {
            let position = variables.iter().filter(|o| o.derivative.is_some()).position(|o| o.index == v.index);
            dependencies.derivatives[position.unwrap()].iter().map(|i| by_index[i].value_reference).collect()
        } else {
            Vec::new()
        };
        writeln!(
            source,
            "    Variable {{ name: {:?}, value_reference: {}, causality: Causality::{causality}, variability: \
             Variability::{variability}, kind: {kind}, unit: {:?}, display_unit: {:?}, description: {:?}, \
             dependencies: &{dependencies:?} }},",
            v.name, v.value_reference, v.unit, v.display_unit, v.description
        )
        .unwrap();
    }
    writeln!(source, "];\n").unwrap();
    // A dense table by value reference: every Get/Set looks its references up here, so the
    // lookup is one bounds check and one indexed load (no search, no string compare).
    let largest = variables.iter().map(|v| v.value_reference).max().unwrap_or(0);
    if largest > 4095 || variables.len() >= usize::from(u16::MAX) {
        fail(format!("value references up to 4095 keep the lookup table small; {largest} is too large"));
    }
    let mut positions = vec![u16::MAX; largest as usize + 1];
    for (position, v) in variables.iter().enumerate() {
        positions[v.value_reference as usize] = position as u16;
    }
    writeln!(source, "/// Position in [`VARIABLES`] by value reference (`u16::MAX`: no such variable).").unwrap();
    writeln!(source, "const POSITION_BY_VALUE_REFERENCE: [u16; {}] = {positions:?};\n", positions.len()).unwrap();
    writeln!(
        source,
        "/// The variable with this value reference: one indexed load in a dense table (it runs on every \
         Get/Set).\n#[inline]\npub fn variable(value_reference: u32) -> Option<&'static Variable> {{\n    \
         let position = POSITION_BY_VALUE_REFERENCE.get(usize::try_from(value_reference).ok()?)?;\n    \
         VARIABLES.get(usize::from(*position))\n}}"
    )
    .unwrap();
    // What Get/Set check per value, as bits in one byte per value reference: the hot path reads
    // one byte instead of a whole table row.
    let mut access = vec![0u8; largest as usize + 1];
    for v in variables {
        use crate::variables::access::{FEEDTHROUGH, FIXED, INTEGER, OUTPUT, PARAMETER, REAL, STRING, WRITABLE};
        let base = match v.base_type {
            BaseType::Real => REAL,
            BaseType::Integer | BaseType::Enumeration => INTEGER,
            BaseType::String => STRING,
        };
        let writable = match (v.causality, v.variability.as_str()) {
            (Causality::Output | Causality::Local, _) => OUTPUT,
            (Causality::Parameter, "fixed") => PARAMETER | FIXED,
            (Causality::Parameter, _) => PARAMETER | WRITABLE,
            (Causality::Input, _) => WRITABLE,
        };
        let feeds_through = v.causality == Causality::Input
            && output_dependencies.iter().any(|dependencies| dependencies.contains(&v.index));
        access[v.value_reference as usize] = base | writable | if feeds_through { FEEDTHROUGH } else { 0 };
    }
    writeln!(
        source,
        "\n/// Per value reference, what Get/Set need to know, as [`access`] bits (0: no such variable).\n\
         pub const ACCESS: [u8; {}] = {access:?};\n\
         /// The bits of [`ACCESS`] (the slave layer's, so that its generic instance reads them too).\n\
         pub use fmi2_slave::variables::access;\n\
         /// The [`ACCESS`] bits of a value reference (0 if there is none).\n\
         #[inline]\npub fn access_of(value_reference: u32) -> u8 {{\n    \
         usize::try_from(value_reference).ok().and_then(|i| ACCESS.get(i)).copied().unwrap_or(0)\n}}",
        access.len()
    )
    .unwrap();
}
