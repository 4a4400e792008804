//! Mann–Whitney U test (Mann & Whitney 1947), unpaired and two-sided, following
//! `scipy.stats.mannwhitneyu` (SciPy 1.17) step by step.
//!
//! - U₁ = R₁ − n₁(n₁+1)/2 with R₁ the sum of x's average ranks in the pooled sample; U₂ = n₁n₂ − U₁.
//! - `Method::Auto` (SciPy's `method='auto'`): exact when min(n₁, n₂) ≤ 8 and there are no
//!   ties, otherwise asymptotic.
//! - Exact: p = 2·P(U ≥ max(U₁, U₂)) under H₀ = 2·P(U ≤ n₁n₂ − max), clipped to 1. The null
//!   distribution is the Gaussian binomial coefficient [n₁+n₂ choose m]_q =
//!   Π_{i=1..m} (1 − q^{n+i})/(1 − q^i) (m = min, n = max size), expanded only up to the degree
//!   needed and rescaled to probabilities after each factor; cost O(m·min(U₁, U₂)). Like SciPy,
//!   a forced exact test with ties uses ⌊max(U₁, U₂)⌋ and ignores the ties.
//! - Asymptotic: z = (max(U₁, U₂) − n₁n₂/2 − ½)/σ with the tie-corrected
//!   σ² = n₁n₂/12 · ((n+1) − Σ(t³−t)/(n(n−1))); p = 2·Φ(−z), clipped to 1. When every value is
//!   tied (σ = 0) this gives p = 1, as in SciPy.

use super::normal::ndtr;
use super::rank::average_ranks;
use super::{Method, MethodUsed, StatsError, check};

/// Result of a two-sided Mann–Whitney U test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MannWhitney {
    /// U statistic of the first sample (SciPy's `statistic`): pairs (xᵢ, yⱼ) with xᵢ > yⱼ, ties ½.
    pub u1: f64,
    /// U statistic of the second sample, n₁n₂ − U₁.
    pub u2: f64,
    /// Two-sided p-value.
    pub p_value: f64,
    /// How the p-value was computed.
    pub method: MethodUsed,
    /// The continuity-corrected z score when the normal approximation was used.
    pub z: Option<f64>,
}

/// Two-sided Mann–Whitney U test of `x` against `y` with SciPy's automatic method choice.
pub fn mann_whitney_u(x: &[f64], y: &[f64]) -> Result<MannWhitney, StatsError> {
    mann_whitney_u_with(x, y, Method::Auto)
}

/// Two-sided Mann–Whitney U test with a chosen method.
pub fn mann_whitney_u_with(
    x: &[f64],
    y: &[f64],
    method: Method,
) -> Result<MannWhitney, StatsError> {
    check(x)?;
    check(y)?;
    let (n1, n2) = (x.len(), y.len());
    let mut pooled = Vec::with_capacity(n1 + n2);
    pooled.extend_from_slice(x);
    pooled.extend_from_slice(y);
    let (mut order, mut ranks) = (Vec::new(), Vec::new());
    let ties = average_ranks(&pooled, &mut order, &mut ranks);
    let r1: f64 = ranks[..n1].iter().sum();
    let (f1, f2) = (n1 as f64, n2 as f64);
    let u1 = r1 - f1 * (f1 + 1.0) / 2.0;
    let u2 = f1 * f2 - u1;
    let u = u1.max(u2);
    let exact = match method {
        Method::Exact => true,
        Method::Asymptotic => false,
        Method::Auto => n1.min(n2) <= 8 && !ties.any,
    };
    if exact {
        let k = u.floor() as usize;
        let p = 2.0 * exact_sf(n1, n2, k);
        return Ok(MannWhitney {
            u1,
            u2,
            p_value: p.clamp(0.0, 1.0),
            method: MethodUsed::Exact,
            z: None,
        });
    }
    let n = f1 + f2;
    let mu = f1 * f2 / 2.0;
    let s = (f1 * f2 / 12.0 * ((n + 1.0) - ties.term / (n * (n - 1.0)))).sqrt();
    let z = (u - mu - 0.5) / s;
    let p = 2.0 * ndtr(-z);
    Ok(MannWhitney {
        u1,
        u2,
        p_value: p.clamp(0.0, 1.0),
        method: MethodUsed::Asymptotic,
        z: Some(z),
    })
}

/// P(U ≥ k) under H₀ for sample sizes n1, n2 (SciPy's `_MWU.sf`, which sums from the left).
fn exact_sf(n1: usize, n2: usize, k: usize) -> f64 {
    let mn = n1 * n2;
    let kc = mn.saturating_sub(k);
    if k < kc {
        // 1 − P(U ≤ k) + P(U = k)
        let (cdf, pmf) = exact_cdf_pmf(n1, n2, k);
        1.0 - cdf + pmf
    } else {
        exact_cdf_pmf(n1, n2, kc).0
    }
}

/// (P(U ≤ k), P(U = k)) under H₀, from the truncated Gaussian binomial coefficient.
fn exact_cdf_pmf(n1: usize, n2: usize, k: usize) -> (f64, f64) {
    let (m, n) = (n1.min(n2), n1.max(n2));
    let mut c = vec![0.0f64; k + 1];
    c[0] = 1.0;
    for i in 1..=m {
        let a = n + i;
        // Multiply by (1 − q^a); descending so c[d − a] is still the old coefficient.
        for d in (a..=k).rev() {
            c[d] -= c[d - a];
        }
        // Divide by (1 − q^i): power-series division is a strided running sum.
        for d in i..=k {
            c[d] += c[d - i];
        }
        // Normalize: coefficients now sum to C(n+i, i) / C(n+i−1, i−1) times the old total.
        let scale = i as f64 / a as f64;
        for v in &mut c {
            *v *= scale;
        }
    }
    (c.iter().sum(), c[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crates_md_example() {
        // CRATES.md: statrs returned 1.0 here; the exact value is 4/140 = 0.028571...
        let r = mann_whitney_u(&[1.0, 2.0, 3.5, 4.0], &[5.0, 6.0, 7.5, 8.0]).unwrap();
        assert_eq!(r.method, MethodUsed::Exact);
        assert_eq!((r.u1, r.u2), (0.0, 16.0));
        assert!((r.p_value - 2.0 / 70.0).abs() < 1e-15);
    }

    #[test]
    fn exact_distribution_sums_to_one() {
        for (n1, n2) in [(1, 1), (3, 5), (8, 8), (8, 40), (12, 7)] {
            let (cdf, _) = exact_cdf_pmf(n1, n2, n1 * n2);
            assert!((cdf - 1.0).abs() < 1e-12, "{n1} {n2} {cdf}");
        }
    }

    #[test]
    fn all_tied_is_p_one() {
        let r = mann_whitney_u(&[2.0; 12], &[2.0; 9]).unwrap();
        assert_eq!(r.p_value, 1.0);
    }
}
