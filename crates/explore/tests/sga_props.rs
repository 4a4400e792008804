//! Solanas & Garcia's assignment (Faigl & Kulich Eq. 1): the first clustering equals a
//! direct k-means of the unknown cells from the map centre, clusters are matched to the
//! robots optimally, and goals equal a slow recomputation of Eq. 1 with its penalties.

use explore::Reachability;
use explore::assign::AssignerKind;
use explore::assign::sga::block_side;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::Goal;
use explore::kmeans::{Init, KMeans, nearest};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

mod common;
#[allow(unused_imports)]
use common::*;

fn decide(fx: &mut Fixture) -> (CandidateSet, Vec<Option<Goal>>) {
    let n = fx.known.len();
    let m = fx.robots.len();
    let mut cands = CandidateSet::new(n);
    let mut out = vec![None; m];
    let mut ctx = fx.ctx();
    CandidateKind::AllFrontiers.generate(&mut ctx, &mut cands);
    AssignerKind::Sga.assign(&mut ctx, &cands, &mut out);
    (cands, out)
}

/// Eq. 1 with penalties, recomputed naively from the centres.
fn oracle(fx: &Fixture, cands: &[u32], centres: &[(f64, f64)]) -> Vec<Option<u32>> {
    let (w, h) = (fx.known.width(), fx.known.height());
    let delta = ((w * w + h * h) as f64).sqrt();
    let rho = fx.range;
    let xy = |c: u32| ((c as usize % w) as f64, (c as usize / w) as f64);
    let d2 = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2);
    let mut o = vec![0.0; cands.len()];
    let add = |o: &mut Vec<f64>, g: u32| {
        for (k, &c) in cands.iter().enumerate() {
            if d2(xy(c), xy(g)) <= rho * rho {
                o[k] += 2.0 * rho;
            }
        }
    };
    let m = fx.robots.len();
    for r in 0..m {
        if !fx.deciding[r]
            && let Some(g) = fx.goals[r]
        {
            add(&mut o, g);
        }
    }
    let mut out = vec![None; m];
    for r in 0..m {
        if !fx.deciding[r] {
            continue;
        }
        let mut reach = Reachability::new(w, h);
        reach.compute(fx.robots[r] as usize, |i| {
            fx.upkeep.is_traversable(&fx.known, i)
        });
        let mut best: Option<(f64, u32)> = None;
        for (k, &c) in cands.iter().enumerate() {
            let Some(path) = reach.cost(c as usize) else {
                continue;
            };
            let cost = if nearest(centres, xy(c)) == r {
                path + o[k]
            } else {
                delta + d2(xy(c), centres[r]) + o[k]
            };
            if best.is_none_or(|(b, _)| cost < b) {
                best = Some((cost, c));
            }
        }
        if let Some((_, g)) = best {
            out[r] = Some(g);
            add(&mut o, g);
        }
    }
    out
}

#[test]
fn block_sides() {
    assert_eq!(block_side(64, 64), 1);
    assert_eq!(block_side(65, 64), 2);
    assert_eq!(block_side(1000, 1000), 16);
}

