//! Running a plan: parallel seeded trials, a progress bar, shards and resumption
//! (issue 9, "Running").
//!
//! Trials run on a rayon pool of the requested size; each finished trial is written to the
//! store at once. Because every trial's seed comes from the plan (never from thread order)
//! and rows are keyed, the database's contents do not depend on the thread count, the
//! order of completion, interruptions or shards — only the `wall_s` column does.
//! A trial that fails (a simulation error, or a panic in a piece of a strategy) is reported
//! and not stored, so a later run retries it.

use std::panic::AssertUnwindSafe;
use std::path::Path;
use std::sync::Mutex;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use sim::RunResult;

use crate::error::BenchError;
use crate::plan::{Plan, Trial};
use crate::store::{Store, TrialRow, TrialSetup};

/// The program version written into every row.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Shard `index` of `count` (1-based, as `--shard I/N`): trial number i belongs to shard
/// `i mod N + 1`, so shards get equal shares of every part of the study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, 1..=count.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let err = || format!("--shard: expected I/N with 1 <= I <= N (e.g. 2/8), found '{s}'");
        let (i, n) = s.split_once('/').ok_or_else(err)?;
        let index: usize = i.trim().parse().map_err(|_| err())?;
        let count: usize = n.trim().parse().map_err(|_| err())?;
        if index == 0 || count == 0 || index > count {
            return Err(err());
        }
        Ok(Shard { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// Whether trial number `i` of the whole study ([`Trial::number`]) belongs to this
    /// shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }

    /// How many of `trials` belong to this shard.
    pub fn share(&self, trials: &[Trial]) -> usize {
        trials.iter().filter(|t| self.contains(t.number)).count()
    }
}

/// How to run a plan.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Worker threads (`None`: rayon's default, one per core).
    pub threads: Option<usize>,
    /// Run only this shard's trials.
    pub shard: Option<Shard>,
    /// Show a progress bar on standard error.
    pub progress: bool,
    /// Run at most this many of the pending trials (the first ones in plan order).
    pub limit: Option<usize>,
    /// Refuse to start when the largest trials, one per thread, would need more than this
    /// many MiB at once (`--memory-mb`; the machine's available memory is checked always).
    pub memory_mb: Option<u64>,
}

/// What a run did.
#[derive(Clone, Debug, Default)]
pub struct RunSummary {
    /// Trials of the plan (of the shard, if any).
    pub total: usize,
    /// Of those, already in the database before this run.
    pub already_done: usize,
    /// Trials run and stored now.
    pub ran: usize,
    /// Trials run now that another run writing to the same database stored first
    /// (the store keeps the first row of a trial).
    pub stored_meanwhile: usize,
    /// Trials that failed: (key, message).
    pub failed: Vec<(String, String)>,
    /// Wall-clock seconds of this run.
    pub wall_s: f64,
}

/// Whether a progress bar should be drawn: standard error is a terminal and `CI` is unset.
pub fn progress_wanted() -> bool {
    use std::io::IsTerminal;
    std::io::stderr().is_terminal() && std::env::var_os("CI").is_none()
}

