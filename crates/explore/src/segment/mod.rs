//! Room segmentation of partial maps (Holz et al. 2010 §2.4, Figure 7).
//!
//! The pipeline follows Figure 7, one step per file:
//!
//! 1. [`skeleton`] and [`graph`]: the Voronoi diagram of free space as a one-cell-wide
//!    skeleton of the distance transform, turned into a graph of nodes (junctions, end
//!    points) with degree and clearance;
//! 2. [`critical`]: critical points — local minima of clearance of degree 2 — under one of
//!    three rules ([`Rule`]);
//! 3. and 4. [`regions`]: two seeds per critical point, every free cell to its nearest seed;
//! 5. and 6. [`merge`]: the split graph and the iterative merge of adjacent segments that do
//!    not come from the same split point.
//!
//! [`cache`] keeps a segmentation between decisions ([`State`]) and [`score`] compares a
//! segmentation with ground-truth rooms.
//!
//! Partial maps: only known free cells are segmented; unknown cells count as not free (as
//! walls) for the distance transform and the skeleton. A room seen only in part is
//! segmented as far as it is seen, and a doorway into unseen space is not a narrowing yet —
//! the split appears once the space behind it has been seen wide enough.
//!
//! Everything is deterministic (index order, no hash maps) and reuses its buffers.

pub mod cache;
pub mod critical;
pub mod graph;
pub mod merge;
pub mod regions;
pub mod score;
pub mod skeleton;

use grid::{Grid, Occ};

pub use cache::State;
pub use critical::CriticalPoint;
pub use graph::{NONE, VoronoiGraph};
pub use skeleton::Skeleton;

/// Which critical points split the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Rule {
    /// Holz's relaxed rule: adjacent to a junction or to a node adjacent to one.
    #[default]
    Holz,
    /// Wurm et al.: adjacent to a junction.
    Wurm,
    /// Thrun: any local minimum of clearance of degree 2.
    Thrun,
}

impl Rule {
    /// All rules, for comparisons.
    pub const ALL: [Rule; 3] = [Rule::Holz, Rule::Wurm, Rule::Thrun];

    /// Lower-case name (`holz`, `wurm`, `thrun`).
    pub fn name(self) -> &'static str {
        match self {
            Rule::Holz => "holz",
            Rule::Wurm => "wurm",
            Rule::Thrun => "thrun",
        }
    }
}

impl std::str::FromStr for Rule {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "holz" => Ok(Rule::Holz),
            "wurm" => Ok(Rule::Wurm),
            "thrun" => Ok(Rule::Thrun),
            _ => Err(format!(
                "unknown segmentation rule '{s}': expected holz, wurm or thrun"
            )),
        }
    }
}

/// A segmentation of the free cells of a map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Segmentation {
    /// Grid width.
    pub width: usize,
    /// Grid height.
    pub height: usize,
    /// Segment id per cell, `0..count`; [`NONE`] for cells that are not free.
    pub labels: Vec<u32>,
    /// Number of segments.
    pub count: u32,
    /// The critical points that split the map.
    pub critical: Vec<CriticalPoint>,
}

impl Segmentation {
    /// The segment of cell `i`, if it is a segmented free cell.
    #[inline]
    pub fn label(&self, i: usize) -> Option<u32> {
        self.labels.get(i).copied().filter(|&l| l != NONE)
    }

    /// How many other segments each segment touches (through 4-adjacent free cells), into
    /// `out` (one entry per segment); `keys` is scratch reused between calls.
    ///
    /// A room has one or two neighbours (its doors), a corridor or hall many: this is what
    /// Seg's room preference reads ([`crate::assign::segment_first`]).
    pub fn neighbour_counts(&self, keys: &mut Vec<u64>, out: &mut Vec<u32>) {
        self.neighbour_pairs(keys);
        out.clear();
        out.resize(self.count as usize, 0);
        for &k in keys.iter() {
            out[(k >> 32) as usize] += 1;
            out[(k & 0xffff_ffff) as usize] += 1;
        }
    }

    /// The pairs of segments that touch (4-adjacent free cells), as sorted, deduplicated
    /// keys `min << 32 | max`, into `keys`.
    pub fn neighbour_pairs(&self, keys: &mut Vec<u64>) {
        let all = cache::Window {
            x0: 0,
            y0: 0,
            w: self.width,
            h: self.labels.len() / self.width.max(1),
        };
        self.neighbour_pairs_within(all, keys);
    }

    /// [`neighbour_pairs`](Self::neighbour_pairs) when every labelled cell lies in `win`.
    pub(crate) fn neighbour_pairs_within(&self, win: cache::Window, keys: &mut Vec<u64>) {
        keys.clear();
        let (w, n) = (self.width, self.labels.len());
        for y in win.rows() {
            for i in win.columns().map(|x| y * w + x) {
                let a = self.labels[i];
                if a == NONE {
                    continue;
                }
                let right = (i % w + 1 < w).then(|| i + 1);
                let down = (i + w < n).then(|| i + w);
                for j in [right, down].into_iter().flatten() {
                    let b = self.labels[j];
                    if b != NONE && b != a {
                        keys.push(pair_key(a, b));
                    }
                }
            }
        }
        keys.sort_unstable();
        keys.dedup();
    }

    /// Number of cells of each segment.
    pub fn sizes(&self) -> Vec<usize> {
        let mut s = vec![0; self.count as usize];
        for &l in &self.labels {
            if l != NONE {
                s[l as usize] += 1;
            }
        }
        s
    }
}

/// The key of the unordered segment pair `{a, b}`.
pub(crate) fn pair_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

/// All buffers of the segmentation pipeline, reused across calls.
#[derive(Clone, Debug, Default)]
pub struct Segmenter {
    /// The skeleton of the last map segmented.
    pub skeleton: Skeleton,
    /// Its Voronoi graph.
    pub graph: VoronoiGraph,
    finder: critical::Finder,
    assigner: regions::Assigner,
    merger: merge::Merger,
    result: Segmentation,
}

impl Segmenter {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Segment the free cells of `known` with critical points under `rule`.
    pub fn run(&mut self, known: &Grid<Occ>, rule: Rule) -> &Segmentation {
        self.skeleton.compute(known);
        self.graph.build(&self.skeleton);
        let r = &mut self.result;
        self.finder
            .find(&self.skeleton, &self.graph, rule, &mut r.critical);
        let initial = self.assigner.assign(known, &r.critical, &mut r.labels);
        r.count = self
            .merger
            .merge(known.width(), &mut r.labels, initial, r.critical.len());
        r.width = known.width();
        r.height = known.height();
        &self.result
    }

    /// The last segmentation computed.
    pub fn result(&self) -> &Segmentation {
        &self.result
    }
}

/// Segment the free cells of `known` (allocating fresh buffers).
pub fn segment(known: &Grid<Occ>, rule: Rule) -> Segmentation {
    let mut s = Segmenter::new();
    s.run(known, rule);
    s.result
}
