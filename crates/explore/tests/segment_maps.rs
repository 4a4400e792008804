//! Room segmentation on hand-built maps, against brute-force oracles.

use explore::segment::score::score;
use explore::segment::skeleton::is_simple;
use explore::segment::{NONE, Rule, Segmenter, State, segment};
use grid::components::{Connectivity, label};
use grid::{Grid, Occ};
use proptest::prelude::*;

/// A `w × h` map of walls.
fn walls(w: usize, h: usize) -> Grid<Occ> {
    Grid::new(w, h, Occ::Occupied)
}

/// Make the rectangle `[x0, x1] × [y0, y1]` (inclusive) free.
fn carve(g: &mut Grid<Occ>, x0: usize, y0: usize, x1: usize, y1: usize) {
    let w = g.width();
    for y in y0..=y1 {
        for x in x0..=x1 {
            g.data_mut()[y * w + x] = Occ::Free;
        }
    }
}

/// Two rooms side by side, `side` cells square, joined by a door `door` cells wide.
fn two_rooms(side: usize, door: usize) -> Grid<Occ> {
    let (w, h) = (2 * side + 3, side + 2);
    let mut g = walls(w, h);
    carve(&mut g, 1, 1, side, side);
    carve(&mut g, side + 2, 1, 2 * side + 1, side);
    let mid = side / 2;
    carve(&mut g, side + 1, mid, side + 1, mid + door - 1);
    g
}

#[test]
fn two_rooms_joined_by_a_door_give_two_segments_split_at_the_door() {
    for (side, door) in [(12, 2), (20, 3), (40, 6), (30, 4)] {
        for rule in Rule::ALL {
            let g = two_rooms(side, door);
            let seg = segment(&g, rule);
            let what = format!("side {side} door {door} rule {}", rule.name());
            assert_eq!(seg.count, 2, "{what}");
            let w = g.width();
            let left = seg.labels[w + 1];
            let right = seg.labels[w + 2 * side + 1];
            assert_ne!(left, right, "{what}");
            for y in 1..=side {
                for x in 1..=side {
                    assert_eq!(seg.labels[y * w + x], left, "{what}: ({x},{y})");
                    let xr = x + side + 1;
                    assert_eq!(seg.labels[y * w + xr], right, "{what}: ({xr},{y})");
                }
            }
            // the split is at the door
            let mid = side / 2;
            assert!(
                seg.critical.iter().any(|c| {
                    let (x, y) = (c.cell as usize % w, c.cell as usize / w);
                    x.abs_diff(side + 1) <= 1 && y + 1 >= mid && y <= mid + door
                }),
                "{what}: critical points {:?}",
                seg.critical
            );
        }
    }
}

#[test]
fn a_long_corridor_is_one_segment() {
    for (len, width) in [(120, 6), (200, 3), (80, 10)] {
        let mut g = walls(len + 2, width + 2);
        carve(&mut g, 1, 1, len, width);
        for rule in Rule::ALL {
            let seg = segment(&g, rule);
            assert_eq!(
                seg.count,
                1,
                "corridor {len} x {width}, rule {}",
                rule.name()
            );
        }
    }
}

/// A corridor with `n` rooms on each side, each with a door to the corridor.
fn hospital_wing(n: usize, room: usize, depth: usize, corridor: usize, door: usize) -> Grid<Occ> {
    let w = n * (room + 1) + 1;
    let h = 2 * depth + corridor + 4;
    let mut g = walls(w, h);
    let cy0 = depth + 2;
    carve(&mut g, 1, cy0, w - 2, cy0 + corridor - 1);
    for k in 0..n {
        let x0 = 1 + k * (room + 1);
        let x1 = x0 + room - 1;
        carve(&mut g, x0, 1, x1, depth);
        let below = cy0 + corridor + 1;
        carve(&mut g, x0, below, x1, below + depth - 1);
        let dx = x0 + (room - door) / 2 + k % 2;
        carve(&mut g, dx, depth + 1, dx + door - 1, depth + 1);
        carve(&mut g, dx, below - 1, dx + door - 1, below - 1);
    }
    g
}

