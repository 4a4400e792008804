//! Connected components of a set of cells: 4-, 8- and motion-connected labelling and flood fill.
//!
//! The set is given by a predicate `inside(i)` over flat row-major indices of a
//! `width × height` grid. Three neighbourhoods are offered ([`Connectivity`]):
//!
//! - [`Connectivity::Four`]: the 4 straight neighbours;
//! - [`Connectivity::Eight`]: all 8 neighbours;
//! - [`Connectivity::Motion`]: the 8 neighbours, but a diagonal step is only allowed when at
//!   least one of the two straight cells it passes between is inside too — the project-wide
//!   "no corner squeezing" rule of 8-connected robot motion.
//!
//! All three relations are symmetric, so "reachable from" is an equivalence and the
//! components are well defined. Cells outside the grid count as outside the set.
//!
//! Motion components are exactly the 4-connected components (an allowed diagonal step can
//! always be replaced by two straight steps through the free side cell), but a motion flood
//! visits cells in a different order; `Motion` is offered so callers can say what they mean.
//!
//! ```
//! use grid::components::{Connectivity, label};
//! // two free cells touching only at a corner:
//! // .#
//! // #.
//! let free = [true, false, false, true];
//! let (_, n8) = label(2, 2, |i| free[i], Connectivity::Eight);
//! let (_, nm) = label(2, 2, |i| free[i], Connectivity::Motion);
//! assert_eq!((n8, nm), (1, 2));
//! ```

use crate::cell::{NEIGHBOURS4, NEIGHBOURS8};
use crate::grid::Grid;

/// Which cells count as neighbours when growing a component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Connectivity {
    /// The 4 straight neighbours.
    Four,
    /// All 8 neighbours, diagonals unconditionally.
    Eight,
    /// 8 neighbours, a diagonal only if not both straight cells beside it are outside.
    Motion,
}

impl Connectivity {
    /// The neighbour offsets this connectivity considers (before the motion rule).
    fn offsets(self) -> &'static [(i32, i32)] {
        match self {
            Connectivity::Four => &NEIGHBOURS4,
            Connectivity::Eight | Connectivity::Motion => &NEIGHBOURS8,
        }
    }
}

/// Whether the step from `(x, y)` by `(dx, dy)` stays in the grid and reaches a cell inside the
/// set under `conn`; `inside` is asked only about in-grid indices.
#[inline]
fn step_ok(
    width: usize,
    height: usize,
    x: usize,
    y: usize,
    (dx, dy): (i32, i32),
    conn: Connectivity,
    inside: &impl Fn(usize) -> bool,
) -> Option<usize> {
    let nx = x.checked_add_signed(dx as isize).filter(|&v| v < width)?;
    let ny = y.checked_add_signed(dy as isize).filter(|&v| v < height)?;
    let j = ny * width + nx;
    if !inside(j) {
        return None;
    }
    if conn == Connectivity::Motion && dx != 0 && dy != 0 {
        // the two straight cells beside the diagonal step are (nx, y) and (x, ny); both are
        // inside the grid because nx and ny are
        if !inside(y * width + nx) && !inside(ny * width + x) {
            return None;
        }
    }
    Some(j)
}

/// Label the components of `{i : inside(i)}` in a `width × height` grid.
///
/// Returns the labels (0 = outside the set, components numbered `1..=count` in row-major
/// order of their first cell) and `count`.
pub fn label(
    width: usize,
    height: usize,
    inside: impl Fn(usize) -> bool,
    conn: Connectivity,
) -> (Grid<u32>, u32) {
    let mut labels = Grid::new(width, height, 0u32);
    let mut stack = Vec::new();
    let count = label_into(width, height, inside, conn, &mut labels, &mut stack);
    (labels, count)
}

/// As [`label`], writing into `labels` (resized to `width × height` if needed) and using
/// `stack` as scratch, so repeated labelling need not allocate. Returns the count.
pub fn label_into(
    width: usize,
    height: usize,
    inside: impl Fn(usize) -> bool,
    conn: Connectivity,
    labels: &mut Grid<u32>,
    stack: &mut Vec<usize>,
) -> u32 {
    if labels.width() != width || labels.height() != height {
        *labels = Grid::new(width, height, 0);
    }
    if conn != Connectivity::Eight {
        // Motion components are the 4-connected ones (module docs).
        return label_runs(width, inside, labels.data_mut(), stack);
    }
    // mark the set once with UNSEEN so the search below never calls `inside` again
    const UNSEEN: u32 = u32::MAX;
    for (i, l) in labels.data_mut().iter_mut().enumerate() {
        *l = if inside(i) { UNSEEN } else { 0 };
    }
    let data = labels.data_mut();
    let offsets = conn.offsets();
    let mut count = 0u32;
    for seed in 0..data.len() {
        if data[seed] != UNSEEN {
            continue;
        }
        count += 1;
        data[seed] = count;
        stack.clear();
        stack.push(seed);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % width, i / width);
            for &off in offsets {
                let inside_now = |j: usize| data[j] != 0;
                if let Some(j) = step_ok(width, height, x, y, off, conn, &inside_now)
                    && data[j] == UNSEEN
                {
                    data[j] = count;
                    stack.push(j);
                }
            }
        }
    }
    count
}

