//! Coverage candidates (Faigl & Kulich 2013, §IV, Algorithm 1, CC).
//!
//! For every reachable frontier cell f_i, the covering cells C_i are the reachable cells
//! from which a laser of range 0.8 ρ covers f_i (Line 3, ray casting; the shorter range
//! "supports navigation towards frontiers"). Then, while some frontier is uncovered, the
//! covering cell that covers the most still-uncovered frontiers becomes a goal candidate
//! (Lines 9–13). Deterministic: ties go to the lower cell index.
//!
//! A frontier cell is covered from c when the laser at c sees **unknown space next to it**
//! (one of its 8-neighbours that is unknown), not merely the frontier cell itself. The paper
//! does not spell out "covered"; the frontier is free space bordering the unknown, and
//! covering it is meant to reveal that unknown. The difference matters on grids: a free cell
//! whose only unknown neighbour is a wall cell seen edge-on (the cells along a wall near a
//! corner) is seen from most of a room, but its unknown neighbour only from a few cells. A
//! robot sent to a cell that sees the frontier cell but not the unknown learns nothing;
//! the cell goes on the visited list, and the next decision sends it to the next such
//! cell, so that a team sweeps the room row by row (on the `faigl2013` suite's 21 × 24 m
//! open space with ρ = 7 m and 3 robots, HA–CC's mean longest path was then more than twice
//! HA–RFE's; docs/reproduce.md has the numbers).
//!
//! How it is computed: visibility under the exact segment rule of `sense::segment` is
//! symmetric between two cells when the far end is exempt from the "crossed cells are free"
//! test at either end (the same cells are crossed and the same vertices touched either
//! way), so the cells that see an unknown cell u are what a line-of-sight scan *from* u
//! sees, with u itself taken as free: one scan per unknown cell next to a frontier, over a
//! copy of the belief (unknown cells are opaque) — by shadow casting ([`sense::shadow`],
//! time ∝ the cells looked at) from 20 cells of range on, by the shared ray template below
//! — keeping free cells that are traversable, reachable and not on the goal lists. C_i is
//! the union of the scans of f_i's unknown neighbours. Each unknown cell is scanned once
//! per decision however many frontier cells it borders, and every cell its scan reports
//! gets those frontier cells in a bit set per covering cell (one bit per frontier cell, so
//! a union needs no deduplication). The greedy choice takes candidates lazily from buckets
//! by their uncovered counts, recounted from the bit sets when taken (counts only fall, so
//! an entry whose count is current is the maximum). Cost ∝ the number of (unknown cell,
//! covering cell) pairs, plus covering cells × frontier cells / 64; all buffers live in
//! [`State`] and are reused.
//!
//! Choices where the paper is silent:
//! - "covered" is as above;
//! - "reachable" is reachability from the first deciding robot (all free space of a run is
//!   one component; Faigl & Kulich assume the same);
//! - frontier cells on the visited/inaccessible lists are not to be covered (a robot stood
//!   there and sensed), and listed cells are never candidates; a frontier cell that no
//!   eligible cell covers is left uncovered rather than looping;
//! - the ray casting is the ideal laser of `sense` (`los`) whatever the robots' sensor is,
//!   as the paper's omnidirectional scanner; ρ is the run's sensor range in cells.
//!
//! Deviation on fine maps: on maps of half [`COVER_CELL_M`] or finer the cover is computed
//! on blocks of `b × b` cells, b the most whole cells that fit in that width ([`cover_block`];
//! b = 2 at 0.05 m, 3 at 0.03 m; coarser maps have b = 1, cell by cell), as the
//! segmenting presets segment them. Faigl & Kulich's grids have cells of "units (or tens)
//! of centimetres"; at 0.05 m with an 8 m laser a frontier cell's unknown neighbours are
//! each seen from up to 51,000 cells, and the (frontier, covering cell) pairs — ∝
//! 1/resolution³ at a fixed range in metres — made CC 70 % of a 5-robot run on a 0.05 m
//! floor plan. On blocks the pairs and the scans are b³ times fewer. A block is occupied
//! when any of its cells is, else unknown when any is, else free; the frontier cells to
//! cover are grouped by block (a block is covered, and credited with its frontier cells,
//! when an unknown block next to one of them is seen); the laser looks from block to
//! block with range 0.8 ρ / b; and the greedy cover takes the blocks in the order of their
//! counts, ties to their eligible cell nearest the block's centre (then the lower index).
//! What blocks see is not what a robot sees from a cell, so two checks keep the cover
//! sound: a block taken goes through its first eligible cell, nearest the centre first,
//! that sees (cell by cell, within 0.8 ρ) unknown next to a frontier cell it newly covers,
//! and is dropped if no cell does; and the frontier cells that no block covers (beside a
//! wall every block is occupied, so a strip one cell wide has no free block) are covered
//! cell by cell as above, their candidates appended. Without the checks a block seeing an
//! unknown block through a hole one cell wide sent robots to cells that see nothing, one
//! cell of the block after another (each goes on the visited list when reached), and a
//! team walked a room cell by cell. Maps coarser than 5 cm, the `faigl2013` suite's
//! among them, are covered cell by cell as above.