/// Run the trials of `plan` missing from the database at `db`.
pub fn run(plan: &Plan, db: &Path, opts: &RunOptions) -> Result<RunSummary, BenchError> {
    let started = Instant::now();
    let source = format!("the study ({})", plan.source);
    let pictures = plan
        .envs
        .iter()
        .map(env_picture)
        .collect::<Result<Vec<_>, _>>()?;
    let mine: Vec<&Trial> = plan
        .trials
        .iter()
        .filter(|t| opts.shard.is_none_or(|s| s.contains(t.number)))
        .collect();
    // The trials still to run, of those in `done`, at most `limit` of them.
    let pending_of = |done: &std::collections::BTreeSet<String>| -> Vec<&Trial> {
        let mut pending: Vec<&Trial> = mine
            .iter()
            .copied()
            .filter(|t| !done.contains(&t.key))
            .collect();
        if let Some(limit) = opts.limit {
            pending.truncate(limit);
        }
        pending
    };
    let fits = |pending: &[&Trial]| {
        check_memory(
            plan,
            pending,
            opts.threads,
            opts.memory_mb,
            grid::machine::available(),
        )
    };
    // A new store is made only for a run that fits in memory: refused, it leaves no file.
    // (Its pending trials are all of them; an existing store's are known once it is read.)
    let new_store = !db.exists();
    if new_store {
        fits(&pending_of(&Default::default()))?;
    }
    // An existing store is checked against the plan read-only first, so that a refused run
    // (an edited scenario) leaves it as it was; one that holds every environment and trial
    // of this run stays read-only, as nothing is left to write (a finished study re-run for
    // its report, from a store the user may only read). Its pending trials are checked
    // against the memory then too, so that a run refused for its memory writes nothing.
    let mut memory_checked = new_store;
    let store = Store::open_unless_finished(db, &plan.name, &plan.fingerprint(), |s| {
        let mut have_envs = true;
        for p in &pictures {
            have_envs &= s.check_env(p, &source)?;
        }
        let done = check_setups(plan, s, db)?;
        fits(&pending_of(&done))?;
        memory_checked = true;
        // An edited description is written too, so that the report says what it now says.
        let described = s.description_is(&plan.description)?;
        Ok(have_envs && described && mine.iter().all(|t| done.contains(&t.key)))
    })?;
    let done = check_setups(plan, &store, db)?;
    let done_count = mine.iter().filter(|t| done.contains(&t.key)).count();
    let pending = pending_of(&done);
    if !memory_checked {
        // A file that held nothing yet, made into a store as a new file is.
        fits(&pending)?;
    }
    if store.is_writable() {
        store.describe(&plan.description)?;
        for p in &pictures {
            store.put_env(p, &source)?;
        }
    }
    let mut summary = RunSummary {
        total: mine.len(),
        already_done: done_count,
        ..RunSummary::default()
    };
    let bar = if opts.progress {
        let bar =
            ProgressBar::with_draw_target(Some(pending.len() as u64), ProgressDrawTarget::stderr());
        if let Ok(style) = ProgressStyle::with_template(
            "{bar:40} {pos}/{len} trials · {per_sec} · ETA {eta} · {msg}",
        ) {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let optimal_cache = crate::competitive::Cache::new(store.optimal_paths()?);
    // What the trials leave of the memory limit is the line of sight's to remember.
    let budget = sim::BatchSights::budget(
        opts.memory_mb,
        grid::machine::available(),
        trials_at_once(plan, &pending, opts.threads).saturating_add(envs_held(plan)),
    );
    let sights = sim::BatchSights::new(
        pending.iter().map(|t| {
            (
                t.env,
                &plan.envs[t.env].map,
                plan.variants[t.variant].sensor,
            )
        }),
        budget,
    );
    let store = Mutex::new(store);
    let failed = Mutex::new(Vec::new());
    let fatal: Mutex<Option<BenchError>> = Mutex::new(None);
    let ran = std::sync::atomic::AtomicUsize::new(0);
    let meanwhile = std::sync::atomic::AtomicUsize::new(0);
    let work = || {
        pending.par_iter().enumerate().for_each(|(i, t)| {
            if fatal.lock().map(|f| f.is_some()).unwrap_or(true) {
                return;
            }
            let t0 = Instant::now();
            let cfg = plan.config(t);
            let map = &plan.envs[t.env].map;
            let sight = sights.get(i, map);
            let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| {
                sim::run_sharing(map, &cfg, sight.as_ref())
            }));
            let wall_s = t0.elapsed().as_secs_f64();
            let message = match outcome {
                Ok(Ok(result)) => {
                    let mut r = row(plan, t, &result, wall_s);
                    match with_optimal(plan, t, &result, &optimal_cache, &store, &mut r) {
                        Err(e) => Some(e.to_string()),
                        Ok(()) => {
                            let inserted = store
                                .lock()
                                .map_err(|e| BenchError::Other(e.to_string()))
                                .and_then(|s| s.insert(&r));
                            match inserted {
                                Ok(new) => {
                                    let count = if new { &ran } else { &meanwhile };
                                    count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                                    None
                                }
                                Err(e) => {
                                    if let Ok(mut f) = fatal.lock() {
                                        f.get_or_insert(e);
                                    }
                                    None
                                }
                            }
                        }
                    }
                }
                Ok(Err(e)) => Some(e.to_string()),
                Err(payload) => Some(format!(
                    "panicked: {}",
                    crate::built::panic_message(payload.as_ref())
                )),
            };
            if let Some(m) = message {
                if let Ok(mut f) = failed.lock() {
                    f.push((t.key.clone(), m));
                }
                bar.set_message(format!("{} failed", failed.lock().map_or(0, |f| f.len())));
            }
            bar.inc(1);
        })
    };
    match worker_threads(opts.threads, pending.len()) {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| BenchError::Other(format!("--threads: {e}")))?
            .install(work),
        None => work(),
    }
    bar.finish_and_clear();
    if let Some(e) = fatal.into_inner().ok().flatten() {
        return Err(e);
    }
    let mut failed = failed.into_inner().unwrap_or_default();
    failed.sort();
    summary.failed = failed;
    summary.ran = ran.into_inner();
    summary.stored_meanwhile = meanwhile.into_inner();
    summary.wall_s = started.elapsed().as_secs_f64();
    Ok(summary)
}