#[test]
fn a_corridor_with_doors_is_not_shattered_and_every_room_is_its_own_segment() {
    for (n, room, depth, corridor, door) in [(6, 16, 20, 10, 5), (5, 7, 9, 4, 2), (8, 12, 14, 8, 4)]
    {
        let g = hospital_wing(n, room, depth, corridor, door);
        let what = format!("wing {n} rooms of {room} x {depth}, corridor {corridor}, door {door}");
        let seg = segment(&g, Rule::Holz);
        let w = g.width();
        let cy0 = depth + 2;
        let corr = seg.labels[cy0 * w + 1];
        for y in cy0..cy0 + corridor {
            for x in 1..w - 1 {
                assert_eq!(
                    seg.labels[y * w + x],
                    corr,
                    "{what}: corridor cell ({x},{y})"
                );
            }
        }
        let mut seen = vec![corr];
        for k in 0..n {
            let x0 = 1 + k * (room + 1);
            for y0 in [1, cy0 + corridor + 1] {
                let l = seg.labels[y0 * w + x0];
                assert!(
                    !seen.contains(&l),
                    "{what}: room {k} at y {y0} shares label {l}"
                );
                seen.push(l);
                for y in y0..y0 + depth {
                    for x in x0..x0 + room {
                        assert_eq!(seg.labels[y * w + x], l, "{what}: room cell ({x},{y})");
                    }
                }
            }
        }
        assert_eq!(seg.count as usize, 2 * n + 1, "{what}");
    }
}

#[test]
fn segmentation_is_deterministic_and_buffers_do_not_leak_between_maps() {
    let a = hospital_wing(5, 12, 14, 8, 4);
    let b = two_rooms(20, 3);
    let fresh = segment(&a, Rule::Holz);
    assert_eq!(segment(&a, Rule::Holz), fresh);
    let mut s = Segmenter::new();
    s.run(&a, Rule::Thrun);
    s.run(&b, Rule::Holz);
    assert_eq!(s.run(&a, Rule::Holz), &fresh);
}

#[test]
fn the_cache_recomputes_or_patches_as_documented() {
    let mut g = hospital_wing(5, 12, 14, 8, 4);
    let mut state = State::new();
    let first = state.update(&g, Rule::Holz).clone();
    assert_eq!(first, segment(&g, Rule::Holz));
    assert_eq!(state.full_runs(), 1);
    // no change: nothing recomputed
    state.update(&g, Rule::Holz);
    assert_eq!((state.full_runs(), state.patches()), (1, 0));
    // a few cells change: patched, new free cells get the label of what they connect to
    let w = g.width();
    let cell = 15 * w + 3; // inside the first lower room? pick a wall cell next to a room
    let wall = (1..w * g.height())
        .find(|&i| g.data()[i] == Occ::Occupied && i > cell && g.data()[i - 1] == Occ::Free)
        .expect("a wall beside free space");
    g.data_mut()[wall] = Occ::Free;
    let patched = state.update(&g, Rule::Holz).clone();
    assert_eq!((state.full_runs(), state.patches()), (1, 1));
    assert_eq!(patched.labels[wall], patched.labels[wall - 1]);
    for i in 0..g.len() {
        if i != wall {
            assert_eq!(patched.labels[i], first.labels[i]);
        }
    }
    // a new rule: recomputed
    state.update(&g, Rule::Thrun);
    assert_eq!(state.full_runs(), 2);
    // a big change: recomputed
    let free = g.data().iter().filter(|c| c.is_free()).count();
    let mut k = 0;
    for i in 0..g.len() {
        if g.data()[i] == Occ::Free && k * 20 < free {
            g.data_mut()[i] = Occ::Unknown;
            k += 1;
        }
    }
    let again = state.update(&g, Rule::Thrun).clone();
    assert_eq!(state.full_runs(), 3);
    assert_eq!(again, segment(&g, Rule::Thrun));
}

#[test]
fn unknown_cells_are_not_segmented() {
    let mut g = two_rooms(20, 3);
    let w = g.width();
    for y in 0..g.height() {
        for x in 25..w {
            g.data_mut()[y * w + x] = Occ::Unknown;
        }
    }
    let seg = segment(&g, Rule::Holz);
    for (i, c) in g.data().iter().enumerate() {
        assert_eq!(seg.labels[i] == NONE, !c.is_free());
    }
}

