//! Map files in and out.
//!
//! Formats, chosen by the file's extension in [`load_map`] and [`save_map`]:
//!
//! | extension | format | resolution |
//! |---|---|---|
//! | `.yaml`, `.yml` | ROS map_server YAML + PGM/PNG image ([`ros`]) | from the YAML |
//! | `.pgm`, `.png` | bare bitmap, e.g. a Stage floor plan ([`bitmap`]) | required in [`LoadOptions`] |
//! | `.map` | MovingAI benchmark map ([`movingai`]) | default 1 m |
//! | `.json` | HouseExpo floor plan, its outline in metres ([`houseexpo`], [`load_houseexpo`]) | required in [`LoadOptions`] |
//! | `.txt` | ASCII art: `#` wall, `.` free, `?` unknown ([`ascii`]) | default 1 m |
//!
//! Every failure is a [`MapError`] naming the file and what is wrong; nothing a file
//! contains makes these functions panic, and maps of more than [`MAX_CELLS`] cells are
//! refused before anything is allocated for them. Given the memory available
//! ([`LoadOptions::memory`]), [`load_map`] also estimates from a file's size and the map's
//! size in its header what loading will take (the file, the decoded pixels and the grid
//! made of them) and refuses, before decoding, a map that would not fit.

pub mod ascii;
pub mod bitmap;
pub mod dungeon;
pub mod error;
pub mod houseexpo;
pub mod movingai;
pub mod pgm;
pub mod png;
pub mod raster;
pub mod ros;

use std::path::Path;

pub use ascii::{ascii_map, parse_ascii, to_ascii};
pub use bitmap::{add_border, parse_bitmap};
pub use dungeon::{DungeonMap, load_dungeon, parse_dungeon};
pub use error::{MEMORY, MapError, MapErrorKind};
pub use houseexpo::{HouseExpoMap, parse_houseexpo};
pub use movingai::{parse_movingai, to_movingai};
pub use pgm::{encode_pgm, parse_pgm};
pub use png::{encode_png, parse_png};
pub use raster::{Raster, Thresholds};
pub use ros::{
    MAX_YAML_BYTES, RosMapMeta, RosMode, parse_ros_yaml, parse_ros_yaml_meta, ros_image_of,
    to_ros_yaml,
};

use crate::grid::Grid;
use crate::memory::Available;
use crate::occ::{GridMap, Occ};
use crate::resample;

/// The coarsest cell a map may have, in metres: a kilometre. Lengths are cells times the
/// resolution, so a resolution near the largest float made every path length infinite.
pub const MAX_RESOLUTION_M: f64 = 1000.0;

/// The folder a file at `path` would be written into, if it does not exist (a bare file
/// name goes into the working folder, which does). The one check of every writer of files
/// (maps, study stores, the CLI's outputs), made before any work.
pub fn missing_folder(path: &Path) -> Option<&Path> {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty() && !d.is_dir())
}

/// Whether `a` and `b` name the same existing file, however they are spelled (relative or
/// absolute, with `..`, through symbolic or hard links). A path that does not exist is no
/// existing file, so it is the same as none. The one test of every writer that must not
/// write over what it reads (study stores, the CLI's outputs).
pub fn same_existing_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        ma.dev() == mb.dev() && ma.ino() == mb.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (ma, mb);
        matches!(
            (std::fs::canonicalize(a), std::fs::canonicalize(b)),
            (Ok(x), Ok(y)) if x == y
        )
    }
}

/// Whether `r` metres per cell is a resolution maps may have: positive and at most
/// [`MAX_RESOLUTION_M`] (so not NaN). The one rule of map files, map messages, the CLI and
/// Python.
pub fn is_valid_resolution(r: f64) -> bool {
    r > 0.0 && r <= MAX_RESOLUTION_M
}

/// The largest map accepted, in cells (2²⁸ ≈ 268 million); larger ones are refused before
/// allocating.
pub const MAX_CELLS: u64 = 1 << 28;

/// The largest file read, in bytes (4 GiB); larger ones are refused before reading.
pub const MAX_FILE_BYTES: u64 = 1 << 32;

