//! Representatives of free edges (Faigl & Kulich 2013, RFE).
//!
//! (Being written.)

use super::CandidateSet;
use crate::decision::DecisionCtx;

/// State kept across decisions.
#[derive(Default)]
pub struct State {}

/// n_f used by the presets: free edges of fewer cells are ignored.
pub const DEFAULT_MIN_EDGE: usize = 3;

/// Fill `out` with the candidates.
pub fn generate(ctx: &mut DecisionCtx<'_>, min_edge: usize, out: &mut CandidateSet) {
    let _ = (ctx, min_edge, out);
    todo!("Representatives of free edges (Faigl & Kulich 2013, RFE).")
}