use sense::shadow::{self, ShadowScratch};
use sense::{LosSensor, MAX_TEMPLATE_RANGE_CELLS};

use grid::{Grid, Occ};

use super::CandidateSet;
use crate::belief_rows::{LogPos, RowLog, sync_rows};
use crate::decision::DecisionCtx;

/// Fraction of the sensor range used for covering (Faigl & Kulich: 0.8 ρ).
pub const COVER_FRACTION: f64 = 0.8;

/// The cover is computed on blocks of as many whole cells as fit in this many metres (see
/// the module documentation).
pub const COVER_CELL_M: f64 = 0.1;

/// The block side, in cells, of the cover on a map of `resolution` metres per cell.
pub fn cover_block(resolution: f64) -> usize {
    crate::segment::cache::block_side(COVER_CELL_M, resolution)
}

/// Bytes the cover's scans hold at their largest in one decision, on a map of `cells`
/// cells of `resolution` metres with a sensor of `range_cells` cells: each unknown block
/// next to the frontier keeps the free blocks its scan sees within the covering range (4
/// bytes each, and 8 in the (target, key) incidences). A frontier about as long as the
/// covering disk's circumference, each of its blocks seeing the whole disk, bounds what
/// was measured (an open 24 × 18 m space at 0.05 m with an 8 m laser: 70 MiB at most
/// against this bound's 59 MiB plus the per-cell part); the disk and the frontier are
/// never counted larger than the map. It grows with the cube of the range, not with the
/// map.
pub fn scan_bytes_bound(cells: usize, range_cells: f64, resolution: f64) -> u64 {
    let b = cover_block(resolution) as f64;
    let r = COVER_FRACTION * range_cells.max(0.0) / b;
    let blocks = cells as f64 / (b * b);
    let keys = (2.0 * std::f64::consts::PI * r).min(blocks);
    let disk = (std::f64::consts::PI * r * r).min(blocks);
    // saturates as a float cast does: no estimate exceeds u64::MAX bytes
    (keys * disk * 12.0) as u64
}

/// The key set's word of a cell already found not to be a covering cell in this decision
/// (no key set starts there: a set's words are fewer than the keys).
const NOT_ELIGIBLE: u32 = u32::MAX;

/// Visibility buffers and the last cover, kept across decisions.
#[derive(Default)]
pub struct State {
    /// The ray template, for ranges where it is faster than shadow casting.
    template: Option<(f64, LosSensor)>,
    /// F: the frontier cells to cover, grouped by key (the block they lie in; on maps
    /// covered cell by cell a key is one frontier cell).
    front: Vec<u32>,
    /// Key k holds the frontier cells `front[key_start[k]..key_start[k + 1]]`.
    key_start: Vec<u32>,
    /// Each frontier cell's key with the cell, `key << 32 | cell`, sorted to group
    /// `front` by key (the keys computed once, not at each comparison of the sort).
    keyed: Vec<u64>,
    /// Key k's key (its block, or its frontier cell on maps covered cell by cell).
    key_of: Vec<u32>,
    /// The cells of the scanned grid whose scans cover the key at hand.
    targets: Vec<u32>,
    /// (target, key) incidences: key k is covered from any cell that sees its target (a
    /// cell of the scanned grid), sorted by target.
    pairs: Vec<(u32, u32)>,
    /// The keys of the target at hand, as (word, bits) of a key bit set.
    masks: Vec<(usize, u64)>,
    /// The blocks of fine maps (unused when the cover is cell by cell).
    coarse: Coarse,
    /// Per scanned cell, valid where its stamp is `epoch`: its candidate's key set, or
    /// none (`NOT_ELIGIBLE` as the word). One load per (target, covering cell) pair finds
    /// where to set the target's bits; the pairs are the cover's hot loop.
    cell_span: Vec<(u32, Span)>,
    epoch: u32,
    /// Candidate id → map cell (a block's representative cell on fine maps).
    cands: Vec<u32>,
    /// Fine maps: candidate id → its block (index into the blocks' grid).
    cand_block: Vec<u32>,
    /// Fine maps: a block's eligible cells in the order they are tried, and the buffers
    /// of the scans that check them.
    tried: Vec<(i64, u32)>,
    unknown: Vec<u32>,
    /// Fine maps: the frontier cells no block covers, and the state of their cover cell by
    /// cell.
    left: Vec<u32>,
    fine: Option<Box<State>>,
    /// Per row of the scanned grid, and one more: the keys in the rows above it.
    row_keys: Vec<u32>,
    /// Candidate id → where its set of the keys it covers lies in `bits`.
    spans: Vec<Span>,
    /// The candidates' key bit sets (only the words of the keys near each), flat.
    bits: Vec<u64>,
    /// The keys some candidate covers, and those covered by the candidates chosen so far.
    coverable: Vec<u64>,
    covered: Vec<u64>,
    /// The greedy cover's candidates by count: bucket n holds [`cell_id`]s.
    buckets: Vec<Vec<u64>>,
    /// The chosen candidates in order, and the frontier cells credited to each.
    chosen: Vec<u32>,
    credit_start: Vec<u32>,
    credit: Vec<u32>,
    /// Visibility kept across decisions (see [`Visibility`]).
    vis: Visibility,
}

