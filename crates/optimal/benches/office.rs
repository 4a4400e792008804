//! The benchmark for the offline optimal search: an indoor map of 350 × 250 units
//! solved at cell size 4 with r = 30 units, G = 0.85 (the paper: 0.33 s, ~2,000 nodes), with
//! the footprint sensor and clustered boundary cells (the paper's Table 1 setting).
//!
//! The paper's indoor map is not published; its text says it has a top corridor and a left
//! vertical corridor, and its Table 1 gives optimal lengths of about 500–520 units at this
//! setting. Two maps stand in for it (one unit = one 0.1 m cell):
//! - the corridor floor ([`corridor_floor`]): an L of two 3 m corridors (top, left) lined
//!   with 2.5 m × 4 m offices, the rest of the rectangle outside the building. Its optimal
//!   paths (about 530–720 units) are of the paper's length, so its search is of the paper's
//!   size; ten starts along the corridors, like the paper's ten initial positions;
//! - a generated 35 m × 25 m office, whose free space is four times larger (optimal
//!   lengths of 1,200–2,600 units): a stress case the search does not finish in seconds.
//!
//! `cargo bench -p optimal --bench office` prints one line per start (floor: all ten;
//! office: the first `FRONTIER_OPT_STARTS`, default 3, with footprint and los; time limit
//! `FRONTIER_OPT_SECONDS`, default 5; weight `FRONTIER_OPT_WEIGHT`; goal
//! `FRONTIER_OPT_GOAL`), then runs criterion on the corridor floor's ten starts (as posed,
//! then with the first incumbent from a 4 times coarser map) and on maps
//! the search finishes: a 120 × 100-unit office, and 200 × 120-unit cave and potholes maps,
//! and the office with `los` at G = 1 (where the landmark path bound applies).
//! `FRONTIER_OPT_HARD=1` instead runs the paper's hard setting once (cell size 1, r = 20,
//! G = 0.95) on the corridor floor ([`hard`]) and prints the bounds reached;
//! `FRONTIER_OPT_SETTING="4,20,0.95"` runs another setting from the floor's ten starts
//! ([`setting`]).

use std::time::Duration;

use criterion::Criterion;
use grid::{Cell, Grid, GridMap, Occ};
use optimal::{ActionSet, Config, HeuristicKind, coarsen_problem, solve};
use sense::SensorSpec;
use world::{EnvKind, EnvSpec};

/// A generated map of `kind`, `size` metres at 0.1 m (one paper unit per cell).
fn generate(kind: EnvKind, size: (f64, f64), seed: u64) -> GridMap {
    world::generate(&EnvSpec {
        kind,
        seed,
        size_m: Some(size),
        resolution: Some(0.1),
    })
    .expect("generate map")
    .map
}

/// The stress map: a generated 35 m × 25 m office (350 × 250 units).
fn office() -> GridMap {
    generate(EnvKind::Office, (35.0, 25.0), 1)
}

/// Walls' thickness, the corridors' and the offices' sizes of [`corridor_floor`] (units).
const WALL: usize = 2;
const CORRIDOR: usize = 30;
const ROOM_DEPTH: usize = 25;
const ROOM_WIDTH: usize = 40;
const DOOR: usize = 10;

/// The paper-sized indoor map, 350 × 250 units at 0.1 m: a top corridor across the
/// building and a left corridor down it, 3 m wide, with a row of 2.5 m × 4 m offices along
/// the inner side of each (a 1 m door in the middle of each office's corridor wall); the
/// rest of the rectangle is outside the building.
fn corridor_floor() -> GridMap {
    let (w, h) = (350, 250);
    let mut cells = Grid::new(w, h, Occ::Occupied);
    let mut free = |x0: usize, y0: usize, x1: usize, y1: usize| {
        for y in y0..y1 {
            for x in x0..x1 {
                cells.set(Cell::new(x as i32, y as i32), Occ::Free);
            }
        }
    };
    let inner = WALL + CORRIDOR + WALL;
    free(WALL, WALL, w - WALL, WALL + CORRIDOR);
    free(WALL, WALL, WALL + CORRIDOR, h - WALL);
    let mut x = inner;
    while x + ROOM_WIDTH <= w - WALL {
        let door = x + (ROOM_WIDTH - DOOR) / 2;
        free(x, inner, x + ROOM_WIDTH, inner + ROOM_DEPTH);
        free(door, inner - WALL, door + DOOR, inner);
        x += ROOM_WIDTH + WALL;
    }
    let mut y = inner + ROOM_DEPTH + WALL;
    while y + ROOM_WIDTH <= h - WALL {
        let door = y + (ROOM_WIDTH - DOOR) / 2;
        free(inner, y, inner + ROOM_DEPTH, y + ROOM_WIDTH);
        free(inner - WALL, door, inner, door + DOOR);
        y += ROOM_WIDTH + WALL;
    }
    GridMap::new(cells, 0.1)
}

