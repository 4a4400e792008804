//! `office`: corridors with rooms and doors, as in the multi-robot coordination study's
//! office environments (25 m × 20 m at 0.5 m by default).
//!
//! Built by the [`floorplan`](crate::floorplan) generator with office proportions: corridors
//! 1.5–2.5 m wide about every 11 m, rooms 3–6 m wide (now and then a larger lab or meeting
//! room), a cross corridor about every 25 m, and some doors between neighbouring rooms.

use grid::{Grid, Occ};

use crate::floorplan::{FloorParams, floorplan};
use crate::rng::Draws;

/// Office proportions for the floor-plan generator.
pub const OFFICE: FloorParams = FloorParams {
    corridor_w: (1.5, 2.5),
    strip_pitch: 11.0,
    cross_pitch: 25.0,
    room_w: (3.0, 6.0),
    depth_max: 6.5,
    big_room_p: 0.12,
    extra_door_p: 0.15,
};

/// Generate an office of `width_m × height_m` metres at `res` m/cell: cells and region ids.
pub fn office(width_m: f64, height_m: f64, res: f64, rng: &mut Draws) -> (Grid<Occ>, Grid<u32>) {
    floorplan(width_m, height_m, res, &OFFICE, rng)
}