/// The keys of the finished trials, once every one of them that the plan holds is checked
/// to have been run as the plan runs it: an edited scenario (another start, `s_max` or map
/// under the same names) plans trials of the same keys that the store would otherwise
/// count as done, keeping results of the old settings under the new ones.
fn check_setups(
    plan: &Plan,
    store: &Store,
    db: &Path,
) -> Result<std::collections::BTreeSet<String>, BenchError> {
    let stored = store.setups()?;
    for t in &plan.trials {
        let Some(have) = stored.get(&t.key) else {
            continue;
        };
        if let Some((column, was, now)) = have.difference(&setup(plan, t)) {
            return Err(BenchError::Store {
                path: db.to_path_buf(),
                message: format!(
                    "holds trial {} run with {column} {was}, but {} now runs it with {column} \
                     {now}: the study changed since these results were stored; run it into \
                     another database file, or undo the change",
                    t.key, plan.source
                ),
            });
        }
    }
    Ok(stored.into_keys().collect())
}

/// Each of `pending` trials' estimated bytes (its run and, with `[optimal]`, its optimal
/// path's search budget) with its key.
fn trial_needs(plan: &Plan, pending: &[&Trial]) -> Vec<(u64, String)> {
    pending
        .iter()
        .map(|t| {
            let map = &plan.envs[t.env].map;
            let run = sim::memory::run_bytes(map.cells.len(), map.resolution, &plan.config(t));
            // The optimal path is searched beside the run's result, within its budget.
            let v = &plan.variants[t.variant];
            let search = match &plan.optimal {
                Some(spec) if crate::competitive::OptimalSpec::applies(&v.sensor, v.robots) => {
                    (spec.memory_mb as u64).saturating_mul(1 << 20)
                }
                _ => 0,
            };
            (run.saturating_add(search), t.key.clone())
        })
        .collect()
}

/// The bytes the largest of `pending` trials take when one runs on each worker thread.
fn trials_at_once(plan: &Plan, pending: &[&Trial], threads: Option<usize>) -> u64 {
    let workers = workers_running(threads, pending.len());
    sim::memory::at_once(&trial_needs(plan, pending), workers)
}

