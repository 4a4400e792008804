//! A search guided toward a set of goals (`Reachability::begin_guided`), or listing only
//! its goals (`Reachability::begin_goals`), against the full Dijkstra search on random
//! maps: advanced bucket by bucket it settles every goal of cost below its next bucket, and
//! every cell it settles has the full search's cost bit for bit and the same path;
//! advanced to the end it is the full search.

use explore::Reachability;
use explore::plan::reachability::{MAX_DIAL_GUIDE_BLOCKS, MAX_GUIDE_BLOCKS};
use proptest::prelude::*;

const W: usize = 61;
const H: usize = 47;

/// Walls: `rects` blocked rectangles `(x, y, w, h)` and scattered blocked cells.
fn passable(rects: &[(usize, usize, usize, usize)], scatter: &[usize]) -> Vec<bool> {
    let mut pass = vec![true; W * H];
    for &(x, y, w, h) in rects {
        for yy in y..(y + h).min(H) {
            for xx in x..(x + w).min(W) {
                pass[yy * W + xx] = false;
            }
        }
    }
    for &i in scatter {
        pass[i] = false;
    }
    pass
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    #[test]
    fn guided_search_equals_the_full_search_on_its_goals(
        rects in prop::collection::vec((0usize..W, 0usize..H, 1usize..20, 1usize..20), 0..8),
        scatter in prop::collection::vec(0usize..W * H, 0..300),
        start in 0usize..W * H,
        goals in prop::collection::vec(0u32..(W * H) as u32, 1..30),
        steps in prop::collection::vec(0usize..12, 1..12),
        canonical: bool,
        flat: bool,
    ) {
        let pass = passable(&rects, &scatter);
        let mut full = Reachability::new(W, H);
        full.compute(start, |i| pass[i]);
        let mut part = Reachability::new(W, H);
        part.set_canonical(canonical);
        // a search left in another state first: the buffers are reused
        part.begin_guided((start + 101) % (W * H), |i| pass[i], &goals[..1]);
        part.advance(5, |i| pass[i]);
        if flat {
            part.begin_goals(start, |i| pass[i], &goals);
        } else {
            part.begin_guided(start, |i| pass[i], &goals);
        }
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let mut through = 0;
        for s in steps {
            through += s;
            let done = part.advance(through, |i| pass[i]);
            prop_assert!(part.next_bucket() > through || done);
            prop_assert_eq!(done, part.is_complete());
            for &g in &goals {
                let g = g as usize;
                if full.cost(g).is_some_and(|c| (c as usize) < part.next_bucket()) || done {
                    prop_assert_eq!(
                        part.cost(g).map(f64::to_bits),
                        full.cost(g).map(f64::to_bits),
                        "goal {}", g
                    );
                }
            }
            for i in 0..W * H {
                if let Some(c) = part.cost(i) {
                    prop_assert_eq!(Some(c.to_bits()), full.cost(i).map(f64::to_bits));
                    prop_assert!(part.path_to(i, &mut a) && full.path_to(i, &mut b));
                    prop_assert_eq!(&a, &b);
                }
            }
        }
        part.advance(usize::MAX, |i| pass[i]);
        prop_assert!(part.is_complete());
        // complete, every cell it looked at is settled
        prop_assert_eq!(part.searched(), part.settled().len());
        for i in 0..W * H {
            prop_assert_eq!(part.cost(i).map(f64::to_bits), full.cost(i).map(f64::to_bits));
        }
    }
}

/// With goals far one way, the guided search settles them having looked at fewer cells
/// than the full search settles below their cost, in either order; with goals in too many
/// blocks it is the full search, cell for cell.
#[test]
fn a_guided_search_looks_toward_its_goals() {
    for canonical in [false, true] {
        looks_toward_its_goals(canonical);
    }
}

