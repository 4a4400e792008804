//! Faigl & Kulich's CC (Algorithm 1) against a slow oracle: covering sets by the direct
//! segment test from each candidate to each unknown cell next to a frontier, and the
//! greedy cover recomputed naively.

use explore::Reachability;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::{FrontierUpkeep, frontiers_from_scratch};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{los_visible, segment_clear};

mod common;
#[allow(unused_imports)]
use common::*;

/// Whether the laser at `c` (range `r`) sees an unknown 8-neighbour of frontier cell `f`.
fn covers(known: &Grid<Occ>, c: u32, f: u32, r: f64) -> bool {
    known.neighbours8(f as usize).any(|u| {
        known[u] == Occ::Unknown && los_visible(known, known.cell(c as usize), known.cell(u), r)
    })
}

/// The frontier cells to cover and the cells eligible as candidates (traversable, reached
/// from `robot`, on no list), both in index order.
fn frontiers_and_eligible(fx: &Fixture, robot: u32) -> (Vec<u32>, Vec<u32>) {
    let known = &fx.known;
    let (w, h) = (known.width(), known.height());
    let trav = |i: usize| fx.upkeep.is_traversable(known, i);
    let mut reach = Reachability::new(w, h);
    reach.compute(robot as usize, trav);
    let ok = |i: u32| !fx.lists.is_excluded(i) && reach.cost(i as usize).is_some();
    let mut front: Vec<u32> = frontiers_from_scratch(known, &fx.upkeep.trav)
        .into_iter()
        .filter(|&f| ok(f))
        .collect();
    front.sort_unstable();
    let cells: Vec<u32> = (0..(w * h) as u32)
        .filter(|&c| trav(c as usize) && ok(c))
        .collect();
    (front, cells)
}

/// The slow Algorithm 1: every eligible cell against every frontier by `los_visible`.
fn oracle(fx: &Fixture, robot: u32) -> Vec<(u32, Vec<u32>)> {
    oracle_of(fx, robot, None)
}

/// [`oracle`] covering only the frontier cells in `only` (all if `None`).
fn oracle_of(fx: &Fixture, robot: u32, only: Option<&[u32]>) -> Vec<(u32, Vec<u32>)> {
    let known = &fx.known;
    let (w, h) = (known.width(), known.height());
    let (mut front, cells) = frontiers_and_eligible(fx, robot);
    if let Some(only) = only {
        front.retain(|f| only.contains(f));
    }
    let r = 0.8 * fx.range;
    let sees: Vec<Vec<u32>> = cells
        .iter()
        .map(|&c| {
            front
                .iter()
                .copied()
                .filter(|&f| covers(known, c, f, r))
                .collect()
        })
        .collect();
    let mut covered = vec![false; w * h];
    let mut out = Vec::new();
    loop {
        let mut best: Option<(usize, usize)> = None; // (count, index into cells)
        for (k, s) in sees.iter().enumerate() {
            let cnt = s.iter().filter(|&&f| !covered[f as usize]).count();
            if cnt > 0 && best.is_none_or(|(b, _)| cnt > b) {
                best = Some((cnt, k));
            }
        }
        let Some((_, k)) = best else { break };
        let credit: Vec<u32> = sees[k]
            .iter()
            .copied()
            .filter(|&f| !covered[f as usize])
            .collect();
        for &f in &credit {
            covered[f as usize] = true;
        }
        out.push((cells[k], credit));
    }
    out
}

