//! Netpbm PGM greyscale images: plain (P2) and binary (P5), 8- and 16-bit.
//!
//! Header: magic `P2`/`P5`, width, height, maxval (1..=65535), separated by whitespace,
//! with `#` comments; then one whitespace byte (after a comment, its newline) and the
//! pixels, row-major from the top.
//! Binary pixels take one byte if `maxval < 256`, else two bytes, most significant first.

use std::path::Path;

use super::error::{MapError, MapErrorKind};
use super::raster::Raster;
use super::{SizeCheck, check_size, grey_bytes};
use crate::grid::Grid;
use crate::occ::Occ;

/// The PNG file signature, to tell a mislabelled PNG apart.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// Decode a PGM image (P2 or P5, 8- or 16-bit); `name` is the file named in errors.
///
/// The size in the header is checked against [`MAX_CELLS`](super::MAX_CELLS) before the
/// pixels are read.
pub fn parse_pgm(bytes: &[u8], name: &Path) -> Result<Raster, MapError> {
    decode_pgm(bytes, name, &check_size)
}

/// Decode a PGM image once `fits(width, height, name)` accepts the size in its header.
pub(crate) fn decode_pgm(bytes: &[u8], name: &Path, fits: &SizeCheck) -> Result<Raster, MapError> {
    let err = |kind| MapError::new(name, kind);
    let plain = match bytes.get(..2) {
        Some(b"P2") => true,
        Some(b"P5") => false,
        _ => {
            return Err(err(MapErrorKind::WrongFormat {
                expected: "PGM",
                found: describe_magic(bytes),
            }));
        }
    };
    let mut pos = 2;
    let width = header_number(bytes, &mut pos, "width", name)?;
    let height = header_number(bytes, &mut pos, "height", name)?;
    let maxval = header_number(bytes, &mut pos, "maxval", name)?;
    if maxval == 0 || maxval > 65535 {
        return Err(err(MapErrorKind::PgmHeader(format!(
            "maxval must be between 1 and 65535, found {maxval}"
        ))));
    }
    fits(width, height, name)?;
    // One whitespace byte ends the header; a comment may come before it, its newline
    // then the byte (pgm(5): "before the whitespace character that delimits the raster,
    // any characters from a '#' through the next carriage return or newline character,
    // is a comment").
    if bytes.get(pos) == Some(&b'#') {
        while bytes.get(pos).is_some_and(|&b| b != b'\n' && b != b'\r') {
            pos += 1;
        }
    }
    match bytes.get(pos) {
        Some(b) if b.is_ascii_whitespace() => pos += 1,
        Some(&b) => {
            return Err(err(MapErrorKind::PgmHeader(format!(
                "expected whitespace after maxval, found {:?}",
                char::from(b)
            ))));
        }
        None => {}
    }
    // Sizes were checked against MAX_CELLS (2^28), so these fit in usize and u64.
    let (w, h) = (width as usize, height as usize);
    let n = w * h;
    let maxval = maxval as u32;
    let values = if plain {
        plain_pixels(&bytes[pos.min(bytes.len())..], w, h, maxval, name)?
    } else {
        binary_pixels(&bytes[pos.min(bytes.len())..], w, h, maxval, name)?
    };
    debug_assert_eq!(values.len(), n);
    Ok(Raster {
        width: w,
        height: h,
        maxval,
        values,
        alpha: Vec::new(),
        alpha_max: 0,
        colours: 1,
    })
}

/// Say what a file that is not a PGM looks like.
pub(crate) fn describe_magic(bytes: &[u8]) -> String {
    if bytes.starts_with(PNG_SIGNATURE) {
        return "it is a PNG image (mislabelled?)".to_string();
    }
    match bytes.get(..2) {
        Some(b"P1") | Some(b"P4") => return "it is a PBM (black and white) image".to_string(),
        Some(b"P3") | Some(b"P6") => return "it is a PPM (colour) image".to_string(),
        _ => {}
    }
    if bytes.is_empty() {
        return "the file is empty".to_string();
    }
    let head: String = bytes
        .iter()
        .take(8)
        .flat_map(|&b| std::ascii::escape_default(b))
        .map(char::from)
        .collect();
    format!("it starts with \"{head}\"")
}

/// Skip whitespace and `#` comments, then read a decimal header field.
fn header_number(bytes: &[u8], pos: &mut usize, field: &str, name: &Path) -> Result<u64, MapError> {
    skip_space_and_comments(bytes, pos);
    let start = *pos;
    let mut value: u64 = 0;
    while let Some(&b) = bytes.get(*pos) {
        if !b.is_ascii_digit() {
            break;
        }
        value = value
            .checked_mul(10)
            .and_then(|v| v.checked_add(u64::from(b - b'0')))
            .ok_or_else(|| {
                MapError::new(
                    name,
                    MapErrorKind::PgmHeader(format!("{field} is too large")),
                )
            })?;
        *pos += 1;
    }
    if *pos == start {
        let found = match bytes.get(*pos) {
            None => "end of file".to_string(),
            Some(&b) => format!("{:?}", char::from(b)),
        };
        return Err(MapError::new(
            name,
            MapErrorKind::PgmHeader(format!("expected {field} (a number), found {found}")),
        ));
    }
    Ok(value)
}

