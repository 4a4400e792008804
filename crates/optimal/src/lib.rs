//! `optimal`: offline optimal exploration paths and competitive ratios, after Quattrini Li,
//! Amigoni & Basilico (2012), "Searching for Optimal Off-Line Exploration Paths in Grid
//! Environments for a Robot with Limited Visibility".
//!
//! For a known map, a start and a 360° sensor (`los` or `footprint`), [`solve`] finds the
//! shortest sequence of sensing positions whose time-discrete perceptions cover all free
//! cells (or a fraction G of them), by A* over states (robot cell, perceived set). An online
//! strategy's competitive ratio is its path length over this optimum ([`competitive_ratio`]).
//!
//! - [`problem`]: the problem, targets, visibility;
//! - [`actions`]: boundary cells, cluster representatives (with the "drop clusters < k"
//!   speed-up); `cluster_rows` computes the same representatives on bit rows, without a
//!   shortest-path search per state;
//! - [`heuristic`]: the paper's bound (with admissibility proofs per sensor) and stronger
//!   ones: for the footprint sensor the paper's order statistic over each cell's path
//!   distance to its nearest viewpoint (`viewpoint_distance`), a Held–Karp bound on a path
//!   through landmarks (`held_karp`) and the coverage-rate bound (`coverage_rate`: each
//!   unit of path uncovers at most ρ* new cells) and, for G < 1, the skip-budget bound
//!   (`skip_budget`: the map's far ends must still be approached, each less closely the
//!   more of the budget the others take); long target lists are counted a block of 64 at
//!   a time (`block_masks`);
//! - [`search`]: A*, weighted A*, limits and bounds (step costs: `step_cost`, from
//!   per-position distance fields when a shortest path lies inside the perceived space;
//!   `recent`: the last expanded states' perceived sets and reachable components, from
//!   which their descendants' are rebuilt; `room`: the caches' growth, within the memory
//!   budget);
//! - [`coarse`]: solving on a coarsened map (the paper's cell sizes 1, 2, 4), and a first
//!   incumbent from a coarser map for searches that will stop with bounds.
//!
//! The search itself, the bounds and the bit-row, block-count and erosion routines are
//! written here: no crate does A* over exploration states, and the rest is specific to it.
//!
//! ```
//! use grid::{Cell, Grid, Occ};
//! use optimal::{Config, Problem, SensorModel, solve};
//! let map = Grid::new(12, 3, Occ::Free);
//! let p = Problem::new(&map, Cell::new(0, 1), SensorModel::Los(3.0)).unwrap();
//! let out = solve(&p, &Config::default()).unwrap();
//! assert_eq!(out.status, optimal::Status::Optimal);
//! assert!(out.upper_bound > 0.0);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod actions;
pub(crate) mod block_masks;
pub(crate) mod cluster_rows;
pub mod coarse;
pub(crate) mod coverage_rate;
pub mod error;
pub(crate) mod held_karp;
pub mod heuristic;
pub mod problem;
pub(crate) mod recent;
pub(crate) mod room;
pub mod search;
pub(crate) mod skip_budget;
pub(crate) mod step_cost;
pub(crate) mod viewpoint_distance;

pub use actions::ActionSet;
pub use coarse::{Coarsened, coarsen_problem};
pub use error::OptimalError;
pub use heuristic::HeuristicKind;
pub use problem::{Problem, SensorModel};
pub use search::{
    Config, MAX_LANDMARKS, Outcome, Progress, SETUP_BYTES_PER_CELL, Solution, Stats, Status,
    StopReason, heuristic_value, setup_bytes, solve, solve_with, walk,
};

/// A `w` × `h` test map with a wall wherever `walls` holds 0 (maps from random bytes).
#[cfg(test)]
pub(crate) fn walled_map(w: usize, h: usize, walls: &[u8]) -> grid::Grid<grid::Occ> {
    let mut map = grid::Grid::new(w, h, grid::Occ::Free);
    for (c, &wall) in map.data_mut().iter_mut().zip(walls) {
        if wall == 0 {
            *c = grid::Occ::Occupied;
        }
    }
    map
}

/// A problem on a `w` × `h` [`walled_map`] from its `pick`-th free cell (modulo their
/// number) with `model`, and that start's flat index; `None` without a free cell.
#[cfg(test)]
pub(crate) fn walled_problem(
    w: usize,
    h: usize,
    walls: &[u8],
    pick: usize,
    model: SensorModel,
) -> Option<(Problem, usize)> {
    let map = walled_map(w, h, walls);
    let free: Vec<usize> = (0..w * h).filter(|&i| map.data()[i].is_free()).collect();
    let start = *free.get(pick % free.len().max(1))?;
    let p = Problem::new(&map, map.cell(start), model).expect("a free start");
    Some((p, start))
}

/// The marks' bitset of `p` holding the targets at the cells where `seen` is not 0, and
/// the target at flat cell `keep`.
#[cfg(test)]
pub(crate) fn perceived_marks(p: &Problem, seen: &[u8], keep: usize) -> Vec<u64> {
    let mut bits = vec![0u64; p.mark_count().div_ceil(64).max(1)];
    for (i, &s) in seen.iter().enumerate().take(p.cells().len()) {
        let t = p.target_index(i);
        if t != problem::NOT_TARGET && (s != 0 || i == keep) {
            heuristic::set(&mut bits, t);
        }
    }
    bits
}

/// Competitive ratio of an online path: `online_length / optimal_length` (same units);
/// `None` if the optimal length is not positive.
pub fn competitive_ratio(online_length: f64, optimal_length: f64) -> Option<f64> {
    (optimal_length > 0.0 && online_length.is_finite()).then(|| online_length / optimal_length)
}
