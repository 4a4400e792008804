//! Helpers shared by the sensors' property tests.

use grid::{Cell, Grid, Occ};

/// The cell `(x, y)` (drawn as at least 0) folded into `grid`: a cell of the grid stays as
/// drawn, so a committed regression seed replays the same case, and one beyond it wraps
/// into it instead of being rejected (rejected draws made proptest abort at high case
/// counts).
pub fn origin_in(grid: &Grid<Occ>, x: i32, y: i32) -> Cell {
    Cell::new(x % grid.width() as i32, y % grid.height() as i32)
}
pub mod sensed;
