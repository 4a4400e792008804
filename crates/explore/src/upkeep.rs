//! Incremental frontier upkeep: what the simulation calls after every integration.
//!
//! Whether a cell is a frontier depends only on its own traversability and on the known states
//! of its 8 neighbours. So after an observation changed the classes of some cells, only
//! (a) the cells whose traversability changed (reported by [`Traversability::update`]) and
//! (b) the 8-neighbours of the changed cells can change frontier status. [`FrontierUpkeep`]
//! re-tests exactly those, so one update costs O(changed cells × clearance disk) for cells that
//! became or stopped being Occupied and O(changed cells) otherwise, independent of the map size.
//! [`crate::frontier::frontiers_from_scratch`] is the oracle it is tested against.

use crate::belief_rows::RowLog;
use crate::bits::CellBits;
use crate::frontier::{FrontierSet, Region, is_frontier_xy};
use crate::traversability::Traversability;
use grid::{Grid, NEIGHBOURS8, Occ};

/// Traversability and the frontier set, kept up to date incrementally, plus scratch buffers.
#[derive(Clone, Debug)]
pub struct FrontierUpkeep {
    /// Per-cell clearance counts.
    pub trav: Traversability,
    /// The current frontier cells.
    pub frontiers: FrontierSet,
    /// Cells whose traversability may have changed in the current update.
    touched: Vec<u32>,
    /// Generation stamps: a cell was re-tested in this update iff `stamp[i] == epoch`
    /// (allocated by the first update: a rebuild does not need them).
    stamp: Vec<u32>,
    epoch: u32,
    /// Cells labelled by the region labelling in progress (allocated by the first
    /// labelling; only frontier cells are marked, and they are unmarked at its end).
    seen: CellBits,
    /// Work stack for region labelling.
    stack: Vec<u32>,
    /// Two rows' flags for [`rebuild`](Self::rebuild).
    row_buf: Vec<u8>,
    /// The rows of the belief each update changed, for copies of it kept by decisions.
    rows: RowLog,
}

impl FrontierUpkeep {
    /// Nothing known yet on a `width × height` map with the robot's clearance in cells.
    pub fn new(width: usize, height: usize, clearance_cells: f64) -> Self {
        Self {
            trav: Traversability::new(width, height, clearance_cells),
            frontiers: FrontierSet::new(width, height),
            touched: Vec::new(),
            stamp: Vec::new(),
            epoch: 0,
            seen: CellBits::default(),
            stack: Vec::new(),
            row_buf: Vec::new(),
            rows: RowLog::new(height),
        }
    }

    /// How many rows or columns from a changed cell of the belief a cell's frontier status
    /// can change: its 8 neighbours and its clearance disk are all it depends on. A copy
    /// of the frontier set is brought up to date by the box of the changed cells grown by
    /// this much.
    pub fn reach(&self) -> usize {
        self.trav.reach().max(1)
    }

    /// The rows of the belief each update changed (see [`crate::belief_rows`]).
    pub(crate) fn row_log(&self) -> &RowLog {
        &self.rows
    }

    /// Update traversability and the frontier set for the cells whose class changed (flat
    /// indices; `known` is the belief after the change and has the size given to `new`);
    /// cost ∝ changed cells. Out-of-grid indices are ignored, duplicates are harmless.
    pub fn update(&mut self, known: &Grid<Occ>, changed: &[u32]) {
        let cells = self.trav.width() * self.trav.height();
        debug_assert_eq!(known.len(), cells, "belief size differs from upkeep size");
        if self.stamp.len() != cells {
            self.stamp = vec![0; cells];
        }
        self.rows.note(self.trav.width(), changed);
        self.touched.clear();
        self.trav.update(known, changed, &mut self.touched);
        self.epoch = next_gen(self.epoch, &mut self.stamp);
        let n = self.stamp.len().min(known.len());
        let (w, h) = (self.trav.width() as i32, self.trav.height() as i32);
        for k in 0..self.touched.len() {
            let i = self.touched[k] as usize;
            self.retest(known, i);
        }
        for &c in changed {
            let i = c as usize;
            if i >= n {
                continue;
            }
            let (x, y) = ((i % w as usize) as i32, (i / w as usize) as i32);
            for &(dx, dy) in &NEIGHBOURS8 {
                let (nx, ny) = (x + dx, y + dy);
                if nx >= 0 && ny >= 0 && nx < w && ny < h {
                    self.retest_xy(known, (ny * w + nx) as usize, nx, ny);
                }
            }
        }
    }

