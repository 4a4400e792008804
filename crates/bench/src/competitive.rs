//! Competitive ratios of online strategies against offline optimal exploration paths
//! (Quattrini Li, Amigoni & Basilico 2012; issue 9's `quattrini2012` suite).
//!
//! A scenario with an `[optimal]` table gives every single-robot trial with a 360° sensor
//! (`los` or `footprint`) the optimal offline path from the same start, with the same sensor
//! and the same coverage goal G (the `optimal` crate's A*), and stores next to the trial its
//! length and proven lower bound and the competitive ratio `online / optimal`. When the
//! search stops at its node or memory budget the best path found is an upper bound, and the
//! ratio is stored against it (a lower bound on the true ratio) together with the proven
//! lower bound (from which an upper bound on the ratio follows).
//!
//! With `min_cluster` (the paper's clustering speed-up) the actions are cluster
//! representatives, and "optimal" means optimal for that action set: a valid exploration
//! path no shorter than the optimum over all boundary cells, so the ratio is then a lower
//! bound on the ratio against the unrestricted optimum.
//!
//! Only node and memory budgets stop the search here, never wall time, so that results are
//! the same on every machine and at every thread count. Optimal paths are computed once per
//! (environment, sensor, start, settings) and kept in the `optimal` table of the store, so
//! resumed and sharded studies reuse them.
//!
//! Online runs must sense the way the optimum assumes: the suite sets `sensing =
//! "on-arrival"` (time-discrete perception at chosen positions, 360° sweeps). They also stop
//! at the optimum's goal: with `[optimal]` the coverage goal defaults to 1, so an online
//! run ends when every reachable free cell is perceived, as the paper measures online
//! strategies (distance to map the share G), rather than when its last frontier is gone
//! (often a wall cell not yet seen, which no goal counts).

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use grid::{Cell, GridMap};
use optimal::{ActionSet, Config, Status, coarsen_problem, solve};
use sense::SensorSpec;

use crate::error::BenchError;

/// Settings of the optimal search of a study (`[optimal]` in a scenario).
#[derive(Clone, Debug, PartialEq)]
pub struct OptimalSpec {
    /// Coarsening factor (the paper's cell sizes 1, 2, 4).
    pub cell_size: usize,
    /// Search only cluster representatives, dropping clusters smaller than this (`None`:
    /// every boundary cell).
    pub min_cluster: Option<usize>,
    /// Weight of weighted A* (1 = optimal).
    pub weight: f64,
    /// Stop after this many expansions.
    pub max_nodes: u64,
    /// Stop before the search's memory exceeds this many MiB.
    pub memory_mb: usize,
}

impl Default for OptimalSpec {
    fn default() -> Self {
        Self {
            cell_size: 1,
            min_cluster: None,
            weight: 1.0,
            max_nodes: 2_000_000,
            memory_mb: 1024,
        }
    }
}

/// Revision of the optimal search in stored keys: its definition (actions, goal) and its
/// heuristic, which decides the bounds reached when a node budget stops it (v3: Held–Karp
/// over viewpoint sets; v4: the footprint's viewpoint distances, field step costs; v5: the
/// skip-budget bound with two far points and its direct term; v6: path costs are exact
/// sums, the diagonal step √2 to 32 binary places; v7: the caches grow within the memory
/// budget, so a search the budget stops stops later, with other bounds).
const SEARCH_REVISION: u32 = 7;

impl OptimalSpec {
    /// A text naming every setting (part of the study's fingerprint and of cache keys), and
    /// the search's revision, so that a store resumed after the search changed (v2: the
    /// paper's boundary with walls) recomputes its optimal paths.
    pub fn fingerprint(&self) -> String {
        format!(
            "search={SEARCH_REVISION} cell={} cluster={} w={} nodes={} mem={}",
            self.cell_size,
            self.min_cluster.map_or("off".into(), |k| k.to_string()),
            self.weight,
            self.max_nodes,
            self.memory_mb
        )
    }

    /// Whether a trial with this sensor and team size gets an optimal path.
    pub fn applies(sensor: &SensorSpec, robots: usize) -> bool {
        robots == 1
            && matches!(
                sensor,
                SensorSpec::Los { .. } | SensorSpec::Footprint { .. }
            )
    }
}

/// The optimal path of one (environment, sensor, start, goal).
#[derive(Clone, Debug, PartialEq)]
pub struct OptimalPath {
    /// Length of the best path found, metres (`None` if the budget ran out before any).
    pub length_m: Option<f64>,
    /// Proven lower bound on the optimal length, metres.
    pub lower_m: f64,
    /// Whether `length_m` is proven optimal.
    pub optimal: bool,
    /// States expanded.
    pub expanded: u64,
    /// Wall-clock seconds of the search (not part of results).
    pub wall_s: f64,
}

impl OptimalPath {
    /// Competitive ratio of an online path of `online_m` metres against the best path found.
    pub fn ratio(&self, online_m: f64) -> Option<f64> {
        self.length_m
            .and_then(|l| optimal::competitive_ratio(online_m, l))
    }
}

/// The cache key of an optimal path.
pub fn key(env: &str, sensor: &SensorSpec, start: Cell, goal: f64, spec: &OptimalSpec) -> String {
    format!(
        "{env}|{sensor}|start={},{}|G={goal}|{}",
        start.x,
        start.y,
        spec.fingerprint()
    )
}

