//! Decision-theoretic samples near frontiers (González-Baños & Latombe; Holz et al. §3.2).
//!
//! (Being written.)

use super::CandidateSet;
use crate::decision::DecisionCtx;

/// State kept across decisions.
#[derive(Default)]
pub struct State {}

/// Fill `out` with the candidates.
pub fn generate(ctx: &mut DecisionCtx<'_>, n: usize, out: &mut CandidateSet) {
    let _ = (ctx, n, out);
    todo!("Decision-theoretic samples near frontiers (González-Baños & Latombe; Holz et al. §3.2).")
}
