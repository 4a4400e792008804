//! `coarsen` and `resample_nearest` against slow, obviously-correct oracles.

use grid::io::{MAX_CELLS, ascii_map, to_ascii};
use grid::resample::{coarsen, resample_nearest, resampled_size};
use grid::{Cell, Grid, GridMap, Occ};
use proptest::prelude::*;

fn occ() -> impl Strategy<Value = Occ> {
    prop_oneof![Just(Occ::Free), Just(Occ::Occupied), Just(Occ::Unknown)]
}

fn grid() -> impl Strategy<Value = Grid<Occ>> {
    (1usize..=24, 1usize..=24).prop_flat_map(|(w, h)| {
        proptest::collection::vec(occ(), w * h)
            .prop_map(move |d| Grid::from_vec(w, h, d).expect("size"))
    })
}

/// Oracle: the coarse cell (cx, cy) from every fine cell of its block, looked up with
/// `GridMap::state` (Unknown outside the map).
fn coarse_oracle(map: &GridMap, f: usize, cx: usize, cy: usize) -> Occ {
    let mut states = Vec::new();
    for y in cy * f..(cy + 1) * f {
        for x in cx * f..(cx + 1) * f {
            states.push(map.state(Cell::new(x as i32, y as i32)));
        }
    }
    if states.contains(&Occ::Occupied) {
        Occ::Occupied
    } else if states.contains(&Occ::Unknown) {
        Occ::Unknown
    } else {
        Occ::Free
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn coarsen_matches_oracle(cells in grid(), f in 1usize..=5, res in 0.01f64..2.0) {
        let map = GridMap { cells, resolution: res, origin: [1.0, 2.0, 0.0] };
        let c = coarsen(&map, f);
        prop_assert_eq!(c.width(), map.width().div_ceil(f));
        prop_assert_eq!(c.height(), map.height().div_ceil(f));
        prop_assert_eq!(c.resolution, res * f as f64);
        for cy in 0..c.height() {
            for cx in 0..c.width() {
                prop_assert_eq!(
                    *c.cells.get(Cell::new(cx as i32, cy as i32)),
                    coarse_oracle(&map, f, cx, cy),
                    "coarse cell ({}, {})", cx, cy
                );
            }
        }
        // The top edge stays put: origin.y + height * resolution is unchanged.
        let top = map.origin[1] + map.height() as f64 * res;
        let ctop = c.origin[1] + c.height() as f64 * c.resolution;
        prop_assert!((top - ctop).abs() < 1e-9, "top {} vs {}", top, ctop);
        prop_assert_eq!(c.origin[0], map.origin[0]);
    }

    #[test]
    fn resample_nearest_matches_oracle(
        cells in grid(),
        rx in prop_oneof![Just(0.05), Just(0.1), Just(0.15), 0.01f64..1.0],
        ry in prop_oneof![Just(0.05), Just(0.1), Just(0.2), 0.01f64..1.0],
    ) {
        let side = rx.min(ry);
        let r = resample_nearest(&cells, (rx, ry), side).expect("small enough");
        let (w, h) = resampled_size(cells.width(), cells.height(), (rx, ry), side).expect("size");
        prop_assert_eq!((r.width(), r.height()), (w, h));
        let want_w = ((cells.width() as f64 * rx / side).round() as usize).max(1);
        let want_h = ((cells.height() as f64 * ry / side).round() as usize).max(1);
        prop_assert_eq!((w, h), (want_w, want_h));
        for c in r.cells() {
            // The source pixel containing the new cell's centre, clamped into the image.
            let px = ((c.x as f64 + 0.5) * side / rx).floor() as i32;
            let py = ((c.y as f64 + 0.5) * side / ry).floor() as i32;
            let px = px.clamp(0, cells.width() as i32 - 1);
            let py = py.clamp(0, cells.height() as i32 - 1);
            prop_assert_eq!(r.get(c), cells.get(Cell::new(px, py)), "cell {}", c);
        }
        // Every new cell is a square of side `side`, so the map keeps its size to within
        // half a cell.
        prop_assert!((w as f64 * side - cells.width() as f64 * rx).abs() <= side / 2.0 + 1e-9);
        prop_assert!((h as f64 * side - cells.height() as f64 * ry).abs() <= side / 2.0 + 1e-9);
    }
}

#[test]
fn coarsen_worked_example() {
    let map = ascii_map(
        "
        .....
        ..#..
        .....
        ?....
        .....
        ",
    );
    let c = coarsen(&map, 2);
    // Blocks: rows 0-1 x cols 0-1 free; cols 2-3 hold '#'; col 4 runs past the edge.
    assert_eq!(to_ascii(&c.cells), ".#?\n?.?\n???\n");
    assert_eq!(c.resolution, 2.0);
    // One extra fine row at the bottom: the lower-left corner moves down one fine cell.
    assert_eq!(c.origin, [0.0, -1.0, 0.0]);
    // factor 1 and 0 leave the map as it is.
    assert_eq!(coarsen(&map, 1), map);
    assert_eq!(coarsen(&map, 0), map);
}

#[test]
fn resample_worked_example_and_limits() {
    let g = ascii_map("#.\n?.").cells;
    let r = resample_nearest(&g, (0.1, 0.2), 0.1).expect("ok");
    assert_eq!(to_ascii(&r), "#.\n#.\n?.\n?.\n");
    let r = resample_nearest(&g, (0.2, 0.2), 0.1).expect("ok");
    assert_eq!(to_ascii(&r), "##..\n##..\n??..\n??..\n");
    assert_eq!(resample_nearest(&g, (0.0, 0.2), 0.1), None);
    assert_eq!(resample_nearest(&g, (f64::NAN, 0.2), 0.1), None);
    assert_eq!(resample_nearest(&g, (0.1, 0.1), -1.0), None);
    assert_eq!(resampled_size(2, 2, (1.0, 1.0), 1e-9), None);
    let side = (MAX_CELLS as f64).sqrt() as usize;
    assert_eq!(
        resampled_size(side, side, (1.0, 1.0), 1.0),
        Some((side, side))
    );
    assert_eq!(resampled_size(side + 1, side, (1.0, 1.0), 1.0), None);
}
