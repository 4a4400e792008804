//! The loop's promises on every built-in environment × single-robot preset × a few seeds:
//! complete exploration with coverage 1.0 under the ideal `los` sensor, robots only ever on
//! truly free cells, 8-connected paths without corner squeezing, reported lengths equal to
//! the summed steps, and bit-identical repeat runs.

use explore::strategy::Strategy;
use grid::{Occ, SQRT2};
use sim::{EndReason, RunConfig, RunResult};
use world::{EnvKind, EnvSpec};

/// The built-in environment `kind` of `seed` at its default size and resolution.
fn generated(kind: EnvKind, seed: u64) -> world::Environment {
    world::generate(&EnvSpec {
        kind,
        seed,
        size_m: None,
        resolution: None,
    })
    .expect("generate")
}

fn run(kind: EnvKind, preset: &str, seed: u64) -> (grid::GridMap, RunResult) {
    let env = generated(kind, seed);
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.seed = seed;
    cfg.record_trace = true;
    let r = sim::run(&env.map, &cfg).expect("run");
    (env.map, r)
}

fn check(kind: EnvKind, preset: &str, seed: u64) {
    let (map, r) = run(kind, preset, seed);
    let what = format!("{kind} seed {seed} {preset}");
    assert_eq!(
        r.reason,
        EndReason::Complete,
        "{what}: ended '{}' at coverage {}",
        r.reason.as_str(),
        r.coverage
    );
    assert_eq!(r.coverage, 1.0, "{what}");
    assert!(r.frontiers_left.is_empty(), "{what}: frontiers left");
    let cells = &map.cells;
    let trace = r.trace.as_ref().expect("trace");
    let trails = trace.trails();
    assert_eq!(trace.events.len(), trace.change_ends.len(), "{what}");
    for (robot, trail) in trails.iter().enumerate() {
        assert_eq!(
            cells.cell(trail[0] as usize),
            r.starts[robot],
            "{what}: trail starts at the start"
        );
        let mut length = 0.0;
        for &c in trail {
            assert_eq!(
                cells[c as usize],
                Occ::Free,
                "{what}: robot stood on {}",
                cells.cell(c as usize)
            );
        }
        for w in trail.windows(2) {
            let (a, b) = (cells.cell(w[0] as usize), cells.cell(w[1] as usize));
            assert!(a.is_neighbour8(b), "{what}: jump {a} -> {b}");
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            if dx != 0 && dy != 0 {
                let side1 = cells[cells.index(a.offset(dx, 0))];
                let side2 = cells[cells.index(a.offset(0, dy))];
                assert!(
                    side1 == Occ::Free || side2 == Occ::Free,
                    "{what}: squeezed {a} -> {b}"
                );
                length += SQRT2;
            } else {
                length += 1.0;
            }
        }
        let reported = r.path_length_m[robot];
        let last = trace
            .events
            .iter()
            .rev()
            .find(|e| e.robot as usize == robot)
            .expect("events");
        assert!(
            (last.dist_m - reported).abs() < 1e-9,
            "{what}: trace distance {} vs {reported}",
            last.dist_m
        );
        assert!(
            (length * map.resolution - reported).abs() < 1e-6,
            "{what}: summed steps {} m, reported {reported} m",
            length * map.resolution
        );
    }
    // Same seed, same result, bit for bit.
    let (_, again) = run(kind, preset, seed);
    assert_eq!(
        again.path_length_m, r.path_length_m,
        "{what}: repeat run differs"
    );
    assert_eq!(again.decisions, r.decisions, "{what}");
    assert_eq!(again.trace, r.trace, "{what}");
    assert_eq!(again.belief, r.belief, "{what}");
    assert_eq!(again.coverage_curve, r.coverage_curve, "{what}");
}

/// The single-robot presets checked on every environment.
const PRESETS: [&str; 4] = ["yamauchi", "cf", "cf-rr", "random"];

fn all_presets(kind: EnvKind) {
    for preset in PRESETS {
        for seed in 0..2 {
            check(kind, preset, seed);
        }
    }
}

#[test]
fn office() {
    all_presets(EnvKind::Office);
}

#[test]
fn hospital() {
    all_presets(EnvKind::Hospital);
}

#[test]
fn cave() {
    all_presets(EnvKind::Cave);
}

#[test]
fn maze() {
    all_presets(EnvKind::Maze);
}

#[test]
fn potholes() {
    all_presets(EnvKind::Potholes);
}

#[test]
fn empty() {
    all_presets(EnvKind::Empty);
}

#[test]
fn closest_frontier_beats_random() {
    // Holz et al.'s Tables 1–3: random frontier paths are far longer than closest frontier.
    let mut cf = 0.0;
    let mut random = 0.0;
    for seed in 0..3 {
        cf += run(EnvKind::Office, "cf", seed).1.path_length_m[0];
        random += run(EnvKind::Office, "random", seed).1.path_length_m[0];
    }
    assert!(random > 1.3 * cf, "random {random} m vs cf {cf} m");
}

#[test]
fn coverage_goal_stops_early() {
    let env = generated(EnvKind::Office, 3);
    let mut cfg = RunConfig::new(Strategy::preset("cf-rr").unwrap());
    cfg.coverage_goal = Some(0.5);
    let r = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(r.reason, EndReason::GoalReached);
    assert!(
        r.coverage >= 0.5 && r.coverage < 1.0,
        "coverage {}",
        r.coverage
    );
}

#[test]
fn step_limit_is_a_stated_reason() {
    let env = generated(EnvKind::Office, 3);
    let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
    cfg.max_moves = 10;
    let r = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(r.reason, EndReason::StepLimit);
    assert_eq!(r.moves, 10);
}

/// A recorded run's trace stops at `trace_events`: the run ends there, its reason stated,
/// rather than outgrow the memory left for the trace; a run that records none, or one
/// under a cap it does not reach, runs as without one.
#[test]
fn trace_limit_is_a_stated_reason() {
    let env = generated(EnvKind::Office, 3);
    let mut cfg = RunConfig::new(Strategy::preset("random").unwrap());
    cfg.record_trace = true;
    let whole = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(whole.reason, EndReason::Complete);
    let events = whole.trace.as_ref().unwrap().events.len() as u64;
    cfg.trace_events = events / 2;
    let capped = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(capped.reason, EndReason::TraceLimit);
    assert_eq!(
        capped.trace.as_ref().unwrap().events.len() as u64,
        events / 2
    );
    assert!(capped.coverage < whole.coverage);
    cfg.trace_events = events;
    assert_eq!(sim::run(&env.map, &cfg).unwrap().moves, whole.moves);
    cfg.record_trace = false;
    cfg.trace_events = 1;
    let untraced = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(
        (untraced.reason, untraced.moves),
        (whole.reason, whole.moves)
    );
}

#[test]
fn bad_parameters_are_named() {
    let env = generated(EnvKind::Empty, 0);
    let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
    cfg.speed = 0.0;
    let e = sim::run(&env.map, &cfg).unwrap_err().to_string();
    assert_eq!(
        e,
        "--speed: expected a positive number of metres per second, from 0.001 to 1000, found 0"
    );
    // Regression: a speed of 1e-308 m/s was accepted and every time came out infinite.
    let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
    cfg.speed = 1e-308;
    let e = sim::run(&env.map, &cfg).unwrap_err().to_string();
    assert!(e.starts_with("--speed: expected"), "{e}");
    let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
    cfg.starts = vec![grid::Cell::new(0, 0)];
    let e = sim::run(&env.map, &cfg).unwrap_err().to_string();
    assert_eq!(e, "start (0, 0): the cell is occupied");
}
