//! ROS map_server maps: a YAML file naming an image (PGM or PNG) and how to read it.
//!
//! ```yaml
//! image: office.pgm        # relative to the YAML's folder
//! resolution: 0.05         # metres per pixel
//! origin: [-10.0, -10.0, 0.0]  # pose [x, y, yaw] of the lower-left pixel
//! negate: 0
//! occupied_thresh: 0.65
//! free_thresh: 0.196
//! mode: trinary            # optional: trinary (default), scale or raw
//! ```
//!
//! `image`, `resolution`, `origin`, `negate`, `occupied_thresh` and `free_thresh` are
//! required, as in ROS; other fields are ignored. Pixels are classified as in
//! [`Thresholds`]: in `trinary` and `scale` modes the occupancy `p = (maxval − v)/maxval`
//! (`v/maxval` with `negate`) is Occupied above `occupied_thresh`, Free below
//! `free_thresh`, else Unknown — `scale` mode's intermediate occupancies have no place in
//! a three-state map, so they are Unknown too. In `trinary` mode a PNG pixel's alpha is
//! averaged in with its colour, as both map_servers do
//! ([`Thresholds::classify_trinary`]); in `scale` mode a pixel that is not fully opaque is
//! Unknown, as in nav2 (ROS 1 makes Unknown only the fully transparent ones between the
//! thresholds; [`Thresholds::classify_scale`]). `raw` mode follows nav2 (see
//! [`Thresholds::classify_raw`]). Image row 0 is
//! grid row 0 (the top); `origin` stays the lower-left corner.

use std::path::{Path, PathBuf};

use yaml_rust2::{Yaml, YamlLoader};

use super::error::{MapError, MapErrorKind};
use super::pgm::decode_pgm;
use super::png::decode_png;
use super::raster::Thresholds;
use super::{
    CELL_BYTES, LoadOptions, PGM_BYTES_PER_PIXEL, PNG_BYTES_PER_PIXEL, SizeCheck,
    check_file_memory, check_resolution, finish, load_check, read_bytes,
};
use crate::occ::GridMap;

/// How map_server turns pixel values into occupancy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RosMode {
    /// Occupied, free or unknown by the thresholds.
    #[default]
    Trinary,
    /// Thresholds, with occupancies in between scaled (Unknown here); a pixel not fully
    /// opaque is Unknown (nav2).
    Scale,
    /// The pixel value is the occupancy in percent.
    Raw,
}

/// The contents of a ROS map YAML file.
#[derive(Clone, Debug, PartialEq)]
pub struct RosMapMeta {
    /// The image's path as written in the YAML.
    pub image: PathBuf,
    /// Metres per pixel.
    pub resolution: f64,
    /// Pose `[x, y, yaw]` of the lower-left corner of the map.
    pub origin: [f64; 3],
    /// Occupancy thresholds and `negate`.
    pub thresholds: Thresholds,
    /// How pixel values are read.
    pub mode: RosMode,
}

/// Longest map YAML text accepted, in bytes (map_server's files are a few hundred).
pub const MAX_YAML_BYTES: usize = 64 * 1024;

/// Counts the alias events of a YAML stream (without expanding them).
struct AliasCount(usize);

impl yaml_rust2::parser::EventReceiver for AliasCount {
    fn on_event(&mut self, ev: yaml_rust2::parser::Event) {
        if let yaml_rust2::parser::Event::Alias(_) = ev {
            self.0 += 1;
        }
    }
}

