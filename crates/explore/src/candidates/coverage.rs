//! Coverage candidates (Faigl & Kulich 2013, Algorithm 1, CC).
//!
//! (Being written.)

use super::CandidateSet;
use crate::decision::DecisionCtx;

/// State kept across decisions.
#[derive(Default)]
pub struct State {}

/// Fill `out` with the candidates.
pub fn generate(ctx: &mut DecisionCtx<'_>, out: &mut CandidateSet) {
    let _ = (ctx, out);
    todo!("Coverage candidates (Faigl & Kulich 2013, Algorithm 1, CC).")
}
