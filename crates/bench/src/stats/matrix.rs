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
//! The matrix computes each unordered pair once and mirrors it, so `m[a][b]` is always the
//! opposite of `m[b][a]`.

use super::{MethodUsed, StatsError, mann_whitney_u, wilcoxon_signed_rank};

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
}

impl Comparison {
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
}
