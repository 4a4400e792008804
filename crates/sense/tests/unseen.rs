//! `Sensor::scan_unseen` of the lidar and the line-of-sight sensor against their full scans
//! on random maps and beliefs: it reports a subset of the full scan's cells, and every cell the full scan
//! reports that the belief does not know yet.

use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{LidarSensor, LosSensor, Observation, Pose, Sensor, Unseen};

/// A random ground truth (some of it Unknown, the outside of a plan) and a belief that
/// knows a random part of what could be seen, as the truth shows it.
fn arb_case() -> impl Strategy<Value = (Grid<Occ>, Grid<Occ>)> {
    (1usize..=40, 1usize..=40, 0u32..=60, 0u32..=100).prop_flat_map(|(w, h, density, known)| {
        proptest::collection::vec((0u32..100, 0u32..100), w * h).prop_map(move |rolls| {
            let truth: Vec<Occ> = rolls
                .iter()
                .map(|&(roll, _)| match roll {
                    r if r < density && r % 4 == 0 => Occ::Unknown,
                    r if r < density => Occ::Occupied,
                    _ => Occ::Free,
                })
                .collect();
            let belief = truth
                .iter()
                .zip(&rolls)
                .map(|(&t, &(_, k))| match (k < known, t) {
                    (false, _) => Occ::Unknown,
                    (true, Occ::Free) => Occ::Free,
                    (true, _) => Occ::Occupied,
                })
                .collect();
            (
                Grid::from_vec(w, h, truth).expect("w*h cells"),
                Grid::from_vec(w, h, belief).expect("w*h cells"),
            )
        })
    })
}

/// The two scans agree on what the belief does not know, and the short one reports only
/// what the full one does.
fn check(
    sensor: &dyn Sensor,
    truth: &Grid<Occ>,
    belief: &Grid<Occ>,
    shift: u32,
    pose: Pose,
) -> Result<(), TestCaseError> {
    let unseen = Unseen::new(truth, belief, shift);
    let (mut full, mut short) = (Observation::new(), Observation::new());
    sensor.scan(truth, pose, &mut full);
    sensor.scan_unseen(truth, pose, &unseen, &mut short);
    prop_assert_eq!(short.origin, full.origin);
    let mut all = full.cells.clone();
    all.sort_unstable();
    all.dedup();
    for c in &short.cells {
        prop_assert!(
            all.binary_search(c).is_ok(),
            "{:?} is not in the full scan",
            c
        );
    }
    let mut kept = short.cells.clone();
    kept.sort_unstable();
    for c in &all {
        if belief[c.0 as usize] == Occ::Unknown {
            prop_assert!(kept.binary_search(c).is_ok(), "{:?} left out", c);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn lidar_scan_unseen_keeps_every_unknown_cell(
        (truth, belief) in arb_case(),
        r in prop_oneof![0.0f64..12.0, 12.0f64..60.0],
        fov in prop_oneof![Just(360.0), Just(180.0), 1.0f64..360.0],
        res in prop_oneof![Just(1.0), 0.25f64..20.0],
        heading in -7.0f64..7.0,
        shift in 0u32..=4,
        (sx, sy) in (0i32..40, 0i32..40),
    ) {
        let o = Cell::new(sx, sy);
        prop_assume!(truth.contains(o));
        let sensor = LidarSensor::new(r, fov, res).expect("valid");
        check(&sensor, &truth, &belief, shift, Pose::new(o, heading))?;
    }

    #[test]
    fn los_scan_unseen_keeps_every_unknown_cell(
        (truth, belief) in arb_case(),
        // Below 20 cells the ray template scans, from 20 on shadow casting.
        r in prop_oneof![0.0f64..20.0, 20.0f64..45.0],
        shift in 0u32..=4,
        (sx, sy) in (0i32..40, 0i32..40),
    ) {
        let o = Cell::new(sx, sy);
        prop_assume!(truth.contains(o));
        let sensor = LosSensor::new(r).expect("valid");
        check(&sensor, &truth, &belief, shift, Pose::new(o, 0.0))?;
    }
}
