//! MinPos (Bautin, Simonin & Charpillet 2012; seed 002 Alg. 4).
//!
//! For robot i and goal j the rank P_ij is the number of robots strictly closer to goal j
//! than robot i, by path. Each deciding robot takes the goal of minimal rank, ties broken by
//! its own cost to it (then by candidate order). Bautin et al. propagate one wavefront per
//! frontier; paths on the grid are symmetric, so the robots' own reachability maps give the
//! same distances: one full map per robot (every robot, deciding or not, counts in the
//! ranks), O(m² n) work for m robots and n candidates, no search per frontier.
//!
//! Precisions and deviations:
//! - "strictly closer" means shorter by more than [`TIE_CELLS`]: two paths of equal length
//!   summed in different orders differ in the last bits, and that noise must not decide;
//! - a robot that cannot reach a goal is not closer to it than anyone;
//! - goals that robots not deciding this time keep are skipped, unless every goal the
//!   robot can reach is such a goal (then it ranks them like the others);
//! - robots decide independently, so two deciding robots may pick the same goal, as in the
//!   paper.

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
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let mut s = std::mem::take(&mut ctx.memory.greedy_utility.scratch);
    s.matrix.fill(ctx, candidates, true);
    let m = &s.matrix;
    s.free.clear();
    s.free.extend(m.rows.iter().map(|&r| ctx.deciding[r]));
    solve(
        m.rows.len(),
        m.n_cols(),
        &m.cost,
        &s.free,
        &m.taken,
        &mut s.assigned,
    );
    for (i, &r) in m.rows.iter().enumerate() {
        if !ctx.deciding[r] {
            continue;
        }
        if let Some(slot) = out.get_mut(r) {
            *slot = s.assigned[i].and_then(|j| {
                let cost = m.at(i, j);
                cost.is_finite().then(|| Goal {
                    cell: m.cols[j],
                    cost,
                })
            });
        }
    }
    ctx.memory.greedy_utility.scratch = s;
}
