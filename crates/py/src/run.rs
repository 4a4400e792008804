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
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use crate::map::{Map, memory_mb_arg};
use crate::{bool_arg, guarded, int_arg, internal, real_arg, str_arg, type_error, value_error};

/// The most threads `explore_many` takes: far more than any machine's cores, so only a
/// mistake (`threads=10**6`) is refused.
pub const MAX_THREADS: usize = 4096;

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
        let key = str_arg(&k, "kwargs", "str keys")?;
        // None leaves these unset (the CLI's default, or no clutter); others refuse it.
        if v.is_none()
            && matches!(
                key.as_str(),
                "start"
                    | "belief"
                    | "sensing"
                    | "motion"
                    | "coverage"
                    | "s_max"
                    | "goal"
                    | "clutter"
            )
        {
            continue;
        }
        let v = &v;
        match key.as_str() {
            "strategy" => o.strategy = str_arg(v, "strategy", "a str")?,
            "sensor" => o.sensor = str_arg(v, "sensor", "a str")?,
            "belief" => o.belief = Some(str_arg(v, "belief", "a str or None")?),
            "sensing" => o.sensing = Some(str_arg(v, "sensing", "a str or None")?),
            "motion" => o.motion = Some(str_arg(v, "motion", "a str or None")?),
            "coverage" => o.coverage = Some(str_arg(v, "coverage", "a str or None")?),
            "robots" => {
                o.robots = int_arg(v, "robots", |n| {
                    value_error(if n.starts_with('-') {
                        format!("--robots: expected at least 1, found {n}")
                    } else {
                        format!("--robots: expected at most {}, found {n}", usize::MAX)
                    })
                })?;
                if o.robots < 1 {
                    return Err(value_error("--robots: expected at least 1, found 0"));
                }
            }
            "seed" => {
                o.seed = int_arg(v, "seed", |n| {
                    value_error(format!("--seed: expected an integer in 0..2^64, found {n}"))
                })?;
            }
            "start" => {
                let (x, y) = crate::pair_arg(v, "start", "a cell (x, y)", start_item)?;
                let (Some(cx), Some(cy)) = (x.0, y.0) else {
                    return Err(value_error(format!(
                        "start: expected a cell (x, y) of 32-bit integers, found ({}, {})",
                        x.1, y.1
                    )));
                };
                o.start = Some(Cell::new(cx, cy));
            }
            "clearance" => o.clearance = real_arg(v, "clearance", "a number of metres")?,
            "speed" => o.speed = real_arg(v, "speed", "a number of metres per second")?,
            "s_max" => {
                o.s_max = Some(int_arg(v, "s_max", |n| {
                    value_error(format!(
                        "--s-max: expected a positive number of cell moves or -1 (on arrival), \
                         found {n}"
                    ))
                })?);
            }
            "goal" => o.goal = Some(real_arg(v, "goal", "a number or None")?),
            "max_moves" => {
                o.max_moves = int_arg(v, "max_moves", |n| {
                    value_error(format!(
                        "--max-moves: expected an integer in 0..2^64, found {n}"
                    ))
                })?;
            }
            "trajectories" => o.record_trace = bool_arg(v, "trajectories")?,
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

/// One coordinate of `start=`: a Python or numpy integer of any size (not a bool or a
/// float), as the 32-bit integer cells are numbered in if it is one, and its digits.
pub(crate) fn start_item(v: &Bound<'_, PyAny>) -> Option<(Option<i32>, String)> {
    Some(match crate::int_value(v)? {
        Ok(n) => (i32::try_from(n).ok(), n.to_string()),
        Err(digits) => (None, digits),
    })
}

/// A run ready to go: the map and its resolved configuration.
struct Job {
    map: Map,
    cfg: RunConfig,
}

/// Resolve one run; `memory_mb` is the user's budget (the CLI's `--memory-mb`).
fn job(map: &Map, kw: Option<&Bound<'_, PyDict>>, memory_mb: Option<u64>) -> PyResult<Job> {
    let mut o = options(kw)?;
    o.or_marked_start(map.start);
    let clutter = match kw.map(|kw| kw.get_item("clutter")).transpose()?.flatten() {
        Some(v) if !v.is_none() => Some(clutter_layer(map, &v)?),
        _ => None,
    };
    let mut cfg = config(&o, &map.map, clutter).map_err(value_error)?;
    bench::explore::check_memory(&mut cfg, &map.map, memory_mb).map_err(value_error)?;
    Ok(Job {
        map: map.clone(),
        cfg,
    })
}

/// Off-plane obstacles (`clutter=`, as the CLI's `--clutter-map`): the occupied cells of
/// a `Map` of the map's size.
fn clutter_layer(map: &Map, v: &Bound<'_, PyAny>) -> PyResult<grid::Grid<bool>> {
    let layer: PyRef<'_, Map> = v
        .extract()
        .map_err(|_| type_error("clutter", "a frontier.Map", v))?;
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
/// `memory_mb` MiB or the machine has available (as `frontier bench` does for its trials);
/// returns the bytes they take at once.
fn check_memory(jobs: &[Job], threads: Option<usize>, memory_mb: Option<u64>) -> PyResult<u64> {
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
        grid::machine::available(),
        "use fewer threads (threads=...) or maps with fewer cells",
    )
    .map_err(|e| value_error(e.to_string()))?;
    Ok(sim::memory::at_once(&needs, workers))
}

/// Run a job (panics caught), its scans through `sight` if given ([`sim::BatchSights`]),
/// until it ends, or until `stop` is raised (`None`).
fn execute(
    j: &Job,
    sight: Option<&Arc<sense::SightCache>>,
    stop: &AtomicBool,
) -> Result<Option<RunResult>, String> {
    guarded(|| {
        sim::run_pausing(&j.map.map, &j.cfg, sight, SLICE, |_| {
            !stop.load(Ordering::Relaxed)
        })
    })?
    .map_err(|e| e.to_string())
}

/// Steps of a run between two looks at the stop flag (a run stops within a few
/// milliseconds of Ctrl-C; pausing the loop does not change the run).
const SLICE: u64 = 64;

/// How often the waiting Python thread wakes to handle signals and report progress.
const TICK: Duration = Duration::from_millis(100);

/// Held by a worker: dropped when it ends (also by a panic, as it unwinds), it raises the
/// flag and wakes the thread waiting for it at once.
struct Ended<'a>(&'a (Mutex<bool>, Condvar));