/// Parse the fields of a ROS map YAML file; `yaml_path` is the file named in errors.
pub fn parse_ros_yaml_meta(text: &str, yaml_path: &Path) -> Result<RosMapMeta, MapError> {
    let err = |kind| MapError::new(yaml_path, kind);
    // A map YAML is a few short fields. Aliases would be expanded by copying, which a few
    // hundred bytes of nested aliases turn into gigabytes ("billion laughs"): refuse them,
    // and any text far longer than a map YAML, before building the document.
    if text.len() > MAX_YAML_BYTES {
        return Err(err(MapErrorKind::YamlSyntax(format!(
            "expected a map YAML of a few fields (at most {MAX_YAML_BYTES} bytes), found {} bytes",
            text.len()
        ))));
    }
    let mut aliases = AliasCount(0);
    yaml_rust2::parser::Parser::new_from_str(text)
        .load(&mut aliases, true)
        .map_err(|e| err(MapErrorKind::YamlSyntax(e.to_string())))?;
    if aliases.0 > 0 {
        return Err(err(MapErrorKind::YamlSyntax(format!(
            "expected plain fields, found {} alias(es) (`*name`): aliases are not supported in a map YAML",
            aliases.0
        ))));
    }
    let docs = YamlLoader::load_from_str(text)
        .map_err(|e| err(MapErrorKind::YamlSyntax(tidy_yaml_error(&e.to_string()))))?;
    let doc = match docs.first() {
        Some(d @ Yaml::Hash(_)) => d,
        Some(other) => {
            return Err(err(MapErrorKind::YamlSyntax(format!(
                "expected a mapping of fields (image, resolution, ...), found {}",
                show(other)
            ))));
        }
        None => {
            return Err(err(MapErrorKind::YamlSyntax(
                "the file is empty: expected a mapping of fields (image, resolution, ...)"
                    .to_string(),
            )));
        }
    };
    let field = |name: &'static str| -> Result<&Yaml, MapError> {
        match &doc[name] {
            Yaml::BadValue => Err(err(MapErrorKind::MissingField(name))),
            y => Ok(y),
        }
    };
    let bad = |name: &'static str, expected: &str, y: &Yaml| {
        err(MapErrorKind::BadField {
            field: name,
            expected: expected.to_string(),
            found: show(y),
        })
    };

    let image = match field("image")? {
        Yaml::String(s) if !s.trim().is_empty() => PathBuf::from(s.trim()),
        y => return Err(bad("image", "an image file name", y)),
    };

    let y = field("resolution")?;
    let resolution = match number(y) {
        Some(r) if r.is_finite() && r > 0.0 => r,
        _ => return Err(bad("resolution", "a positive number", y)),
    };

    let y = field("origin")?;
    let origin = match y {
        Yaml::Array(a) if a.len() == 3 => {
            let mut o = [0.0; 3];
            for ((slot, v), part) in o.iter_mut().zip(a).zip(["x", "y", "yaw"]) {
                match number(v) {
                    Some(x) if x.is_finite() => *slot = x,
                    _ => {
                        return Err(err(MapErrorKind::BadField {
                            field: "origin",
                            expected: format!("a finite number as its {part} ([x, y, yaw])"),
                            found: show(v),
                        }));
                    }
                }
            }
            o
        }
        _ => return Err(bad("origin", "a list of three numbers [x, y, yaw]", y)),
    };

    // As nav2 reads it: an integer (any but 0 negates) or a YAML boolean, yaml-cpp's
    // spellings (`yes`, `on`, …) included.
    let y = field("negate")?;
    let negate = match y {
        Yaml::Integer(i) => *i != 0,
        Yaml::Boolean(b) => *b,
        Yaml::String(s) => match s.to_ascii_lowercase().as_str() {
            "y" | "yes" | "on" | "true" => true,
            "n" | "no" | "off" | "false" => false,
            _ => return Err(bad("negate", "0 or 1 (or a boolean)", y)),
        },
        _ => return Err(bad("negate", "0 or 1 (or a boolean)", y)),
    };

    let threshold = |name: &'static str| -> Result<f64, MapError> {
        let y = field(name)?;
        match number(y) {
            Some(t) if (0.0..=1.0).contains(&t) => Ok(t),
            _ => Err(bad(name, "a number between 0 and 1", y)),
        }
    };
    let occupied = threshold("occupied_thresh")?;
    let free = threshold("free_thresh")?;
    if free > occupied {
        return Err(err(MapErrorKind::BadField {
            field: "free_thresh",
            expected: format!("at most occupied_thresh ({occupied})"),
            found: free.to_string(),
        }));
    }

    // nav2 lower-cases the mode before it reads it.
    let mode = match &doc["mode"] {
        Yaml::BadValue | Yaml::Null => RosMode::Trinary,
        Yaml::String(s) if s.eq_ignore_ascii_case("trinary") => RosMode::Trinary,
        Yaml::String(s) if s.eq_ignore_ascii_case("scale") => RosMode::Scale,
        Yaml::String(s) if s.eq_ignore_ascii_case("raw") => RosMode::Raw,
        y => return Err(bad("mode", "trinary, scale or raw", y)),
    };

    Ok(RosMapMeta {
        image,
        resolution,
        origin,
        thresholds: Thresholds {
            occupied,
            free,
            negate,
        },
        mode,
    })
}

/// The image file a map YAML at `yaml_path` names: relative to the YAML's folder.
fn image_path(yaml_path: &Path, meta: &RosMapMeta) -> PathBuf {
    match yaml_path.parent() {
        Some(dir) if meta.image.is_relative() => dir.join(&meta.image),
        _ => meta.image.clone(),
    }
}

/// The image file the map YAML at `path` names, if `path` is a readable map YAML (a
/// `.yaml` or `.yml` of at most [`MAX_YAML_BYTES`] that parses); `None` otherwise.
pub fn ros_image_of(path: &Path) -> Option<PathBuf> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    if !matches!(ext.as_str(), "yaml" | "yml") {
        return None;
    }
    let bytes = super::read_bytes_at_most(path, MAX_YAML_BYTES as u64).ok()?;
    let text = std::str::from_utf8(&bytes).ok()?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let meta = parse_ros_yaml_meta(text, path).ok()?;
    Some(image_path(path, &meta))
}

