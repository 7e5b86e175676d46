//! Kalker's FASTSIM: the simplified theory of rolling contact solved strip by strip
//! (J.J. Kalker, "A fast algorithm for the simplified theory of rolling contact", Vehicle System
//! Dynamics 11 (1982) 1–13; flexibilities as in CONTACT's `simpflex`, Vollebregt & Kalker).
//!
//! Simplified theory: the surface displacement is u = L p (traction p on the wheel), so in
//! adhesion the traction grows linearly along the rolling path with the rigid slip
//! w = (ξ − φ y, η + φ x) [Kalker's eq.]:
//!
//! ```text
//! p(x − dx, y) = p(x, y) − (w / L) dx,      |p| ≤ μ p_z, else p = μ p_z p/|p| (slip).
//! ```
//!
//! Flexibilities (three, one per creepage; CONTACT's `simpflex`):
//!
//! ```text
//! L1 = 8a / (3 G C11),  L2 = 8a / (3 G C22),  L3 = π a √(a/b) / (4 G C23),
//! ```
//!
//! chosen so that the adhesion limit gives Kalker's linear F_x, F_y exactly; by default blended
//! towards one combined flexibility as the creepage grows, as CONTACT's `simpflex` does
//! ([`Flexibility::ThreeBlended`]: this reproduces CONTACT's published FASTSIM results); or
//! Kalker's single weighted flexibility L = (|ξ| L1 + |η| L2 + c |φ| L3) / √(ξ² + η² + c² φ²),
//! c = √(ab).
//! Traction bound μ p_z: parabolic, p_z = 2Q/(πab) (1 − x²/a² − y²/b²) (Kalker's choice for
//! FASTSIM), or elliptic (Hertz), p_z = 3Q/(2πab) √(1 − x²/a² − y²/b²).
//!
//! Discretisation (ours, not CONTACT's rectangular grid): `strips` strips of equal width across
//! the ellipse, each with its own half-length a(y) = a√(1 − y²/b²) divided into `elements` equal
//! elements, tractions at element centres. The first step from the leading edge is half an
//! element and the slip is taken at mid-step, so in adhesion the traction is exact at the
//! centres and the linear limit is met to O(1/strips²). The bound is normalised so that the
//! discrete pressure carries exactly Q (full slip gives exactly μQ on every grid).
//!
//! Optionally ([`Discretisation::ContactGrid`]) CONTACT's own discretisation, written after the
//! description of open-source CONTACT (Vollebregt & Kalker, Apache-2.0: `src/m_stang.f90`
//! `modif_fastsim`, `src/m_sdis.f90` `srztng`): a rectangular grid over 1.1 a × 1.1 b, the
//! pressure sampled at the element centres without rescaling, each row starting with a full
//! step at its first interior element and the spin slip taken at x + δx/6 (CONTACT's default
//! `facphi`). It reproduces CONTACT's published FASTSIM values on CONTACT's grids; ours
//! converges faster to the same limit (core/tests/library/ladder_contact_case.rs).
//!
//! Work is done in units of a, b and μQ/(ab), so the tractions stay O(1) whatever the inputs;
//! the hot loop marches along each strip carrying the traction and allocates nothing.

use std::f64::consts::PI;

use crate::models::rung::Rung;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, KalkerCoefficients, ModelChoice};

/// Largest number of strips or elements per strip (10⁸ elements: far beyond convergence).
pub const MAX_DIVISIONS: usize = 10_000;
/// Dimensionless traction rates (flexibility⁻¹ × creepage, in units of μQ/(ab) per a) are held
/// here: beyond it every element slips, and the tractions' squares stay finite.
const RATE_MAX: f64 = 1e150;

/// The traction bound μ p_z.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TractionBound {
    /// Parabolic pressure, Kalker's choice for FASTSIM.
    #[default]
    Parabolic,
    /// Hertz's elliptic (semi-ellipsoidal) pressure.
    Elliptic,
}

