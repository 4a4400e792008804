//! A* over exploration states (Quattrini Li, Amigoni & Basilico 2012, "Solution of the
//! Search Problem"), with weighted A*, limits and bounds.
//!
//! A state is (robot cell, set of perceived marks: free targets and walls next to reachable
//! cells). The set is not stored: it is the union of what the positions along the state's
//! parent chain perceive, rebuilt as a bitset when the state is expanded, so a state costs
//! about 100 bytes whatever the map size. States are identified by two independent Zobrist
//! keys (two random 64-bit keys per mark and per cell, XOR-ed; a child's keys cost two
//! XORs per newly perceived mark): 128 bits, so the chance that two of 10⁹ distinct states
//! are taken for one is below 10⁻²⁰. A duplicate reached more cheaply is re-opened (its
//! parent chain changes, its set does not), so the search stays optimal with admissible
//! but inconsistent heuristics.
//!
//! Beyond the paper:
//! - An incumbent from the start: the better of two greedy completions (always to the
//!   nearest action that perceives something new; always to the action that perceives the
//!   most new targets per unit of path) gives an upper bound U; children with g + h ≥ U are
//!   pruned.
//!   When the search stops, the greedy completion of the most advanced open state may
//!   improve U.
//! - Weighted A* (f = g + w·h): the returned length is ≤ w × optimal, and the reported lower
//!   bound is max(U / w, min over open states of g + h).
//! - Limits on expanded nodes, bytes of stored states and wall time, and an observer
//!   ([`solve_with`]) shown the progress periodically that may stop the search: it stops
//!   cleanly with the best lower and upper bounds. Stored bytes (nodes, queue, hash
//!   table, caches) are counted before every allocation that grows, so a budget is a
//!   hard cap on the search's own memory, never an OOM kill.
//! - Actions that perceive no new target are skipped: from (q, M) a move to p that adds at
//!   most walls to M is dominated by moving on directly (triangle inequality inside the
//!   same perceived free space; perceived walls only remove boundary cells).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::hash::BuildHasherDefault;
use std::time::{Duration, Instant};

use grid::Cell;
use sense::Observation;

use crate::actions::{ActionScratch, ActionSet, candidates};
use crate::cluster_rows::ClusterRows;
use crate::error::OptimalError;
use crate::heuristic::{Heuristic, HeuristicKind, MixHasher, dist, has, push_words, set};
use crate::problem::{Problem, SensorModel};
use crate::recent::{self, Recent};
use crate::room::{room_bytes, room_for};
use crate::step_cost::StepCosts;
use explore::plan::Reachability;

/// Tolerance for comparing path lengths (sums of 1 and √2).
pub const EPS: f64 = 1e-9;

/// How to search.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    /// Coverage goal G in (0, 1]: the fraction of targets to perceive.
    pub goal: f64,
    /// The actions of a state.
    pub actions: ActionSet,
    /// The lower bound guiding the search.
    pub heuristic: HeuristicKind,
    /// Weight w ≥ 1 of weighted A* (1 = optimal).
    pub weight: f64,
    /// Number of landmarks for [`HeuristicKind::Landmarks`].
    pub landmarks: usize,
    /// Stop after expanding this many states.
    pub max_nodes: u64,
    /// Stop before the search's own memory exceeds this many bytes.
    pub max_bytes: usize,
    /// Stop after this much wall time (the first greedy completion, for an initial upper
    /// bound, keeps to it too). A stopped search then completes its most advanced open
    /// states greedily for a better upper bound, with up to 5% as many shortest-path
    /// searches as it expanded states, for at most a tenth of the limit (at least 1 s).
    pub time_limit: Option<Duration>,
    /// With a factor f > 1, the first incumbent also comes from the same problem solved on
    /// cells f times larger (with a tenth of the node and time limits, [`crate::coarse`]):
    /// in each of its positions' blocks the cell that perceives the most is visited where
    /// it is reachable inside the perceived space, then the path is completed greedily.
    /// Only the upper bound changes (and with it what is pruned): for large maps whose
    /// search will stop with bounds. The coarse path's cells need not be actions of the
    /// set, so the path returned may be shorter than the set's optimum (never than the
    /// optimum over all positions).
    pub coarse_incumbent: usize,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            goal: 1.0,
            actions: ActionSet::Boundary,
            heuristic: HeuristicKind::Landmarks,
            weight: 1.0,
            landmarks: 32,
            max_nodes: 50_000_000,
            max_bytes: 1 << 30,
            time_limit: None,
            coarse_incumbent: 0,
        }
    }
}

/// How the search ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// No path of the action set is shorter than the solution (w = 1, admissible
    /// heuristic): the solution is optimal for the set, or shorter still when it came
    /// from outside the set ([`Config::coarse_incumbent`]).
    Optimal,
    /// The solution is at most `weight` × optimal (weighted A*).
    WithinBound,
    /// The heuristic is not admissible: a solution, without a guarantee.
    Unproven,
    /// A limit was hit; bounds are reported (the solution, if any, is the best found).
    Stopped,
    /// No sequence of actions reaches the goal (a share G of the targets that no position
    /// perceives; dropped clusters widen the search rather than end it).
    NoSolution,
}

impl Status {
    /// The stable name, as printed in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Optimal => "optimal",
            Status::WithinBound => "within bound",
            Status::Unproven => "unproven",
            Status::Stopped => "stopped",
            Status::NoSolution => "no solution",
        }
    }
}

/// Which limit stopped the search.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// [`Config::max_nodes`].
    NodeLimit,
    /// [`Config::max_bytes`].
    MemoryLimit,
    /// [`Config::time_limit`].
    TimeLimit,
    /// The observer of [`solve_with`] asked to stop (e.g. the user pressed Ctrl-C).
    Interrupted,
}

impl StopReason {
    /// The stable name.
    pub fn as_str(self) -> &'static str {
        match self {
            StopReason::NodeLimit => "node limit",
            StopReason::MemoryLimit => "memory limit",
            StopReason::TimeLimit => "time limit",
            StopReason::Interrupted => "interrupt",
        }
    }
}

/// An exploration path.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The sensing positions q0 (the start), q1, ..., qn.
    pub positions: Vec<Cell>,
    /// Every cell travelled, start first (consecutive cells are 8-neighbours).
    pub path: Vec<Cell>,
    /// Length in cells (straight 1, diagonal √2).
    pub length: f64,
    /// Targets perceived at the end.
    pub perceived: usize,
}

/// Counters of a search.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// States expanded.
    pub expanded: u64,
    /// Child states generated (before duplicate detection and pruning).
    pub generated: u64,
    /// Children that were duplicates of stored states.
    pub duplicates: u64,
    /// Stored states re-opened with a lower cost.
    pub reopened: u64,
    /// Children pruned by the upper bound.
    pub pruned: u64,
    /// States stored.
    pub stored: u64,
    /// Peak bytes counted against the budget.
    pub bytes: usize,
    /// Wall time in seconds.
    pub seconds: f64,
    /// Landmarks used by the heuristic.
    pub landmarks: usize,
}

/// The result of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// How the search ended.
    pub status: Status,
    /// The limit that stopped it, if one did.
    pub stop: Option<StopReason>,
    /// The best solution found.
    pub solution: Option<Solution>,
    /// Proven lower bound on the optimal length (cells); 0 if the heuristic is inadmissible.
    pub lower_bound: f64,
    /// Length of the best solution found (cells), `∞` if none.
    pub upper_bound: f64,
    /// Number of targets |E_f|.
    pub targets: usize,
    /// Targets the goal test needs.
    pub needed: usize,
    /// Counters.
    pub stats: Stats,
    /// A one-line human summary of how it ended.
    pub message: String,
}

