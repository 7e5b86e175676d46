//! exact_table's directional derivatives on the fold planes of its coordinates (issue 27,
//! defect 1), through the C ABI: fmi2GetDirectionalDerivative against one-sided differences of
//! the outputs of fmi2DoStep. On a fold the outputs have a kink (or, by a symmetry, are flat)
//! and the derivative must be one of the one-sided ones (README, "Directional derivatives").

use fmu_test_master::{Fmu, INPUTS as CONTACT, OK};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, Model};

/// The default scene (Q = 100 kN, a = 7.2 mm, b = 5.4 mm, μ = 0.3) with creepages ξ, η, φ.
fn default_scene(xi: f64, eta: f64, phi: f64) -> [f64; 7] {
    [xi, eta, phi, 100e3, 7.2e-3, 5.4e-3, 0.3]
}

/// The exact_table FMU, initialised, and the time of its next step.
struct Stepping {
    fmu: Fmu,
    time: std::cell::Cell<f64>,
}

fn exact_table() -> Stepping {
    let fmu = Fmu::instantiate("exact_table", None);
    assert_eq!(fmu.set_integer(&[vr::CREEP_FORCE_MODEL], &[Model::ExactTable as i32]), OK);
    fmu.initialise(0.0);
    Stepping { fmu, time: std::cell::Cell::new(0.0) }
}

impl Stepping {
    /// One step at the contact `inputs`: false when refused (a/b outside the table).
    fn step(&self, inputs: &[f64; 7]) -> bool {
        assert_eq!(self.fmu.set_real(&CONTACT, inputs), OK);
        let stepped = self.fmu.do_step(self.time.get(), 1e-3) == OK;
        if stepped {
            self.time.set(self.time.get() + 1e-3);
        }
        stepped
    }
}

/// Output `unknown` after a step at the contact `inputs` (NaN where the step is refused).
fn output(fmu: &Stepping, inputs: &[f64; 7], unknown: u32) -> f64 {
    if fmu.step(inputs) {
        fmu.fmu.get_real(&[unknown])[0]
    } else {
        f64::NAN
    }
}

/// J·e_known at `inputs` (ξ, η, φ, Q, a, b, μ: `fmu_test_master::INPUTS`), and the second-order one-sided differences (3F₀ − 4F(±h) + F(±2h))/(∓2h)
/// forward and backward with step `h` of input `k` (index into [`CONTACT`]); NaN for a side
/// outside the domain.
fn derivative_and_sides(fmu: &Stepping, inputs: [f64; 7], k: usize, unknown: u32, h: f64) -> (f64, f64, f64) {
    let at = |t: f64| {
        let mut moved = inputs;
        moved[k] += t;
        output(fmu, &moved, unknown)
    };
    let (f0, p1, p2, m1, m2) = (at(0.0), at(h), at(2.0 * h), at(-h), at(-2.0 * h));
    assert!(fmu.step(&inputs));
    let (status, rates) = fmu.fmu.directional_derivative(&[unknown], &[CONTACT[k]], &[1.0]);
    assert_eq!(status, OK);
    let forward = (-3.0 * f0 + 4.0 * p1 - p2) / (2.0 * h);
    let backward = (3.0 * f0 - 4.0 * m1 + m2) / (2.0 * h);
    (rates[0], forward, backward)
}

fn near(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * a.abs().max(b.abs())
}

/// Plain free rolling with spin, ξ = 0: F_y is even in ξ (the mirror symmetries), and the
/// interpolant has a kink there (one-sided slopes ±24780 N). Before the fix: 168157 N, neither.
#[test]
fn at_zero_longitudinal_creepage_the_lateral_forces_derivative_is_one_sided() {
    let fmu = exact_table();
    let (j, forward, backward) = derivative_and_sides(&fmu, default_scene(0.0, 4e-4, 0.3), 0, vr::FORCE_LATERAL, 1e-9);
    assert!(!near(forward, backward, 1e-2), "a kink: forward {forward}, backward {backward}");
    assert!(near(j, forward, 1e-3) || near(j, backward, 1e-3), "J {j}, forward {forward}, backward {backward}");
}

/// Pure spin (φ = 0.05/m, a/b = 1.33): F_x is exactly 0 along η (F_x is odd in ξ at ξ = 0 by
/// the symmetries), so ∂F_x/∂η = 0. Before the fix: −1.2e7 N.
#[test]
fn at_pure_spin_the_longitudinal_force_does_not_move_with_lateral_creepage() {
    let fmu = exact_table();
    let (j, forward, backward) =
        derivative_and_sides(&fmu, default_scene(0.0, 0.0, 0.05), 1, vr::FORCE_LONGITUDINAL, 1e-9);
    assert_eq!((forward, backward), (0.0, 0.0));
    // Against the scale of the derivatives there, ∂F_x/∂ξ (the creep stiffness, ≈ 1e7 N).
    let (stiffness, _, _) = derivative_and_sides(&fmu, default_scene(0.0, 0.0, 0.05), 0, vr::FORCE_LONGITUDINAL, 1e-9);
    assert!(j.abs() <= 1e-9 * stiffness.abs(), "J {j} against ∂F_x/∂ξ {stiffness}");
}

