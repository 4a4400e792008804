//! The offline exploration problem of Quattrini Li, Amigoni & Basilico (2012), "Optimal
//! Exploration Problem": a known grid, a start cell, a 360° sensor of range r; find the
//! shortest sequence of sensing positions that perceives the free cells.
//!
//! What is set up once here: the cells reachable from the start (8-connected, no corner
//! squeezing), the *target* cells E_f the goal test counts, each position's visible
//! targets, and the *marks*: the targets, then every other cell next to a reachable cell
//! (walls, free cells nothing perceives), whose perception the paper's boundary test needs
//! (`actions`).
//!
//! Deviation: the paper's E_f is every free cell of the map. Here E_f is the free cells some
//! reachable position can perceive — with `los`, exactly the reachable free cells (a clear
//! segment crosses only free cells and never squeezes through a vertex, so its crossed cells
//! form a legal path; and every free cell sees itself); with `footprint`, the free cells
//! within r of a reachable cell. Free cells no position can perceive would make every goal
//! test fail; they are reported in [`Problem::unperceivable`].

use explore::plan::Reachability;
use grid::edt::edt_squared;
use grid::{Cell, Grid, Occ};
use sense::{FootprintSensor, LosSensor, Observation, Pose, Sensor, SensorSpec};

use crate::error::OptimalError;

/// The widest footprint, in cells, the search takes (past the map's diagonal a footprint
/// is cut to it): its bounds' tables grow with the cube of the range.
pub const MAX_FOOTPRINT_CELLS: f64 = 1024.0;

/// Marks a cell that is not a target.
pub const NOT_TARGET: u32 = u32::MAX;

/// The two sensors of the paper, with their range in cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SensorModel {
    /// The paper's laser: a cell is seen iff the segment between the centres is ≤ r long,
    /// crosses only free cells and never squeezes between two blocked cells sharing a vertex.
    Los(f64),
    /// The paper's footprint speed-up: every cell whose centre is within r, through walls.
    Footprint(f64),
}

impl SensorModel {
    /// The model of a sensor spec on a map of `resolution` m/cell (`lidar` is refused: the
    /// offline search needs a 360° sensor).
    pub fn from_spec(spec: &SensorSpec, resolution: f64) -> Result<Self, OptimalError> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(OptimalError::BadParameter {
                field: "resolution",
                expected: "a positive number of metres per cell",
                found: resolution.to_string(),
            });
        }
        let r = spec.range_cells(resolution);
        match spec {
            SensorSpec::Los { .. } => Ok(SensorModel::Los(r)),
            SensorSpec::Footprint { .. } => Ok(SensorModel::Footprint(r)),
            SensorSpec::Lidar { .. } => Err(OptimalError::Sensor(
                "the optimal search supports los and footprint (360° sensors), not lidar".into(),
            )),
            SensorSpec::Square { .. } => Err(OptimalError::Sensor(
                "the optimal search supports los and footprint (round ranges), not square".into(),
            )),
            SensorSpec::Sonar { .. } => Err(OptimalError::Sensor(
                "the optimal search supports los and footprint (ideal sensors), not sonar".into(),
            )),
        }
    }

    /// The same sensor with its range multiplied by `k` (a range in cells measured on cells
    /// `1 / k` times as large).
    pub fn scaled(self, k: f64) -> Self {
        match self {
            SensorModel::Los(r) => SensorModel::Los(grid::units::snap(r * k)),
            SensorModel::Footprint(r) => SensorModel::Footprint(grid::units::snap(r * k)),
        }
    }

    /// The range in cells.
    pub fn range(self) -> f64 {
        match self {
            SensorModel::Los(r) | SensorModel::Footprint(r) => r,
        }
    }

    /// Whether the sensor sees through walls.
    pub fn through_walls(self) -> bool {
        matches!(self, SensorModel::Footprint(_))
    }

    /// At least the number of cells one position perceives (the disc of radius r + 1), for
    /// sizing work done once per target.
    pub(crate) fn disc_cells(self) -> usize {
        let r = self.range() + 1.0;
        (std::f64::consts::PI * r * r) as usize
    }
}

/// The built sensor behind a [`SensorModel`].
#[derive(Clone, Debug)]
enum Built {
    Los(LosSensor),
    Footprint(FootprintSensor),
}

/// A posed problem: ground truth, start, sensor, reachable cells and targets.
#[derive(Clone, Debug)]
pub struct Problem {
    cells: Grid<Occ>,
    start: u32,
    model: SensorModel,
    sensor: Built,
    reach: Vec<bool>,
    reach_count: usize,
    targets: Vec<u32>,
    /// Per cell: its mark index (a target's index below |E_f|, or |E_f| + k for the k-th
    /// other cell next to a reachable cell), or [`NOT_TARGET`].
    midx: Vec<u32>,
    marks: usize,
    /// Per reachable cell: the mark indices of its 8 neighbours, then [`NOT_TARGET`]s.
    nbr: Vec<[u32; 8]>,
    unperceivable: usize,
}

