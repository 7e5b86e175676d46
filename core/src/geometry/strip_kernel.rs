//! The elastic influence of one strip of Kik and Piotrowski's pressure (`non_hertzian.rs`,
//! module doc, 4): the surface displacement at a point of the strips' centre line under the
//! pressure √(L² − x²) (k = 1) on a strip of half-length L, integrated across the strip's width.
//!
//! The pressure on a line across the strips at η from the point displaces it by (times π E*)
//! the kernel ∫ √(L² − x²)/√(x² + η²) dx over |x| < L = 2c (K(m) − E(m)), c² = L² + η²,
//! m = L²/c² ([`agm_kernel`]); scaled, K(L, η) = L f(|η|/L). A strip [η₁, η₂] across contributes
//! ∫ K dη = L² (g(η₂/L) − g(η₁/L)), g the primitive of f, odd in t: continuous in the point's
//! position, also where the point crosses the strip and the kernel is log-singular.
//!
//! [`strip_influence`] takes that exact integral near the point and the midpoint rule (one read
//! of the kernel's table) from [`FAR`] strip widths on, blended in between, so that the
//! displacement is continuous in the point's position and the strips' lengths: a reference
//! point moving across the strips moves the region's load continuously (with the point's
//! neighbours cut into sub-strips instead, the rule changed at fixed distances, and a flange
//! patch's z_ws jumped by 0.17 µm as its reference passed each strip).

use super::sampled_profile::hermite_height;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// From this many strip widths between the strip's centre and the point on, the strip's
/// integral is the midpoint rule's: its error there, w²K″/(24K), is 0.2 % of the strip's where
/// the strip is long (L ≫ |η|, K logarithmic in η) and 1.3 % where it is short (L ≪ |η|, as at a
/// region's edges, where its load is small; K ∝ 1/|η|), falling as 1/η² further out.
const FAR: f64 = 2.5;

/// Within this many strip widths of the point the strip's integral is exact; the two are
/// blended linearly in the distance between [`NEAR`] and [`FAR`].
const NEAR: f64 = 1.5;

/// The strip's displacement at a point `distance` from its centre along the strips (times π E*,
/// k = 1), the strip `width` wide with half-length `length` (module doc); 0 for L = 0.
pub(super) fn strip_influence(length: f64, width: f64, distance: f64) -> f64 {
    if length <= 0.0 {
        return 0.0;
    }
    let midpoint = || width * strip_kernel(length, distance);
    // (Compared without dividing: most strips lie beyond FAR widths.)
    if distance.abs() >= FAR * width {
        return midpoint();
    }
    let widths = distance.abs() / width;
    let exact = length
        * length
        * (kernel_primitive((distance + 0.5 * width) / length) - kernel_primitive((distance - 0.5 * width) / length));
    if widths <= NEAR {
        return exact;
    }
    // (FAR − NEAR is one width: the share is the distance beyond NEAR, in widths.)
    let share = (widths - NEAR) / (FAR - NEAR);
    (1.0 - share) * exact + share * midpoint()
}

/// ∫ √(L² − x²)/√(x² + η²) dx over |x| < L: [`agm_kernel`] read from [`KernelTable`] where the
/// strip lies at |η| ≥ L/99 (every strip the midpoint rule takes: they lie more than a strip
/// width from the point), the mean itself elsewhere. The table's read costs a division and a
/// cubic where the mean's iterations cost four to eight square roots in a chain.
fn strip_kernel(length: f64, eta: f64) -> f64 {
    if length <= 0.0 {
        return 0.0;
    }
    let u = length / (length + eta.abs());
    if u <= KernelTable::LAST {
        length * KernelTable::get().read(u)
    } else {
        agm_kernel(length, eta)
    }
}

/// g(t) = ∫₀ᵗ f(τ) dτ (module doc), odd in t. For |t| ≤ [`PrimitiveTable::SERIES_END`] its
/// series from f = 2 ln(4/t) − 2 + (t²/2) ln(4/t) + O(t⁴ ln t) (K and E about m = 1,
/// Abramowitz & Stegun 17.3.26 and 17.3.36, with k′ = t/√(1 + t²)): g = 2t ln(4/t) +
/// (t³/6)(ln(4/t) + 1/3), within 1e-11 there; beyond, from [`PrimitiveTable`].
fn kernel_primitive(t: f64) -> f64 {
    let magnitude = t.abs();
    let value = if magnitude == 0.0 {
        0.0
    } else if magnitude <= PrimitiveTable::SERIES_END {
        let log = (4.0 / magnitude).ln();
        2.0 * magnitude * log + magnitude * magnitude * magnitude / 6.0 * (log + 1.0 / 3.0)
    } else {
        let u = 1.0 / (1.0 + magnitude);
        PrimitiveTable::get().read(u) - 0.5 * PI * u.ln()
    };
    value.copysign(t)
}

