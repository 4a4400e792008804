//! Shared fixture of the candidate and assigner property tests: a small belief with its
//! upkeep, planner and decision context.
#![allow(dead_code, unused_imports)]

use explore::FrontierUpkeep;
use explore::Reachability;
use explore::assign::AssignerKind;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{DecisionCtx, Goal, GoalLists, Memory, Planner};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::{KnownGrid, LosSensor};

pub struct Fixture {
    pub known: Grid<Occ>,
    pub upkeep: FrontierUpkeep,
    pub planner: Planner,
    pub lists: GoalLists,
    pub rng: Pcg64Mcg,
    pub belief: KnownGrid,
    pub sensor: LosSensor,
    pub memory: Memory,
    pub robots: Vec<u32>,
    pub deciding: Vec<bool>,
    pub goals: Vec<Option<u32>>,
    pub range: f64,
    /// Metres per cell given to the decision (0.2 unless a test sets it).
    pub resolution: f64,
}

impl Fixture {
    pub fn new(known: Grid<Occ>, robots: Vec<u32>, range: f64, seed: u64) -> Self {
        let (w, h) = (known.width(), known.height());
        let mut upkeep = FrontierUpkeep::new(w, h, 0.0);
        upkeep.rebuild(&known);
        let m = robots.len();
        Self {
            planner: Planner::new(w, h, m),
            lists: GoalLists::new(w * h),
            rng: Pcg64Mcg::seed_from_u64(seed),
            belief: KnownGrid::new(w, h),
            sensor: LosSensor::new(range).expect("valid range"),
            memory: Memory::default(),
            deciding: vec![true; m],
            goals: vec![None; m],
            robots,
            range,
            resolution: 0.2,
            known,
            upkeep,
        }
    }

    pub fn ctx(&mut self) -> DecisionCtx<'_> {
        self.planner.invalidate();
        DecisionCtx {
            known: &self.known,
            upkeep: &mut self.upkeep,
            planner: &mut self.planner,
            robots: &self.robots,
            deciding: &self.deciding,
            goals: &self.goals,
            lists: &self.lists,
            resolution: self.resolution,
            sensor_range_cells: self.range,
            rng: &mut self.rng,
            belief: &self.belief,
            sensor: &self.sensor,
            memory: &mut self.memory,
        }
    }
}

/// A random known map: obstacles, a band of unknown on the right, unknown specks.
pub fn random_known(w: usize, h: usize, bits: &[u8], cut: usize) -> Grid<Occ> {
    let mut g = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let (x, b) = (i % w, bits[i % bits.len()]);
        g[i] = if x >= cut || b < 5 {
            Occ::Unknown
        } else if b < 22 {
            Occ::Occupied
        } else {
            Occ::Free
        };
    }
    g
}

/// [`random_known`] with its frontier upkeep (no clearance) rebuilt from it.
pub fn random_upkept(w: usize, h: usize, bits: &[u8], cut: usize) -> (Grid<Occ>, FrontierUpkeep) {
    let known = random_known(w, h, bits, cut);
    let mut up = FrontierUpkeep::new(w, h, 0.0);
    up.rebuild(&known);
    (known, up)
}

/// A random belief of `w × h` cells ([`random_upkept`]) and `m` robots spread over its
/// largest traversable component (`None` if it has none).
pub fn random_team(
    w: usize,
    h: usize,
    bits: &[u8],
    cut: usize,
    m: usize,
) -> Option<(Grid<Occ>, FrontierUpkeep, Vec<u32>)> {
    let (known, up) = random_upkept(w, h, bits, cut);
    let start = largest_component_cell(&known, &up)?;
    let mut reach = Reachability::new(w, h);
    reach.compute(start, |i| up.is_traversable(&known, i));
    let settled = reach.settled();
    let robots = (0..m)
        .map(|k| settled[(k * 7919) % settled.len()])
        .collect();
    Some((known, up, robots))
}

/// The lowest cell of the largest traversable component.
pub fn largest_component_cell(known: &Grid<Occ>, up: &FrontierUpkeep) -> Option<usize> {
    let (w, h) = (known.width(), known.height());
    let mut seen = vec![false; w * h];
    let mut best: Option<(usize, usize)> = None;
    let mut r = Reachability::new(w, h);
    for i in 0..w * h {
        if seen[i] || !up.is_traversable(known, i) {
            continue;
        }
        r.compute(i, |j| up.is_traversable(known, j));
        for &c in r.settled() {
            seen[c as usize] = true;
        }
        let size = r.settled().len();
        if best.is_none_or(|(s, _)| size > s) {
            best = Some((size, i));
        }
    }
    best.map(|(_, i)| i)
}
