//! The step cost of Quattrini Li et al.'s search ("Formulation of the Search Problem"): the
//! shortest-path length from the robot's cell to every cell it may move to, inside the free
//! cells perceived so far (straight steps 1, diagonal √2, no squeezing between two blocked
//! cells sharing a vertex).
//!
//! [`StepCosts::compute`] is a search over the whole perceived space: the same bucket-queue
//! Dijkstra as [`explore::plan::Reachability`] (buckets one step wide, cells of a bucket
//! taken in labelling order, neighbours met right, down, left, up, then the diagonals), so
//! it gives the same costs and settles the cells in the same order, but on a graph built
//! once per problem: only the cells reachable in the full map exist, each with its 8
//! neighbours' indices and its mark, and "passable" is one bit test in the state's
//! perceived set; each cell's cost, flags and mark sit in one 16-byte slot. Written here
//! rather than reused because the generic search asks a closure per cell and addresses a
//! tiled whole-map layout (~17 % faster on the optimal benchmark's cave).
//!
//! With cluster actions a state needs the costs to its five or so representatives only,
//! and they rarely need that search ([`FieldCache`]): the full map's costs from each
//! position are computed once ([`StepCosts::field`]: the same buckets on a grid padded by
//! one cell, where neighbours lie at fixed offsets and cells off the reachable ones hold
//! −∞, 2.5 % faster on the corridor floor than the graph search with every cell
//! passable); when a shortest path of the full map lies inside the
//! perceived space, the cost inside is the full map's ([`StepCosts::inside`]: the path last
//! found between the two is checked first, then a walk back over tied predecessors); when
//! none does, A* from the representative guided by the robot's field finds it
//! ([`StepCosts::guided`]). On the corridor floor every representative took the first two;
//! on the potholes map two thirds of the states need A* for some representative.

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use crate::heuristic::{MixHasher, has, push_words};
use crate::problem::Problem;
use crate::room::{RESERVED_POSITIONS, room_bytes, room_for};

const NONE: u32 = u32::MAX;
/// Buckets in use at once: a step costs at most √2 < 2, so labels reach two buckets ahead.
const BUCKETS: usize = 3;
/// Flag: the cell's cost is final.
const DONE: u32 = 1;
/// Flag: the cell is not perceived (not passable in this search).
const BLOCKED: u32 = 2;
/// Largest search number: it is kept above two flag bits.
const MAX_EPOCH: u32 = u32::MAX >> 2;
/// Costs closer than this are equal: sums of 1 and √2 along paths of a few thousand steps
/// carry rounding far below it, and two different such lengths differ by far more.
const TIE: f64 = 1e-7;
/// The first perceived (`seen`) of the two straight cells diagonal neighbour `k` of a cell
/// with neighbours `nb` passes.
fn side(nb: &[u32; 8], k: usize, seen: impl Fn(u32) -> bool) -> u32 {
    let (a, b) = DIAGONAL_SIDES[k - 4];
    if seen(nb[a]) { nb[a] } else { nb[b] }
}

/// The straight neighbours a diagonal neighbour passes (dr: r, d; dl: l, d; ul: l, u;
/// ur: r, u), as indices into a cell's neighbour list.
const DIAGONAL_SIDES: [(usize, usize); 4] = [(0, 1), (2, 1), (2, 3), (0, 3)];

/// What a search knows of a reachable cell, kept together so that meeting a cell touches
/// one cache line.
#[derive(Clone, Copy, Default)]
struct Slot {
    /// Cost of the best path found (valid when `tag` is of the current search).
    cost: f64,
    /// The search that last met the cell, shifted left by 2, and its flags.
    tag: u32,
    /// The cell's mark (it is a target: every reachable cell can be perceived).
    mark: u32,
}

