//! Multiple-TSP assignment: cluster first, route second (Faigl & Kulich 2013, §III-B, MA).
//!
//! The goals are split by k-means into as many clusters as robots; the clusters are
//! assigned to the robots optimally, the cost of robot i for cluster j being the length of
//! an open TSP route from the robot through the goals of the cluster (Faigl, Kulich &
//! Přeučil's ⟨cluster first, route second⟩); each robot's next goal is the first goal of
//! its route. Robot-to-goal costs are path lengths from the robots' searches, each grown
//! only until it has settled every candidate (the costs are final then, bit for bit those
//! of a full map; [`super::costs`]).
//!
//! Choices and deviations:
//! - **Goal-to-goal distances** are not searched (that would be a Dijkstra per goal): we
//!   use the lower bound d(a, b) = max(octile(a, b), max_r |d_r(a) − d_r(b)|) over the
//!   robots' path costs d_r (triangle inequality), exact in open space and along the
//!   robots' shortest-path trees. Routes are optimised against this bound; the goal a robot
//!   is sent to is still reached by its true shortest path.
//! - Routes for the robot × cluster cost matrix are nearest neighbour + local search
//!   (`OpenTsp::with_effort(1, 0)`); the assigned robot's own route is then re-solved with
//!   the full effort of [`crate::tsp`]. The paper used Chained Lin–Kernighan (Concorde).
//!   Every participant's route through a cluster shares its goal-to-goal part, so each
//!   cluster keeps one route matrix (the participant's costs written into row 0) and its
//!   goals' neighbour lists, made once per decision: the routes are those of a matrix and
//!   lists per route, without the O(goals²) copies and selections per route.
//! - **Memory linear in the goals**: a cluster's matrix is O(goals²), and all frontier
//!   cells of a large open map make clusters of thousands of goals (6,400 on a 1.7 M-cell
//!   warehouse at 3 cm: 1.3 GB of matrices). The matrices are kept while they fit in
//!   [`matrix_budget`] (a few bytes per map cell, which the run's memory estimate counts),
//!   since reading a matrix is the fastest; the clusters beyond compute their route costs
//!   when the solver reads them ([`crate::tsp::Costs`]), from the same expression in the
//!   same order, so the routes and costs are bit for bit those of a matrix.
//! - The optimal cluster-to-robot assignment is the `lsap` solver (SciPy's shortest
//!   augmenting path) on that matrix; goals a robot cannot reach add a large finite penalty.
//! - **Team semantics**: every robot that reaches a goal takes part in the clustering and the
//!   assignment, so the split of the work accounts for the robots that keep their goals;
//!   only deciding robots get new goals. Goals held by non-deciding robots are taken and
//!   left out. With fewer goals than robots there are fewer clusters, and a deciding robot
//!   without a cluster (or whose cluster it cannot reach) takes its cheapest free goal, or
//!   failing that its cheapest goal taken or not (as HA does).
//! - **The clusters start where the last decision's ended.** The paper says only "the
//!   clusters are found by the K-means algorithm". Seeded afresh by k-means++ at every
//!   decision, k-means draws a new partition each time, and a robot's cluster, and its
//!   goal, jumps across the map from one decision to the next: in a 5-robot `ma-cc` run on
//!   willow-full (`los:r=5`, 0.3 m clearance, s_max = 7, seed 3) 547 of 4,104 goals lay
//!   over 10 m from the robot's previous one (HA–CC: 38 of 3,072; started from the last
//!   centres: 19 of 3,148), and over seeds 0–3 the longest path L was 238–258 m against
//!   188–216 m started from the last centres. On the `faigl2013` suite's maps (6 seeds,
//!   ρ = 3, 5, 7 m, 3 and 5 robots, `ma-rfe` and `ma-cc`) starting from the last centres
//!   changed the mean L by −24 to −9 % on `potholes`, −15 to +1 % in the open space and
//!   −9 to +4 % in the office. So Lloyd's iterations start from the last decision's
//!   centres whenever the number of clusters is the same (the clusters follow the
//!   frontier as it moves, as Solanas & Garcia's do), and from k-means++ seeding, drawn
//!   from the run's generator, at the first decision and whenever the number changes: MA
//!   stays stochastic, as in the paper.

