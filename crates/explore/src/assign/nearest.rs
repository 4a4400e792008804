//! Nearest candidate by path (Yamauchi 1997 §2.3; Holz et al. 2010 Eq. 3).
//!
//! A Dijkstra search from the robot stops at the first candidate it settles, so the cost is
//! proportional to the area closer than the nearest frontier, not to the map.

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Each deciding robot independently takes its nearest reachable candidate.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    for (r, slot) in out.iter_mut().enumerate().take(ctx.robots.len()) {
        if !ctx.deciding[r] {
            continue;
        }
        *slot = None;
        if candidates.is_empty() {
            continue;
        }
        let found = ctx
            .planner
            .nearest(r, ctx.robots[r], ctx.known, ctx.upkeep, |i| {
                candidates.contains(i)
            });
        if let Some(cell) = found {
            let cost = ctx
                .planner
                .map(r)
                .cost(cell as usize)
                .unwrap_or(f64::INFINITY);
            *slot = Some(Goal { cell, cost });
        }
    }
}