/// A function of u ∈ [0, last] read by cubic Hermite interpolation from its values and slopes
/// at [`Self::INTERVALS`] equal intervals.
struct HermiteTable {
    /// Per node its value and its slope times the interval's length (the Hermite cubic's
    /// tangent in t), side by side: a read loads one pair of neighbours, and neither a read nor
    /// its tangents divide (the table is read once per strip and region, a few hundred times a
    /// round of a wide patch's balance).
    nodes: Vec<[f64; 2]>,
    /// Intervals per unit of u.
    per_unit: f64,
}

impl HermiteTable {
    const INTERVALS: usize = 2048;

    fn step(last: f64) -> f64 {
        last / Self::INTERVALS as f64
    }

    /// The table of `values` and `slopes` at u = i [`Self::step`]`(last)`, i = 0 ..= INTERVALS.
    fn new(values: Vec<f64>, slopes: Vec<f64>, last: f64) -> Self {
        let h = Self::step(last);
        let nodes = values.into_iter().zip(slopes).map(|(value, slope)| [value, slope * h]).collect();
        Self { nodes, per_unit: Self::INTERVALS as f64 / last }
    }

    /// The value at u ∈ [0, last].
    #[inline]
    fn read(&self, u: f64) -> f64 {
        let position = u * self.per_unit;
        // (u ≤ last: at most the last interval's end, read as t = 1 in the last interval.)
        let i = (position as usize).min(Self::INTERVALS - 1);
        let ([z0, m0], [z1, m1]) = (self.nodes[i], self.nodes[i + 1]);
        hermite_height(position - i as f64, z0, z1, m0, m1)
    }
}

/// The strip kernel scaled, f(t) = K(L, η)/L with t = |η|/L (x = L s: ∫ √(1 − s²)/√(s² + t²) ds),
/// tabulated in u = L/(L + |η|) = 1/(1 + t) ∈ [0, 1], where it is smooth but at u = 1: f is
/// analytic in 1/t = u/(1 − u) far from the strip (f = π/(2t) − π/(16t³) + …, from expanding
/// 1/√(s² + t²)), and its logarithmic singularity, f ≈ −2 ln(1 − u), lies at u = 1 alone. The
/// slopes from the mean by central differences. The error bound h⁴ max|f⁗|/384 (f⁗ ≈
/// 12/(1 − u)⁴ near u = 1) is largest at the table's end, (h/(1 − u))⁴/32 ≈ 1e-8 of f there
/// (measured: `the_kernel_table_is_the_mean`).
struct KernelTable;

impl KernelTable {
    /// The table's last u, t = 1/99: nearer to the strip the singularity's derivatives grow.
    const LAST: f64 = 0.99;

    /// The table, built on first use (some 6000 means, well below a millisecond).
    fn get() -> &'static HermiteTable {
        static TABLE: OnceLock<HermiteTable> = OnceLock::new();
        TABLE.get_or_init(|| {
            let step = HermiteTable::step(Self::LAST);
            // f at u (L = 1, η = t = 1/u − 1); f(0) = 0 infinitely far from the strip.
            let f = |u: f64| if u <= 0.0 { 0.0 } else { agm_kernel(1.0, 1.0 / u - 1.0) };
            let delta = 1e-3 * step;
            let values = (0..=HermiteTable::INTERVALS).map(|i| f(i as f64 * step)).collect();
            // f′(0) = π/2 (f ≈ π u/(2(1 − u)) there); elsewhere central differences, whose
            // error δ² f‴/6 + ε f/δ lies near 1e-12 at δ = h/1000.
            let slopes = (0..=HermiteTable::INTERVALS)
                .map(|i| {
                    let u = i as f64 * step;
                    if i == 0 {
                        0.5 * PI
                    } else {
                        (f(u + delta) - f(u - delta)) / (2.0 * delta)
                    }
                })
                .collect();
            HermiteTable::new(values, slopes, Self::LAST)
        })
    }
}

