//! Decision-theoretic utility `u(p) = I(p)·exp(−λ·L(p))` (González-Baños & Latombe 2002;
//! Holz et al. 2010 §3.2, λ = 0.2 per metre).
//!
//! `I(p)` is the expected information gain in bits of each candidate, as the
//! decision-theoretic generator stored it ([`State::gains`]); if the gains do not belong to
//! these candidates (another generator ran), they are evaluated here the same way. `L(p)` is
//! the path length in metres from the robot's full reachability map. Each deciding robot
//! takes its own best candidate: the greatest utility, ties broken by the lower path cost,
//! then by the lower candidate index. Utilities are compared as `ln I − λL`, which orders
//! them the same way without underflowing for long paths.
//!
//! Lazy gains (exact): when the generator left gains unevaluated ([`State::is_lazy`]), a
//! robot visits the candidates in order of an upper bound on their utility,
//! `ln B(p) − λL(p)`, and evaluates gains only while the next bound could still beat the
//! best `ln I − λL` found. `B(p)` bounds the gain of any scan from `p`: each touched cell
//! drops at most 1 bit (binary entropy ≤ 1) and only uncertain cells (0 < p < 1) drop at
//! all; a scan of range R cells touches only cells whose centres lie within R + √2/2 of the
//! origin's centre. So `B(p)` is the number of uncertain cells in the square of half-side
//! R + 1 around `p` (a summed-area table of the belief, [`UncertainCounts`], built once
//! per decision), capped by π(R + 2)², which bounds the cells in the disc. A candidate
//! whose square holds no uncertain cell has gain 0 and is never evaluated. The tie rule
//! (greater utility, then lower cost, then lower index) is applied to the candidates
//! evaluated, and every one not evaluated is strictly worse than the choice, so the choice
//! is the one the full evaluation makes.
//!
//! A team is not coordinated (the paper is single-robot): every deciding robot takes its
//! own best, and robots may choose the same pose.
//!
//! Beyond the paper (`dt-rr`, its own future work): [`target_utility`] re-evaluates the
//! current target while travelling, so that the loop can re-decide when it has dropped.

use std::cmp::Ordering;

use sense::{Belief, Pose, Sensor, information_gain};

use crate::candidates::CandidateSet;
use crate::candidates::dt_samples::State;
use crate::decision::{DecisionCtx, Goal};

/// Each deciding robot takes the reachable candidate of greatest `I·exp(−λ·L)`.
pub fn assign(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    lambda: f64,
    out: &mut [Option<Goal>],
) {
    let m = ctx.robots.len();
    let mut st = std::mem::take(&mut ctx.memory.dt);
    if !st.aligned_with(candidates) {
        evaluate_all(ctx, candidates, &mut st);
    }
    if st.is_lazy() {
        for r in (0..m).filter(|&r| ctx.deciding[r]) {
            ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
        }
        let range = ctx.sensor_range_cells.max(0.0);
        let disc = std::f64::consts::PI * (range + 2.0).powi(2);
        let mut uncertain = std::mem::take(&mut st.uncertain);
        uncertain.build(ctx.belief);
        let bounds = GainBounds {
            uncertain: &uncertain,
            half_side: range as usize + 1,
            disc,
        };
        for (r, slot) in out.iter_mut().enumerate().take(m) {
            if ctx.deciding[r] {
                *slot = best_lazy(ctx, &mut st, r, lambda * ctx.resolution, &bounds);
            }
        }
        st.uncertain = uncertain;
        ctx.memory.dt = st;
        return;
    }
    for (r, slot) in out.iter_mut().enumerate().take(m) {
        if !ctx.deciding[r] {
            continue;
        }
        *slot = None;
        if candidates.is_empty() {
            continue;
        }
        let reach = ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
        *slot = best(
            &st.gains,
            candidates.cells(),
            lambda * ctx.resolution,
            |c| reach.cost(c as usize),
        );
    }
    ctx.memory.dt = st;
}

