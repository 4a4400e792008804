//! Open travelling-salesman routes by path distance (nearest neighbour, 2-opt, Or-opt), for MTSP.
//!
//! Faigl & Kulich's MA (2013, §III-B) routes each robot from its position through the goals
//! of its cluster and takes the first goal of the route; they solve the routes with the
//! Chained Lin–Kernighan heuristic of Concorde. We do without Concorde, in the same
//! spirit (a local search chained by perturbations):
//!
//! - nearest-neighbour routes, one after each of the [`MAX_STARTS`] first goals nearest to
//!   the start;
//! - each improved by local search until no move improves it: full 3-opt (every reorder
//!   and reversal of two adjacent segments) up to [`FULL_3OPT_UP_TO`] nodes, 2-opt and
//!   Or-opt (segments of 1–3 nodes moved elsewhere, forwards or reversed) beyond, over
//!   neighbour lists: a move must join a node to one of its [`NEIGHBOURS`] nearest, and
//!   2-opt looks again only at nodes whose edges changed (Bentley's neighbour lists and
//!   don't-look bits); the nearest-neighbour routes read the lists too (a node's first
//!   unvisited neighbour is its nearest unvisited node; only when all are visited is its
//!   row scanned). Each pass of the plain moves was O(n²), and MA on all frontier
//!   cells (routes of hundreds of goals) spent 93 % of a run in them;
//! - then [`DEFAULT_KICKS`] perturbations of the best route (double bridges and other
//!   random 3-opt reconnections from a fixed-seed generator), each followed by the local
//!   search, keeping improvements. The best route is a local optimum, so a kicked route's
//!   full 3-opt skips the moves whose nodes are all where the best route has them (they
//!   failed there): the same moves in a third less time at 24 nodes, half at 16.
//!
//! Starts and kicks are capped by [`WORK_BUDGET`] / n on large instances. Up to
//! [`EXACT_UP_TO`] nodes the full-effort solver (any kicks) finds the optimum instead, by
//! Held–Karp's dynamic programme over subsets, which there costs less than the starts and
//! kicks (2¹¹ · 11² steps at 12 nodes).
//!
//! The nearest neighbour + 2-opt + Or-opt asked for alone was 1–10 % above the optimum on
//! about 0.5 % of random instances of ≤ 12 nodes. With the starts and kicks no Euclidean
//! instance of 20,000 was more than 0.7 % above Held–Karp, but path distances on a grid
//! with walls (many equal costs, many local optima) gave an 8-node instance 1.4 % above it;
//! hence the exact solution on small instances, where Concorde's Chained Lin–Kernighan,
//! which the paper used, is optimal in practice. The tests demand the optimum up to
//! [`EXACT_UP_TO`] nodes and ≤ 1 % above it from the heuristic on a fixed sample of random
//! instances of 13–14 nodes; a rare instance is worse (2.6 % on one kept in the tests).
//!
//! The route is *open*: it starts at node 0 (the robot) and ends at whichever goal is
//! best; there is no return. Costs come as a symmetric `n × n` matrix (path distances,
//! or any metric), so the caller decides how goal-to-goal distances are obtained; or, when
//! `n²` of them would not fit in memory, through [`Costs`], computed when read, with the
//! same routes as on the matrix of their values.
//! Deterministic: ties are broken by the lower index, improving moves are taken in a fixed
//! scan order, and the perturbations use a fixed seed.

/// A move must improve the route by more than this to be taken (guards against cycling
/// on rounding noise).
const EPS: f64 = 1e-9;

/// Nearest-neighbour starts (after the first nodes nearest to the start) per solve by default.
pub const MAX_STARTS: usize = 12;

/// Starts and kicks are each capped at `WORK_BUDGET / n`, so that large instances (all
/// frontier cells of a map) stay affordable: 100 kicks and 12 starts at n = 12, 12 at
/// n = 100, a single start and no kick from n = 1200 on.
pub const WORK_BUDGET: usize = 1200;

/// Up to this many nodes the local search is full 3-opt; beyond, 2-opt and Or-opt.
pub const FULL_3OPT_UP_TO: usize = 24;

/// Double-bridge perturbations per solve by default.
pub const DEFAULT_KICKS: usize = 100;

/// Up to this many nodes (the start included) the full-effort solver is exact.
pub const EXACT_UP_TO: usize = 12;

/// Candidate neighbours per node of the 2-opt and Or-opt moves on large routes.
pub const NEIGHBOURS: usize = 10;

/// Symmetric costs between the nodes `0..n` of an instance, as the solver reads them.
///
/// The solver is generic over them (monomorphised, nothing dynamic in its loops), so that
/// costs too many to hold as a matrix can be computed when read: `n²` of them are
/// quadratic memory, which MA's routes through clusters of thousands of goals cannot
/// afford. Instances of up to [`FULL_3OPT_UP_TO`] nodes are always solved on a dense
/// matrix (copied from [`get`](Costs::get) when not [`dense`](Costs::dense)).
pub trait Costs {
    /// The number of nodes.
    fn n(&self) -> usize;
    /// The cost between nodes `a` and `b`.
    fn get(&self, a: u32, b: u32) -> f64;
    /// The costs as a row-major `n × n` matrix, if they are held as one.
    fn dense(&self) -> Option<&[f64]> {
        None
    }
}

/// A row-major `n × n` cost matrix.
#[derive(Clone, Copy, Debug)]
pub struct Dense<'a> {
    n: usize,
    d: &'a [f64],
}

impl<'a> Dense<'a> {
    /// The `n × n` matrix `d`.
    ///
    /// # Panics
    /// If `d.len() != n * n`.
    pub fn new(n: usize, d: &'a [f64]) -> Self {
        assert_eq!(d.len(), n * n, "cost matrix must be n × n");
        Self { n, d }
    }
}

impl Costs for Dense<'_> {
    fn n(&self) -> usize {
        self.n
    }

    #[inline]
    fn get(&self, a: u32, b: u32) -> f64 {
        self.d[a as usize * self.n + b as usize]
    }

    fn dense(&self) -> Option<&[f64]> {
        Some(self.d)
    }
}

/// The dense matrix of an instance small enough to always have one ([`Costs`]).
fn small<C: Costs>(d: &C) -> &[f64] {
    d.dense()
        .expect("instances of up to FULL_3OPT_UP_TO nodes are solved on a dense matrix")
}

