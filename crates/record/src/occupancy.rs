//! `nav_msgs/OccupancyGrid` ⇄ frontier's map, and the map frame's world ⇄ cell transforms.
//!
//! An OccupancyGrid's row 0 is at its origin, the bottom of the map as drawn; frontier's
//! row 0 is the top row (as in a PGM file), so rows flip, exactly as map_server flips a
//! PGM. Cell values follow map_server's trinary reading with its default thresholds: −1
//! (and any negative) is Unknown, values ≥ 65 are Occupied, values ≤ 25 are Free; values in
//! between are neither certain free nor occupied, so they stay Unknown (Holz et al.'s rule for
//! their reflection map: free only when p ≤ 0.25).

use grid::{Cell, Grid, GridMap, Occ};

use crate::msgs::{MapMetaData, OccupancyGrid, Pose, Quaternion};

/// Occupancy at or above which a cell is Occupied (map_server's `occupied_thresh` 0.65).
pub const OCCUPIED_MIN: i8 = 65;
/// Occupancy at or below which a cell is Free (map_server's `free_thresh` 0.25).
pub const FREE_MAX: i8 = 25;
/// The largest map accepted, in cells: grid's [`grid::io::MAX_CELLS`], so that a recorded
/// map is refused exactly when a map file of its size would be (a 0.05 m map of 819 m × 819 m).
pub const MAX_CELLS: usize = grid::io::MAX_CELLS as usize;

/// Why an OccupancyGrid message is not a usable map.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MapMsgError {
    /// Width or height is 0.
    #[error("map message: expected a non-empty map, found {width}x{height} cells")]
    Empty {
        /// Cells per row.
        width: u32,
        /// Rows.
        height: u32,
    },
    /// More cells than [`MAX_CELLS`].
    #[error("map message: expected at most {MAX_CELLS} cells, found {width}x{height}")]
    TooLarge {
        /// Cells per row.
        width: u32,
        /// Rows.
        height: u32,
    },
    /// `data` does not have width × height entries.
    #[error("map message: expected {expected} cells ({width}x{height}), found {found} in data")]
    WrongSize {
        /// Cells per row.
        width: u32,
        /// Rows.
        height: u32,
        /// width × height.
        expected: usize,
        /// data length.
        found: usize,
    },
    /// The resolution is not a positive number of at most [`grid::io::MAX_RESOLUTION_M`].
    #[error(
        "map message: expected a positive resolution of at most {max} m per cell, found {0}",
        max = grid::io::MAX_RESOLUTION_M
    )]
    BadResolution(f32),
    /// The origin has a non-finite coordinate or a non-unit orientation.
    #[error("map message: expected a finite origin with a unit quaternion, found {0}")]
    BadOrigin(String),
    /// The origin tilts the grid (a roll or pitch), which a planar map cannot be read with.
    #[error(
        "map message: expected an origin turned about the vertical axis only (a level map), \
         found orientation ({0}): the grid is tilted"
    )]
    TiltedOrigin(String),
}

/// Where a map lies in the world: size, resolution and origin, with the transforms between
/// world points (metres, in the map's frame) and frontier's cells (row 0 at the top).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapFrame {
    /// Cells per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Metres per cell.
    pub resolution: f64,
    /// World `[x, y, yaw]` of the bottom-left corner of the map.
    pub origin: [f64; 3],
}

impl MapFrame {
    /// The frame of `map`.
    pub fn of(map: &GridMap) -> Self {
        Self {
            width: map.width(),
            height: map.height(),
            resolution: map.resolution,
            origin: map.origin,
        }
    }

    /// World point of the centre of `cell`.
    pub fn world_from_cell(&self, cell: Cell) -> (f64, f64) {
        let u = (f64::from(cell.x) + 0.5) * self.resolution;
        let v = (self.height as f64 - 1.0 - f64::from(cell.y) + 0.5) * self.resolution;
        let (s, c) = self.origin[2].sin_cos();
        (
            self.origin[0] + c * u - s * v,
            self.origin[1] + s * u + c * v,
        )
    }