/// Advance `pos` past whitespace and `#` comments (to the end of their line).
fn skip_space_and_comments(bytes: &[u8], pos: &mut usize) {
    while let Some(&b) = bytes.get(*pos) {
        if b == b'#' {
            while let Some(&c) = bytes.get(*pos) {
                if c == b'\n' || c == b'\r' {
                    break;
                }
                *pos += 1;
            }
        } else if b.is_ascii_whitespace() {
            *pos += 1;
        } else {
            break;
        }
    }
}

/// Decode `w × h` binary pixels.
fn binary_pixels(
    data: &[u8],
    w: usize,
    h: usize,
    maxval: u32,
    name: &Path,
) -> Result<Vec<u32>, MapError> {
    let bpp = if maxval < 256 { 1 } else { 2 };
    let n = w * h;
    let expected = n * bpp;
    if data.len() < expected {
        return Err(MapError::new(
            name,
            MapErrorKind::Truncated {
                width: w as u64,
                height: h as u64,
                expected: expected as u64,
                found: data.len() as u64,
            },
        ));
    }
    let mut values = Vec::with_capacity(n);
    for (i, chunk) in data[..expected].chunks_exact(bpp).enumerate() {
        let v = if bpp == 1 {
            u32::from(chunk[0])
        } else {
            u32::from(chunk[0]) << 8 | u32::from(chunk[1])
        };
        if v > maxval {
            return Err(above_maxval(i, w, &v.to_string(), maxval, name));
        }
        values.push(v);
    }
    Ok(values)
}

/// Decode `w × h` plain (decimal text) pixels.
fn plain_pixels(
    data: &[u8],
    w: usize,
    h: usize,
    maxval: u32,
    name: &Path,
) -> Result<Vec<u32>, MapError> {
    let n = w * h;
    // Each value takes at least one digit and one separator: never reserve more than the
    // data can hold, so a lying header cannot make us allocate.
    let mut values = Vec::with_capacity(n.min(data.len() / 2 + 1));
    let mut pos = 0;
    for i in 0..n {
        skip_space_and_comments(data, &mut pos);
        let start = pos;
        let mut v: u32 = 0;
        while let Some(&b) = data.get(pos) {
            if !b.is_ascii_digit() {
                break;
            }
            v = v.saturating_mul(10).saturating_add(u32::from(b - b'0'));
            pos += 1;
        }
        if pos == start {
            let c = i % w;
            let what = match data.get(pos) {
                None => format!("missing: the file ends after {i} of {w}x{h} pixel values"),
                Some(&b) => format!("expected a number, found {:?}", char::from(b)),
            };
            return Err(MapError::new(
                name,
                MapErrorKind::BadPixel {
                    x: c as u64,
                    y: (i / w) as u64,
                    what,
                },
            ));
        }
        if v > maxval {
            // As written (a saturated `v` is not what the file holds); long runs of digits
            // are shortened.
            let digits = String::from_utf8_lossy(&data[start..pos]);
            let shown = if digits.len() > 24 {
                format!("{}… ({} digits)", &digits[..20], digits.len())
            } else {
                digits.into_owned()
            };
            return Err(above_maxval(i, w, &shown, maxval, name));
        }
        values.push(v);
    }
    Ok(values)
}

/// The error for pixel `i` whose value (`v`, as written) exceeds `maxval`.
fn above_maxval(i: usize, w: usize, v: &str, maxval: u32, name: &Path) -> MapError {
    MapError::new(
        name,
        MapErrorKind::BadPixel {
            x: (i % w) as u64,
            y: (i / w) as u64,
            what: format!("value {v} is above maxval {maxval}"),
        },
    )
}

/// Encode a grid as an 8-bit binary PGM (P5): free 254, occupied 0, unknown 205.
///
/// `name` is the file named in the error for an empty grid.
pub fn encode_pgm(cells: &Grid<Occ>, name: &Path) -> Result<Vec<u8>, MapError> {
    check_size(cells.width() as u64, cells.height() as u64, name)?;
    let header = format!(
        "P5\n# frontier occupancy map: free 254, occupied 0, unknown 205\n{} {}\n255\n",
        cells.width(),
        cells.height()
    );
    let mut out = Vec::with_capacity(header.len() + cells.len());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(&grey_bytes(cells));
    Ok(out)
}
