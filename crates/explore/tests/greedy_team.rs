//! Every coordinated assigner (greedy/IA, GA, greedy with utility, MinPos, HA) through
//! `AssignerKind::assign` on small random maps: deciding robots get reachable candidates with
//! their true path cost, robots that keep their goal are untouched, coordinated assigners
//! (greedy, GA, HA) give distinct goals while there are enough free ones, and the same seed
//! gives the same goals.

use explore::Reachability;
use explore::assign::AssignerKind;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{DecisionCtx, Goal, GoalLists, Memory, Planner};
use explore::upkeep::FrontierUpkeep;
use grid::{Grid, Occ};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

const W: usize = 12;
const H: usize = 9;

const KINDS: [AssignerKind; 5] = [
    AssignerKind::Greedy,
    AssignerKind::RandomOrderGreedy,
    AssignerKind::GreedyUtility { beta: 0.03 },
    AssignerKind::MinPos,
    AssignerKind::Hungarian,
];

/// One decision of `kind`; returns the goals.
fn decide(
    kind: AssignerKind,
    known: &Grid<Occ>,
    robots: &[u32],
    deciding: &[bool],
    goals: &[Option<u32>],
    seed: u64,
) -> Vec<Option<Goal>> {
    let mut upkeep = FrontierUpkeep::new(W, H, 0.0);
    upkeep.rebuild(known);
    let m = robots.len();
    let mut planner = Planner::new(W, H, m);
    let lists = GoalLists::new(W * H);
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let belief = sense::KnownGrid::new(W, H);
    let sensor = sense::LosSensor::new(3.0).expect("sensor");
    let mut memory = Memory::default();
    let mut cands = CandidateSet::new(W * H);
    let mut out = vec![None; m];
    let mut ctx = DecisionCtx {
        known,
        upkeep: &mut upkeep,
        planner: &mut planner,
        robots,
        deciding,
        goals,
        lists: &lists,
        resolution: 0.5,
        sensor_range_cells: 3.0,
        rng: &mut rng,
        belief: &belief,
        sensor: &sensor,
        memory: &mut memory,
    };
    CandidateKind::AllFrontiers.generate(&mut ctx, &mut cands);
    kind.assign(&mut ctx, &cands, &mut out);
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn goals_are_valid_and_deterministic(
        cells in prop::collection::vec(0u8..10, W * H),
        cut in 4usize..W,
        picks in prop::collection::vec(0usize..1000, 1..=5),
        deciding_bits in 1u32..32,
        goal_picks in prop::collection::vec(prop::option::of(0usize..1000), 5),
        seed in 0u64..1000,
    ) {
        let mut known = Grid::new(W, H, Occ::Unknown);
        for (i, &v) in cells.iter().enumerate() {
            if i % W < cut {
                known[i] = if v < 2 { Occ::Occupied } else { Occ::Free };
            }
        }
        let mut upkeep = FrontierUpkeep::new(W, H, 0.0);
        upkeep.rebuild(&known);
        let trav: Vec<u32> = (0..W * H)
            .filter(|&i| upkeep.is_traversable(&known, i))
            .map(|i| i as u32)
            .collect();
        prop_assume!(!trav.is_empty());
        let frontier = upkeep.frontiers.cells().to_vec();
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
        let mut reach = Reachability::new(W, H);
        for kind in KINDS {
            let out = decide(kind, &known, &robots, &deciding, &goals, seed);
            let again = decide(kind, &known, &robots, &deciding, &goals, seed);
            prop_assert_eq!(&out, &again, "{:?}: same seed, same goals", kind);
            let kept = |c: u32| (0..m).any(|k| !deciding[k] && goals[k] == Some(c));
            let mut free_reachable = 0;
            for r in 0..m {
                if !deciding[r] {
                    prop_assert_eq!(out[r], None, "{:?}: robot {} does not decide", kind, r);
                    continue;
                }
                reach.compute(robots[r] as usize, |i| upkeep.is_traversable(&known, i));
                let reachable: Vec<u32> =
                    frontier.iter().copied().filter(|&c| reach.cost(c as usize).is_some()).collect();
                free_reachable = free_reachable.max(reachable.iter().filter(|&&c| !kept(c)).count());
                match out[r] {
                    None => prop_assert!(reachable.is_empty(), "{:?}: robot {} idle", kind, r),
                    Some(g) => {
                        prop_assert!(frontier.contains(&g.cell), "{:?}: not a candidate", kind);
                        let c = reach.cost(g.cell as usize);
                        prop_assert!(c.is_some_and(|c| (c - g.cost).abs() < 1e-9), "{:?}: cost", kind);
                    }
                }
            }
            // Greedy, GA and HA never give one goal twice while free goals remain for all.
            let coordinated = matches!(
                kind,
                AssignerKind::Greedy | AssignerKind::RandomOrderGreedy | AssignerKind::Hungarian
            );
            let deciders = deciding.iter().filter(|&&d| d).count();
            let all_reach_same = (0..m).filter(|&r| deciding[r]).all(|r| {
                reach.compute(robots[r] as usize, |i| upkeep.is_traversable(&known, i));
                frontier.iter().all(|&c| reach.cost(c as usize).is_some())
            });
            if coordinated && all_reach_same && free_reachable >= deciders {
                let mut cells: Vec<u32> = out.iter().flatten().map(|g| g.cell).collect();
                prop_assert!(cells.iter().all(|&c| !kept(c)), "{:?}: kept goal reused", kind);
                cells.sort_unstable();
                let n = cells.len();
                cells.dedup();
                prop_assert_eq!(cells.len(), n, "{:?}: a goal given twice", kind);
            }
        }
    }
}
