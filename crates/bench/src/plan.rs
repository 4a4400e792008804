//! Resolving a scenario into a flat, ordered list of trials before anything runs
//! (issue 9, "Scenario files" and "Running").
//!
//! Everything is validated first — preset names, sensor specs, environments, map files,
//! start cells, numbers — and each mistake is reported with the file, line and key.
//!
//! **Seeds.** A trial's seed is `sim::seed::derive(master, "ENV|start=S|trial=T")`: it
//! depends on the master seed, the environment, the start variant and the trial number,
//! never on the thread count or order. It deliberately does *not* depend on the strategy,
//! sensor or robot count: every strategy meets the same random starts and the same random
//! streams (common random numbers), so paired comparisons by (start variant, trial) are fair.
//!
//! **Starts.** With `perturbations = k > 0`, an environment has k start variants, k
//! distinct cells drawn uniformly without replacement from the traversable cells within
//! `radius` metres (Euclidean, in cells) of its base start and connected to it (Faigl &
//! Kulich's start perturbations: 20 variants of each problem, so no two alike); the
//! base start is the `[[env]]`'s `start`, or drawn by seed. With no perturbations, a given
//! `start` is the only variant; otherwise every trial draws its own start from its seed
//! (the multi-robot study's random starts). Teams stand at the nearest distinct
//! traversable cells around the first robot's start, as `frontier explore` places them.
//!
//! **Trials per variant.** `trials` runs per start variant for stochastic strategies (and
//! for random starts); a deterministic strategy at a fixed start would repeat the same run,
//! so it runs once unless `repeat_deterministic = true`. `trials_for` narrows the repeated
//! strategies to those it names, as a paper's protocol may (Faigl & Kulich repeat only the
//! stochastic assignment methods, GA and MA, though RFE's k-means draws too).

use std::collections::BTreeSet;

use explore::assign::AssignerKind;
use explore::candidates::CandidateKind;
use explore::strategy::{SensingMode, Strategy};
use grid::{Cell, GridMap};
use rand::RngExt;
use sense::{BeliefKind, SensorSpec};
use sim::RunConfig;
use world::{EnvKind, EnvSpec};

use crate::error::BenchError;
use crate::scenario::{ScenarioFile, Source};

/// Revision of the strategies' results in a study's fingerprint: bumped when a preset's
/// results change, so that a store of older results is not resumed with new ones (v2: the
/// decision-theoretic presets sample near reachable frontiers only, stop when none is left,
/// and gate predicted rays at unseen wall cells; v3: the segmenting presets segment maps
/// finer than 0.1 m on 0.1 m blocks; v4: CC covers a frontier cell from where the unknown
/// next to it is seen; v5: CC covers maps finer than 0.1 m on 0.1 m blocks; v6:
/// MA's routes are optimal up to 12 nodes and searched over neighbour lists beyond 24; v7:
/// HA's searches grow by a quarter instead of doubling, which may break ties between
/// assignments of equal total differently; v8: CC on blocks goes through a cell that sees
/// the unknown, and covers cell by cell what no block covers; v9: path costs are exact
/// sums (the diagonal step √2 to 32 binary places), so paths of equal length tie exactly
/// and break the tie by index instead of by rounding; v10: a study's start perturbations
/// are distinct cells, drawn without replacement; v11: a robot sensing on arrival sweeps
/// where it gives up a goal, as Yamauchi's does; v12: a robot sensing on arrival or every
/// n cells, with a clearance, looks around before it comes within its clearance of an
/// obstacle its map does not show, and re-plans if it sees it; with any-angle motion, the
/// coverage curve and the D/T milestones are measured along the string-pulled routes; a
/// trial that stops short of its goal has no competitive ratio; v13: a run's time is the
/// last robot's clock, stops after bumps and waits included, as its milestones' times are,
/// and a team's run ends when no robot can reach a candidate; v14: under imperfect sensing
/// (sonar, furniture) with a clearance, a robot standing within its clearance backs away
/// to a cell that keeps it before it decides; v15: a clearance, range or size that is a
/// multiple of the cell size is that many cells exactly, and a cell exactly the clearance
/// from an obstacle keeps it (Holz's d_max), so a clearance at an exact multiple (0.2 m on
/// 0.05 m cells) blocks one ring of cells fewer; one the quotient fell just short of (0.3
/// m on 0.05 m) is unchanged), and a robot with a directional sensor arriving at a frontier
/// faces each unknown neighbour still unknown after it looked towards their mean direction;
/// v16: MA's k-means starts from the last decision's cluster centres.
pub const STRATEGY_REVISION: u32 = 16;

/// A resolved study: environments, variants, common settings and the flat trial list.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Name of the study.
    pub name: String,
    /// Description from the scenario.
    pub description: String,
    /// Where it came from (file or `suite:NAME`).
    pub source: String,
    /// Master seed.
    pub master_seed: u64,
    /// Environments, in file order (seeds in order).
    pub envs: Vec<EnvInstance>,
    /// Variants: (strategy, sensor, robot count) combinations.
    pub variants: Vec<Variant>,
    /// Settings shared by every trial.
    pub common: Common,
    /// Every trial, in a fixed order (environment, variant, start variant, trial).
    pub trials: Vec<Trial>,
    /// Strategies left out because they are not built yet, with the reason.
    pub skipped: Vec<String>,
    /// Settings of the optimal offline paths, when the study computes competitive ratios.
    pub optimal: Option<crate::competitive::OptimalSpec>,
}

/// One environment of the study.
#[derive(Clone, Debug)]
pub struct EnvInstance {
    /// Unique name (e.g. `office-s3`, or the map file's stem).
    pub name: String,
    /// Built-in kind, or `map`.
    pub kind: String,
    /// Generation seed of a built-in kind.
    pub env_seed: Option<u64>,
    /// The map file, as written in the scenario.
    pub map_file: Option<String>,
    /// The ground truth.
    pub map: GridMap,
    /// Start variants: a fixed team start (cells for the largest team), or `None` = drawn
    /// by each trial's seed.
    pub starts: Vec<Option<Vec<Cell>>>,
}

/// A (strategy, sensor, robot count) combination.
#[derive(Clone, Debug)]
pub struct Variant {
    /// Strategy label in results (preset name, or with `/s_max=N`).
    pub label: String,
    /// The strategy with its parameters.
    pub strategy: Strategy,
    /// The sensor.
    pub sensor: SensorSpec,
    /// Number of robots.
    pub robots: usize,
    /// Whether the strategy draws random numbers.
    pub stochastic: bool,
    /// Whether it runs `trials` times per fixed start: stochastic, and named by the
    /// scenario's `trials_for` if it has one.
    pub repeated: bool,
}

/// Settings shared by every trial.
#[derive(Clone, Debug, PartialEq)]
pub struct Common {
    /// Speed in metres per second.
    pub speed: f64,
    /// Clearance in metres.
    pub clearance_m: f64,
    /// Coverage goal.
    pub coverage_goal: Option<f64>,
    /// Move limit of the team.
    pub max_moves: u64,
    /// Belief map.
    pub belief: BeliefKind,
    /// Sensing mode override.
    pub sensing: Option<SensingMode>,
    /// Trials per start variant.
    pub trials: u32,
    /// Repeat deterministic strategies too.
    pub repeat_deterministic: bool,
}

/// One run to do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trial {
    /// Stable key: `ENV|LABEL|SENSOR|m=ROBOTS|start=S|trial=T`.
    pub key: String,
    /// Index into [`Plan::envs`].
    pub env: usize,
    /// Index into [`Plan::variants`].
    pub variant: usize,
    /// Start variant.
    pub start_variant: u32,
    /// Trial number within the start variant.
    pub trial: u32,
    /// The run's seed.
    pub seed: u64,
    /// Its place in the order shards deal the study's trials out by (trial numbers first,
    /// then the study's order), kept when `--trials` leaves trials out
    /// ([`Plan::first_trials`]): a shard picks its trials by it, so that `--trials K
    /// --shard I/N` runs the first trials of shard I/N, which the shard's later runs into
    /// the same store then find done, and every shard gets an even share of them.
    pub number: usize,
}

