//! Explore-Bench's grid sensor (Xu et al. 2022, its grid simulator): the robot sees the
//! square window of half-side `R` cells around its cell, along straight rays from its cell
//! to every cell on the window's border, each ray ending at the first cell that is not free
//! (which is seen); the robot's own cell and its 8 neighbours are always seen. There is no
//! circular range: a corner of the window is `R·√2` cells away.
//!
//! Deviations from its Python simulator, both at most one cell: the window is symmetric
//! (`−R..=R`; the simulator slices `x − R .. x + R`, one row and column fewer on one side),
//! and rays are traversed cell by cell (Amanatides–Woo, from the robot's cell centre to the
//! border cell's centre) rather than sampled at `max(|dx|, |dy|) + 2` points and floored.
//!
//! `R` is `⌊r⌋` for a range of `r` cells (`square:r=3.5` at 0.05 m: 70 cells).

use std::sync::{Arc, OnceLock};

use grid::{Grid, Occ};

use crate::beam::{BeamTree, BeamWalk, KeptCache, kept};
use crate::error::SenseError;
use crate::footprint::check_plain_range;
use crate::sensor::{Observation, Pose, Sensor, observed, predicted_transparent};
use crate::unseen::Unseen;
use crate::window::{Window, with_seen};

/// The largest half-side whose rays are walked from a tree (351,852 nodes, 2.7 MiB, at 180
/// cells: `square:r=9` at 0.05 m).
const MAX_TREE_HALF: i64 = 180;

/// The largest half-side of the window, in cells. A scan casts a ray to each of the
/// window's `8R` border cells whether or not the map reaches that far, so its cost grows
/// with the range past the map's size: at a million cells (the other sensors' bound) a
/// scan on a 50 × 40 map cast 8 million rays and a run took minutes. 1024 cells is 51.2 m
/// at 0.05 m, past any window Explore-Bench uses.
pub const MAX_SQUARE_HALF_CELLS: f64 = 1024.0;

/// The square-window sensor of Explore-Bench (module doc).
#[derive(Clone)]
pub struct SquareSensor {
    /// Half-side of the window in cells.
    half: i64,
    /// The rays' prefix tree (`None` past [`MAX_TREE_HALF`]), shared by every sensor of
    /// the same half-side.
    tree: Option<Arc<BeamTree>>,
}

impl std::fmt::Debug for SquareSensor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SquareSensor")
            .field("half", &self.half)
            .finish()
    }
}

impl SquareSensor {
    /// A window of half-side `⌊r⌋` cells (`r` finite, `0 ≤ r ≤` [`MAX_SQUARE_HALF_CELLS`]).
    pub fn new(r: f64) -> Result<Self, SenseError> {
        check_plain_range(r)?;
        if r > MAX_SQUARE_HALF_CELLS {
            return Err(SenseError::BadRange {
                max: MAX_SQUARE_HALF_CELLS,
                found: r,
            });
        }
        let half = r.floor() as i64;
        Ok(Self {
            half,
            tree: tree_for(half),
        })
    }

    /// The window's half-side in cells.
    pub fn half_side(&self) -> i64 {
        self.half
    }

    /// Call `seen(index, state)` for the origin, its 8 neighbours and every cell the rays
    /// enter (repeats possible); a ray ends after the first cell that is not `transparent`.
    fn trace(
        &self,
        grid: &Grid<Occ>,
        pose: Pose,
        transparent: impl Fn(usize, Occ) -> bool,
        mut seen: impl FnMut(usize, Occ),
    ) {
        let Some(origin) = grid.checked_index(pose.cell) else {
            return;
        };
        let data = grid.data();
        let (w, h) = (grid.width() as i64, grid.height() as i64);
        let (ox, oy) = (i64::from(pose.cell.x), i64::from(pose.cell.y));
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (x, y) = (ox + dx, oy + dy);
                if x >= 0 && y >= 0 && x < w && y < h {
                    let i = (y * w + x) as usize;
                    seen(i, data[i]);
                }
            }
        }
        if !transparent(origin, data[origin]) || self.half == 0 {
            return;
        }
        for (tx, ty) in border(self.half) {
            for (x, y) in ray(tx, ty) {
                let (gx, gy) = (ox + x, oy + y);
                if gx < 0 || gy < 0 || gx >= w || gy >= h {
                    break;
                }
                let i = (gy * w + gx) as usize;
                seen(i, data[i]);
                if !transparent(i, data[i]) {
                    break;
                }
            }
        }
    }
}

