//! Flags shared by several commands, and their resolution into maps and configurations.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use grid::{Grid, GridMap, Occ};
use world::{EnvKind, EnvSpec};

/// A map file as `--map` reads it (with `--resolution`, `--border`, `--topic` and
/// `--dungeon`), the start it marks (a dungeon PNG's) and the topic a recording's map was
/// read from. A recording's map is checked against `opts.memory` as a map file is.
pub fn load_map_file(
    path: &Path,
    opts: &grid::io::LoadOptions,
    topic: Option<&str>,
    dungeon: bool,
) -> Result<record::map_file::MapFile> {
    use record::map_file::MapFileError;
    record::map_file::load(path, opts, topic, dungeon).map_err(|e| match e {
        MapFileError::TopicWithoutMcap => {
            anyhow::anyhow!("--topic chooses the map topic of an MCAP recording (a FILE.mcap map)")
        }
        MapFileError::McapOption(name) => anyhow::anyhow!(
            "--{name}: an MCAP recording's map carries its own resolution and cells, so \
             --{name} does not apply to {}",
            path.display()
        ),
        MapFileError::DungeonResolution(found) => anyhow::anyhow!(
            "--dungeon: expected one --resolution (square cells) for {}, found {}",
            path.display(),
            match found {
                Some((x, y)) => format!("{x},{y}"),
                None => "none".into(),
            }
        ),
        MapFileError::ResolutionRequired(file, what) => {
            anyhow::anyhow!("{file}: --resolution is required for {what}")
        }
        MapFileError::Load(message) => anyhow::Error::msg(message),
    })
}

/// Generate `spec`, a size or resolution the kind cannot use named by its flag
/// (`--size`, `--resolution`).
pub fn generate(spec: &EnvSpec) -> Result<world::Environment> {
    world::generate(spec).map_err(|e| match &e {
        world::WorldError::InvalidSpec { field, .. } => {
            let flag = if *field == "resolution" {
                "--resolution"
            } else {
                "--size"
            };
            anyhow::anyhow!("{flag}: {e}")
        }
        _ => anyhow::Error::new(e).context(format!("generating {}", spec.kind)),
    })
}

/// Where the ground truth comes from: a built-in environment or a map file.
#[derive(Args, Clone, Debug)]
pub struct MapSource {
    /// Built-in environment kind (see `frontier list`); the default when no --map is given
    /// is `office`.
    #[arg(long, conflicts_with = "map")]
    pub env: Option<String>,
    /// A map file: ROS .yaml, .pgm/.png bitmap (needs --resolution), MovingAI .map, HouseExpo
    /// .json (needs --resolution), ASCII .txt, or an MCAP recording (.mcap: its last
    /// nav_msgs/OccupancyGrid).
    #[arg(long)]
    pub map: Option<PathBuf>,
    /// The OccupancyGrid topic of an MCAP --map (default: its only one, or /map).
    #[arg(long)]
    pub topic: Option<String>,
    /// Metres per cell: needed for bare bitmaps, .json and --dungeon maps, 1 if not given for
    /// .map and .txt, and overriding a ROS YAML's own; "RX,RY" for non-square pixels; for
    /// --env, the resolution to generate at.
    #[arg(allow_hyphen_values = true, long)]
    pub resolution: Option<String>,
    /// Add a wall one cell thick around the map (any file but an MCAP recording; Stage floor
    /// plans often have none); the origin and a dungeon's marked start move with the cells.
    #[arg(long)]
    pub border: bool,
    /// Read --map as a dungeon PNG of learned-exploration work (Chen et al. 2019): pixels
    /// brighter than 150 are free, and pixels of value 208 mark the start (required;
    /// --start overrides it). Needs --resolution.
    #[arg(long)]
    pub dungeon: bool,
    /// Size of a generated environment in metres, "WxH".
    #[arg(allow_hyphen_values = true, long)]
    pub size: Option<String>,
    /// Seed of the generated environment (default: --seed).
    #[arg(allow_negative_numbers = true, long)]
    pub env_seed: Option<u64>,
    /// Furnish a generated office or hospital with tables and chairs off the laser plane
    /// (Yamauchi): planar sensors miss them, sonar hears them, the robot's body bumps into them.
    #[arg(long)]
    pub clutter: bool,
    /// Off-plane obstacles of a map: an image or map file of the same size whose occupied
    /// cells are obstacles a planar laser misses (read like --map, with its --resolution).
    #[arg(long)]
    pub clutter_map: Option<PathBuf>,
}

