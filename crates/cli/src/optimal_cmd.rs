//! `frontier optimal`: the offline optimal exploration path (Quattrini Li, Amigoni &
//! Basilico 2012) for a map, start and sensor, and the competitive ratios of online
//! strategies run with the same sensor and on-arrival perception from the same start.

use crate::out::outln;
use std::path::PathBuf;
use std::sync::Once;
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::Duration;

use anyhow::{Context, Result, bail};
use clap::Args;
use explore::strategy::{SensingMode, Strategy};
use grid::{Cell, Occ};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use optimal::{
    ActionSet, Config, HeuristicKind, Outcome, Progress, SensorModel, coarsen_problem, solve_with,
};
use sense::SensorSpec;
use serde_json::{Value, json};
use sim::RunConfig;
use viz::Picture;

use crate::args::{MapSource, parse_cell};

/// Flags of `frontier optimal`.
#[derive(Args, Clone, Debug)]
pub struct OptimalArgs {
    #[command(flatten)]
    pub source: MapSource,
    /// Seed of a generated environment (unless --env-seed) and of the compared runs.
    #[arg(allow_negative_numbers = true, long, default_value_t = 0)]
    pub seed: u64,
    /// Start cell "X,Y" of the map (column, row; row 0 at the top); default: the free cell
    /// nearest the map's centre.
    #[arg(allow_hyphen_values = true, long)]
    pub start: Option<String>,
    /// Sensor: los:r=R or footprint:r=R (metres; cells with suffix c).
    #[arg(long, default_value = "los:r=5")]
    pub sensor: String,
    /// Solve on cells this many map cells wide (the paper's 1, 2, 4).
    #[arg(allow_negative_numbers = true, long, default_value_t = 1)]
    pub cell_size: usize,
    /// Coverage goal G in (0, 1]: the fraction of free cells to perceive.
    #[arg(allow_negative_numbers = true, long, default_value_t = 1.0)]
    pub goal: f64,
    /// Move only to cluster representatives of the boundary cells.
    #[arg(long)]
    pub cluster: bool,
    /// Drop clusters with fewer than K boundary cells (implies --cluster).
    #[arg(allow_negative_numbers = true, long)]
    pub min_cluster: Option<usize>,
    /// Consider every reachable perceived cell as a position (exact, slow).
    #[arg(long, conflicts_with_all = ["cluster", "min_cluster"])]
    pub all_cells: bool,
    /// Heuristic: landmarks (default), paper, paper-as-published (not admissible with
    /// footprint or G < 1), zero.
    #[arg(long, default_value = "landmarks")]
    pub heuristic: String,
    /// Number of landmarks of the landmark heuristic.
    #[arg(allow_negative_numbers = true, long, default_value_t = 32)]
    pub landmarks: usize,
    /// Weighted A*: the result is at most W times the optimum (1 = optimal).
    #[arg(allow_negative_numbers = true, long, default_value_t = 1.0)]
    pub weight: f64,
    /// Stop after this many seconds with the best bounds (then a little more: the most
    /// advanced open states are completed greedily, with at most 5% as many path searches as
    /// states expanded and for at most a tenth of the limit or 1 s, for a better upper
    /// bound).
    #[arg(allow_negative_numbers = true, long)]
    pub time_limit: Option<f64>,
    /// Stop after expanding this many states.
    #[arg(allow_negative_numbers = true, long, default_value_t = 50_000_000)]
    pub max_nodes: u64,
    /// Start the best path found from the same problem solved on cells F times larger
    /// (with a tenth of the limits), mapped back and completed greedily: a better upper
    /// bound early on large maps whose search stops with bounds (0: off).
    #[arg(allow_negative_numbers = true, long, default_value_t = 0)]
    pub coarse_incumbent: usize,
    /// Memory budget of the search in MiB (a --map whose loading would exceed it is refused
    /// before it is loaded).
    #[arg(
        allow_negative_numbers = true,
        long,
        default_value_t = 1024,
        value_parser = crate::args::parse_memory_mb_usize
    )]
    pub memory_mb: usize,
    /// Online presets to compare, e.g. cf,cf-rr,yamauchi.
    #[arg(long, value_delimiter = ',')]
    pub compare: Vec<String>,
    /// Write optimal.png (the optimal path) into this directory.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Leave the wall-clock time out of the JSON (null), so that equal runs print equal
    /// bytes (as `explore --no-timing`).
    #[arg(long)]
    pub no_timing: bool,
}

