//! PNG images, through the `png` crate: any PNG in, 8-bit greyscale out.
//!
//! Grey, grey+alpha, RGB, RGBA and palette images of 1 to 16 bits are read; a colour pixel's
//! brightness is the mean of its colour channels (ROS 1 map_server) and alpha 0 marks a
//! transparent pixel.

use std::io::Cursor;
use std::path::Path;

use ::png::{BitDepth, ColorType, Transformations};

use super::error::{MapError, MapErrorKind};
use super::pgm::describe_magic;
use super::raster::Raster;
use super::{SizeCheck, check_size, grey_bytes};
use crate::grid::Grid;
use crate::occ::Occ;

/// The PNG file signature.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// Decode a PNG image; `name` is the file named in errors.
///
/// The size in the header is checked against [`MAX_CELLS`](super::MAX_CELLS) before the
/// pixels are decoded.
pub fn parse_png(bytes: &[u8], name: &Path) -> Result<Raster, MapError> {
    decode_png(bytes, name, &check_size)
}

/// Decode a PNG image once `fits(width, height, name)` accepts the size in its header.
pub(crate) fn decode_png(bytes: &[u8], name: &Path, fits: &SizeCheck) -> Result<Raster, MapError> {
    let err = |kind| MapError::new(name, kind);
    if !bytes.starts_with(PNG_SIGNATURE) {
        return Err(err(MapErrorKind::WrongFormat {
            expected: "PNG",
            found: describe_png(bytes),
        }));
    }
    let mut decoder = ::png::Decoder::new(Cursor::new(bytes));
    // Palette to RGB, grey of 1, 2 or 4 bits to 8 (scaled to 0..=255), tRNS to alpha.
    decoder.set_transformations(Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| err(png_error(e)))?;
    let (w, h) = reader.info().size();
    fits(u64::from(w), u64::from(h), name)?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| err(MapErrorKind::Png(format!("a {w}x{h} image is too large"))))?;
    let mut buf = vec![0u8; size];
    let frame = reader.next_frame(&mut buf).map_err(|e| err(png_error(e)))?;
    buf.truncate(frame.buffer_size());
    let (w, h) = (w as usize, h as usize);
    let (channels, alpha) = match frame.color_type {
        ColorType::Grayscale => (1, false),
        ColorType::GrayscaleAlpha => (2, true),
        ColorType::Rgb => (3, false),
        ColorType::Rgba => (4, true),
        ColorType::Indexed => {
            return Err(err(MapErrorKind::Png(
                "a palette image was not expanded".to_string(),
            )));
        }
    };
    let (maxval, values, transparent) = if frame.bit_depth == BitDepth::Sixteen {
        // Samples are big-endian.
        let wide: Vec<u16> = buf
            .chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect();
        samples(&wide, channels, alpha, 65535)
    } else {
        samples(&buf, channels, alpha, 255)
    };
    if values.len() != w * h {
        return Err(err(MapErrorKind::Png(format!(
            "decoded {} pixels for a {w}x{h} image",
            values.len()
        ))));
    }
    Ok(Raster {
        width: w,
        height: h,
        maxval,
        values,
        transparent,
    })
}

/// What a PNG decoding error means for the user.
fn png_error(e: ::png::DecodingError) -> MapErrorKind {
    match e {
        ::png::DecodingError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            MapErrorKind::Png("truncated: the file ends before the image data does".to_string())
        }
        e => MapErrorKind::Png(e.to_string()),
    }
}

/// Say what a file that is not a PNG looks like.
fn describe_png(bytes: &[u8]) -> String {
    match bytes.get(..2) {
        Some(b"P2") | Some(b"P5") => "it is a PGM image (mislabelled?)".to_string(),
        _ => describe_magic(bytes),
    }
}

/// Brightness sums, their maximum and transparency of interleaved samples.
fn samples<T: Copy + Into<u32>>(
    raw: &[T],
    channels: usize,
    alpha: bool,
    channel_max: u32,
) -> (u32, Vec<u32>, Vec<bool>) {
    let colour = if alpha { channels - 1 } else { channels };
    let values = raw
        .chunks_exact(channels)
        .map(|px| px[..colour].iter().map(|&s| s.into()).sum::<u32>())
        .collect();
    let transparent = if alpha {
        raw.chunks_exact(channels)
            .map(|px| px[colour].into() == 0)
            .collect()
    } else {
        Vec::new()
    };
    (channel_max * colour as u32, values, transparent)
}

/// Encode a grid as an 8-bit greyscale PNG: free 254, occupied 0, unknown 205.
///
/// `name` is the file named in the error for an empty grid.
pub fn encode_png(cells: &Grid<Occ>, name: &Path) -> Result<Vec<u8>, MapError> {
    check_size(cells.width() as u64, cells.height() as u64, name)?;
    let (w, h) = (cells.width() as u32, cells.height() as u32);
    encode_grey(&grey_bytes(cells), w, h)
        .map_err(|e| MapError::new(name, MapErrorKind::Encode(e.to_string())))
}

/// Encode `pixels` (row-major, one byte a pixel) as an 8-bit greyscale PNG of `w × h`.
pub fn encode_grey(pixels: &[u8], w: u32, h: u32) -> Result<Vec<u8>, ::png::EncodingError> {
    encode_8bit(pixels, w, h, ColorType::Grayscale)
}

/// Encode `pixels` (row-major, R G B bytes a pixel) as an 8-bit RGB PNG of `w × h`.
pub fn encode_rgb(pixels: &[u8], w: u32, h: u32) -> Result<Vec<u8>, ::png::EncodingError> {
    encode_8bit(pixels, w, h, ColorType::Rgb)
}

/// Encode row-major 8-bit samples of `colour` as a PNG of `w × h`.
fn encode_8bit(
    pixels: &[u8],
    w: u32,
    h: u32,
    colour: ColorType,
) -> Result<Vec<u8>, ::png::EncodingError> {
    let mut out = Vec::new();
    let mut encoder = ::png::Encoder::new(&mut out, w, h);
    encoder.set_color(colour);
    encoder.set_depth(BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(pixels)?;
    writer.finish()?;
    Ok(out)
}
