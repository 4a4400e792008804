//! The fast `LosSensor` scan equals the direct segment test (`los_visible`) on every cell
//! of random small maps, and the footprint sensor equals brute force.

use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{FootprintSensor, LosSensor, Observation, Pose, Sensor, los_visible};

/// A random map: `density`% of cells blocked (a fifth of them ground-truth Unknown), and in
/// "checkerboard" mode extra blocked cells on one colour of a checkerboard, which makes many
/// pairs of blocked cells touching only at a vertex.
fn arb_map() -> impl Strategy<Value = Grid<Occ>> {
    (1usize..=24, 1usize..=24, 0u32..=70, any::<bool>()).prop_flat_map(
        |(w, h, density, checker)| {
            proptest::collection::vec(0u32..100, w * h).prop_map(move |rolls| {
                let data = rolls
                    .iter()
                    .enumerate()
                    .map(|(i, &roll)| {
                        let (x, y) = (i % w, i / w);
                        let on_colour = (x + y) % 2 == 0;
                        if roll < density || (checker && on_colour && roll % 3 == 0) {
                            if roll % 5 == 0 {
                                Occ::Unknown
                            } else {
                                Occ::Occupied
                            }
                        } else {
                            Occ::Free
                        }
                    })
                    .collect();
                Grid::from_vec(w, h, data).expect("w*h cells")
            })
        },
    )
}

/// Ranges: arbitrary fractions, and exact square roots of integers (to hit the boundary).
fn arb_range() -> impl Strategy<Value = f64> {
    prop_oneof![0.0f64..14.0, (0u32..200).prop_map(|k| f64::from(k).sqrt())]
}

fn observed(s: Occ) -> Occ {
    if s == Occ::Free {
        Occ::Free
    } else {
        Occ::Occupied
    }
}

/// Every cell `los_visible` sees from `o` within `r`, with its observed state, by index.
fn seen_by_segment_test(truth: &Grid<Occ>, o: Cell, r: f64) -> Vec<(u32, Occ)> {
    truth
        .cells()
        .filter(|&c| truth.contains(o) && los_visible(truth, o, c, r))
        .map(|c| (truth.index(c) as u32, observed(*truth.get(c))))
        .collect()
}

fn sorted(obs: &Observation) -> Vec<(u32, Occ)> {
    let mut v = obs.cells.clone();
    v.sort_unstable();
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn los_scan_equals_direct_segment_test(
        truth in arb_map(),
        r in arb_range(),
        sx in -1i32..25,
        sy in -1i32..25,
    ) {
        let sensor = LosSensor::new(r).expect("valid range");
        let o = Cell::new(sx, sy);
        let mut obs = Observation::new();
        sensor.scan(&truth, Pose::new(o, 0.7), &mut obs);
        prop_assert_eq!(obs.origin, o);
        let got = sorted(&obs);
        let mut dedup = got.clone();
        dedup.dedup_by_key(|c| c.0);
        prop_assert_eq!(dedup.len(), got.len(), "duplicates");
        let want = seen_by_segment_test(&truth, o, r);
        prop_assert_eq!(got, want);
    }

    #[test]
    fn footprint_equals_brute_force(
        truth in arb_map(),
        r in arb_range(),
        sx in -1i32..25,
        sy in -1i32..25,
    ) {
        let sensor = FootprintSensor::new(r).expect("valid range");
        let o = Cell::new(sx, sy);
        let mut obs = Observation::new();
        sensor.scan(&truth, Pose::new(o, 0.0), &mut obs);
        let want: Vec<(u32, Occ)> = truth
            .cells()
            .filter(|&c| truth.contains(o) && (o.dist2(c) as f64) <= r * r)
            .map(|c| (truth.index(c) as u32, observed(*truth.get(c))))
            .collect();
        prop_assert_eq!(sorted(&obs), want);
    }
}

