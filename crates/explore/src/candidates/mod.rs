//! Goal candidates: which cells a strategy may send a robot to.
//!
//! One file per kind: all frontier cells (Holz's closest frontier, seed 002, Faigl's AF)
//! and region centroids (Yamauchi).

pub mod all_frontiers;
pub mod centroids;

use crate::decision::DecisionCtx;

/// A set of goal candidates with O(1) membership, reused across decisions.
#[derive(Clone, Debug, Default)]
pub struct CandidateSet {
    cells: Vec<u32>,
    mark: Vec<u32>,
    generation: u32,
}

impl CandidateSet {
    /// An empty set for a map of `len` cells.
    pub fn new(len: usize) -> Self {
        Self {
            cells: Vec::new(),
            mark: vec![0; len],
            generation: 1,
        }
    }

    /// Empty the set in O(1) (amortised).
    pub fn clear(&mut self) {
        self.cells.clear();
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.mark.fill(0);
            self.generation = 1;
        }
    }

    /// Add `cell` (no effect if present).
    pub fn insert(&mut self, cell: u32) {
        let m = &mut self.mark[cell as usize];
        if *m != self.generation {
            *m = self.generation;
            self.cells.push(cell);
        }
    }

    /// Whether `cell` is a candidate.
    #[inline]
    pub fn contains(&self, cell: usize) -> bool {
        self.mark[cell] == self.generation
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
}

/// Which candidate generator a strategy uses.
#[derive(Clone, Debug, PartialEq)]
pub enum CandidateKind {
    /// Every frontier cell (AF).
    AllFrontiers,
    /// One goal per frontier region of at least `min_size_m` metres (counted in cells along
    /// the region): its centroid snapped to the nearest reachable cell of the region.
    RegionCentroids {
        /// Minimum region size in metres (Yamauchi: roughly the robot's size).
        min_size_m: f64,
    },
}

impl CandidateKind {
    /// Fill `out` with the candidates of this kind for the current decision.
    pub fn generate(
        &self,
        ctx: &mut DecisionCtx<'_>,
        out: &mut CandidateSet,
        scratch: &mut centroids::Scratch,
    ) {
        out.clear();
        match self {
            CandidateKind::AllFrontiers => all_frontiers::generate(ctx, out),
            CandidateKind::RegionCentroids { min_size_m } => {
                let min_cells = (min_size_m / ctx.resolution).ceil().max(1.0) as usize;
                centroids::generate(ctx, min_cells, out, scratch)
            }
        }
    }
}
