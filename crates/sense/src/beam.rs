//! One beam's exact grid traversal (Amanatides & Woo, 1987), and the traversals of a
//! scanner's beams precomputed for the eight headings of a grid move.
//!
//! A beam leaving a cell's centre crosses column and row boundaries in an order that
//! depends only on its direction and range, not on the cell it leaves from. A robot that
//! moves cell by cell faces one of eight headings (the directions of its last move), so the
//! cells of each beam for those headings are found once, by the same walk, and stored as a
//! prefix tree ([`BeamTree`]): a scan replays them with no floating point and no choice of
//! the next boundary, and skips the rest of a beam (the subtree) at a cell that stops it.
//! The sharing itself is small: beams 1° apart part within a few cells, so at 160 cells'
//! range the tree holds 34,900 cells for the beams' 36,800; the replay is what saves time.
//! The tree holds the walk's own cells, so a scan sees the same cells, bit for bit.

use std::sync::{Arc, Mutex, OnceLock};

use grid::{Cell, Grid, Occ};

use crate::window::Window;

/// The most memory one heading's tree may take, counted as if no beam shared a cell (an
/// upper bound: at 160 cells' range, 181 beams take 466 KiB so counted, 280 KiB built); a
/// scanner whose trees would take more walks every beam afresh.
const MAX_TREE_BYTES: usize = 1 << 20;

/// How many values a [`KeptCache`] keeps (the scanners of one run or study share one).
const KEPT: usize = 8;

/// A process-wide cache of values by key, the last [`KEPT`] made.
pub(crate) type KeptCache<K, V> = OnceLock<Mutex<Vec<(K, Arc<V>)>>>;

/// The value of `cache` for `key`, made by `make` if the cache holds none (dropping the
/// oldest beyond [`KEPT`]).
pub(crate) fn kept<K: PartialEq, V>(
    cache: &KeptCache<K, V>,
    key: K,
    make: impl FnOnce() -> V,
) -> Arc<V> {
    let mut cache = cache
        .get_or_init(|| Mutex::new(Vec::new()))
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((_, v)) = cache.iter().find(|(k, _)| *k == key) {
        return Arc::clone(v);
    }
    let v = Arc::new(make());
    if cache.len() == KEPT {
        cache.remove(0);
    }
    cache.push((key, Arc::clone(&v)));
    v
}

/// The exact traversal of one beam from a cell's centre: the cells it enters, as offsets
/// from that cell, until the next one would be entered at `range` times the direction's
/// length or beyond (`range` cells for a unit direction).
#[derive(Clone, Copy, Debug)]
pub(crate) struct BeamWalk {
    delta_x: f64,
    delta_y: f64,
    t_x: f64,
    t_y: f64,
    range: f64,
    step_x: i64,
    step_y: i64,
    x: i64,
    y: i64,
}

impl BeamWalk {
    /// The walk along direction `(dx, dy)` up to `range` times its length.
    #[inline]
    pub(crate) fn new(dx: f64, dy: f64, range: f64) -> Self {
        let (delta_x, delta_y) = (1.0 / dx.abs(), 1.0 / dy.abs()); // ∞ along an axis
        Self {
            delta_x,
            delta_y,
            t_x: 0.5 * delta_x,
            t_y: 0.5 * delta_y,
            range,
            step_x: if dx < 0.0 { -1 } else { 1 },
            step_y: if dy < 0.0 { -1 } else { 1 },
            x: 0,
            y: 0,
        }
    }
}

impl Iterator for BeamWalk {
    type Item = (i64, i64);

    /// The offset of the next cell the beam enters, `None` once it lies at or beyond the
    /// range.
    #[inline]
    fn next(&mut self) -> Option<(i64, i64)> {
        if self.t_x < self.t_y {
            if self.t_x >= self.range {
                return None;
            }
            self.t_x += self.delta_x;
            self.x += self.step_x;
        } else {
            if self.t_y >= self.range {
                return None;
            }
            self.t_y += self.delta_y;
            self.y += self.step_y;
        }
        Some((self.x, self.y))
    }
}

/// The direction of a beam at angle `(c, s)` relative to a heading whose cosine and sine
/// are `(ch, sh)`: the one rotation every traversal of the scanner uses.
#[inline]
pub(crate) fn rotate((c, s): (f64, f64), ch: f64, sh: f64) -> (f64, f64) {
    (c * ch - s * sh, s * ch + c * sh)
}

/// The headings a robot faces after a grid move, `atan2(dy, dx)` of the eight moves, as the
/// simulation computes them.
pub(crate) fn compass_headings() -> &'static [f64; 8] {
    const MOVES: [(i32, i32); 8] = [
        (1, 0),
        (1, 1),
        (0, 1),
        (-1, 1),
        (-1, 0),
        (-1, -1),
        (0, -1),
        (1, -1),
    ];
    static HEADINGS: OnceLock<[f64; 8]> = OnceLock::new();
    HEADINGS.get_or_init(|| MOVES.map(|(dx, dy)| f64::from(dy).atan2(f64::from(dx))))
}