/// Brute-force simple-point test: removing the centre keeps one 8-component of the set in
/// the neighbourhood, and the complement's 4-components touching the centre are one.
fn simple_oracle(mask: u8) -> bool {
    const RING: [(i32, i32); 8] = [
        (1, 0),
        (1, -1),
        (0, -1),
        (-1, -1),
        (-1, 0),
        (-1, 1),
        (0, 1),
        (1, 1),
    ];
    let on = |x: i32, y: i32| -> bool {
        if x == 0 && y == 0 {
            return false;
        }
        let k = RING.iter().position(|&p| p == (x, y)).expect("ring");
        mask >> k & 1 == 1
    };
    // 8-components of the set among the 8 neighbours
    let cells: Vec<(i32, i32)> = RING.iter().copied().filter(|&(x, y)| on(x, y)).collect();
    if cells.is_empty() {
        return false;
    }
    let comps = |pts: &[(i32, i32)], adj: &dyn Fn((i32, i32), (i32, i32)) -> bool| -> usize {
        let mut seen = vec![false; pts.len()];
        let mut n = 0;
        for s in 0..pts.len() {
            if seen[s] {
                continue;
            }
            n += 1;
            let mut stack = vec![s];
            seen[s] = true;
            while let Some(a) = stack.pop() {
                for b in 0..pts.len() {
                    if !seen[b] && adj(pts[a], pts[b]) {
                        seen[b] = true;
                        stack.push(b);
                    }
                }
            }
        }
        n
    };
    let adj8 = |a: (i32, i32), b: (i32, i32)| (a.0 - b.0).abs() <= 1 && (a.1 - b.1).abs() <= 1;
    let adj4 = |a: (i32, i32), b: (i32, i32)| (a.0 - b.0).abs() + (a.1 - b.1).abs() == 1;
    if comps(&cells, &adj8) != 1 {
        return false;
    }
    // the background neighbours 4-adjacent to the centre lie in one 4-component of the
    // background within the neighbourhood
    let bg: Vec<(i32, i32)> = RING.iter().copied().filter(|&(x, y)| !on(x, y)).collect();
    let mut seen = vec![false; bg.len()];
    let mut touching = 0;
    for s in 0..bg.len() {
        if seen[s] {
            continue;
        }
        let mut comp = vec![s];
        seen[s] = true;
        let mut k = 0;
        while k < comp.len() {
            let a = comp[k];
            k += 1;
            for b in 0..bg.len() {
                if !seen[b] && adj4(bg[a], bg[b]) {
                    seen[b] = true;
                    comp.push(b);
                }
            }
        }
        if comp.iter().any(|&c| adj4(bg[c], (0, 0))) {
            touching += 1;
        }
    }
    touching == 1
}

#[test]
fn the_simple_point_table_matches_a_brute_force_oracle() {
    for m in 0..=255u8 {
        assert_eq!(is_simple(m), simple_oracle(m), "mask {m:08b}");
    }
}

