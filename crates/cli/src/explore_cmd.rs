//! `frontier explore`: one run, a summary or JSON, pictures and a trace.

use crate::out::{out, outln};
use grid::memory::Available;
use std::io::Write;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use sim::RunConfig;

use crate::args::{MapSource, Truth, parse_cell};
use crate::report;

/// Flags of `frontier explore`.
#[derive(Args, Clone, Debug)]
pub struct ExploreArgs {
    #[command(flatten)]
    pub source: MapSource,
    /// Master seed: start cell, random choices (and the environment, unless --env-seed).
    #[arg(allow_negative_numbers = true, long, default_value_t = 0)]
    pub seed: u64,
    /// Start cell "X,Y" (column, row; row 0 at the top); default: a free cell chosen by seed.
    #[arg(allow_hyphen_values = true, long)]
    pub start: Option<String>,
    /// Strategy preset (see `frontier list`).
    #[arg(long, default_value = "cf-rr")]
    pub strategy: String,
    /// Sensor, e.g. los:r=5, footprint:r=3, lidar:r=8,fov=180,res=1 (metres; cells with suffix c).
    #[arg(long, default_value = "los:r=5")]
    pub sensor: String,
    /// Belief map: known, reflection, evidence (default: known; evidence with sonar).
    #[arg(long)]
    pub belief: Option<String>,
    /// Sensing mode: continuous, on-arrival, or every-N (a scan at every N-th cell, at goals
    /// and where the robot decides; Explore-Bench: every-3) (default: the strategy's).
    #[arg(long)]
    pub sensing: Option<String>,
    /// Robot clearance from known obstacles in metres (Holz's d_max).
    #[arg(allow_negative_numbers = true, long, default_value_t = 0.0)]
    pub clearance: f64,
    /// Speed in metres per second.
    #[arg(allow_negative_numbers = true, long, default_value_t = 1.0)]
    pub speed: f64,
    /// How path length is measured: `grid` (cell moves, 1 or √2) or `any-angle` (the route
    /// string-pulled through traversable cells, like a robot with smooth controllers).
    #[arg(long, default_value = "grid")]
    pub motion: String,
    /// Number of robots.
    #[arg(allow_negative_numbers = true, long, default_value_t = 1)]
    pub robots: usize,
    /// Re-plan every this many cell moves (Faigl & Kulich's s_max; -1 = on arrival only);
    /// default: the strategy's. Not for random and dt*, which draw their goals at random.
    #[arg(long, allow_negative_numbers = true)]
    pub s_max: Option<i64>,
    /// Stop at this coverage (0..1]; default: explore everything reachable.
    #[arg(allow_negative_numbers = true, long)]
    pub goal: Option<f64>,
    /// What coverage counts: `reachable` (known free among the reachable free cells) or
    /// `known` (Explore-Bench: known free or occupied among the cells the map knows).
    #[arg(long)]
    pub coverage: Option<String>,
    /// Stop after this many cell moves of the whole team.
    #[arg(allow_negative_numbers = true, long, default_value_t = 10_000_000)]
    pub max_moves: u64,
    /// Write final.png, map.png, belief.yaml + belief.pgm (the map built, ROS format) and trace.json into this directory.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write an animated GIF of the run.
    #[arg(long)]
    pub gif: Option<PathBuf>,
    /// Write a self-contained HTML page that replays the run (opens from a file, no network).
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// Write the run as an MCAP recording (map, belief over time, poses, goals, frontiers;
    /// ROS 2 messages that Foxglove Studio opens).
    #[arg(long)]
    pub mcap: Option<PathBuf>,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Leave wall-clock timings out of the JSON (null), so that equal runs print equal bytes.
    #[arg(long)]
    pub no_timing: bool,
    /// Refuse the run up front if its estimated memory exceeds this many MiB, and a --map
    /// whose loading would, before it is loaded (the memory the machine has available is
    /// always checked).
    #[arg(allow_negative_numbers = true, long, value_parser = crate::args::parse_memory_mb)]
    pub memory_mb: Option<u64>,
    /// Never draw the progress bar (drawn on a terminal for runs longer than a second).
    #[arg(long)]
    pub no_progress: bool,
}

