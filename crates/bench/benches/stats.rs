//! Speed of the statistics on study-sized groups (Faigl & Kulich: 400 trials per method).

use bench::stats::{
    Pairing, mann_whitney_u, pairwise_matrix, shapiro_wilk, summarize, wilcoxon_signed_rank,
};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

/// Deterministic pseudo-random sample (xorshift), shifted by `mu`.
fn sample(n: usize, seed: u64, mu: f64) -> Vec<f64> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            mu + (s >> 11) as f64 / (1u64 << 53) as f64 * 10.0
        })
        .collect()
}

fn bench_stats(c: &mut Criterion) {
    let a = sample(400, 1, 0.0);
    let b = sample(400, 2, 0.5);
    let (s8, l60) = (sample(8, 3, 0.0), sample(60, 4, 1.0));
    let (w50a, w50b) = (sample(50, 5, 0.0), sample(50, 6, 0.3));
    c.bench_function("summarize_400", |bn| bn.iter(|| summarize(black_box(&a))));
    c.bench_function("mann_whitney_400x400_asymptotic", |bn| {
        bn.iter(|| mann_whitney_u(black_box(&a), black_box(&b)))
    });
    c.bench_function("mann_whitney_8x60_exact", |bn| {
        bn.iter(|| mann_whitney_u(black_box(&s8), black_box(&l60)))
    });
    c.bench_function("wilcoxon_400_asymptotic", |bn| {
        bn.iter(|| wilcoxon_signed_rank(black_box(&a), black_box(&b)))
    });
    c.bench_function("wilcoxon_50_exact", |bn| {
        bn.iter(|| wilcoxon_signed_rank(black_box(&w50a), black_box(&w50b)))
    });
    c.bench_function("shapiro_wilk_400", |bn| {
        bn.iter(|| shapiro_wilk(black_box(&a)))
    });
    let groups: Vec<Vec<f64>> = (0..12)
        .map(|i| sample(400, 10 + i, i as f64 * 0.1))
        .collect();
    let refs: Vec<&[f64]> = groups.iter().map(Vec::as_slice).collect();
    c.bench_function("matrix_12_methods_400_paired", |bn| {
        bn.iter(|| pairwise_matrix(black_box(&refs), 0.001, Pairing::Paired))
    });
}

criterion_group!(benches, bench_stats);
criterion_main!(benches);
