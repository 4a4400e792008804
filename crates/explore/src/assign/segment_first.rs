//! Same segment first (Holz et al. 2010 §2.4, Seg).
//!
//! The belief is segmented into rooms ([`crate::segment`]); a deciding robot takes the
//! candidate nearest to it by path among those in its own segment (the segment of the cell
//! it stands on), and only when there is none the nearest candidate overall — exactly the
//! closest-frontier rule otherwise. The segmentation is kept in `ctx.memory.segments` and
//! recomputed only when the map changed enough, on blocks about 0.1 m wide on maps of 5 cm
//! or finer ([`crate::segment::cache`]).
//!
//! Deviation (rooms, not corridors): Holz et al. introduce Seg against one failure — the
//! closest frontier lies outside "the room that is currently explored", so the robot leaves a
//! room unfinished and has to come back (their §1, problem 2, and Figure 2). Read literally,
//! the rule also applies in a corridor, which is a segment too: a robot in a corridor then
//! follows the corridor to its end before it looks into any room it passed, and comes back
//! for each. With a 180° lidar of 4 m that gains nothing over `cf-rr` on the generated
//! hospitals and makes paths 10–22 % longer in offices and caves. So the preference holds
//! only in a segment that is room-like: one that touches at most `max_neighbours` other
//! segments (a room has one or two doors, a corridor or hall many). With the same lidar
//! this shortens hospital runs by 22 % against `cf-rr` (Holz et al. found 12.5 % in their
//! hospital, Table 3), and leaves caves as they were (their Table 1). `max_neighbours =
//! None` is the literal rule (`cf-rr-seg-any`); docs/reference.md has the numbers.

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};
use crate::segment::Rule;

/// Seg's room preference applies in segments with at most this many neighbouring segments.
pub const ROOM_MAX_NEIGHBOURS: u32 = 2;

/// Give goals to the deciding robots: nearest in the robot's own segment when that segment
/// touches at most `max_neighbours` others (any segment when `None`), else nearest overall.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    rule: Rule,
    max_neighbours: Option<u32>,
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
    state.update_logged(
        ctx.known,
        rule,
        crate::segment::cache::block_for(ctx.resolution),
        ctx.upkeep.row_log(),
    );
    let seg = state.segmentation();
    for (r, slot) in out.iter_mut().enumerate().take(n) {
        if !ctx.deciding[r] {
            continue;
        }
        let from = ctx.robots[r];
        let mut found = None;
        let own = seg
            .label(from as usize)
            .filter(|&s| max_neighbours.is_none_or(|m| state.neighbours(s) <= m));
        // The search is guided toward the own segment's candidates; without one it would
        // settle every cell the robot reaches and find nothing.
        if let Some(own) = own {
            let mine: Vec<u32> = candidates
                .cells()
                .iter()
                .copied()
                .filter(|&c| seg.labels[c as usize] == own)
                .collect();
            if !mine.is_empty() {
                found = ctx
                    .planner
                    .nearest(r, from, ctx.known, ctx.upkeep, &mine, |i| {
                        candidates.contains(i) && seg.labels[i] == own
                    });
            }
        }
        if found.is_none() {
            let cells = candidates.cells();
            found = ctx
                .planner
                .nearest(r, from, ctx.known, ctx.upkeep, cells, |i| {
                    candidates.contains(i)
                });
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
