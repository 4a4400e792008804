//! `Planner::settle_goals`, the searches MA grows side by side: every goal a robot can
//! reach is settled at its full-search cost and with its path, and the maps are the same
//! grown side by side and one after the other.

use explore::Reachability;
use explore::decision::Planner;
use proptest::prelude::*;

mod common;
#[allow(unused_imports)]
use common::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn settled_goals_have_full_search_costs_side_by_side_or_not(
        bits in prop::collection::vec(0u8..100, 41),
        cut in 6usize..30,
        m in 1usize..6,
        every in 1usize..40,
    ) {
        let (w, h) = (48, 36);
        let Some((known, up, robots)) = random_team(w, h, &bits, cut, m) else {
            return Ok(());
        };
        let pass = |i| up.is_traversable(&known, i);
        // goals: some free cells everywhere, also out of the robots' reach
        let goals: Vec<u32> = (0..(w * h) as u32)
            .filter(|&i| known[i as usize].is_free())
            .step_by(every)
            .collect();
        // From this thread the searches run side by side on rayon's global pool (a thread
        // per core); from a pool's own thread, one after the other.
        let mut side_by_side = Planner::new(w, h, m);
        side_by_side.settle_goals(&robots, &known, &up, &goals);
        let mut one_by_one = Planner::new(w, h, m);
        rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .expect("pool")
            .install(|| one_by_one.settle_goals(&robots, &known, &up, &goals));
        for (r, &robot) in robots.iter().enumerate() {
            let (seq, par) = (one_by_one.map(r), side_by_side.map(r));
            prop_assert_eq!(seq.settled(), par.settled());
            let mut full = Reachability::new(w, h);
            full.compute(robot as usize, pass);
            for &g in &goals {
                let want = full.cost(g as usize);
                prop_assert_eq!(par.cost(g as usize), seq.cost(g as usize));
                prop_assert_eq!(seq.cost(g as usize).is_some(), want.is_some());
                if want.is_some() {
                    prop_assert_eq!(seq.cost(g as usize), want);
                    let (mut a, mut b) = (Vec::new(), Vec::new());
                    prop_assert!(seq.path_to(g as usize, &mut a));
                    prop_assert!(full.path_to(g as usize, &mut b));
                    prop_assert_eq!(a, b);
                }
            }
        }
    }
}
