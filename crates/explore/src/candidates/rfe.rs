//! Representatives of free edges (Faigl & Kulich 2013, §III-C 2, RFE).
//!
//! Frontier cells are grouped into free edges F_i, the 8-connected components of the
//! frontier set; edges of fewer than n_f cells are ignored. Each edge is split by k-means
//! into n_r = 1 + ⌊|F_i| / (1.8 ρ_g) + 0.5⌋ clusters (ρ_g: sensor range in cells), and the
//! mean of each cluster is a goal candidate. The k-means++ seeding draws from the run's
//! seeded generator, so the candidates are deterministic per seed.
//!
//! Deviations and choices:
//! - A mean may lie off the edge (a curved edge) or in unknown space, so each one is
//!   snapped to the nearest cell of its edge (ties: the lower cell index), so that every
//!   candidate is a frontier cell a robot can go to.
//! - Faigl & Kulich consider "only frontiers that are reachable by all robots"; we keep
//!   the edge cells reachable by the first deciding robot (all free space of a run is one
//!   component, so this is the same set in practice) and not on the visited/inaccessible
//!   lists, and cluster those. n_r is computed from the whole edge, capped by the number of
//!   kept cells.
//! - n_f: the paper's experiments use n_f = 1 ("the minimal number of frontier cells in a
//!   free edge is n_f = 1", §V), so [`DEFAULT_MIN_EDGE`] is 1. With a larger n_f, when no
//!   edge of that size yields a candidate the smaller edges are taken too (as the centroid
//!   generator does): with ideal sensors a small edge is real unexplored space, and without
//!   the fallback the team would stop with reachable space unexplored.

use super::CandidateSet;
use crate::decision::DecisionCtx;
use crate::frontier::Region;
use crate::kmeans::{Init, KMeans, Point};

/// State kept across decisions: edge, point and k-means buffers, and the last
/// representatives (for inspection).
#[derive(Default)]
pub struct State {
    regions: Vec<Region>,
    cells: Vec<u32>,
    points: Vec<Point>,
    kmeans: KMeans,
    reps: Vec<Representative>,
}

/// One representative of the last decision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Representative {
    /// Smallest cell index of its free edge (identifies the edge).
    pub edge: u32,
    /// The k-means centre, in cells.
    pub centre: Point,
    /// The centre snapped to the nearest kept cell of the edge: the candidate.
    pub cell: u32,
}

impl State {
    /// The representatives found by the last decision, edge by edge (edges in order of
    /// their smallest cell index, centres in k-means order).
    pub fn representatives(&self) -> &[Representative] {
        &self.reps
    }
}

/// n_f used by the presets: free edges of fewer cells are ignored (Faigl & Kulich §V: 1).
pub const DEFAULT_MIN_EDGE: usize = 1;

/// n_r = 1 + ⌊|F| / (1.8 ρ_g) + 0.5⌋, the number of representatives of an edge of
/// `edge_cells` cells for a sensor range of `rho_cells` cells (every cell if ρ ≤ 0).
pub fn representatives_for(edge_cells: usize, rho_cells: f64) -> usize {
    if rho_cells > 0.0 && rho_cells.is_finite() {
        1 + (edge_cells as f64 / (1.8 * rho_cells) + 0.5).floor() as usize
    } else {
        edge_cells.max(1)
    }
}

/// Fill `out` with the representatives of the free edges of at least `min_edge` cells.
pub fn generate(ctx: &mut DecisionCtx<'_>, min_edge: usize, out: &mut CandidateSet) {
    let mut st = std::mem::take(&mut ctx.memory.rfe);
    st.reps.clear();
    generate_min(ctx, min_edge, out, &mut st);
    if out.is_empty() && min_edge > 1 {
        generate_min(ctx, 1, out, &mut st);
    }
    ctx.memory.rfe = st;
}

fn generate_min(
    ctx: &mut DecisionCtx<'_>,
    min_edge: usize,
    out: &mut CandidateSet,
    st: &mut State,
) {
    let width = ctx.known.width();
    ctx.upkeep.regions(width, min_edge, &mut st.regions);
    let Some(r) = ctx.deciding.iter().position(|&d| d) else {
        return;
    };
    let reach = ctx
        .planner
        .component(r, ctx.robots[r], ctx.known, ctx.upkeep);
    for region in &st.regions {
        st.cells.clear();
        st.points.clear();
        for &c in &region.cells {
            if !ctx.lists.is_excluded(c) && reach.contains(c as usize) {
                st.cells.push(c);
                st.points.push(xy(c, width));
            }
        }
        if st.cells.is_empty() {
            continue;
        }
        let k = representatives_for(region.cells.len(), ctx.sensor_range_cells).min(st.cells.len());
        st.kmeans
            .fit(&st.points, None, Init::PlusPlus(k), &mut *ctx.rng);
        for &centre in st.kmeans.centres() {
            let mut best = (f64::INFINITY, 0u32);
            for (&c, p) in st.cells.iter().zip(&st.points) {
                let d = (p.0 - centre.0).powi(2) + (p.1 - centre.1).powi(2);
                if d < best.0 {
                    best = (d, c);
                }
            }
            out.insert(best.1);
            st.reps.push(Representative {
                edge: region.cells[0],
                centre,
                cell: best.1,
            });
        }
    }
}

/// Cell `c`'s coordinates as a k-means point.
#[inline]
fn xy(c: u32, width: usize) -> Point {
    ((c as usize % width) as f64, (c as usize / width) as f64)
}
