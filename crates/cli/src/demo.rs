//! `frontier demo`: what frontier is for, on built-in environments with no files needed.
//!
//! Explores generated office, hospital and cave environments with every single-robot
//! preset over a handful of seeds (each seed a different environment and start), prints
//! the mean ± sd path length per strategy — the form of Holz et al.'s Tables 1–3 — and
//! writes one picture per environment and strategy.

use crate::out::{out, outln};
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use explore::strategy::Strategy;
use rayon::prelude::*;
use sense::SensorSpec;
use sim::{RunConfig, RunResult};
use world::{EnvKind, EnvSpec};

use crate::args::parse_list;

/// Flags of `frontier demo`.
#[derive(Args, Clone, Debug)]
pub struct DemoArgs {
    /// Number of seeds per environment and strategy (Holz et al. ran 10).
    #[arg(allow_negative_numbers = true, long, default_value_t = 10)]
    pub seeds: u64,
    /// Environments, comma-separated.
    #[arg(long, default_value = "office,hospital,cave")]
    pub envs: String,
    /// Strategies, comma-separated.
    #[arg(long, default_value = "random,cf,cf-rr,yamauchi")]
    pub strategies: String,
    /// Sensor of every run.
    #[arg(long, default_value = "los:r=5")]
    pub sensor: String,
    /// Directory for the pictures.
    #[arg(long, default_value = "demo-out")]
    pub out: PathBuf,
}

struct Job {
    env: usize,
    strategy: usize,
    seed: u64,
}

/// Mean and sample standard deviation.
pub fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
    } else {
        0.0
    };
    (mean, var.sqrt())
}

/// The most seeds `demo` and `sensors` take: they generate every environment before the
/// first run, so a mistyped count (`--seeds 4294967296`) would fill the memory; larger
/// studies belong in `frontier bench`, which plans and checks them first.
pub const MAX_SEEDS: u64 = 1000;

/// Refuse a seed count of 0 or over [`MAX_SEEDS`].
pub fn check_seeds(seeds: u64) -> Result<()> {
    if !(1..=MAX_SEEDS).contains(&seeds) {
        bail!(
            "--seeds: expected 1 to {MAX_SEEDS} (a larger study is a scenario for `frontier \
             bench`), found {seeds}"
        );
    }
    Ok(())
}

/// Run `frontier demo`.
pub fn run(a: DemoArgs) -> Result<()> {
    check_seeds(a.seeds)?;
    crate::args::check_output_folder("--out", &a.out)?;
    let kinds: Vec<EnvKind> = parse_list(&a.envs, "--envs", str::parse)?;
    let strategies = parse_list(&a.strategies, "--strategies", Strategy::preset)?;
    let sensor: SensorSpec = a
        .sensor
        .parse()
        .map_err(|e| anyhow::anyhow!("--sensor: {e}"))?;
    if sensor.sonar_mode().is_some() {
        bail!(
            "--sensor: expected a range sensor the demo's known grid can take, found {sensor} \
             (a sonar ring needs the evidence grid: `frontier explore --belief evidence`, or \
             `frontier sensors`)"
        );
    }
    // Made once every flag is read: a refused command leaves no folder behind.
    let _folder = crate::files::make_output_folder("--out", &a.out)?;
    // One environment per (kind, seed), shared by all strategies.
    let envs: Vec<Vec<world::Environment>> = kinds
        .iter()
        .map(|&kind| {
            (0..a.seeds)
                .map(|seed| {
                    world::generate(&EnvSpec {
                        kind,
                        seed,
                        size_m: None,
                        resolution: None,
                    })
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<_, _>>()?;
    let jobs: Vec<Job> = (0..kinds.len())
        .flat_map(|env| {
            (0..strategies.len()).flat_map(move |strategy| {
                (0..a.seeds).map(move |seed| Job {
                    env,
                    strategy,
                    seed,
                })
            })
        })
        .collect();
    eprintln!(
        "demo: {} runs ({} environments x {} strategies x {} seeds), sensor {sensor}",
        jobs.len(),
        kinds.len(),
        strategies.len(),
        a.seeds
    );
    let started = std::time::Instant::now();
    let results: Vec<Result<RunResult, sim::SimError>> = jobs
        .par_iter()
        .map(|job| {
            let mut cfg = RunConfig::new(strategies[job.strategy].clone());
            cfg.sensor = sensor;
            cfg.seed = job.seed;
            cfg.record_trace = job.seed == 0;
            sim::run(&envs[job.env][job.seed as usize].map, &cfg)
        })
        .collect();
    let elapsed = started.elapsed().as_secs_f64();

    let mut incomplete = Vec::new();
    let mut table = String::new();
    table += &format!(
        "Path length (m), mean ± sd over {} seeds; sensor {sensor}\n\n",
        a.seeds
    );
    table += &format!("{:<10}", "");
    for s in &strategies {
        table += &format!("{:>18}", s.name);
    }
    table += "\n";
    for (e, kind) in kinds.iter().enumerate() {
        let info = &envs[e][0];
        table += &format!("{:<10}", kind.to_string());
        for (s, strategy) in strategies.iter().enumerate() {
            let mut lengths = Vec::new();
            for (job, result) in jobs.iter().zip(&results) {
                if job.env != e || job.strategy != s {
                    continue;
                }
                let r = result
                    .as_ref()
                    .map_err(|err| anyhow::anyhow!("{kind} seed {}: {err}", job.seed))?;
                if !r.complete() {
                    incomplete.push(format!(
                        "{kind} seed {} {}: {} ({:.1} %)",
                        job.seed,
                        strategy.name,
                        r.reason.as_str(),
                        r.coverage * 100.0
                    ));
                }
                lengths.push(r.path_length_m[0]);
                if job.seed == 0 {
                    let path = a.out.join(format!("{kind}-{}.png", strategy.name));
                    viz::final_picture(&envs[e][0].map, r)
                        .save(&path)
                        .with_context(|| format!("writing {}", path.display()))?;
                }
            }
            let (m, sd) = mean_sd(&lengths);
            table += &format!("{:>18}", format!("{m:.1} ± {sd:.1}"));
        }
        table += &format!(
            "   ({}x{} cells at {} m)\n",
            info.map.width(),
            info.map.height(),
            info.map.resolution
        );
    }
    out!("{table}");
    if incomplete.is_empty() {
        outln!("\nall {} runs explored everything reachable", jobs.len());
    } else {
        outln!("\n{} runs did not finish:", incomplete.len());
        for line in &incomplete {
            outln!("  {line}");
        }
    }
    std::fs::write(a.out.join("table.txt"), &table)
        .with_context(|| format!("writing {}", a.out.join("table.txt").display()))?;
    outln!(
        "pictures of seed 0 in {}/ · {:.1} s wall time",
        a.out.display(),
        elapsed
    );
    Ok(())
}
