//! The error every model returns for an input it cannot accept.

use std::fmt;

/// An input value outside the domain of the models: names the variable, its value and the rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InvalidInput {
    /// The variable's name, as in [`crate::ContactInput`] and the FMU's `modelDescription.xml`.
    pub variable: &'static str,
    /// The rejected value.
    pub value: f64,
    /// The rule it breaks, e.g. "must be finite and > 0".
    pub requirement: &'static str,
}

impl InvalidInput {
    #[cold]
    pub(crate) fn new(variable: &'static str, value: f64, requirement: &'static str) -> Self {
        Self { variable, value, requirement }
    }
}

impl fmt::Display for InvalidInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = ", self.variable)?;
        // Ordinary values as written (0.2, -1); huge and tiny ones in exponent form, not 309 digits.
        let magnitude = self.value.abs();
        if magnitude != 0.0 && magnitude.is_finite() && !(1e-5..1e16).contains(&magnitude) {
            write!(f, "{:e}", self.value)?;
        } else {
            write!(f, "{}", self.value)?;
        }
        write!(f, " is invalid: {}", self.requirement)
    }
}

impl std::error::Error for InvalidInput {}
