//! Solanas & Garcia's assignment (Faigl & Kulich 2013, §III-B, Eq. 1, SGA).
//!
//! The unknown cells are clustered by k-means into m clusters, one per robot: the first
//! clustering starts at the map centre, each later one from the previous centres, and a
//! cluster stays with its robot for the whole exploration. A frontier f belongs to the
//! cluster with the closest centre. Robot j's cost for frontier f is (Eq. 1)
//!
//! - Δ + ‖f − centre(ζ_j)‖² + o_f if f is not in j's cluster ζ_j (Δ: the map's diagonal),
//! - path length(f, r_j) + o_f if it is,
//!
//! each deciding robot in turn takes the frontier of least cost, and then 2ρ is added to
//! the penalty o of every frontier within ρ of the chosen one (ρ: sensor range, cells).
//!
//! Choices and deviations:
//! - ‖·‖² is read as the squared Euclidean distance (the extracted formula is ambiguous
//!   between a square and an L2 subscript). All lengths are in cells.
//! - "The map centre" start: m identical centres would leave all but one cluster empty, so
//!   the first centres sit on a circle of one cell around the centre (angle 2πj/m). After
//!   the first clustering, cluster j is given to robot r by an optimal assignment of the
//!   robots to the centres by Euclidean distance (`lsap`), and the centres are stored in
//!   robot order in [`State`].
//! - The unknown cells (all of them: which unknown cells are "possibly reachable" is not
//!   knowable) are clustered in blocks: cells are pooled into square blocks of side s,
//!   each block a point at the mean of its unknown cells weighted by their number, with s
//!   the smallest side giving at most [`MAX_BLOCKS`] blocks. The centre update is then
//!   exact; only the labelling is per block. On maps of ≤ 4096 cells s = 1 (exact). The
//!   blocks' sums are kept between decisions and redone only where the belief's rows
//!   changed (the sums are of whole numbers, exact in any order, so they are those of a
//!   pass over the map); a clustering of a 1000 × 1000 map therefore costs the rows that
//!   changed plus Lloyd on ≤ 4096 points, instead of Lloyd on up to 10⁶ points.
//! - Team semantics: robots that keep their goal count as having chosen it (their goals are
//!   penalised first); robots decide in index order; only frontiers the robot can reach are
//!   considered. The paper re-plans every s_max = 7 steps; the loop does that.
//! - Costs: a goal outside the robot's cluster needs only to be reachable (one flood fill
//!   per component); goals in it are priced by the robot's search, guided toward them
//!   only and grown until every goal it has not settled would cost more than the best so
//!   far (path + o ≥ path). The choice is that of the full cost list. A chosen goal
//!   outside the cluster gets its path from a search guided toward it alone.

use crate::belief_rows::{LogPos, RowLog};
use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};
use crate::kmeans::{Init, KMeans, Point};

/// Most blocks the unknown cells are pooled into for clustering.
pub const MAX_BLOCKS: usize = 4096;

/// Cluster centres kept between decisions (in robot order) and buffers.
#[derive(Default)]
pub struct State {
    centres: Vec<Point>,
    points: Vec<Point>,
    weights: Vec<f64>,
    /// Per block: the sums of the columns and rows of its unknown cells, and their number,
    /// as of `prev`.
    sums: Vec<(f64, f64, f64)>,
    /// The belief the sums were made from, and how far it followed the belief's row log.
    prev: grid::Grid<grid::Occ>,
    pos: LogPos,
    kmeans: KMeans,
    penalty: Vec<f64>,
    label: Vec<u32>,
    cost: Vec<f64>,
    lazy: crate::assign::costs::LazyCosts,
}

impl State {
    /// Robot r's cluster centre (index r), as left by the last decision.
    pub fn centres(&self) -> &[Point] {
        &self.centres
    }

    /// Make `centres` the kept centres, returning the ones kept so far.
    pub fn replace_centres(&mut self, centres: Vec<Point>) -> Vec<Point> {
        std::mem::replace(&mut self.centres, centres)
    }
}

/// Side of the blocks unknown cells are pooled into on a `w × h` map.
pub fn block_side(w: usize, h: usize) -> usize {
    let mut s = 1;
    while w.div_ceil(s) * h.div_ceil(s) > MAX_BLOCKS {
        s += 1;
    }
    s
}