/// Where a running search stands, as shown to the observer of [`solve_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// States expanded so far.
    pub expanded: u64,
    /// States stored so far.
    pub stored: u64,
    /// Bytes counted against the budget so far.
    pub bytes: usize,
    /// Proven lower bound on the optimal length so far (cells; 0 without an admissible
    /// heuristic).
    pub lower_bound: f64,
    /// Length of the best solution found so far (cells), `∞` if none.
    pub upper_bound: f64,
    /// Wall time so far in seconds.
    pub seconds: f64,
}

/// splitmix64: the fixed stream of Zobrist keys.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

const NONE: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
struct Node {
    pos: u32,
    parent: u32,
    g: f64,
    h: f64,
    key: u64,
    /// The second, independent Zobrist key.
    check: u64,
    count: u32,
    next_same: u32,
    /// Its slot in [`Recent`] once expanded (valid while the slot holds this state).
    slot: u32,
    closed: bool,
}

// The slot fits in what was padding: a state still takes 56 bytes.
const _: () = assert!(std::mem::size_of::<Node>() == 56);

/// Open states completed greedily for an upper bound when the search stops early.
const IMPROVE_STATES: usize = 64;
/// Greedy steps those completions may take, as a share of the states expanded.
const IMPROVE_SHARE: f64 = 0.05;
/// Recently expanded states kept for their descendants ([`crate::recent`]).
const RECENT_STATES: usize = 1024;

/// Min-heap entry: (priority bits, deeper first, id, g bits).
type Entry = Reverse<(u64, u64, u32, u64)>;

fn entry(f: f64, g: f64, id: u32) -> Entry {
    Reverse((f.to_bits(), u64::MAX - g.to_bits(), id, g.to_bits()))
}

/// Each cell's perceived marks (targets, then walls next to reachable cells), computed once
/// on first use.
struct VisCache {
    off: Vec<u32>,
    len: Vec<u32>,
    data: Vec<u32>,
    obs: Observation,
    /// Per cell: its perceived marks as (word, bits), of the marks' bitset, then of the
    /// cluster rows when used.
    word_off: Vec<u32>,
    word_len: Vec<[u32; 2]>,
    word_data: Vec<(u32, u64)>,
    /// The most marks one view holds (the sensor's disc): room kept for the next view.
    most: usize,
}

impl VisCache {
    fn new(n: usize, most: usize) -> Self {
        Self {
            most,
            off: vec![NONE; n],
            len: vec![0; n],
            data: Vec::new(),
            obs: Observation::new(),
            word_off: vec![NONE; n],
            word_len: vec![[0; 2]; n],
            word_data: Vec::new(),
        }
    }

    fn get(&mut self, problem: &Problem, pos: u32) -> (usize, usize) {
        let p = pos as usize;
        if self.off[p] == NONE {
            room_for(&mut self.data, self.most, 0, usize::MAX);
            let start = self.data.len();
            problem.seen_marks(pos, &mut self.obs, &mut self.data);
            self.off[p] = start as u32;
            self.len[p] = (self.data.len() - start) as u32;
        }
        (self.off[p] as usize, self.len[p] as usize)
    }

    /// The marks perceived from `pos` as (word, bits) of the marks' bitset and, with
    /// `rows`, of the cluster rows (computed on first use). Returns the two ranges in
    /// `word_data`.
    fn words(
        &mut self,
        problem: &Problem,
        pos: u32,
        rows: Option<&ClusterRows>,
    ) -> ((usize, usize), (usize, usize)) {
        let p = pos as usize;
        if self.word_off[p] == NONE {
            let (o, l) = self.get(problem, pos);
            room_for(&mut self.word_data, 2 * self.most, 0, usize::MAX);
            let start = self.word_data.len();
            let marks = &self.data[o..o + l];
            push_words(
                &mut self.word_data,
                marks.iter().map(|&t| (t / 64, 1 << (t % 64))),
            );
            let mid = self.word_data.len();
            if let Some(rows) = rows {
                push_words(
                    &mut self.word_data,
                    marks.iter().map(|&t| {
                        let (k, b) = rows.locate_mark(t);
                        (k as u32, 1 << b)
                    }),
                );
            }
            self.word_off[p] = start as u32;
            self.word_len[p] = [(mid - start) as u32, (self.word_data.len() - mid) as u32];
        }
        let (o, [a, b]) = (self.word_off[p] as usize, self.word_len[p]);
        ((o, a as usize), (o + a as usize, b as usize))
    }

    /// The bytes the next view may add to what [`VisCache::bytes`] counts.
    fn growth_bytes(&self) -> usize {
        room_bytes(&self.data, self.most, 0, usize::MAX)
            + room_bytes(&self.word_data, 2 * self.most, 0, usize::MAX)
    }

    /// Forget every computed view, returning its memory: views are computed again on use,
    /// the same, so the search's results do not change.
    fn forget(&mut self) {
        self.off.fill(NONE);
        self.len.fill(0);
        self.data = Vec::new();
        self.word_off.fill(NONE);
        self.word_len.fill([0; 2]);
        self.word_data = Vec::new();
    }

    /// Whether position `pos` perceives a target (a mark below `nt`) not in `bits`.
    fn perceives_new(&mut self, problem: &Problem, pos: u32, bits: &[u64], nt: u32) -> bool {
        let (o, l) = self.get(problem, pos);
        self.data[o..o + l].iter().any(|&t| t < nt && !has(bits, t))
    }

    fn bytes(&self) -> usize {
        self.off.len() * 8
            + self.data.capacity() * 4
            + self.word_off.len() * 12
            + self.word_data.capacity() * 16
    }
}

/// The bits of word `word` of a marks' bitset that are targets (marks below `nt`).
#[inline]
fn target_bits(word: u32, nt: u32) -> u64 {
    let first = word * 64;
    if first + 64 <= nt {
        u64::MAX
    } else if first >= nt {
        0
    } else {
        (1u64 << (nt - first)) - 1
    }
}

/// The search's state and buffers.
struct Engine<'p> {
    problem: &'p Problem,
    cfg: Config,
    need: usize,
    heur: Heuristic,
    vis: VisCache,
    /// Shortest paths inside the perceived free space (the step costs).
    reach: StepCosts,
    scratch: ActionScratch,
    /// Cluster actions on bit rows (with [`ActionSet::Clusters`]), and the perceived set of
    /// the loaded state as rows.
    rows: Option<ClusterRows>,
    seen_rows: Vec<u64>,
    /// Recently expanded states' perceived sets and reachable components.
    recent: Recent,
    /// The greedy completion's perceived set as cluster rows.
    greedy_rows: Vec<u64>,
    zt: Vec<[u64; 2]>,
    zpos: Vec<[u64; 2]>,
    nodes: Vec<Node>,
    table: HashMap<u64, u32, BuildHasherDefault<MixHasher>>,
    open: BinaryHeap<Entry>,
    cur: Vec<u64>,
    child: Vec<u64>,
    cands: Vec<u32>,
    /// What a child perceives anew, as (word, bits) of the marks' bitset.
    fresh_words: Vec<(u32, u64)>,
    /// The step cost to each candidate.
    cand_dist: Vec<f64>,
    inc_cost: f64,
    inc_positions: Vec<u32>,
    /// Whether the incumbent is the coarse map's path (its cells need not be actions).
    inc_coarse: bool,
    stats: Stats,
    fixed_bytes: usize,
    /// Number of targets: marks below it are free cells the goal counts.
    nt: u32,
}