/// xorshift64* step: a tiny fixed-seed generator for the perturbations.
fn next(state: &mut u64) -> u64 {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    state.wrapping_mul(0x2545_F491_4F6C_DD1D)
}

/// Cut `route[1..]` into four pieces A B C D (B, C non-empty) and reconnect B and C
/// differently (swapped and/or reversed): a double bridge or another 3-opt move.
fn double_bridge(route: &mut [u32], state: &mut u64) {
    let len = route.len() - 1; // movable nodes
    if len < 2 {
        return;
    }
    // Three cut points in 0..=len with B and C non-empty (A and D may be empty: the route
    // is open, so moving a piece to the very start or end is a real change).
    let mut cuts = [0usize; 3];
    loop {
        for c in &mut cuts {
            *c = (next(state) % (len as u64 + 1)) as usize;
        }
        cuts.sort_unstable();
        if cuts[0] < cuts[1] && cuts[1] < cuts[2] {
            break;
        }
    }
    let body = &mut route[1..];
    let (p1, p2, p3) = (cuts[0], cuts[1], cuts[2]);
    // B = p1..p2, C = p2..p3. Reconnect as one of the 3-opt variants: B and C swapped or
    // not, each reversed or not (never the identity).
    let r = next(state);
    let (swap, mut rev_b, mut rev_c) = (r & 1 != 0, r & 2 != 0, r & 4 != 0);
    if !swap && !rev_b && !rev_c {
        (rev_b, rev_c) = (true, true);
    }
    if rev_b {
        body[p1..p2].reverse();
    }
    if rev_c {
        body[p2..p3].reverse();
    }
    if swap {
        body[p1..p3].rotate_left(p2 - p1);
    }
}

/// Open-route solver with buffers reused across calls.
#[derive(Clone, Debug)]
pub struct OpenTsp {
    /// Held–Karp's table: `dp[set * m + j]`, the shortest route from node 0 through the
    /// goals of `set` (bit j − 1 for goal j) ending at goal j + 1; `m = n − 1`.
    dp: Vec<f64>,
    /// `nbrs[a * k..(a + 1) * k]`: node a's nearest other nodes, nearest first (k =
    /// `min(NEIGHBOURS, n − 1)`), for the instance in `nbrs_of`.
    nbrs: Vec<u32>,
    /// Scratch for selecting neighbours: (cost, node).
    near: Vec<(f64, u32)>,
    /// Position of each node in `route`.
    pos: Vec<usize>,
    /// 2-opt's work list and its membership marks.
    queue: std::collections::VecDeque<u32>,
    queued: Vec<bool>,
    route: Vec<u32>,
    best: Vec<u32>,
    used: Vec<bool>,
    firsts: Vec<u32>,
    /// Or-opt's memory of moves that failed (see [`or_opt`](Self::or_opt)): a clock that
    /// ticks at every change of the route, per node the tick its predecessor or successor
    /// last changed, per (segment's first node, length − 1) the tick its moves were last
    /// found to fail, and the tick the current local search began.
    clock: u64,
    changed_at: Vec<u64>,
    failed_at: Vec<u64>,
    floor: u64,
    /// Whether the local search skips the moves it knows fail (always, but in the tests
    /// comparing the two).
    remember: bool,
    /// Whether `route` is `best`, a local optimum of full 3-opt, perturbed: its 3-opt skips
    /// the triples whose six nodes are `best`'s at the same places ([`three_opt`](Self::three_opt)).
    kicked: bool,
    /// For a kicked route: per place, whether it holds another node than `best` there, and
    /// `next_k[k]`, the least k' ≥ k whose places k' − 1 or k' do (`len + 1` if none).
    moved: Vec<bool>,
    next_k: Vec<usize>,
    /// A small instance's costs copied into a matrix ([`Costs`]).
    small: Vec<f64>,
    starts: usize,
    kicks: usize,
}

impl Default for OpenTsp {
    fn default() -> Self {
        Self::new()
    }
}

/// Keep the `k` least of `near` by (cost, node), least first: a node's neighbour list.
fn keep_nearest(near: &mut Vec<(f64, u32)>, k: usize) {
    let by = |x: &(f64, u32), y: &(f64, u32)| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1));
    if k > 0 && near.len() > k {
        near.select_nth_unstable_by(k - 1, by);
    }
    near.truncate(k);
    near.sort_unstable_by(by);
}

/// For each node `a` of `from..n` in turn, append its `k` nearest other nodes of
/// `from..n` under the costs `d` of `n` nodes ([`keep_nearest`]'s order) to `out`; `near`
/// is scratch.
fn nearest_lists<C: Costs>(
    near: &mut Vec<(f64, u32)>,
    d: &C,
    from: usize,
    k: usize,
    out: &mut Vec<u32>,
) {
    let n = d.n();
    for a in from..n {
        near.clear();
        near.extend(
            (from as u32..n as u32)
                .filter(|&b| b as usize != a)
                .map(|b| (d.get(a as u32, b), b)),
        );
        keep_nearest(near, k);
        out.extend(near.iter().map(|&(_, b)| b));
    }
}

/// Cost of the open route `route` (consecutive nodes) under the `n × n` matrix `d`.
pub fn route_cost(n: usize, d: &[f64], route: &[u32]) -> f64 {
    route_cost_of(&Dense::new(n, d), route)
}

/// Cost of the open route `route` (consecutive nodes) under the costs `d`.
pub fn route_cost_of<C: Costs>(d: &C, route: &[u32]) -> f64 {
    route.windows(2).map(|w| d.get(w[0], w[1])).sum()
}

impl OpenTsp {
    /// Empty buffers, [`MAX_STARTS`] starts and [`DEFAULT_KICKS`] perturbations per solve.
    pub fn new() -> Self {
        Self::with_effort(MAX_STARTS, DEFAULT_KICKS)
    }

    /// Empty buffers, `starts` nearest-neighbour starts (at least 1) and `kicks`
    /// perturbations per solve; `with_effort(1, 0)` is plain nearest neighbour + local search.
    pub fn with_effort(starts: usize, kicks: usize) -> Self {
        Self {
            dp: Vec::new(),
            nbrs: Vec::new(),
            near: Vec::new(),
            pos: Vec::new(),
            queue: Default::default(),
            queued: Vec::new(),
            route: Vec::new(),
            best: Vec::new(),
            used: Vec::new(),
            firsts: Vec::new(),
            clock: 0,
            changed_at: Vec::new(),
            failed_at: Vec::new(),
            floor: 0,
            remember: true,
            kicked: false,
            moved: Vec::new(),
            next_k: Vec::new(),
            small: Vec::new(),
            starts: starts.max(1),
            kicks,
        }
    }

