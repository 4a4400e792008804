//! Trials per second on the `quick` suite with 1 and 2 threads (issue 9, "How it is
//! checked": goal >= 1.8x speed-up on 2 cores). To keep a criterion sample short, each
//! iteration runs every 8th trial of the suite (a spread over environments, strategies and
//! robot counts) into a fresh database.

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};

fn quick(c: &mut Criterion) {
    let mut plan = bench::suites::plan("quick").expect("quick suite resolves");
    plan.trials = plan.trials.iter().step_by(8).cloned().collect();
    let n = plan.trials.len() as u64;
    let mut g = c.benchmark_group("quick_suite");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n));
    for threads in [1usize, 2] {
        g.bench_function(format!("{n}_trials_{threads}_threads"), |b| {
            b.iter_batched(
                || tempfile::tempdir().expect("temp dir"),
                |dir| {
                    let opts = bench::RunOptions {
                        threads: Some(threads),
                        ..bench::RunOptions::default()
                    };
                    let s = bench::runner::run(&plan, &dir.path().join("q.sqlite"), &opts)
                        .expect("run");
                    assert_eq!(s.ran as u64, n);
                },
                BatchSize::PerIteration,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, quick);
criterion_main!(benches);
