//! The types of the tables that `fmi2_slave::build` generates from a `modelDescription.xml`: one
//! [`Variable`] per `<ScalarVariable>`.

/// `causality` of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Input,
    Parameter,
    Output,
    /// Computed by the model, not connected: the state derivatives of Model Exchange.
    Local,
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
    /// For outputs: the value references of the inputs it depends on (`<ModelStructure><Outputs>`);
    /// for state derivatives: the inputs and states (`<ModelStructure><Derivatives>`).
    pub dependencies: &'static [u32],
}

/// What Get/Set need to know of a variable, as bits in one byte: the generator writes them per
/// value reference into a dense table (`ACCESS`, `access_of`), so that the hot path reads one
/// byte instead of a table row; [`access::of`] computes them from a [`Variable`].
pub mod access {
    use super::{Causality, Kind, Variability, Variable};

    /// A Real variable.
    pub const REAL: u8 = 1;
    /// An Integer or Enumeration variable.
    pub const INTEGER: u8 = 2;
    /// A parameter.
    pub const PARAMETER: u8 = 4;
    /// Writable in every mode that allows Set (inputs, tunable parameters).
    pub const WRITABLE: u8 = 8;
    /// Writable only before initialisation ends (fixed parameters).
    pub const FIXED: u8 = 16;
    /// Computed by the model, never written: an output or a local (a state derivative).
    pub const OUTPUT: u8 = 32;
    /// A String variable.
    pub const STRING: u8 = 64;
    /// An input some output depends on directly (`<ModelStructure>`): after it is written in
    /// step mode, a read of an output first computes the outputs at the new inputs.
    pub const FEEDTHROUGH: u8 = 128;

    /// The bits of `variable` among `variables` (the generator's table holds the same, one byte
    /// per value reference).
    pub fn of(variable: &Variable, variables: &[Variable]) -> u8 {
        let base = match variable.kind {
            Kind::Real { .. } => REAL,
            Kind::Integer { .. } | Kind::Enumeration { .. } => INTEGER,
            Kind::String { .. } => STRING,
        };
        let writable = match (variable.causality, variable.variability) {
            (Causality::Output | Causality::Local, _) => OUTPUT,
            (Causality::Parameter, Variability::Fixed) => PARAMETER | FIXED,
            (Causality::Parameter, _) => PARAMETER | WRITABLE,
            (Causality::Input, _) => WRITABLE,
        };
        let feeds_through = variable.causality == Causality::Input
            && variables
                .iter()
                .any(|o| o.causality == Causality::Output && o.dependencies.contains(&variable.value_reference));
        base | writable | if feeds_through { FEEDTHROUGH } else { 0 }
    }
}

#[cfg(test)]
mod tests {
    use super::access::{self, FEEDTHROUGH, OUTPUT, PARAMETER, REAL, WRITABLE};
    use super::{Causality, Kind, Variability, Variable};

    const fn real(
        name: &'static str,
        value_reference: u32,
        causality: Causality,
        dependencies: &'static [u32],
    ) -> Variable {
        let variability =
            if matches!(causality, Causality::Parameter) { Variability::Tunable } else { Variability::Continuous };
        Variable {
            name,
            value_reference,
            causality,
            variability,
            kind: Kind::Real { start: None },
            unit: None,
            display_unit: None,
            description: "",
            dependencies,
        }
    }

    /// An input is a feedthrough input when some output lists it among its dependencies; an input
    /// no output lists is not, nor is a parameter an output lists.
    #[test]
    fn only_inputs_an_output_depends_on_feed_through() {
        let variables = [
            real("fed", 0, Causality::Input, &[]),
            real("unused", 1, Causality::Input, &[]),
            real("gain", 2, Causality::Parameter, &[]),
            real("out", 3, Causality::Output, &[0, 2]),
        ];
        let bits: Vec<u8> = variables.iter().map(|v| access::of(v, &variables)).collect();
        assert_eq!(bits, [REAL | WRITABLE | FEEDTHROUGH, REAL | WRITABLE, REAL | PARAMETER | WRITABLE, REAL | OUTPUT]);
    }
}