    /// The cell that holds world point `(x, y)`, if it is on the map.
    pub fn cell_from_world(&self, x: f64, y: f64) -> Option<Cell> {
        let (dx, dy) = (x - self.origin[0], y - self.origin[1]);
        let (s, c) = self.origin[2].sin_cos();
        let (u, v) = (c * dx + s * dy, -s * dx + c * dy);
        let (col, row_up) = ((u / self.resolution).floor(), (v / self.resolution).floor());
        if !(col >= 0.0 && row_up >= 0.0 && col < self.width as f64 && row_up < self.height as f64)
        {
            return None;
        }
        let row = self.height - 1 - row_up as usize;
        Some(Cell::new(col as i32, row as i32))
    }
}

/// The number of cells of a `width × height` map, or why it is too large.
pub(crate) fn cells_of(width: u32, height: u32) -> Result<usize, MapMsgError> {
    (width as usize)
        .checked_mul(height as usize)
        .filter(|&n| n <= MAX_CELLS)
        .ok_or(MapMsgError::TooLarge { width, height })
}

/// Check an OccupancyGrid's size, resolution and origin; returns its frame.
pub fn frame_of(msg: &OccupancyGrid) -> Result<MapFrame, MapMsgError> {
    frame_of_parts(&msg.info, msg.data.len())
}

/// [`frame_of`] for a message's metadata and the length of its `data`.
fn frame_of_parts(info: &MapMetaData, data_len: usize) -> Result<MapFrame, MapMsgError> {
    let (w, h) = (info.width, info.height);
    if w == 0 || h == 0 {
        return Err(MapMsgError::Empty {
            width: w,
            height: h,
        });
    }
    let expected = cells_of(w, h)?;
    if data_len != expected {
        return Err(MapMsgError::WrongSize {
            width: w,
            height: h,
            expected,
            found: data_len,
        });
    }
    if !grid::io::is_valid_resolution(f64::from(info.resolution)) {
        return Err(MapMsgError::BadResolution(info.resolution));
    }
    let (p, q) = (info.origin.position, info.origin.orientation);
    let norm = (q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w).sqrt();
    let unit = (norm - 1.0).abs() < 1e-3; // false for NaN too
    if ![p.x, p.y, p.z].iter().all(|v| v.is_finite()) || !unit {
        return Err(MapMsgError::BadOrigin(format!(
            "position ({}, {}, {}), orientation ({}, {}, {}, {})",
            p.x, p.y, p.z, q.x, q.y, q.z, q.w
        )));
    }
    // A yaw alone leaves x and y at 0; 1e-3 (of a unit quaternion) is a tilt of about 0.1°,
    // beyond what rounding leaves. The height, z, is the level the map lies at: dropped.
    if q.x.abs() > 1e-3 * norm || q.y.abs() > 1e-3 * norm {
        return Err(MapMsgError::TiltedOrigin(format!(
            "{}, {}, {}, {}",
            q.x, q.y, q.z, q.w
        )));
    }
    Ok(MapFrame {
        width: w as usize,
        height: h as usize,
        resolution: as_written(info.resolution),
        origin: [p.x, p.y, q.yaw()],
    })
}

/// A message's `float32` resolution as the decimal it was written from: the shortest
/// decimal that reads back as the same `f32` (0.05, not the 0.05000000074505806 that
/// `f64::from` gives). A map saved as ROS YAML says 0.05 and a recording of it says the
/// same, so the two explore alike (sensor ranges in cells, clearances, lengths).
fn as_written(resolution: f32) -> f64 {
    resolution
        .to_string()
        .parse()
        .unwrap_or(f64::from(resolution))
}

/// The class of an OccupancyGrid value.
#[inline]
pub fn class_of(v: i8) -> Occ {
    if v < 0 {
        Occ::Unknown
    } else if v >= OCCUPIED_MIN {
        Occ::Occupied
    } else if v <= FREE_MAX {
        Occ::Free
    } else {
        Occ::Unknown
    }
}

/// Write the classes of `msg`'s cells into `out` (frontier's row order), which must have the
/// frame's size; `msg` must have passed [`frame_of`].
pub fn classify_into(msg: &OccupancyGrid, frame: &MapFrame, out: &mut [Occ]) {
    classify_values_into(&msg.data, |v| v, frame, out);
}

/// Write the classes of `data` (occupancy values read by `value`, the message's row
/// order) into `out` (frontier's row order).
fn classify_values_into<T: Copy>(
    data: &[T],
    value: impl Fn(T) -> i8,
    frame: &MapFrame,
    out: &mut [Occ],
) {
    let w = frame.width;
    debug_assert_eq!(out.len(), w * frame.height);
    debug_assert_eq!(data.len(), w * frame.height);
    for (row_up, src) in data.chunks_exact(w).enumerate() {
        let row = frame.height - 1 - row_up;
        let dst = &mut out[row * w..(row + 1) * w];
        for (d, &v) in dst.iter_mut().zip(src) {
            *d = class_of(value(v));
        }
    }
}

