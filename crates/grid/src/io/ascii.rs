//! ASCII-art maps for tests and small examples: `#` Occupied, `.` Free, `?` Unknown.
//!
//! One text line per row, top row first, all rows the same length. Nothing else is
//! allowed (not even spaces); a trailing newline and `\r\n` line ends are accepted.

use std::path::Path;

use super::error::{MEMORY, MapError, MapErrorKind};
use super::{SizeCheck, check_resolution, check_size};
use crate::grid::Grid;
use crate::occ::{GridMap, Occ};

/// The characters allowed in an ASCII map.
const ALLOWED: &str = "'#' wall, '.' free, '?' unknown";

/// Parse an ASCII map held in memory (errors name the file `<memory>`).
pub fn parse_ascii(text: &str, resolution: f64) -> Result<GridMap, MapError> {
    parse_ascii_named(text, Path::new(MEMORY), resolution, &check_size)
}

/// Parse an ASCII map read from the file `name` once `fits(width, height, name)` accepts
/// its size (the first row's length, the number of rows).
pub(crate) fn parse_ascii_named(
    text: &str,
    name: &Path,
    resolution: f64,
    fits: &SizeCheck,
) -> Result<GridMap, MapError> {
    check_resolution(resolution, name)?;
    // Trailing blank lines are not rows. The lines are walked twice rather than collected:
    // a list of them takes 16 bytes a line, 3.2 GB for a 200 MB file of newlines.
    let rows = super::text_lines(text)
        .enumerate()
        .filter(|(_, l)| !l.is_empty())
        .last()
        .map_or(0, |(i, _)| i + 1);
    let width = super::text_lines(text)
        .next()
        .map_or(0, |l| l.chars().count());
    if width == 0 && rows > 0 {
        return Err(MapError::new(
            name,
            MapErrorKind::BadLine {
                line: 1,
                what: "empty, but the first row gives the map's width".into(),
            },
        ));
    }
    fits(width as u64, rows as u64, name)?;
    let mut data = Vec::with_capacity(width * rows);
    for (y, line) in super::text_lines(text).take(rows).enumerate() {
        let mut n = 0;
        for (x, ch) in line.chars().enumerate() {
            let occ = match ch {
                '#' => Occ::Occupied,
                '.' => Occ::Free,
                '?' => Occ::Unknown,
                _ => {
                    return Err(MapError::new(
                        name,
                        MapErrorKind::BadChar {
                            line: y + 1,
                            column: x + 1,
                            ch,
                            allowed: ALLOWED,
                        },
                    ));
                }
            };
            data.push(occ);
            n += 1;
        }
        if n != width {
            return Err(MapError::new(
                name,
                MapErrorKind::BadLine {
                    line: y + 1,
                    what: format!("row has {n} cells, but the first row has {width}"),
                },
            ));
        }
    }
    let cells = Grid::from_vec(width, rows, data).ok_or_else(|| {
        MapError::new(
            name,
            MapErrorKind::EmptyMap {
                width: width as u64,
                height: rows as u64,
            },
        )
    })?;
    Ok(GridMap::new(cells, resolution))
}

/// The ASCII art of a grid: one line per row, each ending in `\n`.
pub fn to_ascii(cells: &Grid<Occ>) -> String {
    let mut out = String::with_capacity((cells.width() + 1) * cells.height());
    for y in 0..cells.height() {
        for &occ in &cells.data()[y * cells.width()..(y + 1) * cells.width()] {
            out.push(match occ {
                Occ::Occupied => '#',
                Occ::Free => '.',
                Occ::Unknown => '?',
            });
        }
        out.push('\n');
    }
    out
}

/// Test-only convenience: the map drawn in `text`, at 1 m per cell.
///
/// Whitespace around each line is trimmed and blank lines are skipped, so maps can be
/// written as indented raw strings. Panics with the parse error if the art is malformed,
/// so use it only on maps written into tests.
pub fn ascii_map(text: &str) -> GridMap {
    let trimmed: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    match parse_ascii(&trimmed.join("\n"), 1.0) {
        Ok(map) => map,
        Err(e) => panic!("ascii_map: bad test map: {e}"),
    }
}
