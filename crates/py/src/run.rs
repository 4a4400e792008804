//! `frontier.explore` and `frontier.explore_many`: runs through the CLI's code path
//! (`bench::explore`), so the numbers equal `frontier explore --json --no-timing`.

use bench::explore::{ExploreOptions, config, summary_json};
use grid::Cell;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use sim::{RunConfig, RunResult};

use crate::map::Map;
use crate::{guarded, internal, value_error};

/// The keyword arguments `explore` takes besides the map.
const KEYS: &[&str] = &[
    "strategy",
    "sensor",
    "robots",
    "seed",
    "start",
    "belief",
    "sensing",
    "motion",
    "coverage",
    "clearance",
    "speed",
    "s_max",
    "goal",
    "max_moves",
    "trajectories",
    "clutter",
];

/// Read `explore`'s keyword arguments from `kw` into options (CLI defaults for the rest).
pub(crate) fn options(kw: Option<&Bound<'_, PyDict>>) -> PyResult<ExploreOptions> {
    let mut o = ExploreOptions {
        record_trace: true,
        ..ExploreOptions::default()
    };
    let Some(kw) = kw else { return Ok(o) };
    for (k, v) in kw.iter() {
        let key: String = k.extract()?;
        if v.is_none() {
            if matches!(
                key.as_str(),
                "start" | "belief" | "sensing" | "motion" | "coverage" | "s_max" | "goal"
            ) {
                continue;
            }
            return Err(PyTypeError::new_err(format!("{key}: None is not allowed")));
        }
        let typed = |what: &str| {
            PyTypeError::new_err(format!(
                "{key}: expected {what}, found {}",
                v.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        };
        match key.as_str() {
            "strategy" => o.strategy = v.extract().map_err(|_| typed("a str"))?,
            "sensor" => o.sensor = v.extract().map_err(|_| typed("a str"))?,
            "belief" => o.belief = Some(v.extract().map_err(|_| typed("a str"))?),
            "sensing" => o.sensing = Some(v.extract().map_err(|_| typed("a str"))?),
            "motion" => o.motion = Some(v.extract().map_err(|_| typed("a str"))?),
            "coverage" => o.coverage = Some(v.extract().map_err(|_| typed("a str"))?),
            "robots" => {
                let n: i64 = v.extract().map_err(|_| typed("an int"))?;
                if n < 1 {
                    return Err(value_error(format!(
                        "--robots: expected at least 1, found {n}"
                    )));
                }
                o.robots = n as usize;
            }
            "seed" => {
                let s: i128 = v.extract().map_err(|_| typed("an int"))?;
                o.seed = u64::try_from(s).map_err(|_| {
                    value_error(format!("--seed: expected an integer in 0..2^64, found {s}"))
                })?;
            }
            "start" => {
                let (x, y): (i64, i64) = v.extract().map_err(|_| typed("a cell (x, y)"))?;
                let (x, y) = (
                    i32::try_from(x).unwrap_or(i32::MAX),
                    i32::try_from(y).unwrap_or(i32::MAX),
                );
                o.start = Some(Cell::new(x, y));
            }
            "clearance" => o.clearance = v.extract().map_err(|_| typed("a float"))?,
            "speed" => o.speed = v.extract().map_err(|_| typed("a float"))?,
            "s_max" => o.s_max = Some(v.extract().map_err(|_| typed("an int"))?),
            "goal" => o.goal = Some(v.extract().map_err(|_| typed("a float"))?),
            "max_moves" => {
                let n: i128 = v.extract().map_err(|_| typed("an int"))?;
                o.max_moves = u64::try_from(n).map_err(|_| {
                    value_error(format!(
                        "--max-moves: expected a non-negative integer, found {n}"
                    ))
                })?;
            }
            "trajectories" => o.record_trace = v.extract().map_err(|_| typed("a bool"))?,
            // Read by `job` (it is a map, not an option).
            "clutter" => {}
            _ => {
                return Err(PyTypeError::new_err(format!(
                    "explore() got an unexpected keyword argument '{key}' (expected one of {})",
                    KEYS.join(", ")
                )));
            }
        }
    }
    Ok(o)
}

/// A run ready to go: the map and its resolved configuration.
struct Job {
    map: Map,
    cfg: RunConfig,
}

/// Resolve one run; `memory_mb` is the user's budget (the CLI's `--memory-mb`).
fn job(map: &Map, kw: Option<&Bound<'_, PyDict>>, memory_mb: Option<u64>) -> PyResult<Job> {
    let mut o = options(kw)?;
    o.start = o.start.or(map.start);
    let clutter = match kw.map(|kw| kw.get_item("clutter")).transpose()?.flatten() {
        Some(v) if !v.is_none() => Some(clutter_layer(map, &v)?),
        _ => None,
    };
    let cfg = config(&o, &map.map, clutter).map_err(value_error)?;
    bench::explore::check_memory(&cfg, &map.map, memory_mb).map_err(value_error)?;
    Ok(Job {
        map: map.clone(),
        cfg,
    })
}

/// Off-plane obstacles (`clutter=`, as the CLI's `--clutter-map`): the occupied cells of
/// a `Map` of the map's size.
fn clutter_layer(map: &Map, v: &Bound<'_, PyAny>) -> PyResult<grid::Grid<bool>> {
    let layer: PyRef<'_, Map> = v.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "clutter: expected a frontier.Map, found {}",
            v.get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let (w, h) = (map.map.width(), map.map.height());
    if (layer.map.width(), layer.map.height()) != (w, h) {
        return Err(value_error(format!(
            "clutter: expected the map's size {w}x{h} cells, found {}x{}",
            layer.map.width(),
            layer.map.height()
        )));
    }
    let cells = layer
        .map
        .cells
        .data()
        .iter()
        .map(|&c| c == grid::Occ::Occupied)
        .collect();
    grid::Grid::from_vec(w, h, cells).ok_or_else(|| internal("clutter layer size".to_string()))
}

/// Refuse a batch whose largest runs, one per thread, would need more memory at once than
/// `memory_mb` MiB or the machine has available (as `frontier bench` does for its trials).
fn check_memory(jobs: &[Job], threads: Option<usize>, memory_mb: Option<u64>) -> PyResult<()> {
    let workers = threads
        .unwrap_or_else(rayon::current_num_threads)
        .min(jobs.len());
    let needs: Vec<(u64, String)> = jobs
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let bytes = sim::memory::run_bytes(j.map.map.cells.len(), j.map.map.resolution, &j.cfg);
            (bytes, format!("run {i}"))
        })
        .collect();
    sim::memory::check_batch(
        "runs",
        &needs,
        workers,
        memory_mb,
        bench::machine::available_bytes(),
        "use fewer threads (threads=...) or maps with fewer cells",
    )
    .map_err(|e| value_error(e.to_string()))
}