/// Whether a strategy draws random numbers: random assigners, random-order greedy, MA's
/// k-means (k-means++ starts), RFE's k-means, and the decision-theoretic samples. SGA's
/// k-means starts from given centres (a circle about the map's centre, then the last
/// decision's) and draws none.
pub fn is_stochastic(s: &Strategy) -> bool {
    matches!(
        s.assigner,
        AssignerKind::Random | AssignerKind::RandomOrderGreedy | AssignerKind::Mtsp
    ) || matches!(
        s.candidates,
        CandidateKind::Rfe { .. } | CandidateKind::DtSamples { .. }
    )
}

/// The labels `trials_for` names (each must be one of the study's strategies that draws
/// random numbers), or `None` without it (every stochastic strategy is repeated).
fn trials_for(
    src: &Source,
    f: &ScenarioFile,
    strategies: &[(String, Strategy)],
) -> Result<Option<Vec<String>>, BenchError> {
    let Some(list) = &f.trials_for else {
        return Ok(None);
    };
    let mut named = Vec::new();
    for (i, s) in list.get_ref().iter().enumerate() {
        let label = s.get_ref();
        if !strategies.iter().any(|(l, _)| l == label) {
            let known: Vec<&str> = strategies.iter().map(|(l, _)| l.as_str()).collect();
            return Err(src.error(
                span_of(s),
                format!("trials_for[{i}]"),
                format!(
                    "expected one of the study's strategies ({}), found '{label}'",
                    known.join(", ")
                ),
            ));
        }
        let deterministic = strategies
            .iter()
            .any(|(l, st)| l == label && !is_stochastic(st));
        if deterministic {
            let drawing: Vec<&str> = strategies
                .iter()
                .filter(|(_, st)| is_stochastic(st))
                .map(|(l, _)| l.as_str())
                .collect();
            return Err(src.error(
                span_of(s),
                format!("trials_for[{i}]"),
                format!(
                    "expected a strategy that draws random numbers ({}), found '{label}', \
                     which is deterministic: at a fixed start its trials would all be one run, \
                     so it runs once (repeat_deterministic = true repeats every strategy)",
                    if drawing.is_empty() {
                        "the study has none".to_string()
                    } else {
                        drawing.join(", ")
                    }
                ),
            ));
        }
        named.push(label.clone());
    }
    Ok(Some(named))
}

/// What to do with a strategy that is not built yet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unbuilt {
    /// Leave it out and say so in [`Plan::skipped`] (built-in suites).
    Skip,
    /// Report an error naming the key (users' files).
    Error,
}

fn span_of<T>(s: &toml::Spanned<T>) -> Option<std::ops::Range<usize>> {
    Some(s.span())
}

impl Plan {
    /// Parse and resolve a scenario: load or generate every environment, check every value,
    /// and list the trials.
    pub fn resolve(src: &Source, unbuilt: Unbuilt) -> Result<Plan, BenchError> {
        Plan::resolve_within(src, unbuilt, None)
    }

    /// [`Plan::resolve`], loading and holding the environments within `memory_mb` MiB (a
    /// user's `--memory-mb`) as well as the memory the machine has available.
    pub fn resolve_within(
        src: &Source,
        unbuilt: Unbuilt,
        memory_mb: Option<u64>,
    ) -> Result<Plan, BenchError> {
        let file: ScenarioFile = src.parse()?;
        resolve(src, file, unbuilt, memory_mb)
    }

    /// The belief map trial `t` builds: the scenario's, but Yamauchi's evidence grid with a
    /// sonar, whose graded evidence only that grid takes.
    pub fn belief(&self, t: &Trial) -> BeliefKind {
        belief_with(&self.variants[t.variant].sensor, self.common.belief)
    }

    /// The run configuration of `t` (everything but the map).
    pub fn config(&self, t: &Trial) -> RunConfig {
        let v = &self.variants[t.variant];
        let env = &self.envs[t.env];
        let mut cfg = RunConfig::new(v.strategy.clone());
        cfg.sensor = v.sensor;
        cfg.belief = self.belief(t);
        cfg.sensing = self.common.sensing;
        cfg.robots = v.robots;
        cfg.clearance_m = self.common.clearance_m;
        cfg.speed = self.common.speed;
        cfg.seed = t.seed;
        cfg.coverage_goal = self.common.coverage_goal;
        cfg.max_moves = self.common.max_moves;
        if let Some(team) = &env.starts[t.start_variant as usize] {
            cfg.starts = team[..v.robots].to_vec();
        }
        cfg
    }

    /// Keep only the first `n` trials of every start variant (trial numbers `0..n`), for a
    /// first look at every cell of a study: the trials kept have the keys and seeds they
    /// have in the whole study, so the rest can be run later into the same database.
    pub fn first_trials(&mut self, n: u32) {
        self.trials.retain(|t| t.trial < n);
    }

    /// A text naming the settings every trial shares and the strategies' revision; a
    /// results database holds the results of one fingerprint only, so a changed scenario,
    /// or strategies whose results changed, cannot silently mix with old results.
    pub fn fingerprint(&self) -> String {
        let c = &self.common;
        let optimal = self
            .optimal
            .as_ref()
            .map_or(String::new(), |o| format!(" optimal=[{}]", o.fingerprint()));
        format!(
            "strategies={STRATEGY_REVISION} seed={} speed={} clearance={} goal={:?} max_moves={} \
             belief={} sensing={}{optimal}",
            self.master_seed,
            c.speed,
            c.clearance_m,
            c.coverage_goal,
            c.max_moves,
            c.belief,
            c.sensing.map_or("default".to_string(), |s| s.to_string())
        )
    }
}

fn nonneg(src: &Source, v: &toml::Spanned<i64>, key: &str, min: i64) -> Result<u64, BenchError> {
    let x = *v.get_ref();
    if x < min {
        return Err(src.error(
            span_of(v),
            key,
            format!("expected an integer >= {min}, found {x}"),
        ));
    }
    Ok(x as u64)
}

fn positive_f64(src: &Source, v: &toml::Spanned<f64>, key: &str) -> Result<f64, BenchError> {
    let x = *v.get_ref();
    if !(x.is_finite() && x > 0.0) {
        return Err(src.error(
            span_of(v),
            key,
            format!("expected a positive number, found {x}"),
        ));
    }
    Ok(x)
}