/// Bytes a table of Zobrist keys with `capacity` (`HashMap::capacity`) holds: its buckets
/// (7 in 8 of them usable) of a key, a state and a control byte, and a group of control
/// bytes more. Counting the capacity alone at 16 bytes an entry missed a sixth of it.
fn table_bytes(capacity: usize) -> usize {
    if capacity == 0 {
        return 0;
    }
    let buckets = if capacity < 8 {
        capacity + 1
    } else {
        capacity / 7 * 8
    };
    buckets * (std::mem::size_of::<(u64, u32)>() + 1) + 16
}

/// The capacity of a full table of `capacity` after `reserve` asked room for `want`
/// entries in all: buckets for the larger of `want` and one more entry, 8 for each 7,
/// rounded up to a power of two (the standard library's hash table;
/// `table_growth_is_predicted` checks it). Counting only what was asked for let the table
/// pass the budget by up to a half of it.
fn table_capacity_grown(capacity: usize, want: usize) -> usize {
    let cap = want.max(capacity + 1);
    let buckets = if cap < 4 {
        4
    } else if cap < 8 {
        8
    } else {
        (cap.saturating_mul(8) / 7).next_power_of_two()
    };
    if buckets <= 8 {
        buckets - 1
    } else {
        buckets / 8 * 7
    }
}

impl<'p> Engine<'p> {
    fn new(problem: &'p Problem, cfg: &Config) -> Self {
        let n = problem.cells().len();
        let nt = problem.targets().len();
        let nm = problem.mark_count();
        let words = nm.div_ceil(64).max(1);
        let mut seed = 0x0005_EED0_F0B7_14A1_u64;
        let zt = (0..nm)
            .map(|_| [splitmix(&mut seed), splitmix(&mut seed)])
            .collect();
        let zpos = (0..n)
            .map(|_| [splitmix(&mut seed), splitmix(&mut seed)])
            .collect();
        let heur = Heuristic::new(
            problem,
            cfg.heuristic,
            cfg.goal,
            cfg.landmarks,
            cfg.max_bytes / 4,
        );
        let reach = StepCosts::new(problem);
        let reach_bytes = reach.bytes();
        let rows =
            matches!(cfg.actions, ActionSet::Clusters { .. }).then(|| ClusterRows::new(problem));
        let seen_rows = vec![0; rows.as_ref().map_or(0, ClusterRows::words)];
        let rows_bytes = rows.as_ref().map_or(0, ClusterRows::bytes);
        // The ring of recent states: at most a 64th of the memory budget.
        let slot_bytes = Recent::slot_bytes(words, seen_rows.len());
        let recent = Recent::new(
            RECENT_STATES.min(cfg.max_bytes / 64 / slot_bytes),
            words,
            seen_rows.len(),
        );
        Self {
            problem,
            cfg: cfg.clone(),
            need: problem.needed(cfg.goal),
            heur,
            vis: VisCache::new(n, problem.model().disc_cells()),
            reach,
            scratch: ActionScratch::new(n),
            rows,
            seen_rows,
            recent,
            greedy_rows: Vec::new(),
            zt,
            zpos,
            nodes: Vec::new(),
            table: HashMap::default(),
            open: BinaryHeap::new(),
            cur: vec![0; words],
            child: vec![0; words],
            cands: Vec::new(),
            fresh_words: Vec::new(),
            cand_dist: Vec::new(),
            inc_cost: f64::INFINITY,
            inc_positions: Vec::new(),
            inc_coarse: false,
            stats: Stats::default(),
            // Step costs, action marks, Zobrist keys, the problem's arrays.
            fixed_bytes: reach_bytes + rows_bytes + n * (4 + 16 + 12) + nm * 20,
            nt: nt as u32,
        }
    }

    /// Bytes counted against the budget if `extra_nodes` more states were stored.
    fn bytes_with(&self, extra_nodes: usize) -> usize {
        let nodes = self.nodes.capacity().max(self.nodes.len() + extra_nodes);
        nodes * std::mem::size_of::<Node>()
            + self.open.capacity() * 32
            + table_bytes(self.table.capacity())
            + self.heur.bytes()
            + self.vis.bytes()
            + self.recent.bytes()
            + self.fixed_bytes
    }

    /// Whether what the search holds, with what its caches' next growth would add
    /// ([`crate::room`]), exceeds its memory budget (what it holds is noted in the
    /// statistics). Over it, the cached views are forgotten first (they are computed again
    /// when asked for): the budget is exceeded only if the rest still holds more than three
    /// quarters of it, so that views are not computed again and again for a few candidates
    /// each.
    fn over_budget(&mut self) -> bool {
        let bytes = self.bytes_with(0);
        self.stats.bytes = self.stats.bytes.max(bytes);
        let growth = self.vis.growth_bytes() + self.heur.growth_bytes();
        if bytes + growth <= self.cfg.max_bytes {
            return false;
        }
        self.vis.forget();
        let growth = self.vis.growth_bytes() + self.heur.growth_bytes();
        self.bytes_with(0) + growth > self.cfg.max_bytes / 4 * 3
    }

    /// Grow storage for one more state if the budget allows (growth by 1.5×, checked first).
    fn reserve_one(&mut self) -> bool {
        let len = self.nodes.len();
        if len < self.nodes.capacity()
            && self.open.len() < self.open.capacity()
            && self.table.len() < self.table.capacity()
        {
            return true;
        }
        let grow = (len / 2).max(1024);
        let table = self.table.capacity();
        let table_grown = if self.table.len() == table {
            table_capacity_grown(table, len + grow)
        } else {
            table
        };
        let projected =
            self.bytes_with(grow) + grow * 48 + table_bytes(table_grown) - table_bytes(table);
        if projected > self.cfg.max_bytes {
            return false;
        }
        if len == self.nodes.capacity() {
            self.nodes.reserve_exact(grow);
        }
        if self.open.len() == self.open.capacity() {
            self.open.reserve_exact(grow);
        }
        if self.table.len() == self.table.capacity() {
            self.table.reserve(grow);
        }
        self.stats.bytes = self.stats.bytes.max(self.bytes_with(0));
        true
    }

    /// Rebuild the perceived set of state `id` into `self.cur` (and `self.seen_rows`): the
    /// union of what the positions along its parent chain perceive, from its nearest
    /// ancestor (or itself) still in [`Recent`] on. Returns that state's slot and position.
    fn load_state(&mut self, id: u32) -> Option<(usize, u32)> {
        self.cur.fill(0);
        self.seen_rows.fill(0);
        let mut j = id;
        while j != NONE {
            let Node { pos, slot, .. } = self.nodes[j as usize];
            if let Some(slot) = self.recent.find(j, slot) {
                for (c, &m) in self.cur.iter_mut().zip(self.recent.marks(slot)) {
                    *c |= m;
                }
                for (c, &m) in self.seen_rows.iter_mut().zip(self.recent.seen_rows(slot)) {
                    *c |= m;
                }
                return Some((slot, pos));
            }
            let ((o, l), (ro, rl)) = self.vis.words(self.problem, pos, self.rows.as_ref());
            for &(k, b) in &self.vis.word_data[o..o + l] {
                self.cur[k as usize] |= b;
            }
            for &(k, b) in &self.vis.word_data[ro..ro + rl] {
                self.seen_rows[k as usize] |= b;
            }
            j = self.nodes[j as usize].parent;
        }
        None
    }

    /// Make the path through `positions`, of length `cost`, the incumbent; `coarse` when it
    /// is the coarse map's path.
    fn set_incumbent(&mut self, cost: f64, positions: Vec<u32>, coarse: bool) {
        self.inc_cost = cost;
        self.inc_positions = positions;
        self.inc_coarse = coarse;
    }

    fn positions_of(&self, mut id: u32) -> Vec<u32> {
        let mut out = Vec::new();
        while id != NONE {
            out.push(self.nodes[id as usize].pos);
            id = self.nodes[id as usize].parent;
        }
        out.reverse();
        out
    }

