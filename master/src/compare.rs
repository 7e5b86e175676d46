//! Compares two runs' canonical output: every line the same except the `f64:` bit patterns,
//! which must be equal, or within [`RELATIVE_TOLERANCE`] of the variable's magnitude where the
//! platforms' C math libraries (not Rust's arithmetic, which is IEEE 754 on both) round a
//! transcendental function (`ln`, `asinh`, … in the exact theory's influence coefficients)
//! differently in the last bit.
//!
//! The magnitude is the largest |value| of that variable in that scenario (the label's first
//! word) in either run, so a quantity that is zero by symmetry but carries an iterative
//! solver's residual (the exact theory's F_y at zero lateral creepage: 1e-5 N beside
//! F_x = 1e4 N) is judged on the scale of the forces, not on its own noise.

use std::collections::HashMap;
use std::path::Path;

/// The largest difference accepted between two platforms' values, relative to the magnitude.
pub const RELATIVE_TOLERANCE: f64 = 1e-12;

/// How two runs' values compare.
#[derive(Debug, Default, PartialEq)]
pub struct Comparison {
    pub bit_equal: usize,
    pub within_tolerance: usize,
    pub largest_relative_difference: f64,
}

fn bits(token: &str) -> Option<f64> {
    u64::from_str_radix(token.strip_prefix("f64:")?, 16).ok().map(f64::from_bits)
}

/// A line's words, without the part after ` # ` (for people).
fn words(line: &str) -> Vec<&str> {
    line.split(" # ").next().unwrap_or("").split_whitespace().collect()
}

/// (scenario, variable) of a value line: the label's first word and the word before the value.
fn variable_of<'a>(words: &[&'a str]) -> Option<(&'a str, &'a str)> {
    match words {
        [scenario, .., name, value] if value.starts_with("f64:") => Some((scenario, name)),
        _ => None,
    }
}

/// Compares the two texts line by line.
pub fn texts(a: &str, b: &str) -> Result<Comparison, String> {
    let (a_lines, b_lines): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    if a_lines.len() != b_lines.len() {
        return Err(format!("{} lines against {}", a_lines.len(), b_lines.len()));
    }
    let mut magnitudes: HashMap<(&str, &str), f64> = HashMap::new();
    for line in a_lines.iter().chain(&b_lines) {
        let words = words(line);
        if let (Some(variable), Some(value)) = (variable_of(&words), words.last().and_then(|w| bits(w))) {
            let magnitude = magnitudes.entry(variable).or_insert(0.0);
            *magnitude = magnitude.max(value.abs());
        }
    }
    let mut comparison = Comparison::default();
    for (number, (a_line, b_line)) in a_lines.iter().zip(&b_lines).enumerate() {
        let (a_tokens, b_tokens) = (words(a_line), words(b_line));
        let magnitude = variable_of(&a_tokens).and_then(|variable| magnitudes.get(&variable)).copied().unwrap_or(0.0);
        let differs = || format!("line {}: {a_line:?} against {b_line:?}", number + 1);
        if a_tokens.len() != b_tokens.len() {
            return Err(differs());
        }
        for (a_token, b_token) in a_tokens.iter().zip(&b_tokens) {
            match (bits(a_token), bits(b_token)) {
                (Some(x), Some(y)) if x.to_bits() == y.to_bits() => comparison.bit_equal += 1,
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => {
                    let relative = (x - y).abs() / magnitude;
                    if relative > RELATIVE_TOLERANCE {
                        return Err(format!("{}: relative difference {relative:e}", differs()));
                    }
                    comparison.within_tolerance += 1;
                    comparison.largest_relative_difference = comparison.largest_relative_difference.max(relative);
                }
                _ if a_token == b_token => {}
                _ => return Err(differs()),
            }
        }
    }
    Ok(comparison)
}

/// Compares two files and says how.
pub fn files(a: &Path, b: &Path) -> Result<String, String> {
    let read = |path: &Path| std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()));
    let comparison = texts(&read(a)?, &read(b)?)?;
    Ok(format!(
        "{} values: {} equal bit for bit, {} within {RELATIVE_TOLERANCE:e} of their magnitude (largest {:e})",
        comparison.bit_equal + comparison.within_tolerance,
        comparison.bit_equal,
        comparison.within_tolerance,
        comparison.largest_relative_difference
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(scenario: &str, value: f64) -> String {
        format!("{scenario} point=0 force f64:{:016x} # {value:e}\n", value.to_bits())
    }

    #[test]
    fn equal_bits_close_values_and_differences() {
        let x: f64 = 1234.5678;
        let one_ulp = f64::from_bits(x.to_bits() + 1);
        let one = |value| line("s", value);
        assert_eq!(texts(&one(x), &one(x)).unwrap(), Comparison { bit_equal: 1, ..Comparison::default() });
        let close = texts(&one(x), &one(one_ulp)).unwrap();
        assert_eq!(close.within_tolerance, 1);
        assert_eq!(close.largest_relative_difference, (one_ulp - x) / one_ulp);
        assert!(texts(&one(x), &one(x * (1.0 + 1e-11))).is_err(), "beyond 1e-12");
        assert!(texts(&one(f64::NAN), &one(x)).is_err());
        assert!(texts("a OK\n", "a Error\n").is_err(), "other words must be equal");
        assert!(texts(&one(x), &(one(x) + &one(x))).is_err(), "line counts must be equal");
    }

    #[test]
    fn a_small_value_is_judged_on_its_variables_magnitude_in_the_scenario() {
        let (noise, other_noise) = (1.0903865542654487e-5, 1.090386729570075e-5);
        let with = |scenario_of_large: &str, small: f64| line("s", small) + &line(scenario_of_large, 12608.5);
        let comparison = texts(&with("s", noise), &with("s", other_noise)).unwrap();
        assert_eq!(comparison.within_tolerance, 1);
        assert!(comparison.largest_relative_difference < 2e-16);
        assert!(
            texts(&with("other", noise), &with("other", other_noise)).is_err(),
            "another scenario's scale does not count"
        );
    }
}
