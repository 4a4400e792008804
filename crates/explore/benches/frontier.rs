//! Incremental frontier upkeep per scan vs the from-scratch detector on half-explored maps.
//!
//! Each timed iteration reveals a disk of the ground truth next to the known half (every cell
//! in it changes class) and updates the upkeep; an untimed step hides it again.

mod common;

use common::{disk, half_explored, truth};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use explore::frontiers_from_scratch;
use grid::Occ;
use std::hint::black_box;
use std::time::{Duration, Instant};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("frontier");
    g.sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for n in [500usize, 2000] {
        let truth = truth(n);
        let (mut known, mut up) = half_explored(&truth);
        for (name, r) in [("scan_r100", 100i64), ("scan_r5", 5)] {
            // disk just beyond the explored half, touching the frontier
            let cells = disk(n, (n / 2) as i64 + r, (n / 2) as i64, r);
            eprintln!("n = {n}: {name} changes {} cells", cells.len());
            g.bench_function(BenchmarkId::new(format!("incremental_{name}"), n), |b| {
                b.iter_custom(|iters| {
                    let mut total = Duration::ZERO;
                    for _ in 0..iters {
                        for &i in &cells {
                            known[i as usize] = truth[i as usize];
                        }
                        let t = Instant::now();
                        up.update(black_box(&known), black_box(&cells));
                        total += t.elapsed();
                        for &i in &cells {
                            known[i as usize] = Occ::Unknown;
                        }
                        up.update(&known, &cells);
                    }
                    total
                })
            });
        }
        g.bench_function(BenchmarkId::new("from_scratch", n), |b| {
            b.iter(|| black_box(frontiers_from_scratch(black_box(&known), &up.trav)))
        });
        g.bench_function(BenchmarkId::new("rebuild_with_traversability", n), |b| {
            b.iter(|| up.rebuild(black_box(&known)))
        });
        let mut regions = Vec::new();
        g.bench_function(BenchmarkId::new("regions", n), |b| {
            b.iter(|| {
                up.regions(n, 5, &mut regions);
                black_box(regions.len())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
