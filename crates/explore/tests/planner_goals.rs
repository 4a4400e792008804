//! `Planner::grow_toward` (a search guided toward some of the candidates: GA's free goals,
//! SGA's own cluster) and `Planner::grow` (toward every candidate) asked one after the
//! other in the same decision: every goal of the set asked for last, of cost below the
//! bucket grown through, is settled at its full-search cost.

use explore::Reachability;
use explore::decision::Planner;
use proptest::prelude::*;

mod common;
#[allow(unused_imports)]
use common::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_search_guided_toward_some_goals_settles_the_others_when_asked(
        bits in prop::collection::vec(0u8..100, 41),
        cut in 6usize..30,
        every in 1usize..40,
        keep in 2usize..6,
        first in 0usize..40,
        then in 0usize..60,
    ) {
        let (w, h) = (48, 36);
        let (known, up) = random_upkept(w, h, &bits, cut);
        let Some(start) = largest_component_cell(&known, &up) else {
            return Ok(());
        };
        let pass = |i| up.is_traversable(&known, i);
        let goals: Vec<u32> = (0..(w * h) as u32)
            .filter(|&i| known[i as usize].is_free())
            .step_by(every)
            .collect();
        // some of the goals, as a rule that may take only those would ask
        let some: Vec<u32> = goals.iter().copied().step_by(keep).collect();
        let others: Vec<u32> = goals.iter().copied().skip(1).step_by(keep).collect();
        let mut full = Reachability::new(w, h);
        full.compute(start, pass);
        let from = start as u32;
        // toward some, then toward all; toward all, then toward some; toward some, then
        // toward others
        for case in 0..3 {
            let mut planner = Planner::new(w, h, 1);
            planner.invalidate();
            let (last, done) = match case {
                0 => {
                    planner.grow_toward(0, from, &known, &up, (&some, 1), first);
                    (&goals, planner.grow(0, from, &known, &up, &goals, first + then))
                }
                1 => {
                    planner.grow(0, from, &known, &up, &goals, first);
                    let last = (&some[..], 1);
                    (&some, planner.grow_toward(0, from, &known, &up, last, first + then))
                }
                _ => {
                    planner.grow_toward(0, from, &known, &up, (&some, 1), first);
                    let last = (&others[..], 2);
                    (&others, planner.grow_toward(0, from, &known, &up, last, first + then))
                }
            };
            let map = planner.map(0);
            for &g in last {
                let g = g as usize;
                if full.cost(g).is_some_and(|c| (c as usize) <= first + then) || done {
                    prop_assert_eq!(
                        map.cost(g).map(f64::to_bits),
                        full.cost(g).map(f64::to_bits),
                        "case {}, goal {}", case, g
                    );
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Regression (MinPos' proof read a robot's map that the decision had not searched,
    /// holding the previous decision's search from where that robot stood): after
    /// `invalidate`, a map not searched again settles nothing, and a new search from
    /// another cell gives its full-search costs.
    #[test]
    fn a_map_not_searched_since_invalidate_settles_nothing(
        bits in prop::collection::vec(0u8..100, 41),
        cut in 6usize..30,
    ) {
        let (w, h) = (48, 36);
        let (known, up) = random_upkept(w, h, &bits, cut);
        let Some(start) = largest_component_cell(&known, &up) else {
            return Ok(());
        };
        let pass = |i| up.is_traversable(&known, i);
        let mut planner = Planner::new(w, h, 1);
        planner.invalidate();
        planner.full(0, start as u32, &known, &up);
        prop_assert!(planner.map(0).cost(start).is_some());
        planner.invalidate();
        for i in 0..w * h {
            prop_assert!(!planner.map(0).is_settled(i), "cell {} still settled", i);
            prop_assert_eq!(planner.map(0).cost(i), None);
        }
        prop_assert!(planner.map(0).settled().is_empty());
        // searched again from another cell of the component: the full search's costs
        let Some(other) = (0..w * h).rev().find(|&i| i != start && pass(i)) else {
            return Ok(());
        };
        let map = planner.full(0, other as u32, &known, &up);
        let mut fresh = Reachability::new(w, h);
        fresh.compute(other, pass);
        for i in 0..w * h {
            prop_assert_eq!(map.cost(i), fresh.cost(i), "cell {}", i);
        }
    }
}
