//! Wilcoxon signed-rank test (Wilcoxon 1945), paired and two-sided, following
//! `scipy.stats.wilcoxon` (SciPy 1.17, `zero_method='wilcox'`, `correction=True`) step by step.
//! Note SciPy's own default is `correction=False`; we always apply the continuity correction
//! (as Mann–Whitney does by default), so our asymptotic p-values are slightly larger than those
//! of a bare `scipy.stats.wilcoxon(x, y)` call.
//!
//! - Differences dᵢ = xᵢ − yᵢ; zero differences are dropped (Wilcoxon's own rule, SciPy's
//!   default `'wilcox'`): the remaining `n` nonzero |dᵢ| get average ranks, R⁺ / R⁻ are the rank
//!   sums of positive / negative differences, and the statistic is min(R⁺, R⁻).
//! - `Method::Auto` (SciPy's `method='auto'`), where N counts all pairs including zeros:
//!   N > 50 → asymptotic; otherwise no ties and no zeros → exact; otherwise N ≤ 13 → complete
//!   enumeration of the 2ⁿ sign flips (SciPy runs `permutation_test`, which is exhaustive there
//!   because 2¹³ < 9999 resamples); otherwise asymptotic.
//! - Exact: the null distribution of R⁺ for n untied ranks (SciPy's `_get_wilcoxon_distr`,
//!   built the same way so the numbers agree to rounding); p = 2·min(P(R⁺ ≥ ⌊r⁺⌋),
//!   P(R⁺ ≤ ⌈r⁺⌉)), clipped to 1. Costs O(n³); a forced exact test with ties or zeros ignores
//!   them, as SciPy's does.
//! - Permutation: counts of the sign-flip rank sums by dynamic programming over doubled
//!   (integer) average ranks, so ties are exact; p = 2·min(#(S ≤ r⁺), #(S ≥ r⁺))/2ⁿ, clipped.
//! - Asymptotic: z = (R⁺ − n(n+1)/4)/σ, σ² = (n(n+1)(2n+1) − Σ(t³−t)/2)/24, continuity
//!   corrected by ½ towards 0; p = 2·Φ(−|z|).
//!
//! Deviation: when every difference is zero (n = 0) we return p = 1 with
//! `MethodUsed::Degenerate`; SciPy returns NaN for N > 13 (0/0) and 1 for N ≤ 13.

use super::normal::ndtr;
use super::rank::average_ranks;
use super::{Method, MethodUsed, StatsError, check};

/// Result of a two-sided Wilcoxon signed-rank test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wilcoxon {
    /// min(R⁺, R⁻) (SciPy's two-sided `statistic`).
    pub statistic: f64,
    /// Rank sum of the positive differences.
    pub r_plus: f64,
    /// Rank sum of the negative differences.
    pub r_minus: f64,
    /// Number of nonzero differences (the effective sample size).
    pub n: usize,
    /// Number of zero differences that were dropped.
    pub zeros: usize,
    /// Two-sided p-value.
    pub p_value: f64,
    /// How the p-value was computed.
    pub method: MethodUsed,
    /// The continuity-corrected z score when the normal approximation was used.
    pub z: Option<f64>,
}

/// Two-sided Wilcoxon signed-rank test of paired samples (x − y) with SciPy's automatic method.
pub fn wilcoxon_signed_rank(x: &[f64], y: &[f64]) -> Result<Wilcoxon, StatsError> {
    wilcoxon_signed_rank_with(x, y, Method::Auto)
}

/// Two-sided Wilcoxon signed-rank test of paired samples (x − y) with a chosen method.
pub fn wilcoxon_signed_rank_with(
    x: &[f64],
    y: &[f64],
    method: Method,
) -> Result<Wilcoxon, StatsError> {
    if x.len() != y.len() {
        return Err(StatsError::LengthMismatch(x.len(), y.len()));
    }
    check(x)?;
    check(y)?;
    let d: Vec<f64> = x.iter().zip(y).map(|(a, b)| a - b).collect();
    wilcoxon_signed_rank_diffs(&d, method)
}