/// Options for [`load_map`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadOptions {
    /// Size of a pixel in metres, `(along x, along y)`.
    ///
    /// Required for bare bitmaps; overrides the default 1 m of `.map` and `.txt` files and
    /// the `resolution` of a ROS YAML file. Non-square pixels (`rx != ry`) are resampled
    /// to square cells of side `min(rx, ry)` by nearest-neighbour sampling.
    pub resolution: Option<(f64, f64)>,
    /// Grow the map by one Occupied cell on each side (Stage bitmaps often have no
    /// outer wall). Applies to every format.
    pub border: bool,
    /// The memory loading may take: a map whose loading is estimated to need more is
    /// refused before its cells are allocated, the refusal naming this limit. A command
    /// passes the least of what the machine leaves and the user's own budget, so that a
    /// map is refused under `--memory-mb` as a run is. `None`: not checked (maps are still
    /// bounded by [`MAX_CELLS`]).
    pub memory: Option<Available>,
}

impl LoadOptions {
    /// Options with square cells of side `resolution` metres and no border.
    pub fn with_resolution(resolution: f64) -> Self {
        Self {
            resolution: Some((resolution, resolution)),
            ..Self::default()
        }
    }
}

/// Load a map, choosing the format by the extension of `path` (see the [module docs](self)).
pub fn load_map(path: &Path, opts: &LoadOptions) -> Result<GridMap, MapError> {
    let ext = extension(path);
    check_file_memory(path, opts.memory)?;
    let map = match ext.as_str() {
        "yaml" | "yml" => {
            let text = read_text(path)?;
            parse_ros_yaml(&text, path, opts)?
        }
        "pgm" | "png" => {
            must_exist(path)?;
            let (rx, ry) = opts.resolution.ok_or_else(|| {
                MapError::new(path, MapErrorKind::ResolutionRequired("a bare bitmap"))
            })?;
            let bytes = read_bytes(path)?;
            let (what, per_pixel) = if ext == "pgm" {
                ("PGM image", PGM_BYTES_PER_PIXEL)
            } else {
                ("PNG image", PNG_BYTES_PER_PIXEL)
            };
            let fits = load_check(
                (rx, ry),
                opts,
                bytes.len() as u64,
                per_pixel + CELL_BYTES,
                what,
            );
            let raster = if ext == "pgm" {
                pgm::decode_pgm(&bytes, path, &fits)?
            } else {
                png::decode_png(&bytes, path, &fits)?
            };
            let cells = parse_bitmap(&raster);
            finish(GridMap::new(cells, 1.0), (rx, ry), path, opts.border)?
        }
        "map" => {
            let text = read_text(path)?;
            let res = opts.resolution.unwrap_or((1.0, 1.0));
            let fits = load_check(res, opts, text.len() as u64, CELL_BYTES, "MovingAI map");
            let map = movingai::parse_movingai_checked(&text, path, 1.0, &fits)?;
            finish(map, res, path, opts.border)?
        }
        "json" => load_houseexpo(path, opts)?.map,
        "txt" => {
            let text = read_text(path)?;
            let res = opts.resolution.unwrap_or((1.0, 1.0));
            let fits = load_check(res, opts, text.len() as u64, CELL_BYTES, "ASCII map");
            let map = ascii::parse_ascii_named(&text, path, 1.0, &fits)?;
            finish(map, res, path, opts.border)?
        }
        _ if path.is_dir() => return Err(MapError::new(path, MapErrorKind::Folder)),
        _ => return Err(MapError::new(path, MapErrorKind::UnknownFormat(ext))),
    };
    Ok(map)
}