/// The kernel's primitive less its far-field growth, H(u) = g(t) − (π/2) ln(1 + t) with
/// u = 1/(1 + t) ∈ [0, 1/(1 + [`Self::SERIES_END`])]: bounded (f − π/(2(1 + t)) = O(1/t²) far
/// from the strip, so H = H(0) − (π/2) u + O(u²) there) and smooth but near u = 1, where the
/// series takes over. Its slopes are the kernel's, dH/du = −(f(t) − π/(2(1 + t)))/u²; its values
/// integrate them from the series' end by four-point Gauss–Legendre per interval (the nearest
/// singularity, at u = 1, lies 20 intervals or more away: error below 1e-13). Within 1e-9 of the
/// primitive (measured: `the_primitive_is_the_kernels_integral`).
struct PrimitiveTable;

impl PrimitiveTable {
    /// The series of [`kernel_primitive`] for t up to this.
    const SERIES_END: f64 = 0.01;

    /// The table, built on first use (some 14 000 means, about a millisecond).
    fn get() -> &'static HermiteTable {
        static TABLE: OnceLock<HermiteTable> = OnceLock::new();
        TABLE.get_or_init(|| {
            let last = 1.0 / (1.0 + Self::SERIES_END);
            let step = HermiteTable::step(last);
            let slope = |u: f64| {
                if u <= 0.0 {
                    return -0.5 * PI;
                }
                let t = 1.0 / u - 1.0;
                -(agm_kernel(1.0, t) - 0.5 * PI / (1.0 + t)) / (u * u)
            };
            // Gauss–Legendre's four nodes on [−1, 1] and their weights.
            const NODES: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
            const WEIGHTS: [f64; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
            let integral = |low: f64| {
                let (middle, half) = (low + 0.5 * step, 0.5 * step);
                half * NODES
                    .iter()
                    .zip(WEIGHTS)
                    .map(|(node, weight)| weight * (slope(middle - half * node) + slope(middle + half * node)))
                    .sum::<f64>()
            };
            let mut values = vec![0.0; HermiteTable::INTERVALS + 1];
            let end = Self::SERIES_END;
            values[HermiteTable::INTERVALS] = kernel_primitive(end) - 0.5 * PI * (1.0 + end).ln();
            for i in (0..HermiteTable::INTERVALS).rev() {
                values[i] = values[i + 1] - integral(i as f64 * step);
            }
            let slopes = (0..=HermiteTable::INTERVALS).map(|i| slope(i as f64 * step)).collect();
            HermiteTable::new(values, slopes, last)
        })
    }
}

/// ∫ √(L² − x²)/√(x² + η²) dx over |x| < L: 2c (K(m) − E(m)), c² = L² + η², m = L²/c²
/// (module doc), by the arithmetic-geometric mean (DLMF 19.8.1, 19.8.6): with a₀ = 1,
/// b₀ = √(1 − m), c₀ = √m and aₙ₊₁ = (aₙ + bₙ)/2, bₙ₊₁ = √(aₙ bₙ), cₙ₊₁ = (aₙ − bₙ)/2,
/// K = π/(2 a_∞) and K − E = K Σₙ 2ⁿ⁻¹ cₙ², a sum of positive terms (no cancellation where
/// m → 0, far from the strip). Scaled by c (a₀ = c, b₀ = |η|, c₀ = L) the kernel is
/// π Σₙ 2ⁿ⁻¹ cₙ² / a_∞; the sequence converges quadratically: in two or three steps far from
/// the strip (|η| ≥ 10 L, where the kernel tends to π L²/(2|η|)), four at |η| = L, at most 8
/// for |η| ≥ 1e-6 L — one square root each, where Carlson's R_D iterates on three.
fn agm_kernel(length: f64, eta: f64) -> f64 {
    if length <= 0.0 {
        return 0.0;
    }
    if eta == 0.0 {
        // The log singularity (K → ∞); the strips integrate across it instead.
        return f64::INFINITY;
    }
    // (Not `hypot`: L and η are millimetres, far from overflow, and `sqrt` is several times faster.)
    let (mut a, mut b, mut c) = ((length * length + eta * eta).sqrt(), eta.abs(), length);
    let (mut weight, mut sum) = (0.5, 0.5 * length * length);
    // cₙ below 1e-9 aₙ: the next terms, ~cₙ⁴/aₙ², lie below 1e-18 of the sum.
    for _ in 0..64 {
        if c <= 1e-9 * a {
            break;
        }
        (a, b, c) = (0.5 * (a + b), (a * b).sqrt(), 0.5 * (a - b));
        weight *= 2.0;
        sum += weight * c * c;
    }
    PI * sum / a
}