/// The rays' tree for a window of half-side `half` (`None` past [`MAX_TREE_HALF`]), shared
/// by every sensor of that half-side.
fn tree_for(half: i64) -> Option<Arc<BeamTree>> {
    if half > MAX_TREE_HALF {
        return None;
    }
    static CACHE: KeptCache<i64, BeamTree> = OnceLock::new();
    Some(kept(&CACHE, half, || {
        let paths: Vec<Vec<(i16, i16)>> = border(half)
            .map(|(tx, ty)| ray(tx, ty).map(|(x, y)| (x as i16, y as i16)).collect())
            .collect();
        BeamTree::from_paths(&paths)
    }))
}

/// Every border cell of the window of half-side `r` (≥ 1), each once.
fn border(r: i64) -> impl Iterator<Item = (i64, i64)> {
    (-r..=r)
        .flat_map(move |t| [(t, -r), (t, r)])
        .chain((-r + 1..r).flat_map(move |t| [(-r, t), (r, t)]))
}

/// The cells the ray from the origin cell's centre to border cell `(tx, ty)`'s centre
/// enters, in order (offsets from the origin), its target last: the beams' traversal with
/// the ray's parameter running to 1 at the target's centre (no boundary lies exactly there,
/// so the walk ends on the target).
fn ray(tx: i64, ty: i64) -> BeamWalk {
    BeamWalk::new(tx as f64, ty as f64, 1.0)
}

impl SquareSensor {
    /// The scan, reporting only the cells that tell the robot scanning something if
    /// `unseen` is given, each once, by increasing index: the rays' tree is walked, marking
    /// a bitmap of the window (a cell many rays cross is marked many times, reported once);
    /// a window too large for a tree walks every ray and sorts.
    fn scan_keeping(
        &self,
        truth: &Grid<Occ>,
        pose: Pose,
        unseen: Option<&Unseen>,
        out: &mut Observation,
    ) {
        out.clear();
        out.origin = pose.cell;
        let Some(tree) = &self.tree else {
            let cells = &mut out.cells;
            self.trace(
                truth,
                pose,
                |_, s| s == Occ::Free,
                |i, s| {
                    if unseen.is_none_or(|u| u.tells(i)) {
                        cells.push((i as u32, observed(s)))
                    }
                },
            );
            cells.sort_unstable_by_key(|&(i, _)| i);
            cells.dedup_by_key(|&mut (i, _)| i);
            return;
        };
        let Some(window) = Window::around(truth, pose.cell, self.half as f64) else {
            return;
        };
        with_seen(|bits| {
            window.reset(bits);
            let (ox, oy) = (i64::from(pose.cell.x), i64::from(pose.cell.y));
            let (w, h) = (truth.width() as i64, truth.height() as i64);
            for y in (oy - 1).max(0)..=(oy + 1).min(h - 1) {
                for x in (ox - 1).max(0)..=(ox + 1).min(w - 1) {
                    window.mark(bits, x, y);
                }
            }
            if self.half > 0 && *truth.get(pose.cell) == Occ::Free {
                tree.walk(truth, pose.cell, &window, bits);
            }
            let data = truth.data();
            window.drain(bits, unseen, |i| {
                out.cells.push((i as u32, observed(data[i])))
            });
        });
    }
}