    /// Complete greedily from (pos, bits, count): repeatedly move to the nearest action
    /// that perceives a new target or, with `rate`, to the action that perceives the most
    /// new targets per unit of path (`new / (d + 1)`, ties to the nearer, then the lower
    /// cell). Returns the added cost and appends the positions; `None` if no action
    /// perceives a new target or `deadline` passes first.
    fn greedy(
        &mut self,
        mut pos: u32,
        bits: &[u64],
        mut count: usize,
        rate: bool,
        deadline: Option<Instant>,
        out: &mut Vec<u32>,
    ) -> Option<f64> {
        let mut cur = bits.to_vec();
        let mut rows = std::mem::take(&mut self.greedy_rows);
        rows.clear();
        if let Some(r) = &self.rows {
            r.rows_of(&cur, &mut rows);
        }
        let mut cost = 0.0;
        while count < self.need {
            if deadline.is_some_and(|d| Instant::now() >= d) || self.over_budget() {
                self.greedy_rows = rows;
                return None;
            }
            let mut best = None;
            let mut next = Some(self.cfg.actions);
            let mut searched = false;
            while let Some(actions) = next {
                self.actions(pos, &cur, &rows, actions, &mut searched, None);
                let Some(choice) = self.greedy_choice(&cur, rate) else {
                    self.greedy_rows = rows;
                    return None;
                };
                best = choice;
                next = if best.is_some() {
                    None
                } else {
                    actions.wider()
                };
            }
            let Some((d, a)) = best else {
                self.greedy_rows = rows;
                return None;
            };
            count += self.perceive(a, &mut cur, Some(&mut rows));
            cost += d;
            pos = a;
            out.push(a);
        }
        self.greedy_rows = rows;
        Some(cost)
    }

    /// Add what `pos` perceives to the marks' bitset `bits` and, when cluster rows are kept
    /// and `rows` is given, to `rows` (the same set as rows); returns the number of new
    /// targets.
    fn perceive(&mut self, pos: u32, bits: &mut [u64], mut rows: Option<&mut [u64]>) -> usize {
        let (o, l) = self.vis.get(self.problem, pos);
        let mut new = 0;
        for &t in &self.vis.data[o..o + l] {
            if !has(bits, t) {
                set(bits, t);
                new += usize::from(t < self.nt);
                if let (Some(r), Some(rows)) = (&self.rows, rows.as_deref_mut()) {
                    let (k, b) = r.locate_mark(t);
                    rows[k] |= 1 << b;
                }
            }
        }
        new
    }

    /// Fill `cands` and `cand_dist` with the actions `set` of the robot at `pos` having
    /// perceived the marks `bits` (`rows`: the same as cluster rows, when kept) and their
    /// step costs. Clusters come off the bit rows, their costs from the per-position
    /// fields (a shortest path of the full map inside the perceived space, else A* guided
    /// by the field); other action sets (and clusters when no bit rows are kept) come off
    /// the step costs' search over the perceived space, run once per state (`searched`).
    /// `base`: the slot in [`Recent`] and the position of an ancestor of the state, whose
    /// reachable component the clusters' fill starts from.
    fn actions(
        &mut self,
        pos: u32,
        bits: &[u64],
        rows: &[u64],
        set: ActionSet,
        searched: &mut bool,
        base: Option<(usize, u32)>,
    ) {
        self.cand_dist.clear();
        if let (Some(r), ActionSet::Clusters { min_size }) = (&mut self.rows, set) {
            let base = base.map(|(slot, from)| (self.recent.reach(slot), from));
            r.candidates(rows, pos, min_size, base, &mut self.cands);
            for &a in &self.cands {
                let fields = &mut self.heur.fields;
                // A shortest path of the full map inside, else a search guided by it.
                match fields
                    .inside(pos, a, bits)
                    .or_else(|| fields.guided(pos, a, bits))
                {
                    Some(d) => self.cand_dist.push(d),
                    None => break,
                }
            }
            if self.cand_dist.len() == self.cands.len() {
                return;
            }
            self.cand_dist.clear();
        }
        if !*searched {
            self.reach.compute(pos, bits);
            *searched = true;
        }
        if !matches!(set, ActionSet::Clusters { .. }) || self.rows.is_none() {
            candidates(
                self.problem,
                bits,
                self.reach.settled(),
                pos,
                set,
                &mut self.scratch,
                &mut self.cands,
            );
        }
        let reach = &self.reach;
        self.cand_dist
            .extend(self.cands.iter().map(|&a| reach.dist(a as usize)));
    }

    /// The greedy step among the candidates: the nearest that perceives a new target or,
    /// with `rate`, the best new targets per unit of path; `Some(None)` if none perceives
    /// one, `None` if the memory budget ran out.
    fn greedy_choice(&mut self, cur: &[u64], rate: bool) -> Option<Option<(f64, u32)>> {
        let nt = self.nt;
        let mut best: Option<(f64, u32)> = None;
        let mut best_rate = 0.0;
        for k in 0..self.cands.len() {
            // Each view asked for may be computed and kept: the budget is checked as for
            // the search's children.
            if self.over_budget() {
                return None;
            }
            let a = self.cands[k];
            let d = self.cand_dist[k];
            if rate {
                let (o, l) = self.vis.get(self.problem, a);
                let new = self.vis.data[o..o + l]
                    .iter()
                    .filter(|&&t| t < nt && !has(cur, t))
                    .count();
                let r = new as f64 / (d + 1.0);
                if new > 0
                    && (best.is_none()
                        || r > best_rate
                        || (r == best_rate && best.is_some_and(|b| (d, a) < b)))
                {
                    best = Some((d, a));
                    best_rate = r;
                }
                continue;
            }
            if best.is_some_and(|(bd, bi)| (d, a) >= (bd, bi)) {
                continue;
            }
            if self.vis.perceives_new(self.problem, a, cur, nt) {
                best = Some((d, a));
            }
        }
        Some(best)
    }

    /// Try to improve the incumbent with the blocks of cells `seed` from the root: in each
    /// block the perceived cell reachable inside the perceived space that perceives the
    /// most new targets (ties: the first listed) is visited, if any perceives one; the
    /// greedy completions (nearest, then by rate) finish the path, given up at `deadline`.
    fn incumbent_from(&mut self, seed: &[Vec<u32>], deadline: Option<Instant>) {
        let problem = self.problem;
        self.load_state(0);
        let mut bits = self.cur.clone();
        let mut count = self.nodes[0].count as usize;
        let mut pos = problem.start();
        let mut cost = 0.0;
        let mut positions = vec![pos];
        for block in seed {
            if count >= self.need || self.over_budget() {
                break;
            }
            let mut best: Option<(usize, u32)> = None;
            for &p in block {
                let t = problem.target_index(p as usize);
                if p == pos || t == crate::problem::NOT_TARGET || !has(&bits, t) {
                    continue;
                }
                let (o, l) = self.vis.get(problem, p);
                let new = self.vis.data[o..o + l]
                    .iter()
                    .filter(|&&m| m < self.nt && !has(&bits, m))
                    .count();
                if new > 0 && best.is_none_or(|(n, _)| new > n) {
                    best = Some((new, p));
                }
            }
            let Some((_, p)) = best else { continue };
            let fields = &mut self.heur.fields;
            let Some(d) = fields
                .inside(pos, p, &bits)
                .or_else(|| fields.guided(pos, p, &bits))
            else {
                continue;
            };
            count += self.perceive(p, &mut bits, None);
            cost += d;
            pos = p;
            positions.push(p);
        }
        let mut best: Option<(f64, Vec<u32>)> = (count >= self.need).then(|| (0.0, Vec::new()));
        for rate in [false, true] {
            if best.is_some() && count >= self.need {
                break;
            }
            let mut tail = Vec::new();
            if let Some(c) = self.greedy(pos, &bits, count, rate, deadline, &mut tail)
                && best.as_ref().is_none_or(|(b, _)| c < *b)
            {
                best = Some((c, tail));
            }
        }
        if let Some((c, tail)) = best
            && cost + c < self.inc_cost - EPS
        {
            positions.extend(tail);
            self.set_incumbent(cost + c, positions, true);
        }
    }