/// Side of the square blocks in which belief changes are tracked, in cells.
const BLOCK: usize = 16;

/// What each unknown cell next to a frontier is seen from, kept across decisions: the free
/// cells a scan from it reports (before the per-decision eligibility filter), and the
/// blocks of cells the scan looked at. A scan's result depends only on the cells it looked at (the cells it
/// reported, blocking ones included, and the cells beside them that the diagonal squeeze
/// test reads), so it stays valid until a cell in that box of blocks changes. Changes are
/// found by comparing the belief with its copy from the last decision, block by block.
#[derive(Default)]
struct Visibility {
    /// The belief at the last decision (equal to the current one once [`Self::start`] ran;
    /// scans read it, with their origin set free for the scan's duration).
    prev: Grid<Occ>,
    /// How far `prev` has followed the scanned grid's row log.
    pos: LogPos,
    /// Per block: the decision that last saw a change in it.
    changed_at: Vec<u32>,
    blocks_x: usize,
    /// Decisions counted from 1.
    decision: u32,
    /// Per cell: its entry in `entries`, or `NONE`.
    slot: Vec<u32>,
    entries: Vec<Seen>,
    /// Entries not in use.
    spare: Vec<u32>,
    /// Per entry: still a frontier to cover in this decision.
    used: Vec<u32>,
    /// Buffers of the shadow-casting scans.
    scratch: ShadowScratch,
}

/// No cache entry.
const NONE: u32 = u32::MAX;

/// One unknown cell's scan.
#[derive(Default)]
struct Seen {
    cell: u32,
    /// The decision it was scanned in.
    made: u32,
    /// Blocks looked at: columns `bx0..=bx1`, rows `by0..=by1`.
    bx0: u32,
    by0: u32,
    bx1: u32,
    by1: u32,
    /// Free cells reported, in scan order.
    free: Vec<u32>,
}

impl Visibility {
    /// Start a decision on `known` (whose changed rows `log` keeps): note the blocks
    /// changed since the last one.
    fn start(&mut self, known: &Grid<Occ>, log: &RowLog) {
        let (w, h) = (known.width(), known.height());
        let data = known.data();
        self.decision += 1;
        if self.prev.width() != w || self.prev.height() != h {
            self.prev = known.clone();
            self.pos = LogPos::default();
            self.blocks_x = w.div_ceil(BLOCK);
            self.changed_at = vec![0; self.blocks_x * h.div_ceil(BLOCK)];
            self.slot = vec![NONE; data.len()];
            self.entries.clear();
            self.spare.clear();
            self.used.clear();
            return;
        }
        let (changed_at, blocks_x, decision) = (&mut self.changed_at, self.blocks_x, self.decision);
        let follow = (log, &mut self.pos);
        sync_rows(known, &mut self.prev, BLOCK, follow, |y, bx, _, _| {
            changed_at[(y / BLOCK) * blocks_x + bx] = decision;
        });
    }

    /// Whether entry `e` is still what a scan would report.
    fn valid(&self, e: &Seen) -> bool {
        e.made == self.decision
            || (e.by0..=e.by1).all(|by| {
                let row = by as usize * self.blocks_x;
                self.changed_at[row + e.bx0 as usize..=row + e.bx1 as usize]
                    .iter()
                    .all(|&c| c < e.made)
            })
    }