impl Drop for Ended<'_> {
    fn drop(&mut self) {
        *self.0.0.lock().unwrap_or_else(|e| e.into_inner()) = true;
        self.0.1.notify_all();
    }
}

/// Run `work` on a thread of its own with the GIL released, waking every [`TICK`] to let
/// Python handle signals: Ctrl-C raises `KeyboardInterrupt` within a tick. Work that cannot
/// stop part way (a map being generated or read) is then left to finish in the background,
/// and its result is dropped.
pub(crate) fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    use std::sync::mpsc::{RecvTimeoutError, channel};
    let (tx, rx) = channel();
    std::thread::Builder::new()
        .name("frontier-work".into())
        .spawn(move || {
            // nobody waits for it any more after an interrupt
            let _ = tx.send(guarded(work));
        })
        .map_err(|e| internal(format!("could not start a thread: {e}")))?;
    let mut rx = rx;
    loop {
        // (a receiver is not Sync: it goes into the closure and comes back)
        let got;
        (got, rx) = py.detach(move || (rx.recv_timeout(TICK), rx));
        match got {
            Ok(out) => return out.map_err(internal),
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
            Err(RecvTimeoutError::Disconnected) => {
                return Err(internal(
                    "internal error (please report): a worker ended".into(),
                ));
            }
        }
    }
}