/// How the flexibility L of the simplified theory is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Flexibility {
    /// L1, L2, L3 for ξ, η, φ separately, never blended (Kalker 1982). With combined creepages
    /// this is not CONTACT's FASTSIM: on CONTACT's `examples/fastsim` case (η with spin) it gives
    /// F_y 1.2 % (parabolic bound) larger than [`Self::ThreeBlended`].
    Three,
    /// CONTACT's three flexibilities blended towards one combined flexibility as the creepage
    /// grows (open-source CONTACT, `src/m_hertz.f90`, subroutine `simpflex`, Vollebregt):
    ///
    /// ```text
    /// L_crss = (ξ² + η² + s²) / (ξ²/L1 + η²/L2 + s²/L3),   s = φ · (πa²/4) / (8a/3) = 3πaφ/32,
    /// f_crp  = √((ξ² + η² + φ²) / (ξ*² + η*² + φ*²)),     w = min(1, f_crp / 3),
    /// L_i   ← (1 − w) L_i + w L_crss,   i = 1, 2, 3,
    /// ```
    ///
    /// with the characteristic creepages ξ* = μQ/(G c² C11), η* = μQ/(G c² C22),
    /// φ* = μQ/(G c³ C23), c = √(ab) (the creepages at which the linear force reaches μQ).
    /// In the linear range w → 0 and Kalker's linear theory is met as with [`Self::Three`];
    /// towards full slip the three flexibilities approach one, as in Kalker's single-L FASTSIM.
    /// A pure creepage (only ξ, only η or only φ) is unaffected: L_crss is then its own L_i.
    ///
    /// **Unit dependence, reproduced on purpose.** f_crp adds squares of the dimensionless ξ, η
    /// to squares of the spin φ, φ* [1/length], so its value depends on the length unit.
    /// CONTACT computes it in millimetres; we evaluate it exactly as CONTACT does, with φ and φ*
    /// in 1/mm (`CONTACT_LENGTH_UNIT`), so that our results reproduce CONTACT's published
    /// FASTSIM values. This is a property of CONTACT's heuristic, not of the physics: the blend
    /// weight of a spin-dominated contact would differ in another unit system.
    /// L_crss itself is dimensionally consistent.
    #[default]
    ThreeBlended,
    /// Kalker's single L weighted by the creepages.
    SingleWeighted,
}

/// How the contact is divided into elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Discretisation {
    /// Ours: `strips` strips of equal width across the ellipse, each of its own length divided
    /// into `elements` elements, half a first step, slip at mid-step, pressure normalised to Q.
    #[default]
    Strips,
    /// CONTACT's (`modif_fastsim`, `srztng`): `elements` × `strips` equal elements over the
    /// rectangle 2.2 a (rolling direction) × 2.2 b; elements whose centre lies in the ellipse
    /// carry the pressure sampled at the centre (not rescaled); each row starts with a full step
    /// at its first interior element from the leading edge, and the spin part of the lateral
    /// slip is taken at x + δx/6. First order in the grid; CONTACT's published runs use 44 × 44
    /// (40 × 40 in the contact) and 220 × 220.
    ContactGrid,
}

/// Half-size of CONTACT's potential contact area in units of the semi-axes.
const CONTACT_GRID_HALF_SIZE: f64 = 1.1;
/// Offset of the spin-slip point of [`Discretisation::ContactGrid`], in steps towards the
/// leading edge (CONTACT's default `facphi`).
const CONTACT_SPIN_SLIP_OFFSET: f64 = 1.0 / 6.0;

/// FASTSIM with a grid of `strips × elements` and the chosen bound and flexibility.
///
/// CONTACT's `examples/fastsim` case (a = 8 mm, b = 4 mm, η = −6.25e-4, φ = 0.625 /m, μN =
/// 24.6 kN) on CONTACT's own grid (44 × 44 over 2.2 a × 2.2 b, parabolic bound) reproduces
/// CONTACT's published FASTSIM result, F_y/(μN) = −0.6118 and M_z = −39.00 N·m, to its
/// printed digits' rounding and the scheme's details (0.4 %):
///
/// ```
/// use wheel_rail_contact::reference_cases::FASTSIM_CASE;
/// use wheel_rail_contact::{CreepForceModel, Discretisation, Fastsim, Flexibility, TractionBound};
///
/// let ours = Fastsim::new(44, 44, TractionBound::Parabolic, Flexibility::ThreeBlended).unwrap();
/// let contacts = ours.with_discretisation(Discretisation::ContactGrid);
/// assert_eq!((contacts.strips(), contacts.elements(), contacts.bound()), (44, 44, TractionBound::Parabolic));
/// assert_eq!(contacts.discretisation(), Discretisation::ContactGrid);
/// let result = contacts.evaluate(&FASTSIM_CASE).unwrap();
/// let ratio = result.forces.force_lateral / FASTSIM_CASE.friction_limit();
/// assert!((ratio / -0.6118 - 1.0).abs() < 0.004, "F_y/(μN) = {ratio}");
/// assert!((result.forces.spin_moment.unwrap() / -39.00 - 1.0).abs() < 0.004);
/// assert!(result.adhesion_area_fraction > 0.0 && result.adhesion_area_fraction < 1.0, "partly slipping");
/// // Our strips converge faster; the trait gives the forces alone.
/// assert_eq!(ours.creep_forces(&FASTSIM_CASE).unwrap(), ours.evaluate(&FASTSIM_CASE).unwrap().forces);
/// assert!(Fastsim::new(0, 20, TractionBound::Parabolic, Flexibility::ThreeBlended).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fastsim {
    strips: usize,
    elements: usize,
    bound: TractionBound,
    flexibility: Flexibility,
    discretisation: Discretisation,
    /// 1 / (discrete ∫∫ bound dX dY): makes the discrete pressure carry exactly Q.
    load_normalisation: f64,
}

