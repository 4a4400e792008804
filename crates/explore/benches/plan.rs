//! Planning on a 2000 × 2000 map: nearest frontier (near and far, unguided and as the
//! nearest rule searches), full reachability, the
//! resumable search (whole, and to far goals with and without guidance, guided in
//! canonical order and as Dial's), the reachability flood fill, A*, EDT.

mod common;

use common::{half_explored, truth};
use criterion::{Criterion, criterion_group, criterion_main};
use explore::plan::Component;
use explore::{AStar, Reachability};
use grid::edt::{EdtScratch, edt_squared_into};
use grid::{Grid, Occ};
use std::hint::black_box;
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let n = 2000;
    let truth = truth(n);
    let (known, up) = half_explored(&truth);
    let mut g = c.benchmark_group("plan_2000");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    let mut r = Reachability::new(n, n);
    let passable = |i: usize| up.is_traversable(&known, i);
    let is_goal = |i: usize| up.frontiers.contains(i);
    // near: a free cell about 10 cells left of the frontier column x = n/2 in row n/2;
    // far: a free cell near the top-left corner, ~1000 cells from any frontier
    let near = (n / 2) * n + n / 2 - 10;
    let near = (near..near + 5).find(|&i| passable(i)).unwrap_or(near);
    let far = (n * 10 + 10..n * 10 + 20)
        .find(|&i| passable(i))
        .unwrap_or(n * 10 + 10);
    for (name, start) in [("nearest_near", near), ("nearest_far", far)] {
        let goal = r.nearest(start, passable, is_goal);
        eprintln!(
            "{name}: start {start}, goal {goal:?}, cost {:?}, settled {}",
            goal.and_then(|g| r.cost(g)),
            r.settled().len()
        );
        g.bench_function(name, |b| {
            b.iter(|| black_box(r.nearest(start, passable, is_goal)))
        });
    }
    // the same, as the nearest rule searches: toward every frontier cell (more than
    // PROBE_FROM of them, so tried unguided first; from far, the guide is then set)
    let frontier = up.frontiers.cells().to_vec();
    for (name, start) in [("nearest_guided_near", near), ("nearest_guided_far", far)] {
        let goal = r.nearest_guided(start, passable, &frontier, is_goal);
        eprintln!(
            "{name}: {} goals, goal {goal:?}, settled {}",
            frontier.len(),
            r.settled().len()
        );
        g.bench_function(name, |b| {
            b.iter(|| black_box(r.nearest_guided(start, passable, &frontier, is_goal)))
        });
    }
    let truth_passable = |i: usize| truth[i] == Occ::Free;
    let mid = (n * n / 2 + 10..n * n / 2 + 20)
        .find(|&i| truth_passable(i))
        .unwrap_or(0);
    r.compute(mid, truth_passable);
    eprintln!("compute: settled {}", r.settled().len());
    g.bench_function("compute_full_known", |b| {
        b.iter(|| r.compute(mid, truth_passable))
    });
    // the same search as Dial's (the canonical order's worst case: single obstacles)
    let mut dial = Reachability::new(n, n);
    dial.set_canonical(false);
    g.bench_function("dial_full_known", |b| {
        b.iter(|| dial.compute(mid, truth_passable))
    });
    // the resumable search a team decision grows: the whole map by buckets, and guided
    // toward a few frontier cells ~1000 cells away until they are settled
    g.bench_function("advance_full_known", |b| {
        b.iter(|| {
            r.begin(mid, truth_passable);
            r.advance(usize::MAX, truth_passable)
        })
    });
    let goals: Vec<u32> = up.frontiers.cells().iter().step_by(997).copied().collect();
    let last = |r: &Reachability| goals.iter().all(|&c| r.is_settled(c as usize));
    let grow = |r: &mut Reachability, guided: bool| {
        if guided {
            r.begin_guided(far, passable, &goals);
        } else {
            r.begin(far, passable);
        }
        while !last(r) && !r.advance(r.next_bucket(), passable) {}
        r.searched()
    };
    for (name, guided, canonical) in [
        ("advance_to_far_goals", false, true),
        ("guided_to_far_goals", true, true),
        ("dial_guided_to_far_goals", true, false),
    ] {
        let r = if canonical { &mut r } else { &mut dial };
        eprintln!(
            "{name}: {} goals, searched {}",
            goals.len(),
            grow(r, guided)
        );
        g.bench_function(name, |b| b.iter(|| black_box(grow(r, guided))));
    }
    // the flood fill behind "reachable?", over the traversable cells of the half-explored
    // belief, from the far start
    let mut comp = Component::new(n, n);
    comp.compute(far, up.trav.passable());
    eprintln!("component: {} cells", comp.len());
    g.bench_function("component_half_explored", |b| {
        b.iter(|| {
            comp.compute(far, up.trav.passable());
            black_box(comp.len())
        })
    });
    let mut a = AStar::new(n, n);
    let mut path = Vec::new();
    let goal = (n * (n - 20) + n - 20..n * (n - 20) + n - 10)
        .find(|&i| truth_passable(i))
        .unwrap_or(0);
    let s = (n * 20 + 20..n * 20 + 30)
        .find(|&i| truth_passable(i))
        .unwrap_or(0);
    eprintln!(
        "astar corner to corner: {:?}",
        a.search(s, goal, truth_passable, &mut path)
    );
    g.bench_function("astar_corner_to_corner", |b| {
        b.iter(|| black_box(a.search(s, goal, truth_passable, &mut path)))
    });
    let mut out = Grid::new(n, n, 0.0);
    let mut scratch = EdtScratch::new();
    g.bench_function("edt", |b| {
        b.iter(|| edt_squared_into(n, n, |i| truth[i] == Occ::Occupied, &mut out, &mut scratch))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
