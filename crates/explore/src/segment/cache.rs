//! Keeping a segmentation between decisions (Holz et al. 2010 §2.4 segment the map "built so
//! far" at every decision; here it is recomputed only when the map changed enough).
//!
//! The refresh rule: the state remembers the known grid as of its last update. At each
//! update the grid is compared with it cell by cell (a linear scan of bytes, far cheaper than
//! a segmentation) and the changed cells are added to a drift count. The whole pipeline runs
//! again when the rule, the grid size changed, or the drift since the last full run reaches
//! [`REFRESH_FRACTION`] of the free cells of that run (at least one cell). Otherwise the old
//! segmentation is kept and patched: cells that stopped being free lose their label, and
//! newly free cells take the label of the labelled free cell they connect to (a breadth-first
//! growth from the old labels, in index order), so that new frontier cells have a segment.
//! Newly free cells that connect to no labelled cell stay unlabelled until the next full run.
//!
//! Blocks: on fine maps the pipeline runs on blocks of `block × block` cells
//! ([`block_for`]: blocks at least [`SEGMENT_CELL_M`] wide), a block being free when all its
//! cells are free. Holz et al. do not give the resolution they segment at; a doorway is
//! 0.7 m or more, still seven cells or more at 0.1 m, while a 5 cm map of a building has four
//! times as many cells to thin, and its ragged edges (a 1° laser leaves fingers of free
//! cells between unseen wall cells) grow spurs and slivers that are not rooms. Every free
//! cell then takes the label of its block, and free cells of partly free blocks take the
//! label of the labelled free cell they connect to (the growth of the patches below).
//!
//! The state also keeps each segment's neighbouring segments ([`State::neighbours`]) for
//! Seg's room preference: found by a scan with every full run, and extended by the pairs the
//! patched cells create (work proportional to the change).

use std::collections::VecDeque;

use grid::{Grid, Occ};

use super::graph::NONE;
use super::skeleton::RING;
use super::{Rule, Segmentation, Segmenter};

/// Fraction of the free cells that must change before the segmentation is recomputed.
pub const REFRESH_FRACTION: f64 = 0.02;

/// Segmentation blocks are at least this many metres wide (see the module documentation).
pub const SEGMENT_CELL_M: f64 = 0.1;

/// The block side, in cells, for a map of `resolution` metres per cell: the most cells that
/// fit in [`SEGMENT_CELL_M`] (at least 1, at most 8).
pub fn block_for(resolution: f64) -> usize {
    block_side(SEGMENT_CELL_M, resolution)
}

/// The most cells of `resolution` metres that fit in `width_m` metres, at least 1 and at
/// most 8 (blocks of work on fine maps).
pub fn block_side(width_m: f64, resolution: f64) -> usize {
    if !(resolution.is_finite() && resolution > 0.0) {
        return 1;
    }
    ((width_m / resolution + 1e-9).floor() as usize).clamp(1, 8)
}

/// The segmentation kept between decisions.
#[derive(Default)]
pub struct State {
    segmenter: Segmenter,
    block: usize,
    coarse: Option<Grid<Occ>>,
    fine: Segmentation,
    rule: Option<Rule>,
    seen: Vec<Occ>,
    width: usize,
    free_at_full: usize,
    drift: usize,
    changed: Vec<u32>,
    queue: VecDeque<u32>,
    keys: Vec<u64>,
    degrees: Vec<u32>,
    full_runs: usize,
    patches: usize,
}

impl State {
    /// An empty state (nothing segmented yet).
    pub fn new() -> Self {
        Self::default()
    }

    /// Bring the segmentation up to date with `known` under `rule` (see the module
    /// documentation for when it is recomputed) and return it.
    pub fn update(&mut self, known: &Grid<Occ>, rule: Rule) -> &Segmentation {
        self.update_blocks(known, rule, 1)
    }

