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
//! # `Landmarks`: h = max(Paper, coverage rate, MST)
//! The coverage-rate bound (K more targets at most ρ* per unit of path, proof in
//! [`crate::coverage_rate`]) holds for every G. The MST bound below only for G = 1.
//!
//! ## The MST bound (G = 1)
//! Landmarks a_1..a_K are reachable targets chosen by farthest-point sampling with their
//! full-map distance fields; ρ(a) = max_{p∈V(a)} d(a, p) (computed exactly). Order the
//! landmarks of U by when the robot first perceives them, from positions p_1, p_2, ... in
//! path order. Then the remaining cost ≥ d(q, p_1) + Σ d(p_i, p_{i+1}) and, by the triangle
//! inequality, d(q, p_1) ≥ d(q, a_1) − ρ(a_1), d(p_i, p_{i+1}) ≥ d(a_i, a_{i+1}) − ρ(a_i) −
//! ρ(a_{i+1}). With edge weights w clipped at 0 this is the weight of a Hamiltonian path
//! from q through the landmarks of U — a spanning tree, so at least the minimum spanning
//! tree of {q} ∪ (landmarks in U) under w. Admissible. Far-apart landmarks that no single
//! position sees together are exactly the ones with positive w. (For G < 1 the robot may
//! skip any landmark, so the bound is not used there.)

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use explore::plan::Reachability;
use grid::Occ;

use crate::coverage_rate::CoverageRate;
use crate::problem::{NOT_TARGET, Problem, SensorModel};

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
    /// max(Paper, coverage rate, minimum spanning tree over landmarks); the MST part only
    /// for G = 1.
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

/// Path cost to cell `i` in the last search, `∞` if it was not reached.
#[inline]
pub(crate) fn dist(reach: &Reachability, i: usize) -> f64 {
    reach.cost(i).unwrap_or(f64::INFINITY)
}

/// max{|dx| + |dy| : dx² + dy² ≤ r²} over integer offsets.
fn max_l1_within(r: f64) -> f64 {
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
    /// Per position: targets by bound value, descending (value, target).
    order_slot: HashMap<u32, u32>,
    orders: Vec<(f64, u32)>,
    cache_cap_bytes: usize,
    dij: Reachability,
    /// The coverage-rate bound.
    rate: CoverageRate,
    // Landmarks.
    lm_t: Vec<u32>,
    lm_rho: Vec<f64>,
    lm_field: Vec<f64>,
    lm_w: Vec<f64>,
    prim_key: Vec<f64>,
    prim_idx: Vec<usize>,
    /// MST values by (unperceived-landmark mask, position), with at most 64 landmarks:
    /// sibling states share most landmark sets, and Prim's O(K²) dominated the search.
    mst_cache: HashMap<(u64, u32), f64, BuildHasherDefault<MixHasher>>,
}

/// Entries of the MST cache before it is cleared (≈ 40 bytes each).
const MST_CACHE_ENTRIES: usize = 1 << 20;