    /// A short open route from node 0 through nodes `1..n`, under the symmetric row-major
    /// `n × n` cost matrix `d`; returns its cost. The route is then [`route`](Self::route).
    ///
    /// # Panics
    /// If `d.len() != n * n`.
    pub fn solve(&mut self, n: usize, d: &[f64]) -> f64 {
        self.solve_sharing(n, d, None)
    }

    /// [`solve`](Self::solve), given the goals' neighbour lists
    /// ([`goal_neighbours`](Self::goal_neighbours)) made
    /// from a matrix equal to `d` but for row and column 0: the same route and cost, without
    /// the O(n²) selection of every node's nearest (when many starts share their goals,
    /// as MA's robots routed through one cluster do, the lists are made once).
    ///
    /// # Panics
    /// If `d.len() != n * n`, or the lists are not `n - 1` lists of
    /// `min(NEIGHBOURS, n - 2)` nodes.
    pub fn solve_sharing(&mut self, n: usize, d: &[f64], goal_lists: Option<&[u32]>) -> f64 {
        self.solve_costs(&Dense::new(n, d), goal_lists)
    }

    /// [`solve_sharing`](Self::solve_sharing) under any [`Costs`]: the same route and cost
    /// bits as on the matrix of their values.
    ///
    /// # Panics
    /// If the lists are not `n - 1` lists of `min(NEIGHBOURS, n - 2)` nodes.
    pub fn solve_costs<C: Costs>(&mut self, d: &C, goal_lists: Option<&[u32]>) -> f64 {
        let n = d.n();
        if n <= FULL_3OPT_UP_TO && d.dense().is_none() {
            let mut m = std::mem::take(&mut self.small);
            m.clear();
            m.extend(
                (0..n as u32)
                    .flat_map(|a| (0..n as u32).map(move |b| (a, b)))
                    .map(|(a, b)| d.get(a, b)),
            );
            let c = self.solve_costs(&Dense::new(n, &m), goal_lists);
            self.small = m;
            return c;
        }
        self.route.clear();
        if n == 0 {
            return 0.0;
        }
        if self.kicks > 0 && (3..=EXACT_UP_TO).contains(&n) {
            return self.held_karp(n, small(d));
        }
        if n > FULL_3OPT_UP_TO {
            match goal_lists {
                Some(lists) => self.merge_neighbours(d, lists),
                None => self.build_neighbours(d),
            }
        }
        // Multi-start: nearest neighbour after each of the first nodes nearest to the start,
        // each improved by local search; keep the best.
        self.firsts.clear();
        self.firsts.extend(1..n as u32);
        self.firsts
            .sort_by(|&a, &b| d.get(0, a).total_cmp(&d.get(0, b)).then(a.cmp(&b)));
        self.firsts
            .truncate(self.starts.min((WORK_BUDGET / n).max(1)));
        let mut best_cost = f64::INFINITY;
        self.best.clear();
        self.best.push(0);
        for s in 0..self.firsts.len() {
            self.nearest_neighbour(d, self.firsts[s] as usize);
            self.local_search(d);
            let c = route_cost_of(d, &self.route);
            if c < best_cost - EPS {
                best_cost = c;
                self.best.clear();
                self.best.extend_from_slice(&self.route);
            }
        }
        if n < 5 || self.kicks == 0 {
            self.route.clear();
            self.route.extend_from_slice(&self.best);
            return route_cost_of(d, &self.route);
        }
        // Chained local search: perturb the best route by a double bridge, re-optimise,
        // keep the result if shorter. The perturbations come from a fixed-seed generator,
        // so the solver stays deterministic.
        let mut state = 0x9E37_79B9_7F4A_7C15u64 ^ n as u64;
        for _ in 0..self.kicks.min(WORK_BUDGET / n) {
            self.route.clear();
            self.route.extend_from_slice(&self.best);
            double_bridge(&mut self.route, &mut state);
            self.kicked = self.remember;
            self.local_search(d);
            self.kicked = false;
            let c = route_cost_of(d, &self.route);
            if c < best_cost - EPS {
                best_cost = c;
                self.best.clear();
                self.best.extend_from_slice(&self.route);
            }
        }
        self.route.clear();
        self.route.extend_from_slice(&self.best);
        best_cost
    }

    /// The optimal open route by Held–Karp's dynamic programme (3 ≤ n ≤ [`EXACT_UP_TO`]);
    /// among equal routes, the one whose nodes taken backwards from the end are the lowest.
    fn held_karp(&mut self, n: usize, d: &[f64]) -> f64 {
        let m = n - 1;
        let full = (1usize << m) - 1;
        self.dp.clear();
        self.dp.resize((full + 1) * m, f64::INFINITY);
        for j in 0..m {
            self.dp[(1 << j) * m + j] = d[j + 1];
        }
        for set in 1..=full {
            for j in 0..m {
                if set & (1 << j) == 0 {
                    continue;
                }
                let here = self.dp[set * m + j];
                if !here.is_finite() {
                    continue;
                }
                let row = (j + 1) * n;
                for k in 0..m {
                    if set & (1 << k) != 0 {
                        continue;
                    }
                    let next = set | (1 << k);
                    let c = here + d[row + k + 1];
                    if c < self.dp[next * m + k] {
                        self.dp[next * m + k] = c;
                    }
                }
            }
        }
        // The best end, then predecessors backwards, ties to the lower node.
        let mut end = 0;
        for j in 1..m {
            if self.dp[full * m + j] < self.dp[full * m + end] {
                end = j;
            }
        }
        self.best.clear();
        let (mut set, mut j) = (full, end);
        loop {
            self.best.push(j as u32 + 1);
            let rest = set & !(1 << j);
            if rest == 0 {
                break;
            }
            let want = self.dp[set * m + j];
            let mut pick = usize::MAX;
            for k in 0..m {
                if rest & (1 << k) != 0
                    && (self.dp[rest * m + k] + d[(k + 1) * n + j + 1] - want).abs() <= EPS
                {
                    pick = k;
                    break;
                }
            }
            if pick == usize::MAX {
                // unreachable: some predecessor gives each finite entry its value
                break;
            }
            set = rest;
            j = pick;
        }
        self.best.push(0);
        self.best.reverse();
        self.route.clear();
        self.route.extend_from_slice(&self.best);
        if self.route.len() != n {
            // Infinite costs (unreachable goals) leave no finite route: fall back on the
            // nearest-neighbour order.
            self.nearest_neighbour(&Dense::new(n, d), 1);
        }
        route_cost(n, d, &self.route)
    }

