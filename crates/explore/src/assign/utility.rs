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
//! origin's, and a scan whose field of view is at most 180° only cells whose centres lie at
//! most √2/2 behind the line through the origin across its heading (the arrival heading the
//! gain will be evaluated with). So `B(p)` is the number of uncertain cells in that disc, or
//! half-disc, summed row by row from a summed-area table of the belief
//! ([`UncertainCounts`], built once per decision); an evaluated gain is its own bound. A
//! candidate whose disc holds no uncertain cell has gain 0 and is never evaluated. The tie rule
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

use sense::{Belief, Pose, Sensor};

use crate::candidates::CandidateSet;
use crate::candidates::dt_samples::{State, arrival_heading};
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
        let mut uncertain = std::mem::take(&mut st.uncertain);
        uncertain.build(ctx.belief);
        let mut bound = std::mem::take(&mut st.bound);
        bound.set(ctx.sensor_range_cells, ctx.sensor.field_of_view_deg());
        for (r, slot) in out.iter_mut().enumerate().take(m) {
            if ctx.deciding[r] {
                *slot = best_lazy(ctx, &mut st, r, lambda * ctx.resolution, &uncertain, &bound);
            }
        }
        st.uncertain = uncertain;
        st.bound = bound;
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
    uncertain: &UncertainCounts,
    bound: &GainBound,
) -> Option<Goal> {
    let planner = &*ctx.planner;
    let reach = planner.map(r);
    let width = ctx.known.width();
    let omni = ctx.sensor.is_omnidirectional();
    let mut order = std::mem::take(&mut st.order);
    order.clear();
    order.extend(st.cells.iter().enumerate().filter_map(|(k, &c)| {
        let l = reach.cost(c as usize)?;
        let b = if st.gains[k].is_nan() {
            // The heading the gain will be evaluated with (State::gain).
            let heading = if omni {
                0.0
            } else {
                let by = planner.map(st.reachers[k] as usize);
                arrival_heading(ctx.known, by, c)
            };
            bound.of(uncertain, c as usize % width, c as usize / width, heading)
        } else {
            st.gains[k]
        };
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
        let ternary = belief.is_ternary();
        let data = known.data();
        for y in 0..h {
            let mut row = 0u32;
            for x in 0..w {
                let i = y * w + x;
                row += u32::from(if ternary {
                    data[i] == grid::Occ::Unknown
                } else {
                    let p = belief.p_occupied(i);
                    p > 0.0 && p < 1.0
                });
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

/// An upper bound on the gain of any scan from a cell (module doc): the uncertain cells whose
/// centres lie within `R + √2/2` of the origin's (row by row, from the counts' table), and
/// for a field of view of at most 180° only those not more than √2/2 behind the line
/// through the origin across the heading.
#[derive(Clone, Debug, Default)]
pub struct GainBound {
    /// Half-width of the disc's row at each row offset `0..=reach`.
    half_widths: Vec<i64>,
    /// Whether the field of view is at most 180° (the half-plane cut applies).
    forward_only: bool,
}

/// How far behind the line across the heading a touched cell's centre can lie: the half
/// diagonal of a cell, plus room for rounding.
const BEHIND: f64 = std::f64::consts::FRAC_1_SQRT_2 + 1e-6;

impl GainBound {
    /// The bound for a sensor of range `range` cells and field of view `fov_deg` degrees.
    pub fn new(range: f64, fov_deg: f64) -> Self {
        let mut b = Self::default();
        b.set(range, fov_deg);
        b
    }

    /// Re-target to a sensor of range `range` cells and field of view `fov_deg` (keeps buffers).
    pub fn set(&mut self, range: f64, fov_deg: f64) {
        // A touched cell is entered by a ray at a distance < R, so its centre is within
        // R + √2/2 of the origin's.
        let rho = range.max(0.0) + BEHIND;
        let reach = rho.floor() as i64;
        self.half_widths.clear();
        self.half_widths.extend(
            (0..=reach)
                .map(|dy| ((rho * rho - (dy * dy) as f64).max(0.0).sqrt() + 1e-9).floor() as i64),
        );
        self.forward_only = fov_deg <= 180.0;
    }

    /// The bound for a scan from `(x, y)` looking along `heading` (radians; ignored unless
    /// the field of view is at most 180°).
    pub fn of(&self, counts: &UncertainCounts, x: usize, y: usize, heading: f64) -> f64 {
        let (w, h) = (counts.width as i64, counts.height as i64);
        let (x, y) = (x as i64, y as i64);
        let (hx, hy) = if self.forward_only {
            (heading.cos(), heading.sin())
        } else {
            (0.0, 0.0)
        };
        let reach = self.half_widths.len() as i64 - 1;
        let mut n = 0u32;
        for dy in -reach..=reach {
            let row = y + dy;
            if row < 0 || row >= h {
                continue;
            }
            let hw = self.half_widths[dy.unsigned_abs() as usize];
            let (mut lo, mut hi) = (-hw, hw);
            if self.forward_only {
                // Keep dx with hx·dx + hy·dy ≥ −BEHIND, widened by a cell for rounding.
                let q = -BEHIND - hy * dy as f64;
                if hx > 1e-9 {
                    lo = lo.max((q / hx).ceil() as i64 - 1);
                } else if hx < -1e-9 {
                    hi = hi.min((q / hx).floor() as i64 + 1);
                } else if q > 1e-6 {
                    continue;
                }
            }
            let (x0, x1) = ((x + lo).max(0), (x + hi + 1).min(w));
            if x0 < x1 {
                n += counts.count(x0 as usize, row as usize, x1 as usize, row as usize + 1);
            }
        }
        if n == 0 {
            return 0.0;
        }
        // A sum of at most n drops of at most 1 bit each, with room for rounding.
        f64::from(n) * (1.0 + 1e-12) + 1e-9
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
    let gain = dt.gain_at(sensor, belief, target);
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
