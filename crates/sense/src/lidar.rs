//! A planar laser scanner with a field of view (Holz et al.: 180°, 1° resolution): each
//! beam is traced from the sensor cell's centre with the exact grid traversal of
//! Amanatides & Woo (1987). Facing one of the eight headings of a grid move, the scan
//! walks the beams' cells from a prefix tree made once (`beam.rs`), the same cells.
//!
//! # Semantics
//!
//! - Beams leave the centre of the sensor cell at angles `heading − fov/2`,
//!   `heading − fov/2 + res`, … up to `heading + fov/2` (inclusive when `fov/res` is an
//!   integer). With `fov = 360` the beam at `heading + 180°` would repeat the first one and
//!   is left out. Angles are in grid coordinates: direction `(cos θ, sin θ)` with `x` to the
//!   right and `y` **down** (see [`Pose`]).
//! - A beam visits the cells its ray enters at a distance `< r` cells from the centre, in
//!   order. Free cells are reported Free; the first non-free cell (Occupied or ground-truth
//!   Unknown) is reported Occupied and ends the beam; leaving the grid ends it unreported.
//! - The sensor's own cell is always reported; if it is non-free, nothing else is seen.
//! - Cells crossed by several beams are reported once (the observation is sorted by index:
//!   beams mark a bitmap of the box in range, read row by row, so no sort is needed).
//! - A predicted scan ([`Sensor::predict`]) traces the same beams on a belief, passing
//!   through Unknown cells too; it reports cells unsorted and with repeats.

use std::sync::Arc;

use grid::{Grid, Occ};

use crate::beam::{BeamWalk, CompassTrees, rotate};
use crate::error::SenseError;
use crate::footprint::check_plain_range;
use crate::sensor::{Observation, Pose, Sensor, observed};
use crate::unseen::Unseen;
use crate::window::{Window, with_seen};

/// The smallest angular resolution accepted, in degrees (at most 36,000 beams).
pub const MIN_LIDAR_RES_DEG: f64 = 0.01;

/// A laser scanner: range in cells, field of view and angular resolution in degrees.
#[derive(Clone, Debug)]
pub struct LidarSensor {
    range: f64,
    fov_deg: f64,
    res_deg: f64,
    /// Unit directions `(cos, sin)` of the beams relative to the heading.
    beams: Vec<(f64, f64)>,
    /// The beam trees for the eight headings of a grid move, shared by every scanner of
    /// the same range and beams (`None` past the trees' reach).
    compass: Option<Arc<CompassTrees>>,
}

impl LidarSensor {
    /// A lidar of range `r` cells, field of view `fov_deg` in `(0, 360]` and angular
    /// resolution `res_deg` in `[0.01, 360]` degrees.
    pub fn new(r: f64, fov_deg: f64, res_deg: f64) -> Result<Self, SenseError> {
        check_plain_range(r)?;
        if !(fov_deg.is_finite() && fov_deg > 0.0 && fov_deg <= 360.0) {
            return Err(SenseError::BadAngle {
                expected: "a field of view in (0, 360] degrees",
                found: fov_deg,
            });
        }
        if !(res_deg.is_finite() && (MIN_LIDAR_RES_DEG..=360.0).contains(&res_deg)) {
            return Err(SenseError::BadAngle {
                expected: "an angular resolution in [0.01, 360] degrees",
                found: res_deg,
            });
        }
        const EPS: f64 = 1e-9;
        let full = fov_deg >= 360.0;
        let mut beams = Vec::new();
        for k in 0.. {
            let rel = f64::from(k) * res_deg;
            let more = if full {
                rel < 360.0 - EPS
            } else {
                rel <= fov_deg + EPS
            };
            if !more {
                break;
            }
            let a = (rel - fov_deg / 2.0).to_radians();
            beams.push((a.cos(), a.sin()));
        }
        Ok(Self {
            range: r,
            fov_deg,
            res_deg,
            compass: CompassTrees::shared(&beams, r, (fov_deg, res_deg)),
            beams,
        })
    }

    /// Field of view in degrees.
    pub fn fov_deg(&self) -> f64 {
        self.fov_deg
    }

    /// Angular resolution in degrees.
    pub fn res_deg(&self) -> f64 {
        self.res_deg
    }

    /// Number of beams per scan.
    pub fn beams(&self) -> usize {
        self.beams.len()
    }
}