/// A loaded or generated ground truth with the name runs report.
pub struct Truth {
    /// Name used in reports: the environment's name or the map file's stem.
    pub name: String,
    /// The map.
    pub map: GridMap,
    /// Obstacles off the laser plane (same size as the map), if any.
    pub clutter: Option<Grid<bool>>,
    /// The start the map file marks (a dungeon PNG's), if any.
    pub start: Option<grid::Cell>,
    /// A recording's map's frame and log time, which a run's `--mcap` keeps.
    pub recorded_at: Option<record::mcap_read::RecordedAt>,
}

impl Truth {
    /// This truth, for a command that reads only the sensor plane (`command`): off-plane
    /// clutter is an error there rather than silently ignored.
    pub fn plane_only(self, command: &str) -> Result<Truth> {
        if self.clutter.is_some() {
            bail!(
                "--clutter / --clutter-map: {command} reads only the sensor plane; off-plane \
                 clutter applies to explore"
            );
        }
        Ok(self)
    }
}

/// Parse `--memory-mb`: a positive number of MiB (a budget of 0 would refuse everything,
/// as `memory_mb=0` from Python is refused).
pub fn parse_memory_mb(s: &str) -> std::result::Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(0) => Err("expected a positive number of MiB, found 0".into()),
        Ok(v) => Ok(v),
        Err(_) if s.trim().starts_with('-') => {
            Err(format!("expected a positive number of MiB, found {s}"))
        }
        Err(_) => Err(format!(
            "expected a positive whole number of MiB (less than 2^64), found '{s}'"
        )),
    }
}

/// [`parse_memory_mb`] for a budget kept as a `usize`.
pub fn parse_memory_mb_usize(s: &str) -> std::result::Result<usize, String> {
    parse_memory_mb(s)
        .and_then(|v| usize::try_from(v).map_err(|_| format!("expected fewer MiB, found {v}")))
}

/// Parse "R" or "RX,RY" (metres per cell).
pub fn parse_resolution(s: &str) -> Result<(f64, f64)> {
    let parse = |p: &str| -> Result<f64> {
        let v: f64 = p.trim().parse().map_err(|_| anyhow::anyhow!("--resolution: expected a positive number of metres per cell (or RX,RY), found '{s}'"))?;
        if !grid::io::is_valid_resolution(v) {
            bail!(
                "--resolution: expected a positive number of metres per cell, at most {}, \
                 found '{s}'",
                grid::io::MAX_RESOLUTION_M
            );
        }
        Ok(v)
    };
    match s.split_once(',') {
        Some((x, y)) => Ok((parse(x)?, parse(y)?)),
        None => {
            let v = parse(s)?;
            Ok((v, v))
        }
    }
}

/// Parse a comma-separated list given to `flag`, each item trimmed and parsed by `item`;
/// an item's error is reported under the flag's name, and an item given twice is refused.
pub fn parse_list<T, E: std::fmt::Display>(
    s: &str,
    flag: &str,
    item: impl Fn(&str) -> std::result::Result<T, E>,
) -> Result<Vec<T>> {
    let items: Vec<&str> = s.split(',').map(str::trim).collect();
    for (i, x) in items.iter().enumerate() {
        if items[..i].contains(x) {
            // the same runs twice, with the same seeds: twice the time for the same numbers
            bail!("{flag}: expected each item once, found {x} twice in '{s}'");
        }
    }
    items
        .into_iter()
        .map(|x| item(x).map_err(|e| anyhow::anyhow!("{flag}: {e}")))
        .collect()
}

