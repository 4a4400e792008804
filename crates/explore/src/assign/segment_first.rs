//! Same segment first (Holz et al. 2010 §2.4, Seg).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Give goals to the deciding robots.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    rule: crate::segment::Rule,
    out: &mut [Option<Goal>],
) {
    let _ = (ctx, candidates, rule, out);
    todo!("Same segment first (Holz et al. 2010 §2.4, Seg).")
}
