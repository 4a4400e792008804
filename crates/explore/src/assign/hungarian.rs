//! Hungarian assignment (Faigl & Kulich 2013, §III-B, HA): the optimal assignment of the
//! robot × goal path-cost matrix.
//!
//! The linear sum assignment is solved by the `lsap` crate (a port of SciPy's shortest
//! augmenting path solver: rectangular, f64 costs). Faigl & Kulich used a C Hungarian
//! implementation; any exact solver gives the same optimal total cost.
//!
//! Precisions and deviations:
//! - only each robot's k cheapest free goals are offered to the solver (k = number of
//!   deciding robots, ties by candidate order), at most k² columns. This keeps the optimum:
//!   in an optimal assignment a robot whose goal is not among its k cheapest could move to
//!   one of them that the k − 1 others leave free, at no higher cost. So a decision on all
//!   frontier cells (thousands) costs O(k n) for the selection plus a k × k² solve;
//! - unreachable pairs get a large finite cost (lsap rejects infinities), larger than any
//!   assignment of finite pairs, so one is used only if unavoidable; a robot it is given to
//!   counts as unassigned;
//! - goals of robots that keep their goal this time count as assigned;
//! - with more robots than free goals, the robots left without a goal (and those that reach
//!   none of the free goals) take their cheapest reachable goal, taken or not;
//! - should the solver fail (it cannot on finite costs), the greedy rule decides instead;
//! - a single deciding robot takes its nearest free goal (the optimum of a 1 × n problem)
//!   by an early-stopping search ([`greedy::assign_single`]).

use crate::assign::greedy;
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Buffers of [`optimal`], reused across decisions.
#[derive(Clone, Debug, Default)]
pub struct Buffers {
    /// Candidate columns of the reduced problem.
    pub cols: Vec<usize>,
    /// Row-major costs of the reduced problem.
    pub cost: Vec<f64>,
    /// One row's free columns, for selecting its cheapest.
    pub row: Vec<usize>,
}

/// Optimal assignment on a row-major `rows × cols` cost matrix (`INFINITY` = unreachable),
/// columns with `taken[j]` excluded: `out[i]` becomes row `i`'s column, `None` for rows left
/// over (more rows than free columns) or matched only to an unreachable column. Among the
/// assignments with the most reachable pairs it minimises the total cost.
pub fn optimal(
    rows: usize,
    cols: usize,
    cost: &[f64],
    taken: &[bool],
    buf: &mut Buffers,
    out: &mut Vec<Option<usize>>,
) {
    out.clear();
    out.resize(rows, None);
    if rows == 0 || cols == 0 {
        return;
    }
    // Offer each row its k cheapest free columns, (cost, index) order.
    let k = rows;
    buf.cols.clear();
    let key = |i: usize, j: usize| (cost[i * cols + j], j);
    for i in 0..rows {
        buf.row.clear();
        buf.row.extend((0..cols).filter(|&j| !taken[j]));
        if buf.row.len() > k {
            buf.row.select_nth_unstable_by(k - 1, |&a, &b| {
                let (ca, cb) = (key(i, a), key(i, b));
                ca.0.total_cmp(&cb.0).then(ca.1.cmp(&cb.1))
            });
            buf.row.truncate(k);
        }
        buf.cols.extend_from_slice(&buf.row);
    }
    buf.cols.sort_unstable();
    buf.cols.dedup();
    let n = buf.cols.len();
    if n == 0 {
        return;
    }
    let max_finite = buf
        .cols
        .iter()
        .flat_map(|&j| (0..rows).map(move |i| cost[i * cols + j]))
        .filter(|c| c.is_finite())
        .fold(0.0f64, f64::max);
    // Any assignment with one more unreachable pair costs more than one with fewer.
    let big = (max_finite + 1.0) * (rows as f64 + 1.0);
    buf.cost.clear();
    for i in 0..rows {
        buf.cost.extend(buf.cols.iter().map(|&j| {
            let c = cost[i * cols + j];
            if c.is_finite() { c } else { big }
        }));
    }
    match lsap::solve(rows, n, &buf.cost, false) {
        Ok((r, c)) => {
            for (&i, &jj) in r.iter().zip(&c) {
                let j = buf.cols[jj];
                if cost[i * cols + j].is_finite() {
                    out[i] = Some(j);
                }
            }
        }
        Err(_) => {
            let mut free = Vec::new();
            greedy::solve(rows, cols, cost, taken, &mut free, out);
        }
    }
}

