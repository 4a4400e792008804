//! Greedy (the coordination study's Alg. 2 / Faigl & Kulich's IA) and GA against slow re-implementations on
//! random cost matrices with unreachable pairs and taken goals, plus a worked example.

use explore::assign::{greedy, random_order};
use proptest::prelude::*;

/// IA as Faigl & Kulich describe it: all reachable pairs sorted by (cost, robot, goal); the
/// first pair whose robot and goal are both unassigned wins. A pass that leaves robots
/// without a goal refills the goal set (Alg. 2's F = F_init) if that changes anything.
fn slow_greedy(rows: usize, cols: usize, cost: &[f64], taken: &[bool]) -> Vec<Option<usize>> {
    let mut pairs: Vec<(f64, usize, usize)> = (0..rows)
        .flat_map(|i| (0..cols).map(move |j| (cost[i * cols + j], i, j)))
        .filter(|p| p.0.is_finite())
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut out = vec![None; rows];
    let mut free: Vec<bool> = taken.iter().map(|&t| !t).collect();
    loop {
        for &(_, i, j) in &pairs {
            if out[i].is_none() && free[j] {
                out[i] = Some(j);
                free[j] = false;
            }
        }
        if out.iter().all(Option::is_some) || free.iter().all(|&f| f) {
            return out;
        }
        free.iter_mut().for_each(|f| *f = true);
    }
}

/// GA: robots in the given order each take their cheapest free goal (earliest on ties),
/// refilling the goal set when none is left for a robot.
fn slow_ga(cols: usize, cost: &[f64], taken: &[bool], order: &[usize]) -> Vec<Option<usize>> {
    let mut out = vec![None; order.len()];
    let mut free: Vec<bool> = taken.iter().map(|&t| !t).collect();
    for &i in order {
        for attempt in 0..2 {
            let mut options: Vec<(f64, usize)> = (0..cols)
                .filter(|&j| free[j] && cost[i * cols + j].is_finite())
                .map(|j| (cost[i * cols + j], j))
                .collect();
            options.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            if let Some(&(_, j)) = options.first() {
                out[i] = Some(j);
                free[j] = false;
                break;
            }
            if attempt == 0 && free.iter().any(|&f| !f) {
                free.iter_mut().for_each(|f| *f = true);
            } else {
                break;
            }
        }
    }
    out
}

fn matrix() -> impl Strategy<Value = (usize, usize, Vec<f64>, Vec<bool>, Vec<usize>)> {
    (1usize..=6, 0usize..=8).prop_flat_map(|(rows, cols)| {
        (
            Just(rows),
            Just(cols),
            prop::collection::vec(
                prop_oneof![
                    8 => (0u32..20).prop_map(|c| c as f64 * 0.5),
                    1 => Just(f64::INFINITY),
                ],
                rows * cols,
            ),
            prop::collection::vec(prop::bool::weighted(0.2), cols),
            Just((0..rows).collect::<Vec<_>>()).prop_shuffle(),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn greedy_equals_slow((rows, cols, cost, taken, _order) in matrix()) {
        let (mut free, mut out) = (Vec::new(), Vec::new());
        greedy::solve(rows, cols, &cost, &taken, &mut free, &mut out);
        prop_assert_eq!(out, slow_greedy(rows, cols, &cost, &taken));
    }

    #[test]
    fn ga_equals_slow((rows, cols, cost, taken, order) in matrix()) {
        let (mut free, mut out) = (Vec::new(), Vec::new());
        random_order::solve(cols, &cost, &taken, &order, &mut free, &mut out);
        out.resize(rows, None);
        prop_assert_eq!(out, slow_ga(cols, &cost, &taken, &order));
    }
}

#[test]
fn worked_example_with_refill() {
    // Three robots, two goals, goal 1 kept by a robot that is not deciding.
    //          g0   g1
    // r0:       4    1
    // r1:       2    5
    // r2:       3    9
    // g1 is taken, so r1 takes g0 (2, the cheapest free pair); no free goal is left, the
    // set is refilled, and r0 takes g1 (1); then r2 takes g0 (3).
    let cost = [4.0, 1.0, 2.0, 5.0, 3.0, 9.0];
    let (mut free, mut out) = (Vec::new(), Vec::new());
    greedy::solve(3, 2, &cost, &[false, true], &mut free, &mut out);
    assert_eq!(out, vec![Some(1), Some(0), Some(0)]);
    // GA in the order r2, r0, r1: r2 takes g0; nothing is free for r0, so the set is
    // refilled and r0 takes g1; g0 is free again after the refill and r1 takes it.
    random_order::solve(2, &cost, &[false, true], &[2, 0, 1], &mut free, &mut out);
    assert_eq!(out, vec![Some(1), Some(0), Some(0)]);
}

#[test]
fn unreachable_robot_gets_nothing() {
    let cost = [1.0, f64::INFINITY, f64::INFINITY, f64::INFINITY];
    let (mut free, mut out) = (Vec::new(), Vec::new());
    greedy::solve(2, 2, &cost, &[false, false], &mut free, &mut out);
    assert_eq!(out, vec![Some(0), None]);
}
