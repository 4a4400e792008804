//! Lower bounds on the remaining exploration length: Quattrini Li et al.'s heuristic
//! (their Eq. 1 and 2), corrected where it is not admissible, and a stronger bound from a
//! minimum spanning tree over landmark cells (in the spirit of watchman-route searches).
//!
//! Notation: state (q, M); U = targets not in M; d = shortest 8-connected path length in the
//! full map (no corner squeezing); V(t) = reachable positions that perceive target t;
//! every later sensing position p is reached at a cost ≥ d(q, p) (paths inside M are paths
//! of the full map).
//!
//! # `Paper`, line-of-sight sensor: h = max_{t∈U} d(q, t) − c, c = max{|dx|+|dy| : dx²+dy² ≤ r²} ≤ r√2
//! To perceive t the robot must stop at some p ∈ V(t). The segment p→t is clear: its crossed
//! cells are free and, where it passes through a vertex, one of the two touched cells is
//! free. Walking the crossed cells (through a free touched cell at a vertex) is a monotone
//! 4-connected path of exactly |dx|+|dy| steps, so d(p, t) ≤ |dx|+|dy| ≤ c ≤ r√2 (the paper's
//! constant, slightly sharpened to integer offsets). Hence the remaining cost
//! ≥ d(q, p) ≥ d(q, t) − d(p, t) ≥ d(q, t) − c for every t ∈ U: admissible (and consistent:
//! a step to q' that perceives the maximiser t had d(q', t) ≤ c, so d(q, t) − c ≤ d(q, q')).
//!
//! # `Paper`, footprint sensor: h = max_{t∈U} |q − t| − c, c = max{√(dx²+dy²) ≤ r}
//! The footprint sees through walls, so d(p, t) is unbounded and the paper's Eq. 1 is NOT
//! admissible (two rooms back to back: d(q, t) can be 50 while one step perceives t). With
//! Euclidean distance: the cost to reach p ≥ octile(q, p) ≥ |q − p| ≥ |q − t| − |p − t|
//! ≥ |q − t| − c. Admissible.
//!
//! # Weaker goal G < 1 (deviation from the paper's Eq. 2)
//! Eq. 2 multiplies Eq. 1 by max(0, G − |M|/|E_f|). That is not admissible: the farthest
//! cell may be among the (1 − G)·|E_f| cells the goal lets the robot skip (a long dead-end
//! corridor holding 1 % of the cells, G = 0.95: Eq. 2 is 0.45 × its length, the true cost
//! 0). Admissible instead: the robot may leave at most s = |E_f| − ⌈G·|E_f|⌉ targets
//! unperceived, so at least one of the s + 1 targets with the largest bound b(t) above must
//! be perceived: h = the (s + 1)-th largest b(t) over U. Eq. 2 is kept as
//! [`HeuristicKind::PaperAsPublished`], flagged inadmissible.
//!
//! # `Landmarks`: h = max(order statistic, coverage rate, landmark path bound or skip-budget bound)
//! The order statistic is `Paper`'s, except that with the footprint sensor each target's
//! value is D(q, t), the path distance to its nearest viewpoint
//! (`viewpoint_distance`), instead of |q − t| − c: every value is then the exact
//! cost of perceiving that one target, and walls count.
//! The coverage-rate bound (K more targets at most ρ* per unit of path, proof in
//! `coverage_rate`) holds for every G. The landmark bound below only for G = 1;
//! for G < 1 the skip-budget bound (the far ends of the map must still be approached, the
//! budget of unperceived targets shared between them; proof in `skip_budget`).
//!
//! ## The landmark path bound (G = 1)
//! Landmarks a_1..a_K are reachable targets; V(a) is the set of reachable positions that
//! see a. Order the landmarks of U by when the robot first perceives them, from positions
//! p_1 ∈ V(a_1), p_2 ∈ V(a_2), ... in path order. Then the remaining cost
//! ≥ d(q, p_1) + Σ d(p_i, p_{i+1}) ≥ D(q, V(a_1)) + Σ D(V(a_i), V(a_{i+1})), with D the
//! shortest distance between two sets (one multi-source field per landmark, from V(a)).
//! That is the weight of a Hamiltonian path from q through the landmarks of U under the
//! weights w = D, so at least its Held–Karp bound (`held_karp`), itself at least
//! the minimum spanning tree of {q} ∪ (landmarks in U). Admissible. The weights are set
//! distances, not a metric, so a landmark whose V touches another's only adds free
//! bridges: landmarks are chosen by farthest-point sampling in D (the next is the target
//! whose viewpoints are farthest from the start's cell and from every chosen landmark's
//! viewpoints) until every target's viewpoints touch a landmark's. On maps too large to
//! keep every V(t), the sampling uses the distance to the target itself and stops within
//! the sensor's reach. (For G < 1 the robot may skip any landmark, so the bound is not
//! used there.)

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use explore::plan::Reachability;
use grid::Occ;

