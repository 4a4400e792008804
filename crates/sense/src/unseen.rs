//! Where a scan can still reveal something: the blocks of the map holding a cell that is
//! Unknown in the belief and that some ray could reach, kept up to date from the cells a
//! belief changes.
//!
//! A ray reaches a cell only through a free cell next to it (the sensor's own cell is
//! free), so a cell that is not free in the ground truth and has no free 8-neighbour (the
//! inside of a wall, the world outside the plan) is never seen, and a block holding only
//! known cells and such cells has nothing left to show. A scan whose belief classes cannot
//! change once known (a ternary or reflection belief with an exact sensor: a free cell is
//! only ever passed, an obstacle only ever hit) may therefore leave out every known cell,
//! and stop looking where only such blocks are left:
//! [`Sensor::scan_unseen`](crate::Sensor::scan_unseen). Most of what a robot crossing
//! explored space sees is known, so its scans report little, and the belief little to
//! integrate.

use grid::{Grid, Occ};

/// Per-block counts of the cells still to be seen (module doc).
#[derive(Clone, Debug)]
pub struct Unseen {
    /// log₂ of the block side in cells.
    shift: u32,
    /// Grid and block-grid sizes.
    width: usize,
    height: usize,
    blocks_wide: usize,
    /// Cells still to be seen, per block (row-major).
    counts: Vec<u32>,
    /// One bit per cell: some ray could reach it.
    reachable: Vec<u64>,
    /// One bit per cell: counted (reachable and Unknown in the belief).
    pending: Vec<u64>,
}

impl Unseen {
    /// The cells of `known` still to be seen in `truth` (same size), counted on blocks of
    /// `2^shift` cells a side (`shift` at most 8).
    pub fn new(truth: &Grid<Occ>, known: &Grid<Occ>, shift: u32) -> Self {
        let shift = shift.min(8);
        let (w, h) = (truth.width(), truth.height());
        debug_assert_eq!((w, h), (known.width(), known.height()));
        let side = 1usize << shift;
        let (bw, bh) = (w.div_ceil(side), h.div_ceil(side));
        let words = (w * h).div_ceil(64);
        let mut u = Self {
            shift,
            width: w,
            height: h,
            blocks_wide: bw,
            counts: vec![0; bw * bh],
            reachable: vec![0; words],
            pending: vec![0; words],
        };
        let t = truth.data();
        let free = |x: usize, y: usize| t[y * w + x] == Occ::Free;
        for y in 0..h {
            for x in 0..w {
                let seeable = free(x, y)
                    || (y.saturating_sub(1)..=(y + 1).min(h - 1)).any(|ny| {
                        (x.saturating_sub(1)..=(x + 1).min(w - 1)).any(|nx| free(nx, ny))
                    });
                if seeable {
                    let i = y * w + x;
                    u.reachable[i / 64] |= 1 << (i % 64);
                }
            }
        }
        for (i, &class) in known.data().iter().enumerate() {
            u.recount(i, class);
        }
        u
    }

    /// Bring the counts up to date with the cells in `changed`, whose classes in `known`
    /// may have changed since the last call (or since [`new`](Self::new)).
    pub fn update(&mut self, known: &Grid<Occ>, changed: &[u32]) {
        let k = known.data();
        for &c in changed {
            let i = c as usize;
            if i < k.len() {
                self.recount(i, k[i]);
            }
        }
    }

    /// Count cell `i` if it is reachable and `class` is Unknown, uncount it otherwise.
    fn recount(&mut self, i: usize, class: Occ) {
        let bit = 1u64 << (i % 64);
        if self.reachable[i / 64] & bit == 0 {
            return;
        }
        let want = class == Occ::Unknown;
        if want == (self.pending[i / 64] & bit != 0) {
            return;
        }
        self.pending[i / 64] ^= bit;
        let b = self.block_of(i % self.width, i / self.width);
        if want {
            self.counts[b] += 1;
        } else {
            self.counts[b] -= 1;
        }
    }

    fn block_of(&self, x: usize, y: usize) -> usize {
        (y >> self.shift) * self.blocks_wide + (x >> self.shift)
    }