#[test]
fn two_rooms_worked_example() {
    // Two unknown halves left and right of a known corridor column band; robots in the
    // middle: one cluster per side, each robot takes a frontier on its own side.
    let (w, h) = (30, 10);
    let mut g = Grid::new(w, h, Occ::Unknown);
    for y in 0..h as i32 {
        for x in 12..18 {
            g.set(Cell::new(x, y), Occ::Free);
        }
    }
    let r0 = g.index(Cell::new(13, 5)) as u32;
    let r1 = g.index(Cell::new(16, 5)) as u32;
    let mut fx = Fixture::new(g, vec![r0, r1], 3.0, 1);
    let (_, out) = decide(&mut fx);
    let c = fx.memory.sga.centres().to_vec();
    assert!(c[0].0 < 12.0 && c[1].0 > 17.0, "{c:?}");
    let x = |o: Option<Goal>| o.expect("goal").cell as usize % w;
    assert_eq!(x(out[0]), 12);
    assert_eq!(x(out[1]), 17);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn first_clustering_and_eq1(
        bits in prop::collection::vec(0u8..100, 37),
        cut in 6usize..18,
        m in 1usize..5,
        keep in 0usize..5,
        seed in 0u64..100,
        range in 1.0f64..6.0,
    ) {
        let (w, h) = (20, 20);
        let Some((known, _, robots)) = random_team(w, h, &bits, cut, m) else {
            return Ok(());
        };
        let mut fx = Fixture::new(known.clone(), robots.clone(), range, seed);
        let (cands, out) = decide(&mut fx);
        // First clustering: a direct k-means of the unknown cells from the circle round
        // the map centre, then matched to the robots at least total distance.
        let pts: Vec<(f64, f64)> = (0..w * h)
            .filter(|&i| known[i] == Occ::Unknown)
            .map(|i| ((i % w) as f64, (i / w) as f64))
            .collect();
        let init: Vec<(f64, f64)> = (0..m)
            .map(|j| {
                let a = std::f64::consts::TAU * j as f64 / m as f64;
                (w as f64 / 2.0 + a.cos(), h as f64 / 2.0 + a.sin())
            })
            .collect();
        let mut km = KMeans::new();
        km.fit(&pts, None, Init::Centres(&init), &mut Pcg64Mcg::seed_from_u64(0));
        let got = fx.memory.sga.centres().to_vec();
        let mut a = got.clone();
        let mut b = km.centres().to_vec();
        let key = |p: &(f64, f64), q: &(f64, f64)| p.0.total_cmp(&q.0).then(p.1.total_cmp(&q.1));
        a.sort_by(key);
        b.sort_by(key);
        for (p, q) in a.iter().zip(&b) {
            prop_assert!((p.0 - q.0).abs() < 1e-9 && (p.1 - q.1).abs() < 1e-9, "{:?} vs {:?}", a, b);
        }
        // Matching optimal: no permutation of the centres has a smaller total distance.
        let dist = |r: usize, c: (f64, f64)| {
            let p = ((robots[r] as usize % w) as f64, (robots[r] as usize / w) as f64);
            ((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2)).sqrt()
        };
        let total: f64 = (0..m).map(|r| dist(r, got[r])).sum();
        let mut perm: Vec<usize> = (0..m).collect();
        let mut best = f64::INFINITY;
        permute(&mut perm, 0, &mut |p| {
            best = best.min((0..m).map(|r| dist(r, got[p[r]])).sum());
        });
        prop_assert!(total <= best + 1e-9);
        // Goals equal Eq. 1 recomputed.
        let goals: Vec<Option<u32>> = out.iter().map(|g| g.map(|g| g.cell)).collect();
        prop_assert_eq!(&goals, &oracle(&fx, cands.cells(), &got));
        // A second decision with one robot keeping its goal: centres from the previous ones.
        if keep < m {
            fx.deciding[keep] = false;
            fx.goals[keep] = goals[keep];
        }
        let (cands2, out2) = decide(&mut fx);
        let got2 = fx.memory.sga.centres().to_vec();
        let mut km2 = KMeans::new();
        km2.fit(&pts, None, Init::Centres(&got), &mut Pcg64Mcg::seed_from_u64(0));
        prop_assert_eq!(&got2[..], km2.centres());
        let goals2: Vec<Option<u32>> = out2.iter().map(|g| g.map(|g| g.cell)).collect();
        prop_assert_eq!(&goals2, &oracle(&fx, cands2.cells(), &got2));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// On maps large enough that a robot's cluster lies far from goals of other clusters
    /// (each robot's search is guided toward its own cluster's goals), the goals are still
    /// Eq. 1's.
    #[test]
    fn eq1_on_larger_maps(
        bits in prop::collection::vec(0u8..100, 53),
        cut in 20usize..60,
        m in 2usize..5,
        seed in 0u64..100,
        range in 1.0f64..6.0,
    ) {
        let (w, h) = (72, 40);
        let Some((known, _, robots)) = random_team(w, h, &bits, cut, m) else {
            return Ok(());
        };
        let mut fx = Fixture::new(known, robots, range, seed);
        let (cands, out) = decide(&mut fx);
        let centres = fx.memory.sga.centres().to_vec();
        let goals: Vec<Option<u32>> = out.iter().map(|g| g.map(|g| g.cell)).collect();
        prop_assert_eq!(&goals, &oracle(&fx, cands.cells(), &centres));
        let mut full = Reachability::new(w, h);
        for (r, g) in out.iter().enumerate() {
            if let Some(g) = g {
                full.compute(fx.robots[r] as usize, |i| fx.upkeep.is_traversable(&fx.known, i));
                prop_assert_eq!(Some(g.cost.to_bits()), full.cost(g.cell as usize).map(f64::to_bits));
            }
        }
    }
}

fn permute(p: &mut Vec<usize>, k: usize, f: &mut dyn FnMut(&[usize])) {
    if k == p.len() {
        f(p);
        return;
    }
    for i in k..p.len() {
        p.swap(k, i);
        permute(p, k + 1, f);
        p.swap(k, i);
    }
}
