//! Holz et al.'s reachability map: Dijkstra from the robot's cell with no goal, and the same
//! search stopping at the first settled goal cell (the nearest frontier, Yamauchi 1997);
//! also from a set of sources (distance to the nearest one).
//!
//! The priority queue is a bucket queue (Dial's algorithm with buckets one cell-step wide):
//! bucket k holds the cells whose cost lies in [k, k + 1). Every step costs at least 1, so a
//! cell settled from bucket k only labels cells in buckets k + 1 and k + 2, and when bucket k
//! is reached every cost in it is final: the search is exact, not an approximation, and
//! three buckets used in turn hold the whole wavefront (a ring of four serves the guided
//! search below too). Within a bucket the cells are taken
//! in the order they were labelled, except in the bucket where a nearest-goal search ends:
//! that one is taken in (cost, index) order up to the goal.
//!
//! The result is what a binary heap on (cost, index) gives, bit for bit: the same costs
//! (each is the minimum over final neighbour costs, whatever the order), the same goal and
//! the same set of settled cells (everything in earlier buckets, then the heap's order).
//! Predecessors are not stored: [`path_to`](Reachability::path_to) walks back from the goal
//! and takes, at each cell, the neighbour a heap would have settled first among those that
//! give the cell its cost (least (cost, index)), which is the heap's predecessor.
//!
//! The searches run in canonical order by default (`reachability/canonical.rs`): they
//! queue only the cells where shortest paths turn beside obstacles and label the others by
//! walking rows, columns and diagonals, then settle each bucket from the list of the cells
//! labelled in it. The settled cells, costs (path costs are exact sums, see
//! [`grid::SQRT2`]) and paths are those above; only the order within a bucket differs. The
//! guided search below does the same by cost plus bound, and settles only its goals (and
//! the start) until it is complete. [`Reachability::set_canonical`] turns it off (Dial's
//! searches, as the benches compare).
//!
//! Memory is what bounds the search, so the per-cell arrays are small and local: a state
//! byte (met, settled, impassable) and a cost per cell, both stored in 16 × 16 tiles so that
//! a wavefront going any way touches few cache lines and pages. `passable` is asked once per
//! cell and search, the answer kept in the state (a labelled cell is passable); the
//! no-squeezing test of a diagonal step uses the two straight neighbours just looked at. Bucket
//! entries carry column and row, so a settled cell costs no division. On the bench's
//! 2000 × 2000 map a full search takes about 0.18–0.24 s, 2.5–3 × less than with three
//! row-major arrays (costs, labelled and settled stamps) and `passable` asked at each step,
//! which was itself about 1.7 × as fast as the heap.
//!
//! A resumable search may be guided toward a set of goal cells ([`Reachability::begin_guided`],
//! A* toward a set, the bound of [`Guide`]): its buckets hold the cells by cost plus a lower
//! bound of their cost to the nearest goal, so it settles the goals in cost order while
//! leaving out the cells that lead away from every goal; a team assigner that needs a robot's
//! few cheapest goals far away searches toward them instead of around the robot. A bucket one
//! cell-step wide is no longer final when first taken (a step may leave cost plus bound
//! unchanged), so its cells are taken first in, first out, and a cell that gets a lower cost
//! from one taken after it in the same bucket is settled again, until none does: then every
//! cost in the bucket is the least over its neighbours' final costs, which is the unique
//! solution Dijkstra's search finds too. The guided search gives Dijkstra's costs bit for bit
//! and the same predecessors (every neighbour that gives a cell its cost is no farther from
//! the goals, so it is settled by then), and settles every goal below a bucket that
//! Dijkstra's does; only the other cells it settles differ (in canonical order, none but
//! the start until the search is complete). A rule that needs every goal's cost (MA) grows
//! it until the farthest goal is settled ([`Reachability::begin_goals`]): listing every
//! other cell by bucket for the resumable growth cost about a third of its decisions, and
//! the bound still leaves out the cells whose cost plus distance to the nearest goal
//! exceeds the farthest goal's cost (explored rooms away from every goal): 5–20 % of MA's
//! decisions. With goals in more blocks than [`MAX_GUIDE_BLOCKS`] the bound is 0.
//!
//! The states are generation-stamped per tile (a tile met first in a search has its states
//! cleared then), so a new search does not clear O(map) memory, and the buckets and the
//! settled list keep their capacity: in steady state a search allocates nothing and touches
//! only the tiles of the cells it meets.

mod canonical;

use super::guide::Guide;
use crate::upkeep::next_gen;
use canonical::{Queues, Walk};
use grid::SQRT2;

/// Buckets in use at once: a step costs at most √2 < 2, so Dijkstra's labels reach two
/// buckets ahead, a guided search's (cost plus a bound that changes by at most the step's
/// cost) three.
const BUCKETS: usize = 4;

/// State flag: the search met the cell (labelled it, or found it impassable).
const MET: u8 = 1;
/// Goals beyond which [`Reachability::nearest_guided`] first tries an unguided search.
pub const PROBE_FROM: usize = 1024;
/// That search settles at most one cell for this many goals past [`PROBE_FROM`]: setting
/// the guide costs a few nanoseconds a goal, settling a cell some tens. (On a 2000 × 2000
/// office at 0.05 m with `los:r=5`, whose frontier runs along every wall, `cf-rr` decides
/// in 1.8 s with it, 2.9 s without; on willow-full with Holz et al.'s laser the same.)
pub const PROBE_SHARE: usize = 8;

