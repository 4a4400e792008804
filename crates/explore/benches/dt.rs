//! Decision-theoretic decisions at Holz et al.'s scale: a 1000 × 1000 map at 0.05 m (50 m),
//! left half known, a 180° lidar of 8 m (160 cells, 181 beams). Measures one whole decision
//! (reachability, vicinity, 100 or 500 samples, the gains the utility needs, utility) and
//! the gain evaluations of all samples alone, on the shared scattered-obstacle world and on
//! an empty hall (long beams, the worst case).

mod common;

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use explore::FrontierUpkeep;
use explore::assign::utility;
use explore::candidates::CandidateSet;
use explore::candidates::dt_samples;
use explore::decision::{DecisionCtx, GoalLists, Memory, Planner};
use grid::{Cell, Grid, Occ};
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::{
    Belief, GainScratch, InverseModel, KnownGrid, LidarSensor, Observation, Pose, Sensor,
    information_gain,
};

const N: usize = 1000;

struct Scene {
    belief: KnownGrid,
    upkeep: FrontierUpkeep,
    robot: u32,
}

fn scene(truth: &Grid<Occ>) -> Scene {
    let (known, upkeep) = common::half_explored(truth);
    let mut belief = KnownGrid::new(N, N);
    let obs = Observation {
        origin: Cell::new(0, 0),
        cells: known
            .data()
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.is_unknown())
            .map(|(i, &s)| (i as u32, s))
            .collect(),
    };
    belief.integrate(&obs, &mut Vec::new());
    // A traversable cell a few metres inside the known half.
    let robot = (N / 2..N)
        .flat_map(|y| (N / 2 - 60..N / 2 - 20).map(move |x| y * N + x))
        .find(|&i| upkeep.is_traversable(belief.known(), i))
        .expect("a free cell") as u32;
    Scene {
        belief,
        upkeep,
        robot,
    }
}

fn bench_scene(c: &mut Criterion, name: &str, truth: &Grid<Occ>) {
    let mut s = scene(truth);
    let sensor = LidarSensor::new(160.0, 180.0, 1.0).expect("lidar");
    let mut planner = Planner::new(N, N, 1);
    let lists = GoalLists::new(N * N);
    let mut memory = Memory::default();
    let mut candidates = CandidateSet::new(N * N);
    let mut out = vec![None; 1];
    let robots = [s.robot];
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    for n in [100, 500] {
        c.bench_function(&format!("dt/{name}/decision_n{n}"), |b| {
            b.iter(|| {
                planner.invalidate();
                let mut ctx = DecisionCtx {
                    known: s.belief.known(),
                    upkeep: &mut s.upkeep,
                    planner: &mut planner,
                    robots: &robots,
                    deciding: &[true],
                    goals: &[None],
                    lists: &lists,
                    resolution: 0.05,
                    sensor_range_cells: sensor.range_cells(),
                    rng: &mut rng,
                    belief: &s.belief,
                    sensor: &sensor,
                    memory: &mut memory,
                };
                candidates.clear();
                dt_samples::generate(&mut ctx, n, &mut candidates);
                utility::assign(&mut ctx, &candidates, 0.2, &mut out);
                black_box(out[0])
            })
        });
    }
    // The gains alone, at every sample of the last decision (evaluating those the lazy
    // utility assigner did not need), with their arrival headings.
    for k in 0..memory.dt.cells.len() {
        let by = planner.map(memory.dt.reachers[k] as usize);
        memory.dt.gain(k, &sensor, &s.belief, by);
    }
    let poses: Vec<Pose> = memory
        .dt
        .cells
        .iter()
        .zip(&memory.dt.headings)
        .map(|(&c, &h)| Pose::new(s.belief.known().cell(c as usize), h))
        .collect();
    eprintln!(
        "{name}: {} samples, mean gain {:.0} bits",
        poses.len(),
        memory.dt.gains.iter().sum::<f64>() / poses.len().max(1) as f64
    );
    let mut scratch = GainScratch::new();
    c.bench_function(&format!("dt/{name}/gains_500"), |b| {
        b.iter(|| {
            let mut total = 0.0;
            for &p in &poses {
                total +=
                    information_gain(&sensor, &s.belief, &InverseModel::IDEAL, p, &mut scratch);
            }
            black_box(total)
        })
    });
}

fn bench(c: &mut Criterion) {
    bench_scene(c, "scattered", &common::truth(N));
    let mut hall = Grid::new(N, N, Occ::Free);
    for i in 0..N * N {
        let p = hall.cell(i);
        if p.x == 0 || p.y == 0 || p.x as usize == N - 1 || p.y as usize == N - 1 {
            hall[i] = Occ::Occupied;
        }
    }
    bench_scene(c, "hall", &hall);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