/// At the table's edge a/b = 0.1 the derivative in a (and b) is the one from inside the table,
/// the only side there is. Before the fix the clamp of a/b's cell fraction dropped its rate:
/// ∂M_z/∂a was −92729 N·m/m against −40488 from inside.
#[test]
fn at_the_tables_a_over_b_edge_the_derivative_is_the_inside_one() {
    let fmu = exact_table();
    // a/b = 0.1 less 5e-13 of it: accepted as the edge (rounding), the clamped side of it.
    let b = 17e-3;
    let mut inputs = default_scene(0.0, 1e-3, 0.3);
    (inputs[4], inputs[5]) = (0.1 * b * (1.0 - 5e-13), b);
    // a grows (into the table) and b shrinks (into the table).
    for (k, sign) in [(4, 1.0), (5, -1.0)] {
        let h = sign * 1e-7 * inputs[k];
        let (j, inside, outside) = derivative_and_sides(&fmu, inputs, k, vr::SPIN_MOMENT, h);
        assert!(outside.is_nan(), "input {k}: the other side is outside the table");
        assert!(near(j, inside, 1e-3), "input {k}: J {j}, inside {inside}");
    }
}

/// The generic property once through the C ABI (the core's core/tests/library/derivative_properties.rs
/// checks it over the whole domain through the scene): at 60 deterministic points, creepages
/// exactly 0 among them (every fold plane: ξ = 0, η = 0, φ = 0, pure spin, rest), a/b from
/// the table's edges inwards, ∂(F_x, F_y, M_z)/∂(each contact input) from
/// fmi2GetDirectionalDerivative agrees with the central difference of the fmi2DoStep outputs
/// or, on a fold, with one of the one-sided ones (1e-3 relative, with a floor of 1e-6 of μQ,
/// or μQc, over the input's step scale: derivatives that vanish by symmetry).
#[test]
fn derivatives_agree_with_differences_of_the_steps_outputs() {
    let fmu = exact_table();
    let unknowns = [vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::SPIN_MOMENT];
    for n in 0..60 {
        let t = n as f64;
        // Each creepage is 0 at one point in three, on its own cycle, so that every
        // combination of zeros occurs; signs alternate.
        let pick = |cycle: usize, value: f64| if n % cycle == 0 { 0.0 } else { value };
        let xi = pick(3, 3e-3 * (0.7 * t).sin());
        let eta = pick(4, -2e-3 * (1.3 * t).cos());
        let phi = pick(5, 0.8 * (0.9 * t).sin());
        let a_over_b = [0.1, 10f64.powf(1.5), 0.1 * (1.0 + 1e-6), 1.0 + 0.5 * (0.4 * t).sin()][n % 4];
        let c = 6e-3;
        let inputs = [xi, eta, phi, 60e3 + 40e3 * (0.3 * t).cos(), c * a_over_b.sqrt(), c / a_over_b.sqrt(), 0.3];
        let saturation = inputs[6] * inputs[3] / (82e9 * c * c * 3.0);
        let resultant = 1e-3 * (xi.abs() + eta.abs() + c * phi.abs());
        let scales = [
            xi.abs().max(saturation).max(resultant),
            eta.abs().max(saturation).max(resultant),
            phi.abs().max(saturation / c).max(resultant / c),
            inputs[3],
            inputs[4],
            inputs[5],
            inputs[6],
        ];
        for k in 0..7 {
            let h = 1e-8 * scales[k];
            for unknown in unknowns {
                let (j, forward, backward) = derivative_and_sides(&fmu, inputs, k, unknown, h);
                let at = |t: f64| {
                    let mut moved = inputs;
                    moved[k] += t;
                    output(&fmu, &moved, unknown)
                };
                let (plus, minus, value) = (at(h), at(-h), at(0.0));
                let central = (plus - minus) / (2.0 * h);
                // The size of the output: the Coulomb limit μQ (μQc for M_z), the scale on which
                // the interpolant's rounding is (a force that is 0 by symmetry has no size).
                let limit = inputs[6] * inputs[3] * if unknown == vr::SPIN_MOMENT { c } else { 1.0 };
                let size = limit.max(value.abs()).max(plus.abs()).max(minus.abs());
                let floor = 1e-6 * size / scales[k] + 16.0 * f64::EPSILON * size / h;
                let agrees = |d: f64| (j - d).abs() <= 1e-3 * j.abs().max(d.abs()) + floor;
                assert!(
                    agrees(central) || agrees(forward) || agrees(backward),
                    "point {n} {inputs:?}, input {k}, output {unknown}: J {j}, central {central}, \
                     forward {forward}, backward {backward}"
                );
            }
        }
    }
}