#[cfg(test)]
mod tests {
    use super::{agm_kernel, kernel_primitive, strip_influence, strip_kernel, KernelTable, PrimitiveTable};
    use std::f64::consts::PI;

    /// The strip kernel integrated over [low, high] (low < high) by the midpoint rule on n and
    /// 2n parts, extrapolated to zero part width (Richardson: the rule's error is ∝ h²), its log
    /// singularity at 0 subtracted and integrated in closed form: K − 2L (ln(4L/|η|) − 1) is
    /// bounded (`kernel_primitive`'s series).
    fn integrated(length: f64, low: f64, high: f64, n: u32) -> f64 {
        (4.0 * midpoint(length, low, high, 2 * n) - midpoint(length, low, high, n)) / 3.0
    }

    fn midpoint(length: f64, low: f64, high: f64, n: u32) -> f64 {
        let asymptote = |eta: f64| 2.0 * length * ((4.0 * length / eta.abs()).ln() - 1.0);
        let primitive = |eta: f64| if eta == 0.0 { 0.0 } else { 2.0 * length * eta * (4.0 * length / eta.abs()).ln() };
        let h = (high - low) / f64::from(n);
        let smooth: f64 = (0..n)
            .map(|i| {
                let eta = low + (f64::from(i) + 0.5) * h;
                (agm_kernel(length, eta) - asymptote(eta)) * h
            })
            .sum();
        smooth + primitive(high) - primitive(low)
    }

    /// The strip integral against Hertz's circle: under p = k √(a² − r²) the centre sinks by
    /// k/(π E*) ∫∫ √(a² − r²)/r dA = k/(π E*) · π² a²/2 (polar coordinates), Hertz's
    /// δ = π a p₀/(2 E*) with p₀ = k a (Johnson 1985, eq. 3.41). Strips of L(y) = √(a² − y²)
    /// 0.1 mm wide on a = 5 mm, summed as the normal problem sums them, at the centre and
    /// between strips: within 0.05 % (the strips' L is constant across each: the circle's
    /// edges are stepped).
    #[test]
    fn strips_give_hertzs_approach_on_a_circle() {
        let (a, width): (f64, f64) = (5e-3, 1e-4);
        let strips = (a / width).round() as i32;
        let exact = PI * PI * a * a / 2.0;
        for offset in [0.0, 0.25, 0.5] {
            let sum: f64 = (-strips..=strips)
                .map(|j| {
                    let centre = (f64::from(j) + offset) * width;
                    let length = (a * a - centre * centre).max(0.0).sqrt();
                    strip_influence(length, width, centre)
                })
                .sum();
            assert!((sum / exact - 1.0).abs() < 5e-4, "offset {offset}: {sum} against {exact}");
        }
    }

    /// A strip's influence is its kernel's integral over its width, near the point (across the
    /// singularity, and beside it), in the blend and far from it, for a long (L = 30 w) and a
    /// short strip (L = w/10): within 1e-8 where it is exact, within the midpoint rule's error
    /// beyond (`FAR`: 0.25 % on the long strip, 1.5 % on the short); and it is continuous in the
    /// distance where the rules change.
    #[test]
    fn a_strips_influence_is_its_integral() {
        let width = 1e-4;
        for length in [3e-3, 1e-5] {
            for widths in [0.0, 0.2, 0.5, 0.7, 1.4, 1.5, 2.0, 2.5, 3.0, 10.0] {
                let distance = widths * width;
                let reference = integrated(length, distance - 0.5 * width, distance + 0.5 * width, 200_000);
                let influence = strip_influence(length, width, distance);
                let tolerance = match (widths <= 1.5, length > width) {
                    (true, _) => 1e-8,
                    (false, true) => 2.5e-3,
                    (false, false) => 1.5e-2,
                };
                assert!(
                    (influence / reference - 1.0).abs() < tolerance,
                    "L {length}, {widths} widths: {influence} against {reference}"
                );
                assert_eq!(strip_influence(length, width, -distance), influence, "even in the distance");
            }
            for edge in [super::NEAR, super::FAR] {
                let (before, after) = (
                    strip_influence(length, width, edge * width * (1.0 - 1e-12)),
                    strip_influence(length, width, edge * width * (1.0 + 1e-12)),
                );
                assert!((before / after - 1.0).abs() < 1e-9, "L {length}, {edge} widths: {before} against {after}");
            }
        }
        assert_eq!(strip_influence(0.0, width, 0.0), 0.0);
        // From FAR widths on, the midpoint rule itself (one read of the kernel's table).
        for widths in [2.5, 3.0, 7.0] {
            let distance = widths * width;
            assert_eq!(strip_influence(3e-3, width, distance), width * strip_kernel(3e-3, distance));
        }
    }