/// Ten starts evenly spaced along the corridor floor's centre line, from the bottom of the
/// left corridor up and then along the top corridor.
fn floor_starts(map: &GridMap) -> Vec<Cell> {
    let mid = (WALL + CORRIDOR / 2) as i32;
    let (w, h) = (map.width() as i32, map.height() as i32);
    let (down, across) = (h - 2 * mid, w - 2 * mid);
    let total = f64::from(down + across);
    (0..10)
        .map(|k| {
            let s = (total * (k as f64 + 0.5) / 10.0).round() as i32;
            if s <= down {
                Cell::new(mid, h - mid - s)
            } else {
                Cell::new(mid + s - down, mid)
            }
        })
        .collect()
}

/// The free cell nearest to `target` (ties: lower row, then column).
fn nearest_free(map: &GridMap, target: Cell) -> Cell {
    map.cells
        .cells()
        .filter(|&c| map.cells.get(c).is_free())
        .min_by_key(|&c| (c.dist2(target), c.y, c.x))
        .expect("a free cell")
}

/// Ten start cells: the free cells nearest to a 5 × 2 lattice over the map.
fn starts(map: &GridMap) -> Vec<Cell> {
    let (w, h) = (map.width() as i32, map.height() as i32);
    let mut out = Vec::new();
    for j in 0..2 {
        for i in 0..5 {
            out.push(nearest_free(
                map,
                Cell::new(w * (2 * i + 1) / 10, h * (2 * j + 1) / 4),
            ));
        }
    }
    out
}

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn config(goal: f64) -> Config {
    Config {
        goal,
        actions: ActionSet::Clusters { min_size: 1 },
        heuristic: HeuristicKind::Landmarks,
        weight: env_or("FRONTIER_OPT_WEIGHT", 1.0),
        time_limit: Some(Duration::from_secs_f64(env_or("FRONTIER_OPT_SECONDS", 5.0))),
        ..Config::default()
    }
}

/// The corridor floor from its ten starts (the paper's setting), printed per start and on
/// average; criterion then times all ten. Then the same with the first incumbent from the
/// map coarsened 4 times (`--coarse-incumbent 4`): its paths, off the cluster action set,
/// are shorter than the cluster optimum, and the search proves that no cluster path is
/// shorter than them.
fn floor(c: &mut Criterion) {
    let map = corridor_floor();
    let spec: SensorSpec = "footprint:r=3".parse().expect("sensor");
    let starts = floor_starts(&map);
    let problems: Vec<_> = starts
        .iter()
        .map(|&s| coarsen_problem(&map, 4, s, &spec).expect("problem"))
        .collect();
    let mut cfg = config(0.85);
    cfg.time_limit = None;
    cfg.weight = 1.0;
    let coarse = Config {
        coarse_incumbent: 4,
        ..cfg.clone()
    };
    let mut group = c.benchmark_group("optimal corridor floor");
    group.sample_size(10);
    for (name, cfg) in [("", &cfg), (", coarse incumbent 4", &coarse)] {
        let (mut secs, mut nodes, mut generated, mut length) = (0.0, 0, 0, 0.0);
        for (k, co) in problems.iter().enumerate() {
            let out = solve(&co.problem, cfg).expect("solve");
            secs += out.stats.seconds;
            nodes += out.stats.expanded;
            generated += out.stats.generated;
            length += out.upper_bound * 4.0;
            println!(
                "corridor floor, cell 4, footprint:r=3, G 0.85{name}, start {k} {}: {} length {:.1} units, {} expanded, {} generated, {:.4} s",
                starts[k],
                out.status.as_str(),
                out.upper_bound * 4.0,
                out.stats.expanded,
                out.stats.generated,
                out.stats.seconds
            );
        }
        let n = problems.len() as f64;
        println!(
            "corridor floor, cell 4, footprint:r=3, G 0.85{name}: mean length {:.1} units, {:.0} expanded, {:.0} generated, {:.4} s",
            length / n,
            nodes as f64 / n,
            generated as f64 / n,
            secs / n
        );
        group.bench_function(
            format!("cell 4 footprint:r=3 G 0.85{name}, ten starts"),
            |b| {
                b.iter(|| {
                    for co in &problems {
                        solve(&co.problem, cfg).expect("solve");
                    }
                })
            },
        );
    }
    group.finish();
}

