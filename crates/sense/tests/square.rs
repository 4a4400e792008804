//! Explore-Bench's square sensor on random small maps: what it reports is true, unique,
//! sorted and inside the window; an extra obstacle never reveals a cell (rays are fixed and
//! end at obstacles); in open space it sees the whole window; a prediction on the truth
//! itself sees what a scan sees.

mod common;

use common::origin_in;
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{Observation, Pose, Sensor, SquareSensor};

fn arb_map() -> impl Strategy<Value = Grid<Occ>> {
    (1usize..=24, 1usize..=24, 0u32..=40).prop_flat_map(|(w, h, density)| {
        proptest::collection::vec(0u32..100, w * h).prop_map(move |rolls| {
            let data = rolls
                .iter()
                .map(|&roll| {
                    if roll < density {
                        Occ::Occupied
                    } else {
                        Occ::Free
                    }
                })
                .collect();
            Grid::from_vec(w, h, data).expect("w*h cells")
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn square_reports_the_truth_inside_its_window(
        truth in arb_map(), r in 0.0f64..10.0, sx in 0i32..24, sy in 0i32..24, pick in 0usize..1000,
    ) {
        let o = origin_in(&truth, sx, sy);
        let s = SquareSensor::new(r).expect("valid");
        let half = s.half_side() as i32;
        let mut obs = Observation::new();
        s.scan(&truth, Pose::new(o, 0.0), &mut obs);
        for w in obs.cells.windows(2) {
            prop_assert!(w[0].0 < w[1].0, "sorted, no duplicates");
        }
        for &(i, seen) in &obs.cells {
            let c = truth.cell(i as usize);
            prop_assert_eq!(seen, truth[i as usize]);
            let cheb = (c.x - o.x).abs().max((c.y - o.y).abs());
            prop_assert!(cheb <= half.max(1), "outside the window: {:?}", c);
        }
        // Rays are fixed, so an extra obstacle only shortens them: nothing new is seen.
        if let Some(&(q, _)) = obs.cells.get(pick % obs.cells.len().max(1)) {
            let mut blocked = truth.clone();
            blocked[q as usize] = Occ::Occupied;
            let mut after = Observation::new();
            s.scan(&blocked, Pose::new(o, 0.0), &mut after);
            for &(i, _) in &after.cells {
                prop_assert!(obs.cells.iter().any(|&(j, _)| j == i), "{} newly seen", i);
            }
        }
        // A prediction on the truth touches the same cells.
        let mut predicted = Vec::new();
        s.predict(&truth, Pose::new(o, 0.0), &mut predicted);
        predicted.sort_unstable();
        predicted.dedup();
        let scanned: Vec<u32> = obs.cells.iter().map(|&(i, _)| i).collect();
        prop_assert_eq!(predicted, scanned);
    }

    #[test]
    fn open_space_shows_the_whole_window(r in 0.0f64..12.0, sx in 0i32..30, sy in 0i32..30) {
        let truth = Grid::new(30, 30, Occ::Free);
        let o = Cell::new(sx, sy);
        let s = SquareSensor::new(r).expect("valid");
        let half = s.half_side().max(1) as i32;
        let mut obs = Observation::new();
        s.scan(&truth, Pose::new(o, 0.0), &mut obs);
        let want = (0..900)
            .filter(|&i| {
                let c = truth.cell(i);
                (c.x - o.x).abs() <= half && (c.y - o.y).abs() <= half
            })
            .count();
        prop_assert_eq!(obs.cells.len(), want);
    }
}
