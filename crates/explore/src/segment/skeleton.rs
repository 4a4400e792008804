//! The Voronoi skeleton of free space (Holz et al. 2010, Figure 7 step 1; Wurm et al.'s
//! "distance transform and skeletonization").
//!
//! Free cells are thinned in order of increasing clearance (distance-ordered homotopic
//! thinning, Pudney 1998): a cell is removed when it is *simple* — removing it changes neither
//! the 8-connected components of the skeleton nor the 4-connected components of the rest —
//! and is not an end point. What is left is a one-cell-wide, 8-connected curve per free
//! component that keeps every loop around an obstacle and runs along the ridge of the
//! distance transform: a grid version of the generalized Voronoi diagram.
//!
//! Clearance is the exact Euclidean distance to the nearest cell that is not free
//! (`grid::edt`), or to just outside the grid if that is nearer. On a partial map, unknown
//! cells count as not free, so the skeleton of a partly seen room ends at its frontier.
//!
//! Deviations: (1) cells already visited and kept are re-examined as soon as a neighbour is
//! removed (last in, first out) instead of by their exact priority — a difference only in
//! which of two equally centred cells stays. (2) Short spurs are pruned once: a branch from an
//! end point to a junction that runs straight into a wall (its length along the skeleton is at
//! most the clearance it loses plus one cell) comes from a notch in a wall, not from a room
//! corner (a corner branch runs diagonally and is about √2 times longer).

use grid::edt::{EdtScratch, edt_squared_into};
use grid::{Grid, Occ};

