//! One `los` scan + `KnownGrid` integration at r = 100 cells, the template build, the
//! ray template against shadow casting ([`sense::shadow`]) at several ranges, and Holz et
//! al.'s laser at 0.05 m facing a move heading (beam tree) and another (beams walked), and
//! Explore-Bench's square window at 0.1 m; and a scan read from a remembered line of sight
//! ([`sense::SightCache`]) against shadow casting at r = 35 (7 m at 0.2 m), with all in
//! range unseen or only a strip at its edge.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use grid::{Cell, Grid, Occ};
use sense::{
    Belief, KnownGrid, LidarSensor, LosSensor, LosTemplate, Observation, Pose, Sensor, SightBudget,
    SightCache, Unseen,
};

const N: usize = 400;
const R: f64 = 100.0;

/// 400×400 rooms of 40×40 cells: walls every 40 cells with a 4-cell door in each wall
/// segment, plus a few pillars.
fn rooms() -> Grid<Occ> {
    let mut g = Grid::new(N, N, Occ::Free);
    for i in 0..N {
        for w in (0..N).step_by(40) {
            let door = i % 40 >= 18 && i % 40 < 22;
            if !door {
                g.set(Cell::new(w as i32, i as i32), Occ::Occupied);
                g.set(Cell::new(i as i32, w as i32), Occ::Occupied);
            }
        }
    }
    for y in (10..N).step_by(40) {
        for x in (10..N).step_by(40) {
            g.set(Cell::new(x as i32, y as i32), Occ::Occupied);
        }
    }
    g
}

/// 400×400 cells, about 5 % of them single obstacles scattered at random (a fixed
/// sequence), as the `potholes` environment's.
fn holes() -> Grid<Occ> {
    let mut g = Grid::new(N, N, Occ::Free);
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    for c in g.data_mut() {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        if x.is_multiple_of(20) {
            *c = Occ::Occupied;
        }
    }
    g
}

fn bench(c: &mut Criterion) {
    let sensor = LosSensor::new(R).expect("valid range");
    eprintln!(
        "template r={R}: {} targets, {} nodes",
        sensor.template().targets(),
        sensor.template().len()
    );
    // The centre of a room (walls lie on multiples of 40, pillars at 10 + 40k).
    let pose = Pose::new(Cell::new(220, 220), 0.0);
    for (name, truth) in [("open", Grid::new(N, N, Occ::Free)), ("rooms", rooms())] {
        let mut obs = Observation::new();
        let mut changed = Vec::new();
        sensor.scan(&truth, pose, &mut obs);
        eprintln!("{name}: {} cells seen", obs.len());
        c.bench_function(&format!("los_scan_integrate_r100_{name}"), |b| {
            // A fresh, all-Unknown belief per iteration (built outside the timing).
            b.iter_batched_ref(
                || KnownGrid::new(N, N),
                |belief| {
                    changed.clear();
                    sensor.scan(black_box(&truth), pose, &mut obs);
                    belief.integrate(&obs, &mut changed);
                    black_box(changed.len())
                },
                BatchSize::LargeInput,
            )
        });
        c.bench_function(&format!("los_scan_only_r100_{name}"), |b| {
            b.iter(|| {
                sensor.scan(black_box(&truth), pose, &mut obs);
                black_box(obs.len())
            })
        });
    }
    // Ray template against shadow casting, the same cells, by range.
    let mut scratch = sense::shadow::ShadowScratch::default();
    for (name, truth) in [("open", Grid::new(N, N, Occ::Free)), ("rooms", rooms())] {
        for r in [12.0, 15.0, 28.0, 64.0, 128.0] {
            let los = LosSensor::new(r).expect("valid range");
            let mut n = 0usize;
            c.bench_function(&format!("visible_template_r{r}_{name}"), |b| {
                b.iter(|| {
                    los.for_each_seen(black_box(&truth), pose.cell, |i, _| n += i as usize);
                })
            });
            c.bench_function(&format!("visible_shadow_r{r}_{name}"), |b| {
                b.iter(|| {
                    sense::shadow::visible(
                        black_box(&truth),
                        pose.cell,
                        r,
                        |s| s == Occ::Free,
                        &mut scratch,
                        |i, _| n += i as usize,
                    )
                })
            });
            black_box(n);
        }
    }
    // Holz et al.'s laser (8 m, 180° at 1°) at 0.05 m: 160 cells.
    let lidar = LidarSensor::new(160.0, 180.0, 1.0).expect("valid lidar");
    for (name, truth) in [("open", Grid::new(N, N, Occ::Free)), ("rooms", rooms())] {
        for (heading_name, heading) in [("move_heading", 0.0), ("other_heading", 0.3)] {
            let mut obs = Observation::new();
            c.bench_function(&format!("lidar_scan_r160_{name}_{heading_name}"), |b| {
                b.iter(|| {
                    lidar.scan(black_box(&truth), Pose::new(pose.cell, heading), &mut obs);
                    black_box(obs.len())
                })
            });
        }
    }
    // Explore-Bench's window (3.5 m at 0.1 m: half-side 35 cells).
    let square = sense::SquareSensor::new(35.0).expect("valid window");
    for (name, truth) in [("open", Grid::new(N, N, Occ::Free)), ("rooms", rooms())] {
        let mut obs = Observation::new();
        c.bench_function(&format!("square_scan_r35_{name}"), |b| {
            b.iter(|| {
                square.scan(black_box(&truth), pose, &mut obs);
                black_box(obs.len())
            })
        });
    }
    // A remembered line of sight against shadow casting, r = 35.
    let los = LosSensor::new(35.0).expect("valid range");
    for (name, truth) in [("holes", holes()), ("rooms", rooms())] {
        let cache =
            SightCache::new(&truth, los.clone(), SightBudget::new(u64::MAX / 2)).expect("fits");
        let mut obs = Observation::new();
        // The second scan from a cell makes its set.
        cache.scan(pose, &mut obs);
        cache.scan(pose, &mut obs);
        let fresh = Unseen::new(&truth, 1, 2);
        // Sensed: everything but the last 5 columns in range, east of the robot.
        let mut most = Unseen::new(&truth, 1, 2);
        let sensed = (0..truth.len() as u32).filter(|&i| (i as usize % N) < 220 + 30);
        most.record(0, sensed);
        for (which, unseen) in [("unseen", &fresh), ("strip", &most)] {
            c.bench_function(&format!("los_scan_unseen_r35_{name}_{which}"), |b| {
                b.iter(|| {
                    los.scan_unseen(black_box(&truth), pose, unseen, &mut obs);
                    black_box(obs.len())
                })
            });
            c.bench_function(&format!("sight_scan_unseen_r35_{name}_{which}"), |b| {
                b.iter(|| {
                    cache.scan_unseen(pose, black_box(unseen), &mut obs);
                    black_box(obs.len())
                })
            });
        }
    }
    let mut g = c.benchmark_group("template");
    g.sample_size(10);
    g.bench_function("los_template_build_r100", |b| {
        b.iter(|| black_box(LosTemplate::new(black_box(R)).expect("valid").len()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
