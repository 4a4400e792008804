//! Any map file a front end takes, read by one rule: an MCAP recording (`.mcap`) gives its
//! last `nav_msgs/OccupancyGrid`, a dungeon PNG gives its map and the start it marks, and
//! every other file is one of [`grid::io::load_map`]'s formats.
//!
//! The CLI's `--map`, Python's `frontier.Map.load` and a study's `[[env]] map` all read
//! maps through [`load`], so they tell formats apart and refuse options alike. Each front end
//! names its own parameters in the message it makes of a [`MapFileError`] (a flag, a
//! keyword argument, a scenario key).

use std::path::Path;

use grid::io::{LoadOptions, MapErrorKind};
use grid::{Cell, GridMap};

/// Whether `path` names an MCAP recording (by its extension, in any case).
pub fn is_mcap(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
}

/// Why a map file was not read.
#[derive(Debug, Clone, PartialEq)]
pub enum MapFileError {
    /// A topic was given for a file that is not an MCAP recording.
    TopicWithoutMcap,
    /// An option that sets pixels (`"resolution"`, `"border"` or `"dungeon"`, the first
    /// given) was given for an MCAP recording, whose map carries its own resolution.
    McapOption(&'static str),
    /// A dungeon PNG needs one resolution for square cells; this was given instead.
    DungeonResolution(Option<(f64, f64)>),
    /// The file's format needs a resolution and none was given: the file as the message
    /// shows it, and what it is (e.g. `a bare bitmap`).
    ResolutionRequired(String, &'static str),
    /// The file could not be read as a map; the message names the file.
    Load(String),
}

/// A map read from a file.
#[derive(Debug, Clone)]
pub struct MapFile {
    /// The map.
    pub map: GridMap,
    /// The start the file marks (a dungeon PNG's).
    pub start: Option<Cell>,
    /// The topic a recording's map was read from (`None` for other files).
    pub topic: Option<String>,
    /// A recording's map's frame and log time (`None` for other files).
    pub recorded_at: Option<crate::mcap_read::RecordedAt>,
}

/// The map in the file at `path`, read with `opts` (its memory bound applies to recordings
/// too); `topic` chooses a recording's map topic, `dungeon` reads a PNG as a dungeon map.
pub fn load(
    path: &Path,
    opts: &LoadOptions,
    topic: Option<&str>,
    dungeon: bool,
) -> Result<MapFile, MapFileError> {
    let mcap = is_mcap(path);
    if topic.is_some() && !mcap {
        return Err(MapFileError::TopicWithoutMcap);
    }
    if mcap {
        let pixel_option = [
            ("resolution", opts.resolution.is_some()),
            ("border", opts.border),
            ("dungeon", dungeon),
        ]
        .into_iter()
        .find_map(|(name, given)| given.then_some(name));
        if let Some(name) = pixel_option {
            return Err(MapFileError::McapOption(name));
        }
        let r = crate::mcap_read::load_map(path, topic, opts.memory).map_err(MapFileError::Load)?;
        return Ok(MapFile {
            map: r.map,
            start: None,
            topic: Some(r.topic),
            recorded_at: Some(r.at),
        });
    }
    if dungeon {
        let Some((r, _)) = opts.resolution.filter(|(x, y)| x == y) else {
            return Err(MapFileError::DungeonResolution(opts.resolution));
        };
        let d =
            grid::io::load_dungeon(path, r, opts).map_err(|e| MapFileError::Load(e.to_string()))?;
        return Ok(MapFile {
            map: d.map,
            start: Some(d.start),
            topic: None,
            recorded_at: None,
        });
    }
    let map = grid::io::load_map(path, opts).map_err(|e| match e.kind {
        MapErrorKind::ResolutionRequired(what) => {
            MapFileError::ResolutionRequired(e.path.display().to_string(), what)
        }
        // The formats the map files of `grid` read, and recordings besides.
        MapErrorKind::UnknownFormat(ext) => MapFileError::Load(format!(
            "{}: unknown map format {ext:?}: expected {MAP_FORMATS}",
            e.path.display()
        )),
        MapErrorKind::Folder => MapFileError::Load(match recording_in(&e.path) {
            // A rosbag2 bag is a folder holding the recording.
            Some(file) => format!(
                "{}: is a folder, expected one map file: give the recording in it, {}",
                e.path.display(),
                file.display()
            ),
            None => format!(
                "{}: is a folder, expected one map file ({MAP_FORMATS})",
                e.path.display()
            ),
        }),
        _ => MapFileError::Load(e.to_string()),
    })?;
    Ok(MapFile {
        map,
        start: None,
        topic: None,
        recorded_at: None,
    })
}

/// The extensions of the map files [`load`] reads.
const MAP_FORMATS: &str = ".yaml, .yml, .pgm, .png, .map, .json (HouseExpo), .txt or .mcap \
                           (a recording)";

/// The first `.mcap` file (by name) in `folder`, if any.
fn recording_in(folder: &Path) -> Option<std::path::PathBuf> {
    let mut found: Vec<_> = std::fs::read_dir(folder)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| is_mcap(p))
        .collect();
    found.sort();
    found.into_iter().next()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(resolution: Option<(f64, f64)>, border: bool) -> LoadOptions {
        LoadOptions {
            resolution,
            border,
            memory: None,
        }
    }

    #[test]
    fn a_topic_needs_a_recording() {
        let e = load(
            Path::new("plan.yaml"),
            &opts(None, false),
            Some("/map"),
            false,
        );
        assert_eq!(e.unwrap_err(), MapFileError::TopicWithoutMcap);
    }

    #[test]
    fn a_recording_refuses_pixel_options_by_name() {
        let path = Path::new("run.MCAP");
        let first = |o: &LoadOptions, dungeon| load(path, o, None, dungeon).unwrap_err();
        assert_eq!(
            first(&opts(Some((0.05, 0.05)), true), true),
            MapFileError::McapOption("resolution")
        );
        assert_eq!(
            first(&opts(None, true), true),
            MapFileError::McapOption("border")
        );
        assert_eq!(
            first(&opts(None, false), true),
            MapFileError::McapOption("dungeon")
        );
    }

    /// Regression: the unknown-format and folder messages listed every format but the
    /// recordings `--map` also reads, and a rosbag2 bag's folder was not pointed into.
    #[test]
    fn format_and_folder_errors_name_recordings_too() {
        let dir = std::env::temp_dir().join(format!("record-map-errors-{}", std::process::id()));
        let bag = dir.join("rosbag2_x");
        std::fs::create_dir_all(&bag).unwrap();
        let msg = |p: &Path| match load(p, &opts(None, false), None, false).unwrap_err() {
            MapFileError::Load(m) => m,
            e => panic!("{e:?}"),
        };
        let e = msg(&dir.join("plan.bmp"));
        assert!(e.ends_with(".txt or .mcap (a recording)"), "{e}");
        let e = msg(&bag);
        assert!(
            e.contains("is a folder, expected one map file (.yaml"),
            "{e}"
        );
        std::fs::write(bag.join("rosbag2_x_0.mcap"), b"").unwrap();
        let e = msg(&bag);
        assert!(
            e.ends_with(&format!(
                "give the recording in it, {}",
                bag.join("rosbag2_x_0.mcap").display()
            )),
            "{e}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_dungeon_needs_one_square_resolution() {
        let path = Path::new("dungeon.png");
        for r in [None, Some((0.1, 0.2))] {
            let e = load(path, &opts(r, false), None, true).unwrap_err();
            assert_eq!(e, MapFileError::DungeonResolution(r));
        }
    }

    #[test]
    fn a_map_file_is_read_by_its_format() {
        let dir = std::env::temp_dir().join(format!("record-map-file-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("plan.txt");
        std::fs::write(&path, "####\n#..#\n####\n").unwrap();
        let MapFile {
            map,
            start,
            topic,
            recorded_at,
        } = load(&path, &opts(Some((0.5, 0.5)), false), None, false).unwrap();
        assert_eq!(
            (map.width(), map.height(), start, topic, recorded_at),
            (4, 3, None, None, None)
        );
        assert_eq!(map.resolution, 0.5);
        // a bitmap that is there (one that is not is unreadable first)
        std::fs::write(dir.join("plan.png"), b"not decoded before the resolution").unwrap();
        let bitmap = load(&dir.join("plan.png"), &opts(None, false), None, false);
        let want = (dir.join("plan.png").display().to_string(), "a bare bitmap");
        assert_eq!(
            bitmap.unwrap_err(),
            MapFileError::ResolutionRequired(want.0, want.1)
        );
        let missing = load(&dir.join("none.txt"), &opts(None, false), None, false);
        assert!(matches!(missing, Err(MapFileError::Load(m)) if m.contains("none.txt")));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
