//! Holz et al.'s reachability map: Dijkstra from the robot's cell with no goal, and the same
//! search stopping at the first settled goal cell (the nearest frontier, Yamauchi 1997).
//!
//! The priority queue is a bucket queue (Dial's algorithm with buckets one cell-step wide):
//! bucket k holds the cells whose cost lies in [k, k + 1). Every step costs at least 1, so a
//! cell settled from bucket k only labels cells in buckets k + 1 and k + 2, and when bucket k
//! is reached every cost in it is final: the search is exact, not an approximation, and
//! three buckets used in turn hold the whole wavefront. This replaces a binary heap and makes
//! a full map about twice as fast. Within a bucket cells are taken in the order (cost, index),
//! so the cells settle in exactly the order a heap on (cost, index) gives, ties included, and
//! every cost, predecessor and goal found is the heap's.
//!
//! Costs and predecessors live in generation-stamped arrays, so a new search does not clear
//! O(map) memory, and the buckets and the settled list keep their capacity: in steady state a
//! search allocates nothing and touches only the cells it labels.

use crate::upkeep::next_gen;
use grid::for_each_move;

/// Buckets in use at once: a step costs at most √2 < 2, so labels reach two buckets ahead.
const BUCKETS: usize = 3;

/// Dijkstra over passable cells from one start: cost and predecessor per cell, path extraction.
#[derive(Clone, Debug)]
pub struct Reachability {
    width: usize,
    height: usize,
    /// Tentative or final cost of a cell labelled in the current epoch.
    cost: Vec<f64>,
    /// Predecessor of a cell labelled in the current epoch (the start is its own predecessor).
    pred: Vec<u32>,
    /// `labelled[i] == epoch` iff cell `i` has a cost in the current search.
    labelled: Vec<u32>,
    /// `done[i] == epoch` iff cell `i` was settled in the current search.
    done: Vec<u32>,
    epoch: u32,
    /// Bucket `k % BUCKETS` holds the cells labelled with a cost in `[k, k + 1)` (and stale
    /// entries of cells labelled again more cheaply, skipped when met).
    buckets: [Vec<u32>; BUCKETS],
    /// The live cells of the bucket being settled, as `(cost bits, cell)`, sorted.
    order: Vec<(u64, u32)>,
    settled: Vec<u32>,
    start: Option<usize>,
}

impl Reachability {
    /// Buffers for searches on a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        let n = width * height;
        Self {
            width,
            height,
            cost: vec![0.0; n],
            pred: vec![0; n],
            labelled: vec![0; n],
            done: vec![0; n],
            epoch: 0,
            buckets: Default::default(),
            order: Vec::new(),
            settled: Vec::new(),
            start: None,
        }
    }

    /// Full Dijkstra from `start` over cells where `passable(i)` (the start itself is always
    /// allowed). A start outside the grid gives an empty result.
    pub fn compute(&mut self, start: usize, passable: impl Fn(usize) -> bool) {
        self.run(start, &passable, |_| false);
    }

    /// Dijkstra from `start` that stops at the first settled cell with `is_goal(i)` (which may be
    /// the start itself) and returns it; `None` if no reachable cell is a goal. Afterwards
    /// [`cost`](Self::cost) and [`path_to`](Self::path_to) are valid for every settled cell.
    pub fn nearest(
        &mut self,
        start: usize,
        passable: impl Fn(usize) -> bool,
        is_goal: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        self.run(start, &passable, is_goal)
    }

    fn run(
        &mut self,
        start: usize,
        passable: &impl Fn(usize) -> bool,
        is_goal: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        self.epoch = next_gen(self.epoch, &mut self.labelled);
        if self.epoch == 1 {
            // the labelled stamps were just cleared (first search or wrap-around): clear `done`
            self.done.fill(0);
        }
        for b in &mut self.buckets {
            b.clear();
        }
        self.settled.clear();
        if start >= self.cost.len() {
            self.start = None;
            return None;
        }
        self.start = Some(start);
        let epoch = self.epoch;
        self.labelled[start] = epoch;
        self.cost[start] = 0.0;
        self.pred[start] = start as u32;
        self.buckets[0].push(start as u32);
        let (w, h) = (self.width, self.height);
        let mut k = 0usize;
        loop {
            let slot = k % BUCKETS;
            if self.buckets[slot].is_empty() {
                if self.buckets.iter().all(Vec::is_empty) {
                    return None;
                }
                k += 1;
                continue;
            }
            // Every cost in bucket k is final: take its live cells in (cost, index) order.
            self.order.clear();
            for &i in &self.buckets[slot] {
                let iu = i as usize;
                if self.done[iu] != epoch {
                    debug_assert_eq!(self.cost[iu] as usize, k);
                    self.order.push((self.cost[iu].to_bits(), i));
                }
            }
            self.buckets[slot].clear();
            self.order.sort_unstable();
            self.order.dedup();
            let (cost, pred, labelled, done, buckets, order, settled) = (
                &mut self.cost,
                &mut self.pred,
                &mut self.labelled,
                &mut self.done,
                &mut self.buckets,
                &self.order,
                &mut self.settled,
            );
            for &(_, i) in order {
                let i = i as usize;
                done[i] = epoch;
                settled.push(i as u32);
                if is_goal(i) {
                    return Some(i);
                }
                let ci = cost[i];
                for_each_move(w, h, i, passable, |j, step| {
                    if done[j] == epoch {
                        return;
                    }
                    let c = ci + step;
                    if labelled[j] != epoch || c < cost[j] {
                        labelled[j] = epoch;
                        cost[j] = c;
                        pred[j] = i as u32;
                        buckets[c as usize % BUCKETS].push(j as u32);
                    }
                });
            }
            k += 1;
        }
    }

    /// Whether cell `i` was settled by the last search (its cost is final).
    #[inline]
    pub fn is_settled(&self, i: usize) -> bool {
        self.done.get(i) == Some(&self.epoch) && self.epoch != 0
    }

    /// Shortest-path cost in cells from the start to a settled cell (after `compute`: every
    /// reachable cell); `None` for cells not settled by the last search.
    #[inline]
    pub fn cost(&self, i: usize) -> Option<f64> {
        self.is_settled(i).then(|| self.cost[i])
    }

    /// Write the shortest path start..=goal (inclusive) to `out`; false (and `out` empty) if
    /// `goal` was not settled by the last search.
    pub fn path_to(&self, goal: usize, out: &mut Vec<u32>) -> bool {
        out.clear();
        if !self.is_settled(goal) {
            return false;
        }
        let mut c = goal;
        out.push(c as u32);
        while self.pred[c] as usize != c {
            c = self.pred[c] as usize;
            out.push(c as u32);
        }
        out.reverse();
        true
    }

    /// Cells in the order the last search settled them (non-decreasing cost).
    pub fn settled(&self) -> &[u32] {
        &self.settled
    }

    /// The start of the last search, if it was inside the grid.
    pub fn start(&self) -> Option<usize> {
        self.start
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }
}
