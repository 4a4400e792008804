//! `MapError`: every way reading or writing a map file can fail, always naming the file.

use std::path::{Path, PathBuf};

/// The name used in errors for maps parsed from memory rather than read from a file.
pub const MEMORY: &str = "<memory>";

/// A map file could not be read or written: the file and what is wrong with it.
///
/// Displays as `path: what is wrong`, e.g.
/// `maps/office.yaml: field 'resolution': expected a positive number, found "abc"`.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct MapError {
    /// The file the problem is in (`<memory>` for text or bytes parsed from memory).
    pub path: PathBuf,
    /// What is wrong.
    pub kind: MapErrorKind,
}

impl MapError {
    /// An error of `kind` in the file `path`.
    pub fn new(path: &Path, kind: MapErrorKind) -> Self {
        Self {
            path: path.to_path_buf(),
            kind,
        }
    }
}

/// What is wrong with a map file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MapErrorKind {
    /// The file could not be read.
    #[error("cannot read: {0}")]
    Read(#[source] std::io::Error),
    /// The file could not be written.
    #[error("cannot write: {0}")]
    Write(#[source] std::io::Error),
    /// The file is larger than any map this crate will read.
    #[error("file is {size} bytes, more than the limit of {limit} bytes")]
    FileTooLarge {
        /// Size of the file in bytes.
        size: u64,
        /// The largest file read, in bytes.
        limit: u64,
    },
    /// The extension does not say which format the file is in.
    #[error(
        "unknown map format {0:?}: expected .yaml, .yml, .pgm, .png, .map, .json (HouseExpo) or .txt"
    )]
    UnknownFormat(String),
    /// The path is a folder, where one map file was expected.
    #[error("is a folder, expected one map file (.yaml, .yml, .pgm, .png, .map, .json or .txt)")]
    Folder,
    /// A folder was given where a map file is to be written.
    #[error(
        "is a folder, expected the name of a map file to write (.yaml, .yml, .pgm, .png, .map or .txt)"
    )]
    WriteFolder,
    /// The folder a map file is to be written into does not exist.
    #[error("cannot write: the folder {0} does not exist")]
    NoFolder(std::path::PathBuf),
    /// The extension names no format maps are written in (HouseExpo is read only).
    #[error("cannot write map format {0:?}: expected .yaml, .yml, .pgm, .png, .map or .txt")]
    UnwritableFormat(String),
    /// A bare bitmap or a HouseExpo plan (the file named) was loaded without a resolution.
    #[error("--resolution is required for {0}")]
    ResolutionRequired(&'static str),
    /// Non-square pixels were given for a format read at one resolution (the file named).
    #[error("expected one resolution (square cells) for {what}, found {rx} x {ry} m")]
    SquareResolution {
        /// What is read at one resolution.
        what: &'static str,
        /// Width of a pixel given, in metres.
        rx: crate::Num,
        /// Height of a pixel given, in metres.
        ry: crate::Num,
    },
    /// A resolution was zero, negative, not finite or over [`super::MAX_RESOLUTION_M`].
    #[error(
        "resolution must be a positive number of metres per cell, at most {max}, found {0}",
        max = super::MAX_RESOLUTION_M
    )]
    BadResolution(f64),
    /// A map with no cells.
    #[error("empty map: width {width} and height {height} must both be positive")]
    EmptyMap {
        /// Width found.
        width: u64,
        /// Height found.
        height: u64,
    },
    /// A map with more cells than [`MAX_CELLS`](super::MAX_CELLS); refused before allocating.
    #[error("map too large: {width}x{height} cells is more than the limit of {limit} cells")]
    TooLarge {
        /// Width found.
        width: u64,
        /// Height found.
        height: u64,
        /// The largest number of cells accepted.
        limit: u64,
    },
    /// Non-square pixels resampled to square cells would make more cells than
    /// [`MAX_CELLS`](super::MAX_CELLS) (or more than a number can count); refused before
    /// allocating.
    #[error(
        "map too large: {width}x{height} pixels of {rx:?} x {ry:?} m resampled to square cells of \
         {side:?} m make about {cells:.3e} cells, more than the limit of {limit} cells"
    )]
    ResampledTooLarge {
        /// Width of the picture in pixels.
        width: u64,
        /// Height of the picture in pixels.
        height: u64,
        /// Pixel width in metres.
        rx: f64,
        /// Pixel height in metres.
        ry: f64,
        /// Side of the square cells in metres (the smaller of `rx` and `ry`).
        side: f64,
        /// The cells resampling would make.
        cells: f64,
        /// The largest number of cells accepted.
        limit: u64,
    },
    /// Loading the map would need more memory than is available; refused before the map's
    /// cells are allocated.
    #[error("{what} needs about {}, more than {limit}; {fix}", crate::memory::describe_bytes(*.needed))]
    OutOfMemory {
        /// What would be loaded, e.g. "loading this 16384x16384 PGM".
        what: String,
        /// Estimated bytes.
        needed: u64,
        /// The memory available and the limit that leaves it.
        limit: crate::memory::Available,
        /// How to make it fit.
        fix: &'static str,
    },
    /// The bytes are not in the format the extension or the YAML says.
    #[error("not a {expected} file: {found}")]
    WrongFormat {
        /// Format expected.
        expected: &'static str,
        /// What the bytes look like instead.
        found: String,
    },
    /// A malformed PGM header.
    #[error("bad PGM header: {0}")]
    PgmHeader(String),
    /// The pixel data is shorter than the header says.
    #[error(
        "truncated: header says {width}x{height} pixels ({expected} bytes), \
         file has {} of pixel data",
        bytes(*found)
    )]
    Truncated {
        /// Width in the header.
        width: u64,
        /// Height in the header.
        height: u64,
        /// Bytes of pixel data needed.
        expected: u64,
        /// Bytes of pixel data present.
        found: u64,
    },
    /// A plain (P2) PGM with fewer samples than the header says, or a bad sample.
    #[error("pixel ({x}, {y}): {what}")]
    BadPixel {
        /// Column of the pixel.
        x: u64,
        /// Row of the pixel.
        y: u64,
        /// What is wrong with it.
        what: String,
    },
    /// The PNG decoder refused the file.
    #[error("bad PNG: {0}")]
    Png(String),
    /// The image could not be encoded.
    #[error("cannot encode image: {0}")]
    Encode(String),
    /// The YAML is not well-formed.
    #[error("YAML syntax error: {0}")]
    YamlSyntax(String),
    /// A required YAML field is missing.
    #[error("missing field '{0}'")]
    MissingField(&'static str),
    /// A YAML field has the wrong type or an invalid value.
    #[error("field '{field}': expected {expected}, found {found}")]
    BadField {
        /// The field's name.
        field: &'static str,
        /// What it must be.
        expected: String,
        /// What it is (as written in the file).
        found: String,
    },
    /// The image named by a ROS YAML file could not be read.
    #[error("image file '{}': {source}", image.display())]
    ImageFile {
        /// The image's path (relative paths are taken from the YAML's folder).
        image: PathBuf,
        /// Why it could not be read.
        #[source]
        source: std::io::Error,
    },
    /// A line of a text map (MovingAI header or rows, ASCII rows) is malformed.
    #[error("line {line}: {what}")]
    BadLine {
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        what: String,
    },
    /// A character not allowed in a text map.
    #[error("line {line}, column {column}: unknown character {ch:?} (allowed: {allowed})")]
    BadChar {
        /// 1-based line number.
        line: usize,
        /// 1-based column (in characters).
        column: usize,
        /// The character found.
        ch: char,
        /// The characters allowed.
        allowed: &'static str,
    },
    /// A file name that cannot be written into a ROS YAML file.
    #[error("file name {0:?} is not valid UTF-8")]
    BadFileName(PathBuf),
}

/// `n` bytes, or one byte.
fn bytes(n: u64) -> String {
    if n == 1 {
        "1 byte".to_string()
    } else {
        format!("{n} bytes")
    }
}