/// Dijkstra inside the perceived free space, on the problem's reachable cells.
pub(crate) struct StepCosts {
    /// Per flat cell: its index among the reachable cells, or `NONE`.
    index: Vec<u32>,
    /// Per reachable cell: its flat cell.
    flat: Vec<u32>,
    /// Per reachable cell: the reachable neighbours right, down, left, up, down-right,
    /// down-left, up-left, up-right (`NONE` for others).
    nbr: Vec<[u32; 8]>,
    /// Per reachable cell: its mark, and its cost and flags in the search that last met it.
    slot: Vec<Slot>,
    epoch: u32,
    buckets: [Vec<u32>; BUCKETS],
    /// Flat cells in settling order.
    settled: Vec<u32>,
    /// The stack of [`StepCosts::inside`].
    walk: Vec<u32>,
    /// The marks the last greedy walk back needed perceived ([`StepCosts::walked`]).
    walked: Vec<u32>,
    /// The open list of [`StepCosts::guided`].
    heap: std::collections::BinaryHeap<AstarEntry>,
    /// The full map's graph on a grid padded by one cell ([`StepCosts::field`]).
    padded: Padded,
}

/// The reachable cells on a grid with a one-cell border, for [`StepCosts::field`]: a cell's
/// neighbours lie at fixed offsets and its allowed diagonals are one byte, so the full-map
/// search reads no neighbour lists and keeps no search numbers.
struct Padded {
    /// Per reachable cell: its padded cell.
    cell: Vec<u32>,
    /// Per padded cell: bit j set when diagonal move 4 + j (down-right, down-left, up-left,
    /// up-right) leads to a reachable cell past a reachable straight cell (no corner
    /// squeezing). Straight moves need no bit: cells off the reachable ones hold −∞.
    diagonals: Vec<u8>,
    /// Move k's offset in padded cells.
    offset: [isize; 8],
    /// Scratch: costs by padded cell.
    cost: Vec<f64>,
    /// The costs before a search: ∞ on the reachable cells, −∞ elsewhere.
    unlabelled: Vec<f64>,
}

/// An open entry of [`StepCosts::guided`]: least f first, then largest g, then cell.
type AstarEntry = std::cmp::Reverse<(u64, u64, u32)>;

/// The entry of cell `u` at priority `f` (≥ 0, so its bits order as the number) and cost `g`.
fn astar_entry(f: f64, g: f64, u: u32) -> AstarEntry {
    std::cmp::Reverse((f.to_bits(), u64::MAX - g.to_bits(), u))
}

impl StepCosts {
    /// The graph of `problem`'s reachable cells.
    pub(crate) fn new(problem: &Problem) -> Self {
        let cells = problem.cells();
        let (w, h) = (cells.width() as i64, cells.height() as i64);
        let n = cells.len();
        let mut index = vec![NONE; n];
        let mut flat = Vec::with_capacity(problem.reachable_count());
        for (i, slot) in index.iter_mut().enumerate() {
            if problem.reachable(i) {
                *slot = flat.len() as u32;
                flat.push(i as u32);
            }
        }
        let slot: Vec<Slot> = flat
            .iter()
            .map(|&i| Slot {
                mark: problem.target_index(i as usize),
                ..Slot::default()
            })
            .collect();
        debug_assert!(slot.iter().all(|s| s.mark != crate::problem::NOT_TARGET));
        let nbr: Vec<[u32; 8]> = flat
            .iter()
            .map(|&i| {
                let (x, y) = (i as i64 % w, i as i64 / w);
                grid::NEIGHBOURS8.map(|(dx, dy)| {
                    let (nx, ny) = (x + i64::from(dx), y + i64::from(dy));
                    if nx < 0 || ny < 0 || nx >= w || ny >= h {
                        NONE
                    } else {
                        index[(ny * w + nx) as usize]
                    }
                })
            })
            .collect();
        let pw = w as usize + 2;
        let offset = grid::NEIGHBOURS8.map(|(dx, dy)| dy as isize * pw as isize + dx as isize);
        let pad =
            |i: u32| ((i as usize / w as usize + 1) * pw + i as usize % w as usize + 1) as u32;
        let mut diagonals = vec![0u8; pw * (h as usize + 2)];
        for (u, nb) in nbr.iter().enumerate() {
            let open = |k: usize| nb[k] != NONE;
            let mut m = 0u8;
            for (j, &(a, b)) in DIAGONAL_SIDES.iter().enumerate() {
                m |= u8::from(open(4 + j) && (open(a) || open(b))) << j;
            }
            diagonals[pad(flat[u]) as usize] = m;
        }
        let cell: Vec<u32> = flat.iter().map(|&i| pad(i)).collect();
        let mut unlabelled = vec![f64::NEG_INFINITY; diagonals.len()];
        for &p in &cell {
            unlabelled[p as usize] = f64::INFINITY;
        }
        let padded = Padded {
            cell,
            cost: unlabelled.clone(),
            unlabelled,
            diagonals,
            offset,
        };
        Self {
            padded,
            index,
            flat,
            nbr,
            slot,
            epoch: 0,
            buckets: Default::default(),
            settled: Vec::new(),
            walk: Vec::new(),
            walked: Vec::new(),
            heap: std::collections::BinaryHeap::new(),
        }
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.index.len() * 4
            + self.flat.len() * (4 + 32 + 4 + std::mem::size_of::<Slot>())
            + self.padded.diagonals.len() * (1 + 16)
            + self.settled.capacity() * 4
    }

