//! Lengths in metres as numbers of cells.
//!
//! A length set to a multiple of the cell size (a 0.3 m clearance on 0.05 m cells, a 1.2 m
//! range on 0.2 m cells) must mean that many cells, but the floating-point quotient can
//! fall just short of it (0.3 / 0.05 = 5.999999999999999), and comparisons against whole
//! distances (a cell exactly 6 cells from a wall) then went the other way than for 0.25 m
//! (5 cells exactly). [`cells`] gives the whole number in such cases.

/// `metres` as cells of `resolution` metres: the quotient, or the whole number it rounds
/// to when the two differ by rounding error only (within a billionth), so that
/// `cells(0.3, 0.05)` is 6 as `cells(0.25, 0.05)` is 5.
pub fn cells(metres: f64, resolution: f64) -> f64 {
    snap(metres / resolution)
}

/// `x`, or the whole number it rounds to when the two differ by rounding error only
/// (within a billionth of it): a count of cells computed by floating point (a range scaled
/// to coarser cells) made exact where it should be.
pub fn snap(x: f64) -> f64 {
    let n = x.round();
    if (x - n).abs() <= 1e-9 * n.abs().max(1.0) {
        n
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: a clearance of 0.3 m on 0.05 m cells was 5.999999999999999 cells, so the
    /// cells exactly 6 cells from a wall were judged by another rule than at 0.25 m.
    #[test]
    fn regression_multiples_of_the_cell_size_are_whole() {
        assert_ne!(0.3 / 0.05, 6.0, "the float quotient this guards against");
        for (m, res, want) in [
            (0.3, 0.05, 6.0),
            (0.3, 0.1, 3.0),
            (0.15, 0.05, 3.0),
            (1.2, 0.2, 6.0),
            (0.35, 0.025, 14.0),
            (0.25, 0.05, 5.0),
            (8.0, 0.05, 160.0),
            (3.0, 0.1, 30.0),
        ] {
            assert_eq!(cells(m, res), want, "{m} m at {res} m");
        }
    }

    #[test]
    fn lengths_between_multiples_are_kept() {
        assert_eq!(cells(0.31, 0.05), 0.31 / 0.05);
        assert_eq!(cells(0.3000001, 0.05), 0.3000001 / 0.05);
        assert_eq!(cells(0.0, 0.05), 0.0);
        assert_eq!(cells(0.07, 0.1), 0.07 / 0.1);
        assert_eq!(snap(2.5), 2.5);
        assert!(snap(f64::NAN).is_nan());
        assert_eq!(snap(f64::INFINITY), f64::INFINITY);
    }
}
