//! The types of the tables that `fmi2_slave::build` generates from a `modelDescription.xml`: one
//! [`Variable`] per `<ScalarVariable>`.

/// `causality` of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Input,
    Parameter,
    Output,
}

/// `variability` of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Tunable,
    Continuous,
}

/// The base type of a variable, with its start value (`None` for outputs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    Real {
        start: Option<f64>,
    },
    Integer {
        start: Option<i32>,
    },
    Enumeration {
        declared_type: &'static str,
        items: &'static [(&'static str, i32, &'static str)],
        start: i32,
    },
    /// A String parameter (kept apart from the `Copy` value structs, in the generated `Strings`).
    String {
        start: &'static str,
    },
}

/// One `<ScalarVariable>`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    pub name: &'static str,
    pub value_reference: u32,
    pub causality: Causality,
    pub variability: Variability,
    pub kind: Kind,
    pub unit: Option<&'static str>,
    pub display_unit: Option<&'static str>,
    pub description: &'static str,
    /// For outputs: the value references of the inputs it depends on (`<ModelStructure><Outputs>`).
    pub dependencies: &'static [u32],
}