/// How [`Reachability::nearest_settled`] stopped.
enum Probe {
    /// The nearest goal.
    Found(usize),
    /// Every reachable cell settled, no goal among them.
    Exhausted,
    /// More cells settled than the budget, no goal among them yet.
    Budget,
}

/// State flag: the cell is settled (its cost is final).
const DONE: u8 = 2;
/// State flag: the cell is impassable (only the start is ever both this and labelled).
const BLOCKED: u8 = 4;
/// State flag: the cell is in the settled list (a guided search may settle a cell again).
const LISTED: u8 = 8;

/// A guided search with goals in more blocks than this is Dijkstra's: goals all around
/// (every frontier cell of a large map) make the bound weak, and the bound's cost then
/// outweighs the cells it saves. The canonical search asks the bound once per jump point,
/// so it pays off with more goals than Dial's, which asks it per label: with every
/// frontier cell as a goal (AF), 1024 blocks made willow's 5-robot runs 15–25 % faster
/// than 64, and CC's a few per cent slower (unlimited: slower again, each tile's list of
/// the nearest blocks being made from all of them).
pub const MAX_GUIDE_BLOCKS: usize = 1024;

/// [`MAX_GUIDE_BLOCKS`] for Dial's guided search
/// ([`set_canonical(false)`](Reachability::set_canonical)).
pub const MAX_DIAL_GUIDE_BLOCKS: usize = 64;

/// The per-cell arrays are stored in tiles of `TILE × TILE` cells (`TILE = 1 << TILE_SHIFT`),
/// one tile after the other by rows of tiles, each tile row-major.
const TILE_SHIFT: u32 = 4;
const TILE: usize = 1 << TILE_SHIFT;
const TILE_MASK: usize = TILE - 1;
/// Cells per tile.
const TILE_CELLS: usize = TILE * TILE;

/// A bucket entry: a cell's column and row.
type Entry = (u32, u32);

/// The slot of the cell in column `x`, row `y`, with `tile_row` slots per row of tiles.
#[inline(always)]
fn slot_xy(tile_row: usize, x: usize, y: usize) -> usize {
    (y >> TILE_SHIFT) * tile_row
        + ((x >> TILE_SHIFT) << (2 * TILE_SHIFT))
        + ((y & TILE_MASK) << TILE_SHIFT)
        + (x & TILE_MASK)
}

/// If slot `q`'s tile is met for the first time in search `epoch`, stamp it and return the
/// range of its slots, whose per-cell states the caller then forgets.
#[inline(always)]
fn enter_tile(tile_epoch: &mut [u32], epoch: u32, q: usize) -> Option<std::ops::Range<usize>> {
    let t = q >> (2 * TILE_SHIFT);
    (tile_epoch[t] != epoch).then(|| {
        tile_epoch[t] = epoch;
        t * TILE_CELLS..(t + 1) * TILE_CELLS
    })
}

/// Where a search puts the cells it labels.
trait Queue {
    /// Whether a settled cell is final (never labelled again).
    const FINAL: bool;
    /// Cell `xy` was labelled with cost `c`.
    fn push(&mut self, c: f64, xy: Entry);
    /// Whether settled cell `xy`, of cost `c`, may still get a lower cost.
    fn reopens(&mut self, c: f64, xy: Entry) -> bool;
}

/// Dijkstra's: the bucket of its cost; a settled cell is final.
impl Queue for &mut [Vec<Entry>; BUCKETS] {
    const FINAL: bool = true;

    #[inline(always)]
    fn push(&mut self, c: f64, xy: Entry) {
        self[c as usize % BUCKETS].push(xy);
    }

    #[inline(always)]
    fn reopens(&mut self, _: f64, _: Entry) -> bool {
        false
    }
}

/// A guided search's: the bucket of its cost plus the guide's bound, never one before
/// the bucket `current` being settled; a cell settled in that bucket may be settled again.
struct Guided<'a> {
    buckets: &'a mut [Vec<Entry>; BUCKETS],
    guide: &'a mut Guide,
    current: usize,
}

impl Guided<'_> {
    /// The bucket of cost `c` plus the bound at `(x, y)`.
    #[inline(always)]
    fn bucket(&mut self, c: f64, (x, y): Entry) -> usize {
        (c + self.guide.bound(x as usize, y as usize)) as usize
    }
}

impl Queue for Guided<'_> {
    const FINAL: bool = false;

    #[inline(always)]
    fn push(&mut self, c: f64, xy: Entry) {
        let k = self.bucket(c, xy).max(self.current);
        // a step adds at most √2 to the cost and to the bound: at most 2√2 to their sum
        debug_assert!(k < self.current + BUCKETS);
        self.buckets[k % BUCKETS].push(xy);
    }

    #[inline(always)]
    fn reopens(&mut self, c: f64, xy: Entry) -> bool {
        self.bucket(c, xy) >= self.current
    }
}

/// The per-cell arrays of a running search.
struct Wave<'a, Q> {
    epoch: u32,
    tile_epoch: &'a mut [u32],
    state: &'a mut [u8],
    cost: &'a mut [f64],
    queue: Q,
}