/// Fx-style multiply-rotate hasher for integer keys (the MST cache, the search's table of
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
        let cells = problem.cells();
        let mut h = Self {
            kind,
            model,
            goal,
            c,
            n_targets,
            skip: n_targets - problem.needed(goal),
            order_slot: HashMap::new(),
            orders: Vec::new(),
            cache_cap_bytes,
            dij: Reachability::new(cells.width(), cells.height()),
            rate: CoverageRate::new(model),
            lm_t: Vec::new(),
            lm_rho: Vec::new(),
            lm_field: Vec::new(),
            lm_w: Vec::new(),
            prim_key: Vec::new(),
            prim_idx: Vec::new(),
            mst_cache: HashMap::default(),
        };
        if kind == HeuristicKind::Landmarks && h.skip == 0 && landmarks > 0 {
            h.choose_landmarks(problem, landmarks);
        }
        h
    }

    /// Bytes held by the caches.
    pub(crate) fn bytes(&self) -> usize {
        self.orders.capacity() * 16
            + self.order_slot.len() * 24
            + self.lm_field.capacity() * 8
            + self.mst_cache.capacity() * 40
    }

    /// Number of landmarks in use.
    pub(crate) fn landmark_count(&self) -> usize {
        self.lm_t.len()
    }

    fn choose_landmarks(&mut self, problem: &Problem, k: usize) {
        let cells = problem.cells();
        let n = cells.len();
        let data = cells.data();
        let free = |i: usize| data[i] == Occ::Free;
        let reach_targets: Vec<u32> = problem
            .targets()
            .iter()
            .copied()
            .filter(|&i| problem.reachable(i as usize))
            .collect();
        if reach_targets.is_empty() {
            return;
        }
        let mut mind = vec![f64::INFINITY; n];
        // Seed: the start's field, so the first landmark is the farthest target from it.
        self.dij.compute(problem.start() as usize, free);
        for &i in &reach_targets {
            mind[i as usize] = dist(&self.dij, i as usize);
        }
        let mut obs = sense::Observation::new();
        let mut seen = Vec::new();
        while self.lm_t.len() < k {
            let mut best = None;
            for &i in &reach_targets {
                let d = mind[i as usize];
                if best.is_none_or(|(bd, _)| d > bd) {
                    best = Some((d, i));
                }
            }
            let Some((d, a)) = best else { break };
            if d <= self.c {
                break;
            }
            self.dij.compute(a as usize, free);
            let base = self.lm_field.len();
            self.lm_field.extend((0..n).map(|i| dist(&self.dij, i)));
            for &i in &reach_targets {
                let m = &mut mind[i as usize];
                *m = m.min(self.lm_field[base + i as usize]);
            }
            // ρ(a) = max over reachable positions that see a (symmetric sensors) of d(a, p).
            seen.clear();
            problem.seen_targets(a, &mut obs, &mut seen);
            let mut rho: f64 = 0.0;
            for &t in &seen {
                let p = problem.targets()[t as usize] as usize;
                if problem.reachable(p) {
                    rho = rho.max(self.lm_field[base + p]);
                }
            }
            self.lm_t.push(problem.target_index(a as usize));
            self.lm_rho.push(rho);
        }
        let kk = self.lm_t.len();
        self.lm_w = vec![0.0; kk * kk];
        for i in 0..kk {
            for j in 0..kk {
                let bj = problem.targets()[self.lm_t[j] as usize] as usize;
                let d = self.lm_field[i * n + bj];
                self.lm_w[i * kk + j] = (d - self.lm_rho[i] - self.lm_rho[j]).max(0.0);
            }
        }
    }

    /// The distance order of position `pos` (computed on first use).
    fn order(&mut self, problem: &Problem, pos: u32) -> usize {
        if let Some(&s) = self.order_slot.get(&pos) {
            return s as usize * self.n_targets;
        }
        if self.orders.len() * 16 > self.cache_cap_bytes {
            self.orders.clear();
            self.order_slot.clear();
        }
        let slot = self.order_slot.len();
        let base = self.orders.len();
        let targets = problem.targets();
        let cells = problem.cells();
        let euclid = matches!(self.model, SensorModel::Footprint(_))
            && self.kind != HeuristicKind::PaperAsPublished;
        if euclid {
            let q = cells.cell(pos as usize);
            self.orders.extend(
                targets
                    .iter()
                    .enumerate()
                    .map(|(t, &i)| (q.dist(cells.cell(i as usize)), t as u32)),
            );
        } else {
            let data = cells.data();
            self.dij.compute(pos as usize, |i| data[i] == Occ::Free);
            for &i in self.dij.settled() {
                let t = problem.target_index(i as usize);
                if t != NOT_TARGET {
                    self.orders.push((dist(&self.dij, i as usize), t));
                }
            }
            // Targets the path cannot reach (footprint only) bound nothing: value 0.
            let got = self.orders.len() - base;
            if got < self.n_targets {
                let mut present = vec![false; self.n_targets];
                for &(_, t) in &self.orders[base..] {
                    present[t as usize] = true;
                }
                for (t, &p) in present.iter().enumerate() {
                    if !p {
                        self.orders.push((0.0, t as u32));
                    }
                }
            }
        }
        // Descending by bound value (ties: lower target first).
        self.orders[base..].sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        self.order_slot.insert(pos, slot as u32);
        base
    }

    /// The bound for the robot at `pos` having perceived `bits` (`count` targets).
    pub(crate) fn eval(&mut self, problem: &Problem, pos: u32, bits: &[u64], count: usize) -> f64 {
        if self.kind == HeuristicKind::Zero || self.n_targets - count <= self.skip {
            return 0.0;
        }
        let base = self.order(problem, pos);
        let list = &self.orders[base..base + self.n_targets];
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
            // The (skip + 1)-th largest bound among unperceived targets.
            let mut left = self.skip;
            let mut v = 0.0;
            for &(d, t) in list {
                if !has(bits, t) {
                    if left == 0 {
                        v = d;
                        break;
                    }
                    left -= 1;
                }
            }
            (v - self.c).max(0.0)
        };
        if self.kind != HeuristicKind::Landmarks {
            return paper;
        }
        let rate = self.rate.bound(self.n_targets - self.skip - count);
        if self.lm_t.is_empty() {
            return paper.max(rate);
        }
        paper.max(rate).max(self.mst(problem, pos, bits))
    }

    /// Prim's MST over {pos} ∪ (landmarks not in `bits`).
    fn mst(&mut self, problem: &Problem, pos: u32, bits: &[u64]) -> f64 {
        let kk = self.lm_t.len();
        if kk > 64 {
            return self.prim(problem, pos, bits);
        }
        let mut mask = 0u64;
        for (a, &t) in self.lm_t.iter().enumerate() {
            if !has(bits, t) {
                mask |= 1 << a;
            }
        }
        if let Some(&v) = self.mst_cache.get(&(mask, pos)) {
            return v;
        }
        let v = self.prim(problem, pos, bits);
        if self.mst_cache.len() >= MST_CACHE_ENTRIES {
            self.mst_cache.clear();
        }
        self.mst_cache.insert((mask, pos), v);
        v
    }

    /// Prim's MST over {pos} ∪ (landmarks not in `bits`), computed.
    fn prim(&mut self, problem: &Problem, pos: u32, bits: &[u64]) -> f64 {
        let n = problem.cells().len();
        let kk = self.lm_t.len();
        self.prim_idx.clear();
        self.prim_key.clear();
        for a in 0..kk {
            if !has(bits, self.lm_t[a]) {
                self.prim_idx.push(a);
                let d = self.lm_field[a * n + pos as usize];
                self.prim_key.push((d - self.lm_rho[a]).max(0.0));
            }
        }
        let mut total = 0.0;
        let mut m = self.prim_idx.len();
        while m > 0 {
            let mut bi = 0;
            for i in 1..m {
                if self.prim_key[i] < self.prim_key[bi] {
                    bi = i;
                }
            }
            total += self.prim_key[bi];
            let a = self.prim_idx[bi];
            m -= 1;
            self.prim_idx.swap(bi, m);
            self.prim_key.swap(bi, m);
            for i in 0..m {
                let w = self.lm_w[a * kk + self.prim_idx[i]];
                if w < self.prim_key[i] {
                    self.prim_key[i] = w;
                }
            }
        }
        total
    }
}
