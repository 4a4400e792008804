//! A* between two cells with the octile heuristic (admissible and consistent for 8-connected
//! motion with costs 1 and √2), on generation-stamped buffers that are reused across calls.

use super::{HeapEntry, entry};
use crate::upkeep::next_gen;
use grid::SQRT2;
use grid::for_each_move;
use std::collections::BinaryHeap;

/// A* search buffers for a `width × height` grid.
#[derive(Clone, Debug)]
pub struct AStar {
    width: usize,
    height: usize,
    g: Vec<f64>,
    pred: Vec<u32>,
    labelled: Vec<u32>,
    done: Vec<u32>,
    epoch: u32,
    heap: BinaryHeap<HeapEntry>,
}

impl AStar {
    /// Buffers for searches on a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        let n = width * height;
        Self {
            width,
            height,
            g: vec![0.0; n],
            pred: vec![0; n],
            labelled: vec![0; n],
            done: vec![0; n],
            epoch: 0,
            heap: BinaryHeap::new(),
        }
    }

    /// Octile distance between cells `a` and `b`.
    #[inline]
    fn octile(&self, a: usize, b: usize) -> f64 {
        let (ax, ay) = (a % self.width, a / self.width);
        let (bx, by) = (b % self.width, b / self.width);
        let (dx, dy) = (ax.abs_diff(bx), ay.abs_diff(by));
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        (hi - lo) as f64 + SQRT2 * lo as f64
    }

    /// Shortest path cost in cells from `start` to `goal` over cells where `passable(i)` (the
    /// start is always allowed, the goal must be passable unless it is the start); the path
    /// start..=goal is written to `path`. `None` (and `path` empty) if unreachable or either
    /// cell is outside the grid.
    pub fn search(
        &mut self,
        start: usize,
        goal: usize,
        passable: impl Fn(usize) -> bool,
        path: &mut Vec<u32>,
    ) -> Option<f64> {
        path.clear();
        let n = self.g.len();
        if start >= n || goal >= n {
            return None;
        }
        self.epoch = next_gen(self.epoch, &mut self.labelled);
        if self.epoch == 1 {
            self.done.fill(0);
        }
        self.heap.clear();
        let epoch = self.epoch;
        self.labelled[start] = epoch;
        self.g[start] = 0.0;
        self.pred[start] = start as u32;
        self.heap.push(entry(self.octile(start, goal), start));
        let (w, h) = (self.width, self.height);
        while let Some(std::cmp::Reverse((_, i))) = self.heap.pop() {
            let i = i as usize;
            if self.done[i] == epoch {
                continue;
            }
            self.done[i] = epoch;
            if i == goal {
                let mut c = goal;
                path.push(c as u32);
                while self.pred[c] as usize != c {
                    c = self.pred[c] as usize;
                    path.push(c as u32);
                }
                path.reverse();
                return Some(self.g[goal]);
            }
            let gi = self.g[i];
            let (gx, gy) = (goal % w, goal / w);
            let (g, pred, labelled, done, heap) = (
                &mut self.g,
                &mut self.pred,
                &mut self.labelled,
                &self.done,
                &mut self.heap,
            );
            for_each_move(w, h, i, &passable, |j, step| {
                if done[j] == epoch {
                    return;
                }
                let c = gi + step;
                if labelled[j] != epoch || c < g[j] {
                    labelled[j] = epoch;
                    g[j] = c;
                    pred[j] = i as u32;
                    let (dx, dy) = ((j % w).abs_diff(gx), (j / w).abs_diff(gy));
                    let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
                    let hj = (hi - lo) as f64 + SQRT2 * lo as f64;
                    heap.push(entry(c + hj, j));
                }
            });
        }
        None
    }
}
