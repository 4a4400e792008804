//! MinPos (Bautin, Simonin & Charpillet 2012; the coordination study's Alg. 4).
//!
//! For robot i and goal j the rank P_ij is the number of robots strictly closer to goal j
//! than robot i, by path. Each deciding robot takes the goal of minimal rank, ties broken by
//! its own cost to it (then by candidate order). Bautin et al. propagate one wavefront per
//! frontier; paths on the grid are symmetric, so the robots' own searches give the same
//! distances, grown only as far as the ranks of the goals looked at need (every robot,
//! deciding or not, counts in the ranks); no search per frontier.
//!
//! Precisions and deviations:
//! - "strictly closer" means shorter by more than [`TIE_CELLS`]: two paths of equal length
//!   summed in different orders differ in the last bits, and that noise must not decide;
//! - a robot that cannot reach a goal is not closer to it than anyone;
//! - goals that robots not deciding this time keep are skipped, unless every goal the
//!   robot can reach is such a goal (then it ranks them like the others);
//! - robots decide independently, so two deciding robots may pick the same goal, as in the
//!   paper.

use crate::assign::costs::LazyCosts;
use crate::assign::greedy::Scratch;
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Path-length difference (cells) below which two robots count as equally far from a goal.
pub const TIE_CELLS: f64 = 1e-6;

/// Rank of row `i` for column `j` in a row-major `rows × cols` cost matrix: the number of
/// other rows whose finite cost is smaller by more than [`TIE_CELLS`].
pub fn rank(cost: &[f64], rows: usize, cols: usize, i: usize, j: usize) -> usize {
    let c = cost[i * cols + j];
    (0..rows)
        .filter(|&k| k != i && cost[k * cols + j] < c - TIE_CELLS)
        .count()
}

/// MinPos on a row-major `rows × cols` cost matrix (`INFINITY` = unreachable) over all
/// robots: for every row with `deciding[i]`, `out[i]` becomes the column of minimal
/// (rank, cost, index), preferring columns without `taken[j]`; other rows get `None`.
pub fn solve(
    rows: usize,
    cols: usize,
    cost: &[f64],
    deciding: &[bool],
    taken: &[bool],
    out: &mut Vec<Option<usize>>,
) {
    out.clear();
    out.resize(rows, None);
    for (i, slot) in out.iter_mut().enumerate() {
        if !deciding[i] {
            continue;
        }
        let mut best = best_goal(cost, rows, cols, i, |j| !taken[j]);
        if best.is_none() {
            best = best_goal(cost, rows, cols, i, |_| true);
        }
        *slot = best;
    }
}

/// The column `j` with `allowed(j)` and finite cost for row `i` of minimal (rank, cost, j).
fn best_goal(
    cost: &[f64],
    rows: usize,
    cols: usize,
    i: usize,
    allowed: impl Fn(usize) -> bool,
) -> Option<usize> {
    let row = &cost[i * cols..(i + 1) * cols];
    let mut best: Option<(usize, f64, usize)> = None;
    for (j, &c) in row.iter().enumerate() {
        if !c.is_finite() || !allowed(j) {
            continue;
        }
        // A column can only beat the best with a rank no larger: stop counting beyond it.
        let limit = best.map_or(usize::MAX, |(p, _, _)| p);
        let mut p = 0;
        for k in 0..rows {
            if k != i && cost[k * cols + j] < c - TIE_CELLS {
                p += 1;
                if p > limit {
                    break;
                }
            }
        }
        if best.is_none_or(|(bp, bc, _)| p < bp || (p == bp && c < bc)) {
            best = Some((p, c, j));
        }
    }
    best.map(|(_, _, j)| j)
}

