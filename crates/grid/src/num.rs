//! Numbers as messages show them.

use std::fmt;

/// A number as an error message shows it: as Rust prints it (`0.05`, `8`, `1000`), but in
/// exponent form (`1e-300`, `1e300`) when that would take more than about 16 digits, so that
/// a mistyped value stays one short word of the message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x != 0.0 && x.is_finite() && !(1e-6..1e16).contains(&x.abs()) {
            write!(f, "{x:e}")
        } else {
            write!(f, "{x}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Num;

    /// Regression: `--speed 1e-300` and `--clearance 1e300` were echoed as 300 digits.
    #[test]
    fn regression_tiny_and_huge_numbers_print_short() {
        for (x, want) in [
            (0.05, "0.05"),
            (8.0, "8"),
            (-3.5, "-3.5"),
            (0.0, "0"),
            (1e-300, "1e-300"),
            (1e300, "1e300"),
            (-2.5e20, "-2.5e20"),
            (1e15, "1000000000000000"),
            (0.000001, "0.000001"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(Num(x).to_string(), want, "{x:e}");
        }
    }
}
