//! Traversability with a robot clearance (Holz et al. 2010's `d_max`), kept incrementally.
//!
//! A cell is *traversable* iff it is known Free and no known Occupied cell lies closer than
//! the robot's clearance to it: cell `c` is blocked iff some known Occupied `o` has centre
//! distance `|c − o| < clearance`, or is `c` itself (so a clearance of at most one cell blocks
//! only the occupied cells themselves). Holz et al. neglect the cells "whose distance to the
//! closest obstacle region falls below" `d_max`, so a cell exactly `d_max` away is kept.
//! Unknown cells are never traversable.
//!
//! [`Traversability`] keeps, for every cell, the number of known Occupied cells within the
//! clearance disk around it. When a cell becomes or stops being Occupied, the counts of the
//! cells in its disk change by one, so an update costs O(changed cells × disk size) for the
//! cells whose occupancy changed and O(1) for the others — independent of the map size.

use crate::bits::CellBits;
use grid::{Grid, Occ};

/// Per-cell counts of known Occupied cells within the clearance disk, maintained incrementally.
#[derive(Clone, Debug)]
pub struct Traversability {
    width: usize,
    height: usize,
    clearance: f64,
    /// Offsets `(dx, dy)` with `√(dx² + dy²) < clearance`, and `(0, 0)` (clipped to the grid
    /// size).
    disk: Vec<(i32, i32)>,
    /// The disk by rows: `(dy, h)` for the offsets `(−h..=h, dy)` (a disk's row is one run).
    spans: Vec<(i32, i32)>,
    /// Number of counted Occupied cells whose disk covers the cell.
    count: Counts,
    /// The cells currently counted as Occupied.
    counted: CellBits,
    /// The traversable cells, kept with the counts (a flood fill reads them a word at a
    /// time).
    passable: CellBits,
    /// Whether anything was ever counted (else the counts are still the zeroed allocation).
    dirty: bool,
}

impl Traversability {
    /// Nothing counted yet for a `width × height` map and a clearance in cells (negative or NaN
    /// clearances act as 0 for occupied cells themselves, which are never traversable anyway).
    pub fn new(width: usize, height: usize, clearance_cells: f64) -> Self {
        let n = width * height;
        let disk = disk_offsets(clearance_cells, width.max(height));
        Self {
            width,
            height,
            clearance: clearance_cells,
            spans: disk_spans(&disk),
            count: Counts::for_disk(disk.len(), n),
            disk,
            counted: CellBits::new(n),
            passable: CellBits::new(n),
            dirty: false,
        }
    }

    /// Forget every count and count the Occupied cells of `known` (same size) afresh: the
    /// state [`update`](Self::update) reaches with every cell as changed, at a fraction of
    /// its cost. Each Occupied cell marks where its disk's rows start and end (a difference
    /// array: +1 at a run's first cell, −1 after its last, in wrapping arithmetic), and one
    /// running sum per row turns the marks into counts; nothing is reported as touched, and
    /// counts still zero from the allocation are not cleared again.
    pub fn rebuild(&mut self, known: &Grid<Occ>) {
        let n = self.width * self.height;
        debug_assert_eq!(known.len(), n, "belief size differs");
        if self.dirty {
            self.count = Counts::for_disk(self.disk.len(), n);
            self.counted = CellBits::new(n);
            self.passable = CellBits::new(n);
        }
        self.dirty = true;
        let (w, h) = (self.width, self.height);
        let data = known.data();
        let h = h.min(data.len() / w.max(1));
        let counted = &mut self.counted;
        match &mut self.count {
            Counts::U8(count) => count_from_scratch(count, &self.spans, data, w, h, counted),
            Counts::U32(count) => count_from_scratch(count, &self.spans, data, w, h, counted),
        }
        for (i, o) in data[..w * h].iter().enumerate() {
            if o.is_free() && self.count.is_zero(i) == Some(true) {
                self.passable.insert(i);
            }
        }
    }