/// One cell of a [`BeamTree`]: its offset from the sensor cell and where its subtree ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BeamNode {
    /// Column offset from the sensor cell.
    pub dx: i16,
    /// Row offset from the sensor cell.
    pub dy: i16,
    /// Index just past this node's subtree: where a walk goes on when the cell stops beams.
    pub skip: u32,
}

/// Every beam's cells for one heading, merged into one prefix tree stored in pre-order (a
/// first part that beams share is stored and walked once). A walk visits a node when every
/// cell before it on its beams lets beams through, and jumps past the subtree of a cell
/// that stops them.
#[derive(Clone, Debug)]
pub(crate) struct BeamTree {
    /// The cells in pre-order.
    pub nodes: Vec<BeamNode>,
}

impl BeamTree {
    /// The tree of `beams` (unit directions relative to the heading) for `heading`, up to
    /// `range` cells (at most [`i16::MAX`] cells: callers check).
    pub(crate) fn new(beams: &[(f64, f64)], heading: f64, range: f64) -> Self {
        let (ch, sh) = (heading.cos(), heading.sin());
        let paths: Vec<Vec<(i16, i16)>> = beams
            .iter()
            .map(|&beam| {
                let (dx, dy) = rotate(beam, ch, sh);
                BeamWalk::new(dx, dy, range)
                    .map(|(x, y)| (x as i16, y as i16))
                    .collect()
            })
            .collect();
        Self::from_paths(&paths)
    }

    /// The tree of rays that enter the cells of `paths` (offsets from the sensor cell, in
    /// order; each ray moves one way along each axis). Built with a stack of its own, not
    /// by recursion: a ray may be tens of thousands of cells long.
    pub(crate) fn from_paths(paths: &[Vec<(i16, i16)>]) -> Self {
        /// What is left to do, innermost last.
        enum Task {
            /// Split `members[lo..hi]`, rays sharing their first `depth` cells and going on
            /// past them, by their next cell, one subtree per cell in ray order.
            Split { lo: usize, hi: usize, depth: usize },
            /// Add the node of `members[lo..hi]`'s common cell at `depth`, then its subtree.
            Node { lo: usize, hi: usize, depth: usize },
            /// Node `at`'s subtree is complete: it ends here.
            Close { at: usize },
        }
        let mut members: Vec<usize> = (0..paths.len()).filter(|&b| !paths[b].is_empty()).collect();
        let mut nodes = Vec::new();
        let mut cells: Vec<(i16, i16)> = Vec::new();
        let mut tasks = vec![Task::Split {
            lo: 0,
            hi: members.len(),
            depth: 0,
        }];
        while let Some(task) = tasks.pop() {
            match task {
                Task::Split { lo, hi, depth } => {
                    // Group by cell in order of first appearance (a stable sort keeps the
                    // rays' order within a group); push the groups last first.
                    cells.clear();
                    for &m in &members[lo..hi] {
                        if !cells.contains(&paths[m][depth]) {
                            cells.push(paths[m][depth]);
                        }
                    }
                    let group = |m: &usize| cells.iter().position(|&c| c == paths[*m][depth]);
                    members[lo..hi].sort_by_key(group);
                    let mut end = hi;
                    for k in (0..cells.len()).rev() {
                        let start = lo + members[lo..end].partition_point(|m| group(m) < Some(k));
                        tasks.push(Task::Node {
                            lo: start,
                            hi: end,
                            depth,
                        });
                        end = start;
                    }
                }
                Task::Node { lo, hi, depth } => {
                    let (dx, dy) = paths[members[lo]][depth];
                    tasks.push(Task::Close { at: nodes.len() });
                    nodes.push(BeamNode { dx, dy, skip: 0 });
                    // Only the rays that go on past this cell have a subtree.
                    let mut going_on = lo;
                    for i in lo..hi {
                        if paths[members[i]].len() > depth + 1 {
                            members[going_on] = members[i];
                            going_on += 1;
                        }
                    }
                    if going_on > lo {
                        tasks.push(Task::Split {
                            lo,
                            hi: going_on,
                            depth: depth + 1,
                        });
                    }
                }
                Task::Close { at } => nodes[at].skip = nodes.len() as u32,
            }
        }
        Self { nodes }
    }