impl<Q: Queue> Wave<'_, Q> {
    /// Make the states of slot `q`'s tile valid for this search: the first time the search
    /// meets one of its cells, forget the older states.
    #[inline(always)]
    fn enter_tile(&mut self, q: usize) {
        if let Some(t) = enter_tile(self.tile_epoch, self.epoch, q) {
            self.state[t].fill(0);
        }
    }

    /// Meet cell `j` (column and row `xy`, slot `q`) at cost `c` from a settled neighbour:
    /// label it (or lower its label) if it is passable and not settled; its passability is
    /// looked up once per search and kept. `other_tile`: `j` may lie in a tile the search
    /// has not entered (a neighbour in the settled cell's own tile never does). Returns
    /// whether `j` is passable.
    #[inline(always)]
    fn visit(
        &mut self,
        passable: &impl Fn(usize) -> bool,
        (q, j, xy): (usize, usize, Entry),
        c: f64,
        other_tile: bool,
    ) -> bool {
        if other_tile {
            self.enter_tile(q);
        }
        let s = self.state[q];
        if s & MET != 0 {
            if s & BLOCKED != 0 {
                return false;
            }
            if Q::FINAL && s & DONE != 0 {
                return true; // settled for good: its cost is not even read
            }
            if c < self.cost[q] && (s & DONE == 0 || self.queue.reopens(self.cost[q], xy)) {
                self.state[q] = s & !DONE;
                self.cost[q] = c;
                self.queue.push(c, xy);
            }
            true
        } else if passable(j) {
            self.state[q] = MET;
            self.cost[q] = c;
            self.queue.push(c, xy);
            true
        } else {
            self.state[q] = MET | BLOCKED;
            false
        }
    }
}

impl<Q: Queue> Wave<'_, Q> {
    /// Label the neighbours of the settled cell at column and row `(xu, yu)` (slot `p`) on a
    /// grid of `dims = (width, height, slots per row of tiles)`.
    #[inline(always)]
    fn relax(
        &mut self,
        passable: &impl Fn(usize) -> bool,
        (w, h, tile_row): (usize, usize, usize),
        (xu, yu): Entry,
        p: usize,
    ) {
        let (x, y) = (xu as usize, yu as usize);
        let i = y * w + x;
        let ci = self.cost[p];
        let (left, right, up, down) = (x > 0, x + 1 < w, y > 0, y + 1 < h);
        // slot offsets of the steps right, left, down and up (wrapping: negative)
        let (xm, ym) = (x & TILE_MASK, y & TILE_MASK);
        let dr = if xm == TILE_MASK {
            TILE_CELLS - TILE_MASK
        } else {
            1
        };
        let dl = if xm == 0 { TILE_CELLS - TILE_MASK } else { 1 }.wrapping_neg();
        let dd = if ym == TILE_MASK {
            tile_row - TILE_MASK * TILE
        } else {
            TILE
        };
        let du = if ym == 0 {
            tile_row - TILE_MASK * TILE
        } else {
            TILE
        }
        .wrapping_neg();
        let (sr, sl) = (p.wrapping_add(dr), p.wrapping_add(dl));
        // the neighbours' columns and rows (wrapping: only used inside the grid)
        let (xr, xl) = (xu.wrapping_add(1), xu.wrapping_sub(1));
        let (yd, ya) = (yu.wrapping_add(1), yu.wrapping_sub(1));
        // whether a step right, left, down or up leaves the settled cell's tile
        let (xr_out, xl_out) = (xm == TILE_MASK, xm == 0);
        let (yd_out, yu_out) = (ym == TILE_MASK, ym == 0);
        let c1 = ci + 1.0;
        let pr = right && self.visit(passable, (sr, i + 1, (xr, yu)), c1, xr_out);
        let pd = down && self.visit(passable, (p.wrapping_add(dd), i + w, (xu, yd)), c1, yd_out);
        let pl = left && self.visit(passable, (sl, i - 1, (xl, yu)), c1, xl_out);
        let pu = up && self.visit(passable, (p.wrapping_add(du), i - w, (xu, ya)), c1, yu_out);
        let c2 = ci + SQRT2;
        if right && down && (pr || pd) {
            let q = sr.wrapping_add(dd);
            self.visit(passable, (q, i + w + 1, (xr, yd)), c2, xr_out || yd_out);
        }
        if left && down && (pl || pd) {
            let q = sl.wrapping_add(dd);
            self.visit(passable, (q, i + w - 1, (xl, yd)), c2, xl_out || yd_out);
        }
        if left && up && (pl || pu) {
            let q = sl.wrapping_add(du);
            self.visit(passable, (q, i - w - 1, (xl, ya)), c2, xl_out || yu_out);
        }
        if right && up && (pr || pu) {
            let q = sr.wrapping_add(du);
            self.visit(passable, (q, i - w + 1, (xr, ya)), c2, xr_out || yu_out);
        }
    }
}

/// Dijkstra over passable cells from one start: cost per cell, path extraction.
#[derive(Clone, Debug)]
pub struct Reachability {
    width: usize,
    height: usize,
    /// Tiles per row of tiles.
    tiles_x: usize,
    /// Per tile: the last search that met one of its cells; the tile's states are valid
    /// only if it is the current one (older ones mean "not met").
    tile_epoch: Vec<u32>,
    /// Per cell (by slot, see [`slot_xy`]): flags [`MET`], [`DONE`], [`BLOCKED`].
    state: Vec<u8>,
    /// Per cell (by slot): tentative or final cost if labelled in the current search.
    cost: Vec<f64>,
    epoch: u32,
    /// Bucket `k % BUCKETS` holds the cells labelled with a cost in `[k, k + 1)` (and stale
    /// entries of cells labelled again more cheaply, skipped when met).
    buckets: [Vec<Entry>; BUCKETS],
    /// The live cells of the bucket where a nearest-goal search ends, as `(cost bits, cell)`.
    order: Vec<(u64, u32)>,
    settled: Vec<u32>,
    start: Option<usize>,
    /// Resumable search ([`begin`](Reachability::begin)): the next bucket to settle, and
    /// whether every bucket is empty (the search is complete).
    next: usize,
    exhausted: bool,
    /// Whether the last search was started by `begin` (and may be advanced).
    resumable: bool,
    /// Whether the last search is guided ([`begin_guided`](Reachability::begin_guided)):
    /// its buckets are by cost plus `guide`'s bound.
    guided: bool,
    guide: Guide,
    /// Whether the last search runs in canonical order (module docs), and whether
    /// unguided searches do ([`set_canonical`](Reachability::set_canonical)).
    canonical: bool,
    use_canonical: bool,
    /// Canonical search: per slot, the directions of the walks that labelled the cell and
    /// of the walks from it; the buckets of labels and jump points.
    dirs: Vec<u16>,
    queues: Queues,
}

