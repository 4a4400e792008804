//! PNG images, through the `png` crate: any PNG in, 8-bit greyscale out.
//!
//! Grey, grey+alpha, RGB, RGBA and palette images of 1 to 16 bits are read; a colour pixel's
//! brightness is the mean of its colour channels (ROS 1 map_server), and its alpha is kept
//! for the rules that read it ([`Thresholds`](super::Thresholds)).

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
    let (w, h) = (w as usize, h as usize);
    let (color_type, bit_depth) = reader.output_color_type();
    let (channels, alpha) = match color_type {
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
    // Rows are decoded one at a time into the brightness sums: a whole decoded frame takes up
    // to 8 bytes a pixel (16-bit RGBA), 2 GiB for a 16384 x 16384 image that a 2 MB file can
    // hold, before the raster's own 4 or 5.
    let wide = bit_depth == BitDepth::Sixteen;
    let (sample_bytes, channel_max) = if wide { (2, 65535) } else { (1, 255) };
    let colour = if alpha { channels - 1 } else { channels };
    let mut values = vec![0u32; w * h];
    let mut alphas = if alpha { vec![0u16; w * h] } else { Vec::new() };
    let passes: &[Pass] = if reader.info().interlaced {
        &ADAM7
    } else {
        &[Pass {
            x0: 0,
            y0: 0,
            dx: 1,
            dy: 1,
        }]
    };
    for pass in passes {
        let (samples, lines) = (pass.samples(w), pass.lines(h));
        if samples == 0 {
            continue; // the decoder skips passes without pixels
        }
        for line in 0..lines {
            let row = reader
                .next_row()
                .map_err(|e| err(png_error(e)))?
                .ok_or_else(|| {
                    err(MapErrorKind::Png(format!(
                        "decoded fewer rows than the {w}x{h} image has"
                    )))
                })?;
            let data = row.data();
            let pixel_bytes = channels * sample_bytes;
            if data.len() != samples * pixel_bytes {
                return Err(err(MapErrorKind::Png(format!(
                    "decoded a row of {} bytes for {samples} pixels of {pixel_bytes} bytes",
                    data.len()
                ))));
            }
            let y = pass.y0 + line * pass.dy;
            for (k, px) in data.chunks_exact(pixel_bytes).enumerate() {
                let sample = |c: usize| {
                    if wide {
                        u32::from(u16::from_be_bytes([px[2 * c], px[2 * c + 1]]))
                    } else {
                        u32::from(px[c])
                    }
                };
                let i = y * w + pass.x0 + k * pass.dx;
                values[i] = (0..colour).map(sample).sum();
                if alpha {
                    // At most 65535: a sample is one or two bytes.
                    alphas[i] = sample(colour) as u16;
                }
            }
        }
    }
    // Past the last row the decoder checks and skips the rest of the image data.
    if reader.next_row().map_err(|e| err(png_error(e)))?.is_some() {
        return Err(err(MapErrorKind::Png(format!(
            "decoded more rows than the {w}x{h} image has"
        ))));
    }
    Ok(Raster {
        width: w,
        height: h,
        maxval: channel_max * colour as u32,
        values,
        alpha: alphas,
        alpha_max: if alpha { channel_max } else { 0 },
        colours: colour as u32,
    })
}

/// One pass over an image's pixels: columns `x0, x0 + dx, …` of rows `y0, y0 + dy, …`.
struct Pass {
    x0: usize,
    y0: usize,
    dx: usize,
    dy: usize,
}

impl Pass {
    /// How many pixels of a row of `width` the pass takes.
    fn samples(&self, width: usize) -> usize {
        width.saturating_sub(self.x0).div_ceil(self.dx)
    }

    /// How many rows of an image of `height` the pass takes.
    fn lines(&self, height: usize) -> usize {
        height.saturating_sub(self.y0).div_ceil(self.dy)
    }
}

/// The seven passes of an Adam7-interlaced PNG, in the order its rows come.
const ADAM7: [Pass; 7] = [
    Pass {
        x0: 0,
        y0: 0,
        dx: 8,
        dy: 8,
    },
    Pass {
        x0: 4,
        y0: 0,
        dx: 8,
        dy: 8,
    },
    Pass {
        x0: 0,
        y0: 4,
        dx: 4,
        dy: 8,
    },
    Pass {
        x0: 2,
        y0: 0,
        dx: 4,
        dy: 4,
    },
    Pass {
        x0: 0,
        y0: 2,
        dx: 2,
        dy: 4,
    },
    Pass {
        x0: 1,
        y0: 0,
        dx: 2,
        dy: 2,
    },
    Pass {
        x0: 0,
        y0: 1,
        dx: 1,
        dy: 2,
    },
];

/// What a PNG decoding error means for the user.
fn png_error(e: ::png::DecodingError) -> MapErrorKind {
    MapErrorKind::Png(match e {
        ::png::DecodingError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            "truncated: the file ends before the image data does".to_string()
        }
        ::png::DecodingError::LimitsExceeded => "an image row or chunk is larger than the \
                                                 PNG decoder's limit of 64 MiB"
            .to_string(),
        e => tidy_chunk_names(&e.to_string()),
    })
}

/// `message` with the decoder's debug print of a chunk type (`ChunkType { type: IHDR,
/// critical: true, … }`) shortened to the chunk's name, and its capital first letter
/// (`Invalid image dimensions`, `CRC error`) kept where it is an acronym only.
fn tidy_chunk_names(message: &str) -> String {
    const OPEN: &str = "ChunkType { type: ";
    let mut out = String::new();
    let mut rest = message;
    while let Some(at) = rest.find(OPEN) {
        out.push_str(&rest[..at]);
        let after = &rest[at + OPEN.len()..];
        let name_end = after.find([',', ' ', '}']).unwrap_or(after.len());
        out.push_str(&after[..name_end]);
        rest = after.find('}').map_or("", |end| &after[end + 1..]);
    }
    out.push_str(rest);
    match out.split_whitespace().next() {
        Some(word) if word.chars().skip(1).any(|c| c.is_ascii_lowercase()) => {
            let mut chars = out.chars();
            let first = chars.next().map(|c| c.to_ascii_lowercase());
            first.into_iter().chain(chars).collect()
        }
        _ => out,
    }
}

/// Say what a file that is not a PNG looks like.
fn describe_png(bytes: &[u8]) -> String {
    match bytes.get(..2) {
        Some(b"P2") | Some(b"P5") => "it is a PGM image (mislabelled?)".to_string(),
        _ => describe_magic(bytes),
    }
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

#[cfg(test)]
mod tests {
    use super::tidy_chunk_names;

    #[test]
    fn chunk_types_are_named_and_sentences_start_small() {
        assert_eq!(
            tidy_chunk_names(
                "CRC error: expected 0x5a3c22bf have 0x5ac322bf while decoding ChunkType { \
                 type: IHDR, critical: true, private: false, reserved: false, safecopy: false } \
                 chunk."
            ),
            "CRC error: expected 0x5a3c22bf have 0x5ac322bf while decoding IHDR chunk."
        );
        assert_eq!(
            tidy_chunk_names("Invalid image dimensions"),
            "invalid image dimensions"
        );
        assert_eq!(tidy_chunk_names("ChunkType { type: tEXt"), "tEXt");
    }
}
