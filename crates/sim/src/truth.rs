//! What the ground truth says about a run: where a robot may stand, where it starts, and
//! which cells it could ever reach (the denominator of coverage).

use grid::components::{Connectivity, flood, label};
use grid::edt::edt_squared;
use grid::{Cell, Grid, Occ};
use rand::RngExt;

use crate::config::SimError;

/// Ground-truth traversability: free and farther than `clearance_cells` from every
/// non-free cell (outside-the-world cells count as obstacles, as sensors report them).
pub fn traversable(truth: &Grid<Occ>, clearance_cells: f64) -> Vec<bool> {
    let d2 = edt_squared(truth.width(), truth.height(), |i| truth[i] != Occ::Free);
    let c2 = clearance_cells * clearance_cells;
    (0..truth.len())
        .map(|i| truth[i] == Occ::Free && d2[i] > c2)
        .collect()
}

/// The plane `truth` with every cell of `clutter` (obstacles off the sensor plane, same
/// size) made occupied: where the robot's body can be.
pub fn with_clutter(truth: &Grid<Occ>, clutter: &Grid<bool>) -> Grid<Occ> {
    let mut out = truth.clone();
    for i in 0..out.len() {
        if clutter[i] {
            out[i] = Occ::Occupied;
        }
    }
    out
}

/// The cells reachable from `start` over `trav` (8-connected, no corner squeezing).
pub fn reachable_from(truth: &Grid<Occ>, trav: &[bool], start: usize) -> Vec<bool> {
    let mut cells = Vec::new();
    flood(
        truth.width(),
        truth.height(),
        start,
        |i| trav[i],
        Connectivity::Motion,
        &mut cells,
    );
    let mut out = vec![false; truth.len()];
    for c in cells {
        out[c] = true;
    }
    out
}

/// A start cell drawn uniformly (from `rng`) from the largest connected traversable region.
pub fn random_start(
    truth: &Grid<Occ>,
    trav: &[bool],
    rng: &mut impl rand::Rng,
    clearance_m: f64,
) -> Result<Cell, SimError> {
    let (labels, count) = label(
        truth.width(),
        truth.height(),
        |i| trav[i],
        Connectivity::Motion,
    );
    if count == 0 {
        return Err(SimError::NoFreeSpace { clearance_m });
    }
    let mut sizes = vec![0usize; count as usize + 1];
    for &l in labels.data() {
        sizes[l as usize] += 1;
    }
    sizes[0] = 0;
    // Largest component; ties go to the lowest label (first in row-major order).
    let (best, &n) = sizes
        .iter()
        .enumerate()
        .rev()
        .max_by_key(|&(_, s)| *s)
        .expect("count > 0");
    let k = rng.random_range(0..n);
    let i = labels
        .data()
        .iter()
        .enumerate()
        .filter(|&(_, &l)| l as usize == best)
        .nth(k)
        .map(|(i, _)| i)
        .expect("k < n");
    Ok(truth.cell(i))
}

/// `m` distinct traversable start cells: `first`, then the nearest others in
/// breadth-first order over the traversable cells around it.
pub fn team_starts(
    truth: &Grid<Occ>,
    trav: &[bool],
    first: Cell,
    m: usize,
) -> Result<Vec<Cell>, SimError> {
    let start = truth.index(first);
    let mut cells = Vec::new();
    flood(
        truth.width(),
        truth.height(),
        start,
        |i| trav[i],
        Connectivity::Motion,
        &mut cells,
    );
    if cells.len() < m {
        return Err(SimError::BadStart {
            cell: first,
            why: format!(
                "only {} traversable cells are connected to it, {m} robots need one each",
                cells.len()
            ),
        });
    }
    Ok(cells[..m].iter().map(|&i| truth.cell(i)).collect())
}

/// Check a user-given start: inside the map and traversable.
pub fn check_start(truth: &Grid<Occ>, trav: &[bool], cell: Cell) -> Result<(), SimError> {
    let Some(i) = truth.checked_index(cell) else {
        return Err(SimError::BadStart {
            cell,
            why: format!("outside the {}x{} map", truth.width(), truth.height()),
        });
    };
    if !trav[i] {
        let what = match truth[i] {
            Occ::Free => "free but closer to an obstacle than the robot's clearance",
            Occ::Occupied => "occupied",
            Occ::Unknown => "outside the mapped world (unknown)",
        };
        return Err(SimError::BadStart {
            cell,
            why: format!("the cell is {what}"),
        });
    }
    Ok(())
}
