//! `frontier env`: generate a built-in environment and write it.

use crate::out::outln;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use world::{EnvKind, EnvSpec};

use crate::args::{parse_resolution, parse_size};

/// Flags of `frontier env`.
#[derive(Args, Clone, Debug)]
pub struct EnvArgs {
    /// Kind of environment (office, hospital, cave, maze, potholes, empty).
    pub kind: Option<String>,
    /// List the kinds with their default sizes and resolutions.
    #[arg(long)]
    pub list: bool,
    /// Seed.
    #[arg(allow_negative_numbers = true, long, default_value_t = 0)]
    pub seed: u64,
    /// Size in metres, "WxH".
    #[arg(allow_hyphen_values = true, long)]
    pub size: Option<String>,
    /// Metres per cell.
    #[arg(allow_hyphen_values = true, long)]
    pub resolution: Option<String>,
    /// Output file: .png, .yaml (ROS map_server YAML + PGM beside it), .pgm, .map or .txt.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Print every kind with its defaults.
pub fn print_kinds() -> anyhow::Result<()> {
    for &kind in EnvKind::all() {
        let info = kind.info();
        outln!(
            "  {:<9} {:>5} m x {:<5} m at {:<5} m/cell  {}",
            kind.to_string(),
            info.size_m.0,
            info.size_m.1,
            info.resolution,
            info.description
        );
    }
    Ok(())
}

/// Run `frontier env`.
pub fn run(a: EnvArgs) -> Result<()> {
    if a.list {
        print_kinds()?;
        return Ok(());
    }
    let Some(kind) = a.kind.as_deref() else {
        bail!("give a kind (e.g. `frontier env office --out office.yaml`) or --list");
    };
    let kind: EnvKind = kind.parse().map_err(|e| anyhow::anyhow!("{e}"))?;
    let Some(out) = &a.out else {
        bail!("--out FILE is required (.png, .yaml, .pgm, .map or .txt)")
    };
    let mut files = crate::files::Files::new();
    files.writes("--out", out)?;
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if matches!(ext.as_deref(), Some("yaml" | "yml")) {
        // The image beside it.
        files.writes("--out", &out.with_extension("pgm"))?;
    }
    let resolution = match a.resolution.as_deref().map(parse_resolution).transpose()? {
        Some((x, y)) if x != y => bail!("--resolution: give one number (cells are square)"),
        r => r.map(|r| r.0),
    };
    let spec = EnvSpec {
        kind,
        seed: a.seed,
        size_m: a.size.as_deref().map(parse_size).transpose()?,
        resolution,
    };
    bench::explore::check_generate_memory(&spec, None).map_err(anyhow::Error::msg)?;
    let env = crate::args::generate(&spec)?;
    grid::io::save_map(&env.map, out).context("--out")?;
    let (free, occ, unk) = env.map.counts();
    outln!(
        "{}: {}x{} cells at {} m ({} free, {} occupied, {} unknown{}) written to {}",
        env.name,
        env.map.width(),
        env.map.height(),
        env.map.resolution,
        free,
        occ,
        unk,
        if env.room_count > 0 {
            format!(", {} rooms", env.room_count)
        } else {
            String::new()
        },
        out.display()
    );
    Ok(())
}