    /// The entry of unknown cell `u`: the cells that see it within `range` cells, scanned
    /// again if the belief changed where the last scan looked.
    fn get(&mut self, u: u32, range: f64, template: Option<&LosSensor>) -> u32 {
        let mut k = self.slot[u as usize];
        if k != NONE && self.valid(&self.entries[k as usize]) {
            self.used[k as usize] = self.decision;
            return k;
        }
        if k == NONE {
            k = self.spare.pop().unwrap_or_else(|| {
                self.entries.push(Seen::default());
                self.used.push(0);
                (self.entries.len() - 1) as u32
            });
            self.slot[u as usize] = k;
        }
        self.used[k as usize] = self.decision;
        let Visibility {
            prev,
            entries,
            scratch,
            blocks_x,
            changed_at,
            decision,
            ..
        } = self;
        let e = &mut entries[k as usize];
        e.cell = u;
        e.made = *decision;
        e.free.clear();
        // A segment from u is clear if every cell it crosses but the far end is free, u
        // included: u is taken as free for its own scan (never "touched" at a vertex, so
        // nothing else changes).
        let was = prev.data()[u as usize];
        prev.data_mut()[u as usize] = Occ::Free;
        let known = &*prev;
        let origin = known.cell(u as usize);
        let mut push = |i: u32, s: Occ| {
            if s == Occ::Free && i != u {
                e.free.push(i);
            }
        };
        if let Some(sensor) = template {
            // Short ranges: the ray template is the faster walk.
            let w = known.width();
            let (bw, bh) = (*blocks_x, changed_at.len() / (*blocks_x).max(1));
            let (ux, uy) = (u as usize % w, u as usize / w);
            let (mut x0, mut x1, mut y0, mut y1) = (ux, ux, uy, uy);
            sensor.for_each_seen(known, origin, |i, s| {
                let (x, y) = (i as usize % w, i as usize / w);
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
                push(i, s);
            });
            // one cell more each way: the squeeze test reads the cells beside a diagonal step
            e.bx0 = (x0.saturating_sub(1) / BLOCK) as u32;
            e.by0 = (y0.saturating_sub(1) / BLOCK) as u32;
            e.bx1 = ((x1 + 1) / BLOCK).min(bw - 1) as u32;
            e.by1 = ((y1 + 1) / BLOCK).min(bh - 1) as u32;
        } else {
            let read = shadow::visible(known, origin, range, |s| s == Occ::Free, scratch, push);
            // The scan read only the cells of this box, so it stays valid until one changes.
            if let Some(b) = read {
                e.bx0 = (b.x0 / BLOCK) as u32;
                e.by0 = (b.y0 / BLOCK) as u32;
                e.bx1 = (b.x1 / BLOCK) as u32;
                e.by1 = (b.y1 / BLOCK) as u32;
            }
        }
        prev.data_mut()[u as usize] = was;
        k
    }

    /// Drop the entries of cells that no frontier to cover needed in this decision.
    fn sweep(&mut self) {
        for k in 0..self.entries.len() {
            let cell = self.entries[k].cell as usize;
            if self.used[k] != self.decision && self.slot.get(cell) == Some(&(k as u32)) {
                self.slot[cell] = NONE;
                self.entries[k].free = Vec::new();
                self.spare.push(k as u32);
            }
        }
    }
}

/// The belief on blocks of `block × block` cells, kept up from the rows that changed.
#[derive(Default)]
struct Coarse {
    block: usize,
    /// The fine belief it was made from, and how far it has followed the belief's row log.
    fine: Grid<Occ>,
    pos: LogPos,
    /// One cell per block: occupied if any cell is, else unknown if any is, else free.
    grid: Grid<Occ>,
    /// The rows of `grid` each update changed.
    log: RowLog,
    /// Blocks to recompute, and a mark per block against listing one twice.
    dirty: Vec<u32>,
    marked: Vec<bool>,
}

impl Coarse {
    /// Bring the blocks up to `known`, whose changed rows `log` keeps (work ∝ the rows that
    /// changed).
    fn update(&mut self, known: &Grid<Occ>, block: usize, log: &RowLog) {
        let (w, h) = (known.width(), known.height());
        let cw = w.div_ceil(block);
        if self.block != block || self.fine.width() != w || self.fine.height() != h {
            self.block = block;
            self.fine = known.clone();
            self.pos = LogPos::default();
            self.grid = Grid::new(cw, h.div_ceil(block), Occ::Free);
            self.log = RowLog::new(self.grid.height());
            self.marked = vec![false; self.grid.len()];
            for b in 0..self.grid.len() {
                self.grid[b] = block_state(known, block, cw, b);
            }
            return;
        }
        let (marked, dirty) = (&mut self.marked, &mut self.dirty);
        let follow = (log, &mut self.pos);
        sync_rows(known, &mut self.fine, block, follow, |y, bx, _, _| {
            let b = (y / block) * cw + bx;
            if !marked[b] {
                marked[b] = true;
                dirty.push(b as u32);
            }
        });
        self.log.begin();
        for &b in &self.dirty {
            let state = block_state(known, block, cw, b as usize);
            if self.grid[b as usize] != state {
                self.grid[b as usize] = state;
                self.log.mark_row(b as usize / cw);
            }
            self.marked[b as usize] = false;
        }
        self.dirty.clear();
    }