    /// Mark in `window`'s `bits` every cell of the tree seen from `cell` (inside the grid) in
    /// `truth`: a cell is seen when every cell before it on one of its rays is free. A cell
    /// that is not free, or lies outside the grid (a ray moves one way along each axis, so
    /// it never comes back), skips the rest of its subtree.
    pub(crate) fn walk(&self, truth: &Grid<Occ>, cell: Cell, window: &Window, bits: &mut [u64]) {
        let data = truth.data();
        let (w, h) = (truth.width() as i64, truth.height() as i64);
        let (cx, cy) = (i64::from(cell.x), i64::from(cell.y));
        let nodes = &self.nodes;
        let mut n = 0;
        while let Some(node) = nodes.get(n) {
            let (x, y) = (cx + i64::from(node.dx), cy + i64::from(node.dy));
            if x < 0 || y < 0 || x >= w || y >= h {
                n = node.skip as usize;
                continue;
            }
            window.mark(bits, x, y);
            n = if data[(y * w + x) as usize] == Occ::Free {
                n + 1
            } else {
                node.skip as usize
            };
        }
    }
}

/// A scanner's beam trees for the eight move headings, each built at its first use.
pub(crate) struct CompassTrees {
    /// Unit directions of the beams relative to the heading.
    beams: Vec<(f64, f64)>,
    /// Range in cells.
    range: f64,
    /// The trees, by the index of their heading in [`compass_headings`]; `None` when one
    /// would take more than [`MAX_TREE_BYTES`].
    trees: [OnceLock<Option<BeamTree>>; 8],
}

impl std::fmt::Debug for CompassTrees {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let built = self.trees.iter().filter(|t| t.get().is_some()).count();
        write!(
            f,
            "CompassTrees({} beams, {built} of 8 built)",
            self.beams.len()
        )
    }
}

impl CompassTrees {
    /// The trees of a scanner with `beams` (unit directions relative to the heading) of
    /// `range` cells, described by `key` (its field of view and resolution), shared with
    /// every other scanner so described; `None` if the range is past an offset's reach.
    pub(crate) fn shared(beams: &[(f64, f64)], range: f64, key: (f64, f64)) -> Option<Arc<Self>> {
        if range >= f64::from(i16::MAX) {
            return None;
        }
        static CACHE: KeptCache<[u64; 3], CompassTrees> = OnceLock::new();
        let key = [range.to_bits(), key.0.to_bits(), key.1.to_bits()];
        Some(kept(&CACHE, key, || Self {
            beams: beams.to_vec(),
            range,
            trees: Default::default(),
        }))
    }

    /// The tree for `heading` if it is exactly one of [`compass_headings`] and its tree is
    /// not too large.
    pub(crate) fn tree(&self, heading: f64) -> Option<&BeamTree> {
        let k = compass_headings().iter().position(|&h| h == heading)?;
        self.trees[k]
            .get_or_init(|| {
                let bound = self.beams.len() as f64
                    * (2.0 * self.range + 2.0)
                    * std::mem::size_of::<BeamNode>() as f64;
                (bound <= MAX_TREE_BYTES as f64)
                    .then(|| BeamTree::new(&self.beams, heading, self.range))
            })
            .as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (stack overflow): a tree was grown by recursion, one call a cell, so a
    /// beam of tens of thousands of cells overflowed a thread's stack.
    #[test]
    fn a_long_beam_builds_on_a_small_stack() {
        let nodes = std::thread::Builder::new()
            .stack_size(256 * 1024)
            .spawn(|| BeamTree::new(&[(1.0, 0.0)], 0.3, 30_000.0).nodes.len())
            .expect("spawned")
            .join()
            .expect("no overflow");
        // One beam: a path, each cell the only child of the one before.
        assert!(nodes > 30_000);
    }

    /// The tree holds each beam's cells in order: following first children from the root
    /// and skips between siblings lists every beam's path.
    #[test]
    fn every_beam_is_a_path_down_the_tree() {
        let beams: Vec<(f64, f64)> = (0..=36)
            .map(|k| {
                let a = (f64::from(k) * 5.0 - 90.0).to_radians();
                (a.cos(), a.sin())
            })
            .collect();
        for &heading in compass_headings() {
            let tree = BeamTree::new(&beams, heading, 40.0);
            let (ch, sh) = (heading.cos(), heading.sin());
            for &beam in &beams {
                let (dx, dy) = rotate(beam, ch, sh);
                // Search each next cell among the children of the current node.
                let (mut lo, mut hi) = (0usize, tree.nodes.len());
                for (x, y) in BeamWalk::new(dx, dy, 40.0) {
                    let (x, y) = (x as i16, y as i16);
                    let mut n = lo;
                    while n < hi && (tree.nodes[n].dx, tree.nodes[n].dy) != (x, y) {
                        n = tree.nodes[n].skip as usize;
                    }
                    assert!(n < hi, "cell ({x}, {y}) of a beam is not in the tree");
                    (lo, hi) = (n + 1, tree.nodes[n].skip as usize);
                }
            }
        }
    }
}
