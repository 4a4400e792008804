//! Nearest candidate by path (Yamauchi 1997 §2.3; Holz et al. 2010 Eq. 3).
//!
//! A search from the robot stops at the first candidate it settles. It is guided toward the
//! candidates (A* with the octile distance to the nearest of them as its bound,
//! [`Reachability::nearest_guided`](crate::Reachability::nearest_guided)), so its cost
//! follows the way to the nearest candidate, not the disk of cells closer than it: with
//! sparse candidates (RFE's representatives, region centroids) that disk is most of a map.

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
        let found = ctx.planner.nearest(
            r,
            ctx.robots[r],
            ctx.known,
            ctx.upkeep,
            candidates.cells(),
            |i| candidates.contains(i),
        );
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