use super::costs::LazyCosts;
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};
use crate::kmeans::{Init, KMeans, Point};
use crate::tsp::{Costs, OpenTsp};
use grid::{Grid, Occ};

/// Added to a route's cost for each goal of the cluster the robot cannot reach.
const UNREACHABLE: f64 = 1e9;

/// Bytes per map cell the route matrices of a decision may take, beyond
/// [`MATRIX_BASE_BYTES`] ([`matrix_budget`]).
pub const MATRIX_BYTES_PER_CELL: u64 = 24;

/// Bytes the route matrices of a decision may take on any map ([`matrix_budget`]).
pub const MATRIX_BASE_BYTES: u64 = 4 << 20;

/// Most bytes the route matrices of a decision on a map of `cells` cells take: clusters
/// are given matrices in turn while they fit, the others compute their route costs when
/// read (see the module documentation). 29 MiB on willow-full's 1.1 M cells, more than
/// the 22 MiB its largest MA decision needs for clusters of up to 1,100 goals.
pub fn matrix_budget(cells: usize) -> u64 {
    MATRIX_BASE_BYTES.saturating_add(MATRIX_BYTES_PER_CELL.saturating_mul(cells as u64))
}

/// Clusters, matrices and routes, kept across decisions.
pub struct State {
    goals: Vec<u32>,
    points: Vec<Point>,
    /// Participating robots.
    part: Vec<usize>,
    /// `dist[p * goals + g]`: path cost of participant p to goal g (∞ if unreachable).
    dist: Vec<f64>,
    kmeans: KMeans,
    /// The last decision's cluster centres, where the next decision's k-means starts.
    centres: Vec<Point>,
    /// Goals ordered by cluster: cluster j is `order[cstart[j]..cstart[j + 1]]`.
    order: Vec<u32>,
    cstart: Vec<usize>,
    /// The nodes of one route through a cluster without a matrix ([`on_demand`]).
    ncell: Vec<grid::Cell>,
    ndist: Vec<f64>,
    /// One cluster's goal cells and its participants' costs to them, participant by
    /// participant ([`fill_bounds`]).
    ccell: Vec<grid::Cell>,
    ccost: Vec<f64>,
    /// Entries the route matrices may hold in all, if not [`matrix_budget`]'s (tests).
    budget: Option<usize>,
    /// Each cluster's route matrix: cluster j's, `(c + 1) × (c + 1)` for its c goals
    /// (node a + 1 = the cluster's goal a, row-major), starts at `gm[goff[j]]`
    /// (`usize::MAX`: the cluster has none, beyond the budget); its goal part holds the
    /// goal-to-goal bounds, row and column 0 the costs of the participant routed last.
    /// And the cluster positions of a route's goals.
    gm: Vec<f64>,
    goff: Vec<usize>,
    at: Vec<usize>,
    /// Each cluster's goals' neighbour lists ([`OpenTsp::goal_neighbours`]), at
    /// `lists[loff[j]..loff[j + 1]]`: made once per decision, shared by every participant
    /// that reaches all of the cluster's goals.
    lists: Vec<u32>,
    loff: Vec<usize>,
    /// Participants × clusters route costs, row-major.
    cost: Vec<f64>,
    /// Cluster of each participant (`usize::MAX` for none) from the last decision.
    cluster_of: Vec<usize>,
    fast: OpenTsp,
    full: OpenTsp,
    /// The robots' searches, grown until every candidate is settled.
    lazy: LazyCosts,
}