/// Refuse to start when the largest trials, one per worker thread, would need more memory
/// at once than `memory_mb` MiB or the machine has `available` (estimated before any runs):
/// each trial's run and, with `[optimal]`, its optimal path's search budget.
fn check_memory(
    plan: &Plan,
    pending: &[&Trial],
    threads: Option<usize>,
    memory_mb: Option<u64>,
    available: Option<grid::memory::Available>,
) -> Result<(), BenchError> {
    let workers = workers_running(threads, pending.len());
    let needs = trial_needs(plan, pending);
    let fix = if plan.optimal.is_some() {
        "use fewer threads (-j), maps with fewer cells, or a smaller [optimal] memory_mb"
    } else {
        "use fewer threads (-j) or maps with fewer cells"
    };
    sim::memory::check_batch("trials", &needs, workers, memory_mb, available, fix)
        .map_err(|e| BenchError::Other(e.to_string()))?;
    // A user's budget holds the study's environments beside its trials (the machine's
    // available memory has them spent already).
    let held = envs_held(plan);
    sim::memory::check(
        &format!(
            "running {} trial{} on {workers} thread{} beside the {} MiB the study's {} \
             environment{} hold",
            needs.len(),
            if needs.len() == 1 { "" } else { "s" },
            if workers == 1 { "" } else { "s" },
            held.div_ceil(1 << 20),
            plan.envs.len(),
            if plan.envs.len() == 1 { "" } else { "s" },
        ),
        sim::memory::at_once(&needs, workers).saturating_add(held),
        memory_mb,
        None,
        fix,
    )
    .map_err(|e| BenchError::Other(e.to_string()))
}

/// The bytes the plan's environments hold while its trials run.
fn envs_held(plan: &Plan) -> u64 {
    plan.envs.iter().fold(0u64, |sum, e| {
        sum.saturating_add(
            (e.map.cells.len() as u64).saturating_mul(crate::plan::ENV_HELD_BYTES_PER_CELL),
        )
    })
}

/// The threads `pending` trials run on: [`worker_threads`], or rayon's pool's, no more
/// than there are trials.
fn workers_running(requested: Option<usize>, pending: usize) -> usize {
    worker_threads(requested, pending).unwrap_or_else(|| rayon::current_num_threads().min(pending))
}

/// Worker threads for `pending` trials when `requested` were asked for: never more than
/// there are trials (so `-j 10000` for 6 trials starts 6), at least one.
pub fn worker_threads(requested: Option<usize>, pending: usize) -> Option<usize> {
    requested.map(|n| n.min(pending).max(1))
}

/// Fill the optimal-path columns of `r` (studies with `[optimal]`, single robots with a 360°
/// sensor): the path from the trial's start is taken from `cache` or solved and stored.
fn with_optimal(
    plan: &Plan,
    t: &Trial,
    result: &RunResult,
    cache: &crate::competitive::Cache,
    store: &Mutex<Store>,
    r: &mut TrialRow,
) -> Result<(), BenchError> {
    let Some(spec) = &plan.optimal else {
        return Ok(());
    };
    let v = &plan.variants[t.variant];
    let (Some(&start), true) = (
        result.starts.first(),
        crate::competitive::OptimalSpec::applies(&v.sensor, v.robots),
    ) else {
        return Ok(());
    };
    let env = &plan.envs[t.env];
    let goal = plan.common.coverage_goal.unwrap_or(1.0);
    let key = crate::competitive::key(&env.name, &v.sensor, start, goal, spec);
    let (path, solved) = cache.get_or_solve(&key, || {
        crate::competitive::solve_path(&env.map, start, &v.sensor, goal, spec)
    });
    // The caller names the trial.
    let path = path.map_err(BenchError::Other)?;
    if solved {
        store
            .lock()
            .map_err(|e| BenchError::Other(e.to_string()))?
            .put_optimal(&key, &path)?;
    }
    r.optimal_m = path.length_m;
    r.optimal_lower_m = Some(path.lower_m);
    r.optimal_proven = Some(path.optimal);
    // A trial that stopped short of the goal has no competitive ratio.
    r.ratio = path
        .ratio(r.total_path)
        .filter(|_| result.reason.reached_goal());
    Ok(())
}

/// The ground truth of `env` as a PNG picture.
pub fn env_picture(env: &crate::plan::EnvInstance) -> Result<crate::store::EnvPicture, BenchError> {
    let png = viz::map_picture(&env.map.cells)
        .to_png()
        .map_err(|e| BenchError::Other(format!("picture of {}: {e}", env.name)))?;
    Ok(crate::store::EnvPicture {
        name: env.name.clone(),
        width: env.map.width() as i64,
        height: env.map.height() as i64,
        resolution: env.map.resolution,
        png,
    })
}

