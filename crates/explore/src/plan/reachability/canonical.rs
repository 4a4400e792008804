//! The searches in canonical order (Sturtevant & Rabin, "Canonical Orderings on Grids",
//! IJCAI 2016): the same costs, settled cells and paths as Dial's search, with far fewer
//! queue entries and neighbour tests; guided, the same as Dial's A* on its goals.
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
//! Guided (A* toward a set of goals, the bound of [`Guide`]): jump points are queued by the
//! bucket of their cost plus bound, and a walk goes [`GUIDED_HORIZON`] buckets past its
//! jump point's cost (more from farther jump points), then queues where it stopped. The
//! bound is consistent, so along a canonical shortest path cost plus bound never falls: the
//! jump points before a cell are in its bucket or earlier. A bucket is settled by walking
//! from its jump points, and from those its walks add to it, until none is left; then every
//! cell of cost plus bound below k + 1 has its final cost. Only the goals (a bit per cell)
//! and the start are listed by bucket, at their cost (their bound is 0), so the bound is
//! asked once per jump point, not per cell; the other cells are settled when the search is
//! complete. The path to a goal goes back over labelled cells: every neighbour that gives a
//! final cell its cost is final and no farther from the goals. Beside a diagonal step u → j
//! that gives j its cost, a passable cell is labelled by then: if u was labelled by a
//! diagonal walk in the step's direction, its two straight walks label both sides; by a
//! straight walk along one side, the walk labels that side, and the other side, if
//! passable, is a shortest way to j (a diagonal step from the walk's previous cell); by a
//! walk away from a side, its previous cell is that side; by a diagonal walk across the
//! step, its straight walk labels one side and the other cannot be passable (j would be
//! cheaper through it).
//!
//! Speed: on willow-full with 5 robots, MA's decisions take 13–31 % less than with Dial's
//! search, RFE's about half (docs/teams.md); a standalone full search on floor plans ran
//! 2–4 times faster.
//! Scattered single obstacles are the worst case, each making jump points of its
//! neighbours: the plan bench's map (3 % of its cells) takes 1.7 times Dial's time.

use super::{BLOCKED, DONE, Entry, MET, Reachability, TILE_CELLS, enter_tile, slot_xy};
use crate::plan::guide::Guide;
use grid::SQRT2;
use std::mem::take;

/// How many buckets beyond the one being settled a walk may label: a walk that would go
/// further queues its last cell to go on from later. Walks that ran to the end labelled
/// cells far beyond where a nearest-goal or resumable search stops, and spread their
/// labels over thousands of buckets, each write to another buffer's end; a few buckets
/// ahead keep those buffers in the cache. At least 2, so that every walk takes a step.
const HORIZON: usize = 8;
/// The least [`HORIZON`] of a guided search, whose walks toward the goals would otherwise
/// stop every few cells to queue a jump point and ask its bound: 16 took RFE's and AF's
/// team decisions on willow 10–15 % less time than 8 (4: 20–40 % more).
const GUIDED_HORIZON: usize = 16;
/// A guided search's horizon grows with its jump point's cost, one bucket for every
/// [`HORIZON_DIV`], up to this. The cells a walk labels beyond where the search stops are
/// a ring as wide as the horizon around what it settled, so in a search that goes far the
/// same share of waste allows a wider ring, and fewer jump points queued: on willow's
/// 5-robot runs the searches of `ma-cc`, `ma-rfe` and `minpos-af` took 15–20 % less time
/// (perf's shares) with 64 buckets than with 16, and the K-nearest searches of the Python
/// environment (a few metres) 10–30 % more, so one width does not suit both; 128 and 512
/// were as 64.
const GUIDED_HORIZON_MAX: usize = 64;
/// Cost (in buckets) of a jump point per bucket of its guided horizon (see
/// [`GUIDED_HORIZON_MAX`]).
const HORIZON_DIV: usize = 8;
const _: () = assert!(HORIZON >= 2 && GUIDED_HORIZON >= 2 && GUIDED_HORIZON_MAX >= GUIDED_HORIZON);

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
    /// A guided search's guide (jump points by the bucket of cost plus bound, only the
    /// goals and the start listed as labels), and the bucket being settled.
    guide: Option<&'a mut Guide>,
    current: usize,
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
    /// Cells a guided search has labelled: its work, as it settles only its goals until
    /// it is complete.
    pub(super) labelled_cells: usize,
}

impl Queues {
    /// Empty every bucket (a new search).
    pub(super) fn clear(&mut self) {
        for k in 0..self.end.min(self.labelled.len()) {
            self.recycle(k);
        }
        self.end = 0;
        self.labelled_cells = 0;
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
        (self.take_labels(k), self.take_jumps(k))
    }

