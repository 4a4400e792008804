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
/// Side of the squares the centres are filed by, as a shift (64 cells, 4 × 4 tiles).
const AREA_SHIFT: u32 = 6;
const AREA: usize = 1 << AREA_SHIFT;
/// With more centres than this, a tile's list is made from the squares around it, nearest
/// first, rather than from every centre.
const FILED_FROM: usize = 64;

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
    /// The centres filed by squares of [`AREA`] cells, row-major with `areas_x` squares a
    /// row: square `s` holds `by_area[area_start[s]..area_start[s + 1]]`.
    areas_x: usize,
    areas_y: usize,
    area_start: Vec<u32>,
    by_area: Vec<(f64, f64)>,
    /// Set by [`flatten`](Self::flatten): the goals are only marked, the bound is 0.
    flat: bool,
    /// Set by [`set`](Self::set) when the goals lie in more blocks than it was asked for:
    /// `points` is then empty and the bound must not be asked.
    too_many: bool,
}

impl Guide {
    /// Toward the cells `goals` of a `width × height` grid (cells outside it are ignored);
    /// whether they lie in at least one and at most `most` blocks. Beyond `most` blocks the
    /// bound is not worth asking: the guide then holds no goal (the caller searches
    /// without it, or [`flatten`]s it toward the goals), and the blocks are neither all
    /// found nor filed nor the goals marked. A rule whose goals are every frontier cell of
    /// a large map sets a guide at every decision.
    ///
    /// [`flatten`]: Self::flatten
    pub fn set(&mut self, width: usize, height: usize, goals: &[u32], most: usize) -> bool {
        self.flat = false;
        self.too_many = false;
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
            let (x, y) = (g % width / BLOCK, g / width / BLOCK);
            let b = y * bx + x;
            if self.block_mark[b] != self.epoch {
                if self.points.len() == most {
                    // One block too many: the bound will not be asked.
                    self.points.clear();
                    self.too_many = true;
                    self.mark_goals(width, height, &[]);
                    return false;
                }
                self.block_mark[b] = self.epoch;
                self.points
                    .push(((x * BLOCK) as f64 + half, (y * BLOCK) as f64 + half));
            }
        }
        self.mark_goals(width, height, goals);
        if self.points.len() > FILED_FROM {
            self.file_by_area(width, height);
        }
        !self.points.is_empty()
    }

    /// Toward the cells `goals` of a `width × height` grid, with a bound of 0 everywhere:
    /// for a search that must settle every goal wherever it lies and only wants the goals
    /// marked, not the way toward them.
    pub fn flatten(&mut self, width: usize, height: usize, goals: &[u32]) {
        self.mark_goals(width, height, goals);
        self.points.clear();
        self.flat = true;
        self.too_many = false;
    }

    /// Forget the last goals' bits and mark the cells `goals` inside a `width × height`
    /// grid instead, keeping them in `self.goals`.
    fn mark_goals(&mut self, width: usize, height: usize, goals: &[u32]) {
        for &g in &self.goals {
            if let Some(b) = self.goal_bits.get_mut(g as usize >> 6) {
                *b = 0;
            }
        }
        self.goal_bits.resize((width * height).div_ceil(64), 0);
        self.goals.clear();
        for &g in goals {
            let g = g as usize;
            if g < width * height {
                self.goal_bits[g >> 6] |= 1 << (g & 63);
                self.goals.push(g as u32);
            }
        }
    }

    /// File the centres by squares of [`AREA`] cells.
    fn file_by_area(&mut self, width: usize, height: usize) {
        let (ax, ay) = (width.div_ceil(AREA), height.div_ceil(AREA));
        (self.areas_x, self.areas_y) = (ax, ay);
        let area =
            |&(px, py): &(f64, f64)| (py as usize >> AREA_SHIFT) * ax + (px as usize >> AREA_SHIFT);
        self.by_area.clear();
        self.by_area.extend_from_slice(&self.points);
        self.by_area.sort_unstable_by_key(area);
        self.area_start.clear();
        self.area_start.resize(ax * ay + 1, 0);
        for p in &self.by_area {
            self.area_start[area(p) + 1] += 1;
        }
        for s in 1..self.area_start.len() {
            self.area_start[s] += self.area_start[s - 1];
        }
    }

    /// Whether cell `i` (of the grid last set) is one of the goals.
    #[inline(always)]
    pub fn is_goal(&self, i: usize) -> bool {
        self.goal_bits[i >> 6] >> (i & 63) & 1 != 0
    }

    /// The lower bound at column `x`, row `y` (`INFINITY` without goals; 0 if flat).
    #[inline]
    pub fn bound(&mut self, x: usize, y: usize) -> f64 {
        debug_assert!(!self.too_many, "the bound of goals in too many blocks");
        if self.flat {
            return 0.0;
        }
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
        let a = self.lists.len();
        // gather the centres within a tile's diameter of the least distance so far (returned)
        let mut least = f64::INFINITY;
        let mut gather = |centres: &[(f64, f64)], lists: &mut Vec<(f64, f64)>| {
            for p in centres {
                let d = from_tile(p);
                if d <= least + TILE_DIAMETER {
                    lists.push(*p);
                }
                least = least.min(d);
            }
            least
        };
        if self.points.len() <= FILED_FROM {
            gather(&self.points, &mut self.lists);
        } else {
            // squares ring by ring around the tile's: one r rings out lies more than
            // (r - 1) squares' sides away, so the rings end once that exceeds the least
            // distance found plus a tile's diameter
            let (sx, sy) = ((x0 as i64) >> AREA_SHIFT, (y0 as i64) >> AREA_SHIFT);
            let (ax, ay) = (self.areas_x as i64, self.areas_y as i64);
            let mut found = f64::INFINITY;
            for r in 0..=ax.max(ay) {
                if r > 0 && ((r - 1) * AREA as i64) as f64 > found + TILE_DIAMETER {
                    break;
                }
                for qy in (sy - r).max(0)..=(sy + r).min(ay - 1) {
                    let edge = qy == sy - r || qy == sy + r;
                    let step = if edge { 1 } else { (2 * r) as usize };
                    for qx in (sx - r..=sx + r).step_by(step) {
                        if (0..ax).contains(&qx) {
                            let q = (qy * ax + qx) as usize;
                            let square =
                                self.area_start[q] as usize..self.area_start[q + 1] as usize;
                            found = gather(&self.by_area[square], &mut self.lists);
                        }
                    }
                }
            }
        }
        // and keep those within a tile's diameter of the least over all of them
        let mut kept = a;
        for i in a..self.lists.len() {
            let p = self.lists[i];
            if from_tile(&p) <= least + TILE_DIAMETER {
                self.lists[kept] = p;
                kept += 1;
            }
        }
        self.lists.truncate(kept);
        let a = a as u32;
        self.tile_mark[t] = self.epoch;
        self.tile_range[t] = (a, self.lists.len() as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// With goals in more blocks than [`FILED_FROM`] (each tile's list made from the
        /// squares around it), in a corner or anywhere: the least over every block's
        /// centre, bit for bit, near the goals and many squares away.
        #[test]
        fn filed_centres_give_the_nearest(
            corner in prop::collection::vec((0u32..120, 0u32..70), 150..600),
            anywhere in prop::collection::vec(0u32..(600 * 400), 0..300),
            cells in prop::collection::vec(0usize..(600 * 400), 1..200),
        ) {
            let (w, h) = (600usize, 400usize);
            let goals: Vec<u32> = corner
                .iter()
                .map(|&(x, y)| y * w as u32 + x)
                .chain(anywhere)
                .collect();
            let mut guide = Guide::default();
            guide.set(w, h, &goals, usize::MAX);
            let half = (BLOCK as f64 - 1.0) / 2.0;
            let centres: Vec<(f64, f64)> = goals
                .iter()
                .map(|&g| {
                    let (bx, by) = (g as usize % w / BLOCK, g as usize / w / BLOCK);
                    ((bx * BLOCK) as f64 + half, (by * BLOCK) as f64 + half)
                })
                .collect();
            for &i in &cells {
                let (x, y) = ((i % w) as f64, (i / w) as f64);
                let least = centres
                    .iter()
                    .map(|&(px, py)| octile((x - px).abs(), (y - py).abs()))
                    .fold(f64::INFINITY, f64::min);
                prop_assert_eq!(
                    guide.bound(i % w, i / w).to_bits(),
                    (least - SLACK).max(0.0).to_bits()
                );
            }
        }

        /// With a block limit: true exactly when the goals lie in 1..=most blocks, and then
        /// the goals marked and the same bounds as without a limit; beyond it no goal
        /// marked (none of an earlier set either), and flattened toward them, all marked.
        #[test]
        fn a_block_limit_says_whether_the_goals_fit(
            goals in prop::collection::vec(0u32..(200 * 120), 0..120),
            most in 0usize..80,
            cells in prop::collection::vec(0usize..(200 * 120), 1..40),
        ) {
            let (w, h) = (200usize, 120usize);
            let blocks: std::collections::HashSet<(usize, usize)> = goals
                .iter()
                .map(|&g| (g as usize % w / BLOCK, g as usize / w / BLOCK))
                .collect();
            let mut limited = Guide::default();
            // A guide set before with other goals, as a search's guide is.
            limited.set(w, h, &[5, 7000, 23000], usize::MAX);
            let fits = limited.set(w, h, &goals, most);
            prop_assert_eq!(fits, !blocks.is_empty() && blocks.len() <= most);
            let over = blocks.len() > most;
            for i in 0..w * h {
                prop_assert_eq!(limited.is_goal(i), !over && goals.contains(&(i as u32)));
            }
            if over {
                let mut flat = limited.clone();
                flat.flatten(w, h, &goals);
                for i in 0..w * h {
                    prop_assert_eq!(flat.is_goal(i), goals.contains(&(i as u32)));
                }
                prop_assert_eq!(flat.bound(cells[0] % w, cells[0] / w), 0.0);
            }
            if fits {
                let mut full = Guide::default();
                full.set(w, h, &goals, usize::MAX);
                for &i in &cells {
                    prop_assert_eq!(
                        limited.bound(i % w, i / w).to_bits(),
                        full.bound(i % w, i / w).to_bits()
                    );
                }
            }
        }

        /// Against the octile distance to every goal: never above it, 0 on a goal, and
        /// changing by at most the step's cost between neighbours.
        #[test]
        fn the_bound_is_admissible_and_consistent(
            goals in prop::collection::vec(0u32..(70 * 45), 1..40),
            cells in prop::collection::vec(0usize..(70 * 45), 1..60),
        ) {
            let (w, h) = (70usize, 45usize);
            let mut guide = Guide::default();
            guide.set(w, h, &goals, usize::MAX);
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
