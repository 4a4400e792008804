//! Random-order greedy assignment (Faigl & Kulich 2013, §III-B, GA).
//!
//! The deciding robots are put in a random order (a Fisher–Yates shuffle drawn from the
//! run's seeded stream, so no robot is preferred), and each in turn takes its cheapest goal
//! not yet assigned. Costs are path lengths in cells.
//!
//! Precisions and deviations:
//! - goals of robots that keep their goal this time count as assigned;
//! - Faigl & Kulich do not say what a robot does when every goal is taken; as in greedy
//!   (the coordination study's Alg. 2) the goal set is then refilled, so that robot takes its cheapest goal
//!   overall (later robots again prefer goals nobody took since the refill);
//! - ties between goals of equal cost go to the earlier candidate;
//! - each robot's search, guided toward the goals free at its turn, grows only until it
//!   settles one (see [`crate::assign::costs`]); a single deciding robot takes its nearest
//!   free goal by an early-stopping search ([`greedy::assign_single`]).

use rand::RngExt;

use crate::assign::costs::Pair;
use crate::assign::greedy;
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// GA on a row-major `rows × cols` cost matrix (`INFINITY` = unreachable): the rows in
/// `order` each take their cheapest free column. Columns with `taken[j]` start unavailable;
/// `out[i]` becomes the column of row `i`; `free` is a scratch buffer.
pub fn solve(
    cols: usize,
    cost: &[f64],
    taken: &[bool],
    order: &[usize],
    free: &mut Vec<bool>,
    out: &mut Vec<Option<usize>>,
) {
    let rows = cost.len().checked_div(cols).unwrap_or(0);
    free.clear();
    free.extend(taken.iter().take(cols).map(|&t| !t));
    free.resize(cols, true);
    out.clear();
    out.resize(
        rows.max(order.iter().map(|&i| i + 1).max().unwrap_or(0)),
        None,
    );
    if cols == 0 {
        return;
    }
    for &i in order {
        let row = &cost[i * cols..(i + 1) * cols];
        let mut pick = cheapest_free(row, free);
        if pick.is_none() && free.iter().any(|&f| !f) {
            free.fill(true);
            pick = cheapest_free(row, free);
        }
        if let Some(j) = pick {
            out[i] = Some(j);
            free[j] = false;
        }
    }
}

/// The free column of least finite cost in `row` (earliest on ties).
fn cheapest_free(row: &[f64], free: &[bool]) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for (j, &c) in row.iter().enumerate() {
        if free[j] && c.is_finite() && best.is_none_or(|(b, _)| c < b) {
            best = Some((c, j));
        }
    }
    best.map(|(_, j)| j)
}

/// Give goals to the deciding robots: in random order, each its cheapest free goal.
///
/// Each robot's search grows one bucket at a time until it settles a free goal: the
/// cheapest free one found in that bucket is its cheapest free goal, as in [`solve`].
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    if greedy::assign_single(ctx, candidates, out) {
        return;
    }
    let mut s = std::mem::take(&mut ctx.memory.greedy_utility.scratch);
    s.start(ctx, candidates, false);
    let k = s.matrix.rows.len();
    s.order.clear();
    s.order.extend(0..k);
    for i in (1..k).rev() {
        let j = ctx.rng.random_range(0..=i);
        s.order.swap(i, j);
    }
    let cheapest = |pairs: &[Pair], free: &[bool]| {
        pairs
            .iter()
            .filter(|p| free[p.col])
            .map(|p| (p.cost, p.col))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(_, j)| j)
    };
    if !s.matrix.cols.is_empty() {
        for n in 0..k {
            let i = s.order[n];
            let r = s.matrix.rows[i];
            // The robot wants its cheapest free goal, and nothing is freed during its turn:
            // its search heads for the free goals only (the same pick, fewer cells when the
            // goals near it are taken).
            let free = s.matrix.cols.iter().zip(&s.free);
            s.lazy
                .guide_toward(free.filter(|&(_, &f)| f).map(|(&c, _)| c));
            let mut seen = 0;
            let mut pick = loop {
                let done = s.lazy.step(ctx, candidates, r, false);
                let found = s.lazy.found(r);
                // earlier pairs were all taken, and nothing is freed during this turn
                let pick = cheapest(&found[seen..], &s.free);
                seen = found.len();
                if pick.is_some() || done {
                    break pick;
                }
            };
            if pick.is_none() && s.free.iter().any(|&f| !f) {
                s.free.fill(true);
                pick = cheapest(s.lazy.found(r), &s.free);
            }
            if let Some(j) = pick {
                s.assigned[i] = Some(j);
                s.free[j] = false;
            }
        }
    }
    greedy::write_found(&s, out);
    ctx.memory.greedy_utility.scratch = s;
}
