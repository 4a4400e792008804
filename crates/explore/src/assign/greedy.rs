//! Greedy assignment (the coordination study's Alg. 2; Faigl & Kulich's IA).
//!
//! Repeatedly the globally cheapest (robot, goal) pair whose robot has no goal yet and whose
//! goal is still free is taken, and both leave their lists. When the free goals run out
//! before the robots do, the goal set is refilled with every candidate (Alg. 2's
//! `if F = ∅ then F = F_init`). Faigl & Kulich's IA (a centralised Broadcast of Local
//! Eligibility: all pairs ordered by cost, the first pair whose robot and goal are both
//! unassigned wins) is the same rule, so it is implemented once and named both ways.
//!
//! Costs are path lengths in cells from one full reachability map per deciding robot
//! ([`CostMatrix`], shared with the other coordinated assigners of this directory).
//!
//! Deviations and precisions:
//! - ties are broken by robot index, then by candidate order (deterministic);
//! - goals of robots that keep their goal this time (`!ctx.deciding[r]`) start taken;
//! - the refill happens when no free goal is reachable by a robot still without one (not
//!   only when the free set is empty): a robot cut off from the free goals would otherwise
//!   idle although it can reach a goal another robot took;
//! - cost O(m² n) for m deciding robots and n candidates (m passes over the m × n matrix),
//!   no O(n²) step;
//! - when a single robot decides (on arrival) the rule reduces to its nearest free goal,
//!   found by a search that stops at the first one ([`assign_single`], shared with GA and
//!   HA); equal-cost ties then go to the goal settled first.

use crate::assign::costs::LazyCosts;
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Robot → candidate path costs of one decision: rows are robots, columns candidates.
///
/// Unreachable pairs cost `f64::INFINITY`. Buffers are reused across decisions.
#[derive(Clone, Debug, Default)]
pub struct CostMatrix {
    /// Robot index of each row.
    pub rows: Vec<usize>,
    /// Candidate cell of each column, in candidate order.
    pub cols: Vec<u32>,
    /// Row-major costs in cells (`rows.len() × cols.len()`), `INFINITY` if unreachable.
    pub cost: Vec<f64>,
    /// Columns that are the current goals of robots not deciding this time.
    pub taken: Vec<bool>,
}

impl CostMatrix {
    /// Fill the matrix for this decision: one row per deciding robot (per robot if
    /// `all_robots`), one column per candidate; computes each row robot's full
    /// reachability map once. (The assigners grow searches only as far as they need, see
    /// [`crate::assign::costs`]; the full matrix is their test oracle.)
    pub fn fill(&mut self, ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, all_robots: bool) {
        self.frame(ctx, candidates, all_robots);
        for &r in &self.rows {
            let reach = ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
            self.cost.extend(
                self.cols
                    .iter()
                    .map(|&c| reach.cost(c as usize).unwrap_or(f64::INFINITY)),
            );
        }
    }

    /// Rows, columns and taken columns of this decision, with no costs.
    pub fn frame(&mut self, ctx: &DecisionCtx<'_>, candidates: &CandidateSet, all_robots: bool) {
        let m = ctx.robots.len();
        self.rows.clear();
        self.rows
            .extend((0..m).filter(|&r| all_robots || ctx.deciding[r]));
        self.cols.clear();
        self.cols.extend_from_slice(candidates.cells());
        self.cost.clear();
        self.taken.clear();
        self.taken.resize(self.cols.len(), false);
        for r in 0..m {
            if ctx.deciding[r] {
                continue;
            }
            let Some(g) = ctx.goals.get(r).copied().flatten() else {
                continue;
            };
            if let Some(j) = candidates.index_of(g as usize) {
                self.taken[j] = true;
            }
        }
    }

    /// Number of columns (candidates).
    pub fn n_cols(&self) -> usize {
        self.cols.len()
    }

    /// Cost of row `i`, column `j`.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.cost[i * self.cols.len() + j]
    }

    /// Write the goals `assigned[i]` (a column per row) to the row robots' slots of `out`;
    /// rows without a column, or with an unreachable one, get `None`.
    pub fn write(&self, assigned: &[Option<usize>], out: &mut [Option<Goal>]) {
        for (i, &r) in self.rows.iter().enumerate() {
            let Some(slot) = out.get_mut(r) else {
                continue;
            };
            *slot = assigned.get(i).copied().flatten().and_then(|j| {
                let cost = self.at(i, j);
                cost.is_finite().then(|| Goal {
                    cell: self.cols[j],
                    cost,
                })
            });
        }
    }
}

