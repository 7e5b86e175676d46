//! Small numerical helpers shared by the models.

/// √(x² + y²) without spurious underflow or overflow: squares are formed directly when they are
/// safe (the common case, a few instructions) and of scaled values otherwise.
pub(crate) fn magnitude(x: f64, y: f64) -> f64 {
    let largest = x.abs().max(y.abs());
    if largest > 1e-150 && largest < 1e150 {
        (x * x + y * y).sqrt()
    } else if largest == 0.0 || !largest.is_finite() {
        largest
    } else {
        let (xs, ys) = (x / largest, y / largest);
        largest * (xs * xs + ys * ys).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::magnitude;

    #[test]
    fn exact_across_the_whole_range() {
        assert_eq!(magnitude(3.0, -4.0), 5.0);
        // Scaled path: exact to a few ulps where x² and y² would underflow or overflow.
        for (x, y, expected) in [(3e-300, 4e-300, 5e-300), (-3e200, 4e200, 5e200)] {
            assert!((magnitude(x, y) / expected - 1.0).abs() < 4.0 * f64::EPSILON);
        }
        assert_eq!(magnitude(0.0, -0.0), 0.0);
        assert_eq!(magnitude(1e-320, 0.0), 1e-320);
        assert_eq!(magnitude(f64::MAX, f64::MAX), f64::INFINITY);
        for (x, y) in [(1e-151, 2e-151), (1e149, 1e151), (0.3, 1e-170)] {
            assert!((magnitude(x, y) / x.hypot(y) - 1.0).abs() < 4.0 * f64::EPSILON);
        }
    }
}
