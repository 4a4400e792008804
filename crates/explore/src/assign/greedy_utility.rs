//! Greedy with utility (seed 002 Alg. 3; Burgard et al., Simmons et al.).
//!
//! (Being written.)

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// State kept across decisions.
#[derive(Default)]
pub struct State {}

/// β used by the `greedy-utility` presets (utility per cell of path).
pub const DEFAULT_BETA: f64 = 0.1;

/// Give goals to the deciding robots.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    beta: f64,
    out: &mut [Option<Goal>],
) {
    let _ = (ctx, candidates, beta, out);
    todo!("Greedy with utility (seed 002 Alg. 3; Burgard et al., Simmons et al.).")
}
