//! The unguided searches in canonical order (Sturtevant & Rabin, "Canonical Orderings on
//! Grids", IJCAI 2016): the same costs, settled cells and paths as Dial's search, with far
//! fewer queue entries and neighbour tests.
//!
//! Every shortest path on an 8-connected grid can be taken in a canonical order: diagonal
//! steps first, then straight steps in one of the diagonal's two directions, turning only at
//! cells beside an obstacle (jump points). The search queues only jump points, by the
//! bucket of their cost; from each it walks its canonical successors (the diagonal, and
//! from every cell of the diagonal the two straight rows), labelling cells as it walks, and
//! queues a cell of a walk when an obstacle beside it opens a direction the walk does not
//! cover (a forced neighbour). A walk stops at an impassable cell, at a cell labelled more
//! cheaply, or at one labelled as cheaply by a walk in the same direction.
//!
//! A walk labels cells far beyond the bucket being settled, so every label also goes on the
//! list of its cost's bucket. A walk from a jump point of cost c labels cells of cost at
//! least c + 1, and the last jump point on a cell's canonical shortest path is cheaper than
//! the cell by at least a step: when bucket k is reached, every jump point of an earlier
//! bucket has been walked, so every cost in `[k, k + 1)` is final and bucket k's list holds
//! every such cell. Settling the bucket is reading its list; the settled cells, the order
//! of the bucket where a nearest-goal search ends and the resumable growth are Dial's.
//!
//! Costs are sums of 1 and [`grid::SQRT2`], exact whatever the order of the steps, so a cell
//! walked to along another shortest path than Dijkstra's gets the same bits. Passability is
//! asked each time a walk looks at a cell (each cell is looked at by the walks of three
//! rows or columns): the planner's passability is a bit set, cheaper to read again than an
//! answer cached in the tiled states. Only labels and settled cells are marked there, so
//! [`Reachability::predecessor`]'s test of the cells beside a diagonal step reads the same
//! thing as after Dial's search: a passable cell beside a settled one is settled before
//! any cell a diagonal step from there reaches.
//!
//! Speed: on willow-full with 5 robots, MA's decisions take 13–31 % less than with Dial's
//! search (docs/teams.md); a standalone full search on floor plans ran 2–4 times faster.
//! Scattered single obstacles are the worst case, each making jump points of its
//! neighbours: the plan bench's map (3 % of its cells) takes 1.7 times Dial's time.

use super::{BLOCKED, DONE, Entry, MET, Reachability, TILE_CELLS, enter_tile, slot_xy};
use grid::SQRT2;
use std::mem::take;

/// How many buckets beyond the one being settled a walk may label: a walk that would go
/// further queues its last cell to go on from later. Walks that ran to the end labelled
/// cells far beyond where a nearest-goal or resumable search stops, and spread their
/// labels over thousands of buckets, each write to another buffer's end; a few buckets
/// ahead keep those buffers in the cache. At least 2, so that every walk takes a step.
const HORIZON: usize = 8;
const _: () = assert!(HORIZON >= 2);

/// A queued jump point: column, row, the direction to walk (see [`code`]) and its cost
/// when queued (stale once the cell's cost is lower).
#[derive(Clone, Copy, Debug)]
pub(super) struct Jump {
    x: u32,
    y: u32,
    dir: u8,
    cost: f64,
}

/// The code of a direction `(dx, dy)`: `(dy + 1) * 3 + dx + 1`; [`START`] walks every way.
#[inline(always)]
fn code(dx: i64, dy: i64) -> u8 {
    ((dy + 1) * 3 + dx + 1) as u8
}

/// Code 4, `(0, 0)`: a start, walked in all eight directions.
const START: u8 = 4;

/// The direction of code `c`.
#[inline(always)]
fn dir(c: u8) -> (i64, i64) {
    (i64::from(c % 3) - 1, i64::from(c / 3) - 1)
}

