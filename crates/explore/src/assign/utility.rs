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
//! robot visits the candidates in order of path cost (then index) and evaluates a gain
//! only while `ln I_max − λL` could still beat the best `ln I − λL` found; the first
//! candidate it cannot beat ends the visit, since every later one is no nearer. `I_max` is
//! an upper bound on any scan's gain: each touched cell drops at most 1 bit (binary
//! entropy ≤ 1), and a scan of range R cells touches only cells whose centres lie within
//! R + √2/2 of the origin's centre; their unit squares are disjoint and lie in the disc of
//! radius R + √2, so there are at most π(R + √2)² of them (we use R + 2). The visit order
//! and the tie rule (greater utility, then lower cost, then lower index) make the choice the
//! one the full evaluation makes.
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
        let bound = (std::f64::consts::PI * (ctx.sensor_range_cells.max(0.0) + 2.0).powi(2)).ln();
        for (r, slot) in out.iter_mut().enumerate().take(m) {
            if ctx.deciding[r] {
                *slot = best_lazy(ctx, &mut st, r, lambda * ctx.resolution, bound);
            }
        }
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
/// order of cost, evaluated while `ln_bound − λL` can still beat the best; gain 0 is skipped.
fn best_lazy(
    ctx: &DecisionCtx<'_>,
    st: &mut State,
    r: usize,
    lambda_per_cell: f64,
    ln_bound: f64,
) -> Option<Goal> {
    let planner = &*ctx.planner;
    let reach = planner.map(r);
    let mut order = std::mem::take(&mut st.order);
    order.clear();
    order.extend(
        st.cells
            .iter()
            .enumerate()
            .filter_map(|(k, &c)| reach.cost(c as usize).map(|l| (l, k as u32))),
    );
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut best: Option<(f64, Goal)> = None;
    for &(l, k) in &order {
        if let Some((s, _)) = best
            && ln_bound - lambda_per_cell * l < s
        {
            break;
        }
        let k = k as usize;
        let by = planner.map(st.reachers[k] as usize);
        let gain = st.gain(k, ctx.sensor, ctx.belief, by);
        if gain <= 0.0 {
            continue;
        }
        let score = gain.ln() - lambda_per_cell * l;
        // visited by (cost, index): an equal score never replaces the best
        if best.is_none_or(|(s, _)| score > s) {
            best = Some((
                score,
                Goal {
                    cell: st.cells[k],
                    cost: l,
                },
            ));
        }
    }
    st.order = order;
    best.map(|(_, g)| g)
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
