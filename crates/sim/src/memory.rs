//! How much memory a run needs, estimated before anything is allocated, and how much the
//! machine has.
//!
//! A run holds a handful of flat per-cell arrays (truth, belief, traversability, frontier
//! and candidate indices, one search field per robot, the coverage cache of CC candidates),
//! so its peak is close to linear in the map's cells. The coefficients below are upper
//! bounds of peak resident memory measured on whole runs of the 0.05 m willow-full floor
//! plan (1.1 M cells): 42 B/cell for one robot, 75 with 5 robots, 113 with 10, 64 for
//! `dt500`, 160 for a 5-robot `ha-cc`; large teams on small maps add up to 18 B/cell and
//! 0.25 MiB per robot (measured on teams of 20–200). MA adds its route matrices, at most
//! [`matrix_budget`] (4 MiB and 24 B/cell), and
//! 8 B/cell of per-goal buffers: a 5-robot `ma-af` run on a 1.7 M-cell warehouse at 3 cm
//! peaked at 221 MiB (178 MiB without matrices), of 229 MiB counted. A map the loader
//! accepts (up to 2^28 cells) can need tens of GiB; the commands compare this estimate
//! with `--memory-mb` and the memory available (which they read: `sim` touches no files;
//! the least the machine, a cgroup and `ulimit -v` leave, the refusal naming which), and
//! refuse up front instead of being killed half-way.

use explore::assign::AssignerKind;
use explore::assign::mtsp::matrix_budget;
use explore::candidates::CandidateKind;
use grid::memory::Available;

use crate::RunConfig;

/// Memory every run needs whatever the map (binary, buffers, small tables).
pub const BASE_BYTES: u64 = 16 << 20;

/// Per-cell bytes of a single-robot run (truth, belief, frontier, one field, candidates).
const PER_CELL: u64 = 48;
/// Per-cell bytes each robot past the first adds: its search field (state, cost and the
/// canonical walks' directions, 11 bytes a cell, allocated whole) and what a search that
/// settles the map lists (its settled cells, its queued turning cells), and GA's searches
/// begun again toward other goals. Measured as the growth from 20 to 80 robots on a
/// generated 40 × 30 m office at 0.1 m (120,000 cells), per robot: 1.1–1.3 MB for the
/// coordination study's presets and SGA, 1.5–1.8 MB for MinPos, IA, HA and MA, 2.1–2.2
/// MB for GA (18 bytes a cell).
const PER_CELL_PER_ROBOT: u64 = 18;
/// Bytes each robot past the first adds whatever the map (its searches' buckets, queues
/// and guide; the first's are in [`BASE_BYTES`]). With 200 robots on a 20 × 15 m office at
/// 0.1 m (30,000 cells) a robot took 0.35–0.6 MB, about 0.2 MB more than its cells account
/// for.
const PER_ROBOT: u64 = 256 << 10;
/// Per-cell bytes of the coverage (CC) candidates' visibility cache.
const PER_CELL_COVERAGE: u64 = 128;
/// Per-cell bytes of the decision-theoretic samples' gain evaluation.
const PER_CELL_DT: u64 = 32;
/// Per-cell bytes of MA's per-goal buffers (goals, their participants' costs, neighbour
/// lists, the searches' settled goals: about 250 B per goal, and all frontier cells can
/// be a few percent of the cells), beside its route matrices.
const PER_CELL_MA: u64 = 8;

/// Trace bytes per move (its event, the trail and the belief changes beside it): about
/// 70 measured on a 1 M-cell office at 0.05 m with a one-cell sensor (923,000 moves).
const TRACE_PER_MOVE: u64 = 80;
/// Trace bytes per cell: its belief changes (a cell changes about once, the reflection
/// belief's a few times).
const TRACE_PER_CELL: u64 = 16;
/// Trace bytes per decision-theoretic sample kept with its decision (cell, gain, cost,
/// utility).
const TRACE_PER_SAMPLE: u64 = 32;
/// Replay page bytes per move and per cell beside the trace (its events and changes
/// packed, base64-encoded and embedded in the page): about 220 and 40 measured on the
/// office above (243 MiB beside the trace's 64).
const REPLAY_PER_MOVE: u64 = 260;
/// Replay page bytes per cell (the truth's classes and the changes, packed).
const REPLAY_PER_CELL: u64 = 48;