/// Resolve flags into a run configuration (everything but the map), checked against the
/// memory it may spend, and the limit that caps its trace when it records one.
pub fn config(a: &ExploreArgs, truth: &Truth) -> Result<(RunConfig, Option<Available>)> {
    let start = a
        .start
        .as_deref()
        .map(|s| parse_cell(s, "--start"))
        .transpose()?;
    let mut opts = bench::explore::ExploreOptions {
        seed: a.seed,
        start,
        start_marked: false,
        strategy: a.strategy.clone(),
        sensor: a.sensor.clone(),
        belief: a.belief.clone(),
        sensing: a.sensing.clone(),
        clearance: a.clearance,
        speed: a.speed,
        robots: a.robots,
        s_max: a.s_max,
        goal: a.goal,
        coverage: a.coverage.clone(),
        max_moves: a.max_moves,
        record_trace: a.out.is_some() || a.gif.is_some() || a.html.is_some() || a.mcap.is_some(),
        motion: Some(a.motion.clone()),
    };
    opts.or_marked_start(truth.start);
    let mut cfg = bench::explore::config(&opts, &truth.map, truth.clutter.clone())
        .map_err(anyhow::Error::msg)?;
    let limit =
        bench::explore::check_memory_with(&mut cfg, &truth.map, a.memory_mb, a.html.is_some())
            .map_err(anyhow::Error::msg)?;
    Ok((cfg, limit))
}

/// Steps of the loop between two looks at the clock.
const PROGRESS_STEPS: u64 = 256;
/// A run shorter than this draws no bar.
const PROGRESS_AFTER: Duration = Duration::from_secs(1);
/// The bar is redrawn at most this often.
const PROGRESS_EVERY: Duration = Duration::from_millis(100);

/// Run the exploration; with `progress`, a run that lasts longer than [`PROGRESS_AFTER`]
/// shows its coverage, moves and path on standard error until it ends (the run is the same
/// either way: the loop only pauses between its steps).
fn run_with_progress(truth: &Truth, cfg: &RunConfig, progress: bool) -> Result<sim::RunResult> {
    let steps = if progress { PROGRESS_STEPS } else { u64::MAX };
    let started = Instant::now();
    let mut bar: Option<(ProgressBar, Instant)> = None;
    let result = sim::run_pausing(&truth.map, cfg, None, steps, |session| {
        let now = Instant::now();
        if now.duration_since(started) < PROGRESS_AFTER
            || bar
                .as_ref()
                .is_some_and(|(_, at)| now.duration_since(*at) < PROGRESS_EVERY)
        {
            return true;
        }
        let (b, at) = bar.get_or_insert_with(|| (progress_bar(now - started), now));
        *at = now;
        let coverage = session.coverage();
        b.set_position((coverage * 1000.0).round() as u64);
        b.set_message(format!(
            "{:.1} % covered · {} moves · {:.1} m",
            100.0 * coverage,
            session.moves(),
            session.total_path_length_m()
        ));
        true
    })?;
    if let Some((b, _)) = bar {
        b.finish_and_clear();
    }
    result.context("internal error: the run stopped before its end")
}

/// The bar of a run `elapsed` old: coverage in per mille.
fn progress_bar(elapsed: Duration) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr())
        .with_elapsed(elapsed);
    if let Ok(style) = ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {msg}") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// The files `--out` writes.
const OUT_FILES: [&str; 5] = [
    "final.png",
    "map.png",
    "belief.yaml",
    "belief.pgm",
    "trace.json",
];

