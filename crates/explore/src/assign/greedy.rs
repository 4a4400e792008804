//! Greedy assignment (seed 002 Alg. 2; Faigl & Kulich's IA).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Give goals to the deciding robots.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let _ = (ctx, candidates, out);
    todo!("Greedy assignment (seed 002 Alg. 2; Faigl & Kulich's IA).")
}