impl Default for State {
    fn default() -> Self {
        Self {
            goals: Vec::new(),
            points: Vec::new(),
            part: Vec::new(),
            dist: Vec::new(),
            kmeans: KMeans::new(),
            centres: Vec::new(),
            order: Vec::new(),
            cstart: Vec::new(),
            ncell: Vec::new(),
            ndist: Vec::new(),
            ccell: Vec::new(),
            ccost: Vec::new(),
            budget: None,
            gm: Vec::new(),
            goff: Vec::new(),
            at: Vec::new(),
            lists: Vec::new(),
            loff: Vec::new(),
            cost: Vec::new(),
            cluster_of: Vec::new(),
            fast: OpenTsp::with_effort(1, 0),
            full: OpenTsp::new(),
            lazy: LazyCosts::default(),
        }
    }
}

impl State {
    /// Robots that took part in the last decision.
    pub fn participants(&self) -> &[usize] {
        &self.part
    }

    /// The last robot × cluster route-cost matrix (participants × clusters, row-major) and
    /// its number of clusters.
    pub fn cost_matrix(&self) -> (&[f64], usize) {
        (&self.cost, self.cstart.len().saturating_sub(1))
    }

    /// The cluster assigned to each participant in the last decision (`None`: no cluster).
    pub fn assignment(&self) -> impl Iterator<Item = Option<usize>> + '_ {
        self.cluster_of
            .iter()
            .map(|&c| (c != usize::MAX).then_some(c))
    }

    /// The cluster centres the next decision's k-means starts from (the last decision's).
    pub fn centres(&self) -> &[Point] {
        &self.centres
    }

    /// Make `centres` the centres the next decision starts from, returning the ones kept
    /// so far.
    pub fn replace_centres(&mut self, centres: Vec<Point>) -> Vec<Point> {
        std::mem::replace(&mut self.centres, centres)
    }

    /// The free goals of the last decision (cells).
    pub fn goals(&self) -> &[u32] {
        &self.goals
    }

    /// The goals of cluster `j` in the last decision, as indices into [`goals`](Self::goals).
    pub fn cluster(&self, j: usize) -> &[u32] {
        &self.order[self.cstart[j]..self.cstart[j + 1]]
    }

    /// Let the route matrices hold `entries` entries in all instead of
    /// [`matrix_budget`]'s bytes (`None`): for tests comparing the two ways of reading
    /// route costs.
    #[doc(hidden)]
    pub fn set_matrix_budget(&mut self, entries: Option<usize>) {
        self.budget = entries;
    }
}

/// The bound max(octile(a, b), max_q |d_q(a) − d_q(b)|) of the module documentation
/// between goals at cells `a` and `b`, from each participant's costs to the two (in
/// participant order). Not symmetric to the bit in principle: every caller passes the
/// goal earlier in its cluster first.
#[inline]
fn bound(a: grid::Cell, b: grid::Cell, costs: impl Iterator<Item = (f64, f64)>) -> f64 {
    let mut d = a.octile(b);
    for (x, y) in costs {
        if x.is_finite() && y.is_finite() {
            d = d.max((x - y).abs());
        }
    }
    d
}

/// The route costs of a cluster without a matrix, computed when read, bit for bit the
/// entries its matrix would hold: node a ≥ 1 is the goal at `cells[a]` (goals in cluster
/// order), with the participants' costs `dist[a * np..(a + 1) * np]`; node 0 is
/// participant `p` (`cells[0]` and `dist[..np]` are unused).
struct OnDemand<'a> {
    cells: &'a [grid::Cell],
    dist: &'a [f64],
    np: usize,
    p: usize,
}

impl Costs for OnDemand<'_> {
    fn n(&self) -> usize {
        self.cells.len()
    }

    #[inline]
    fn get(&self, a: u32, b: u32) -> f64 {
        let (a, b) = (a.min(b) as usize, a.max(b) as usize);
        let np = self.np;
        if a == b {
            0.0
        } else if a == 0 {
            self.dist[b * np + self.p]
        } else {
            let (da, db) = (
                &self.dist[a * np..(a + 1) * np],
                &self.dist[b * np..(b + 1) * np],
            );
            bound(
                self.cells[a],
                self.cells[b],
                da.iter().copied().zip(db.iter().copied()),
            )
        }
    }
}

