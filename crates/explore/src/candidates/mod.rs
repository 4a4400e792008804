//! Goal candidates: which cells a strategy may send a robot to.
//!
//! One file per kind: all frontier cells (Holz's closest frontier, the coordination study's, Faigl's AF),
//! region centroids (Yamauchi), free-edge representatives (RFE) and coverage candidates
//! (CC) of Faigl & Kulich, and decision-theoretic samples (González-Baños & Latombe).

pub mod all_frontiers;
pub mod centroids;
pub mod coverage;
pub mod dt_samples;
pub mod rfe;

use std::cell::{Cell, RefCell};

use crate::bits::CellBits;
use crate::decision::DecisionCtx;

/// A set of goal candidates with O(1) membership, reused across decisions.
///
/// Membership is one bit per cell of the map ([`CellBits`]), so a set of frontier cells
/// touches few pages of it. The positions [`index_of`](Self::index_of) answers come from an
/// array of the map's size that is written only when first asked: the assigners that only
/// test membership never touch it.
#[derive(Clone, Debug, Default)]
pub struct CandidateSet {
    cells: Vec<u32>,
    members: CellBits,
    /// Position of each member in `cells`; valid for the members `cells[..indexed]`
    /// (allocated and caught up by `index_of`).
    index: RefCell<Vec<u32>>,
    indexed: Cell<usize>,
}

impl CandidateSet {
    /// An empty set for a map of `len` cells.
    pub fn new(len: usize) -> Self {
        Self {
            cells: Vec::new(),
            members: CellBits::new(len),
            index: RefCell::new(Vec::new()),
            indexed: Cell::new(0),
        }
    }

    /// Empty the set (cost ∝ members).
    pub fn clear(&mut self) {
        for &c in &self.cells {
            self.members.remove(c as usize);
        }
        self.cells.clear();
        self.indexed.set(0);
    }

    /// Add `cell` (no effect if present).
    pub fn insert(&mut self, cell: u32) {
        if !self.members.contains(cell as usize) {
            self.members.insert(cell as usize);
            self.cells.push(cell);
        }
    }

    /// Whether `cell` is a candidate.
    #[inline]
    pub fn contains(&self, cell: usize) -> bool {
        self.members.contains(cell)
    }

    /// The position of `cell` in [`cells`](Self::cells), if it is a candidate.
    #[inline]
    pub fn index_of(&self, cell: usize) -> Option<usize> {
        // Asked for every cell a search settles: the membership bit is the inlined fast
        // path, the look-up of a member's position the call.
        if !self.contains(cell) {
            return None;
        }
        Some(self.position(cell))
    }

    /// The position of member `cell`, indexing the candidates added since the last call.
    #[inline(never)]
    fn position(&self, cell: usize) -> usize {
        let mut index = self.index.borrow_mut();
        let from = self.indexed.get();
        if from < self.cells.len() {
            if index.len() != self.members.len() {
                *index = vec![0; self.members.len()];
            }
            for (k, &c) in self.cells.iter().enumerate().skip(from) {
                index[c as usize] = k as u32;
            }
            self.indexed.set(self.cells.len());
        }
        index[cell] as usize
    }

    /// The candidates, in the order they were added (deterministic).
    pub fn cells(&self) -> &[u32] {
        &self.cells
    }

    /// Number of candidates.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether there are no candidates.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Whether the set is sized for a map of `len` cells.
    pub fn fits(&self, len: usize) -> bool {
        self.members.len() == len
    }
}

/// Which candidate generator a strategy uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CandidateKind {
    /// Every frontier cell (AF).
    AllFrontiers,
    /// One goal per frontier region of at least `min_size_m` metres (counted in cells along
    /// the region): its centroid snapped to the nearest reachable cell of the region.
    RegionCentroids {
        /// Minimum region size in metres (Yamauchi: roughly the robot's size).
        min_size_m: f64,
    },
    /// Faigl & Kulich's representatives of free edges: k-means per free edge of at least
    /// `min_edge` cells, n_r = 1 + floor(|F| / (1.8 ρ) + 0.5) representatives each.
    Rfe {
        /// n_f: the smallest free edge kept, in cells.
        min_edge: usize,
    },
    /// Faigl & Kulich's Algorithm 1: a greedy set cover of the frontier cells by cells that
    /// see them within 0.8 ρ.
    Coverage,
    /// González-Baños & Latombe's samples near frontiers, scored by information gain.
    DtSamples {
        /// Number of sampled poses.
        n: usize,
    },
}