/// FASTSIM's rung of the ladder.
pub const RUNG: Rung = Rung {
    name: "fastsim",
    fmu_value: 4,
    type_name: "Fastsim",
    fmu_parameters: &["fastsim_strips", "fastsim_elements", "fastsim_traction_bound", "fastsim_flexibility"],
    spin_moment: true,
    friction_limited: true,
    offline: false,
    summary: "Kalker's simplified theory, any strips × elements, parabolic or elliptic bound, three (blended as CONTACT does) or one flexibility; CONTACT's own grid as an option",
    source: "Kalker 1982; CONTACT",
    documentation: "Kalker's FASTSIM (VSD 11, 1982) on <code>fastsim_strips</code> × <code>fastsim_elements</code>
(default 20 × 20); <code>fastsim_traction_bound</code> parabolic (Kalker's choice, default) or
elliptic (Hertz); <code>fastsim_flexibility</code> <code>three_blended</code> (default: L1 = 8a/(3G C11),
L2 = 8a/(3G C22), L3 = πa√(a/b)/(4G C23) blended towards one combined flexibility as the creepage grows, as
CONTACT's <code>simpflex</code> does), <code>three</code> (separately) or <code>single_weighted</code> (Kalker's
single L). Gives M<sub>z</sub>. First-order in the grid: its error against the exact theory and its time per grid
are measured in docs/trade/README.md in the source repository (<code>cargo run --release -p lab --bin trade_report</code>).",
    default_model: || {
        Ok(ModelChoice::Fastsim(Fastsim::new(20, 20, TractionBound::Parabolic, Flexibility::ThreeBlended)?))
    },
};

/// FASTSIM's output: the forces and moment, and the share of the contact area in adhesion.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FastsimResult {
    /// F_x, F_y and M_z (always `Some`).
    pub forces: CreepForces,
    /// Adhesion area / contact area \[1\], 1 in the linear limit, 0 in full slip.
    pub adhesion_area_fraction: f64,
}

impl Fastsim {
    /// FASTSIM on `strips` strips of `elements` elements each (both in 1..=[`MAX_DIVISIONS`]).
    pub fn new(
        strips: usize,
        elements: usize,
        bound: TractionBound,
        flexibility: Flexibility,
    ) -> Result<Self, InvalidInput> {
        for (variable, value) in [("fastsim_strips", strips), ("fastsim_elements", elements)] {
            if !(1..=MAX_DIVISIONS).contains(&value) {
                return Err(InvalidInput::new(variable, value as f64, "must be an integer in 1..=10000"));
            }
        }
        let mut model = Self {
            strips,
            elements,
            bound,
            flexibility,
            discretisation: Discretisation::Strips,
            load_normalisation: 1.0,
        };
        model.load_normalisation = 1.0 / model.discrete_load();
        Ok(model)
    }

    /// The same model on another discretisation. With [`Discretisation::ContactGrid`],
    /// `strips` counts the rows across 2.2 b and `elements` the elements along 2.2 a.
    pub fn with_discretisation(self, discretisation: Discretisation) -> Self {
        let mut model = Self { discretisation, load_normalisation: 1.0, ..self };
        if discretisation == Discretisation::Strips {
            model.load_normalisation = 1.0 / model.discrete_load();
        }
        model
    }

    /// The discretisation.
    pub fn discretisation(&self) -> Discretisation {
        self.discretisation
    }

