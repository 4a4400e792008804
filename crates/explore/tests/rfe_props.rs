//! Faigl & Kulich's RFE: n_r per edge, representatives are snapped Lloyd fixed points of
//! their edge's cells, determinism per seed.

use explore::Reachability;
use explore::Region;
use explore::candidates::rfe::{DEFAULT_MIN_EDGE, representatives_for};
use explore::candidates::{CandidateKind, CandidateSet};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;

mod common;
#[allow(unused_imports)]
use common::*;

fn run_rfe(fx: &mut Fixture, min_edge: usize) -> Vec<u32> {
    let n = fx.known.len();
    let mut out = CandidateSet::new(n);
    let mut ctx = fx.ctx();
    CandidateKind::Rfe { min_edge }.generate(&mut ctx, &mut out);
    out.cells().to_vec()
}

#[test]
fn n_r_follows_the_formula() {
    assert_eq!(DEFAULT_MIN_EDGE, 1);
    // 1 + floor(|F| / (1.8 ρ) + 0.5)
    assert_eq!(representatives_for(3, 5.0), 1);
    assert_eq!(representatives_for(10, 5.0), 2);
    assert_eq!(representatives_for(38, 5.0), 5);
    assert_eq!(representatives_for(4, 1.0), 3);
    assert_eq!(representatives_for(7, 0.0), 7);
}

#[test]
fn straight_edge_worked_example() {
    // A 40 × 40 room, known for x < 20: the frontier is the column x = 19, y = 1..=38
    // (38 cells), so with ρ = 5 there are 5 representatives, spread along the column.
    let (w, h) = (40, 40);
    let mut g = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let c = g.cell(i);
        if c.x == 0 || c.y == 0 || c.y == 39 {
            g[i] = Occ::Occupied;
        } else if c.x >= 20 {
            g[i] = Occ::Unknown;
        }
    }
    let robot = g.index(Cell::new(5, 20)) as u32;
    let mut fx = Fixture::new(g, vec![robot], 5.0, 7);
    let got = run_rfe(&mut fx, 1);
    assert_eq!(got.len(), 5);
    let mut ys: Vec<i32> = got.iter().map(|&c| fx.known.cell(c as usize).y).collect();
    assert!(got.iter().all(|&c| fx.known.cell(c as usize).x == 19));
    ys.sort_unstable();
    // Lloyd on 38 evenly spaced cells gives clusters of 7–8 cells: consecutive
    // representatives 6–9 rows apart.
    for pair in ys.windows(2) {
        assert!((6..=9).contains(&(pair[1] - pair[0])), "{ys:?}");
    }
    // Same seed, same candidates.
    let mut fx2 = Fixture::new(fx.known.clone(), vec![robot], 5.0, 7);
    assert_eq!(run_rfe(&mut fx2, 1), got);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn representatives_are_snapped_lloyd_fixed_points(
        bits in prop::collection::vec(0u8..100, 37),
        cut in 6usize..18,
        range in 0.5f64..6.0,
        min_edge in 1usize..4,
        seed in 0u64..100,
    ) {
        let (w, h) = (20, 20);
        let (known, mut up) = random_upkept(w, h, &bits, cut);
        let Some(robot) = largest_component_cell(&known, &up) else {
            return Ok(());
        };
        let mut fx = Fixture::new(known.clone(), vec![robot as u32], range, seed);
        let got = run_rfe(&mut fx, min_edge);
        let reps = fx.memory.rfe.representatives().to_vec();
        // Oracle inputs: edges and reachability recomputed here.
        let mut reach = Reachability::new(w, h);
        reach.compute(robot, |i| up.is_traversable(&known, i));
        let mut edges: Vec<Region> = Vec::new();
        up.regions(w, min_edge, &mut edges);
        let kept_of = |e: &Region| -> Vec<u32> {
            e.cells.iter().copied().filter(|&c| reach.cost(c as usize).is_some()).collect()
        };
        let mut any_big = edges.iter().any(|e| !kept_of(e).is_empty());
        if !any_big && min_edge > 1 {
            up.regions(w, 1, &mut edges); // the fallback to smaller edges
            any_big = edges.iter().any(|e| !kept_of(e).is_empty());
        }
        let mut expect_cells: Vec<u32> = Vec::new();
        for e in &edges {
            let kept = kept_of(e);
            let mine: Vec<_> = reps.iter().filter(|r| r.edge == e.cells[0]).collect();
            if kept.is_empty() {
                prop_assert!(mine.is_empty());
                continue;
            }
            prop_assert_eq!(mine.len(), representatives_for(e.cells.len(), range).min(kept.len()));
            let centres: Vec<(f64, f64)> = mine.iter().map(|r| r.centre).collect();
            let xy = |c: u32| ((c as usize % w) as f64, (c as usize / w) as f64);
            // Lloyd fixed point: every centre is the mean of the kept cells nearest to it.
            for (j, cj) in centres.iter().enumerate() {
                let mut s = (0.0, 0.0, 0.0);
                for &c in &kept {
                    let p = xy(c);
                    if explore::kmeans::nearest(&centres, p) == j {
                        s = (s.0 + p.0, s.1 + p.1, s.2 + 1.0);
                    }
                }
                prop_assert!(s.2 > 0.0, "empty cluster");
                prop_assert!((s.0 / s.2 - cj.0).abs() < 1e-9 && (s.1 / s.2 - cj.1).abs() < 1e-9);
            }
            // Snapped to the nearest kept cell (ties: lower index).
            for r in &mine {
                let d = |c: u32| { let p = xy(c); (p.0 - r.centre.0).powi(2) + (p.1 - r.centre.1).powi(2) };
                let best = kept.iter().copied().min_by(|&a, &b| d(a).total_cmp(&d(b)).then(a.cmp(&b)));
                prop_assert_eq!(Some(r.cell), best);
                if !expect_cells.contains(&r.cell) {
                    expect_cells.push(r.cell);
                }
            }
        }
        prop_assert_eq!(&got, &expect_cells);
        prop_assert_eq!(got.is_empty(), !any_big);
        // Deterministic per seed.
        let mut fx2 = Fixture::new(known, vec![robot as u32], range, seed);
        prop_assert_eq!(run_rfe(&mut fx2, min_edge), got);
    }
}
