//! Greedy with utility (the coordination study's Alg. 3; Burgard et al., Simmons et al.).
//!
//! Every goal starts with utility U_j = 1. Repeatedly the pair (robot k, goal j) of a robot
//! without a goal and a free goal maximising U_j − β·c_kj is taken, and the utility of every
//! goal j' near the chosen one is lowered: U_j' ← U_j' − P(‖g_j − g_j'‖) with
//! P(d) = 1 − d/ρ for d < ρ and 0 otherwise (ρ = sensor range in cells, Euclidean distance
//! between the cells in cells). As in greedy (Alg. 2), the goal set is refilled when it runs
//! out before the robots; utilities are not reset by the refill, so a robot sent to an
//! already chosen area prefers the least covered goal.
//!
//! Choice of β. The coordination study gives no value. Costs are path lengths in
//! cells and utilities lie in [0, 1], so 1/β is the detour (in cells) a robot accepts to
//! avoid a goal whose whole utility was taken away by a goal chosen on top of it; the
//! natural scale is β ≈ 1/ρ (a detour of about one sensor range). Measured with this code
//! (mean exploration time over 8 seeds, 3 and 4 robots, 5 m `los` sensor): on the office
//! and maze (ρ = 10 cells) β from 0.01 to 1 changed times by a few per cent; on the cave
//! (ρ = 50 cells) β = 0.01–0.03 gave 41–47 s, β = 0.1 gave 49–55 s, β = 1 gave 60–71 s
//! (plain greedy 69 s). We take β = 0.03 per cell, good on all three. A much smaller β
//! sends robots across the map for a goal of full utility; a β well above 1/ρ turns the rule
//! into plain greedy.
//!
//! Precisions and deviations:
//! - the study lowers the utility of the goals "in the visibility of the robot sensors";
//!   as Burgard et al., visibility is taken by distance alone (P above, within ρ), with no
//!   line-of-sight test, so a goal behind a wall within ρ is lowered too;
//! - goals of robots that keep their goal this time count as taken, and lower the utilities
//!   around them as if they had just been assigned (Burgard's reduction for targets of other
//!   robots), even when such a goal is not among the candidates;
//! - utilities may become negative when several chosen goals overlap, as in Burgard et al.;
//! - ties are broken by robot index, then candidate order;
//! - the robots' searches grow only until the best pair beats every pair not seen yet
//!   (see [`assign`]); no O(n²) step. A single deciding robot while no other robot holds a
//!   goal (all utilities 1) takes its nearest goal by an early-stopping search.

use crate::assign::greedy::{self, Scratch};
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// State kept across decisions: the buffers of the cost-matrix assigners.
///
/// `greedy`, `ga`, `minpos` and `ha` borrow the same buffers (they own no `Memory` field).
#[derive(Default)]
pub struct State {
    /// Cost matrix and work buffers, reused across decisions.
    pub scratch: Scratch,
    /// Cell coordinates `(x, y)` of the candidates.
    pub positions: Vec<(f64, f64)>,
    /// Cell coordinates of goals kept by robots not deciding this time.
    pub kept: Vec<(f64, f64)>,
    /// Reduced-problem buffers of the Hungarian assigner.
    pub hungarian: crate::assign::hungarian::Buffers,
}

/// β used by the `greedy-utility` presets (utility per cell of path).
pub const DEFAULT_BETA: f64 = 0.03;

/// P(d) = 1 − d/ρ for d < ρ, else 0: how much of a goal's utility a goal at distance `d`
/// (cells) takes away.
#[inline]
pub fn overlap(d: f64, rho: f64) -> f64 {
    if d < rho { 1.0 - d / rho } else { 0.0 }
}

/// Lower `utility[j]` by P(‖positions[j] − p‖) for every goal j.
fn lower_around(utility: &mut [f64], positions: &[(f64, f64)], p: (f64, f64), rho: f64) {
    let rho2 = rho * rho;
    for (u, &(x, y)) in utility.iter_mut().zip(positions) {
        let d2 = (x - p.0) * (x - p.0) + (y - p.1) * (y - p.1);
        if d2 < rho2 {
            *u -= overlap(d2.sqrt(), rho);
        }
    }
}