    /// Number of strips across the contact.
    pub fn strips(&self) -> usize {
        self.strips
    }

    /// Number of elements along each strip.
    pub fn elements(&self) -> usize {
        self.elements
    }

    /// The traction bound.
    pub fn bound(&self) -> TractionBound {
        self.bound
    }

    /// Forces, moment and adhesion-area fraction for one contact.
    pub fn evaluate(&self, input: &ContactInput) -> Result<FastsimResult, InvalidInput> {
        input.validate()?;
        if input.transmits_no_force() {
            return Ok(FastsimResult { forces: CreepForces::default(), adhesion_area_fraction: 0.0 });
        }
        let (a, b) = (input.semi_axis_a, input.semi_axis_b);
        let limit = input.friction_limit();
        let rates = self.rates(input);
        let sums = match self.discretisation {
            Discretisation::Strips => self.march(&rates),
            Discretisation::ContactGrid => self.march_contact_grid(&rates),
        };
        let forces = CreepForces::new(
            limit * sums.force_x,
            limit * sums.force_y,
            // M_z = ∫∫ (x p_y − y p_x) dA in units of μQ: a X P_y − b Y P_x.
            Some(limit * (a * sums.moment_x_py - b * sums.moment_y_px)),
            limit,
        );
        // The contact area is never empty: the element centre nearest the origin has
        // |X|, |Y| ≤ 0.55 on any grid, inside the ellipse.
        Ok(FastsimResult { forces, adhesion_area_fraction: sums.adhesion_area / sums.area })
    }

    /// The slip rates per unit X, in units of μQ/(ab): dP/dX = −(rx, ry0 + ry1 X).
    fn rates(&self, input: &ContactInput) -> Rates {
        let (a, b) = (input.semi_axis_a, input.semi_axis_b);
        let c = KalkerCoefficients::new(a / b, input.poisson_ratio);
        let g_area_per_load = input.shear_modulus * a * b / input.friction_limit();
        // a / (L_i μ p_scale) with p_scale = Q/(ab): k1 = 3 G C11 ab/(8 μQ), k2 likewise,
        // k3 = 4 G C23 ab √(b/a) / (π μQ). `min` also maps NaN (0/0 after underflow) to the cap.
        let k1 = (3.0 / 8.0 * c.c11 * g_area_per_load).min(RATE_MAX);
        let k2 = (3.0 / 8.0 * c.c22 * g_area_per_load).min(RATE_MAX);
        let k3 = (4.0 / PI * c.c23 * (b / a).sqrt() * g_area_per_load).min(RATE_MAX);
        let xi = clamp_rate(input.creepage_longitudinal);
        let eta = clamp_rate(input.creepage_lateral);
        let spin_a = clamp_rate(input.spin_creepage * a);
        let spin_b = clamp_rate(input.spin_creepage * b);
        let (k1, k2, k3) = match self.flexibility {
            Flexibility::Three => (k1, k2, k3),
            Flexibility::ThreeBlended => {
                let weight = blend_weight(input, &c, g_area_per_load);
                blended(weight, (xi, eta, spin_a), (k1, k2, k3))
            }
            Flexibility::SingleWeighted => {
                // 1/k = (|ξ|/k1 + |η|/k2 + c|φ|/k3) / √(ξ² + η² + c²φ²), c|φ| = √(spin_a spin_b),
                // with every creepage divided by the largest so that no square over/underflows.
                let spin_c = clamp_rate(input.spin_creepage.abs() * (a * b).sqrt());
                let largest = xi.abs().max(eta.abs()).max(spin_c);
                if largest == 0.0 {
                    (k1, k2, k3) // no creepage: any flexibility gives zero force
                } else {
                    let (x, y, s) = (xi.abs() / largest, eta.abs() / largest, spin_c / largest);
                    let k = ((x * x + y * y + s * s).sqrt() / (x / k1 + y / k2 + s / k3)).min(RATE_MAX);
                    (k, k, k)
                }
            }
        };
        Rates {
            along_strip: clamp_rate(k1 * xi),
            spin_across: clamp_rate(k3 * spin_b),
            lateral: clamp_rate(k2 * eta),
            spin_along: clamp_rate(k3 * spin_a),
        }
    }

