//! Per-group descriptive statistics: n, mean ± sample sd, median, quartiles, IQR, min, max.
//!
//! Quantiles use NumPy's default (`method='linear'`, Hyndman & Fan type 7): the q-quantile of
//! sorted x₀ ≤ … ≤ xₙ₋₁ sits at virtual index h = (n − 1)·q and is interpolated linearly
//! between x⌊h⌋ and x⌊h⌋₊₁ (with NumPy's symmetric lerp, so results match `np.percentile`
//! to rounding). The sd is the sample sd (ddof = 1, `np.std(x, ddof=1)`); for n = 1 it is NaN,
//! as in NumPy. The median is `np.median` (mean of the two middle values for even n).

use super::{StatsError, check};

/// Descriptive statistics of one group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// Number of observations.
    pub n: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (divisor n − 1); NaN when n = 1.
    pub sd: f64,
    /// Median.
    pub median: f64,
    /// First quartile (NumPy linear quantile 0.25).
    pub q1: f64,
    /// Third quartile (NumPy linear quantile 0.75).
    pub q3: f64,
    /// Interquartile range q3 − q1.
    pub iqr: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

/// Summarizes a non-empty, finite sample (one allocation: a sorted copy).
pub fn summarize(x: &[f64]) -> Result<Summary, StatsError> {
    check(x)?;
    let n = x.len();
    let mut sorted = x.to_vec();
    sorted.sort_by(f64::total_cmp);
    let mean = x.iter().sum::<f64>() / n as f64;
    let sd = if n > 1 {
        (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1) as f64).sqrt()
    } else {
        f64::NAN
    };
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0
    };
    let q1 = quantile_linear(&sorted, 0.25);
    let q3 = quantile_linear(&sorted, 0.75);
    Ok(Summary {
        n,
        mean,
        sd,
        median,
        q1,
        q3,
        iqr: q3 - q1,
        min: sorted[0],
        max: sorted[n - 1],
    })
}

/// The q-quantile (0 ≤ q ≤ 1) of an ascending, non-empty slice by NumPy's default `linear`
/// method; NaN for an empty slice.
pub fn quantile_linear(sorted: &[f64], q: f64) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    let h = (n - 1) as f64 * q.clamp(0.0, 1.0);
    let lo = (h.floor() as usize).min(n - 1);
    let hi = (lo + 1).min(n - 1);
    let t = h - lo as f64;
    let (a, b) = (sorted[lo], sorted[hi]);
    let d = b - a;
    // NumPy's `_lerp`: a + d·t, or b − d·(1 − t) when t ≥ 0.5 (monotone and exact at ends).
    if t >= 0.5 {
        b - d * (1.0 - t)
    } else {
        a + d * t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worked_example() {
        // np.percentile([1, 2, 3, 4, 10], [25, 75]) = [2, 4]; mean 4, sd sqrt(12.5)
        let s = summarize(&[10.0, 2.0, 3.0, 1.0, 4.0]).unwrap();
        assert_eq!(
            (s.n, s.mean, s.median, s.q1, s.q3, s.iqr),
            (5, 4.0, 3.0, 2.0, 4.0, 2.0)
        );
        assert!((s.sd - 12.5f64.sqrt()).abs() < 1e-15);
        assert_eq!((s.min, s.max), (1.0, 10.0));
        // Even n: np.percentile([1, 2, 3, 4], 25) = 1.75, median 2.5.
        let s = summarize(&[4.0, 3.0, 2.0, 1.0]).unwrap();
        assert_eq!((s.q1, s.median, s.q3), (1.75, 2.5, 3.25));
        let s = summarize(&[7.0]).unwrap();
        assert!(s.sd.is_nan());
        assert_eq!((s.mean, s.median, s.iqr), (7.0, 7.0, 0.0));
        assert_eq!(summarize(&[]), Err(StatsError::Empty));
        assert_eq!(summarize(&[1.0, f64::NAN]), Err(StatsError::NonFinite));
    }
}