fn pair_count_ari(a: &[u32], b: &[u32]) -> f64 {
    let (mut n11, mut n10, mut n01, mut n00) = (0f64, 0f64, 0f64, 0f64);
    for i in 0..a.len() {
        for j in i + 1..a.len() {
            match (a[i] == a[j], b[i] == b[j]) {
                (true, true) => n11 += 1.0,
                (true, false) => n10 += 1.0,
                (false, true) => n01 += 1.0,
                (false, false) => n00 += 1.0,
            }
        }
    }
    let den = (n11 + n01) * (n01 + n00) + (n11 + n10) * (n10 + n00);
    if den == 0.0 {
        return if n10 == 0.0 && n01 == 0.0 { 1.0 } else { 0.0 };
    }
    2.0 * (n11 * n00 - n01 * n10) / den
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn ari_matches_the_brute_force_pair_count(
        pairs in proptest::collection::vec((0u32..4, 1u32..5), 2..40)
    ) {
        let seg: Vec<u32> = pairs.iter().map(|p| p.0).collect();
        let truth: Vec<u32> = pairs.iter().map(|p| p.1).collect();
        let s = score(&seg, &truth);
        let oracle = pair_count_ari(&seg, &truth);
        prop_assert!((s.ari - oracle).abs() < 1e-9, "ari {} oracle {}", s.ari, oracle);
    }

    #[test]
    fn precision_and_recall_match_a_brute_force_count(
        pairs in proptest::collection::vec((0u32..4, 1u32..5), 1..60)
    ) {
        let seg: Vec<u32> = pairs.iter().map(|p| p.0).collect();
        let truth: Vec<u32> = pairs.iter().map(|p| p.1).collect();
        let s = score(&seg, &truth);
        let mut matched = 0;
        let mut segs = std::collections::BTreeSet::new();
        let mut rooms = std::collections::BTreeSet::new();
        for (&a, &b) in seg.iter().zip(&truth) {
            segs.insert(a);
            rooms.insert(b);
        }
        for &r in &rooms {
            let size_r = truth.iter().filter(|&&t| t == r).count() as f64;
            for &g in &segs {
                let size_g = seg.iter().filter(|&&t| t == g).count() as f64;
                let both = seg.iter().zip(&truth).filter(|(a, b)| **a == g && **b == r).count() as f64;
                if both >= 0.8 * size_r && both >= 0.8 * size_g {
                    matched += 1;
                }
            }
        }
        prop_assert_eq!(s.matched, matched);
        prop_assert!((s.recall - matched as f64 / rooms.len() as f64).abs() < 1e-12);
        prop_assert!((s.precision - matched as f64 / segs.len() as f64).abs() < 1e-12);
    }

    #[test]
    fn segments_partition_free_space_into_connected_pieces(
        rects in proptest::collection::vec((1usize..22, 1usize..22, 1usize..10, 1usize..10), 1..8),
        noise in proptest::collection::vec(0usize..576, 0..20),
        rule in 0usize..3,
    ) {
        let (w, h) = (24, 24);
        let mut g = walls(w, h);
        for &(x, y, rw, rh) in &rects {
            carve(&mut g, x, y, (x + rw).min(w - 2), (y + rh).min(h - 2));
        }
        for &i in &noise {
            g.data_mut()[i] = Occ::Unknown;
        }
        let rule = Rule::ALL[rule];
        let mut s = Segmenter::new();
        let seg = s.run(&g, rule).clone();
        // skeleton inside free space, one skeleton component per free component (8-connected)
        let free = |i: usize| g.data()[i].is_free();
        let (_, free_comps) = label(w, h, free, Connectivity::Eight);
        let on = |i: usize| s.skeleton.contains(i);
        let (_, skel_comps) = label(w, h, on, Connectivity::Eight);
        prop_assert_eq!(free_comps, skel_comps);
        for i in 0..w * h {
            prop_assert!(!s.skeleton.contains(i) || free(i));
        }
        // every free cell labelled, every label used, every segment connected
        let mut used = vec![false; seg.count as usize];
        for i in 0..w * h {
            prop_assert_eq!(seg.labels[i] == NONE, !free(i));
            if seg.labels[i] != NONE {
                prop_assert!(seg.labels[i] < seg.count);
                used[seg.labels[i] as usize] = true;
            }
        }
        prop_assert!(used.iter().all(|&u| u));
        for l in 0..seg.count {
            // 8-connected: a diagonal step may pass beside a cell of another segment
            let (_, c) = label(w, h, |i| seg.labels[i] == l, Connectivity::Eight);
            prop_assert_eq!(c, 1, "segment {} in {} pieces", l, c);
        }
    }
}

/// Brute force: the set of 4-adjacent label pairs, counted per segment.
fn neighbour_oracle(seg: &explore::segment::Segmentation) -> Vec<u32> {
    let mut pairs = std::collections::BTreeSet::new();
    let (w, h) = (seg.width, seg.height);
    for y in 0..h {
        for x in 0..w {
            let a = seg.labels[y * w + x];
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx < w && ny < h {
                    let b = seg.labels[ny * w + nx];
                    if a != NONE && b != NONE && a != b {
                        pairs.insert((a.min(b), a.max(b)));
                    }
                }
            }
        }
    }
    let mut out = vec![0; seg.count as usize];
    for (a, b) in pairs {
        out[a as usize] += 1;
        out[b as usize] += 1;
    }
    out
}