    /// Try to improve the incumbent with the greedy completions (nearest, then by rate) of
    /// stored state `id`, given up at `deadline`.
    fn improve_from(&mut self, id: u32, deadline: Option<Instant>) -> u64 {
        let n = self.nodes[id as usize];
        self.load_state(id);
        let bits = self.cur.clone();
        let mut steps = 0;
        for rate in [false, true] {
            let mut tail = Vec::new();
            let done = self.greedy(n.pos, &bits, n.count as usize, rate, deadline, &mut tail);
            steps += tail.len() as u64 + 1;
            if let Some(c) = done
                && n.g + c < self.inc_cost - EPS
            {
                let mut p = self.positions_of(id);
                p.extend(tail);
                self.set_incumbent(n.g + c, p, false);
            }
        }
        steps
    }

    fn run(
        &mut self,
        started: Instant,
        every: Duration,
        observe: &mut dyn FnMut(&Progress) -> bool,
    ) -> Outcome {
        let problem = self.problem;
        let start = problem.start();
        // Root.
        let (o, l) = self.vis.get(problem, start);
        let [mut key, mut check] = self.zpos[start as usize];
        let mut count = 0usize;
        for k in o..o + l {
            let t = self.vis.data[k];
            if !has(&self.cur, t) {
                set(&mut self.cur, t);
                key ^= self.zt[t as usize][0];
                check ^= self.zt[t as usize][1];
                count += usize::from(t < self.nt);
            }
        }
        let admissible = self
            .cfg
            .heuristic
            .admissible(problem.model(), self.cfg.goal);
        let w = self.cfg.weight;
        if count >= self.need {
            self.set_incumbent(0.0, vec![start], false);
            return self.finish(Status::Optimal, None, 0.0, started);
        }
        let cur = self.cur.clone();
        let h0 = self.heur.eval(problem, start, &cur, count);
        self.reserve_one();
        self.nodes.push(Node {
            pos: start,
            parent: NONE,
            g: 0.0,
            h: h0,
            key,
            check,
            count: count as u32,
            next_same: NONE,
            slot: recent::NONE,
            closed: false,
        });
        self.table.insert(key, 0);
        self.open.push(entry(w * h0, 0.0, 0));
        self.stats.stored = 1;
        // The first greedy completion keeps to the time limit: on a large map with a long
        // sensor range it can take minutes (a scan per candidate cell).
        // (a deadline past what an Instant can hold is none)
        let deadline = self.cfg.time_limit.and_then(|t| started.checked_add(t));
        self.improve_from(0, deadline);
        if self.cfg.coarse_incumbent > 1 {
            let seed =
                crate::coarse::coarse_positions(problem, self.cfg.coarse_incumbent, &self.cfg);
            self.incumbent_from(&seed, deadline);
        }
        let mut stop = None;
        let mut popped_lb = f64::INFINITY;
        // The largest priority popped so far, over w: every popped priority is the least in
        // the open list then, and the least g + w·h over open states is at most w times the
        // least g + h, itself a lower bound with an admissible h (some open state lies on an
        // optimal path with its optimal g while the incumbent is not optimal).
        let mut running_lb = 0.0f64;
        let mut next_report = every;
        while let Some(Reverse((fbits, _, id, gbits))) = self.open.pop() {
            let node = self.nodes[id as usize];
            if node.closed || gbits != node.g.to_bits() {
                continue;
            }
            let f = f64::from_bits(fbits);
            if f >= self.inc_cost - EPS {
                // Every open state is at least as long as the incumbent (weighted: w ×).
                popped_lb = node.g + node.h;
                self.open.push(entry(f, node.g, id));
                break;
            }
            running_lb = running_lb.max(f / w);
            if self.stats.expanded >= self.cfg.max_nodes {
                stop = Some(StopReason::NodeLimit);
            } else {
                // The clock is read before every expansion: on a wide open map with a long
                // range one expansion can take half a second, and reading it every 64th
                // let a 5 s limit run for 40 s, and Ctrl-C and the progress line wait as
                // long. A reading costs tens of nanoseconds, an expansion microseconds.
                let elapsed = started.elapsed();
                if self.cfg.time_limit.is_some_and(|t| elapsed >= t) {
                    stop = Some(StopReason::TimeLimit);
                } else if elapsed >= next_report {
                    next_report = elapsed.saturating_add(every);
                    let progress = Progress {
                        expanded: self.stats.expanded,
                        stored: self.stats.stored,
                        bytes: self.stats.bytes,
                        lower_bound: if admissible {
                            running_lb.min(self.inc_cost)
                        } else {
                            0.0
                        },
                        upper_bound: self.inc_cost,
                        seconds: elapsed.as_secs_f64(),
                    };
                    if !observe(&progress) {
                        stop = Some(StopReason::Interrupted);
                    }
                }
            }
            if stop.is_some() {
                self.open.push(entry(f, node.g, id));
                break;
            }
            self.nodes[id as usize].closed = true;
            self.stats.expanded += 1;
            if !self.expand(id) {
                stop = Some(StopReason::MemoryLimit);
                self.nodes[id as usize].closed = false;
                self.open.push(entry(f, node.g, id));
                break;
            }
        }
        // Lower bound: min over open states of g + h (valid with an admissible h), or the
        // largest popped priority over w if that is larger.
        let mut lb = popped_lb;
        for Reverse((_, _, id, gbits)) in self.open.iter() {
            let n = &self.nodes[*id as usize];
            if !n.closed && *gbits == n.g.to_bits() {
                lb = lb.min(n.g + n.h);
            }
        }
        lb = lb.max(running_lb);
        if stop.is_some() {
            // Tighten the upper bound by completing the most advanced open states greedily
            // (most targets perceived first, then least g + h): up to IMPROVE_STATES of them,
            // within IMPROVE_SHARE of the expansions in greedy steps (at least one).
            let mut open: Vec<(Reverse<u32>, u64, u32)> = self
                .open
                .iter()
                .filter_map(|Reverse((_, _, id, gbits))| {
                    let n = &self.nodes[*id as usize];
                    (!n.closed && *gbits == n.g.to_bits())
                        .then(|| (Reverse(n.count), (n.g + n.h).to_bits(), *id))
                })
                .collect();
            open.sort_unstable();
            open.dedup();
            // The budget counts greedy steps (one shortest-path search each, like an
            // expansion), not time, so a stop by the node limit stays deterministic.
            let mut budget = (self.stats.expanded as f64 * IMPROVE_SHARE) as u64;
            // Stopped by the clock, they also keep to a short grace (a tenth of the time
            // limit, at least a second): one completion of a large map can take minutes.
            let deadline = match stop {
                Some(StopReason::TimeLimit) => self
                    .cfg
                    .time_limit
                    .and_then(|t| Instant::now().checked_add((t / 10).max(Duration::from_secs(1)))),
                Some(StopReason::Interrupted) => Some(Instant::now() + Duration::from_secs(1)),
                _ => None,
            };
            for &(_, _, id) in open.iter().take(IMPROVE_STATES) {
                let steps = self.improve_from(id, deadline);
                budget = budget.saturating_sub(steps);
                if budget == 0 {
                    break;
                }
            }
        }
        if !admissible {
            lb = 0.0;
        } else if stop.is_none() && self.inc_cost.is_finite() {
            lb = lb.max(self.inc_cost / w);
        }
        let lb = lb.min(self.inc_cost).max(0.0);
        let status = match (stop, self.inc_cost.is_finite()) {
            (Some(_), _) => Status::Stopped,
            (None, false) => Status::NoSolution,
            (None, true) if !admissible => Status::Unproven,
            (None, true) if w > 1.0 => Status::WithinBound,
            (None, true) => Status::Optimal,
        };
        self.finish(status, stop, lb, started)
    }