/// Run `frontier explore`.
pub fn run(a: ExploreArgs) -> Result<()> {
    let mut files = crate::files::Files::new();
    files.reads_source(&a.source);
    if let Some(dir) = &a.out {
        files.writes_into("--out", dir, &OUT_FILES)?;
    }
    let outputs = [
        ("--gif", &a.gif, &["gif"][..], "a GIF animation"),
        ("--html", &a.html, &["html", "htm"][..], "an HTML page"),
        ("--mcap", &a.mcap, &["mcap"][..], "an MCAP recording"),
    ];
    for (flag, path, exts, what) in outputs {
        if let Some(path) = path {
            files.writes_as(flag, path, exts, what)?;
        }
    }
    let truth = a.source.resolve(a.seed, a.memory_mb)?;
    let (cfg, trace_limit) = config(&a, &truth)?;
    // Once the map and every flag are read and before the run: a folder that cannot be
    // made fails before a long run, and one made is removed again if the run fails.
    let _folder = match &a.out {
        Some(dir) => Some(crate::files::make_output_folder("--out", dir)?),
        None => None,
    };
    let result = run_with_progress(
        &truth,
        &cfg,
        !a.no_progress && bench::runner::progress_wanted(),
    )?;
    if let Some(dir) = &a.out {
        let png = dir.join("final.png");
        viz::final_picture(&truth.map, &result)
            .save(&png)
            .with_context(|| format!("writing {}", png.display()))?;
        let map_png = dir.join("map.png");
        viz::map_picture(&truth.map.cells)
            .save(&map_png)
            .with_context(|| format!("writing {}", map_png.display()))?;
        let belief = dir.join("belief.yaml");
        let built = grid::GridMap {
            cells: result.belief.clone(),
            resolution: truth.map.resolution,
            origin: truth.map.origin,
        };
        grid::io::save_map(&built, &belief)
            .with_context(|| format!("writing {}", belief.display()))?;
        let trace = dir.join("trace.json");
        crate::files::write_whole(&trace, |file| {
            let mut w = std::io::BufWriter::new(file);
            report::write_trace_json(&mut w, &truth, &cfg, &result)?;
            Ok(w.flush()?)
        })
        .with_context(|| format!("writing {}", trace.display()))?;
    }
    if let Some(path) = &a.gif {
        let bytes =
            viz::animate::animate_gif(&truth.map, &result, &viz::animate::GifOptions::default())?;
        crate::files::write_whole(path, |mut file| Ok(file.write_all(&bytes)?))
            .with_context(|| format!("--gif {}: writing", path.display()))?;
    }
    if let Some(path) = &a.html {
        let meta = format!(
            "{} · {} robot(s) · sensor {} ({}) · seed {} · {}x{} cells at {} m",
            cfg.strategy.name,
            cfg.robots,
            cfg.sensor,
            cfg.sensing_mode(),
            cfg.seed,
            truth.map.width(),
            truth.map.height(),
            truth.map.resolution
        );
        let page = viz::replay::replay_html(&truth.map, &result, &truth.name, &meta)?;
        crate::files::write_whole(path, |mut file| Ok(file.write_all(page.as_bytes())?))
            .with_context(|| format!("--html {}: writing", path.display()))?;
    }
    if let Some(path) = &a.mcap {
        crate::files::write_whole(path, |file| {
            let w = std::io::BufWriter::new(file);
            crate::mcap_out::write_run(w, &truth.map, truth.recorded_at.as_ref(), &cfg, &result)
        })
        .with_context(|| format!("--mcap {}: writing", path.display()))?;
    }
    if let Some(limit) = trace_limit.filter(|_| result.reason == sim::EndReason::TraceLimit) {
        eprintln!(
            "warning: the run stopped after {} moves, before it explored everything: the \
             trace that --out, --gif, --html and --mcap are made of filled what {limit} \
             leaves beside the run (the strategy moved far more than expected); without \
             those flags, or with more memory, it runs to the end",
            result.moves
        );
    }
    if a.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&report::summary_json(
                &truth,
                &cfg,
                &result,
                !a.no_timing
            ))?
        );
    } else {
        out!("{}", report::summary_text(&truth, &cfg, &result));
        if let Some(dir) = &a.out {
            outln!("pictures and trace written to {}", dir.display());
        }
        for (what, path) in [
            ("animation", &a.gif),
            ("replay page", &a.html),
            ("recording", &a.mcap),
        ] {
            if let Some(path) = path {
                outln!("{what} written to {}", path.display());
            }
        }
    }
    Ok(())
}