    /// Account for cells whose class changed (flat indices), given the belief AFTER the change;
    /// pushes every cell whose traversability may have changed to `touched` (it keeps its own
    /// record of which cells it has counted as occupied, so a cell that stops being Occupied is
    /// handled too). Indices outside the grid are ignored; duplicates are harmless.
    pub fn update(&mut self, known: &Grid<Occ>, changed: &[u32], touched: &mut Vec<u32>) {
        let n = self.width * self.height;
        self.dirty = true;
        let from = touched.len();
        for &c in changed {
            let i = c as usize;
            if i >= n || i >= known.len() {
                continue;
            }
            // its own class changed: Free-ness may have changed
            touched.push(c);
            let occ = known[i].is_occupied();
            if occ == self.counted.contains(i) {
                continue;
            }
            if occ {
                self.counted.insert(i);
            } else {
                self.counted.remove(i);
            }
            let (x, y) = ((i % self.width) as i32, (i / self.width) as i32);
            let (w, h) = (self.width, self.height);
            match &mut self.count {
                Counts::U8(count) => count_disk(count, &self.disk, (x, y), (w, h), occ, touched),
                Counts::U32(count) => count_disk(count, &self.disk, (x, y), (w, h), occ, touched),
            }
        }
        // A cell's traversability changes only with its own class or when its count
        // becomes or stops being zero: the cells just touched.
        for &c in &touched[from..] {
            let i = c as usize;
            let free = known[i].is_free() && self.count.is_zero(i) == Some(true);
            self.passable.set(i, free);
        }
    }

    /// Whether cell `i` is traversable: known Free and no known Occupied cell within
    /// clearance. `known` is the belief last given to [`update`](Self::update) or
    /// [`rebuild`](Self::rebuild); the answer is the cell's bit in
    /// [`passable`](Self::passable) (debug builds check it against `known` and the counts).
    #[inline]
    pub fn is_traversable(&self, known: &Grid<Occ>, i: usize) -> bool {
        let bit = self.passable.contains(i);
        debug_assert_eq!(
            bit,
            known.data().get(i).is_some_and(|o| o.is_free()) && self.count.is_zero(i) == Some(true),
            "cell {i}: the belief was changed without an update"
        );
        bit
    }

    /// The traversable cells (as of the last update): [`is_traversable`](Self::is_traversable)
    /// of the belief that update was given, for every cell.
    pub fn passable(&self) -> &CellBits {
        &self.passable
    }

    /// Whether some counted Occupied cell lies within the clearance of cell `i`.
    #[inline]
    pub fn is_blocked(&self, i: usize) -> bool {
        self.count.is_zero(i) == Some(false)
    }

    /// The robot's clearance in cells, as given to [`Traversability::new`].
    pub fn clearance_cells(&self) -> f64 {
        self.clearance
    }

    /// How many rows or columns away an Occupied cell can block a cell (the disk's reach).
    pub fn reach(&self) -> usize {
        self.disk
            .iter()
            .map(|&(dx, dy)| dx.unsigned_abs().max(dy.unsigned_abs()) as usize)
            .max()
            .unwrap_or(0)
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The disk offsets `(dx, dy)` counted around each occupied cell.
    pub fn disk(&self) -> &[(i32, i32)] {
        &self.disk
    }
}

/// The per-cell counts, in the narrowest type that holds a whole disk: a byte per cell
/// while the disk has at most 255 cells (clearances below √82 ≈ 9.06 cells), a quarter of
/// the memory and of the pages that counting a new map touches.
#[derive(Clone, Debug)]
enum Counts {
    /// Disks of at most 255 cells.
    U8(Vec<u8>),
    /// Larger disks.
    U32(Vec<u32>),
}

impl Counts {
    /// Zero counts for `n` cells and a disk of `disk_cells` cells.
    fn for_disk(disk_cells: usize, n: usize) -> Self {
        if disk_cells <= usize::from(u8::MAX) {
            Counts::U8(vec![0; n])
        } else {
            Counts::U32(vec![0; n])
        }
    }