    /// The block of map cell `i` (`w` = the map's width).
    #[inline]
    fn of(&self, i: usize, w: usize) -> usize {
        (i / w / self.block) * self.grid.width() + (i % w) / self.block
    }
}

/// The state of block `b` (`cw` blocks a row): occupied if any cell is, else unknown if any
/// is, else free.
fn block_state(known: &Grid<Occ>, block: usize, cw: usize, b: usize) -> Occ {
    let (w, h) = (known.width(), known.height());
    let (x0, y0) = ((b % cw) * block, (b / cw) * block);
    let (x1, y1) = ((x0 + block).min(w), (y0 + block).min(h));
    let mut state = Occ::Free;
    for y in y0..y1 {
        for &c in &known.data()[y * w + x0..y * w + x1] {
            match c {
                Occ::Occupied => return Occ::Occupied,
                Occ::Unknown => state = Occ::Unknown,
                Occ::Free => {}
            }
        }
    }
    state
}

impl State {
    /// The frontier cells the last decision had to cover.
    pub fn frontiers(&self) -> &[u32] {
        &self.front
    }

    /// The candidates of the last decision in the order chosen, each with the frontier
    /// cells it newly covered when chosen.
    pub fn credits(&self) -> impl Iterator<Item = (u32, &[u32])> + '_ {
        self.chosen.iter().enumerate().map(|(k, &c)| {
            let (a, b) = (
                self.credit_start[k] as usize,
                self.credit_start[k + 1] as usize,
            );
            (c, &self.credit[a..b])
        })
    }
}

/// Fill `out` with a greedy cover of the reachable frontier cells.
pub fn generate(ctx: &mut DecisionCtx<'_>, out: &mut CandidateSet) {
    let mut st = std::mem::take(&mut ctx.memory.coverage);
    cover(ctx, &mut st);
    for &c in &st.chosen {
        out.insert(c);
    }
    ctx.memory.coverage = st;
}

/// The cover: on blocks for fine maps, then cell by cell for the frontier cells that no
/// block covers (module documentation); cell by cell on the others.
fn cover(ctx: &mut DecisionCtx<'_>, st: &mut State) {
    let block = cover_block(ctx.resolution);
    cover_on(ctx, st, block, None);
    if block == 1 {
        return;
    }
    st.left.clear();
    for kk in 0..st.key_start.len().saturating_sub(1) {
        if st
            .covered
            .get(kk / 64)
            .is_none_or(|w| w >> (kk % 64) & 1 == 0)
        {
            st.left
                .extend_from_slice(key_cells(&st.front, &st.key_start, kk));
        }
    }
    if st.left.is_empty() {
        return;
    }
    let mut fine = st.fine.take().unwrap_or_default();
    let left = std::mem::take(&mut st.left);
    cover_on(ctx, &mut fine, 1, Some(&left));
    st.left = left;
    for (c, credited) in fine.credits() {
        if !st.chosen.contains(&c) {
            st.chosen.push(c);
            st.credit.extend_from_slice(credited);
            st.credit_start.push(st.credit.len() as u32);
        }
    }
    st.fine = Some(fine);
}