fn looks_toward_its_goals(canonical: bool) {
    // large enough that the canonical walks' reach past the goal's way (16 cells) is small
    let (w, h) = (241usize, 121usize);
    let pass = vec![true; w * h];
    let goal = (h / 2 * w + w - 2) as u32;
    let mut guided = Reachability::new(w, h);
    guided.set_canonical(canonical);
    guided.begin_guided(h / 2 * w + 1, |i| pass[i], &[goal]);
    let cost = loop {
        let done = guided.advance(guided.next_bucket(), |i| pass[i]);
        if let Some(c) = guided.cost(goal as usize) {
            break c;
        }
        assert!(!done);
    };
    let mut full = Reachability::new(w, h);
    full.compute(h / 2 * w + 1, |i| pass[i]);
    let nearer = (0..w * h)
        .filter(|&i| full.cost(i).is_some_and(|c| c <= cost))
        .count();
    assert!(
        guided.searched() * 3 < nearer,
        "guided {} cells, full {} below the goal's cost",
        guided.searched(),
        nearer
    );

    let (w, h) = (288usize, 264usize);
    let open = |_: usize| true;
    let everywhere: Vec<u32> = (0..(w * h) as u32).step_by(5).collect();
    assert!((w / 8) * (h / 8) > MAX_GUIDE_BLOCKS.max(MAX_DIAL_GUIDE_BLOCKS));
    let mut wide = Reachability::new(w, h);
    wide.set_canonical(canonical);
    wide.begin_guided(0, open, &everywhere);
    let mut plain = Reachability::new(w, h);
    plain.set_canonical(canonical);
    plain.begin(0, open);
    for through in [0, 3, 9, 40, usize::MAX] {
        wide.advance(through, open);
        plain.advance(through, open);
        assert_eq!(wide.settled(), plain.settled());
    }
}

/// With goals in more than [`MAX_GUIDE_BLOCKS`] blocks the bound would be weak, so
/// `begin_goals` drops it (a bound of 0) and still lists only its goals while it grows:
/// advanced bucket by bucket it settles each goal at the full search's cost, bit for bit,
/// with its path, and complete it is the full search.
#[test]
fn goals_in_many_blocks_are_settled_with_the_full_search_costs() {
    const W: usize = 400;
    const H: usize = 300;
    // walls with doors every 60 cells, both ways
    let pass: Vec<bool> = (0..W * H)
        .map(|i| {
            let (x, y) = (i % W, i / W);
            !((x % 60 == 30 && y % 60 != 45) || (y % 60 == 30 && x % 60 != 15))
        })
        .collect();
    let goals: Vec<u32> = (0..(W * H) as u32)
        .filter(|&i| (i as usize % W) % 7 == 3 && (i as usize / W) % 7 == 5)
        .filter(|&i| pass[i as usize])
        .collect();
    let blocks: std::collections::HashSet<(usize, usize)> = goals
        .iter()
        .map(|&g| (g as usize % W / 8, g as usize / W / 8))
        .collect();
    assert!(blocks.len() > MAX_GUIDE_BLOCKS, "{} blocks", blocks.len());
    let start = 10 * W + 10;
    let mut full = Reachability::new(W, H);
    full.compute(start, |i| pass[i]);
    let mut part = Reachability::new(W, H);
    part.begin_goals(start, |i| pass[i], &goals);
    assert!(part.lists_only_goals());
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let mut through = 0;
    loop {
        let done = part.advance(through, |i| pass[i]);
        for &g in &goals {
            let g = g as usize;
            if full
                .cost(g)
                .is_some_and(|c| (c as usize) < part.next_bucket())
                || done
            {
                assert_eq!(
                    part.cost(g).map(f64::to_bits),
                    full.cost(g).map(f64::to_bits)
                );
                if part.cost(g).is_some() {
                    assert!(part.path_to(g, &mut a) && full.path_to(g, &mut b));
                    assert_eq!(a, b, "path to {g}");
                }
            }
        }
        if done {
            // complete: every reachable cell is settled, and listed
            assert_eq!(part.settled().len(), full.settled().len());
            break;
        }
        // growing: only the goals (and the start) are listed
        assert!(
            part.settled()
                .iter()
                .all(|&c| c as usize == start || goals.contains(&c))
        );
        through += 97;
    }
}
