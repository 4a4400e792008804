//! A robot whose sensor looks one way (a lidar with a narrow field of view) turns on
//! arrival towards the unknown cells beside its goal and looks at each: a frontier it
//! reached is not left with unknown neighbours it never faced.

use explore::strategy::Strategy;
use grid::{Cell, Grid, GridMap, Occ};
use sim::{EndReason, RunConfig};

/// A 30 x 16 room with an inner wall along row 5, open in a door at columns 20-23.
fn room_with_a_door() -> GridMap {
    let (w, h) = (30, 16);
    let mut cells = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let c = cells.cell(i);
        let (x, y) = (c.x as usize, c.y as usize);
        if x == 0 || y == 0 || x == w - 1 || y == h - 1 || (y == 5 && !(20..=23).contains(&x)) {
            cells[i] = Occ::Occupied;
        }
    }
    GridMap::new(cells, 1.0)
}

/// Regression: on arrival the robot faced the mean direction of its unknown neighbours;
/// with unknown cells on both sides (the wall above a corridor of the room, the room
/// below) they cancelled, it faced along the corridor, saw nothing, and the goal went on
/// the visited list: the door was never seen, and the run ended "no reachable frontier"
/// at 68 % coverage (16 % on a generated office at 0.1 m).
#[test]
fn regression_a_narrow_view_faces_each_unknown_side() {
    let map = room_with_a_door();
    for preset in ["cf", "cf-rr"] {
        let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
        cfg.sensor = "lidar:r=2c,fov=10,res=1".parse().expect("sensor");
        cfg.starts = vec![Cell::new(5, 12)];
        let result = sim::run(&map, &cfg).expect("run");
        assert_eq!(
            result.reason,
            EndReason::Complete,
            "{preset}: {}",
            result.coverage
        );
    }
}
