//! The dungeon maps of learned-exploration work (Chen et al. 2019, "Self-learning
//! exploration and mapping for mobile robots via deep reinforcement learning", whose
//! simulator ships them as PNG floor plans): a grey image whose pixels brighter than 150
//! (of 255) are free and the others obstacles, with the robot's start marked by a blob of
//! pixels of value 208 (free). Their simulator starts the robot at the 128th marked pixel
//! in row-major order; so does this reader, or at the middle one of a smaller blob.

use std::path::Path;

use super::error::{MapError, MapErrorKind};
use super::png::decode_png;
use super::{
    LoadOptions, SizeCheck, add_border, check_file_memory, check_size, load_check, read_bytes,
};
use crate::cell::Cell;
use crate::grid::Grid;
use crate::occ::{GridMap, Occ};

/// The pixel value that marks the start.
pub const START_VALUE: u32 = 208;
/// Pixels brighter than this (of 255) are free.
pub const FREE_ABOVE: u32 = 150;
/// Which marked pixel (0-based, row-major) is the start, when there are that many.
pub const START_INDEX: usize = 127;

/// A dungeon map and the start cell its marker gives.
#[derive(Clone, Debug)]
pub struct DungeonMap {
    /// The map (resolution as given; origin at 0, 0, or one cell down and left of it with a
    /// border).
    pub map: GridMap,
    /// The marked start cell.
    pub start: Cell,
}

/// Read a dungeon PNG (`name` is the file named in errors) at `resolution` metres per cell.
pub fn parse_dungeon(bytes: &[u8], name: &Path, resolution: f64) -> Result<DungeonMap, MapError> {
    parse_dungeon_checked(bytes, name, resolution, &check_size)
}

/// Read the dungeon PNG at `path` at `resolution` metres per cell, refusing before decoding
/// a file or a picture that would need more than `opts.memory` (the file, the decoded
/// pixels and the map, bordered too). `opts.border` adds a wall around the map, as around a
/// bare bitmap ([`add_border`]), and the start moves with the cells; `opts.resolution`
/// does not apply.
pub fn load_dungeon(
    path: &Path,
    resolution: f64,
    opts: &LoadOptions,
) -> Result<DungeonMap, MapError> {
    check_file_memory(path, opts.memory)?;
    let bytes = read_bytes(path)?;
    let opts = LoadOptions {
        memory: opts.memory,
        border: opts.border,
        resolution: None,
    };
    let fits = load_check(
        (resolution, resolution),
        &opts,
        bytes.len() as u64,
        super::PNG_BYTES_PER_PIXEL + super::CELL_BYTES,
        "dungeon PNG",
    );
    let d = parse_dungeon_checked(&bytes, path, resolution, &fits)?;
    if !opts.border {
        return Ok(d);
    }
    Ok(DungeonMap {
        map: add_border(&d.map),
        start: Cell::new(d.start.x + 1, d.start.y + 1),
    })
}

/// Read a dungeon PNG once `fits(width, height, name)` accepts the size in its header.
fn parse_dungeon_checked(
    bytes: &[u8],
    name: &Path,
    resolution: f64,
    fits: &SizeCheck,
) -> Result<DungeonMap, MapError> {
    let raster = decode_png(bytes, name, fits)?;
    let (w, h) = (raster.width, raster.height);
    // Brightness on a 0..=255 scale (grey images read exactly).
    let grey = |v: u32| {
        ((u64::from(v) * 255 + u64::from(raster.maxval) / 2) / u64::from(raster.maxval.max(1)))
            as u32
    };
    // The marked pixels are counted, then the start is found by a second walk: a list of
    // them took 8 bytes a pixel of a picture that is all marker.
    let mut marked = 0usize;
    let data: Vec<Occ> = raster
        .values
        .iter()
        .map(|&v| {
            let g = grey(v);
            if g == START_VALUE {
                marked += 1;
            }
            if g > FREE_ABOVE {
                Occ::Free
            } else {
                Occ::Occupied
            }
        })
        .collect();
    if marked == 0 {
        return Err(MapError::new(
            name,
            MapErrorKind::BadField {
                field: "start marker",
                expected: format!("pixels of value {START_VALUE} marking the robot's start"),
                found: "none".into(),
            },
        ));
    }
    let k = if marked > START_INDEX {
        START_INDEX
    } else {
        marked / 2
    };
    let at = raster
        .values
        .iter()
        .enumerate()
        .filter(|&(_, &v)| grey(v) == START_VALUE)
        .nth(k)
        .map(|(i, _)| i)
        .expect("k is less than the marked pixels' count");
    let cells = Grid::from_vec(w, h, data).expect("raster size checked");
    let start = cells.cell(at);
    Ok(DungeonMap {
        map: GridMap::new(cells, resolution),
        start,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(w: u32, h: u32, pixels: &[u8]) -> Vec<u8> {
        crate::io::png::encode_grey(pixels, w, h).expect("encode")
    }

    #[test]
    fn classes_and_start() {
        // 4 x 3: a wall column, free greys, a two-pixel start blob.
        let pixels = [0, 255, 151, 208, 10, 150, 208, 255, 0, 255, 255, 255];
        let d = parse_dungeon(&png(4, 3, &pixels), Path::new("d.png"), 0.1).expect("reads");
        let g = &d.map.cells;
        assert_eq!(g[0], Occ::Occupied);
        assert_eq!(g[1], Occ::Free);
        assert_eq!(g[2], Occ::Free, "151 > 150 is free");
        assert_eq!(g[5], Occ::Occupied, "150 is not");
        assert_eq!(g[3], Occ::Free, "the marker is free");
        // Two marked pixels (3 and 6): the middle one of a small blob is the second.
        assert_eq!(d.start, g.cell(6));
        assert_eq!(d.map.resolution, 0.1);
    }

    #[test]
    fn the_128th_marked_pixel_of_a_large_blob() {
        let (w, h) = (20u32, 10u32);
        let mut pixels = vec![255u8; (w * h) as usize];
        for p in pixels.iter_mut().skip(5).take(150) {
            *p = 208;
        }
        let d = parse_dungeon(&png(w, h, &pixels), Path::new("d.png"), 1.0).expect("reads");
        assert_eq!(d.start, d.map.cells.cell(5 + 127));
    }

    #[test]
    fn no_marker_is_an_error_naming_the_file() {
        let err = parse_dungeon(&png(2, 2, &[255; 4]), Path::new("maps/d.png"), 1.0)
            .expect_err("no start");
        let msg = err.to_string();
        assert!(msg.contains("maps/d.png") && msg.contains("208"), "{msg}");
    }
}
