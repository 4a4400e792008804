//! Solanas & Garcia's assignment (Faigl & Kulich Eq. 1).
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
    todo!("Solanas & Garcia's assignment (Faigl & Kulich Eq. 1).")
}