use crate::block_masks::{BLOCK, BlockMasks};
use crate::coverage_rate::CoverageRate;
use crate::held_karp::PathBound;
use crate::problem::{Problem, SensorModel};
use crate::room::{RESERVED_POSITIONS, room_bytes, room_for};
use crate::skip_budget::SkipBudget;
use crate::step_cost::FieldCache;
use crate::viewpoint_distance::ViewpointDistance;

/// Which lower bound guides the search.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeuristicKind {
    /// h = 0: uniform-cost search.
    Zero,
    /// The paper's Eq. 1, admissible per sensor (module doc), order statistic for G < 1.
    Paper,
    /// The paper's Eq. 1/2 exactly as printed (path distance − r√2, × max(0, G − |M|/|E_f|));
    /// NOT admissible with the footprint sensor or G < 1.
    PaperAsPublished,
    /// max(Paper, coverage rate, Held–Karp bound on a path through landmarks at G = 1 or
    /// the skip-budget bound at G < 1).
    Landmarks,
}

impl HeuristicKind {
    /// Whether the bound is a proven lower bound for this sensor and goal.
    pub fn admissible(self, model: SensorModel, goal: f64) -> bool {
        match self {
            HeuristicKind::PaperAsPublished => !model.through_walls() && goal >= 1.0,
            _ => true,
        }
    }

    /// The stable name (`zero`, `paper`, `paper-as-published`, `landmarks`).
    pub fn name(self) -> &'static str {
        match self {
            HeuristicKind::Zero => "zero",
            HeuristicKind::Paper => "paper",
            HeuristicKind::PaperAsPublished => "paper-as-published",
            HeuristicKind::Landmarks => "landmarks",
        }
    }
}

impl std::str::FromStr for HeuristicKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "zero" => Ok(HeuristicKind::Zero),
            "paper" => Ok(HeuristicKind::Paper),
            "paper-as-published" => Ok(HeuristicKind::PaperAsPublished),
            "landmarks" => Ok(HeuristicKind::Landmarks),
            other => Err(format!(
                "expected zero, paper, paper-as-published or landmarks, found '{other}'"
            )),
        }
    }
}

/// Whether target `t` is in the bitset.
#[inline]
pub(crate) fn has(bits: &[u64], t: u32) -> bool {
    bits[(t >> 6) as usize] >> (t & 63) & 1 == 1
}

/// Add target (or mark) `t` to the bitset.
#[inline]
pub(crate) fn set(bits: &mut [u64], t: u32) {
    bits[(t >> 6) as usize] |= 1 << (t & 63);
}

/// Append `bits` ((word, bit) pairs) to `out` as (word, bits) with one entry per word,
/// by word.
pub(crate) fn push_words(out: &mut Vec<(u32, u64)>, bits: impl Iterator<Item = (u32, u64)>) {
    let start = out.len();
    out.extend(bits);
    out[start..].sort_unstable_by_key(|&(k, _)| k);
    let mut kept = start;
    for j in start..out.len() {
        let (k, b) = out[j];
        if kept > start && out[kept - 1].0 == k {
            out[kept - 1].1 |= b;
        } else {
            out[kept] = (k, b);
            kept += 1;
        }
    }
    out.truncate(kept);
}

/// Path cost to cell `i` in the last search, `∞` if it was not reached.
#[inline]
pub(crate) fn dist(reach: &Reachability, i: usize) -> f64 {
    reach.cost(i).unwrap_or(f64::INFINITY)
}

/// max{|dx| + |dy| : dx² + dy² ≤ r²} over integer offsets.
pub(crate) fn max_l1_within(r: f64) -> f64 {
    let reach = r.floor() as i64;
    let mut best = 0;
    for dx in 0..=reach {
        for dy in 0..=reach {
            if ((dx * dx + dy * dy) as f64) <= r * r {
                best = best.max(dx + dy);
            }
        }
    }
    best as f64
}

