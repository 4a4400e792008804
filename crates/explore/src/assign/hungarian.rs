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
/// Each robot's search grows until it has settled k free goals (k = deciding robots) and
/// finished that bucket: its k cheapest free goals are then known. The solver gets the
/// union of these columns, with the costs the searches found; a pair no search reached is
/// offered at the unreachable price. That keeps the optimum of [`solve`]: any optimal
/// assignment can move each robot into its own k cheapest free goals at no higher cost
/// (see the module docs), and those pairs are all priced exactly. Only among assignments
/// of equal total cost may the solver's choice differ from the full matrix's.
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
fn lazy_optimal(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    s: &mut greedy::Scratch,
    buf: &mut Buffers,
) {
    s.matrix.frame(ctx, candidates, false);
    s.lazy.reset(ctx.robots.len());
    let rows = s.matrix.rows.len();
    let cols = s.matrix.cols.len();
    s.assigned.clear();
    s.assigned.resize(rows, None);
    if rows == 0 || cols == 0 {
        return;
    }
    let k = rows;
    let taken = &s.matrix.taken;
    // Each row's k cheapest free columns, (cost, index) order; if it reaches fewer, the
    // lowest free columns it cannot reach fill up (as the full matrix's selection does).
    buf.cols.clear();
    for i in 0..rows {
        let r = s.matrix.rows[i];
        let mut free_found = 0;
        let mut seen = 0;
        loop {
            let done = s.lazy.step(ctx, candidates, r, false);
            let found = s.lazy.found(r);
            free_found += found[seen..].iter().filter(|p| !taken[p.col]).count();
            seen = found.len();
            if free_found >= k || done {
                break;
            }
        }
        buf.row.clear();
        buf.row.extend(
            s.lazy
                .found(r)
                .iter()
                .enumerate()
                .filter(|(_, p)| !taken[p.col])
                .map(|(n, _)| n),
        );
        let found = s.lazy.found(r);
        if buf.row.len() > k {
            buf.row.select_nth_unstable_by(k - 1, |&a, &b| {
                let (pa, pb) = (found[a], found[b]);
                pa.cost.total_cmp(&pb.cost).then(pa.col.cmp(&pb.col))
            });
            buf.row.truncate(k);
        }
        let own = buf.row.len();
        buf.cols.extend(buf.row.iter().map(|&n| found[n].col));
        if own < k {
            // the search is complete: the other free columns are unreachable for this row
            s.values.clear();
            s.values.resize(cols, 0.0);
            for p in found {
                s.values[p.col] = 1.0;
            }
            buf.cols.extend(
                (0..cols)
                    .filter(|&j| !taken[j] && s.values[j] == 0.0)
                    .take(k - own),
            );
        }
    }
    buf.cols.sort_unstable();
    buf.cols.dedup();
    let n = buf.cols.len();
    if n == 0 {
        return;
    }
    // Column j of the full problem → its position in the reduced one (+1; 0: absent).
    s.order.clear();
    s.order.resize(cols, 0);
    for (jj, &j) in buf.cols.iter().enumerate() {
        s.order[j] = jj + 1;
    }
    buf.cost.clear();
    buf.cost.resize(rows * n, f64::INFINITY);
    let mut max_finite = 0.0f64;
    for i in 0..rows {
        for p in s.lazy.found(s.matrix.rows[i]) {
            let jj = s.order[p.col];
            if jj > 0 {
                buf.cost[i * n + jj - 1] = p.cost;
                max_finite = max_finite.max(p.cost);
            }
        }
    }
    // Any assignment with one more unreachable pair costs more than one with fewer.
    let big = (max_finite + 1.0) * (rows as f64 + 1.0);
    let mut priced = std::mem::take(&mut s.values);
    priced.clear();
    priced.extend(
        buf.cost
            .iter()
            .map(|&c| if c.is_finite() { c } else { big }),
    );
    match lsap::solve(rows, n, &priced, false) {
        Ok((r, c)) => {
            for (&i, &jj) in r.iter().zip(&c) {
                if buf.cost[i * n + jj].is_finite() {
                    s.assigned[i] = Some(buf.cols[jj]);
                }
            }
        }
        Err(_) => greedy::lazy_greedy(ctx, candidates, s),
    }
    s.values = priced;
    // Robots left over take their cheapest reachable goal, taken or not (earliest on ties).
    for i in 0..rows {
        if s.assigned[i].is_some() {
            continue;
        }
        s.assigned[i] = s
            .lazy
            .found(s.matrix.rows[i])
            .iter()
            .map(|p| (p.cost, p.col))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
            .map(|(_, j)| j);
    }
}
