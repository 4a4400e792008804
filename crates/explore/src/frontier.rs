//! Frontier cells and frontier regions (Yamauchi 1997), as DESIGN.md defines them.
//!
//! A *frontier cell* is traversable (see [`Traversability`]) and has at least one Unknown
//! 8-neighbour; cells outside the grid are not Unknown. A *frontier region* (Holz et al.'s
//! "free edge") is an 8-connected component of frontier cells. Reachability from the robot is
//! left to the planner ([`crate::plan::Reachability`]).
//!
//! This file holds the definitions, the sparse [`FrontierSet`] that the incremental upkeep
//! ([`crate::upkeep::FrontierUpkeep`]) maintains, and the from-scratch detector used as its
//! test oracle.

use crate::traversability::Traversability;
use grid::{Grid, NEIGHBOURS8, Occ};

/// Marker for "not in the set" in [`FrontierSet`]'s position array: zero, so that a new
/// set is a zeroed allocation (pages the operating system maps on first touch).
const ABSENT: u32 = 0;

/// A sparse set of flat cell indices: O(1) insert, remove and membership, cells as a slice.
#[derive(Clone, Debug)]
pub struct FrontierSet {
    /// One more than the position of each cell in `dense`, or `ABSENT`.
    pos: Vec<u32>,
    /// The members, in insertion order modified by swap-remove.
    dense: Vec<u32>,
}

impl FrontierSet {
    /// An empty set over a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            pos: vec![ABSENT; width * height],
            dense: Vec::new(),
        }
    }

    /// Whether cell `i` is in the set (false outside the grid).
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.pos.get(i).is_some_and(|&p| p != ABSENT)
    }

    /// Add cell `i`; returns whether it was newly added (false if present or outside the grid).
    #[inline]
    pub fn insert(&mut self, i: usize) -> bool {
        match self.pos.get_mut(i) {
            Some(p) if *p == ABSENT => {
                self.dense.push(i as u32);
                *p = self.dense.len() as u32;
                true
            }
            _ => false,
        }
    }

    /// Remove cell `i`; returns whether it was present. The last member takes its place.
    #[inline]
    pub fn remove(&mut self, i: usize) -> bool {
        let Some(&p) = self.pos.get(i) else {
            return false;
        };
        if p == ABSENT {
            return false;
        }
        let (k, last) = (p as usize - 1, self.dense.len() - 1);
        self.dense.swap_remove(k);
        if k < last {
            let moved = self.dense[k] as usize;
            self.pos[moved] = p;
        }
        self.pos[i] = ABSENT;
        true
    }

    /// Remove every member (cost ∝ members).
    pub fn clear(&mut self) {
        for &c in &self.dense {
            self.pos[c as usize] = ABSENT;
        }
        self.dense.clear();
    }

    /// The members (insertion order with swap-remove: deterministic, not sorted).
    #[inline]
    pub fn cells(&self) -> &[u32] {
        &self.dense
    }

    /// Number of members.
    #[inline]
    pub fn len(&self) -> usize {
        self.dense.len()
    }

    /// Whether the set is empty.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.dense.is_empty()
    }
}

/// Whether cell `i` is a frontier cell: traversable with at least one Unknown in-grid
/// 8-neighbour that is not behind a corner squeeze.
///
/// Deviation from the papers' "adjacent to an unknown cell": a diagonal unknown neighbour
/// whose two cells sharing the vertex are both occupied does not count. Motion never
/// squeezes between two blocked cells sharing a vertex and the line-of-sight sensor never
/// sees through such a vertex, so that neighbour can never be entered or seen from here;
/// counting it would leave a permanent phantom frontier at every inner wall corner.
pub fn is_frontier(known: &Grid<Occ>, trav: &Traversability, i: usize) -> bool {
    let w = known.width().max(1);
    is_frontier_xy(known, trav, i, (i % w) as i32, (i / w) as i32)
}

/// [`is_frontier`] for cell `i` at column `x`, row `y` (saves the division in hot loops).
#[inline]
pub(crate) fn is_frontier_xy(
    known: &Grid<Occ>,
    trav: &Traversability,
    i: usize,
    x: i32,
    y: i32,
) -> bool {
    if !trav.is_traversable(known, i) {
        return false;
    }
    let (w, h) = (known.width() as i32, known.height() as i32);
    let data = known.data();
    NEIGHBOURS8.iter().any(|&(dx, dy)| {
        let (nx, ny) = (x + dx, y + dy);
        if !(nx >= 0 && ny >= 0 && nx < w && ny < h && data[(ny * w + nx) as usize].is_unknown()) {
            return false;
        }
        // A diagonal neighbour behind a corner squeeze (both cells sharing the vertex are
        // occupied) is neither reachable nor visible from here: it does not count.
        dx == 0
            || dy == 0
            || !(data[(y * w + nx) as usize].is_occupied()
                && data[(ny * w + x) as usize].is_occupied())
    })
}

/// Every frontier cell of the map, sorted by flat index: the slow, obviously-correct oracle.
pub fn frontiers_from_scratch(known: &Grid<Occ>, trav: &Traversability) -> Vec<u32> {
    (0..known.len())
        .filter(|&i| is_frontier(known, trav, i))
        .map(|i| i as u32)
        .collect()
}

/// A frontier region: an 8-connected component of frontier cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// The region's cells, sorted by flat index.
    pub cells: Vec<u32>,
    /// Mean `(x, y)` of the cells' centres, in cells.
    pub centroid: (f64, f64),
    /// The region cell nearest the centroid (ties: lowest index).
    pub representative: u32,
}

impl Region {
    /// Fill `centroid` and `representative` from `cells` (sorted, non-empty) on a grid of
    /// `width` columns.
    pub(crate) fn finish(&mut self, width: usize) {
        let n = self.cells.len() as f64;
        let (mut sx, mut sy) = (0.0, 0.0);
        for &c in &self.cells {
            sx += (c as usize % width) as f64;
            sy += (c as usize / width) as f64;
        }
        let (cx, cy) = (sx / n, sy / n);
        self.centroid = (cx, cy);
        let mut best = f64::INFINITY;
        for &c in &self.cells {
            let dx = (c as usize % width) as f64 - cx;
            let dy = (c as usize / width) as f64 - cy;
            let d = dx * dx + dy * dy;
            if d < best {
                best = d;
                self.representative = c;
            }
        }
    }
}
