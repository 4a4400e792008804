//! Multiple-TSP assignment: cluster first, route second (Faigl & Kulich's MA).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// State kept across decisions.
#[derive(Default)]
pub struct State {}

/// Give goals to the deciding robots.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let _ = (ctx, candidates, out);
    todo!("Multiple-TSP assignment: cluster first, route second (Faigl & Kulich's MA).")
}