/// Load a ROS map: parse the YAML `text` of the file `yaml_path`, then read its image
/// (a relative `image` path is taken from the YAML's folder).
///
/// `opts.resolution`, if given, overrides the YAML's; `opts.border` adds a wall.
pub fn parse_ros_yaml(
    text: &str,
    yaml_path: &Path,
    opts: &LoadOptions,
) -> Result<GridMap, MapError> {
    let meta = parse_ros_yaml_meta(text, yaml_path)?;
    let image = image_path(yaml_path, &meta);
    let image_err = |source| {
        MapError::new(
            yaml_path,
            MapErrorKind::ImageFile {
                image: image.clone(),
                source,
            },
        )
    };
    let ext = image
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let (decode, what, per_pixel) = match ext.as_str() {
        "pgm" | "pnm" => (
            decode_pgm as fn(&[u8], &Path, &SizeCheck) -> _,
            "PGM image",
            PGM_BYTES_PER_PIXEL,
        ),
        "png" => (decode_png as _, "PNG image", PNG_BYTES_PER_PIXEL),
        _ => {
            return Err(MapError::new(
                yaml_path,
                MapErrorKind::BadField {
                    field: "image",
                    expected: "a .pgm or .png file".to_string(),
                    found: format!("{:?}", meta.image.display().to_string()),
                },
            ));
        }
    };
    // The image may be anything the YAML names (a device, a pipe, a huge file): read it
    // with the same bounds as a map file, reporting failures as the YAML's image.
    check_file_memory(&image, opts.memory)?;
    let bytes = read_bytes(&image).map_err(|e| {
        image_err(match e.kind {
            MapErrorKind::Read(source) => source,
            kind => std::io::Error::new(std::io::ErrorKind::InvalidInput, kind.to_string()),
        })
    })?;
    let res = opts
        .resolution
        .unwrap_or((meta.resolution, meta.resolution));
    let fits = load_check(res, opts, bytes.len() as u64, per_pixel + CELL_BYTES, what);
    let raster = decode(&bytes, &image, &fits)?;
    let cells = match meta.mode {
        RosMode::Trinary => meta.thresholds.classify_trinary(&raster),
        RosMode::Scale => meta.thresholds.classify_scale(&raster),
        RosMode::Raw => meta.thresholds.classify_raw(&raster),
    };
    let map = GridMap {
        cells,
        resolution: meta.resolution,
        origin: meta.origin,
    };
    finish(map, res, yaml_path, opts.border)
}

/// `message` of the YAML parser with its debug print of a key (`String("image"):
/// duplicated key in mapping`) written as the key (`image: duplicated key in mapping`).
fn tidy_yaml_error(message: &str) -> String {
    match message.strip_prefix("String(\"") {
        Some(rest) => match rest.split_once("\"):") {
            Some((key, after)) => format!("{key}:{after}"),
            None => message.to_string(),
        },
        None => message.to_string(),
    }
}

/// The ROS map YAML for `map` whose image is saved as `image` (written as given, so
/// normally a bare file name beside the YAML); `yaml_path` is named in errors.
///
/// Written with mode trinary, negate 0, occupied_thresh 0.65, free_thresh 0.196, which
/// read the grey levels of [`grey_of`](super::grey_of) back exactly.
pub fn to_ros_yaml(map: &GridMap, image: &Path, yaml_path: &Path) -> Result<String, MapError> {
    check_resolution(map.resolution, yaml_path)?;
    if map.origin.iter().any(|v| !v.is_finite()) {
        return Err(MapError::new(
            yaml_path,
            MapErrorKind::BadField {
                field: "origin",
                expected: "finite numbers".to_string(),
                found: format!("{:?}", map.origin),
            },
        ));
    }
    let name = image
        .to_str()
        .ok_or_else(|| MapError::new(yaml_path, MapErrorKind::BadFileName(image.to_path_buf())))?;
    let [x, y, yaw] = map.origin;
    Ok(format!(
        "image: {}\nmode: trinary\nresolution: {:?}\norigin: [{x:?}, {y:?}, {yaw:?}]\n\
         negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
        quote(name),
        map.resolution,
    ))
}

/// `s` as a YAML double-quoted string.
fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A YAML value as a number: floats, integers, and strings holding a number.
fn number(y: &Yaml) -> Option<f64> {
    match y {
        Yaml::Real(_) => y.as_f64(),
        Yaml::Integer(i) => Some(*i as f64),
        Yaml::String(s) if s.bytes().any(|b| b.is_ascii_digit()) => s.trim().parse().ok(),
        _ => None,
    }
}

/// A YAML value as written, for error messages.
fn show(y: &Yaml) -> String {
    match y {
        Yaml::Real(s) => s.clone(),
        Yaml::Integer(i) => i.to_string(),
        Yaml::String(s) => format!("{s:?}"),
        Yaml::Boolean(b) => b.to_string(),
        Yaml::Array(a) if a.len() == 1 => "a list of 1 item".to_string(),
        Yaml::Array(a) => format!("a list of {} items", a.len()),
        Yaml::Hash(_) => "a mapping".to_string(),
        Yaml::Alias(_) => "an alias".to_string(),
        Yaml::Null => "nothing (null)".to_string(),
        Yaml::BadValue => "an invalid value".to_string(),
    }
}