impl LidarSensor {
    /// Trace every beam from `pose` in `grid`: `seen(flat index, x, y, state)` for each cell a beam
    /// enters within range, in beam order (cells may repeat across beams). A beam passes
    /// through cells whose state is `transparent` and ends at (after reporting) the first
    /// other one; leaving the grid ends it unreported. The sensor's own cell is reported
    /// first; if it is not transparent nothing else is.
    #[inline]
    fn trace(
        &self,
        grid: &Grid<Occ>,
        pose: Pose,
        transparent: impl Fn(usize, Occ) -> bool,
        mut seen: impl FnMut(usize, i64, i64, Occ),
    ) {
        let Some(origin) = grid.checked_index(pose.cell) else {
            return;
        };
        let data = grid.data();
        seen(
            origin,
            i64::from(pose.cell.x),
            i64::from(pose.cell.y),
            data[origin],
        );
        if !transparent(origin, data[origin]) {
            return;
        }
        let (w, h) = (grid.width() as i64, grid.height() as i64);
        let (ch, sh) = (pose.heading.cos(), pose.heading.sin());
        for &beam in &self.beams {
            let (dx, dy) = rotate(beam, ch, sh);
            let (ox, oy) = (i64::from(pose.cell.x), i64::from(pose.cell.y));
            for (x, y) in BeamWalk::new(dx, dy, self.range) {
                let (x, y) = (ox + x, oy + y);
                if x < 0 || y < 0 || x >= w || y >= h {
                    break;
                }
                let i = (y * w + x) as usize;
                seen(i, x, y, data[i]);
                if !transparent(i, data[i]) {
                    break;
                }
            }
        }
    }
}

impl LidarSensor {
    /// The scan, reporting only the cells that tell the robot scanning something if
    /// `unseen` is given, each once, by increasing index. The beams mark every cell they
    /// enter; the question is asked when the marks are read, 64 cells at a time, so the
    /// walk itself reads nothing but the ground truth.
    fn scan_keeping(
        &self,
        truth: &Grid<Occ>,
        pose: Pose,
        unseen: Option<&Unseen>,
        out: &mut Observation,
    ) {
        out.clear();
        out.origin = pose.cell;
        let Some(window) = Window::around(truth, pose.cell, self.range) else {
            return;
        };
        with_seen(|bits| {
            window.reset(bits);
            if !self.trace_compass(truth, pose, &window, bits) {
                self.trace(
                    truth,
                    pose,
                    |_, s| s == Occ::Free,
                    |_, x, y, _| window.mark(bits, x, y),
                );
            }
            let data = truth.data();
            window.drain(bits, unseen, |i| {
                out.cells.push((i as u32, observed(data[i])))
            });
        });
    }
}

impl LidarSensor {
    /// The walk of [`trace`](Self::trace) through free cells of `truth`, marking `window`'s
    /// `bits`, taken down the beam tree of the pose's heading when it faces one of the
    /// eight move headings exactly: each cell the beams share is visited once, and a cell
    /// that stops them (or lies outside the grid: a beam moves one way along each axis, so
    /// it never comes back) skips the rest of its subtree. Returns whether it did the walk.
    fn trace_compass(
        &self,
        truth: &Grid<Occ>,
        pose: Pose,
        window: &Window,
        bits: &mut [u64],
    ) -> bool {
        let Some(tree) = self.compass.as_ref().and_then(|c| c.tree(pose.heading)) else {
            return false;
        };
        let cell = pose.cell;
        window.mark(bits, i64::from(cell.x), i64::from(cell.y));
        if *truth.get(cell) == Occ::Free {
            tree.walk(truth, cell, window, bits);
        }
        true
    }
}

impl Sensor for LidarSensor {
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation) {
        self.scan_keeping(truth, pose, None, out);
    }

    /// Every beam is walked (it is the walk that finds what hides what), but only the cells
    /// that tell the robot scanning something are reported: on a real plan most of a scan
    /// is known already.
    fn scan_unseen(&self, truth: &Grid<Occ>, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        self.scan_keeping(truth, pose, Some(unseen), out);
    }

    fn skips_known(&self) -> bool {
        true
    }

    fn range_cells(&self) -> f64 {
        self.range
    }

    fn field_of_view_deg(&self) -> f64 {
        self.fov_deg
    }

    /// The beams of [`scan`](Sensor::scan) on the belief, unsorted and with repeats (no
    /// sort: callers deduplicate with a mark buffer).
    fn predict(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        self.predict_through(known, pose, false, |_| true, out);
    }

    fn predict_unknown(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        self.predict_through(known, pose, true, |_| true, out);
    }

    fn predict_gated(
        &self,
        known: &Grid<Occ>,
        pose: Pose,
        unknown_only: bool,
        passable: &dyn Fn(usize) -> bool,
        out: &mut Vec<u32>,
    ) {
        self.predict_through(known, pose, unknown_only, passable, out);
    }
}

