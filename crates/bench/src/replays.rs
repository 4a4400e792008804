//! Replay pages of a report: per environment, one representative trial (the first trial of
//! the first strategy in name order) is run again from its stored settings and seed with
//! the trace on, and written as `replays/<env>.html`. The store keeps metrics, not traces;
//! runs are deterministic per seed, so the re-run is the stored trial. The ground truth is
//! read back from the environment's stored picture (drawn by [`viz::map_picture`] at a
//! whole-number scale), so map-file environments need not be found again.

use grid::{Cell, GridMap};
use sim::RunConfig;

use crate::error::BenchError;
use crate::store::{EnvPicture, TrialRow};

/// The representative trial of environment `env`: the lowest (strategy, sensor, robots,
/// start variant, trial) among its rows.
pub fn representative<'a>(rows: &'a [TrialRow], env: &str) -> Option<&'a TrialRow> {
    rows.iter().filter(|r| r.env == env).min_by(|a, b| {
        (&a.strategy, &a.sensor, a.robots, a.start_variant, a.trial).cmp(&(
            &b.strategy,
            &b.sensor,
            b.robots,
            b.start_variant,
            b.trial,
        ))
    })
}

/// The ground truth drawn in `pic` ([`viz::map_from_picture`]).
pub fn truth_from_picture(pic: &EnvPicture) -> Result<GridMap, BenchError> {
    let bad = |why: String| BenchError::Other(format!("picture of {}: {why}", pic.name));
    let (w, h) = (pic.width as usize, pic.height as usize);
    let s = u64::from(viz::scale_for(w, h));
    let expected = (w as u64)
        .saturating_mul(s)
        .saturating_mul((h as u64).saturating_mul(s));
    let img = viz::Picture::from_png(&pic.png, expected).map_err(|e| bad(e.to_string()))?;
    let cells = viz::map_from_picture(&img, w, h).ok_or_else(|| {
        bad(format!(
            "{}x{} pixels do not draw {w}x{h} cells",
            img.width(),
            img.height()
        ))
    })?;
    Ok(GridMap {
        cells,
        resolution: pic.resolution,
        origin: [0.0, 0.0, 0.0],
    })
}

/// The run configuration stored in `row`, with the trace on.
pub fn config_of(row: &TrialRow) -> Result<RunConfig, BenchError> {
    let bad = |what: &str, why: String| {
        BenchError::Other(format!("trial {}: stored {what}: {why}", row.key))
    };
    let mut strategy = explore::strategy::Strategy::preset(&row.preset)
        .map_err(|e| bad("preset", e.to_string()))?;
    strategy.replan.every_moves = row.s_max.map(|v| v as u32);
    let mut cfg = RunConfig::new(strategy);
    cfg.sensor = row
        .sensor
        .parse()
        .map_err(|e: <sense::SensorSpec as std::str::FromStr>::Err| bad("sensor", e.to_string()))?;
    let belief = row
        .belief
        .parse()
        .map_err(|e: <sense::BeliefKind as std::str::FromStr>::Err| bad("belief", e.to_string()))?;
    // Stores written before a sonar trial's row named its evidence grid hold the
    // scenario's belief there; the run built the evidence grid all the same.
    cfg.belief = crate::plan::belief_with(&cfg.sensor, belief);
    cfg.sensing = Some(row.sensing.parse().map_err(
        |e: <explore::strategy::SensingMode as std::str::FromStr>::Err| {
            bad("sensing", e.to_string())
        },
    )?);
    cfg.robots = row.robots as usize;
    cfg.clearance_m = row.clearance;
    cfg.speed = row.speed;
    cfg.seed = row
        .seed
        .parse()
        .map_err(|e: std::num::ParseIntError| bad("seed", e.to_string()))?;
    cfg.coverage_goal = row.coverage_goal;
    cfg.max_moves = row.max_moves as u64;
    let starts: Vec<[i32; 2]> =
        serde_json::from_str(&row.starts).map_err(|e| bad("starts", e.to_string()))?;
    cfg.starts = starts.into_iter().map(|[x, y]| Cell { x, y }).collect();
    cfg.record_trace = true;
    Ok(cfg)
}

/// The replay page of `row` run again on the truth drawn in `pic`.
pub fn replay_page(pic: &EnvPicture, row: &TrialRow) -> Result<String, BenchError> {
    let truth = truth_from_picture(pic)?;
    let cfg = config_of(row)?;
    let result = sim::run(&truth, &cfg)
        .map_err(|e| BenchError::Other(format!("re-running {}: {e}", row.key)))?;
    let meta = format!(
        "{} · {} · {} robot(s) · start {} · trial {} · seed {}",
        row.strategy, row.sensor, row.robots, row.start_variant, row.trial, row.seed
    );
    viz::replay::replay_html(
        &truth,
        &result,
        &format!("{} · {}", row.env, row.strategy),
        &meta,
    )
    .map_err(|e| BenchError::Other(format!("replay of {}: {e}", row.key)))
}