/// A `resolution` as written, one number or `[x, y]`, each positive and at most
/// [`grid::io::MAX_RESOLUTION_M`]: the pixel size `(x, y)`.
fn resolution_of(
    src: &Source,
    v: &toml::Spanned<crate::scenario::Resolution>,
    key: &str,
) -> Result<(f64, f64), BenchError> {
    let bad = |found: String| {
        src.error(
            span_of(v),
            key,
            format!(
                "expected a positive number of metres per cell, at most {}, or [x, y] of them, \
                 found {found}",
                grid::io::MAX_RESOLUTION_M
            ),
        )
    };
    let ok = |x: f64| grid::io::is_valid_resolution(x);
    match v.get_ref() {
        crate::scenario::Resolution::Square(x) if ok(*x) => Ok((*x, *x)),
        crate::scenario::Resolution::Square(x) => Err(bad(grid::Num(*x).to_string())),
        crate::scenario::Resolution::Pixels(p) => match p.as_slice() {
            &[x, y] if ok(x) && ok(y) => Ok((x, y)),
            _ => Err(bad(format!(
                "[{}]",
                p.iter()
                    .map(|x| grid::Num(*x).to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))),
        },
    }
}

/// The belief a run with `sensor` builds when `belief` is asked for: the evidence grid with a
/// sonar (its graded evidence fits no other belief), `belief` otherwise.
pub fn belief_with(sensor: &SensorSpec, belief: BeliefKind) -> BeliefKind {
    if sensor.sonar_mode().is_some() {
        BeliefKind::Evidence
    } else {
        belief
    }
}

/// Why a scenario's `topic` was refused: it chooses a recording's map topic.
const TOPIC_WITHOUT_MCAP: &str =
    "chooses the map topic of an MCAP recording (`map` = a .mcap file)";

/// s_max as written: -1 = on arrival, N > 0 = every N moves.
fn s_max_value(src: &Source, v: &toml::Spanned<i64>, key: &str) -> Result<Option<u32>, BenchError> {
    match *v.get_ref() {
        -1 => Ok(None),
        n if n > 0 && n <= i64::from(u32::MAX) => Ok(Some(n as u32)),
        n => Err(src.error(
            span_of(v),
            key,
            format!("expected a positive number of cell moves or -1 (on arrival), found {n}"),
        )),
    }
}

/// The longest study, environment or strategy name: each is part of file names (the
/// database's, a report's plots and replays), which the file system bounds (255 bytes).
const MAX_NAME_CHARS: usize = 100;

/// Whether `name` can name an environment or a strategy's label: not empty, at most
/// [`MAX_NAME_CHARS`] characters, and without '|' (which separates a trial key's parts) or
/// control characters (which would break a report's lines).
fn plain_name(name: &str) -> bool {
    !name.is_empty()
        && name.chars().count() <= MAX_NAME_CHARS
        && !name.contains('|')
        && !name.chars().any(char::is_control)
}

/// What [`plain_name`] expects and `name` is, as a message.
fn not_a_plain_name(name: &str) -> String {
    format!(
        "expected a non-empty name of at most {MAX_NAME_CHARS} characters, without '|' or \
         control characters, found {name:?}"
    )
}

/// The study's `name`, which is also the default database file (`NAME.sqlite`, beside
/// where the study runs): a plain file name, neither empty, hidden, nor a path elsewhere.
fn study_name(src: &Source, n: &toml::Spanned<String>) -> Result<String, BenchError> {
    let name = n.get_ref();
    if name.is_empty()
        || name.starts_with('.')
        || name.contains(['/', '\\'])
        || name.chars().any(char::is_control)
        || name.chars().count() > MAX_NAME_CHARS
    {
        return Err(src.error(
            span_of(n),
            "name",
            format!(
                "expected a plain file name (the default database is NAME.sqlite): not empty, \
                 at most {MAX_NAME_CHARS} characters, not starting with '.', without '/', '\\' \
                 or control characters; found {name:?}"
            ),
        ));
    }
    Ok(name.clone())
}

fn resolve(
    src: &Source,
    f: ScenarioFile,
    unbuilt: Unbuilt,
    memory_mb: Option<u64>,
) -> Result<Plan, BenchError> {
    let master_seed = match &f.seed {
        Some(s) => nonneg(src, s, "seed", 0)?,
        None => 0,
    };
    let name = match &f.name {
        Some(n) => study_name(src, n)?,
        None => std::path::Path::new(&src.file)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "study".into()),
    };

    // Common settings.
    let speed = match &f.speed {
        Some(v) => {
            let x = *v.get_ref();
            if !sim::run::SPEED_RANGE.contains(&x) {
                return Err(src.error(
                    span_of(v),
                    "speed",
                    format!(
                        "expected a positive number of metres per second, from {} to {}, \
                         found {}",
                        sim::run::SPEED_RANGE.start(),
                        sim::run::SPEED_RANGE.end(),
                        grid::Num(x)
                    ),
                ));
            }
            x
        }
        None => 1.0,
    };
    let clearance_m = match &f.clearance {
        Some(v) => {
            let x = *v.get_ref();
            if !(x.is_finite() && x >= 0.0) {
                return Err(src.error(
                    span_of(v),
                    "clearance",
                    format!("expected a number of metres >= 0, found {}", grid::Num(x)),
                ));
            }
            x
        }
        None => 0.0,
    };
    let coverage_goal = match &f.coverage_goal {
        Some(v) => {
            let x = *v.get_ref();
            if !(x > 0.0 && x <= 1.0) {
                return Err(src.error(
                    span_of(v),
                    "coverage_goal",
                    format!("expected a share in (0, 1], found {x}"),
                ));
            }
            Some(x)
        }
        None => None,
    };
    let max_moves = match &f.max_moves {
        Some(v) => nonneg(src, v, "max_moves", 1)?,
        None => 10_000_000,
    };
    let belief = match &f.belief {
        Some(v) => v
            .get_ref()
            .parse::<BeliefKind>()
            .map_err(|e| src.error(span_of(v), "belief", e.to_string()))?,
        None => BeliefKind::Known,
    };
    let sensing = match &f.sensing {
        Some(v) => Some(
            v.get_ref()
                .parse::<SensingMode>()
                .map_err(|e| src.error(span_of(v), "sensing", e))?,
        ),
        None => None,
    };
    let trials = match &f.trials {
        Some(v) => {
            let n = nonneg(src, v, "trials", 1)?;
            if n > MAX_PLAN_TRIALS {
                return Err(src.error(
                    span_of(v),
                    "trials",
                    format!(
                        "expected at most {MAX_PLAN_TRIALS} runs per start variant (the most \
                         trials one study may plan), found {n}"
                    ),
                ));
            }
            n as u32
        }
        None => 1,
    };
    let common = Common {
        speed,
        clearance_m,
        coverage_goal,
        max_moves,
        belief,
        sensing,
        trials,
        repeat_deterministic: f.repeat_deterministic.unwrap_or(false),
    };

    // Strategies.
    let global_s_max = f
        .s_max
        .as_ref()
        .map(|v| s_max_value(src, v, "s_max"))
        .transpose()?;
    let mut strategies: Vec<(String, Strategy)> = Vec::new();
    let mut skipped = Vec::new();
    let mut add = |label: String,
                   strategy: Strategy,
                   span: Option<std::ops::Range<usize>>,
                   key: &str|
     -> Result<(), BenchError> {
        if strategies.iter().any(|(l, _)| *l == label) {
            return Err(src.error(span, key, format!("strategy '{label}' is listed twice")));
        }
        if let Err(why) = crate::built::check(&strategy) {
            match unbuilt {
                Unbuilt::Skip => {
                    skipped.push(format!("{label}: not built yet ({why})"));
                    return Ok(());
                }
                Unbuilt::Error => {
                    return Err(src.error(
                        span,
                        key,
                        format!("strategy '{label}' cannot run yet: {why}"),
                    ));
                }
            }
        }
        strategies.push((label, strategy));
        Ok(())
    };
    let listed: &[toml::Spanned<String>] = f.strategies.as_ref().map_or(&[], |l| l.get_ref());
    for (i, s) in listed.iter().enumerate() {
        let key = format!("strategies[{i}]");
        let mut strategy = Strategy::preset(s.get_ref())
            .map_err(|e| src.error(span_of(s), &key, e.to_string()))?;
        if let (Some(every), Some(_)) = (global_s_max, strategy.replan.every_moves) {
            strategy.replan.every_moves = every;
        }
        add(s.get_ref().clone(), strategy, span_of(s), &key)?;
    }
    for (i, entry) in f.strategy.iter().enumerate() {
        let e = entry.get_ref();
        let key = format!("strategy[{i}].preset");
        let mut strategy = Strategy::preset(e.preset.get_ref())
            .map_err(|err| src.error(span_of(&e.preset), &key, err.to_string()))?;
        let mut label = e.preset.get_ref().clone();
        if let Some(v) = &e.s_max {
            let key = format!("strategy[{i}].s_max");
            strategy.replan.every_moves = s_max_value(src, v, &key)?;
            if strategy.replan.every_moves.is_some() && strategy.draws_its_goal() {
                return Err(src.error(
                    span_of(v),
                    key,
                    crate::explore::no_periodic_replan(e.preset.get_ref(), *v.get_ref()),
                ));
            }
            label = format!("{label}/s_max={}", v.get_ref());
        } else if let (Some(every), Some(_)) = (global_s_max, strategy.replan.every_moves) {
            strategy.replan.every_moves = every;
        }
        if let Some(l) = &e.label {
            if !plain_name(l.get_ref()) {
                return Err(src.error(
                    span_of(l),
                    format!("strategy[{i}].label"),
                    not_a_plain_name(l.get_ref()),
                ));
            }
            label = l.get_ref().clone();
        }
        add(label, strategy, span_of(&e.preset), &key)?;
    }
    if strategies.is_empty() && skipped.is_empty() {
        return Err(src.error(
            f.strategies.as_ref().and_then(span_of),
            "strategies",
            "expected at least one strategy (a preset name in `strategies`, or a \
             [[strategy]] table), found none",
        ));
    }

    // Sensors and robot counts; each sensor with its key and place, for errors about it.
    let mut sensors: Vec<SensorSpec> = Vec::new();
    let mut sensor_at: Vec<(String, Option<std::ops::Range<usize>>)> = Vec::new();
    match &f.sensors {
        Some(list) => {
            if list.get_ref().is_empty() {
                return Err(src.error(span_of(list), "sensors", "expected at least one sensor"));
            }
            let mut seen = BTreeSet::new();
            for (i, s) in list.get_ref().iter().enumerate() {
                let key = format!("sensors[{i}]");
                let sensor = s
                    .get_ref()
                    .parse::<SensorSpec>()
                    .map_err(|e| src.error(span_of(s), &key, e.to_string()))?;
                // Trial keys name the sensor as written back: two spellings of one sensor
                // would be the same trials.
                if !seen.insert(sensor.to_string()) {
                    return Err(src.error(span_of(s), &key, format!("{sensor} is listed twice")));
                }
                sensors.push(sensor);
                sensor_at.push((key, span_of(s)));
            }
        }
        None => {
            sensors.push(SensorSpec::Los {
                r: sense::Range::Metres(5.0),
            });
            sensor_at.push(("sensors".into(), None));
        }
    }
    let robots: Vec<usize> = match &f.robots {
        Some(list) => {
            if list.get_ref().is_empty() {
                return Err(src.error(
                    span_of(list),
                    "robots",
                    "expected at least one robot count",
                ));
            }
            let mut out = Vec::new();
            for (i, r) in list.get_ref().iter().enumerate() {
                let n = nonneg(src, r, &format!("robots[{i}]"), 1)?;
                if n > 1000 {
                    return Err(src.error(
                        span_of(r),
                        format!("robots[{i}]"),
                        format!("expected at most 1000 robots, found {n}"),
                    ));
                }
                if out.contains(&(n as usize)) {
                    return Err(src.error(
                        span_of(r),
                        format!("robots[{i}]"),
                        format!("{n} is listed twice"),
                    ));
                }
                out.push(n as usize);
            }
            out
        }
        None => vec![1],
    };
    let max_robots = robots.iter().copied().max().unwrap_or(1);

    // Perturbations.
    let perturbations = match &f.perturbations {
        Some(v) => {
            // Each variant is drawn and held before the trial count is known: bound it here.
            let n = nonneg(src, v, "perturbations", 0)?;
            if n > MAX_PLAN_TRIALS {
                return Err(src.error(
                    span_of(v),
                    "perturbations",
                    format!("expected at most {MAX_PLAN_TRIALS} start variants, found {n}"),
                ));
            }
            n as u32
        }
        None => 0,
    };
    let radius_m = match (&f.radius, perturbations) {
        // The radius is only where perturbations are drawn: alone it would change nothing.
        (Some(v), 0) => {
            let why = if f.perturbations.is_some() {
                "`perturbations = 0`"
            } else {
                "no `perturbations`"
            };
            return Err(src.error(
                span_of(v),
                "radius",
                format!(
                    "the radius of the start perturbations has no effect with {why}: add \
                     `perturbations = N` (start variants drawn within the radius of each \
                     environment's start) or remove `radius`"
                ),
            ));
        }
        (Some(v), _) => Some(positive_f64(src, v, "radius")?),
        (None, 0) => None,
        (None, _) => {
            return Err(src.error(
                f.perturbations.as_ref().and_then(span_of),
                "radius",
                "perturbations need a radius in metres",
            ));
        }
    };

    // Variants: strategy-major, then sensor, then robots. Each is planned on every
    // environment, so more variants than trials allowed is refused before listing them.
    let lists = [
        ("strategies", strategies.len()),
        ("sensors", sensors.len()),
        ("robots", robots.len()),
    ];
    let n_variants = lists
        .iter()
        .fold(1u64, |n, (_, len)| n.saturating_mul(*len as u64));
    if n_variants > MAX_PLAN_TRIALS {
        let (key, _) = lists
            .iter()
            .max_by_key(|(_, len)| *len)
            .unwrap_or(&lists[0]);
        let span = match *key {
            "strategies" => f.strategies.as_ref().and_then(span_of),
            "sensors" => f.sensors.as_ref().and_then(span_of),
            _ => f.robots.as_ref().and_then(span_of),
        };
        return Err(src.error(
            span,
            *key,
            format!(
                "the study has {n_variants} variants ({} strategies x {} sensors x {} robot \
                 counts), each run on every environment; expected at most {MAX_PLAN_TRIALS} \
                 trials in one scenario (shorten the lists, or split the study)",
                lists[0].1, lists[1].1, lists[2].1
            ),
        ));
    }
    let named = trials_for(src, &f, &strategies)?;
    let repeated = |label: &str| named.as_ref().is_none_or(|n| n.iter().any(|l| l == label));
    let mut variants = Vec::new();
    for (label, strategy) in &strategies {
        for sensor in &sensors {
            for &m in &robots {
                let stochastic = is_stochastic(strategy);
                variants.push(Variant {
                    label: label.clone(),
                    stochastic,
                    repeated: stochastic && repeated(label),
                    strategy: strategy.clone(),
                    sensor: *sensor,
                    robots: m,
                });
            }
        }
    }

    // Environments: counted, with the trials they give and the memory their maps take,
    // before any is generated or loaded (every environment of a plan is held in memory,
    // and every trial with its key, in --dry-run too).
    if f.env.is_empty() {
        return Err(src.error(None, "env", "no [[env]] given"));
    }
    let mut extents = Vec::new();
    let mut env_total: u64 = 0;
    let mut total: u64 = 0;
    let mut plan_bytes: u64 = 0;
    for (i, entry) in f.env.iter().enumerate() {
        let extent = env_extent(src, i, entry)?;
        env_total += extent.count;
        if env_total > MAX_PLAN_ENVS {
            return Err(src.error(
                extent.span.clone(),
                &extent.key,
                format!(
                    "the study has {env_total} environments up to this [[env]]; expected at \
                     most {MAX_PLAN_ENVS} in one scenario (give fewer seeds, or split the study)"
                ),
            ));
        }
        // Start variants: k perturbations, or one (fixed or drawn by each trial's seed).
        let fixed = entry.get_ref().start.is_some() || perturbations > 0;
        let starts = u64::from(perturbations.max(1));
        // A trial's key names its environment (the name given, else a generated name or a
        // file's stem: taken as 64 characters), variant and sensor.
        let name_len = entry
            .get_ref()
            .name
            .as_ref()
            .map_or(64, |n| n.get_ref().len() + 12) as u64;
        let mut per_env_bytes = 0u64;
        let per_env = variants.iter().fold(0u64, |sum, v| {
            let n = if !fixed || v.repeated || common.repeat_deterministic {
                common.trials
            } else {
                1
            };
            let count = starts.saturating_mul(u64::from(n));
            let key = name_len + v.label.len() as u64 + v.sensor.to_string().len() as u64 + 40;
            per_env_bytes = per_env_bytes
                .saturating_add(count.saturating_mul(TRIAL_BYTES.saturating_add(2 * key)));
            sum.saturating_add(count)
        });
        total = total.saturating_add(extent.count.saturating_mul(per_env));
        plan_bytes = plan_bytes.saturating_add(extent.count.saturating_mul(per_env_bytes));
        extents.push(extent);
    }
    if total > MAX_PLAN_TRIALS {
        return Err(src.error(
            f.trials.as_ref().and_then(span_of),
            "trials",
            format!(
                "the study has {total} trials; expected at most {MAX_PLAN_TRIALS} in one \
                 scenario (lower trials, perturbations or the variants, or split the study)"
            ),
        ));
    }
    // The trials' list and their keys (each key twice: the trial's and the uniqueness
    // check's), before any is made: 2 M trials with names of 100 characters took 1.5 GiB.
    sim::memory::check(
        &format!("planning the study's {total} trials"),
        sim::memory::BASE_BYTES.saturating_add(plan_bytes),
        memory_mb,
        grid::machine::available(),
        "lower trials, perturbations or the variants, use shorter names, or split the study",
    )
    .map_err(|e| src.error(f.trials.as_ref().and_then(span_of), "trials", e.to_string()))?;
    check_env_memory(src, &extents, memory_limit(memory_mb))?;

    let mut envs: Vec<EnvInstance> = Vec::new();
    let mut checked = BTreeSet::new();
    for (i, (entry, extent)) in f.env.iter().zip(&extents).enumerate() {
        for mut env in load_env(src, i, entry, &extent.seeds, memory_mb)? {
            let key = format!("env[{i}]");
            let start = entry
                .get_ref()
                .start
                .as_ref()
                .map(|s| {
                    let v = s.get_ref();
                    match v.as_slice() {
                        [x, y] if i32::try_from(*x).is_ok() && i32::try_from(*y).is_ok() => {
                            Ok(Cell::new(*x as i32, *y as i32))
                        }
                        _ => Err(src.error(
                            span_of(s),
                            format!("{key}.start"),
                            format!(
                                "expected a cell [x, y] of two integers of at most 2^31 - 1 in \
                                 size, found {v:?}"
                            ),
                        )),
                    }
                })
                .transpose()?;
            if start.is_none() && perturbations == 0 {
                // Each trial draws its own start: check that there is room for one and its
                // team with the clearance, or every trial would fail when it runs.
                room_for_team(&env, clearance_m, max_robots)
                    .map_err(|p| p.error(src, &f, entry, &key, &env.name))?;
            }
            env.starts = start_variants(
                &env,
                start,
                perturbations,
                radius_m,
                clearance_m,
                master_seed,
                max_robots,
            )
            .map_err(|p| p.error(src, &f, entry, &key, &env.name))?;
            let name_span = entry
                .get_ref()
                .name
                .as_ref()
                .map_or(Some(entry.span()), span_of);
            if !plain_name(&env.name) {
                // The name is part of each trial's key, whose parts '|' separates, and of
                // the report's file names.
                return Err(src.error(
                    name_span,
                    format!("{key}.name"),
                    not_a_plain_name(&env.name),
                ));
            }
            if envs.iter().any(|e| e.name == env.name) {
                return Err(src.error(
                    Some(entry.span()),
                    format!("{key}.name"),
                    format!("environment '{}' appears twice", env.name),
                ));
            }
            let file = crate::report::slug(&env.name);
            if let Some(other) = envs.iter().find(|e| crate::report::slug(&e.name) == file) {
                return Err(src.error(
                    name_span,
                    format!("{key}.name"),
                    format!(
                        "environment '{}' would write the report files of '{}' (both are \
                         '{file}' in file names): expected a name that differs in letters, \
                         digits, '-' or '.'",
                        env.name, other.name
                    ),
                ));
            }
            check_sensors(
                src,
                &sensors,
                &sensor_at,
                &strategies,
                &env,
                clearance_m,
                &mut checked,
            )?;
            envs.push(env);
        }
    }

    let mut trials = Vec::new();
    let mut keys = BTreeSet::new();
    for (e, env) in envs.iter().enumerate() {
        for (vi, v) in variants.iter().enumerate() {
            for (sv, start) in env.starts.iter().enumerate() {
                let n = if start.is_none() || v.repeated || common.repeat_deterministic {
                    common.trials
                } else {
                    1
                };
                for t in 0..n {
                    let key = format!(
                        "{}|{}|{}|m={}|start={sv}|trial={t}",
                        env.name, v.label, v.sensor, v.robots
                    );
                    let seed = sim::seed::derive(
                        master_seed,
                        &format!("{}|start={sv}|trial={t}", env.name),
                    );
                    if !keys.insert(key.clone()) {
                        return Err(src.error(
                            None,
                            "env",
                            format!("trial key '{key}' is not unique"),
                        ));
                    }
                    trials.push(Trial {
                        key,
                        env: e,
                        variant: vi,
                        start_variant: sv as u32,
                        trial: t,
                        seed,
                        number: trials.len(),
                    });
                }
            }
        }
    }
    debug_assert_eq!(
        trials.len() as u64,
        total,
        "the trials counted before planning"
    );
    // Shards deal the trials out by trial number first. In the study's order the first
    // runs of the repeated strategies' starts lie `common.trials` apart, and every N-th
    // trial of that order would give `--trials 1 --shard I/1000` of faigl2013 from 5 to 78
    // trials a shard; dealt by trial number first, every shard gets 8 or 9.
    let mut order: Vec<usize> = (0..trials.len()).collect();
    order.sort_by_key(|&i| (trials[i].trial, i));
    for (number, &i) in order.iter().enumerate() {
        trials[i].number = number;
    }
    let optimal = f
        .optimal
        .as_ref()
        .map(|o| optimal_spec(src, o))
        .transpose()?;
    if let Some(spec) = &optimal {
        check_coarse_maps(src, &f, spec, &envs, &variants)?;
    }
    // A competitive ratio compares lengths to the same goal: with `[optimal]`, online runs
    // stop once the goal's share of the free cells is perceived (all of them by default),
    // not when the last frontier (often an unseen wall cell) is gone.
    let mut common = common;
    if optimal.is_some() && common.coverage_goal.is_none() {
        common.coverage_goal = Some(1.0);
    }
    Ok(Plan {
        name,
        description: f.description.clone().unwrap_or_default(),
        source: src.file.clone(),
        master_seed,
        envs,
        variants,
        common,
        trials,
        skipped,
        optimal,
    })
}