    /// [`update`](Self::update), running the pipeline on blocks of `block × block` cells
    /// (see the module documentation; `block_for` gives the block for a resolution).
    pub fn update_blocks(&mut self, known: &Grid<Occ>, rule: Rule, block: usize) -> &Segmentation {
        let block = block.max(1);
        let cells = known.data();
        let fresh = self.rule != Some(rule)
            || self.block != block
            || self.width != known.width()
            || self.seen.len() != cells.len();
        if !fresh {
            self.changed.clear();
            // chunks compared branch-free first: most of a big map does not change
            const CHUNK: usize = 64;
            let chunks = self.seen.chunks_mut(CHUNK).zip(cells.chunks(CHUNK));
            for (c, (seen, now)) in chunks.enumerate() {
                let diff = seen
                    .iter()
                    .zip(now)
                    .fold(0u8, |acc, (&a, &b)| acc | (a as u8 ^ b as u8));
                if diff == 0 {
                    continue;
                }
                for (k, (s, &v)) in seen.iter_mut().zip(now).enumerate() {
                    if *s != v {
                        *s = v;
                        self.changed.push((c * CHUNK + k) as u32);
                    }
                }
            }
            if self.changed.is_empty() {
                return &self.fine;
            }
            self.drift += self.changed.len();
            let limit = ((REFRESH_FRACTION * self.free_at_full as f64) as usize).max(1);
            if self.drift < limit {
                self.patches += 1;
                self.patch(known);
                self.patch_neighbours();
                return &self.fine;
            }
        }
        self.full(known, rule, block);
        self.fine.neighbour_pairs(&mut self.keys);
        count_pairs(&self.keys, self.fine.count, &mut self.degrees);
        &self.fine
    }

    /// How many other segments segment `s` of the current segmentation touches.
    pub fn neighbours(&self, s: u32) -> u32 {
        self.degrees.get(s as usize).copied().unwrap_or(0)
    }

    /// Add the segment pairs that the patched cells create (pairs are only added between
    /// full runs: a cell that stops being free leaves its pairs until the next full run).
    fn patch_neighbours(&mut self) {
        let seg = &self.fine;
        let (w, n) = (seg.width, seg.labels.len());
        let before = self.keys.len();
        for &c in &self.changed {
            let i = c as usize;
            let a = seg.labels[i];
            if a == NONE {
                continue;
            }
            let x = i % w;
            let around = [
                (x + 1 < w).then(|| i + 1),
                (x > 0).then(|| i - 1),
                (i + w < n).then(|| i + w),
                i.checked_sub(w),
            ];
            for j in around.into_iter().flatten() {
                let b = seg.labels[j];
                if b != NONE && b != a {
                    self.keys.push(super::pair_key(a, b));
                }
            }
        }
        if self.keys.len() > before {
            self.keys.sort_unstable();
            self.keys.dedup();
            count_pairs(&self.keys, seg.count, &mut self.degrees);
        }
    }

    /// The segmentation as of the last update.
    pub fn segmentation(&self) -> &Segmentation {
        &self.fine
    }

    /// How many times the whole pipeline ran.
    pub fn full_runs(&self) -> usize {
        self.full_runs
    }

    /// How many times the segmentation was patched instead.
    pub fn patches(&self) -> usize {
        self.patches
    }

    fn full(&mut self, known: &Grid<Occ>, rule: Rule, block: usize) {
        if block == 1 {
            self.segmenter.run(known, rule);
            self.fine.clone_from(self.segmenter.result());
        } else {
            self.full_blocks(known, rule, block);
        }
        self.rule = Some(rule);
        self.block = block;
        self.width = known.width();
        self.seen.clear();
        self.seen.extend_from_slice(known.data());
        self.free_at_full = self.seen.iter().filter(|c| c.is_free()).count();
        self.drift = 0;
        self.full_runs += 1;
    }

