//! HA (Faigl & Kulich's Hungarian assignment) against brute force over every assignment on
//! small random cost matrices with unreachable pairs and taken goals: the same number of
//! reachable pairs and the same least total cost, even though only each robot's k cheapest
//! goals are offered to the solver.

use explore::assign::hungarian::{Buffers, optimal, solve};
use proptest::prelude::*;

/// Best (reachable pairs, total cost) over all injective assignments of rows to free
/// columns (or of free columns to rows when rows are more): most pairs first, then least cost.
fn brute(rows: usize, cols: usize, cost: &[f64], taken: &[bool]) -> (usize, f64) {
    let free: Vec<usize> = (0..cols).filter(|&j| !taken[j]).collect();
    let mut best = (0usize, 0.0f64);
    let mut used = vec![false; cols];
    #[allow(clippy::too_many_arguments)]
    fn rec(
        i: usize,
        rows: usize,
        cols: usize,
        cost: &[f64],
        free: &[usize],
        used: &mut [bool],
        acc: (usize, f64),
        best: &mut (usize, f64),
    ) {
        if i == rows {
            if acc.0 > best.0 || (acc.0 == best.0 && acc.1 < best.1) {
                *best = acc;
            }
            return;
        }
        // Row i unmatched (needed when rows outnumber free columns; never better otherwise).
        rec(i + 1, rows, cols, cost, free, used, acc, best);
        for &j in free {
            if used[j] {
                continue;
            }
            used[j] = true;
            let c = cost[i * cols + j];
            let next = if c.is_finite() {
                (acc.0 + 1, acc.1 + c)
            } else {
                acc
            };
            rec(i + 1, rows, cols, cost, free, used, next, best);
            used[j] = false;
        }
    }
    rec(0, rows, cols, cost, &free, &mut used, (0, 0.0), &mut best);
    best
}

fn matrix() -> impl Strategy<Value = (usize, usize, Vec<f64>, Vec<bool>)> {
    (1usize..=4, 0usize..=8).prop_flat_map(|(rows, cols)| {
        (
            Just(rows),
            Just(cols),
            prop::collection::vec(
                prop_oneof![
                    8 => (0u32..40).prop_map(|c| c as f64 * 0.5),
                    1 => Just(f64::INFINITY),
                ],
                rows * cols,
            ),
            prop::collection::vec(prop::bool::weighted(0.15), cols),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn optimal_equals_brute_force((rows, cols, cost, taken) in matrix()) {
        let mut buf = Buffers::default();
        let mut out = Vec::new();
        optimal(rows, cols, &cost, &taken, &mut buf, &mut out);
        prop_assert_eq!(out.len(), rows);
        let mut used = vec![false; cols];
        let mut got = (0usize, 0.0f64);
        for (i, a) in out.iter().enumerate() {
            if let Some(j) = *a {
                prop_assert!(!taken[j], "taken goal {} given", j);
                prop_assert!(!used[j], "goal {} given twice", j);
                used[j] = true;
                let c = cost[i * cols + j];
                prop_assert!(c.is_finite(), "unreachable goal given");
                got = (got.0 + 1, got.1 + c);
            }
        }
        let want = brute(rows, cols, &cost, &taken);
        prop_assert_eq!(got.0, want.0, "reachable pairs");
        prop_assert!((got.1 - want.1).abs() < 1e-9, "cost {} vs brute force {}", got.1, want.1);
    }

    #[test]
    fn leftovers_take_their_cheapest((rows, cols, cost, taken) in matrix()) {
        let mut buf = Buffers::default();
        let (mut matched, mut out) = (Vec::new(), Vec::new());
        optimal(rows, cols, &cost, &taken, &mut buf, &mut matched);
        solve(rows, cols, &cost, &taken, &mut buf, &mut out);
        for i in 0..rows {
            let row = &cost[i * cols..(i + 1) * cols];
            let cheapest = row.iter().cloned().filter(|c| c.is_finite()).fold(f64::INFINITY, f64::min);
            match (matched[i], out[i]) {
                (Some(a), Some(b)) => prop_assert_eq!(a, b),
                (None, Some(b)) => prop_assert_eq!(row[b], cheapest),
                (None, None) => prop_assert!(cheapest.is_infinite()),
                (Some(_), None) => prop_assert!(false, "matched robot lost its goal"),
            }
        }
    }
}

#[test]
fn worked_example_beats_greedy() {
    // Two robots, two goals: greedy takes the cheapest pair (r0, g0) = 1 and leaves r1 with
    // g1 = 10 (total 11); the optimum is r0 → g1 (2), r1 → g0 (3), total 5.
    let cost = [1.0, 2.0, 3.0, 10.0];
    let mut buf = Buffers::default();
    let mut out = Vec::new();
    solve(2, 2, &cost, &[false, false], &mut buf, &mut out);
    assert_eq!(out, vec![Some(1), Some(0)]);
    // More robots than goals: the third robot takes its cheapest goal.
    let cost = [1.0, 2.0, 3.0, 10.0, 4.0, 5.0];
    solve(3, 2, &cost, &[false, false], &mut buf, &mut out);
    assert_eq!(out, vec![Some(1), Some(0), Some(0)]);
}