/// Buffers of the cost-matrix assigners (greedy, GA, greedy with utility, MinPos, HA).
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    /// The decision's cost matrix.
    pub matrix: CostMatrix,
    /// Which columns are still free.
    pub free: Vec<bool>,
    /// The column chosen for each row.
    pub assigned: Vec<Option<usize>>,
    /// Per-assigner extra buffer (robot order, sub-matrix columns, MinPos' goals left).
    pub order: Vec<usize>,
    /// Per-assigner extra buffer of reals (utilities, sub-matrix costs).
    pub values: Vec<f64>,
    /// Pairs found by the robots' searches, grown only as far as needed.
    pub lazy: LazyCosts,
    /// Per row: how many of its found pairs were already looked at.
    pub scan: Vec<usize>,
    /// MinPos' robots that may be strictly closer to a goal, by octile distance to it.
    pub nearest: Vec<(f64, usize)>,
}

impl Scratch {
    /// Start a decision on lazily grown searches: rows (every robot if `all_robots`, else
    /// the deciding ones), columns and taken goals; no pair found yet, every untaken goal
    /// free, no row assigned.
    pub fn start(&mut self, ctx: &DecisionCtx<'_>, candidates: &CandidateSet, all_robots: bool) {
        self.matrix.frame(ctx, candidates, all_robots);
        self.lazy.reset(ctx.robots.len(), true);
        let rows = self.matrix.rows.len();
        self.free.clear();
        self.free.extend(self.matrix.taken.iter().map(|&t| !t));
        self.assigned.clear();
        self.assigned.resize(rows, None);
        self.scan.clear();
        self.scan.resize(rows, 0);
    }

    /// Grow the search of every row without a goal through bucket `k`; whether all of
    /// them are complete.
    pub fn grow_unassigned(
        &mut self,
        ctx: &mut DecisionCtx<'_>,
        candidates: &CandidateSet,
        k: usize,
    ) -> bool {
        let mut all_done = true;
        for (i, &r) in self.matrix.rows.iter().enumerate() {
            if self.assigned[i].is_none() {
                all_done &= self.lazy.grow(ctx, candidates, r, k);
            }
        }
        all_done
    }
}

/// Greedy (IA) on a row-major `rows × cols` cost matrix (`INFINITY` = unreachable):
/// `out[i]` becomes the column of row `i`, or `None` when it can reach no goal. Columns with
/// `taken[j]` start unavailable; `free` is a scratch buffer.
pub fn solve(
    rows: usize,
    cols: usize,
    cost: &[f64],
    taken: &[bool],
    free: &mut Vec<bool>,
    out: &mut Vec<Option<usize>>,
) {
    free.clear();
    free.extend(taken.iter().take(cols).map(|&t| !t));
    free.resize(cols, true);
    out.clear();
    out.resize(rows, None);
    let mut left = rows;
    let mut refilled = false;
    while left > 0 {
        let mut best: Option<(f64, usize, usize)> = None;
        for (i, row) in cost.chunks_exact(cols.max(1)).take(rows).enumerate() {
            if out[i].is_some() {
                continue;
            }
            for (j, &c) in row.iter().enumerate().take(cols) {
                if free[j] && c.is_finite() && best.is_none_or(|(b, _, _)| c < b) {
                    best = Some((c, i, j));
                }
            }
        }
        match best {
            Some((_, i, j)) => {
                out[i] = Some(j);
                free[j] = false;
                left -= 1;
                refilled = false;
            }
            None if !refilled && free.iter().any(|&f| !f) => {
                free.fill(true);
                refilled = true;
            }
            None => break,
        }
    }
}