/// max{√(dx² + dy²) ≤ r} over integer offsets.
fn max_euclid_within(r: f64) -> f64 {
    let reach = r.floor() as i64;
    let mut best = 0i64;
    for dx in 0..=reach {
        for dy in 0..=reach {
            let d2 = dx * dx + dy * dy;
            if (d2 as f64) <= r * r {
                best = best.max(d2);
            }
        }
    }
    (best as f64).sqrt()
}

/// The heuristic with its caches (distance orders per position, landmark fields).
pub(crate) struct Heuristic {
    kind: HeuristicKind,
    model: SensorModel,
    goal: f64,
    /// Constant subtracted from a distance (module doc).
    c: f64,
    n_targets: usize,
    /// Targets that may stay unperceived at the end.
    skip: usize,
    /// Per flat cell: the slot of its order in `orders` (`u32::MAX`: none yet). An order
    /// is the `order_len` targets of largest bound value, descending (value, target).
    order_slot: Vec<u32>,
    /// Entries kept per position: all for the paper's formula as published, else
    /// 2(s + 1) + [`ORDER_SLACK`] and at least [`ORDER_MIN`] (on a 350 × 250 map at G = 0.95
    /// a seventh of the targets).
    order_len: usize,
    orders: Vec<(f64, u32)>,
    /// The orders' blocks, `order_len.div_ceil(BLOCK)` per slot.
    blocks: BlockMasks,
    /// Scratch of [`sort_desc_stable`].
    sort_scratch: (Vec<u32>, Vec<(f64, u32)>),
    cache_cap_bytes: usize,
    dij: Reachability,
    /// Per-position path costs in the full map (the orders' distances; the search's step
    /// costs to cluster representatives).
    pub(crate) fields: FieldCache,
    /// With the footprint sensor and [`HeuristicKind::Landmarks`]: orders by the distance
    /// to the nearest viewpoint (`viewpoint_distance`) instead of |q − t| − c.
    vd: Option<ViewpointDistance>,
    /// The coverage-rate bound.
    rate: CoverageRate,
    /// The skip-budget bound (G < 1 only).
    far: Option<SkipBudget>,
    // Landmarks.
    lm_t: Vec<u32>,
    lm_field: Vec<f64>,
    lm_w: Vec<f64>,
    /// The unperceived landmarks of the state being bounded.
    left: Vec<usize>,
    /// The Held–Karp bound's scratch and weight matrix.
    hk: PathBound,
    hk_w: Vec<f64>,
    /// Landmark path bounds by (unperceived-landmark mask, position), with at most 64
    /// landmarks: sibling states share most landmark sets, and the bound costs O(K²) per
    /// subgradient step.
    path_cache: HashMap<(u64, u32), f64, BuildHasherDefault<MixHasher>>,
}

/// Entries kept in a position's distance order beyond 2(s + 1).
const ORDER_SLACK: usize = 256;
/// Entries a position's distance order keeps at least (maps of a few thousand targets keep
/// them all: there the order statistic often lies deeper than 2(s + 1) + 256).
const ORDER_MIN: usize = 4096;

/// Entries of the landmark path cache before it is cleared (≈ 40 bytes each).
const PATH_CACHE_ENTRIES: usize = 1 << 20;

/// Fx-style multiply-rotate hasher for integer keys (the landmark path cache, the search's table of
/// Zobrist keys).
#[derive(Default)]
pub(crate) struct MixHasher(u64);

impl Hasher for MixHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7C_C1_B7_27_22_0A_95);
    }
    fn write_u32(&mut self, v: u32) {
        self.write_u64(u64::from(v));
    }
}

