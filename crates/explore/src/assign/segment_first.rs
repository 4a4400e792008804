//! Same segment first (Holz et al. 2010 §2.4, Seg).
//!
//! The belief is segmented into rooms ([`crate::segment`]); a deciding robot takes the
//! candidate nearest to it by path among those in its own segment (the segment of the cell
//! it stands on), and only when there is none the nearest candidate overall — exactly the
//! closest-frontier rule otherwise. The segmentation is kept in `ctx.memory.segments` and
//! recomputed only when the map changed enough ([`crate::segment::cache`]).

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};
use crate::segment::Rule;

/// Give goals to the deciding robots.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    rule: Rule,
    out: &mut [Option<Goal>],
) {
    let n = ctx.robots.len().min(out.len());
    for slot in out.iter_mut().take(n).zip(ctx.deciding).filter(|p| *p.1) {
        *slot.0 = None;
    }
    if candidates.is_empty() || !ctx.deciding.iter().take(n).any(|&d| d) {
        return;
    }
    let mut state = std::mem::take(&mut ctx.memory.segments);
    let seg = state.update(ctx.known, rule);
    for (r, slot) in out.iter_mut().enumerate().take(n) {
        if !ctx.deciding[r] {
            continue;
        }
        let from = ctx.robots[r];
        let mut found = None;
        if let Some(own) = seg.label(from as usize) {
            found = ctx.planner.nearest(r, from, ctx.known, ctx.upkeep, |i| {
                candidates.contains(i) && seg.labels[i] == own
            });
        }
        if found.is_none() {
            found = ctx
                .planner
                .nearest(r, from, ctx.known, ctx.upkeep, |i| candidates.contains(i));
        }
        if let Some(cell) = found {
            let cost = ctx
                .planner
                .map(r)
                .cost(cell as usize)
                .unwrap_or(f64::INFINITY);
            *slot = Some(Goal { cell, cost });
        }
    }
    ctx.memory.segments = state;
}
