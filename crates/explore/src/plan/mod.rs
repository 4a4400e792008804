//! Grid planning: Holz et al.'s reachability map (Dijkstra with no goal), the nearest-goal
//! Dijkstra that stops at the first settled goal (Yamauchi's nearest frontier), and A*.
//!
//! Motion everywhere: 8-connected, straight step 1, diagonal √2; a diagonal step is forbidden
//! iff BOTH orthogonal cells it passes between fail `passable` ("no corner squeezing"). The start
//! cell is always allowed; every other cell on a path must pass `passable`. Ties are broken by
//! flat index: the priority-queue key is `(cost, index)`.

pub mod astar;
pub mod reachability;

pub use astar::AStar;
pub use reachability::Reachability;

use grid::SQRT2;
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

/// Call `f(j, step)` for every allowed move from cell `i` of a `width × height` grid to a
/// passable neighbour `j`, applying the no-corner-squeezing rule.
#[inline]
pub(crate) fn for_each_move(
    width: usize,
    height: usize,
    i: usize,
    passable: &impl Fn(usize) -> bool,
    mut f: impl FnMut(usize, f64),
) {
    let (x, y) = (i % width, i / width);
    let (left, right, up, down) = (x > 0, x + 1 < width, y > 0, y + 1 < height);
    let pr = right && passable(i + 1);
    let pd = down && passable(i + width);
    let pl = left && passable(i - 1);
    let pu = up && passable(i - width);
    if pr {
        f(i + 1, 1.0);
    }
    if pd {
        f(i + width, 1.0);
    }
    if pl {
        f(i - 1, 1.0);
    }
    if pu {
        f(i - width, 1.0);
    }
    if right && down && (pr || pd) && passable(i + width + 1) {
        f(i + width + 1, SQRT2);
    }
    if left && down && (pl || pd) && passable(i + width - 1) {
        f(i + width - 1, SQRT2);
    }
    if left && up && (pl || pu) && passable(i - width - 1) {
        f(i - width - 1, SQRT2);
    }
    if right && up && (pr || pu) && passable(i - width + 1) {
        f(i - width + 1, SQRT2);
    }
}
