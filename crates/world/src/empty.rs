//! `empty`: an open rectangle inside its boundary wall, like Faigl & Kulich's "em"
//! environment (21 m × 24 m).

use grid::{Grid, Occ};

use crate::raster::{Scale, WALL_M, border};

/// Generate an empty room of `width × height` cells at `res` m/cell.
pub fn empty(width: usize, height: usize, res: f64) -> Grid<Occ> {
    let mut cells = Grid::new(width, height, Occ::Free);
    border(&mut cells, Scale { res }.cells_at_least_one(WALL_M));
    cells
}
