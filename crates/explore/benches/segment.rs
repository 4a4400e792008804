//! Room segmentation (Holz et al. 2010 Fig. 7) on a 1000 × 1000 partial map: the whole
//! pipeline, its first step alone, and the cached state when nothing or little changed.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use explore::segment::{Rule, Segmenter, State};
use grid::{Grid, Occ};
use std::hint::black_box;
use world::{EnvKind, EnvSpec};

/// A 50 m × 50 m hospital at 5 cm (1000 × 1000 cells) of which only the left 60 % and a
/// disc are known.
fn partial_map() -> Grid<Occ> {
    let spec = EnvSpec::new(EnvKind::Hospital, 1)
        .with_size(50.0, 50.0)
        .with_resolution(0.05);
    let env = world::generate(&spec).expect("generate");
    let mut g = env.map.cells;
    let (w, h) = (g.width(), g.height());
    for y in 0..h {
        for x in 0..w {
            let (dx, dy) = (x as f64 - 800.0, y as f64 - 500.0);
            if x > 600 && dx * dx + dy * dy > 150.0 * 150.0 {
                g.data_mut()[y * w + x] = Occ::Unknown;
            }
        }
    }
    g
}

fn bench(c: &mut Criterion) {
    let map = partial_map();
    let mut s = Segmenter::new();
    let seg = s.run(&map, Rule::Holz);
    eprintln!(
        "1000 x 1000 partial hospital: {} segments, {} critical points",
        seg.count,
        seg.critical.len()
    );
    let mut g = c.benchmark_group("segment_1000x1000");
    g.sample_size(10);
    for rule in Rule::ALL {
        g.bench_function(format!("full_{}", rule.name()), |b| {
            b.iter(|| black_box(s.run(black_box(&map), rule).count))
        });
    }
    g.bench_function("skeleton_only", |b| {
        b.iter(|| s.skeleton.compute(black_box(&map)))
    });
    let mut state = State::new();
    state.update(&map, Rule::Holz);
    g.bench_function("cached_unchanged", |b| {
        b.iter(|| black_box(state.update(black_box(&map), Rule::Holz).count))
    });
    // a sensor's worth of new cells (a 20-cell-radius disc becomes known) is patched
    let mut grown = map.clone();
    let w = grown.width();
    for y in 480..520 {
        for x in 601..660 {
            if (x as i64 - 601).pow(2) + (y as i64 - 500).pow(2) < 400 {
                grown.data_mut()[y * w + x] = Occ::Free;
            }
        }
    }
    g.bench_function("cached_patch", |b| {
        b.iter_batched(
            || {
                let mut st = State::new();
                st.update(&map, Rule::Holz);
                st
            },
            |mut st| {
                let n = st.update(black_box(&grown), Rule::Holz).count;
                assert_eq!(
                    st.full_runs(),
                    1,
                    "the disc must be patched, not recomputed"
                );
                black_box(n)
            },
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