impl LidarSensor {
    /// The predicted beams on the belief: Free cells pass, Occupied ones stop a beam, an
    /// Unknown cell passes where `passable(index)`; every cell reached is pushed (only the
    /// Unknown ones if `unknown_only`). The one walk behind the three `predict*` methods.
    fn predict_through(
        &self,
        known: &Grid<Occ>,
        pose: Pose,
        unknown_only: bool,
        passable: impl Fn(usize) -> bool,
        out: &mut Vec<u32>,
    ) {
        out.clear();
        let transparent = |i: usize, s: Occ| match s {
            Occ::Free => true,
            Occ::Unknown => passable(i),
            Occ::Occupied => false,
        };
        self.trace(known, pose, transparent, |i, _, _, s| {
            if !unknown_only || s == Occ::Unknown {
                out.push(i as u32);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::compass_headings;
    use crate::test_grids::grid_from;
    use grid::Cell;
    use proptest::prelude::*;

    /// The scan as the beams walk it afresh: every cell [`LidarSensor::trace`] enters
    /// through free cells, once, by index.
    fn walked_scan(s: &LidarSensor, g: &Grid<Occ>, pose: Pose) -> Vec<(u32, Occ)> {
        let mut cells = Vec::new();
        s.trace(
            g,
            pose,
            |_, o| o == Occ::Free,
            |i, _, _, o| cells.push((i as u32, observed(o))),
        );
        cells.sort_unstable();
        cells.dedup();
        cells
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// Facing a move heading, the scan down the beam tree sees exactly the cells the
        /// beams' own walk sees, near the grid's edges too.
        #[test]
        fn the_beam_tree_sees_what_walked_beams_see(
            bits in proptest::collection::vec(any::<u8>(), 16..400),
            density in 0u8..40,
            w in 1usize..70,
            h in 1usize..70,
            ox in 0i32..70,
            oy in 0i32..70,
            range in 0.0f64..40.0,
            fov in prop::sample::select(vec![1.0, 90.0, 180.0, 270.0, 360.0]),
            res in prop::sample::select(vec![0.5, 1.0, 3.0, 10.0]),
            heading in 0usize..8,
        ) {
            let g = grid_from(w, h, &bits, density);
            let s = LidarSensor::new(range, fov, res).expect("valid");
            let heading = compass_headings()[heading];
            let pose = Pose::new(Cell::new(ox % w as i32, oy % h as i32), heading);
            let mut obs = Observation::new();
            s.scan(&g, pose, &mut obs);
            prop_assert!(s.compass.as_ref().and_then(|c| c.tree(heading)).is_some());
            prop_assert_eq!(obs.cells, walked_scan(&s, &g, pose));
        }
    }

    /// The beam tree is taken for exactly the eight headings a grid move gives (the
    /// simulation's `atan2(dy, dx)`), and only for them.
    #[test]
    fn move_headings_take_the_beam_tree() {
        let mut g = Grid::new(400, 400, Occ::Free);
        for y in 0..400 {
            g.set(Cell::new(250, y), Occ::Occupied);
        }
        let s = LidarSensor::new(160.0, 180.0, 1.0).expect("valid");
        let headings = compass_headings();
        // Every move the simulation makes, as it computes the heading after it.
        for (dx, dy) in (-1..=1).flat_map(|dx| (-1..=1).map(move |dy| (dx, dy))) {
            if (dx, dy) != (0, 0) {
                let h = f64::from(dy).atan2(f64::from(dx));
                assert!(headings.contains(&h), "{dx}, {dy}");
            }
        }
        let window = Window::around(&g, Cell::new(200, 200), 160.0).expect("inside");
        let mut bits = Vec::new();
        for h in [0.3, -2.0, 1e-9] {
            window.reset(&mut bits);
            let pose = Pose::new(Cell::new(200, 200), h);
            assert!(!s.trace_compass(&g, pose, &window, &mut bits));
        }
        for &h in headings {
            window.reset(&mut bits);
            let pose = Pose::new(Cell::new(200, 200), h);
            assert!(s.trace_compass(&g, pose, &window, &mut bits));
            let mut obs = Observation::new();
            s.scan(&g, pose, &mut obs);
            assert_eq!(obs.cells, walked_scan(&s, &g, pose));
        }
    }

    /// A scanner whose tables would be too large walks its beams instead.
    #[test]
    fn huge_tables_are_not_built() {
        let s = LidarSensor::new(100_000.0, 360.0, 0.01).expect("valid");
        assert!(s.compass.is_none());
        let s = LidarSensor::new(3_000.0, 360.0, 0.1).expect("valid");
        assert!(s.compass.as_ref().is_some_and(|c| c.tree(0.0).is_none()));
        let g = Grid::new(30, 20, Occ::Free);
        let mut obs = Observation::new();
        let pose = Pose::new(Cell::new(3, 4), 0.0);
        s.scan(&g, pose, &mut obs);
        assert_eq!(obs.cells, walked_scan(&s, &g, pose));
    }

    #[test]
    fn beam_counts() {
        assert_eq!(
            LidarSensor::new(5.0, 180.0, 1.0).expect("valid").beams(),
            181
        );
        assert_eq!(
            LidarSensor::new(5.0, 360.0, 1.0).expect("valid").beams(),
            360
        );
        assert_eq!(
            LidarSensor::new(5.0, 100.0, 3.0).expect("valid").beams(),
            34
        );
        assert!(LidarSensor::new(5.0, 0.0, 1.0).is_err());
        assert!(LidarSensor::new(5.0, 400.0, 1.0).is_err());
        assert!(LidarSensor::new(5.0, 180.0, 0.0).is_err());
        assert!(LidarSensor::new(f64::NAN, 180.0, 1.0).is_err());
    }

    #[test]
    fn wall_at_known_distance() {
        // Sensor at (1, 5) looking right (+x); wall column at x = 6.
        let mut g = Grid::new(10, 11, Occ::Free);
        for y in 0..11 {
            g.set(Cell::new(6, y), Occ::Occupied);
        }
        let s = LidarSensor::new(20.0, 2.0, 1.0).expect("valid"); // beams at −1°, 0°, +1°
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(1, 5), 0.0), &mut obs);
        let want: Vec<(u32, Occ)> = (1..=6)
            .map(|x| {
                (
                    g.index(Cell::new(x, 5)) as u32,
                    if x == 6 { Occ::Occupied } else { Occ::Free },
                )
            })
            .collect();
        assert_eq!(obs.cells, want);
        // Out of range: r = 4.5 reaches cells entered before 4.5, i.e. up to x = 5 (entered at 3.5).
        let s = LidarSensor::new(4.5, 2.0, 1.0).expect("valid");
        s.scan(&g, Pose::new(Cell::new(1, 5), 0.0), &mut obs);
        assert_eq!(obs.cells.len(), 5);
        assert!(obs.cells.iter().all(|c| c.1 == Occ::Free));
        let s = LidarSensor::new(3.4, 2.0, 1.0).expect("valid");
        s.scan(&g, Pose::new(Cell::new(1, 5), 0.0), &mut obs);
        assert_eq!(obs.cells.len(), 4);
    }

    #[test]
    fn half_fov_sees_only_the_front_half() {
        let g = Grid::new(21, 21, Occ::Free);
        let o = Cell::new(10, 10);
        let s = LidarSensor::new(8.0, 180.0, 1.0).expect("valid");
        let mut obs = Observation::new();
        // Heading π/2 looks down (+y): every seen cell has y ≥ the sensor's row.
        s.scan(&g, Pose::new(o, std::f64::consts::FRAC_PI_2), &mut obs);
        assert!(obs.cells.iter().all(|&(i, _)| g.cell(i as usize).y >= o.y));
        assert!(
            obs.cells
                .iter()
                .any(|&(i, _)| g.cell(i as usize) == Cell::new(10, 18))
        );
        // And looking up (heading −π/2): only rows ≤ the sensor's.
        s.scan(&g, Pose::new(o, -std::f64::consts::FRAC_PI_2), &mut obs);
        assert!(obs.cells.iter().all(|&(i, _)| g.cell(i as usize).y <= o.y));
        assert!(
            obs.cells
                .iter()
                .any(|&(i, _)| g.cell(i as usize) == Cell::new(10, 2))
        );
        // The sides are seen at exactly ±90°.
        assert!(
            obs.cells
                .iter()
                .any(|&(i, _)| g.cell(i as usize) == Cell::new(2, 10))
        );
        assert!(
            obs.cells
                .iter()
                .any(|&(i, _)| g.cell(i as usize) == Cell::new(18, 10))
        );
    }
}
