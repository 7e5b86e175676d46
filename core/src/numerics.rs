//! Small numerical helpers shared by the models, and the number type they are written over.

use num_dual::{Dual64, DualNum};

/// A real number for the models: `f64` for values, a dual number (`num_dual::Dual64`) for exact
/// derivatives. Models are written once over `Scalar`; branches look at [`value`] only, except
/// on a fold of a model's coordinates, where the side is the one the direction points to
/// ([`rate`]).
pub trait Scalar: DualNum<Primitive = f64> + Copy {
    /// The rate along the direction of differentiation (0 for a plain value).
    fn rate(self) -> f64;

    /// This number with its value replaced and its rate kept (a plain value is `value` itself).
    /// Formed as `self + (value − self)` it would cost a plain value two dependent additions
    /// where it needs none.
    fn with_value(self, value: f64) -> Self;
}

impl Scalar for f64 {
    fn rate(self) -> f64 {
        0.0
    }

    fn with_value(self, value: f64) -> Self {
        value
    }
}

impl Scalar for Dual64 {
    fn rate(self) -> f64 {
        self.eps
    }

    fn with_value(self, value: f64) -> Self {
        Dual64::new(value, self.eps)
    }
}

/// The real part (the value without its derivative).
pub(crate) fn value<D: Scalar>(x: D) -> f64 {
    x.re()
}

/// x < 0 at x + 0⁺·(its rate): the side of 0 a point on the fold x = 0 moves to along the
/// direction of differentiation (the value's own side elsewhere).
pub(crate) fn moves_negative<D: Scalar>(x: D) -> bool {
    value(x) < 0.0 || (value(x) == 0.0 && x.rate() < 0.0)
}

/// √(x² + y²) without spurious underflow or overflow: squares are formed directly when they are
/// safe (the common case, a few instructions) and of scaled values otherwise.
pub(crate) fn magnitude<D: Scalar>(x: D, y: D) -> D {
    let largest = value(x).abs().max(value(y).abs());
    if largest > 1e-150 && largest < 1e150 {
        (x * x + y * y).sqrt()
    } else if largest == 0.0 || !largest.is_finite() {
        D::from(largest)
    } else {
        let (xs, ys) = (x / largest, y / largest);
        (xs * xs + ys * ys).sqrt() * largest
    }
}

#[cfg(test)]
mod tests {
    use num_dual::Dual64;

    use super::{magnitude, moves_negative};

    /// On the fold x = 0 the direction's rate picks the side; elsewhere the value's sign, and a
    /// plain value at 0 is on the positive side.
    #[test]
    fn the_side_of_zero_is_the_directions() {
        assert!(!moves_negative(Dual64::new(0.0, 1.0)));
        assert!(moves_negative(Dual64::new(0.0, -1.0)));
        assert!(moves_negative(Dual64::new(-1e-300, 1.0)));
        assert!(!moves_negative(Dual64::new(1e-300, -1.0)));
        assert!(!moves_negative(0.0_f64) && !moves_negative(-0.0_f64) && moves_negative(-1e-300_f64));
    }

    #[test]
    fn exact_across_the_whole_range() {
        assert_eq!(magnitude(3.0, -4.0), 5.0);
        // Scaled path: exact to a few ulps where x² and y² would underflow or overflow.
        for (x, y, expected) in [(3e-300_f64, 4e-300, 5e-300), (-3e200, 4e200, 5e200)] {
            assert!((magnitude(x, y) / expected - 1.0).abs() < 4.0 * f64::EPSILON);
        }
        assert_eq!(magnitude(0.0, -0.0), 0.0);
        assert_eq!(magnitude(1e-320, 0.0), 1e-320);
        assert_eq!(magnitude(f64::MAX, f64::MAX), f64::INFINITY);
        for (x, y) in [(1e-151_f64, 2e-151), (1e149, 1e151), (0.3, 1e-170)] {
            assert!((magnitude(x, y) / x.hypot(y) - 1.0).abs() < 4.0 * f64::EPSILON);
        }
    }
}
