//! The one interface every rung of the speed–accuracy ladder implements.

use num_dual::Dual64;

use crate::{ContactInput, CreepForces, InvalidInput};

/// A creep-force model: contact state in, tangential forces out.
///
/// Implementations validate the input (returning [`InvalidInput`]), return zero force when
/// [`ContactInput::transmits_no_force`], and never return NaN or infinity for a valid input.
///
/// Every rung implements it; a model's derivative agrees with [`central_difference`] where its
/// forces are smooth:
///
/// ```
/// use wheel_rail_contact::{central_difference, ContactInput, CreepForceModel, KalkerLinear, Polach};
///
/// let contact = ContactInput {
///     creepage_longitudinal: 1e-3,
///     creepage_lateral: 0.0,
///     spin_creepage: 0.0,
///     normal_force: 82e3,
///     semi_axis_a: 8e-3,
///     semi_axis_b: 4e-3,
///     friction_coefficient: 0.3,
///     shear_modulus: 82e9,
///     poisson_ratio: 0.25,
/// };
/// // The rate of ξ alone: Kalker's dF_x/dξ = −G ab C11 exactly (C11 = 5.10 at a/b = 2, ν = 0.25).
/// let along_xi = ContactInput {
///     creepage_longitudinal: 1.0,
///     normal_force: 0.0,
///     semi_axis_a: 0.0,
///     semi_axis_b: 0.0,
///     friction_coefficient: 0.0,
///     shear_modulus: 0.0,
///     poisson_ratio: 0.0,
///     ..contact
/// };
/// let exact = KalkerLinear.directional_derivative(&contact, &along_xi).unwrap();
/// assert!((exact.force_longitudinal + 82e9 * 32e-6 * 5.10).abs() < 1e-3);
/// let models: [&dyn CreepForceModel; 2] = [&KalkerLinear, &Polach::default()];
/// for model in models {
///     let exact = model.directional_derivative(&contact, &along_xi).unwrap();
///     let numeric = central_difference(model, &contact, &along_xi).unwrap();
///     assert!((exact.force_longitudinal / numeric.force_longitudinal - 1.0).abs() < 1e-6);
/// }
/// // A rate of ν is refused: the tables have no derivative in it.
/// let error = KalkerLinear.directional_derivative(&contact, &ContactInput { poisson_ratio: 1.0, ..along_xi });
/// assert_eq!(error.unwrap_err().variable, "poisson_ratio");
/// ```
pub trait CreepForceModel {
    /// Evaluates the forces for one contact patch.
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput>;