/// The route costs of a participant that does not reach every goal of a cluster with a
/// matrix, read from it: node a ≥ 1 is the goal at cluster position `at[a − 1]` (rows and
/// columns `at[a − 1] + 1` of the cluster's matrix `m`, `stride × stride`), node 0 the
/// participant, whose costs to the goals (indices into the decision's goals) are `start`.
struct Reached<'a> {
    m: &'a [f64],
    stride: usize,
    at: &'a [usize],
    start: &'a [f64],
    cluster: &'a [u32],
}

impl Costs for Reached<'_> {
    fn n(&self) -> usize {
        self.at.len() + 1
    }

    #[inline]
    fn get(&self, a: u32, b: u32) -> f64 {
        let (a, b) = (a as usize, b as usize);
        match (a, b) {
            (0, 0) => 0.0,
            (0, g) | (g, 0) => self.start[self.cluster[self.at[g - 1]] as usize],
            _ => self.m[(self.at[a - 1] + 1) * self.stride + self.at[b - 1] + 1],
        }
    }
}

/// The route costs of participant `p` through the goals `nodes` of a cluster without a
/// matrix ([`OnDemand`]): a dummy node 0, then the goals (indices into `goals`, cells of
/// `known`), their cells written into `cells` and the `np` participants' costs
/// `dist[q * goals.len() + g]` into `costs`.
#[allow(clippy::too_many_arguments)]
fn on_demand<'a>(
    goals: &[u32],
    known: &Grid<Occ>,
    dist: &[f64],
    np: usize,
    p: usize,
    nodes: impl Iterator<Item = u32>,
    cells: &'a mut Vec<grid::Cell>,
    costs: &'a mut Vec<f64>,
) -> OnDemand<'a> {
    let ng = goals.len();
    cells.clear();
    costs.clear();
    cells.push(grid::Cell::new(0, 0));
    costs.resize(np, 0.0);
    for g in nodes {
        cells.push(known.cell(goals[g as usize] as usize));
        costs.extend((0..np).map(|q| dist[q * ng + g as usize]));
    }
    OnDemand {
        cells,
        dist: costs,
        np,
        p,
    }
}

/// Give goals to the deciding robots.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let mut st = std::mem::take(&mut ctx.memory.mtsp);
    run(ctx, candidates, out, &mut st);
    ctx.memory.mtsp = st;
}

