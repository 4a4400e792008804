//! Statistics for comparing strategies: per-group summaries, rank tests, a normality test and
//! Faigl-style `+`/`=`/`-` matrices.
//!
//! Everything here is written from the published algorithms and checked against SciPy 1.17
//! (`crates/bench/tests/fixtures/stats.json`, made by `make_stats_fixtures.py` next to it):
//!
//! - [`summarize`]: n, mean ± sample sd, median, quartiles (NumPy's default `linear` quantile),
//!   IQR, min, max.
//! - [`mann_whitney_u`]: unpaired two-sided Mann–Whitney U (`scipy.stats.mannwhitneyu`).
//! - [`wilcoxon_signed_rank`]: paired two-sided Wilcoxon signed-rank, zeros dropped
//!   (`scipy.stats.wilcoxon`, `zero_method='wilcox'`).
//! - [`shapiro_wilk`]: Shapiro–Wilk W and p (Royston 1995, AS R94, as `scipy.stats.shapiro`).
//! - [`compare`] / [`pairwise_matrix`]: Faigl & Kulich 2013 Table I style verdicts.
//!
//! The normal distribution function is our own port of Cephes `ndtr` (the code SciPy uses), so
//! no crate with untrusted p-values is involved.

mod mann_whitney;
mod matrix;
mod normal;
mod rank;
mod shapiro_wilk;
mod summary;
mod wilcoxon;

pub use mann_whitney::{MannWhitney, mann_whitney_u, mann_whitney_u_with};
pub use matrix::{
    Comparison, Pairing, PairwiseMatrix, Verdict, compare, needed, pairwise_matrix, smallest_p,
};
pub use normal::ndtr;
pub use shapiro_wilk::{ShapiroWilk, shapiro_wilk};
pub use summary::{Summary, quantile_linear, summarize};
pub use wilcoxon::{
    Wilcoxon, wilcoxon_signed_rank, wilcoxon_signed_rank_diffs, wilcoxon_signed_rank_with,
};

/// The significance level Faigl & Kulich 2013 use for their Table I (P < 0.001).
pub const DEFAULT_ALPHA: f64 = 0.001;

/// How a test should compute its p-value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// SciPy's `method='auto'` choice (each test documents its thresholds).
    #[default]
    Auto,
    /// The exact null distribution (which, as in SciPy, ignores ties).
    Exact,
    /// The normal approximation with tie and continuity corrections.
    Asymptotic,
}

/// How a p-value was actually computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodUsed {
    /// Exact null distribution of the statistic.
    Exact,
    /// Normal approximation (tie- and continuity-corrected).
    Asymptotic,
    /// Complete enumeration of the sign-flip permutation distribution (exact given the ties).
    Permutation,
    /// Royston's (1995) approximation (Shapiro–Wilk).
    Royston,
    /// Nothing to test (e.g. zero range, all differences zero): p = 1.
    Degenerate,
}

/// Why a statistic could not be computed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StatsError {
    /// A sample was empty.
    #[error("empty sample")]
    Empty,
    /// A sample contained NaN or an infinity.
    #[error("sample contains a non-finite value")]
    NonFinite,
    /// Paired samples of different lengths.
    #[error("paired samples differ in length ({0} vs {1})")]
    LengthMismatch(usize, usize),
    /// Fewer observations than the test needs.
    #[error("need at least {need} observations, got {got}")]
    TooFew {
        /// Minimum number of observations.
        need: usize,
        /// Number given.
        got: usize,
    },
}

/// Checks that a sample is non-empty and finite.
fn check(x: &[f64]) -> Result<(), StatsError> {
    if x.is_empty() {
        return Err(StatsError::Empty);
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(StatsError::NonFinite);
    }
    Ok(())
}