/// One compared online run.
struct Compared {
    name: String,
    length_m: f64,
    coverage: f64,
    reason: &'static str,
    /// The ratio to the best path found: the competitive ratio when that path is optimal,
    /// else a lower bound on it.
    ratio: Option<f64>,
    /// The ratio to the proven lower bound: an upper bound on the competitive ratio.
    ratio_max: Option<f64>,
}

/// Estimated set-up bytes of the search on `map` coarsened by `factor`.
fn setup_bytes_at(map: &grid::GridMap, factor: usize, spec: &SensorSpec) -> Result<u64> {
    let (w, h) = (map.width().div_ceil(factor), map.height().div_ceil(factor));
    let model = SensorModel::from_spec(spec, map.resolution * factor as f64)
        .map_err(|e| anyhow::anyhow!("--sensor: {e}"))?;
    Ok(optimal::setup_bytes(w * h, model))
}

/// Refuse a search whose set-up alone exceeds `--memory-mb` or the machine's available
/// memory, before the problem is built, naming the `--cell-size` that would fit.
fn check_setup_memory(
    map: &grid::GridMap,
    factor: usize,
    spec: &SensorSpec,
    memory_mb: usize,
) -> Result<()> {
    let needed = setup_bytes_at(map, factor, spec)?;
    let available = grid::machine::available();
    let limit = sim::memory::limit(Some(memory_mb as u64), available).map_or(u64::MAX, |l| l.bytes);
    if needed <= limit {
        return Ok(());
    }
    let mut fix = String::new();
    for f in factor + 1..=64 {
        if setup_bytes_at(map, f, spec).is_ok_and(|b| 2 * b <= limit) {
            fix = format!("use --cell-size {f} (cells {f} times larger) or ");
            break;
        }
    }
    let what = format!(
        "setting up the search of this {}x{} map{}",
        map.width().div_ceil(factor),
        map.height().div_ceil(factor),
        if factor > 1 { " (coarsened)" } else { "" }
    );
    fix.push_str(&format!(
        "give --memory-mb at least {}",
        needed.div_ceil(1 << 20) * 2
    ));
    sim::memory::check(&what, needed, Some(memory_mb as u64), available, &fix)?;
    Ok(())
}

fn default_start(map: &grid::GridMap) -> Option<Cell> {
    let centre = Cell::new(map.width() as i32 / 2, map.height() as i32 / 2);
    map.cells
        .cells()
        .filter(|&c| map.cells.get(c).is_free())
        .min_by_key(|&c| (c.dist2(centre), c.y, c.x))
}