/// The greedy cover on blocks of `block × block` cells of the frontier cells `only` (all
/// reachable ones if `None`).
fn cover_on(ctx: &mut DecisionCtx<'_>, st: &mut State, block: usize, only: Option<&[u32]>) {
    st.front.clear();
    st.key_start.clear();
    st.pairs.clear();
    st.cands.clear();
    st.cand_block.clear();
    st.bits.clear();
    st.spans.clear();
    st.chosen.clear();
    st.credit.clear();
    st.credit_start.clear();
    st.credit_start.push(0);
    let Some(r) = ctx.deciding.iter().position(|&d| d) else {
        return;
    };
    let range = (COVER_FRACTION * ctx.sensor_range_cells / block as f64)
        .clamp(0.0, MAX_TEMPLATE_RANGE_CELLS);
    let range = if range.is_finite() { range } else { 0.0 };
    if range >= shadow::FASTER_FROM_RANGE {
        st.template = None;
    } else if st.template.as_ref().is_none_or(|(r0, _)| *r0 != range) {
        match LosSensor::new(range) {
            Ok(s) => st.template = Some((range, s)),
            Err(_) => return, // unreachable: the range was clamped into the valid interval
        }
    }
    let known = ctx.known;
    let w = known.width();
    if block > 1 {
        st.coarse.update(known, block, ctx.upkeep.row_log());
    }
    // The grid the laser looks over: the belief, or its blocks on fine maps.
    let scanned = if block > 1 { &st.coarse.grid } else { known };
    let n = scanned.len();
    if st.cell_span.len() != n {
        st.cell_span = vec![(0, Span::default()); n];
        st.epoch = 0;
    }
    st.epoch = crate::upkeep::next_gen(st.epoch, &mut st.cell_span);

    let lists = ctx.lists;
    let reach = ctx.planner.component(r, ctx.robots[r], known, ctx.upkeep);
    let upkeep = &*ctx.upkeep;
    let scanned_log = if block > 1 {
        &st.coarse.log
    } else {
        upkeep.row_log()
    };
    st.vis.start(scanned, scanned_log);
    let coarse = &st.coarse;
    let key = |i: u32| -> u32 {
        if block > 1 {
            coarse.of(i as usize, w) as u32
        } else {
            i
        }
    };
    // An eligible map cell: traversable, reached, on no list.
    let eligible = |i: usize| {
        upkeep.is_traversable(known, i) && !lists.is_excluded(i as u32) && reach.contains(i)
    };

    // Lines 2–4: covering cells of every frontier cell (of every key).
    st.keyed.clear();
    st.key_of.clear();
    for &f in only.unwrap_or(upkeep.frontiers.cells()) {
        if lists.is_excluded(f) || !reach.contains(f as usize) {
            continue;
        }
        st.keyed.push(u64::from(key(f)) << 32 | u64::from(f));
    }
    // Frontier order is the upkeep's (history dependent); sort for determinism by index.
    st.keyed.sort_unstable();
    for (k, &kf) in st.keyed.iter().enumerate() {
        let kk = (kf >> 32) as u32;
        if st.key_of.last() != Some(&kk) {
            st.key_start.push(k as u32);
            st.key_of.push(kk);
        }
        st.front.push(kf as u32);
    }
    st.key_start.push(st.front.len() as u32);
    let nk = st.key_start.len() - 1;
    // The (target, key) incidences: key k is covered from what sees one of its targets.
    for kk in 0..nk {
        st.targets.clear();
        for &f in key_cells(&st.front, &st.key_start, kk) {
            for u in known.neighbours8(f as usize) {
                let t = key(u as u32);
                if known[u] == Occ::Unknown && !st.targets.contains(&t) {
                    st.targets.push(t);
                }
            }
        }
        st.pairs.extend(st.targets.iter().map(|&t| (t, kk as u32)));
    }
    st.pairs.sort_unstable();
    // Each candidate's keys as a bit set; one scan per target, whose cells all get the
    // target's keys. A candidate's set spans only the words of the keys whose rows it can
    // cover (a scan reports cells within `range` rows of its target, and a key lies within
    // a row of its target), so the sets take memory ∝ the keys near each candidate.
    let words = nk.div_ceil(64).max(1);
    let (sw, sh) = (scanned.width(), scanned.height());
    st.row_keys.clear();
    st.row_keys.resize(sh + 1, 0);
    for kk in 0..nk {
        let kc = st.key_of[kk] as usize;
        st.row_keys[kc / sw + 1] += 1;
    }
    for y in 0..sh {
        st.row_keys[y + 1] += st.row_keys[y];
    }
    let rows = range.ceil() as usize + 1;
    st.covered.clear();
    st.covered.resize(words, 0);
    let template = st.template.as_ref().map(|t| &t.1);
    // Spans of every key, if a key ever fell outside a candidate's rows (it cannot).
    let mut full = false;
    loop {
        st.cands.clear();
        st.cand_block.clear();
        st.bits.clear();
        st.spans.clear();
        st.coverable.clear();
        st.coverable.resize(words, 0);
        let mut spilled = false;
        let (cell_span, epoch) = (&mut st.cell_span, st.epoch);
        let (cands, cand_block, bits, spans, masks) = (
            &mut st.cands,
            &mut st.cand_block,
            &mut st.bits,
            &mut st.spans,
            &mut st.masks,
        );
        let row_keys = &st.row_keys;
        for group in st.pairs.chunk_by(|a, b| a.0 == b.0) {
            // the target's keys as (word, bits), words ascending (keys are)
            masks.clear();
            for &(_, kk) in group {
                let (w, b) = (kk as usize / 64, 1u64 << (kk % 64));
                match masks.last_mut() {
                    Some((lw, lm)) if *lw == w => *lm |= b,
                    _ => masks.push((w, b)),
                }
            }
            let k = st.vis.get(group[0].0, range, template);
            let mut seen_by_any = false;
            for &i in &st.vis.entries[k as usize].free {
                let iu = i as usize;
                let (at_epoch, known_span) = cell_span[iu];
                let sp = if at_epoch == epoch {
                    known_span
                } else {
                    let cell = if block > 1 {
                        representative(known, block, coarse.grid.width(), iu, &eligible)
                    } else {
                        eligible(iu).then_some(i)
                    };
                    let Some(cell) = cell else {
                        cell_span[iu] = (
                            epoch,
                            Span {
                                word: NOT_ELIGIBLE,
                                ..Span::default()
                            },
                        );
                        continue;
                    };
                    cands.push(cell);
                    cand_block.push(i);
                    let (w0, w1) = if full {
                        (0, words)
                    } else {
                        let y = iu / sw;
                        let lo = row_keys[y.saturating_sub(rows)] as usize;
                        let hi = row_keys[(y + rows + 1).min(sh)] as usize;
                        (lo / 64, hi.div_ceil(64).max(lo / 64))
                    };
                    let sp = Span {
                        word: w0 as u32,
                        at: bits.len() as u32,
                        len: (w1 - w0) as u32,
                    };
                    spans.push(sp);
                    cell_span[iu] = (epoch, sp);
                    bits.resize(bits.len() + w1 - w0, 0);
                    sp
                };
                if sp.word == NOT_ELIGIBLE {
                    continue;
                }
                seen_by_any = true;
                for &(w, m) in masks.iter() {
                    let j = w.wrapping_sub(sp.word as usize);
                    if j < sp.len as usize {
                        bits[sp.at as usize + j] |= m;
                    } else {
                        spilled = true;
                    }
                }
            }
            if seen_by_any {
                for &(w, m) in masks.iter() {
                    st.coverable[w] |= m;
                }
            }
        }
        if !spilled || full {
            break;
        }
        debug_assert!(false, "a key outside the rows its covering cell can see");
        full = true;
        st.epoch = crate::upkeep::next_gen(st.epoch, &mut st.cell_span);
    }
    st.vis.sweep();

    // Lines 9–13: greedy cover, lazily, on buckets of candidates by their count of
    // uncovered keys as last counted, ties to the lower cell index. Counts only fall, so a
    // taken entry whose count is current is the maximum; one whose count fell goes to a
    // lower bucket. No entry ever enters the bucket being taken from or one above it, so
    // each bucket is sorted once, when it is reached, and the order is a max-heap's on
    // (count, lower cell) without its cost per entry. It stops once every key that some
    // candidate covers is covered.
    let buckets = &mut st.buckets;
    for b in buckets.iter_mut() {
        b.clear();
    }
    for (id, &c) in st.cands.iter().enumerate() {
        let n = ones(st.spans[id].of(&st.bits)) as usize;
        if n > 0 {
            if buckets.len() <= n {
                buckets.resize_with(n + 1, Vec::new);
            }
            buckets[n].push(cell_id(c, id as u32));
        }
    }
    let mut k = buckets.len().saturating_sub(1);
    let mut sorted = usize::MAX;
    let mut left = ones(&st.coverable);
    while left > 0 {
        while k > 0 && buckets[k].is_empty() {
            k -= 1;
        }
        if k == 0 {
            break;
        }
        if sorted != k {
            // descending by cell: the lowest is taken first, from the end (a candidate's
            // cell is its own, so the id never decides)
            buckets[k].sort_unstable_by(|a, b| b.cmp(a));
            sorted = k;
        }
        let Some(entry) = buckets[k].pop() else {
            break;
        };
        let (cell, id) = ((entry >> 32) as u32, entry as u32);
        let cnt = k as u32;
        let sp = st.spans[id as usize];
        let row = sp.of(&st.bits);
        let covered = &st.covered[sp.word as usize..][..row.len()];
        let now: u32 = row
            .iter()
            .zip(covered.iter())
            .map(|(b, c)| (b & !c).count_ones())
            .sum();
        if now == 0 {
            continue;
        }
        if now != cnt {
            buckets[now as usize].push(entry);
            continue;
        }
        // On blocks, the candidate goes through a cell of its block that sees, cell by
        // cell, unknown space next to a frontier cell it is credited with; a block with no
        // such cell is no candidate (module documentation).
        let cell = if block > 1 {
            // The unknown cells next to the frontier cells of the keys it would newly cover.
            st.unknown.clear();
            for kk in new_keys(row, covered, sp.word) {
                for &f in key_cells(&st.front, &st.key_start, kk) {
                    for u in known.neighbours8(f as usize) {
                        if known[u] == Occ::Unknown {
                            st.unknown.push(u as u32);
                        }
                    }
                }
            }
            st.unknown.sort_unstable();
            st.unknown.dedup();
            let cells = eligible_by_centre(
                known,
                block,
                st.coarse.grid.width(),
                st.cand_block[id as usize] as usize,
                &eligible,
            );
            let range = COVER_FRACTION * ctx.sensor_range_cells;
            let Some(c) = seeing_cell(known, cells, range, &st.unknown, &mut st.tried) else {
                continue;
            };
            c
        } else {
            cell
        };
        st.chosen.push(cell);
        let covered = &mut st.covered[sp.word as usize..][..row.len()];
        for k in new_keys(row, covered, sp.word) {
            st.credit
                .extend_from_slice(key_cells(&st.front, &st.key_start, k));
        }
        for (c, &b) in covered.iter_mut().zip(row) {
            *c |= b;
        }
        left -= now;
        st.credit_start.push(st.credit.len() as u32);
    }
}

