//! The actions of a state (Quattrini Li et al., "Formulation of the Search Problem" and the
//! "Clustering boundary cells" / "Eliminating small clusters" speed-ups).
//!
//! From (q, M) the robot may move to a reachable free cell of M on the boundary between
//! perceived and unperceived space, or only to cluster representatives: boundary cells are
//! grouped into 8-connected clusters and each cluster is represented by its cell nearest
//! (Euclidean) to the cluster's centroid, ties to the lowest flat index; clusters with fewer
//! than k cells can be dropped.
//!
//! A boundary cell is a perceived free cell with an unperceived cell of any kind among its
//! 8 neighbours: a free cell, a wall, or a cell no position perceives (the paper's
//! "unknown"). So the state tracks the perceived walls next to reachable cells as well as
//! the free cells (the goal counts only free ones). This is also the online frontier (a
//! known free cell with an unknown 8-neighbour), so every online run with time-discrete
//! perception is a sequence of boundary actions and cannot be shorter than their optimum.
//!
//! Deviation: clusters group only the boundary cells that border an unperceived *free*
//! cell. Strips of cells along unseen walls joined the clusters otherwise and pulled their
//! representatives (the cell nearest the centroid) to poor viewpoints: on a 10 × 10 m
//! office at 0.5 m with `footprint:r=3c` from (16, 15) the cluster optimum was 52.7 m with
//! them and is 42.7 m without (the boundary optimum: 42.8 m or less). Representatives stay
//! boundary cells, so the cluster optimum is never below the boundary optimum.
//!
//! Deviation: when no candidate perceives a new free cell but some are left to perceive
//! (the footprint sensor sees through walls, so a pocket behind a wall is a target no
//! boundary cell borders), the search offers the next larger set instead (clusters →
//! boundary cells → every reachable perceived cell, `ActionSet::wider`). Then the
//! boundary and cluster actions reach the goal whenever any sequence does: if unperceived
//! targets lay on a path inside the reachable cells, the first of them would border a
//! boundary cell that perceives it.
//!
//! [`ActionSet::All`] (every reachable perceived cell) is offered beyond the paper: it makes
//! the search exact over all position sequences.

use crate::heuristic::has;
use crate::problem::{NOT_TARGET, Problem};

/// Which cells a state may move to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ActionSet {
    /// Every boundary cell (the paper's basic formulation).
    Boundary,
    /// One representative per 8-connected cluster of boundary cells, dropping clusters of
    /// fewer than `min_size` cells (1 keeps all).
    Clusters {
        /// The paper's k.
        min_size: usize,
    },
    /// Every reachable perceived cell (exact over all position sequences; slow).
    All,
}

impl ActionSet {
    /// The next larger set, offered when no candidate of this one perceives a new target:
    /// clusters → boundary → all (each state's actions then stay a subset of the next
    /// set's, so clusters never beat the boundary optimum).
    pub(crate) fn wider(self) -> Option<ActionSet> {
        match self {
            ActionSet::Clusters { .. } => Some(ActionSet::Boundary),
            ActionSet::Boundary => Some(ActionSet::All),
            ActionSet::All => None,
        }
    }
}

/// Scratch for computing actions without allocating per state.
pub(crate) struct ActionScratch {
    mark: Vec<u32>,
    epoch: u32,
    stack: Vec<u32>,
    cluster: Vec<u32>,
    members: Vec<u32>,
}

impl ActionScratch {
    /// Scratch for a grid of `n` cells.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            mark: vec![0; n],
            epoch: 0,
            stack: Vec::new(),
            cluster: Vec::new(),
            members: Vec::new(),
        }
    }
}

/// Whether perceived free cell `i` has an unperceived mark below `below` among its 8
/// neighbours: any mark (target, wall, ...) with `u32::MAX`, a free target with |E_f|.
#[inline]
pub(crate) fn is_boundary(problem: &Problem, bits: &[u64], i: usize, below: u32) -> bool {
    for &t in problem.neighbour_marks(i) {
        if t == NOT_TARGET {
            return false;
        }
        if t < below && !has(bits, t) {
            return true;
        }
    }
    false
}

