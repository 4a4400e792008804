//! `Sensor::scan_unseen` of the lidar, line-of-sight and square sensors against their full
//! scans on random maps and records of who sensed what: it reports a subset of the full
//! scan's cells, and every cell of it that would tell the robot scanning something.

mod common;

use common::origin_in;
use common::sensed::{Sensed, arb_case, unseen_of};
use grid::{Grid, Occ};
use proptest::prelude::*;
use sense::{LidarSensor, LosSensor, Observation, Pose, Sensor, SquareSensor, Unseen};

/// For every robot: the two scans agree on the cells that would tell it something (nobody
/// sensed them, or one other robot did), and the short one reports only what the full one
/// does; if `exact`, nothing else.
fn check(
    sensor: &dyn Sensor,
    truth: &Grid<Occ>,
    robots: usize,
    sensed: &[Sensed],
    shift: u32,
    pose: Pose,
    exact: bool,
) -> Result<(), TestCaseError> {
    let mut unseen = unseen_of(truth, robots, sensed, shift);
    let mut full = Observation::new();
    sensor.scan(truth, pose, &mut full);
    let mut all = full.cells.clone();
    all.sort_unstable();
    all.dedup();
    for r in 0..robots {
        unseen.look_as(r);
        let mut short = Observation::new();
        sensor.scan_unseen(truth, pose, &unseen, &mut short);
        prop_assert_eq!(short.origin, full.origin);
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
            let tells = match sensed[c.0 as usize] {
                Sensed::None => true,
                Sensed::One(a) => a != r,
                Sensed::Two(..) => false,
            };
            if tells {
                prop_assert!(
                    kept.binary_search(c).is_ok(),
                    "{:?} left out for robot {}",
                    c,
                    r
                );
            } else if exact {
                prop_assert!(
                    kept.binary_search(c).is_err(),
                    "{:?} tells robot {} nothing but is reported",
                    c,
                    r
                );
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn lidar_scan_unseen_keeps_every_unknown_cell(
        (truth, robots, sensed) in arb_case(40),
        r in prop_oneof![0.0f64..12.0, 12.0f64..60.0],
        fov in prop_oneof![Just(360.0), Just(180.0), 1.0f64..360.0],
        res in prop_oneof![Just(1.0), 0.25f64..20.0],
        heading in -7.0f64..7.0,
        shift in 0u32..=4,
        (sx, sy) in (0i32..40, 0i32..40),
    ) {
        let o = origin_in(&truth, sx, sy);
        let sensor = LidarSensor::new(r, fov, res).expect("valid");
        check(&sensor, &truth, robots, &sensed, shift, Pose::new(o, heading), true)?;
    }

    #[test]
    fn los_scan_unseen_keeps_every_unknown_cell(
        (truth, robots, sensed) in arb_case(40),
        // Below 20 cells the ray template scans, from 20 on shadow casting.
        r in prop_oneof![0.0f64..20.0, 20.0f64..45.0],
        shift in 0u32..=4,
        (sx, sy) in (0i32..40, 0i32..40),
    ) {
        let o = origin_in(&truth, sx, sy);
        let sensor = LosSensor::new(r).expect("valid");
        check(&sensor, &truth, robots, &sensed, shift, Pose::new(o, 0.0), false)?;
    }

    #[test]
    fn square_scan_unseen_keeps_every_unknown_cell(
        (truth, robots, sensed) in arb_case(40),
        r in 0.0f64..30.0,
        shift in 0u32..=4,
        (sx, sy) in (0i32..40, 0i32..40),
    ) {
        let o = origin_in(&truth, sx, sy);
        let sensor = SquareSensor::new(r).expect("valid");
        check(&sensor, &truth, robots, &sensed, shift, Pose::new(o, 0.0), false)?;
    }

    /// `tells` and `telling_bits` against the definition, after records in any order
    /// (repeats, robots sensing a cell again, a third robot): a cell tells robot r
    /// something iff nobody sensed it, or exactly one robot did and it is not r.
    #[test]
    fn tells_follows_who_sensed_what(
        (w, h) in (1usize..=150, 1usize..=12),
        robots in 1usize..=4,
        records in proptest::collection::vec(
            (0usize..4, proptest::collection::vec(0usize..1800, 0..40)),
            0..12,
        ),
    ) {
        let truth = Grid::new(w, h, Occ::Free);
        let n = w * h;
        let mut unseen = Unseen::new(&truth, robots, 2);
        let mut who: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (r, cells) in &records {
            let r = r % robots;
            let cells: Vec<u32> = cells.iter().map(|&c| (c % n) as u32).collect();
            unseen.record(r, cells.iter().copied());
            for &c in &cells {
                if !who[c as usize].contains(&r) {
                    who[c as usize].push(r);
                }
            }
        }
        for r in 0..robots {
            unseen.look_as(r);
            let oracle = |i: usize| who[i].is_empty() || (who[i].len() == 1 && who[i][0] != r);
            for i in 0..n {
                prop_assert_eq!(unseen.tells(i), oracle(i), "cell {} robot {}", i, r);
                let bits = unseen.telling_bits(i);
                for k in 0..64.min(n - i) {
                    prop_assert_eq!(bits >> k & 1 == 1, oracle(i + k), "bit {} of {}", k, i);
                }
            }
        }
    }
}