/// A HouseExpo floor plan file (`.json`) with its rooms, read as [`load_map`] reads it
/// (`opts.resolution` required and square; `opts.border` grows the rooms' labels by a ring
/// of 0 with the map), for scoring a segmentation against its room boxes.
pub fn load_houseexpo(path: &Path, opts: &LoadOptions) -> Result<HouseExpoMap, MapError> {
    must_exist(path)?;
    let (rx, ry) = opts.resolution.ok_or_else(|| {
        MapError::new(
            path,
            MapErrorKind::ResolutionRequired(
                "a HouseExpo floor plan (metres per cell to rasterise it at)",
            ),
        )
    })?;
    if rx != ry {
        return Err(MapError::new(
            path,
            MapErrorKind::SquareResolution {
                what: "a HouseExpo floor plan (its outline is in metres)",
                rx: crate::Num(rx),
                ry: crate::Num(ry),
            },
        ));
    }
    let text = read_text(path)?;
    let fits = load_check(
        (rx, rx),
        opts,
        text.len() as u64,
        houseexpo::BYTES_PER_CELL,
        "HouseExpo floor plan",
    );
    let plan = houseexpo::parse_houseexpo_checked(&text, path, rx, &fits)?;
    let (w, h) = (plan.map.width(), plan.map.height());
    let map = finish(plan.map, (rx, rx), path, opts.border)?;
    let rooms = if opts.border {
        let mut grown = vec![0u32; map.width() * map.height()];
        for (y, row) in plan.rooms.chunks_exact(w.max(1)).take(h).enumerate() {
            let at = (y + 1) * map.width() + 1;
            grown[at..at + w].copy_from_slice(row);
        }
        grown
    } else {
        plan.rooms
    };
    Ok(HouseExpoMap {
        map,
        rooms,
        room_types: plan.room_types,
    })
}

/// Save a map, choosing the format by the extension of `path`.
///
/// `.png`: 8-bit greyscale PNG (free 254, occupied 0, unknown 205); `.pgm`: the same as
/// binary PGM (P5); `.yaml`/`.yml`: ROS map_server YAML plus a P5 PGM beside it with the
/// same stem; `.map`: MovingAI (Unknown is written as `@`, out of bounds, and so reads
/// back as Occupied); `.txt`: ASCII art. Only the YAML keeps the resolution and origin.
pub fn save_map(map: &GridMap, path: &Path) -> Result<(), MapError> {
    if path.is_dir() {
        return Err(MapError::new(path, MapErrorKind::WriteFolder));
    }
    if let Some(dir) = missing_folder(path) {
        return Err(MapError::new(
            path,
            MapErrorKind::NoFolder(dir.to_path_buf()),
        ));
    }
    let ext = extension(path);
    match ext.as_str() {
        "png" => write(path, &encode_png(&map.cells, path)?),
        "pgm" => write(path, &encode_pgm(&map.cells, path)?),
        "map" => write(path, to_movingai(&map.cells).as_bytes()),
        "txt" => write(path, to_ascii(&map.cells).as_bytes()),
        "yaml" | "yml" => {
            let image = path.with_extension("pgm");
            let image_name = image
                .file_name()
                .map(Path::new)
                .ok_or_else(|| MapError::new(path, MapErrorKind::UnknownFormat(ext.clone())))?;
            let yaml = to_ros_yaml(map, image_name, path)?;
            let pgm = encode_pgm(&map.cells, &image)?;
            write(&image, &pgm)?;
            write(path, yaml.as_bytes())
        }
        _ => Err(MapError::new(path, MapErrorKind::UnwritableFormat(ext))),
    }
}

/// The lower-case extension of `path`, or `""`.
fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// A check of a raster's `(width, height)` from its header, before its pixels are decoded;
/// the path is the file named in the error.
pub(crate) type SizeCheck = dyn Fn(u64, u64, &Path) -> Result<(), MapError>;

/// The lines of a text map, as [`str::lines`] gives them, but a last line that ends in a
/// bare `\r` (a CRLF file without its final newline) without it.
pub(crate) fn text_lines(text: &str) -> impl Iterator<Item = &str> {
    text.lines().map(|l| l.strip_suffix('\r').unwrap_or(l))
}

/// Bytes a cell of a grid takes.
pub(crate) const CELL_BYTES: u64 = 1;
/// Bytes a pixel of a decoded PGM takes (its value, a `u32`).
pub(crate) const PGM_BYTES_PER_PIXEL: u64 = 4;
/// Bytes a pixel of a decoded PNG takes (its value, a `u32`, and its alpha, a `u16`).
pub(crate) const PNG_BYTES_PER_PIXEL: u64 = 6;

