//! One run as `frontier explore` describes it: its options resolved into a run
//! configuration, and its JSON summary.
//!
//! The CLI and the Python package both go through these functions, so that a run started
//! from either reports the same numbers, and a mistake gets the same message.

use explore::strategy::{SensingMode, Strategy};
use grid::{Cell, Grid, GridMap};
use sense::{BeliefKind, SensorSpec};
use serde_json::{Value, json};
use sim::{RunConfig, RunResult};

/// The options of one run, as given by the user (names are the CLI's flags).
#[derive(Clone, Debug, PartialEq)]
pub struct ExploreOptions {
    /// Master seed (`--seed`).
    pub seed: u64,
    /// Start cell of the first robot (`--start`); `None` = chosen by seed.
    pub start: Option<Cell>,
    /// Whether `start` is the one the map file marks (a dungeon PNG's), not `--start`:
    /// a refusal names it so.
    pub start_marked: bool,
    /// Strategy preset (`--strategy`).
    pub strategy: String,
    /// Sensor spec (`--sensor`).
    pub sensor: String,
    /// Belief map kind (`--belief`); `None` = known, or evidence with sonar.
    pub belief: Option<String>,
    /// Sensing mode (`--sensing`); `None` = the strategy's.
    pub sensing: Option<String>,
    /// Clearance in metres (`--clearance`).
    pub clearance: f64,
    /// Speed in metres per second (`--speed`).
    pub speed: f64,
    /// Number of robots (`--robots`).
    pub robots: usize,
    /// Re-planning period in moves, -1 = on arrival (`--s-max`); `None` = the strategy's.
    pub s_max: Option<i64>,
    /// Coverage goal (`--goal`).
    pub goal: Option<f64>,
    /// What coverage counts (`--coverage`: `reachable` or `known`; default reachable).
    pub coverage: Option<String>,
    /// Move limit of the team (`--max-moves`).
    pub max_moves: u64,
    /// Keep a trace (trails, goals) for pictures.
    pub record_trace: bool,
    /// How path length is measured (`--motion`: `grid` or `any-angle`); `None` = grid.
    pub motion: Option<String>,
}

impl Default for ExploreOptions {
    /// The CLI's defaults.
    fn default() -> Self {
        Self {
            seed: 0,
            start: None,
            start_marked: false,
            strategy: "cf-rr".into(),
            sensor: "los:r=5".into(),
            belief: None,
            sensing: None,
            clearance: 0.0,
            speed: 1.0,
            robots: 1,
            s_max: None,
            goal: None,
            coverage: None,
            max_moves: 10_000_000,
            record_trace: false,
            motion: None,
        }
    }
}

impl ExploreOptions {
    /// Start at the cell the map file marks (a dungeon PNG's) unless `--start` gave one;
    /// a refusal then names it as the map's.
    pub fn or_marked_start(&mut self, marked: Option<Cell>) {
        self.start_marked = self.start.is_none() && marked.is_some();
        self.start = self.start.or(marked);
    }
}

/// Refuse a run of `cfg` on `map` whose estimated peak memory exceeds `memory_mb` (the
/// user's `--memory-mb`) or what the machine has available, before anything map-sized is
/// allocated; the error says what would not fit, the limit and how to make it fit. A
/// recording run's trace is capped at what that limit leaves ([`check_memory_with`]).
pub fn check_memory(
    cfg: &mut RunConfig,
    map: &GridMap,
    memory_mb: Option<u64>,
) -> Result<(), String> {
    check_memory_with(cfg, map, memory_mb, false).map(|_| ())
}

