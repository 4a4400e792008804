//! Open TSP routes as MA solves them (`explore::tsp`): full effort (12 starts and up to
//! 1200 / n perturbations) on goals scattered over a 200 × 200 grid, costs their octile
//! distances. Up to 24 nodes the local search is full 3-opt (`full_n16`, `full_n24`), beyond
//! it 2-opt and Or-opt over neighbour lists (`full_n200`); `fast_n200` is the one start
//! without perturbations of MA's robot × cluster matrix.

use criterion::{Criterion, criterion_group, criterion_main};
use explore::tsp::OpenTsp;
use grid::Cell;
use std::hint::black_box;

/// The octile-distance matrix ([`Cell::octile`]) of `n` cells drawn by a fixed linear
/// congruential generator.
fn instance(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    let mut draw = || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((s >> 33) % 200) as i32
    };
    let cells: Vec<Cell> = (0..n).map(|_| Cell::new(draw(), draw())).collect();
    cells
        .iter()
        .flat_map(|&a| cells.iter().map(move |&b| a.octile(b)))
        .collect()
}

fn bench(c: &mut Criterion) {
    for (name, n, starts, kicks) in [
        ("full_n16", 16, 12, 100),
        ("full_n24", 24, 12, 100),
        ("full_n200", 200, 12, 100),
        ("fast_n200", 200, 1, 0),
    ] {
        let instances: Vec<Vec<f64>> = (0..8).map(|s| instance(n, s + 1)).collect();
        let mut tsp = OpenTsp::with_effort(starts, kicks);
        c.bench_function(&format!("tsp_{name}"), |b| {
            b.iter(|| {
                let mut total = 0.0;
                for d in &instances {
                    total += tsp.solve(n, black_box(d));
                }
                total
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