#[test]
fn a_corridor_touches_every_room_and_each_room_only_the_corridor() {
    let (n, room, depth, corridor, door) = (5, 12, 14, 8, 4);
    let g = hospital_wing(n, room, depth, corridor, door);
    let seg = segment(&g, Rule::Holz);
    let (mut keys, mut counts) = (Vec::new(), Vec::new());
    seg.neighbour_counts(&mut keys, &mut counts);
    let corr = seg.labels[(depth + 2) * g.width() + 1] as usize;
    for (s, &c) in counts.iter().enumerate() {
        let want = if s == corr { 2 * n as u32 } else { 1 };
        assert_eq!(c, want, "segment {s}");
    }
    assert_eq!(counts, neighbour_oracle(&seg));
    let mut state = State::new();
    state.update(&g, Rule::Holz);
    assert_eq!(state.neighbours(corr as u32), 2 * n as u32);
}

proptest! {
    #[test]
    fn neighbour_counts_equal_the_brute_force_pairs(
        w in 2usize..12, h in 2usize..12, count in 1u32..6,
        raw in proptest::collection::vec(0u32..7, 144),
    ) {
        let labels: Vec<u32> = (0..w * h)
            .map(|i| if raw[i] >= count { NONE } else { raw[i] })
            .collect();
        let seg = explore::segment::Segmentation {
            width: w, height: h, labels, count, critical: Vec::new(),
        };
        let (mut keys, mut counts) = (Vec::new(), Vec::new());
        seg.neighbour_counts(&mut keys, &mut counts);
        prop_assert_eq!(counts, neighbour_oracle(&seg));
    }
}

#[test]
fn patched_neighbour_counts_equal_a_fresh_count_of_the_patched_labels() {
    let mut g = hospital_wing(5, 12, 14, 8, 4);
    let w = g.width();
    let mut state = State::new();
    state.update(&g, Rule::Holz);
    let (mut keys, mut counts) = (Vec::new(), Vec::new());
    // open the side walls between neighbouring upper rooms one cell at a time: each opening
    // joins two rooms that did not touch before
    let mut opened = 0;
    for i in w..g.len() - w {
        if g.data()[i] == Occ::Occupied
            && i % w > 0
            && i % w + 1 < w
            && g.data()[i - 1].is_free()
            && g.data()[i + 1].is_free()
            && i / w < 10
        {
            g.data_mut()[i] = Occ::Free;
            opened += 1;
            let seg = state.update(&g, Rule::Holz).clone();
            seg.neighbour_counts(&mut keys, &mut counts);
            for (s, &c) in counts.iter().enumerate() {
                assert_eq!(state.neighbours(s as u32), c, "after opening cell {i}");
            }
        }
    }
    assert!(opened >= 4 && state.patches() >= 4, "{opened} openings");
}

/// `g` with every cell replaced by a `k × k` block of the same state.
fn upscale(g: &Grid<Occ>, k: usize) -> Grid<Occ> {
    let (w, h) = (g.width(), g.height());
    let mut out = Grid::new(w * k, h * k, Occ::Occupied);
    for y in 0..h * k {
        for x in 0..w * k {
            out.data_mut()[y * w * k + x] = g.data()[(y / k) * w + x / k];
        }
    }
    out
}

#[test]
fn block_segmentation_of_an_upscaled_map_is_the_upscaled_segmentation() {
    let coarse = hospital_wing(5, 12, 14, 8, 4);
    let want = segment(&coarse, Rule::Holz);
    for k in [2, 3] {
        let fine = upscale(&coarse, k);
        let mut state = State::new();
        let got = state.update_blocks(&fine, Rule::Holz, k).clone();
        assert_eq!(got.count, want.count, "block {k}");
        assert_eq!(got.critical.len(), want.critical.len(), "block {k}");
        let w = fine.width();
        for (i, &l) in got.labels.iter().enumerate() {
            let c = (i / w / k) * coarse.width() + (i % w) / k;
            assert_eq!(l, want.labels[c], "block {k}, cell {i}");
        }
        // each critical point lands in its block
        for (g, c) in got.critical.iter().zip(&want.critical) {
            let (gx, gy) = (g.cell as usize % w, g.cell as usize / w);
            let cw = coarse.width();
            assert_eq!(
                (gx / k, gy / k),
                (c.cell as usize % cw, c.cell as usize / cw)
            );
        }
    }
}