    /// Meet reachable cell `u` at cost `c` from a settled neighbour: label it (or lower its
    /// label) if it is perceived and not settled. Returns whether it is passable.
    #[inline(always)]
    fn visit(&mut self, bits: &[u64], u: u32, c: f64) -> bool {
        if u == NONE {
            return false;
        }
        let tag = self.epoch << 2;
        let slot = &mut self.slot[u as usize];
        if slot.tag & !3 == tag {
            let f = slot.tag & 3;
            if f & BLOCKED != 0 {
                return false;
            }
            if f & DONE == 0 && c < slot.cost {
                slot.cost = c;
                self.buckets[c as usize % BUCKETS].push(u);
            }
            true
        } else if has(bits, slot.mark) {
            slot.tag = tag;
            slot.cost = c;
            self.buckets[c as usize % BUCKETS].push(u);
            true
        } else {
            slot.tag = tag | BLOCKED;
            false
        }
    }

    /// Costs from reachable cell `start` to every cell reachable inside the perceived free
    /// cells `bits` (a set of marks); the start itself is always left.
    pub(crate) fn compute(&mut self, start: u32, bits: &[u64]) {
        let tag = self.fresh_tag();
        for b in &mut self.buckets {
            b.clear();
        }
        self.settled.clear();
        let s = self.index[start as usize];
        if s == NONE {
            return;
        }
        let slot = &mut self.slot[s as usize];
        slot.tag = tag | if has(bits, slot.mark) { 0 } else { BLOCKED };
        slot.cost = 0.0;
        self.buckets[0].push(s);
        let mut k = 0usize;
        loop {
            let slot = k % BUCKETS;
            if self.buckets[slot].is_empty() {
                if self.buckets.iter().all(Vec::is_empty) {
                    return;
                }
                k += 1;
                continue;
            }
            let mut bucket = std::mem::take(&mut self.buckets[slot]);
            for &u in &bucket {
                let ui = u as usize;
                let slot = &mut self.slot[ui];
                if slot.tag & DONE != 0 {
                    continue; // labelled again more cheaply, or listed twice
                }
                slot.tag |= DONE;
                let ci = slot.cost;
                self.settled.push(self.flat[ui]);
                let [r, d, l, up, dr, dl, ul, ur] = self.nbr[ui];
                let c1 = ci + 1.0;
                let pr = self.visit(bits, r, c1);
                let pd = self.visit(bits, d, c1);
                let pl = self.visit(bits, l, c1);
                let pu = self.visit(bits, up, c1);
                let c2 = ci + grid::SQRT2;
                if pr || pd {
                    self.visit(bits, dr, c2);
                }
                if pl || pd {
                    self.visit(bits, dl, c2);
                }
                if pl || pu {
                    self.visit(bits, ul, c2);
                }
                if pr || pu {
                    self.visit(bits, ur, c2);
                }
            }
            bucket.clear();
            self.buckets[slot] = bucket;
            k += 1;
        }
    }

    /// Number of reachable cells (the length of a [`StepCosts::field`]).
    pub(crate) fn len(&self) -> usize {
        self.flat.len()
    }