    /// Expand state `id`; false if the memory budget ran out.
    fn expand(&mut self, id: u32) -> bool {
        let node = self.nodes[id as usize];
        let base = self.load_state(id);
        self.heur.enter();
        let mut next = Some(self.cfg.actions);
        let mut searched = false;
        while let Some(actions) = next {
            let cur = std::mem::take(&mut self.cur);
            let rows = std::mem::take(&mut self.seen_rows);
            self.actions(node.pos, &cur, &rows, actions, &mut searched, base);
            (self.cur, self.seen_rows) = (cur, rows);
            if self.over_budget() {
                return false;
            }
            // No candidate perceives a new target: offer the next larger set (the
            // deviation in `actions`).
            next = match self.children(id, node) {
                None => return false,
                Some(true) => None,
                Some(false) => actions.wider(),
            };
        }
        // Keep the state for its descendants, with R: cluster rows are kept only with the
        // cluster actions, whose first set's candidates found R.
        let reach = self
            .rows
            .as_ref()
            .map_or((&[][..], (0, 0)), ClusterRows::reach);
        self.nodes[id as usize].slot = self.recent.keep(id, &self.cur, &self.seen_rows, reach);
        self.stats.bytes = self.stats.bytes.max(self.bytes_with(0));
        true
    }

    /// Generate the children of state `id` (`node`, bits in `self.cur`) for the candidates
    /// in `self.cands`: `None` if the memory budget ran out, else whether any candidate
    /// perceives a new target (pruned or not).
    fn children(&mut self, id: u32, node: Node) -> Option<bool> {
        let problem = self.problem;
        let w = self.cfg.weight;
        let nt = self.nt;
        let mut useful = false;
        for k in 0..self.cands.len() {
            // The caches grow as candidates are looked at (a candidate's view, a child's
            // heuristic): the budget is checked at each, not only when a state is stored,
            // or one expansion of a wide open map overshot it several times over.
            if self.over_budget() {
                return None;
            }
            let a = self.cands[k];
            let g2 = node.g + self.cand_dist[k];
            if g2 >= self.inc_cost - EPS {
                self.stats.pruned += 1;
                useful = useful || self.vis.perceives_new(problem, a, &self.cur, nt);
                continue;
            }
            // What `a` perceives that the state has not, word by word.
            let ((o, l), _) = self.vis.words(problem, a, self.rows.as_ref());
            self.fresh_words.clear();
            let mut new_targets = 0;
            for &(word, bits) in &self.vis.word_data[o..o + l] {
                let f = bits & !self.cur[word as usize];
                if f != 0 {
                    self.fresh_words.push((word, f));
                    new_targets += (f & target_bits(word, nt)).count_ones() as usize;
                }
            }
            // A move that perceives no new target (walls at most) is dominated: the
            // boundary only shrinks and the perceived free space stays the same.
            if new_targets == 0 {
                continue;
            }
            useful = true;
            self.stats.generated += 1;
            let count2 = node.count as usize + new_targets;
            if count2 >= self.need {
                let mut p = self.positions_of(id);
                p.push(a);
                self.set_incumbent(g2, p, false);
                continue;
            }
            self.child.copy_from_slice(&self.cur);
            let (zq, za) = (self.zpos[node.pos as usize], self.zpos[a as usize]);
            let mut key2 = node.key ^ zq[0] ^ za[0];
            let mut check2 = node.check ^ zq[1] ^ za[1];
            for &(word, f) in &self.fresh_words {
                self.child[word as usize] |= f;
                let mut m = f;
                while m != 0 {
                    let t = word as usize * 64 + m.trailing_zeros() as usize;
                    m &= m - 1;
                    key2 ^= self.zt[t][0];
                    check2 ^= self.zt[t][1];
                }
            }
            // Duplicate detection (a stored state keeps its bound).
            let head = self.table.get(&key2).copied().unwrap_or(NONE);
            let mut dup = NONE;
            let mut j = head;
            while j != NONE {
                let n = &self.nodes[j as usize];
                if n.pos == a && n.key == key2 && n.check == check2 {
                    dup = j;
                    break;
                }
                j = n.next_same;
            }
            if dup != NONE {
                let n = &mut self.nodes[dup as usize];
                if g2 + n.h >= self.inc_cost - EPS {
                    self.stats.pruned += 1;
                    continue;
                }
                self.stats.duplicates += 1;
                if g2 < n.g - EPS {
                    if n.closed {
                        self.stats.reopened += 1;
                    }
                    n.g = g2;
                    n.parent = id;
                    n.closed = false;
                    let f = g2 + w * n.h;
                    self.open.push(entry(f, g2, dup));
                }
                continue;
            }
            // Bounds at or beyond the incumbent prune the child: no need to finish them.
            let cut = self.inc_cost - EPS - g2;
            let h = self
                .heur
                .eval_child(problem, a, &self.child, count2, &self.cur, cut);
            if g2 + h >= self.inc_cost - EPS {
                self.stats.pruned += 1;
                continue;
            }
            if !self.reserve_one() {
                return None;
            }
            let nid = self.nodes.len() as u32;
            self.nodes.push(Node {
                pos: a,
                parent: id,
                g: g2,
                h,
                key: key2,
                check: check2,
                count: count2 as u32,
                next_same: head,
                slot: recent::NONE,
                closed: false,
            });
            self.table.insert(key2, nid);
            self.open.push(entry(g2 + w * h, g2, nid));
            self.stats.stored += 1;
        }
        Some(useful)
    }

    fn finish(
        &mut self,
        status: Status,
        stop: Option<StopReason>,
        lb: f64,
        started: Instant,
    ) -> Outcome {
        let problem = self.problem;
        let solution = if self.inc_cost.is_finite() {
            let cells: Vec<Cell> = self
                .inc_positions
                .iter()
                .map(|&p| problem.cells().cell(p as usize))
                .collect();
            // The positions come from the search itself; re-walking them cannot fail.
            walk(problem, &cells).ok()
        } else {
            None
        };
        self.stats.seconds = started.elapsed().as_secs_f64();
        self.stats.landmarks = self.heur.landmark_count();
        self.stats.bytes = self.stats.bytes.max(self.bytes_with(0));
        let ub = self.inc_cost;
        let message = match status {
            Status::Optimal if self.inc_coarse => format!(
                "optimal: length {ub:.3} cells, the coarse incumbent's path (its positions \
                 are not all actions of the set; no path of the set is shorter)"
            ),
            Status::Optimal => format!("optimal: length {ub:.3} cells"),
            Status::WithinBound => format!(
                "weighted A* (w = {}): length {ub:.3} cells, optimal ≥ {lb:.3}",
                self.cfg.weight
            ),
            Status::Unproven => format!(
                "length {ub:.3} cells; heuristic {} is not admissible here, no guarantee",
                self.cfg.heuristic.name()
            ),
            Status::Stopped => format!(
                "stopped by the {} after {} expansions: optimal length in [{lb:.3}, {}] cells",
                stop.map_or("limit", StopReason::as_str),
                self.stats.expanded,
                if ub.is_finite() {
                    format!("{ub:.3}")
                } else {
                    "∞".into()
                }
            ),
            Status::NoSolution => {
                "no sequence of actions reaches the goal with this action set".into()
            }
        };
        Outcome {
            status,
            stop,
            solution,
            lower_bound: lb,
            upper_bound: ub,
            targets: problem.targets().len(),
            needed: self.need,
            stats: self.stats,
            message,
        }
    }
}

