//! `frontier map info`: what a map file holds.

use crate::out::outln;
use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;
use grid::Occ;
use grid::components::{Connectivity, label};
use serde_json::json;

use crate::args::parse_resolution;

/// Subcommands of `frontier map`.
#[derive(Subcommand, Clone, Debug)]
pub enum MapCommand {
    /// Size, resolution, cell counts and free connected components of a map file.
    Info {
        /// The map file (.yaml, .pgm, .png, .map, .txt, HouseExpo .json, or .mcap: its last
        /// OccupancyGrid).
        file: PathBuf,
        /// Metres per cell ("R" or "RX,RY"): needed for bare bitmaps, .json and --dungeon
        /// maps, 1 if not given for .map and .txt, and overriding a ROS YAML's own.
        #[arg(allow_hyphen_values = true, long)]
        resolution: Option<String>,
        /// Add a wall one cell thick around the map (any file but an MCAP recording; the
        /// origin and a dungeon's marked start move with the cells).
        #[arg(long)]
        border: bool,
        /// The OccupancyGrid topic of an MCAP file (default: its only one, or /map).
        #[arg(long)]
        topic: Option<String>,
        /// Read the file as a dungeon PNG (pixels of value 208 mark the start, which is
        /// printed too); needs --resolution.
        #[arg(long)]
        dungeon: bool,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Refuse the file up front if the estimated memory of its loading exceeds this many
        /// MiB, before it is loaded (the memory the machine has available is always checked).
        #[arg(allow_negative_numbers = true, long, value_parser = crate::args::parse_memory_mb)]
        memory_mb: Option<u64>,
    },
}

/// Run `frontier map ...`.
pub fn run(cmd: MapCommand) -> Result<()> {
    let MapCommand::Info {
        file,
        resolution,
        border,
        topic,
        dungeon,
        json,
        memory_mb,
    } = cmd;
    let resolution = resolution.as_deref().map(parse_resolution).transpose()?;
    let record::map_file::MapFile {
        map,
        start,
        topic,
        recorded_at,
    } = crate::args::load_map_file(
        &file,
        &grid::io::LoadOptions {
            resolution,
            border,
            memory: sim::memory::limit(memory_mb, grid::machine::available()),
        },
        topic.as_deref(),
        dungeon,
    )?;
    let (free, occupied, unknown) = map.counts();
    let cells = &map.cells;
    // Beside the map (a byte a cell): the labels (4 bytes a cell) and one 8-byte entry
    // per run of free cells in a row (at most one per two cells).
    sim::memory::check(
        &format!(
            "counting the free components of this {}x{} map",
            map.width(),
            map.height()
        ),
        sim::memory::BASE_BYTES.saturating_add(9u64.saturating_mul(cells.len() as u64)),
        memory_mb,
        grid::machine::available(),
        "use a map with fewer, larger cells",
    )?;
    let (_, components) = label(
        cells.width(),
        cells.height(),
        |i| cells[i] == Occ::Free,
        Connectivity::Motion,
    );
    let (w, h) = (map.width(), map.height());
    if json {
        let v = json!({
            "file": file.display().to_string(),
            "width": w, "height": h,
            "resolution": map.resolution,
            "width_m": metres(w, map.resolution), "height_m": metres(h, map.resolution),
            "origin": map.origin,
            "free": free, "occupied": occupied, "unknown": unknown,
            "free_components": components,
            "start": start.map(|c| [c.x, c.y]),
            "topic": topic,
            "frame_id": recorded_at.as_ref().map(|r| r.frame_id.clone()),
            "log_time_ns": recorded_at.as_ref().map(|r| r.log_time),
        });
        outln!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        outln!("{}", file.display());
        if let Some(topic) = &topic {
            outln!("  topic       {topic} (its last map)");
        }
        if let Some(r) = &recorded_at {
            outln!(
                "  recorded    in frame {} at log time {} ns (a run's --mcap keeps both)",
                r.frame_id,
                r.log_time
            );
        }
        // To the centimetre; a size below one (a resolution of 1e-9 m) as it is, not 0.00.
        let metres = |cells: usize| {
            let m = cells as f64 * map.resolution;
            if m >= 0.01 {
                format!("{m:.2}")
            } else {
                grid::Num(m).to_string()
            }
        };
        outln!(
            "  size        {w} x {h} cells, {} m x {} m",
            metres(w),
            metres(h)
        );
        outln!(
            "  resolution  {} m/cell, origin [{}, {}, {}]",
            grid::Num(map.resolution),
            map.origin[0],
            map.origin[1],
            map.origin[2]
        );
        outln!("  cells       {free} free, {occupied} occupied, {unknown} unknown");
        outln!(
            "  free space  {components} connected component(s) (8-connected, no corner squeezing)"
        );
        if let Some(c) = start {
            outln!("  start       {},{} (the file's mark)", c.x, c.y);
        }
    }
    Ok(())
}

/// `cells` cells of `resolution` metres, in metres to the nanometre: the product's float
/// error (604 × 0.05 = 30.200000000000003) is not the map's.
fn metres(cells: usize, resolution: f64) -> f64 {
    (cells as f64 * resolution * 1e9).round() / 1e9
}