    fn local_search<C: Costs>(&mut self, d: &C) {
        let n = d.n();
        if self.route.len() <= FULL_3OPT_UP_TO {
            while self.three_opt(n, small(d)) {}
            return;
        }
        // A new route: nothing remembered from earlier ones holds.
        self.clock += 1;
        self.floor = self.clock;
        if self.changed_at.len() < n {
            self.changed_at.resize(n, 0);
            self.failed_at.resize(3 * n, 0);
        }
        loop {
            let a = self.two_opt(d);
            let b = self.or_opt(d);
            if !a && !b {
                break;
            }
        }
    }

    /// Each node's [`NEIGHBOURS`] nearest other nodes, nearest first (ties to the lower node).
    fn build_neighbours<C: Costs>(&mut self, d: &C) {
        self.nbrs.clear();
        let k = NEIGHBOURS.min(d.n() - 1);
        nearest_lists(&mut self.near, d, 0, k, &mut self.nbrs);
    }

    /// The goals' neighbour lists of an `n`-node instance for
    /// [`solve_sharing`](Self::solve_sharing): for each goal `1..n` in turn, its
    /// `min(NEIGHBOURS, n - 2)` nearest other goals by (cost, index), nearest first,
    /// appended to `out`. Row and column 0 of `d` (the start) are not read, so one set of
    /// lists serves every start.
    pub fn goal_neighbours(&mut self, n: usize, d: &[f64], out: &mut Vec<u32>) {
        self.goal_neighbours_of(&Dense::new(n, d), out);
    }

    /// [`goal_neighbours`](Self::goal_neighbours) under any [`Costs`].
    pub fn goal_neighbours_of<C: Costs>(&mut self, d: &C, out: &mut Vec<u32>) {
        let kg = NEIGHBOURS.min(d.n().saturating_sub(2));
        nearest_lists(&mut self.near, d, 1, kg, out);
    }

    /// [`build_neighbours`](Self::build_neighbours)' lists from the goals' own lists (see
    /// [`goal_neighbours`](Self::goal_neighbours)): node 0 joins a goal's list where its cost places it (before
    /// goals of equal cost: it has the lowest index), and its own list is selected from
    /// row 0.
    fn merge_neighbours<C: Costs>(&mut self, d: &C, goal_lists: &[u32]) {
        let n = d.n();
        let k = NEIGHBOURS.min(n - 1);
        let kg = NEIGHBOURS.min(n.saturating_sub(2));
        assert_eq!(
            goal_lists.len(),
            (n - 1) * kg,
            "goal lists for another instance"
        );
        self.nbrs.clear();
        self.near.clear();
        self.near.extend((1..n as u32).map(|b| (d.get(0, b), b)));
        keep_nearest(&mut self.near, k);
        self.nbrs.extend(self.near.iter().map(|&(_, b)| b));
        for a in 1..n {
            let list = &goal_lists[(a - 1) * kg..a * kg];
            let d0 = d.get(a as u32, 0);
            let at = list
                .iter()
                .position(|&b| d0.total_cmp(&d.get(a as u32, b)).is_le())
                .unwrap_or(kg);
            let start = self.nbrs.len();
            self.nbrs.extend_from_slice(&list[..at]);
            self.nbrs.push(0);
            self.nbrs.extend_from_slice(&list[at..]);
            self.nbrs.truncate(start + k);
        }
    }

    /// Set `pos` to the position of each of the `n` nodes in `route`.
    fn index_route(&mut self, n: usize) {
        self.pos.clear();
        self.pos.resize(n, 0);
        for (p, &v) in self.route.iter().enumerate() {
            self.pos[v as usize] = p;
        }
    }

    /// Reverse `route[i..=j]` and keep `pos` up to date (and the ticks of the nodes whose
    /// neighbours changed: all of them, and the nodes on either side).
    fn reverse(&mut self, i: usize, j: usize) {
        self.route[i..=j].reverse();
        self.clock += 1;
        for p in i..=j {
            self.pos[self.route[p] as usize] = p;
            self.changed_at[self.route[p] as usize] = self.clock;
        }
        for p in [i.wrapping_sub(1), j + 1] {
            if let Some(&v) = self.route.get(p) {
                self.changed_at[v as usize] = self.clock;
            }
        }
    }

    /// Put node `a` on 2-opt's work list.
    fn enqueue(&mut self, a: u32) {
        if !self.queued[a as usize] {
            self.queued[a as usize] = true;
            self.queue.push_back(a);
        }
    }

