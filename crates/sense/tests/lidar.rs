//! Lidar properties on random small maps: what it reports is true, unique, in range and
//! in its field of view.

mod common;

use common::origin_in;
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{LidarSensor, Observation, Pose, Sensor};

fn arb_map() -> impl Strategy<Value = Grid<Occ>> {
    (1usize..=24, 1usize..=24, 0u32..=60).prop_flat_map(|(w, h, density)| {
        proptest::collection::vec(0u32..100, w * h).prop_map(move |rolls| {
            let data = rolls
                .iter()
                .map(|&roll| match roll {
                    r if r < density && r % 4 == 0 => Occ::Unknown,
                    r if r < density => Occ::Occupied,
                    _ => Occ::Free,
                })
                .collect();
            Grid::from_vec(w, h, data).expect("w*h cells")
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn lidar_reports_only_the_truth(
        truth in arb_map(),
        r in prop_oneof![0.0f64..12.0, 20.0f64..100.0],
        fov in prop_oneof![Just(360.0), Just(180.0), 1.0f64..360.0],
        res in prop_oneof![Just(1.0), 0.5f64..20.0],
        heading in -7.0f64..7.0,
        sx in 0i32..24,
        sy in 0i32..24,
    ) {
        let o = origin_in(&truth, sx, sy);
        let sensor = LidarSensor::new(r, fov, res).expect("valid");
        let mut obs = Observation::new();
        sensor.scan(&truth, Pose::new(o, heading), &mut obs);
        prop_assert_eq!(obs.origin, o);
        // The sensor's own cell is always reported.
        prop_assert!(obs.cells.iter().any(|&(i, _)| truth.cell(i as usize) == o));
        for w in obs.cells.windows(2) {
            prop_assert!(w[0].0 < w[1].0, "sorted, no duplicates");
        }
        for &(i, seen) in &obs.cells {
            let c = truth.cell(i as usize);
            let state = truth[i as usize];
            match seen {
                Occ::Free => prop_assert_eq!(state, Occ::Free),
                Occ::Occupied => prop_assert_ne!(state, Occ::Free),
                Occ::Unknown => prop_assert!(false, "Unknown reported"),
            }
            if c == o {
                continue;
            }
            // Entered by a beam at a distance < r: the centre is within r + √2/2.
            prop_assert!(o.dist(c) < r + std::f64::consts::FRAC_1_SQRT_2 + 1e-9);
            // Inside the field of view: the cell's angular interval (seen from the sensor
            // centre, relative to the heading) meets [−fov/2, fov/2].
            if fov < 360.0 {
                let wrap = |a: f64| {
                    (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI
                };
                let (dx, dy) = (f64::from(c.x - o.x), f64::from(c.y - o.y));
                let centre = dy.atan2(dx);
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for (cx, cy) in [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)] {
                    // Corner angles relative to the centre direction (the cell spans < 180°).
                    let a = wrap((dy + cy).atan2(dx + cx) - centre);
                    lo = lo.min(a);
                    hi = hi.max(a);
                }
                let mid = wrap(centre - heading);
                let half = fov.to_radians() / 2.0 + 1e-9;
                // The interval may straddle ±π (a cell straight behind a robot whose field
                // of view is nearly 360°): it meets the field of view if some 2π shift does.
                let meets = [-std::f64::consts::TAU, 0.0, std::f64::consts::TAU]
                    .iter()
                    .any(|k| mid + hi + k >= -half && mid + lo + k <= half);
                prop_assert!(meets, "{} outside fov", c);
            }
        }
        // If the origin is blocked, nothing else is seen.
        if truth[truth.index(o)] != Occ::Free {
            prop_assert_eq!(obs.cells.len(), 1);
        }
        // Exactly the beams' cells, sorted and deduplicated: a predicted scan traces the
        // same beams, and with the world's Unknown cells made Occupied it stops where the
        // scan stops.
        let opaque = truth.map(|&s| if s == Occ::Free { Occ::Free } else { Occ::Occupied });
        let mut beams = Vec::new();
        sensor.predict(&opaque, Pose::new(o, heading), &mut beams);
        beams.sort_unstable();
        beams.dedup();
        let want: Vec<(u32, Occ)> = beams.iter().map(|&i| (i, opaque[i as usize])).collect();
        prop_assert_eq!(&obs.cells, &want);
    }
}

#[test]
fn full_circle_in_the_open_reaches_every_direction() {
    let g = Grid::new(31, 31, Occ::Free);
    let o = Cell::new(15, 15);
    let s = LidarSensor::new(10.0, 360.0, 1.0).expect("valid");
    assert!(s.is_omnidirectional());
    let mut obs = Observation::new();
    s.scan(&g, Pose::new(o, 0.3), &mut obs);
    for c in [(25, 15), (5, 15), (15, 25), (15, 5), (22, 22), (8, 8)] {
        let i = g.index(Cell::new(c.0, c.1)) as u32;
        assert!(obs.cells.iter().any(|&(j, _)| j == i), "{c:?}");
    }
    // Nothing beyond the range.
    assert!(
        obs.cells
            .iter()
            .all(|&(i, _)| o.dist(g.cell(i as usize)) < 10.71)
    );
}

#[test]
fn leaving_the_grid_ends_the_beam_unreported() {
    let g = Grid::new(3, 1, Occ::Free);
    let s = LidarSensor::new(50.0, 10.0, 1.0).expect("valid");
    let mut obs = Observation::new();
    s.scan(&g, Pose::new(Cell::new(0, 0), 0.0), &mut obs);
    assert_eq!(
        obs.cells,
        vec![(0, Occ::Free), (1, Occ::Free), (2, Occ::Free)]
    );
    s.scan(&g, Pose::new(Cell::new(5, 0), 0.0), &mut obs);
    assert!(obs.is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// A gated prediction sees what a scan sees on the belief with every passable Unknown
    /// cell made Free and every other Unknown cell made Occupied; with every cell passable it
    /// is the plain prediction.
    #[test]
    fn gated_prediction_is_a_scan_of_the_gated_belief(
        known in arb_map(),
        r in 0.0f64..12.0,
        fov in prop_oneof![Just(360.0), Just(180.0), 1.0f64..360.0],
        res in prop_oneof![Just(1.0), 0.5f64..20.0],
        heading in -7.0f64..7.0,
        sx in 0i32..24,
        sy in 0i32..24,
        salt in any::<u64>(),
        unknown_only in any::<bool>(),
    ) {
        let o = origin_in(&known, sx, sy);
        let sensor = LidarSensor::new(r, fov, res).expect("valid");
        let pose = Pose::new(o, heading);
        let passable = |i: usize| (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ salt >= u64::MAX / 3;
        let gated_truth = Grid::from_vec(
            known.width(),
            known.height(),
            known
                .data()
                .iter()
                .enumerate()
                .map(|(i, &s)| match s {
                    Occ::Unknown if passable(i) => Occ::Free,
                    Occ::Unknown => Occ::Occupied,
                    s => s,
                })
                .collect(),
        )
        .expect("same size");
        let mut obs = Observation::new();
        sensor.scan(&gated_truth, pose, &mut obs);
        let mut want: Vec<u32> = obs
            .cells
            .iter()
            .map(|&(i, _)| i)
            .filter(|&i| !unknown_only || known[i as usize] == Occ::Unknown)
            .collect();
        want.sort_unstable();
        let mut got = Vec::new();
        sensor.predict_gated(&known, pose, unknown_only, &passable, &mut got);
        got.sort_unstable();
        got.dedup();
        prop_assert_eq!(got, want);
        // Everything passable: the plain prediction.
        let mut plain = Vec::new();
        if unknown_only {
            sensor.predict_unknown(&known, pose, &mut plain);
        } else {
            sensor.predict(&known, pose, &mut plain);
        }
        plain.sort_unstable();
        plain.dedup();
        let mut all = Vec::new();
        sensor.predict_gated(&known, pose, unknown_only, &|_| true, &mut all);
        all.sort_unstable();
        all.dedup();
        prop_assert_eq!(all, plain);
    }
}
