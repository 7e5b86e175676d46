//! Kalker's linear-theory creepage coefficients C11, C22, C23 and the spin-moment coefficient C33
//! as continuous functions of the semi-axis ratio a/b and Poisson's ratio ν.
//!
//! Sources: Kalker (1990), *Three-dimensional elastic bodies in rolling contact*, Table E.3
//! (`data/kalker_coefficients.csv` and `data/kalker_c33.csv`, turned into constants by `build.rs`),
//! and Kalker's asymptotic formulas for thin ellipses (g < 0.1, docs/reference/kalker-asymptotes.md).
//!
//! Interpolation, as in Kalker's CONTACT program (`linrol` in its m_hertz.f90): first, for each
//! tabulated ν, C is linear in g = smaller/larger semi-axis between the two rows around g; then
//! 1/C is quadratic (Lagrange) in ν through ν = 0, 0.25, 0.5. Written with one division,
//!
//! ```text
//! C(ν) = 1 / (w0/c0 + w1/c1 + w2/c2) = c0 c1 c2 / (w0 c1 c2 + w1 c0 c2 + w2 c0 c1),
//! ```
//!
//! where c_k are the g-interpolated values at the nodes and w_k the Lagrange weights.
//!
//! Below g = 0.1 the asymptotes differ from the table's g = 0.1 row by a few per cent, so a hard
//! switch would make the forces jump. We blend multiplicatively:
//!
//! ```text
//! C(g) = C_asym(g) · [1 + (C_table(0.1)/C_asym(0.1) − 1) · g/0.1],   g < 0.1,
//! ```
//!
//! which equals the table at g = 0.1 and tends to the asymptote (relative correction → 0) as
//! g → 0: continuous in a/b over the whole range, with both published limits honoured.
//!
//! C33 is computed separately ([`KalkerCoefficients::spin_moment_c33`]) so that models without a
//! spin moment (Polach) do not pay for it. Its thin-ellipse limits:
//! - a ≪ b: every lateral slice y of the contact rolls like a 2-D contact of half-length
//!   a(y) = a√(1 − y²/b²), whose force per unit width is π G a(y) ξ_y / (2(1 − ν)) (the 2-D
//!   result behind the C11 asymptote π²/(4(1 − ν))). Pure spin gives each slice the creepage
//!   ξ_y = −φ y, so M_z = −∫ y F'_x dy = −π² G a b³ φ / (16(1 − ν)), i.e.
//!   C33 = π² / (16 (1 − ν) g). It matches the table's a/b = 0.1 row to 4 % (6.17 vs 6.42 at ν = 0).
//! - b ≪ a: we found no asymptote we could verify against the table, so C33 is held at its
//!   tabulated b/a = 0.1 value below it (continuous and bounded; such slender contacts are rare in
//!   wheel–rail contact).

use std::f64::consts::PI;

use crate::numerics::{value, Scalar};

/// One tabulated coefficient: per table row, C at ν = 0, 0.25, 0.5.
pub(crate) type Column = [[f64; 3]; 19];

include!(concat!(env!("OUT_DIR"), "/kalker_table.rs"));

/// Index of the table row with a/b = 1 (rows before it are a/b = 0.1 … 0.9, after it b/a = 0.9 … 0.1).
const ROW_ROUND: usize = 9;
/// Index of the last table row (b/a = 0.1).
const ROW_LAST: usize = 18;
/// Smallest tabulated ratio g; below it the asymptotes apply.
const G_TABLE_MIN: f64 = 0.1;
/// Numerical floor of g: keeps g^{3/2} and 1/g far from underflow/overflow for absurd ratios.
/// Physical contacts never come near it; below it the coefficients are held constant.
const G_FLOOR: f64 = 1e-100;

/// Kalker's creepage coefficients for one ellipse shape and material \[1\].
///
/// `T` is `f64` for values, a dual number where the models differentiate with respect to a/b.
///
/// Kalker's Table E.3 at its nodes, interpolated between them (module doc):
///
/// ```
/// use wheel_rail_contact::KalkerCoefficients;
///
/// let circle = KalkerCoefficients::new(1.0, 0.25);
/// assert_eq!((circle.c11, circle.c22, circle.c23), (4.12, 3.67, 1.47));
/// assert_eq!(KalkerCoefficients::spin_moment_c33(1.0, 0.25), 1.19);
/// // b/a = 0.5 (a = 2b), ν = 0: 4.37, 4.37, 2.35; ν = 0.5: 6.11, 5.56, 2.96.
/// let near = |c: KalkerCoefficients, table: [f64; 3]| (c.c11 - table[0]).abs() + (c.c22 - table[1]).abs() + (c.c23 - table[2]).abs() < 1e-12;
/// assert!(near(KalkerCoefficients::new(2.0, 0.0), [4.37, 4.37, 2.35]));
/// assert!(near(KalkerCoefficients::new(2.0, 0.5), [6.11, 5.56, 2.96]));
/// // Between rows: linear in g = b/a (halfway between the rows b/a = 0.8 and 0.7 at ν = 0: 3.65, 3.82).
/// let between = KalkerCoefficients::new(1.0 / 0.75, 0.0);
/// assert!((between.c11 - 0.5 * (3.65 + 3.82)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KalkerCoefficients<T = f64> {
    /// Longitudinal creepage coefficient C11.
    pub c11: T,
    /// Lateral creepage coefficient C22.
    pub c22: T,
    /// Lateral force from spin, C23 (= −C32 for quasi-identical bodies).
    pub c23: T,
}