/// [`label_into`] for 4-connected components, by runs: each row's runs of cells in the set
/// get provisional ids, joined (union–find in `parent`) with the runs they touch in the row
/// above; then every run takes its component's number, in row-major order of the
/// components' first cells. `inside` is asked once per cell, in order, and no cell is
/// pushed on a stack: several times faster than the search on floor plans.
fn label_runs(
    width: usize,
    inside: impl Fn(usize) -> bool,
    data: &mut [u32],
    parent: &mut Vec<usize>,
) -> u32 {
    fn root(parent: &mut [usize], mut r: usize) -> usize {
        while parent[r] != r {
            parent[r] = parent[parent[r]];
            r = parent[r];
        }
        r
    }
    parent.clear();
    // Pass 1: provisional ids (run id + 1), then unions of each run with those it touches
    // in the row above.
    for (y, row) in (0..data.len()).step_by(width.max(1)).enumerate() {
        let mut start = None;
        for x in 0..=width {
            let open = x < width && inside(row + x);
            match (open, start) {
                (true, None) => {
                    parent.push(parent.len());
                    start = Some(x);
                }
                (false, Some(s)) if y > 0 => {
                    let id = parent.len() - 1;
                    let above = &data[row - width..row];
                    for ax in s..x {
                        let a = above[ax];
                        // once per run above: at its first cell over this run
                        if a != 0 && (ax == s || above[ax - 1] != a) {
                            let (ra, rb) = (root(parent, a as usize - 1), root(parent, id));
                            parent[ra.max(rb)] = ra.min(rb);
                        }
                    }
                }
                _ => {}
            }
            if !open {
                start = None;
            }
            if x < width {
                data[row + x] = if open { parent.len() as u32 } else { 0 };
            }
        }
    }
    // Pass 2: component numbers by first appearance (a root is its component's first run).
    let mut number = vec![0u32; parent.len()];
    let mut count = 0u32;
    let mut last = (0u32, 0u32); // (provisional id, number) of the run being read
    for d in data.iter_mut() {
        if *d == 0 {
            continue;
        }
        if *d != last.0 {
            let r = root(parent, *d as usize - 1);
            if number[r] == 0 {
                count += 1;
                number[r] = count;
            }
            last = (*d, number[r]);
        }
        *d = last.1;
    }
    count
}

/// Number of cells with each label: `sizes[l]` for `l` in `0..=count` (`sizes[0]` counts the
/// cells outside the set), so a label indexes the result directly. Labels above `count` are
/// ignored.
pub fn component_sizes(labels: &Grid<u32>, count: u32) -> Vec<usize> {
    let mut sizes = vec![0usize; count as usize + 1];
    for &l in labels.data() {
        if let Some(s) = sizes.get_mut(l as usize) {
            *s += 1;
        }
    }
    sizes
}

/// The label of the largest component given [`component_sizes`] (ties: the smallest label),
/// or `None` if there is no component.
pub fn largest(sizes: &[usize]) -> Option<u32> {
    let mut best: Option<(u32, usize)> = None;
    for (l, &s) in sizes.iter().enumerate().skip(1) {
        if best.is_none_or(|(_, bs)| s > bs) {
            best = Some((l as u32, s));
        }
    }
    best.map(|(l, _)| l)
}

/// Reusable buffers for flood fills from single cells, so repeated fills do not allocate.
///
/// Visited cells are marked with a generation stamp, so starting a new fill costs nothing.
#[derive(Clone, Debug, Default)]
pub struct FloodFill {
    /// `stamp[i] == generation` iff cell `i` was reached in the current fill.
    stamp: Vec<u32>,
    /// Stamp of the current fill.
    generation: u32,
}

