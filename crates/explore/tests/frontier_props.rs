//! Incremental frontier upkeep against slow, obviously-correct oracles on random walks that
//! reveal random patches of a random ground truth (with cells flipping class, as probabilistic
//! belief maps do).

use explore::{FrontierUpkeep, Region, frontiers_from_scratch};
use grid::{Grid, Occ};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Brute force: known Free and no known Occupied cell closer than the clearance (centre
/// distance < clearance: a cell exactly the clearance away is kept, as Holz's d_max keeps it).
fn brute_traversable(known: &Grid<Occ>, clearance: f64) -> Vec<bool> {
    let w = known.width();
    (0..known.len())
        .map(|i| {
            let c = known.cell(i);
            known[i] == Occ::Free
                && !(0..known.len())
                    .any(|j| known[j] == Occ::Occupied && c.dist(known.cell(j)) < clearance)
        })
        .inspect(|_| debug_assert!(w > 0))
        .collect()
}

/// Brute force frontier cells, sorted.
fn brute_frontiers(known: &Grid<Occ>, trav: &[bool]) -> Vec<u32> {
    (0..known.len())
        .filter(|&i| {
            let c = known.cell(i);
            trav[i]
                && (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        (dx, dy) != (0, 0)
                            && known.try_get(c.offset(dx, dy)) == Some(&Occ::Unknown)
                            && !(dx != 0
                                && dy != 0
                                && known.try_get(c.offset(dx, 0)) == Some(&Occ::Occupied)
                                && known.try_get(c.offset(0, dy)) == Some(&Occ::Occupied))
                    })
                })
        })
        .map(|i| i as u32)
        .collect()
}

