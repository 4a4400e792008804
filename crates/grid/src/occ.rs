//! The three known states of a cell and a map with its physical resolution.

use crate::cell::Cell;
use crate::grid::Grid;

/// What is known of a cell: Unknown, Free or Occupied.
///
/// In a ground-truth map, `Unknown` is space outside the mapped world (grey in a ROS
/// map); sensors treat it as opaque and robots never enter it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
#[repr(u8)]
pub enum Occ {
    /// Not observed (in a belief) or outside the world (in a ground truth).
    #[default]
    Unknown = 0,
    /// Known to be empty space.
    Free = 1,
    /// Known to hold an obstacle.
    Occupied = 2,
}

impl Occ {
    /// Whether the state is `Free`.
    #[inline]
    pub fn is_free(self) -> bool {
        self == Occ::Free
    }

    /// Whether the state is `Occupied`.
    #[inline]
    pub fn is_occupied(self) -> bool {
        self == Occ::Occupied
    }

    /// Whether the state is `Unknown`.
    #[inline]
    pub fn is_unknown(self) -> bool {
        self == Occ::Unknown
    }
}

/// An occupancy map: a grid of `Occ` with its resolution (metres per cell) and the world
/// pose `[x, y, yaw]` of its lower-left corner (ROS map_server's `origin`).
#[derive(Clone, Debug, PartialEq)]
pub struct GridMap {
    /// The cells; row 0 is the top row of the image.
    pub cells: Grid<Occ>,
    /// Side of a square cell in metres.
    pub resolution: f64,
    /// World pose `[x, y, yaw]` of the lower-left corner of the map (ROS convention).
    pub origin: [f64; 3],
}

impl GridMap {
    /// A map over `cells` at `resolution` m/cell with origin `[0, 0, 0]`.
    pub fn new(cells: Grid<Occ>, resolution: f64) -> Self {
        Self {
            cells,
            resolution,
            origin: [0.0, 0.0, 0.0],
        }
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.cells.width()
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.cells.height()
    }

    /// The state of `cell`; cells outside the grid are `Unknown`.
    pub fn state(&self, cell: Cell) -> Occ {
        self.cells.try_get(cell).copied().unwrap_or(Occ::Unknown)
    }

    /// Counts of `(free, occupied, unknown)` cells.
    pub fn counts(&self) -> (usize, usize, usize) {
        let mut n = [0usize; 3];
        for &c in self.cells.data() {
            n[c as usize] += 1;
        }
        (
            n[Occ::Free as usize],
            n[Occ::Occupied as usize],
            n[Occ::Unknown as usize],
        )
    }
}