/// One bit per direction (a start's is every bit).
#[inline(always)]
fn bit(c: u8) -> u8 {
    match c {
        START => u8::MAX,
        c if c > START => 1 << (c - 1),
        c => 1 << c,
    }
}

/// A running canonical search over the fields of a [`Reachability`].
pub(super) struct Walk<'a, P> {
    width: usize,
    height: usize,
    tile_row: usize,
    epoch: u32,
    tile_epoch: &'a mut [u32],
    state: &'a mut [u8],
    /// Per slot: the walk directions that labelled the cell at its cost (low byte) and the
    /// jump directions walked from it at that cost (high byte).
    dirs: &'a mut [u16],
    cost: &'a mut [f64],
    queues: &'a mut Queues,
    passable: &'a P,
    /// Walks label no cost at or above this; they queue where they stopped instead.
    limit: f64,
}

/// The canonical search's buckets, by whole cost: the cells labelled in each, and the jump
/// points to walk from. Emptied buckets give their buffers back to a pool, so that a search
/// allocates nothing in steady state and holds buffers for the labels outstanding only.
#[derive(Clone, Debug, Default)]
pub(super) struct Queues {
    labelled: Vec<Vec<Entry>>,
    jumps: Vec<Vec<Jump>>,
    spare_labels: Vec<Vec<Entry>>,
    spare_jumps: Vec<Vec<Jump>>,
    /// One past the highest bucket that holds an entry.
    pub(super) end: usize,
}

impl Queues {
    /// Empty every bucket (a new search).
    pub(super) fn clear(&mut self) {
        for k in 0..self.end.min(self.labelled.len()) {
            self.recycle(k);
        }
        self.end = 0;
    }

    /// Give bucket `k`'s buffers back to the pool.
    fn recycle(&mut self, k: usize) {
        let (l, j) = (take(&mut self.labelled[k]), take(&mut self.jumps[k]));
        self.put_back(l, j);
    }

    /// Make bucket `k` exist.
    #[inline(always)]
    fn reach(&mut self, k: usize) {
        if self.labelled.len() <= k {
            self.labelled.resize_with(k + 1, Vec::new);
            self.jumps.resize_with(k + 1, Vec::new);
        }
        self.end = self.end.max(k + 1);
    }

    #[inline(always)]
    fn label(&mut self, k: usize, xy: Entry) {
        self.reach(k);
        push_pooled(&mut self.labelled[k], &mut self.spare_labels, xy);
    }

    #[inline(always)]
    fn jump(&mut self, k: usize, j: Jump) {
        self.reach(k);
        push_pooled(&mut self.jumps[k], &mut self.spare_jumps, j);
    }

    /// Take bucket `k`'s labelled cells and jump points (empty if it does not exist).
    pub(super) fn take(&mut self, k: usize) -> (Vec<Entry>, Vec<Jump>) {
        if k >= self.labelled.len() {
            return (Vec::new(), Vec::new());
        }
        (take(&mut self.labelled[k]), take(&mut self.jumps[k]))
    }

    /// Give back bucket `k`'s buffers taken by [`take`](Self::take), emptied.
    pub(super) fn put_back(&mut self, labels: Vec<Entry>, jumps: Vec<Jump>) {
        give_back(labels, &mut self.spare_labels);
        give_back(jumps, &mut self.spare_jumps);
    }
}

/// Push `x` to bucket buffer `b`, which takes a buffer from `spare` if it has none.
#[inline(always)]
fn push_pooled<T>(b: &mut Vec<T>, spare: &mut Vec<Vec<T>>, x: T) {
    if b.capacity() == 0 {
        *b = spare.pop().unwrap_or_default();
    }
    b.push(x);
}

/// Empty buffer `v` into the pool `spare` (unless it never held anything).
fn give_back<T>(mut v: Vec<T>, spare: &mut Vec<Vec<T>>) {
    if v.capacity() > 0 {
        v.clear();
        spare.push(v);
    }
}