fn easy(map: &GridMap, c: &mut Criterion) {
    let mut starts = starts(map);
    starts.truncate(env_or("FRONTIER_OPT_STARTS", 3));
    for sensor in ["footprint:r=3", "los:r=3"] {
        let spec: SensorSpec = sensor.parse().expect("sensor");
        let (mut total_s, mut total_nodes) = (0.0, 0);
        for (k, &s) in starts.iter().enumerate() {
            let co = coarsen_problem(map, 4, s, &spec).expect("problem");
            let out =
                solve(&co.problem, &config(env_or("FRONTIER_OPT_GOAL", 0.85))).expect("solve");
            total_s += out.stats.seconds;
            total_nodes += out.stats.expanded;
            println!(
                "cell 4, {sensor}, G 0.85, start {k} {s}: {} length {:.1} units (optimal >= {:.1}), {} expanded, {} stored, {:.4} s",
                out.status.as_str(),
                out.upper_bound * 4.0,
                out.lower_bound * 4.0,
                out.stats.expanded,
                out.stats.stored,
                out.stats.seconds
            );
        }
        println!(
            "cell 4, {sensor}, G 0.85: mean {:.4} s, {:.0} nodes expanded",
            total_s / starts.len() as f64,
            total_nodes as f64 / starts.len() as f64
        );
    }
    // Criterion on problems that finish: a 12 m x 10 m office (120 x 100 units), and 20 m x
    // 12 m cave and potholes maps (200 x 120 units) whose optimal paths (about 300 and 400
    // units) and node counts (about 1,400 and 2,500) are of the paper's indoor order.
    let cases: [Case; 4] = [
        (
            EnvKind::Office,
            (12.0, 10.0),
            0,
            &["footprint:r=3", "los:r=3"],
        ),
        (EnvKind::Cave, (20.0, 12.0), 0, &["footprint:r=3"]),
        (EnvKind::Potholes, (20.0, 12.0), 0, &["footprint:r=3"]),
        // G = 1, where the landmark path bound applies.
        (EnvKind::Office, (12.0, 10.0), 0, &["los:r=3 G=1"]),
    ];
    for (kind, size, seed, sensors) in cases {
        let small = generate(kind, size, seed);
        let centre = Cell::new(small.width() as i32 / 2, small.height() as i32 / 2);
        let s = nearest_free(&small, centre);
        let name = format!("{} {}x{} units", kind.name(), small.width(), small.height());
        for &case in sensors {
            let (sensor, goal) = match case.split_once(" G=") {
                Some((sensor, g)) => (sensor, g.parse().expect("goal")),
                None => (case, 0.85),
            };
            let spec: SensorSpec = sensor.parse().expect("sensor");
            let co = coarsen_problem(&small, 4, s, &spec).expect("problem");
            let mut cfg = config(goal);
            cfg.time_limit = None;
            cfg.weight = 1.0;
            let out = solve(&co.problem, &cfg).expect("solve");
            println!(
                "{name}, cell 4, {sensor}, G {goal}: {} length {:.1} units, {} expanded, {:.4} s",
                out.status.as_str(),
                out.upper_bound * 4.0,
                out.stats.expanded,
                out.stats.seconds
            );
            c.bench_function(&format!("optimal {name} cell 4 {sensor} G {goal}"), |b| {
                b.iter(|| solve(&co.problem, &cfg).expect("solve"))
            });
        }
    }
}

/// A map to solve: kind, size in metres, seed, sensors.
type Case = (EnvKind, (f64, f64), u64, &'static [&'static str]);

