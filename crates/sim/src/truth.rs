//! What the ground truth says about a run: where a robot may stand, where it starts, and
//! which cells it could ever reach (the denominator of coverage).

use grid::components::{Connectivity, FloodFill, label};
use grid::edt::edt_squared;
use grid::{Cell, Grid, Occ};
use rand::RngExt;

use crate::config::SimError;

/// Ground-truth traversability: free and at least `clearance_cells` from every non-free
/// cell, centre to centre (Holz et al.'s `d_max`: a cell closer than it is neglected;
/// outside-the-world cells count as obstacles, as sensors report them). The belief's
/// [`explore::traversability`] applies the same rule to known obstacles.
pub fn traversable(truth: &Grid<Occ>, clearance_cells: f64) -> Vec<bool> {
    if clearance_cells <= 0.0 {
        // A free cell is at least one cell from every other: no distances needed.
        return truth.data().iter().map(|&c| c == Occ::Free).collect();
    }
    let d2 = edt_squared(truth.width(), truth.height(), |i| truth[i] != Occ::Free);
    // Squared, as whole as the clearance (√2 cells keeps the diagonal neighbours).
    let c2 = grid::units::snap(clearance_cells * clearance_cells);
    (0..truth.len())
        .map(|i| truth[i] == Occ::Free && d2[i] >= c2)
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

/// The components of the traversable cells `trav` (8-connected, no corner squeezing):
/// labels `1..=count` and `count`, labelled once for [`random_start`] and
/// [`reachable_from`].
pub fn components(truth: &Grid<Occ>, trav: &[bool]) -> (Grid<u32>, u32) {
    label(
        truth.width(),
        truth.height(),
        |i| trav[i],
        Connectivity::Motion,
    )
}

/// The cells reachable from `start` (its component in `labels`, see [`components`]; none
/// from a cell that is not traversable).
pub fn reachable_from(labels: &Grid<u32>, start: usize) -> Vec<bool> {
    match labels.data().get(start) {
        Some(&own) if own != 0 => labels.data().iter().map(|&l| l == own).collect(),
        _ => vec![false; labels.len()],
    }
}

/// A start cell drawn uniformly (from `rng`) from the largest connected traversable region
/// (`components`: [`components`]' labels and count).
pub fn random_start(
    (labels, count): &(Grid<u32>, u32),
    rng: &mut impl rand::Rng,
    clearance_m: f64,
) -> Result<Cell, SimError> {
    let count = *count;
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
    Ok(labels.cell(i))
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
    FloodFill::new().run_first(
        truth.width(),
        truth.height(),
        start,
        |i| trav[i],
        Connectivity::Motion,
        m,
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Random maps of free, occupied and unknown cells.
    fn map() -> impl Strategy<Value = Grid<Occ>> {
        (1usize..=10, 1usize..=10).prop_flat_map(|(w, h)| {
            proptest::collection::vec(0u8..3, w * h).prop_map(move |v| {
                let mut g = Grid::new(w, h, Occ::Free);
                for (i, c) in v.into_iter().enumerate() {
                    g[i] = [Occ::Free, Occ::Occupied, Occ::Unknown][c as usize];
                }
                g
            })
        })
    }

    /// Regression: 0.3 m on 0.05 m cells was 5.999999999999999 cells, which kept the cells
    /// exactly 6 cells from a wall, while 0.25 m (5 cells exactly) blocked those 5 away: both
    /// clearances kept the same cells. A cell exactly the clearance away is kept (d_max).
    #[test]
    fn regression_clearances_at_multiples_of_the_cell_size_keep_cells_that_far() {
        // A wall, then 11 free cells.
        let mut truth = Grid::new(12, 1, Occ::Free);
        truth[0] = Occ::Occupied;
        let first_kept = |clearance_m: f64| {
            let trav = traversable(&truth, grid::units::cells(clearance_m, 0.05));
            trav.iter().position(|&t| t)
        };
        assert_eq!(first_kept(0.25), Some(5));
        assert_eq!(first_kept(0.3), Some(6));
        assert_eq!(first_kept(0.31), Some(7));
        assert_eq!(first_kept(0.05), Some(1));
    }

    proptest! {
        /// Regression test for the shortcut without distances: with no clearance the
        /// traversable cells are the free ones, as the distance test finds them.
        #[test]
        fn no_clearance_is_the_free_cells(truth in map()) {
            let d2 = edt_squared(truth.width(), truth.height(), |i| truth[i] != Occ::Free);
            let want: Vec<bool> = (0..truth.len()).map(|i| truth[i] == Occ::Free && d2[i] > 0.0).collect();
            prop_assert_eq!(traversable(&truth, 0.0), want);
        }

        /// The ground truth's clearance rule is the belief's ([`explore::traversability`]):
        /// on a map of free and occupied cells both keep the same cells, for clearances at
        /// whole numbers of cells, at √2 and between them.
        #[test]
        fn truth_and_belief_keep_the_same_cells(truth in map(), ci in 0usize..9) {
            let clearance = [0.0, 0.5, 1.0, std::f64::consts::SQRT_2, 1.5, 2.0, 2.5, 3.0,
                grid::units::cells(0.15, 0.05)][ci];
            let mut known = truth.clone();
            for i in 0..known.len() {
                if known[i] == Occ::Unknown {
                    known[i] = Occ::Free;
                }
            }
            let all: Vec<u32> = (0..known.len() as u32).collect();
            let mut belief = explore::traversability::Traversability::new(known.width(), known.height(), clearance);
            belief.update(&known, &all, &mut Vec::new());
            let want: Vec<bool> = (0..known.len()).map(|i| belief.is_traversable(&known, i)).collect();
            prop_assert_eq!(traversable(&known, clearance), want, "clearance {}", clearance);
        }

        /// The reachable cells are the start's motion component (or none from a cell that
        /// is not traversable), as a flood from the start finds them.
        #[test]
        fn reachable_cells_are_the_flood_from_the_start(truth in map(), at in 0usize..100) {
            let trav = traversable(&truth, 0.0);
            let start = at % truth.len();
            let mut cells = Vec::new();
            FloodFill::new().run(truth.width(), truth.height(), start, |i| trav[i], Connectivity::Motion, &mut cells);
            let mut want = vec![false; truth.len()];
            for c in cells {
                want[c] = true;
            }
            prop_assert_eq!(reachable_from(&components(&truth, &trav).0, start), want);
        }
    }
}