/// Whether flat cell `i` is reachable and among the perceived targets `bits`: where [`walk`]
/// may pass.
fn perceived_free(problem: &Problem, bits: &[u64]) -> impl Fn(usize) -> bool {
    move |i| problem.reachable(i) && has(bits, problem.target_index(i))
}

/// Re-walk a position sequence with time-discrete perception: each leg is a shortest path
/// inside the free cells perceived so far. Errors if a position is not reachable that way.
pub fn walk(problem: &Problem, positions: &[Cell]) -> Result<Solution, String> {
    let cells = problem.cells();
    let nt = problem.targets().len();
    let mut bits = vec![0u64; nt.div_ceil(64).max(1)];
    let mut count = 0;
    let mut obs = Observation::new();
    let mut seen = Vec::new();
    let mut reach = Reachability::new(cells.width(), cells.height());
    let mut path: Vec<u32> = Vec::new();
    let mut leg: Vec<u32> = Vec::new();
    let mut length = 0.0;
    let Some(&first) = positions.first() else {
        return Err("no positions".into());
    };
    if cells.checked_index(first) != Some(problem.start() as usize) {
        return Err(format!("the sequence starts at {first}, not at the start"));
    }
    for (k, &p) in positions.iter().enumerate() {
        let Some(pi) = cells.checked_index(p) else {
            return Err(format!("position {k} {p} is outside the map"));
        };
        if k > 0 {
            let from = path[path.len() - 1] as usize;
            let passable = perceived_free(problem, &bits);
            // Settled in the same order as a full search, so the same cost and path.
            reach.nearest(from, &passable, |i| i == pi);
            let d = dist(&reach, pi);
            if !d.is_finite() || (pi != from && !passable(pi)) {
                return Err(format!(
                    "position {k} {p} is not reachable inside the perceived free space"
                ));
            }
            length += d;
            reach.path_to(pi, &mut leg);
            path.extend_from_slice(&leg[1..]); // the leg's first cell is the previous position
        } else {
            path.push(pi as u32);
        }
        seen.clear();
        problem.seen_targets(pi as u32, &mut obs, &mut seen);
        for &t in &seen {
            if !has(&bits, t) {
                set(&mut bits, t);
                count += 1;
            }
        }
    }
    Ok(Solution {
        positions: positions.to_vec(),
        path: path.iter().map(|&i| cells.cell(i as usize)).collect(),
        length,
        perceived: count,
    })
}

/// Solve `problem` with `cfg`: the shortest sequence of sensing positions (for the action
/// set) whose perceptions cover the goal fraction of the targets, or bounds when a limit
/// stops the search first.
pub fn solve(problem: &Problem, cfg: &Config) -> Result<Outcome, OptimalError> {
    solve_with(problem, cfg, Duration::MAX, &mut |_| true)
}

/// The most landmarks the landmark heuristic takes.
pub const MAX_LANDMARKS: usize = 4096;

/// Set-up bytes per map cell, before the first expansion: the problem's neighbour and
/// mark tables, two step-cost tables (the search's and the heuristic's), Zobrist keys, the
/// visibility index and the heuristic's per-cell slots. Measured as peak resident memory
/// at one expansion: 527–542 B per cell on open maps of 0.36–1.44 M cells, all reachable.
pub const SETUP_BYTES_PER_CELL: u64 = 560;

/// Estimated peak bytes of setting up the search on a map of `cells` cells sensed with
/// `model`, before the first state is stored: counted against [`Config::max_bytes`] and
/// checked before anything map-sized is allocated. The line-of-sight model adds its ray
/// template, whose size depends on the range alone.
pub fn setup_bytes(cells: usize, model: SensorModel) -> u64 {
    let views = cells
        .saturating_mul(model.disc_cells())
        .min(crate::heuristic::VIEW_ENTRIES);
    let template = match model {
        SensorModel::Los(r) => sense::ray_template::build_bytes(r),
        SensorModel::Footprint(_) => 0,
    };
    SETUP_BYTES_PER_CELL
        .saturating_mul(cells as u64)
        .saturating_add(4 * views as u64)
        .saturating_add(template)
}

/// [`solve`], showing `observe` the search's [`Progress`] at most once per `every` of wall
/// time (checked before every expansion, so `Duration::ZERO` means before each); when
/// it returns false the search stops as if a limit was hit ([`StopReason::Interrupted`]),
/// with the best bounds. The observer does not change the search otherwise: the result is
/// the same as [`solve`]'s unless it asks to stop.
pub fn solve_with(
    problem: &Problem,
    cfg: &Config,
    every: Duration,
    observe: &mut dyn FnMut(&Progress) -> bool,
) -> Result<Outcome, OptimalError> {
    if !(cfg.goal > 0.0 && cfg.goal <= 1.0) {
        return Err(OptimalError::BadParameter {
            field: "goal",
            expected: "a coverage fraction in (0, 1]",
            found: cfg.goal.to_string(),
        });
    }
    if !(cfg.weight.is_finite() && cfg.weight >= 1.0) {
        return Err(OptimalError::BadParameter {
            field: "weight",
            expected: "a finite weight ≥ 1",
            found: cfg.weight.to_string(),
        });
    }
    if cfg.landmarks > MAX_LANDMARKS {
        return Err(OptimalError::BadParameter {
            field: "landmarks",
            expected: "at most 4096 landmarks",
            found: cfg.landmarks.to_string(),
        });
    }
    let needed = setup_bytes(problem.cells().len(), problem.model());
    if needed > cfg.max_bytes as u64 {
        return Err(OptimalError::Memory {
            needed,
            budget: cfg.max_bytes as u64,
        });
    }
    let started = Instant::now();
    let mut engine = Engine::new(problem, cfg);
    Ok(engine.run(started, every, observe))
}

