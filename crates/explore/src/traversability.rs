//! Traversability with a robot clearance (Holz et al. 2010's `d_max`), kept incrementally.
//!
//! A cell is *traversable* iff it is known Free and no known Occupied cell lies within the
//! robot's clearance of it: cell `c` is blocked iff some known Occupied `o` has centre distance
//! `|c − o| ≤ clearance` (so clearance 0 blocks only the occupied cells themselves). Unknown
//! cells are never traversable.
//!
//! [`Traversability`] keeps, for every cell, the number of known Occupied cells within the
//! clearance disk around it. When a cell becomes or stops being Occupied, the counts of the
//! cells in its disk change by one, so an update costs O(changed cells × disk size) for the
//! cells whose occupancy changed and O(1) for the others — independent of the map size.

use grid::{Grid, Occ};

/// Per-cell counts of known Occupied cells within the clearance disk, maintained incrementally.
#[derive(Clone, Debug)]
pub struct Traversability {
    width: usize,
    height: usize,
    clearance: f64,
    /// Offsets `(dx, dy)` with `√(dx² + dy²) ≤ clearance` (clipped to the grid size).
    disk: Vec<(i32, i32)>,
    /// Number of counted Occupied cells whose disk covers the cell.
    count: Vec<u32>,
    /// Whether the cell is currently counted as Occupied.
    counted: Vec<bool>,
}

impl Traversability {
    /// Nothing counted yet for a `width × height` map and a clearance in cells (negative or NaN
    /// clearances act as 0 for occupied cells themselves, which are never traversable anyway).
    pub fn new(width: usize, height: usize, clearance_cells: f64) -> Self {
        let n = width * height;
        Self {
            width,
            height,
            clearance: clearance_cells,
            disk: disk_offsets(clearance_cells, width.max(height)),
            count: vec![0; n],
            counted: vec![false; n],
        }
    }

    /// Account for cells whose class changed (flat indices), given the belief AFTER the change;
    /// pushes every cell whose traversability may have changed to `touched` (it keeps its own
    /// record of which cells it has counted as occupied, so a cell that stops being Occupied is
    /// handled too). Indices outside the grid are ignored; duplicates are harmless.
    pub fn update(&mut self, known: &Grid<Occ>, changed: &[u32], touched: &mut Vec<u32>) {
        let n = self.count.len();
        for &c in changed {
            let i = c as usize;
            if i >= n || i >= known.len() {
                continue;
            }
            // its own class changed: Free-ness may have changed
            touched.push(c);
            let occ = known[i].is_occupied();
            if occ == self.counted[i] {
                continue;
            }
            self.counted[i] = occ;
            let (x, y) = ((i % self.width) as i32, (i / self.width) as i32);
            let (w, h) = (self.width as i32, self.height as i32);
            for &(dx, dy) in &self.disk {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx >= w || ny >= h {
                    continue;
                }
                let j = ny as usize * self.width + nx as usize;
                if occ {
                    self.count[j] += 1;
                    if self.count[j] == 1 {
                        touched.push(j as u32);
                    }
                } else {
                    self.count[j] -= 1;
                    if self.count[j] == 0 {
                        touched.push(j as u32);
                    }
                }
            }
        }
    }

    /// Whether cell `i` is traversable: known Free and no known Occupied cell within clearance.
    #[inline]
    pub fn is_traversable(&self, known: &Grid<Occ>, i: usize) -> bool {
        known.data().get(i).is_some_and(|o| o.is_free()) && self.count.get(i) == Some(&0)
    }

    /// Whether some counted Occupied cell lies within the clearance of cell `i`.
    #[inline]
    pub fn is_blocked(&self, i: usize) -> bool {
        self.count.get(i).is_some_and(|&c| c > 0)
    }

    /// The robot's clearance in cells, as given to [`Traversability::new`].
    pub fn clearance_cells(&self) -> f64 {
        self.clearance
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The disk offsets `(dx, dy)` counted around each occupied cell.
    pub fn disk(&self) -> &[(i32, i32)] {
        &self.disk
    }
}

/// Offsets with centre distance `≤ clearance`, clipped to `|dx|, |dy| < max_side`.
fn disk_offsets(clearance: f64, max_side: usize) -> Vec<(i32, i32)> {
    if clearance.is_nan() || clearance < 0.0 || max_side == 0 {
        // an occupied cell still blocks itself (it is not Free anyway)
        return vec![(0, 0)];
    }
    let r = clearance.floor().min((max_side - 1) as f64) as i32;
    let mut out = Vec::new();
    for dy in -r..=r {
        for dx in -r..=r {
            let d = f64::from(dx * dx + dy * dy).sqrt();
            if d <= clearance {
                out.push((dx, dy));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_sizes() {
        assert_eq!(disk_offsets(0.0, 10).len(), 1);
        assert_eq!(disk_offsets(1.0, 10).len(), 5);
        assert_eq!(disk_offsets(1.5, 10).len(), 9);
        assert_eq!(disk_offsets(2.0, 10).len(), 13);
        assert_eq!(disk_offsets(2.5, 10).len(), 21);
        assert_eq!(disk_offsets(-1.0, 10).len(), 1);
        assert_eq!(disk_offsets(f64::NAN, 10).len(), 1);
        assert_eq!(disk_offsets(1e12, 2).len(), 9);
    }

    #[test]
    fn worked_example() {
        // 5x1 corridor: F F O F F with clearance 1 blocks x = 1..=3
        let known = Grid::from_vec(
            5,
            1,
            vec![Occ::Free, Occ::Free, Occ::Occupied, Occ::Free, Occ::Free],
        )
        .unwrap();
        let mut t = Traversability::new(5, 1, 1.0);
        let mut touched = Vec::new();
        t.update(&known, &[0, 1, 2, 3, 4], &mut touched);
        let tr: Vec<bool> = (0..5).map(|i| t.is_traversable(&known, i)).collect();
        assert_eq!(tr, [true, false, false, false, true]);
        // the obstacle turns free again
        let mut known = known;
        known[2] = Occ::Free;
        touched.clear();
        t.update(&known, &[2], &mut touched);
        assert!((0..5).all(|i| t.is_traversable(&known, i)));
        touched.sort_unstable();
        touched.dedup();
        assert_eq!(touched, [1, 2, 3]);
    }
}