/// Refuse an `[optimal]` cell size that leaves an environment's coarsened map with no free
/// cell: every trial it applies to would run and then fail for want of an optimal path.
fn check_coarse_maps(
    src: &Source,
    f: &ScenarioFile,
    spec: &crate::competitive::OptimalSpec,
    envs: &[EnvInstance],
    variants: &[Variant],
) -> Result<(), BenchError> {
    let applies = variants
        .iter()
        .any(|v| crate::competitive::OptimalSpec::applies(&v.sensor, v.robots));
    if spec.cell_size <= 1 || !applies {
        return Ok(());
    }
    for env in envs {
        let coarse = grid::resample::coarsen(&env.map, spec.cell_size);
        if !coarse.cells.data().iter().any(|o| o.is_free()) {
            let span = f
                .optimal
                .as_ref()
                .and_then(|o| o.get_ref().cell_size.as_ref());
            return Err(src.error(
                span.and_then(span_of),
                "optimal.cell_size",
                format!(
                    "{}: the map coarsened by {} ({} m cells) has no free cell: expected a \
                     smaller cell size",
                    env.name,
                    spec.cell_size,
                    grid::Num(coarse.resolution)
                ),
            ));
        }
    }
    Ok(())
}

/// Check the `[optimal]` table.
fn optimal_spec(
    src: &Source,
    o: &toml::Spanned<crate::scenario::OptimalEntry>,
) -> Result<crate::competitive::OptimalSpec, BenchError> {
    let e = o.get_ref();
    let mut spec = crate::competitive::OptimalSpec::default();
    if let Some(v) = &e.cell_size {
        let n = nonneg(src, v, "optimal.cell_size", 1)?;
        if n > 64 {
            return Err(src.error(
                span_of(v),
                "optimal.cell_size",
                format!("expected a coarsening factor in 1..=64, found {n}"),
            ));
        }
        spec.cell_size = n as usize;
    }
    if let Some(v) = &e.min_cluster {
        spec.min_cluster = Some(nonneg(src, v, "optimal.min_cluster", 1)? as usize);
    }
    if let Some(v) = &e.weight {
        let w = *v.get_ref();
        if !(w.is_finite() && w >= 1.0) {
            return Err(src.error(
                span_of(v),
                "optimal.weight",
                format!("expected a number >= 1, found {w}"),
            ));
        }
        spec.weight = w;
    }
    if let Some(v) = &e.max_nodes {
        spec.max_nodes = nonneg(src, v, "optimal.max_nodes", 1)?;
    }
    if let Some(v) = &e.memory_mb {
        spec.memory_mb = nonneg(src, v, "optimal.memory_mb", 1)? as usize;
    }
    Ok(spec)
}