impl Heuristic {
    /// Set up `kind` for `problem` and goal `g`; `landmarks` is the number of landmarks.
    pub(crate) fn new(
        problem: &Problem,
        kind: HeuristicKind,
        goal: f64,
        landmarks: usize,
        cache_cap_bytes: usize,
    ) -> Self {
        let model = problem.model();
        let r = model.range();
        let c = match (kind, model) {
            (HeuristicKind::PaperAsPublished, _) => r * grid::SQRT2,
            (_, SensorModel::Los(_)) => max_l1_within(r),
            (_, SensorModel::Footprint(_)) => max_euclid_within(r),
        };
        let n_targets = problem.targets().len();
        let skip = n_targets - problem.needed(goal);
        let order_len = if kind == HeuristicKind::PaperAsPublished {
            n_targets
        } else {
            n_targets.min((2 * (skip + 1) + ORDER_SLACK).max(ORDER_MIN))
        };
        let cells = problem.cells();
        let mut h = Self {
            kind,
            model,
            goal,
            c,
            n_targets,
            skip,
            order_len,
            order_slot: vec![u32::MAX; cells.len()],
            orders: Vec::new(),
            blocks: BlockMasks::default(),
            sort_scratch: Default::default(),
            cache_cap_bytes,
            dij: Reachability::new(cells.width(), cells.height()),
            fields: FieldCache::new(problem, cache_cap_bytes / 2),
            vd: if kind == HeuristicKind::Landmarks && model.through_walls() {
                ViewpointDistance::new(&crate::coverage_rate::offsets(model))
            } else {
                None
            },
            rate: CoverageRate::new(model),
            far: None,
            lm_t: Vec::new(),
            lm_field: Vec::new(),
            lm_w: Vec::new(),
            left: Vec::new(),
            hk: PathBound::default(),
            hk_w: Vec::new(),
            path_cache: HashMap::default(),
        };
        if kind == HeuristicKind::Landmarks && h.skip == 0 && landmarks > 0 {
            h.choose_landmarks(problem, landmarks);
        }
        if kind == HeuristicKind::Landmarks {
            h.far = SkipBudget::new(problem, h.skip, &mut h.fields);
            if h.vd.is_some()
                && let Some(far) = &mut h.far
            {
                far.without_single_point();
            }
        }
        h
    }

    /// Bytes held by the caches.
    pub(crate) fn bytes(&self) -> usize {
        self.orders.capacity() * 16
            + self.blocks.bytes()
            + self.order_slot.len() * 4
            + self.lm_field.capacity() * 8
            + self.path_cache.capacity() * 40
            + self.far.as_ref().map_or(0, SkipBudget::bytes)
            + self.vd.as_ref().map_or(0, ViewpointDistance::bytes)
            + self.fields.bytes()
    }

    /// Number of landmarks in use.
    pub(crate) fn landmark_count(&self) -> usize {
        self.lm_t.len()
    }

    /// Choose up to `k` landmarks and compute their viewpoint fields and edge weights.
    fn choose_landmarks(&mut self, problem: &Problem, k: usize) {
        let cells = problem.cells();
        let n = cells.len();
        let data = cells.data();
        let reach_targets: Vec<u32> = problem
            .targets()
            .iter()
            .copied()
            .filter(|&i| problem.reachable(i as usize))
            .collect();
        if reach_targets.is_empty() {
            return;
        }
        let views = Views::new(problem, &reach_targets);
        // score[j]: how far target reach_targets[j] is from the start and the landmarks
        // chosen so far (module doc); the next landmark is the farthest.
        self.dij
            .compute(problem.start() as usize, |i| data[i] == Occ::Free);
        let mut field: Vec<f64> = (0..n).map(|i| dist(&self.dij, i)).collect();
        let mut score = vec![f64::INFINITY; reach_targets.len()];
        // V(a) of each chosen landmark.
        let mut chosen: Vec<Vec<usize>> = Vec::new();
        loop {
            views.lower(&reach_targets, &field, &mut score);
            if chosen.len() >= k {
                break;
            }
            let mut best: Option<(f64, usize)> = None;
            for (j, &d) in score.iter().enumerate() {
                if best.is_none_or(|(bd, _)| d > bd) {
                    best = Some((d, j));
                }
            }
            let Some((d, j)) = best else { break };
            if d <= views.spacing(self.c) {
                break;
            }
            let a = reach_targets[j];
            let va = views.of(problem, j, a);
            self.dij.compute_from(&va, |i| data[i] == Occ::Free);
            field.clear();
            field.extend((0..n).map(|i| dist(&self.dij, i)));
            self.lm_field.extend_from_slice(&field);
            self.lm_t.push(problem.target_index(a as usize));
            chosen.push(va);
        }
        let kk = self.lm_t.len();
        self.lm_w = vec![0.0; kk * kk];
        for (j, vj) in chosen.iter().enumerate() {
            // D(V(a_i), V(a_j)): the field of V(a_i) at the nearest viewpoint of a_j.
            for i in 0..kk {
                let f = &self.lm_field[i * n..(i + 1) * n];
                self.lm_w[i * kk + j] = vj.iter().map(|&p| f[p]).fold(f64::INFINITY, f64::min);
            }
        }
        // Symmetric up to rounding; keep the smaller so the bound stays valid.
        for i in 0..kk {
            for j in i + 1..kk {
                let m = self.lm_w[i * kk + j].min(self.lm_w[j * kk + i]);
                self.lm_w[i * kk + j] = m;
                self.lm_w[j * kk + i] = m;
            }
        }
    }