fn run(
    ctx: &mut DecisionCtx<'_>,
    candidates: &CandidateSet,
    out: &mut [Option<Goal>],
    st: &mut State,
) {
    let m = ctx.robots.len();
    for (r, slot) in out.iter_mut().enumerate().take(m) {
        if ctx.deciding[r] {
            *slot = None;
        }
    }
    st.goals.clear();
    st.part.clear();
    st.cstart.clear();
    st.cost.clear();
    st.cluster_of.clear();
    if candidates.is_empty() || !ctx.deciding.iter().any(|&d| d) {
        return;
    }
    // Each robot's search grows until it has settled every candidate (or all it can
    // reach): the costs MA reads are then final, and the cells beyond are never searched.
    // The searches are independent, so they grow side by side on rayon's threads first.
    st.lazy.reset(m, false);
    ctx.planner
        .settle_goals(ctx.robots, ctx.known, ctx.upkeep, candidates.cells());
    for r in 0..m {
        while !st.lazy.step(ctx, candidates, r, false) && st.lazy.found(r).len() < candidates.len()
        {
        }
    }
    let planner = &*ctx.planner;
    let taken = |c: u32| (0..m).any(|r| !ctx.deciding[r] && ctx.goals[r] == Some(c));
    let width = ctx.known.width();
    // Free goals reachable by some robot; participants = robots reaching one of them.
    for &c in candidates.cells() {
        if !taken(c) && (0..m).any(|r| planner.map(r).cost(c as usize).is_some()) {
            st.goals.push(c);
        }
    }
    let ng = st.goals.len();
    for r in 0..m {
        if st
            .goals
            .iter()
            .any(|&g| planner.map(r).cost(g as usize).is_some())
        {
            st.part.push(r);
        }
    }
    st.dist.clear();
    for &r in &st.part {
        let map = planner.map(r);
        st.dist.extend(
            st.goals
                .iter()
                .map(|&g| map.cost(g as usize).unwrap_or(f64::INFINITY)),
        );
    }
    let np = st.part.len();
    if ng > 0 {
        // Cluster first.
        st.points.clear();
        st.points.extend(
            st.goals
                .iter()
                .map(|&g| ((g as usize % width) as f64, (g as usize / width) as f64)),
        );
        let k = np.min(ng);
        let init = if st.centres.len() == k {
            Init::Centres(&st.centres)
        } else {
            Init::PlusPlus(k)
        };
        st.kmeans.fit(&st.points, None, init, &mut *ctx.rng);
        st.centres.clear();
        st.centres.extend_from_slice(st.kmeans.centres());
        let k = st.centres.len();
        st.order.clear();
        st.cstart.push(0);
        for j in 0..k {
            for (g, &l) in st.kmeans.labels().iter().enumerate() {
                if l as usize == j {
                    st.order.push(g as u32);
                }
            }
            st.cstart.push(st.order.len());
        }
        let budget = st
            .budget
            .unwrap_or((matrix_budget(ctx.known.len()) / 8) as usize);
        bounds(st, ctx.known, budget);
        // Route second: the participants × clusters matrix.
        st.cost.resize(np * k, 0.0);
        for p in 0..np {
            for j in 0..k {
                let (c, _) = route(st, p, j, false, ctx.known);
                st.cost[p * k + j] = c;
            }
        }
        st.cluster_of.resize(np, usize::MAX);
        // The solver cannot fail on finite costs; if it did, everyone falls back below.
        if let Ok((rows, cols)) = lsap::solve(np, k, &st.cost, false) {
            for (p, j) in rows.into_iter().zip(cols) {
                st.cluster_of[p] = j;
            }
        }
        for p in 0..np {
            let r = st.part[p];
            let j = st.cluster_of[p];
            if !ctx.deciding[r] || j == usize::MAX {
                continue;
            }
            let (_, first) = route(st, p, j, true, ctx.known);
            if let Some(g) = first {
                let cell = st.goals[g];
                out[r] = Some(Goal {
                    cell,
                    cost: st.dist[p * ng + g],
                });
            }
        }
    }
    // Deciding robots left without a goal: cheapest free goal, else cheapest goal.
    for (r, slot) in out.iter_mut().enumerate().take(m) {
        if !ctx.deciding[r] || slot.is_some() {
            continue;
        }
        let map = planner.map(r);
        let cheapest = |cells: &mut dyn Iterator<Item = u32>| {
            let mut best: Option<Goal> = None;
            for c in cells {
                if let Some(cost) = map.cost(c as usize)
                    && best.is_none_or(|b| cost < b.cost)
                {
                    best = Some(Goal { cell: c, cost });
                }
            }
            best
        };
        *slot = cheapest(&mut st.goals.iter().copied())
            .or_else(|| cheapest(&mut candidates.cells().iter().copied()));
    }
}

