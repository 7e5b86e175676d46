//! The model-description generator (`fmi2_slave::build::generate`, run by both FMUs' build
//! scripts) on a small model description of its own: what it writes (the packaged description
//! with the standard `<ModelStructure>`, the state layout tag) and what it refuses, each refusal
//! by its message.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

/// A valid description: one input, one parameter, one output depending on both.
const VALID: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="probe" guid="{00000000-0000-0000-0000-000000000001}">
  <CoSimulation modelIdentifier="probe" canHandleVariableCommunicationStepSize="true"/>
  <UnitDefinitions>
    <Unit name="N">
      <BaseUnit kg="1" m="1" s="-2"/>
    </Unit>
  </UnitDefinitions>
  <ModelVariables>
    <ScalarVariable name="load" valueReference="0" causality="input" variability="continuous" description="A load">
      <Real unit="N" start="1"/>
    </ScalarVariable>
    <ScalarVariable name="gain" valueReference="100" causality="parameter" variability="fixed" description="A gain">
      <Real unit="N" start="2"/>
    </ScalarVariable>
    <ScalarVariable name="force" valueReference="200" causality="output" variability="continuous" description="A force">
      <Real unit="N"/>
    </ScalarVariable>
  </ModelVariables>
  <!-- By name: the generator writes the indices. -->
  <ModelStructure>
    <Output name="force" dependsOn="load gain"/>
  </ModelStructure>
</fmiModelDescription>
"#;