/// Give each robot `out[i] == None` its cheapest reachable column (earliest on ties).
fn leftovers_take_cheapest(cols: usize, cost: &[f64], out: &mut [Option<usize>]) {
    for (i, slot) in out.iter_mut().enumerate() {
        if slot.is_some() {
            continue;
        }
        let row = &cost[i * cols..(i + 1) * cols];
        let mut best: Option<(f64, usize)> = None;
        for (j, &c) in row.iter().enumerate() {
            if c.is_finite() && best.is_none_or(|(b, _)| c < b) {
                best = Some((c, j));
            }
        }
        *slot = best.map(|(_, j)| j);
    }
}

/// HA on a cost matrix: [`optimal`], then the robots left over take their cheapest goal.
pub fn solve(
    rows: usize,
    cols: usize,
    cost: &[f64],
    taken: &[bool],
    buf: &mut Buffers,
    out: &mut Vec<Option<usize>>,
) {
    optimal(rows, cols, cost, taken, buf, out);
    if cols > 0 {
        leftovers_take_cheapest(cols, cost, out);
    }
}

/// Give goals to the deciding robots: the assignment of least total path cost.
///
/// The robots' searches grow only until the optimum is certified. A robot whose search
/// has settled every bucket below L knows its exact cost to every goal it settled, and
/// that every other goal costs at least L (or is unreachable, once its search is complete).
/// The solver gets the lower-bound matrix: exact costs where known, L elsewhere (each robot
/// offered its k cheapest free goals found plus k stand-in columns at its L, which by the
/// argument of the module docs keeps the optimum; a robot with k free goals found needs no
/// bound at all). If its optimal assignment uses only
/// exact costs, it is optimal for the true matrix too (every true cost is at least its
/// bound); otherwise the searches of the robots given a bound grow (by a quarter of their
/// radius: the cells searched past the goals needed are waste, and solving again is cheap)
/// and the problem is solved again. Ties between assignments of equal total may be broken
/// differently from the full matrix's [`solve`].
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    if greedy::assign_single(ctx, candidates, out) {
        return;
    }
    let mut st = std::mem::take(&mut ctx.memory.greedy_utility);
    lazy_optimal(ctx, candidates, &mut st.scratch, &mut st.hungarian);
    greedy::write_found(&st.scratch, out);
    ctx.memory.greedy_utility = st;
}

