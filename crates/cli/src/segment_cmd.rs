//! `frontier segment`: segment a map into rooms (Holz et al. 2010, Figure 7), draw the
//! segments and, with ground-truth rooms, score them.
//!
//! Ground truth comes from a generated office or hospital (its room labels), a HouseExpo
//! plan (its room boxes), or `--truth FILE`: the same floor plan with every doorway drawn
//! closed, so that each room is one connected free region (the convention of public
//! room-segmentation datasets).

use crate::out::outln;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use explore::segment::score::{RoomScores, score};
use explore::segment::{NONE, Rule, Segmentation, segment};
use grid::components::{Connectivity, label};
use grid::{Grid, GridMap, Occ};
use serde_json::json;
use viz::Picture;
use world::{EnvKind, EnvSpec};

use crate::args::{MapSource, parse_resolution, parse_size};

/// Flags of `frontier segment`.
#[derive(Args, Clone, Debug)]
pub struct SegmentArgs {
    /// The map to segment.
    #[command(flatten)]
    pub source: MapSource,
    /// Seed of a generated environment (when --env-seed is not given).
    #[arg(allow_negative_numbers = true, long, default_value_t = 0)]
    pub seed: u64,
    /// Critical-point rule: holz (relaxed, default), wurm (adjacent to a junction) or
    /// thrun (every local minimum).
    #[arg(long, default_value = "holz")]
    pub rule: String,
    /// Ground-truth rooms: the same floor plan with every doorway closed (same size and
    /// format options as --map).
    #[arg(long)]
    pub truth: Option<PathBuf>,
    /// Write a picture of the segments (PNG).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Refuse up front if the estimated memory exceeds this many MiB, and a --map or --truth
    /// whose loading would, before it is loaded (the memory the machine has available is
    /// always checked).
    #[arg(allow_negative_numbers = true, long, value_parser = crate::args::parse_memory_mb)]
    pub memory_mb: Option<u64>,
}

/// Peak bytes per map cell of segmenting, an upper bound: the distance transform, the
/// skeleton, the graph and seed labels, region labels, the picture and ground-truth labels.
/// Measured peaks: 36 B/cell on the 1165 x 945 willow-full plan and on a 4000 x 4000
/// generated office (584 MiB), both with the map and picture included.
const SEGMENT_BYTES_PER_CELL: u64 = 48;

/// Estimated peak bytes of segmenting a map of `cells` cells.
fn segment_bytes(cells: usize) -> u64 {
    sim::memory::BASE_BYTES + SEGMENT_BYTES_PER_CELL.saturating_mul(cells as u64)
}

/// Refuse ground-truth rooms that share no cell with the segmented free space, and warn
/// when they cover less than half of it: the scores count only the common cells, so a truth
/// of another plan (of the map's size) or one free cell scored F1 1 and ARI 1.
fn check_rooms_cover(labels: &[u32], rooms: &[u32], truth: Option<&std::path::Path>) -> Result<()> {
    let free = labels.iter().filter(|&&l| l != NONE).count();
    let common = labels
        .iter()
        .zip(rooms)
        .filter(|&(&l, &r)| l != NONE && r != 0)
        .count();
    let source = truth.map_or_else(
        || "the rooms".to_string(),
        |t| format!("--truth {}", t.display()),
    );
    if free > 0 && common == 0 {
        bail!(
            "{source}: expected rooms that cover the map's free cells, found none of its {free} \
             free cells in a room"
        );
    }
    if 2 * common < free {
        eprintln!(
            "warning: {source}: its rooms cover {common} of the map's {free} free cells; the \
             scores count only those"
        );
    }
    Ok(())
}

/// Run `frontier segment`.
pub fn run(a: SegmentArgs) -> Result<()> {
    let rule: Rule = a
        .rule
        .parse()
        .map_err(|e: String| anyhow::anyhow!("--rule: {e}"))?;
    if a.truth.is_some() && a.source.map.is_none() {
        bail!("--truth goes with --map; a generated office or hospital has its own rooms");
    }
    let mut files = crate::files::Files::new();
    files.reads_source(&a.source);
    if let Some(truth) = &a.truth {
        files.reads_map("--truth", truth);
    }
    if let Some(out) = &a.out {
        files.writes_as("--out", out, &["png"], "a PNG picture")?;
    }
    let truth = a
        .source
        .resolve(a.seed, a.memory_mb)?
        .plane_only("segment")?;
    let (w, h) = (truth.map.width(), truth.map.height());
    sim::memory::check(
        &format!("segmenting this {w}x{h} map"),
        segment_bytes(w * h),
        a.memory_mb,
        grid::machine::available(),
        "use a map with fewer, larger cells (scale the image down and raise its resolution)",
    )?;
    let rooms = match (&a.truth, &a.source.map) {
        (Some(path), _) => Some(truth_rooms(path, &a.source, &truth.map, a.memory_mb)?),
        (None, None) => generated_rooms(&a.source, a.seed)?,
        (None, Some(path)) if is_houseexpo(path) => houseexpo_rooms(path, &a.source, a.memory_mb)?,
        (None, Some(_)) => None,
    };
    let seg = segment(&truth.map.cells, rule);
    if let Some(r) = &rooms {
        check_rooms_cover(&seg.labels, r.data(), a.truth.as_deref())?;
    }
    let scores = rooms.as_ref().map(|r| score(&seg.labels, r.data()));
    if let Some(out) = &a.out {
        picture(&truth.map, &seg)
            .save(out)
            .with_context(|| format!("writing {}", out.display()))?;
    }
    if a.json {
        let s = scores.map(|s| {
            json!({
                "precision": s.precision, "recall": s.recall, "f1": s.f1, "ari": s.ari,
                "segments_scored": s.segments, "rooms": s.rooms, "matched": s.matched,
            })
        });
        let v = json!({
            "map": truth.name,
            "rule": rule.name(),
            "segments": seg.count,
            "critical_points": seg.critical.len(),
            "scores": s,
        });
        outln!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        outln!(
            "{}: {} segments ({} critical points, rule {})",
            truth.name,
            seg.count,
            seg.critical.len(),
            rule.name()
        );
        if let Some(s) = scores {
            print_scores(&s)?;
        }
    }
    Ok(())
}