/// [`check_memory`], with the replay page made of the run's trace beside it when `page`
/// (`--html`). A run that records a trace gets [`RunConfig::trace_events`] from the same
/// limit: one whose trace outgrows its estimate (`random` can) then ends at `trace limit`
/// instead of being killed for memory. Returns that limit, to name it if the run stops there.
pub fn check_memory_with(
    cfg: &mut RunConfig,
    map: &GridMap,
    memory_mb: Option<u64>,
    page: bool,
) -> Result<Option<grid::memory::Available>, String> {
    let (w, h) = (map.width(), map.height());
    let what = format!(
        "exploring this {w}x{h} map with {} robot{} ({})",
        cfg.robots,
        if cfg.robots == 1 { "" } else { "s" },
        cfg.strategy.name
    );
    let template = cfg.sensor.build_bytes(map.resolution);
    let fix = format!(
        "use a map with fewer, larger cells (scale the image down and raise its resolution), \
         fewer robots, or another candidate generator{}",
        if template > 0 {
            format!(
                "; the {} sensor's ray template alone needs about {} MiB (a shorter range \
                 in cells needs less)",
                cfg.sensor,
                template.div_ceil(1 << 20)
            )
        } else {
            String::new()
        }
    );
    let extra = match page {
        true => sim::memory::replay_bytes(w * h, map.resolution, cfg),
        false => 0,
    };
    // The trace is named where it is a large part of the need (a quarter or more), so
    // that a run refused for its recording says so; a small one is left out.
    let needed = sim::memory::run_bytes(w * h, map.resolution, cfg).saturating_add(extra);
    let trace = match cfg.record_trace {
        true => sim::memory::trace_bytes(w * h, map.resolution, cfg).saturating_add(extra),
        false => 0,
    };
    let fix = match trace >= needed / 4 {
        true => format!(
            "{fix}; the trace it records for pictures, a replay or trajectories takes about \
             {} MiB of it (a run that records none keeps none)",
            trace.div_ceil(1 << 20)
        ),
        false => fix,
    };
    let available = grid::machine::available();
    sim::memory::check(&what, needed, memory_mb, available, &fix).map_err(|e| e.to_string())?;
    let limit = sim::memory::limit(memory_mb, available).filter(|_| cfg.record_trace);
    if let Some(limit) = limit {
        cfg.trace_events =
            sim::memory::trace_events_within(limit.bytes, w * h, map.resolution, cfg, page);
    }
    Ok(limit)
}

/// Refuse to generate the environment `spec` when its generation would need more than
/// `memory_mb` or the memory available now (the generators' peak, 24 bytes a cell). A spec
/// that is wrong in itself passes: generating it gives its error.
pub fn check_generate_memory(spec: &world::EnvSpec, memory_mb: Option<u64>) -> Result<(), String> {
    let Ok(cells) = spec.cells() else {
        return Ok(());
    };
    sim::memory::check(
        &format!("generating this {} of {cells} cells", spec.kind),
        sim::memory::BASE_BYTES
            .saturating_add(cells.saturating_mul(world::GENERATE_BYTES_PER_CELL)),
        memory_mb,
        grid::machine::available(),
        "choose a smaller size or a coarser resolution",
    )
    .map_err(|e| e.to_string())
}

/// Why `preset`, which draws each goal at random ([`Strategy::draws_its_goal`]), takes no
/// re-plan every `n` moves: the words after a flag's or a key's name.
pub(crate) fn no_periodic_replan(preset: &str, n: i64) -> String {
    format!(
        "expected -1 for {preset}, found {n}: it draws each goal at random, so re-planning \
         every {n} moves would walk at random; it re-plans on arrival"
    )
}