/// Run a job (panics caught).
fn execute(j: &Job) -> Result<RunResult, String> {
    guarded(|| sim::run(&j.map.map, &j.cfg))?.map_err(|e| e.to_string())
}

/// The JSON summary text (`--json --no-timing` unless `timing`).
fn summary(j: &Job, r: &RunResult, timing: bool) -> String {
    summary_json(&j.map.name, &j.map.map, &j.cfg, r, timing).to_string()
}

/// One run: returns (summary JSON text, final belief (H, W) uint8, trajectories as a list
/// of (n, 2) int32 arrays of (x, y) cells, or None when not recorded).
/// A run whose estimated memory exceeds `memory_mb` MiB or what the machine has available
/// is refused before it starts.
#[pyfunction]
#[pyo3(signature = (map, kwargs=None, timing=false, memory_mb=None))]
pub fn explore<'py>(
    py: Python<'py>,
    map: &Map,
    kwargs: Option<&Bound<'py, PyDict>>,
    timing: bool,
    memory_mb: Option<u64>,
) -> PyResult<(String, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let j = job(map, kwargs, memory_mb)?;
    let r = py.detach(|| execute(&j)).map_err(|e| {
        if e.starts_with("internal error") {
            internal(e)
        } else {
            value_error(e)
        }
    })?;
    let text = summary(&j, &r, timing);
    let belief: Vec<u8> = r.belief.data().iter().map(|&o| o as u8).collect();
    let belief = PyArray1::from_vec(py, belief)
        .reshape([r.belief.height(), r.belief.width()])?
        .into_any();
    let trajectories = match &r.trace {
        Some(t) => {
            let w = r.belief.width();
            let list = PyList::empty(py);
            for trail in t.trails() {
                let xy: Vec<i32> = trail
                    .iter()
                    .flat_map(|&i| [(i as usize % w) as i32, (i as usize / w) as i32])
                    .collect();
                let n = trail.len();
                list.append(PyArray1::from_vec(py, xy).reshape([n, 2])?)?;
            }
            list.into_any()
        }
        None => py.None().into_bound(py),
    };
    Ok((text, belief, trajectories))
}

/// Many runs in parallel on Rust threads with the GIL released: `runs` is a list of
/// (map, kwargs) pairs; returns one summary JSON text per run, in order. Every run is
/// checked before any starts; an error names the run's index. The largest runs, one per
/// thread, must fit in `memory_mb` MiB and in the memory the machine has available.
#[pyfunction]
#[pyo3(signature = (runs, threads=None, timing=false, memory_mb=None))]
pub fn explore_many(
    py: Python<'_>,
    runs: Vec<(PyRef<'_, Map>, Option<Bound<'_, PyDict>>)>,
    threads: Option<usize>,
    timing: bool,
    memory_mb: Option<u64>,
) -> PyResult<Vec<String>> {
    let mut jobs = Vec::with_capacity(runs.len());
    for (i, (map, kw)) in runs.iter().enumerate() {
        if let Some(kw) = kw
            && kw.contains("trajectories")?
        {
            return Err(PyTypeError::new_err(format!(
                "run {i}: explore_many returns summaries only; drop 'trajectories'"
            )));
        }
        let mut j = job(map, kw.as_ref(), memory_mb).map_err(|e| {
            let msg = format!("run {i}: {}", e.value(py));
            if e.is_instance_of::<PyTypeError>(py) {
                PyTypeError::new_err(msg)
            } else {
                value_error(msg)
            }
        })?;
        j.cfg.record_trace = false;
        jobs.push(j);
    }
    if threads == Some(0) {
        return Err(value_error("threads: expected at least 1, found 0"));
    }
    check_memory(&jobs, threads, memory_mb)?;
    let out: Result<Vec<String>, String> = py.detach(|| {
        let work = || {
            jobs.par_iter()
                .enumerate()
                .map(|(i, j)| {
                    execute(j)
                        .map(|r| summary(j, &r, timing))
                        .map_err(|e| format!("run {i}: {e}"))
                })
                .collect()
        };
        match threads {
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| e.to_string())?
                .install(work),
            None => work(),
        }
    });
    out.map_err(|e| {
        if e.contains("internal error") {
            internal(e)
        } else {
            value_error(e)
        }
    })
}

/// The strategy presets: (name, description) pairs, as `frontier list` prints them.
#[pyfunction]
pub fn strategies() -> Vec<(&'static str, &'static str)> {
    ::explore::strategy::PRESETS.to_vec()
}