impl<'a, P: Fn(usize) -> bool> Walk<'a, P> {
    /// The search over `r`'s fields with `passable`.
    pub(super) fn new(r: &'a mut Reachability, passable: &'a P) -> Self {
        Walk {
            width: r.width,
            height: r.height,
            tile_row: r.tiles_x * TILE_CELLS,
            epoch: r.epoch,
            tile_epoch: &mut r.tile_epoch,
            state: &mut r.state,
            dirs: &mut r.dirs,
            cost: &mut r.cost,
            queues: &mut r.queues,
            passable,
            limit: f64::INFINITY,
        }
    }

    /// Walk from the jump points of bucket `k` only as far as [`HORIZON`] buckets ahead.
    pub(super) fn at_bucket(mut self, k: usize) -> Self {
        self.limit = (k + 1 + HORIZON) as f64;
        self
    }

    /// The slot of column `x`, row `y` (inside the grid), its tile's states made valid for
    /// this search.
    #[inline(always)]
    fn slot(&mut self, x: usize, y: usize) -> usize {
        let q = slot_xy(self.tile_row, x, y);
        if let Some(t) = enter_tile(self.tile_epoch, self.epoch, q) {
            self.state[t.clone()].fill(0);
            self.dirs[t].fill(0);
        }
        q
    }

    /// Whether column `x`, row `y` is a passable cell of the grid. Asked again each time (the
    /// cells beside a walk are asked by the walks of three rows): the planner's passability
    /// is a bit set, cheaper to read than a cached answer in the tiled states.
    #[inline(always)]
    fn pass(&self, x: i64, y: i64) -> bool {
        x >= 0
            && y >= 0
            && x < self.width as i64
            && y < self.height as i64
            && (self.passable)(y as usize * self.width + x as usize)
    }

    /// Label start `(x, y)` (in the grid) at cost 0 and queue it, unless listed already.
    pub(super) fn start(&mut self, x: usize, y: usize) {
        let q = self.slot(x, y);
        if self.state[q] & MET != 0 {
            return; // listed twice (starts are labelled before any walk)
        }
        let open = (self.passable)(y * self.width + x);
        self.state[q] = if open { MET } else { MET | BLOCKED };
        self.cost[q] = 0.0;
        self.dirs[q] = 0xff00; // nothing else walks into a start (cost 0) but as cheaply
        let xy = (x as u32, y as u32);
        self.queues.label(0, xy);
        self.queues.jump(
            0,
            Jump {
                x: xy.0,
                y: xy.1,
                dir: START,
                cost: 0.0,
            },
        );
    }

    /// Label passable cell `(x, y)` with cost `c` by a walk in direction `d`; whether the
    /// walk goes on through it.
    #[inline(always)]
    fn label(&mut self, x: usize, y: usize, c: f64, d: u8) -> bool {
        let q = self.slot(x, y);
        let s = self.state[q];
        let b = u16::from(bit(d));
        if s & MET == 0 || c < self.cost[q] {
            debug_assert!(s & DONE == 0, "a settled cell labelled more cheaply");
            self.state[q] = MET;
            self.cost[q] = c;
            self.dirs[q] = b;
            self.queues.label(c as usize, (x as u32, y as u32));
            true
        } else if c == self.cost[q] && self.dirs[q] & b == 0 {
            self.dirs[q] |= b;
            true
        } else {
            false
        }
    }