    /// How the orders make room for one more position: (entries appended, first room, the
    /// cap in entries: what their blocks leave of the caches' share). A full list is
    /// appended before it is cut to `order_len`.
    fn order_room(&self) -> (usize, usize, usize) {
        let first = self
            .order_len
            .saturating_mul(RESERVED_POSITIONS)
            .saturating_add(self.n_targets);
        let limit = self.cache_cap_bytes.saturating_sub(self.blocks.bytes()) / 16;
        (self.n_targets, first, limit)
    }

    /// The bytes the caches may add for the next position they take in ([`Heuristic::bytes`]
    /// counts what they hold).
    pub(crate) fn growth_bytes(&self) -> usize {
        let (need, first, limit) = self.order_room();
        room_bytes(&self.orders, need, first, limit)
            + self.blocks.growth_bytes(self.order_len)
            + self.fields.growth_bytes()
    }

    /// The distance order of position `pos` (computed on first use).
    fn order(&mut self, problem: &Problem, pos: u32) -> usize {
        let s = self.order_slot[pos as usize];
        if s != u32::MAX {
            return s as usize * self.order_len;
        }
        let (need, first, limit) = self.order_room();
        if !room_for(&mut self.orders, need, first, limit) {
            self.orders.clear();
            self.order_slot.fill(u32::MAX);
            self.blocks.clear();
            room_for(&mut self.orders, need, first, limit);
        }
        let base = self.orders.len();
        let slot = base / self.order_len;
        let targets = problem.targets();
        let cells = problem.cells();
        let euclid = matches!(self.model, SensorModel::Footprint(_))
            && self.kind != HeuristicKind::PaperAsPublished;
        if let Some(vd) = &mut self.vd {
            vd.append(problem, self.fields.costs(pos), &mut self.orders);
            // Every target has a reachable viewpoint; a value that is not finite bounds
            // nothing.
            for e in &mut self.orders[base..] {
                if !e.0.is_finite() {
                    e.0 = 0.0;
                }
            }
        } else if euclid {
            let q = cells.cell(pos as usize);
            self.orders.extend(
                targets
                    .iter()
                    .enumerate()
                    .map(|(t, &i)| (q.dist(cells.cell(i as usize)), t as u32)),
            );
        } else {
            // Path distances from the position's field, shared with the step costs. Targets
            // the path cannot reach (footprint only: seen through a wall) bound nothing:
            // value 0.
            let costs = self.fields.costs(pos);
            self.orders
                .extend(targets.iter().enumerate().map(|(t, &i)| {
                    let d = costs(i as usize);
                    (if d.is_finite() { d } else { 0.0 }, t as u32)
                }));
        }
        // Descending by bound value (ties: lower target first), the first `order_len` kept.
        let desc = |a: &(f64, u32), b: &(f64, u32)| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1));
        if self.order_len < self.n_targets {
            self.orders[base..].select_nth_unstable_by(self.order_len - 1, desc);
            self.orders.truncate(base + self.order_len);
            self.orders[base..].sort_unstable_by(desc);
        } else {
            // Listed by target, values ≥ 0: a stable sort on the value alone keeps ties by
            // target.
            sort_desc_stable(&mut self.orders[base..], &mut self.sort_scratch);
        }
        self.blocks
            .push_list(self.orders[base..].iter().map(|&(_, t)| t));
        self.order_slot[pos as usize] = slot as u32;
        base
    }

    /// Prepare to bound the children of a new state ([`Heuristic::eval_child`]).
    pub(crate) fn enter(&mut self) {
        if let Some(far) = &mut self.far {
            far.enter();
        }
    }

    /// The bound for the robot at `pos` having perceived `bits` (`count` targets).
    pub(crate) fn eval(&mut self, problem: &Problem, pos: u32, bits: &[u64], count: usize) -> f64 {
        self.eval_at(problem, pos, bits, count, None, f64::INFINITY)
    }

    /// [`Heuristic::eval`] for a child of the state last [`Heuristic::enter`]ed, whose
    /// perceived set is `parent`: `bits` is `parent` plus what `pos` perceives (parts of
    /// the bound are shared between siblings). Once a part of the bound reaches `cut` the
    /// rest is not computed: the value is exact below `cut`, and at least `cut` otherwise.
    pub(crate) fn eval_child(
        &mut self,
        problem: &Problem,
        pos: u32,
        bits: &[u64],
        count: usize,
        parent: &[u64],
        cut: f64,
    ) -> f64 {
        self.eval_at(problem, pos, bits, count, Some(parent), cut)
    }

    fn eval_at(
        &mut self,
        problem: &Problem,
        pos: u32,
        bits: &[u64],
        count: usize,
        parent: Option<&[u64]>,
        cut: f64,
    ) -> f64 {
        if self.kind == HeuristicKind::Zero || self.n_targets - count <= self.skip {
            return 0.0;
        }
        // The coverage-rate bound first: it costs nothing.
        let rate = if self.kind == HeuristicKind::Landmarks {
            self.rate.bound(self.n_targets - self.skip - count)
        } else {
            0.0
        };
        if rate >= cut {
            return rate;
        }
        let base = self.order(problem, pos);
        let list = &self.orders[base..base + self.order_len];
        let paper = if self.kind == HeuristicKind::PaperAsPublished {
            let far = list
                .iter()
                .find(|&&(_, t)| !has(bits, t))
                .map_or(0.0, |&(d, _)| d);
            let factor = if self.goal < 1.0 {
                (self.goal - count as f64 / self.n_targets as f64).max(0.0)
            } else {
                1.0
            };
            ((far - self.c) * factor).max(0.0)
        } else {
            // The (skip + 1)-th largest bound among unperceived targets (0 if the kept part
            // of the order holds fewer unperceived targets: still a lower bound).
            // Counted a block at a time ([`crate::block_masks`]); the block holding it is
            // then walked entry by entry.
            let mut left = self.skip;
            let mut v = 0.0;
            let first_block = base / self.order_len * self.order_len.div_ceil(BLOCK);
            for (b, block) in list.chunks(BLOCK).enumerate() {
                let open = self.blocks.open(first_block + b, bits, block);
                if open <= left {
                    left -= open;
                    continue;
                }
                for &(d, t) in block {
                    if !has(bits, t) {
                        if left == 0 {
                            v = d;
                            break;
                        }
                        left -= 1;
                    }
                }
                break;
            }
            // Viewpoint distances are the bound itself; the others lose the sensor's reach.
            let reach = if self.vd.is_some() { 0.0 } else { self.c };
            (v - reach).max(0.0)
        };
        if self.kind != HeuristicKind::Landmarks || paper.max(rate) >= cut {
            return paper.max(rate);
        }
        if let Some(far) = &mut self.far {
            return far.bound(pos, bits, paper.max(rate), parent, cut);
        }
        if self.lm_t.is_empty() {
            return paper.max(rate);
        }
        paper.max(rate).max(self.landmark_path(problem, pos, bits))
    }

    /// The landmark path bound from `pos` (cached).
    fn landmark_path(&mut self, problem: &Problem, pos: u32, bits: &[u64]) -> f64 {
        let kk = self.lm_t.len();
        if kk > 64 {
            return self.path_bound(problem, pos, bits);
        }
        let mut mask = 0u64;
        for (a, &t) in self.lm_t.iter().enumerate() {
            if !has(bits, t) {
                mask |= 1 << a;
            }
        }
        if let Some(&v) = self.path_cache.get(&(mask, pos)) {
            return v;
        }
        let v = self.path_bound(problem, pos, bits);
        if self.path_cache.len() >= PATH_CACHE_ENTRIES {
            self.path_cache.clear();
        }
        self.path_cache.insert((mask, pos), v);
        v
    }

    /// The Held–Karp bound on a path from `pos` through the landmarks not in `bits`
    /// (at least their MST), computed.
    fn path_bound(&mut self, problem: &Problem, pos: u32, bits: &[u64]) -> f64 {
        let n = problem.cells().len();
        let kk = self.lm_t.len();
        self.left.clear();
        self.left
            .extend((0..kk).filter(|&a| !has(bits, self.lm_t[a])));
        // Node 0 is the robot, node i + 1 the i-th unperceived landmark.
        let m = self.left.len() + 1;
        self.hk_w.clear();
        self.hk_w.resize(m * m, 0.0);
        for (i, &a) in self.left.iter().enumerate() {
            let to_robot = self.lm_field[a * n + pos as usize];
            self.hk_w[i + 1] = to_robot;
            self.hk_w[(i + 1) * m] = to_robot;
            for (j, &b) in self.left.iter().enumerate() {
                self.hk_w[(i + 1) * m + j + 1] = self.lm_w[a * kk + b];
            }
        }
        self.hk.bound(m, &self.hk_w)
    }
}