/// Fill `out` with the candidate positions among `settled` (the reachable perceived cells,
/// in settling order) for action set `set`; `here` (the robot's cell) is never a candidate.
pub(crate) fn candidates(
    problem: &Problem,
    bits: &[u64],
    settled: &[u32],
    here: u32,
    set: ActionSet,
    scratch: &mut ActionScratch,
    out: &mut Vec<u32>,
) {
    out.clear();
    match set {
        ActionSet::All => out.extend(settled.iter().copied().filter(|&i| i != here)),
        ActionSet::Boundary => out.extend(
            settled
                .iter()
                .copied()
                .filter(|&i| i != here && is_boundary(problem, bits, i as usize, u32::MAX)),
        ),
        ActionSet::Clusters { min_size } => {
            // Clusters group the cells that border unperceived free cells (module doc).
            let nt = problem.targets().len() as u32;
            // Two fresh marks: boundary cells, then cells visited by the cluster fill (all
            // marks are cleared when the counter would wrap).
            if scratch.epoch > u32::MAX - 2 {
                scratch.mark.fill(0);
                scratch.epoch = 0;
            }
            let (boundary, visited) = (scratch.epoch + 1, scratch.epoch + 2);
            scratch.epoch = visited;
            for &i in settled {
                if is_boundary(problem, bits, i as usize, nt) {
                    scratch.mark[i as usize] = boundary;
                }
            }
            candidates_clusters(
                problem, settled, here, min_size, boundary, visited, scratch, out,
            );
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn candidates_clusters(
    problem: &Problem,
    settled: &[u32],
    here: u32,
    min_size: usize,
    boundary: u32,
    visited: u32,
    scratch: &mut ActionScratch,
    out: &mut Vec<u32>,
) {
    let cells = problem.cells();
    let (w, h) = (cells.width(), cells.height());
    // Seeds in increasing flat index for a deterministic cluster order.
    let mut seeds = std::mem::take(&mut scratch.cluster);
    seeds.clear();
    seeds.extend(
        settled
            .iter()
            .copied()
            .filter(|&i| scratch.mark[i as usize] == boundary),
    );
    seeds.sort_unstable();
    let mut members = std::mem::take(&mut scratch.members);
    for &s in &seeds {
        if scratch.mark[s as usize] != boundary {
            continue;
        }
        members.clear();
        scratch.mark[s as usize] = visited;
        scratch.stack.clear();
        scratch.stack.push(s);
        while let Some(i) = scratch.stack.pop() {
            members.push(i);
            let (x, y) = ((i as usize % w) as i64, (i as usize / w) as i64);
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let j = ny as usize * w + nx as usize;
                    if scratch.mark[j] == boundary {
                        scratch.mark[j] = visited;
                        scratch.stack.push(j as u32);
                    }
                }
            }
        }
        if members.len() < min_size.max(1) {
            continue;
        }
        let best = representative(&members, w);
        if best != here {
            out.push(best);
        }
    }
    scratch.cluster = seeds;
    scratch.members = members;
}

/// The member nearest (Euclidean) to the members' centroid, ties to the lowest flat index.
pub(crate) fn representative(members: &[u32], w: usize) -> u32 {
    let (mut sx, mut sy) = (0.0, 0.0);
    for &i in members {
        sx += (i as usize % w) as f64;
        sy += (i as usize / w) as f64;
    }
    let m = members.len() as f64;
    let (cx, cy) = (sx / m, sy / m);
    let mut best = (f64::INFINITY, u32::MAX);
    for &i in members {
        let dx = (i as usize % w) as f64 - cx;
        let dy = (i as usize / w) as f64 - cy;
        let d = dx * dx + dy * dy;
        if d < best.0 || (d == best.0 && i < best.1) {
            best = (d, i);
        }
    }
    best.1
}
