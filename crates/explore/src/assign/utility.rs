//! Decision-theoretic utility I(p)·exp(−λL(p)) (González-Baños & Latombe).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Give goals to the deciding robots.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    lambda: f64,
    out: &mut [Option<Goal>],
) {
    let _ = (ctx, candidates, lambda, out);
    todo!("Decision-theoretic utility I(p)·exp(−λL(p)) (González-Baños & Latombe).")
}