impl FloodFill {
    /// An empty flood filler; buffers grow on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// Write into `out` the flat indices of all cells reachable from `start` through cells of
    /// `{i : inside(i)}` under `conn`, in breadth-first order starting with `start`.
    ///
    /// `out` is cleared first; it stays empty if `start` is outside the grid or the set.
    pub fn run(
        &mut self,
        width: usize,
        height: usize,
        start: usize,
        inside: impl Fn(usize) -> bool,
        conn: Connectivity,
        out: &mut Vec<usize>,
    ) {
        self.run_first(width, height, start, inside, conn, usize::MAX, out);
    }

    /// The first `count` cells of [`run`](Self::run)'s order (all if fewer): the fill stops
    /// there.
    #[allow(clippy::too_many_arguments)]
    pub fn run_first(
        &mut self,
        width: usize,
        height: usize,
        start: usize,
        inside: impl Fn(usize) -> bool,
        conn: Connectivity,
        count: usize,
        out: &mut Vec<usize>,
    ) {
        out.clear();
        if count == 0 {
            return;
        }
        let n = width.saturating_mul(height);
        if start >= n || !inside(start) {
            return;
        }
        if self.stamp.len() < n {
            self.stamp.resize(n, 0);
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            // stamps wrapped around: forget every old mark
            self.stamp.fill(0);
            self.generation = 1;
        }
        let g = self.generation;
        self.stamp[start] = g;
        out.push(start);
        let mut head = 0;
        while head < out.len() && out.len() < count {
            let i = out[head];
            head += 1;
            let (x, y) = (i % width, i / width);
            for &off in conn.offsets() {
                if let Some(j) = step_ok(width, height, x, y, off, conn, &inside)
                    && self.stamp[j] != g
                {
                    self.stamp[j] = g;
                    out.push(j);
                    if out.len() == count {
                        return;
                    }
                }
            }
        }
    }
}