    /// Append to `cost` the costs from reachable cell `start` to every reachable cell in
    /// the full map (every cell passable), by reachable index. Dial's buckets of width 1 (no
    /// step is shorter, so a bucket's cells are final when it is reached) on the padded
    /// grid: a cell is listed again only when its cost drops to a lower bucket, and an
    /// entry is skipped when its cell's cost has left its bucket. A cell's cost is the
    /// least of its neighbours' final costs plus the step whatever the order of the
    /// search, so the costs are those of [`StepCosts::compute`] with every mark
    /// perceived, bit for bit.
    pub(crate) fn field(&mut self, start: u32, cost: &mut Vec<f64>) {
        let s = self.index[start as usize];
        if s == NONE {
            cost.extend(std::iter::repeat_n(f64::INFINITY, self.flat.len()));
            return;
        }
        let Padded {
            cell,
            diagonals,
            offset,
            cost: c,
            unlabelled,
        } = &mut self.padded;
        c.copy_from_slice(unlabelled);
        for b in &mut self.buckets {
            b.clear();
        }
        let s = cell[s as usize];
        c[s as usize] = 0.0;
        self.buckets[0].push(s);
        let mut pending = 1usize;
        let mut k = 0usize;
        while pending > 0 {
            let slot = k % BUCKETS;
            let mut bucket = std::mem::take(&mut self.buckets[slot]);
            pending -= bucket.len();
            for &u in &bucket {
                let ui = u as usize;
                let cu = c[ui];
                if cu as usize != k {
                    continue; // its cost dropped to a lower bucket
                }
                // Cells off the reachable ones hold −∞, so no step lowers them; a diagonal
                // also needs its bit (no corner squeezing).
                let m = diagonals[ui];
                let buckets = &mut self.buckets;
                let mut relax = |v: usize, nc: f64, allowed: bool| {
                    let old = c[v];
                    if nc < old && allowed {
                        c[v] = nc;
                        if !(old.is_finite() && old as usize == nc as usize) {
                            buckets[nc as usize % BUCKETS].push(v as u32);
                            pending += 1;
                        }
                    }
                };
                let (c1, c2) = (cu + 1.0, cu + grid::SQRT2);
                let at = |j: usize| ui.wrapping_add_signed(offset[j]);
                relax(at(0), c1, true);
                relax(at(1), c1, true);
                relax(at(2), c1, true);
                relax(at(3), c1, true);
                relax(at(4), c2, m & 1 != 0);
                relax(at(5), c2, m & 2 != 0);
                relax(at(6), c2, m & 4 != 0);
                relax(at(7), c2, m & 8 != 0);
            }
            bucket.clear();
            self.buckets[slot] = bucket;
            k += 1;
        }
        cost.extend(cell.iter().map(|&p| c[p as usize]));
    }

    /// The cost from reachable cell `from` to reachable cell `to` inside the perceived free
    /// cells `bits` if some shortest path of the full map joins them there, given `field`,
    /// the full map's costs from `from` ([`StepCosts::field`]); `None` if none does (the
    /// cost inside may then be larger). Walks back from `to` over the cells whose full-map
    /// cost is a predecessor's plus the step, perceived, with the step allowed inside the
    /// perceived cells (a diagonal needs one of its two straight cells perceived): a path
    /// inside that is as short as the full map's is exactly such a walk. Takes a fresh
    /// search number, so the costs of the last [`StepCosts::compute`] are gone (its settled
    /// cells stay).
    pub(crate) fn inside(
        &mut self,
        field: &[f64],
        from: u32,
        to: u32,
        bits: &[u64],
    ) -> Option<f64> {
        let (s, t) = (self.index[from as usize], self.index[to as usize]);
        if s == NONE || t == NONE || !field[t as usize].is_finite() {
            return None;
        }
        // First one walk back, taking the first tied predecessor that is perceived: usually
        // one shortest path is perceived all along.
        if self.greedy_walk_inside(field, s, t, bits) {
            return Some(field[t as usize]);
        }
        self.walked.clear();
        // A fresh search number marks the cells met by this walk (DONE) and those found
        // not perceived (BLOCKED).
        let tag = self.fresh_tag();
        self.walk.clear();
        self.walk.push(t);
        self.slot[t as usize].tag = tag | DONE;
        while let Some(x) = self.walk.pop() {
            if x == s {
                return Some(field[t as usize]);
            }
            let fx = field[x as usize];
            let nb = self.nbr[x as usize];
            let open = self.straight_open(bits, &nb, s, tag);
            for (k, &y) in nb.iter().enumerate() {
                if y == NONE {
                    continue;
                }
                let step = if k < 4 {
                    1.0
                } else {
                    let (a, b) = DIAGONAL_SIDES[k - 4];
                    if !(open[a] || open[b]) {
                        continue;
                    }
                    grid::SQRT2
                };
                if (field[y as usize] + step - fx).abs() > TIE {
                    continue;
                }
                if y != s && !self.passable(bits, y, tag) {
                    continue;
                }
                let slot = &mut self.slot[y as usize];
                if slot.tag == tag | DONE {
                    continue;
                }
                slot.tag = tag | DONE;
                self.walk.push(y);
            }
        }
        None
    }

