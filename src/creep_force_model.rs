//! The one interface every rung of the speed–accuracy ladder implements.

use num_dual::Dual64;

use crate::{ContactInput, CreepForces, InvalidInput};

/// A creep-force model: contact state in, tangential forces out.
///
/// Implementations validate the input (returning [`InvalidInput`]), return zero force when
/// [`ContactInput::transmits_no_force`], and never return NaN or infinity for a valid input.
pub trait CreepForceModel {
    /// Evaluates the forces for one contact patch.
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput>;

    /// The derivative of the forces at `input` along `direction` (J·direction, the quantity
    /// FMI's directional derivative asks for): `direction` holds one rate per input; the result
    /// holds d(F_x), d(F_y), d(M_z), d(|F|/μQ). The Poisson ratio's rate must be 0.
    ///
    /// The default is a central finite difference (see [`central_difference`]) for models
    /// whose forces are not smooth in their inputs (FASTSIM's grid); smooth models override it
    /// with exact forward-mode derivatives.
    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        central_difference(self, input, direction)
    }
}

/// Checks that `direction` is a usable rate vector at `input`.
fn validate_direction(input: &ContactInput, direction: &ContactInput) -> Result<(), InvalidInput> {
    input.validate()?;
    for (variable, rate) in FIELD_NAMES.into_iter().zip(fields(direction)) {
        if !rate.is_finite() {
            return Err(InvalidInput::new(variable, rate, "its rate in the derivative's direction must be finite"));
        }
    }
    if direction.poisson_ratio != 0.0 {
        return Err(InvalidInput::new("poisson_ratio", direction.poisson_ratio, "no derivative with respect to it"));
    }
    Ok(())
}

const FIELD_NAMES: [&str; 9] = [
    "creepage_longitudinal",
    "creepage_lateral",
    "spin_creepage",
    "normal_force",
    "semi_axis_a",
    "semi_axis_b",
    "friction_coefficient",
    "shear_modulus",
    "poisson_ratio",
];

fn fields(x: &ContactInput) -> [f64; 9] {
    [
        x.creepage_longitudinal,
        x.creepage_lateral,
        x.spin_creepage,
        x.normal_force,
        x.semi_axis_a,
        x.semi_axis_b,
        x.friction_coefficient,
        x.shear_modulus,
        x.poisson_ratio,
    ]
}

fn from_fields(f: [f64; 9]) -> ContactInput {
    ContactInput {
        creepage_longitudinal: f[0],
        creepage_lateral: f[1],
        spin_creepage: f[2],
        normal_force: f[3],
        semi_axis_a: f[4],
        semi_axis_b: f[5],
        friction_coefficient: f[6],
        shear_modulus: f[7],
        poisson_ratio: f[8],
    }
}

/// Exact J·direction by forward-mode dual numbers: `forces` is evaluated once with every input
/// carrying its rate as the dual part.
///
/// Where a model has a kink, the derivative is the one-sided derivative of the branch the value
/// takes: in a/b at the rows of Kalker's table (piecewise linear in a/b, as in CONTACT), in Φ at
/// Φ = 0 and aΦ = −2η (the switches of Polach's eq. 21).
///
/// At zero creepage the forces are homogeneous of degree one in the creepages (the linear
/// range), so their derivative along the direction is the same anywhere on the ray: it is taken
/// a vanishing step (1e-100 of the direction) away from the kink of √(ξ² + η²) at the origin.
pub(crate) fn dual_derivative(
    input: &ContactInput,
    direction: &ContactInput,
    forces: impl Fn(&ContactInput<Dual64>) -> CreepForces<Dual64>,
) -> Result<CreepForces, InvalidInput> {
    validate_direction(input, direction)?;
    let at_rest = input.creepage_longitudinal == 0.0 && input.creepage_lateral == 0.0 && input.spin_creepage == 0.0;
    let step = if at_rest { RAY_STEP } else { 0.0 };
    let dual = |x: f64, rate: f64| Dual64::new(x + step * rate, rate);
    let seeded = ContactInput {
        creepage_longitudinal: dual(input.creepage_longitudinal, direction.creepage_longitudinal),
        creepage_lateral: dual(input.creepage_lateral, direction.creepage_lateral),
        spin_creepage: dual(input.spin_creepage, direction.spin_creepage),
        normal_force: Dual64::new(input.normal_force, direction.normal_force),
        semi_axis_a: Dual64::new(input.semi_axis_a, direction.semi_axis_a),
        semi_axis_b: Dual64::new(input.semi_axis_b, direction.semi_axis_b),
        friction_coefficient: Dual64::new(input.friction_coefficient, direction.friction_coefficient),
        shear_modulus: Dual64::new(input.shear_modulus, direction.shear_modulus),
        poisson_ratio: Dual64::from(input.poisson_ratio),
    };
    let f = forces(&seeded);
    Ok(CreepForces {
        force_longitudinal: f.force_longitudinal.eps,
        force_lateral: f.force_lateral.eps,
        spin_moment: f.spin_moment.map(|m| m.eps),
        adhesion_utilisation: f.adhesion_utilisation.eps,
    })
}

/// How far along the direction the at-rest derivative is taken (see [`dual_derivative`]).
const RAY_STEP: f64 = 1e-100;

/// Relative step of [`central_difference`].
const DIFFERENCE_STEP: f64 = 1e-6;

/// J·direction by a central difference (F(x + t d) − F(x − t d)) / 2t. The step t moves every
/// input by at most 1e-6 of its own size; creepages at or near zero are moved by at most 1e-6 of
/// the creepage at which the force reaches μQ in Kalker's linear theory, μQ/(G·ab·C), taken
/// with C = 3 (the smallest coefficient of Kalker's table is 2.5).
pub fn central_difference<M: CreepForceModel + ?Sized>(
    model: &M,
    input: &ContactInput,
    direction: &ContactInput,
) -> Result<CreepForces, InvalidInput> {
    validate_direction(input, direction)?;
    let x = fields(input);
    let d = fields(direction);
    let area = input.semi_axis_a * input.semi_axis_b;
    let saturation_creepage = input.friction_limit() / (input.shear_modulus * area * 3.0);
    let saturation_spin = saturation_creepage / input.semi_axis_a.min(input.semi_axis_b);
    let scales = [saturation_creepage, saturation_creepage, saturation_spin, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let step = (0..9)
        .filter(|&i| d[i] != 0.0)
        .map(|i| DIFFERENCE_STEP * x[i].abs().max(scales[i]) / d[i].abs())
        .filter(|t| *t > 0.0)
        .fold(f64::INFINITY, f64::min);
    if !step.is_finite() {
        return Ok(CreepForces {
            spin_moment: model.creep_forces(input)?.spin_moment.map(|_| 0.0),
            ..CreepForces::default()
        });
    }
    let shifted = |sign: f64| from_fields(std::array::from_fn(|i| x[i] + sign * step * d[i]));
    let (plus, minus) = (model.creep_forces(&shifted(1.0))?, model.creep_forces(&shifted(-1.0))?);
    let rate = |p: f64, m: f64| (p - m) / (2.0 * step);
    Ok(CreepForces {
        force_longitudinal: rate(plus.force_longitudinal, minus.force_longitudinal),
        force_lateral: rate(plus.force_lateral, minus.force_lateral),
        spin_moment: plus.spin_moment.zip(minus.spin_moment).map(|(p, m)| rate(p, m)),
        adhesion_utilisation: rate(plus.adhesion_utilisation, minus.adhesion_utilisation),
    })
}