/// Moves of a `random` run, cells^1.5 times this over the range squared, for sensors that
/// see a few cells: each arrival reveals about range² cells and the next goal is anywhere,
/// so the decisions grow with the cells over range² and each trip with the map's side. At
/// most 0.22 measured (offices of 14 × 10 and 20 × 14 m at 0.05 m with 1–5-cell ranges,
/// willow-full with 10 cells: 2.5–2.9 M moves).
const RANDOM_NEAR: f64 = 0.3;
/// Moves of a `random` run, cells^1.5 times this over the root of the range, for sensors
/// that walls stop first (measured at most 0.0085: willow-full with a 5 m `los` and Holz's
/// 8 m laser, nav2's depot with 0.5 and 5 m).
const RANDOM_FAR: f64 = 0.012;

/// The most moves a run of `cfg` with a sensor of `range_cells` cells is expected to take
/// on a map of `cells` cells: every cell for a one-cell sensor, fewer as the sensor sees
/// farther, taken as cells / sqrt(range) (measured: a one-cell sensor on a 1 M-cell office
/// 923,000 moves; `dt500` with a 30-cell range there 88,000 against 183,000; `dt500` and
/// Holz's 160-cell laser on willow-full's 1.1 M cells about 29,000 against 87,000). `random`
/// sends the robot across the map for every goal, so its moves grow faster than the cells
/// ([`RANDOM_NEAR`], [`RANDOM_FAR`]); a maze can still exceed that (1.4 times on a 14 ×
/// 10 m maze at 0.05 m with a 2-cell range), which is why a recorded run's trace is capped
/// at run time too ([`trace_events_within`]). Never more than `cfg.max_moves`.
fn moves_bound(cells: usize, range_cells: f64, cfg: &RunConfig) -> u64 {
    let (n, r) = (cells as f64, range_cells.max(1.0));
    let mut moves = n / r.sqrt();
    if cfg.strategy.assigner == AssignerKind::Random {
        moves = moves.max(n * n.sqrt() * (RANDOM_NEAR / (r * r)).max(RANDOM_FAR / r.sqrt()));
    }
    (moves.ceil() as u64).min(cfg.max_moves)
}

/// Trace bytes per move of a run of `cfg`: its event and, for the decision-theoretic
/// samples, its share of every decision's samples (decisions taken as one per half range
/// of moves: 1,351 decisions in the 88,000 moves above, against 12,200).
fn trace_per_move(resolution: f64, cfg: &RunConfig) -> u64 {
    let range = cfg.sensor.range_cells(resolution);
    let samples = match cfg.strategy.candidates {
        CandidateKind::DtSamples { n } => {
            (n as f64 * TRACE_PER_SAMPLE as f64 / (range / 2.0).max(1.0)).ceil() as u64
        }
        _ => 0,
    };
    TRACE_PER_MOVE.saturating_add(samples)
}

/// Estimated bytes of the trace a run of `cfg` keeps when it records one (`--out`,
/// `--gif`, `--html`, `--mcap`): its moves, belief changes and, for the decision-theoretic
/// samples, every decision's samples.
pub fn trace_bytes(cells: usize, resolution: f64, cfg: &RunConfig) -> u64 {
    let moves = moves_bound(cells, cfg.sensor.range_cells(resolution), cfg);
    TRACE_PER_CELL
        .saturating_mul(cells as u64)
        .saturating_add(trace_per_move(resolution, cfg).saturating_mul(moves))
}

/// The most events the trace of a recorded run of `cfg` may hold within `limit` bytes, the
/// memory a command may spend ([`limit`]): what the run without its trace, the trace's
/// per-cell part and, with `page`, the replay page made of it leave, at the trace's (and
/// the page's) bytes per move. The run's estimate ([`run_bytes`]) fitting in `limit`
/// leaves at least the moves it expects; [`RunConfig::trace_events`] takes this.
pub fn trace_events_within(
    limit: u64,
    cells: usize,
    resolution: f64,
    cfg: &RunConfig,
    page: bool,
) -> u64 {
    let mut fixed = untraced_bytes(cells, resolution, cfg)
        .saturating_add(TRACE_PER_CELL.saturating_mul(cells as u64));
    let mut per_move = trace_per_move(resolution, cfg);
    if page {
        fixed = fixed.saturating_add(REPLAY_PER_CELL.saturating_mul(cells as u64));
        per_move = per_move.saturating_add(REPLAY_PER_MOVE);
    }
    limit.saturating_sub(fixed) / per_move.max(1)
}

/// Estimated bytes of making a run's replay page (`--html`) beside its trace.
pub fn replay_bytes(cells: usize, resolution: f64, cfg: &RunConfig) -> u64 {
    let moves = moves_bound(cells, cfg.sensor.range_cells(resolution), cfg);
    REPLAY_PER_CELL
        .saturating_mul(cells as u64)
        .saturating_add(REPLAY_PER_MOVE.saturating_mul(moves))
}