    /// Whether walking back from `t`, always to the first neighbour (straight ones first)
    /// on a shortest path of `field` that is perceived in `bits` and reached by a step
    /// allowed inside them, reaches `s`.
    fn greedy_walk_inside(&mut self, field: &[f64], s: u32, t: u32, bits: &[u64]) -> bool {
        let seen = |u: u32| u == s || (u != NONE && has(bits, self.slot[u as usize].mark));
        self.walked.clear();
        let mut x = t;
        while x != s {
            let fx = field[x as usize];
            let nb = &self.nbr[x as usize];
            let next = (0..8).find(|&k| {
                let y = nb[k];
                if y == NONE {
                    return false;
                }
                let step = if k < 4 { 1.0 } else { grid::SQRT2 };
                if (field[y as usize] + step - fx).abs() > TIE || !seen(y) {
                    return false;
                }
                let (a, b) = DIAGONAL_SIDES[k % 4];
                k < 4 || seen(nb[a]) || seen(nb[b])
            });
            let Some(k) = next else { return false };
            let y = nb[k];
            // What this step needs perceived: the cell, and for a diagonal the first of
            // its two straight cells that is.
            for u in [y, if k < 4 { NONE } else { side(nb, k, seen) }] {
                if u != NONE && u != s {
                    self.walked.push(self.slot[u as usize].mark);
                }
            }
            x = y;
        }
        true
    }

    /// The marks that [`StepCosts::inside`]'s last walk back needed perceived, when it
    /// found its path without searching: if a perceived set holds them all, that path is
    /// inside it too.
    pub(crate) fn walked(&self) -> &[u32] {
        &self.walked
    }

    /// The cost from reachable cell `from` to reachable cell `to` inside the perceived free
    /// cells `bits`, by A* from `to` towards `from` guided by `field`, the full map's costs
    /// from `from` (a consistent lower bound: paths inside are paths of the full map, and
    /// the steps are symmetric); `None` if `from` cannot be reached inside. For the
    /// representatives whose shortest paths leave the perceived space: the search stays
    /// near the detour instead of labelling the whole perceived space. Takes a fresh search
    /// number, as [`StepCosts::inside`] does.
    pub(crate) fn guided(
        &mut self,
        field: &[f64],
        from: u32,
        to: u32,
        bits: &[u64],
    ) -> Option<f64> {
        let (s, t) = (self.index[from as usize], self.index[to as usize]);
        if s == NONE || t == NONE || !field[t as usize].is_finite() {
            return None;
        }
        let tag = self.fresh_tag();
        self.heap.clear();
        self.slot[t as usize].tag = tag;
        self.slot[t as usize].cost = 0.0;
        self.heap.push(astar_entry(field[t as usize], 0.0, t));
        while let Some(std::cmp::Reverse((_, gbits, x))) = self.heap.pop() {
            let g = f64::from_bits(u64::MAX - gbits);
            let slot = &mut self.slot[x as usize];
            if slot.tag == tag | DONE || g > slot.cost {
                continue;
            }
            slot.tag = tag | DONE;
            if x == s {
                return Some(g);
            }
            let nb = self.nbr[x as usize];
            let open = self.straight_open(bits, &nb, s, tag);
            for (k, &y) in nb.iter().enumerate() {
                let step = if k < 4 {
                    if !open[k] {
                        continue;
                    }
                    1.0
                } else {
                    let (a, b) = DIAGONAL_SIDES[k - 4];
                    if !(open[a] || open[b]) || !(y == s || self.passable(bits, y, tag)) {
                        continue;
                    }
                    grid::SQRT2
                };
                let ng = g + step;
                let slot = &mut self.slot[y as usize];
                if slot.tag == tag | DONE || (slot.tag == tag && ng >= slot.cost) {
                    continue;
                }
                slot.tag = tag;
                slot.cost = ng;
                self.heap.push(astar_entry(ng + field[y as usize], ng, y));
            }
        }
        None
    }

