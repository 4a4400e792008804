//! Which cells a robot can reach at all, without their costs: a flood fill instead of a
//! reachability map, for the candidate generators and assigners that only ask "reachable?".
//!
//! Under the motion model of [`crate::plan`] a diagonal step is allowed only when one of
//! the two straight cells it passes between is passable, and then that cell joins the two
//! ends by straight steps. So the cells a search from a passable start settles are exactly
//! the start's 4-connected component of passable cells; from an impassable start (which is
//! always left) they are the start and the components of its passable straight neighbours.
//! A scanline fill finds that set with no costs and no queue of cells, reading the passable
//! cells as bits ([`Traversability::passable`](crate::Traversability::passable)): a run of
//! a row is found, marked and its neighbours' runs seeded a word of 64 cells at a time, so
//! a fill costs about the runs of its component, not its cells.
//!
//! The marks are bits too, and a new fill clears only the runs the last one marked; the
//! run lists keep their capacity: in steady state a fill allocates nothing.

use crate::bits::CellBits;

/// The cells reachable from one start (see the module docs).
#[derive(Clone, Debug)]
pub struct Component {
    width: usize,
    height: usize,
    /// The cells of the last fill (allocated by the first fill: strategies that never ask
    /// "reachable?" never pay for it).
    mark: CellBits,
    /// The runs marked by the last fill, as inclusive flat ranges.
    runs: Vec<(usize, usize)>,
    /// Seeds of runs still to fill: `(x, y)`.
    stack: Vec<(u32, u32)>,
    start: Option<usize>,
    start_passable: bool,
    len: usize,
}

impl Component {
    /// Buffers for fills on a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            mark: CellBits::default(),
            runs: Vec::new(),
            stack: Vec::new(),
            start: None,
            start_passable: false,
            len: 0,
        }
    }

    /// Fill the cells reachable from `start` over the cells in `passable` (a set for this
    /// grid's cells; the start itself is always included). A start outside the grid gives
    /// an empty set.
    pub fn compute(&mut self, start: usize, passable: &CellBits) {
        let (w, h) = (self.width, self.height);
        if self.mark.len() != w * h {
            self.mark = CellBits::new(w * h);
            self.runs.clear();
        }
        for &(a, b) in &self.runs {
            self.mark.set_range(a, b, false);
        }
        self.runs.clear();
        self.stack.clear();
        self.len = 0;
        self.start = None;
        self.start_passable = false;
        if start >= w * h || passable.len() != w * h {
            return;
        }
        self.start = Some(start);
        let (x0, y0) = ((start % w) as u32, (start / w) as u32);
        self.start_passable = passable.contains(start);
        if self.start_passable {
            self.stack.push((x0, y0));
        } else {
            self.mark.insert(start);
            self.runs.push((start, start));
            self.len = 1;
            let (x, y) = (x0 as usize, y0 as usize);
            let around = [
                (x + 1 < w).then(|| (x0 + 1, y0)),
                (y + 1 < h).then(|| (x0, y0 + 1)),
                (x > 0).then(|| (x0 - 1, y0)),
                (y > 0).then(|| (x0, y0 - 1)),
            ];
            for (nx, ny) in around.into_iter().flatten() {
                if passable.contains(ny as usize * w + nx as usize) {
                    self.stack.push((nx, ny));
                }
            }
        }
        let open = |mark: &CellBits, k: usize| passable.word(k) & !mark.word(k);
        while let Some((x, y)) = self.stack.pop() {
            let (x, y) = (x as usize, y as usize);
            let row = y * w;
            if self.mark.contains(row + x) {
                continue;
            }
            // The run of unmarked passable cells through (x, y).
            let a = run_start(|k| open(&self.mark, k), row + x, row);
            let b = run_end(|k| open(&self.mark, k), row + x, row + w - 1);
            self.mark.set_range(a, b, true);
            self.runs.push((a, b));
            self.len += b - a + 1;
            // One seed per run of fillable cells in the rows above and below.
            for ny in [y.wrapping_sub(1), y + 1] {
                if ny >= h {
                    continue;
                }
                let nrow = ny * w;
                let (lo, hi) = (nrow + a - row, nrow + b - row);
                let stack = &mut self.stack;
                run_starts(
                    |k| open(&self.mark, k),
                    lo,
                    hi,
                    |s| stack.push(((s - nrow) as u32, ny as u32)),
                );
            }
        }
    }

    /// Whether cell `i` is reachable from the start of the last fill.
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.mark.contains(i)
    }

    /// Number of cells in the component.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the component is empty (no fill yet, or a start outside the grid).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The start of the last fill, if inside the grid.
    pub fn start(&self) -> Option<usize> {
        self.start
    }

    /// Whether a fill from `other` gives the same set as the last one: both starts are
    /// passable and `other` is in this component (the components of passable cells
    /// partition them).
    pub fn same_from(&self, other: usize, passable: &CellBits) -> bool {
        self.start.is_some()
            && self.start_passable
            && self.contains(other)
            && passable.contains(other)
    }
}

/// The first cell of the run of open cells through open cell `p`, not before `lo`; `open(k)`
/// is word k of the open cells.
#[inline]
fn run_start(open: impl Fn(usize) -> u64, p: usize, lo: usize) -> usize {
    let mut q = p;
    loop {
        let off = q & 63;
        // bit q at the top: the open cells from q down are the leading ones
        let ones = (!(open(q >> 6) << (63 - off))).leading_zeros() as usize;
        let start = q + 1 - ones;
        if start <= lo {
            return lo;
        }
        if ones <= off {
            return start;
        }
        q = start - 1;
    }
}

/// The last cell of the run of open cells through open cell `p`, not after `hi`.
#[inline]
fn run_end(open: impl Fn(usize) -> u64, p: usize, hi: usize) -> usize {
    let mut q = p;
    loop {
        let off = q & 63;
        // bit q at the bottom: the open cells from q up are the trailing ones
        let ones = (!(open(q >> 6) >> off)).trailing_zeros() as usize;
        if ones == 0 {
            return q - 1;
        }
        let end = q + ones - 1;
        if end >= hi {
            return hi;
        }
        if off + ones < 64 {
            return end;
        }
        q = end + 1;
    }
}

/// Call `seed(s)` for the first cell s of every run of open cells within `lo..=hi` (a run
/// that starts before `lo` is seeded at `lo`).
#[inline]
fn run_starts(open: impl Fn(usize) -> u64, lo: usize, hi: usize, mut seed: impl FnMut(usize)) {
    let mut carry = 0u64;
    for k in lo >> 6..=hi >> 6 {
        let mut word = open(k);
        if k == lo >> 6 {
            word &= u64::MAX << (lo & 63);
        }
        if k == hi >> 6 {
            word &= u64::MAX >> (63 - (hi & 63));
        }
        let mut starts = word & !((word << 1) | carry);
        carry = word >> 63;
        while starts != 0 {
            seed(k * 64 + starts.trailing_zeros() as usize);
            starts &= starts - 1;
        }
    }
}