    /// The march over all strips: sums of the normalised tractions times element areas.
    fn march(&self, rates: &Rates) -> Sums {
        let mut sums = Sums::default();
        let strip_width = 2.0 / self.strips as f64;
        let bound_scale = self.bound_scale();
        for strip in 0..self.strips {
            let y = -1.0 + (strip as f64 + 0.5) * strip_width;
            let half_length_sq = 1.0 - y * y;
            let half_length = half_length_sq.sqrt();
            let step = 2.0 * half_length / self.elements as f64;
            // Longitudinal rate is constant along the strip: w_x = ξ − φ y.
            let rate_x = rates.along_strip - rates.spin_across * y;
            // Half a step from the leading edge X = A to the first centre, slip at mid-step.
            let mut x = half_length - 0.5 * step;
            let mut px = -rate_x * 0.5 * step;
            let mut py = -(rates.lateral + rates.spin_along * (half_length - 0.25 * step)) * 0.5 * step;
            let mut strip_sums = StripSums { elements: self.elements, ..StripSums::default() };
            for element in 0..self.elements {
                if element > 0 {
                    // Full step from the previous centre, with w_y at the mid-step X + step/2.
                    px -= rate_x * step;
                    py -= (rates.lateral + rates.spin_along * (x + 0.5 * step)) * step;
                }
                let bound = self.bound_at(half_length_sq - x * x, bound_scale);
                strip_sums.add(&mut px, &mut py, x, bound);
                x -= step;
            }
            sums.add_strip(&strip_sums, y, step * strip_width);
        }
        sums
    }

    /// CONTACT's march ([`Discretisation::ContactGrid`]): rows of `elements` equal elements over
    /// −1.1 ≤ X ≤ 1.1, `strips` rows over −1.1 ≤ Y ≤ 1.1, from the leading edge X = 1.1 down.
    fn march_contact_grid(&self, rates: &Rates) -> Sums {
        let mut sums = Sums::default();
        let step = 2.0 * CONTACT_GRID_HALF_SIZE / self.elements as f64;
        let row_width = 2.0 * CONTACT_GRID_HALF_SIZE / self.strips as f64;
        let bound_scale = self.bound_scale();
        for row in 0..self.strips {
            let y = -CONTACT_GRID_HALF_SIZE + (row as f64 + 0.5) * row_width;
            let rate_x = rates.along_strip - rates.spin_across * y;
            let (mut px, mut py) = (0.0, 0.0);
            let mut strip_sums = StripSums::default();
            for element in (0..self.elements).rev() {
                let x = -CONTACT_GRID_HALF_SIZE + (element as f64 + 0.5) * step;
                let depth = 1.0 - x * x - y * y;
                if depth <= 0.0 {
                    // Outside the ellipse: no traction; a row re-entering it starts afresh.
                    (px, py) = (0.0, 0.0);
                    continue;
                }
                // A full step into every interior element, spin slip at x + δx/6 (`srztng`).
                px -= rate_x * step;
                py -= (rates.lateral + rates.spin_along * (x + CONTACT_SPIN_SLIP_OFFSET * step)) * step;
                strip_sums.add(&mut px, &mut py, x, self.bound_at(depth, bound_scale));
                strip_sums.elements += 1;
            }
            sums.add_strip(&strip_sums, y, step * row_width);
        }
        sums
    }

    /// Factor of the dimensionless bound: 2/π (parabolic) or 3/(2π) (elliptic), times the
    /// discrete-load normalisation.
    fn bound_scale(&self) -> f64 {
        let continuous = match self.bound {
            TractionBound::Parabolic => 2.0 / PI,
            TractionBound::Elliptic => 1.5 / PI,
        };
        continuous * self.load_normalisation
    }

    /// μ p_z / (μQ/(ab)) at a point with 1 − X² − Y² = `depth`.
    fn bound_at(&self, depth: f64, scale: f64) -> f64 {
        match self.bound {
            TractionBound::Parabolic => scale * depth,
            TractionBound::Elliptic => scale * depth.sqrt(),
        }
    }

    /// ∑ bound · dX dY over the grid's element centres with the continuous scale: 1 + O(h²).
    fn discrete_load(&self) -> f64 {
        let strip_width = 2.0 / self.strips as f64;
        let scale = self.bound_scale();
        let mut load = 0.0;
        for strip in 0..self.strips {
            let y = -1.0 + (strip as f64 + 0.5) * strip_width;
            let half_length_sq = 1.0 - y * y;
            let step = 2.0 * half_length_sq.sqrt() / self.elements as f64;
            let mut strip_load = 0.0;
            for element in 0..self.elements {
                let x = half_length_sq.sqrt() - (element as f64 + 0.5) * step;
                strip_load += self.bound_at(half_length_sq - x * x, scale);
            }
            load += strip_load * step * strip_width;
        }
        load
    }
}