/// Run `frontier optimal`.
pub fn run(a: OptimalArgs) -> Result<()> {
    // Presets are read before the search, which may take long; each once.
    let mut presets = Vec::with_capacity(a.compare.len());
    for (i, name) in a.compare.iter().enumerate() {
        if a.compare[..i].contains(name) {
            anyhow::bail!("--compare: expected each preset once, found '{name}' twice");
        }
        let strategy = Strategy::preset(name).map_err(|e| anyhow::anyhow!("--compare: {e}"))?;
        presets.push((name, strategy));
    }
    let mut files = crate::files::Files::new();
    files.reads_source(&a.source);
    if let Some(dir) = &a.out {
        files.writes_into("--out", dir, &["optimal.png"])?;
    }
    let truth = a
        .source
        .resolve(a.seed, Some(a.memory_mb as u64))?
        .plane_only("optimal")?;
    let map = &truth.map;
    let spec: SensorSpec = a
        .sensor
        .parse()
        .map_err(|e| anyhow::anyhow!("--sensor: {e}"))?;
    if matches!(spec, SensorSpec::Lidar { .. } | SensorSpec::Sonar { .. }) {
        bail!(
            "--sensor: the optimal search needs an ideal 360° sensor: los:r=R or footprint:r=R, \
             found {spec}"
        );
    }
    // The online runs build the sensor on this map: its range is checked as `explore`
    // checks it, with the same message.
    spec.build(map.resolution)
        .map_err(|e| anyhow::anyhow!("--sensor: {e}"))?;
    let heuristic: HeuristicKind = a
        .heuristic
        .parse()
        .map_err(|e| anyhow::anyhow!("--heuristic: {e}"))?;
    if !(a.goal > 0.0 && a.goal <= 1.0) {
        bail!(
            "--goal: expected a coverage fraction in (0, 1], found {}",
            a.goal
        );
    }
    if !(a.weight.is_finite() && a.weight >= 1.0) {
        bail!(
            "--weight: expected a number ≥ 1, found {}",
            grid::Num(a.weight)
        );
    }
    if !(1..=64).contains(&a.cell_size) {
        bail!(
            "--cell-size: expected a factor in 1..=64, found {}",
            a.cell_size
        );
    }
    if a.coarse_incumbent == 1 || a.coarse_incumbent > 64 {
        bail!(
            "--coarse-incumbent: expected 0 (off) or a factor in 2..=64, found {}",
            a.coarse_incumbent
        );
    }
    let time_limit = match a.time_limit {
        None => None,
        // A limit beyond what a Duration holds (about 5.8e11 years) is no limit.
        Some(s) if s.is_finite() && s > 0.0 => {
            Some(Duration::try_from_secs_f64(s).unwrap_or(Duration::MAX))
        }
        Some(s) => bail!("--time-limit: expected a positive number of seconds, found {s}"),
    };
    let start = match &a.start {
        Some(s) => {
            let c = parse_cell(s, "--start")?;
            if !map.cells.contains(c) {
                bail!(
                    "--start {s}: outside the {}x{} map",
                    map.width(),
                    map.height()
                );
            }
            if !map.cells.get(c).is_free() {
                bail!("--start {s}: not a free cell");
            }
            c
        }
        // A dungeon's marked start, as `explore` takes it.
        None => match truth.start {
            Some(c) if map.cells.get(c).is_free() => c,
            Some(c) => bail!("the map's marked start {c}: not a free cell"),
            None => default_start(map).context("the map has no free cell")?,
        },
    };
    let actions = if a.all_cells {
        ActionSet::All
    } else if a.cluster || a.min_cluster.is_some() {
        ActionSet::Clusters {
            min_size: a.min_cluster.unwrap_or(1).max(1),
        }
    } else {
        ActionSet::Boundary
    };
    if a.landmarks > optimal::MAX_LANDMARKS {
        bail!(
            "--landmarks: expected at most {}, found {}",
            optimal::MAX_LANDMARKS,
            a.landmarks
        );
    }
    let cfg = Config {
        goal: a.goal,
        actions,
        heuristic,
        weight: a.weight,
        landmarks: a.landmarks,
        max_nodes: a.max_nodes,
        max_bytes: a.memory_mb.saturating_mul(1 << 20),
        time_limit,
        coarse_incumbent: a.coarse_incumbent,
    };
    check_setup_memory(map, a.cell_size, &spec, a.memory_mb)?;
    // The compared runs explore the full map after the search, each within --memory-mb:
    // checked now, before the search.
    let mut runs = Vec::with_capacity(presets.len());
    for (name, strategy) in presets {
        let mut rc = RunConfig::new(strategy);
        rc.sensor = spec;
        rc.sensing = Some(SensingMode::OnArrival);
        rc.starts = vec![start];
        rc.seed = a.seed;
        // The same goal as the optimum: stop once G of the free cells are perceived.
        rc.coverage_goal = Some(a.goal);
        bench::explore::check_memory(&mut rc, map, Some(a.memory_mb as u64))
            .map_err(|e| anyhow::anyhow!("--compare {name}: {e}"))?;
        runs.push((name, rc));
    }
    // Once every flag is checked and before the search: a failing command leaves no folder.
    let _folder = match &a.out {
        Some(dir) => Some(crate::files::make_output_folder("--out", dir)?),
        None => None,
    };
    let co = coarsen_problem(map, a.cell_size, start, &spec)?;
    if co.kept_area < KEPT_AREA_WARNING {
        eprintln!(
            "warning: --cell-size {}: the coarse map reaches only {:.0}% of the free area \
             reachable from the start (a coarse cell is free only if all its cells are, so \
             doors and passages narrower than {} cells close); a smaller --cell-size keeps more",
            a.cell_size,
            100.0 * co.kept_area,
            a.cell_size
        );
    }
    let res = co.resolution();
    let out = solve_watched(&co.problem, &cfg, res)?;
    let optimal_m = out.upper_bound * res;

    let mut compared = Vec::new();
    for (name, rc) in runs {
        let r = sim::run(map, &rc).with_context(|| format!("running {name}"))?;
        let length_m = r.path_length_m.first().copied().unwrap_or(0.0);
        compared.push(Compared {
            name: name.clone(),
            length_m,
            coverage: r.coverage,
            reason: r.reason.as_str(),
            // A run that stopped short of the goal has no competitive ratio.
            ratio: if out.upper_bound.is_finite() && r.reason.reached_goal() {
                optimal::competitive_ratio(length_m, optimal_m)
            } else {
                None
            },
            ratio_max: if r.reason.reached_goal() {
                optimal::competitive_ratio(length_m, out.lower_bound * res)
            } else {
                None
            },
        });
    }

    if let Some(dir) = &a.out {
        let png = dir.join("optimal.png");
        picture(&co, &out)
            .save(&png)
            .with_context(|| format!("writing {}", png.display()))?;
    }
    if a.json {
        let v = to_json(
            (map.width(), map.height()),
            &truth.name,
            &a,
            &co,
            start,
            &out,
            &compared,
        );
        outln!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print_summary(
            (map.width(), map.height()),
            &truth.name,
            &a,
            &co,
            start,
            &out,
            &compared,
        )?;
        if let Some(dir) = &a.out {
            outln!("picture written to {}", dir.join("optimal.png").display());
        }
    }
    if out.stop == Some(optimal::StopReason::Interrupted) {
        // The bounds are reported, but the run did not finish: say so to the shell (128 +
        // SIGINT, as an uncaught Ctrl-C would).
        eprintln!("interrupted: the optimum lies within the bounds above");
        std::process::exit(130);
    }
    Ok(())
}