/// Parse "WxH" in metres.
pub fn parse_size(s: &str) -> Result<(f64, f64)> {
    let err = || anyhow::anyhow!("--size: expected WxH in metres (e.g. 25x20), found '{s}'");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
    let w: f64 = w.trim().parse().map_err(|_| err())?;
    let h: f64 = h.trim().parse().map_err(|_| err())?;
    if !(w.is_finite() && h.is_finite() && w > 0.0 && h > 0.0) {
        return Err(err());
    }
    Ok((w, h))
}

/// Parse "X,Y" (cells).
pub fn parse_cell(s: &str, flag: &str) -> Result<grid::Cell> {
    let err = || anyhow::anyhow!("{flag}: expected a cell X,Y (column, row), found '{s}'");
    let (x, y) = s.split_once(',').ok_or_else(err)?;
    Ok(grid::Cell::new(
        x.trim().parse().map_err(|_| err())?,
        y.trim().parse().map_err(|_| err())?,
    ))
}

impl MapSource {
    /// How a map file is read with these flags (`--resolution`, `--border`), within
    /// `memory_mb` MiB (the command's `--memory-mb`) and the memory available.
    pub fn load_options(&self, memory_mb: Option<u64>) -> Result<grid::io::LoadOptions> {
        let resolution = self
            .resolution
            .as_deref()
            .map(parse_resolution)
            .transpose()?;
        Ok(grid::io::LoadOptions {
            resolution,
            border: self.border,
            memory: sim::memory::limit(memory_mb, grid::machine::available()),
        })
    }

    /// Load the map file or generate the environment (`seed` is the default env seed),
    /// refusing one that would need more than `memory_mb` (the command's `--memory-mb`) or
    /// the memory available before it is loaded or generated.
    pub fn resolve(&self, seed: u64, memory_mb: Option<u64>) -> Result<Truth> {
        let resolution = self
            .resolution
            .as_deref()
            .map(parse_resolution)
            .transpose()?;
        if self.topic.is_some() && self.map.is_none() {
            bail!("--topic chooses the map topic of an MCAP recording (--map FILE.mcap)");
        }
        if let Some(path) = &self.map {
            if self.size.is_some() {
                bail!("--size applies to generated environments (--env), not to --map");
            }
            if self.env_seed.is_some() {
                bail!("--env-seed applies to generated environments (--env), not to --map");
            }
            let opts = self.load_options(memory_mb)?;
            let record::map_file::MapFile {
                map,
                start,
                recorded_at,
                ..
            } = load_map_file(path, &opts, self.topic.as_deref(), self.dungeon)?;
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "map".into());
            if self.clutter {
                bail!(
                    "--clutter furnishes generated environments (--env); for a map file give \
                     its off-plane obstacles with --clutter-map FILE"
                );
            }
            let clutter = self.load_clutter(&map, &opts)?;
            return Ok(Truth {
                name,
                map,
                clutter,
                start,
                recorded_at,
            });
        }
        if self.border {
            bail!("--border adds a wall around a --map, not to --env");
        }
        if self.dungeon {
            bail!("--dungeon reads --map as a dungeon PNG; it does not apply to --env");
        }
        let kind: EnvKind = self
            .env
            .as_deref()
            .unwrap_or("office")
            .parse()
            .map_err(|e| anyhow::anyhow!("--env: {e}"))?;
        let resolution = match resolution {
            Some((x, y)) if x != y => {
                bail!("--resolution: a generated environment has square cells; give one number")
            }
            Some((x, _)) => Some(x),
            None => None,
        };
        let spec = EnvSpec {
            kind,
            seed: self.env_seed.unwrap_or(seed),
            size_m: self.size.as_deref().map(parse_size).transpose()?,
            resolution,
        };
        bench::explore::check_generate_memory(&spec, memory_mb).map_err(anyhow::Error::msg)?;
        let env = generate(&spec)?;
        let opts = grid::io::LoadOptions {
            resolution: Some((env.map.resolution, env.map.resolution)),
            border: false,
            memory: sim::memory::limit(memory_mb, grid::machine::available()),
        };
        let clutter = if self.clutter {
            if env.rooms.is_none() {
                bail!("--clutter: {kind} has no rooms to furnish; use office or hospital");
            }
            let params = world::clutter::ClutterParams::default();
            Some(world::clutter::furnish(&env, spec.seed, &params))
        } else {
            self.load_clutter(&env.map, &opts)?
        };
        Ok(Truth {
            name: env.name.clone(),
            map: env.map,
            clutter,
            start: None,
            recorded_at: None,
        })
    }

    /// The --clutter-map layer for `map`, if given: its occupied cells, checked to be the
    /// map's size.
    fn load_clutter(
        &self,
        map: &GridMap,
        opts: &grid::io::LoadOptions,
    ) -> Result<Option<Grid<bool>>> {
        let Some(path) = &self.clutter_map else {
            return Ok(None);
        };
        let layer = load_layer("--clutter-map", path, map, opts)?;
        let cells = layer
            .cells
            .data()
            .iter()
            .map(|&c| c == Occ::Occupied)
            .collect();
        Ok(Grid::from_vec(map.width(), map.height(), cells))
    }
}