/// Resolve `o` into a run configuration for `map` (with its off-plane `clutter`); the
/// error names the flag, what was expected and what was found.
pub fn config(
    o: &ExploreOptions,
    map: &GridMap,
    clutter: Option<Grid<bool>>,
) -> Result<RunConfig, String> {
    let mut strategy = Strategy::preset(&o.strategy).map_err(|e| format!("--strategy: {e}"))?;
    let sensor: SensorSpec = o.sensor.parse().map_err(|e| format!("--sensor: {e}"))?;
    let belief: BeliefKind = match o.belief.as_deref() {
        Some(b) => b.parse().map_err(|e| format!("--belief: {e}"))?,
        None => crate::plan::belief_with(&sensor, BeliefKind::Known),
    };
    let sensing = o
        .sensing
        .as_deref()
        .map(|s| s.parse::<SensingMode>())
        .transpose()
        .map_err(|e| format!("--sensing: {e}"))?;
    match o.s_max {
        None => {}
        Some(-1) => strategy.replan.every_moves = None,
        Some(n) if n > 0 && n <= i64::from(u32::MAX) => {
            if strategy.draws_its_goal() {
                return Err(format!("--s-max: {}", no_periodic_replan(&o.strategy, n)));
            }
            strategy.replan.every_moves = Some(n as u32)
        }
        Some(n) => {
            return Err(format!(
                "--s-max: expected a positive number of cell moves or -1 (on arrival), found {n}"
            ));
        }
    }
    let mut cfg = RunConfig::new(strategy);
    cfg.sensor = sensor;
    cfg.belief = belief;
    cfg.sensing = sensing;
    cfg.robots = o.robots;
    // + 0.0: `--clearance -0` is no clearance, and prints as 0.
    cfg.clearance_m = o.clearance + 0.0;
    cfg.speed = o.speed;
    cfg.seed = o.seed;
    cfg.coverage_goal = o.goal;
    if let Some(c) = o.coverage.as_deref() {
        cfg.coverage = c.parse()?;
    }
    cfg.max_moves = o.max_moves;
    cfg.record_trace = o.record_trace;
    if let Some(m) = o.motion.as_deref() {
        cfg.motion = m.parse().map_err(|e| format!("--motion: {e}"))?;
    }
    cfg.clutter = clutter;
    if let Some(first) = o.start {
        let trav =
            sim::truth::traversable(&map.cells, grid::units::cells(o.clearance, map.resolution));
        sim::truth::check_start(&map.cells, &trav, first)
            .map_err(|e| named_start(first, o.start_marked, e))?;
        cfg.starts = if o.robots == 1 {
            vec![first]
        } else {
            sim::truth::team_starts(&map.cells, &trav, first, o.robots)
                .map_err(|e| e.to_string())?
        };
    }
    sim::check_config(&cfg).map_err(|e| e.to_string())?;
    Ok(cfg)
}

/// A start refused by the run, named as the user gave it: by its flag, or as the start the
/// map file marks (`marked`). A team starts around it.
fn named_start(start: Cell, marked: bool, e: sim::SimError) -> String {
    match e {
        sim::SimError::BadStart { why, .. } if marked => {
            format!("the start the map marks, {},{}: {why}", start.x, start.y)
        }
        sim::SimError::BadStart { why, .. } => format!("--start {},{}: {why}", start.x, start.y),
        e => e.to_string(),
    }
}

/// Why `start` cannot be the first robot's start on `map` for a robot with `clearance_m`
/// metres of clearance (outside the map, or not a cell the robot fits in), named as
/// [`config`] names it (`marked`: the start the map file marks); `None` if it can.
pub fn start_problem(map: &GridMap, start: Cell, marked: bool, clearance_m: f64) -> Option<String> {
    let trav = sim::truth::traversable(&map.cells, grid::units::cells(clearance_m, map.resolution));
    sim::truth::check_start(&map.cells, &trav, start)
        .err()
        .map(|e| named_start(start, marked, e))
}

/// Round to `digits` decimals so that JSON stays short and stable.
fn round(v: f64, digits: i32) -> f64 {
    let f = 10f64.powi(digits);
    (v * f).round() / f
}

/// At most `n` points of the coverage curve, evenly spaced by index, last point kept.
fn downsample(curve: &[(f64, f64)], n: usize) -> Vec<Value> {
    if curve.is_empty() {
        return Vec::new();
    }
    let step = curve.len().div_ceil(n).max(1);
    let mut out: Vec<Value> = curve
        .iter()
        .step_by(step)
        .map(|&(d, c)| json!([round(d, 3), round(c, 5)]))
        .collect();
    if !(curve.len() - 1).is_multiple_of(step) {
        let &(d, c) = curve.last().expect("non-empty");
        out.push(json!([round(d, 3), round(c, 5)]));
    }
    out
}