/// The slow Algorithm 1 on blocks of `b × b` cells, as CC computes it on maps finer than
/// 0.1 m: blocks occupied if any cell is, else unknown if any is, else free; the frontier
/// cells grouped by block; a group covered from a free block that sees, within 0.8 ρ / b, a
/// block holding an unknown 8-neighbour of one of its cells; the greedy order by the count
/// of groups, ties to the block's eligible cell nearest its centre (then the lower index);
/// a block chosen through its first eligible cell, in that order, that sees within 0.8 ρ
/// (cell by cell) an unknown 8-neighbour of a frontier cell of the groups it newly covers,
/// and dropped if none does; then the cell-by-cell [`oracle`] for the frontier cells of the
/// groups left uncovered, its candidates appended unless already chosen.
fn block_oracle(fx: &Fixture, robot: u32, b: usize) -> Vec<(u32, Vec<u32>)> {
    let known = &fx.known;
    let (w, h) = (known.width(), known.height());
    let (cw, ch) = (w.div_ceil(b), h.div_ceil(b));
    let blk = |i: usize| (i / w / b) * cw + (i % w) / b;
    let mut coarse = Grid::new(cw, ch, Occ::Free);
    for i in 0..w * h {
        match known[i] {
            Occ::Occupied => coarse[blk(i)] = Occ::Occupied,
            Occ::Unknown if coarse[blk(i)] != Occ::Occupied => coarse[blk(i)] = Occ::Unknown,
            _ => {}
        }
    }
    let (front, cells) = frontiers_and_eligible(fx, robot);
    let mut keys: std::collections::BTreeMap<usize, Vec<u32>> = Default::default();
    for &f in &front {
        keys.entry(blk(f as usize)).or_default().push(f);
    }
    let groups: Vec<Vec<u32>> = keys.values().cloned().collect();
    let targets: Vec<Vec<usize>> = groups
        .iter()
        .map(|g| {
            let mut t: Vec<usize> = g
                .iter()
                .flat_map(|&f| known.neighbours8(f as usize))
                .filter(|&u| known[u] == Occ::Unknown)
                .map(blk)
                .collect();
            t.sort_unstable();
            t.dedup();
            t
        })
        .collect();
    // Each free block's eligible cells, nearest the centre first; the first is its
    // representative.
    let mut reps: Vec<(u32, usize)> = Vec::new();
    let mut order: std::collections::HashMap<usize, Vec<u32>> = Default::default();
    for c in 0..cw * ch {
        if coarse[c] != Occ::Free {
            continue;
        }
        let (bx, by) = ((c % cw) * b, (c / cw) * b);
        let centre = ((2 * bx + b - 1) as i64, (2 * by + b - 1) as i64);
        let mut mine: Vec<u32> = cells
            .iter()
            .copied()
            .filter(|&i| blk(i as usize) == c)
            .collect();
        mine.sort_by_key(|&i| {
            let (x, y) = ((i as usize % w) as i64, (i as usize / w) as i64);
            let (dx, dy) = (2 * x - centre.0, 2 * y - centre.1);
            (dx * dx + dy * dy, i)
        });
        if let Some(&rep) = mine.first() {
            reps.push((rep, c));
            order.insert(c, mine);
        }
    }
    reps.sort_unstable();
    let r = 0.8 * fx.range / b as f64;
    let sees: Vec<Vec<usize>> = reps
        .iter()
        .map(|&(_, c)| {
            (0..groups.len())
                .filter(|&k| {
                    targets[k]
                        .iter()
                        .any(|&t| los_visible(&coarse, coarse.cell(c), coarse.cell(t), r))
                })
                .collect()
        })
        .collect();
    let mut covered = vec![false; groups.len()];
    let mut dropped = vec![false; reps.len()];
    let mut out = Vec::new();
    loop {
        let mut best: Option<(usize, usize)> = None;
        for (k, s) in sees.iter().enumerate() {
            let cnt = s.iter().filter(|&&g| !covered[g]).count();
            if !dropped[k] && cnt > 0 && best.is_none_or(|(bc, _)| cnt > bc) {
                best = Some((cnt, k));
            }
        }
        let Some((_, k)) = best else { break };
        let new: Vec<usize> = sees[k].iter().copied().filter(|&g| !covered[g]).collect();
        let pick = order[&reps[k].1].iter().copied().find(|&c| {
            new.iter()
                .flat_map(|&g| groups[g].iter())
                .any(|&f| covers(known, c, f, 0.8 * fx.range))
        });
        let Some(pick) = pick else {
            dropped[k] = true;
            continue;
        };
        let mut credit = Vec::new();
        for g in new {
            covered[g] = true;
            credit.extend_from_slice(&groups[g]);
        }
        out.push((pick, credit));
    }
    let left: Vec<u32> = (0..groups.len())
        .filter(|&g| !covered[g])
        .flat_map(|g| groups[g].iter().copied())
        .collect();
    if !left.is_empty() {
        for (c, credit) in oracle_of(fx, robot, Some(&left)) {
            if !out.iter().any(|(o, _)| *o == c) {
                out.push((c, credit));
            }
        }
    }
    out
}

