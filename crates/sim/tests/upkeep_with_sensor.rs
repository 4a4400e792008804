//! Incremental frontier upkeep fed by the real `los` sensor and known grid equals the
//! from-scratch detector after every scan of a random walk (property test).

use explore::{FrontierUpkeep, frontiers_from_scratch};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{BeliefKind, LosSensor, Observation, Pose, Sensor};

fn world(w: usize, h: usize, walls: &[bool]) -> Grid<Occ> {
    let mut g = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let c = g.cell(i);
        let border = c.x == 0 || c.y == 0 || c.x as usize == w - 1 || c.y as usize == h - 1;
        if border || walls[i] {
            g[i] = Occ::Occupied;
        }
    }
    g
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn incremental_equals_scratch(
        w in 6usize..22, h in 6usize..22,
        walls in proptest::collection::vec(proptest::bool::weighted(0.22), 22 * 22),
        moves in proptest::collection::vec(0usize..8, 1..40),
        r in 1.5f64..7.0,
        clearance in prop_oneof![Just(0.0), Just(1.0), Just(1.5)],
        kind in prop_oneof![Just(BeliefKind::Known), Just(BeliefKind::Reflection), Just(BeliefKind::Evidence)],
    ) {
        let truth = world(w, h, &walls[..w * h]);
        let Some(mut at) = (0..truth.len()).find(|&i| truth[i] == Occ::Free) else { return Ok(()) };
        let sensor = LosSensor::new(r).unwrap();
        let mut belief = kind.build(w, h);
        let mut upkeep = FrontierUpkeep::new(w, h, clearance);
        let mut obs = Observation::new();
        let mut changed = Vec::new();
        for m in moves {
            sensor.scan(&truth, Pose { cell: truth.cell(at), heading: 0.0 }, &mut obs);
            changed.clear();
            belief.integrate(&obs, &mut changed);
            upkeep.update(belief.known(), &changed);
            let mut inc: Vec<u32> = upkeep.frontiers.cells().to_vec();
            inc.sort_unstable();
            prop_assert_eq!(inc, frontiers_from_scratch(belief.known(), &upkeep.trav));
            let (dx, dy) = grid::NEIGHBOURS8[m];
            let next = truth.cell(at).offset(dx, dy);
            if truth.try_get(next) == Some(&Occ::Free) && next != Cell::new(0, 0) {
                at = truth.index(next);
            }
        }
    }
}
