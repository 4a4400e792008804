//! Grid planning: Holz et al.'s reachability map (Dijkstra with no goal, on a bucket queue),
//! the nearest-goal Dijkstra that stops at the first settled goal (Yamauchi's nearest
//! frontier), the same search resumed bucket by bucket (costs only as far as a decision
//! needs them), a flood fill for reachability without costs, and A* (on a binary heap).
//!
//! Motion everywhere: 8-connected, straight step 1, diagonal √2; a diagonal step is forbidden
//! iff BOTH orthogonal cells it passes between fail `passable` ("no corner squeezing"). The start
//! cell is always allowed; every other cell on a path must pass `passable`. Ties are broken by
//! flat index: the priority is `(cost, index)` (the bucket queue gives the same results).

pub mod astar;
pub mod component;
pub mod guide;
pub mod reachability;

pub use astar::AStar;
pub use component::Component;
pub use reachability::Reachability;

use std::cmp::Reverse;

/// Priority-queue entry: `Reverse((key bits, index))`, a min-heap on `(key, index)`. Keys are
/// non-negative finite `f64`s, whose bit patterns order like their values.
pub(crate) type HeapEntry = Reverse<(u64, u32)>;

/// The min-heap entry for `key` (≥ 0) and cell `i`.
#[inline]
pub(crate) fn entry(key: f64, i: usize) -> HeapEntry {
    debug_assert!(key >= 0.0);
    Reverse((key.to_bits(), i as u32))
}
