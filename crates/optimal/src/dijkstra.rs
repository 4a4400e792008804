//! Grid Dijkstra with reusable, generation-stamped buffers: the step cost of the search
//! (shortest paths inside the perceived free space) and the full-map distance fields the
//! heuristics read.
//!
//! Motion is DESIGN.md's: 8-connected, straight 1, diagonal √2, and a diagonal step is
//! forbidden iff both orthogonal cells it passes between are not passable (no squeezing
//! between two blocked cells sharing a vertex). Ties in the queue are broken by flat index.

use grid::for_each_move;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Dijkstra buffers for one `width × height` grid; a new search clears nothing of size O(map).
#[derive(Clone, Debug)]
pub struct Dijkstra {
    width: usize,
    height: usize,
    dist: Vec<f64>,
    pred: Vec<u32>,
    stamp: Vec<u32>,
    done: Vec<u32>,
    epoch: u32,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    settled: Vec<u32>,
}

impl Dijkstra {
    /// Buffers for searches on a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        let n = width * height;
        Self {
            width,
            height,
            dist: vec![f64::INFINITY; n],
            pred: vec![u32::MAX; n],
            stamp: vec![0; n],
            done: vec![0; n],
            epoch: 0,
            heap: BinaryHeap::new(),
            settled: Vec::new(),
        }
    }

    /// Full search from `start` over cells where `passable(i)` (the start is always allowed).
    /// Cells are settled in order of `(distance, index)`; [`settled`](Self::settled) lists them.
    pub fn run(&mut self, start: usize, passable: impl Fn(usize) -> bool) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.fill(0);
            self.done.fill(0);
            self.epoch = 1;
        }
        self.heap.clear();
        self.settled.clear();
        let e = self.epoch;
        self.dist[start] = 0.0;
        self.pred[start] = start as u32;
        self.stamp[start] = e;
        self.heap.push(Reverse((0f64.to_bits(), start as u32)));
        let (w, h) = (self.width, self.height);
        while let Some(Reverse((bits, i))) = self.heap.pop() {
            let i = i as usize;
            if self.done[i] == e {
                continue;
            }
            let d = f64::from_bits(bits);
            self.done[i] = e;
            self.settled.push(i as u32);
            let (dist, stamp, pred, heap) = (
                &mut self.dist,
                &mut self.stamp,
                &mut self.pred,
                &mut self.heap,
            );
            for_each_move(w, h, i, &passable, |j, step| {
                let nd = d + step;
                if stamp[j] != e || nd < dist[j] {
                    stamp[j] = e;
                    dist[j] = nd;
                    pred[j] = i as u32;
                    heap.push(Reverse((nd.to_bits(), j as u32)));
                }
            });
        }
    }

    /// Distance of cell `i` in the last search (`∞` if it was not reached).
    #[inline]
    pub fn dist(&self, i: usize) -> f64 {
        if self.done[i] == self.epoch {
            self.dist[i]
        } else {
            f64::INFINITY
        }
    }

    /// The cells reached by the last search, in settling order (start first).
    pub fn settled(&self) -> &[u32] {
        &self.settled
    }

    /// The path from the last search's start to `i` (both included), appended to `out`;
    /// nothing if `i` was not reached.
    pub fn path_to(&self, i: usize, out: &mut Vec<u32>) {
        if self.done[i] != self.epoch {
            return;
        }
        let from = out.len();
        let mut c = i;
        loop {
            out.push(c as u32);
            let p = self.pred[c] as usize;
            if p == c {
                break;
            }
            c = p;
        }
        out[from..].reverse();
    }
}
