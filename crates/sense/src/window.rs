//! The cells a scan has seen, as a bitmap of the box in its range: rays mark the cells they
//! enter (a cell many rays cross is marked many times, reported once), and reading the
//! rows in order lists them by flat index with no sort, asking whether each tells the robot
//! anything 64 cells at a time ([`Unseen::telling_bits`]).

use grid::{Grid, Occ};

use crate::unseen::Unseen;

thread_local! {
    /// The cells a scan has seen, one bit per cell of its [`Window`] (kept per thread so that
    /// a scan allocates nothing once it has run).
    static SEEN: std::cell::RefCell<Vec<u64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// Run `f` with this thread's bitmap of seen cells (sized by [`Window::reset`]).
pub(crate) fn with_seen<R>(f: impl FnOnce(&mut Vec<u64>) -> R) -> R {
    SEEN.with(|bits| f(&mut bits.borrow_mut()))
}

/// The box of cells a scan can reach, as a bitmap of whole 64-bit words per row: marking a
/// cell is a bit set, and reading the rows in order lists the seen cells by flat index,
/// each once, with no sort.
pub(crate) struct Window {
    /// Columns and rows of the box in the grid, inclusive lower and exclusive upper bounds.
    x0: i64,
    y0: i64,
    y1: i64,
    /// Words per row of the bitmap.
    words: usize,
    /// Grid width.
    width: usize,
}

impl Window {
    /// The box of cells within `range` cells (plus one for rounding) of `cell`, clipped to
    /// the grid; `None` if `cell` is outside it.
    pub(crate) fn around(grid: &Grid<Occ>, cell: grid::Cell, range: f64) -> Option<Self> {
        grid.checked_index(cell)?;
        let (w, h) = (grid.width() as i64, grid.height() as i64);
        // A beam enters cells at a distance < range, so their columns and rows are within
        // range + ½ of the origin's.
        let reach = (range.ceil() + 1.0).min((w + h) as f64) as i64;
        let (cx, cy) = (i64::from(cell.x), i64::from(cell.y));
        let (x0, x1) = ((cx - reach).max(0), (cx + reach + 1).min(w));
        let (y0, y1) = ((cy - reach).max(0), (cy + reach + 1).min(h));
        Some(Self {
            x0,
            y0,
            y1,
            words: ((x1 - x0) as usize).div_ceil(64),
            width: grid.width(),
        })
    }

    /// Size `bits` for this box, all clear.
    pub(crate) fn reset(&self, bits: &mut Vec<u64>) {
        bits.clear();
        bits.resize(self.words * (self.y1 - self.y0) as usize, 0);
    }

    /// Mark cell `(x, y)` of the grid, which lies in the box.
    #[inline]
    pub(crate) fn mark(&self, bits: &mut [u64], x: i64, y: i64) {
        let (lx, ly) = ((x - self.x0) as usize, (y - self.y0) as usize);
        bits[ly * self.words + lx / 64] |= 1 << (lx % 64);
    }

    /// Every marked cell's flat index that `unseen` (if any) says tells the robot
    /// scanning something, in increasing order.
    pub(crate) fn drain(&self, bits: &[u64], unseen: Option<&Unseen>, mut f: impl FnMut(usize)) {
        for (ly, row) in bits.chunks_exact(self.words).enumerate() {
            let base = (self.y0 as usize + ly) * self.width + self.x0 as usize;
            for (k, &word) in row.iter().enumerate() {
                let mut word = word;
                if word != 0
                    && let Some(u) = unseen
                {
                    word &= u.telling_bits(base + k * 64);
                }
                while word != 0 {
                    f(base + k * 64 + word.trailing_zeros() as usize);
                    word &= word - 1;
                }
            }
        }
    }
}
