//! Open TSP routes against Held–Karp (exact dynamic programme) for n ≤ 12, on Euclidean
//! instances and on path distances of small random grids.

use explore::Reachability;
use explore::tsp::{OpenTsp, route_cost};
use proptest::prelude::*;

/// Held–Karp for the open route from node 0 through all nodes of the `n × n` matrix.
fn held_karp(n: usize, d: &[f64]) -> f64 {
    if n <= 1 {
        return 0.0;
    }
    let m = n - 1; // nodes 1..n as bits 0..m
    let full = 1usize << m;
    let mut dp = vec![f64::INFINITY; full * m];
    for j in 0..m {
        dp[(1 << j) * m + j] = d[j + 1];
    }
    for mask in 1..full {
        for j in 0..m {
            let v = dp[mask * m + j];
            if mask & (1 << j) == 0 || !v.is_finite() {
                continue;
            }
            for k in 0..m {
                if mask & (1 << k) == 0 {
                    let nm = mask | (1 << k);
                    let c = v + d[(j + 1) * n + k + 1];
                    if c < dp[nm * m + k] {
                        dp[nm * m + k] = c;
                    }
                }
            }
        }
    }
    (0..m)
        .map(|j| dp[(full - 1) * m + j])
        .fold(f64::INFINITY, f64::min)
}

fn euclid(points: &[(f64, f64)]) -> Vec<f64> {
    let n = points.len();
    let mut d = vec![0.0; n * n];
    for a in 0..n {
        for b in 0..n {
            d[a * n + b] = (points[a].0 - points[b].0).hypot(points[a].1 - points[b].1);
        }
    }
    d
}

/// Solve the open route through `pts` (full effort) and check it is a route of the cost
/// returned: the node count, the matrix and the cost.
fn solve_euclid(pts: &[(f64, f64)]) -> (usize, Vec<f64>, f64) {
    let n = pts.len();
    let d = euclid(pts);
    let mut t = OpenTsp::new();
    let cost = t.solve(n, &d);
    check_route(n, t.route());
    assert!((cost - route_cost(n, &d, t.route())).abs() < 1e-9);
    (n, d, cost)
}

fn check_route(n: usize, route: &[u32]) {
    assert_eq!(route.len(), n);
    if n > 0 {
        assert_eq!(route[0], 0, "route starts at node 0");
    }
    let mut seen = vec![false; n];
    for &v in route {
        assert!(!seen[v as usize], "node {v} twice");
        seen[v as usize] = true;
    }
}

#[test]
fn worked_example_nearest_neighbour_is_improved() {
    // From (5, 0), nearest neighbour goes left first (14.30); the optimum sweeps right to
    // (9, 0) first and comes back: 4 + √5 + √10 + 4 = 13.398.
    let pts = [(5.0, 0.0), (4.0, 0.0), (0.0, 0.0), (7.0, 1.0), (9.0, 0.0)];
    let d = euclid(&pts);
    let mut t = OpenTsp::new();
    let cost = t.solve(5, &d);
    let best = 8.0 + 5f64.sqrt() + 10f64.sqrt();
    assert!((held_karp(5, &d) - best).abs() < 1e-12);
    assert!((cost - best).abs() < 1e-12, "cost {cost}");
    assert_eq!(t.route(), &[0, 4, 3, 1, 2]);
    // Trivial sizes.
    assert_eq!(t.solve(0, &[]), 0.0);
    assert!(t.route().is_empty());
    assert_eq!(t.solve(1, &[0.0]), 0.0);
    assert_eq!(t.route(), &[0]);
}

/// Path distances on a 16 × 16 grid with `walls`, between the distinct free cells of
/// `picks` reachable from the first one: the node count and the cost matrix.
fn grid_instance(walls: &[bool], picks: &[usize]) -> (usize, Vec<f64>) {
    let (w, h) = (16, 16);
    let passable = |i: usize| !walls[i];
    let mut nodes: Vec<usize> = Vec::new();
    let mut r0 = Reachability::new(w, h);
    for &p in picks {
        if !passable(p) || nodes.contains(&p) {
            continue;
        }
        if let Some(&s) = nodes.first() {
            if r0.cost(p).is_none() {
                continue;
            }
            let _ = s;
        } else {
            r0.compute(p, passable);
        }
        nodes.push(p);
    }
    let n = nodes.len();
    let mut d = vec![0.0; n * n];
    let mut r = Reachability::new(w, h);
    for a in 0..n {
        r.compute(nodes[a], passable);
        for b in 0..n {
            d[a * n + b] = r.cost(nodes[b]).expect("same component");
        }
    }
    (n, d)
}