    /// Start a new search: the next search number, shifted above the two flag bits (every
    /// cell's tag is cleared when the number would overflow).
    fn fresh_tag(&mut self) -> u32 {
        self.epoch += 1;
        if self.epoch > MAX_EPOCH {
            for slot in &mut self.slot {
                slot.tag = 0;
            }
            self.epoch = 1;
        }
        self.epoch << 2
    }

    /// Whether each straight neighbour in `nb` (right, down, left, up) may be stepped on
    /// inside the perceived cells `bits` under search `tag`: perceived, or `s`.
    fn straight_open(&mut self, bits: &[u64], nb: &[u32; 8], s: u32, tag: u32) -> [bool; 4] {
        std::array::from_fn(|k| nb[k] == s || self.passable(bits, nb[k], tag))
    }

    /// Whether reachable cell `u` is perceived, remembered under `tag` when it is not.
    #[inline]
    fn passable(&mut self, bits: &[u64], u: u32, tag: u32) -> bool {
        if u == NONE {
            return false;
        }
        let slot = &mut self.slot[u as usize];
        if slot.tag == tag | BLOCKED {
            return false;
        }
        if slot.tag == tag | DONE || has(bits, slot.mark) {
            return true;
        }
        slot.tag = tag | BLOCKED;
        false
    }

    /// The flat cells settled by the last search, in settling order (the start first).
    pub(crate) fn settled(&self) -> &[u32] {
        &self.settled
    }

    /// The cost to flat cell `i` in the last search, `∞` if it was not reached.
    #[inline]
    pub(crate) fn dist(&self, i: usize) -> f64 {
        let u = self.index[i];
        if u == NONE {
            return f64::INFINITY;
        }
        let slot = &self.slot[u as usize];
        if slot.tag & !BLOCKED == self.epoch << 2 | DONE {
            slot.cost
        } else {
            f64::INFINITY
        }
    }
}

/// Per position: the full map's step costs from it ([`StepCosts::field`]), computed on
/// first use and dropped all at once when they outgrow their share of the memory budget.
/// The heuristic's distance orders and the search's step costs to cluster representatives
/// ([`FieldCache::inside`]) both read them.
pub(crate) struct FieldCache {
    steps: StepCosts,
    /// Per flat cell: its field's number, or `NONE`.
    slot: Vec<u32>,
    len: usize,
    cost: Vec<f64>,
    cap_bytes: usize,
    /// Per (from, to): the marks (as (word, bits)) the last path found inside needed
    /// perceived; a perceived set that holds them has that path.
    paths: HashMap<(u32, u32), (u32, u32), BuildHasherDefault<MixHasher>>,
    path_words: Vec<(u32, u64)>,
}

impl FieldCache {
    /// Fields for `problem`, at most `cap_bytes` of them at once.
    pub(crate) fn new(problem: &Problem, cap_bytes: usize) -> Self {
        let steps = StepCosts::new(problem);
        Self {
            slot: vec![NONE; problem.cells().len()],
            len: steps.len(),
            steps,
            cost: Vec::new(),
            cap_bytes,
            paths: HashMap::default(),
            path_words: Vec::new(),
        }
    }

    /// How the fields make room for one more: (entries a field, first room, the cap in
    /// entries).
    fn room(&self) -> (usize, usize, usize) {
        let first = self.len.saturating_mul(RESERVED_POSITIONS);
        (self.len, first, self.cap_bytes / 8)
    }

    /// The bytes the next field may add to [`FieldCache::bytes`].
    pub(crate) fn growth_bytes(&self) -> usize {
        let (len, first, limit) = self.room();
        room_bytes(&self.cost, len, first, limit)
    }

