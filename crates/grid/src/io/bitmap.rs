//! Bare bitmaps such as Stage floor plans: dark = obstacle, light = free, grey = unknown.
//!
//! A bare PGM or PNG has no resolution, so the user gives one. Pixels are classified with
//! ROS map_server's default thresholds (occupied 0.65, free 0.196, negate off; see
//! [`Thresholds`]). Stage bitmaps often have no outer wall: [`add_border`] adds one.

use crate::grid::Grid;
use crate::occ::{GridMap, Occ};

use super::raster::{Raster, Thresholds};

/// The cell states of a bare bitmap (ROS default thresholds; transparent → Unknown).
pub fn parse_bitmap(raster: &Raster) -> Grid<Occ> {
    Thresholds::default().classify_raster(raster)
}

/// The map grown by one Occupied cell on each side; the origin (the world position of the
/// lower-left corner) moves one cell down and left, along the map's yaw.
pub fn add_border(map: &GridMap) -> GridMap {
    let (w, h) = (map.width(), map.height());
    let mut cells = Grid::new(w + 2, h + 2, Occ::Occupied);
    for y in 0..h {
        let src = &map.cells.data()[y * w..(y + 1) * w];
        let start = (y + 1) * (w + 2) + 1;
        cells.data_mut()[start..start + w].copy_from_slice(src);
    }
    let [ox, oy, yaw] = map.origin;
    let (s, c) = yaw.sin_cos();
    let r = map.resolution;
    // The corner moves by (-r, -r) in the map's frame.
    let origin = [ox - r * c + r * s, oy - r * s - r * c, yaw];
    GridMap {
        cells,
        resolution: map.resolution,
        origin,
    }
}