/// The keys set in `row` (a candidate's set, from key word `word` on) and not in `covered`
/// (the same words of the covered keys): those the candidate would newly cover, ascending.
fn new_keys<'a>(row: &'a [u64], covered: &'a [u64], word: u32) -> impl Iterator<Item = usize> + 'a {
    row.iter()
        .zip(covered)
        .enumerate()
        .flat_map(move |(j, (&b, &c))| {
            let base = (word as usize + j) * 64;
            let mut new = b & !c;
            std::iter::from_fn(move || {
                (new != 0).then(|| {
                    let k = base + new.trailing_zeros() as usize;
                    new &= new - 1;
                    k
                })
            })
        })
}

/// The frontier cells of key `k`: `front[key_start[k]..key_start[k + 1]]`.
fn key_cells<'a>(front: &'a [u32], key_start: &[u32], k: usize) -> &'a [u32] {
    &front[key_start[k] as usize..key_start[k + 1] as usize]
}

/// Where a candidate's key bit set lies: it holds the words `word..word + len` of a set
/// over all keys, stored at `bits[at..at + len]`.
#[derive(Clone, Copy, Debug, Default)]
struct Span {
    word: u32,
    at: u32,
    len: u32,
}

impl Span {
    /// The stored words of this set in `bits`.
    #[inline]
    fn of(self, bits: &[u64]) -> &[u64] {
        &bits[self.at as usize..(self.at + self.len) as usize]
    }
}

