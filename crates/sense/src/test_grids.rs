//! Random grids for the sensors' property tests.

use grid::{Grid, Occ};

/// A `w` × `h` grid of free cells in which about `density` % of the cells, chosen by the
/// bytes `bits` (repeated), are Occupied or, one in three, ground-truth Unknown.
pub(crate) fn grid_from(w: usize, h: usize, bits: &[u8], density: u8) -> Grid<Occ> {
    let mut g = Grid::new(w, h, Occ::Free);
    for (i, &b) in bits.iter().cycle().take(w * h).enumerate() {
        let v = b % 100;
        if v < density {
            g.data_mut()[i] = if v % 3 == 0 {
                Occ::Unknown
            } else {
                Occ::Occupied
            };
        }
    }
    g
}