    /// The derivative of the forces at `input` along `direction` (J·direction, the quantity
    /// FMI's directional derivative asks for): `direction` holds one rate per input; the result
    /// holds d(F_x), d(F_y), d(M_z), d(|F|/μQ). The Poisson ratio's rate must be 0.
    ///
    /// At μ = 0 and at Q = 0 (no force) the derivative is the one-sided one from inside the
    /// contact (μ, Q → 0⁺) for every friction-limited model, e.g. dF_x/dμ = −Q·ξ/s_C in full
    /// slip; Kalker's linear theory, whose force jumps there, gives that of its zero force.
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
///
/// At the no-force boundary (μ = 0, or Q = 0; see [`NoForceBoundary`]) a model whose forces
/// vanish continuously there is differentiated just inside the contact, at μ or Q of
/// [`inside_no_force_boundary`]: the one-sided derivative from μ, Q → 0⁺ (the only side inside
/// the domain for μ, the contact closing for Q), e.g. dF/dμ = −Q·ξ/s_C for Polach (full slip).
/// Its Jacobian is applied to the whole direction, so a negative rate of μ or Q gives the
/// negative of the positive one's.
pub(crate) fn dual_derivative(
    input: &ContactInput,
    direction: &ContactInput,
    boundary: NoForceBoundary,
    forces: impl Fn(&ContactInput<Dual64>) -> CreepForces<Dual64>,
) -> Result<CreepForces, InvalidInput> {
    validate_direction(input, direction)?;
    let at_rest = input.creepage_longitudinal == 0.0 && input.creepage_lateral == 0.0 && input.spin_creepage == 0.0;
    let step = if at_rest { RAY_STEP } else { 0.0 };
    let creepage = |x: f64, rate: f64| x + step * rate;
    let creepages = [
        creepage(input.creepage_longitudinal, direction.creepage_longitudinal),
        creepage(input.creepage_lateral, direction.creepage_lateral),
        creepage(input.spin_creepage, direction.spin_creepage),
    ];
    let (friction_coefficient, normal_force) = match boundary {
        NoForceBoundary::Continuous => {
            inside_no_force_boundary(input, creepages).unwrap_or((input.friction_coefficient, input.normal_force))
        }
        NoForceBoundary::Jump => (input.friction_coefficient, input.normal_force),
    };
    let seeded = ContactInput {
        creepage_longitudinal: Dual64::new(creepages[0], direction.creepage_longitudinal),
        creepage_lateral: Dual64::new(creepages[1], direction.creepage_lateral),
        spin_creepage: Dual64::new(creepages[2], direction.spin_creepage),
        normal_force: Dual64::new(normal_force, direction.normal_force),
        semi_axis_a: Dual64::new(input.semi_axis_a, direction.semi_axis_a),
        semi_axis_b: Dual64::new(input.semi_axis_b, direction.semi_axis_b),
        friction_coefficient: Dual64::new(friction_coefficient, direction.friction_coefficient),
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

/// How a model's forces behave where the contact transmits no force (μ = 0 or Q ≤ 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NoForceBoundary {
    /// They vanish continuously as μQ → 0⁺ (every friction-limited model): the derivative at
    /// μ = 0 or Q = 0 is the one-sided one from inside the contact.
    Continuous,
    /// They jump (Kalker's linear theory ignores friction): no one-sided derivative in μ or Q
    /// exists; the derivative is that of the zero force the value takes, 0 in every input.
    Jump,
}

/// How deep inside the contact a one-sided derivative at the no-force boundary is taken: at a
/// Coulomb limit μQ of 1e-6 of G·ab·3·s, the limit at which the largest creepage s would just
/// saturate a linear contact of creep coefficient 3 (the smallest of Kalker's table is 2.5), so
/// the contact is in full slip to within ~1e-18 there, as it is in the limit μQ → 0⁺.
const NO_FORCE_DEPTH: f64 = 1e-6;

/// (μ, Q) just inside the contact for an input on the no-force boundary (μ = 0 or Q = 0, with
/// Q ≥ 0: lift-off, Q < 0, is inside the zero-force region, not on its edge) with creepages
/// `creepages` (ξ, η, φ); `None` off the boundary, without creepage (no force on either side) or
/// at scales where the point's μQ (outside 1e-150 … 1e150) or its μ and Q would not be usable.
/// The zero one of μ and Q is raised (both, to the same value, when both are zero) so that μQ
/// is [`NO_FORCE_DEPTH`] of the saturating limit.
pub(crate) fn inside_no_force_boundary(input: &ContactInput, creepages: [f64; 3]) -> Option<(f64, f64)> {
    let (friction, load) = (input.friction_coefficient, input.normal_force);
    if !(load >= 0.0 && (friction == 0.0 || load == 0.0)) {
        return None;
    }
    let [xi, eta, spin] = creepages;
    let largest = xi.abs().max(eta.abs()).max((spin * input.semi_axis_a).abs());
    let friction_limit = NO_FORCE_DEPTH * input.shear_modulus * input.semi_axis_a * input.semi_axis_b * 3.0 * largest;
    // Squares of μQ appear in the derivatives (d(1/μQ)): outside 1e-150 … 1e150 they would
    // underflow or overflow, so at such extreme scales the zero force's derivative is given.
    if !(1e-150..=1e150).contains(&friction_limit) {
        return None;
    }
    let inside = match (friction > 0.0, load > 0.0) {
        (false, true) => (friction_limit / load, load),
        (true, false) => (friction, friction_limit / friction),
        _ => (friction_limit.sqrt(), friction_limit.sqrt()),
    };
    // At extreme scales the quotient may overflow or underflow: no usable point inside then.
    (inside.0 > 0.0 && inside.0 <= f64::MAX && inside.1 > 0.0 && inside.1 <= f64::MAX).then_some(inside)
}

/// Relative step of [`central_difference`].
const DIFFERENCE_STEP: f64 = 1e-6;

/// J·direction by a central difference (F(x + t d) − F(x − t d)) / 2t. The step t moves every
/// input by at most 1e-6 of its own size; creepages at or near zero are moved by at most 1e-6 of
/// the larger of the creepage at which the force reaches μQ in Kalker's linear theory,
/// μQ/(G·ab·C), taken with C = 3 (the smallest coefficient of Kalker's table is 2.5), and 1e-3
/// of the resultant creepage |ξ| + |η| + a|φ|; the spin creepage by those over a.
///
/// On the no-force boundary (μ = 0 with a rate of μ, or Q = 0 with a rate of Q) the forces have
/// no central difference (μ < 0 is not an input; lift-off has no force): the one-sided
/// difference into the contact is taken instead, as the exact (dual-number) derivatives do.
pub fn central_difference<M: CreepForceModel + ?Sized>(
    model: &M,
    input: &ContactInput,
    direction: &ContactInput,
) -> Result<CreepForces, InvalidInput> {
    validate_direction(input, direction)?;
    if let Some(derivative) = one_sided_difference(model, input, direction)? {
        return Ok(derivative);
    }
    let x = fields(input);
    let d = fields(direction);
    let area = input.semi_axis_a * input.semi_axis_b;
    let saturation_creepage = input.friction_limit() / (input.shear_modulus * area * 3.0);
    // Spin acts on the lateral creepage as aφ (the spin creepage's share at the leading edge,
    // Kalker; Polach's eq. 21): on the rolling semi-axis a its step moves the forces about as
    // much as the creepages' steps do for every a/b (c·C23/(a·C22) = 0.3 … 0.45 over a/b = 0.1
    // … 31.6, where the smaller semi-axis gave 0.3 … 11).
    let a = input.semi_axis_a;
    let saturation_spin = saturation_creepage / a;
    // A creepage that is 0 beside large ones moves on 1e-3 of them: in full slip the forces are
    // computed on the scale of μQ, and a step of the saturation creepage alone would be lost
    // in their rounding.
    let resultant = 1e-3 * (x[0].abs() + x[1].abs() + a * x[2].abs());
    let scales = [
        saturation_creepage.max(resultant),
        saturation_creepage.max(resultant),
        saturation_spin.max(resultant / a),
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ];
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

/// The one-sided difference of [`central_difference`] on the no-force boundary: `None` off it.
/// The step moves into the contact (the sign of the rate of μ, or else of Q, that is on the
/// boundary) until μQ reaches the depth of [`inside_no_force_boundary`]; the forces being
/// zero on the boundary, (F(x ± t·d) − F(x))/(±t) loses no digits to cancellation.
fn one_sided_difference<M: CreepForceModel + ?Sized>(
    model: &M,
    input: &ContactInput,
    direction: &ContactInput,
) -> Result<Option<CreepForces>, InvalidInput> {
    let creepages = [input.creepage_longitudinal, input.creepage_lateral, input.spin_creepage];
    let on_friction = input.friction_coefficient == 0.0 && direction.friction_coefficient != 0.0;
    let on_load = input.normal_force == 0.0 && direction.normal_force != 0.0;
    if !(on_friction || on_load) {
        return Ok(None);
    }
    // Without creepage the forces are homogeneous of degree one along the direction (the
    // creepages then come from it), so any depth does: that of a unit creepage.
    let reference = if creepages.iter().any(|c| *c != 0.0) { creepages } else { [1.0, 0.0, 0.0] };
    // Lifted off (Q < 0), or a depth that underflows: zero force on both sides to rounding.
    let zero = || -> Result<Option<CreepForces>, InvalidInput> {
        let spin_moment = model.creep_forces(input)?.spin_moment.map(|_| 0.0);
        Ok(Some(CreepForces { spin_moment, ..Default::default() }))
    };
    let Some((friction, load)) = inside_no_force_boundary(input, reference) else {
        return zero();
    };
    let (rate, target) =
        if on_friction { (direction.friction_coefficient, friction) } else { (direction.normal_force, load) };
    let step = (target / rate).abs();
    if !(step > 0.0 && step.is_finite()) {
        return zero();
    }
    let sign = rate.signum();
    let x = fields(input);
    let d = fields(direction);
    let moved = from_fields(std::array::from_fn(|i| x[i] + sign * step * d[i]));
    let (inside, on) = (model.creep_forces(&moved)?, model.creep_forces(input)?);
    let rate = |p: f64, o: f64| sign * (p - o) / step;
    Ok(Some(CreepForces {
        force_longitudinal: rate(inside.force_longitudinal, on.force_longitudinal),
        force_lateral: rate(inside.force_lateral, on.force_lateral),
        spin_moment: inside.spin_moment.zip(on.spin_moment).map(|(p, o)| rate(p, o)),
        adhesion_utilisation: rate(inside.adhesion_utilisation, on.adhesion_utilisation),
    }))
}
