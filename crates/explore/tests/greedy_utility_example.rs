//! Greedy with utility (the coordination study's Alg. 3) on worked examples: the utility reduction sends the
//! second robot away from the first one's goal where plain greedy would not.

use explore::assign::{greedy, greedy_utility};

#[test]
fn overlap_is_linear_inside_the_range() {
    assert_eq!(greedy_utility::overlap(0.0, 4.0), 1.0);
    assert_eq!(greedy_utility::overlap(2.0, 4.0), 0.5);
    assert_eq!(greedy_utility::overlap(4.0, 4.0), 0.0);
    assert_eq!(greedy_utility::overlap(9.0, 4.0), 0.0);
}

#[test]
fn second_robot_avoids_the_first_ones_view() {
    // Goals on a line at x = 0, 2, 10; ρ = 4 cells, β = 0.1 per cell.
    //          g0    g1    g2
    // r0:       1     2     9
    // r1:       2   1.5     5
    // Step 1: values U − βc: r0 (0.9, 0.8, 0.1), r1 (0.8, 0.85, 0.5) → r0 takes g0.
    //   Utilities: g0 1 − 1 = 0, g1 1 − (1 − 2/4) = 0.5, g2 1.
    // Step 2: r1: g1 0.5 − 0.15 = 0.35, g2 1 − 0.5 = 0.5 → r1 takes g2.
    //   Utilities: g2 1 − 1 = 0.
    let cost = [1.0, 2.0, 9.0, 2.0, 1.5, 5.0];
    let pos = [(0.0, 0.0), (2.0, 0.0), (10.0, 0.0)];
    let (mut u, mut free, mut out) = (Vec::new(), Vec::new(), Vec::new());
    greedy_utility::solve(
        2,
        &cost,
        &pos,
        &[],
        &[false; 3],
        4.0,
        0.1,
        &mut u,
        &mut free,
        &mut out,
    );
    assert_eq!(out, vec![Some(0), Some(2)]);
    assert_eq!(u, vec![0.0, 0.5, 0.0]);
    // Plain greedy sends r1 to g1 (cost 1.5), next to r0's goal.
    greedy::solve(2, 3, &cost, &[false; 3], &mut free, &mut out);
    assert_eq!(out, vec![Some(0), Some(1)]);
}

#[test]
fn kept_goals_lower_utilities_and_are_taken() {
    // One deciding robot; another robot keeps g0. g0 is taken; g1 (2 cells away) has
    // utility 0.5: value 0.5 − 0.1 = 0.4 against g2's 1 − 0.6 = 0.4 at cost 6 — a tie,
    // broken by candidate order (g1). At cost 5.9 for g2 it wins (0.41).
    let pos = [(0.0, 0.0), (2.0, 0.0), (10.0, 0.0)];
    let (mut u, mut free, mut out) = (Vec::new(), Vec::new(), Vec::new());
    for (c2, want) in [(6.0, 1), (5.9, 2)] {
        let cost = [0.5, 1.0, c2];
        greedy_utility::solve(
            1,
            &cost,
            &pos,
            &[(0.0, 0.0)],
            &[true, false, false],
            4.0,
            0.1,
            &mut u,
            &mut free,
            &mut out,
        );
        assert_eq!(out, vec![Some(want)], "g2 at cost {c2}");
    }
}

#[test]
fn with_more_robots_than_goals_the_set_is_refilled() {
    // Two goals far apart (ρ = 4), three robots: after both goals are taken the third robot
    // gets the one of greater U − βc (both utilities 0 now): the cheaper, g1.
    let cost = [1.0, 8.0, 8.0, 1.0, 3.0, 2.0];
    let pos = [(0.0, 0.0), (20.0, 0.0)];
    let (mut u, mut free, mut out) = (Vec::new(), Vec::new(), Vec::new());
    greedy_utility::solve(
        3,
        &cost,
        &pos,
        &[],
        &[false, false],
        4.0,
        0.1,
        &mut u,
        &mut free,
        &mut out,
    );
    assert_eq!(out, vec![Some(0), Some(1), Some(1)]);
}