/// Sort `list` (finite values ≥ 0) by value, descending, keeping the order of equal values:
/// a counting sort on the values' integer parts, then each part sorted alone (a few
/// entries each, where a comparison sort of the whole list was a tenth of the search).
fn sort_desc_stable(list: &mut [(f64, u32)], scratch: &mut (Vec<u32>, Vec<(f64, u32)>)) {
    let (count, out) = scratch;
    let top = list.iter().fold(0.0f64, |m, &(v, _)| m.max(v));
    if !(top.is_finite() && top < 1e7) {
        list.sort_by_key(|&(v, _)| std::cmp::Reverse(v.to_bits()));
        return;
    }
    let buckets = top as usize + 1;
    // Bucket b holds the values in [b, b + 1); listed from the top bucket down.
    let key = |v: f64| buckets - 1 - v as usize;
    count.clear();
    count.resize(buckets + 1, 0);
    for &(v, _) in list.iter() {
        count[key(v) + 1] += 1;
    }
    for b in 0..buckets {
        count[b + 1] += count[b];
    }
    out.clear();
    out.resize(list.len(), (0.0, 0));
    for &e in list.iter() {
        let k = key(e.0);
        out[count[k] as usize] = e;
        count[k] += 1;
    }
    let mut start = 0;
    while start < out.len() {
        let k = key(out[start].0);
        let mut end = start + 1;
        while end < out.len() && key(out[end].0) == k {
            end += 1;
        }
        out[start..end].sort_by_key(|&(v, _)| std::cmp::Reverse(v.to_bits()));
        start = end;
    }
    list.copy_from_slice(out);
}