/// Give goals to the deciding robots.
pub fn assign(ctx: &mut DecisionCtx<'_>, candidates: &CandidateSet, out: &mut [Option<Goal>]) {
    let mut st = std::mem::take(&mut ctx.memory.sga);
    run(ctx, candidates, out, &mut st);
    ctx.memory.sga = st;
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
    if m == 0 {
        return;
    }
    cluster_unknown(ctx, st);
    if candidates.is_empty() {
        return;
    }
    st.lazy.reset(m, true);
    let (w, h) = (ctx.known.width(), ctx.known.height());
    let delta = ((w * w + h * h) as f64).sqrt();
    let rho = ctx.sensor_range_cells.max(0.0);
    let xy = |c: u32| ((c as usize % w) as f64, (c as usize / w) as f64);
    let cells = candidates.cells();
    st.penalty.clear();
    st.penalty.resize(cells.len(), 0.0);
    st.label.clear();
    st.label.extend(
        cells
            .iter()
            .map(|&c| crate::kmeans::nearest(&st.centres, xy(c)) as u32),
    );
    let penalise = |penalty: &mut [f64], at: u32| {
        let p = xy(at);
        for (o, &c) in penalty.iter_mut().zip(cells) {
            let q = xy(c);
            if (p.0 - q.0).powi(2) + (p.1 - q.1).powi(2) <= rho * rho {
                *o += 2.0 * rho;
            }
        }
    };
    for r in 0..m {
        if !ctx.deciding[r]
            && let Some(g) = ctx.goals[r]
        {
            penalise(&mut st.penalty, g);
        }
    }
    for (r, slot) in out.iter_mut().enumerate().take(m) {
        if !ctx.deciding[r] {
            continue;
        }
        let centre = st.centres[r];
        // Goals outside the robot's cluster: their cost needs no path, only reachability.
        let comp = ctx
            .planner
            .component(r, ctx.robots[r], ctx.known, ctx.upkeep);
        let mut best: Option<(f64, usize)> = None; // (cost, index)
        let mut inside = 0; // reachable goals in the robot's cluster
        for (i, &c) in cells.iter().enumerate() {
            if !comp.contains(c as usize) {
                continue;
            }
            if st.label[i] as usize == r {
                inside += 1;
                continue;
            }
            let f = xy(c);
            let cost = delta + (f.0 - centre.0).powi(2) + (f.1 - centre.1).powi(2) + st.penalty[i];
            if best.is_none_or(|(b, _)| cost < b) {
                best = Some((cost, i));
            }
        }
        // Goals in it cost their path plus penalty: grow the search, guided toward them
        // only, until nothing it has not settled can be cheaper than the best so far, or
        // all of them are settled.
        if inside > 0 {
            let own = cells
                .iter()
                .zip(&st.label)
                .filter(|&(_, &l)| l as usize == r);
            st.lazy.guide_toward(own.map(|(&c, _)| c));
        }
        let mut seen = 0;
        while inside > 0 {
            let done = st.lazy.step(ctx, candidates, r, false);
            let found = st.lazy.found(r);
            for p in &found[seen..] {
                if st.label[p.col] as usize != r {
                    continue;
                }
                inside -= 1;
                let cost = p.cost + st.penalty[p.col];
                if best.is_none_or(|(b, bi)| (cost, p.col) < (b, bi)) {
                    best = Some((cost, p.col));
                }
            }
            seen = found.len();
            if done || best.is_some_and(|(b, _)| st.lazy.next_bucket(ctx, r) as f64 > b) {
                break;
            }
        }
        // The path length of the goal chosen (settled by the search, which may not have
        // started yet when the robot's cluster holds no goal).
        let best = best.and_then(|(_, i)| {
            let cell = cells[i] as usize;
            let settled = ctx.planner.is_searching(r) && ctx.planner.map(r).is_settled(cell);
            if !settled {
                // a goal outside the cluster: a search toward it alone
                st.lazy.guide_toward([cells[i]]);
            }
            st.lazy.grow(ctx, candidates, r, 0);
            loop {
                if let Some(path) = ctx.planner.map(r).cost(cell) {
                    break Some((0.0, i, path));
                }
                if st.lazy.step(ctx, candidates, r, false) {
                    break ctx.planner.map(r).cost(cell).map(|path| (0.0, i, path));
                }
            }
        });
        if let Some((_, i, path)) = best {
            *slot = Some(Goal {
                cell: cells[i],
                cost: path,
            });
            penalise(&mut st.penalty, cells[i]);
        }
    }
}

/// k-means of the unknown cells (pooled in blocks) from the previous centres, or from the
/// map centre the first time; leaves the centres in robot order in `st.centres`.
fn cluster_unknown(ctx: &mut DecisionCtx<'_>, st: &mut State) {
    let m = ctx.robots.len();
    let known = ctx.known;
    let (w, h) = (known.width(), known.height());
    let s = block_side(w, h);
    let follow = (ctx.upkeep.row_log(), &mut st.pos);
    pool_unknown(&mut st.sums, &mut st.prev, follow, known, s);
    st.points.clear();
    st.weights.clear();
    for b in &st.sums {
        if b.2 > 0.0 {
            st.points.push((b.0 / b.2, b.1 / b.2));
            st.weights.push(b.2);
        }
    }
    let first = st.centres.len() != m;
    if first {
        let (cx, cy) = (w as f64 / 2.0, h as f64 / 2.0);
        st.centres.clear();
        st.centres.extend((0..m).map(|j| {
            let a = std::f64::consts::TAU * j as f64 / m as f64;
            (cx + a.cos(), cy + a.sin())
        }));
    }
    st.kmeans.fit(
        &st.points,
        Some(&st.weights),
        Init::Centres(&st.centres),
        &mut *ctx.rng,
    );
    st.centres.clear();
    st.centres.extend_from_slice(st.kmeans.centres());
    if first && m > 1 {
        // Give each robot a cluster: optimal matching by Euclidean distance.
        st.cost.clear();
        for &rc in ctx.robots {
            let p = ((rc as usize % w) as f64, (rc as usize / w) as f64);
            st.cost.extend(
                st.centres
                    .iter()
                    .map(|c| ((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2)).sqrt()),
            );
        }
        if let Ok((rows, cols)) = lsap::solve(m, m, &st.cost, false) {
            let old = st.centres.clone();
            for (r, j) in rows.into_iter().zip(cols) {
                st.centres[r] = old[j];
            }
        }
    }
}