/// Ctrl-C state: outside a search it ends the program as usual; during one it stops the
/// search, which then reports its bounds (a second Ctrl-C ends the program).
static CTRL_C: AtomicU8 = AtomicU8::new(IDLE);
const IDLE: u8 = 0;
const SEARCHING: u8 = 1;
const INTERRUPTED: u8 = 2;

/// Solve with a progress line on a terminal (states, memory, current bounds in metres) and
/// Ctrl-C stopping the search cleanly with the best bounds found.
fn solve_watched(problem: &optimal::Problem, cfg: &Config, res: f64) -> Result<Outcome> {
    static HANDLER: Once = Once::new();
    HANDLER.call_once(|| {
        // Without a handler (e.g. no signal support), Ctrl-C just ends the program.
        let _ = ctrlc::set_handler(|| {
            if CTRL_C
                .compare_exchange(SEARCHING, INTERRUPTED, Ordering::SeqCst, Ordering::SeqCst)
                .is_err()
            {
                std::process::exit(130);
            }
        });
    });
    let bar = if bench::runner::progress_wanted() {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed_precise} {msg}") {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    CTRL_C.store(SEARCHING, Ordering::SeqCst);
    let out = solve_with(
        problem,
        cfg,
        Duration::from_millis(100),
        &mut |p: &Progress| {
            let ub = if p.upper_bound.is_finite() {
                format!("{:.2}", p.upper_bound * res)
            } else {
                "∞".into()
            };
            bar.set_message(format!(
                "{} expanded, {} stored, {} MiB, optimal in [{:.2}, {ub}] m; Ctrl-C stops here",
                p.expanded,
                p.stored,
                p.bytes >> 20,
                p.lower_bound * res
            ));
            bar.tick();
            CTRL_C.load(Ordering::SeqCst) != INTERRUPTED
        },
    );
    CTRL_C.store(IDLE, Ordering::SeqCst);
    bar.finish_and_clear();
    Ok(out?)
}