/// Greedy with utility on a row-major `rows × cols` cost matrix (`INFINITY` = unreachable).
///
/// `positions[j]` is goal j's cell, `kept` the goals other robots keep (their neighbourhoods
/// lose utility first), `taken[j]` marks columns that start unavailable. `out[i]` becomes the
/// column of row `i`; `utility` ends with the final utilities.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    rows: usize,
    cost: &[f64],
    positions: &[(f64, f64)],
    kept: &[(f64, f64)],
    taken: &[bool],
    rho: f64,
    beta: f64,
    utility: &mut Vec<f64>,
    free: &mut Vec<bool>,
    out: &mut Vec<Option<usize>>,
) {
    let cols = positions.len();
    utility.clear();
    utility.resize(cols, 1.0);
    for &p in kept {
        lower_around(utility, positions, p, rho);
    }
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
            for (j, &c) in row.iter().enumerate() {
                if !free[j] || !c.is_finite() {
                    continue;
                }
                let v = utility[j] - beta * c;
                if best.is_none_or(|(b, _, _)| v > b) {
                    best = Some((v, i, j));
                }
            }
        }
        match best {
            Some((_, i, j)) => {
                out[i] = Some(j);
                free[j] = false;
                left -= 1;
                refilled = false;
                lower_around(utility, positions, positions[j], rho);
            }
            None if !refilled && free.iter().any(|&f| !f) => {
                free.fill(true);
                refilled = true;
            }
            None => break,
        }
    }
}

/// Give goals to the deciding robots: greedy on utility minus β × path cost.
///
/// The searches of the robots still without a goal grow together, one bucket at a time.
/// After bucket k every pair not seen costs at least k + 1, so its value is at most
/// U_max − β (k + 1) (U_max: the largest utility of a free goal); the best known pair is
/// the matrix rule's pick as soon as its value is above that bound (or every search is
/// complete). Ties go by robot, then candidate order, as in [`solve`].
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    beta: f64,
    out: &mut [Option<Goal>],
) {
    let m = ctx.robots.len();
    let kept_any =
        (0..m).any(|r| !ctx.deciding[r] && ctx.goals.get(r).copied().flatten().is_some());
    // With no goal kept by another robot every utility is 1: the nearest goal wins.
    if !kept_any && crate::assign::greedy::assign_single(ctx, candidates, out) {
        return;
    }
    let mut st = std::mem::take(&mut ctx.memory.greedy_utility);
    let s = &mut st.scratch;
    s.start(ctx, candidates, false);
    let width = ctx.known.width().max(1);
    let xy = |c: u32| ((c as usize % width) as f64, (c as usize / width) as f64);
    st.positions.clear();
    st.positions.extend(s.matrix.cols.iter().map(|&c| xy(c)));
    st.kept.clear();
    for (r, g) in ctx.goals.iter().enumerate().take(m) {
        if let (false, Some(g)) = (ctx.deciding[r], *g) {
            st.kept.push(xy(g));
        }
    }
    let rho = ctx.sensor_range_cells;
    let cols = st.positions.len();
    let mut utility_buf = std::mem::take(&mut s.values);
    let utility = &mut utility_buf;
    utility.clear();
    utility.resize(cols, 1.0);
    for &p in &st.kept {
        lower_around(utility, &st.positions, p, rho);
    }
    let rows = s.matrix.rows.len();
    let mut left = rows;
    let mut refilled = false;
    let mut k = 0usize;
    // The best known pair (value, row, column) over the pairs looked at, if still valid.
    let mut best: Option<(f64, usize, usize)> = None;
    let mut stale = true;
    let mut u_max = f64::NEG_INFINITY;
    let better = |v: f64, i: usize, j: usize, b: Option<(f64, usize, usize)>| {
        b.is_none_or(|(bv, bi, bj)| v > bv || (v == bv && (i, j) < (bi, bj)))
    };
    while left > 0 {
        let all_done = s.grow_unassigned(ctx, candidates, k);
        loop {
            if stale {
                best = None;
                s.scan.fill(0);
                u_max = (0..cols)
                    .filter(|&j| s.free[j])
                    .map(|j| utility[j])
                    .fold(f64::NEG_INFINITY, f64::max);
                stale = false;
            }
            for i in 0..rows {
                if s.assigned[i].is_some() {
                    continue;
                }
                let found = s.lazy.found(s.matrix.rows[i]);
                for p in &found[s.scan[i]..] {
                    if s.free[p.col] {
                        let v = utility[p.col] - beta * p.cost;
                        if better(v, i, p.col, best) {
                            best = Some((v, i, p.col));
                        }
                    }
                }
                s.scan[i] = found.len();
            }
            let Some((v, i, j)) = best else { break };
            if !all_done && v <= u_max - beta * (k + 1) as f64 {
                break; // a pair not seen yet might still be worth more
            }
            s.assigned[i] = Some(j);
            s.free[j] = false;
            left -= 1;
            refilled = false;
            lower_around(utility, &st.positions, st.positions[j], rho);
            stale = true;
            if left == 0 {
                break;
            }
        }
        if left == 0 {
            break;
        }
        if all_done {
            // every pair is known and none is free for a robot still without a goal
            if !refilled && s.free.iter().any(|&f| !f) {
                s.free.fill(true);
                refilled = true;
                stale = true;
                continue;
            }
            break;
        }
        k += 1;
    }
    s.values = utility_buf;
    greedy::write_found(s, out);
    ctx.memory.greedy_utility = st;
}
