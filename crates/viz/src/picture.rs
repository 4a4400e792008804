//! An RGB picture in memory, written as PNG: all the raster `viz` and the commands draw
//! into (8 bits a channel, row-major, no alpha).

use std::path::Path;

use crate::VizError;

/// A `width × height` RGB picture, 8 bits a channel, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl Picture {
    /// A black picture of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![0; width as usize * height as usize * 3],
        }
    }

    /// A picture whose pixel (x, y) is `colour(x, y)`.
    pub fn from_fn(width: u32, height: u32, mut colour: impl FnMut(u32, u32) -> [u8; 3]) -> Self {
        let mut p = Self::new(width, height);
        for y in 0..height {
            for x in 0..width {
                p.put_pixel(x, y, colour(x, y));
            }
        }
        p
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The colour of pixel (x, y); panics outside the picture.
    pub fn get_pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let k = self.offset(x, y);
        [self.data[k], self.data[k + 1], self.data[k + 2]]
    }

    /// Paint pixel (x, y); panics outside the picture.
    pub fn put_pixel(&mut self, x: u32, y: u32, colour: [u8; 3]) {
        let k = self.offset(x, y);
        self.data[k..k + 3].copy_from_slice(&colour);
    }

    /// The picture as a PNG file's bytes.
    pub fn to_png(&self) -> Result<Vec<u8>, VizError> {
        grid::io::png::encode_rgb(&self.data, self.width, self.height)
            .map_err(|e| VizError::Png(e.to_string()))
    }

    /// Write the picture to `path` as PNG.
    pub fn save(&self, path: &Path) -> Result<(), VizError> {
        std::fs::write(path, self.to_png()?).map_err(VizError::Io)
    }

    /// Read a PNG (as [`Picture::to_png`] writes; other colour types are made RGB) of at
    /// most `max_pixels` pixels, checked in its header before any pixel is decoded.
    pub fn from_png(bytes: &[u8], max_pixels: u64) -> Result<Self, VizError> {
        let png = |e: png::DecodingError| VizError::Png(e.to_string());
        let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info().map_err(png)?;
        let (w, h) = reader.info().size();
        if u64::from(w) * u64::from(h) > max_pixels {
            return Err(VizError::Png(format!(
                "a {w}x{h} picture, more than the {max_pixels} pixels expected"
            )));
        }
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| VizError::Png("the picture is too large".to_string()))?;
        let mut buf = vec![0u8; size];
        let frame = reader.next_frame(&mut buf).map_err(png)?;
        buf.truncate(frame.buffer_size());
        let channels = frame.color_type.samples();
        let mut p = Self::new(frame.width, frame.height);
        for (px, out) in buf.chunks_exact(channels).zip(p.data.chunks_exact_mut(3)) {
            match channels {
                1 | 2 => out.fill(px[0]),
                _ => out.copy_from_slice(&px[..3]),
            }
        }
        Ok(p)
    }

    fn offset(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside the picture"
        );
        (y as usize * self.width as usize + x as usize) * 3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip() {
        let p = Picture::from_fn(5, 3, |x, y| [x as u8 * 40, y as u8 * 80, 7]);
        let back = Picture::from_png(&p.to_png().expect("encode"), 15).expect("decode");
        assert_eq!(back, p);
        assert_eq!(back.get_pixel(4, 2), [160, 160, 7]);
        let e = Picture::from_png(&p.to_png().expect("encode"), 14).unwrap_err();
        assert!(e.to_string().contains("5x3"), "{e}");
    }
}