/// The goal-to-goal distances of each cluster, once per decision: the lower bound
/// max(octile, max_q |d_q(a) − d_q(b)|) of the module documentation, in the goal part of
/// the cluster's route matrix (while the matrices fit in `budget` entries; the other
/// clusters compute it when read); and the goals' neighbour lists where routes use them.
fn bounds(st: &mut State, known: &Grid<Occ>, budget: usize) {
    let ng = st.goals.len();
    let np = st.part.len();
    st.gm.clear();
    st.goff.clear();
    st.lists.clear();
    st.loff.clear();
    st.loff.push(0);
    let cell = |g: usize| known.cell(st.goals[g] as usize);
    for j in 0..st.cstart.len() - 1 {
        let cluster = &st.order[st.cstart[j]..st.cstart[j + 1]];
        let n = cluster.len() + 1;
        if st.gm.len() + n * n > budget {
            st.goff.push(usize::MAX);
            if n > crate::tsp::FULL_3OPT_UP_TO {
                let nodes = cluster.iter().copied();
                let (cells, costs) = (&mut st.ncell, &mut st.ndist);
                let d = on_demand(&st.goals, known, &st.dist, np, 0, nodes, cells, costs);
                st.fast.goal_neighbours_of(&d, &mut st.lists);
            }
            st.loff.push(st.lists.len());
            continue;
        }
        let off = st.gm.len();
        st.goff.push(off);
        st.gm.resize(off + n * n, 0.0);
        st.ccell.clear();
        st.ccell.extend(cluster.iter().map(|&g| cell(g as usize)));
        st.ccost.clear();
        for q in 0..np {
            let row = &st.dist[q * ng..(q + 1) * ng];
            st.ccost.extend(cluster.iter().map(|&g| row[g as usize]));
        }
        fill_bounds(&st.ccell, &st.ccost, &mut st.gm[off..off + n * n]);
        if n > crate::tsp::FULL_3OPT_UP_TO {
            st.fast
                .goal_neighbours(n, &st.gm[off..off + n * n], &mut st.lists);
        }
        st.loff.push(st.lists.len());
    }
}

/// The goal part of a cluster's route matrix `m` (`n × n`, n = the goals + 1, node a + 1
/// = goal a): [`bound`] between every two goals, from the goals' `cells` and the
/// participants' costs to them (`costs[q * goals + a]`: participant q's to goal a). The
/// same bits as [`bound`] pair by pair (a maximum is exact, so the order of its terms
/// does not matter), computed a row at a time over contiguous costs: a pair at a time
/// reads one cost per participant from as many places and writes its mirror a matrix row
/// away, which on clusters of hundreds of goals (`ma-af`) costs as much as routing them.
/// Rows and column 0 are left as they are.
fn fill_bounds(cells: &[grid::Cell], costs: &[f64], m: &mut [f64]) {
    let c = cells.len();
    let n = c + 1;
    debug_assert_eq!(m.len(), n * n, "a matrix of the cluster's size");
    for a in 0..c {
        // goals a + 1.. of row a + 1 (columns a + 2..n)
        let row = &mut m[(a + 1) * n + a + 2..(a + 2) * n];
        let ca = cells[a];
        for (d, &cb) in row.iter_mut().zip(&cells[a + 1..]) {
            *d = ca.octile(cb);
        }
        for q in costs.chunks_exact(c) {
            let x = q[a];
            if !x.is_finite() {
                continue;
            }
            for (d, &y) in row.iter_mut().zip(&q[a + 1..]) {
                // `d.max(t)` for a finite y, as a select (x is finite: t is never NaN)
                let t = (x - y).abs();
                *d = if y.abs() < f64::INFINITY && t > *d {
                    t
                } else {
                    *d
                };
            }
        }
    }
    // The lower triangle mirrors the upper, in tiles that stay in the cache.
    const TILE: usize = 32;
    for a0 in (1..n).step_by(TILE) {
        for b0 in (a0..n).step_by(TILE) {
            for a in a0..(a0 + TILE).min(n) {
                for b in b0.max(a + 1)..(b0 + TILE).min(n) {
                    m[b * n + a] = m[a * n + b];
                }
            }
        }
    }
}

