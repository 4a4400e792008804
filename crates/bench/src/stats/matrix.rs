//! Faigl-style `+`/`=`/`-` verdicts (Faigl & Kulich 2013, §V and Table I).
//!
//! The paper tests the null hypothesis "both strategies give statistically identical L" with a
//! Wilcoxon test and calls them different when P < 0.001; then "the strategy providing a smaller
//! average value of L is considered as a better", so "a vs b: +" means a is better (lower) than
//! b. We do the same for any lower-is-better metric, at any α (default
//! [`DEFAULT_ALPHA`](super::DEFAULT_ALPHA) = 0.001), with either the unpaired Mann–Whitney U
//! (Wilcoxon rank-sum) test or the paired Wilcoxon signed-rank test (pairs = same start
//! variant and trial), both two-sided with SciPy's automatic method choice. Significance is
//! strict (p < α); equal means with p < α give `=`.
//!
//! With few observations no outcome can be significant: the smallest two-sided p of the exact
//! Wilcoxon test of n pairs is 2/2ⁿ (1.95·10⁻³ for n = 10, above α = 0.001), that of the
//! exact Mann–Whitney test of sizes n₁, n₂ is 2/C(n₁+n₂, n₁). [`Comparison::min_p_value`] is
//! that smallest p for the samples at hand (same test, method, ties and zeros; see
//! [`smallest_p`]), so a `=` that could not have been anything else can be told apart
//! ([`Comparison::underpowered`]), and [`needed`] says how many observations would do.
//!
//! The matrix computes each unordered pair once and mirrors it, so `m[a][b]` is always the
//! opposite of `m[b][a]`.

use super::{
    Method, MethodUsed, StatsError, mann_whitney_u, wilcoxon_signed_rank,
    wilcoxon_signed_rank_diffs,
};

/// Which two-sample test to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pairing {
    /// Independent samples: Mann–Whitney U.
    Unpaired,
    /// Paired samples (equal lengths, element i of each is the same condition): Wilcoxon
    /// signed-rank.
    Paired,
}

/// Verdict of "a vs b" for a lower-is-better metric.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// a is significantly better (lower mean) than b: `+`.
    Better,
    /// No significant difference: `=`.
    Same,
    /// a is significantly worse (higher mean) than b: `-`.
    Worse,
}

impl Verdict {
    /// The table symbol: `+`, `=` or `-`.
    pub fn symbol(self) -> char {
        match self {
            Verdict::Better => '+',
            Verdict::Same => '=',
            Verdict::Worse => '-',
        }
    }

    /// The verdict of "b vs a".
    pub fn flip(self) -> Verdict {
        match self {
            Verdict::Better => Verdict::Worse,
            Verdict::Same => Verdict::Same,
            Verdict::Worse => Verdict::Better,
        }
    }
}

/// One "a vs b" comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// `+`/`=`/`-` for a vs b.
    pub verdict: Verdict,
    /// Two-sided p-value of the test.
    pub p_value: f64,
    /// How the p-value was computed.
    pub method: MethodUsed,
    /// Mean of a.
    pub mean_a: f64,
    /// Mean of b.
    pub mean_b: f64,
    /// The smallest p the same test could give with these sample sizes, ties and zero
    /// differences (the most extreme arrangement of the same values; see [`smallest_p`]).
    pub min_p_value: f64,
}

impl Comparison {
    /// Whether no outcome could have been significant at `alpha` (min p ≥ α): a `=` that says
    /// nothing about a difference.
    pub fn underpowered(&self, alpha: f64) -> bool {
        self.min_p_value >= alpha
    }

    /// The same comparison seen as "b vs a".
    pub fn flip(self) -> Comparison {
        Comparison {
            verdict: self.verdict.flip(),
            mean_a: self.mean_b,
            mean_b: self.mean_a,
            ..self
        }
    }
}

/// Compares samples a and b of a lower-is-better metric at level `alpha`.
pub fn compare(
    a: &[f64],
    b: &[f64],
    alpha: f64,
    pairing: Pairing,
) -> Result<Comparison, StatsError> {
    let (p_value, method) = match pairing {
        Pairing::Unpaired => {
            let r = mann_whitney_u(a, b)?;
            (r.p_value, r.method)
        }
        Pairing::Paired => {
            let r = wilcoxon_signed_rank(a, b)?;
            (r.p_value, r.method)
        }
    };
    let mean_a = a.iter().sum::<f64>() / a.len() as f64;
    let mean_b = b.iter().sum::<f64>() / b.len() as f64;
    let verdict = if p_value < alpha && mean_a < mean_b {
        Verdict::Better
    } else if p_value < alpha && mean_a > mean_b {
        Verdict::Worse
    } else {
        Verdict::Same
    };
    Ok(Comparison {
        verdict,
        p_value,
        method,
        mean_a,
        mean_b,
        min_p_value: smallest_p(a, b, pairing)?,
    })
}