fn print_scores(s: &RoomScores) -> anyhow::Result<()> {
    outln!(
        "  rooms {}, recovered {} (overlap >= 80 % both ways)",
        s.rooms,
        s.matched
    );
    outln!(
        "  precision {:.3}  recall {:.3}  F1 {:.3}  ARI {:.3}",
        s.precision,
        s.recall,
        s.f1,
        s.ari
    );
    Ok(())
}

/// The room labels of a generated office or hospital; `None` for kinds without rooms.
fn generated_rooms(source: &MapSource, seed: u64) -> Result<Option<Grid<u32>>> {
    let kind: EnvKind = source
        .env
        .as_deref()
        .unwrap_or("office")
        .parse()
        .map_err(|e| anyhow::anyhow!("--env: {e}"))?;
    let resolution = source
        .resolution
        .as_deref()
        .map(parse_resolution)
        .transpose()?
        .map(|r| r.0);
    let spec = EnvSpec {
        kind,
        seed: source.env_seed.unwrap_or(seed),
        size_m: source.size.as_deref().map(parse_size).transpose()?,
        resolution,
    };
    let env = crate::args::generate(&spec)?;
    Ok(env.rooms)
}

/// Whether `path` names a HouseExpo plan (`.json`), whose room boxes are its ground truth.
fn is_houseexpo(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// The rooms of a HouseExpo plan, numbered 1, 2, … in the order of its room boxes, 0
/// outside every box; `None` for a plan without room boxes.
fn houseexpo_rooms(
    path: &std::path::Path,
    source: &MapSource,
    memory_mb: Option<u64>,
) -> Result<Option<Grid<u32>>> {
    let plan = grid::io::load_houseexpo(path, &source.load_options(memory_mb)?)?;
    if plan.room_types.is_empty() {
        return Ok(None);
    }
    let (w, h) = (plan.map.width(), plan.map.height());
    // One label per cell of the map, as the reader makes them.
    Ok(Grid::from_vec(w, h, plan.rooms))
}

/// Room labels from a ground-truth floor plan (loaded within `memory_mb`, the command's
/// `--memory-mb`): its free components, numbered from 1.
fn truth_rooms(
    path: &std::path::Path,
    source: &MapSource,
    map: &GridMap,
    memory_mb: Option<u64>,
) -> Result<Grid<u32>> {
    let t = crate::args::load_layer("--truth", path, map, &source.load_options(memory_mb)?)?;
    let cells = &t.cells;
    // components numbered 1..=count, 0 outside
    let (labels, _) = label(
        cells.width(),
        cells.height(),
        |i| cells[i] == Occ::Free,
        Connectivity::Motion,
    );
    Ok(labels)
}

/// A distinct, deterministic colour per segment.
fn colour(label: u32) -> [u8; 3] {
    // golden-ratio hue steps, moderate saturation
    let h = (f64::from(label) * 0.618_033_988_749_895).fract() * 6.0;
    let (s, v) = (0.55, 0.95);
    let c = v * s;
    let x = c * (1.0 - ((h % 2.0) - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = v - c;
    let to = |u: f64| ((u + m) * 255.0).round() as u8;
    [to(r), to(g), to(b)]
}

/// The segments in colour over the map, critical points in red.
fn picture(map: &GridMap, seg: &Segmentation) -> Picture {
    let (w, h) = (map.width(), map.height());
    let s = viz::scale_for(w, h);
    let mut img = Picture::new(w as u32 * s, h as u32 * s);
    let mut critical = vec![false; w * h];
    for cp in &seg.critical {
        critical[cp.cell as usize] = true;
    }
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let px = if critical[i] {
                [220, 20, 20]
            } else if seg.labels[i] != NONE {
                colour(seg.labels[i])
            } else {
                match map.cells[i] {
                    Occ::Occupied => [25, 25, 25],
                    _ => [205, 205, 205],
                }
            };
            for dy in 0..s {
                for dx in 0..s {
                    img.put_pixel(x as u32 * s + dx, y as u32 * s + dy, px);
                }
            }
        }
    }
    img
}