    /// The side of a block in cells.
    pub fn block_side(&self) -> usize {
        1 << self.shift
    }

    /// Whether cell `(x, y)` is still to be seen.
    pub fn is_pending(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.is_pending_at(y * self.width + x)
    }

    /// Whether the cell of flat index `i` (in the grid) is still to be seen.
    #[inline]
    pub fn is_pending_at(&self, i: usize) -> bool {
        self.pending[i / 64] & (1 << (i % 64)) != 0
    }

    /// Call `f(x0, y0, x1, y1)` with the cell box (inclusive, clipped to the grid) of every
    /// block overlapping columns `x0..=x1` and rows `y0..=y1` that holds a cell still to
    /// be seen; returns how many there were.
    pub fn for_each_pending_block(
        &self,
        (x0, y0): (i64, i64),
        (x1, y1): (i64, i64),
        mut f: impl FnMut(i64, i64, i64, i64),
    ) -> usize {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x0, y0, x1, y1) = (x0.max(0), y0.max(0), x1.min(w - 1), y1.min(h - 1));
        if x0 > x1 || y0 > y1 {
            return 0;
        }
        let s = self.shift;
        let side = 1i64 << s;
        let mut n = 0;
        for by in (y0 >> s)..=(y1 >> s) {
            let row = &self.counts[by as usize * self.blocks_wide..];
            for bx in (x0 >> s)..=(x1 >> s) {
                if row[bx as usize] != 0 {
                    n += 1;
                    let (cx, cy) = (bx * side, by * side);
                    f(
                        cx,
                        cy,
                        (cx + side - 1).min(w - 1),
                        (cy + side - 1).min(h - 1),
                    );
                }
            }
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::Cell;

    #[test]
    fn walls_inside_and_the_outside_are_never_pending() {
        let rows = "#####\n#...#\n#####\n#####\n#####\n#####\n";
        let truth = grid::io::parse_ascii(rows, 1.0).unwrap();
        let known = truth.cells.map(|_| Occ::Unknown);
        let u = Unseen::new(&truth.cells, &known, 1);
        // The rows of wall below the corridor's wall have no free neighbour.
        assert!(u.is_pending(0, 0) && u.is_pending(2, 1) && u.is_pending(4, 2));
        assert!(!u.is_pending(2, 3) && !u.is_pending(0, 5));
        let mut boxes = Vec::new();
        u.for_each_pending_block((0, 0), (4, 5), |a, b, c, d| boxes.push((a, b, c, d)));
        // Blocks of 2 × 2; the last column is one cell wide; rows 4-5 hold nothing to see.
        assert_eq!(
            boxes,
            vec![
                (0, 0, 1, 1),
                (2, 0, 3, 1),
                (4, 0, 4, 1),
                (0, 2, 1, 3),
                (2, 2, 3, 3),
                (4, 2, 4, 3)
            ]
        );
    }

    #[test]
    fn counts_follow_the_belief() {
        let truth = grid::io::parse_ascii("....\n....\n", 1.0).unwrap();
        let mut known = truth.cells.map(|_| Occ::Unknown);
        let mut u = Unseen::new(&truth.cells, &known, 1);
        assert_eq!(u.for_each_pending_block((0, 0), (3, 1), |_, _, _, _| {}), 2);
        for x in 0..2 {
            for y in 0..2 {
                let i = known.index(Cell::new(x, y));
                known.data_mut()[i] = Occ::Free;
                u.update(&known, &[i as u32]);
            }
        }
        let mut boxes = Vec::new();
        u.for_each_pending_block((0, 0), (3, 1), |a, b, c, d| boxes.push((a, b, c, d)));
        assert_eq!(boxes, vec![(2, 0, 3, 1)]);
        // A cell forgotten again counts again (beliefs that can forget).
        let i = known.index(Cell::new(1, 1));
        known.data_mut()[i] = Occ::Unknown;
        u.update(&known, &[i as u32, i as u32]);
        assert_eq!(u.for_each_pending_block((0, 0), (3, 1), |_, _, _, _| {}), 2);
    }
}