impl KalkerCoefficients {
    /// Coefficients for semi-axis ratio `a_over_b` = a/b (a in the rolling direction) and
    /// Poisson's ratio `poisson_ratio` in [0, 0.5]. `a_over_b` must be > 0 (not checked here:
    /// callers validate their inputs first).
    pub fn new(a_over_b: f64, poisson_ratio: f64) -> Self {
        Self::at(a_over_b, poisson_ratio)
    }

    /// Kalker's spin-moment coefficient C33 \[1\] for the same arguments as [`Self::new`], with
    /// M_z = G c³ C23 η − G c⁴ C33 φ, c = √(ab) (moment on the wheel, Kalker's convention).
    pub fn spin_moment_c33(a_over_b: f64, poisson_ratio: f64) -> f64 {
        spin_moment_c33_at(a_over_b, poisson_ratio)
    }
}

impl KalkerCoefficients {
    /// The coefficients as another [`Scalar`] (constants: no derivative).
    pub(crate) fn map<D: Scalar>(self, into: impl Fn(f64) -> D) -> KalkerCoefficients<D> {
        KalkerCoefficients { c11: into(self.c11), c22: into(self.c22), c23: into(self.c23) }
    }
}

impl<D: Scalar> KalkerCoefficients<D> {
    /// [`KalkerCoefficients::new`] for any [`Scalar`] a/b.
    pub(crate) fn at(a_over_b: D, poisson_ratio: f64) -> Self {
        let point = TablePoint::new(a_over_b, poisson_ratio);
        match point.lookup() {
            Lookup::BetweenRows { lower, fraction } => Self {
                c11: point.interpolate(&C11, lower, fraction),
                c22: point.interpolate(&C22, lower, fraction),
                c23: point.interpolate(&C23, lower, fraction),
            },
            Lookup::BelowTable { edge_row, weight } => {
                let asymptote_edge = asymptotes(D::from(G_TABLE_MIN), point.a_is_shorter, poisson_ratio);
                let asymptote = asymptotes(point.floored_g(), point.a_is_shorter, poisson_ratio);
                let blend = |column: &Column, asym: D, asym_edge: D| {
                    blend(asym, point.at_row(column, edge_row), value(asym_edge), weight)
                };
                Self {
                    c11: blend(&C11, asymptote.c11, asymptote_edge.c11),
                    c22: blend(&C22, asymptote.c22, asymptote_edge.c22),
                    c23: blend(&C23, asymptote.c23, asymptote_edge.c23),
                }
            }
        }
    }
}

/// C33 for any [`Scalar`] a/b; see [`KalkerCoefficients::spin_moment_c33`].
pub(crate) fn spin_moment_c33_at<D: Scalar>(a_over_b: D, poisson_ratio: f64) -> D {
    let point = TablePoint::new(a_over_b, poisson_ratio);
    match point.lookup() {
        Lookup::BetweenRows { lower, fraction } => point.interpolate(&C33, lower, fraction),
        Lookup::BelowTable { edge_row, weight } if point.a_is_shorter => {
            let thin_strip = |g: D| g.recip() * (PI * PI / (16.0 * (1.0 - poisson_ratio)));
            let edge = value(thin_strip(D::from(G_TABLE_MIN)));
            blend(thin_strip(point.floored_g()), point.at_row(&C33, edge_row), edge, weight)
        }
        Lookup::BelowTable { edge_row, .. } => D::from(point.at_row(&C33, edge_row)),
    }
}

/// Where one ellipse shape and material sit in Kalker's table; shared by every coefficient.
struct TablePoint<D> {
    /// Lagrange weights of the nodes ν = 0, 0.25, 0.5.
    weights: [f64; 3],
    /// g = smaller/larger semi-axis.
    g: D,
    /// a ≤ b (the a/b branch of the table).
    a_is_shorter: bool,
}