impl Problem {
    /// Pose the problem on `cells` (ground truth; only `Free` is free) from `start`.
    pub fn new(cells: &Grid<Occ>, start: Cell, model: SensorModel) -> Result<Self, OptimalError> {
        let r = model.range();
        if !(r.is_finite() && r > 0.0) {
            return Err(OptimalError::BadParameter {
                field: "sensor range",
                expected: "a positive number of cells",
                found: r.to_string(),
            });
        }
        let Some(s) = cells.checked_index(start) else {
            return Err(OptimalError::BadStart {
                cell: start,
                why: format!("outside the {}x{} map", cells.width(), cells.height()),
            });
        };
        if !cells[s].is_free() {
            return Err(OptimalError::BadStart {
                cell: start,
                why: "not a free cell".into(),
            });
        }
        // A footprint reaching past the map's diagonal perceives what one reaching it does;
        // its bounds' tables grow with the range (the coverage rate's with its cube).
        let diagonal = ((cells.width().pow(2) + cells.height().pow(2)) as f64)
            .sqrt()
            .ceil();
        let model = match model {
            SensorModel::Footprint(r) if r > diagonal => SensorModel::Footprint(diagonal.max(1.0)),
            m => m,
        };
        if let SensorModel::Footprint(r) = model
            && r > MAX_FOOTPRINT_CELLS
        {
            return Err(OptimalError::BadParameter {
                field: "sensor range",
                expected: "a footprint of at most 1024 cells (or one past the map's diagonal)",
                found: format!("{r} cells"),
            });
        }
        let sensor = match model {
            SensorModel::Los(r) => {
                Built::Los(LosSensor::new(r).map_err(|e| OptimalError::Sensor(e.to_string()))?)
            }
            SensorModel::Footprint(r) => Built::Footprint(
                FootprintSensor::new(r).map_err(|e| OptimalError::Sensor(e.to_string()))?,
            ),
        };
        let (w, h) = (cells.width(), cells.height());
        let data = cells.data();
        let mut dij = Reachability::new(w, h);
        dij.compute(s, |i| data[i].is_free());
        let mut reach = vec![false; w * h];
        for &i in dij.settled() {
            reach[i as usize] = true;
        }
        let reach_count = dij.settled().len();
        let perceivable: Vec<bool> = match model {
            // Los: exactly the reachable free cells (module doc).
            SensorModel::Los(_) => reach.clone(),
            SensorModel::Footprint(r) => {
                let d2 = edt_squared(w, h, |i| reach[i]);
                (0..w * h)
                    .map(|i| data[i].is_free() && d2[i] <= r * r)
                    .collect()
            }
        };
        let mut midx = vec![NOT_TARGET; w * h];
        let mut targets = Vec::new();
        let mut unperceivable = 0;
        for i in 0..w * h {
            if perceivable[i] {
                midx[i] = targets.len() as u32;
                targets.push(i as u32);
            } else if data[i].is_free() {
                unperceivable += 1;
            }
        }
        // Marks: the targets, then every other cell next to a reachable cell (walls, free
        // cells no position perceives), so the boundary test sees the paper's "unknown".
        let mut marks = targets.len();
        for (i, m) in midx.iter_mut().enumerate() {
            if *m == NOT_TARGET && cells.neighbours8(i).any(|j| reach[j]) {
                *m = marks as u32;
                marks += 1;
            }
        }
        let mut nbr = vec![[NOT_TARGET; 8]; w * h];
        for (i, list) in nbr.iter_mut().enumerate() {
            if !reach[i] {
                continue;
            }
            let near = cells.neighbours8(i).map(|j| midx[j]);
            for (slot, t) in list.iter_mut().zip(near.filter(|&t| t != NOT_TARGET)) {
                *slot = t;
            }
        }
        Ok(Self {
            cells: cells.clone(),
            start: s as u32,
            model,
            sensor,
            reach,
            reach_count,
            targets,
            midx,
            marks,
            nbr,
            unperceivable,
        })
    }

    /// The ground truth.
    pub fn cells(&self) -> &Grid<Occ> {
        &self.cells
    }

    /// Flat index of the start cell.
    pub fn start(&self) -> u32 {
        self.start
    }

    /// The sensor model.
    pub fn model(&self) -> SensorModel {
        self.model
    }

    /// Whether flat cell `i` is free and reachable from the start.
    #[inline]
    pub fn reachable(&self, i: usize) -> bool {
        self.reach[i]
    }

    /// Number of reachable cells.
    pub fn reachable_count(&self) -> usize {
        self.reach_count
    }

    /// The mark indices among the 8 neighbours of reachable cell `i`, padded with
    /// [`NOT_TARGET`] (all padding for other cells).
    #[inline]
    pub(crate) fn neighbour_marks(&self, i: usize) -> &[u32; 8] {
        &self.nbr[i]
    }

    /// Number of marks: the targets (indices `0..|E_f|`), then the other cells next to a
    /// reachable cell, whose perception the boundary test needs (walls, mostly).
    pub(crate) fn mark_count(&self) -> usize {
        self.marks
    }