    /// Segment `known` on blocks of `block × block` cells and carry the labels back.
    fn full_blocks(&mut self, known: &Grid<Occ>, rule: Rule, block: usize) {
        let (w, h) = (known.width(), known.height());
        let (cw, ch) = (w.div_ceil(block), h.div_ceil(block));
        let cells = known.data();
        let grid = match self.coarse.take() {
            Some(g) if g.width() == cw && g.height() == ch => g,
            _ => Grid::new(cw, ch, Occ::Occupied),
        };
        let grid = self.coarse.insert(grid);
        let coarse = grid.data_mut();
        coarse.fill(Occ::Free);
        for (y, row) in cells.chunks(w).enumerate() {
            let base = (y / block) * cw;
            for (cx, run) in row.chunks(block).enumerate() {
                if !run.iter().all(|c| c.is_free()) {
                    coarse[base + cx] = Occ::Occupied;
                }
            }
        }
        let seg = self.segmenter.run(grid, rule);
        let fine = &mut self.fine;
        fine.width = w;
        fine.height = h;
        fine.count = seg.count;
        fine.labels.clear();
        fine.labels.resize(w * h, NONE);
        self.changed.clear();
        for (y, row) in cells.chunks(w).enumerate() {
            let base = (y / block) * cw;
            for (cx, run) in row.chunks(block).enumerate() {
                let l = seg.labels[base + cx];
                for (k, c) in run.iter().enumerate() {
                    if c.is_free() {
                        let i = y * w + cx * block + k;
                        fine.labels[i] = l;
                        if l == NONE {
                            self.changed.push(i as u32);
                        }
                    }
                }
            }
        }
        let to_fine = |c: u32| {
            let (x, y) = (c as usize % cw, c as usize / cw);
            let fx = (x * block + block / 2).min(w - 1);
            let fy = (y * block + block / 2).min(h - 1);
            (fy * w + fx) as u32
        };
        fine.critical.clear();
        fine.critical
            .extend(seg.critical.iter().map(|cp| super::CriticalPoint {
                cell: to_fine(cp.cell),
                clearance: cp.clearance * block as f64,
                side_a: to_fine(cp.side_a),
                side_b: to_fine(cp.side_b),
            }));
        self.grow(known);
    }

    /// Clear the labels of changed cells that are no longer free and grow labels into the
    /// changed free cells that have none.
    fn patch(&mut self, known: &Grid<Occ>) {
        let cells = known.data();
        for &c in &self.changed {
            if !cells[c as usize].is_free() {
                self.fine.labels[c as usize] = NONE;
            }
        }
        self.grow(known);
    }

    /// Give every unlabelled free cell among the changed cells, and every unlabelled free
    /// cell connected to one, the label of a labelled free cell it connects to
    /// (breadth-first, in index order).
    fn grow(&mut self, known: &Grid<Occ>) {
        let (w, h) = (known.width() as i64, known.height() as i64);
        let cells = known.data();
        let labels = &mut self.fine.labels;
        // motion-connected free neighbour of `i` in direction (dx, dy)
        let neighbour = |i: usize, dx: i32, dy: i32| -> Option<usize> {
            let (x, y) = ((i as i64) % w, (i as i64) / w);
            let (nx, ny) = (x + dx as i64, y + dy as i64);
            if nx < 0 || ny < 0 || nx >= w || ny >= h {
                return None;
            }
            let j = (ny * w + nx) as usize;
            if !cells[j].is_free() {
                return None;
            }
            if dx != 0 && dy != 0 {
                let a = cells[(y * w + nx) as usize].is_free();
                let b = cells[(ny * w + x) as usize].is_free();
                if !a && !b {
                    return None;
                }
            }
            Some(j)
        };
        self.queue.clear();
        for &c in &self.changed {
            let c = c as usize;
            if !cells[c].is_free() || labels[c] != NONE {
                continue;
            }
            let from = RING
                .iter()
                .filter_map(|&(dx, dy)| neighbour(c, dx, dy))
                .find(|&j| labels[j] != NONE);
            if let Some(j) = from {
                labels[c] = labels[j];
                self.queue.push_back(c as u32);
            }
        }
        while let Some(i) = self.queue.pop_front() {
            let i = i as usize;
            for &(dx, dy) in RING.iter() {
                if let Some(j) = neighbour(i, dx, dy)
                    && labels[j] == NONE
                {
                    labels[j] = labels[i];
                    self.queue.push_back(j as u32);
                }
            }
        }
    }
}

/// Per-segment counts of the sorted, deduplicated pair keys `keys` into `out`.
fn count_pairs(keys: &[u64], count: u32, out: &mut Vec<u32>) {
    out.clear();
    out.resize(count as usize, 0);
    for &k in keys {
        for s in [(k >> 32) as usize, (k & 0xffff_ffff) as usize] {
            if let Some(c) = out.get_mut(s) {
                *c += 1;
            }
        }
    }
}
