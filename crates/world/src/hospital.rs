//! `hospital`: many small rooms off long corridors, like Stage's "hospital" world used by
//! Holz et al. (2010).
//!
//! Built by the [`floorplan`](crate::floorplan) generator with hospital proportions: long
//! corridors 2–2.5 m wide about every 12 m lined on both sides by small rooms 2.8–4.2 m wide,
//! each with its own door to the corridor (no doors between rooms), an occasional larger
//! ward, and a cross corridor about every 18 m.

use grid::{Grid, Occ};

use crate::floorplan::{FloorParams, floorplan};
use crate::rng::Draws;

/// Hospital proportions for the floor-plan generator.
pub const HOSPITAL: FloorParams = FloorParams {
    corridor_w: (2.0, 2.5),
    strip_pitch: 12.0,
    cross_pitch: 18.0,
    room_w: (2.8, 4.2),
    depth_max: 6.0,
    big_room_p: 0.05,
    extra_door_p: 0.0,
};

/// Generate a hospital of `width_m × height_m` metres at `res` m/cell: cells and region ids.
pub fn hospital(width_m: f64, height_m: f64, res: f64, rng: &mut Draws) -> (Grid<Occ>, Grid<u32>) {
    floorplan(width_m, height_m, res, &HOSPITAL, rng)
}