    /// Target index of flat cell `i`, or [`NOT_TARGET`].
    #[inline]
    pub fn target_index(&self, i: usize) -> u32 {
        let m = self.midx[i];
        if (m as usize) < self.targets.len() {
            m
        } else {
            NOT_TARGET
        }
    }

    /// Mark index of flat cell `i` (a target's index, or |E_f| + k for the other cells next
    /// to a reachable cell), or [`NOT_TARGET`].
    #[inline]
    pub(crate) fn mark_index(&self, i: usize) -> u32 {
        self.midx[i]
    }

    /// Flat cells of the targets E_f, by target index (row-major order).
    pub fn targets(&self) -> &[u32] {
        &self.targets
    }

    /// Free cells no reachable position can perceive (left out of E_f).
    pub fn unperceivable(&self) -> usize {
        self.unperceivable
    }

    /// Number of targets that must be perceived for coverage goal `g` in (0, 1]:
    /// `ceil(g · |E_f|)` (computed with a small tolerance so that g = 0.85 of 100 is 85).
    pub fn needed(&self, g: f64) -> usize {
        let n = self.targets.len() as f64;
        let need = (g * n - 1e-9).ceil().max(0.0) as usize;
        need.min(self.targets.len())
    }

    /// Append to `out` the target indices perceived from flat cell `pos` (each once);
    /// `obs` is scratch for the footprint scan.
    pub fn seen_targets(&self, pos: u32, obs: &mut Observation, out: &mut Vec<u32>) {
        self.seen(self.targets.len() as u32, pos, obs, out);
    }

    /// Append to `out` the viewpoints of flat cell `cell`: the reachable cells that perceive
    /// it (the sensors are symmetric, so the reachable cells it would perceive), as flat
    /// cells; `obs` is scratch for the footprint scan.
    pub(crate) fn viewpoints(&self, cell: u32, obs: &mut Observation, out: &mut Vec<u32>) {
        let start = out.len();
        self.seen_targets(cell, obs, out);
        let mut kept = start;
        for k in start..out.len() {
            let p = self.targets[out[k] as usize];
            if self.reach[p as usize] {
                out[kept] = p;
                kept += 1;
            }
        }
        out.truncate(kept);
    }

    /// Append to `out` the mark indices perceived from flat cell `pos` (each once).
    pub(crate) fn seen_marks(&self, pos: u32, obs: &mut Observation, out: &mut Vec<u32>) {
        self.seen(NOT_TARGET, pos, obs, out);
    }

    /// Append to `out` the mark indices below `below` perceived from flat cell `pos`.
    fn seen(&self, below: u32, pos: u32, obs: &mut Observation, out: &mut Vec<u32>) {
        let origin = self.cells.cell(pos as usize);
        match &self.sensor {
            Built::Los(s) => s.for_each_seen(&self.cells, origin, |i, _| {
                let t = self.midx[i as usize];
                if t < below {
                    out.push(t);
                }
            }),
            Built::Footprint(s) => {
                s.scan(&self.cells, Pose::new(origin, 0.0), obs);
                for &(i, _) in &obs.cells {
                    let t = self.midx[i as usize];
                    if t < below {
                        out.push(t);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod footprint_range_tests {
    use super::*;

    /// Regression: `optimal --sensor footprint:r=100000c` on a 5 x 5 ring tried to allocate
    /// 40 GB for the coverage-rate bound's table of offsets and aborted, and 2000 cells took
    /// 92 s (the bound's scan grows with the cube of the range). A footprint past the map's
    /// diagonal is cut to it, the same perception, and one wider than 1024 cells is refused.
    #[test]
    fn a_footprint_past_the_map_is_cut_to_its_diagonal() {
        let mut ring = Grid::new(5, 5, Occ::Occupied);
        for (x, y) in [
            (1, 1),
            (2, 1),
            (3, 1),
            (1, 2),
            (3, 2),
            (1, 3),
            (2, 3),
            (3, 3),
        ] {
            ring.set(Cell::new(x, y), Occ::Free);
        }
        let start = Cell::new(1, 1);
        let wide = Problem::new(&ring, start, SensorModel::Footprint(100_000.0)).expect("cut");
        assert_eq!(wide.model().range(), 8.0);
        let cut = Problem::new(&ring, start, SensorModel::Footprint(8.0)).expect("valid");
        let cfg = crate::Config::default();
        let (a, b) = (
            crate::solve(&wide, &cfg).unwrap(),
            crate::solve(&cut, &cfg).unwrap(),
        );
        assert_eq!((a.upper_bound, a.status), (b.upper_bound, b.status));
        let open = Grid::new(1100, 1100, Occ::Free);
        let e = Problem::new(&open, start, SensorModel::Footprint(1500.0)).unwrap_err();
        assert!(
            e.to_string().contains("a footprint of at most 1024 cells"),
            "{e}"
        );
    }
}