/// The viewpoints V(t) of the reachable targets (the reachable cells that see t; the
/// sensors are symmetric), kept when they fit in [`VIEW_ENTRIES`]; else only the landmarks'
/// are computed, and landmark selection falls back to distances to the target itself.
struct Views {
    /// Per reachable target: its range in `data`, when kept.
    at: Vec<(u32, u32)>,
    data: Vec<u32>,
    kept: bool,
}

/// Most viewpoint entries kept for landmark selection (4 bytes each, during set-up only).
pub(crate) const VIEW_ENTRIES: usize = 16 << 20;

impl Views {
    fn new(problem: &Problem, reach_targets: &[u32]) -> Self {
        let mut v = Self {
            at: Vec::new(),
            data: Vec::new(),
            kept: false,
        };
        if reach_targets
            .len()
            .saturating_mul(problem.model().disc_cells())
            > VIEW_ENTRIES
        {
            return v;
        }
        let mut obs = sense::Observation::new();
        for &t in reach_targets {
            let start = v.data.len() as u32;
            problem.viewpoints(t, &mut obs, &mut v.data);
            v.at.push((start, v.data.len() as u32));
        }
        v.kept = true;
        v
    }

    /// V(t) of `t = reach_targets[j]` (flat cells).
    fn of(&self, problem: &Problem, j: usize, t: u32) -> Vec<usize> {
        if self.kept {
            let (a, b) = self.at[j];
            return self.data[a as usize..b as usize]
                .iter()
                .map(|&p| p as usize)
                .collect();
        }
        let mut v = Vec::new();
        problem.viewpoints(t, &mut sense::Observation::new(), &mut v);
        v.into_iter().map(|p| p as usize).collect()
    }

    /// Lower `score[j]` to the distance in `field` from the source set to the nearest
    /// viewpoint of target `reach_targets[j]` (kept views), or to the target itself.
    fn lower(&self, reach_targets: &[u32], field: &[f64], score: &mut [f64]) {
        for (j, &t) in reach_targets.iter().enumerate() {
            let d = if self.kept {
                let (a, b) = self.at[j];
                self.data[a as usize..b as usize]
                    .iter()
                    .map(|&p| field[p as usize])
                    .fold(f64::INFINITY, f64::min)
            } else {
                field[t as usize]
            };
            score[j] = score[j].min(d);
        }
    }