/// How to make a map's loading fit in memory, said in every refusal.
const MEMORY_FIX: &str = "use a map with fewer, larger cells (scale the image down, or give a \
                          HouseExpo plan or a resampled map a coarser resolution)";

/// A map's `(width, height)` in cells.
type Size = (u64, u64);

/// The sizes, `(width, height)`, of what [`finish`] makes of a `w × h` map with pixel size
/// `(rx, ry)` and `border`: the resampled map (the map itself if the pixels are square) and
/// the finished one, each checked to be within [`MAX_CELLS`] (as the map itself is).
fn finished_sizes(
    w: u64,
    h: u64,
    (rx, ry): (f64, f64),
    border: bool,
    path: &Path,
) -> Result<(Size, Size), MapError> {
    check_size(w, h, path)?;
    if !(rx.is_finite() && ry.is_finite() && rx > 0.0 && ry > 0.0) {
        return Ok(((w, h), (w, h))); // `finish` names the bad resolution
    }
    let resampled = if rx == ry {
        (w, h)
    } else {
        let side = rx.min(ry);
        let size = usize::try_from(w)
            .ok()
            .zip(usize::try_from(h).ok())
            .and_then(|(w, h)| resample::resampled_size(w, h, (rx, ry), side));
        let Some((rw, rh)) = size else {
            return Err(resampled_too_large(w, h, (rx, ry), path));
        };
        check_size(rw as u64, rh as u64, path)?;
        (rw as u64, rh as u64)
    };
    let finished = if border {
        check_size(resampled.0 + 2, resampled.1 + 2, path)?;
        (resampled.0 + 2, resampled.1 + 2)
    } else {
        resampled
    };
    Ok((resampled, finished))
}

/// The refusal of a `w × h` picture whose pixels of `(rx, ry)` resampled to square cells
/// would make more than [`MAX_CELLS`] cells: the resampled size, or where a side would not
/// fit in an integer (a resolution of 1e-300 m), the picture, the pixels and the number of
/// cells as a float (a side's cast saturated to 18446744073709551615).
fn resampled_too_large(w: u64, h: u64, (rx, ry): (f64, f64), path: &Path) -> MapError {
    let side = rx.min(ry);
    let (rw, rh) = (
        (w as f64 * rx / side).round(),
        (h as f64 * ry / side).round(),
    );
    // Integers up to 2^53 are exact floats.
    const EXACT: f64 = 9_007_199_254_740_992.0;
    if rw < EXACT && rh < EXACT {
        return MapError::new(
            path,
            MapErrorKind::TooLarge {
                width: rw as u64,
                height: rh as u64,
                limit: MAX_CELLS,
            },
        );
    }
    let cells = rw * rh;
    MapError::new(
        path,
        MapErrorKind::ResampledTooLarge {
            width: w,
            height: h,
            rx,
            ry,
            side,
            cells,
            limit: MAX_CELLS,
        },
    )
}

/// The check that a raster's header size gives a map [`finish`] can make with pixel size
/// `(rx, ry)` and `border`: the raster itself, its resampled size and the border all within
/// [`MAX_CELLS`], so that a picture the map would outgrow is refused before it is decoded.
pub(crate) fn finished_size_check(
    res: (f64, f64),
    border: bool,
) -> impl Fn(u64, u64, &Path) -> Result<(), MapError> {
    move |w, h, path| finished_sizes(w, h, res, border, path).map(|_| ())
}

/// The check a loader makes of a map's size as soon as it knows it (from an image's
/// header, a text's header or rows, a floor plan's outline), before allocating its cells:
/// [`finished_size_check`] with `opts`' border, then the estimate of what loading will hold
/// at its peak against `opts.memory`: `held` bytes already read (the file), `per_cell` bytes
/// a cell of the map as read (its decoded pixels and the grid made of them), and the grids
/// [`finish`] makes (resampled, bordered). `what` names the kind of map in the refusal.
pub(crate) fn load_check<'a>(
    res: (f64, f64),
    opts: &LoadOptions,
    held: u64,
    per_cell: u64,
    what: &'a str,
) -> impl Fn(u64, u64, &Path) -> Result<(), MapError> + 'a {
    let (border, memory) = (opts.border, opts.memory);
    move |w, h, path| {
        let (resampled, finished) = finished_sizes(w, h, res, border, path)?;
        let Some(memory) = memory else {
            return Ok(());
        };
        // Every size is within MAX_CELLS (2^28): no product overflows.
        let mut needed = held + w * h * per_cell;
        if resampled != (w, h) || res.0 != res.1 {
            needed += resampled.0 * resampled.1 * CELL_BYTES;
        }
        if border {
            needed += finished.0 * finished.1 * CELL_BYTES;
        }
        check_memory(
            &format!("loading this {w}x{h} {what}"),
            needed,
            memory,
            path,
        )
    }
}