/// The paper's hard setting (cell size 1, r = 20, G = 0.95) on the corridor floor from
/// start `FRONTIER_OPT_START` (default 0) of its ten, under a time limit of
/// `FRONTIER_OPT_SECONDS` (default 60) and a memory budget of `FRONTIER_OPT_MB` MiB
/// (default 2048), its first incumbent from the map coarsened by `FRONTIER_OPT_COARSE`
/// (default 4; 0 for none); prints the bounds reached.
fn hard() {
    let map = corridor_floor();
    let secs: u64 = env_or("FRONTIER_OPT_SECONDS", 60);
    let spec: SensorSpec = "footprint:r=2".parse().expect("sensor");
    let k: usize = env_or("FRONTIER_OPT_START", 0);
    let s = floor_starts(&map)[k.min(9)];
    let co = coarsen_problem(&map, 1, s, &spec).expect("problem");
    let mut cfg = config(0.95);
    cfg.time_limit = Some(Duration::from_secs(secs));
    cfg.max_bytes = env_or("FRONTIER_OPT_MB", 2048usize) << 20;
    cfg.coarse_incumbent = env_or("FRONTIER_OPT_COARSE", 4);
    let out = solve(&co.problem, &cfg).expect("solve");
    println!(
        "corridor floor, cell 1, footprint r 20, G 0.95, start {k} {s}: {} [{:.1}, {:.1}] units, {} expanded, {} stored, {} MB, {:.1} s: {}",
        out.status.as_str(),
        out.lower_bound,
        out.upper_bound,
        out.stats.expanded,
        out.stats.stored,
        out.stats.bytes >> 20,
        out.stats.seconds,
        out.message
    );
}

/// Another of the paper's settings on the corridor floor's ten starts, from
/// `FRONTIER_OPT_SETTING` = "cell size,range in units,G" (e.g. "4,20,0.95", where the paper
/// timed out at 5 hours on 2 of its 10 starts), each start under `FRONTIER_OPT_SECONDS`
/// (default 600): one line per start and the mean.
fn setting(spec: &str) {
    let parts: Vec<f64> = spec
        .split(',')
        .filter_map(|p| p.trim().parse().ok())
        .collect();
    let [cell, range, goal] = parts[..] else {
        eprintln!("FRONTIER_OPT_SETTING: expected \"cell size,range in units,G\", found {spec:?}");
        return;
    };
    let map = corridor_floor();
    // One unit is one 0.1 m cell.
    let sensor: SensorSpec = format!("footprint:r={}", range / 10.0)
        .parse()
        .expect("sensor");
    let mut cfg = config(goal);
    cfg.weight = 1.0;
    cfg.time_limit = Some(Duration::from_secs(env_or("FRONTIER_OPT_SECONDS", 600)));
    cfg.max_bytes = env_or("FRONTIER_OPT_MB", 2048usize) << 20;
    let (mut secs, mut length, mut proven) = (0.0, 0.0, 0);
    let starts = floor_starts(&map);
    for (k, &s) in starts.iter().enumerate() {
        let co = coarsen_problem(&map, cell as usize, s, &sensor).expect("problem");
        let out = solve(&co.problem, &cfg).expect("solve");
        secs += out.stats.seconds;
        length += out.upper_bound * cell;
        proven += usize::from(out.status == optimal::Status::Optimal);
        println!(
            "corridor floor, cell {cell}, footprint r {range}, G {goal}, start {k} {s}: {} [{:.1}, {:.1}] units, {} expanded, {} MB, {:.2} s",
            out.status.as_str(),
            out.lower_bound * cell,
            out.upper_bound * cell,
            out.stats.expanded,
            out.stats.bytes >> 20,
            out.stats.seconds
        );
    }
    let n = starts.len() as f64;
    println!(
        "corridor floor, cell {cell}, footprint r {range}, G {goal}: {proven} of 10 optimal, mean length {:.1} units, mean {:.2} s",
        length / n,
        secs / n
    );
}

fn main() {
    if std::env::args().any(|a| a == "--list") {
        println!("office: bench");
        return;
    }
    if std::env::var("FRONTIER_OPT_HARD").is_ok() {
        hard();
        return;
    }
    if let Ok(spec) = std::env::var("FRONTIER_OPT_SETTING") {
        setting(&spec);
        return;
    }
    let mut c = Criterion::default()
        .configure_from_args()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    floor(&mut c);
    easy(&office(), &mut c);
    c.final_summary();
}
