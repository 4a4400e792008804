//! All frontier cells as candidates (Holz's closest frontier; Faigl & Kulich's AF).

use super::CandidateSet;
use crate::decision::DecisionCtx;

/// Every frontier cell that is not on the visited/inaccessible lists.
pub fn generate(ctx: &mut DecisionCtx<'_>, out: &mut CandidateSet) {
    for &c in ctx.upkeep.frontiers.cells() {
        if !ctx.lists.is_excluded(c) {
            out.insert(c);
        }
    }
}