/// The best of `cells` (gains aligned) by `ln(gain) − lambda_per_cell·cost`, ties by lower
/// cost then lower index; cells without a cost are unreachable and skipped.
fn best(
    gains: &[f64],
    cells: &[u32],
    lambda_per_cell: f64,
    cost: impl Fn(u32) -> Option<f64>,
) -> Option<Goal> {
    let mut best: Option<(f64, Goal)> = None;
    for (&c, &gain) in cells.iter().zip(gains) {
        let Some(l) = cost(c) else {
            continue;
        };
        let score = gain.ln() - lambda_per_cell * l;
        let better = match &best {
            None => true,
            Some((s, g)) => match score.total_cmp(s) {
                Ordering::Greater => true,
                Ordering::Less => false,
                // Equal utilities (including two zero gains): the cheaper, then the earlier.
                Ordering::Equal => l < g.cost,
            },
        };
        if better {
            best = Some((score, Goal { cell: c, cost: l }));
        }
    }
    best.map(|(_, g)| g)
}

/// Robot `r`'s best candidate when some gains are not evaluated (module doc): candidates in
/// order of their utility bound, evaluated while the bound can still beat the best; gain 0
/// is skipped.
fn best_lazy(
    ctx: &DecisionCtx<'_>,
    st: &mut State,
    r: usize,
    lambda_per_cell: f64,
    bounds: &GainBounds<'_>,
) -> Option<Goal> {
    let planner = &*ctx.planner;
    let reach = planner.map(r);
    let width = ctx.known.width();
    let mut order = std::mem::take(&mut st.order);
    order.clear();
    order.extend(st.cells.iter().enumerate().filter_map(|(k, &c)| {
        let l = reach.cost(c as usize)?;
        let b = bounds.of(c as usize % width, c as usize / width);
        // No uncertain cell in reach of a scan from there: its gain is 0.
        (b > 0.0).then(|| (b.ln() - lambda_per_cell * l, l, k as u32))
    }));
    order.sort_by(|a, b| {
        b.0.total_cmp(&a.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.cmp(&b.2))
    });
    let mut best: Option<(f64, f64, u32)> = None;
    for &(ub, l, k) in &order {
        if best.is_some_and(|(s, _, _)| ub < s) {
            break;
        }
        let by = planner.map(st.reachers[k as usize] as usize);
        let gain = st.gain(k as usize, ctx.sensor, ctx.belief, by);
        if gain <= 0.0 {
            continue;
        }
        let score = gain.ln() - lambda_per_cell * l;
        let better = best.is_none_or(|(s, bl, bk)| match score.total_cmp(&s) {
            Ordering::Greater => true,
            Ordering::Less => false,
            Ordering::Equal => (l, k) < (bl, bk),
        });
        if better {
            best = Some((score, l, k));
        }
    }
    st.order = order;
    best.map(|(_, l, k)| Goal {
        cell: st.cells[k as usize],
        cost: l,
    })
}

/// The number of uncertain cells (0 < p(occupied) < 1) in any axis-aligned rectangle of the
/// belief, from a summed-area table rebuilt per decision (buffers kept).
#[derive(Clone, Debug, Default)]
pub struct UncertainCounts {
    width: usize,
    height: usize,
    /// `sat[y · (width + 1) + x]`: uncertain cells with column < x and row < y.
    sat: Vec<u32>,
}

impl UncertainCounts {
    /// Rebuild the table for `belief`.
    pub fn build(&mut self, belief: &dyn Belief) {
        let known = belief.known();
        let (w, h) = (known.width(), known.height());
        self.width = w;
        self.height = h;
        self.sat.clear();
        self.sat.resize((w + 1) * (h + 1), 0);
        for y in 0..h {
            let mut row = 0u32;
            for x in 0..w {
                let p = belief.p_occupied(y * w + x);
                row += u32::from(p > 0.0 && p < 1.0);
                self.sat[(y + 1) * (w + 1) + x + 1] = self.sat[y * (w + 1) + x + 1] + row;
            }
        }
    }

    /// Uncertain cells with column in `x0..x1` and row in `y0..y1` (clipped to the map).
    pub fn count(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> u32 {
        let (x1, y1) = (x1.min(self.width), y1.min(self.height));
        if x0 >= x1 || y0 >= y1 {
            return 0;
        }
        let s = |x: usize, y: usize| self.sat[y * (self.width + 1) + x];
        s(x1, y1) + s(x0, y0) - s(x0, y1) - s(x1, y0)
    }
}

/// Upper bounds on the gain of a scan from a cell (module doc).
struct GainBounds<'a> {
    uncertain: &'a UncertainCounts,
    /// Half-side of the square around the origin holding every cell a scan can touch.
    half_side: usize,
    /// π(R + 2)²: at most this many cells of a scan.
    disc: f64,
}