/// Below this share of the reachable free area kept by coarsening, `optimal` warns.
const KEPT_AREA_WARNING: f64 = 0.5;

fn positions(out: &Outcome) -> Vec<Cell> {
    out.solution
        .as_ref()
        .map(|s| s.positions.clone())
        .unwrap_or_default()
}

/// The summary's line on the path's length in metres (`res` metres per solve cell).
fn length_line(out: &Outcome, res: f64) -> String {
    if out.upper_bound.is_finite() {
        format!(
            "length {:.2} m ({:.3} cells), optimal: {}, bounds [{:.2}, {:.2}] m",
            out.upper_bound * res,
            out.upper_bound,
            out.status == optimal::Status::Optimal,
            out.lower_bound * res,
            out.upper_bound * res
        )
    } else if out.status == optimal::Status::NoSolution {
        "no solution".into()
    } else {
        format!(
            "no path found before the search stopped; optimal length ≥ {:.2} m",
            out.lower_bound * res
        )
    }
}

fn print_summary(
    fine: (usize, usize),
    name: &str,
    a: &OptimalArgs,
    co: &optimal::Coarsened,
    start: Cell,
    out: &Outcome,
    compared: &[Compared],
) -> anyhow::Result<()> {
    let res = co.resolution();
    outln!(
        "{name}: {}x{} cells at {} m (cell size {}), start {start}{}, sensor {}, goal {}",
        co.map.width(),
        co.map.height(),
        res,
        a.cell_size,
        if co.start_moved {
            " (moved to the nearest free coarse cell)"
        } else {
            ""
        },
        a.sensor,
        a.goal
    );
    outln!(
        "targets {} (need {}), {} free cells no position can perceive",
        out.targets,
        out.needed,
        co.problem.unperceivable()
    );
    if a.cell_size > 1 {
        outln!(
            "the coarse map keeps {:.0}% of the free area reachable from the start",
            100.0 * co.kept_area
        );
    }
    outln!("{}", out.message);
    outln!("{}", length_line(out, res));
    outln!(
        "nodes expanded {}, generated {}, stored {}, {:.1} MiB, {:.3} s",
        out.stats.expanded,
        out.stats.generated,
        out.stats.stored,
        out.stats.bytes as f64 / f64::from(1 << 20),
        out.stats.seconds
    );
    let ps: Vec<String> = positions(out)
        .iter()
        .map(|&c| co.to_fine(c, fine.0, fine.1).to_string())
        .collect();
    outln!("positions (map cells): {}", ps.join(" "));
    let proven = out.status == optimal::Status::Optimal;
    for c in compared {
        // Without a proven optimum the ratio is only known to lie between the ratios to
        // the best path found and to the lower bound.
        let ratio = match (c.ratio, c.ratio_max) {
            (Some(r), _) if proven => format!("{r:.3}"),
            (Some(r), Some(m)) => format!("in [{r:.3}, {m:.3}] (optimum not proven)"),
            (Some(r), None) => format!("≥ {r:.3} (optimum not proven)"),
            (None, Some(m)) => format!("≤ {m:.3} (no path found)"),
            (None, None) => "n/a".into(),
        };
        outln!(
            "{:<10} length {:.2} m, coverage {:.3} ({}), competitive ratio {ratio}",
            c.name,
            c.length_m,
            c.coverage,
            c.reason,
        );
    }
    Ok(())
}