/// Run `work` on another thread with the GIL released, waking every [`TICK`] to let Python
/// handle signals (Ctrl-C raises `KeyboardInterrupt`) and to call `tick`. An error from
/// either raises `stop`, which `work` is to watch, and is returned once `work` has ended.
fn with_checks<T: Send>(
    py: Python<'_>,
    stop: &AtomicBool,
    work: impl FnOnce() -> T + Send,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    let ended = (Mutex::new(false), Condvar::new());
    std::thread::scope(|scope| {
        let signal = Ended(&ended);
        let handle = scope.spawn(move || {
            let _signal = signal;
            work()
        });
        let mut failed = None;
        loop {
            let finished = py.detach(|| {
                let (lock, cv) = &ended;
                let done = lock.lock().unwrap_or_else(|e| e.into_inner());
                let (done, _) = cv
                    .wait_timeout_while(done, TICK, |d| !*d)
                    .unwrap_or_else(|e| e.into_inner());
                *done
            });
            if finished {
                break;
            }
            if failed.is_none()
                && let Err(e) = py.check_signals().and_then(|()| tick(py))
            {
                stop.store(true, Ordering::Relaxed);
                failed = Some(e);
            }
        }
        let out = handle
            .join()
            .map_err(|_| internal("internal error (please report): a worker panicked".into()))?;
        match failed {
            Some(e) => Err(e),
            None => Ok(out),
        }
    })
}

/// The JSON summary text (`--json --no-timing` unless `timing`).
fn summary(j: &Job, r: &RunResult, timing: bool) -> String {
    summary_json(&j.map.name, &j.map.map, &j.cfg, r, timing).to_string()
}

/// `map=` of `explore`.
fn map_arg<'py>(v: &Bound<'py, PyAny>) -> PyResult<PyRef<'py, Map>> {
    v.extract()
        .map_err(|_| type_error("map", "a frontier.Map", v))
}

/// `kwargs=` of `explore`: the run's options, or None.
fn kwargs_arg<'py>(v: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyDict>>> {
    if v.is_none() {
        return Ok(None);
    }
    v.cast::<PyDict>()
        .map(|d| Some(d.clone()))
        .map_err(|_| type_error("kwargs", "a dict or None", v))
}

/// `timing=` of `explore` and `explore_many`.
fn timing_arg(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    bool_arg(v, "timing")
}

/// `runs=` of `explore_many`: (map, kwargs) pairs.
#[allow(clippy::type_complexity)]
fn runs_arg<'py>(
    v: &Bound<'py, PyAny>,
) -> PyResult<Vec<(PyRef<'py, Map>, Option<Bound<'py, PyDict>>)>> {
    v.extract()
        .map_err(|_| type_error("runs", "a list of (frontier.Map, dict or None) pairs", v))
}

/// `threads=` of `explore_many`: None, or 1 to [`MAX_THREADS`] (a Python or numpy int).
fn threads_arg(v: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    if v.is_none() {
        return Ok(None);
    }
    let range = |n: &str| {
        value_error(if n.starts_with('-') || n == "0" {
            format!("threads: expected at least 1, found {n}")
        } else {
            format!("threads: expected at most {MAX_THREADS}, found {n}")
        })
    };
    let n: i128 = int_arg(v, "threads", range)?;
    if n < 1 || n > MAX_THREADS as i128 {
        return Err(range(&n.to_string()));
    }
    Ok(Some(n as usize))
}

/// `progress=` of `explore_many`: None, or a callable.
fn progress_arg(v: &Bound<'_, PyAny>) -> PyResult<Option<Py<PyAny>>> {
    if v.is_none() {
        return Ok(None);
    }
    if !v.is_callable() {
        return Err(type_error("progress", "a callable or None", v));
    }
    Ok(Some(v.clone().unbind()))
}