/// The heuristic's value for the robot at `pos` having perceived the targets in `perceived`
/// (indexed like [`Problem::targets`]); for tests and diagnostics.
pub fn heuristic_value(problem: &Problem, cfg: &Config, pos: Cell, perceived: &[bool]) -> f64 {
    let nt = problem.targets().len();
    let mut bits = vec![0u64; nt.div_ceil(64).max(1)];
    let mut count = 0;
    for (t, &p) in perceived.iter().enumerate().take(nt) {
        if p {
            set(&mut bits, t as u32);
            count += 1;
        }
    }
    let mut h = Heuristic::new(problem, cfg.heuristic, cfg.goal, cfg.landmarks, usize::MAX);
    match problem.cells().checked_index(pos) {
        Some(p) => h.eval(problem, p as u32, &bits, count),
        None => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// [`solve`] with the cluster actions on bit rows (`fast`) or read off the step costs'
    /// search for every state.
    fn solve_as(problem: &Problem, cfg: &Config, fast: bool) -> Outcome {
        let mut engine = Engine::new(problem, cfg);
        if !fast {
            // As an engine built without cluster rows: no rows to load or keep either.
            engine.rows = None;
            engine.seen_rows.clear();
            engine.recent = Recent::new(RECENT_STATES, engine.cur.len(), 0);
        }
        engine.run(Instant::now(), Duration::MAX, &mut |_| true)
    }

    /// Regression: a memory budget smaller than the set-up was spent anyway and the search
    /// stopped after 0 expansions as if it had run; it is refused before the engine exists.
    #[test]
    fn budget_below_the_set_up_is_refused() {
        let (p, _) = crate::walled_problem(20, 12, &[1; 240], 0, SensorModel::Los(3.0))
            .expect("an open problem");
        let need = setup_bytes(p.cells().len(), p.model());
        assert!(need >= SETUP_BYTES_PER_CELL * 240, "{need}");
        let cfg = Config {
            max_bytes: need as usize - 1,
            ..Config::default()
        };
        match solve(&p, &cfg) {
            Err(OptimalError::Memory { needed, budget }) => {
                assert_eq!((needed, budget), (need, need - 1));
            }
            other => panic!("expected a memory error, got {other:?}"),
        }
        let cfg = Config {
            max_bytes: 2 * need as usize,
            ..Config::default()
        };
        assert!(solve(&p, &cfg).is_ok());
    }

    /// The standard library's hash table grows as [`table_capacity_grown`] predicts, as
    /// [`Engine::reserve_one`] grows it: from full, by half its entries or 1024.
    #[test]
    fn table_growth_is_predicted() {
        let mut t: HashMap<u64, u32, BuildHasherDefault<MixHasher>> = HashMap::default();
        let mut next = 0u64;
        for _ in 0..12 {
            while t.len() < t.capacity() {
                t.insert(next, 0);
                next += 1;
            }
            let (len, cap) = (t.len(), t.capacity());
            let grow = (len / 2).max(1024);
            t.reserve(grow);
            assert_eq!(
                t.capacity(),
                table_capacity_grown(cap, len + grow),
                "{len} + {grow}"
            );
        }
    }

    /// Regression: the heuristic's caches (the positions' distance orders and path-cost
    /// fields) were emptied once their entries passed their share of the budget, but grew
    /// by doubling before that, to twice the share: the search counted more bytes than its
    /// budget in one step. An open 60 x 60 m map at 0.2 m with `--memory-mb 200` stopped
    /// after 6 s having counted 236 MiB (resident 184 MiB); the table of states, counted
    /// at 16 bytes an entry and grown by the standard library's rounding, added to it. The
    /// caches now grow only up to their share.
    #[test]
    fn heuristic_caches_stay_within_the_budget() {
        let (p, _) = crate::walled_problem(60, 45, &[1; 2700], 1300, SensorModel::Los(4.0))
            .expect("an open problem");
        let need = setup_bytes(p.cells().len(), p.model()) as usize;
        for times in [2, 3, 5, 8] {
            let max_bytes = need * times;
            let cfg = Config {
                max_bytes,
                ..Config::default()
            };
            let held = solve(&p, &cfg).expect("solve");
            assert!(
                held.stats.bytes <= max_bytes,
                "{} > {max_bytes} ({times} x the set-up)",
                held.stats.bytes
            );
        }
    }

    /// Regression: the greedy completions that give the search its upper bounds computed
    /// a view for every candidate they weighed and kept it, with no look at the budget: an
    /// open 60 x 60 m map at 0.2 m with `--memory-mb 150` counted 214 MiB and held 191 MiB.
    /// Here every perceived cell is an action, so the completions weigh them all.
    /// Views are now forgotten when the budget is reached (and computed again when asked
    /// for), so the bounds are the same within a budget the views alone would exceed.
    #[test]
    fn greedy_views_stay_within_the_budget() {
        let (p, _) = crate::walled_problem(80, 60, &[1; 4800], 2440, SensorModel::Los(10.0))
            .expect("an open problem");
        let cfg = Config {
            max_nodes: 1,
            actions: ActionSet::All,
            ..Config::default()
        };
        let free = solve(&p, &cfg).expect("solve");
        let need = setup_bytes(p.cells().len(), p.model()) as usize;
        let max_bytes = need / 10 * 13;
        let held = solve(&p, &Config { max_bytes, ..cfg }).expect("solve");
        assert!(
            held.stats.bytes <= max_bytes,
            "{} > {max_bytes}",
            held.stats.bytes
        );
        assert_eq!(
            (held.lower_bound, held.upper_bound, held.status),
            (free.lower_bound, free.upper_bound, free.status)
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// A first incumbent from the coarsened problem changes only the upper bound: a
        /// search that finishes ends as without it, never longer (the coarse path's cells
        /// need not be actions of the set, so it may be shorter than the set's optimum), its
        /// path is valid, and it is never shorter than the optimum over all positions.
        #[test]
        fn coarse_incumbent_keeps_the_optimum(
            w in 6usize..20,
            h in 4usize..12,
            walls in proptest::collection::vec(0u8..8, 20 * 12),
            pick in 0usize..240,
            fp in any::<bool>(),
            full in any::<bool>(),
            factor in 2usize..4,
        ) {
            let model = if fp { SensorModel::Footprint(3.0) } else { SensorModel::Los(3.0) };
            let case = crate::walled_problem(w, h, &walls, pick, model);
            prop_assume!(case.is_some());
            let (p, _) = case.expect("assumed");
            let cfg = Config {
                goal: if full { 1.0 } else { 0.9 },
                actions: ActionSet::Clusters { min_size: 1 },
                max_nodes: 20_000,
                ..Config::default()
            };
            let plain = solve(&p, &cfg).expect("solve");
            let seeded = solve(&p, &Config { coarse_incumbent: factor, ..cfg }).expect("solve");
            prop_assert_eq!(plain.status, seeded.status);
            if plain.status == Status::Optimal {
                prop_assert!(seeded.upper_bound <= plain.upper_bound + 1e-9,
                    "{} > {}", seeded.upper_bound, plain.upper_bound);
                let sol = seeded.solution.expect("solution");
                let again = walk(&p, &sol.positions).expect("valid path");
                prop_assert!((again.length - seeded.upper_bound).abs() < 1e-9);
                prop_assert!(again.perceived >= p.needed(cfg.goal));
                // A path shorter than the set's optimum is the coarse incumbent's, and says so.
                if seeded.upper_bound < plain.upper_bound - 1e-9 {
                    prop_assert!(seeded.message.contains("coarse incumbent"), "{}", seeded.message);
                }
                let all = solve(&p, &Config { actions: ActionSet::All, ..cfg }).expect("solve");
                if all.status == Status::Optimal {
                    prop_assert!(seeded.upper_bound >= all.upper_bound - 1e-9);
                }
            }
        }

        /// Cluster actions on bit rows with step costs from the per-position fields give
        /// the search's own result: same status, length and bounds, on random maps with
        /// rooms behind walls (footprint), both sensors, G = 1 and 0.85. (Not always the
        /// same expansions: a field's cost and the search's may differ in the last bit when
        /// two shortest paths tie, which can reorder equal priorities.)
        #[test]
        fn bit_row_clusters_search_like_the_step_cost_search(
            w in 6usize..24,
            h in 4usize..14,
            walls in proptest::collection::vec(0u8..6, 24 * 14),
            pick in 0usize..336,
            fp in any::<bool>(),
            full in any::<bool>(),
            min_size in 1usize..3,
        ) {
            let model = if fp { SensorModel::Footprint(2.5) } else { SensorModel::Los(2.5) };
            let case = crate::walled_problem(w, h, &walls, pick, model);
            prop_assume!(case.is_some());
            let (p, _) = case.expect("assumed");
            let cfg = Config {
                goal: if full { 1.0 } else { 0.85 },
                actions: ActionSet::Clusters { min_size },
                max_nodes: 20_000,
                ..Config::default()
            };
            let fast = solve_as(&p, &cfg, true);
            let slow = solve_as(&p, &cfg, false);
            prop_assert_eq!(fast.status, slow.status);
            prop_assert!((fast.upper_bound - slow.upper_bound).abs() < 1e-9 || fast.upper_bound == slow.upper_bound,
                "{} vs {}", fast.upper_bound, slow.upper_bound);
            prop_assert!((fast.lower_bound - slow.lower_bound).abs() < 1e-9, "{} vs {}", fast.lower_bound, slow.lower_bound);
        }
    }
}
