//! Generation time of the built-in environments.

use criterion::{Criterion, criterion_group, criterion_main};
use world::{EnvKind, EnvSpec, generate};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("generate");
    g.sample_size(10);
    for &kind in EnvKind::all() {
        g.bench_function(format!("{kind}-default"), |b| {
            b.iter(|| generate(&EnvSpec::new(kind, 1)).map(|e| e.room_count))
        });
    }
    let big = EnvSpec::new(EnvKind::Office, 1)
        .with_size(100.0, 100.0)
        .with_resolution(0.05);
    g.bench_function("office-100x100m-r0.05", |b| {
        b.iter(|| generate(&big).map(|e| e.room_count))
    });
    // Caves dig tunnels between their caves: their time should grow with the cells, as
    // the others' does (a search per tunnel made a 120 x 120 m cave take 4.2 s).
    let cave = EnvSpec::new(EnvKind::Cave, 1)
        .with_size(100.0, 100.0)
        .with_resolution(0.05);
    g.bench_function("cave-100x100m-r0.05", |b| {
        b.iter(|| generate(&cave).map(|e| e.room_count))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