fn to_json(
    fine: (usize, usize),
    name: &str,
    a: &OptimalArgs,
    co: &optimal::Coarsened,
    start: Cell,
    out: &Outcome,
    compared: &[Compared],
) -> Value {
    let res = co.resolution();
    let finite = |v: f64| if v.is_finite() { json!(v) } else { Value::Null };
    json!({
        "map": name,
        "cell_size": a.cell_size,
        "coarse_kept_area": co.kept_area,
        "resolution_m": res,
        "start": [start.x, start.y],
        "start_moved": co.start_moved,
        "sensor": a.sensor,
        "goal": a.goal,
        "heuristic": a.heuristic,
        "weight": a.weight,
        "status": out.status.as_str(),
        "optimal": out.status == optimal::Status::Optimal,
        "stop": out.stop.map(|s| s.as_str()),
        "message": out.message,
        "length_m": finite(out.upper_bound * res),
        "lower_bound_m": out.lower_bound * res,
        "upper_bound_m": finite(out.upper_bound * res),
        "targets": out.targets,
        "needed": out.needed,
        "nodes_expanded": out.stats.expanded,
        "nodes_generated": out.stats.generated,
        "nodes_stored": out.stats.stored,
        "bytes": out.stats.bytes,
        "seconds": (!a.no_timing).then_some(out.stats.seconds),
        "positions": positions(out)
            .iter()
            .map(|&c| {
                let f = co.to_fine(c, fine.0, fine.1);
                json!([f.x, f.y])
            })
            .collect::<Vec<_>>(),
        "compare": compared.iter().map(|c| json!({
            "strategy": c.name,
            "length_m": c.length_m,
            "coverage": c.coverage,
            "end": c.reason,
            "competitive_ratio": c.ratio,
            "competitive_ratio_max": c.ratio_max,
        })).collect::<Vec<_>>(),
    })
}

/// The paper's Figure 2: unperceived cells black, obstacles light grey, perceived free
/// cells white, sensing positions dark grey, the path red.
fn picture(co: &optimal::Coarsened, out: &Outcome) -> Picture {
    let cells = co.problem.cells();
    let (w, h) = (cells.width(), cells.height());
    let scale = (800 / w.max(h).max(1)).clamp(1, 16) as u32;
    let mut perceived = vec![false; cells.len()];
    let mut obs = sense::Observation::new();
    let mut seen = Vec::new();
    if let Some(sol) = &out.solution {
        for &p in &sol.positions {
            seen.clear();
            co.problem
                .seen_targets(cells.index(p) as u32, &mut obs, &mut seen);
            for &t in &seen {
                perceived[co.problem.targets()[t as usize] as usize] = true;
            }
        }
    }
    let mut colour: Vec<[u8; 3]> = (0..cells.len())
        .map(|i| match cells[i] {
            Occ::Free if perceived[i] => [255, 255, 255],
            Occ::Free => [0, 0, 0],
            _ => [200, 200, 200],
        })
        .collect();
    if let Some(sol) = &out.solution {
        for &c in &sol.path {
            colour[cells.index(c)] = [220, 30, 30];
        }
        for &c in &sol.positions {
            colour[cells.index(c)] = [90, 90, 90];
        }
    }
    Picture::from_fn(w as u32 * scale, h as u32 * scale, |x, y| {
        colour[(y / scale) as usize * w + (x / scale) as usize]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An outcome of `status` with bounds `lower` and `upper` (cells).
    fn outcome(status: optimal::Status, lower: f64, upper: f64) -> Outcome {
        Outcome {
            status,
            stop: None,
            solution: None,
            lower_bound: lower,
            upper_bound: upper,
            targets: 0,
            needed: 0,
            stats: Default::default(),
            message: String::new(),
        }
    }

    /// Regression: a search stopped by a limit before it found a path (willow-full with
    /// `--time-limit 10` spends the limit setting up) printed "no solution", as if none
    /// existed.
    #[test]
    fn regression_stopped_search_without_path_is_not_no_solution() {
        let stopped = length_line(
            &outcome(optimal::Status::Stopped, 7358.8, f64::INFINITY),
            0.05,
        );
        assert_eq!(
            stopped,
            "no path found before the search stopped; optimal length ≥ 367.94 m"
        );
        let none = length_line(
            &outcome(optimal::Status::NoSolution, 0.0, f64::INFINITY),
            0.05,
        );
        assert_eq!(none, "no solution");
        let found = length_line(&outcome(optimal::Status::Optimal, 20.0, 20.0), 0.5);
        assert_eq!(
            found,
            "length 10.00 m (20.000 cells), optimal: true, bounds [10.00, 10.00] m"
        );
    }
}
