//! Frontier cells and frontier regions (Yamauchi 1997), as defined below.
//!
//! A *frontier cell* is traversable (see [`Traversability`]) and has at least one Unknown
//! 8-neighbour; cells outside the grid are not Unknown. A *frontier region* (Holz et al.'s
//! "free edge") is an 8-connected component of frontier cells. Reachability from the robot is
//! left to the planner ([`crate::plan::Reachability`]).
//!
//! This file holds the definitions, the sparse [`FrontierSet`] that the incremental upkeep
//! ([`crate::upkeep::FrontierUpkeep`]) maintains, and the from-scratch detector used as its
//! test oracle.

use crate::bits::CellBits;
use crate::traversability::Traversability;
use grid::{Grid, NEIGHBOURS8, Occ};

/// A sparse set of flat cell indices: O(1) insert, remove and membership, cells as a slice.
///
/// Membership is one bit per cell ([`CellBits`]). The position of each member in the
/// slice, which only removal needs, is an array of the map's size written from the first
/// removal on: a set only filled and cleared (a map counted from scratch) touches the
/// pages of its bits and nothing else of the map's size.
#[derive(Clone, Debug)]
pub struct FrontierSet {
    members: CellBits,
    /// One more than the position of each member in `dense` (empty until a removal).
    pos: Vec<u32>,
    /// The members, in insertion order modified by swap-remove.
    dense: Vec<u32>,
}

impl FrontierSet {
    /// An empty set over a `width × height` grid.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            members: CellBits::new(width * height),
            pos: Vec::new(),
            dense: Vec::new(),
        }
    }

    /// Whether cell `i` is in the set (false outside the grid).
    #[inline]
    pub fn contains(&self, i: usize) -> bool {
        self.members.contains(i)
    }

    /// Add cell `i`; returns whether it was newly added (false if present or outside the grid).
    #[inline]
    pub fn insert(&mut self, i: usize) -> bool {
        if i >= self.members.len() || self.members.contains(i) {
            return false;
        }
        self.members.insert(i);
        self.dense.push(i as u32);
        if !self.pos.is_empty() {
            self.pos[i] = self.dense.len() as u32;
        }
        true
    }

    /// Remove cell `i`; returns whether it was present. The last member takes its place.
    #[inline(always)]
    pub fn remove(&mut self, i: usize) -> bool {
        if !self.members.contains(i) {
            return false;
        }
        if self.pos.is_empty() {
            self.write_positions();
        }
        let p = self.pos[i];
        let (k, last) = (p as usize - 1, self.dense.len() - 1);
        self.dense.swap_remove(k);
        if k < last {
            let moved = self.dense[k] as usize;
            self.pos[moved] = p;
        }
        self.members.remove(i);
        true
    }

    /// Allocate the position array and write every member's position (the first removal;
    /// out of line, so that the removal stays small enough to inline).
    #[cold]
    #[inline(never)]
    fn write_positions(&mut self) {
        self.pos = vec![0; self.members.len()];
        for (k, &c) in self.dense.iter().enumerate() {
            self.pos[c as usize] = k as u32 + 1;
        }
    }

    /// Remove every member (cost ∝ members).
    pub fn clear(&mut self) {
        for &c in &self.dense {
            self.members.remove(c as usize);
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

    /// Cells `from..from + out.len()` as bytes, 1 for a member and 0 otherwise (a row of a
    /// frontier layer; [`CellBits::bytes_into`]).
    pub fn bytes_into(&self, from: usize, out: &mut [u8]) {
        self.members.bytes_into(from, out);
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Inserts, removes and clears in any order: the set holds what a list with
        /// swap-remove holds, in the same order (removal builds the positions lazily).
        #[test]
        fn behaves_as_a_list_with_swap_remove(
            ops in proptest::collection::vec((0usize..50, 0u8..6), 0..300)
        ) {
            let mut set = FrontierSet::new(8, 6);
            let mut list: Vec<u32> = Vec::new();
            for (i, op) in ops {
                let at = list.iter().position(|&c| c as usize == i);
                match op {
                    0 => {
                        set.clear();
                        list.clear();
                    }
                    1 | 2 => {
                        prop_assert_eq!(set.remove(i), at.is_some());
                        if let Some(k) = at {
                            list.swap_remove(k);
                        }
                    }
                    _ => {
                        let fresh = i < 48 && at.is_none();
                        prop_assert_eq!(set.insert(i), fresh);
                        if fresh {
                            list.push(i as u32);
                        }
                    }
                }
                prop_assert_eq!(set.cells(), &list[..]);
                prop_assert_eq!(set.len(), list.len());
                for c in 0..50 {
                    prop_assert_eq!(set.contains(c), list.contains(&(c as u32)));
                }
            }
        }
    }
}