    /// The primitive against the kernel's integral from 0 (series, across its end at
    /// t = 0.01, and the table from the strip to far from it, t up to 1e5): within 1e-9 of the
    /// integral (relatively, or absolutely where it is below 1); odd in t.
    #[test]
    fn the_primitive_is_the_kernels_integral() {
        let end = PrimitiveTable::SERIES_END;
        for t in [1e-4f64, 0.003, end * (1.0 - 1e-12), end * (1.0 + 1e-12), 0.02, 0.1, 1.0, 3.0, 40.0, 1e3, 1e5] {
            // (L = 1: the kernel is f; the integral piecewise between powers of ten.)
            let pieces: Vec<f64> = [0.0].into_iter().chain((-2..=5).map(|k| t.min(10f64.powi(k)))).collect();
            let integral: f64 =
                pieces.windows(2).filter(|w| w[1] > w[0]).map(|w| integrated(1.0, w[0], w[1], 100_000)).sum();
            let primitive = kernel_primitive(t);
            assert!((primitive - integral).abs() < 1e-9 * integral.max(1.0), "t {t}: {primitive} against {integral}");
            assert_eq!(kernel_primitive(-t), -primitive);
        }
        assert_eq!(kernel_primitive(0.0), 0.0);
    }

    /// The kernel by the arithmetic-geometric mean against Carlson's form of it,
    /// 2c (m/3) R_D(0, 1 − m, 1) (DLMF 19.25.1), from next to the strip to far from it
    /// (|η|/L from 1e-6 to 1e4): within 1e-13.
    #[test]
    fn the_strip_kernel_is_carlsons() {
        let length = 3e-3;
        for k in -60..=40 {
            let eta = length * 10f64.powf(f64::from(k) / 10.0);
            let c2 = length * length + eta * eta;
            let m = length * length / c2;
            let carlson = 2.0 * c2.sqrt() * m / 3.0 * ellip::elliprd(0.0, eta * eta / c2, 1.0).unwrap();
            let kernel = agm_kernel(length, eta);
            assert!((kernel / carlson - 1.0).abs() < 1e-13, "|η|/L {}: {kernel} against {carlson}", eta / length);
            assert_eq!(agm_kernel(length, -eta), kernel);
        }
    }

    /// The kernel as read from its table against the mean, from the table's end (|η| = L/99) to
    /// far from the strip (|η| = 1e6 L), 200 000 points: measured within 1.3e-8 relatively (at
    /// the table's end, as the error bound has it; 1e-12 beyond |η| = L).
    #[test]
    fn the_kernel_table_is_the_mean() {
        let length = 4e-3;
        let (mut worst, mut far) = (0.0f64, 0.0f64);
        for i in 0..200_000 {
            let t = (1.0 / 99.0) * 1e8f64.powf(f64::from(i) / 200_000.0);
            let (table, mean) = (strip_kernel(length, t * length), agm_kernel(length, t * length));
            let error = (table / mean - 1.0).abs();
            worst = worst.max(error);
            if t >= 1.0 {
                far = far.max(error);
            }
        }
        println!("worst {worst:e}, beyond |η| = L {far:e}");
        assert!(worst < 3e-8 && far < 1e-10, "worst {worst:e}, beyond |η| = L {far:e}");
        assert!(KernelTable::LAST < 1.0 && strip_kernel(length, 0.0) == f64::INFINITY);
    }

    /// The kernel's closed form 2c (K − E) against the integral it stands for, by the midpoint
    /// rule over x on a fine grid, near (η = L/10), at (η = L) and far from the strip (η = 20 L).
    #[test]
    fn the_strip_kernel_is_its_integral() {
        let length = 2e-3;
        for eta in [2e-4, 2e-3, 4e-2] {
            let n = 200_000;
            let dx = 2.0 * length / f64::from(n);
            let numeric: f64 = (0..n)
                .map(|i| {
                    let x = -length + (f64::from(i) + 0.5) * dx;
                    (length * length - x * x).sqrt() / (x * x + eta * eta).sqrt() * dx
                })
                .sum();
            let closed = strip_kernel(length, eta);
            assert!((closed / numeric - 1.0).abs() < 1e-6, "η {eta}: {closed} against {numeric}");
        }
    }
}