/// Load or generate the environments of `[[env]]` number `i` (a built-in kind with the
/// `seeds` its [`EnvExtent`] lists).
fn load_env(
    src: &Source,
    i: usize,
    entry: &toml::Spanned<crate::scenario::EnvEntry>,
    seeds: &[u64],
    memory_mb: Option<u64>,
) -> Result<Vec<EnvInstance>, BenchError> {
    let e = entry.get_ref();
    let key = format!("env[{i}]");
    let pixels = e
        .resolution
        .as_ref()
        .map(|r| resolution_of(src, r, &format!("{key}.resolution")))
        .transpose()?;
    let names_mcap = |m: &toml::Spanned<String>| record::map_file::is_mcap(m.get_ref().as_ref());
    if e.topic.is_some() && e.map.as_ref().is_none_or(|m| !names_mcap(m)) {
        return Err(src.error(
            e.topic.as_ref().and_then(span_of),
            format!("{key}.topic"),
            TOPIC_WITHOUT_MCAP,
        ));
    }
    match (&e.kind, &e.map) {
        (Some(_), Some(m)) => Err(src.error(
            span_of(m),
            format!("{key}.map"),
            "give either `kind` (a built-in environment) or `map` (a file), not both",
        )),
        (None, None) => Err(src.error(
            Some(entry.span()),
            format!("{key}.kind"),
            "expected `kind` (a built-in environment) or `map` (a file)",
        )),
        (None, Some(m)) => {
            let misplaced = [
                ("seeds", e.seeds.as_ref().map(|v| v.span())),
                ("count", e.count.as_ref().map(|v| v.span())),
                ("size", e.size.as_ref().map(|v| v.span())),
            ];
            for (field, span) in misplaced {
                if let Some(span) = span {
                    return Err(src.error(
                        Some(span),
                        format!("{key}.{field}"),
                        "applies to built-in environments (`kind`), not to map files",
                    ));
                }
            }
            let path = match &src.dir {
                Some(d) => d.join(m.get_ref()),
                None => std::path::PathBuf::from(m.get_ref()),
            };
            let opts = grid::io::LoadOptions {
                resolution: pixels,
                border: e.border.unwrap_or(false),
                memory: memory_limit(memory_mb),
            };
            let topic = e.topic.as_ref().map(|t| t.get_ref().as_str());
            let map = record::map_file::load(&path, &opts, topic, false)
                .map_err(|err| {
                    use record::map_file::MapFileError;
                    let (field, message) = match err {
                        MapFileError::McapOption(field) => (
                            field,
                            "an MCAP recording's map carries its own resolution (give no \
                         `resolution` or `border`)"
                                .to_string(),
                        ),
                        MapFileError::TopicWithoutMcap => ("topic", TOPIC_WITHOUT_MCAP.to_string()),
                        // A scenario reads no dungeon maps, so this is not met.
                        MapFileError::DungeonResolution(_) => (
                            "resolution",
                            "expected one resolution (square cells)".to_string(),
                        ),
                        MapFileError::ResolutionRequired(file, what) => (
                            "resolution",
                            format!("{file}: `resolution` is required for {what}"),
                        ),
                        MapFileError::Load(message) => ("map", message),
                    };
                    src.error(span_of(m), format!("{key}.{field}"), message)
                })?
                .map;
            let name = match &e.name {
                Some(n) => n.get_ref().clone(),
                None => path
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| "map".into()),
            };
            Ok(vec![EnvInstance {
                name,
                kind: "map".into(),
                env_seed: None,
                map_file: Some(m.get_ref().clone()),
                map,
                starts: Vec::new(),
            }])
        }
        (Some(k), None) => {
            if e.border.is_some() {
                return Err(src.error(
                    span_of(k),
                    format!("{key}.border"),
                    "applies to map files, not to built-in environments",
                ));
            }
            let kind: EnvKind = k
                .get_ref()
                .parse()
                .map_err(|err| src.error(span_of(k), format!("{key}.kind"), format!("{err}")))?;
            let size_m = match &e.size {
                Some(s) => match s.get_ref().as_slice() {
                    [w, h] => Some((*w, *h)),
                    _ => {
                        return Err(src.error(
                            span_of(s),
                            format!("{key}.size"),
                            "expected [width, height] in metres",
                        ));
                    }
                },
                None => None,
            };
            if e.name.is_some() && seeds.len() > 1 {
                return Err(src.error(
                    e.name.as_ref().and_then(span_of),
                    format!("{key}.name"),
                    "a name applies to one environment; several seeds are named by seed",
                ));
            }
            let resolution = match pixels {
                Some((x, y)) if x != y => {
                    return Err(src.error(
                        e.resolution.as_ref().and_then(span_of),
                        format!("{key}.resolution"),
                        "a built-in environment has square cells; give one number",
                    ));
                }
                other => other.map(|(x, _)| x),
            };
            let mut out = Vec::new();
            for &seed in seeds {
                let spec = EnvSpec {
                    kind,
                    seed,
                    size_m,
                    resolution,
                };
                let env = world::generate(&spec).map_err(|err| {
                    let span = e.size.as_ref().map_or(span_of(k), span_of);
                    src.error(span, key.clone(), err.to_string())
                })?;
                out.push(EnvInstance {
                    name: e.name.as_ref().map_or(env.name, |n| n.get_ref().clone()),
                    kind: kind.to_string(),
                    env_seed: Some(seed),
                    map_file: None,
                    map: env.map,
                    starts: Vec::new(),
                });
            }
            Ok(out)
        }
    }
}