/// The map an OccupancyGrid message holds.
pub fn map_from_msg(msg: &OccupancyGrid) -> Result<GridMap, MapMsgError> {
    map_from_values(&msg.info, &msg.data, |v| v)
}

/// [`map_from_msg`] for a message's metadata and its cells as raw CDR bytes (the values as
/// two's-complement bytes, read in place).
pub(crate) fn map_from_bytes(info: &MapMetaData, data: &[u8]) -> Result<GridMap, MapMsgError> {
    map_from_values(info, data, |v| v as i8)
}

/// The map of `info` and `data` (occupancy values read by `value`).
fn map_from_values<T: Copy>(
    info: &MapMetaData,
    data: &[T],
    value: impl Fn(T) -> i8,
) -> Result<GridMap, MapMsgError> {
    let frame = frame_of_parts(info, data.len())?;
    let mut cells = Grid::new(frame.width, frame.height, Occ::Unknown);
    classify_values_into(data, value, &frame, cells.data_mut());
    Ok(GridMap {
        cells,
        resolution: frame.resolution,
        origin: frame.origin,
    })
}

/// The OccupancyGrid message of `map` (Free 0, Occupied 100, Unknown −1) in frame `frame_id`.
pub fn msg_from_map(map: &GridMap, frame_id: &str, stamp: crate::msgs::Time) -> OccupancyGrid {
    let (w, h) = (map.width(), map.height());
    let mut data = Vec::with_capacity(w * h);
    for row_up in 0..h {
        let row = h - 1 - row_up;
        data.extend(
            map.cells.data()[row * w..(row + 1) * w]
                .iter()
                .map(|c| match c {
                    Occ::Free => 0i8,
                    Occ::Occupied => 100,
                    Occ::Unknown => -1,
                }),
        );
    }
    OccupancyGrid {
        header: crate::msgs::Header {
            stamp,
            frame_id: frame_id.to_string(),
        },
        info: MapMetaData {
            map_load_time: stamp,
            resolution: map.resolution as f32,
            width: w as u32,
            height: h as u32,
            origin: Pose {
                position: crate::msgs::Point {
                    x: map.origin[0],
                    y: map.origin[1],
                    z: 0.0,
                },
                orientation: Quaternion::from_yaw(map.origin[2]),
            },
        },
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::io::parse_ascii;
    use proptest::prelude::*;

    fn msg(w: u32, h: u32, data: Vec<i8>) -> OccupancyGrid {
        let mut m = OccupancyGrid::default();
        m.info.width = w;
        m.info.height = h;
        m.info.resolution = 0.05;
        m.data = data;
        m
    }

    #[test]
    fn rows_flip_and_values_classify_like_map_server() {
        // Bottom row (row_up 0) first: -1, 0, 25; top row: 26, 65, 100.
        let m = msg(3, 2, vec![-1, 0, 25, 26, 65, 100]);
        let map = map_from_msg(&m).unwrap();
        use Occ::*;
        assert_eq!(
            map.cells.data(),
            &[Unknown, Occupied, Occupied, Unknown, Free, Free]
        );
    }

    #[test]
    fn bad_messages_are_errors_naming_what_is_wrong() {
        assert_eq!(
            map_from_msg(&msg(0, 4, vec![])).unwrap_err(),
            MapMsgError::Empty {
                width: 0,
                height: 4
            }
        );
        let e = map_from_msg(&msg(3, 2, vec![0; 5])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "map message: expected 6 cells (3x2), found 5 in data"
        );
        let mut m = msg(1, 1, vec![0]);
        m.info.resolution = f32::NAN;
        assert!(matches!(
            map_from_msg(&m),
            Err(MapMsgError::BadResolution(_))
        ));
        m.info.resolution = -0.05;
        assert!(matches!(
            map_from_msg(&m),
            Err(MapMsgError::BadResolution(_))
        ));
        // Regression: a huge resolution was accepted and every length came out infinite.
        m.info.resolution = 1e30;
        assert!(matches!(
            map_from_msg(&m),
            Err(MapMsgError::BadResolution(_))
        ));
        m.info.resolution = 0.05;
        m.info.origin.position.x = f64::INFINITY;
        assert!(matches!(map_from_msg(&m), Err(MapMsgError::BadOrigin(_))));
        m.info.origin.position.x = 0.0;
        m.info.origin.orientation.w = 0.0;
        assert!(matches!(map_from_msg(&m), Err(MapMsgError::BadOrigin(_))));
        // Regression: a roll of 0.5 rad was read as no rotation at all (the yaw alone kept).
        let (s, c) = (0.25f64.sin(), 0.25f64.cos());
        m.info.origin.orientation.x = s;
        m.info.origin.orientation.w = c;
        assert!(matches!(
            map_from_msg(&m),
            Err(MapMsgError::TiltedOrigin(_))
        ));
        // A yaw alone, and a height, are read.
        m.info.origin.orientation.x = 0.0;
        m.info.origin.orientation.z = s;
        m.info.origin.position.z = 3.5;
        let frame = map_from_msg(&m).expect("a level map");
        assert!((frame.origin[2] - 0.5).abs() < 1e-12, "{:?}", frame.origin);
        m.info.origin.orientation = Default::default();
        m.info.origin.orientation.w = 1.0;
        m.info.origin.position.z = 0.0;
        let huge = msg(u32::MAX, u32::MAX, vec![]);
        assert!(matches!(
            map_from_msg(&huge),
            Err(MapMsgError::TooLarge { .. })
        ));
    }

    #[test]
    fn a_map_survives_the_message() {
        let mut map = parse_ascii("#####\n#..?#\n#.#.#\n#####\n", 0.1).unwrap();
        map.origin = [-1.5, 2.0, 0.3];
        let back = map_from_msg(&msg_from_map(&map, "map", Default::default())).unwrap();
        assert_eq!(back.cells, map.cells);
        assert_eq!(back.resolution, 0.1);
        assert!((back.origin[2] - 0.3).abs() < 1e-12);
    }

    /// Regression: a message's float32 resolution was read as 0.05000000074505806 for a map
    /// of 0.05 m, so a run on a recording of a map differed from the run on the map (5 %
    /// longer for a 3-robot `ha-cc` on nav2's depot: sensor ranges and clearances in cells
    /// came out a hair different). It reads as the decimal it was written from, for any
    /// resolution a ROS YAML file can hold.
    #[test]
    fn regression_a_resolution_reads_as_the_decimal_it_was_written_from() {
        for written in [0.05, 0.03, 0.1, 0.025, 0.0368, 0.2, 0.5, 1.0, 0.0123456] {
            let mut m = msg(1, 1, vec![0]);
            m.info.resolution = written as f32;
            assert_eq!(frame_of(&m).unwrap().resolution, written, "{written}");
        }
        // One that is not a short decimal stays the float32's value.
        let mut m = msg(1, 1, vec![0]);
        m.info.resolution = f32::from_bits(0.05f32.to_bits() + 1);
        let r = frame_of(&m).unwrap().resolution;
        assert_eq!(r as f32, m.info.resolution);
    }

    #[test]
    fn the_bottom_left_cell_is_at_the_origin() {
        let f = MapFrame {
            width: 4,
            height: 3,
            resolution: 0.5,
            origin: [10.0, 20.0, 0.0],
        };
        assert_eq!(f.world_from_cell(Cell::new(0, 2)), (10.25, 20.25));
        assert_eq!(f.cell_from_world(10.1, 20.1), Some(Cell::new(0, 2)));
        assert_eq!(f.cell_from_world(11.9, 21.4), Some(Cell::new(3, 0)));
        assert_eq!(f.cell_from_world(9.9, 20.1), None);
        assert_eq!(f.cell_from_world(10.1, 21.6), None);
    }

    proptest! {
        #[test]
        fn cell_world_cell_is_the_identity(
            w in 1usize..40, h in 1usize..40, x in 0usize..40, y in 0usize..40,
            ox in -50.0f64..50.0, oy in -50.0f64..50.0, yaw in -3.1f64..3.1, res in 0.01f64..1.0,
        ) {
            let f = MapFrame { width: w, height: h, resolution: res, origin: [ox, oy, yaw] };
            let c = Cell::new((x % w) as i32, (y % h) as i32);
            let (wx, wy) = f.world_from_cell(c);
            prop_assert_eq!(f.cell_from_world(wx, wy), Some(c));
        }
    }
}
