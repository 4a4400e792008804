//! Keeping a segmentation between decisions (Holz et al. 2010 §2.4 segment the map "built so
//! far" at every decision; here it is recomputed only when the map changed enough).
//!
//! The refresh rule: the state remembers the known grid as of its last update. At each
//! update the grid is compared with it (only the rows the belief's row log has changed
//! since, when the caller keeps one, as the simulation's frontier upkeep does) and the
//! changed cells are added to a drift count. The whole pipeline runs again when the rule,
//! the grid size changed, or the drift since the last full run reaches [`REFRESH_FRACTION`]
//! of the free cells of that run (at least one cell). Otherwise the old segmentation is
//! kept and patched: cells that stopped being free lose their label, and newly free cells
//! take the label of the labelled free cell they connect to (a breadth-first growth from
//! the old labels, in index order), so that new frontier cells have a segment. Newly free
//! cells that connect to no labelled cell stay unlabelled until the next full run.
//!
//! Blocks: on fine maps the pipeline runs on blocks of `block × block` cells
//! ([`block_for`]: the most whole cells that fit in [`SEGMENT_CELL_M`], so two at 0.05 m and
//! three at 0.03 m, and one, cell by cell, on maps coarser than 0.05 m), a block being free
//! when all its cells are free. Holz et al. do not give the resolution they segment at; a doorway is
//! 0.7 m or more, still seven cells or more at 0.1 m, while a 5 cm map of a building has four
//! times as many cells to thin, and its ragged edges (a 1° laser leaves fingers of free
//! cells between unseen wall cells) grow spurs and slivers that are not rooms. Every free
//! cell then takes the label of its block, and free cells of partly free blocks take the
//! label of the labelled free cell they connect to (the growth of the patches below).
//!
//! Window: a full run segments only a window of the grid that holds every free cell (the
//! bounding box of the cells free at some update since the state began, grown from the
//! changed cells), widened by one cell (block) on each side where the grid goes on. The
//! pipeline treats everything that is not free as wall and the grid's outside as wall just
//! beyond its edge; outside the window nothing is free, and the ring around it is wall, so
//! every free cell's nearest wall, the skeleton, the seeds' distances and the order of
//! cells (row-major order survives cropping) are those of the whole grid: the labels are
//! the same, and a run early in an exploration costs what the known part of the map does,
//! not the whole map.
//!
//! The state also keeps each segment's neighbouring segments ([`State::neighbours`]) for
//! Seg's room preference: found by a scan with every full run, and extended by the pairs the
//! patched cells create (work proportional to the change).

use std::collections::VecDeque;

use grid::{Grid, Occ};

use super::graph::NONE;
use super::skeleton::RING;
use super::{Rule, Segmentation, Segmenter};
use crate::belief_rows::{LogPos, RowLog, sync_rows};

/// Fraction of the free cells that must change before the segmentation is recomputed.
pub const REFRESH_FRACTION: f64 = 0.02;

/// Segmentation blocks are as many whole cells as fit in this many metres (see the module
/// documentation).
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
    (grid::units::cells(width_m, resolution).floor() as usize).clamp(1, 8)
}