/// Give goals to the deciding robots: each the goal where it ranks best.
///
/// The deciding robot's search grows bucket by bucket; a goal it settles at cost c is
/// ranked by growing each other robot's search until it settles the goal or passes
/// c − [`TIE_CELLS`], nearest robots first as the crow flies, so that a rank that cannot
/// beat the best is known after fewer searches. Once a goal of rank 0 is
/// found, the bucket of its cost is finished and the search stops: every goal not settled
/// costs more. Without one, the search stops once every goal it can reach and has not settled
/// (costing at least the next bucket B) has, by the other searches grown to B, at least as
/// many robots strictly closer as the best rank so far (tried as B doubles); a goal's rank
/// is counted only as far as it can still beat the best. The result is that of [`solve`]
/// on the full matrix.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let mut s = std::mem::take(&mut ctx.memory.greedy_utility.scratch);
    s.start(ctx, candidates, true);
    let m = ctx.robots.len();
    for r in 0..m {
        if !ctx.deciding[r] {
            continue;
        }
        let taken = std::mem::take(&mut s.matrix.taken);
        let mut best = best_lazy(ctx, candidates, &mut s, r, |j| !taken[j]);
        if best.is_none() {
            best = best_lazy(ctx, candidates, &mut s, r, |_| true);
        }
        s.matrix.taken = taken;
        if let Some(slot) = out.get_mut(r) {
            *slot = best.map(|(_, cost, j)| Goal {
                cell: s.matrix.cols[j],
                cost,
            });
        }
    }
    ctx.memory.greedy_utility.scratch = s;
}

/// Robot `r`'s goal of minimal (rank, cost, column) among columns with `allowed(j)`,
/// growing the searches only as far as needed (`s`: the searches and the proof's buffers,
/// its matrix's taken goals lent to `allowed`).
fn best_lazy(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    s: &mut Scratch,
    r: usize,
    allowed: impl Fn(usize) -> bool,
) -> Option<(usize, f64, usize)> {
    let mut best: Option<(usize, f64, usize)> = None;
    let mut seen = 0;
    // The next bound at which to try the rank bound of the goals not settled yet.
    let mut check = 1;
    loop {
        let (lazy, nearest) = (&mut s.lazy, &mut s.nearest);
        let done = lazy.step(ctx, candidates, r, false);
        let upto = lazy.found(r).len();
        for n in seen..upto {
            let p = lazy.found(r)[n];
            if !allowed(p.col) {
                continue;
            }
            let threshold = p.cost - TIE_CELLS;
            let cell = candidates.cells()[p.col] as usize;
            // Ranks are counted only as far as they can matter: a goal after the best by
            // (cost, column) beats it only with a smaller rank (none, if the best has rank
            // 0), one before it with a rank no larger.
            let limit = match best {
                None => usize::MAX,
                Some((q, c, j)) if (p.cost, p.col) < (c, j) => q,
                Some((0, ..)) => continue,
                Some((q, ..)) => q - 1,
            };
            let mut rank = 0;
            if threshold > 0.0 {
                by_octile(ctx, r, cell, threshold, nearest);
                for &(_, k) in nearest.iter() {
                    if closer(ctx, candidates, lazy, k, cell, threshold) {
                        rank += 1;
                        if rank > limit {
                            break;
                        }
                    }
                }
            }
            if best.is_none_or(|(q, c, j)| (rank, p.cost, p.col) < (q, c, j)) {
                best = Some((rank, p.cost, p.col));
            }
        }
        seen = upto;
        if done {
            return best;
        }
        // Every goal not settled yet costs at least the next bucket.
        let bound = lazy.next_bucket(ctx, r);
        match best {
            Some((0, c, _)) if bound as f64 > c => return best,
            Some((p, c, _)) if bound as f64 > c && bound >= check => {
                if ranks_at_least(ctx, candidates, s, r, bound, p, &allowed) {
                    return best;
                }
                check = 2 * bound;
            }
            _ => {}
        }
    }
}

/// Write to `open` the allowed goals robot `r` reaches (its component of passable cells)
/// and its search has not settled: those a bound on the goals not settled must speak for
/// (a goal it cannot reach is never its goal, whatever its rank; frontier cells beside
/// walls within the clearance, which no robot reaches, would otherwise hold the answer at
/// no until robot `r`'s search is complete).
fn open_goals(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    r: usize,
    allowed: &impl Fn(usize) -> bool,
    open: &mut Vec<usize>,
) {
    let goals = candidates.cells();
    open.clear();
    open.extend(
        (0..goals.len())
            .filter(|&j| allowed(j) && !ctx.planner.map(r).is_settled(goals[j] as usize)),
    );
    let reach = ctx
        .planner
        .component(r, ctx.robots[r], ctx.known, ctx.upkeep);
    open.retain(|&j| reach.contains(goals[j] as usize));
}