    /// Whether cell `i`'s count is zero (`None` outside the grid).
    #[inline]
    fn is_zero(&self, i: usize) -> Option<bool> {
        match self {
            Counts::U8(c) => c.get(i).map(|&c| c == 0),
            Counts::U32(c) => c.get(i).map(|&c| c == 0),
        }
    }
}

/// A count type: wrapping arithmetic for the difference arrays, exact for counts it holds.
trait Count: Copy + Eq + std::ops::Add<Output = Self> + std::ops::Sub<Output = Self> {
    const ZERO: Self;
    const ONE: Self;
    fn wrapping_add(self, d: Self) -> Self;
    fn wrapping_sub(self, d: Self) -> Self;
}

/// `Count` for an unsigned integer type, by its own wrapping arithmetic.
macro_rules! impl_count {
    ($($t:ty),*) => {$(
        impl Count for $t {
            const ZERO: Self = 0;
            const ONE: Self = 1;
            fn wrapping_add(self, d: Self) -> Self {
                <$t>::wrapping_add(self, d)
            }
            fn wrapping_sub(self, d: Self) -> Self {
                <$t>::wrapping_sub(self, d)
            }
        }
    )*};
}

impl_count!(u8, u32);

/// [`Traversability::rebuild`] on zero counts: every Occupied cell of the first `h` rows
/// of `data` (`w` columns) goes into `counted` and marks its disk's row runs in `count`
/// (+1 at a run's first cell, −1 after its last, wrapping); one running sum per marked row
/// turns the marks into counts. A count never exceeds the disk's size, which the type
/// holds, so the wrapping sums are exact.
fn count_from_scratch<T: Count>(
    count: &mut [T],
    spans: &[(i32, i32)],
    data: &[Occ],
    w: usize,
    h: usize,
    counted: &mut CellBits,
) {
    let mut marked = vec![false; h];
    for y in 0..h {
        let row = &data[y * w..(y + 1) * w];
        // Most of a row holds no obstacle: skip 16 cells at a time.
        for (k, chunk) in row.chunks(16).enumerate() {
            if !chunk.iter().fold(false, |a, o| a | o.is_occupied()) {
                continue;
            }
            for (d, _) in chunk.iter().enumerate().filter(|(_, o)| o.is_occupied()) {
                let x = k * 16 + d;
                counted.insert(y * w + x);
                for &(dy, hx) in spans {
                    let ny = y as i64 + i64::from(dy);
                    if ny < 0 || ny >= h as i64 {
                        continue;
                    }
                    let ny = ny as usize;
                    marked[ny] = true;
                    let lo = (x as i64 - i64::from(hx)).max(0) as usize;
                    let end = x + hx as usize + 1;
                    let c = &mut count[ny * w + lo];
                    *c = c.wrapping_add(T::ONE);
                    if end < w {
                        let c = &mut count[ny * w + end];
                        *c = c.wrapping_sub(T::ONE);
                    }
                }
            }
        }
    }
    for (y, _) in marked.iter().enumerate().filter(|(_, m)| **m) {
        let mut acc = T::ZERO;
        for c in &mut count[y * w..(y + 1) * w] {
            acc = acc.wrapping_add(*c);
            // Stores only where the count is not already right: the zero runs between
            // obstacles' disks stay untouched (a new map's pages are never written).
            if *c != acc {
                *c = acc;
            }
        }
    }
}

/// Count (`occ`) or uncount the Occupied cell at `(x, y)` in the cells of its disk on a
/// `w × h` grid, pushing each cell whose count becomes or stops being zero to `touched`.
fn count_disk<T: Count>(
    count: &mut [T],
    disk: &[(i32, i32)],
    (x, y): (i32, i32),
    (w, h): (usize, usize),
    occ: bool,
    touched: &mut Vec<u32>,
) {
    let (wi, hi) = (w as i32, h as i32);
    for &(dx, dy) in disk {
        let (nx, ny) = (x + dx, y + dy);
        if nx < 0 || ny < 0 || nx >= wi || ny >= hi {
            continue;
        }
        let j = ny as usize * w + nx as usize;
        if occ {
            count[j] = count[j] + T::ONE;
            if count[j] == T::ONE {
                touched.push(j as u32);
            }
        } else {
            count[j] = count[j] - T::ONE;
            if count[j] == T::ZERO {
                touched.push(j as u32);
            }
        }
    }
}

/// The rows of `disk` as `(dy, h)`: the offsets of row `dy` are `−h..=h` (a disk of centre
/// distances is symmetric, and convex along a row).
fn disk_spans(disk: &[(i32, i32)]) -> Vec<(i32, i32)> {
    let mut spans: Vec<(i32, i32)> = Vec::new();
    for &(dx, dy) in disk {
        match spans.iter_mut().find(|s| s.0 == dy) {
            Some(s) => s.1 = s.1.max(dx.abs()),
            None => spans.push((dy, dx.abs())),
        }
    }
    debug_assert_eq!(
        spans.iter().map(|s| 2 * s.1 as usize + 1).sum::<usize>(),
        disk.len(),
        "every disk row is one run"
    );
    spans
}

/// Offsets with centre distance `< clearance`, and `(0, 0)`, clipped to `|dx|, |dy| <
/// max_side`.
fn disk_offsets(clearance: f64, max_side: usize) -> Vec<(i32, i32)> {
    if clearance.is_nan() || clearance < 0.0 || max_side == 0 {
        // an occupied cell still blocks itself (it is not Free anyway)
        return vec![(0, 0)];
    }
    let r = clearance.floor().min((max_side - 1) as f64) as i32;
    // Squared, as whole as the clearance (√2 cells keeps the diagonal neighbours).
    let c2 = grid::units::snap(clearance * clearance);
    let mut out = Vec::new();
    for dy in -r..=r {
        for dx in -r..=r {
            let d2 = dx * dx + dy * dy;
            if d2 == 0 || f64::from(d2) < c2 {
                out.push((dx, dy));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_sizes() {
        // A cell exactly the clearance away is outside the disk (Holz's d_max keeps it).
        assert_eq!(disk_offsets(0.0, 10).len(), 1);
        assert_eq!(disk_offsets(1.0, 10).len(), 1);
        assert_eq!(disk_offsets(1.01, 10).len(), 5);
        assert_eq!(disk_offsets(1.5, 10).len(), 9);
        assert_eq!(disk_offsets(2.0, 10).len(), 9);
        assert_eq!(disk_offsets(2.5, 10).len(), 21);
        assert_eq!(disk_offsets(3.0, 10).len(), 25);
        assert_eq!(disk_offsets(-1.0, 10).len(), 1);
        assert_eq!(disk_offsets(f64::NAN, 10).len(), 1);
        assert_eq!(disk_offsets(1e12, 2).len(), 9);
    }

    #[test]
    fn disk_rows_are_single_runs() {
        for c in [0.0, 1.0, 1.5, 2.5, 4.0, 7.3, -1.0] {
            let disk = disk_offsets(c, 50);
            let spans = disk_spans(&disk);
            let mut from_spans: Vec<(i32, i32)> = spans
                .iter()
                .flat_map(|&(dy, h)| (-h..=h).map(move |dx| (dx, dy)))
                .collect();
            let mut disk = disk;
            from_spans.sort_unstable();
            disk.sort_unstable();
            assert_eq!(from_spans, disk, "clearance {c}");
        }
    }

    #[test]
    fn worked_example() {
        // 5x1 corridor: F F O F F with clearance 1.5 blocks x = 1..=3
        let known = Grid::from_vec(
            5,
            1,
            vec![Occ::Free, Occ::Free, Occ::Occupied, Occ::Free, Occ::Free],
        )
        .unwrap();
        // A cell exactly the clearance away is kept (Holz's d_max): 1.0 blocks only x = 2.
        let mut exact = Traversability::new(5, 1, 1.0);
        exact.update(&known, &[0, 1, 2, 3, 4], &mut Vec::new());
        let tr: Vec<bool> = (0..5).map(|i| exact.is_traversable(&known, i)).collect();
        assert_eq!(tr, [true, true, false, true, true]);
        let mut t = Traversability::new(5, 1, 1.5);
        let mut touched = Vec::new();
        t.update(&known, &[0, 1, 2, 3, 4], &mut touched);
        let tr: Vec<bool> = (0..5).map(|i| t.is_traversable(&known, i)).collect();
        assert_eq!(tr, [true, false, false, false, true]);
        // the obstacle turns free again
        let mut known = known;
        known[2] = Occ::Free;
        touched.clear();
        t.update(&known, &[2], &mut touched);
        assert!((0..5).all(|i| t.is_traversable(&known, i)));
        touched.sort_unstable();
        touched.dedup();
        assert_eq!(touched, [1, 2, 3]);
    }
}