/// Route participant `p` through cluster `j`: its cost (with penalties for unreachable
/// goals) and the first goal (index into `st.goals`). `full` selects the thorough solver.
fn route(
    st: &mut State,
    p: usize,
    j: usize,
    full: bool,
    known: &Grid<Occ>,
) -> (f64, Option<usize>) {
    let ng = st.goals.len();
    let cluster = &st.order[st.cstart[j]..st.cstart[j + 1]];
    // The route's nodes: the cluster positions of the goals participant p reaches.
    st.at.clear();
    let mut penalty = 0.0;
    for (a, &g) in cluster.iter().enumerate() {
        if st.dist[p * ng + g as usize].is_finite() {
            st.at.push(a);
        } else {
            penalty += UNREACHABLE;
        }
    }
    // The goal-to-goal bounds do not depend on the participant (see `bounds`): one who
    // reaches every goal of the cluster is routed on the cluster's matrix with its own row
    // 0 and the shared neighbour lists; another on a matrix of the goals it reaches. A
    // cluster without a matrix gives the same costs when read.
    let (off, c) = (st.goff[j], cluster.len());
    let n = st.at.len() + 1;
    let solver = if full { &mut st.full } else { &mut st.fast };
    let c = if off == usize::MAX {
        let np = st.part.len();
        let nodes = st.at.iter().map(|&a| cluster[a]);
        let (cells, costs) = (&mut st.ncell, &mut st.ndist);
        let d = on_demand(&st.goals, known, &st.dist, np, p, nodes, cells, costs);
        let lists = &st.lists[st.loff[j]..st.loff[j + 1]];
        let lists = (n == c + 1 && !lists.is_empty()).then_some(lists);
        solver.solve_costs(&d, lists)
    } else if n == c + 1 {
        let m = &mut st.gm[off..off + n * n];
        for a in 1..n {
            let d0 = st.dist[p * ng + cluster[a - 1] as usize];
            m[a] = d0;
            m[a * n] = d0;
        }
        let lists = &st.lists[st.loff[j]..st.loff[j + 1]];
        solver.solve_sharing(n, m, (!lists.is_empty()).then_some(lists))
    } else {
        let stride = c + 1;
        let d = Reached {
            m: &st.gm[off..off + stride * stride],
            stride,
            at: &st.at,
            start: &st.dist[p * ng..(p + 1) * ng],
            cluster,
        };
        solver.solve_costs(&d, None)
    };
    let first = solver
        .route()
        .get(1)
        .map(|&v| cluster[st.at[v as usize - 1]] as usize);
    (c + penalty, first)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The rows filled at once hold [`bound`]'s bits for every pair, unreachable
        /// goals (infinite costs) included, and leave row and column 0 alone.
        #[test]
        fn filled_bounds_are_the_pairwise_bounds(
            goals in prop::collection::vec((0i32..40, 0i32..40), 0..60),
            np in 1usize..6,
            raw in prop::collection::vec(0u32..400, 360),
            inf in prop::collection::vec(0u8..10, 360),
        ) {
            let c = goals.len();
            let cells: Vec<grid::Cell> =
                goals.iter().map(|&(x, y)| grid::Cell::new(x, y)).collect();
            // path costs: whole steps and diagonals, some unreachable
            let costs: Vec<f64> = (0..np * c)
                .map(|i| match inf[i % inf.len()] {
                    0 => f64::INFINITY,
                    _ => f64::from(raw[i % raw.len()] % 37)
                        + grid::SQRT2 * f64::from(raw[i % raw.len()] / 37),
                })
                .collect();
            let n = c + 1;
            let mut m = vec![-1.0; n * n];
            fill_bounds(&cells, &costs, &mut m);
            for a in 0..c {
                for b in a + 1..c {
                    let want = bound(
                        cells[a],
                        cells[b],
                        (0..np).map(|q| (costs[q * c + a], costs[q * c + b])),
                    );
                    prop_assert_eq!(m[(a + 1) * n + b + 1].to_bits(), want.to_bits());
                    prop_assert_eq!(m[(b + 1) * n + a + 1].to_bits(), want.to_bits());
                }
            }
            for a in 0..n {
                prop_assert_eq!(m[a], -1.0);
                prop_assert_eq!(m[a * n], -1.0);
            }
        }
    }
}