    /// 2-opt over neighbour lists with don't-look bits: for each node on the work list,
    /// try to join it to a near neighbour by reversing the part of the route between them
    /// (so that the new edge replaces the node's edge to its successor or predecessor);
    /// the nodes of the edges changed go back on the list. Returns whether anything changed.
    fn two_opt<C: Costs>(&mut self, d: &C) -> bool {
        let n = d.n();
        let len = self.route.len();
        let k = NEIGHBOURS.min(n - 1);
        let c = |a: u32, b: u32| d.get(a, b);
        self.index_route(n);
        self.queued.clear();
        self.queued.resize(n, false);
        self.queue.clear();
        for p in 0..len {
            let a = self.route[p];
            self.enqueue(a);
        }
        let mut any = false;
        while let Some(a) = self.queue.pop_front() {
            self.queued[a as usize] = false;
            let mut changed: Option<[u32; 4]> = None;
            let p = self.pos[a as usize];
            // The successor edge (a, s) gives way to (a, b).
            if p + 1 < len {
                let s = self.route[p + 1];
                let das = c(a, s);
                for &b in &self.nbrs[a as usize * k..(a as usize + 1) * k] {
                    let dab = c(a, b);
                    if dab >= das - EPS {
                        break;
                    }
                    let q = self.pos[b as usize];
                    if q > p + 1 {
                        // reverse route[p + 1..=q]: edges (a, b) and (s, after b)
                        let after = (q + 1 < len).then(|| self.route[q + 1]);
                        let delta = dab - das + after.map_or(0.0, |t| c(s, t) - c(b, t));
                        if delta < -EPS {
                            self.reverse(p + 1, q);
                            changed = Some([a, s, b, after.unwrap_or(a)]);
                            break;
                        }
                    } else if q + 1 < p {
                        // reverse route[q + 1..=p]: edges (b, a) and (after b, s)
                        let t = self.route[q + 1];
                        let delta = dab + c(t, s) - c(b, t) - das;
                        if delta < -EPS {
                            self.reverse(q + 1, p);
                            changed = Some([a, s, b, t]);
                            break;
                        }
                    }
                }
            }
            // The predecessor edge (before a, a) gives way to (b, a).
            if changed.is_none() && p >= 1 {
                let pr = self.route[p - 1];
                let dap = c(a, pr);
                for &b in &self.nbrs[a as usize * k..(a as usize + 1) * k] {
                    let dab = c(a, b);
                    if dab >= dap - EPS {
                        break;
                    }
                    let q = self.pos[b as usize];
                    if q > p + 1 {
                        // reverse route[p..=q − 1]: edges (pr, before b) and (a, b)
                        let t = self.route[q - 1];
                        let delta = c(pr, t) + dab - dap - c(t, b);
                        if delta < -EPS {
                            self.reverse(p, q - 1);
                            changed = Some([a, pr, b, t]);
                            break;
                        }
                    } else if q >= 1 && q + 1 < p {
                        // reverse route[q..=p − 1]: edges (before b, pr) and (b, a)
                        let t = self.route[q - 1];
                        let delta = c(t, pr) + dab - c(t, b) - dap;
                        if delta < -EPS {
                            self.reverse(q, p - 1);
                            changed = Some([a, pr, b, t]);
                            break;
                        }
                    }
                }
            }
            if let Some(nodes) = changed {
                any = true;
                for v in nodes {
                    self.enqueue(v);
                }
            }
        }
        any
    }

    /// The last route: node 0 first, then every other node once.
    pub fn route(&self) -> &[u32] {
        &self.route
    }

    /// Nearest-neighbour route 0, `first`, then always the nearest unvisited node.
    fn nearest_neighbour<C: Costs>(&mut self, d: &C, first: usize) {
        let n = d.n();
        self.route.clear();
        self.used.clear();
        self.used.resize(n, false);
        self.used[0] = true;
        self.used[first] = true;
        self.route.push(0);
        self.route.push(first as u32);
        let mut at = first;
        // The neighbour lists (made for this instance beyond full 3-opt's sizes) hold each
        // node's nearest by (cost, index): their first unvisited node is the nearest
        // unvisited one; only when all are visited is the row scanned.
        let k = if n > FULL_3OPT_UP_TO {
            NEIGHBOURS.min(n - 1)
        } else {
            0
        };
        for _ in 2..n {
            if let Some(&b) = self.nbrs[at * k..(at + 1) * k]
                .iter()
                .find(|&&b| !self.used[b as usize])
            {
                self.used[b as usize] = true;
                self.route.push(b);
                at = b as usize;
                continue;
            }
            let mut best = usize::MAX;
            let mut bd = f64::INFINITY;
            for j in 1..n {
                if !self.used[j] {
                    let c = d.get(at as u32, j as u32);
                    if best == usize::MAX || c < bd {
                        bd = c;
                        best = j;
                    }
                }
            }
            self.used[best] = true;
            self.route.push(best as u32);
            at = best;
        }
    }

