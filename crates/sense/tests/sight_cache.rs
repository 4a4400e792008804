//! `SightCache` against the line-of-sight sensor it remembers: the same observation, cell
//! for cell and in the same order, for full scans and for scans of what is unseen, whether
//! a cell's set is not yet made (first scan), made now (second) or read (later), within
//! any budget, and shared between threads.

mod common;

use std::sync::Arc;

use common::origin_in;
use common::sensed::{Sensed, arb_case, unseen_of};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{LosSensor, Observation, Pose, Sensor, SightBudget, SightCache};

/// Three scans from each origin (the set not made, made, read): each equals the sensor's.
fn check(
    truth: &Grid<Occ>,
    robots: usize,
    sensed: &[Sensed],
    r: f64,
    shift: u32,
    origins: &[Cell],
    budget: u64,
) -> Result<(), TestCaseError> {
    let sensor = LosSensor::new(r).expect("valid");
    let budget = SightBudget::new(budget);
    let Some(cache) = SightCache::new(truth, sensor.clone(), budget.clone()) else {
        prop_assert!(budget.left() < SightCache::base_bytes(truth.len(), &sensor));
        return Ok(());
    };
    prop_assert!(cache.serves(truth, r));
    let mut unseen = unseen_of(truth, robots, sensed, shift);
    let (mut want, mut got) = (Observation::new(), Observation::new());
    for _ in 0..3 {
        for &o in origins {
            let pose = Pose::new(o, 0.0);
            sensor.scan(truth, pose, &mut want);
            cache.scan(pose, &mut got);
            prop_assert_eq!(&got, &want, "full scan from {:?}", o);
            for viewer in 0..robots {
                unseen.look_as(viewer);
                sensor.scan_unseen(truth, pose, &unseen, &mut want);
                cache.scan_unseen(pose, &unseen, &mut got);
                prop_assert_eq!(&got, &want, "robot {} from {:?}", viewer, o);
            }
        }
    }
    drop(cache);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Ranges on both sides of the switch to shadow casting, and past 32 cells, where a
    /// set's rows are wider than a word.
    #[test]
    fn remembered_scans_equal_the_sensors(
        (truth, robots, sensed) in arb_case(48),
        r in prop_oneof![0.0f64..14.0, 14.0f64..30.0, 30.0f64..45.0],
        shift in 0u32..=4,
        origins in proptest::collection::vec((0i32..48, 0i32..48), 1..4),
        tight in any::<bool>(),
    ) {
        let origins: Vec<Cell> = origins.iter().map(|&(x, y)| origin_in(&truth, x, y)).collect();
        let sensor = LosSensor::new(r).expect("valid");
        // A tight budget holds the cache and one set: the other origins are scanned as
        // the sensor scans them.
        let budget = if tight {
            SightCache::base_bytes(truth.len(), &sensor) + SightCache::set_bytes(&sensor)
        } else {
            u64::MAX / 2
        };
        check(&truth, robots, &sensed, r, shift, &origins, budget)?;
    }
}

/// A cell outside the grid sees nothing; a cache does not serve another truth or range.
#[test]
fn outside_and_other_truths() {
    let truth = Grid::new(10, 7, Occ::Free);
    let sensor = LosSensor::new(3.0).expect("valid");
    let cache = SightCache::new(&truth, sensor, SightBudget::new(u64::MAX / 2)).expect("fits");
    let mut obs = Observation::new();
    cache.scan(Pose::new(Cell::new(-1, 3), 0.0), &mut obs);
    assert!(obs.is_empty());
    assert!(cache.serves(&truth, 3.0));
    assert!(cache.serves(&truth, 3.1)); // the same cells within range
    assert!(!cache.serves(&truth, 4.0));
    let mut other = truth.clone();
    other.data_mut()[5] = Occ::Occupied;
    assert!(!cache.serves(&other, 3.0));
    assert!(!cache.serves(&Grid::new(7, 10, Occ::Free), 3.0));
}

/// The budget pays for the cache and its sets, and gets them back when it is dropped; a
/// budget too small for the cache makes none.
#[test]
fn the_budget_is_taken_and_given_back() {
    let truth = Grid::new(30, 20, Occ::Free);
    let sensor = LosSensor::new(5.0).expect("valid");
    let base = SightCache::base_bytes(truth.len(), &sensor);
    let set = SightCache::set_bytes(&sensor);
    assert!(SightCache::new(&truth, sensor.clone(), SightBudget::new(base - 1)).is_none());
    let budget = SightBudget::new(base + 2 * set);
    let cache = SightCache::new(&truth, sensor.clone(), budget.clone()).expect("fits");
    assert_eq!(budget.left(), 2 * set);
    let (mut want, mut got) = (Observation::new(), Observation::new());
    for x in [3, 3, 3, 9, 9, 15, 15] {
        let pose = Pose::new(Cell::new(x, 5), 0.0);
        sensor.scan(&truth, pose, &mut want);
        cache.scan(pose, &mut got);
        assert_eq!(got, want, "from ({x}, 5)");
    }
    // Cells 3 and 9 were scanned twice: their sets were made; 15's found no budget.
    assert_eq!(budget.left(), 0);
    drop(cache);
    assert_eq!(budget.left(), base + 2 * set);
}

/// Threads sharing one cache see what the sensor sees, whichever makes a set first.
#[test]
fn a_cache_shared_by_threads_answers_as_the_sensor() {
    let mut truth = Grid::new(60, 40, Occ::Free);
    for (i, c) in truth.data_mut().iter_mut().enumerate() {
        if (i * 7919) % 23 == 0 {
            *c = Occ::Occupied;
        }
    }
    let sensor = LosSensor::new(16.0).expect("valid");
    let cache = Arc::new(
        SightCache::new(&truth, sensor.clone(), SightBudget::new(u64::MAX / 2)).expect("fits"),
    );
    std::thread::scope(|s| {
        for t in 0..4 {
            let (cache, sensor, truth) = (cache.clone(), sensor.clone(), &truth);
            s.spawn(move || {
                let (mut want, mut got) = (Observation::new(), Observation::new());
                for k in 0..200 {
                    let c = Cell::new((k * 13 + t) % 60, (k * 7) % 40);
                    sensor.scan(truth, Pose::new(c, 0.0), &mut want);
                    cache.scan(Pose::new(c, 0.0), &mut got);
                    assert_eq!(got, want, "from {c:?}");
                }
            });
        }
    });
}