/// 8-neighbour offsets in the order of the simple-point table: E, NE, N, NW, W, SW, S, SE.
pub(crate) const RING: [(i32, i32); 8] = [
    (1, 0),
    (1, -1),
    (0, -1),
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Yokoi's 8-connectivity number of a neighbourhood mask (bit k set = RING[k] in the set).
const fn connectivity8(mask: u8) -> u32 {
    let mut n = 0;
    let mut k = 0;
    while k < 8 {
        let a = 1 - ((mask >> k) & 1) as u32;
        let b = 1 - ((mask >> ((k + 1) % 8)) & 1) as u32;
        let c = 1 - ((mask >> ((k + 2) % 8)) & 1) as u32;
        n += a - a * b * c;
        k += 2;
    }
    n
}

const fn simple_table() -> [bool; 256] {
    let mut t = [false; 256];
    let mut m = 0;
    while m < 256 {
        t[m] = connectivity8(m as u8) == 1;
        m += 1;
    }
    t
}

/// `SIMPLE[mask]`: whether a cell whose 8-neighbourhood is `mask` (bits in [`RING`] order) can
/// be removed without changing the topology (8-connected set, 4-connected complement).
pub(crate) const SIMPLE: [bool; 256] = simple_table();

/// Whether a neighbourhood mask describes a simple cell (exposed for tests).
pub fn is_simple(mask: u8) -> bool {
    SIMPLE[mask as usize]
}

/// Buffers of the skeleton, reused across calls.
#[derive(Clone, Debug)]
pub struct Skeleton {
    width: usize,
    height: usize,
    /// Squared clearance per cell in cells² (0 for cells that are not free).
    pub(crate) d2: Vec<u32>,
    /// Whether each cell is on the skeleton.
    pub(crate) on: Vec<bool>,
    edt: Grid<f64>,
    edt_scratch: EdtScratch,
    order: Vec<u32>,
    count: Vec<u32>,
    visited: Vec<bool>,
    stack: Vec<u32>,
    chain: Vec<u32>,
}

impl Default for Skeleton {
    fn default() -> Self {
        Self {
            width: 0,
            height: 0,
            d2: Vec::new(),
            on: Vec::new(),
            edt: Grid::new(0, 0, 0.0),
            edt_scratch: EdtScratch::new(),
            order: Vec::new(),
            count: Vec::new(),
            visited: Vec::new(),
            stack: Vec::new(),
            chain: Vec::new(),
        }
    }
}

impl Skeleton {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Grid width.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Grid height.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Whether cell `i` is on the skeleton.
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.on[i]
    }

    /// Clearance of cell `i` in cells (0 for cells that are not free).
    #[inline]
    pub fn clearance(&self, i: usize) -> f64 {
        f64::from(self.d2[i]).sqrt()
    }

    /// Squared clearance of cell `i` in cells².
    #[inline]
    pub fn clearance2(&self, i: usize) -> u32 {
        self.d2[i]
    }

    /// The skeleton cells, in index order.
    pub fn cells(&self) -> impl Iterator<Item = usize> + '_ {
        self.on.iter().enumerate().filter(|p| *p.1).map(|p| p.0)
    }

    /// Compute the clearance and the skeleton of the free cells of `known`.
    pub fn compute(&mut self, known: &Grid<Occ>) {
        let (w, h) = (known.width(), known.height());
        self.width = w;
        self.height = h;
        let n = w * h;
        let cells = known.data();
        edt_squared_into(
            w,
            h,
            |i| !cells[i].is_free(),
            &mut self.edt,
            &mut self.edt_scratch,
        );
        self.d2.clear();
        self.d2.resize(n, 0);
        let mut max_d2 = 0u32;
        for (i, c) in cells.iter().enumerate() {
            if !c.is_free() {
                continue;
            }
            let (x, y) = ((i % w) as u64, (i / w) as u64);
            // just outside the grid counts as not free
            let border = (x + 1).min(y + 1).min(w as u64 - x).min(h as u64 - y);
            let e = self.edt.data()[i];
            let b2 = (border * border) as f64;
            let v = if e < b2 { e } else { b2 };
            let v = v.min(f64::from(u32::MAX)) as u32;
            self.d2[i] = v;
            max_d2 = max_d2.max(v);
        }
        // counting sort of the free cells by (clearance², index)
        self.count.clear();
        self.count.resize(max_d2 as usize + 2, 0);
        for i in 0..n {
            if self.d2[i] > 0 {
                self.count[self.d2[i] as usize + 1] += 1;
            }
        }
        for k in 1..self.count.len() {
            self.count[k] += self.count[k - 1];
        }
        let free = self.count[self.count.len() - 1] as usize;
        self.order.clear();
        self.order.resize(free, 0);
        for i in 0..n {
            let d = self.d2[i];
            if d > 0 {
                let slot = &mut self.count[d as usize];
                self.order[*slot as usize] = i as u32;
                *slot += 1;
            }
        }
        // the rank of a cell in the order: visited cells are those ranked before the current
        self.on.clear();
        self.on.extend(self.d2.iter().map(|&d| d > 0));
        self.visited.clear();
        self.visited.resize(n, false);
        let order = std::mem::take(&mut self.order);
        for &p in &order {
            let p = p as usize;
            self.visited[p] = true;
            self.try_remove(p);
            while let Some(q) = self.stack.pop() {
                self.try_remove(q as usize);
            }
        }
        self.order = order;
        self.prune_spurs();
    }

    /// Neighbourhood mask of `i` over skeleton cells, and the number of set bits.
    #[inline]
    pub(crate) fn mask(&self, i: usize) -> (u8, u32) {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = ((i as i64) % w, (i as i64) / w);
        let mut m = 0u8;
        for (k, &(dx, dy)) in RING.iter().enumerate() {
            let (nx, ny) = (x + dx as i64, y + dy as i64);
            if nx >= 0 && ny >= 0 && nx < w && ny < h && self.on[(ny * w + nx) as usize] {
                m |= 1 << k;
            }
        }
        (m, m.count_ones())
    }

    /// Remove `p` if it is on the skeleton, simple and not an end point; queue the visited
    /// neighbours for a re-check.
    fn try_remove(&mut self, p: usize) {
        if !self.on[p] {
            return;
        }
        let (m, deg) = self.mask(p);
        if deg <= 1 || !SIMPLE[m as usize] {
            return;
        }
        self.on[p] = false;
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = ((p as i64) % w, (p as i64) / w);
        for &(dx, dy) in RING.iter() {
            let (nx, ny) = (x + dx as i64, y + dy as i64);
            if nx >= 0 && ny >= 0 && nx < w && ny < h {
                let q = (ny * w + nx) as usize;
                if self.on[q] && self.visited[q] {
                    self.stack.push(q as u32);
                }
            }
        }
    }

    /// The skeleton neighbours of `i`, in [`RING`] order, into `out` (cleared first).
    pub(crate) fn neighbours(&self, i: usize, out: &mut [usize; 8]) -> usize {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = ((i as i64) % w, (i as i64) / w);
        let mut k = 0;
        for &(dx, dy) in RING.iter() {
            let (nx, ny) = (x + dx as i64, y + dy as i64);
            if nx >= 0 && ny >= 0 && nx < w && ny < h {
                let q = (ny * w + nx) as usize;
                if self.on[q] {
                    out[k] = q;
                    k += 1;
                }
            }
        }
        k
    }

    /// One round of spur pruning (see the module documentation).
    fn prune_spurs(&mut self) {
        let n = self.on.len();
        let mut nb = [0usize; 8];
        let mut chain = std::mem::take(&mut self.chain);
        for tip in 0..n {
            if !self.on[tip] || self.neighbours(tip, &mut nb) != 1 {
                continue;
            }
            chain.clear();
            chain.push(tip as u32);
            let mut prev = tip;
            let mut cur = nb[0];
            let mut length = step(self.width, prev, cur);
            let junction = loop {
                let k = self.neighbours(cur, &mut nb);
                if k != 2 {
                    break (k >= 3).then_some(cur);
                }
                let next = if nb[0] == prev { nb[1] } else { nb[0] };
                chain.push(cur as u32);
                length += step(self.width, cur, next);
                prev = cur;
                cur = next;
                if cur == tip {
                    break None;
                }
            };
            let Some(j) = junction else { continue };
            if length <= self.clearance(j) - self.clearance(tip) + 1.0 {
                for &c in &chain {
                    self.on[c as usize] = false;
                }
            }
        }
        self.chain = chain;
    }
}

/// Length of the step between two 8-adjacent cells.
#[inline]
pub(crate) fn step(width: usize, a: usize, b: usize) -> f64 {
    if a % width != b % width && a / width != b / width {
        grid::SQRT2
    } else {
        1.0
    }
}
