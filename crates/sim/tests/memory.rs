//! The run estimate against what a run takes: a counting allocator measures the peak heap
//! of whole runs, and `sim::memory::run_bytes`, which every command and the Python package
//! check before a run, must bound it.

#[path = "../../grid/tests/common/counting.rs"]
mod counting;

use explore::strategy::Strategy;
use sim::RunConfig;

/// Peak heap bytes of a whole run of `preset` with `robots` robots on `truth`, with Holz's
/// laser and a 0.3 m clearance, and the estimate for it.
fn peak_and_estimate(truth: &grid::GridMap, preset: &str, robots: usize) -> (u64, u64) {
    let mut cfg = RunConfig::new(Strategy::preset(preset).unwrap());
    cfg.sensor = "lidar:r=8,fov=180,res=1".parse().unwrap();
    cfg.clearance_m = 0.3;
    cfg.robots = robots;
    let estimate = sim::memory::run_bytes(truth.cells.len(), truth.resolution, &cfg);
    let (_, peak) = counting::peak_of(|| sim::run(truth, &cfg).unwrap());
    (peak as u64, estimate)
}

fn env(kind: world::EnvKind, size: (f64, f64)) -> grid::GridMap {
    let mut spec = world::EnvSpec::new(kind, 3);
    spec.size_m = Some(size);
    spec.resolution = Some(0.05);
    world::generate(&spec).unwrap().map
}

/// Every kind of candidates and assigner, one robot and five, on offices of two sizes at
/// 0.05 m (so that neither the fixed nor the per-cell part alone carries the estimate) and
/// on an open space, where the frontier is longest for its map.
#[test]
fn the_run_estimate_bounds_what_a_run_takes() {
    let _turn = counting::turn();
    let maps = [
        (
            "office 14 x 10 m",
            env(world::EnvKind::Office, (14.0, 10.0)),
        ),
        (
            "office 28 x 20 m",
            env(world::EnvKind::Office, (28.0, 20.0)),
        ),
        ("open 24 x 18 m", env(world::EnvKind::Empty, (24.0, 18.0))),
    ];
    for (name, truth) in &maps {
        for (preset, robots) in [
            ("cf-rr", 1),
            ("cf-rr-seg", 1),
            ("dt500", 1),
            ("yamauchi", 1),
            ("nearest-cc", 1),
            ("ha-cc", 5),
            ("ma-af", 5),
            ("sga-af", 5),
            ("minpos", 5),
            ("greedy-utility", 5),
        ] {
            let (peak, estimate) = peak_and_estimate(truth, preset, robots);
            assert!(
                peak <= estimate,
                "{preset} with {robots} robot(s) on the {name}: took {} MiB, estimated {} MiB",
                peak >> 20,
                estimate >> 20
            );
        }
    }
}

/// Regression: a robot's search field was counted at 10 bytes a cell, which the other
/// coefficients' slack covered for five or ten robots but not for large teams (200 robots
/// on a 20 × 15 m office at 0.1 m: MinPos peaked at 118 MiB against 80 MiB estimated;
/// 1,000 robots of `greedy` on 40 × 30 m at 1.32 GiB against 1.17 GiB). Teams of 200 on a
/// small office, where the robots' searches are most of the run, stay within it (the
/// heap of `greedy`'s: 52 MiB, against 51 MiB estimated before).
#[test]
fn the_run_estimate_bounds_a_large_team() {
    let _turn = counting::turn();
    let mut spec = world::EnvSpec::new(world::EnvKind::Office, 3);
    spec.size_m = Some((15.0, 12.0));
    spec.resolution = Some(0.1);
    let truth = world::generate(&spec).unwrap().map;
    for preset in ["greedy", "ga-rfe", "ha-rfe"] {
        let (peak, estimate) = peak_and_estimate(&truth, preset, 200);
        assert!(
            peak <= estimate,
            "{preset} with 200 robots: took {} KiB, estimated {} KiB",
            peak >> 10,
            estimate >> 10
        );
    }
}

/// Regression: the trace a run keeps for `--out`, `--gif`, `--html` and `--mcap` was not in
/// the estimate, and with a short sensor it outgrows the run (a one-cell sensor on a 1 M-cell
/// office: 65 MiB without it, 128 MiB with it, against 72 MiB estimated). The estimate of
/// a recording run bounds its peak, where the one without the trace does not.
#[test]
fn the_trace_estimate_bounds_a_recorded_run() {
    let _turn = counting::turn();
    let small = env(world::EnvKind::Office, (14.0, 10.0));
    let large = env(world::EnvKind::Office, (40.0, 30.0));
    let mut beyond = 0;
    for (truth, preset, sensor) in [
        (&small, "dt500", "los:r=30c"),
        (&small, "cf", "lidar:r=8,fov=180,res=1"),
        (&large, "cf-rr", "los:r=1c"),
    ] {
        let mut cfg = RunConfig::new(Strategy::preset(preset).unwrap());
        cfg.sensor = sensor.parse().unwrap();
        cfg.record_trace = true;
        let estimate = sim::memory::run_bytes(truth.cells.len(), truth.resolution, &cfg);
        let (_, peak) = counting::peak_of(|| sim::run(truth, &cfg).unwrap());
        let peak = peak as u64;
        assert!(
            peak <= estimate,
            "{preset} with {sensor}, recorded: took {} KiB, estimated {} KiB",
            peak >> 10,
            estimate >> 10
        );
        cfg.record_trace = false;
        let untraced = sim::memory::run_bytes(truth.cells.len(), truth.resolution, &cfg);
        beyond += usize::from(peak > untraced);
    }
    // The BASE_BYTES allowance covers small runs; the trace of the one-cell sensor's run on
    // the 480,000-cell office is larger.
    assert!(
        beyond >= 1,
        "no recorded run outgrew the estimate without its trace"
    );
}

/// Regression: `random` sends the robot across the map for every goal, so its moves grow
/// faster than the cells, and its recorded trace outgrew the estimate (willow-full with a
/// 10-cell `los`: 2.5 M moves against the 348,000 allowed, a peak of 152 MiB against 121
/// MiB estimated). Its recorded run's estimate bounds its peak.
#[test]
fn the_trace_estimate_bounds_a_recorded_random_run() {
    let _turn = counting::turn();
    let truth = env(world::EnvKind::Office, (14.0, 10.0));
    let mut cfg = RunConfig::new(Strategy::preset("random").unwrap());
    cfg.sensor = "los:r=2c".parse().unwrap();
    cfg.record_trace = true;
    let estimate = sim::memory::run_bytes(truth.cells.len(), truth.resolution, &cfg);
    let (r, peak) = counting::peak_of(|| sim::run(&truth, &cfg).unwrap());
    assert_eq!(r.reason, sim::EndReason::Complete);
    assert!(
        peak as u64 <= estimate,
        "random with los:r=2c, recorded ({} moves): took {} MiB, estimated {} MiB",
        r.moves,
        peak >> 20,
        estimate >> 20
    );
}