/// The segmentation kept between decisions.
#[derive(Default)]
pub struct State {
    segmenter: Segmenter,
    block: usize,
    /// The window of the grid (or of its blocks) the last full run segmented.
    crop: Grid<Occ>,
    fine: Segmentation,
    rule: Option<Rule>,
    /// The belief as of the last update, and how far it followed the belief's row log.
    seen: Grid<Occ>,
    pos: LogPos,
    /// A window holding every cell that was free at some update since the last fresh
    /// start: every free cell and every labelled cell lies in it.
    free: Window,
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
        self.update_logged(known, rule, block, &RowLog::default())
    }

    /// [`update_blocks`](Self::update_blocks) for a belief whose changed rows `log` records:
    /// only the rows changed since the last update are compared.
    pub(crate) fn update_logged(
        &mut self,
        known: &Grid<Occ>,
        rule: Rule,
        block: usize,
        log: &RowLog,
    ) -> &Segmentation {
        let block = block.max(1);
        let fresh = self.rule != Some(rule)
            || self.block != block
            || self.width != known.width()
            || self.seen.len() != known.len();
        if !fresh {
            self.changed.clear();
            let changed = &mut self.changed;
            let w = known.width();
            // chunks of 64 cells, compared whole first: most of a changed row is not
            const CHUNK: usize = 64;
            sync_rows(
                known,
                &mut self.seen,
                CHUNK,
                (log, &mut self.pos),
                |y, k, now, before| {
                    let at = y * w + k * CHUNK;
                    for (j, (a, b)) in now.iter().zip(before).enumerate() {
                        if a != b {
                            changed.push((at + j) as u32);
                        }
                    }
                },
            );
            if self.changed.is_empty() {
                return &self.fine;
            }
            for &c in &self.changed {
                let i = c as usize;
                if known.data()[i].is_free() {
                    self.free.add_run(i / w, i % w, i % w);
                }
            }
            self.drift += self.changed.len();
            let limit = ((REFRESH_FRACTION * self.free_at_full as f64) as usize).max(1);
            if self.drift < limit {
                self.patches += 1;
                self.patch(known);
                self.patch_neighbours();
                return &self.fine;
            }
        } else {
            self.seen.clone_from(known);
            self.pos = log.now();
            self.free = Window::of_free(known);
            // labels of an earlier history may lie anywhere
            self.fine.labels.clear();
        }
        self.full(known, rule, block);
        self.fine.neighbour_pairs_within(self.free, &mut self.keys);
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

    /// Segment `known` afresh (`seen` holds it, `free` holds its free cells).
    fn full(&mut self, known: &Grid<Occ>, rule: Rule, block: usize) {
        let (w, h) = (known.width(), known.height());
        // the window of blocks holding every free cell, widened: what the pipeline sees
        let (cw, ch) = (w.div_ceil(block), h.div_ceil(block));
        let f = self.free;
        let win = if f.w == 0 || f.h == 0 {
            f
        } else {
            let (x0, y0) = (f.x0 / block, f.y0 / block);
            Window {
                x0,
                y0,
                w: (f.x0 + f.w - 1) / block + 1 - x0,
                h: (f.y0 + f.h - 1) / block + 1 - y0,
            }
        }
        .widened(cw, ch);
        crop_blocks(known, block, win, &mut self.crop);
        let seg = self.segmenter.run(&self.crop, rule);
        let fine = &mut self.fine;
        fine.width = w;
        fine.height = h;
        fine.count = seg.count;
        if fine.labels.len() != w * h {
            fine.labels.clear();
            fine.labels.resize(w * h, NONE);
        }
        self.changed.clear();
        let cells = known.data();
        let mut free_cells = 0;
        // every free cell, and every cell labelled before, lies in `free`
        for y in f.rows() {
            let (row, labels) = (&cells[y * w..][..w], &mut fine.labels[y * w..][..w]);
            let by = y / block - win.y0;
            for x in f.columns() {
                if !row[x].is_free() {
                    labels[x] = NONE;
                    continue;
                }
                free_cells += 1;
                let l = seg.labels[by * win.w + x / block - win.x0];
                labels[x] = l;
                if l == NONE {
                    self.changed.push((y * w + x) as u32);
                }
            }
        }
        let to_fine = |c: u32| {
            let b = win.to_grid(c, cw);
            let (x, y) = (b % cw, b / cw);
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
        if block > 1 {
            // free cells of blocks that are not wholly free join the segment they touch
            self.grow(known);
        }
        self.rule = Some(rule);
        self.block = block;
        self.width = w;
        self.free_at_full = free_cells;
        self.drift = 0;
        self.full_runs += 1;
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

/// A rectangle of a grid: columns `x0..x0 + w`, rows `y0..y0 + h` (empty when `w` or `h`
/// is 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Window {
    pub(crate) x0: usize,
    pub(crate) y0: usize,
    pub(crate) w: usize,
    pub(crate) h: usize,
}

impl Window {
    /// No cell.
    const EMPTY: Window = Window {
        x0: 0,
        y0: 0,
        w: 0,
        h: 0,
    };

    /// The smallest window holding every free cell of `grid`.
    fn of_free(grid: &Grid<Occ>) -> Window {
        let mut win = Window::EMPTY;
        for (y, row) in grid.data().chunks(grid.width().max(1)).enumerate() {
            if let Some(x0) = row.iter().position(|c| c.is_free()) {
                let x1 = row.iter().rposition(|c| c.is_free()).unwrap_or(x0);
                win.add_run(y, x0, x1);
            }
        }
        win
    }

    /// Grow to hold cells `x0..=x1` of row `y`.
    fn add_run(&mut self, y: usize, x0: usize, x1: usize) {
        if self.w == 0 || self.h == 0 {
            *self = Window {
                x0,
                y0: y,
                w: x1 - x0 + 1,
                h: 1,
            };
            return;
        }
        let (ax, ay) = (self.x0.min(x0), self.y0.min(y));
        let bx = (self.x0 + self.w).max(x1 + 1);
        let by = (self.y0 + self.h).max(y + 1);
        *self = Window {
            x0: ax,
            y0: ay,
            w: bx - ax,
            h: by - ay,
        };
    }

    /// Widened by one cell on each side, within a `gw × gh` grid (an empty window becomes
    /// one cell, which segments like a grid without free cells).
    fn widened(self, gw: usize, gh: usize) -> Window {
        if self.w == 0 || self.h == 0 {
            return Window {
                x0: 0,
                y0: 0,
                w: gw.min(1),
                h: gh.min(1),
            };
        }
        let (x0, y0) = (self.x0.saturating_sub(1), self.y0.saturating_sub(1));
        let x1 = (self.x0 + self.w + 1).min(gw);
        let y1 = (self.y0 + self.h + 1).min(gh);
        Window {
            x0,
            y0,
            w: x1 - x0,
            h: y1 - y0,
        }
    }

    /// The flat index in a `gw`-wide grid of the window's cell of flat index `c`.
    fn to_grid(self, c: u32, gw: usize) -> usize {
        let c = c as usize;
        (self.y0 + c / self.w) * gw + self.x0 + c % self.w
    }

    /// The window's rows.
    pub(crate) fn rows(&self) -> std::ops::Range<usize> {
        self.y0..self.y0 + self.h
    }

    /// The window's columns.
    pub(crate) fn columns(&self) -> std::ops::Range<usize> {
        self.x0..self.x0 + self.w
    }
}

/// Window `win` of the grid of `block × block` blocks of `known` into `out`: a block is free
/// when all its cells are.
fn crop_blocks(known: &Grid<Occ>, block: usize, win: Window, out: &mut Grid<Occ>) {
    if out.width() != win.w || out.height() != win.h {
        *out = Grid::new(win.w, win.h, Occ::Free);
    }
    out.fill(Occ::Free);
    let (w, h) = (known.width(), known.height());
    let (x0, x1) = (win.x0 * block, ((win.x0 + win.w) * block).min(w));
    let crop = out.data_mut();
    for y in win.y0 * block..((win.y0 + win.h) * block).min(h) {
        let row = &known.data()[y * w + x0..y * w + x1];
        let at = (y / block - win.y0) * win.w;
        for (k, run) in row.chunks(block).enumerate() {
            if !run.iter().all(|c| c.is_free()) {
                crop[at + k] = Occ::Occupied;
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
