//! MinPos (Bautin et al.; the coordination study's Alg. 4): ranks from the robots' reachability maps equal a
//! brute-force count over wavefronts grown from each frontier cell (Bautin's own method), and
//! each deciding robot gets a goal of minimal (rank, cost), on small random maps.

use explore::Reachability;
use explore::assign::AssignerKind;
use explore::assign::minpos::{TIE_CELLS, rank};
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{DecisionCtx, Goal, GoalLists, Memory, Planner};
use explore::upkeep::FrontierUpkeep;
use grid::{Grid, Occ};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

const W: usize = 11;
const H: usize = 8;

/// A belief: columns `x >= cut` unknown, the rest free or occupied by `cells`.
fn belief(cells: &[u8], cut: usize) -> Grid<Occ> {
    let mut g = Grid::new(W, H, Occ::Unknown);
    for (i, &v) in cells.iter().enumerate() {
        if i % W < cut {
            g[i] = if v < 2 { Occ::Occupied } else { Occ::Free };
        }
    }
    g
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn minpos_matches_wavefront_ranks(
        cells in prop::collection::vec(0u8..10, W * H),
        cut in 4usize..W,
        picks in prop::collection::vec(0usize..1000, 2..=5),
        deciding_bits in 1u32..32,
        goal_picks in prop::collection::vec(prop::option::of(0usize..1000), 5),
    ) {
        let known = belief(&cells, cut);
        let mut upkeep = FrontierUpkeep::new(W, H, 0.0);
        upkeep.rebuild(&known);
        let trav: Vec<u32> = (0..W * H)
            .filter(|&i| upkeep.is_traversable(&known, i))
            .map(|i| i as u32)
            .collect();
        prop_assume!(!trav.is_empty());
        let frontier: Vec<u32> = upkeep.frontiers.cells().to_vec();
        let m = picks.len();
        let robots: Vec<u32> = picks.iter().map(|&p| trav[p % trav.len()]).collect();
        let mut deciding: Vec<bool> = (0..m).map(|r| deciding_bits >> r & 1 == 1).collect();
        if !deciding.iter().any(|&d| d) {
            deciding[0] = true;
        }
        let goals: Vec<Option<u32>> = (0..m)
            .map(|r| match (deciding[r], goal_picks[r]) {
                (false, Some(g)) if !frontier.is_empty() => Some(frontier[g % frontier.len()]),
                _ => None,
            })
            .collect();

        let mut planner = Planner::new(W, H, m);
        let lists = GoalLists::new(W * H);
        let mut rng = Pcg64Mcg::seed_from_u64(1);
        let belief_dummy = sense::KnownGrid::new(W, H);
        let sensor = sense::LosSensor::new(3.0).expect("sensor");
        let mut memory = Memory::default();
        let mut cands = CandidateSet::new(W * H);
        let mut out: Vec<Option<Goal>> = vec![None; m];
        {
            let mut ctx = DecisionCtx {
                known: &known,
                upkeep: &mut upkeep,
                planner: &mut planner,
                robots: &robots,
                deciding: &deciding,
                goals: &goals,
                lists: &lists,
                resolution: 0.5,
                sensor_range_cells: 3.0,
                rng: &mut rng,
                belief: &belief_dummy,
                sensor: &sensor,
                memory: &mut memory,
            };
            CandidateKind::AllFrontiers.generate(&mut ctx, &mut cands);
            AssignerKind::MinPos.assign(&mut ctx, &cands, &mut out);
        }

        // Bautin's wavefront from every candidate: d[j][k] = path length candidate j → robot k.
        let mut wave = Reachability::new(W, H);
        let n = cands.len();
        let mut d = vec![f64::INFINITY; n * m];
        for (j, &c) in cands.cells().iter().enumerate() {
            wave.compute(c as usize, |i| upkeep.is_traversable(&known, i));
            for k in 0..m {
                d[j * m + k] = wave.cost(robots[k] as usize).unwrap_or(f64::INFINITY);
            }
        }
        let brute_rank = |i: usize, j: usize| {
            (0..m).filter(|&k| k != i && d[j * m + k] < d[j * m + i] - TIE_CELLS).count()
        };
        // Ranks from the robots' own full maps equal the brute-force count (MinPos grows
        // the same searches only as far as it needs).
        let mut cost = vec![f64::INFINITY; m * n];
        let mut reach = Reachability::new(W, H);
        for k in 0..m {
            reach.compute(robots[k] as usize, |i| upkeep.is_traversable(&known, i));
            for (j, &c) in cands.cells().iter().enumerate() {
                cost[k * n + j] = reach.cost(c as usize).unwrap_or(f64::INFINITY);
                prop_assert!(
                    (cost[k * n + j] - d[j * m + k]).abs() < 1e-9
                        || cost[k * n + j] == d[j * m + k],
                    "paths are symmetric"
                );
            }
        }
        for i in 0..m {
            for j in 0..n {
                if cost[i * n + j].is_finite() {
                    prop_assert_eq!(rank(&cost, m, n, i, j), brute_rank(i, j));
                }
            }
        }
        let kept = |c: u32| (0..m).any(|k| !deciding[k] && goals[k] == Some(c));
        for i in 0..m {
            if !deciding[i] {
                prop_assert_eq!(out[i], None, "a robot that does not decide is untouched");
                continue;
            }
            let reach: Vec<usize> = (0..n).filter(|&j| d[j * m + i].is_finite()).collect();
            let free: Vec<usize> = reach.iter().copied().filter(|&j| !kept(cands.cells()[j])).collect();
            let pool = if free.is_empty() { reach } else { free };
            let Some(goal) = out[i] else {
                prop_assert!(pool.is_empty(), "robot {} got no goal but can reach one", i);
                continue;
            };
            let j = cands.cells().iter().position(|&c| c == goal.cell).expect("a candidate");
            prop_assert!(pool.contains(&j), "goal {} not allowed", goal.cell);
            prop_assert!((goal.cost - d[j * m + i]).abs() < 1e-9, "reported cost");
            let best_rank = pool.iter().map(|&j| brute_rank(i, j)).min().expect("nonempty");
            prop_assert_eq!(brute_rank(i, j), best_rank, "rank not minimal");
            let best_cost = pool
                .iter()
                .filter(|&&j| brute_rank(i, j) == best_rank)
                .map(|&j| d[j * m + i])
                .fold(f64::INFINITY, f64::min);
            prop_assert!(goal.cost <= best_cost + 1e-9, "tie not broken by cost");
        }
    }
}

#[test]
fn worked_example() {
    // Three robots on a corridor, goals at both ends: robot 0 is nearest to g0; robots 1 and
    // 2 are both nearer g1 than robot 0. Robot 1: rank(g0) = 1 (robot 0 closer), rank(g1) =
    // 0 → g1. Robot 2: rank(g1) = 1 (robot 1 closer), rank(g0) = 1 (robot 0 closer) → tie
    // broken by its cost: g1 (3) before g0 (4).
    //        g0  g1
    let cost = [
        1.0, 9.0, // robot 0
        5.0, 2.0, // robot 1
        4.0, 3.0, // robot 2
    ];
    let mut out = Vec::new();
    explore::assign::minpos::solve(3, 2, &cost, &[true, true, true], &[false, false], &mut out);
    assert_eq!(out, vec![Some(0), Some(1), Some(1)]);
    assert_eq!(rank(&cost, 3, 2, 2, 0), 1);
    assert_eq!(rank(&cost, 3, 2, 2, 1), 1);
    // With g1 kept by robot 1 (not deciding), robot 2 is sent to g0.
    explore::assign::minpos::solve(3, 2, &cost, &[false, false, true], &[false, true], &mut out);
    assert_eq!(out, vec![None, None, Some(0)]);
}