/// A worked example: a room with a pillar and a diagonal squeeze, every visible cell
/// listed by hand.
#[test]
fn worked_example_small_room() {
    // S = sensor at (1, 1). Cells (3,2) and (2,3) block the diagonal through vertex (3, 3)
    // in cell-corner coordinates, so (3,3) is hidden although its own cell is free.
    let rows = ["#####", "#S..#", "#..##", "#.#.#", "#####"];
    let data = rows
        .iter()
        .flat_map(|r| r.chars())
        .map(|c| if c == '#' { Occ::Occupied } else { Occ::Free })
        .collect();
    let truth = Grid::from_vec(5, 5, data).expect("5x5");
    let sensor = LosSensor::new(10.0).expect("valid");
    let mut obs = Observation::new();
    sensor.scan(&truth, Pose::new(Cell::new(1, 1), 0.0), &mut obs);
    let seen: Vec<Cell> = sorted(&obs)
        .iter()
        .map(|&(i, _)| truth.cell(i as usize))
        .collect();
    assert!(
        !seen.contains(&Cell::new(3, 3)),
        "squeeze between (3,2) and (2,3)"
    );
    // Seen: the free cells other than (3,3) and the walls that end a clear segment.
    for c in [
        (1, 0),
        (2, 0),
        (2, 2),
        (3, 2),
        (2, 3),
        (1, 3),
        (4, 1),
        (1, 4),
    ] {
        assert!(seen.contains(&Cell::new(c.0, c.1)), "{c:?} should be seen");
    }
    // Hidden behind walls: (4,0) lies behind (3,0), (0,4) behind (0,3), (4,4) behind the
    // squeeze, and the corner (0,0) behind the squeeze between walls (1,0) and (0,1).
    assert!(!seen.contains(&Cell::new(0, 0)));
    // (3,0) lies behind the wall (2,0); (2,4) behind the pillar (2,3).
    assert!(!seen.contains(&Cell::new(3, 0)));
    assert!(!seen.contains(&Cell::new(2, 4)));
    assert!(!seen.contains(&Cell::new(4, 0)));
    assert!(!seen.contains(&Cell::new(0, 4)));
    assert!(!seen.contains(&Cell::new(4, 4)));
    assert!(!seen.contains(&Cell::new(3, 4)));
    assert!(!seen.contains(&Cell::new(4, 3)));
    // And the oracle agrees on this map cell by cell.
    for c in truth.cells() {
        let in_scan = seen.contains(&c);
        assert_eq!(
            in_scan,
            los_visible(&truth, Cell::new(1, 1), c, 10.0),
            "{c}"
        );
    }
}

/// A random map for the long ranges: `density`% of cells blocked, a fifth of them Unknown.
fn arb_large_map() -> impl Strategy<Value = Grid<Occ>> {
    (20usize..=64, 20usize..=64, 0u32..=40).prop_flat_map(|(w, h, density)| {
        proptest::collection::vec(0u32..100, w * h).prop_map(move |rolls| {
            let data = rolls
                .iter()
                .map(|&roll| match roll {
                    r if r < density && r % 5 == 0 => Occ::Unknown,
                    r if r < density => Occ::Occupied,
                    _ => Occ::Free,
                })
                .collect();
            Grid::from_vec(w, h, data).expect("w*h cells")
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// From 20 cells of range on, a scan is computed by shadow casting: the same cells,
    /// in the same order, as the template walk, and those `los_visible` sees.
    #[test]
    fn long_range_scan_equals_the_template_walk_in_order(
        truth in arb_large_map(),
        r in prop_oneof![20.0f64..48.0, (400u32..2304).prop_map(|k| f64::from(k).sqrt())],
        sx in -1i32..65,
        sy in -1i32..65,
    ) {
        let sensor = LosSensor::new(r).expect("valid range");
        let o = Cell::new(sx, sy);
        let mut obs = Observation::new();
        sensor.scan(&truth, Pose::new(o, 0.0), &mut obs);
        let mut walk = Vec::new();
        sensor.for_each_seen(&truth, o, |i, s| walk.push((i, s)));
        prop_assert_eq!(&obs.cells, &walk);
        let want = seen_by_segment_test(&truth, o, r);
        prop_assert_eq!(sorted(&obs), want);
    }
}

/// `grid` with every Unknown cell made Free: a predicted scan treats Unknown as transparent.
fn unknown_as_free(grid: &Grid<Occ>) -> Grid<Occ> {
    let data = grid
        .data()
        .iter()
        .map(|&s| if s == Occ::Unknown { Occ::Free } else { s })
        .collect();
    Grid::from_vec(grid.width(), grid.height(), data).expect("same size")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// A predicted scan sees through Unknown cells: the cells, in the template walk's
    /// order, that a scan of the map with Unknown made Free sees, and of them the Unknown
    /// ones for `predict_unknown`, at short ranges (the walk) and long ones (shadow
    /// casting).
    #[test]
    fn predicted_scan_equals_the_walk_with_unknown_transparent(
        known in arb_large_map(),
        r in prop_oneof![0.0f64..20.0, 20.0f64..48.0, (400u32..2304).prop_map(|k| f64::from(k).sqrt())],
        sx in -1i32..65,
        sy in -1i32..65,
    ) {
        let sensor = LosSensor::new(r).expect("valid range");
        let o = Cell::new(sx, sy);
        let clear = unknown_as_free(&known);
        let mut walk = Vec::new();
        sensor.for_each_seen(&clear, o, |i, _| walk.push(i));
        let mut got = Vec::new();
        sensor.predict(&known, Pose::new(o, 0.0), &mut got);
        prop_assert_eq!(&got, &walk);
        let unknown: Vec<u32> =
            walk.into_iter().filter(|&i| known.data()[i as usize] == Occ::Unknown).collect();
        sensor.predict_unknown(&known, Pose::new(o, 0.0), &mut got);
        prop_assert_eq!(got, unknown);
    }
}