/// Bring `sums` (per block of side `s`: the sums of the columns and rows of its unknown
/// cells, and their number) from the belief `prev` to `known`, redoing only the rows that
/// changed (those `log` has changed since `pos`, if `prev` followed it); `prev` becomes a
/// copy of `known`. Sums of whole numbers are exact in any order, so they equal a pass over
/// `known`.
fn pool_unknown(
    sums: &mut Vec<(f64, f64, f64)>,
    prev: &mut grid::Grid<grid::Occ>,
    (log, pos): (&RowLog, &mut LogPos),
    known: &grid::Grid<grid::Occ>,
    s: usize,
) {
    let (w, h) = (known.width(), known.height());
    let (bw, bh) = (w.div_ceil(s), h.div_ceil(s));
    if prev.width() != w || prev.height() != h || sums.len() != bw * bh {
        // Nothing counted yet: every cell of an all-unknown copy is unknown.
        *prev = grid::Grid::new(w, h, grid::Occ::Unknown);
        *pos = LogPos::default();
        sums.clear();
        sums.resize(bw * bh, (0.0, 0.0, 0.0));
        for y in 0..h {
            for x in 0..w {
                let b = &mut sums[(y / s) * bw + x / s];
                b.0 += x as f64;
                b.1 += y as f64;
                b.2 += 1.0;
            }
        }
    }
    crate::belief_rows::sync_rows(known, prev, s, (log, pos), |y, k, new, old| {
        let b = &mut sums[(y / s) * bw + k];
        for (d, (&n, &o)) in new.iter().zip(old).enumerate() {
            let sign = match (n == grid::Occ::Unknown, o == grid::Occ::Unknown) {
                (true, false) => 1.0,
                (false, true) => -1.0,
                _ => continue,
            };
            b.0 += sign * (k * s + d) as f64;
            b.1 += sign * y as f64;
            b.2 += sign;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::{Grid, Occ};
    use proptest::prelude::*;

    /// The sums of a pass over the map, the obvious way.
    fn pooled(known: &Grid<Occ>, s: usize) -> Vec<(f64, f64, f64)> {
        let (w, h) = (known.width(), known.height());
        let mut sums = vec![(0.0, 0.0, 0.0); w.div_ceil(s) * h.div_ceil(s)];
        for y in 0..h {
            for x in 0..w {
                if known[y * w + x] == Occ::Unknown {
                    let b = &mut sums[(y / s) * w.div_ceil(s) + x / s];
                    b.0 += x as f64;
                    b.1 += y as f64;
                    b.2 += 1.0;
                }
            }
        }
        sums
    }

    proptest! {
        /// Beliefs one after the other (cells revealed, and some becoming unknown again):
        /// the kept sums equal a pass over each, bit for bit, with blocks of any side.
        #[test]
        fn kept_sums_equal_a_pass_over_the_map(
            (w, h) in (1usize..90, 1usize..60),
            s in 1usize..5,
            steps in prop::collection::vec(prop::collection::vec((0usize..5400, 0u8..3), 0..200), 1..5),
        ) {
            let (mut sums, mut prev) = (Vec::new(), Grid::new(0, 0, Occ::Unknown));
            let mut known = Grid::new(w, h, Occ::Unknown);
            // the copy follows a row log of the changes, as in a run
            let (mut log, mut pos) = (RowLog::new(h), LogPos::default());
            for step in steps {
                let mut cells = Vec::new();
                for (i, o) in step {
                    known[i % (w * h)] = [Occ::Unknown, Occ::Free, Occ::Occupied][o as usize];
                    cells.push((i % (w * h)) as u32);
                }
                log.note(w, &cells);
                pool_unknown(&mut sums, &mut prev, (&log, &mut pos), &known, s);
                let want = pooled(&known, s);
                prop_assert_eq!(sums.len(), want.len());
                for (g, e) in sums.iter().zip(&want) {
                    prop_assert_eq!((g.0.to_bits(), g.1.to_bits(), g.2.to_bits()), (e.0.to_bits(), e.1.to_bits(), e.2.to_bits()));
                }
            }
        }
    }
}