/// Regression: on path distances of a grid with walls (many equal costs), the chained
/// local search left this 8-node route 1.4 % above the optimum (48.70 against 48.04).
#[test]
fn an_eight_node_grid_route_with_many_ties_is_optimal() {
    let mut walls = vec![false; 256];
    for i in [
        84, 97, 98, 100, 101, 115, 121, 128, 130, 134, 147, 148, 149, 151, 152, 154, 168, 170, 184,
        187, 189, 203, 206, 217, 218, 232, 236, 249,
    ] {
        walls[i] = true;
    }
    let (n, d) = grid_instance(&walls, &[177, 122, 31, 163, 204, 131, 90, 160]);
    assert_eq!(n, 8);
    let mut t = OpenTsp::new();
    let cost = t.solve(n, &d);
    check_route(n, t.route());
    assert!((cost - held_karp(n, &d)).abs() <= 1e-9, "{cost}");
    assert!((cost - 48.041630560342625).abs() < 1e-9, "{cost}");
}

proptest! {
    // A sample, not a law: the local search is within 1 % of the optimum on nearly every
    // random instance, not all (see the 14-node instance below), so the sample is fixed.
    #![proptest_config(ProptestConfig {
        rng_seed: proptest::test_runner::RngSeed::Fixed(2013),
        ..ProptestConfig::with_cases(256)
    })]

    #[test]
    fn heuristic_within_one_percent_of_held_karp_euclidean(
        pts in prop::collection::vec((0.0..100.0f64, 0.0..100.0f64), 13..=14)
    ) {
        // Beyond EXACT_UP_TO nodes the solver is the chained local search.
        let (n, d, cost) = solve_euclid(&pts);
        let opt = held_karp(n, &d);
        prop_assert!(cost >= opt - 1e-9, "below the optimum: {} < {}", cost, opt);
        prop_assert!(cost <= opt * 1.01 + 1e-9, "route {} vs optimum {}", cost, opt);
    }
}

/// The worst random instance met so far: 14 nodes, 2.6 % above the optimum (the starts
/// and kicks find a route within 1 % on nearly all others).
#[test]
fn a_hard_fourteen_node_instance_is_within_three_percent() {
    let pts = [
        (16.127841236105226, 32.54828560745388),
        (94.12902879335299, 12.15648939881395),
        (0.0, 75.09299525210075),
        (52.54245088262597, 28.362922758759954),
        (5.555644427873194, 73.20206182219056),
        (82.58048988247675, 79.9866894422153),
        (88.62158589307718, 97.03004881033749),
        (47.539760703018, 13.948320477782028),
        (5.141834041795235, 77.6487027227062),
        (35.905492170615275, 7.90024723366922),
        (58.711969111272474, 73.9942604634985),
        (43.01761886793758, 86.43718706280443),
        (77.82731733286982, 80.1560711679124),
        (40.932831982878454, 39.461953544252),
    ];
    let (n, d, cost) = solve_euclid(&pts);
    let opt = held_karp(n, &d);
    assert!(
        cost >= opt - 1e-9 && cost <= opt * 1.03,
        "route {cost} vs optimum {opt}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn optimal_up_to_twelve_nodes_euclidean(
        pts in prop::collection::vec((0.0..100.0f64, 0.0..100.0f64), 1..=12)
    ) {
        let (n, d, cost) = solve_euclid(&pts);
        let opt = held_karp(n, &d);
        prop_assert!((cost - opt).abs() <= 1e-9, "route {} vs optimum {}", cost, opt);
    }

    #[test]
    fn optimal_up_to_twelve_nodes_on_grid_paths(
        walls in prop::collection::vec(prop::bool::weighted(0.25), 16 * 16),
        picks in prop::collection::vec(0usize..256, 2..=12),
    ) {
        let (n, d) = grid_instance(&walls, &picks);
        let mut t = OpenTsp::new();
        let cost = t.solve(n, &d);
        check_route(n, t.route());
        let opt = held_karp(n, &d);
        prop_assert!((cost - opt).abs() <= 1e-9, "route {} vs optimum {}", cost, opt);
    }

}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn deterministic(pts in prop::collection::vec((0.0..50.0f64, 0.0..50.0f64), 1..32)) {
        let n = pts.len();
        let d = euclid(&pts);
        let mut a = OpenTsp::new();
        let mut b = OpenTsp::new();
        let ca = a.solve(n, &d);
        b.solve(3.min(n), &euclid(&pts[..3.min(n)])); // dirty buffers first
        let cb = b.solve(n, &d);
        check_route(n, a.route());
        prop_assert_eq!(a.route(), b.route());
        prop_assert_eq!(ca, cb);
    }
}