/// How a coefficient is found for one [`TablePoint`].
enum Lookup<D> {
    /// Linear interpolation between rows `lower` and `lower + 1`.
    BetweenRows { lower: usize, fraction: D },
    /// g < 0.1: the asymptote, blended with the edge row by `weight` = g/0.1.
    BelowTable { edge_row: usize, weight: D },
}

impl<D: Scalar> TablePoint<D> {
    fn new(a_over_b: D, nu: f64) -> Self {
        let (g, a_is_shorter) = if value(a_over_b) <= 1.0 { (a_over_b, true) } else { (a_over_b.recip(), false) };
        Self { weights: lagrange_weights(nu), g, a_is_shorter }
    }

    fn floored_g(&self) -> D {
        if value(self.g) < G_FLOOR {
            D::from(G_FLOOR)
        } else {
            self.g
        }
    }

    fn lookup(&self) -> Lookup<D> {
        if value(self.g) < G_TABLE_MIN {
            let edge_row = if self.a_is_shorter { 0 } else { ROW_LAST };
            return Lookup::BelowTable { edge_row, weight: self.g / G_TABLE_MIN };
        }
        // Position in rows: a/b branch row i at g = 0.1(i+1); b/a branch row 9+j at g = 1 − 0.1 j.
        let position = if self.a_is_shorter { self.g * 10.0 - 1.0 } else { (-self.g + 1.0) * 10.0 + ROW_ROUND as f64 };
        let lower = (value(position) as usize).min(ROW_LAST - 1);
        Lookup::BetweenRows { lower, fraction: position - lower as f64 }
    }

    /// The coefficient at the tabulated row `row`, at this ν.
    fn at_row(&self, column: &Column, row: usize) -> f64 {
        self.at_poisson(column[row])
    }

    /// Linear interpolation in g between rows `lower` and `lower + 1` at each tabulated ν, then
    /// the quadratic rule in ν.
    fn interpolate(&self, column: &Column, lower: usize, fraction: D) -> D {
        let (low, high) = (column[lower], column[lower + 1]);
        self.at_poisson([0, 1, 2].map(|k| fraction * (high[k] - low[k]) + low[k]))
    }

    /// 1/C quadratic in ν through the node values [c0, c1, c2], with a single division.
    fn at_poisson<T: Scalar>(&self, [c0, c1, c2]: [T; 3]) -> T {
        let [w0, w1, w2] = self.weights;
        c0 * c1 * c2 / (c1 * c2 * w0 + c0 * c2 * w1 + c0 * c1 * w2)
    }
}

/// The multiplicative blend of the module documentation.
fn blend<D: Scalar>(asymptote: D, table_edge: f64, asymptote_edge: f64, weight: D) -> D {
    asymptote * (weight * (table_edge / asymptote_edge - 1.0) + 1.0)
}

/// Lagrange weights of the nodes ν = 0, 0.25, 0.5 (CSV header):
/// 1/C(ν) = 8(ν−¼)(ν−½)/C(0) − 16(ν−½)ν/C(¼) + 8ν(ν−¼)/C(½).
fn lagrange_weights(nu: f64) -> [f64; 3] {
    [8.0 * (nu - 0.25) * (nu - 0.5), -16.0 * (nu - 0.5) * nu, 8.0 * nu * (nu - 0.25)]
}

/// Kalker's asymptotic coefficients for a thin ellipse, g = smaller/larger semi-axis → 0.
fn asymptotes<D: Scalar>(g: D, a_is_shorter: bool, nu: f64) -> KalkerCoefficients<D> {
    let ln_4 = 4.0_f64.ln();
    if a_is_shorter {
        // a ≪ b: the contact is a thin strip across the rail.
        KalkerCoefficients {
            c11: D::from(PI * PI / (4.0 * (1.0 - nu))),
            c22: D::from(PI * PI / 4.0),
            c23: g.sqrt() * (PI / (3.0 * (1.0 - nu))) * ((g.recip() * 16.0).ln() * nu + (1.0 - 5.0 * nu)),
        }
    } else {
        // a ≫ b, with Λ = ln(16/g²) written as ln 16 − 2 ln g so that g² cannot underflow.
        let lambda = g.ln() * -2.0 + 16.0_f64.ln();
        let d11 = lambda - 2.0 * nu;
        let c11 = (d11 * g).recip() * (2.0 * PI) * (d11.recip() * (3.0 - ln_4) + 1.0);
        let d22 = lambda * (1.0 - nu) + 2.0 * nu;
        let c22 = g.recip() * (2.0 * PI) * (d22.recip() * ((1.0 - nu) * (3.0 - ln_4)) + 1.0) / d22;
        let c23 = (g * g.sqrt() * (lambda * (1.0 - nu) - 2.0 + 4.0 * nu) * 3.0).recip() * (2.0 * PI);
        KalkerCoefficients { c11, c22, c23 }
    }
}
