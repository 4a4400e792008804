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

use grid::{Grid, Occ};

use crate::error::SenseError;
use crate::footprint::check_plain_range;
use crate::sensor::{Observation, Pose, Sensor, observed, predicted_transparent};
use crate::unseen::Unseen;

/// The square-window sensor of Explore-Bench (module doc).
#[derive(Clone, Debug)]
pub struct SquareSensor {
    /// Half-side of the window in cells.
    half: i64,
}

impl SquareSensor {
    /// A window of half-side `⌊r⌋` cells (`r` finite, `0 ≤ r ≤`
    /// [`MAX_RANGE_CELLS`](crate::footprint::MAX_RANGE_CELLS)).
    pub fn new(r: f64) -> Result<Self, SenseError> {
        check_plain_range(r)?;
        Ok(Self {
            half: r.floor() as i64,
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
        let r = self.half;
        // Every border cell of the window, each once.
        let border = (-r..=r)
            .flat_map(|t| [(t, -r), (t, r)])
            .chain((-r + 1..r).flat_map(|t| [(-r, t), (r, t)]));
        for (tx, ty) in border {
            let (step_x, step_y) = (tx.signum(), ty.signum());
            // Parameter t runs from 0 (origin's centre) to 1 (target's centre).
            let (delta_x, delta_y) = (
                if tx == 0 {
                    f64::INFINITY
                } else {
                    1.0 / tx.abs() as f64
                },
                if ty == 0 {
                    f64::INFINITY
                } else {
                    1.0 / ty.abs() as f64
                },
            );
            let (mut t_x, mut t_y) = (0.5 * delta_x, 0.5 * delta_y);
            let (mut x, mut y) = (0i64, 0i64);
            while (x, y) != (tx, ty) {
                if t_x < t_y {
                    x += step_x;
                    t_x += delta_x;
                } else {
                    y += step_y;
                    t_y += delta_y;
                }
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

impl SquareSensor {
    /// The scan, reporting only the cells `keep` accepts (by flat index), each once, by
    /// increasing index.
    fn scan_keeping(
        &self,
        truth: &Grid<Occ>,
        pose: Pose,
        keep: impl Fn(usize) -> bool,
        out: &mut Observation,
    ) {
        out.clear();
        out.origin = pose.cell;
        let cells = &mut out.cells;
        self.trace(
            truth,
            pose,
            |_, s| s == Occ::Free,
            |i, s| {
                if keep(i) {
                    cells.push((i as u32, observed(s)))
                }
            },
        );
        cells.sort_unstable_by_key(|&(i, _)| i);
        cells.dedup_by_key(|&mut (i, _)| i);
    }
}

impl Sensor for SquareSensor {
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation) {
        self.scan_keeping(truth, pose, |_| true, out);
    }

    /// Every ray is walked, but only the cells that tell the robot scanning something are
    /// reported (and sorted).
    fn scan_unseen(&self, truth: &Grid<Occ>, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        self.scan_keeping(truth, pose, |i| unseen.tells(i), out);
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
    use grid::Cell;

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