/// A CC fixture on a random `w × h` map: one robot in the largest component, the cells
/// of `visited` (but the robot's) on the visited list; `None` when no cell is free.
fn random_fixture(
    (w, h): (usize, usize),
    bits: &[u8],
    cut: usize,
    range: f64,
    resolution: f64,
    visited: &[usize],
) -> Option<(Fixture, usize)> {
    let known = random_known(w, h, bits, cut);
    let mut up = FrontierUpkeep::new(w, h, 0.0);
    up.rebuild(&known);
    let robot = largest_component_cell(&known, &up)?;
    let mut fx = Fixture::new(known, vec![robot as u32], range, 3);
    fx.resolution = resolution;
    for &v in visited {
        if v != robot {
            fx.lists.mark_visited(v as u32);
        }
    }
    Some((fx, robot))
}

/// Run CC on the fixture: the candidates in the order chosen, each with the frontier cells
/// credited to it, and the candidate set's cells.
fn run_cc(fx: &mut Fixture) -> (Vec<(u32, Vec<u32>)>, Vec<u32>) {
    let mut out = CandidateSet::new(fx.known.len());
    let mut ctx = fx.ctx();
    CandidateKind::Coverage.generate(&mut ctx, &mut out);
    let credits = fx
        .memory
        .coverage
        .credits()
        .map(|(c, s)| (c, s.to_vec()))
        .collect();
    (credits, out.cells().to_vec())
}

#[test]
fn corridor_worked_example() {
    // A 3-wide corridor, known for x < 12, unknown beyond: the frontier is the column
    // x = 11 (3 cells). With ρ = 5 (0.8 ρ = 4), the lowest cell that sees unknown space
    // next to all three wins.
    let (w, h) = (20, 5);
    let mut g = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let c = g.cell(i);
        if c.y == 0 || c.y == 4 {
            g[i] = Occ::Occupied;
        } else if c.x >= 12 {
            g[i] = Occ::Unknown;
        }
    }
    let robot = g.index(Cell::new(1, 2)) as u32;
    let mut fx = Fixture::new(g, vec![robot], 5.0, 1);
    let (credits, cells) = run_cc(&mut fx);
    assert_eq!(credits.len(), 1);
    // (8, 1) sees (11, 3) but none of its unknown neighbours (12, 2), (12, 3) within 4
    // (squared distances 17, 20); (9, 1) sees (12, 1) and (12, 2), next to all three.
    assert_eq!(fx.known.cell(credits[0].0 as usize), Cell::new(9, 1));
    assert_eq!(credits, oracle(&fx, robot));
    assert_eq!(cells, [credits[0].0]);
}

/// A walled room, all known but the given cells, with the robot in the middle.
fn room_with_unknown(unknown: &[(i32, i32)], range: f64) -> Fixture {
    let (w, h) = (12, 10);
    let mut g = Grid::new(w, h, Occ::Free);
    for i in 0..w * h {
        let c = g.cell(i);
        if c.x == 0 || c.y == 0 || c.x == w as i32 - 1 || c.y == h as i32 - 1 {
            g[i] = Occ::Occupied;
        }
    }
    for &(x, y) in unknown {
        let i = g.index(Cell::new(x, y));
        g[i] = Occ::Unknown;
    }
    let robot = g.index(Cell::new(6, 5)) as u32;
    Fixture::new(g, vec![robot], range, 1)
}

