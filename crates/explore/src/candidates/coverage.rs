//! Coverage candidates (Faigl & Kulich 2013, §IV, Algorithm 1, CC).
//!
//! For every reachable frontier cell f_i, the covering cells C_i are the reachable cells
//! from which a laser of range 0.8 ρ sees f_i (Line 3, ray casting; the shorter range
//! "supports navigation towards frontiers"). Then, while some frontier is uncovered, the
//! covering cell that sees the most still-uncovered frontiers becomes a goal candidate
//! (Lines 9–13). Deterministic: ties go to the lower cell index.
//!
//! How it is computed: visibility under the exact segment rule of `sense::segment` is
//! symmetric between two free cells (the same cells are crossed and the same vertices
//! touched either way, and both ends are free), so C_i is what a line-of-sight scan *from*
//! f_i sees: one walk of the shared ray template per frontier cell over the belief
//! (unknown cells are opaque), keeping free cells that are traversable, reachable and not
//! on the goal lists. The incidences go into two flat adjacency arrays (frontier →
//! covering cells, covering cell → frontiers), and the greedy choice uses a lazy max-heap
//! on the uncovered counts (counts only fall, so a popped entry whose count is current is
//! the maximum). Cost ∝ the number of (frontier, covering cell) pairs; all buffers live in
//! [`State`] and are reused.
//!
//! Choices where the paper is silent:
//! - "reachable" is reachability from the first deciding robot (all free space of a run is
//!   one component; Faigl & Kulich assume the same);
//! - frontier cells on the visited/inaccessible lists are not to be covered (a robot stood
//!   there and sensed), and listed cells are never candidates; a frontier cell that no
//!   eligible cell sees is left uncovered rather than looping;
//! - the ray casting is the ideal laser of `sense` (`los`) whatever the robots' sensor is,
//!   as the paper's omnidirectional scanner; ρ is the run's sensor range in cells.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use sense::{LosSensor, MAX_TEMPLATE_RANGE_CELLS};

use super::CandidateSet;
use crate::decision::DecisionCtx;

/// Fraction of the sensor range used for covering (Faigl & Kulich: 0.8 ρ).
pub const COVER_FRACTION: f64 = 0.8;

/// `cid` of a cell already found not to be a covering cell in this decision.
const NOT_ELIGIBLE: u32 = u32::MAX;

/// Visibility buffers and the last cover, kept across decisions.
#[derive(Default)]
pub struct State {
    /// Range the sensor was built for, and the sensor.
    sensor: Option<(f64, LosSensor)>,
    /// F: the frontier cells to cover.
    front: Vec<u32>,
    /// Frontier k's covering candidates are `f_cov[f_start[k]..f_start[k + 1]]` (ids).
    f_start: Vec<u32>,
    f_cov: Vec<u32>,
    /// Candidate id of each map cell (or `NOT_ELIGIBLE`), valid where `stamp == epoch`.
    cid: Vec<u32>,
    stamp: Vec<u32>,
    epoch: u32,
    /// Candidate id → cell.
    cands: Vec<u32>,
    /// Candidate id → number of uncovered frontiers it sees.
    count: Vec<u32>,
    /// Candidate id → the frontiers (indices into `front`) it sees, flat.
    c_start: Vec<u32>,
    c_front: Vec<u32>,
    fill: Vec<u32>,
    covered: Vec<bool>,
    heap: BinaryHeap<(u32, Reverse<u32>, u32)>,
    /// The chosen candidates in order, and the frontier cells credited to each.
    chosen: Vec<u32>,
    credit_start: Vec<u32>,
    credit: Vec<u32>,
}

impl State {
    /// The frontier cells the last decision had to cover.
    pub fn frontiers(&self) -> &[u32] {
        &self.front
    }

    /// The candidates of the last decision in the order chosen, each with the frontier
    /// cells it newly covered when chosen.
    pub fn credits(&self) -> impl Iterator<Item = (u32, &[u32])> + '_ {
        self.chosen.iter().enumerate().map(|(k, &c)| {
            let (a, b) = (
                self.credit_start[k] as usize,
                self.credit_start[k + 1] as usize,
            );
            (c, &self.credit[a..b])
        })
    }
}

/// Fill `out` with a greedy cover of the reachable frontier cells.
pub fn generate(ctx: &mut DecisionCtx<'_>, out: &mut CandidateSet) {
    let mut st = std::mem::take(&mut ctx.memory.coverage);
    cover(ctx, &mut st);
    for &c in &st.chosen {
        out.insert(c);
    }
    ctx.memory.coverage = st;
}