/// The smallest two-sided p the test of [`compare`] can give for samples like `a` and `b`:
/// the p of the most extreme arrangement of the same values, which keeps the sizes, ties and
/// zero differences and so the method SciPy's automatic choice picks.
///
/// Paired: every difference |aᵢ − bᵢ| made positive (exact: 2/2ⁿ for n nonzero differences).
/// Unpaired: a given the n₁ smallest or the n₁ largest of the pooled values, whichever
/// gives the smaller p (exact: 2/C(n₁+n₂, n₁) both; with ties at either split they differ,
/// and the tie correction, a property of the pooled values, is the same for every
/// arrangement, so no other arrangement is more extreme).
pub fn smallest_p(a: &[f64], b: &[f64], pairing: Pairing) -> Result<f64, StatsError> {
    match pairing {
        Pairing::Paired => {
            if a.len() != b.len() {
                return Err(StatsError::LengthMismatch(a.len(), b.len()));
            }
            let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x - y).abs()).collect();
            Ok(wilcoxon_signed_rank_diffs(&d, Method::Auto)?.p_value)
        }
        Pairing::Unpaired => {
            let mut pooled: Vec<f64> = a.iter().chain(b).copied().collect();
            pooled.sort_by(f64::total_cmp);
            let (lo, hi) = pooled.split_at(a.len());
            let low = mann_whitney_u(lo, hi)?.p_value;
            let (lo, hi) = pooled.split_at(b.len());
            let high = mann_whitney_u(hi, lo)?.p_value;
            Ok(low.min(high))
        }
    }
}

/// The fewest observations with which the test can reach `p < alpha` for untied data without
/// zero differences: pairs for [`Pairing::Paired`] (2/2ⁿ < α while exact), observations per
/// sample (equal sizes) for [`Pairing::Unpaired`] (2/C(2n, n) < α while exact). `None` above
/// 10,000.
pub fn needed(alpha: f64, pairing: Pairing) -> Option<usize> {
    (1..=10_000).find(|&n| {
        let a: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let b: Vec<f64> = (0..n).map(|i| (n + i) as f64).collect();
        let p = match pairing {
            Pairing::Paired => wilcoxon_signed_rank_diffs(&b, Method::Auto).map(|w| w.p_value),
            Pairing::Unpaired => mann_whitney_u(&a, &b).map(|r| r.p_value),
        };
        p.is_ok_and(|p| p < alpha)
    })
}

/// All pairwise comparisons of k groups: row = a, column = b.
#[derive(Clone, Debug, PartialEq)]
pub struct PairwiseMatrix {
    k: usize,
    cells: Vec<Option<Comparison>>,
}

impl PairwiseMatrix {
    /// Number of groups.
    pub fn len(&self) -> usize {
        self.k
    }

    /// Whether there are no groups.
    pub fn is_empty(&self) -> bool {
        self.k == 0
    }

    /// "Group a vs group b", `None` on the diagonal.
    pub fn get(&self, a: usize, b: usize) -> Option<&Comparison> {
        self.cells.get(a * self.k + b).and_then(Option::as_ref)
    }

    /// The table symbol of "a vs b": `+`, `=`, `-`, or `·` on the diagonal.
    pub fn symbol(&self, a: usize, b: usize) -> char {
        self.get(a, b).map_or('·', |c| c.verdict.symbol())
    }

    /// Number of `+` in row a (how many groups a beats).
    pub fn wins(&self, a: usize) -> usize {
        (0..self.k).filter(|&b| self.symbol(a, b) == '+').count()
    }
}

