//! The error every model returns for an input it cannot accept.

use std::fmt;

/// An input value outside the domain of the models: names the variable, its value and the rule.
///
/// ```
/// use wheel_rail_contact::hertz::RelativeCurvature;
///
/// let error = RelativeCurvature::from_radii(0.46, f64::INFINITY, -0.3).unwrap_err();
/// assert_eq!((error.variable, error.value), ("rail_profile_radius", -0.3));
/// assert_eq!(error.with, [Some(("wheel_profile_radius", f64::INFINITY)), None]);
/// assert!(error.to_string().starts_with("rail_profile_radius = -0.3 is invalid with wheel_profile_radius = inf: "));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InvalidInput {
    /// The variable's name, as in [`crate::ContactInput`] and the FMU's `modelDescription.xml`.
    pub variable: &'static str,
    /// The rejected value.
    pub value: f64,
    /// The rule it breaks, e.g. "must be finite and > 0".
    pub requirement: &'static str,
    /// Other inputs the rule involves, with their values (printed after the value): a rule on
    /// a combination names every input in it.
    pub with: [Option<(&'static str, f64)>; 2],
}

impl InvalidInput {
    #[cold]
    pub(crate) fn new(variable: &'static str, value: f64, requirement: &'static str) -> Self {
        Self { variable, value, requirement, with: [None; 2] }
    }

    /// The same error naming `others` (input, value) as well; see [`InvalidInput::with`].
    #[cold]
    pub(crate) fn involving(self, others: [Option<(&'static str, f64)>; 2]) -> Self {
        Self { with: others, ..self }
    }
}

/// Ordinary values as written (0.2, -1); huge and tiny ones in exponent form, not 309 digits.
fn write_value(f: &mut fmt::Formatter<'_>, value: f64) -> fmt::Result {
    let magnitude = value.abs();
    if magnitude != 0.0 && magnitude.is_finite() && !(1e-5..1e16).contains(&magnitude) {
        write!(f, "{value:e}")
    } else {
        write!(f, "{value}")
    }
}

impl fmt::Display for InvalidInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = ", self.variable)?;
        write_value(f, self.value)?;
        write!(f, " is invalid")?;
        for (position, (variable, value)) in self.with.iter().flatten().enumerate() {
            write!(f, "{} {variable} = ", if position == 0 { " with" } else { "," })?;
            write_value(f, *value)?;
        }
        write!(f, ": {}", self.requirement)
    }
}

impl std::error::Error for InvalidInput {}
