//! One decision for 10 robots on a 1000 × 1000 map with ~1000 frontier cells (the left half
//! known): Faigl & Kulich's RFE and CC generation, and the MA and SGA assigners.
//!
//! The robots' reachability maps are computed once before the timed pieces (they are
//! shared by every piece of a decision and benchmarked in `plan`); `decision_*` times a
//! whole decision including the 10 maps.

mod common;

use common::{half_explored, truth};
use criterion::{Criterion, criterion_group, criterion_main};
use explore::FrontierUpkeep;
use explore::assign::AssignerKind;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{DecisionCtx, Goal, GoalLists, Memory, Planner};
use grid::{Grid, Occ};
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::{KnownGrid, LosSensor};
use std::hint::black_box;

/// Sensor range in cells (5 m at 0.2 m, the default sensor on the default potholes map).
const RHO: f64 = 25.0;
const ROBOTS: usize = 10;

struct Fx {
    known: Grid<Occ>,
    up: FrontierUpkeep,
    planner: Planner,
    lists: GoalLists,
    rng: Pcg64Mcg,
    belief: KnownGrid,
    sensor: LosSensor,
    memory: Memory,
    robots: Vec<u32>,
    deciding: Vec<bool>,
    goals: Vec<Option<u32>>,
}

impl Fx {
    fn ctx(&mut self, fresh_maps: bool) -> DecisionCtx<'_> {
        if fresh_maps {
            self.planner.invalidate();
        }
        DecisionCtx {
            known: &self.known,
            upkeep: &mut self.up,
            planner: &mut self.planner,
            robots: &self.robots,
            deciding: &self.deciding,
            goals: &self.goals,
            lists: &self.lists,
            resolution: 0.2,
            sensor_range_cells: RHO,
            rng: &mut self.rng,
            belief: &self.belief,
            sensor: &self.sensor,
            memory: &mut self.memory,
        }
    }
}

fn bench(c: &mut Criterion) {
    let n = 1000;
    let truth = truth(n);
    let (known, up) = half_explored(&truth);
    // Ten robots spread over the known half, on traversable cells.
    let robots: Vec<u32> = (0..ROBOTS)
        .map(|k| {
            let y = 50 + k * 90;
            let base = y * n + 100 + 30 * k;
            (base..base + 50)
                .find(|&i| up.is_traversable(&known, i))
                .expect("a free cell") as u32
        })
        .collect();
    let mut fx = Fx {
        planner: Planner::new(n, n, ROBOTS),
        lists: GoalLists::new(n * n),
        rng: Pcg64Mcg::seed_from_u64(1),
        belief: KnownGrid::new(n, n),
        sensor: LosSensor::new(RHO).expect("range"),
        memory: Memory::default(),
        deciding: vec![true; ROBOTS],
        goals: vec![None; ROBOTS],
        robots,
        known,
        up,
    };
    eprintln!("frontier cells: {}", fx.up.frontiers.len());
    let mut af = CandidateSet::new(n * n);
    let mut rfe = CandidateSet::new(n * n);
    let mut cc = CandidateSet::new(n * n);
    let mut out: Vec<Option<Goal>> = vec![None; ROBOTS];
    {
        let mut ctx = fx.ctx(true);
        for r in 0..ROBOTS {
            ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
        }
        CandidateKind::AllFrontiers.generate(&mut ctx, &mut af);
        CandidateKind::Rfe { min_edge: 1 }.generate(&mut ctx, &mut rfe);
        CandidateKind::Coverage.generate(&mut ctx, &mut cc);
    }
    eprintln!(
        "candidates: af {}, rfe {}, cc {}",
        af.len(),
        rfe.len(),
        cc.len()
    );

    let mut g = c.benchmark_group("candidates_1000_10robots");
    g.sample_size(10);
    g.bench_function("rfe_generate", |b| {
        b.iter(|| {
            let mut ctx = fx.ctx(false);
            CandidateKind::Rfe { min_edge: 1 }.generate(&mut ctx, &mut rfe);
            black_box(rfe.len())
        })
    });
    g.bench_function("cc_generate", |b| {
        b.iter(|| {
            let mut ctx = fx.ctx(false);
            CandidateKind::Coverage.generate(&mut ctx, &mut cc);
            black_box(cc.len())
        })
    });
    for (name, kind, set) in [
        ("ma_on_cc", AssignerKind::Mtsp, &cc),
        ("ma_on_rfe", AssignerKind::Mtsp, &rfe),
        ("sga_on_af", AssignerKind::Sga, &af),
        ("sga_on_cc", AssignerKind::Sga, &cc),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut ctx = fx.ctx(false);
                kind.assign(&mut ctx, set, &mut out);
                black_box(out[0])
            })
        });
    }
    g.bench_function("decision_cc_ma_with_maps", |b| {
        b.iter(|| {
            let mut ctx = fx.ctx(true);
            CandidateKind::Coverage.generate(&mut ctx, &mut cc);
            AssignerKind::Mtsp.assign(&mut ctx, &cc, &mut out);
            black_box(out[0])
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