/// Faigl-style matrix of every group against every other at level `alpha`.
pub fn pairwise_matrix(
    groups: &[&[f64]],
    alpha: f64,
    pairing: Pairing,
) -> Result<PairwiseMatrix, StatsError> {
    let k = groups.len();
    let mut cells = vec![None; k * k];
    for a in 0..k {
        for b in a + 1..k {
            let c = compare(groups[a], groups[b], alpha, pairing)?;
            cells[a * k + b] = Some(c);
            cells[b * k + a] = Some(c.flip());
        }
    }
    Ok(PairwiseMatrix { k, cells })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worked_example() {
        let low: Vec<f64> = (0..30).map(|i| i as f64).collect();
        let high: Vec<f64> = (0..30).map(|i| 100.0 + i as f64).collect();
        let mid: Vec<f64> = (0..30).map(|i| 0.5 + i as f64).collect();
        let m = pairwise_matrix(&[&low, &high, &mid], 0.001, Pairing::Unpaired).unwrap();
        assert_eq!(m.symbol(0, 1), '+');
        assert_eq!(m.symbol(1, 0), '-');
        assert_eq!(m.symbol(0, 2), '=');
        assert_eq!(m.symbol(1, 1), '·');
        assert_eq!((m.wins(0), m.wins(1), m.wins(2)), (1, 0, 1));
        let p = compare(&low, &mid, 0.001, Pairing::Paired).unwrap();
        // Every difference is −0.5: R⁻ = 465, p far below 0.001 (N = 30 with ties → asymptotic).
        assert_eq!(
            (p.verdict, p.method),
            (Verdict::Better, MethodUsed::Asymptotic)
        );
    }

    /// Regression: with 10 pairs every verdict at α = 0.001 was `=` and nothing said that no
    /// other verdict was possible: the smallest exact Wilcoxon p is 2/2¹⁰ = 1.95·10⁻³.
    #[test]
    fn regression_min_p_of_few_pairs() {
        let a: Vec<f64> = (0..10).map(f64::from).collect();
        let b: Vec<f64> = (0..10)
            .map(|i| f64::from(i) + 1.0 + f64::from(i) / 8.0)
            .collect();
        let c = compare(&a, &b, 0.001, Pairing::Paired).unwrap();
        assert_eq!(c.verdict, Verdict::Same);
        assert!((c.min_p_value - 2.0 / 1024.0).abs() < 1e-15, "{c:?}");
        assert!(c.underpowered(0.001) && !c.underpowered(0.01));
        // Unpaired 6 + 6, untied: 2/C(12, 6) = 2/924.
        let u = compare(&a[..6], &b[4..], 0.001, Pairing::Unpaired).unwrap();
        assert!((u.min_p_value - 2.0 / 924.0).abs() < 1e-15, "{u:?}");
        // Ties and zero differences keep their method: 12 pairs, 4 equal → 8 nonzero, tied
        // ranks → complete enumeration, smallest p 2/2⁸.
        let x = [
            1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0,
        ];
        let y = [
            2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 9.0, 10.0, 11.0, 12.0,
        ];
        assert!((smallest_p(&x, &y, Pairing::Paired).unwrap() - 2.0 / 256.0).abs() < 1e-15);
        // Regression: with ties at the split, only "a holds the smallest" was tried, so
        // the same two samples had a smallest p of 6.30e-3 one way round and 8.3e-4 the
        // other, and a report marked one direction of a comparison "could not be + or -".
        let cf = [100.0, 104.0, 105.0, 106.0, 106.0, 106.0];
        let rr = [
            102.0, 106.0, 107.0, 108.0, 110.0, 112.0, 113.0, 120.0, 124.0, 125.0, 129.0, 129.0,
        ];
        let one = smallest_p(&cf, &rr, Pairing::Unpaired).unwrap();
        assert_eq!(one, smallest_p(&rr, &cf, Pairing::Unpaired).unwrap());
        assert!(one < 1e-3, "{one}");
        assert_eq!(needed(0.001, Pairing::Paired), Some(11));
        assert_eq!(needed(0.001, Pairing::Unpaired), Some(7));
        assert_eq!(needed(0.05, Pairing::Paired), Some(6));
        // Enough pairs: 11 untied → 2/2048 < 0.001.
        let a11: Vec<f64> = (0..11).map(f64::from).collect();
        let b11: Vec<f64> = (0..11)
            .map(|i| f64::from(i) + 1.0 + f64::from(i) / 8.0)
            .collect();
        let c = compare(&a11, &b11, 0.001, Pairing::Paired).unwrap();
        assert!(
            !c.underpowered(0.001) && c.verdict == Verdict::Better,
            "{c:?}"
        );
    }

    proptest::proptest! {
        /// The unpaired smallest p is the least p over every split of the pooled values
        /// into samples of the two sizes (all of them tried, ties and all).
        #[test]
        fn unpaired_smallest_p_is_the_least_over_every_arrangement(
            a in proptest::collection::vec(0u8..5, 1..6),
            b in proptest::collection::vec(0u8..5, 1..6),
        ) {
            let a: Vec<f64> = a.into_iter().map(f64::from).collect();
            let b: Vec<f64> = b.into_iter().map(f64::from).collect();
            let pooled: Vec<f64> = a.iter().chain(&b).copied().collect();
            let n = pooled.len();
            let mut least = f64::INFINITY;
            for mask in 0u32..(1 << n) {
                if mask.count_ones() as usize != a.len() {
                    continue;
                }
                let side = |inside: bool| -> Vec<f64> {
                    (0..n).filter(|i| (mask >> i & 1 == 1) == inside).map(|i| pooled[i]).collect()
                };
                let (x, y) = (side(true), side(false));
                if let Ok(r) = mann_whitney_u(&x, &y) {
                    least = least.min(r.p_value);
                }
            }
            match smallest_p(&a, &b, Pairing::Unpaired) {
                Ok(p) => proptest::prop_assert!((p - least).abs() <= 1e-12 * least.max(1e-300),
                    "{p} against {least}"),
                // Every value equal: no arrangement can be tested either.
                Err(_) => proptest::prop_assert!(least.is_infinite()),
            }
        }
    }
}