impl GainBounds<'_> {
    /// A bound on the gain of any scan from cell `(x, y)`.
    fn of(&self, x: usize, y: usize) -> f64 {
        let h = self.half_side;
        let n = self.uncertain.count(
            x.saturating_sub(h),
            y.saturating_sub(h),
            x + h + 1,
            y + h + 1,
        );
        if n == 0 {
            return 0.0;
        }
        // A sum of at most n drops of at most 1 bit each, with room for rounding.
        (f64::from(n) * (1.0 + 1e-12) + 1e-9).min(self.disc)
    }
}

/// Evaluate the gain of every candidate into `st` (for candidates the decision-theoretic
/// generator did not make), with the arrival heading of the first deciding robot that
/// reaches each.
fn evaluate_all(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, st: &mut State) {
    st.gains.clear();
    st.cells.clear();
    st.headings.clear();
    st.reachers.clear();
    let m = ctx.robots.len();
    for r in (0..m).filter(|&r| ctx.deciding[r]) {
        ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
    }
    let planner = &*ctx.planner;
    for &c in candidates.cells() {
        let reacher = (0..m).find(|&r| ctx.deciding[r] && planner.map(r).is_settled(c as usize));
        match reacher {
            Some(r) => {
                st.record(ctx.sensor, ctx.belief, planner.map(r), r, c);
            }
            None => st.push(c, 0.0, 0.0, 0),
        }
    }
}

/// The utility `I·exp(−λ·L)` of a target now: the gain of a predicted scan from `target`
/// (its cell and the heading the robot will arrive with) on the current belief, discounted
/// by the remaining path cost `remaining_cells` (cells; metres = cells × `resolution`,
/// λ per metre). Uses `dt`'s gain model and buffers; allocates nothing in steady state.
///
/// For `dt-rr`: the loop evaluates it at decision time (remaining = the goal's cost; equal
/// to the chosen candidate's utility) and again while travelling, and re-decides when it
/// falls below `utility_drop` times the first value.
pub fn target_utility(
    dt: &mut State,
    belief: &dyn Belief,
    sensor: &dyn Sensor,
    target: Pose,
    remaining_cells: f64,
    resolution: f64,
    lambda: f64,
) -> f64 {
    let gain = information_gain(sensor, belief, &dt.model, target, &mut dt.scratch);
    gain * (-lambda * remaining_cells.max(0.0) * resolution).exp()
}

/// The heading the decision-theoretic generator assumed at `cell` when it was chosen (the
/// arrival heading its gain was evaluated with), if `cell` is a current candidate.
pub fn chosen_heading(dt: &State, cell: u32) -> Option<f64> {
    dt.cells
        .iter()
        .position(|&c| c == cell)
        .map(|k| dt.headings[k])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn best_orders_by_utility_then_cost_then_index() {
        let cells = [10, 11, 12, 13];
        let costs = [5.0, 1.0, 1.0, 9.0];
        let cost = |c: u32| Some(costs[(c - 10) as usize]);
        // λ = 0: the greatest gain.
        let g = best(&[1.0, 2.0, 8.0, 3.0], &cells, 0.0, cost).expect("some");
        assert_eq!(g.cell, 12);
        // Equal gains and λ = 0: the cheaper; equal cost too: the earlier.
        let g = best(&[2.0, 2.0, 2.0, 2.0], &cells, 0.0, cost).expect("some");
        assert_eq!(g.cell, 11);
        // Huge λ: the nearest.
        let g = best(&[100.0, 1.0, 2.0, 1e9], &cells, 1e9, cost).expect("some");
        assert_eq!((g.cell, g.cost), (12, 1.0));
        // All gains 0: the nearest.
        let g = best(&[0.0; 4], &cells, 0.01, cost).expect("some");
        assert_eq!(g.cell, 11);
        // Unreachable cells are skipped.
        assert!(best(&[1.0; 4], &cells, 0.0, |_| None).is_none());
    }
}