#[test]
fn block_one_is_the_plain_update_and_partly_free_blocks_take_a_label() {
    let g = hospital_wing(5, 12, 14, 8, 4);
    let mut a = State::new();
    let mut b = State::new();
    assert_eq!(a.update(&g, Rule::Holz), b.update_blocks(&g, Rule::Holz, 1));
    // blocks of 2 over an odd-sized map: blocks on the edges and across walls are partly
    // free, and their free cells still get the label of the free cells they connect to
    let mut c = State::new();
    let seg = c.update_blocks(&g, Rule::Holz, 2).clone();
    for (i, o) in g.data().iter().enumerate() {
        if o.is_free() {
            assert_ne!(seg.labels[i], NONE, "free cell {i} unlabelled");
        } else {
            assert_eq!(seg.labels[i], NONE);
        }
    }
}

/// Rooms and corridors (`rects`, inclusive boxes clamped into the grid) carved free in a
/// `w × h` grid of `outside` (walls or unknown space).
fn rooms_in(w: usize, h: usize, outside: Occ, rects: &[(usize, usize, usize, usize)]) -> Grid<Occ> {
    let mut g = Grid::new(w, h, outside);
    for &(x, y, rw, rh) in rects {
        let (x0, y0) = (x % w, y % h);
        carve(&mut g, x0, y0, (x0 + rw).min(w - 1), (y0 + rh).min(h - 1));
    }
    g
}

/// The segmentation of the grid of `block × block` blocks of `g` (a block is free when all
/// its cells are), computed on the whole grid of blocks.
fn whole_block_segmentation(
    g: &Grid<Occ>,
    block: usize,
) -> (Grid<Occ>, explore::segment::Segmentation) {
    let (w, h) = (g.width(), g.height());
    let (cw, ch) = (w.div_ceil(block), h.div_ceil(block));
    let mut coarse = Grid::new(cw, ch, Occ::Free);
    for y in 0..h {
        for x in 0..w {
            if !g.data()[y * w + x].is_free() {
                coarse.data_mut()[(y / block) * cw + x / block] = Occ::Occupied;
            }
        }
    }
    let seg = segment(&coarse, Rule::Holz);
    (coarse, seg)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The cache segments only the window of the free cells (module documentation of
    /// `segment::cache`): its full runs equal the segmentation of the whole grid, cell by
    /// cell, with free space anywhere in a large grid, against its edges or not, as the
    /// free space grows and shrinks between runs.
    #[test]
    fn windowed_full_runs_equal_the_whole_grid_segmentation(
        (w, h) in (8usize..90, 8usize..70),
        unknown_outside in any::<bool>(),
        steps in proptest::collection::vec(
            proptest::collection::vec((0usize..90, 0usize..70, 0usize..30, 0usize..25), 1..5),
            1..5,
        ),
        block in 1usize..4,
    ) {
        let outside = if unknown_outside { Occ::Unknown } else { Occ::Occupied };
        let mut state = State::new();
        let mut runs = 0;
        let mut free_so_far: Vec<(usize, usize, usize, usize)> = Vec::new();
        for (k, rects) in steps.iter().enumerate() {
            // every other step shrinks the free space to the new rooms alone
            if k % 2 == 1 {
                free_so_far.clear();
            }
            free_so_far.extend(rects);
            let g = rooms_in(w, h, outside, &free_so_far);
            let got = state.update_blocks(&g, Rule::Holz, block).clone();
            if state.full_runs() == runs {
                continue; // patched: not a full run
            }
            runs = state.full_runs();
            if block == 1 {
                prop_assert_eq!(&got, &segment(&g, Rule::Holz));
                continue;
            }
            let (coarse, want) = whole_block_segmentation(&g, block);
            prop_assert_eq!(got.count, want.count);
            prop_assert_eq!(got.critical.len(), want.critical.len());
            let cw = coarse.width();
            for (i, &l) in got.labels.iter().enumerate() {
                let c = (i / w / block) * cw + (i % w) / block;
                if coarse.data()[c].is_free() {
                    prop_assert_eq!(l, want.labels[c], "cell {}", i);
                } else if !g.data()[i].is_free() {
                    prop_assert_eq!(l, NONE, "cell {}", i);
                }
            }
            for (a, b) in got.critical.iter().zip(&want.critical) {
                let (ax, ay) = (a.cell as usize % w, a.cell as usize / w);
                prop_assert_eq!((ax / block, ay / block), (b.cell as usize % cw, b.cell as usize / cw));
                prop_assert_eq!(a.clearance, b.clearance * block as f64);
            }
        }
    }
}