/// HA on lazily grown searches: `s.assigned[i]` becomes row i's column.
// Row i's state is spread over parallel buffers (rows, completeness, found pairs).
#[allow(clippy::needless_range_loop)]
fn lazy_optimal(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    s: &mut greedy::Scratch,
    buf: &mut Buffers,
) {
    s.start(ctx, candidates, false);
    let rows = s.matrix.rows.len();
    let cols = s.matrix.cols.len();
    if rows == 0 || cols == 0 {
        return;
    }
    let k = rows;
    // Column j of the full problem → its position in the reduced one (+1; 0: absent).
    s.order.clear();
    s.order.resize(cols, 0);
    buf.cols.clear();
    // Per row: whether its search is complete.
    let mut complete = vec![false; rows];
    let mut enough = vec![false; rows];
    for i in 0..rows {
        complete[i] = s.lazy.step(ctx, candidates, s.matrix.rows[i], false);
    }
    loop {
        let taken = &s.matrix.taken;
        // Each row's k cheapest free columns found, (cost, index) order.
        for &j in &buf.cols {
            s.order[j] = 0;
        }
        buf.cols.clear();
        for i in 0..rows {
            let found = s.lazy.found(s.matrix.rows[i]);
            buf.row.clear();
            buf.row.extend(
                found
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| !taken[p.col])
                    .map(|(n, _)| n),
            );
            if buf.row.len() > k {
                buf.row.select_nth_unstable_by(k - 1, |&a, &b| {
                    let (pa, pb) = (found[a], found[b]);
                    pa.cost.total_cmp(&pb.cost).then(pa.col.cmp(&pb.col))
                });
                buf.row.truncate(k);
            }
            // k free goals found: its k cheapest are exact, and by the swap argument its
            // optimal goal is among them, so it needs no bound.
            enough[i] = buf.row.len() >= k;
            buf.cols.extend(buf.row.iter().map(|&n| found[n].col));
        }
        buf.cols.sort_unstable();
        buf.cols.dedup();
        for (jj, &j) in buf.cols.iter().enumerate() {
            s.order[j] = jj + 1;
        }
        // Exact costs, bounds (the row's next bucket) and unreachable pairs; then k
        // stand-in columns for the goals no row has offered.
        let n = buf.cols.len() + k;
        const UNKNOWN: f64 = f64::NEG_INFINITY;
        buf.cost.clear();
        buf.cost.resize(rows * n, UNKNOWN);
        let mut max_finite = 0.0f64;
        for i in 0..rows {
            let r = s.matrix.rows[i];
            for p in s.lazy.found(r) {
                let jj = s.order[p.col];
                if jj > 0 {
                    buf.cost[i * n + jj - 1] = p.cost;
                    max_finite = max_finite.max(p.cost);
                }
            }
            if !complete[i] {
                max_finite = max_finite.max(s.lazy.next_bucket(ctx, r) as f64);
            }
        }
        // Any assignment with one more unreachable pair costs more than one with fewer.
        let big = (max_finite + 1.0) * (rows as f64 + 1.0);
        s.values.clear();
        for i in 0..rows {
            let bound = if complete[i] || enough[i] {
                big
            } else {
                s.lazy.next_bucket(ctx, s.matrix.rows[i]) as f64
            };
            for jj in 0..n {
                let c = buf.cost[i * n + jj];
                s.values.push(if c == UNKNOWN { bound } else { c });
            }
        }
        let Ok((r, c)) = lsap::solve(rows, n, &s.values, false) else {
            greedy::lazy_greedy(ctx, candidates, s);
            return;
        };
        // Rows given a bound must look further; otherwise the assignment is optimal.
        let mut grew = false;
        for (&i, &jj) in r.iter().zip(&c) {
            if buf.cost[i * n + jj] == UNKNOWN && !complete[i] && !enough[i] {
                let row = s.matrix.rows[i];
                let next = s.lazy.next_bucket(ctx, row);
                complete[i] = s.lazy.grow(ctx, candidates, row, next + next / 4 + 8);
                grew = true;
            }
        }
        if grew {
            continue;
        }
        for (&i, &jj) in r.iter().zip(&c) {
            if jj < buf.cols.len() && buf.cost[i * n + jj] != UNKNOWN {
                s.assigned[i] = Some(buf.cols[jj]);
            }
        }
        break;
    }
    // Robots left over take their cheapest reachable goal, taken or not (earliest on ties).
    for i in 0..rows {
        if s.assigned[i].is_some() {
            continue;
        }
        let r = s.matrix.rows[i];
        while s.lazy.found(r).is_empty() && !complete[i] {
            complete[i] = s.lazy.step(ctx, candidates, r, false);
        }
        s.assigned[i] = s
            .lazy
            .found(r)
            .iter()
            .map(|p| (p.cost, p.col))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(_, j)| j);
    }
}
