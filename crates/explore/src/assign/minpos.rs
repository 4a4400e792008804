//! MinPos (Bautin et al.; seed 002).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Give goals to the deciding robots.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let _ = (ctx, candidates, out);
    todo!("MinPos (Bautin et al.; seed 002).")
}
