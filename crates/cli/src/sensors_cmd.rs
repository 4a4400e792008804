//! `frontier sensors`: Yamauchi's comparison of sensing set-ups on cluttered offices.
//!
//! Yamauchi (1997, §2.1) built his evidence grids with laser-limited sonar because sonar
//! alone suffers specular reflections (phantom open space, phantom frontiers) and a planar
//! laser alone misses tables and chairs. This command explores generated offices furnished
//! with such off-plane clutter ([`world::clutter`]) once per sensor and seed, and prints,
//! per sensor, the mean ± sd over seeds of map accuracy, phantom frontier regions, goals on
//! phantoms, the share of clutter mapped, coverage and path length ([`sim::MapAudit`]).

use crate::out::outln;
use anyhow::{Result, bail};
use clap::Args;
use explore::strategy::Strategy;
use rayon::prelude::*;
use sense::{BeliefKind, SensorSpec};
use serde_json::json;
use sim::{RunConfig, RunResult};
use world::clutter::{ClutterParams, furnish};
use world::{EnvKind, EnvSpec};

use crate::args::parse_size;
use crate::demo::mean_sd;

/// Flags of `frontier sensors`.
#[derive(Args, Clone, Debug)]
pub struct SensorsArgs {
    /// Sensors to compare, comma-separated (see `frontier list`).
    #[arg(long, default_value = "sonar,laser,laser-limited-sonar")]
    pub sensors: String,
    /// Environment kind with rooms to furnish: office or hospital.
    #[arg(long, default_value = "office")]
    pub env: String,
    /// Number of seeds (each a different environment, furniture and start).
    #[arg(allow_negative_numbers = true, long, default_value_t = 10)]
    pub seeds: u64,
    /// Strategy preset of every run.
    #[arg(long, default_value = "yamauchi")]
    pub strategy: String,
    /// Size of the environments in metres, "WxH" (default: the kind's).
    #[arg(allow_hyphen_values = true, long)]
    pub size: Option<String>,
    /// Metres per cell (sonar cones need cells well below their 10 ft range).
    #[arg(allow_negative_numbers = true, long, default_value_t = 0.1)]
    pub resolution: f64,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Refuse the comparison up front if its estimated memory (the furnished environments,
    /// the runs side by side and their results) exceeds this many MiB (the memory the
    /// machine has available is always checked).
    #[arg(allow_negative_numbers = true, long, value_parser = crate::args::parse_memory_mb)]
    pub memory_mb: Option<u64>,
}

/// Bytes a cell of a furnished environment held for the whole comparison: the map, its
/// rooms and the clutter layer.
const ENV_BYTES_PER_CELL: u64 = 8;
/// Bytes a cell of each run's result kept until the table is made (its belief and audit).
const RESULT_BYTES_PER_CELL: u64 = 4;

/// The sensor specs of a comma-separated list: a part with `=` and no `:` (`fov=180` of
/// `lidar:r=8,fov=180,res=1`) is a parameter of the spec before it, not a sensor.
fn sensor_list(s: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for part in s.split(',').map(str::trim) {
        match out.last_mut() {
            Some(last) if part.contains('=') && !part.contains(':') => {
                last.push(',');
                last.push_str(part);
            }
            _ => out.push(part.to_string()),
        }
    }
    out
}

/// Refuse a comparison whose environments, runs side by side (one per worker thread) and
/// results would need more than `--memory-mb` or the memory available, before any
/// environment is generated. A size the kind cannot take passes: generating it says why.
fn check_memory(
    a: &SensorsArgs,
    kind: EnvKind,
    size_m: Option<(f64, f64)>,
    strategy: &Strategy,
    sensors: &[SensorSpec],
) -> Result<()> {
    let spec = EnvSpec {
        kind,
        seed: 0,
        size_m,
        resolution: Some(a.resolution),
    };
    let Ok(cells) = spec.cells() else {
        return Ok(());
    };
    let runs = sensors.len() as u64 * a.seeds;
    let held = (ENV_BYTES_PER_CELL * a.seeds + RESULT_BYTES_PER_CELL * runs).saturating_mul(cells);
    let largest = sensors
        .iter()
        .map(|&sensor| {
            let mut cfg = RunConfig::new(strategy.clone());
            cfg.sensor = sensor;
            cfg.belief = BeliefKind::Evidence;
            sim::memory::run_bytes(
                usize::try_from(cells).unwrap_or(usize::MAX),
                a.resolution,
                &cfg,
            )
        })
        .max()
        .unwrap_or(0);
    let workers = rayon::current_num_threads().min(runs as usize).max(1) as u64;
    sim::memory::check(
        &format!(
            "comparing {} sensor{} on {} furnished {kind}{} of {cells} cells ({workers} \
             run{} at once)",
            sensors.len(),
            if sensors.len() == 1 { "" } else { "s" },
            a.seeds,
            if a.seeds == 1 { "" } else { "s" },
            if workers == 1 { "" } else { "s" },
        ),
        held.saturating_add(largest.saturating_mul(workers)),
        a.memory_mb,
        grid::machine::available(),
        "use fewer --seeds, a smaller --size or a coarser --resolution",
    )?;
    Ok(())
}

/// Run `frontier sensors`.
pub fn run(a: SensorsArgs) -> Result<()> {
    crate::demo::check_seeds(a.seeds)?;
    if !(a.resolution.is_finite() && a.resolution > 0.0) {
        bail!(
            "--resolution: expected a positive number of metres per cell, found {}",
            a.resolution
        );
    }
    let kind: EnvKind = a.env.parse().map_err(|e| anyhow::anyhow!("--env: {e}"))?;
    if !matches!(kind, EnvKind::Office | EnvKind::Hospital) {
        bail!("--env: expected a kind with rooms to furnish (office, hospital), found {kind}");
    }
    let strategy = Strategy::preset(&a.strategy).map_err(|e| anyhow::anyhow!("--strategy: {e}"))?;
    let names = sensor_list(&a.sensors);
    let sensors: Vec<SensorSpec> = names
        .iter()
        .map(|n| n.parse().map_err(|e| anyhow::anyhow!("--sensors: {e}")))
        .collect::<Result<_>>()?;
    if let Some(k) = (1..sensors.len()).find(|&k| sensors[..k].contains(&sensors[k])) {
        bail!(
            "--sensors: expected each sensor once, found {} twice",
            names[k]
        );
    }
    let size_m = a.size.as_deref().map(parse_size).transpose()?;
    check_memory(&a, kind, size_m, &strategy, &sensors)?;
    let envs: Vec<(world::Environment, grid::Grid<bool>)> = (0..a.seeds)
        .map(|seed| {
            // Through the CLI's rule: a size or resolution the kind cannot use is named by
            // its flag.
            let env = crate::args::generate(&EnvSpec {
                kind,
                seed,
                size_m,
                resolution: Some(a.resolution),
            })?;
            let clutter = furnish(&env, seed, &ClutterParams::default());
            Ok((env, clutter))
        })
        .collect::<Result<_>>()?;
    let jobs: Vec<(usize, u64)> = (0..sensors.len())
        .flat_map(|s| (0..a.seeds).map(move |seed| (s, seed)))
        .collect();
    eprintln!(
        "sensors: {} runs ({} sensors x {} furnished {kind}s), strategy {}",
        jobs.len(),
        sensors.len(),
        a.seeds,
        strategy.name
    );
    let results: Vec<Result<RunResult, sim::SimError>> = jobs
        .par_iter()
        .map(|&(s, seed)| {
            let (env, clutter) = &envs[seed as usize];
            let mut cfg = RunConfig::new(strategy.clone());
            cfg.sensor = sensors[s];
            cfg.belief = BeliefKind::Evidence;
            cfg.clutter = Some(clutter.clone());
            cfg.seed = seed;
            sim::run(&env.map, &cfg)
        })
        .collect();
    let mut by_sensor: Vec<Vec<RunResult>> = vec![Vec::new(); sensors.len()];
    for (&(s, _), r) in jobs.iter().zip(results) {
        by_sensor[s].push(r?);
    }
    let rows: Vec<Row> = by_sensor.iter().map(|rs| Row::of(rs)).collect();
    if a.json {
        let out: Vec<_> = names
            .iter()
            .zip(&sensors)
            .zip(&rows)
            .map(|((name, spec), row)| {
                json!({
                    "sensor": name,
                    "spec": spec.to_string(),
                    "runs": row.runs,
                    "complete": row.complete,
                    "accuracy": row.accuracy,
                    "phantom_regions_per_decision": row.phantom_regions,
                    "phantom_region_share": row.phantom_share,
                    "phantom_goals": row.phantom_goals,
                    "false_free_cells": row.false_free,
                    "clutter_mapped": row.clutter_mapped,
                    "coverage": row.coverage,
                    "path_length_m": row.path,
                })
            })
            .collect();
        outln!(
            "{}",
            serde_json::to_string_pretty(&json!({
                "env": kind.to_string(),
                "resolution": a.resolution,
                "strategy": strategy.name,
                "seeds": a.seeds,
                "sensors": out,
            }))?
        );
        return Ok(());
    }
    let pm = |(m, sd): (f64, f64), scale: f64, digits: usize| {
        format!("{:.digits$} ± {:.digits$}", m * scale, sd * scale)
    };
    outln!(
        "Furnished {kind}s at {} m per cell, strategy {}, evidence grid; mean ± sd over {} seeds\n",
        a.resolution,
        strategy.name,
        a.seeds
    );
    outln!(
        "{:<22}{:>14}{:>17}{:>17}{:>15}{:>15}{:>15}{:>14}{:>16}",
        "sensor",
        "map right %",
        "phantom regions",
        "phantom share %",
        "phantom goals",
        "phantom free",
        "clutter map %",
        "coverage %",
        "path m"
    );
    for (name, row) in names.iter().zip(&rows) {
        outln!(
            "{:<22}{:>14}{:>17}{:>17}{:>15}{:>15}{:>15}{:>14}{:>16}",
            name,
            pm(row.accuracy, 100.0, 1),
            pm(row.phantom_regions, 1.0, 2),
            pm(row.phantom_share, 100.0, 1),
            pm(row.phantom_goals, 1.0, 1),
            pm(row.false_free, 1.0, 0),
            pm(row.clutter_mapped, 100.0, 1),
            pm(row.coverage, 100.0, 1),
            pm(row.path, 1.0, 1),
        );
    }
    outln!(
        "\nphantom regions: frontier regions with a cell that is not free in truth, per \
         decision, and their share of all frontier regions; phantom goals: goals chosen on \
         such cells; phantom free: cells believed free at the end that are not (walls \
         erased, tables, outside)"
    );
    Ok(())
}

/// Means and standard deviations of one sensor's runs.
struct Row {
    runs: usize,
    complete: usize,
    accuracy: (f64, f64),
    phantom_regions: (f64, f64),
    phantom_share: (f64, f64),
    phantom_goals: (f64, f64),
    false_free: (f64, f64),
    clutter_mapped: (f64, f64),
    coverage: (f64, f64),
    path: (f64, f64),
}

impl Row {
    fn of(rs: &[RunResult]) -> Row {
        let stat = |f: &dyn Fn(&RunResult) -> f64| mean_sd(&rs.iter().map(f).collect::<Vec<_>>());
        Row {
            runs: rs.len(),
            complete: rs.iter().filter(|r| r.complete()).count(),
            accuracy: stat(&|r| r.audit.accuracy),
            phantom_regions: stat(&|r| r.audit.phantom_regions_mean(r.decisions)),
            phantom_share: stat(&|r| r.audit.phantom_share()),
            phantom_goals: stat(&|r| r.audit.phantom_goals as f64),
            false_free: stat(&|r| r.audit.false_free_cells as f64),
            clutter_mapped: stat(&|r| {
                if r.audit.clutter_cells == 0 {
                    0.0
                } else {
                    r.audit.clutter_mapped as f64 / r.audit.clutter_cells as f64
                }
            }),
            coverage: stat(&|r| r.coverage),
            path: stat(&|r| r.max_path_length_m()),
        }
    }
}
