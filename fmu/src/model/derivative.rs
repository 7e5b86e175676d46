//! fmi2GetDirectionalDerivative: the arguments checked and decoded here, the mathematics the
//! core's ([`wheel_rail_contact::scene::Scene::directional_derivative`], through
//! [`crate::scene::directional_derivative`]).

use crate::model_description::{self, variable, Causality, Kind, Values, Variability, Variable, CONTINUOUS_STATES};
use crate::scene::{directional_derivative as scene_derivative, finite, ContactCache};
use crate::snapshot::ContactState;

/// `unknown_rates` = J·`known_rates`, J = ∂(outputs, state derivatives)/∂(inputs, continuous
/// states) at `state`'s values, or why not. Knowns must be continuous inputs or continuous states
/// (a value reference given twice adds its rates), unknowns outputs or state derivatives;
/// all-or-nothing like Get. The continuous states, the relaxed forces, act only with
/// creep_relaxation on, where the derivative is refused ([`scene_derivative`]): otherwise
/// nothing depends on them and the state derivatives are 0, so their columns and rows are 0.
pub(super) fn directional_derivative(
    cache: &mut ContactCache,
    state: &ContactState,
    unknowns: &[u32],
    knowns: &[u32],
    known_rates: &[f64],
    unknown_rates: &mut [f64],
) -> Result<(), String> {
    let mut rates = Values::default();
    for input in model_description::VARIABLES.iter().filter(|v| v.causality == Causality::Input) {
        if let Some(rate) = rates.real_mut(input.value_reference) {
            *rate = 0.0;
        }
    }
    for (&value_reference, &rate) in knowns.iter().zip(known_rates) {
        match variable(value_reference) {
            Some(v) if is_known(v) && rate.is_finite() => {
                *rates.real_mut(value_reference).expect("a Real input") += rate;
            }
            Some(v) if is_known(v) => {
                return Err(format!("dvKnown = {rate} for {} is invalid: must be finite", v.name));
            }
            Some(v) => {
                return Err(format!(
                    "{} (value reference {value_reference}) cannot be a known: derivatives are taken with respect \
                     to the continuous Real inputs and the continuous states only",
                    v.name
                ));
            }
            None => return Err(format!("unknown value reference {value_reference}")),
        }
    }
    let is_unknown = |r: u32| {
        variable(r).is_some_and(|v| v.causality == Causality::Output)
            || CONTINUOUS_STATES.iter().any(|&(_, derivative, _)| derivative == r)
    };
    if let Some(&value_reference) = unknowns.iter().find(|&&r| !is_unknown(r)) {
        return Err(match variable(value_reference) {
            Some(v) => format!(
                "{} (value reference {value_reference}) cannot be an unknown: not an output or a state derivative",
                v.name
            ),
            None => format!("unknown value reference {value_reference}"),
        });
    }
    let outputs = scene_derivative(&state.values, &state.strings, cache, &state.wheel, &rates.inputs)?;
    finite(&outputs)?;
    // The state derivatives' rates are 0 (the function's documentation): `rates`' own, which no
    // known writes (the knowns are inputs and states).
    let derivative = Values { outputs, ..rates };
    for (&value_reference, slot) in unknowns.iter().zip(unknown_rates.iter_mut()) {
        *slot = derivative.real(value_reference).unwrap_or(f64::NAN);
    }
    Ok(())
}

/// Whether a variable can be a known of fmi2GetDirectionalDerivative: a continuous Real input or
/// a continuous state.
fn is_known(v: &Variable) -> bool {
    (v.causality == Causality::Input && v.variability == Variability::Continuous && matches!(v.kind, Kind::Real { .. }))
        || CONTINUOUS_STATES.iter().any(|&(state, ..)| state == v.value_reference)
}