/// Brute-force labelling of 8-connected components by repeated min-label propagation.
fn brute_regions(known: &Grid<Occ>, frontier: &[u32], min_size: usize) -> Vec<Region> {
    let n = known.len();
    let mut is_f = vec![false; n];
    for &f in frontier {
        is_f[f as usize] = true;
    }
    let mut label: Vec<usize> = (0..n).collect();
    loop {
        let mut changed = false;
        for i in 0..n {
            if !is_f[i] {
                continue;
            }
            let c = known.cell(i);
            for j in 0..n {
                if is_f[j] && c.is_neighbour8(known.cell(j)) && label[j] < label[i] {
                    label[i] = label[j];
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let mut out = Vec::new();
    for root in 0..n {
        if !is_f[root] || label[root] != root {
            continue;
        }
        let cells: Vec<u32> = (0..n)
            .filter(|&i| is_f[i] && label[i] == root)
            .map(|i| i as u32)
            .collect();
        if cells.len() < min_size {
            continue;
        }
        let k = cells.len() as f64;
        let cx = cells
            .iter()
            .map(|&c| known.cell(c as usize).x as f64)
            .sum::<f64>()
            / k;
        let cy = cells
            .iter()
            .map(|&c| known.cell(c as usize).y as f64)
            .sum::<f64>()
            / k;
        // nearest to the centroid, ties lowest index
        let d = |c: u32| {
            let p = known.cell(c as usize);
            (p.x as f64 - cx).powi(2) + (p.y as f64 - cy).powi(2)
        };
        let mut rep = cells[0];
        for &c in &cells {
            if d(c) < d(rep) {
                rep = c;
            }
        }
        out.push(Region {
            cells,
            centroid: (cx, cy),
            representative: rep,
        });
    }
    out
}

fn random_truth(rng: &mut Pcg64Mcg, w: usize, h: usize) -> Grid<Occ> {
    let data = (0..w * h)
        .map(|_| match rng.random_range(0..100) {
            0..4 => Occ::Unknown,
            4..26 => Occ::Occupied,
            _ => Occ::Free,
        })
        .collect();
    Grid::from_vec(w, h, data).unwrap()
}

/// Run a random walk; after every step compare the upkeep with the oracles.
fn check_walk(
    w: usize,
    h: usize,
    clearance: f64,
    seed: u64,
    flips: bool,
) -> Result<(), TestCaseError> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let truth = random_truth(&mut rng, w, h);
    let mut known = Grid::new(w, h, Occ::Unknown);
    let mut up = FrontierUpkeep::new(w, h, clearance);
    let (mut x, mut y) = (rng.random_range(0..w) as i32, rng.random_range(0..h) as i32);
    let mut changed = Vec::new();
    let mut regions = Vec::new();
    for _step in 0..12 {
        x = (x + rng.random_range(-3..=3)).clamp(0, w as i32 - 1);
        y = (y + rng.random_range(-3..=3)).clamp(0, h as i32 - 1);
        changed.clear();
        let disk = rng.random_bool(0.5);
        let r = rng.random_range(0..=5i32);
        let (rx, ry) = (rng.random_range(0..=4i32), rng.random_range(0..=4i32));
        for i in 0..w * h {
            let c = known.cell(i);
            let (dx, dy) = (c.x - x, c.y - y);
            let inside = if disk {
                dx * dx + dy * dy <= r * r
            } else {
                dx.abs() <= rx && dy.abs() <= ry
            };
            if inside && known[i] != truth[i] {
                known[i] = truth[i];
                changed.push(i as u32);
            }
        }
        if flips {
            for _ in 0..rng.random_range(0..4) {
                let i = rng.random_range(0..w * h);
                let new = match rng.random_range(0..3) {
                    0 => Occ::Unknown,
                    1 => Occ::Free,
                    _ => Occ::Occupied,
                };
                // an Occupied cell that turns Free is the common case: bias towards it
                let new = if known[i] == Occ::Occupied && rng.random_bool(0.5) {
                    Occ::Free
                } else {
                    new
                };
                if known[i] != new {
                    known[i] = new;
                    changed.push(i as u32);
                }
            }
            // duplicates and unchanged cells in `changed` must be harmless
            if !changed.is_empty() && rng.random_bool(0.3) {
                changed.push(changed[0]);
                changed.push(rng.random_range(0..(w * h) as u32));
            }
        }
        up.update(&known, &changed);

        let trav = brute_traversable(&known, clearance);
        for (i, &t) in trav.iter().enumerate() {
            prop_assert_eq!(up.is_traversable(&known, i), t, "traversable({})", i);
            prop_assert_eq!(up.trav.passable().contains(i), t, "passable bit {}", i);
        }
        let want = brute_frontiers(&known, &trav);
        let scratch = frontiers_from_scratch(&known, &up.trav);
        prop_assert_eq!(&scratch, &want);
        let mut got = up.frontiers.cells().to_vec();
        got.sort_unstable();
        prop_assert_eq!(&got, &want);
        prop_assert_eq!(up.frontiers.len(), want.len());
        for i in 0..w * h {
            prop_assert_eq!(
                up.frontiers.contains(i),
                want.binary_search(&(i as u32)).is_ok()
            );
        }

        let min_size = rng.random_range(0..4);
        up.regions(w, min_size, &mut regions);
        let want_regions = brute_regions(&known, &want, min_size);
        prop_assert_eq!(regions.len(), want_regions.len());
        for (g, b) in regions.iter().zip(&want_regions) {
            prop_assert_eq!(&g.cells, &b.cells);
            prop_assert!((g.centroid.0 - b.centroid.0).abs() < 1e-9);
            prop_assert!((g.centroid.1 - b.centroid.1).abs() < 1e-9);
            prop_assert_eq!(g.representative, b.representative);
        }
    }
    // a full rebuild agrees with the incremental state
    let mut fresh = FrontierUpkeep::new(w, h, clearance);
    fresh.rebuild(&known);
    let mut a = fresh.frontiers.cells().to_vec();
    a.sort_unstable();
    let mut b = up.frontiers.cells().to_vec();
    b.sort_unstable();
    prop_assert_eq!(a, b);
    Ok(())
}

/// Clearances in cells: 9 has the largest disk kept in byte counts (253 cells), 9.5 one of
/// 293 cells, kept in wider counts.
const CLEARANCES: [f64; 7] = [0.0, 1.0, 1.5, 2.5, std::f64::consts::SQRT_2, 9.0, 9.5];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn incremental_equals_scratch_on_reveal_walks(
        w in 1usize..20, h in 1usize..20, ci in 0usize..CLEARANCES.len(), seed in any::<u64>()
    ) {
        check_walk(w, h, CLEARANCES[ci], seed, false)?;
    }

    #[test]
    fn incremental_equals_scratch_with_flips(
        w in 1usize..20, h in 1usize..20, ci in 0usize..CLEARANCES.len(), seed in any::<u64>()
    ) {
        check_walk(w, h, CLEARANCES[ci], seed, true)?;
    }
}

#[test]
fn worked_example_regions() {
    // ? = unknown, . = free, # = occupied; clearance 0
    // row 0: . . ? . .
    // row 1: . . # . .
    // row 2: . . . . .
    let s = ["..?..", "..#..", "....."];
    let data = s
        .iter()
        .flat_map(|r| r.chars())
        .map(|c| match c {
            '?' => Occ::Unknown,
            '#' => Occ::Occupied,
            _ => Occ::Free,
        })
        .collect();
    let known = Grid::from_vec(5, 3, data).unwrap();
    let mut up = FrontierUpkeep::new(5, 3, 0.0);
    up.rebuild(&known);
    let mut f = up.frontiers.cells().to_vec();
    f.sort_unstable();
    // neighbours of (2,0): (1,0),(3,0),(1,1),(3,1); (2,1) is occupied
    assert_eq!(f, [1, 3, 6, 8]);
    let mut regions = Vec::new();
    up.regions(5, 1, &mut regions);
    // (1,0),(1,1) and (3,0),(3,1) are two regions: x = 2 between them is unknown / occupied
    assert_eq!(regions.len(), 2);
    assert_eq!(regions[0].cells, [1, 6]);
    assert_eq!(regions[0].centroid, (1.0, 0.5));
    assert_eq!(regions[0].representative, 1); // tie between (1,0) and (1,1): lowest index
    assert_eq!(regions[1].cells, [3, 8]);
    up.regions(5, 3, &mut regions);
    assert!(regions.is_empty());
    // clearance 1 keeps the obstacle's 4-neighbours, exactly 1 away (Holz's d_max)
    let mut up = FrontierUpkeep::new(5, 3, 1.0);
    up.rebuild(&known);
    let mut f = up.frontiers.cells().to_vec();
    f.sort_unstable();
    assert_eq!(f, [1, 3, 6, 8]);
    // clearance 1.2 blocks the 4-neighbours; (1,0) and (3,0) are √2 away
    let mut up = FrontierUpkeep::new(5, 3, 1.2);
    up.rebuild(&known);
    let mut f = up.frontiers.cells().to_vec();
    f.sort_unstable();
    assert_eq!(f, [1, 3]);
    // so does √2, which keeps them, exactly √2 away
    let mut up = FrontierUpkeep::new(5, 3, std::f64::consts::SQRT_2);
    up.rebuild(&known);
    let mut f = up.frontiers.cells().to_vec();
    f.sort_unstable();
    assert_eq!(f, [1, 3]);
    // clearance 1.5 blocks them too: no frontier left
    let mut up = FrontierUpkeep::new(5, 3, 1.5);
    up.rebuild(&known);
    assert!(up.frontiers.is_empty());
}

/// A random belief: each cell Unknown, Occupied or Free with the given percentages.
fn random_belief(rng: &mut Pcg64Mcg, w: usize, h: usize, unknown: u32, occupied: u32) -> Grid<Occ> {
    let data = (0..w * h)
        .map(|_| {
            let r = rng.random_range(0..100);
            if r < unknown {
                Occ::Unknown
            } else if r < unknown + occupied {
                Occ::Occupied
            } else {
                Occ::Free
            }
        })
        .collect();
    Grid::from_vec(w, h, data).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// The from-scratch rebuild (row spans, no touched list, zeroed counts reused) gives the
    /// brute-force traversability and exactly the oracle's frontier cells in index order, on a
    /// fresh upkeep and on one that has already counted another map.
    #[test]
    fn rebuild_equals_the_oracles(
        w in 1usize..24, h in 1usize..24, ci in 0usize..CLEARANCES.len(),
        unknown in 0u32..60, occupied in 0u32..40, seed in any::<u64>()
    ) {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let clearance = CLEARANCES[ci];
        let mut up = FrontierUpkeep::new(w, h, clearance);
        for _ in 0..2 {
            let known = random_belief(&mut rng, w, h, unknown, occupied);
            up.rebuild(&known);
            let trav = brute_traversable(&known, clearance);
            for (i, &t) in trav.iter().enumerate() {
                prop_assert_eq!(up.is_traversable(&known, i), t, "traversable({})", i);
                prop_assert_eq!(up.trav.passable().contains(i), t, "passable bit {}", i);
            }
            let want = brute_frontiers(&known, &trav);
            prop_assert_eq!(up.frontiers.cells(), &want[..]);
            prop_assert_eq!(frontiers_from_scratch(&known, &up.trav), want);
            // and incremental updates carry on from the rebuilt state
            let next = random_belief(&mut rng, w, h, unknown, occupied);
            let changed: Vec<u32> = (0..w * h)
                .filter(|&i| next[i] != known[i])
                .map(|i| i as u32)
                .collect();
            up.update(&next, &changed);
            let trav = brute_traversable(&next, clearance);
            for (i, &t) in trav.iter().enumerate() {
                prop_assert_eq!(up.trav.passable().contains(i), t, "passable bit {}", i);
            }
            let mut got = up.frontiers.cells().to_vec();
            got.sort_unstable();
            prop_assert_eq!(got, brute_frontiers(&next, &trav));
        }
    }
}