/// The plain local search the neighbour lists replace on large routes: nearest neighbour
/// from the start, then full passes of 2-opt (every reversal) and Or-opt (every segment of
/// 1–3 nodes to every other place, both ways) until neither improves.
fn plain_local_search(n: usize, d: &[f64]) -> f64 {
    let c = |a: u32, b: u32| d[a as usize * n + b as usize];
    let mut r: Vec<u32> = vec![0];
    let mut used = vec![false; n];
    used[0] = true;
    for _ in 1..n {
        let at = *r.last().expect("non-empty");
        let next = (0..n as u32)
            .filter(|&j| !used[j as usize])
            .min_by(|&a, &b| c(at, a).total_cmp(&c(at, b)).then(a.cmp(&b)))
            .expect("a node left");
        used[next as usize] = true;
        r.push(next);
    }
    let cost = |r: &[u32]| route_cost(n, d, r);
    loop {
        let before = cost(&r);
        for i in 1..n {
            for j in i + 1..n {
                let mut t = r.clone();
                t[i..=j].reverse();
                if cost(&t) < cost(&r) - 1e-9 {
                    r = t;
                }
            }
        }
        for seg in 1..=3 {
            for i in 1..n {
                if i + seg > n {
                    break;
                }
                for at in 0..=n - seg {
                    for rev in [false, true] {
                        let mut t = r.clone();
                        let mut piece: Vec<u32> = t.drain(i..i + seg).collect();
                        if rev {
                            piece.reverse();
                        }
                        if at < 1 {
                            continue;
                        }
                        let at = at.min(t.len());
                        t.splice(at..at, piece);
                        if cost(&t) < cost(&r) - 1e-9 {
                            r = t;
                        }
                    }
                }
            }
        }
        if cost(&r) >= before - 1e-9 {
            return cost(&r);
        }
    }
}

/// Points from a fixed-seed generator (xorshift), so the quality test is the same on
/// every run.
fn seeded_points(n: usize, seed: u64) -> Vec<(f64, f64)> {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 100.0
    };
    (0..n).map(|_| (next(), next())).collect()
}

#[test]
fn large_routes_are_as_short_as_the_plain_local_searchs() {
    // 24 fixed instances of 30–90 nodes: the solver (neighbour lists, starts and kicks)
    // against one run of the plain O(n²)-per-pass 2-opt and Or-opt.
    let mut ratios = Vec::new();
    for seed in 0..24u64 {
        let n = 30 + (seed as usize * 7) % 61;
        let pts = seeded_points(n, seed);
        let d = euclid(&pts);
        let mut t = OpenTsp::new();
        let cost = t.solve(n, &d);
        check_route(n, t.route());
        assert!((cost - route_cost(n, &d, t.route())).abs() < 1e-9);
        ratios.push(cost / plain_local_search(n, &d));
    }
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let worst = ratios.iter().cloned().fold(0.0, f64::max);
    assert!(mean <= 1.0, "mean ratio {mean}: {ratios:?}");
    assert!(worst <= 1.03, "worst ratio {worst}: {ratios:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn large_routes_are_valid_and_no_longer_than_nearest_neighbour(
        pts in prop::collection::vec((0.0..100.0f64, 0.0..100.0f64), 25..=120),
        fast in any::<bool>(),
    ) {
        let n = pts.len();
        let d = euclid(&pts);
        let mut t = if fast { OpenTsp::with_effort(1, 0) } else { OpenTsp::new() };
        let cost = t.solve(n, &d);
        check_route(n, t.route());
        prop_assert!((cost - route_cost(n, &d, t.route())).abs() < 1e-9);
        // the nearest-neighbour route from the start is where the local search begins
        let mut used = vec![false; n];
        used[0] = true;
        let mut at = 0usize;
        let mut nn_cost = 0.0;
        for _ in 1..n {
            let next = (0..n)
                .filter(|&j| !used[j])
                .min_by(|&a, &b| d[at * n + a].total_cmp(&d[at * n + b]).then(a.cmp(&b)))
                .expect("a node left");
            used[next] = true;
            nn_cost += d[at * n + next];
            at = next;
        }
        prop_assert!(cost <= nn_cost + 1e-9, "{} > nearest neighbour {}", cost, nn_cost);
        let mut again = if fast { OpenTsp::with_effort(1, 0) } else { OpenTsp::new() };
        prop_assert_eq!(again.solve(n, &d), cost);
        prop_assert_eq!(again.route(), t.route());
    }
}
