//! Shared bench fixtures: a seeded random ground truth and a half-explored belief.

#![allow(dead_code)]

use explore::FrontierUpkeep;
use grid::{Grid, Occ};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Robot clearance used by the benches, in cells.
pub const CLEARANCE: f64 = 1.5;

/// An `n × n` world: scattered obstacles (3 %), a border wall and a wall every 250 columns with
/// doors every 50 rows.
pub fn truth(n: usize) -> Grid<Occ> {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    let mut g = Grid::new(n, n, Occ::Free);
    for i in 0..n * n {
        let c = g.cell(i);
        let (x, y) = (c.x as usize, c.y as usize);
        let border = x == 0 || y == 0 || x == n - 1 || y == n - 1;
        let wall = x % 250 == 125 && y % 50 > 4;
        if border || wall || rng.random_bool(0.03) {
            g[i] = Occ::Occupied;
        }
    }
    g
}

/// The belief with the left half (`x < n / 2`) known, and its frontier upkeep.
pub fn half_explored(truth: &Grid<Occ>) -> (Grid<Occ>, FrontierUpkeep) {
    let n = truth.width();
    let mut known = Grid::new(n, truth.height(), Occ::Unknown);
    for i in 0..truth.len() {
        if (i % n) < n / 2 {
            known[i] = truth[i];
        }
    }
    let mut up = FrontierUpkeep::new(n, truth.height(), CLEARANCE);
    up.rebuild(&known);
    (known, up)
}

/// Flat indices of the cells of the disk of radius `r` around `(cx, cy)` (clipped to the grid).
pub fn disk(n: usize, cx: i64, cy: i64, r: i64) -> Vec<u32> {
    let mut out = Vec::new();
    for y in (cy - r).max(0)..=(cy + r).min(n as i64 - 1) {
        for x in (cx - r).max(0)..=(cx + r).min(n as i64 - 1) {
            if (x - cx).pow(2) + (y - cy).pow(2) <= r * r {
                out.push((y as usize * n + x as usize) as u32);
            }
        }
    }
    out
}