/// Two-sided Wilcoxon signed-rank test of the differences `d` against zero.
pub fn wilcoxon_signed_rank_diffs(d: &[f64], method: Method) -> Result<Wilcoxon, StatsError> {
    check(d)?;
    let total = d.len();
    let abs: Vec<f64> = d.iter().filter(|v| **v != 0.0).map(|v| v.abs()).collect();
    let n = abs.len();
    let zeros = total - n;
    let (mut order, mut ranks) = (Vec::new(), Vec::new());
    let ties = average_ranks(&abs, &mut order, &mut ranks);
    let (mut r_plus, mut r_minus) = (0.0, 0.0);
    // Walk the nonzero differences in the same order as `abs` / `ranks`.
    for (v, r) in d.iter().filter(|v| **v != 0.0).zip(&ranks) {
        if *v > 0.0 {
            r_plus += r;
        } else {
            r_minus += r;
        }
    }
    let mut out = Wilcoxon {
        statistic: f64::min(r_plus, r_minus),
        r_plus,
        r_minus,
        n,
        zeros,
        p_value: 1.0,
        method: MethodUsed::Degenerate,
        z: None,
    };
    let chosen = match method {
        Method::Exact => MethodUsed::Exact,
        Method::Asymptotic => MethodUsed::Asymptotic,
        Method::Auto if total > 50 => MethodUsed::Asymptotic,
        Method::Auto if !ties.any && zeros == 0 => MethodUsed::Exact,
        Method::Auto if total <= 13 => MethodUsed::Permutation,
        Method::Auto => MethodUsed::Asymptotic,
    };
    if n == 0 {
        return Ok(out);
    }
    out.method = chosen;
    out.p_value = match chosen {
        MethodUsed::Exact => exact_p(n, r_plus),
        MethodUsed::Permutation => permutation_p(&ranks, r_plus),
        _ => {
            let nf = n as f64;
            let mean = nf * (nf + 1.0) * 0.25;
            let se = ((nf * (nf + 1.0) * (2.0 * nf + 1.0) - ties.term / 2.0) / 24.0).sqrt();
            let mut z = (r_plus - mean) / se;
            let sign = if z > 0.0 {
                1.0
            } else if z < 0.0 {
                -1.0
            } else {
                0.0
            };
            z -= sign * 0.5 / se;
            out.z = Some(z);
            2.0 * ndtr(-z.abs())
        }
    }
    .clamp(0.0, 1.0);
    Ok(out)
}

/// Exact two-sided p from the untied null distribution of R⁺ (SciPy's `WilcoxonDistribution`).
fn exact_p(n: usize, r_plus: f64) -> f64 {
    // pmf of R⁺ over 0..=n(n+1)/2, built like SciPy's `_get_wilcoxon_distr`.
    let total = n * (n + 1) / 2;
    let mut c = vec![0.0f64; total + 1];
    let mut prev = vec![0.0f64; total + 1];
    c[0] = 1.0;
    let mut len = 1;
    for k in 1..=n {
        prev[..len].copy_from_slice(&c[..len]);
        let new_len = k * (k + 1) / 2 + 1;
        c[..new_len].fill(0.0);
        for i in 0..len {
            c[i] = prev[i] * 0.5;
        }
        let off = new_len - len;
        for i in 0..len {
            c[off + i] += prev[i] * 0.5;
        }
        len = new_len;
    }
    let mean = n as f64 * (n as f64 + 1.0) / 4.0;
    let sum = |lo: usize, hi: usize| -> f64 {
        // Σ pmf[lo..=hi] (empty when lo > hi or lo > total).
        if lo > hi || lo > total {
            0.0
        } else {
            c[lo..=hi.min(total)].iter().sum()
        }
    };
    let cdf = |k: usize| -> f64 {
        if k as f64 <= mean {
            sum(0, k)
        } else {
            1.0 - sum(k + 1, total)
        }
    };
    let sf = |k: usize| -> f64 {
        if k as f64 <= mean {
            sum(k, total)
        } else {
            1.0 - if k == 0 { 0.0 } else { sum(0, k - 1) }
        }
    };
    let lo = r_plus.floor() as usize;
    let hi = r_plus.ceil() as usize;
    2.0 * f64::min(sf(lo), cdf(hi))
}

/// Two-sided p of the complete sign-flip permutation test, exact with tied ranks.
fn permutation_p(ranks: &[f64], r_plus: f64) -> f64 {
    // Doubled average ranks are integers.
    let max: usize = ranks.iter().map(|r| (2.0 * r).round() as usize).sum();
    let mut counts = vec![0.0f64; max + 1];
    counts[0] = 1.0;
    let mut reach = 0;
    for r in ranks {
        let w = (2.0 * r).round() as usize;
        for s in (0..=reach).rev() {
            counts[s + w] += counts[s];
        }
        reach += w;
    }
    let obs = (2.0 * r_plus).round() as usize;
    let less: f64 = counts[..=obs.min(max)].iter().sum();
    let greater: f64 = counts[obs.min(max + 1)..].iter().sum();
    let all = (2.0f64).powi(ranks.len() as i32);
    2.0 * less.min(greater) / all
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worked_example() {
        // d = 1..=6 all positive: R⁺ = 21, R⁻ = 0; exact p = 2/64.
        let d: Vec<f64> = (1..=6).map(f64::from).collect();
        let r = wilcoxon_signed_rank_diffs(&d, Method::Auto).unwrap();
        assert_eq!(
            (r.statistic, r.r_plus, r.n, r.method),
            (0.0, 21.0, 6, MethodUsed::Exact)
        );
        assert!((r.p_value - 2.0 / 64.0).abs() < 1e-15);
    }

    #[test]
    fn all_zero_is_degenerate() {
        let r = wilcoxon_signed_rank(&[1.0; 20], &[1.0; 20]).unwrap();
        assert_eq!(
            (r.n, r.zeros, r.p_value, r.method),
            (0, 20, 1.0, MethodUsed::Degenerate)
        );
        assert!(matches!(
            wilcoxon_signed_rank(&[1.0], &[1.0, 2.0]),
            Err(StatsError::LengthMismatch(1, 2))
        ));
    }
}