/// Estimated peak bytes of running `cfg` on a map of `cells` cells of `resolution` metres:
/// the per-cell arrays, the coverage candidates' scans (which grow with the range's cube,
/// not the map: [`CandidateKind::scan_bytes_bound`]), MA's route matrices
/// what building the sensor takes (the `los` kind's ray template, up to about 480 MiB
/// at 256 cells of range, whatever the map's size) and the trace, when the run keeps one
/// ([`trace_bytes`]). `tests/memory.rs` checks that it
/// bounds whole runs' peaks.
pub fn run_bytes(cells: usize, resolution: f64, cfg: &RunConfig) -> u64 {
    let trace = match cfg.record_trace {
        true => trace_bytes(cells, resolution, cfg),
        false => 0,
    };
    untraced_bytes(cells, resolution, cfg).saturating_add(trace)
}

/// [`run_bytes`] without the trace, whether or not `cfg` records one.
fn untraced_bytes(cells: usize, resolution: f64, cfg: &RunConfig) -> u64 {
    let robots = cfg.robots.max(1) as u64;
    let mut per_cell = PER_CELL.saturating_add(PER_CELL_PER_ROBOT.saturating_mul(robots - 1));
    per_cell += match cfg.strategy.candidates {
        CandidateKind::Coverage => PER_CELL_COVERAGE,
        CandidateKind::DtSamples { .. } => PER_CELL_DT,
        _ => 0,
    };
    let scans = cfg.strategy.candidates.scan_bytes_bound(
        cells,
        cfg.sensor.range_cells(resolution),
        resolution,
    );
    let matrices = match cfg.strategy.assigner {
        AssignerKind::Mtsp => {
            matrix_budget(cells).saturating_add(PER_CELL_MA.saturating_mul(cells as u64))
        }
        _ => 0,
    };
    BASE_BYTES
        .saturating_add(per_cell.saturating_mul(cells as u64))
        .saturating_add(PER_ROBOT.saturating_mul(robots - 1))
        .saturating_add(scans)
        .saturating_add(matrices)
        .saturating_add(cfg.sensor.build_bytes(resolution))
}

/// The part of [`run_bytes`] that runs in one process share: the program and its tables
/// ([`BASE_BYTES`]) and the sensor's ray template (built once per range and resolution). A
/// process running n such runs side by side needs this once and the rest n times.
pub fn shared_bytes(resolution: f64, cfg: &RunConfig) -> u64 {
    BASE_BYTES.saturating_add(cfg.sensor.build_bytes(resolution))
}

/// Why a run would not fit in memory.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{what} needs about {} MiB, more than {}; {fix}",
    .needed.div_ceil(1 << 20),
    .limit
)]
pub struct TooBig {
    /// What would be run, e.g. "exploring this 16384 x 16384 map with 1 robot".
    pub what: String,
    /// Estimated bytes.
    pub needed: u64,
    /// The limit it exceeds, as the user would name it (e.g. "--memory-mb 512").
    pub limit: String,
    /// How to make it fit.
    pub fix: String,
}

/// The memory a command may spend: the tighter of `budget_mb` (a user's `--memory-mb`) and
/// the memory `available` (the budget on a tie), named as a refusal names it. A command
/// compares every estimate with it, a run's ([`check`]) and a map file's loading
/// (`grid::io::LoadOptions::memory`) alike.
pub fn limit(budget_mb: Option<u64>, available: Option<Available>) -> Option<Available> {
    grid::memory::least([
        budget_mb.map(|mb| Available::flag("--memory-mb", mb)),
        available,
    ])
}

/// Check `needed` bytes against `budget_mb` (a user's `--memory-mb`) and the memory
/// `available` (with the limit that leaves it): `Err` names the tighter limit exceeded
/// ([`limit`]).
pub fn check(
    what: &str,
    needed: u64,
    budget_mb: Option<u64>,
    available: Option<Available>,
    fix: &str,
) -> Result<(), TooBig> {
    match limit(budget_mb, available) {
        Some(limit) if needed > limit.bytes => Err(TooBig {
            what: what.to_string(),
            needed,
            limit: limit.to_string(),
            fix: fix.to_string(),
        }),
        _ => Ok(()),
    }
}