/// Solve the optimal exploration path of `map` from `start`.
pub fn solve_path(
    map: &GridMap,
    start: Cell,
    sensor: &SensorSpec,
    goal: f64,
    spec: &OptimalSpec,
) -> Result<OptimalPath, BenchError> {
    let co = coarsen_problem(map, spec.cell_size, start, sensor)
        .map_err(|e| BenchError::Other(format!("optimal path: {e}")))?;
    let cfg = Config {
        goal,
        actions: match spec.min_cluster {
            Some(k) => ActionSet::Clusters { min_size: k.max(1) },
            None => ActionSet::Boundary,
        },
        weight: spec.weight,
        max_nodes: spec.max_nodes,
        max_bytes: spec.memory_mb.saturating_mul(1 << 20),
        time_limit: None,
        ..Config::default()
    };
    let out =
        solve(&co.problem, &cfg).map_err(|e| BenchError::Other(format!("optimal path: {e}")))?;
    let res = co.resolution();
    Ok(OptimalPath {
        length_m: out.upper_bound.is_finite().then_some(out.upper_bound * res),
        lower_m: out.lower_bound * res,
        optimal: out.status == Status::Optimal,
        expanded: out.stats.expanded,
        wall_s: out.stats.seconds,
    })
}

/// One cache entry: solved once, then read by every trial that needs it.
type Slot = Arc<OnceLock<Result<OptimalPath, String>>>;

/// Optimal paths shared by parallel trials: each key is solved once, by the first trial
/// that needs it, while the others wait for it.
#[derive(Default)]
pub struct Cache {
    slots: Mutex<HashMap<String, Slot>>,
}

impl Cache {
    /// A cache holding `known` (paths already in the store).
    pub fn new(known: impl IntoIterator<Item = (String, OptimalPath)>) -> Self {
        let slots = known
            .into_iter()
            .map(|(k, p)| {
                let cell = OnceLock::new();
                let _ = cell.set(Ok(p));
                (k, Arc::new(cell))
            })
            .collect();
        Self {
            slots: Mutex::new(slots),
        }
    }

    /// The path of `key`, solving it with `solve` if nobody has; whether this call solved it.
    pub fn get_or_solve(
        &self,
        key: &str,
        solve: impl FnOnce() -> Result<OptimalPath, BenchError>,
    ) -> (Result<OptimalPath, String>, bool) {
        let slot = {
            let mut slots = match self.slots.lock() {
                Ok(s) => s,
                Err(p) => p.into_inner(),
            };
            slots.entry(key.to_string()).or_default().clone()
        };
        let mut solved = false;
        let r = slot.get_or_init(|| {
            solved = true;
            solve().map_err(|e| e.to_string())
        });
        (r.clone(), solved)
    }
}

/// The competitive-ratio table of one setting (strategy → its trials): per strategy n, how
/// many optima were proven, the ratio's mean ± sd, median, min and max, and — when some
/// searches stopped at their budget — the mean of the ratio's upper bound (online over the
/// proven lower bound). `None` when no trial has a ratio.
pub fn ratio_table(
    by_strategy: &std::collections::BTreeMap<String, Vec<&crate::store::TrialRow>>,
) -> Option<(Vec<String>, Vec<Vec<String>>)> {
    let f = |x: f64| format!("{x:.3}");
    let mut body = Vec::new();
    let mut any_unproven = false;
    for (s, rs) in by_strategy {
        let with: Vec<&&crate::store::TrialRow> = rs.iter().filter(|r| r.ratio.is_some()).collect();
        if with.is_empty() {
            continue;
        }
        let ratios: Vec<f64> = with.iter().filter_map(|r| r.ratio).collect();
        let proven = with
            .iter()
            .filter(|r| r.optimal_proven == Some(true))
            .count();
        any_unproven |= proven < with.len();
        let upper: Vec<f64> = with
            .iter()
            .filter_map(|r| {
                r.optimal_lower_m
                    .filter(|&l| l > 0.0)
                    .map(|l| r.total_path / l)
            })
            .collect();
        let mut row = vec![
            s.clone(),
            with.len().to_string(),
            format!("{proven}/{}", with.len()),
        ];
        match crate::stats::summarize(&ratios) {
            Ok(x) => row.extend([
                crate::report::mean_sd(x.mean, x.sd, f),
                f(x.median),
                f(x.min),
                f(x.max),
            ]),
            Err(e) => row.extend([e.to_string(), String::new(), String::new(), String::new()]),
        }
        row.push(if proven < with.len() && !upper.is_empty() {
            f(upper.iter().sum::<f64>() / upper.len() as f64)
        } else {
            "–".into()
        });
        body.push(row);
    }
    if body.is_empty() {
        return None;
    }
    let mut header = [
        "strategy",
        "n",
        "optimum proven",
        "ratio mean ± sd",
        "median",
        "min",
        "max",
        "mean ratio ≤ (budget hit)",
    ]
    .map(String::from)
    .to_vec();
    if !any_unproven {
        header.pop();
        for r in &mut body {
            r.pop();
        }
    }
    Some((header, body))
}