/// Write into `out` the cells reachable from `start` (see [`FloodFill::run`]); allocates its
/// visited marks, so use a [`FloodFill`] when filling repeatedly.
pub fn flood(
    width: usize,
    height: usize,
    start: usize,
    inside: impl Fn(usize) -> bool,
    conn: Connectivity,
    out: &mut Vec<usize>,
) {
    FloodFill::new().run(width, height, start, inside, conn, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Slow oracle: repeated relaxation of "smallest index in my component" until nothing
    /// changes, using the adjacency relation written out directly from its definition.
    fn oracle(width: usize, height: usize, set: &[bool], conn: Connectivity) -> Vec<usize> {
        let n = width * height;
        let at = |x: i64, y: i64| -> bool {
            x >= 0
                && y >= 0
                && (x as usize) < width
                && (y as usize) < height
                && set[y as usize * width + x as usize]
        };
        let adjacent = |a: usize, b: usize| -> bool {
            let (ax, ay) = ((a % width) as i64, (a / width) as i64);
            let (bx, by) = ((b % width) as i64, (b / width) as i64);
            let (dx, dy) = (bx - ax, by - ay);
            if !set[a] || !set[b] || a == b || dx.abs() > 1 || dy.abs() > 1 {
                return false;
            }
            let diagonal = dx != 0 && dy != 0;
            match conn {
                Connectivity::Four => !diagonal,
                Connectivity::Eight => true,
                Connectivity::Motion => !diagonal || at(bx, ay) || at(ax, by),
            }
        };
        let mut rep: Vec<usize> = (0..n).collect();
        loop {
            let mut changed = false;
            for a in 0..n {
                for b in 0..n {
                    if adjacent(a, b) && rep[b] < rep[a] {
                        rep[a] = rep[b];
                        changed = true;
                    }
                }
            }
            if !changed {
                return rep;
            }
        }
    }

    fn conn_strategy() -> impl Strategy<Value = Connectivity> {
        prop_oneof![
            Just(Connectivity::Four),
            Just(Connectivity::Eight),
            Just(Connectivity::Motion)
        ]
    }

    fn map_strategy() -> impl Strategy<Value = (usize, usize, Vec<bool>)> {
        (1usize..=12, 1usize..=12).prop_flat_map(|(w, h)| {
            (
                Just(w),
                Just(h),
                proptest::collection::vec(proptest::bool::weighted(0.6), w * h),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn label_matches_oracle((w, h, set) in map_strategy(), conn in conn_strategy()) {
            let (labels, count) = label(w, h, |i| set[i], conn);
            let rep = oracle(w, h, &set, conn);
            // same partition: two set cells share a label iff they share an oracle representative
            for a in 0..w * h {
                prop_assert_eq!(labels[a] == 0, !set[a]);
                for b in 0..w * h {
                    if set[a] && set[b] {
                        prop_assert_eq!(labels[a] == labels[b], rep[a] == rep[b], "{} {}", a, b);
                    }
                }
            }
            // numbering: 1..=count in row-major order of first cell
            let mut next = 1u32;
            for a in 0..w * h {
                if set[a] && rep[a] == a {
                    prop_assert_eq!(labels[a], next);
                    next += 1;
                }
            }
            prop_assert_eq!(count, next - 1);
            let sizes = component_sizes(&labels, count);
            prop_assert_eq!(sizes.len(), count as usize + 1);
            prop_assert_eq!(sizes[0], set.iter().filter(|&&s| !s).count());
            for l in 1..=count {
                prop_assert_eq!(sizes[l as usize], labels.data().iter().filter(|&&v| v == l).count());
            }
        }

        #[test]
        fn motion_components_are_four_components((w, h, set) in map_strategy()) {
            let (l4, n4) = label(w, h, |i| set[i], Connectivity::Four);
            let (lm, nm) = label(w, h, |i| set[i], Connectivity::Motion);
            prop_assert_eq!(n4, nm);
            prop_assert_eq!(l4, lm);
        }

        #[test]
        fn flood_matches_oracle(
            (w, h, set) in map_strategy(),
            conn in conn_strategy(),
            start_frac in 0.0f64..1.0,
        ) {
            let start = ((w * h) as f64 * start_frac) as usize;
            let rep = oracle(w, h, &set, conn);
            let mut out = Vec::new();
            let mut ff = FloodFill::new();
            // run twice with the same filler to exercise stamp reuse
            for _ in 0..2 {
                ff.run(w, h, start, |i| set[i], conn, &mut out);
                let mut got = out.clone();
                got.sort_unstable();
                let want: Vec<usize> = if set[start] {
                    (0..w * h).filter(|&b| set[b] && rep[b] == rep[start]).collect()
                } else {
                    Vec::new()
                };
                prop_assert_eq!(&got, &want);
                if !out.is_empty() {
                    prop_assert_eq!(out[0], start);
                }
            }
            let mut out2 = Vec::new();
            flood(w, h, start, |i| set[i], conn, &mut out2);
            prop_assert_eq!(&out, &out2);
            // stopped early: the same order's first cells
            for count in 0..=out.len() + 1 {
                ff.run_first(w, h, start, |i| set[i], conn, count, &mut out2);
                prop_assert_eq!(&out2[..], &out[..count.min(out.len())]);
            }
        }
    }

    #[test]
    fn worked_example() {
        // #.#..
        // .#...
        // #..#.
        let rows = ["#.#..", ".#...", "#..#."];
        let set: Vec<bool> = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| b == b'.'))
            .collect();
        let (l4, n4) = label(5, 3, |i| set[i], Connectivity::Four);
        assert_eq!(n4, 3);
        assert_eq!(
            l4.data(),
            &[0, 1, 0, 2, 2, 3, 0, 2, 2, 2, 0, 2, 2, 0, 2],
            "4-connected labels"
        );
        let (_, n8) = label(5, 3, |i| set[i], Connectivity::Eight);
        assert_eq!(n8, 1);
        // (1,0) touches (0,1) only at a corner squeezed between two walls: its own component;
        // (1,0) to (2,1) passes (2,0)# and (1,1)# — also squeezed
        let (lm, nm) = label(5, 3, |i| set[i], Connectivity::Motion);
        assert_eq!(nm, 3);
        assert_eq!(lm.data(), &[0, 1, 0, 2, 2, 3, 0, 2, 2, 2, 0, 2, 2, 0, 2]);
        let sizes = component_sizes(&lm, nm);
        assert_eq!(sizes, vec![5, 1, 8, 1]);
        assert_eq!(largest(&sizes), Some(2));
        assert_eq!(largest(&[4]), None);
    }

    #[test]
    fn flood_from_outside_is_empty() {
        let mut out = vec![7];
        flood(3, 3, 4, |_| false, Connectivity::Eight, &mut out);
        assert!(out.is_empty());
        flood(3, 3, 99, |_| true, Connectivity::Eight, &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn label_into_resizes_and_reuses() {
        let mut labels = Grid::new(1, 1, 9u32);
        let mut stack = Vec::new();
        let n = label_into(
            4,
            2,
            |i| i != 1 && i != 5,
            Connectivity::Four,
            &mut labels,
            &mut stack,
        );
        assert_eq!(n, 2);
        assert_eq!(labels.data(), &[1, 0, 2, 2, 1, 0, 2, 2]);
    }
}