impl CandidateKind {
    /// The shortest sensor range, in cells, these candidates can be found with: Faigl &
    /// Kulich's cover looks from within 0.8 of the range, which must reach the cell next
    /// to a frontier cell (0 for the others).
    pub fn min_range_cells(self) -> f64 {
        match self {
            CandidateKind::Coverage => 1.0 / coverage::COVER_FRACTION,
            _ => 0.0,
        }
    }

    /// Fill `out` with the candidates of this kind for the current decision.
    pub fn generate(&self, ctx: &mut DecisionCtx<'_>, out: &mut CandidateSet) {
        out.clear();
        match *self {
            CandidateKind::AllFrontiers => all_frontiers::generate(ctx, out),
            CandidateKind::RegionCentroids { min_size_m } => {
                let min_cells = grid::units::cells(min_size_m, ctx.resolution)
                    .ceil()
                    .max(1.0) as usize;
                centroids::generate(ctx, min_cells, out)
            }
            CandidateKind::Rfe { min_edge } => rfe::generate(ctx, min_edge, out),
            CandidateKind::Coverage => coverage::generate(ctx, out),
            CandidateKind::DtSamples { n } => dt_samples::generate(ctx, n, out),
        }
    }

    /// Bytes this kind's kept scans may take on a map of `cells` cells of `resolution`
    /// metres with a sensor of `range_cells` cells, beside its per-cell arrays: only
    /// coverage candidates keep scans ([`coverage::scan_bytes_bound`]).
    pub fn scan_bytes_bound(&self, cells: usize, range_cells: f64, resolution: f64) -> u64 {
        match self {
            CandidateKind::Coverage => coverage::scan_bytes_bound(cells, range_cells, resolution),
            _ => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Inserts and clears in any order: the set holds what a list without duplicates
        /// holds, in insertion order, with the same positions.
        #[test]
        fn behaves_as_a_list_without_duplicates(
            ops in proptest::collection::vec((0u32..40, 0u8..8), 0..200)
        ) {
            let mut set = CandidateSet::new(40);
            let mut list: Vec<u32> = Vec::new();
            for (cell, op) in ops {
                if op == 0 {
                    set.clear();
                    list.clear();
                } else if !list.contains(&cell) {
                    set.insert(cell);
                    list.push(cell);
                } else {
                    set.insert(cell);
                }
                prop_assert_eq!(set.cells(), &list[..]);
                for c in 0..40 {
                    let at = list.iter().position(|&x| x == c);
                    prop_assert_eq!(set.contains(c as usize), at.is_some());
                    prop_assert_eq!(set.index_of(c as usize), at);
                }
            }
        }

        /// The same with positions asked only now and then, so that the lazily written
        /// positions catch up over many inserts and clears at once.
        #[test]
        fn positions_catch_up_after_many_inserts(
            ops in proptest::collection::vec((0u32..40, 0u8..12), 0..200)
        ) {
            let mut set = CandidateSet::new(40);
            let mut list: Vec<u32> = Vec::new();
            for (cell, op) in ops {
                match op {
                    0 => {
                        set.clear();
                        list.clear();
                    }
                    1 => {
                        for c in 0..40 {
                            let at = list.iter().position(|&x| x == c);
                            prop_assert_eq!(set.index_of(c as usize), at);
                        }
                    }
                    _ => {
                        if !list.contains(&cell) {
                            list.push(cell);
                        }
                        set.insert(cell);
                    }
                }
                prop_assert_eq!(set.cells(), &list[..]);
                for c in 0..40 {
                    prop_assert_eq!(set.contains(c as usize), list.contains(&c));
                }
            }
            for c in 0..40 {
                let at = list.iter().position(|&x| x == c);
                prop_assert_eq!(set.index_of(c as usize), at);
            }
        }
    }
}