/// With exactly one deciding robot, greedy, GA and HA all give it its cheapest free goal
/// (its cheapest goal if every goal it can reach is taken): found by a search that stops at
/// the first such goal instead of a full reachability map. Returns false (doing nothing)
/// when more than one robot decides. Ties between goals of equal cost go to the one the
/// search settles first (lower cell index).
pub fn assign_single(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    out: &mut [Option<Goal>],
) -> bool {
    let m = ctx.robots.len();
    let mut deciding = (0..m).filter(|&r| ctx.deciding[r]);
    let (Some(r), None) = (deciding.next(), deciding.next()) else {
        return false;
    };
    let (goals, decides) = (ctx.goals, ctx.deciding);
    let kept =
        |i: usize| (0..m).any(|k| !decides[k] && goals.get(k).copied().flatten() == Some(i as u32));
    let from = ctx.robots[r];
    let cells = candidates.cells();
    let mut found = ctx
        .planner
        .nearest(r, from, ctx.known, ctx.upkeep, cells, |i| {
            candidates.contains(i) && !kept(i)
        });
    let any_taken = (0..m).any(|k| {
        !decides[k]
            && goals
                .get(k)
                .copied()
                .flatten()
                .is_some_and(|g| candidates.contains(g as usize))
    });
    if found.is_none() && any_taken {
        found = ctx
            .planner
            .nearest(r, from, ctx.known, ctx.upkeep, cells, |i| {
                candidates.contains(i)
            });
    }
    if let Some(slot) = out.get_mut(r) {
        *slot = found.and_then(|cell| {
            let cost = ctx.planner.map(r).cost(cell as usize)?;
            Some(Goal { cell, cost })
        });
    }
    true
}

/// Give goals to the deciding robots: greedy on the global cost order.
///
/// The searches of the robots still without a goal grow together, one bucket at a time:
/// once all have settled bucket k, every pair of cost below k + 1 is known and any other
/// costs more, so the cheapest free pair among the known ones is the matrix rule's next
/// pick (ties by robot, then candidate order, as in [`solve`]).
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    if assign_single(ctx, candidates, out) {
        return;
    }
    let mut s = std::mem::take(&mut ctx.memory.greedy_utility.scratch);
    lazy_greedy(ctx, candidates, &mut s);
    write_found(&s, out);
    ctx.memory.greedy_utility.scratch = s;
}

/// Write each row's goal (`s.assigned`, a column) with its cost from the row's found
/// pairs; rows without a column get `None`.
pub(crate) fn write_found(s: &Scratch, out: &mut [Option<Goal>]) {
    for (i, &r) in s.matrix.rows.iter().enumerate() {
        let Some(slot) = out.get_mut(r) else {
            continue;
        };
        *slot = s.assigned.get(i).copied().flatten().and_then(|j| {
            let pair = s.lazy.found(r).iter().find(|p| p.col == j)?;
            Some(Goal {
                cell: s.matrix.cols[j],
                cost: pair.cost,
            })
        });
    }
}

/// Greedy (IA) on lazily grown searches: `s.assigned[i]` becomes row i's column.
pub(crate) fn lazy_greedy(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, s: &mut Scratch) {
    s.start(ctx, candidates, false);
    let rows = s.matrix.rows.len();
    let mut left = rows;
    let mut refilled = false;
    let mut k = 0usize;
    while left > 0 {
        let all_done = s.grow_unassigned(ctx, candidates, k);
        // Every unassigned row's pairs below k + 1 are known: pick while a free one is left.
        loop {
            let mut best: Option<(f64, usize, usize)> = None;
            for i in 0..rows {
                if s.assigned[i].is_some() {
                    continue;
                }
                for p in &s.lazy.found(s.matrix.rows[i])[s.scan[i]..] {
                    if s.free[p.col]
                        && best.is_none_or(|(c, bi, bj)| (p.cost, i, p.col) < (c, bi, bj))
                    {
                        best = Some((p.cost, i, p.col));
                    }
                }
            }
            let Some((_, i, j)) = best else { break };
            s.assigned[i] = Some(j);
            s.free[j] = false;
            left -= 1;
            refilled = false;
        }
        // The pairs looked at are all taken now (and stay so until a refill).
        for i in 0..rows {
            s.scan[i] = s.lazy.found(s.matrix.rows[i]).len();
        }
        if left == 0 {
            break;
        }
        if all_done {
            if !refilled && s.free.iter().any(|&f| !f) {
                s.free.fill(true);
                refilled = true;
                s.scan.fill(0);
                continue;
            }
            break;
        }
        k += 1;
    }
}