/// One run: returns (summary JSON text, final belief (H, W) uint8, trajectories as a list
/// of (n, 2) int32 arrays of (x, y) cells, or None when not recorded).
/// A run whose estimated memory exceeds `memory_mb` MiB or what the machine has available
/// is refused before it starts.
#[pyfunction]
#[pyo3(signature = (map, kwargs=None, timing=false, memory_mb=None))]
pub fn explore<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = map_arg)] map: PyRef<'py, Map>,
    #[pyo3(from_py_with = kwargs_arg)] kwargs: Option<Bound<'py, PyDict>>,
    #[pyo3(from_py_with = timing_arg)] timing: bool,
    #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
) -> PyResult<(String, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let j = job(&map, kwargs.as_ref(), memory_mb)?;
    let stop = AtomicBool::new(false);
    let r = with_checks(py, &stop, || execute(&j, None, &stop), |_| Ok(()))?
        .map_err(|e| {
            if e.starts_with("internal error") {
                internal(e)
            } else {
                value_error(e)
            }
        })?
        .ok_or_else(|| internal("internal error (please report): a run stopped unasked".into()))?;
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
/// checked before any starts; an error names the run's index. `threads` (at most
/// [`MAX_THREADS`]) is capped at the number of runs. The largest runs, one per thread, must
/// fit in `memory_mb` MiB and in the memory the machine has available.
/// `progress(done, total)` is called about ten times a second while runs finish and once at
/// the end; an exception from it, or Ctrl-C, stops the batch and is raised.
#[pyfunction]
#[pyo3(signature = (runs, threads=None, timing=false, memory_mb=None, progress=None))]
pub fn explore_many<'py>(
    py: Python<'py>,
    #[pyo3(from_py_with = runs_arg)] runs: Vec<(PyRef<'py, Map>, Option<Bound<'py, PyDict>>)>,
    #[pyo3(from_py_with = threads_arg)] threads: Option<usize>,
    #[pyo3(from_py_with = timing_arg)] timing: bool,
    #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
    #[pyo3(from_py_with = progress_arg)] progress: Option<Py<PyAny>>,
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
    // The checks each run's start makes (its sensor on its map's cells, the starts given),
    // made for every run before any starts: a sensor once per spec, resolution, clearance
    // and kind of candidates.
    let mut sensed = std::collections::HashSet::new();
    for (i, j) in jobs.iter().enumerate() {
        let sensor = (
            j.cfg.sensor.to_string(),
            j.map.map.resolution.to_bits(),
            j.cfg.clearance_m.to_bits(),
            format!("{:?}", j.cfg.strategy.candidates),
        );
        sim::check_run(&j.map.map, &j.cfg, sensed.insert(sensor))
            .map_err(|e| value_error(format!("run {i}: {e}")))?;
    }
    let at_once = check_memory(&jobs, threads, memory_mb)?;
    // Runs on the same map share what the line-of-sight sensor sees from its cells.
    let sights = sim::BatchSights::new(
        jobs.iter()
            .map(|j| (Arc::as_ptr(&j.map.map) as usize, &*j.map.map, j.cfg.sensor)),
        sim::BatchSights::budget(memory_mb, grid::machine::available(), at_once),
    );
    let pool = match threads {
        // No more threads than runs: a thread with no run to take would only be started.
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n.min(jobs.len()).max(1))
                .build()
                .map_err(|e| value_error(format!("threads: {e}")))?,
        ),
        None => None,
    };
    let (stop, done) = (AtomicBool::new(false), AtomicUsize::new(0));
    let work = || {
        let all = || -> Vec<Result<Option<String>, String>> {
            jobs.par_iter()
                .enumerate()
                .map(|(i, j)| {
                    if stop.load(Ordering::Relaxed) {
                        return Ok(None);
                    }
                    let sight = sights.get(i, &j.map.map);
                    let r = execute(j, sight.as_ref(), &stop)
                        .map(|r| r.map(|r| summary(j, &r, timing)));
                    done.fetch_add(1, Ordering::Relaxed);
                    r
                })
                .collect()
        };
        match &pool {
            Some(p) => p.install(all),
            None => all(),
        }
    };
    let total = jobs.len();
    let mut told = usize::MAX;
    let mut report = |py: Python<'_>| -> PyResult<()> {
        let now = done.load(Ordering::Relaxed);
        if let Some(f) = &progress
            && now != told
        {
            told = now;
            f.call1(py, (now, total))?;
        }
        Ok(())
    };
    let out = with_checks(py, &stop, work, &mut report)?;
    let mut texts = Vec::with_capacity(out.len());
    // the first failed run, in order
    for (i, r) in out.into_iter().enumerate() {
        match r {
            Ok(Some(t)) => texts.push(t),
            Ok(None) => {
                return Err(internal(
                    "internal error (please report): a run stopped unasked".into(),
                ));
            }
            Err(e) if e.contains("internal error") => {
                return Err(internal(format!("run {i}: {e}")));
            }
            Err(e) => return Err(value_error(format!("run {i}: {e}"))),
        }
    }
    report(py)?;
    Ok(texts)
}

/// Every strategy name a run takes: (name, description) pairs, the presets `frontier list`
/// prints, then each team name `<assigner>-<candidates>` spelled out.
#[pyfunction]
pub fn strategies() -> Vec<(String, String)> {
    ::explore::strategy::every_name()
}