fn cover(ctx: &mut DecisionCtx<'_>, st: &mut State) {
    st.front.clear();
    st.f_start.clear();
    st.f_cov.clear();
    st.cands.clear();
    st.count.clear();
    st.chosen.clear();
    st.credit.clear();
    st.credit_start.clear();
    st.credit_start.push(0);
    let Some(r) = ctx.deciding.iter().position(|&d| d) else {
        return;
    };
    let range = (COVER_FRACTION * ctx.sensor_range_cells).clamp(0.0, MAX_TEMPLATE_RANGE_CELLS);
    let range = if range.is_finite() { range } else { 0.0 };
    if st.sensor.as_ref().is_none_or(|(r0, _)| *r0 != range) {
        match LosSensor::new(range) {
            Ok(s) => st.sensor = Some((range, s)),
            Err(_) => return, // unreachable: the range was clamped into the valid interval
        }
    }
    let n = ctx.known.len();
    if st.cid.len() != n {
        st.cid = vec![0; n];
        st.stamp = vec![0; n];
        st.epoch = 0;
    }
    st.epoch = crate::upkeep::next_gen(st.epoch, &mut st.stamp);

    let known = ctx.known;
    let lists = ctx.lists;
    let reach = ctx.planner.component(r, ctx.robots[r], known, ctx.upkeep);
    let upkeep = &*ctx.upkeep;
    let sensor = &st.sensor.as_ref().expect("built above").1;
    let origin_of = |c: u32| known.cell(c as usize);

    // Lines 2–4: covering cells of every frontier cell.
    for &f in upkeep.frontiers.cells() {
        if lists.is_excluded(f) || !reach.contains(f as usize) {
            continue;
        }
        st.front.push(f);
    }
    // Frontier order is the upkeep's (history dependent); sort for determinism by index.
    st.front.sort_unstable();
    let (cid, stamp, epoch) = (&mut st.cid, &mut st.stamp, st.epoch);
    let (cands, count, f_cov, f_start) =
        (&mut st.cands, &mut st.count, &mut st.f_cov, &mut st.f_start);
    for &f in &st.front {
        f_start.push(f_cov.len() as u32);
        sensor.for_each_seen(known, origin_of(f), |i, _| {
            let iu = i as usize;
            if stamp[iu] == epoch {
                let id = cid[iu];
                if id != NOT_ELIGIBLE {
                    f_cov.push(id);
                    count[id as usize] += 1;
                }
                return;
            }
            stamp[iu] = epoch;
            if !upkeep.is_traversable(known, iu) || lists.is_excluded(i) || !reach.contains(iu) {
                cid[iu] = NOT_ELIGIBLE;
                return;
            }
            let id = cands.len() as u32;
            cid[iu] = id;
            cands.push(i);
            count.push(1);
            f_cov.push(id);
        });
    }
    f_start.push(f_cov.len() as u32);

    // Lines 5–8: the frontiers each covering cell sees (transpose).
    let nc = st.cands.len();
    st.c_start.clear();
    st.c_start.reserve(nc + 1);
    let mut acc = 0u32;
    st.c_start.push(0);
    for &c in &st.count {
        acc += c;
        st.c_start.push(acc);
    }
    st.c_front.clear();
    st.c_front.resize(acc as usize, 0);
    st.fill.clear();
    st.fill.extend_from_slice(&st.c_start[..nc]);
    for k in 0..st.front.len() {
        for &id in &st.f_cov[st.f_start[k] as usize..st.f_start[k + 1] as usize] {
            let slot = &mut st.fill[id as usize];
            st.c_front[*slot as usize] = k as u32;
            *slot += 1;
        }
    }

    // Lines 9–13: greedy cover with a lazy max-heap, ties to the lower cell index.
    st.covered.clear();
    st.covered.resize(st.front.len(), false);
    st.heap.clear();
    for (id, (&c, &cnt)) in st.cands.iter().zip(&st.count).enumerate() {
        st.heap.push((cnt, Reverse(c), id as u32));
    }
    while let Some((cnt, Reverse(cell), id)) = st.heap.pop() {
        let now = st.count[id as usize];
        if now == 0 {
            continue;
        }
        if now != cnt {
            st.heap.push((now, Reverse(cell), id));
            continue;
        }
        st.chosen.push(cell);
        let (a, b) = (
            st.c_start[id as usize] as usize,
            st.c_start[id as usize + 1] as usize,
        );
        for &k in &st.c_front[a..b] {
            let k = k as usize;
            if st.covered[k] {
                continue;
            }
            st.covered[k] = true;
            st.credit.push(st.front[k]);
            for &other in &st.f_cov[st.f_start[k] as usize..st.f_start[k + 1] as usize] {
                st.count[other as usize] -= 1;
            }
        }
        st.credit_start.push(st.credit.len() as u32);
    }
}
