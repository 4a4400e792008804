//! One team exploration per preset on a floor plan of real-map size and resolution: a
//! generated office of 60 m × 35 m at 0.05 m (1200 × 700 cells), 5 robots, Holz et al.'s
//! laser (`lidar:r=8,fov=180,res=1`, reflection belief, 0.3 m clearance), run until half
//! of the reachable space is known. Single-robot `cf` is the yardstick for a decision's
//! cost (the aim: a team decision within 5× a `cf` decision).
//!
//! `cargo bench -p sim --bench team [PRESET ...]` (criterion, 10 samples a preset; the
//! whole list takes several minutes, `ma-af` the longest); before each preset's samples
//! its decisions and the share of time spent deciding are printed once.

use criterion::{Criterion, criterion_group, criterion_main};
use explore::strategy::Strategy;
use sim::RunConfig;
use std::time::Duration;
use world::{EnvKind, EnvSpec};

/// `cf`, the yardstick, then every team preset of docs/teams.md's table, in its order.
const PRESETS: [&str; 27] = [
    "cf",
    "greedy",
    "greedy-utility",
    "nearest",
    "minpos",
    "nearest-af",
    "nearest-rfe",
    "greedy-utility-af",
    "greedy-utility-rfe",
    "minpos-af",
    "minpos-rfe",
    "ia-af",
    "ia-rfe",
    "ha-af",
    "ha-rfe",
    "ga-af",
    "ga-rfe",
    "sga-af",
    "sga-rfe",
    "ha-centroids",
    "ga-cc",
    "ia-cc",
    "ha-cc",
    "sga-cc",
    "ma-rfe",
    "ma-cc",
    "ma-af",
];

fn config(preset: &str) -> RunConfig {
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.robots = if preset == "cf" { 1 } else { 5 };
    cfg.seed = 1;
    cfg.sensor = "lidar:r=8,fov=180,res=1".parse().expect("sensor");
    cfg.belief = "reflection".parse().expect("belief");
    cfg.clearance_m = 0.3;
    cfg.coverage_goal = Some(0.5);
    cfg
}

fn bench(c: &mut Criterion) {
    let map = world::generate(&EnvSpec {
        kind: EnvKind::Office,
        seed: 1,
        size_m: Some((60.0, 35.0)),
        resolution: Some(0.05),
    })
    .expect("generate office")
    .map;
    let mut g = c.benchmark_group("team_office_1200x700");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5));
    // Presets named on the command line (criterion's filters), or all.
    let wanted: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    for preset in PRESETS {
        if !wanted.is_empty() && !wanted.iter().any(|w| preset.contains(w.as_str())) {
            continue;
        }
        let cfg = config(preset);
        let r = sim::run(&map, &cfg).expect("run");
        eprintln!(
            "{preset}: {} decisions, {:.3} ms a decision, decide {:.0} % of {:.2} s",
            r.decisions,
            r.times.decide_s * 1e3 / r.decisions.max(1) as f64,
            100.0 * r.times.decide_s / r.times.total_s,
            r.times.total_s
        );
        g.bench_function(preset, |b| {
            b.iter(|| sim::run(&map, &cfg).expect("run"));
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