/// Load `path`, given by `flag`, as a layer of `map`: the same plan, so a bare bitmap
/// takes the map's cell size unless `opts` (the command's --resolution) gives one, and
/// the layer must have the map's size. Errors name the flag.
pub fn load_layer(
    flag: &str,
    path: &Path,
    map: &GridMap,
    opts: &grid::io::LoadOptions,
) -> Result<GridMap> {
    let mut opts = opts.clone();
    opts.resolution
        .get_or_insert((map.resolution, map.resolution));
    let layer = grid::io::load_map(path, &opts).with_context(|| flag.to_string())?;
    if (layer.width(), layer.height()) != (map.width(), map.height()) {
        bail!(
            "{flag} {}: expected the map's size {}x{} cells, found {}x{}",
            path.display(),
            map.width(),
            map.height(),
            layer.width(),
            layer.height()
        );
    }
    Ok(layer)
}

/// Check, before a run, that the file `flag` names can be written: its folder exists, it
/// is not itself a folder, and it opens for writing (a file that is there is left as it
/// is, one made for the test is removed), so that a long run does not end in an error
/// about its output.
pub fn check_output_file(flag: &str, path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!(
            "{flag} {}: expected a file name, found a folder",
            path.display()
        );
    }
    if let Some(folder) = grid::io::missing_folder(path) {
        let found = if folder.exists() {
            format!("{}, which is a file", folder.display())
        } else {
            format!("no folder {}", folder.display())
        };
        bail!(
            "{flag} {}: expected a file in an existing folder, found {found}",
            path.display()
        );
    }
    let existed = path.exists();
    // Through a symbolic link whose target is not there yet, the test makes the target:
    // that is the file to remove, not the link.
    let target = crate::files::written_at(path);
    match std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
    {
        Ok(_) if !existed => {
            let _ = std::fs::remove_file(target);
        }
        Ok(_) => {}
        Err(e) => bail!(
            "{flag} {}: expected a file that can be written, found {e}",
            path.display()
        ),
    }
    Ok(())
}

/// Refuse `dir` for the folder `flag` names if a file is there: checked before any work,
/// the folder itself made later ([`crate::files::make_output_folder`]), once the command's input is read.
pub fn check_output_folder(flag: &str, dir: &Path) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!("{flag} {}: expected a folder, found a file", dir.display());
    }
    Ok(())
}
