//! `Session` with external goals is the same loop as `run()`: driven by the strategy's own
//! assigner through `propose`, it reproduces the run exactly, for one robot and for teams;
//! and a caller's goals are checked.

use std::borrow::Cow;

use explore::strategy::Strategy;
use grid::GridMap;
use sense::{Range, SensorSpec};
use sim::{RunConfig, RunResult, Session, SimError, Status};
use world::{EnvKind, EnvSpec};

fn office() -> GridMap {
    let spec = EnvSpec::new(EnvKind::Office, 3)
        .with_size(15.0, 12.0)
        .with_resolution(0.25);
    world::generate(&spec).expect("office").map
}

fn config(preset: &str, robots: usize, seed: u64) -> RunConfig {
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.sensor = SensorSpec::Los {
        r: Range::Metres(3.0),
    };
    cfg.robots = robots;
    cfg.seed = seed;
    cfg
}

/// Play a whole run with goals from outside, chosen by the strategy's assigner.
fn external(map: &GridMap, cfg: &RunConfig) -> RunResult {
    let mut s = Session::start(Cow::Borrowed(map), Cow::Borrowed(cfg), true).expect("start");
    while s.advance() == Status::Decide {
        let cells = s.candidates().to_vec();
        let goals: Vec<Option<u32>> = s
            .propose(cfg.strategy.assigner, &cells)
            .iter()
            .map(|g| g.map(|g| g.cell))
            .collect();
        s.choose(&goals).expect("a proposed goal is reachable");
    }
    s.finish()
}

#[test]
fn external_session_driven_by_the_assigner_equals_run() {
    let map = office();
    for (preset, robots) in [
        ("cf-rr", 1),
        ("cf", 1),
        ("random", 1),
        ("yamauchi", 1),
        ("dt", 1),
        ("greedy", 3),
        ("ha-cc", 3),
        ("minpos", 2),
    ] {
        for seed in 0..2 {
            let cfg = config(preset, robots, seed);
            let want = sim::run(&map, &cfg).expect("run");
            let got = external(&map, &cfg);
            assert_eq!(
                got.path_length_m, want.path_length_m,
                "{preset} seed {seed}"
            );
            assert_eq!(got.decisions, want.decisions, "{preset} seed {seed}");
            assert_eq!(got.moves, want.moves, "{preset} seed {seed}");
            assert_eq!(got.reason, want.reason, "{preset} seed {seed}");
            assert_eq!(
                got.coverage_curve, want.coverage_curve,
                "{preset} seed {seed}"
            );
            assert_eq!(got.belief, want.belief, "{preset} seed {seed}");
            assert_eq!(got.starts, want.starts, "{preset} seed {seed}");
        }
    }
}

#[test]
fn nearest_candidates_are_the_cheapest_in_order() {
    let map = office();
    let cfg = config("cf", 1, 0);
    let mut s = Session::start(Cow::Borrowed(&map), Cow::Borrowed(&cfg), true).expect("start");
    assert_eq!(s.advance(), Status::Decide);
    assert_eq!(s.deciding(), &[true]);
    let mut all = Vec::new();
    s.nearest_candidates(0, usize::MAX, &mut all);
    let mut few = Vec::new();
    s.nearest_candidates(0, 5, &mut few);
    assert!(all.len() > 5 && few.len() == 5);
    assert_eq!(&all[..5], &few[..]);
    assert!(all.windows(2).all(|p| p[0].cost <= p[1].cost));
    // The nearest assigner takes the cheapest.
    let cells = s.candidates().to_vec();
    let nearest = s.propose(cfg.strategy.assigner, &cells)[0].expect("a goal");
    assert_eq!(nearest.cost, all[0].cost);
}

#[test]
fn goals_from_outside_are_checked() {
    let map = office();
    let cfg = config("cf", 1, 0);
    let mut s = Session::start(Cow::Borrowed(&map), Cow::Borrowed(&cfg), true).expect("start");
    assert_eq!(s.advance(), Status::Decide);
    let wall = map
        .cells
        .data()
        .iter()
        .position(|o| o.is_occupied())
        .expect("a wall") as u32;
    let bad = s.choose(&[Some(wall)]);
    assert!(matches!(
        bad,
        Err(SimError::BadParameter { field: "goal", .. })
    ));
    let bad = s.choose(&[Some(u32::MAX)]);
    assert!(matches!(
        bad,
        Err(SimError::BadParameter { field: "goal", .. })
    ));
    let bad = s.choose(&[None, None]);
    assert!(matches!(
        bad,
        Err(SimError::BadParameter { field: "goals", .. })
    ));
    // No goal: the robot stops and the run ends.
    s.choose(&[None]).expect("no goal is allowed");
    assert!(matches!(s.advance(), Status::Ended(_)));
    assert!(s.choose(&[None]).is_err());
}