/// At most 65 points of a curve, evenly spaced by index, first and last kept.
pub fn thin_curve(curve: &[(f64, f64)]) -> Vec<(f64, f64)> {
    const K: usize = 64;
    if curve.len() <= K + 1 {
        return curve.to_vec();
    }
    let n = curve.len() - 1;
    (0..=K).map(|k| curve[(k * n + K / 2) / K]).collect()
}

/// Start cells as stored, JSON `[[x, y], ...]`.
fn starts_json(starts: &[grid::Cell]) -> String {
    let cells: Vec<[i32; 2]> = starts.iter().map(|c| [c.x, c.y]).collect();
    serde_json::to_string(&cells).unwrap_or_default()
}

/// How trial `t` runs, as its row will store it (starts only when fixed by the plan).
pub fn setup(plan: &Plan, t: &Trial) -> TrialSetup {
    let v = &plan.variants[t.variant];
    let env = &plan.envs[t.env];
    let cfg = plan.config(t);
    TrialSetup {
        env_kind: env.kind.clone(),
        env_seed: env.env_seed.map(|s| s as i64),
        resolution: env.map.resolution,
        width: env.map.width() as i64,
        height: env.map.height() as i64,
        preset: v.strategy.name.clone(),
        s_max: v.strategy.replan.every_moves.map(i64::from),
        sensing: cfg.sensing_mode().to_string(),
        seed: t.seed.to_string(),
        starts: (!cfg.starts.is_empty()).then(|| starts_json(&cfg.starts)),
    }
}

/// The database row of trial `t` with `result`.
pub fn row(plan: &Plan, t: &Trial, result: &RunResult, wall_s: f64) -> TrialRow {
    let v = &plan.variants[t.variant];
    let env = &plan.envs[t.env];
    let s = setup(plan, t);
    TrialRow {
        key: t.key.clone(),
        scenario: plan.name.clone(),
        env: env.name.clone(),
        env_kind: s.env_kind,
        env_seed: s.env_seed,
        map_file: env.map_file.clone(),
        resolution: s.resolution,
        width: s.width,
        height: s.height,
        strategy: v.label.clone(),
        preset: s.preset,
        s_max: s.s_max,
        sensor: v.sensor.to_string(),
        belief: plan.belief(t).to_string(),
        sensing: s.sensing,
        robots: v.robots as i64,
        start_variant: i64::from(t.start_variant),
        trial: i64::from(t.trial),
        seed: s.seed,
        starts: starts_json(&result.starts),
        clearance: plan.common.clearance_m,
        speed: plan.common.speed,
        coverage_goal: plan.common.coverage_goal,
        max_moves: plan.common.max_moves.min(i64::MAX as u64) as i64,
        path_lengths: serde_json::to_string(&result.path_length_m).unwrap_or_default(),
        max_path: result.max_path_length_m(),
        total_path: result.total_path_length_m(),
        time_s: result.time_s,
        coverage: result.coverage,
        decisions: result.decisions as i64,
        moves: result.moves as i64,
        reason: result.reason.as_str().to_string(),
        reachable_cells: result.reachable_cells as i64,
        coverage_curve: serde_json::to_string(&thin_curve(&result.coverage_curve))
            .unwrap_or_default(),
        version: VERSION.to_string(),
        wall_s,
        optimal_m: None,
        optimal_lower_m: None,
        optimal_proven: None,
        ratio: None,
        d90_m: result.milestone(90).map(|m| m.0),
        t90_s: result.milestone(90).map(|m| m.1),
        d99_m: result.milestone(99).map(|m| m.0),
        t99_s: result.milestone(99).map(|m| m.1),
        overlap: result.overlap,
        idle_s: serde_json::to_string(&result.idle_s).unwrap_or_default(),
    }
}