#[test]
fn cc_sends_robots_where_they_see_the_unknown_not_only_the_frontier() {
    // Regression: a wall cell seen edge-on stays unknown, and the free cells beside it are
    // frontier cells seen from most of the room. Candidates that saw the frontier cells but
    // not the wall cell taught the robot nothing, went on the visited list one by one, and
    // a team swept the room row by row (HA-CC 78 m against HA-RFE 31 m on the open space).
    let mut fx = room_with_unknown(&[(0, 5)], 10.0);
    let (got, cells) = run_cc(&mut fx);
    assert_eq!(cells.len(), 1);
    let c = fx.known.cell(cells[0] as usize);
    // (1, 1), the lowest cell that sees the three frontier cells, does not see (0, 5).
    assert_ne!(c, Cell::new(1, 1));
    assert!(los_visible(&fx.known, c, Cell::new(0, 5), 8.0), "{c:?}");
    let robot = fx.known.index(Cell::new(6, 5)) as u32;
    assert_eq!(got, oracle(&fx, robot));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn visibility_is_symmetric_between_free_cells(
        bits in prop::collection::vec(0u8..100, 144),
        a in 0usize..144,
        b in 0usize..144,
    ) {
        let g = random_known(12, 12, &bits, 12);
        prop_assume!(g[a] == Occ::Free && g[b] == Occ::Free);
        let (ca, cb) = (g.cell(a), g.cell(b));
        prop_assert_eq!(segment_clear(&g, ca, cb), segment_clear(&g, cb, ca));
    }

    #[test]
    fn cover_equals_the_slow_greedy_and_is_sound(
        bits in prop::collection::vec(0u8..100, 37),
        cut in 6usize..16,
        range in prop_oneof![1.0f64..7.0, 24.0f64..32.0],
        visited in prop::collection::vec(0usize..256, 0..4),
    ) {
        let Some((mut fx, robot)) = random_fixture((16, 16), &bits, cut, range, 0.2, &visited)
        else {
            return Ok(());
        };
        let (got, cells) = run_cc(&mut fx);
        // Soundness by the direct segment test: from every candidate, unknown space next
        // to each frontier it is credited with is seen within 0.8 ρ.
        let r2 = (0.8 * range) * (0.8 * range);
        for (c, fs) in &got {
            let cc = fx.known.cell(*c as usize);
            prop_assert!(fx.upkeep.is_traversable(&fx.known, *c as usize));
            for &f in fs {
                let seen = fx.known.neighbours8(f as usize).any(|u| {
                    let cu = fx.known.cell(u);
                    fx.known[u] == Occ::Unknown
                        && segment_clear(&fx.known, cc, cu)
                        && (cc.dist2(cu) as f64) <= r2 + 1e-9
                });
                prop_assert!(seen, "{:?} sees no unknown cell next to {:?}", cc, fx.known.cell(f as usize));
            }
        }
        // Completeness: every frontier to cover that some eligible cell covers is credited
        // exactly once, and no other.
        let mut credited: Vec<u32> = got.iter().flat_map(|(_, f)| f.iter().copied()).collect();
        credited.sort_unstable();
        let mut front = fx.memory.coverage.frontiers().to_vec();
        front.sort_unstable();
        let (want_front, eligible) = frontiers_and_eligible(&fx, robot as u32);
        prop_assert_eq!(&front, &want_front);
        let coverable: Vec<u32> = front
            .iter()
            .copied()
            .filter(|&f| eligible.iter().any(|&c| covers(&fx.known, c, f, 0.8 * range)))
            .collect();
        prop_assert_eq!(&credited, &coverable);
        // Equal to the slow greedy, candidate by candidate.
        prop_assert_eq!(&got, &oracle(&fx, robot as u32));
        let chosen: Vec<u32> = got.iter().map(|(c, _)| *c).collect();
        prop_assert_eq!(cells, chosen);
    }

    #[test]
    fn cover_with_cached_visibility_equals_a_fresh_one(
        bits in prop::collection::vec(0u8..100, 97),
        cut in 10usize..40,
        range in prop_oneof![1.0f64..12.0, 24.0f64..40.0],
        rounds in prop::collection::vec(
            (0usize..40, 0usize..24, 1usize..12, 1usize..8, prop::collection::vec(0u8..100, 7)),
            1..6,
        ),
        resolution in prop_oneof![Just(0.2f64), Just(0.05), Just(0.03)],
    ) {
        // Belief changes in random boxes between decisions; one fixture keeps its cache
        // (and, on fine maps, its blocks).
        let (w, h) = (40, 24);
        let known = random_known(w, h, &bits, cut);
        let up = {
            let mut u = FrontierUpkeep::new(w, h, 0.0);
            u.rebuild(&known);
            u
        };
        let Some(robot) = largest_component_cell(&known, &up) else {
            return Ok(());
        };
        let mut kept = Fixture::new(known, vec![robot as u32], range, 3);
        kept.resolution = resolution;
        for (x0, y0, bw, bh, pattern) in rounds {
            let before = run_cc(&mut kept);
            let mut fresh = Fixture::new(kept.known.clone(), kept.robots.clone(), range, 3);
            fresh.resolution = resolution;
            prop_assert_eq!(&before, &run_cc(&mut fresh));
            // change a box of cells
            for y in y0..(y0 + bh).min(h) {
                for x in x0..(x0 + bw).min(w) {
                    let b = pattern[(x * 3 + y) % pattern.len()];
                    kept.known[y * w + x] = if b < 20 {
                        Occ::Unknown
                    } else if b < 40 {
                        Occ::Occupied
                    } else {
                        Occ::Free
                    };
                }
            }
            let known = kept.known.clone();
            kept.upkeep.rebuild(&known);
            let Some(robot) = largest_component_cell(&kept.known, &kept.upkeep) else {
                return Ok(());
            };
            kept.robots = vec![robot as u32];
        }
        let last = {
            let mut out = CandidateSet::new(w * h);
            let mut ctx = kept.ctx();
            CandidateKind::Coverage.generate(&mut ctx, &mut out);
            out.cells().to_vec()
        };
        let mut fresh = Fixture::new(kept.known.clone(), kept.robots.clone(), range, 3);
        fresh.resolution = resolution;
        let want = {
            let mut out = CandidateSet::new(w * h);
            let mut ctx = fresh.ctx();
            CandidateKind::Coverage.generate(&mut ctx, &mut out);
            out.cells().to_vec()
        };
        prop_assert_eq!(last, want);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// The deviation on fine maps: the cover on blocks equals the slow block oracle, and
    /// every candidate is an eligible cell.
    #[test]
    fn cover_on_blocks_equals_the_slow_block_greedy(
        bits in prop::collection::vec(0u8..100, 41),
        cut in 8usize..20,
        (resolution, b) in prop_oneof![Just((0.05, 2usize)), Just((0.03, 3)), Just((0.0125, 8))],
        range in prop_oneof![2.0f64..14.0, 40.0f64..64.0],
        visited in prop::collection::vec(0usize..480, 0..4),
    ) {
        prop_assert_eq!(explore::candidates::coverage::cover_block(resolution), b);
        let Some((mut fx, robot)) =
            random_fixture((24, 20), &bits, cut, range, resolution, &visited)
        else {
            return Ok(());
        };
        let (got, cells) = run_cc(&mut fx);
        let (_, eligible) = frontiers_and_eligible(&fx, robot as u32);
        for (c, _) in &got {
            prop_assert!(eligible.binary_search(c).is_ok(), "{} is not eligible", c);
        }
        prop_assert_eq!(&got, &block_oracle(&fx, robot as u32, b));
        let chosen: Vec<u32> = got.iter().map(|(c, _)| *c).collect();
        prop_assert_eq!(cells, chosen);
    }
}
