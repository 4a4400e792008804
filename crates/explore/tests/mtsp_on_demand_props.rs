//! MA's route costs computed when read (clusters beyond the matrix budget) give the routes
//! and costs of the route matrices, bit for bit: whole MA decisions with every budget
//! against the default one.

use explore::assign::AssignerKind;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::Goal;
use proptest::prelude::*;

mod common;
#[allow(unused_imports)]
use common::*;

/// One MA decision on `fx` with the route matrices limited to `budget` entries (`None`:
/// the default budget): the goals, the participants × clusters cost bits, the assignment
/// and the clusters.
type Decision = (
    Vec<Option<Goal>>,
    Vec<u64>,
    Vec<Option<usize>>,
    Vec<Vec<u32>>,
);

fn decide(fx: &mut Fixture, kind: CandidateKind, budget: Option<usize>) -> Decision {
    let n = fx.known.len();
    let m = fx.robots.len();
    let mut cands = CandidateSet::new(n);
    let mut out = vec![None; m];
    fx.memory.mtsp.set_matrix_budget(budget);
    let mut ctx = fx.ctx();
    kind.generate(&mut ctx, &mut cands);
    AssignerKind::Mtsp.assign(&mut ctx, &cands, &mut out);
    let st = &fx.memory.mtsp;
    let (cost, k) = st.cost_matrix();
    (
        out,
        cost.iter().map(|c| c.to_bits()).collect(),
        st.assignment().collect(),
        (0..k).map(|j| st.cluster(j).to_vec()).collect(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// MA decides the same with any matrix budget: none (every cluster computes its costs
    /// when read), a few clusters' worth, or the default (all matrices), for robots in any
    /// component (some reach only part of a cluster), over two decisions sharing the state.
    #[test]
    fn ma_decides_alike_with_any_matrix_budget(
        bits in prop::collection::vec(0u8..100, 53),
        cut in 10usize..40,
        m in 1usize..5,
        picks in prop::collection::vec(any::<prop::sample::Index>(), 4),
        keep in 0usize..5,
        seed in 0u64..100,
        cc in any::<bool>(),
        budget in 0usize..6000,
    ) {
        let (w, h) = (44, 40);
        let (known, up) = random_upkept(w, h, &bits, cut);
        let free: Vec<u32> = (0..w * h)
            .filter(|&i| up.is_traversable(&known, i))
            .map(|i| i as u32)
            .collect();
        if free.is_empty() {
            return Ok(());
        }
        let robots: Vec<u32> = picks[..m].iter().map(|p| free[p.index(free.len())]).collect();
        let kind = if cc { CandidateKind::Coverage } else { CandidateKind::AllFrontiers };
        let run = |budget: Option<usize>| {
            let mut fx = Fixture::new(known.clone(), robots.clone(), 4.0, seed);
            let first = decide(&mut fx, kind, budget);
            if keep < m {
                fx.deciding[keep] = false;
                fx.goals[keep] = first.0[keep].map(|g| g.cell);
            }
            (first, decide(&mut fx, kind, budget))
        };
        let want = run(None);
        prop_assert_eq!(&run(Some(0)), &want);
        prop_assert_eq!(&run(Some(budget)), &want);
    }
}