/// Most trials one scenario may plan (the `faigl2013` suite has 77,040); each is held in
/// memory with its key.
pub const MAX_PLAN_TRIALS: u64 = 2_000_000;

/// Bytes of a planned trial beside its key's characters: the [`Trial`], its key's string
/// and the uniqueness check's node.
const TRIAL_BYTES: u64 = 300;

/// Most environments one scenario may plan (the suites have up to 4); each is generated or
/// loaded, held in memory and pictured in the results database.
pub const MAX_PLAN_ENVS: u64 = 10_000;

/// Bytes a planned environment holds per cell (its ground truth, one byte a cell).
pub(crate) const ENV_HELD_BYTES_PER_CELL: u64 = 1;

/// How many environments one `[[env]]` gives and how large they are, known before any is
/// generated or loaded.
#[derive(Clone, Debug)]
struct EnvExtent {
    /// Environments it gives (its seeds; one map file).
    count: u64,
    /// The seeds of a built-in kind (empty for a map file).
    seeds: Vec<u64>,
    /// Cells of each generated environment (0 for a map file or a spec the generator will
    /// refuse: the loader and the generator bound those themselves).
    cells: u64,
    /// The key and place errors about its count name.
    key: String,
    span: Option<std::ops::Range<usize>>,
}

/// The [`EnvExtent`] of `[[env]]` number `i`: its seeds are checked here (at least one, and
/// `count` at most [`MAX_PLAN_ENVS`]), the rest when it is generated or loaded.
fn env_extent(
    src: &Source,
    i: usize,
    entry: &toml::Spanned<crate::scenario::EnvEntry>,
) -> Result<EnvExtent, BenchError> {
    let e = entry.get_ref();
    let key = format!("env[{i}]");
    let (Some(k), None) = (&e.kind, &e.map) else {
        return Ok(EnvExtent {
            count: 1,
            seeds: Vec::new(),
            cells: 0,
            key,
            span: Some(entry.span()),
        });
    };
    let kind: EnvKind = k
        .get_ref()
        .parse()
        .map_err(|err| src.error(span_of(k), format!("{key}.kind"), format!("{err}")))?;
    let (seeds, key, span) = match (&e.seeds, &e.count) {
        (Some(_), Some(c)) => {
            return Err(src.error(
                span_of(c),
                format!("{key}.count"),
                "give either `seeds` or `count`, not both",
            ));
        }
        (Some(list), None) => {
            let k = format!("{key}.seeds");
            if list.get_ref().is_empty() {
                return Err(src.error(
                    span_of(list),
                    k,
                    "expected at least one environment seed, found an empty list",
                ));
            }
            let seeds: Vec<u64> = list
                .get_ref()
                .iter()
                .enumerate()
                .map(|(j, s)| nonneg(src, s, &format!("{key}.seeds[{j}]"), 0))
                .collect::<Result<_, _>>()?;
            let mut seen = std::collections::BTreeMap::new();
            for (j, &seed) in seeds.iter().enumerate() {
                if let Some(first) = seen.insert(seed, j) {
                    return Err(src.error(
                        span_of(&list.get_ref()[j]),
                        format!("{key}.seeds[{j}]"),
                        format!(
                            "expected distinct seeds, found {seed} again (also seeds[{first}])"
                        ),
                    ));
                }
            }
            (seeds, k, span_of(list))
        }
        (None, Some(c)) => {
            let k = format!("{key}.count");
            let n = nonneg(src, c, &k, 1)?;
            if n > MAX_PLAN_ENVS {
                return Err(src.error(
                    span_of(c),
                    k,
                    format!(
                        "expected at most {MAX_PLAN_ENVS} environments in one scenario, found \
                         {n} (split the study)"
                    ),
                ));
            }
            ((0..n).collect(), k, span_of(c))
        }
        (None, None) => (vec![0], key, Some(entry.span())),
    };
    let info = kind.info();
    let (w_m, h_m) = match e.size.as_ref().map(|s| s.get_ref().as_slice()) {
        Some(&[w, h]) => (w, h),
        _ => info.size_m,
    };
    let res = match e.resolution.as_ref().map(|r| r.get_ref()) {
        Some(crate::scenario::Resolution::Square(r)) => *r,
        Some(crate::scenario::Resolution::Pixels(p)) => p.first().copied().unwrap_or(f64::NAN),
        None => info.resolution,
    };
    let cells = (w_m / res).round() * (h_m / res).round();
    let cells = if cells.is_finite() && cells >= 0.0 && cells <= world::MAX_CELLS as f64 {
        cells as u64
    } else {
        0
    };
    Ok(EnvExtent {
        count: seeds.len() as u64,
        seeds,
        cells,
        key,
        span,
    })
}

