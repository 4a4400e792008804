//! Whole explorations with the one loop: `cf-rr`, `cf` and `yamauchi` on default-size
//! generated environments (criterion).

use criterion::{Criterion, criterion_group, criterion_main};
use explore::strategy::Strategy;
use sim::RunConfig;
use world::{EnvKind, EnvSpec};

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("explore");
    group.sample_size(10);
    for kind in [EnvKind::Office, EnvKind::Hospital, EnvKind::Cave] {
        let env = world::generate(&EnvSpec {
            kind,
            seed: 1,
            size_m: None,
            resolution: None,
        })
        .unwrap();
        for preset in ["cf-rr", "cf", "yamauchi"] {
            let cfg = RunConfig::new(Strategy::preset(preset).unwrap());
            group.bench_function(format!("{kind}/{preset}"), |b| {
                b.iter(|| sim::run(&env.map, &cfg).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
