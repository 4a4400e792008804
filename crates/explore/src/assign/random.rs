//! Random frontier (Holz et al. 2010 §3.2): a reachable candidate drawn uniformly.

use rand::RngExt;

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Each deciding robot takes a candidate drawn uniformly from those it can reach.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    for (r, slot) in out.iter_mut().enumerate().take(ctx.robots.len()) {
        if !ctx.deciding[r] {
            continue;
        }
        *slot = None;
        let reach = ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
        let reachable = candidates
            .cells()
            .iter()
            .filter(|&&c| reach.cost(c as usize).is_some())
            .count();
        if reachable == 0 {
            continue;
        }
        let k = ctx.rng.random_range(0..reachable);
        let reach = ctx.planner.map(r);
        let cell = candidates
            .cells()
            .iter()
            .copied()
            .filter(|&c| reach.cost(c as usize).is_some())
            .nth(k)
            .expect("k < number of reachable candidates");
        let cost = reach.cost(cell as usize).unwrap_or(f64::INFINITY);
        *slot = Some(Goal { cell, cost });
    }
}