/// The memory a study's environments may take: the tighter of `memory_mb` (`--memory-mb`)
/// and what the machine has available.
fn memory_limit(memory_mb: Option<u64>) -> Option<grid::memory::Available> {
    sim::memory::limit(memory_mb, grid::machine::available())
}

/// Refuse a study whose environments would not fit in the memory `available` (all of them
/// held, the largest being generated), naming the `[[env]]` with the most cells.
fn check_env_memory(
    src: &Source,
    extents: &[EnvExtent],
    available: Option<grid::memory::Available>,
) -> Result<(), BenchError> {
    let held = extents.iter().fold(0u64, |sum, x| {
        sum.saturating_add(
            x.count
                .saturating_mul(x.cells)
                .saturating_mul(ENV_HELD_BYTES_PER_CELL),
        )
    });
    let Some((_, x)) = extents
        .iter()
        .enumerate()
        .max_by_key(|(i, x)| (x.count.saturating_mul(x.cells), std::cmp::Reverse(*i)))
    else {
        return Ok(());
    };
    let peak = extents.iter().map(|x| x.cells).max().unwrap_or(0);
    let needed = sim::memory::BASE_BYTES
        .saturating_add(held)
        .saturating_add(peak.saturating_mul(world::GENERATE_BYTES_PER_CELL));
    let envs: u64 = extents.iter().map(|x| x.count).sum();
    sim::memory::check(
        &format!(
            "holding the study's {envs} environment(s) (here {} of {} cells each)",
            x.count, x.cells
        ),
        needed,
        None,
        available,
        "give fewer seeds, smaller sizes or coarser resolutions, or split the study",
    )
    .map_err(|e| src.error(x.span.clone(), &x.key, e.to_string()))
}

/// Check that every sensor can run on `env` (its range in cells, its 360° sweep, a sonar's
/// cell size, a range the strategies' candidates can work with), once per resolution:
/// otherwise every trial would fail when it runs.
fn check_sensors(
    src: &Source,
    sensors: &[SensorSpec],
    sensor_at: &[(String, Option<std::ops::Range<usize>>)],
    strategies: &[(String, Strategy)],
    env: &EnvInstance,
    clearance_m: f64,
    checked: &mut BTreeSet<(u64, usize)>,
) -> Result<(), BenchError> {
    let res = env.map.resolution;
    for (j, (sensor, (key, span))) in sensors.iter().zip(sensor_at).enumerate() {
        if !checked.insert((res.to_bits(), j)) {
            continue;
        }
        let problem = match sensor.sonar(res) {
            Some(Err(sense::SenseError::SonarTooCoarse(_))) => Some(format!(
                "sonar needs cells of at most {} m (on coarser cells its 25° cones paint \
                 corridors occupied and exploration stops early), found {res} m: give the \
                 [[env]] `resolution = {}` or finer, or a map of finer cells",
                sense::spec::SONAR_MAX_CELL_M,
                sense::spec::SONAR_MAX_CELL_M
            )),
            Some(Err(e)) => Some(e.to_string()),
            _ => sensor
                .build(res)
                .and_then(|_| sensor.sweep().build(res))
                .err()
                .map(|e| e.to_string()),
        };
        let problem = problem.or_else(|| {
            sim::check_range_beyond_clearance(sensor, clearance_m, res)
                .err()
                .map(|e| e.to_string())
        });
        if let Some(p) = problem {
            return Err(src.error(span.clone(), key, format!("{sensor} on {}: {p}", env.name)));
        }
        for (label, strategy) in strategies {
            if let Err(e) = sim::check_sensor_range(strategy.candidates, sensor, res) {
                return Err(src.error(
                    span.clone(),
                    key,
                    format!("{sensor} on {} with {label}: {e}", env.name),
                ));
            }
        }
    }
    Ok(())
}