    /// Selection stops once no target is farther than this: 0 with kept views (every
    /// target's viewpoints touch a landmark's), else `c` (the sensor's reach).
    fn spacing(&self, c: f64) -> f64 {
        if self.kept { 0.0 } else { c }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::Cell;
    use proptest::prelude::*;

    proptest! {
        /// The counting sort gives the stable comparison sort's order.
        #[test]
        fn counting_sort_is_the_stable_sort(
            values in proptest::collection::vec((0u32..50, 0u32..4), 0..300),
        ) {
            let list: Vec<(f64, u32)> = values
                .iter()
                .enumerate()
                .map(|(t, &(a, b))| (a as f64 * 0.5 + b as f64 * grid::SQRT2, t as u32))
                .collect();
            let mut want = list.clone();
            want.sort_by(|x, y| y.0.total_cmp(&x.0));
            let mut got = list;
            sort_desc_stable(&mut got, &mut Default::default());
            prop_assert_eq!(got, want);
        }

        /// The order statistic read off a truncated distance order equals the one over all
        /// unperceived targets when the kept part holds enough of them, and is never above
        /// it (orders cut short as on large maps, both sensors, G = 1 and 0.9).
        #[test]
        fn truncated_orders_give_the_order_statistic_or_less(
            walls in proptest::collection::vec(0u8..8, 24 * 16),
            seen in proptest::collection::vec(0u8..4, 24 * 16),
            pos in 0usize..24 * 16,
            radius in 2.0f64..30.0,
            fp in any::<bool>(),
            goal in prop_oneof![Just(1.0), Just(0.9)],
        ) {
            let (w, h) = (24, 16);
            let mut map = crate::walled_map(w, h, &walls);
            map.data_mut()[0] = Occ::Free;
            let model = if fp { SensorModel::Footprint(2.0) } else { SensorModel::Los(2.0) };
            let p = Problem::new(&map, Cell::new(0, 0), model).expect("problem");
            let reach: Vec<u32> = (0..w * h).filter(|&i| p.reachable(i)).map(|i| i as u32).collect();
            let pos = reach[pos % reach.len()];
            let n = p.targets().len();
            let mut heur = Heuristic::new(&p, HeuristicKind::Paper, goal, 0, 1 << 30);
            // A short order, as on large maps (orders are built on first use).
            heur.order_len = heur.order_len.min(2 * (heur.skip + 1) + 16);
            prop_assume!(heur.order_len < n);
            // Perceived: the targets farther than `radius` from `pos` (so the order's kept
            // head may hold none unperceived) and a random quarter of the others.
            let q = p.cells().cell(pos as usize);
            let mut bits = vec![0u64; p.mark_count().div_ceil(64)];
            let mut count = 0;
            for t in 0..n {
                let c = p.targets()[t] as usize;
                if seen[c] == 0 || q.dist(p.cells().cell(c)) > radius {
                    set(&mut bits, t as u32);
                    count += 1;
                }
            }
            prop_assume!(n - count > heur.skip);
            let got = heur.eval(&p, pos, &bits, count);
            // Brute force over every target: its bound value as `order` computes it.
            let base = heur.order(&p, pos);
            let kept: Vec<(f64, u32)> = heur.orders[base..base + heur.order_len].to_vec();
            let cells = p.cells();
            let mut values: Vec<f64> = if fp {
                let q = cells.cell(pos as usize);
                (0..n)
                    .filter(|&t| !has(&bits, t as u32))
                    .map(|t| q.dist(cells.cell(p.targets()[t] as usize)))
                    .collect()
            } else {
                let mut dij = Reachability::new(w, h);
                dij.compute(pos as usize, |i| cells.data()[i] == Occ::Free);
                (0..n)
                    .filter(|&t| !has(&bits, t as u32))
                    .map(|t| dist(&dij, p.targets()[t] as usize))
                    .map(|d| if d.is_finite() { d } else { 0.0 })
                    .collect()
            };
            values.sort_by(|a, b| b.total_cmp(a));
            let exact = (values[heur.skip] - heur.c).max(0.0);
            prop_assert!(got <= exact + 1e-9, "{} > {}", got, exact);
            let unperceived_kept = kept.iter().filter(|&&(_, t)| !has(&bits, t)).count();
            if unperceived_kept > heur.skip {
                prop_assert_eq!(got.to_bits(), exact.to_bits());
            }
        }
    }
}