    /// One pass of full 3-opt on the open route: for every two adjacent segments
    /// B = `route[i..j]`, C = `route[j..k]`, try every other order and orientation of B and
    /// C (this contains every 2-opt and Or-opt move). Returns whether anything changed.
    ///
    /// A triple (i, j, k) reads only the nodes at places i − 1, i, j − 1, j, k − 1 and k.
    /// A kicked route is `best` perturbed, and `best` is a local optimum: the last pass over
    /// it found no move, so a triple whose six places hold `best`'s nodes fails again and
    /// is skipped, the same pass in less time. A double bridge changes the places of B and
    /// C only, so the first pass after a kick skips the triples that lie wholly before or
    /// after them.
    fn three_opt(&mut self, n: usize, d: &[f64]) -> bool {
        let len = self.route.len();
        let row = |a: u32| &d[a as usize * n..(a as usize + 1) * n];
        let known = self.kicked && self.best.len() == len;
        if known {
            self.mark_moved();
        }
        let mut any = false;
        for i in 1..len {
            for j in i + 1..len {
                let mut k = j + 1;
                // B = route[i..j] stays fixed while C = route[j..k] grows: the terms that do
                // not involve C's last node or the node after it are read once per (i, j),
                // and again after a move changed B and C.
                'terms: while k <= len {
                    // B's ends and the nodes beside them are `best`'s: only the k whose
                    // places k − 1 or k are not can improve.
                    let skip = known
                        && !(self.moved[i - 1] || self.moved[i] || self.moved[j - 1])
                        && !self.moved[j];
                    let r = &self.route;
                    let (prev, b0, b1, c0) = (r[i - 1], r[i], r[j - 1], r[j]);
                    let (dp, db0, db1, dc0) = (row(prev), row(b0), row(b1), row(c0));
                    let (p_b0, p_b1, p_c0) = (dp[b0 as usize], dp[b1 as usize], dp[c0 as usize]);
                    let (b1_c0, b0_c0) = (db1[c0 as usize], db0[c0 as usize]);
                    let head = p_b0 + b1_c0;
                    while k <= len {
                        if skip {
                            k = self.next_k[k];
                            if k > len {
                                break;
                            }
                        }
                        let r = &self.route;
                        let c1 = r[k - 1];
                        let dc1 = row(c1);
                        // the cost of the edge from `x` to the node after C (none at the end)
                        let tail = |dx: &[f64]| if k < len { dx[r[k] as usize] } else { 0.0 };
                        let old = head + tail(dc1);
                        // Each reconnection's cost, in the order of its code: bit 0 swaps B and
                        // C, bit 1 reverses B, bit 2 reverses C. Every sum is formed as
                        // (prev → first) + (first piece's end → second piece's start) + tail.
                        let (c1_b0, c1_b1) = (dc1[b0 as usize], dc1[b1 as usize]);
                        let new = [
                            p_c0 + c1_b0 + tail(db1),
                            p_b1 + b0_c0 + tail(dc1),
                            p_c0 + c1_b1 + tail(db0),
                            p_b0 + db1[c1 as usize] + tail(dc0),
                            dp[c1 as usize] + dc0[b0 as usize] + tail(db1),
                            p_b1 + db0[c1 as usize] + tail(dc0),
                            dp[c1 as usize] + dc0[b1 as usize] + tail(db0),
                        ];
                        let mut best = (-EPS, 0u8);
                        for (code, &cost) in (1u8..8).zip(&new) {
                            let delta = cost - old;
                            if delta < best.0 {
                                best = (delta, code);
                            }
                        }
                        if best.1 != 0 {
                            let code = best.1;
                            let r = &mut self.route;
                            if code & 2 != 0 {
                                r[i..j].reverse();
                            }
                            if code & 4 != 0 {
                                r[j..k].reverse();
                            }
                            if code & 1 != 0 {
                                r[i..k].rotate_left(j - i);
                            }
                            if known {
                                self.mark_moved();
                            }
                            any = true;
                            k += 1;
                            continue 'terms;
                        }
                        k += 1;
                    }
                }
            }
        }
        any
    }

    /// `moved` and `next_k` of the kicked route (see [`three_opt`](Self::three_opt)).
    fn mark_moved(&mut self) {
        let len = self.route.len();
        self.moved.clear();
        self.moved
            .extend(self.route.iter().zip(&self.best).map(|(a, b)| a != b));
        self.next_k.clear();
        self.next_k.resize(len + 2, len + 1);
        for k in (1..=len).rev() {
            let hit = self.moved[k - 1] || (k < len && self.moved[k]);
            self.next_k[k] = if hit { k } else { self.next_k[k + 1] };
        }
    }

    /// Or-opt over neighbour lists: move a segment of 1–3 nodes, forwards or reversed, next
    /// to a near neighbour of one of its ends (between that neighbour and the node before or
    /// after it). Passes until none improves; a segment whose moves failed is looked at
    /// again only once something they read has changed ([`still_fails`](Self::still_fails):
    /// the same moves, without re-reading the cost matrix for the ones known to fail).
    /// Returns whether anything changed.
    fn or_opt<C: Costs>(&mut self, d: &C) -> bool {
        let n = d.n();
        let c = |a: u32, b: u32| d.get(a, b);
        let len = self.route.len();
        let k = NEIGHBOURS.min(n - 1);
        self.index_route(n);
        let mut any = false;
        let mut improved = true;
        while improved {
            improved = false;
            for seg in 1..=3usize {
                let mut i = 1;
                while i + seg <= len {
                    let e = i + seg; // the segment is route[i..e]
                    let key = self.route[i] as usize * 3 + seg - 1;
                    if self.remember && self.still_fails(i, e, k, self.failed_at[key]) {
                        i += 1;
                        continue;
                    }
                    if self.or_move(i, e, k, &c) {
                        improved = true;
                        any = true;
                    } else {
                        self.failed_at[key] = self.clock;
                    }
                    i += 1;
                }
            }
        }
        any
    }

    /// Whether the Or-opt moves of `route[i..e]`, found to fail at tick `failed` (of this
    /// local search), still fail: what [`or_move`](Self::or_move) reads is the segment's
    /// nodes and their neighbours and the neighbours of the nodes on its ends' lists, so if
    /// none of those nodes' neighbours changed since, the same segment meets the same
    /// costs and fails again. Skipping it then changes nothing but the time.
    fn still_fails(&self, i: usize, e: usize, k: usize, failed: u64) -> bool {
        if failed < self.floor {
            return false;
        }
        let quiet = |v: u32| self.changed_at[v as usize] <= failed;
        let (first, last) = (self.route[i], self.route[e - 1]);
        self.route[i..e].iter().all(|&v| quiet(v))
            && [first, last].iter().all(|&u| {
                self.nbrs[u as usize * k..(u as usize + 1) * k]
                    .iter()
                    .all(|&b| quiet(b))
            })
    }

    /// Try Or-opt moves of `route[i..e]` next to near neighbours of its ends; make the first
    /// that improves. Returns whether one was made.
    fn or_move(&mut self, i: usize, e: usize, k: usize, c: &impl Fn(u32, u32) -> f64) -> bool {
        let len = self.route.len();
        let r = &self.route;
        let (first, last, prev) = (r[i], r[e - 1], r[i - 1]);
        let removed = if e < len {
            c(prev, first) + c(last, r[e]) - c(prev, r[e])
        } else {
            c(prev, first)
        };
        // whether a route position lies within the segment
        let inside = |p: usize| (i..e).contains(&p);
        for (u, v, u_first) in [(first, last, true), (last, first, false)] {
            for &b in &self.nbrs[u as usize * k..(u as usize + 1) * k] {
                let q = self.pos[b as usize];
                if inside(q) {
                    continue;
                }
                // between b and the node after it: b, u … v, after
                if q + 1 == len || !inside(q + 1) {
                    let after = (q + 1 < len).then(|| self.route[q + 1]);
                    let added = c(b, u) + after.map_or(0.0, |t| c(v, t) - c(b, t));
                    if added - removed < -EPS {
                        self.move_segment_tracked(i, e, q, !u_first);
                        return true;
                    }
                }
                // between the node before b and b: before, v … u, b
                if q >= 1 && !inside(q - 1) {
                    let before = self.route[q - 1];
                    let added = c(u, b) + c(before, v) - c(before, b);
                    if added - removed < -EPS {
                        self.move_segment_tracked(i, e, q - 1, u_first);
                        return true;
                    }
                }
            }
        }
        false
    }

    /// [`move_segment`](Self::move_segment), keeping `pos` up to date for the nodes moved
    /// and the ticks of those whose neighbours change: the segment's, the nodes on either
    /// side of it and of the place it goes to.
    fn move_segment_tracked(&mut self, i: usize, e: usize, p: usize, reversed: bool) {
        self.clock += 1;
        for q in [i - 1, e, p, p + 1].into_iter().chain(i..e) {
            if let Some(&v) = self.route.get(q) {
                self.changed_at[v as usize] = self.clock;
            }
        }
        self.move_segment(i, e, p, reversed);
        let (a, b) = if p < i { (p + 1, e) } else { (i, p + 1) };
        for q in a..b {
            self.pos[self.route[q] as usize] = q;
        }
    }

    /// Move `route[i..e]` to just after the node now at position `p` (outside `i-1..e`),
    /// reversing it if asked.
    fn move_segment(&mut self, i: usize, e: usize, p: usize, reversed: bool) {
        let r = &mut self.route;
        let seg = e - i;
        let at = if p < i {
            // Segment moves earlier: rotate r[p+1..e] right by seg.
            r[p + 1..e].rotate_right(seg);
            p + 1
        } else {
            // Segment moves later: rotate r[i..=p] left by seg.
            r[i..=p].rotate_left(seg);
            p + 1 - seg
        };
        if reversed {
            r[at..at + seg].reverse();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// One pass of full 3-opt written plainly, every cost read where it is used: the
    /// oracle of the pass that reads the terms of each (i, j) once.
    fn three_opt_plain(route: &mut [u32], n: usize, d: &[f64]) -> bool {
        let c = |a: u32, b: u32| d[a as usize * n + b as usize];
        let len = route.len();
        let mut any = false;
        for i in 1..len {
            for j in i + 1..len {
                for k in j + 1..=len {
                    let r = &*route;
                    let prev = r[i - 1];
                    let next = (k < len).then(|| r[k]);
                    let tail = |x: u32| next.map_or(0.0, |y| c(x, y));
                    let (b0, b1, c0, c1) = (r[i], r[j - 1], r[j], r[k - 1]);
                    let old = c(prev, b0) + c(b1, c0) + tail(c1);
                    let b = [(b0, b1), (b1, b0)];
                    let cc = [(c0, c1), (c1, c0)];
                    let mut best = (-EPS, 0u8);
                    for code in 1u8..8 {
                        let (swap, rb, rc) = (code & 1 != 0, code & 2 != 0, code & 4 != 0);
                        let (x, y) = if swap {
                            (cc[rc as usize], b[rb as usize])
                        } else {
                            (b[rb as usize], cc[rc as usize])
                        };
                        let delta = c(prev, x.0) + c(x.1, y.0) + tail(y.1) - old;
                        if delta < best.0 {
                            best = (delta, code);
                        }
                    }
                    if best.1 != 0 {
                        if best.1 & 2 != 0 {
                            route[i..j].reverse();
                        }
                        if best.1 & 4 != 0 {
                            route[j..k].reverse();
                        }
                        if best.1 & 1 != 0 {
                            route[i..k].rotate_left(j - i);
                        }
                        any = true;
                    }
                }
            }
        }
        any
    }

    /// 3-opt passes of `tsp` on its route and plain passes on `plain` (the same route)
    /// until neither moves: the same moves, pass after pass.
    fn same_passes_as_plain(
        tsp: &mut OpenTsp,
        plain: &mut [u32],
        n: usize,
        d: &[f64],
    ) -> Result<(), TestCaseError> {
        loop {
            let moved = tsp.three_opt(n, d);
            prop_assert_eq!(moved, three_opt_plain(plain, n, d));
            prop_assert_eq!(&tsp.route[..], &plain[..]);
            if !moved {
                return Ok(());
            }
        }
    }

    proptest! {
        /// Regression test for the 3-opt pass that reads each (i, j)'s terms once: the same
        /// moves as the plain pass, pass after pass, on random symmetric instances (integer
        /// costs give many ties, real ones rounding), so the same routes.
        #[test]
        fn three_opt_pass_makes_the_plain_pass_moves(
            n in 3usize..16,
            seed in any::<u64>(),
            integer in any::<bool>(),
        ) {
            let mut state = seed | 1;
            let mut d = vec![0.0; n * n];
            for a in 0..n {
                for b in a + 1..n {
                    let v = next(&mut state) % 1000;
                    let v = if integer { (v % 7) as f64 } else { v as f64 * 0.37 + 0.1 };
                    d[a * n + b] = v;
                    d[b * n + a] = v;
                }
            }
            let mut route: Vec<u32> = (0..n as u32).collect();
            double_bridge(&mut route, &mut state);
            let mut plain = route.clone();
            let mut tsp = OpenTsp::new();
            tsp.route = route;
            same_passes_as_plain(&mut tsp, &mut plain, n, &d)?;
        }
    }

    proptest! {
        /// Regression test for the kicked routes' 3-opt skipping the triples whose six nodes
        /// are the local optimum's: the same moves as the plain pass, pass after pass, from
        /// a local optimum perturbed by a double bridge (ties, rounding and unreachable
        /// pairs included).
        #[test]
        fn kicked_three_opt_makes_the_plain_pass_moves(
            n in 5usize..=FULL_3OPT_UP_TO,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
        ) {
            let d = instance(n, seed, integer, holes);
            let mut state = seed | 1;
            let mut best: Vec<u32> = (0..n as u32).collect();
            double_bridge(&mut best, &mut state);
            while three_opt_plain(&mut best, n, &d) {}
            let mut route = best.clone();
            double_bridge(&mut route, &mut state);
            let mut plain = route.clone();
            let mut tsp = OpenTsp::new();
            tsp.best = best;
            tsp.route = route;
            tsp.kicked = true;
            same_passes_as_plain(&mut tsp, &mut plain, n, &d)?;
        }

        /// A full-effort solve whose kicked routes skip the triples known to fail finds the
        /// routes and cost bits of one that tries them all, on instances beyond Held–Karp's
        /// and within full 3-opt's sizes.
        #[test]
        fn kicks_skipping_known_triples_give_the_same_routes(
            n in (EXACT_UP_TO + 1)..=FULL_3OPT_UP_TO,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
        ) {
            let d = instance(n, seed, integer, holes);
            let mut plain = OpenTsp::new();
            plain.remember = false;
            let mut quick = OpenTsp::new();
            let a = plain.solve(n, &d);
            let b = quick.solve(n, &d);
            prop_assert_eq!(a.to_bits(), b.to_bits());
            prop_assert_eq!(plain.route(), quick.route());
        }
    }

    /// A random symmetric `n × n` instance: integer costs (many ties) or real ones, some
    /// pairs unreachable (infinite) if `holes`.
    fn instance(n: usize, seed: u64, integer: bool, holes: bool) -> Vec<f64> {
        let mut state = seed | 1;
        let mut d = vec![0.0; n * n];
        for a in 0..n {
            for b in a + 1..n {
                let v = next(&mut state) % 1000;
                let v = if holes && v.is_multiple_of(13) {
                    f64::INFINITY
                } else if integer {
                    (v % 7) as f64
                } else {
                    v as f64 * 0.37 + 0.1
                };
                d[a * n + b] = v;
                d[b * n + a] = v;
            }
        }
        d
    }

    /// The nearest-neighbour route by scanning every row: the oracle of the walk over the
    /// neighbour lists.
    fn nearest_neighbour_plain(n: usize, d: &[f64], first: usize) -> Vec<u32> {
        let mut used = vec![false; n];
        let (mut route, mut at) = (vec![0, first as u32], first);
        used[0] = true;
        used[first] = true;
        for _ in 2..n {
            let mut best = usize::MAX;
            for j in 1..n {
                if !used[j] && (best == usize::MAX || d[at * n + j] < d[at * n + best]) {
                    best = j;
                }
            }
            used[best] = true;
            route.push(best as u32);
            at = best;
        }
        route
    }

    proptest! {
        /// The nearest-neighbour route read from the neighbour lists is the one scanning
        /// every row gives, ties and unreachable pairs included (taking a list's first entry
        /// whether visited or not, or scanning only the lists, fails it).
        #[test]
        fn nearest_neighbour_over_lists_is_the_row_scans(
            n in (FULL_3OPT_UP_TO + 1)..90,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
            first in any::<prop::sample::Index>(),
        ) {
            let d = instance(n, seed, integer, holes);
            let first = 1 + first.index(n - 1);
            let mut tsp = OpenTsp::new();
            tsp.build_neighbours(&Dense::new(n, &d));
            tsp.nearest_neighbour(&Dense::new(n, &d), first);
            prop_assert_eq!(&tsp.route, &nearest_neighbour_plain(n, &d, first));
        }

        /// Routes on neighbour lists merged from the goals' own lists equal routes on lists
        /// built whole, for any start row, with both efforts: the same nodes and cost bits.
        #[test]
        fn shared_goal_lists_give_the_same_routes(
            n in (FULL_3OPT_UP_TO + 1)..70,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
            other_start in any::<u64>(),
        ) {
            let d = instance(n, seed, integer, holes);
            // the lists come from the same goals under another start's row
            let mut e = d.clone();
            let row0 = instance(n, other_start, integer, false);
            for b in 1..n {
                e[b] = row0[b];
                e[b * n] = row0[b];
            }
            let mut lists = Vec::new();
            OpenTsp::new().goal_neighbours(n, &e, &mut lists);
            for (mut plain, mut shared) in [
                (OpenTsp::with_effort(1, 0), OpenTsp::with_effort(1, 0)),
                (OpenTsp::new(), OpenTsp::new()),
            ] {
                let a = plain.solve(n, &d);
                let b = shared.solve_sharing(n, &d, Some(&lists));
                prop_assert_eq!(a.to_bits(), b.to_bits());
                prop_assert_eq!(plain.route(), shared.route());
                prop_assert_eq!(&plain.nbrs, &shared.nbrs);
            }
        }
    }

    proptest! {
        /// Or-opt remembering the moves that failed makes the moves of Or-opt trying every
        /// segment again: the same routes and cost bits, both efforts, on instances large
        /// enough for 2-opt and Or-opt (ties and unreachable pairs included; not marking
        /// the nodes beside a moved segment, or those of a reversed stretch, fails it).
        #[test]
        fn or_opt_remembering_failures_makes_the_same_moves(
            n in (FULL_3OPT_UP_TO + 1)..90,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
        ) {
            let d = instance(n, seed, integer, holes);
            for effort in [(1, 0), (MAX_STARTS, DEFAULT_KICKS)] {
                let mut plain = OpenTsp::with_effort(effort.0, effort.1);
                plain.remember = false;
                let mut quick = OpenTsp::with_effort(effort.0, effort.1);
                let a = plain.solve(n, &d);
                let b = quick.solve(n, &d);
                prop_assert_eq!(a.to_bits(), b.to_bits());
                prop_assert_eq!(plain.route(), quick.route());
            }
        }
    }

    /// A matrix the solver may only read entry by entry, as it reads costs computed on demand.
    struct Computed<'a>(Dense<'a>);

    impl Costs for Computed<'_> {
        fn n(&self) -> usize {
            self.0.n()
        }

        fn get(&self, a: u32, b: u32) -> f64 {
            self.0.get(a, b)
        }
    }

    // Route costs computed when read give the routes and costs of a matrix, bit for bit:
    // the solver on costs it reads through `Costs` against the same costs as a matrix.
    proptest! {
        /// Costs read entry by entry give the matrix's routes and cost bits, both efforts, with
        /// and without shared goal lists, small instances (copied into a matrix) and large.
        #[test]
        fn costs_read_when_needed_give_the_matrix_routes(
            n in 0usize..80,
            seed in any::<u64>(),
            integer in any::<bool>(),
            holes in any::<bool>(),
        ) {
            let d = instance(n, seed, integer, holes);
            let computed = Computed(Dense::new(n, &d));
            let (mut lists, mut read) = (Vec::new(), Vec::new());
            if n > FULL_3OPT_UP_TO {
                OpenTsp::new().goal_neighbours(n, &d, &mut lists);
                OpenTsp::new().goal_neighbours_of(&computed, &mut read);
                prop_assert_eq!(&lists, &read);
            }
            let lists = (!lists.is_empty()).then_some(&lists[..]);
            for (starts, kicks) in [(1, 0), (12, 100)] {
                for shared in [None, lists] {
                    let mut dense = OpenTsp::with_effort(starts, kicks);
                    let mut ondemand = OpenTsp::with_effort(starts, kicks);
                    let a = dense.solve_sharing(n, &d, shared);
                    let b = ondemand.solve_costs(&computed, shared);
                    prop_assert_eq!(a.to_bits(), b.to_bits());
                    prop_assert_eq!(dense.route(), ondemand.route());
                    prop_assert_eq!(
                        route_cost(n, &d, dense.route()).to_bits(),
                        route_cost_of(&computed, ondemand.route()).to_bits()
                    );
                }
            }
        }
    }
}