/// Whether a team of `robots` can start somewhere on `env` with `clearance_m`: a start the
/// trials could draw, and its team around it (the error a trial would end with otherwise).
fn room_for_team(env: &EnvInstance, clearance_m: f64, robots: usize) -> Result<(), StartProblem> {
    let cells = &env.map.cells;
    let trav = sim::truth::traversable(cells, grid::units::cells(clearance_m, env.map.resolution));
    let components = sim::truth::components(cells, &trav);
    let mut rng = sim::seed::rng(0, &format!("{}|room", env.name));
    let first = sim::truth::random_start(&components, &mut rng, clearance_m)
        .map_err(|e| StartProblem::Clearance(e.to_string()))?;
    sim::truth::team_starts(cells, &trav, first, robots)
        .map_err(|e| StartProblem::Robots(format!("a start drawn at random, {e}")))?;
    Ok(())
}

/// Why an environment's starts could not be placed, by the key that is to blame.
#[derive(Debug)]
enum StartProblem {
    /// The `[[env]]`'s `start` is not a free cell with the clearance.
    Start(String),
    /// No cell has the clearance to start from.
    Clearance(String),
    /// The largest team does not fit around its first robot's start (with the clearance).
    Robots(String),
    /// There are fewer cells within the radius than perturbations asked for.
    Perturbations(String),
}

impl StartProblem {
    /// The scenario error: the key to blame (`key` is the environment's, `env[i]`), its
    /// span in `f`, and the message with the environment's `name`.
    fn error(
        self,
        src: &Source,
        f: &ScenarioFile,
        entry: &toml::Spanned<crate::scenario::EnvEntry>,
        key: &str,
        name: &str,
    ) -> BenchError {
        let or_entry = |span: Option<std::ops::Range<usize>>| span.or(Some(entry.span()));
        let (span, key, message) = match self {
            StartProblem::Start(m) => (
                or_entry(entry.get_ref().start.as_ref().and_then(span_of)),
                format!("{key}.start"),
                m,
            ),
            StartProblem::Clearance(m) => (
                or_entry(f.clearance.as_ref().and_then(span_of)),
                "clearance".into(),
                m,
            ),
            // A clearance the file sets is what shrinks the room, so it is blamed first.
            StartProblem::Robots(m) if f.clearance.is_some() => (
                or_entry(f.clearance.as_ref().and_then(span_of)),
                "clearance".into(),
                m,
            ),
            StartProblem::Robots(m) => (
                or_entry(f.robots.as_ref().and_then(span_of)),
                "robots".into(),
                m,
            ),
            StartProblem::Perturbations(m) => (
                or_entry(f.perturbations.as_ref().and_then(span_of)),
                "perturbations".into(),
                m,
            ),
        };
        src.error(span, key, format!("{name}: {message}"))
    }
}

/// The start variants of `env` (see the module doc).
fn start_variants(
    env: &EnvInstance,
    start: Option<Cell>,
    perturbations: u32,
    radius_m: Option<f64>,
    clearance_m: f64,
    master_seed: u64,
    max_robots: usize,
) -> Result<Vec<Option<Vec<Cell>>>, StartProblem> {
    let cells = &env.map.cells;
    if start.is_none() && perturbations == 0 {
        return Ok(vec![None]);
    }
    let trav = sim::truth::traversable(cells, grid::units::cells(clearance_m, env.map.resolution));
    let components = sim::truth::components(cells, &trav);
    let base = match start {
        Some(c) => {
            sim::truth::check_start(cells, &trav, c)
                .map_err(|e| StartProblem::Start(e.to_string()))?;
            c
        }
        None => {
            let mut rng = sim::seed::rng(master_seed, &format!("{}|base", env.name));
            sim::truth::random_start(&components, &mut rng, clearance_m)
                .map_err(|e| StartProblem::Clearance(e.to_string()))?
        }
    };
    let team = |first: Cell| {
        sim::truth::team_starts(cells, &trav, first, max_robots)
            .map_err(|e| StartProblem::Robots(e.to_string()))
    };
    if perturbations == 0 {
        return Ok(vec![Some(team(base)?)]);
    }
    let r_cells = grid::units::cells(radius_m.unwrap_or(0.0), env.map.resolution);
    let reach = sim::truth::reachable_from(&components.0, cells.index(base));
    let near: Vec<usize> = (0..cells.len())
        .filter(|&i| {
            let c = cells.cell(i);
            let (dx, dy) = (f64::from(c.x - base.x), f64::from(c.y - base.y));
            reach[i] && dx * dx + dy * dy <= r_cells * r_cells
        })
        .collect();
    if perturbations as usize > near.len() {
        return Err(StartProblem::Perturbations(format!(
            "{perturbations} perturbations of the start within {} m, but only {} reachable \
             cells lie there: expected at most that many (or a larger radius)",
            radius_m.unwrap_or(0.0),
            near.len()
        )));
    }
    // A partial Fisher–Yates shuffle: the first k cells of it are k distinct draws, and
    // the first j of them do not depend on k.
    let mut near = near;
    let mut rng = sim::seed::rng(master_seed, &format!("{}|starts", env.name));
    (0..perturbations as usize)
        .map(|j| {
            let pick = rng.random_range(j..near.len());
            near.swap(j, pick);
            team(cells.cell(near[j])).map(Some)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: SGA was counted as drawing random numbers, so a scenario repeated its
    /// runs `trials` times per start for identical results. Its runs are the same whatever
    /// the run's seed; those that draw differ.
    #[test]
    fn regression_sga_is_deterministic() {
        let map = world::generate(&EnvSpec {
            kind: world::EnvKind::Office,
            seed: 1,
            size_m: None,
            resolution: None,
        })
        .expect("generate")
        .map;
        let length = |preset: &str, seed: u64| {
            let mut cfg = sim::RunConfig::new(Strategy::preset(preset).expect("preset"));
            cfg.robots = 3;
            cfg.seed = seed;
            cfg.starts = vec![
                grid::Cell::new(10, 10),
                grid::Cell::new(11, 10),
                grid::Cell::new(10, 11),
            ];
            sim::run(&map, &cfg).expect("run").path_length_m
        };
        for preset in ["sga-af", "sga-cc", "ha-af"] {
            assert!(
                !is_stochastic(&Strategy::preset(preset).expect("preset")),
                "{preset}"
            );
            assert_eq!(length(preset, 1), length(preset, 2), "{preset}");
        }
        for preset in ["ga-af", "ma-af", "sga-rfe"] {
            assert!(
                is_stochastic(&Strategy::preset(preset).expect("preset")),
                "{preset}"
            );
        }
        assert_ne!(length("ga-af", 1), length("ga-af", 2));
    }

    /// Environments that together need more memory than is available are refused before
    /// any is generated, naming the `[[env]]` that holds the most cells.
    #[test]
    fn environments_beyond_the_memory_available_are_refused() {
        let text = "strategies = [\"cf\"]\n\n[[env]]\nkind = \"maze\"\n\n[[env]]\n\
                    kind = \"empty\"\ncount = 100\nsize = [100, 100]\nresolution = 0.01\n";
        let src = Source {
            file: "s.toml".into(),
            text: text.into(),
            dir: None,
        };
        let f = src.parse().unwrap();
        let extents: Vec<EnvExtent> = f
            .env
            .iter()
            .enumerate()
            .map(|(i, e)| env_extent(&src, i, e).unwrap())
            .collect();
        assert_eq!(extents[1].count, 100);
        assert_eq!(extents[1].cells, 10_000 * 10_000);
        // 100 maps of 10^8 cells held: about 9.3 GiB.
        let gib4 = grid::memory::Available::new(4 << 30, grid::memory::Limit::Machine);
        let e = check_env_memory(&src, &extents, Some(gib4))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("s.toml:8: key `env[1].count`"), "{e}");
        assert!(e.contains("101 environment(s)"), "{e}");
        assert!(e.contains("more than the 4096 MiB"), "{e}");
        let gib64 = grid::memory::Available::new(64 << 30, grid::memory::Limit::Machine);
        check_env_memory(&src, &extents, Some(gib64)).unwrap();
        check_env_memory(&src, &extents, None).unwrap();
    }
}