impl Sensor for SquareSensor {
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation) {
        self.scan_keeping(truth, pose, None, out);
    }

    /// Every ray is walked, but only the cells that tell the robot scanning something are
    /// reported.
    fn scan_unseen(&self, truth: &Grid<Occ>, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        self.scan_keeping(truth, pose, Some(unseen), out);
    }

    fn skips_known(&self) -> bool {
        true
    }

    /// The radius of the circle around the window (`R·√2`): no seen cell is farther.
    fn range_cells(&self) -> f64 {
        self.half as f64 * std::f64::consts::SQRT_2
    }

    fn predict(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        out.clear();
        self.trace(
            known,
            pose,
            |_, s| predicted_transparent(s),
            |i, _| out.push(i as u32),
        );
    }

    fn predict_unknown(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        out.clear();
        self.trace(
            known,
            pose,
            |_, s| predicted_transparent(s),
            |i, s| {
                if s == Occ::Unknown {
                    out.push(i as u32);
                }
            },
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_grids::grid_from;
    use grid::Cell;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The scan down the rays' tree sees exactly the cells the rays' own walk sees,
        /// each once and by index, near the grid's edges too.
        #[test]
        fn the_ray_tree_sees_what_walked_rays_see(
            bits in proptest::collection::vec(any::<u8>(), 16..400),
            density in 0u8..50,
            w in 1usize..60,
            h in 1usize..60,
            ox in 0i32..60,
            oy in 0i32..60,
            r in 0.0f64..25.0,
        ) {
            let g = grid_from(w, h, &bits, density);
            let s = SquareSensor::new(r).expect("valid");
            prop_assert!(s.tree.is_some());
            let pose = Pose::new(Cell::new(ox % w as i32, oy % h as i32), 0.0);
            let mut want = Vec::new();
            s.trace(&g, pose, |_, o| o == Occ::Free, |i, o| want.push((i as u32, observed(o))));
            want.sort_unstable();
            want.dedup();
            let mut obs = Observation::new();
            s.scan(&g, pose, &mut obs);
            prop_assert_eq!(obs.cells, want);
        }
    }

    /// A window too large for a tree walks its rays: the same cells, each once, by index.
    #[test]
    fn a_huge_window_walks_its_rays() {
        let s = SquareSensor::new(500.0).expect("valid");
        assert!(s.tree.is_none());
        let mut g = Grid::new(40, 30, Occ::Free);
        g.set(Cell::new(20, 12), Occ::Occupied);
        let pose = Pose::new(Cell::new(18, 10), 0.0);
        let mut want = Vec::new();
        s.trace(
            &g,
            pose,
            |_, o| o == Occ::Free,
            |i, o| want.push((i as u32, observed(o))),
        );
        want.sort_unstable();
        want.dedup();
        let mut obs = Observation::new();
        s.scan(&g, pose, &mut obs);
        assert!(want.len() > 100);
        assert_eq!(obs.cells, want);
    }

    #[test]
    fn open_space_shows_the_whole_window() {
        let g = Grid::new(21, 21, Occ::Free);
        let s = SquareSensor::new(3.9).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(10, 10), 0.0), &mut obs);
        assert_eq!(obs.cells.len(), 7 * 7, "the 7 x 7 window, corners included");
        assert!(obs.cells.iter().all(|&(_, o)| o == Occ::Free));
        assert!((s.range_cells() - 3.0 * std::f64::consts::SQRT_2).abs() < 1e-12);
    }

    #[test]
    fn a_wall_hides_what_is_behind_it() {
        // A wall at x = 12 across the window: cells beyond it are not seen.
        let mut g = Grid::new(21, 21, Occ::Free);
        for y in 0..21 {
            g.set(Cell::new(12, y), Occ::Occupied);
        }
        let s = SquareSensor::new(5.0).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(10, 10), 0.0), &mut obs);
        assert!(obs.cells.iter().all(|&(i, _)| g.cell(i as usize).x <= 12));
        assert!(
            obs.cells
                .contains(&(g.index(Cell::new(12, 10)) as u32, Occ::Occupied))
        );
    }

    #[test]
    fn the_neighbours_are_seen_even_inside_a_wall() {
        let mut g = Grid::new(5, 5, Occ::Occupied);
        g.set(Cell::new(2, 2), Occ::Free);
        let s = SquareSensor::new(2.0).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(2, 2), 0.0), &mut obs);
        assert_eq!(obs.cells.len(), 9);
    }
}