/// Write to `out` the robots other than `r` that are nearer to `cell` than `threshold` as
/// the crow flies, nearest first (ties by index): the octile distance bounds every path
/// from below, so no other robot is strictly closer, and the nearest are the likeliest to
/// be.
fn by_octile(
    ctx: &DecisionCtx<'_>,
    r: usize,
    cell: usize,
    threshold: f64,
    out: &mut Vec<(f64, usize)>,
) {
    out.clear();
    out.extend(
        (0..ctx.robots.len())
            .filter(|&k| k != r)
            .map(|k| (octile(ctx, k, cell), k))
            .filter(|&(d, _)| d < threshold),
    );
    out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
}

/// Whether robot `k`'s path cost to candidate `cell` is below `threshold`, its search
/// grown only until that is known: until it settles the candidate, or every cost below
/// the threshold (the same answer as growing it through the threshold's bucket).
fn closer(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    lazy: &mut LazyCosts,
    k: usize,
    cell: usize,
    threshold: f64,
) -> bool {
    let through = threshold as usize;
    loop {
        let map = ctx.planner.map(k);
        if map.is_settled(cell) {
            return map.cost(cell).is_some_and(|d| d < threshold);
        }
        let next = lazy.next_bucket(ctx, k);
        if next > through {
            return false; // every cost below the threshold is settled, the candidate's not
        }
        if lazy.grow(ctx, candidates, k, next) {
            // complete, or every candidate robot k reaches is settled
            return ctx.planner.map(k).cost(cell).is_some_and(|d| d < threshold);
        }
    }
}

/// Octile distance from robot `k` to cell `c`, a lower bound of its path cost.
fn octile(ctx: &DecisionCtx<'_>, k: usize, c: usize) -> f64 {
    let w = ctx.known.width();
    let at = |i: usize| grid::Cell::new((i % w) as i32, (i / w) as i32);
    at(ctx.robots[k] as usize).octile(at(c))
}

/// Whether every allowed goal robot `r` reaches and has not settled ranks at least `p` for
/// it ([`open_goals`]), when its search has settled every goal of cost below `bound`: such
/// a goal costs robot `r` at least `bound`, so every other robot closer to it than
/// `bound` − [`TIE_CELLS`] is strictly closer than robot `r` (the other searches grow until
/// they tell, at most that far).
fn ranks_at_least(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    s: &mut Scratch,
    r: usize,
    bound: usize,
    p: usize,
    allowed: &impl Fn(usize) -> bool,
) -> bool {
    let m = ctx.robots.len();
    let threshold = bound as f64 - TIE_CELLS;
    let (lazy, open) = (&mut s.lazy, &mut s.order);
    open_goals(ctx, candidates, r, allowed, open);
    // Only robots nearer than the threshold as the crow flies to a goal in question can be
    // strictly closer to it: if some goal has fewer than p of them, the answer is no, and
    // the other robots' searches need not grow.
    for &j in open.iter() {
        let cell = candidates.cells()[j] as usize;
        let count = (0..m)
            .filter(|&k| k != r && octile(ctx, k, cell) < threshold)
            .count();
        if count < p {
            return false;
        }
    }
    // Each search grows only as far as the goals it is asked about need, nearest robots
    // first, and the first goal with fewer than p robots strictly closer answers no.
    let nearest = &mut s.nearest;
    for &j in open.iter() {
        let cell = candidates.cells()[j] as usize;
        by_octile(ctx, r, cell, threshold, nearest);
        let mut closer_robots = 0;
        for &(_, k) in nearest.iter() {
            if closer_robots >= p {
                break;
            }
            closer_robots += usize::from(closer(ctx, candidates, lazy, k, cell, threshold));
        }
        if closer_robots < p {
            return false;
        }
    }
    true
}