impl Reachability {
    /// Buffers for searches on a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x * height.div_ceil(TILE);
        Self {
            width,
            height,
            tiles_x,
            tile_epoch: vec![0; tiles],
            state: vec![0; tiles * TILE_CELLS],
            cost: vec![0.0; tiles * TILE_CELLS],
            epoch: 0,
            buckets: Default::default(),
            order: Vec::new(),
            settled: Vec::new(),
            start: None,
            next: 0,
            exhausted: true,
            resumable: false,
            guided: false,
            guide: Guide::default(),
            canonical: false,
            use_canonical: true,
            dirs: vec![0; tiles * TILE_CELLS],
            queues: Queues::default(),
        }
    }

    /// Run the unguided searches in canonical order (the default, see the module docs) or as
    /// Dial's search; both give the same costs, settled cells and paths.
    pub fn set_canonical(&mut self, on: bool) {
        self.use_canonical = on;
    }

    /// Full Dijkstra from `start` over cells where `passable(i)` (the start itself is always
    /// allowed). A start outside the grid gives an empty result.
    pub fn compute(&mut self, start: usize, passable: impl Fn(usize) -> bool) {
        self.run(&[start], &passable, None::<fn(usize) -> bool>);
    }

    /// Full Dijkstra from a set of sources, each left at cost 0 like the start of
    /// [`compute`](Self::compute) (sources outside the grid are ignored): every cost is the
    /// distance from the nearest source. With more than one source there is no single
    /// start, so [`start`](Self::start) is `None` and [`path_to`](Self::path_to) finds no
    /// path.
    pub fn compute_from(&mut self, sources: &[usize], passable: impl Fn(usize) -> bool) {
        self.run(sources, &passable, None::<fn(usize) -> bool>);
    }

    /// Dijkstra from `start` that stops at the first settled cell with `is_goal(i)` (which may be
    /// the start itself) and returns it; `None` if no reachable cell is a goal. Afterwards
    /// [`cost`](Self::cost) and [`path_to`](Self::path_to) are valid for every settled cell.
    pub fn nearest(
        &mut self,
        start: usize,
        passable: impl Fn(usize) -> bool,
        is_goal: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        self.run(&[start], &passable, Some(is_goal))
    }

    /// [`nearest`](Self::nearest) by a search guided toward `goals`, a superset of the cells
    /// with `is_goal` ([`begin_guided`](Self::begin_guided)): the same goal, minimal by
    /// (cost, index), and its cost and path, but when the goals are few and far the search
    /// covers the way to the nearest rather than the disk around the start. Other cells are
    /// not settled.
    ///
    /// Setting the guide takes time in the number of goals. With many goals (every
    /// frontier cell of a large map) the nearest is mostly a few steps away, so an
    /// unguided search is tried first, up to one settled cell for [`PROBE_SHARE`] goals
    /// past [`PROBE_FROM`]; only if it finds none is the guide set and the search begun
    /// again. Either way the goal is the same.
    pub fn nearest_guided(
        &mut self,
        start: usize,
        passable: impl Fn(usize) -> bool,
        goals: &[u32],
        is_goal: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        if goals.len() > PROBE_FROM {
            self.begin(start, &passable);
            let budget = (goals.len() - PROBE_FROM) / PROBE_SHARE;
            match self.nearest_settled(&passable, &is_goal, budget) {
                Probe::Found(goal) => return Some(goal),
                Probe::Exhausted => return None,
                Probe::Budget => {}
            }
        }
        self.begin_guided(start, &passable, goals);
        match self.nearest_settled(&passable, &is_goal, usize::MAX) {
            Probe::Found(goal) => Some(goal),
            _ => None,
        }
    }

    /// Advance the search begun bucket by bucket until it settles a cell with `is_goal`
    /// (the least by cost and index: through bucket k every goal of cost below k + 1 is
    /// settled, and none was found below k, so a goal settled now is final and any other
    /// costs more), it is complete, or it has settled more than `budget` cells.
    fn nearest_settled(
        &mut self,
        passable: &impl Fn(usize) -> bool,
        is_goal: &impl Fn(usize) -> bool,
        budget: usize,
    ) -> Probe {
        let mut scanned = 0;
        loop {
            let done = self.advance(self.next, passable);
            let found = self.settled[scanned..]
                .iter()
                .map(|&i| i as usize)
                .filter(|&i| is_goal(i))
                .map(|i| (self.cost[self.slot(i)].to_bits(), i))
                .min();
            if let Some((_, goal)) = found {
                return Probe::Found(goal);
            }
            if done {
                return Probe::Exhausted;
            }
            if self.settled.len() > budget {
                return Probe::Budget;
            }
            scanned = self.settled.len();
        }
    }

    /// Start a resumable search from `start` (see [`advance`](Self::advance)): nothing is
    /// settled until it is advanced. Costs, paths and the settled order are those of
    /// [`compute`](Self::compute) for every cell settled so far.
    pub fn begin(&mut self, start: usize, passable: impl Fn(usize) -> bool) {
        self.begin_with(start, &passable, self.use_canonical, false);
    }

    fn begin_with(
        &mut self,
        start: usize,
        passable: &impl Fn(usize) -> bool,
        canonical: bool,
        guided: bool,
    ) {
        self.init(&[start], passable, canonical, guided);
        self.resumable = true;
        if self.buckets.iter().all(Vec::is_empty) && self.queues.end == 0 {
            self.exhausted = true;
        }
    }

    /// Start a resumable search from `start` guided toward the cells `goals` (see the module
    /// docs): [`advance`](Self::advance) then settles every *goal* of cost below
    /// `through + 1`, with [`begin`](Self::begin)'s costs and paths, and
    /// [`next_bucket`](Self::next_bucket) bounds the cost of every goal not settled; other
    /// cells are settled only toward the goals (in canonical order, the default, none but
    /// the start), and every reachable cell once the search is complete. Without goals, or
    /// with goals in more than [`MAX_GUIDE_BLOCKS`] blocks, it is `begin`'s search.
    pub fn begin_guided(&mut self, start: usize, passable: impl Fn(usize) -> bool, goals: &[u32]) {
        if !self.set_guide(goals) {
            self.begin(start, &passable);
            return;
        }
        if self.use_canonical {
            self.begin_with(start, &passable, true, true);
            return;
        }
        self.begin_with(start, &passable, false, false);
        if self.exhausted {
            return;
        }
        // `begin` labelled the start alone; its bucket is the first.
        self.guided = true;
        let start = self.buckets[0][0];
        self.buckets[0].clear();
        let mut queue = Guided {
            buckets: &mut self.buckets,
            guide: &mut self.guide,
            current: 0,
        };
        queue.current = queue.bucket(0.0, start);
        queue.push(0.0, start);
        self.next = queue.current;
    }

    /// Start a resumable search from `start` that lists only the cells `goals` (and the
    /// start) as it settles them, in cost order: [`advance`](Self::advance) then settles
    /// every goal of cost below `through + 1`, with [`begin`](Self::begin)'s costs and
    /// paths, and every reachable cell once the search is complete. For a rule that needs
    /// every goal's cost: it spares listing every other cell by bucket, and with goals in
    /// at most [`MAX_GUIDE_BLOCKS`] blocks it is the guided search (A* toward the goals),
    /// which settles the goals in the same order but leaves out the cells whose cost plus
    /// distance to the nearest goal exceeds the farthest goal's cost; with more, the
    /// bound is 0. As Dial's search (not in canonical order) it is `begin`'s.
    pub fn begin_goals(&mut self, start: usize, passable: impl Fn(usize) -> bool, goals: &[u32]) {
        if !self.use_canonical {
            self.begin(start, &passable);
            return;
        }
        if !self.set_guide(goals) {
            self.guide.flatten(self.width, self.height, goals);
        }
        self.begin_with(start, &passable, true, true);
    }

    /// Set the guide toward `goals`; whether its bound is worth asking: some goal, in at
    /// most [`MAX_GUIDE_BLOCKS`] blocks ([`MAX_DIAL_GUIDE_BLOCKS`] for Dial's search).
    fn set_guide(&mut self, goals: &[u32]) -> bool {
        let most = if self.use_canonical {
            MAX_GUIDE_BLOCKS
        } else {
            MAX_DIAL_GUIDE_BLOCKS
        };
        self.guide.set(self.width, self.height, goals, most)
    }

    /// Settle every bucket up to and including bucket `through` of the search started by
    /// [`begin`](Self::begin): afterwards every cell of cost below `through + 1` is settled
    /// with its final cost (and nothing beyond the buckets settled). Returns whether the
    /// search is complete (every reachable cell settled). `passable` must be the one given
    /// to `begin`. After a search not started by `begin` it does nothing.
    pub fn advance(&mut self, through: usize, passable: impl Fn(usize) -> bool) -> bool {
        while self.resumable && !self.exhausted && self.next <= through {
            let k = self.next;
            if self.canonical {
                if k >= self.queues.end {
                    self.exhausted = true;
                    if self.guided {
                        self.settle_rest();
                    }
                    break;
                }
                if self.guided {
                    self.settle_guided(k, &passable);
                } else {
                    self.settle_canonical(k, &passable, None::<&fn(usize) -> bool>);
                }
            } else if self.buckets[k % BUCKETS].is_empty() {
                if self.buckets.iter().all(Vec::is_empty) {
                    self.exhausted = true;
                    break;
                }
            } else if self.guided {
                self.expand_guided(k, &passable);
            } else {
                self.expand(k, &passable);
            }
            self.next = k + 1;
        }
        self.exhausted
    }

    /// An id of the last search begun, which changes whenever a search begins (0 before
    /// the first): whoever reads [`settled`](Self::settled) piece by piece can tell a new
    /// search from the one it read.
    pub fn search_id(&self) -> u32 {
        self.epoch
    }

    /// The first bucket a resumable search has not settled: every cell of cost below it is
    /// settled (for a complete search, every reachable cell).
    pub fn next_bucket(&self) -> usize {
        self.next
    }

    /// Whether the last search lists only its goals (and start) in
    /// [`settled`](Self::settled) until it is complete (guided, in canonical order).
    pub fn lists_only_goals(&self) -> bool {
        self.guided && self.canonical
    }

    /// Whether the last search settled every cell it can reach (a full search, or a
    /// resumable one advanced to its end).
    pub fn is_complete(&self) -> bool {
        self.exhausted
    }

    fn run(
        &mut self,
        starts: &[usize],
        passable: &impl Fn(usize) -> bool,
        is_goal: Option<impl Fn(usize) -> bool>,
    ) -> Option<usize> {
        self.init(starts, passable, self.use_canonical, false);
        if self.canonical {
            let mut k = 0;
            while k < self.queues.end {
                if let Some(goal) = self.settle_canonical(k, passable, is_goal.as_ref()) {
                    self.next = k;
                    return Some(goal);
                }
                k += 1;
            }
            self.exhausted = true;
            self.next = k;
            return None;
        }
        let mut k = 0usize;
        loop {
            let slot = k % BUCKETS;
            if self.buckets[slot].is_empty() {
                if self.buckets.iter().all(Vec::is_empty) {
                    self.exhausted = true;
                    self.next = k;
                    return None;
                }
                k += 1;
                continue;
            }
            // Every cost in bucket k is final. A goal among them ends the search at the
            // first goal in (cost, index) order, settling what a heap settles before it.
            if let Some(is_goal) = &is_goal {
                let entries = std::mem::take(&mut self.buckets[slot]);
                let goal = self.settle_to_goal(&entries, is_goal);
                self.buckets[slot] = entries;
                if let Some(goal) = goal {
                    self.buckets[slot].clear();
                    // Not resumable: the goal's bucket is settled only in part.
                    self.next = k;
                    return Some(goal);
                }
            }
            self.expand(k, passable);
            k += 1;
        }
    }

    /// Forget the last search: until the next one begins, no cell is settled (a map kept
    /// from an earlier decision answers nothing, rather than costs from where its robot
    /// stood then). O(1): the cells' states are dropped with the search's epoch.
    pub fn forget(&mut self) {
        self.epoch = next_gen(self.epoch, &mut self.tile_epoch);
        for b in &mut self.buckets {
            b.clear();
        }
        self.queues.clear();
        self.settled.clear();
        self.start = None;
        self.next = 0;
        self.exhausted = false;
        self.resumable = false;
        self.guided = false;
    }

    /// Start a new search from `starts` (those inside the grid) with nothing settled, in
    /// canonical order or not, guided by the guide or not (canonical only: Dial's guided
    /// search starts from an unguided one).
    fn init(
        &mut self,
        starts: &[usize],
        passable: &impl Fn(usize) -> bool,
        canonical: bool,
        guided: bool,
    ) {
        self.forget();
        self.canonical = canonical;
        self.guided = guided && canonical;
        let (w, h) = (self.width, self.height);
        self.start = match starts {
            &[start] if start < w * h => Some(start),
            _ => None,
        };
        if canonical {
            let mut walk = Walk::new(self, passable, self.guided.then_some(0));
            let mut first = 0;
            for &start in starts.iter().filter(|&&s| s < w * h) {
                first = walk.start(start % w, start / w);
            }
            self.next = first; // a guided search's first bucket is its start's
            return;
        }
        let tile_row = self.tiles_x * TILE_CELLS;
        let mut wave = Wave {
            epoch: self.epoch,
            tile_epoch: &mut self.tile_epoch,
            state: &mut self.state,
            cost: &mut self.cost,
            queue: &mut self.buckets,
        };
        // The start is always left, but a diagonal step may pass beside it only if it is
        // passable: an impassable start is labelled and marked impassable.
        for &start in starts.iter().filter(|&&s| s < w * h) {
            let (x0, y0) = (start % w, start / w);
            let s0 = slot_xy(tile_row, x0, y0);
            wave.enter_tile(s0);
            if wave.state[s0] & MET != 0 {
                continue; // listed twice
            }
            wave.state[s0] = if passable(start) { MET } else { MET | BLOCKED };
            wave.cost[s0] = 0.0;
            wave.queue[0].push((x0 as u32, y0 as u32));
        }
    }

    /// Settle bucket `k` of a canonical search: every cell labelled in it is final; then
    /// walk from its jump points. With `is_goal`, a goal among its cells ends the search
    /// as in Dial's search (returned).
    fn settle_canonical(
        &mut self,
        k: usize,
        passable: &impl Fn(usize) -> bool,
        is_goal: Option<&impl Fn(usize) -> bool>,
    ) -> Option<usize> {
        let (labels, jumps) = self.queues.take(k);
        let (w, tile_row) = (self.width, self.tiles_x * TILE_CELLS);
        if let Some(is_goal) = is_goal
            && let Some(goal) = self.settle_to_goal(&labels, is_goal)
        {
            self.queues.put_back(labels, jumps);
            return Some(goal);
        }
        for &(x, y) in &labels {
            let q = slot_xy(tile_row, x as usize, y as usize);
            if self.state[q] & DONE == 0 {
                debug_assert_eq!(self.cost[q] as usize, k);
                self.state[q] |= DONE;
                self.settled.push(y * w as u32 + x);
            }
        }
        let mut walk = Walk::new(self, passable, None);
        for &j in &jumps {
            walk.expand(j);
        }
        self.queues.put_back(labels, jumps);
        None
    }

    /// Settle bucket `k` of a guided canonical search (jump points of cost plus bound in
    /// `[k, k + 1)`): walk from its jump points, and from those the walks add to it, until
    /// none is left; then every cell of cost plus bound below `k + 1` has its final cost,
    /// and the goals listed in the bucket are settled.
    fn settle_guided(&mut self, k: usize, passable: &impl Fn(usize) -> bool) {
        loop {
            let jumps = self.queues.take_jumps(k);
            if jumps.is_empty() {
                break;
            }
            let mut walk = Walk::new(self, passable, Some(k));
            for &j in &jumps {
                walk.expand(j);
            }
            self.queues.put_back(Vec::new(), jumps);
        }
        let labels = self.queues.take_labels(k);
        let (w, tile_row) = (self.width, self.tiles_x * TILE_CELLS);
        for &(x, y) in &labels {
            let q = slot_xy(tile_row, x as usize, y as usize);
            if self.state[q] & DONE == 0 {
                debug_assert!(self.cost[q] < (k + 1) as f64);
                self.state[q] |= DONE;
                self.settled.push(y * w as u32 + x);
            }
        }
        self.queues.put_back(labels, Vec::new());
    }

    /// At the end of a guided canonical search every label is final: settle the cells not
    /// settled yet (by tiles), so that a complete search has settled every reachable cell.
    fn settle_rest(&mut self) {
        let w = self.width;
        for (t, _) in self
            .tile_epoch
            .iter()
            .enumerate()
            .filter(|&(_, &e)| e == self.epoch)
        {
            let (x0, y0) = ((t % self.tiles_x) * TILE, (t / self.tiles_x) * TILE);
            for (o, s) in self.state[t * TILE_CELLS..(t + 1) * TILE_CELLS]
                .iter_mut()
                .enumerate()
            {
                if *s & (MET | BLOCKED | DONE) == MET {
                    *s |= DONE;
                    let (x, y) = (x0 + (o & TILE_MASK), y0 + (o >> TILE_SHIFT));
                    self.settled.push((y * w + x) as u32);
                }
            }
        }
    }

    /// If the live cells of a bucket's `entries` (every cost in the bucket final) hold a
    /// goal, settle them in (cost, index) order up to the first goal, as a heap does, and
    /// return it.
    fn settle_to_goal(
        &mut self,
        entries: &[Entry],
        is_goal: &impl Fn(usize) -> bool,
    ) -> Option<usize> {
        let (w, tile_row) = (self.width, self.tiles_x * TILE_CELLS);
        let (state, cost) = (&self.state, &self.cost);
        // (cost bits, cell) orders as (cost, cell): costs are not negative
        let live = |&(x, y): &Entry| {
            let (x, y) = (x as usize, y as usize);
            let q = slot_xy(tile_row, x, y);
            (state[q] & DONE == 0).then_some((cost[q].to_bits(), y * w + x))
        };
        let goal = entries
            .iter()
            .filter_map(live)
            .filter(|&(_, i)| is_goal(i))
            .min()
            .map(|(_, i)| i)?;
        self.order.clear();
        self.order
            .extend(entries.iter().filter_map(live).map(|(c, i)| (c, i as u32)));
        self.order.sort_unstable();
        self.order.dedup();
        for &(_, i) in &self.order {
            let i = i as usize;
            self.state[slot_xy(tile_row, i % w, i / w)] |= DONE;
            self.settled.push(i as u32);
            if i == goal {
                break;
            }
        }
        Some(goal)
    }

    /// Settle bucket `k`: every cell labelled in it is final; label its neighbours.
    #[inline]
    fn expand(&mut self, k: usize, passable: &impl Fn(usize) -> bool) {
        let dims = (self.width, self.height, self.tiles_x * TILE_CELLS);
        let slot = k % BUCKETS;
        let mut bucket = std::mem::take(&mut self.buckets[slot]);
        let mut wave = Wave {
            epoch: self.epoch,
            tile_epoch: &mut self.tile_epoch,
            state: &mut self.state,
            cost: &mut self.cost,
            queue: &mut self.buckets,
        };
        for &xy in &bucket {
            let p = slot_xy(dims.2, xy.0 as usize, xy.1 as usize);
            let state = wave.state[p];
            if state & DONE != 0 {
                continue; // labelled again more cheaply, or listed twice
            }
            debug_assert_eq!(wave.cost[p] as usize, k);
            wave.state[p] = state | DONE;
            self.settled.push(xy.1 * dims.0 as u32 + xy.0);
            wave.relax(passable, dims, xy, p);
        }
        bucket.clear();
        self.buckets[slot] = bucket;
    }

    /// Settle bucket `k` of a guided search (cells of cost plus bound in `[k, k + 1)`): a
    /// cell may get a lower cost from another of the bucket settled after it, and is then
    /// settled again, until none does; then every cost in it is final.
    fn expand_guided(&mut self, k: usize, passable: &impl Fn(usize) -> bool) {
        let dims = (self.width, self.height, self.tiles_x * TILE_CELLS);
        let slot = k % BUCKETS;
        let mut wave = Wave {
            epoch: self.epoch,
            tile_epoch: &mut self.tile_epoch,
            state: &mut self.state,
            cost: &mut self.cost,
            queue: Guided {
                buckets: &mut self.buckets,
                guide: &mut self.guide,
                current: k,
            },
        };
        // First in, first out: cells labelled in this bucket are taken after the others.
        let mut n = 0;
        while let Some(&xy) = wave.queue.buckets[slot].get(n) {
            n += 1;
            let p = slot_xy(dims.2, xy.0 as usize, xy.1 as usize);
            let state = wave.state[p];
            if state & DONE != 0 {
                continue; // labelled again more cheaply, or listed twice
            }
            wave.state[p] = state | DONE | LISTED;
            if state & LISTED == 0 {
                self.settled.push(xy.1 * dims.0 as u32 + xy.0);
            }
            wave.relax(passable, dims, xy, p);
        }
        wave.queue.buckets[slot].clear();
    }

    /// The slot of cell `i < width * height`.
    #[inline]
    fn slot(&self, i: usize) -> usize {
        slot_xy(self.tiles_x * TILE_CELLS, i % self.width, i / self.width)
    }

    /// The state flags of cell `i < width * height` in the last search (none if not met).
    #[inline]
    fn state_of(&self, i: usize) -> u8 {
        let q = self.slot(i);
        if self.tile_epoch[q >> (2 * TILE_SHIFT)] == self.epoch {
            self.state[q]
        } else {
            0
        }
    }

    /// Whether cell `i` was settled by the last search (its cost is final).
    #[inline]
    pub fn is_settled(&self, i: usize) -> bool {
        self.epoch != 0 && i < self.width * self.height && self.state_of(i) & DONE != 0
    }

    /// Shortest-path cost in cells from the start to a settled cell (after `compute`: every
    /// reachable cell); `None` for cells not settled by the last search.
    #[inline]
    pub fn cost(&self, i: usize) -> Option<f64> {
        self.is_settled(i).then(|| self.cost[self.slot(i)])
    }

    /// Write the shortest path start..=goal (inclusive) to `out`; false (and `out` empty) if
    /// `goal` was not settled by the last search. Each cell's predecessor is the settled
    /// neighbour that gives it its cost by a legal step, least by (cost, index).
    pub fn path_to(&self, goal: usize, out: &mut Vec<u32>) -> bool {
        out.clear();
        if !self.is_settled(goal) {
            return false;
        }
        let Some(start) = self.start else {
            return false;
        };
        let mut c = goal;
        out.push(c as u32);
        while c != start {
            match self.step_back(c) {
                Some(p) => c = p,
                None => {
                    // unreachable for a settled cell; never loop or return a broken path
                    debug_assert!(false, "settled cell {c} without a predecessor");
                    out.clear();
                    return false;
                }
            }
            out.push(c as u32);
        }
        out.reverse();
        true
    }

    /// The cell before settled cell `j` on [`path_to`](Self::path_to)'s path (the heap's
    /// predecessor); `None` for the start and for cells not settled by the last search.
    pub fn predecessor(&self, j: usize) -> Option<usize> {
        if !self.is_settled(j) || Some(j) == self.start {
            return None;
        }
        self.step_back(j)
    }

    /// [`predecessor`](Self::predecessor) of a cell `j` other than the start whose cost is
    /// final: settled, or on the path to a settled cell. Only neighbours whose cost is final
    /// give `j` its cost: a label is never below its cell's cost, nor `j`'s cost below a
    /// neighbour's plus the step. A guided canonical search settles only its goals, so
    /// there the neighbours are those labelled; every one that gives `j` its cost is no
    /// farther from the goals than `j` (its cost plus bound no higher), so it is labelled
    /// when `j` is final, and so is a passable cell beside the step, see `canonical.rs`.
    fn step_back(&self, j: usize) -> Option<usize> {
        let guided = self.lists_only_goals();
        let given = |u: usize| {
            if guided {
                let s = self.state_of(u);
                s & MET != 0 && (s & BLOCKED == 0 || Some(u) == self.start)
            } else {
                self.is_settled(u)
            }
        };
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = ((j % self.width) as i64, (j / self.width) as i64);
        // A cell known passable in the last search: met and not found impassable (the
        // straight neighbours of a cell settled before the last bucket were all met).
        // (In canonical order, too: a passable straight neighbour of a settled cell costs a
        // step more at most, so it is settled before any cell a diagonal step from there.)
        let open = |i: usize| self.state_of(i) & (MET | BLOCKED) == MET;
        let cj = self.cost[self.slot(j)];
        let mut best: Option<(f64, usize)> = None;
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let (ux, uy) = (x + dx, y + dy);
                if (dx, dy) == (0, 0) || ux < 0 || uy < 0 || ux >= w || uy >= h {
                    continue;
                }
                let u = (uy * w + ux) as usize;
                if !given(u) {
                    continue;
                }
                let step = if dx != 0 && dy != 0 {
                    // the step u -> j passes beside (ux, y) and (x, uy): one must be passable
                    if !open((y * w + ux) as usize) && !open((uy * w + x) as usize) {
                        continue;
                    }
                    SQRT2
                } else {
                    1.0
                };
                let cu = self.cost[self.slot(u)];
                if cu + step == cj && best.is_none_or(|(bc, bu)| (cu, u) < (bc, bu)) {
                    best = Some((cu, u));
                }
            }
        }
        best.map(|(_, u)| u)
    }

    /// Cells in the order the last search settled them: bucket by bucket (each cell after
    /// every cell at least one straight step cheaper); in the bucket where a nearest-goal
    /// search ended, by (cost, index) up to the goal, which is last. A guided canonical
    /// search lists its goals (and start) by bucket, then, once complete, the other cells.
    pub fn settled(&self) -> &[u32] {
        &self.settled
    }

    /// How many cells the last search has looked at: those it settled, or, guided in
    /// canonical order (which settles only its goals until complete), those it labelled.
    pub fn searched(&self) -> usize {
        if self.lists_only_goals() {
            self.queues.labelled_cells
        } else {
            self.settled.len()
        }
    }

    /// The start of the last search, if it was inside the grid.
    pub fn start(&self) -> Option<usize> {
        self.start
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Number of rows.
    pub fn height(&self) -> usize {
        self.height
    }
}