/// Refuse, naming `path`, `what` needing `needed` bytes when more than `memory` are left.
pub(crate) fn check_memory(
    what: &str,
    needed: u64,
    memory: Available,
    path: &Path,
) -> Result<(), MapError> {
    check_fits(what, needed, memory, MEMORY_FIX).map_err(|kind| MapError::new(path, kind))
}

/// Refuse `what` (e.g. "loading this 16384x16384 PGM image"), estimated to need `needed`
/// bytes, when `memory` leaves fewer; `fix` says how to make it fit. The one refusal of
/// every map loader: the map files' here and a recording's map (`record`), which name
/// their source around it.
pub fn check_fits(
    what: &str,
    needed: u64,
    memory: Available,
    fix: &'static str,
) -> Result<(), MapErrorKind> {
    if needed <= memory.bytes {
        return Ok(());
    }
    Err(MapErrorKind::OutOfMemory {
        what: what.to_string(),
        needed,
        limit: memory,
        fix,
    })
}

/// Refuse a file that is not there (or cannot be looked at) as unreadable, before the
/// options it would need are asked for: a missing bitmap is not told to need a resolution.
fn must_exist(path: &Path) -> Result<(), MapError> {
    std::fs::metadata(path)
        .map(drop)
        .map_err(|e| MapError::new(path, MapErrorKind::Read(e)))
}

/// Refuse a file at `path` that is larger than `memory` before reading it (loading holds
/// the whole file, then the map); a file that cannot be read is left to the reader.
pub(crate) fn check_file_memory(path: &Path, memory: Option<Available>) -> Result<(), MapError> {
    let Some(memory) = memory else {
        return Ok(());
    };
    match std::fs::metadata(path) {
        Ok(meta) if meta.is_file() => check_memory(
            &format!(
                "reading this file of {}",
                crate::memory::describe_bytes(meta.len())
            ),
            meta.len(),
            memory,
            path,
        ),
        _ => Ok(()),
    }
}

/// Apply the pixel size `(rx, ry)` (resampling non-square pixels) and the optional border.
pub(crate) fn finish(
    map: GridMap,
    (rx, ry): (f64, f64),
    path: &Path,
    border: bool,
) -> Result<GridMap, MapError> {
    for r in [rx, ry] {
        check_resolution(r, path)?;
    }
    // The same check the raster decoders make on a header, so the sizes are checked once.
    finished_size_check((rx, ry), border)(map.width() as u64, map.height() as u64, path)?;
    let mut map = map;
    if rx == ry {
        map.resolution = rx;
    } else {
        let side = rx.min(ry);
        let cells = resample::resample_nearest(&map.cells, (rx, ry), side).ok_or_else(|| {
            resampled_too_large(map.width() as u64, map.height() as u64, (rx, ry), path)
        })?;
        map = GridMap {
            cells,
            resolution: side,
            origin: map.origin,
        };
    }
    if border {
        map = add_border(&map);
    }
    Ok(map)
}

/// Error unless `r` is a positive resolution of at most [`MAX_RESOLUTION_M`].
pub(crate) fn check_resolution(r: f64, path: &Path) -> Result<(), MapError> {
    if is_valid_resolution(r) {
        Ok(())
    } else {
        Err(MapError::new(path, MapErrorKind::BadResolution(r)))
    }
}

