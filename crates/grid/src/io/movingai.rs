//! MovingAI benchmark maps (Sturtevant 2012, "Benchmarks for grid-based pathfinding").
//!
//! ```text
//! type octile
//! height 2
//! width 3
//! map
//! .@T
//! ..G
//! ```
//!
//! `.`, `G` (ground) and `S` (swamp) are Free; `@`, `O` (out of bounds), `T` (trees) and
//! `W` (water) are Occupied. Row 0 is the first map line. The format has no resolution.

use std::path::Path;

use super::error::{MapError, MapErrorKind};
use super::{SizeCheck, check_resolution, check_size};
use crate::grid::Grid;
use crate::occ::{GridMap, Occ};

/// The characters allowed in the map rows.
const ALLOWED: &str = "'.', 'G', 'S' free; '@', 'O', 'T', 'W' blocked";

/// Parse a MovingAI `.map` file's text; `name` is the file named in errors.
pub fn parse_movingai(text: &str, name: &Path, resolution: f64) -> Result<GridMap, MapError> {
    parse_movingai_checked(text, name, resolution, &check_size)
}

/// Parse a MovingAI map once `fits(width, height, name)` accepts the size in its header.
pub(crate) fn parse_movingai_checked(
    text: &str,
    name: &Path,
    resolution: f64,
    fits: &SizeCheck,
) -> Result<GridMap, MapError> {
    check_resolution(resolution, name)?;
    let bad_line =
        |line: usize, what: String| MapError::new(name, MapErrorKind::BadLine { line, what });
    let mut lines = super::text_lines(text).enumerate().map(|(i, l)| (i + 1, l));
    let (mut kind, mut height, mut width) = (None, None, None);
    let mut last = 0;
    loop {
        let Some((n, line)) = lines.next() else {
            return Err(bad_line(
                last + 1,
                "the file ends before the 'map' line".to_string(),
            ));
        };
        last = n;
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        let value = words.next();
        if key == "map" && value.is_none() {
            break;
        }
        let (Some(value), None) = (value, words.next()) else {
            return Err(bad_line(
                n,
                format!(
                    "expected a header line 'type octile', 'height H', 'width W' or 'map', found {line:?}"
                ),
            ));
        };
        let number = || {
            value
                .parse::<u64>()
                .map_err(|_| bad_line(n, format!("{key} must be a whole number, found {value:?}")))
        };
        let slot_taken = match key {
            "type" => kind.replace((n, value.to_string())).is_some(),
            "height" => height.replace(number()?).is_some(),
            "width" => width.replace(number()?).is_some(),
            _ => {
                return Err(bad_line(
                    n,
                    format!("unknown header field {key:?} (expected type, height, width or map)"),
                ));
            }
        };
        if slot_taken {
            return Err(bad_line(n, format!("{key} is given twice")));
        }
    }
    let header_end = last;
    match &kind {
        Some((_, t)) if t == "octile" => {}
        Some((n, other)) => {
            return Err(bad_line(
                *n,
                format!("type must be 'octile', found {other:?}"),
            ));
        }
        None => {
            return Err(bad_line(
                header_end,
                "header has no 'type' line".to_string(),
            ));
        }
    }
    let height =
        height.ok_or_else(|| bad_line(header_end, "header has no 'height' line".to_string()))?;
    let width =
        width.ok_or_else(|| bad_line(header_end, "header has no 'width' line".to_string()))?;
    fits(width, height, name)?;
    let (w, h) = (width as usize, height as usize);
    // Reserve no more than the text can hold, whatever the header claims.
    let mut data = Vec::with_capacity((w * h).min(text.len()));
    for row in 0..h {
        let Some((n, line)) = lines.next() else {
            return Err(bad_line(
                header_end + row + 1,
                format!("the file ends after {row} of {h} map rows"),
            ));
        };
        let mut count = 0;
        for (x, ch) in line.chars().enumerate() {
            let occ = match ch {
                '.' | 'G' | 'S' => Occ::Free,
                '@' | 'O' | 'T' | 'W' => Occ::Occupied,
                _ => {
                    return Err(MapError::new(
                        name,
                        MapErrorKind::BadChar {
                            line: n,
                            column: x + 1,
                            ch,
                            allowed: ALLOWED,
                        },
                    ));
                }
            };
            if count < w {
                data.push(occ);
            }
            count += 1;
        }
        if count != w {
            return Err(bad_line(
                n,
                format!("map row has {count} cells, but width is {w}"),
            ));
        }
    }
    if let Some((n, _)) = lines.find(|(_, l)| !l.trim().is_empty()) {
        return Err(bad_line(n, format!("more map rows than the height {h}")));
    }
    let cells = Grid::from_vec(w, h, data)
        .ok_or_else(|| MapError::new(name, MapErrorKind::EmptyMap { width, height }))?;
    Ok(GridMap::new(cells, resolution))
}

/// The MovingAI text of a grid: Free `.`, Occupied `@`, and Unknown also `@` (out of
/// bounds), since the format has no unknown cells.
pub fn to_movingai(cells: &Grid<Occ>) -> String {
    let mut out = format!(
        "type octile\nheight {}\nwidth {}\nmap\n",
        cells.height(),
        cells.width()
    );
    out.reserve((cells.width() + 1) * cells.height());
    for y in 0..cells.height() {
        for &occ in &cells.data()[y * cells.width()..(y + 1) * cells.width()] {
            out.push(if occ == Occ::Free { '.' } else { '@' });
        }
        out.push('\n');
    }
    out
}