    /// Forget everything and recount from `known` (cost ∝ map; for a first, pre-filled belief,
    /// such as a map received whole): the clearance counts from the Occupied cells alone
    /// ([`Traversability::rebuild`]), then the frontier test row by row on the traversable
    /// cells, in index order — many times faster than [`update`](Self::update) with every
    /// known cell as changed, and the same frontier set in the same order as
    /// [`crate::frontier::frontiers_from_scratch`].
    pub fn rebuild(&mut self, known: &Grid<Occ>) {
        let (w, h) = (self.trav.width(), self.trav.height());
        debug_assert_eq!(known.len(), w * h, "belief size differs from upkeep size");
        self.rows.restart();
        self.trav.rebuild(known);
        self.frontiers.clear();
        let data = known.data();
        let h = h.min(data.len() / w.max(1));
        // unknown[x + 1]: some cell of column x in rows y − 1..=y + 1 is Unknown; a
        // frontier cell has an Unknown 8-neighbour, so it has one of unknown[x..=x + 2].
        // near[x]: cell x is Free and has one. These byte passes leave the exact test to
        // the few cells near unknown space, found eight at a time.
        let mut buf = std::mem::take(&mut self.row_buf);
        buf.clear();
        buf.resize(2 * w + 2, 0);
        let (unknown, near) = buf.split_at_mut(w + 2);
        for y in 0..h {
            let row = &data[y * w..(y + 1) * w];
            let above = if y > 0 {
                &data[(y - 1) * w..y * w]
            } else {
                row
            };
            let below = if y + 1 < h {
                &data[(y + 1) * w..(y + 2) * w]
            } else {
                row
            };
            for (((u, a), c), b) in unknown[1..=w].iter_mut().zip(above).zip(row).zip(below) {
                *u = u8::from(a.is_unknown() | c.is_unknown() | b.is_unknown());
            }
            let sides = unknown[..w].iter().zip(&unknown[1..=w]).zip(&unknown[2..]);
            for ((n, ((l, m), r)), c) in near.iter_mut().zip(sides).zip(row) {
                *n = (l | m | r) & u8::from(c.is_free());
            }
            for (k, chunk) in near.chunks(8).enumerate() {
                let any = match <[u8; 8]>::try_from(chunk) {
                    Ok(eight) => u64::from_ne_bytes(eight) != 0,
                    Err(_) => chunk.iter().any(|&n| n != 0),
                };
                if !any {
                    continue;
                }
                for (d, _) in chunk.iter().enumerate().filter(|(_, n)| **n != 0) {
                    let x = k * 8 + d;
                    if is_frontier_xy(known, &self.trav, y * w + x, x as i32, y as i32) {
                        self.frontiers.insert(y * w + x);
                    }
                }
            }
        }
        self.row_buf = buf;
    }

    #[inline]
    fn retest(&mut self, known: &Grid<Occ>, i: usize) {
        if self.stamp[i] == self.epoch {
            return;
        }
        let w = self.trav.width();
        self.retest_xy(known, i, (i % w) as i32, (i / w) as i32);
    }

    #[inline(always)]
    fn retest_xy(&mut self, known: &Grid<Occ>, i: usize, x: i32, y: i32) {
        if self.stamp[i] == self.epoch {
            return;
        }
        self.stamp[i] = self.epoch;
        if is_frontier_xy(known, &self.trav, i, x, y) {
            self.frontiers.insert(i);
        } else {
            self.frontiers.remove(i);
        }
    }

    /// 8-connected regions of the current frontier set with at least `min_size` cells, sorted by
    /// their smallest cell index (deterministic); each region's cells are sorted. `grid_width`
    /// must be the width given to `new` (checked in debug builds). Reuses `out`'s and internal
    /// buffers; cost ∝ frontier cells (times log for the sorting).
    pub fn regions(&mut self, grid_width: usize, min_size: usize, out: &mut Vec<Region>) {
        debug_assert_eq!(
            grid_width,
            self.trav.width(),
            "grid width differs from upkeep width"
        );
        let (w, h) = (self.trav.width() as i32, self.trav.height() as i32);
        let cells = self.trav.width() * self.trav.height();
        if self.seen.len() != cells {
            self.seen = CellBits::new(cells);
        }
        let mut n_out = 0;
        for k in 0..self.frontiers.len() {
            let seed = self.frontiers.cells()[k];
            if self.seen.contains(seed as usize) {
                continue;
            }
            if n_out == out.len() {
                out.push(Region {
                    cells: Vec::new(),
                    centroid: (0.0, 0.0),
                    representative: 0,
                });
            }
            let region = &mut out[n_out];
            region.cells.clear();
            self.seen.insert(seed as usize);
            self.stack.clear();
            self.stack.push(seed);
            while let Some(c) = self.stack.pop() {
                region.cells.push(c);
                let (x, y) = ((c as i32) % w, (c as i32) / w);
                for &(dx, dy) in &NEIGHBOURS8 {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w || ny >= h {
                        continue;
                    }
                    let j = (ny * w + nx) as usize;
                    if !self.seen.contains(j) && self.frontiers.contains(j) {
                        self.seen.insert(j);
                        self.stack.push(j as u32);
                    }
                }
            }
            if region.cells.len() >= min_size.max(1) {
                region.cells.sort_unstable();
                region.finish(w as usize);
                n_out += 1;
            }
        }
        for &c in self.frontiers.cells() {
            self.seen.remove(c as usize);
        }
        out.truncate(n_out);
        out.sort_unstable_by_key(|r| r.cells[0]);
    }

    /// Whether cell `i` is traversable in `known` under the kept clearance counts.
    #[inline]
    pub fn is_traversable(&self, known: &Grid<Occ>, i: usize) -> bool {
        self.trav.is_traversable(known, i)
    }
}

/// The next generation stamp, clearing `stamps` when the counter wraps (to their default:
/// a stamp of 0, or an entry stamped 0 with what it keeps beside the stamp).
pub(crate) fn next_gen<T: Clone + Default>(epoch: u32, stamps: &mut [T]) -> u32 {
    if epoch == u32::MAX {
        stamps.fill(T::default());
        1
    } else {
        epoch + 1
    }
}
