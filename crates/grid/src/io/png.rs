//! PNG images, through the `image` crate: any PNG in, 8-bit greyscale out.
//!
//! Grey, grey+alpha, RGB, RGBA and palette images of 1 to 16 bits are read; a colour pixel's
//! brightness is the mean of its colour channels (ROS 1 map_server) and alpha 0 marks a
//! transparent pixel.

use std::io::Cursor;
use std::path::Path;

use image::codecs::png::{PngDecoder, PngEncoder};
use image::{DynamicImage, ExtendedColorType, ImageDecoder, ImageEncoder};

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
    let decoder = PngDecoder::new(Cursor::new(bytes)).map_err(|e| err(png_error(e)))?;
    let (w, h) = decoder.dimensions();
    fits(u64::from(w), u64::from(h), name)?;
    let image = DynamicImage::from_decoder(decoder).map_err(|e| err(png_error(e)))?;
    let (w, h) = (w as usize, h as usize);
    let (maxval, values, transparent) = match &image {
        DynamicImage::ImageLuma8(i) => samples(i.as_raw(), 1, false, 255),
        DynamicImage::ImageLumaA8(i) => samples(i.as_raw(), 2, true, 255),
        DynamicImage::ImageRgb8(i) => samples(i.as_raw(), 3, false, 255),
        DynamicImage::ImageRgba8(i) => samples(i.as_raw(), 4, true, 255),
        DynamicImage::ImageLuma16(i) => samples(i.as_raw(), 1, false, 65535),
        DynamicImage::ImageLumaA16(i) => samples(i.as_raw(), 2, true, 65535),
        DynamicImage::ImageRgb16(i) => samples(i.as_raw(), 3, false, 65535),
        DynamicImage::ImageRgba16(i) => samples(i.as_raw(), 4, true, 65535),
        other => samples(other.to_rgba16().as_raw(), 4, true, 65535),
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
fn png_error(e: image::ImageError) -> MapErrorKind {
    match e {
        image::ImageError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
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
    let mut out = Vec::new();
    PngEncoder::new(&mut out)
        .write_image(&grey_bytes(cells), w, h, ExtendedColorType::L8)
        .map_err(|e| MapError::new(name, MapErrorKind::Encode(e.to_string())))?;
    Ok(out)
}
