//! Which cells a robot can reach at all, without their costs: a flood fill instead of a
//! reachability map, for the candidate generators and assigners that only ask "reachable?".
//!
//! Under the motion model of [`crate::plan`] a diagonal step is allowed only when one of
//! the two straight cells it passes between is passable, and then that cell joins the two
//! ends by straight steps. So the cells a search from a passable start settles are exactly
//! the start's 4-connected component of passable cells; from an impassable start (which is
//! always left) they are the start and the components of its passable straight neighbours.
//! A scanline fill finds that set touching each cell a few times with no costs and no
//! queue of cells, several times faster than a full Dijkstra search on a floor plan.
//!
//! The marks are generation-stamped, so a new fill does not clear O(map) memory, and the
//! run stack keeps its capacity: in steady state a fill allocates nothing.

use crate::upkeep::next_gen;

/// The cells reachable from one start (see the module docs).
#[derive(Clone, Debug)]
pub struct Component {
    width: usize,
    height: usize,
    /// `mark[i] == epoch` iff cell i is in the component of the last fill (allocated by
    /// the first fill: strategies that never ask "reachable?" never pay for it).
    mark: Vec<u32>,
    epoch: u32,
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
            mark: Vec::new(),
            epoch: 0,
            stack: Vec::new(),
            start: None,
            start_passable: false,
            len: 0,
        }
    }

    /// Fill the cells reachable from `start` over cells where `passable(i)` (the start itself
    /// is always included). A start outside the grid gives an empty set.
    pub fn compute(&mut self, start: usize, passable: impl Fn(usize) -> bool) {
        if self.mark.len() != self.width * self.height {
            self.mark = vec![0; self.width * self.height];
        }
        self.epoch = next_gen(self.epoch, &mut self.mark);
        self.stack.clear();
        self.len = 0;
        let (w, h) = (self.width, self.height);
        if start >= w * h {
            self.start = None;
            self.start_passable = false;
            return;
        }
        self.start = Some(start);
        let (x0, y0) = ((start % w) as u32, (start / w) as u32);
        self.start_passable = passable(start);
        if self.start_passable {
            self.stack.push((x0, y0));
        } else {
            self.mark[start] = self.epoch;
            self.len = 1;
            let (x, y) = (x0 as usize, y0 as usize);
            let around = [
                (x + 1 < w).then(|| (x0 + 1, y0)),
                (y + 1 < h).then(|| (x0, y0 + 1)),
                (x > 0).then(|| (x0 - 1, y0)),
                (y > 0).then(|| (x0, y0 - 1)),
            ];
            for (nx, ny) in around.into_iter().flatten() {
                if passable(ny as usize * w + nx as usize) {
                    self.stack.push((nx, ny));
                }
            }
        }
        while let Some((x, y)) = self.stack.pop() {
            let (x, y) = (x as usize, y as usize);
            let row = y * w;
            if self.mark[row + x] == self.epoch {
                continue;
            }
            // The run of unmarked passable cells through (x, y).
            let (mut a, mut b) = (x, x);
            while a > 0 && self.mark[row + a - 1] != self.epoch && passable(row + a - 1) {
                a -= 1;
            }
            while b + 1 < w && self.mark[row + b + 1] != self.epoch && passable(row + b + 1) {
                b += 1;
            }
            self.mark[row + a..=row + b].fill(self.epoch);
            self.len += b - a + 1;
            // One seed per run of fillable cells in the rows above and below.
            for ny in [y.wrapping_sub(1), y + 1] {
                if ny >= h {
                    continue;
                }
                let nrow = ny * w;
                let mut in_run = false;
                for nx in a..=b {
                    let j = nrow + nx;
                    let open = self.mark[j] != self.epoch && passable(j);
                    if open && !in_run {
                        self.stack.push((nx as u32, ny as u32));
                    }
                    in_run = open;
                }
            }
        }
    }

    /// Whether cell `i` is reachable from the start of the last fill.
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.epoch != 0 && self.mark.get(i) == Some(&self.epoch)
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
    pub fn same_from(&self, other: usize, passable: impl Fn(usize) -> bool) -> bool {
        self.start.is_some() && self.start_passable && self.contains(other) && passable(other)
    }
}
