//! Lower bounds on the path cost from a cell to the nearest of a set of goal cells: the
//! heuristic of a search that streams the goals in cost order (A* toward a set).
//!
//! The bound is the octile distance (the cost of the shortest 8-connected path with no
//! obstacles) to the nearest centre of a [`BLOCK`] × [`BLOCK`] block holding a goal, less
//! [`SLACK`], the farthest a cell of a block lies from its centre; never below 0. A goal
//! lies within `SLACK` of its block's centre, so the bound is at most the octile distance
//! to every goal, and so at most every path cost to one (admissible). The octile distance
//! is a metric whose value between neighbours is the step's cost, so the bound changes by
//! at most a step's cost from a cell to its neighbour (consistent): A* with it settles
//! every cell at its exact cost, and a goal, whose bound is 0, leaves the queue at its cost,
//! after every goal cheaper than it.
//!
//! Blocks rather than goals keep the work per cell small when the goals are many (every
//! frontier cell of a map): each 16 × 16 tile of cells keeps the few block centres that can
//! be nearest to one of its cells, found the first time a search asks for the tile.

use grid::SQRT2;

/// Side of the blocks whose centres stand for the goals, in cells.
pub const BLOCK: usize = 8;
/// The farthest a cell of a block lies from the block's centre (octile), with a margin
/// for rounding.
pub const SLACK: f64 = (BLOCK as f64 - 1.0) / 2.0 * SQRT2 + 1e-6;

/// Side of the tiles that keep their candidate centres, as a shift (16 cells).
const TILE_SHIFT: u32 = 4;
const TILE: usize = 1 << TILE_SHIFT;
/// The octile diameter of a tile, with a margin for rounding.
const TILE_DIAMETER: f64 = (TILE as f64 - 1.0) * SQRT2 + 1e-6;

/// Octile distance of a displacement `(dx, dy)` (both ≥ 0).
#[inline(always)]
fn octile(dx: f64, dy: f64) -> f64 {
    let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
    hi + (SQRT2 - 1.0) * lo
}

/// The heuristic toward one set of goal cells (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct Guide {
    width: usize,
    tiles_x: usize,
    /// Centres `(x, y)` of the blocks holding a goal.
    points: Vec<(f64, f64)>,
    /// Per block: the goal set it was last marked for (deduplication).
    block_mark: Vec<u32>,
    /// Per tile: the goal set its list was made for; its list is `lists[range]`, the
    /// centres themselves (not indices: the bound reads them in a row).
    tile_mark: Vec<u32>,
    tile_range: Vec<(u32, u32)>,
    lists: Vec<(f64, f64)>,
    epoch: u32,
    /// The goal cells, and the same as one bit per cell of the grid.
    goals: Vec<u32>,
    goal_bits: Vec<u64>,
}

impl Guide {
    /// Toward the cells `goals` of a `width × height` grid (cells outside it are ignored).
    pub fn set(&mut self, width: usize, height: usize, goals: &[u32]) {
        let (bx, by) = (width.div_ceil(BLOCK), height.div_ceil(BLOCK));
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x * height.div_ceil(TILE);
        if self.width != width || self.block_mark.len() != bx * by || self.tile_mark.len() != tiles
        {
            self.block_mark = vec![0; bx * by];
            self.tile_mark = vec![0; tiles];
            self.tile_range = vec![(0, 0); tiles];
            self.epoch = 0;
        }
        for &g in &self.goals {
            if let Some(b) = self.goal_bits.get_mut(g as usize >> 6) {
                *b = 0;
            }
        }
        self.goal_bits.resize((width * height).div_ceil(64), 0);
        self.goals.clear();
        self.width = width;
        self.tiles_x = tiles_x;
        self.epoch = crate::upkeep::next_gen(self.epoch, &mut self.block_mark);
        if self.epoch == 1 {
            self.tile_mark.fill(0);
        }
        self.points.clear();
        self.lists.clear();
        let half = (BLOCK as f64 - 1.0) / 2.0;
        for &g in goals {
            let g = g as usize;
            if g >= width * height {
                continue;
            }
            self.goal_bits[g >> 6] |= 1 << (g & 63);
            self.goals.push(g as u32);
            let (x, y) = (g % width / BLOCK, g / width / BLOCK);
            let b = y * bx + x;
            if self.block_mark[b] != self.epoch {
                self.block_mark[b] = self.epoch;
                self.points
                    .push(((x * BLOCK) as f64 + half, (y * BLOCK) as f64 + half));
            }
        }
    }