impl CreepForceModel for Fastsim {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        self.evaluate(input).map(|result| result.forces)
    }
}

/// Slip rates of one contact, in units of μQ/(ab) per unit X.
struct Rates {
    /// a ξ / (L1 μ p_scale).
    along_strip: f64,
    /// The φ y term of w_x per unit Y: a φ b / (L3 μ p_scale).
    spin_across: f64,
    /// a η / (L2 μ p_scale).
    lateral: f64,
    /// The φ x term of w_y per unit X: a φ a / (L3 μ p_scale).
    spin_along: f64,
}

/// Sums over one strip's elements (before multiplying by the element area).
#[derive(Default)]
struct StripSums {
    px: f64,
    py: f64,
    x_py: f64,
    adhesion_elements: usize,
    /// Elements in contact (counted by the ContactGrid march only; a strip is all contact).
    elements: usize,
}

impl StripSums {
    /// Coulomb's law at one element: a traction over the `bound` is scaled onto it (slip),
    /// one within it counts as adhesion; then the traction at `x` is added to the sums.
    #[inline]
    fn add(&mut self, px: &mut f64, py: &mut f64, x: f64, bound: f64) {
        let magnitude_sq = *px * *px + *py * *py;
        if magnitude_sq > bound * bound {
            let scale = bound / magnitude_sq.sqrt();
            *px *= scale;
            *py *= scale;
        } else {
            self.adhesion_elements += 1;
        }
        self.px += *px;
        self.py += *py;
        self.x_py += x * *py;
    }
}

/// Sums over the contact, in units of μQ (forces) and μQ·a or μQ·b (moment parts).
#[derive(Default)]
struct Sums {
    force_x: f64,
    force_y: f64,
    moment_x_py: f64,
    moment_y_px: f64,
    adhesion_area: f64,
    area: f64,
}

impl Sums {
    /// Adds one strip at lateral position `y` whose elements have area `element_area`.
    fn add_strip(&mut self, strip: &StripSums, y: f64, element_area: f64) {
        self.force_x += strip.px * element_area;
        self.force_y += strip.py * element_area;
        self.moment_x_py += strip.x_py * element_area;
        self.moment_y_px += y * strip.px * element_area;
        self.adhesion_area += strip.adhesion_elements as f64 * element_area;
        self.area += strip.elements as f64 * element_area;
    }
}

/// The length unit in which CONTACT evaluates its blend weight f_crp: 1 mm (see
/// [`Flexibility::ThreeBlended`]).
const CONTACT_LENGTH_UNIT: f64 = 1e-3;

/// CONTACT's blend weight w = min(1, f_crp/3) (`simpflex`), spin in 1/mm as CONTACT has it.
/// With the weight in mm our converged results meet CONTACT's published ones (see
/// core/tests/library/ladder_contact_case.rs); with φ in 1/m, or with φ·√(ab), an emulation of CONTACT's own
/// scheme misses its published parabolic-bound results by 2–3 %.
/// `g_area_per_load` = G ab/(μQ), so that ξ* = 1/(g C11), η* = 1/(g C22), φ* = 1/(g c C23),
/// and f_crp = g |(ξ, η, φ)| / |(1/C11, 1/C22, 1/(c C23))|.
fn blend_weight(input: &ContactInput, c: &KalkerCoefficients, g_area_per_load: f64) -> f64 {
    // Squares of creepages clamped to 1e150 cannot overflow; one that underflows is < 1e-154 and
    // its share of the weight negligible. (1 mm/(c C23))² = (1 mm)²/(ab C23²) needs no root.
    let square = |value: f64| clamp_rate(value).powi(2);
    let creepage_sq = square(input.creepage_longitudinal)
        + square(input.creepage_lateral)
        + square(input.spin_creepage * CONTACT_LENGTH_UNIT);
    let spin_characteristic_sq =
        CONTACT_LENGTH_UNIT * CONTACT_LENGTH_UNIT / (input.semi_axis_a * input.semi_axis_b * c.c23 * c.c23);
    let characteristic_sq = 1.0 / (c.c11 * c.c11) + 1.0 / (c.c22 * c.c22) + spin_characteristic_sq;
    let weight = g_area_per_load * (creepage_sq / characteristic_sq).sqrt() / 3.0;
    // A NaN (0 · ∞ from absurd inputs) fails the test and gives the unblended flexibilities.
    if weight > 0.0 {
        weight.min(1.0)
    } else {
        0.0
    }
}