/// The generated Rust source and packaged description, or the message the generator stopped
/// with.
fn generate(xml: &str, name: &str) -> Result<(String, String), String> {
    let directory = std::env::temp_dir().join(format!("fmi2-slave-generator-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let xml_path = directory.join("modelDescription.in.xml");
    std::fs::write(&xml_path, xml).unwrap();
    let out_path: PathBuf = directory.join("model_description.rs");
    let result = catch_unwind(AssertUnwindSafe(|| fmi2_slave::build::generate(xml_path.to_str().unwrap(), &out_path)));
    let outcome = match result {
        Ok(()) => Ok((
            std::fs::read_to_string(&out_path).unwrap(),
            std::fs::read_to_string(directory.join("modelDescription.xml")).unwrap(),
        )),
        Err(panic) => Err(panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
            .unwrap_or_default()),
    };
    std::fs::remove_dir_all(&directory).unwrap();
    outcome
}

/// 64-bit FNV-1a, checked on the published test vectors below.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &byte| (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3))
}

#[test]
fn the_packaged_description_has_the_standard_model_structure_and_the_rest_unchanged() {
    let (source, packaged) = generate(VALID, "packaged").unwrap();
    // FMI 2.0 section 2.2.8: outputs and initial unknowns by 1-based index of ModelVariables.
    let structure = "<ModelStructure>\n    <Outputs>\n      <Unknown index=\"3\" dependencies=\"1\" dependenciesKind=\"dependent\"/>";
    assert!(packaged.contains(structure), "{packaged}");
    assert!(!packaged.contains("dependsOn") && !packaged.contains("By name"), "{packaged}");
    let before = &VALID[..VALID.find("  <!-- By name").unwrap()];
    assert!(packaged.starts_with(before) && packaged.ends_with("</ModelStructure>\n</fmiModelDescription>\n"));
    assert!(source.contains("pub const GUID: &str = \"{00000000-0000-0000-0000-000000000001}\";"), "{source}");
}

#[test]
fn the_state_layout_tag_is_fnv1a_over_the_variable_rows() {
    // FNV's published vectors (Fowler, Noll, Vo: the FNV-1a 64-bit test suite).
    assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
    assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
    assert_eq!(fnv1a(b"foobar"), 0x8594_4171_f739_67e8);
    let (source, _) = generate(VALID, "tag").unwrap();
    let rows = "load|0|Input|Real;gain|100|Parameter|Real;force|200|Output|Real;";
    let expected = format!("pub const STATE_LAYOUT_TAG: u64 = {:#018x};", fnv1a(rows.as_bytes()));
    assert!(source.contains(&expected), "{expected} not in the source");
}

#[test]
fn malformed_descriptions_are_refused_by_their_fault() {
    let refusal = |name: &str, from: &str, to: &str| -> String {
        assert!(VALID.contains(from), "{from}");
        generate(&VALID.replace(from, to), name).expect_err(name)
    };
    let root = "modelDescription.xml: the root must be <fmiModelDescription fmiVersion=\"2.0\">";
    assert_eq!(refusal("version", "fmiVersion=\"2.0\"", "fmiVersion=\"3.0\""), root);
    assert_eq!(refusal("root", "fmiModelDescription", "fmiModelDescriptions"), root);
    assert_eq!(
        refusal("output start", "<Real unit=\"N\"/>", "<Real unit=\"N\" start=\"0\"/>"),
        "modelDescription.xml: output force: initial=\"calculated\" forbids a start value"
    );
    assert_eq!(
        refusal("input start", "<Real unit=\"N\" start=\"1\"/>", "<Real unit=\"N\"/>"),
        "modelDescription.xml: load: inputs and parameters need a start"
    );
    // Value references up to 4095 (the dense lookup table's bound), not beyond.
    assert!(generate(&VALID.replace("valueReference=\"200\"", "valueReference=\"4095\""), "4095").is_ok());
    assert_eq!(
        refusal("4096", "valueReference=\"200\"", "valueReference=\"4096\""),
        "modelDescription.xml: value references up to 4095 keep the lookup table small; 4096 is too large"
    );
}

/// A Model Exchange description: the output `position` is a continuous state, `der(position)`
/// its derivative, depending on the input and the state.
const WITH_STATE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="probe" guid="{00000000-0000-0000-0000-000000000002}">
  <CoSimulation modelIdentifier="probe" canHandleVariableCommunicationStepSize="true"/>
  <ModelExchange modelIdentifier="probe"/>
  <UnitDefinitions>
    <Unit name="m">
      <BaseUnit m="1"/>
    </Unit>
    <Unit name="m/s">
      <BaseUnit m="1" s="-1"/>
    </Unit>
  </UnitDefinitions>
  <ModelVariables>
    <ScalarVariable name="speed" valueReference="0" causality="input" variability="continuous" description="A speed">
      <Real unit="m/s" start="1"/>
    </ScalarVariable>
    <ScalarVariable name="start" valueReference="100" causality="parameter" variability="fixed" description="Where it starts">
      <Real unit="m" start="2"/>
    </ScalarVariable>
    <ScalarVariable name="position" valueReference="200" causality="output" variability="continuous" description="A position">
      <Real unit="m" nominal="0.001"/>
    </ScalarVariable>
    <ScalarVariable name="der(position)" valueReference="300" causality="local" variability="continuous" description="Its rate">
      <Real unit="m/s" derivative="3"/>
    </ScalarVariable>
  </ModelVariables>
  <ModelStructure>
    <Output name="position" dependsOn="start"/>
    <Derivative name="der(position)" dependsOn="speed position"/>
  </ModelStructure>
</fmiModelDescription>
"#;

#[test]
fn a_continuous_state_gets_its_derivative_structure_and_table() {
    let (source, packaged) = generate(WITH_STATE, "state").unwrap();
    // FMI 2.0 §2.2.8: the output that is a state depends on that state; the derivative on the
    // input (1) and the state (3); the initial unknowns are the output and the derivative, in
    // index order, the derivative on every known.
    let structure = "<ModelStructure>\n    <Outputs>\n      <Unknown index=\"3\" dependencies=\"3\" dependenciesKind=\"dependent\"/>\n    </Outputs>\n    <Derivatives>\n      <Unknown index=\"4\" dependencies=\"1 3\" dependenciesKind=\"dependent dependent\"/>\n    </Derivatives>\n    <InitialUnknowns>\n      <Unknown index=\"3\" dependencies=\"2\"/>\n      <Unknown index=\"4\"/>\n    </InitialUnknowns>\n  </ModelStructure>";
    assert!(packaged.contains(structure), "{packaged}");
    assert!(source.contains("pub const CONTINUOUS_STATES: &[(u32, u32, f64)] = &[(200, 300, 0.001)];"), "{source}");
    assert!(source.contains("pub const MODEL_EXCHANGE: bool = true;"), "{source}");
    assert!(source.contains("pub der_position: f64,"), "{source}");
    assert!(source.contains("pub const DER_POSITION: u32 = 300;"), "{source}");
    assert!(source.contains("value_reference::DER_POSITION => Some(self.locals.der_position),"), "{source}");
    assert!(source.contains("dependencies: &[0, 200] }"), "{source}");
    let (plain, _) = generate(VALID, "plain").unwrap();
    assert!(plain.contains("pub const CONTINUOUS_STATES: &[(u32, u32, f64)] = &[];"), "{plain}");
    assert!(plain.contains("pub const MODEL_EXCHANGE: bool = false;"), "{plain}");
}

/// A continuous state that is neither input nor output (a local, as the contact FMU's relaxed
/// forces): a continuous state of Model Exchange, not an output, and an initial unknown.
#[test]
fn a_local_continuous_state_is_a_state_and_an_initial_unknown() {
    let local = WITH_STATE
        .replace(
            "name=\"position\" valueReference=\"200\" causality=\"output\"",
            "name=\"position\" valueReference=\"250\" causality=\"local\"",
        )
        .replace(
            "  </ModelVariables>",
            "    <ScalarVariable name=\"reading\" valueReference=\"200\" causality=\"output\" variability=\"continuous\" description=\"A reading of the position\">\n      <Real unit=\"m\"/>\n    </ScalarVariable>\n  </ModelVariables>",
        )
        .replace("<Output name=\"position\" dependsOn=\"start\"/>", "<Output name=\"reading\" dependsOn=\"start position speed\"/>");
    let (source, packaged) = generate(&local, "local state").unwrap();
    // The output (5) depends on the input (1) and the state (3) in <Outputs>; as an initial
    // unknown on the input and the parameter (2) only: the state is calculated too.
    let structure = "<ModelStructure>\n    <Outputs>\n      <Unknown index=\"5\" dependencies=\"1 3\" dependenciesKind=\"dependent dependent\"/>\n    </Outputs>\n    <Derivatives>\n      <Unknown index=\"4\" dependencies=\"1 3\" dependenciesKind=\"dependent dependent\"/>\n    </Derivatives>\n    <InitialUnknowns>\n      <Unknown index=\"3\"/>\n      <Unknown index=\"4\"/>\n      <Unknown index=\"5\" dependencies=\"1 2\"/>\n    </InitialUnknowns>\n  </ModelStructure>";
    assert!(packaged.contains(structure), "{packaged}");
    assert!(source.contains("pub const CONTINUOUS_STATES: &[(u32, u32, f64)] = &[(250, 300, 0.001)];"), "{source}");
    assert!(source.contains("value_reference::POSITION => Some(self.locals.position),"), "{source}");
    // The state's row has no dependencies (it is no output); its derivative's has its own.
    assert!(source.contains("name: \"position\", value_reference: 250, causality: Causality::Local"), "{source}");
    assert!(source.contains("dependencies: &[0, 250] }"), "{source}");
    // A second local that is neither a derivative nor the state of one.
    let stray = local.replace(
        "  </ModelVariables>",
        "    <ScalarVariable name=\"stray\" valueReference=\"251\" causality=\"local\" variability=\"continuous\" description=\"?\">\n      <Real unit=\"m\"/>\n    </ScalarVariable>\n  </ModelVariables>",
    );
    assert_eq!(
        generate(&stray, "stray").expect_err("stray"),
        "modelDescription.xml: local stray: a local is a state derivative (with `derivative`) or the continuous state \
         of one"
    );
}

#[test]
fn malformed_states_are_refused_by_their_fault() {
    let refusal = |name: &str, from: &str, to: &str| -> String {
        assert!(WITH_STATE.contains(from), "{from}");
        generate(&WITH_STATE.replace(from, to), name).expect_err(name)
    };
    let not_the_state =
        "modelDescription.xml: der(position): derivative = 2 must be the index of the continuous Real it is named after";
    assert_eq!(refusal("index", "derivative=\"3\"", "derivative=\"2\""), not_the_state);
    // The input `speed` (1) is a continuous Real, but not the one the derivative is named after.
    let not_the_input =
        "modelDescription.xml: der(position): derivative = 1 must be the index of the continuous Real it is named after";
    assert_eq!(refusal("input", "derivative=\"3\"", "derivative=\"1\""), not_the_input);
    // Named after the parameter `start` (2), a Real of fixed variability: not a state.
    let fixed = WITH_STATE.replace("der(position)", "der(start)").replace("derivative=\"3\"", "derivative=\"2\"");
    assert_eq!(
        generate(&fixed, "fixed").expect_err("fixed"),
        "modelDescription.xml: der(start): derivative = 2 must be the index of the continuous Real it is named after"
    );
    assert_eq!(
        refusal(
            "local start",
            "<Real unit=\"m/s\" derivative=\"3\"/>",
            "<Real unit=\"m/s\" derivative=\"3\" start=\"0\"/>"
        ),
        "modelDescription.xml: local der(position): initial=\"calculated\" forbids a start value"
    );
    assert_eq!(
        refusal("identifier", "name=\"speed\"", "name=\"_speed\""),
        "modelDescription.xml: variable `_speed`: names must be snake_case identifiers or der(identifier) (they become \
         Rust fields)"
    );
    assert_eq!(
        refusal("no derivative", " derivative=\"3\"", ""),
        "modelDescription.xml: local der(position): a local is a state derivative (with `derivative`) or the \
         continuous state of one"
    );
    assert_eq!(
        refusal(
            "derivative output",
            "valueReference=\"300\" causality=\"local\"",
            "valueReference=\"300\" causality=\"output\""
        ),
        "modelDescription.xml: variable der(position): only locals can be state derivatives (with `derivative`)"
    );
    assert_eq!(
        refusal("parameter", "dependsOn=\"speed position\"", "dependsOn=\"speed start\""),
        "modelDescription.xml: der(position) cannot depend on `start`: not an input or continuous state"
    );
    assert_eq!(
        refusal("missing", "    <Derivative name=\"der(position)\" dependsOn=\"speed position\"/>\n", ""),
        "modelDescription.xml: <ModelStructure> must declare exactly the Derivatives [\"der(position)\"], in order"
    );
    assert_eq!(
        refusal("no ME", "  <ModelExchange modelIdentifier=\"probe\"/>\n", ""),
        "modelDescription.xml: state derivatives need <ModelExchange>"
    );
    assert_eq!(
        refusal("other binary", "<ModelExchange modelIdentifier=\"probe\"/>", "<ModelExchange modelIdentifier=\"other\"/>"),
        "modelDescription.xml: <ModelExchange> must have <CoSimulation>'s modelIdentifier: one binary holds both interfaces"
    );
    assert_eq!(
        refusal("nominal", "nominal=\"0.001\"", "nominal=\"0\""),
        "modelDescription.xml: variable position: nominal = 0 must be finite and > 0"
    );
}
