//! One firing of Yamauchi's sonar ring (16 cones) and its integration into the evidence
//! grid, alone and laser-limited, at 0.1 m per cell (10 ft = 30.5 cells) among rooms.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use grid::{Cell, Grid, Occ};
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::{EvidenceGrid, Pose, SonarParams, SonarSensor};

const N: usize = 200;

/// 200×200 rooms of 40×40 cells with 8-cell doors.
fn rooms() -> Grid<Occ> {
    let mut g = Grid::new(N, N, Occ::Free);
    for i in 0..N {
        for w in (0..N).step_by(40) {
            if !(16..24).contains(&(i % 40)) {
                g.set(Cell::new(w as i32, i as i32), Occ::Occupied);
                g.set(Cell::new(i as i32, w as i32), Occ::Occupied);
            }
        }
    }
    g
}

fn bench(c: &mut Criterion) {
    let truth = rooms();
    let mut sonar = SonarSensor::new(SonarParams::yamauchi(0.1)).expect("sonar");
    let pose = Pose::new(Cell::new(95, 90), 0.3);
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    let mut readings = Vec::new();
    let mut hits = Vec::new();
    let mut changed = Vec::new();
    c.bench_function("sonar_fire_16", |b| {
        b.iter(|| {
            sonar.fire(black_box(&truth), None, pose, &mut rng, &mut readings);
            black_box(readings.len())
        })
    });
    for limited in [false, true] {
        let name = if limited {
            "laser_limited_sonar_fire_integrate"
        } else {
            "sonar_fire_integrate"
        };
        c.bench_function(name, |b| {
            b.iter_batched_ref(
                || EvidenceGrid::new(N, N),
                |belief| {
                    changed.clear();
                    hits.clear();
                    sonar.fire(&truth, None, pose, &mut rng, &mut readings);
                    if limited {
                        sonar.limit_by_laser(&truth, pose.cell, &mut readings, &mut hits);
                    }
                    sonar.integrate(pose.cell, &readings, &hits, belief, &mut changed);
                    black_box(changed.len())
                },
                BatchSize::LargeInput,
            )
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