/// The dimensionless stiffnesses k_i ∝ 1/L_i after CONTACT's blend with weight `weight` towards
/// 1/L_crss (see [`Flexibility::ThreeBlended`]); `spin_a` = φ a.
fn blended(weight: f64, (xi, eta, spin_a): (f64, f64, f64), (k1, k2, k3): (f64, f64, f64)) -> (f64, f64, f64) {
    // s = φ (πa²/4)/(8a/3): CONTACT's spin term in L_crss (f4/f3 in `simpflex`).
    let s = clamp_rate(3.0 * PI / 32.0 * spin_a);
    let largest = xi.abs().max(eta.abs()).max(s.abs());
    if weight <= 0.0 || largest == 0.0 {
        return (k1, k2, k3);
    }
    // 1/L_crss = (ξ²/L1 + η²/L2 + s²/L3) / (ξ² + η² + s²), creepages scaled by the largest.
    let scale = 1.0 / largest;
    let (x, y, z) = (xi * scale, eta * scale, s * scale);
    let k_crss = (x * x * k1 + y * y * k2 + z * z * k3) / (x * x + y * y + z * z);
    // 1/k' = (1 − w)/k + w/k_crss, written without dividing by a zero stiffness.
    let mix = |k: f64| {
        if weight >= 1.0 {
            return k_crss;
        }
        let denominator = (1.0 - weight) * k_crss + weight * k;
        if denominator > 0.0 {
            k * k_crss / denominator
        } else {
            0.0
        }
    };
    (mix(k1), mix(k2), mix(k3))
}

fn clamp_rate(value: f64) -> f64 {
    value.clamp(-RATE_MAX, RATE_MAX)
}

/// Nothing carried from one evaluation to the next: each solve sweeps its strips from the leading edge.
impl crate::models::sequence::SequenceModel for Fastsim {
    type Memory = ();
    type Cache = ();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference_cases::FASTSIM_CASE;

    /// CONTACT's blend weight (`simpflex`) worked in millimetres on its `examples/fastsim` case:
    /// a = 8, b = 4, c = √32 mm, η = −6.25e-4, φ = 6.25e-4 /mm, G ab/(μQ) = 82e3 N/mm² · 32 mm² /
    /// 24.6e3 N; ξ* = 1/(g C11), η* = 1/(g C22), φ* = 1/(g c C23) [1/mm];
    /// w = √((η² + φ²)/(ξ*² + η*² + φ*²))/3.
    #[test]
    fn the_blend_weight_is_contacts_creepage_ratio_over_three() {
        let c = KalkerCoefficients::new(2.0, 0.28);
        let g = 82e3 * 32.0 / (0.3 * 82e3);
        let characteristic = [1.0 / (g * c.c11), 1.0 / (g * c.c22), 1.0 / (g * 32f64.sqrt() * c.c23)];
        let ratio =
            ((6.25e-4f64.powi(2) + 6.25e-4f64.powi(2)) / characteristic.iter().map(|s| s * s).sum::<f64>()).sqrt();
        let g_area_per_load = 82e9 * 8e-3 * 4e-3 / (0.3 * 82e3);
        let weight = blend_weight(&FASTSIM_CASE, &c, g_area_per_load);
        assert!((weight - ratio / 3.0).abs() < 1e-12 * ratio, "{weight} against {}", ratio / 3.0);
        assert!(weight > 0.1 && weight < 1.0, "{weight}: the case lies inside the blend");
        // At rest none; from three times the characteristic size on, full.
        let at = |scale: f64| {
            let input = ContactInput {
                creepage_lateral: scale * FASTSIM_CASE.creepage_lateral,
                spin_creepage: scale * FASTSIM_CASE.spin_creepage,
                ..FASTSIM_CASE
            };
            blend_weight(&input, &c, g_area_per_load)
        };
        assert_eq!((at(0.0), at(3.0 / ratio), at(1e3)), (0.0, 1.0, 1.0));
    }
}