#[cfg(test)]
mod tests {
    use super::{check_memory, envs_held, trial_needs, worker_threads};
    use crate::{Plan, Source, Unbuilt};

    /// Regression: the trials were checked against `--memory-mb` alone, and the study's
    /// environments, held beside them all along, alone when planned; a study could pass
    /// both and need more than the budget in all.
    #[test]
    fn trials_and_the_environments_held_beside_them_fit_a_budget_together() {
        let seeds: Vec<String> = (0..40).map(|k| k.to_string()).collect();
        let text = format!(
            "name = \"m\"\nsensors = [\"los:r=3c\"]\nstrategies = [\"cf\"]\n\n[[env]]\n\
             kind = \"office\"\nseeds = [{}]\nsize = [30, 30]\nresolution = 0.05\n",
            seeds.join(", ")
        );
        let src = Source {
            file: "m.toml".into(),
            text,
            dir: None,
        };
        let plan = Plan::resolve(&src, Unbuilt::Error).expect("resolves");
        let pending: Vec<_> = plan.trials.iter().collect();
        let trials = sim::memory::at_once(&trial_needs(&plan, &pending), 1);
        let held = envs_held(&plan);
        assert!(held > 4 << 20, "the environments hold {held} bytes");
        // room for the trials alone, not for the environments beside them
        let budget_mb = (trials + held / 2).div_ceil(1 << 20);
        let e = check_memory(&plan, &pending, Some(1), Some(budget_mb), None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("running 40 trials on 1 thread beside the")
                && e.contains("the study's 40 environments hold")
                && e.contains(&format!("more than --memory-mb {budget_mb}")),
            "{e}"
        );
        let enough = (trials + held).div_ceil(1 << 20);
        assert!(check_memory(&plan, &pending, Some(1), Some(enough), None).is_ok());
    }

    /// Trials whose maps would not fit in memory together are refused before any runs,
    /// naming the largest trial and the thread count.
    #[test]
    fn trials_beyond_available_memory_are_refused_up_front() {
        let text = "name = \"m\"\nseed = 1\nrobots = [5]\nsensors = [\"los:r=3c\"]\n\
                    strategies = [\"cf\", \"ha-cc\"]\n\n[[env]]\nkind = \"office\"\n\
                    seeds = [0]\nsize = [20, 20]\nresolution = 0.1\n";
        let src = Source {
            file: "m.toml".into(),
            text: text.into(),
            dir: None,
        };
        let plan = Plan::resolve(&src, Unbuilt::Error).expect("resolves");
        let pending: Vec<_> = plan.trials.iter().collect();
        assert!(check_memory(&plan, &pending, Some(2), None, None).is_ok());
        let machine = |b| {
            Some(grid::memory::Available::new(
                b,
                grid::memory::Limit::Machine,
            ))
        };
        assert!(check_memory(&plan, &pending, Some(2), None, machine(1 << 40)).is_ok());
        let e = check_memory(&plan, &pending, Some(2), None, machine(20 << 20))
            .unwrap_err()
            .to_string();
        assert!(e.contains("running 2 trials on 2 threads"), "{e}");
        assert!(e.contains("ha-cc"), "{e}");
        assert!(e.contains("20 MiB this machine has available"), "{e}");
        // A user's --memory-mb is the tighter limit, and is named as given.
        let e = check_memory(&plan, &pending, Some(2), Some(20), machine(1 << 40))
            .unwrap_err()
            .to_string();
        assert!(e.contains("more than --memory-mb 20"), "{e}");
        assert!(check_memory(&plan, &pending, Some(2), Some(1 << 20), machine(1 << 40)).is_ok());
    }

    /// Regression: `-j 10000` started 10,000 threads for 6 trials.
    #[test]
    fn thousands_of_threads_are_capped_by_the_trials() {
        assert_eq!(worker_threads(Some(10_000), 6), Some(6));
        assert_eq!(worker_threads(Some(2), 6), Some(2));
        assert_eq!(worker_threads(Some(4), 0), Some(1));
        assert_eq!(worker_threads(None, 6), None);
    }
}