    /// The offset of the field of reachable flat cell `pos` in `cost`.
    fn of(&mut self, pos: u32) -> usize {
        let p = pos as usize;
        if self.slot[p] == NONE {
            let (len, first, limit) = self.room();
            if !room_for(&mut self.cost, len, first, limit) {
                self.cost.clear();
                self.slot.fill(NONE);
                room_for(&mut self.cost, len, first, limit);
            }
            self.slot[p] = (self.cost.len() / self.len.max(1)) as u32;
            self.steps.field(pos, &mut self.cost);
        }
        self.slot[p] as usize * self.len
    }

    /// The full map's path costs from reachable flat cell `pos`, by flat cell (∞ off the
    /// reachable cells).
    pub(crate) fn costs(&mut self, pos: u32) -> impl Fn(usize) -> f64 + '_ {
        let base = self.of(pos);
        let (index, cost) = (&self.steps.index, &self.cost[base..base + self.len]);
        move |i| match index[i] {
            NONE => f64::INFINITY,
            u => cost[u as usize],
        }
    }

    /// [`StepCosts::inside`] from `from` to `to` inside the perceived cells `bits`.
    pub(crate) fn inside(&mut self, from: u32, to: u32, bits: &[u64]) -> Option<f64> {
        let base = self.of(from);
        let cost = &self.cost[base..base + self.len];
        // The last path found between the two, if still perceived all along.
        if let Some(&(o, l)) = self.paths.get(&(from, to))
            && self.path_words[o as usize..(o + l) as usize]
                .iter()
                .all(|&(k, m)| bits[k as usize] & m == m)
        {
            return Some(cost[self.steps.index[to as usize] as usize]);
        }
        let found = self.steps.inside(cost, from, to, bits);
        if found.is_some() && !self.steps.walked().is_empty() {
            if self.path_words.len() * 12 > self.cap_bytes / 8 {
                self.path_words.clear();
                self.paths.clear();
            }
            let o = self.path_words.len();
            push_words(
                &mut self.path_words,
                self.steps.walked().iter().map(|&t| (t / 64, 1 << (t % 64))),
            );
            self.paths
                .insert((from, to), (o as u32, (self.path_words.len() - o) as u32));
        }
        found
    }

    /// [`StepCosts::guided`] from `from` to `to` inside the perceived cells `bits`.
    pub(crate) fn guided(&mut self, from: u32, to: u32, bits: &[u64]) -> Option<f64> {
        let base = self.of(from);
        self.steps
            .guided(&self.cost[base..base + self.len], from, to, bits)
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.steps.bytes()
            + self.slot.len() * 4
            + self.cost.capacity() * 8
            + self.path_words.capacity() * 16
            + self.paths.capacity() * 20
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::SensorModel;
    use explore::plan::Reachability;
    use proptest::prelude::*;

    proptest! {
        /// The same costs and the same settling order as the generic search asked "is this
        /// cell reachable and perceived", on random maps, perceived sets and starts.
        #[test]
        fn same_as_the_generic_search(
            w in 2usize..12,
            h in 2usize..12,
            walls in proptest::collection::vec(0u8..4, 144),
            seen in proptest::collection::vec(0u8..5, 144),
            pick in 0usize..144,
        ) {
            let case = crate::walled_problem(w, h, &walls, pick, SensorModel::Los(2.0));
            prop_assume!(case.is_some());
            let (p, start) = case.expect("assumed");
            // A random perceived set of marks (most cells perceived), the start's included.
            let bits = crate::perceived_marks(&p, &seen, start);
            let mut ours = StepCosts::new(&p);
            let mut generic = Reachability::new(w, h);
            // Dial's search settles a bucket in the order its cells were labelled, as ours
            generic.set_canonical(false);
            // Every reachable cell as a source, so the searches also start next to walls.
            for s in (0..w * h).filter(|&i| p.reachable(i) && has(&bits, p.target_index(i))) {
                ours.compute(s as u32, &bits);
                generic.compute(s, |i| p.reachable(i) && has(&bits, p.target_index(i)));
                prop_assert_eq!(ours.settled(), generic.settled());
                for i in 0..w * h {
                    let g = generic.cost(i).unwrap_or(f64::INFINITY);
                    prop_assert_eq!(ours.dist(i).to_bits(), g.to_bits(), "cell {} from {}", i, s);
                }
            }
        }

        /// `inside` gives the cost inside the perceived cells exactly when it equals the
        /// full map's, and nothing otherwise, and `guided` always gives it (or that there is
        /// none), on random maps, perceived sets and cells.
        #[test]
        fn inside_is_the_cost_when_a_full_map_shortest_path_is_perceived(
            w in 2usize..14,
            h in 2usize..14,
            walls in proptest::collection::vec(0u8..4, 196),
            seen in proptest::collection::vec(0u8..6, 196),
            pick in 0usize..196,
        ) {
            let case = crate::walled_problem(w, h, &walls, pick, SensorModel::Los(2.0));
            prop_assume!(case.is_some());
            let (p, start) = case.expect("assumed");
            let words = p.mark_count().div_ceil(64).max(1);
            let bits = crate::perceived_marks(&p, &seen, start);
            let all = vec![u64::MAX; words];
            let mut ours = StepCosts::new(&p);
            for s in (0..w * h).filter(|&i| p.reachable(i) && has(&bits, p.target_index(i))) {
                let mut field = Vec::new();
                ours.field(s as u32, &mut field);
                // The full-map field is the search with every mark perceived.
                ours.compute(s as u32, &all);
                for (u, &f) in field.iter().enumerate() {
                    prop_assert_eq!(f.to_bits(), ours.dist(ours.flat[u] as usize).to_bits());
                }
                ours.compute(s as u32, &bits);
                let costs: Vec<f64> = (0..w * h).map(|i| ours.dist(i)).collect();
                for t in (0..w * h).filter(|&i| p.reachable(i) && has(&bits, p.target_index(i))) {
                    // The guided search finds the cost inside exactly, or that there is none.
                    let guided = ours.guided(&field, s as u32, t as u32, &bits);
                    if costs[t].is_finite() {
                        prop_assert!(guided.is_some_and(|c| (c - costs[t]).abs() < 1e-9), "{} -> {}: {:?} vs {}", s, t, guided, costs[t]);
                    } else {
                        prop_assert_eq!(guided, None);
                        continue;
                    }
                    let full = field[ours.index[t] as usize];
                    let got = ours.inside(&field, s as u32, t as u32, &bits);
                    if (costs[t] - full).abs() < 1e-9 {
                        prop_assert!(got.is_some_and(|c| (c - costs[t]).abs() < 1e-9), "{} -> {}: {:?} vs {}", s, t, got, costs[t]);
                    } else {
                        prop_assert!(costs[t] > full);
                        prop_assert_eq!(got, None, "{} -> {}", s, t);
                    }
                }
            }
        }

        /// The field cache's remembered paths give what a fresh walk gives, whatever
        /// perceived sets come between (larger, then smaller again), on random maps.
        #[test]
        fn remembered_paths_answer_like_a_fresh_walk(
            w in 2usize..12,
            h in 2usize..12,
            walls in proptest::collection::vec(0u8..4, 144),
            sets in proptest::collection::vec(proptest::collection::vec(0u8..5, 144), 1..5),
            pick in 0usize..144,
        ) {
            let case = crate::walled_problem(w, h, &walls, pick, SensorModel::Los(2.0));
            prop_assume!(case.is_some());
            let (p, _) = case.expect("assumed");
            let mut cache = FieldCache::new(&p, usize::MAX);
            let mut fresh = StepCosts::new(&p);
            let reach: Vec<u32> = (0..w * h).filter(|&i| p.reachable(i)).map(|i| i as u32).collect();
            for seen in &sets {
                let bits = crate::perceived_marks(&p, seen, usize::MAX);
                for &a in &reach {
                    for &b in &reach {
                        let mut field = Vec::new();
                        fresh.field(a, &mut field);
                        let want = fresh.inside(&field, a, b, &bits);
                        prop_assert_eq!(cache.inside(a, b, &bits), want, "{} -> {}", a, b);
                    }
                }
            }
        }
    }
}