/// A bucket entry: candidate `id` whose cell is `cell`, ordered by cell as one integer.
fn cell_id(cell: u32, id: u32) -> u64 {
    u64::from(cell) << 32 | u64::from(id)
}

/// The number of bits set in `words`.
fn ones(words: &[u64]) -> u32 {
    words.iter().map(|w| w.count_ones()).sum()
}

/// The cell through which a free block is a chosen candidate: the first of its eligible
/// `cells` ([`eligible_by_centre`]), nearest the block's centre first (ties to the lower
/// index), that sees one of the cells `unknown` within `range` cells, cell by cell over the
/// belief; `None` if none sees one.
///
/// The cover on blocks looks from block to block, which is not what a robot's laser sees
/// from a cell: a ray between two blocks may pass where every ray between their cells is
/// blocked (through a doorway one cell wide, say), and the block's centre may see less than
/// another of its cells. A candidate that sees nothing it is credited with would send a
/// robot to learn nothing; its cell goes on the visited list, the next decision offers the
/// next cell of the same block, and a team walks the free space cell by cell.
fn seeing_cell(
    known: &Grid<Occ>,
    cells: impl Iterator<Item = (i64, u32)>,
    range: f64,
    unknown: &[u32],
    tried: &mut Vec<(i64, u32)>,
) -> Option<u32> {
    tried.clear();
    tried.extend(cells);
    tried.sort_unstable();
    tried.iter().map(|&(_, c)| c).find(|&c| {
        let from = known.cell(c as usize);
        unknown
            .iter()
            .any(|&u| sense::segment::seen_from(known, from, known.cell(u as usize), range))
    })
}

/// The cell through which free block `b` (`cw` blocks a row) is a candidate: its eligible
/// cell nearest the block's centre, ties to the lower index; `None` if it has none.
fn representative(
    known: &Grid<Occ>,
    block: usize,
    cw: usize,
    b: usize,
    eligible: &impl Fn(usize) -> bool,
) -> Option<u32> {
    eligible_by_centre(known, block, cw, b, eligible)
        .min()
        .map(|(_, i)| i)
}

/// The eligible cells of block `b` (`cw` blocks a row), each with its squared distance from
/// the block's centre in doubled coordinates (so that even blocks have an integral centre).
fn eligible_by_centre<'a>(
    known: &Grid<Occ>,
    block: usize,
    cw: usize,
    b: usize,
    eligible: &'a impl Fn(usize) -> bool,
) -> impl Iterator<Item = (i64, u32)> + 'a {
    let (w, h) = (known.width(), known.height());
    let (x0, y0) = ((b % cw) * block, (b / cw) * block);
    let (cx2, cy2) = ((2 * x0 + block - 1) as i64, (2 * y0 + block - 1) as i64);
    (y0..(y0 + block).min(h))
        .flat_map(move |y| (x0..(x0 + block).min(w)).map(move |x| (x, y)))
        .filter(move |&(x, y)| eligible(y * w + x))
        .map(move |(x, y)| {
            let (dx, dy) = (2 * x as i64 - cx2, 2 * y as i64 - cy2);
            (dx * dx + dy * dy, (y * w + x) as u32)
        })
}
