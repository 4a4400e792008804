//! Planners against slow oracles on random small maps: Dijkstra == Bellman–Ford (with the
//! no-corner-squeezing rule), `nearest` finds a goal of minimal cost, A* == Dijkstra, and
//! extracted paths are valid 8-connected paths whose step costs sum to the reported cost;
//! the bucket queue settles exactly what a binary heap on (cost, index) settles; the flood
//! fill reaches what Bellman–Ford reaches.

use explore::bits::CellBits;
use explore::plan::Component;
use explore::{AStar, Reachability};
use grid::SQRT2;
use proptest::prelude::*;

/// Bellman–Ford over the same motion model, written independently of the planners.
fn bellman_ford(w: usize, h: usize, pass: &[bool], start: usize) -> Vec<f64> {
    let mut d = vec![f64::INFINITY; w * h];
    d[start] = 0.0;
    for _ in 0..w * h {
        let mut changed = false;
        for u in 0..w * h {
            if d[u].is_infinite() {
                continue;
            }
            let (ux, uy) = ((u % w) as i64, (u / w) as i64);
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let (vx, vy) = (ux + dx, uy + dy);
                    if (dx, dy) == (0, 0) || vx < 0 || vy < 0 || vx >= w as i64 || vy >= h as i64 {
                        continue;
                    }
                    let v = (vy * w as i64 + vx) as usize;
                    if !pass[v] {
                        continue;
                    }
                    let step = if dx != 0 && dy != 0 {
                        let a = pass[(uy * w as i64 + vx) as usize];
                        let b = pass[(vy * w as i64 + ux) as usize];
                        if !a && !b {
                            continue;
                        }
                        SQRT2
                    } else {
                        1.0
                    };
                    if d[u] + step < d[v] - 1e-12 {
                        d[v] = d[u] + step;
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    d
}

/// A valid path: start..=goal, 8-connected steps, passable cells after the start, no squeezing;
/// returns its summed step cost.
fn check_path(
    w: usize,
    pass: &[bool],
    path: &[u32],
    start: usize,
    goal: usize,
) -> Result<f64, TestCaseError> {
    prop_assert_eq!(path.first().map(|&c| c as usize), Some(start));
    prop_assert_eq!(path.last().map(|&c| c as usize), Some(goal));
    let mut total = 0.0;
    for win in path.windows(2) {
        let (a, b) = (win[0] as usize, win[1] as usize);
        prop_assert!(pass[b], "impassable cell {} on path", b);
        let (ax, ay) = ((a % w) as i64, (a / w) as i64);
        let (bx, by) = ((b % w) as i64, (b / w) as i64);
        let (dx, dy) = (bx - ax, by - ay);
        prop_assert!(
            dx.abs() <= 1 && dy.abs() <= 1 && (dx, dy) != (0, 0),
            "not a step"
        );
        if dx != 0 && dy != 0 {
            let o1 = pass[(ay * w as i64 + bx) as usize];
            let o2 = pass[(by * w as i64 + ax) as usize];
            prop_assert!(o1 || o2, "corner squeeze {} -> {}", a, b);
            total += SQRT2;
        } else {
            total += 1.0;
        }
    }
    Ok(total)
}

/// Textbook Dijkstra with a binary heap on (cost bits, index) over the same moves: costs,
/// predecessors and settled order, for the bucket queue to match bit for bit.
fn heap_dijkstra(
    w: usize,
    h: usize,
    pass: &[bool],
    start: usize,
    is_goal: impl Fn(usize) -> bool,
) -> (Vec<f64>, Vec<usize>, Vec<usize>) {
    use std::cmp::Reverse;
    let n = w * h;
    let (mut cost, mut pred, mut done) =
        (vec![f64::INFINITY; n], vec![usize::MAX; n], vec![false; n]);
    let mut order = Vec::new();
    let mut heap = std::collections::BinaryHeap::new();
    cost[start] = 0.0;
    pred[start] = start;
    heap.push(Reverse((0f64.to_bits(), start)));
    while let Some(Reverse((_, i))) = heap.pop() {
        if done[i] {
            continue;
        }
        done[i] = true;
        order.push(i);
        if is_goal(i) {
            break;
        }
        grid::for_each_move(w, h, i, &|j| pass[j], |j, step| {
            let c = cost[i] + step;
            if !done[j] && c < cost[j] {
                cost[j] = c;
                pred[j] = i;
                heap.push(Reverse((c.to_bits(), j)));
            }
        });
    }
    (cost, pred, order)
}

/// The last search of `r` settled the cells the heap settled (`order`), each with the heap's
/// cost bit for bit and the heap's predecessor on its path.
fn same_as_heap(
    r: &Reachability,
    cost: &[f64],
    pred: &[usize],
    order: &[usize],
) -> Result<(), TestCaseError> {
    let mut settled = r.settled().iter().map(|&c| c as usize).collect::<Vec<_>>();
    settled.sort_unstable();
    let mut want = order.to_vec();
    want.sort_unstable();
    prop_assert_eq!(settled, want);
    let mut path = Vec::new();
    for &i in order {
        prop_assert_eq!(r.cost(i).map(f64::to_bits), Some(cost[i].to_bits()));
        prop_assert!(r.path_to(i, &mut path));
        let p = if path.len() > 1 {
            path[path.len() - 2] as usize
        } else {
            i
        };
        prop_assert_eq!(p, pred[i], "predecessor of {}", i);
        // `predecessor` is the path's last step (none at the start).
        prop_assert_eq!(r.predecessor(i), (p != i).then_some(p));
    }
    Ok(())
}

fn map() -> impl Strategy<Value = (usize, usize, Vec<bool>)> {
    (1usize..20, 1usize..20, 0.4f64..0.95).prop_flat_map(|(w, h, p)| {
        (
            Just(w),
            Just(h),
            proptest::collection::vec(prop::bool::weighted(p), w * h),
        )
    })
}

/// `nearest_guided` toward `goals` gives `nearest`'s goal, cost and path, in canonical
/// order and as Dial's search, after an earlier search on the same buffers (so that stale
/// data from it must not leak).
fn same_nearest_guided(
    w: usize,
    h: usize,
    pass: &[bool],
    start: usize,
    goals: &[u32],
    is_goal: impl Fn(usize) -> bool + Copy,
) -> Result<(), TestCaseError> {
    for canonical in [true, false] {
        let mut plain = Reachability::new(w, h);
        plain.set_canonical(canonical);
        let want = plain.nearest(start, |i| pass[i], is_goal);
        let mut guided = Reachability::new(w, h);
        guided.set_canonical(canonical);
        guided.compute((start + 1) % (w * h), |i| pass[i]);
        let got = guided.nearest_guided(start, |i| pass[i], goals, is_goal);
        prop_assert_eq!(got, want);
        if let Some(g) = want {
            prop_assert_eq!(
                guided.cost(g).map(f64::to_bits),
                plain.cost(g).map(f64::to_bits)
            );
            let (mut a, mut b) = (Vec::new(), Vec::new());
            prop_assert!(guided.path_to(g, &mut a) && plain.path_to(g, &mut b));
            prop_assert_eq!(a, b);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    /// Rows wider than a word, fills one after the other on the same buffers: the flood
    /// fill holds exactly the cells Bellman–Ford reaches (an impassable start included).
    #[test]
    fn the_fill_reaches_what_bellman_ford_reaches(
        (w, h, pass) in (1usize..150, 1usize..12, 0.5f64..0.97).prop_flat_map(|(w, h, p)| {
            (Just(w), Just(h), proptest::collection::vec(prop::bool::weighted(p), w * h))
        }),
        starts in proptest::collection::vec(any::<prop::sample::Index>(), 1..4),
    ) {
        let mut bits = CellBits::new(w * h);
        for (i, &p) in pass.iter().enumerate() {
            bits.set(i, p);
        }
        let mut comp = Component::new(w, h);
        for s in starts {
            let start = s.index(w * h);
            comp.compute(start, &bits);
            let bf = bellman_ford(w, h, &pass, start);
            for (i, d) in bf.iter().enumerate() {
                prop_assert_eq!(comp.contains(i), d.is_finite(), "cell {} from {}", i, start);
            }
            prop_assert_eq!(comp.len(), bf.iter().filter(|d| d.is_finite()).count());
        }
    }

    #[test]
    fn dijkstra_matches_bellman_ford((w, h, pass) in map(), starts in proptest::collection::vec(any::<prop::sample::Index>(), 1..4)) {
        let mut r = Reachability::new(w, h);
        let mut path = Vec::new();
        // several searches on the same buffers exercise the generation stamps
        for s in starts {
            let start = s.index(w * h);
            r.compute(start, |i| pass[i]);
            prop_assert_eq!(r.start(), Some(start));
            let bf = bellman_ford(w, h, &pass, start);
            for (i, &want) in bf.iter().enumerate() {
                match r.cost(i) {
                    None => prop_assert!(want.is_infinite(), "cell {} unreached, bf {}", i, want),
                    Some(c) => {
                        prop_assert!((c - want).abs() < 1e-9, "cell {}: {} vs bf {}", i, c, want);
                        prop_assert!(r.path_to(i, &mut path));
                        let total = check_path(w, &pass, &path, start, i)?;
                        prop_assert!((total - c).abs() < 1e-9);
                    }
                }
            }
            // settled bucket by bucket (cost rounded down never decreases), each exactly once
            let settled = r.settled();
            prop_assert_eq!(settled.len(), bf.iter().filter(|d| d.is_finite()).count());
            for win in settled.windows(2) {
                prop_assert!(bf[win[0] as usize].floor() <= (bf[win[1] as usize] + 1e-9).floor());
            }
        }
    }

    /// From a set of sources: the distance to the nearest, as the minimum of single-source
    /// searches.
    #[test]
    fn sources_give_the_distance_to_the_nearest((w, h, pass) in map(), picks in proptest::collection::vec(any::<prop::sample::Index>(), 1..5)) {
        let sources: Vec<usize> = picks.iter().map(|s| s.index(w * h)).collect();
        let mut want = vec![f64::INFINITY; w * h];
        for &s in &sources {
            for (m, d) in want.iter_mut().zip(bellman_ford(w, h, &pass, s)) {
                *m = m.min(d);
            }
        }
        let mut r = Reachability::new(w, h);
        r.compute_from(&sources, |i| pass[i]);
        for (i, &d) in want.iter().enumerate() {
            match r.cost(i) {
                None => prop_assert!(d.is_infinite(), "cell {} unreached, want {}", i, d),
                Some(c) => prop_assert!((c - d).abs() < 1e-9, "cell {}: {} vs {}", i, c, d),
            }
        }
        prop_assert_eq!(r.settled().len(), want.iter().filter(|d| d.is_finite()).count());
        prop_assert_eq!(r.start(), (sources.len() == 1).then_some(sources[0]));
    }

    #[test]
    fn nearest_finds_a_cheapest_goal(
        (w, h, pass) in map(),
        s in any::<prop::sample::Index>(),
        goals_p in 0.0f64..0.2,
        seed in any::<u64>(),
    ) {
        let start = s.index(w * h);
        // goal set from a cheap hash of the seed
        let is_goal: Vec<bool> = (0..w * h)
            .map(|i| {
                let x = (seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                ((x >> 11) as f64 / (1u64 << 53) as f64) < goals_p
            })
            .collect();
        let bf = bellman_ford(w, h, &pass, start);
        let best = (0..w * h).filter(|&i| is_goal[i]).map(|i| bf[i]).fold(f64::INFINITY, f64::min);
        let mut r = Reachability::new(w, h);
        // a full search first, so stale data from it must not leak into `nearest`
        r.compute((start + 1) % (w * h), |i| pass[i]);
        let got = r.nearest(start, |i| pass[i], |i| is_goal[i]);
        match got {
            None => prop_assert!(best.is_infinite()),
            Some(g) => {
                prop_assert!(is_goal[g]);
                prop_assert!((bf[g] - best).abs() < 1e-9, "goal cost {} best {}", bf[g], best);
                let c = r.cost(g);
                prop_assert!(c.is_some());
                prop_assert!((c.unwrap_or(f64::NAN) - best).abs() < 1e-9);
                let mut path = Vec::new();
                prop_assert!(r.path_to(g, &mut path));
                let total = check_path(w, &pass, &path, start, g)?;
                prop_assert!((total - best).abs() < 1e-9);
                // every settled cell has its final cost; goal is the last settled
                prop_assert_eq!(r.settled().last().map(|&c| c as usize), Some(g));
                for &c in r.settled() {
                    let c = c as usize;
                    prop_assert!((r.cost(c).unwrap_or(f64::NAN) - bf[c]).abs() < 1e-9);
                    // nothing cheaper than the goal is a goal... except by tie
                    if is_goal[c] {
                        prop_assert_eq!(c, g);
                    }
                }
                // cells not settled report no cost
                let n_settled = (0..w * h).filter(|&i| r.cost(i).is_some()).count();
                prop_assert_eq!(n_settled, r.settled().len());
            }
        }
    }

    #[test]
    fn nearest_guided_is_nearest_bit_for_bit(
        (w, h, pass) in map(),
        s in any::<prop::sample::Index>(),
        goals in proptest::collection::vec(any::<prop::sample::Index>(), 0..12),
        keep in 1u32..4,
    ) {
        let start = s.index(w * h);
        // guided toward `goals`, a goal being only every `keep`-th of them (a superset
        // guides, as candidates guide an assigner's search for its free goals)
        let goals: Vec<u32> = goals.iter().map(|g| g.index(w * h) as u32).collect();
        let is_goal = |i: usize| goals.iter().position(|&g| g as usize == i).is_some_and(|p| (p as u32).is_multiple_of(keep));
        same_nearest_guided(w, h, &pass, start, &goals, is_goal)?;
    }

    /// With more goals than `PROBE_FROM` the nearest is looked for unguided first, up to
    /// a budget of settled cells, then guided: the same goal, cost and path whether the
    /// probe finds it, finds none reachable or runs out (real goals every `keep`-th of
    /// the guiding cells, from all of them to a few far ones).
    #[test]
    fn nearest_guided_with_many_goals_is_nearest_bit_for_bit(
        (w, h, pass) in (20usize..70, 20usize..70, 0.5f64..0.95).prop_flat_map(|(w, h, p)| {
            (Just(w), Just(h), proptest::collection::vec(prop::bool::weighted(p), w * h))
        }),
        s in any::<prop::sample::Index>(),
        goals in proptest::collection::vec(any::<prop::sample::Index>(), 900..4000),
        keep in prop_oneof![1u32..4, 100u32..4000],
    ) {
        let start = s.index(w * h);
        let goals: Vec<u32> = goals.iter().map(|g| g.index(w * h) as u32).collect();
        let mut real = vec![false; w * h];
        for (p, &g) in goals.iter().enumerate() {
            if (p as u32).is_multiple_of(keep) {
                real[g as usize] = true;
            }
        }
        let is_goal = |i: usize| real[i];
        same_nearest_guided(w, h, &pass, start, &goals, is_goal)?;
    }

    #[test]
    fn bucket_queue_is_the_heap_bit_for_bit(
        (w, h, pass) in map(),
        s in any::<prop::sample::Index>(),
        goal in any::<prop::sample::Index>(),
    ) {
        let (start, goal) = (s.index(w * h), goal.index(w * h));
        // in canonical order (the default) and as Dial's search
        for canonical in [true, false] {
            let mut r = Reachability::new(w, h);
            r.set_canonical(canonical);
            // full map: every cost and predecessor is the heap's, bit for bit
            r.compute(start, |i| pass[i]);
            let (cost, pred, order) = heap_dijkstra(w, h, &pass, start, |_| false);
            same_as_heap(&r, &cost, &pred, &order)?;
            // nearest: the same goal, the same cells settled (the goal last), the same paths
            let is_goal = |i: usize| i == goal || i % 7 == 3;
            let got = r.nearest(start, |i| pass[i], is_goal);
            let (cost, pred, order) = heap_dijkstra(w, h, &pass, start, is_goal);
            let found = order.last().copied().filter(|&i| is_goal(i));
            prop_assert_eq!(got, found);
            if found.is_some() {
                prop_assert_eq!(r.settled().last().map(|&c| c as usize), order.last().copied());
            }
            same_as_heap(&r, &cost, &pred, &order)?;
        }
    }

    #[test]
    fn astar_matches_dijkstra((w, h, pass) in map(), pairs in proptest::collection::vec((any::<prop::sample::Index>(), any::<prop::sample::Index>()), 1..5)) {
        let mut a = AStar::new(w, h);
        let mut path = Vec::new();
        for (s, g) in pairs {
            let (start, goal) = (s.index(w * h), g.index(w * h));
            let bf = bellman_ford(w, h, &pass, start);
            match a.search(start, goal, |i| pass[i], &mut path) {
                None => {
                    prop_assert!(bf[goal].is_infinite(), "A* found nothing, bf {}", bf[goal]);
                    prop_assert!(path.is_empty());
                }
                Some(c) => {
                    prop_assert!((c - bf[goal]).abs() < 1e-9, "A* {} vs bf {}", c, bf[goal]);
                    let total = check_path(w, &pass, &path, start, goal)?;
                    prop_assert!((total - c).abs() < 1e-9);
                }
            }
        }
    }
}

#[test]
fn squeeze_rule_worked_example() {
    // 2x2: passable only on the diagonal (0,0) and (1,1): the diagonal step squeezes
    let pass = [true, false, false, true];
    let mut r = Reachability::new(2, 2);
    r.compute(0, |i| pass[i]);
    assert_eq!(r.cost(3), None);
    let mut a = AStar::new(2, 2);
    let mut path = Vec::new();
    assert_eq!(a.search(0, 3, |i| pass[i], &mut path), None);
    // one orthogonal cell open: the diagonal step is allowed
    let pass = [true, true, false, true];
    r.compute(0, |i| pass[i]);
    assert_eq!(r.cost(3), Some(SQRT2));
    assert_eq!(a.search(0, 3, |i| pass[i], &mut path), Some(SQRT2));
    assert_eq!(path, [0, 3]);
}

#[test]
fn start_is_always_allowed_and_ties_break_by_index() {
    // 3x1 corridor, the start cell itself impassable
    let pass = [true, false, true];
    let mut r = Reachability::new(3, 1);
    r.compute(1, |i| pass[i]);
    assert_eq!(r.cost(0), Some(1.0));
    assert_eq!(r.cost(2), Some(1.0));
    let mut settled = r.settled().to_vec();
    settled.sort_unstable();
    assert_eq!(settled, [0, 1, 2]);
    // two goals at equal cost: the lower index is settled first
    assert_eq!(r.nearest(1, |i| pass[i], |i| i != 1), Some(0));
    // the start may itself be the goal
    assert_eq!(r.nearest(1, |i| pass[i], |_| true), Some(1));
    let mut path = Vec::new();
    assert!(r.path_to(1, &mut path));
    assert_eq!(path, [1]);
    // out-of-grid input does not panic
    r.compute(99, |_| true);
    assert_eq!(r.start(), None);
    assert_eq!(r.cost(0), None);
    assert!(!r.path_to(0, &mut path));
    let mut a = AStar::new(3, 1);
    assert_eq!(a.search(0, 99, |_| true, &mut path), None);
    assert_eq!(a.search(1, 1, |_| false, &mut path), Some(0.0));
    assert_eq!(path, [1]);
}