    /// Number of blocks holding a goal.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there is no goal.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Whether cell `i` (of the grid last set) is one of the goals.
    #[inline(always)]
    pub fn is_goal(&self, i: usize) -> bool {
        self.goal_bits[i >> 6] >> (i & 63) & 1 != 0
    }

    /// The lower bound at column `x`, row `y` (`INFINITY` without goals).
    #[inline]
    pub fn bound(&mut self, x: usize, y: usize) -> f64 {
        let t = (y >> TILE_SHIFT) * self.tiles_x + (x >> TILE_SHIFT);
        if self.tile_mark[t] != self.epoch {
            self.make_list(t, x >> TILE_SHIFT, y >> TILE_SHIFT);
        }
        let (a, b) = self.tile_range[t];
        let (fx, fy) = (x as f64, y as f64);
        let mut best = f64::INFINITY;
        for &(px, py) in &self.lists[a as usize..b as usize] {
            let d = octile((fx - px).abs(), (fy - py).abs());
            // distances are never NaN: a plain comparison, not `f64::min`
            best = if d < best { d } else { best };
        }
        (best - SLACK).max(0.0)
    }

    /// Keep, for tile `t` (column `tx`, row `ty` of tiles), the centres that can be nearest
    /// to one of its cells: within a tile's diameter of the least distance from the tile.
    fn make_list(&mut self, t: usize, tx: usize, ty: usize) {
        let (x0, y0) = ((tx * TILE) as f64, (ty * TILE) as f64);
        let (x1, y1) = (x0 + (TILE - 1) as f64, y0 + (TILE - 1) as f64);
        let from_tile = |&(px, py): &(f64, f64)| {
            let dx = (x0 - px).max(px - x1).max(0.0);
            let dy = (y0 - py).max(py - y1).max(0.0);
            octile(dx, dy)
        };
        let least = self
            .points
            .iter()
            .map(from_tile)
            .fold(f64::INFINITY, f64::min);
        let a = self.lists.len() as u32;
        for p in &self.points {
            if from_tile(p) <= least + TILE_DIAMETER {
                self.lists.push(*p);
            }
        }
        self.tile_mark[t] = self.epoch;
        self.tile_range[t] = (a, self.lists.len() as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Against the octile distance to every goal: never above it, 0 on a goal, and
        /// changing by at most the step's cost between neighbours.
        #[test]
        fn the_bound_is_admissible_and_consistent(
            goals in prop::collection::vec(0u32..(70 * 45), 1..40),
            cells in prop::collection::vec(0usize..(70 * 45), 1..60),
        ) {
            let (w, h) = (70usize, 45usize);
            let mut guide = Guide::default();
            guide.set(w, h, &goals);
            let exact = |i: usize| {
                goals.iter().map(|&g| {
                    let g = g as usize;
                    octile((g % w).abs_diff(i % w) as f64, (g / w).abs_diff(i / w) as f64)
                }).fold(f64::INFINITY, f64::min)
            };
            for &g in &goals {
                prop_assert_eq!(guide.bound(g as usize % w, g as usize / w), 0.0);
            }
            for &i in &cells {
                let (x, y) = (i % w, i / w);
                let b = guide.bound(x, y);
                prop_assert!(b <= exact(i) + 1e-9, "bound {} above {}", b, exact(i));
                prop_assert!(b >= exact(i) - 2.0 * SLACK - 1e-9, "bound {} too loose", b);
                for (dx, dy) in [(1i64, 0i64), (0, 1), (1, 1), (1, -1)] {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let step = if dx != 0 && dy != 0 { SQRT2 } else { 1.0 };
                    let nb = guide.bound(nx as usize, ny as usize);
                    prop_assert!((b - nb).abs() <= step + 1e-9);
                }
            }
        }
    }
}