    /// Walk from jump point `j` unless it is stale or walked already.
    pub(super) fn expand(&mut self, j: Jump) {
        let (x, y) = (j.x as usize, j.y as usize);
        let q = self.slot(x, y);
        if self.cost[q] != j.cost {
            return; // labelled more cheaply since
        }
        let b = u16::from(bit(j.dir)) << 8;
        if j.dir != START {
            if self.dirs[q] & b == b {
                return;
            }
            self.dirs[q] |= b;
        }
        let (x, y) = (i64::from(j.x), i64::from(j.y));
        if j.dir == START {
            for (dx, dy) in [(1, 1), (-1, 1), (-1, -1), (1, -1)] {
                self.diagonal(x, y, j.cost, dx, dy);
            }
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                self.straight(x, y, j.cost, dx, dy);
            }
        } else {
            let (dx, dy) = dir(j.dir);
            if dx != 0 && dy != 0 {
                self.diagonal(x, y, j.cost, dx, dy);
            } else {
                self.straight(x, y, j.cost, dx, dy);
            }
        }
    }

    #[inline(always)]
    fn queue(&mut self, x: i64, y: i64, dx: i64, dy: i64, cost: f64) {
        let j = Jump {
            x: x as u32,
            y: y as u32,
            dir: code(dx, dy),
            cost,
        };
        self.queues.jump(cost as usize, j);
    }

    /// Walk straight from `(x, y)` (cost `c`) in direction `(dx, dy)`. Each cell's
    /// passability and its two sides' are asked once, when the walk looks a cell ahead.
    fn straight(&mut self, x: i64, y: i64, c: f64, dx: i64, dy: i64) {
        let d = code(dx, dy);
        // across the walk
        let (sx, sy) = (dy.abs(), dx.abs());
        let (mut x, mut y, mut c) = (x, y, c);
        let (ax, ay) = (x + dx, y + dy);
        if !self.pass(ax, ay) {
            return;
        }
        // the sides of the cell ahead
        let mut side = [self.pass(ax + sx, ay + sy), self.pass(ax - sx, ay - sy)];
        loop {
            let (nx, ny) = (x + dx, y + dy);
            if c + 1.0 >= self.limit {
                self.queue(x, y, dx, dy, c); // go on from here later
                return;
            }
            c += 1.0;
            if !self.label(nx as usize, ny as usize, c, d) {
                return;
            }
            let (fx, fy) = (nx + dx, ny + dy);
            if !self.pass(fx, fy) {
                return;
            }
            let ahead = [self.pass(fx + sx, fy + sy), self.pass(fx - sx, fy - sy)];
            // forced: beside this cell blocked, beside the next one open (the diagonal step
            // between them is legal: the next cell is open)
            for (k, s) in [(0, 1), (1, -1)] {
                if !side[k] && ahead[k] {
                    self.queue(nx, ny, dx + s * sx, dy + s * sy, c);
                }
            }
            side = ahead;
            (x, y) = (nx, ny);
        }
    }

    /// Walk diagonally from `(x, y)` (cost `c`) in direction `(dx, dy)`, and straight from
    /// every cell of the diagonal in its two directions.
    fn diagonal(&mut self, x: i64, y: i64, c: f64, dx: i64, dy: i64) {
        let d = code(dx, dy);
        let (mut x, mut y, mut c) = (x, y, c);
        loop {
            let (nx, ny) = (x + dx, y + dy);
            // the step passes between (nx, y) and (x, ny): one must be passable
            if !self.pass(nx, ny) || !(self.pass(nx, y) || self.pass(x, ny)) {
                return;
            }
            if c + SQRT2 >= self.limit {
                self.queue(x, y, dx, dy, c); // go on from here later
                return;
            }
            c += SQRT2;
            if !self.label(nx as usize, ny as usize, c, d) {
                return;
            }
            // forced: behind one side blocked, the cell past it open, and the step legal
            if !self.pass(nx - dx, ny) && self.pass(nx - dx, ny + dy) && self.pass(nx, ny + dy) {
                self.queue(nx, ny, -dx, dy, c);
            }
            if !self.pass(nx, ny - dy) && self.pass(nx + dx, ny - dy) && self.pass(nx + dx, ny) {
                self.queue(nx, ny, dx, -dy, c);
            }
            self.straight(nx, ny, c, dx, 0);
            self.straight(nx, ny, c, 0, dy);
            (x, y) = (nx, ny);
        }
    }
}
