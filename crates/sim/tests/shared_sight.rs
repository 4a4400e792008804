//! Runs that share one `SightCache` (a study's trials on one map) are the runs they would
//! be without it, whether the cache is empty, half made or full; and a run takes a cache
//! only for its own ground truth and range.

mod common;

use std::borrow::Cow;
use std::sync::Arc;

use common::assert_same_run;
use explore::strategy::Strategy;
use grid::GridMap;
use sense::{BeliefKind, LosSensor, Range, SensorSpec, SightBudget, SightCache};
use sim::{RunConfig, Session};
use world::{EnvKind, EnvSpec};

fn map(kind: EnvKind, seed: u64) -> GridMap {
    let spec = EnvSpec::new(kind, seed)
        .with_size(15.0, 12.0)
        .with_resolution(0.2);
    world::generate(&spec).expect("environment").map
}

fn config(preset: &str, robots: usize, r_m: f64, seed: u64) -> RunConfig {
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.sensor = SensorSpec::Los {
        r: Range::Metres(r_m),
    };
    cfg.robots = robots;
    cfg.seed = seed;
    cfg
}

fn cache_for(map: &GridMap, r_m: f64, budget: u64) -> Arc<SightCache> {
    let sensor = LosSensor::new(r_m / map.resolution).expect("range");
    Arc::new(SightCache::new(&map.cells, sensor, SightBudget::new(budget)).expect("fits"))
}

/// Three runs after one another through one cache (the later ones find the sets the
/// earlier made), on maps of rooms and of scattered obstacles, with the ray template
/// (3 m = 15 cells) and shadow casting (5 m = 25 cells), for one robot and teams.
#[test]
fn runs_through_a_shared_cache_are_the_runs_without() {
    for (kind, env_seed) in [(EnvKind::Office, 3), (EnvKind::Potholes, 1)] {
        let map = map(kind, env_seed);
        for r_m in [3.0, 5.0] {
            let cache = cache_for(&map, r_m, u64::MAX / 2);
            for (preset, robots) in [("cf-rr", 1), ("ha-cc", 3), ("ma-rfe", 3), ("minpos", 2)] {
                for seed in 0..3 {
                    let cfg = config(preset, robots, r_m, seed);
                    let want = sim::run(&map, &cfg).expect("run");
                    let got = sim::run_sharing(&map, &cfg, Some(&cache)).expect("run");
                    let what = format!("{kind:?} r={r_m} {preset} seed {seed}");
                    assert_same_run(&got, &want, &what);
                }
            }
        }
    }
}

/// With an evidence grid every scan reports all it sees (nothing is skipped as known):
/// through the cache too; and a budget that pays for few sets leaves the rest to the
/// sensor, with the same run.
#[test]
fn full_scans_and_a_spent_budget_give_the_same_run() {
    let map = map(EnvKind::Office, 5);
    let sensor = LosSensor::new(5.0 / map.resolution).expect("range");
    let few =
        SightCache::base_bytes(map.cells.len(), &sensor) + 20 * SightCache::set_bytes(&sensor);
    for budget in [u64::MAX / 2, few] {
        let cache = cache_for(&map, 5.0, budget);
        for belief in [BeliefKind::Evidence, BeliefKind::Reflection] {
            for _ in 0..2 {
                let mut cfg = config("cf", 1, 5.0, 1);
                cfg.belief = belief;
                let want = sim::run(&map, &cfg).expect("run");
                let got = sim::run_sharing(&map, &cfg, Some(&cache)).expect("run");
                assert_same_run(&got, &want, &format!("{belief:?}, budget {budget}"));
            }
        }
    }
}

/// A cache is taken only by runs of its ground truth with the line-of-sight sensor of its
/// range.
#[test]
fn a_run_takes_only_a_cache_of_its_own_truth_and_range() {
    let office = map(EnvKind::Office, 3);
    let other = map(EnvKind::Office, 4);
    let cache = cache_for(&office, 3.0, u64::MAX / 2);
    let takes = |map: &GridMap, cfg: &RunConfig| {
        let mut s = Session::start(Cow::Borrowed(map), Cow::Borrowed(cfg), false).expect("start");
        s.share_sight(cache.clone())
    };
    assert!(takes(&office, &config("cf", 1, 3.0, 0)));
    assert!(takes(&office, &config("ha-cc", 3, 3.0, 0)));
    assert!(!takes(&other, &config("cf", 1, 3.0, 0)), "another map");
    assert!(!takes(&office, &config("cf", 1, 4.0, 0)), "another range");
    let mut lidar = config("cf", 1, 3.0, 0);
    lidar.sensor = "lidar:r=3,fov=360,res=1".parse().expect("lidar");
    assert!(!takes(&office, &lidar), "another sensor");
}