/// Error unless a `width × height` map is non-empty and at most [`MAX_CELLS`] cells.
pub(crate) fn check_size(width: u64, height: u64, path: &Path) -> Result<(), MapError> {
    if width == 0 || height == 0 {
        return Err(MapError::new(
            path,
            MapErrorKind::EmptyMap { width, height },
        ));
    }
    match width.checked_mul(height) {
        Some(n) if n <= MAX_CELLS => Ok(()),
        _ => Err(MapError::new(
            path,
            MapErrorKind::TooLarge {
                width,
                height,
                limit: MAX_CELLS,
            },
        )),
    }
}

/// Read a whole regular file of at most [`MAX_FILE_BYTES`]; others are refused unread.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, MapError> {
    read_bytes_at_most(path, MAX_FILE_BYTES)
}

/// Read a whole regular file of at most `limit` bytes, as [`read_bytes`] with another limit.
///
/// Devices, pipes, sockets and directories are refused before reading: a device such as
/// `/dev/zero` reads without end, a pipe can block for ever, and neither has a size to
/// check. A file larger than `limit` is refused from its size, and one that grows past
/// `limit` while read is refused once `limit` bytes have been read.
pub fn read_bytes_at_most(path: &Path, limit: u64) -> Result<Vec<u8>, MapError> {
    let err = |e| MapError::new(path, MapErrorKind::Read(e));
    let (file, size) = open_at_most(path, limit)?;
    // A device or a file growing while read (e.g. /dev/zero, whose size reads 0) must not be
    // read past the limit either.
    let mut bytes = Vec::with_capacity(size as usize);
    std::io::Read::read_to_end(
        &mut std::io::Read::take(file, limit.saturating_add(1)),
        &mut bytes,
    )
    .map_err(err)?;
    if bytes.len() as u64 > limit {
        return Err(MapError::new(
            path,
            MapErrorKind::FileTooLarge {
                size: bytes.len() as u64,
                limit,
            },
        ));
    }
    Ok(bytes)
}

/// Open a regular file of at most `limit` bytes for reading, with its size, as
/// [`read_bytes_at_most`] reads one: for a reader that reads it piecewise (a recording,
/// read a record at a time), which reads no more than that size.
pub fn open_at_most(path: &Path, limit: u64) -> Result<(std::fs::File, u64), MapError> {
    let err = |e| MapError::new(path, MapErrorKind::Read(e));
    let meta = std::fs::metadata(path).map_err(err)?;
    if !meta.is_file() {
        // A device (/dev/zero) or pipe has no size to check before reading: refuse it.
        return Err(MapError::new(
            path,
            MapErrorKind::WrongFormat {
                expected: "regular",
                found: if meta.is_dir() {
                    "a directory".to_string()
                } else {
                    "a device, pipe or socket".to_string()
                },
            },
        ));
    }
    let size = meta.len();
    if size > limit {
        return Err(MapError::new(
            path,
            MapErrorKind::FileTooLarge { size, limit },
        ));
    }
    let file = std::fs::File::open(path).map_err(err)?;
    Ok((file, size))
}

/// Read a whole UTF-8 text file, without the byte order mark some editors write first
/// (YAML 1.2 allows one at the start of a stream; ROS's yaml-cpp reads past it).
pub(crate) fn read_text(path: &Path) -> Result<String, MapError> {
    let mut bytes = read_bytes(path)?;
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    String::from_utf8(bytes).map_err(|e| {
        MapError::new(
            path,
            MapErrorKind::WrongFormat {
                expected: "text",
                found: format!("invalid UTF-8 at byte {}", e.utf8_error().valid_up_to()),
            },
        )
    })
}

/// Write a whole file.
fn write(path: &Path, bytes: &[u8]) -> Result<(), MapError> {
    std::fs::write(path, bytes).map_err(|e| MapError::new(path, MapErrorKind::Write(e)))
}

/// The grey level written for a state: free 254, occupied 0, unknown 205 (as ROS map_saver).
pub fn grey_of(occ: Occ) -> u8 {
    match occ {
        Occ::Free => 254,
        Occ::Occupied => 0,
        Occ::Unknown => 205,
    }
}

/// The grey image of a grid, row-major, one byte per cell (see [`grey_of`]).
pub(crate) fn grey_bytes(cells: &Grid<Occ>) -> Vec<u8> {
    cells.data().iter().map(|&o| grey_of(o)).collect()
}