    /// Take bucket `k`'s labelled cells (empty if it does not exist).
    pub(super) fn take_labels(&mut self, k: usize) -> Vec<Entry> {
        self.labelled.get_mut(k).map(take).unwrap_or_default()
    }

    /// Take bucket `k`'s jump points (empty if it does not exist).
    pub(super) fn take_jumps(&mut self, k: usize) -> Vec<Jump> {
        self.jumps.get_mut(k).map(take).unwrap_or_default()
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
    /// The search over `r`'s fields with `passable`; guided by `r`'s guide if `guided`
    /// names the bucket being settled.
    pub(super) fn new(r: &'a mut Reachability, passable: &'a P, guided: Option<usize>) -> Self {
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
            guide: guided.is_some().then_some(&mut r.guide),
            current: guided.unwrap_or(0),
        }
    }

    /// The bucket of a jump point at column `x`, row `y` of cost `c`: of its cost, or,
    /// guided, of its cost plus bound (never one before the bucket being settled).
    #[inline(always)]
    fn bucket(&mut self, x: usize, y: usize, c: f64) -> usize {
        match &mut self.guide {
            None => c as usize,
            Some(g) => ((c + g.bound(x, y)) as usize).max(self.current),
        }
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

    /// Label start `(x, y)` (in the grid) at cost 0 and queue it, unless listed already;
    /// returns its bucket.
    pub(super) fn start(&mut self, x: usize, y: usize) -> usize {
        let q = self.slot(x, y);
        if self.state[q] & MET != 0 {
            return 0; // listed twice (starts are labelled before any walk)
        }
        let open = (self.passable)(y * self.width + x);
        self.state[q] = if open { MET } else { MET | BLOCKED };
        self.cost[q] = 0.0;
        self.dirs[q] = 0xff00; // nothing else walks into a start (cost 0) but as cheaply
        let xy = (x as u32, y as u32);
        self.queues.labelled_cells += usize::from(self.guide.is_some());
        let k = self.bucket(x, y, 0.0);
        self.queues.label(k, xy);
        self.queues.jump(
            k,
            Jump {
                x: xy.0,
                y: xy.1,
                dir: START,
                cost: 0.0,
            },
        );
        k
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
            match &self.guide {
                None => self.queues.label(c as usize, (x as u32, y as u32)),
                Some(g) => {
                    self.queues.labelled_cells += usize::from(s & MET == 0);
                    if g.is_goal(y * self.width + x) {
                        let k = (c as usize).max(self.current);
                        self.queues.label(k, (x as u32, y as u32));
                    }
                }
            }
            true
        } else if c == self.cost[q] && self.dirs[q] & b == 0 {
            self.dirs[q] |= b;
            true
        } else {
            false
        }
    }

    /// Walk from jump point `j` unless it is stale or walked already, as far as
    /// [`HORIZON`] buckets past its own (guided: its cost over [`HORIZON_DIV`], within
    /// [`GUIDED_HORIZON`]..=[`GUIDED_HORIZON_MAX`]).
    pub(super) fn expand(&mut self, j: Jump) {
        let (x, y) = (j.x as usize, j.y as usize);
        let q = self.slot(x, y);
        if self.cost[q] != j.cost {
            return; // labelled more cheaply since
        }
        let horizon = if self.guide.is_some() {
            (j.cost as usize / HORIZON_DIV).clamp(GUIDED_HORIZON, GUIDED_HORIZON_MAX)
        } else {
            HORIZON
        };
        self.limit = (j.cost as usize + 1 + horizon) as f64;
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
        let k = self.bucket(x as usize, y as usize, cost);
        self.queues.jump(k, j);
    }

    /// Walk straight from `(x, y)` (cost `c`) in direction `(dx, dy)`: one copy of the walk
    /// per direction, whose steps and sides are then constants.
    #[inline(always)]
    fn straight(&mut self, x: i64, y: i64, c: f64, dx: i64, dy: i64) {
        match (dx, dy) {
            (1, 0) => self.straight_in::<1, 0>(x, y, c),
            (-1, 0) => self.straight_in::<-1, 0>(x, y, c),
            (0, 1) => self.straight_in::<0, 1>(x, y, c),
            _ => {
                debug_assert_eq!((dx, dy), (0, -1), "a straight walk's direction");
                self.straight_in::<0, -1>(x, y, c)
            }
        }
    }

    /// Walk straight from `(x, y)` (cost `c`) in direction `(DX, DY)`. Each cell's
    /// passability and its two sides' are asked once, when the walk looks a cell ahead.
    fn straight_in<const DX: i64, const DY: i64>(&mut self, x: i64, y: i64, c: f64) {
        let (dx, dy) = (DX, DY);
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
