//! One decision of every coordinated assigner for 10 robots on a 1000 × 1000 map with about
//! 1000 frontier cells (the left half known): the assignment alone on a precomputed cost
//! matrix (`solve_*`), and the whole decision including the 10 reachability maps
//! (`decide_*`).

mod common;

use common::{half_explored, truth};
use criterion::{Criterion, criterion_group, criterion_main};
use explore::assign::greedy::CostMatrix;
use explore::assign::{AssignerKind, greedy, greedy_utility, hungarian, minpos, random_order};
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{DecisionCtx, GoalLists, Memory, Planner};
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let n = 1000;
    let m = 10;
    let truth = truth(n);
    let (known, mut up) = half_explored(&truth);
    // Ten robots spread over the known half.
    let robots: Vec<u32> = (0..m)
        .map(|k| {
            let y = 50 + k * 90;
            let x = 100 + (k % 3) * 120;
            (y * n + x..y * n + x + 50)
                .find(|&i| up.is_traversable(&known, i))
                .expect("a traversable cell") as u32
        })
        .collect();
    let deciding = vec![true; m];
    let goals = vec![None; m];
    let lists = GoalLists::new(n * n);
    let mut planner = Planner::new(n, n, m);
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    let belief = sense::KnownGrid::new(n, n);
    let sensor = sense::LosSensor::new(10.0).expect("sensor");
    let mut memory = Memory::default();
    let mut cands = CandidateSet::new(n * n);
    let mut matrix = CostMatrix::default();
    let mut out = vec![None; m];
    let mut g = c.benchmark_group("assign_1000_m10");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    {
        let mut ctx = DecisionCtx {
            known: &known,
            upkeep: &mut up,
            planner: &mut planner,
            robots: &robots,
            deciding: &deciding,
            goals: &goals,
            lists: &lists,
            resolution: 0.05,
            sensor_range_cells: 10.0,
            rng: &mut rng,
            belief: &belief,
            sensor: &sensor,
            memory: &mut memory,
        };
        CandidateKind::AllFrontiers.generate(&mut ctx, &mut cands);
        matrix.fill(&mut ctx, &cands, true);
        eprintln!("{} candidates, {} robots", cands.len(), m);
        for (name, kind) in [
            ("decide_greedy", AssignerKind::Greedy),
            ("decide_ga", AssignerKind::RandomOrderGreedy),
            (
                "decide_greedy_utility",
                AssignerKind::GreedyUtility {
                    beta: greedy_utility::DEFAULT_BETA,
                },
            ),
            ("decide_minpos", AssignerKind::MinPos),
            ("decide_ha", AssignerKind::Hungarian),
        ] {
            g.bench_function(name, |b| {
                b.iter(|| {
                    ctx.planner.invalidate();
                    kind.assign(&mut ctx, &cands, &mut out);
                    black_box(&out);
                })
            });
        }
    }
    let cols = matrix.n_cols();
    let (mut free, mut assigned) = (Vec::new(), Vec::new());
    g.bench_function("solve_greedy", |b| {
        b.iter(|| {
            greedy::solve(
                m,
                cols,
                &matrix.cost,
                &matrix.taken,
                &mut free,
                &mut assigned,
            );
            black_box(&assigned);
        })
    });
    let order: Vec<usize> = (0..m).rev().collect();
    g.bench_function("solve_ga", |b| {
        b.iter(|| {
            random_order::solve(
                cols,
                &matrix.cost,
                &matrix.taken,
                &order,
                &mut free,
                &mut assigned,
            );
            black_box(&assigned);
        })
    });
    let pos: Vec<(f64, f64)> = matrix
        .cols
        .iter()
        .map(|&c| ((c as usize % n) as f64, (c as usize / n) as f64))
        .collect();
    let mut util = Vec::new();
    g.bench_function("solve_greedy_utility", |b| {
        b.iter(|| {
            greedy_utility::solve(
                m,
                &matrix.cost,
                &pos,
                &[],
                &matrix.taken,
                10.0,
                greedy_utility::DEFAULT_BETA,
                &mut util,
                &mut free,
                &mut assigned,
            );
            black_box(&assigned);
        })
    });
    g.bench_function("solve_minpos", |b| {
        b.iter(|| {
            minpos::solve(
                m,
                cols,
                &matrix.cost,
                &deciding,
                &matrix.taken,
                &mut assigned,
            );
            black_box(&assigned);
        })
    });
    let mut buf = hungarian::Buffers::default();
    g.bench_function("solve_ha", |b| {
        b.iter(|| {
            hungarian::solve(
                m,
                cols,
                &matrix.cost,
                &matrix.taken,
                &mut buf,
                &mut assigned,
            );
            black_box(&assigned);
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