/// The JSON summary of a run of `map` (named `name` in reports) as `frontier explore
/// --json` prints it (`timing`: include wall-clock times, else `null`).
pub fn summary_json(
    name: &str,
    map: &GridMap,
    cfg: &RunConfig,
    r: &RunResult,
    timing: bool,
) -> Value {
    let ms = |s: f64| {
        if timing {
            json!(round(s * 1000.0, 3))
        } else {
            Value::Null
        }
    };
    json!({
        "env": name,
        "width": map.width(),
        "height": map.height(),
        "resolution": map.resolution,
        "seed": cfg.seed,
        "strategy": cfg.strategy.name,
        "robots": cfg.robots,
        "sensor": cfg.sensor.to_string(),
        "sensing": cfg.sensing_mode().to_string(),
        "belief": cfg.belief.to_string(),
        "clearance_m": cfg.clearance_m,
        "speed": cfg.speed,
        "s_max": cfg.strategy.replan.every_moves,
        "starts": r.starts.iter().map(|c| json!([c.x, c.y])).collect::<Vec<_>>(),
        "complete": r.complete(),
        "reason": r.reason.as_str(),
        "coverage": round(r.coverage, 6),
        "coverage_kind": cfg.coverage.to_string(),
        "reachable_cells": r.reachable_cells,
        "path_length_m": r.path_length_m.iter().map(|&l| round(l, 4)).collect::<Vec<_>>(),
        "max_path_length_m": round(r.max_path_length_m(), 4),
        "total_path_length_m": round(r.total_path_length_m(), 4),
        "motion": r.motion.name(),
        "grid_path_length_m": r.grid_path_length_m.iter().map(|&l| round(l, 4)).collect::<Vec<_>>(),
        "time_s": round(r.time_s, 4),
        "decisions": r.decisions,
        "moves": r.moves,
        "decide_ms": ms(r.times.decide_s),
        "timing_ms": {
            "sense": ms(r.times.sense_s),
            "upkeep": ms(r.times.upkeep_s),
            "decide": ms(r.times.decide_s),
            "total": ms(r.times.total_s),
        },
        "d90_m": milestone(r, 90).0,
        "t90_s": milestone(r, 90).1,
        "d98_m": milestone(r, 98).0,
        "t98_s": milestone(r, 98).1,
        "d99_m": milestone(r, 99).0,
        "t99_s": milestone(r, 99).1,
        "overlap": round(r.overlap, 6),
        "idle_s": r.idle_s.iter().map(|&t| round(t, 4)).collect::<Vec<_>>(),
        "map": audit_json(r),
        "coverage_curve": downsample(&r.coverage_curve, 100),
    })
}

/// Distance and time (JSON numbers, or null if never reached) at which coverage first
/// reached `percent`.
fn milestone(r: &RunResult, percent: u32) -> (Value, Value) {
    match r.milestone(percent) {
        Some((d, t)) => (json!(round(d, 4)), json!(round(t, 4))),
        None => (Value::Null, Value::Null),
    }
}

/// The map built against the ground truth ([`sim::MapAudit`]).
pub fn audit_json(r: &RunResult) -> Value {
    let a = &r.audit;
    json!({
        "accuracy": round(a.accuracy, 6),
        "false_free_cells": a.false_free_cells,
        "clutter_cells": a.clutter_cells,
        "clutter_mapped": a.clutter_mapped,
        "phantom_frontier_regions": a.phantom_regions,
        "phantom_frontier_regions_per_decision": round(a.phantom_regions_mean(r.decisions), 4),
        "phantom_frontier_regions_max": a.phantom_regions_max,
        "phantom_frontier_share": round(a.phantom_share(), 6),
        "phantom_goals": a.phantom_goals,
    })
}
