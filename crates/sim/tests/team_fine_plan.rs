//! Teams on a floor plan at a real map's resolution: 5 robots explore a generated office of
//! 16 m × 10 m at 0.05 m (320 × 200 cells) completely with every team preset (each
//! assigner of Faigl & Kulich's framework with each candidate generator, and the
//! multi-robot study's presets), with a 3 m, 180° laser. Real floor plans are this fine;
//! the generated environments of `team.rs` are 0.5 m grids. (The size and range keep the
//! coverage candidates' ray casting, O(frontier cells × cells within 0.8 ρ) per decision,
//! within a test's time.)

use explore::strategy::Strategy;
use sim::{EndReason, RunConfig};
use world::{EnvKind, EnvSpec};

const ASSIGNERS: [&str; 9] = [
    "nearest",
    "greedy",
    "ia",
    "ga",
    "greedy-utility",
    "minpos",
    "ha",
    "ma",
    "sga",
];
const CANDIDATES: [&str; 4] = ["af", "centroids", "rfe", "cc"];

fn check(preset: &str, map: &grid::GridMap) {
    let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
    cfg.robots = 5;
    cfg.seed = 3;
    cfg.sensor = "lidar:r=3,fov=180,res=1".parse().expect("sensor");
    cfg.clearance_m = 0.15;
    let r = sim::run(map, &cfg).expect("run");
    assert_eq!(
        r.reason,
        EndReason::Complete,
        "{preset}: ended '{}' at coverage {}",
        r.reason.as_str(),
        r.coverage
    );
    assert_eq!(r.coverage, 1.0, "{preset}");
    // (Frontier cells may be left beside wall cells between the laser's 1° rays, which no
    // pose sees at this resolution: completeness is about the reachable free space.)
}

fn office() -> grid::GridMap {
    world::generate(&EnvSpec {
        kind: EnvKind::Office,
        seed: 2,
        size_m: Some((16.0, 10.0)),
        resolution: Some(0.05),
    })
    .expect("generate")
    .map
}

#[test]
fn study_presets_explore_a_fine_floor_plan() {
    let map = office();
    for preset in ["nearest", "greedy", "greedy-utility", "minpos"] {
        check(preset, &map);
    }
}

macro_rules! per_assigner {
    ($($test:ident => $a:literal),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                let map = office();
                for c in CANDIDATES {
                    check(&format!("{}-{c}", $a), &map);
                }
            }
        )*
    };
}

per_assigner! {
    nearest_explores_a_fine_floor_plan => "nearest",
    greedy_explores_a_fine_floor_plan => "greedy",
    ia_explores_a_fine_floor_plan => "ia",
    ga_explores_a_fine_floor_plan => "ga",
    greedy_utility_explores_a_fine_floor_plan => "greedy-utility",
    minpos_explores_a_fine_floor_plan => "minpos",
    ha_explores_a_fine_floor_plan => "ha",
    ma_explores_a_fine_floor_plan => "ma",
    sga_explores_a_fine_floor_plan => "sga",
}

#[test]
fn every_assigner_is_listed() {
    for a in ASSIGNERS {
        assert!(Strategy::preset(&format!("{a}-af")).is_ok(), "{a}");
    }
}