/// A batch run on `workers` threads: the largest of `needs` (estimated bytes and name of
/// each run), one per thread, must fit at once ([`check`]); `noun` names the runs in the
/// message ("trials", "runs").
pub fn check_batch(
    noun: &str,
    needs: &[(u64, String)],
    workers: usize,
    budget_mb: Option<u64>,
    available: Option<Available>,
    fix: &str,
) -> Result<(), TooBig> {
    let workers = workers.max(1);
    let mut order: Vec<usize> = (0..needs.len()).collect();
    // largest first, the earliest among equals
    order.sort_by(|&a, &b| needs[b].0.cmp(&needs[a].0).then(a.cmp(&b)));
    let Some(&first) = order.first() else {
        return Ok(());
    };
    let (largest, name) = &needs[first];
    // "1 trial", not "1 trials"
    let noun = match needs.len() {
        1 => noun.strip_suffix('s').unwrap_or(noun),
        _ => noun,
    };
    let what = format!(
        "running {} {noun} on {workers} thread{} (the largest, {name}, about {} MiB)",
        needs.len(),
        if workers == 1 { "" } else { "s" },
        largest.div_ceil(1 << 20)
    );
    check(&what, at_once(needs, workers), budget_mb, available, fix)
}

/// The bytes the largest of `needs` (estimated bytes of each run) take when one runs on
/// each of `workers` threads: what [`check_batch`] checks.
pub fn at_once(needs: &[(u64, String)], workers: usize) -> u64 {
    let mut bytes: Vec<u64> = needs.iter().map(|n| n.0).collect();
    bytes.sort_unstable_by(|a, b| b.cmp(a));
    bytes.iter().take(workers.max(1)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use explore::strategy::Strategy;
    use grid::memory::Limit;

    /// The trace cap a command derives from its memory limit ([`trace_events_within`])
    /// leaves exactly the moves the estimate expects when the estimate fills the limit
    /// (with and without a replay page), fewer under a smaller limit: a run the estimate
    /// lets through is not cut short before it.
    #[test]
    fn the_trace_cap_of_a_fitting_run_is_its_expected_moves() {
        let cells = 280 * 200;
        for (preset, sensor, res) in [
            ("random", "los:r=2c", 0.05),
            ("random", "lidar:r=8,fov=180,res=1", 0.05),
            ("cf-rr", "los:r=1c", 0.05),
            ("dt500", "los:r=30c", 0.1),
        ] {
            let mut cfg = RunConfig::new(Strategy::preset(preset).unwrap());
            cfg.sensor = sensor.parse().unwrap();
            cfg.record_trace = true;
            let moves = moves_bound(cells, cfg.sensor.range_cells(res), &cfg);
            for page in [false, true] {
                let mut limit = run_bytes(cells, res, &cfg);
                if page {
                    limit += replay_bytes(cells, res, &cfg);
                }
                let events = trace_events_within(limit, cells, res, &cfg, page);
                assert_eq!(events, moves, "{preset} {sensor} page {page}");
                let less = trace_events_within(limit - (1 << 20), cells, res, &cfg, page);
                assert!(less < events, "{preset} {sensor} page {page}: {less}");
            }
        }
    }

    /// `random`'s moves are bounded by more than the others' (it crosses the map for every
    /// goal), and never by more than the run's move limit.
    #[test]
    fn random_expects_more_moves_within_the_move_limit() {
        let sensor: sense::SensorSpec = "los:r=2c".parse().unwrap();
        let range = sensor.range_cells(0.05);
        let cf = RunConfig::new(Strategy::preset("cf").unwrap());
        let mut random = RunConfig::new(Strategy::preset("random").unwrap());
        let cells = 1_100_000;
        assert!(moves_bound(cells, range, &random) > 10 * moves_bound(cells, range, &cf));
        assert_eq!(moves_bound(cells, range, &random), random.max_moves);
        random.max_moves = 1000;
        assert_eq!(moves_bound(cells, range, &random), 1000);
    }

    #[test]
    fn estimate_grows_with_robots_and_coverage_candidates() {
        let cf = RunConfig::new(Strategy::preset("cf").unwrap());
        let mut team = RunConfig::new(Strategy::preset("minpos").unwrap());
        team.robots = 5;
        let mut cc = RunConfig::new(Strategy::preset("ha-cc").unwrap());
        cc.robots = 5;
        let n = 1_000_000;
        assert!(run_bytes(n, 0.05, &cf) < run_bytes(n, 0.05, &team));
        assert!(run_bytes(n, 0.05, &team) < run_bytes(n, 0.05, &cc));
        // The measured peaks on willow-full (1.1 M cells) lie below the estimates.
        assert!(run_bytes(1_100_000, 0.05, &cf) > 50 << 20);
        assert!(run_bytes(1_100_000, 0.05, &cc) > 180 << 20);
    }

    /// MA's route matrices, kept within their budget, and per-goal buffers are counted (a
    /// 5-robot `ma-af` run on a 1.7 M-cell warehouse at 3 cm peaked at 855 MiB when the
    /// matrices were not capped, 221 MiB since).
    #[test]
    fn ma_route_matrices_are_counted() {
        let mut ma = RunConfig::new(Strategy::preset("ma-af").unwrap());
        ma.robots = 5;
        let mut minpos = RunConfig::new(Strategy::preset("minpos").unwrap());
        minpos.robots = 5;
        let n = 1_684_044;
        assert_eq!(
            run_bytes(n, 0.03, &ma) - run_bytes(n, 0.03, &minpos),
            matrix_budget(n) + PER_CELL_MA * n as u64
        );
        assert!(run_bytes(n, 0.03, &ma) > 221 << 20);
    }

    /// A 5 m line-of-sight sensor on 2 cm cells builds a ray template of 250 cells' range
    /// (about 480 MB at its peak, 1 GB before the template was built with linked children)
    /// on however small a map: the estimate counts it.
    #[test]
    fn a_fine_los_template_is_counted_whatever_the_map() {
        let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
        cfg.sensor = "los:r=5".parse().unwrap();
        let small_map = 200 * 200;
        assert!(run_bytes(small_map, 0.02, &cfg) > 400 << 20);
        assert!(run_bytes(small_map, 0.1, &cfg) < 64 << 20);
        cfg.sensor = "lidar:r=5,fov=360,res=1".parse().unwrap();
        assert!(run_bytes(small_map, 0.02, &cfg) < 64 << 20);
    }

    #[test]
    fn the_tighter_limit_is_named() {
        let machine = |b: u64| Some(Available::new(b, Limit::Machine));
        let e = check("x", 3 << 30, Some(1024), machine(8 << 30), "fix it").unwrap_err();
        assert!(e.to_string().contains("--memory-mb 1024"), "{e}");
        assert!(e.to_string().contains("about 3072 MiB"), "{e}");
        let e = check("x", 3 << 30, None, machine(2 << 30), "fix it").unwrap_err();
        assert!(
            e.to_string()
                .contains("2048 MiB this machine has available"),
            "{e}"
        );
        let ulimit = Some(Available::new(2 << 30, Limit::AddressSpace));
        let e = check("x", 3 << 30, None, ulimit, "fix it").unwrap_err();
        assert!(
            e.to_string()
                .contains("more than the 2048 MiB ulimit -v leaves; fix it"),
            "{e}"
        );
        // Over both, the tighter is named: lowering the estimate below the budget alone
        // would not do.
        let e = check("x", 3 << 30, Some(2560), machine(2 << 30), "fix it").unwrap_err();
        assert!(
            e.to_string()
                .contains("2048 MiB this machine has available"),
            "{e}"
        );
        let e = check("x", 3 << 30, Some(2048), machine(2 << 30), "fix it").unwrap_err();
        assert!(e.to_string().contains("--memory-mb 2048"), "{e}");
        assert!(check("x", 1 << 30, Some(2048), machine(2 << 30), "").is_ok());
        assert!(check("x", u64::MAX, None, None, "").is_ok());
    }

    #[test]
    fn a_batch_needs_its_largest_runs_one_per_thread() {
        let mib = |n: u64| n << 20;
        let needs: Vec<(u64, String)> = [
            (mib(10), "a"),
            (mib(30), "b"),
            (mib(30), "c"),
            (mib(5), "d"),
        ]
        .into_iter()
        .map(|(b, n)| (b, n.to_string()))
        .collect();
        // two threads: b and c at once, 60 MiB; the largest named is the earliest, b
        let e = check_batch("runs", &needs, 2, Some(59), None, "fewer").unwrap_err();
        assert_eq!(
            e.to_string(),
            "running 4 runs on 2 threads (the largest, b, about 30 MiB) needs about 60 MiB, \
             more than --memory-mb 59; fewer"
        );
        assert!(check_batch("runs", &needs, 2, Some(60), None, "").is_ok());
        // one thread: the largest alone; zero threads count as one
        assert!(check_batch("runs", &needs, 1, Some(30), None, "").is_ok());
        assert!(check_batch("runs", &needs, 0, Some(30), None, "").is_ok());
        // every thread busy: all four, 75 MiB
        assert!(check_batch("runs", &needs, 8, Some(74), None, "").is_err());
        assert!(check_batch("runs", &[], 2, Some(1), None, "").is_ok());
        // Regression: a batch of one said "running 1 trials".
        let e = check_batch("trials", &needs[1..2], 1, Some(1), None, "fewer").unwrap_err();
        assert!(
            e.to_string().starts_with("running 1 trial on 1 thread "),
            "{e}"
        );
    }
}
