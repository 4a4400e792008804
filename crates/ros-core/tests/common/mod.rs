//! A pretend robot for the tests: a true map, an ideal sensor, and the map a SLAM node
//! would publish from what the robot has seen.
#![allow(dead_code)]

use grid::{Cell, GridMap, Occ};
use record::msgs::{OccupancyGrid, Time};
use record::occupancy::{MapFrame, msg_from_map};
use sense::{Belief, KnownGrid, Observation, Pose, Sensor, SensorSpec};

/// The true world and what has been seen of it.
pub struct World {
    pub truth: GridMap,
    pub seen: KnownGrid,
    sensor: Box<dyn Sensor>,
    obs: Observation,
    changed: Vec<u32>,
}

impl World {
    /// A world over `truth` seen with sensor `spec`.
    pub fn new(truth: GridMap, spec: &str) -> Self {
        let sensor = spec
            .parse::<SensorSpec>()
            .unwrap()
            .build(truth.resolution)
            .unwrap();
        let seen = KnownGrid::new(truth.width(), truth.height());
        Self {
            truth,
            seen,
            sensor,
            obs: Observation::new(),
            changed: Vec::new(),
        }
    }

    /// The map frame.
    pub fn frame(&self) -> MapFrame {
        MapFrame::of(&self.truth)
    }

    /// Look around from world point `(x, y)`.
    pub fn sense_at(&mut self, x: f64, y: f64) {
        let cell = self.frame().cell_from_world(x, y).expect("on the map");
        self.sensor.scan(
            &self.truth.cells,
            Pose { cell, heading: 0.0 },
            &mut self.obs,
        );
        self.changed.clear();
        self.seen.integrate(&self.obs, &mut self.changed);
    }

    /// The map message of what was seen.
    pub fn map_msg(&self) -> OccupancyGrid {
        let map = GridMap {
            cells: self.seen.known().clone(),
            resolution: self.truth.resolution,
            origin: self.truth.origin,
        };
        msg_from_map(&map, "map", Time::default())
    }

    /// World centre of `cell`.
    pub fn world(&self, cell: Cell) -> (f64, f64) {
        self.frame().world_from_cell(cell)
    }

    /// Share of the true free cells reachable from `start` (4-connected flood over free
    /// cells) that are known free.
    pub fn coverage_from(&self, start: Cell) -> f64 {
        let t = &self.truth.cells;
        let mut seen = vec![false; t.len()];
        let mut stack = vec![t.index(start)];
        seen[stack[0]] = true;
        let (mut n, mut known) = (0usize, 0usize);
        while let Some(i) = stack.pop() {
            n += 1;
            known += usize::from(self.seen.known()[i] == Occ::Free);
            for j in t.neighbours8(i) {
                if !seen[j] && t[j] == Occ::Free {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        known as f64 / n as f64
    }
}
