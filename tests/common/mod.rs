//! Shared test inputs for the ladder tests.
#![allow(dead_code)]

use wheel_rail_contact::{ContactInput, Fastsim, Flexibility, ModelChoice, Polach, TractionBound};
use wheel_rail_contact::{KalkerLinear, ShenHedrickElkins};

/// A typical wheel–rail contact (a/b = 1.5) with the given creepages.
pub fn contact(xi: f64, eta: f64, phi: f64) -> ContactInput {
    ContactInput {
        creepage_longitudinal: xi,
        creepage_lateral: eta,
        spin_creepage: phi,
        normal_force: 80e3,
        semi_axis_a: 6e-3,
        semi_axis_b: 4e-3,
        friction_coefficient: 0.3,
        shear_modulus: 8e10,
        poisson_ratio: 0.28,
    }
}

pub fn fastsim(n: usize, bound: TractionBound) -> Fastsim {
    Fastsim::new(n, n, bound, Flexibility::Three).unwrap()
}

/// Every saturating model (friction-limited), with a name for messages.
pub fn saturating_models() -> Vec<ModelChoice> {
    vec![
        ModelChoice::Polach(Polach::default()),
        ModelChoice::ShenHedrickElkins(ShenHedrickElkins),
        ModelChoice::Fastsim(fastsim(20, TractionBound::Parabolic)),
        ModelChoice::Fastsim(fastsim(20, TractionBound::Elliptic)),
        ModelChoice::Fastsim(Fastsim::new(15, 25, TractionBound::Parabolic, Flexibility::SingleWeighted).unwrap()),
    ]
}

/// Every model of the ladder.
pub fn all_models() -> Vec<ModelChoice> {
    let mut models = saturating_models();
    models.push(ModelChoice::KalkerLinear(KalkerLinear));
    models
}
