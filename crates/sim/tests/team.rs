//! Teams: every multi-robot preset (the coordination study's nearest, greedy, greedy-utility, MinPos and
//! Faigl & Kulich's `<assigner>-<candidates>`) explores every built-in environment
//! completely (coverage 1.0, no frontier left) with m ∈ {1, 3, 5, 10} robots, and a repeat
//! run with the same seed gives the same result bit for bit.
//!
//! To keep the debug-mode run time of the default test run modest, it covers the two
//! environments of the multi-robot study (office and maze, 50 × 40 cells) with every team
//! size; `FRONTIER_FULL_TESTS=1 cargo test --release -p sim --test team` runs every built-in
//! environment (m = 10 on the four smaller ones). Default-size environments, one seed each,
//! the repeat run for m = 3.

use explore::strategy::Strategy;
use sim::{EndReason, RunConfig, RunResult};
use world::{EnvKind, EnvSpec};

/// Team sizes checked (Faigl & Kulich use 3–10; 1 checks the degenerate team).
const TEAMS: [usize; 4] = [1, 3, 5, 10];

fn run(map: &grid::GridMap, preset: &str, robots: usize, seed: u64) -> RunResult {
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.robots = robots;
    cfg.seed = seed;
    sim::run(map, &cfg).expect("run")
}

fn check(preset: &str) {
    let full = std::env::var_os("FRONTIER_FULL_TESTS").is_some();
    let kinds: &[EnvKind] = if full {
        EnvKind::all()
    } else {
        &[EnvKind::Office, EnvKind::Maze]
    };
    for &kind in kinds {
        let seed = 1;
        let env = world::generate(&EnvSpec {
            kind,
            seed,
            size_m: None,
            resolution: None,
        })
        .expect("generate");
        for m in TEAMS {
            if m == 10 && matches!(kind, EnvKind::Hospital | EnvKind::Potholes) {
                continue;
            }
            let what = format!("{preset} on {kind} seed {seed} with {m} robots");
            let r = run(&env.map, preset, m, seed);
            assert_eq!(
                r.reason,
                EndReason::Complete,
                "{what}: ended '{}' at coverage {}",
                r.reason.as_str(),
                r.coverage
            );
            assert_eq!(r.coverage, 1.0, "{what}");
            assert!(r.frontiers_left.is_empty(), "{what}: frontiers left");
            assert_eq!(r.path_length_m.len(), m, "{what}: one length per robot");
            if m == 3 {
                let again = run(&env.map, preset, m, seed);
                assert_eq!(
                    again.path_length_m, r.path_length_m,
                    "{what}: repeat differs"
                );
                assert_eq!(again.decisions, r.decisions, "{what}: repeat differs");
                assert_eq!(again.moves, r.moves, "{what}: repeat differs");
                assert_eq!(again.ends, r.ends, "{what}: repeat differs");
                assert_eq!(again.belief, r.belief, "{what}: repeat differs");
            }
        }
    }
}

macro_rules! presets {
    ($($test:ident => $name:literal),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                check($name);
            }
        )*
    };
}

presets! {
    nearest => "nearest",
    greedy => "greedy",
    greedy_utility => "greedy-utility",
    minpos => "minpos",
    ga_af => "ga-af",
    ia_af => "ia-af",
    ha_af => "ha-af",
    ga_rfe => "ga-rfe",
    ia_rfe => "ia-rfe",
    ha_rfe => "ha-rfe",
    ga_cc => "ga-cc",
    ia_cc => "ia-cc",
    ha_cc => "ha-cc",
    ma_rfe => "ma-rfe",
    ma_cc => "ma-cc",
    sga_af => "sga-af",
}

/// Regression: a coverage strategy with a sensor of 1 cell found no candidate (its cover
/// looks within 0.8 of the range, short of the cell next to a frontier cell) and ended at
/// once with "no reachable frontier" at 0.2 % coverage. Such a run is refused, naming the
/// sensor and what range it needs; 1.25 cells explores everything, and other candidates
/// still run with 1 cell.
#[test]
fn regression_coverage_candidates_need_a_range_of_1_25_cells() {
    let map = world::generate(&EnvSpec::new(EnvKind::Office, 1))
        .expect("office")
        .map;
    let with = |preset: &str, sensor: &str| {
        let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
        cfg.robots = 2;
        cfg.sensor = sensor.parse().expect("sensor");
        sim::run(&map, &cfg)
    };
    for preset in ["ha-cc", "ma-cc", "nearest-cc"] {
        let e = with(preset, "los:r=1c").expect_err(preset).to_string();
        assert!(
            e.starts_with("--sensor: expected a range of at least 1.25 cells")
                && e.contains("found los:r=1c, 1 cell(s) at 0.5 m per cell"),
            "{preset}: {e}"
        );
        let r = with(preset, "los:r=1.25c").expect(preset);
        assert_eq!(r.reason, EndReason::Complete, "{preset}");
    }
    assert_eq!(
        with("ha-rfe", "los:r=1c").expect("ha-rfe").reason,
        EndReason::Complete
    );
}

/// Regression: a team ran on until its last robot reached a goal explored on its way,
/// though both multi-robot papers end when no frontier is left: on the coordination
/// study's maze (4 robots, `greedy`, a 4-cell sensor, seed 3) robot 1 found nothing left
/// at 212.9 s and robot 0 walked to a goal it had been sent to until 428.1 s, the time
/// reported. The run now ends when no robot can reach a candidate.
#[test]
fn regression_team_stops_when_no_frontier_is_left() {
    let map = world::generate(&EnvSpec {
        kind: EnvKind::Maze,
        seed: 3,
        size_m: None,
        resolution: None,
    })
    .expect("generate")
    .map;
    let mut cfg = RunConfig::new(Strategy::preset("greedy").expect("preset"));
    cfg.robots = 4;
    cfg.seed = 3;
    cfg.sensor = "los:r=4c".parse().expect("sensor");
    let r = sim::run(&map, &cfg).expect("run");
    assert_eq!(r.reason, EndReason::Complete);
    let (_, t99) = r.milestone(99).expect("reached");
    assert!(r.time_s < 1.1 * t99, "time {} against T99 {t99}", r.time_s);
}
