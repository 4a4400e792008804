//! The cluster actions of a state ([`crate::actions`], the paper's "Clustering boundary
//! cells" speed-up) computed on bit rows instead of from a shortest-path search.
//!
//! The clusters need three sets: R, the perceived free cells the robot can reach inside the
//! perceived space; B, the cells of R next to an unperceived free target; and B's
//! 8-connected components. [`crate::actions::candidates`] reads R off a Dijkstra that also
//! prices every cell of R. Here the perceived set is kept as rows of 64-bit words (bit x of
//! row y is cell (x, y)), and:
//! - R is a span fill from the robot's cell. A diagonal step is allowed only when one of
//!   the two straight cells it passes is passable, so 8-connected reachability without
//!   corner squeezing is 4-connectivity, and a span fill (one run of a row at a time, runs
//!   found with word operations) is exact;
//! - B = R ∩ dilate₈(targets \ perceived), a few word operations per row;
//! - clusters are flood-filled over B's bits in increasing flat index, so they, their
//!   order and their representatives (the member nearest the centroid, ties to the lowest
//!   flat index) are exactly those of [`crate::actions::candidates`]; a cluster is taken
//!   out run by run, so the work is per run of boundary cells, not per cell.
//!
//! The step costs to the few representatives then come from [`crate::step_cost`]'s
//! per-position distance fields. On the corridor floor benchmark a state has a thousand
//! reachable perceived cells but about five representatives, and the representatives fall
//! on a few dozen distinct cells over thousands of states.

use crate::problem::Problem;

/// A reachable component R as rows, with its first and last rows.
pub(crate) type Reach<'a> = (&'a [u64], (usize, usize));

/// Row-bitset geometry and the per-problem rows: reachable cells and targets.
pub(crate) struct ClusterRows {
    /// Cells per row.
    w: usize,
    /// Rows.
    h: usize,
    /// Words per row.
    wpr: usize,
    /// Reachable cells.
    reach: Vec<u64>,
    /// Target cells (free cells some reachable position perceives).
    targets: Vec<u64>,
    /// Scratch: the passable cells (reachable and perceived) of the state.
    pass: Vec<u64>,
    /// Scratch: R, the filled component.
    filled: Vec<u64>,
    /// R's first and last rows.
    span: (usize, usize),
    /// Scratch: unperceived targets, dilated along rows.
    wide: Vec<u64>,
    /// Scratch: B, then what is left of it while clusters are taken out.
    bound: Vec<u64>,
    /// Scratch: span seeds (row, column).
    seeds: Vec<(u32, u32)>,
    /// Scratch: the runs (row, first column, last column) of the cluster being taken out.
    runs: Vec<(usize, usize, usize)>,
    /// Per mark (a target, or another cell next to a reachable one): its flat cell.
    mark_cell: Vec<u32>,
}

impl ClusterRows {
    /// The rows of `problem`'s map.
    pub(crate) fn new(problem: &Problem) -> Self {
        let cells = problem.cells();
        let (w, h) = (cells.width(), cells.height());
        let wpr = w.div_ceil(64).max(1);
        let mut reach = vec![0u64; wpr * h];
        let mut targets = vec![0u64; wpr * h];
        let mut mark_cell = vec![0; problem.mark_count()];
        for i in 0..w * h {
            let m = problem.mark_index(i);
            if m != crate::problem::NOT_TARGET {
                mark_cell[m as usize] = i as u32;
            }
            let (x, y) = (i % w, i / w);
            let (k, b) = (y * wpr + x / 64, x % 64);
            if problem.reachable(i) {
                reach[k] |= 1 << b;
            }
            if problem.target_index(i) != crate::problem::NOT_TARGET {
                targets[k] |= 1 << b;
            }
        }
        let n = wpr * h;
        Self {
            w,
            h,
            wpr,
            reach,
            targets,
            pass: vec![0; n],
            filled: vec![0; n],
            span: (0, 0),
            wide: vec![0; n],
            bound: vec![0; n],
            seeds: Vec::new(),
            runs: Vec::new(),
            mark_cell,
        }
    }

    /// Words of one row set (`wpr` × `h`).
    pub(crate) fn words(&self) -> usize {
        self.wpr * self.h
    }

    /// The word index and bit of flat cell `i`.
    #[inline]
    pub(crate) fn locate(&self, i: usize) -> (usize, u32) {
        let (x, y) = (i % self.w, i / self.w);
        (y * self.wpr + x / 64, (x % 64) as u32)
    }

    /// The word index and bit of mark `m`'s cell.
    #[inline]
    pub(crate) fn locate_mark(&self, m: u32) -> (usize, u32) {
        self.locate(self.mark_cell[m as usize] as usize)
    }

    /// The marks' bitset `marks` as rows, into `out`.
    pub(crate) fn rows_of(&self, marks: &[u64], out: &mut Vec<u64>) {
        out.clear();
        out.resize(self.words(), 0);
        for (k, &word) in marks.iter().enumerate() {
            let mut m = word;
            while m != 0 {
                let (j, b) = self.locate_mark((k * 64) as u32 + m.trailing_zeros());
                m &= m - 1;
                out[j] |= 1 << b;
            }
        }
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.reach.len() * 8 * 6
            + self.seeds.capacity() * 8
            + self.runs.capacity() * 24
            + self.mark_cell.len() * 4
    }

    /// Fill `out` with the representatives of the clusters of the state whose perceived
    /// cells are `seen` (rows), the robot at flat cell `here`; clusters of fewer than
    /// `min_size` cells are dropped and `here` is never a candidate. The same candidates,
    /// in the same order, as [`crate::actions::candidates`] with
    /// [`crate::actions::ActionSet::Clusters`].
    ///
    /// `base`, when given, is R (rows and row range, [`ClusterRows::reach`]) of an
    /// ancestor of the state, whose robot stood at flat cell `from`: the fill then starts
    /// from it. It lies in this state's R: the perceived set only grew since, each later
    /// position was a candidate of the state before it (a perceived cell of that state's
    /// R, which is connected and holds that state's cell), so every R along the way is
    /// joined to the next. The ancestor's own cell was passable there by fiat (the robot
    /// stands on it), so `base` is used only when `from` is perceived here.
    pub(crate) fn candidates(
        &mut self,
        seen: &[u64],
        here: u32,
        min_size: usize,
        base: Option<(Reach<'_>, u32)>,
        out: &mut Vec<u32>,
    ) {
        out.clear();
        for ((p, &r), &s) in self.pass.iter_mut().zip(&self.reach).zip(seen) {
            *p = r & s;
        }
        let base = base.filter(|&(_, from)| {
            let (k, b) = self.locate(from as usize);
            self.pass[k] >> b & 1 == 1
        });
        // The robot's own cell is always left (as in the step costs' search).
        let (k, b) = self.locate(here as usize);
        self.pass[k] |= 1 << b;
        // Rows of one or two words (maps up to 128 cells wide, as at the paper's cell
        // sizes) get code for their width, whose word loops the compiler unrolls.
        match self.wpr {
            1 => self.rest::<1>(seen, here, min_size, base.map(|(r, _)| r), out),
            2 => self.rest::<2>(seen, here, min_size, base.map(|(r, _)| r), out),
            _ => self.rest::<0>(seen, here, min_size, base.map(|(r, _)| r), out),
        }
    }

    /// [`ClusterRows::candidates`] once the passable cells are set, for rows of `W` words
    /// (0: `self.wpr`, read at run time).
    fn rest<const W: usize>(
        &mut self,
        seen: &[u64],
        here: u32,
        min_size: usize,
        base: Option<Reach<'_>>,
        out: &mut Vec<u32>,
    ) {
        let (y0, y1) = self.fill::<W>(here as usize, base);
        #[cfg(debug_assertions)]
        if base.is_some() {
            let kept = self.filled.clone();
            let fresh = self.fill::<W>(here as usize, None);
            assert_eq!((y0, y1), fresh, "R's rows from an ancestor");
            assert!(kept == self.filled, "R from an ancestor");
        }
        self.span = (y0, y1);
        self.boundary::<W>(seen, y0, y1);
        self.clusters::<W>(y0, y1, here, min_size, out);
    }

    /// Words per row: `W`, or `self.wpr` when `W` is 0.
    #[inline(always)]
    fn row_words<const W: usize>(&self) -> usize {
        if W == 0 { self.wpr } else { W }
    }

    /// R (rows and row range) of the last [`ClusterRows::candidates`].
    pub(crate) fn reach(&self) -> Reach<'_> {
        (&self.filled, self.span)
    }

    /// R: the 4-connected component of passable cells holding flat cell `start`, by span
    /// filling, from `base` (a part of it, with its row range) when given; returns the
    /// first and last rows it touches.
    fn fill<const W: usize>(&mut self, start: usize, base: Option<Reach<'_>>) -> (usize, usize) {
        let (w, wpr) = (self.w, self.row_words::<W>());
        self.seeds.clear();
        self.seeds.push(((start / w) as u32, (start % w) as u32));
        let (mut y0, mut y1) = (start / w, start / w);
        if let Some((rows, (b0, b1))) = base {
            self.filled.copy_from_slice(rows);
            (y0, y1) = (y0.min(b0), y1.max(b1));
            // One seed per run of passable cells outside the part, next to it.
            for y in b0.saturating_sub(1)..=(b1 + 1).min(self.h - 1) {
                let row = y * wpr;
                for k in 0..wpr {
                    let f = self.filled[row + k];
                    let left = if k > 0 { self.filled[row + k - 1] } else { 0 };
                    let right = if k + 1 < wpr {
                        self.filled[row + k + 1]
                    } else {
                        0
                    };
                    let mut near = spread(f, left, right);
                    if y > 0 {
                        near |= self.filled[row - wpr + k];
                    }
                    if y + 1 < self.h {
                        near |= self.filled[row + wpr + k];
                    }
                    let mut m = self.pass[row + k] & !f & near;
                    while m != 0 {
                        let bit = m.trailing_zeros();
                        self.seeds.push((y as u32, (k * 64) as u32 + bit));
                        m &= m.wrapping_add(1 << bit);
                    }
                }
            }
        } else {
            self.filled.fill(0);
        }
        while let Some((y, x)) = self.seeds.pop() {
            let (y, x) = (y as usize, x as usize);
            let row = y * wpr;
            if self.filled[row + x / 64] >> (x % 64) & 1 == 1 {
                continue;
            }
            let pass = &self.pass[row..row + wpr];
            let (a, b) = (run_start(pass, x), run_end(pass, x));
            set_range(&mut self.filled[row..row + wpr], a, b);
            y0 = y0.min(y);
            y1 = y1.max(y);
            for ny in [y.wrapping_sub(1), y + 1] {
                if ny >= self.h {
                    continue;
                }
                let nrow = ny * wpr;
                for k in a / 64..=b / 64 {
                    let mut m = self.pass[nrow + k] & !self.filled[nrow + k] & range_mask(k, a, b);
                    while m != 0 {
                        let bit = m.trailing_zeros();
                        self.seeds.push((ny as u32, (k * 64) as u32 + bit));
                        // Drop the lowest run of m: one seed per run.
                        m &= m.wrapping_add(1 << bit);
                    }
                }
            }
        }
        (y0, y1)
    }

    /// B = R ∩ dilate₈(targets \ seen) over rows `y0..=y1` (left in `bound`; other rows
    /// are not read).
    fn boundary<const W: usize>(&mut self, seen: &[u64], y0: usize, y1: usize) {
        let wpr = self.row_words::<W>();
        // Unperceived targets dilated along their row, for rows y0 - 1 ..= y1 + 1.
        let lo = y0.saturating_sub(1);
        let hi = (y1 + 1).min(self.h - 1);
        for y in lo..=hi {
            let row = y * wpr;
            let mut prev = 0u64;
            for k in 0..wpr {
                let u = self.targets[row + k] & !seen[row + k];
                let next = if k + 1 < wpr {
                    self.targets[row + k + 1] & !seen[row + k + 1]
                } else {
                    0
                };
                self.wide[row + k] = spread(u, prev, next);
                prev = u;
            }
        }
        for y in y0..=y1 {
            let row = y * wpr;
            for k in 0..wpr {
                let mut d = self.wide[row + k];
                if y > 0 {
                    d |= self.wide[row - wpr + k];
                }
                if y + 1 < self.h {
                    d |= self.wide[row + wpr + k];
                }
                self.bound[row + k] = self.filled[row + k] & d;
            }
        }
    }

    /// The representatives of B's 8-connected clusters in rows `y0..=y1`, by increasing
    /// first flat index (module doc). A cluster is taken out run by run: a run of B in one
    /// row, then the runs of the rows above and below that touch it or its two ends
    /// diagonally.
    fn clusters<const W: usize>(
        &mut self,
        y0: usize,
        y1: usize,
        here: u32,
        min_size: usize,
        out: &mut Vec<u32>,
    ) {
        let (w, wpr) = (self.w, self.row_words::<W>());
        for y in y0..=y1 {
            for k in 0..wpr {
                while self.bound[y * wpr + k] != 0 {
                    let x = k * 64 + self.bound[y * wpr + k].trailing_zeros() as usize;
                    self.runs.clear();
                    self.take_run::<W>(y, x);
                    let mut next = 0;
                    while next < self.runs.len() {
                        let (ry, a, b) = self.runs[next];
                        next += 1;
                        let (lo, hi) = (a.saturating_sub(1), (b + 1).min(w - 1));
                        for ny in [ry.wrapping_sub(1), ry + 1] {
                            if ny < y0 || ny > y1 {
                                continue;
                            }
                            let mut nx = lo;
                            while let Some(found) =
                                first_set(&self.bound[ny * wpr..(ny + 1) * wpr], nx, hi)
                            {
                                let end = self.take_run::<W>(ny, found);
                                nx = end + 1;
                            }
                        }
                    }
                    let size: usize = self.runs.iter().map(|&(_, a, b)| b - a + 1).sum();
                    if size < min_size.max(1) {
                        continue;
                    }
                    let best = nearest_in_runs(&self.runs, size, w);
                    if best != here {
                        out.push(best);
                    }
                }
            }
        }
    }

    /// Clear the run of B holding column `x` of row `y`, list it, return its last column.
    fn take_run<const W: usize>(&mut self, y: usize, x: usize) -> usize {
        let wpr = self.row_words::<W>();
        let row = &mut self.bound[y * wpr..(y + 1) * wpr];
        let (a, b) = (run_start(row, x), run_end(row, x));
        clear_range(row, a, b);
        self.runs.push((y, a, b));
        b
    }
}

/// The cell of the runs (row, first column, last column) nearest (Euclidean) to their
/// cells' centroid, ties to the lowest flat index: the same cell as [`crate::actions::representative`]
/// over the runs' cells, found per run at the column nearest the centroid's.
fn nearest_in_runs(runs: &[(usize, usize, usize)], size: usize, w: usize) -> u32 {
    // Sums of integers, exact in f64 as in `crate::actions::representative`.
    let (mut sx, mut sy) = (0u64, 0u64);
    for &(y, a, b) in runs {
        let len = (b - a + 1) as u64;
        sx += (a + b) as u64 * len / 2;
        sy += y as u64 * len;
    }
    let m = size as f64;
    let (cx, cy) = (sx as f64 / m, sy as f64 / m);
    // The centroid's neighbouring columns (cx ≥ 0), clamped into each run in integers.
    let (fl, ce) = (cx.floor() as usize, cx.ceil() as usize);
    let mut best = (f64::INFINITY, u32::MAX);
    for &(y, a, b) in runs {
        let dy = y as f64 - cy;
        let dy2 = dy * dy;
        // Every cell of the run is at least dy² away: none can beat or tie the best.
        if dy2 > best.0 {
            continue;
        }
        let (f, c) = (fl.clamp(a, b), ce.clamp(a, b));
        for x in [f, c].into_iter().take(if f == c { 1 } else { 2 }) {
            let dx = x as f64 - cx;
            let d = dx * dx + dy2;
            let i = (y * w + x) as u32;
            if d < best.0 || (d == best.0 && i < best.1) {
                best = (d, i);
            }
        }
    }
    best.1
}

/// A word of a row widened by one column either way, `left` and `right` the words beside
/// it (0 past the row's ends).
#[inline]
fn spread(word: u64, left: u64, right: u64) -> u64 {
    word | word << 1 | word >> 1 | left >> 63 | right << 63
}

/// Bits `a..=b` of word `k` of a row (columns `64k..64k + 63`).
#[inline]
fn range_mask(k: usize, a: usize, b: usize) -> u64 {
    let lo = a.max(k * 64) - k * 64;
    let hi = b.min(k * 64 + 63) - k * 64;
    (u64::MAX >> (63 - hi)) & (u64::MAX << lo)
}

/// Clear bits `a..=b` of a row.
fn clear_range(row: &mut [u64], a: usize, b: usize) {
    for (k, word) in row.iter_mut().enumerate().take(b / 64 + 1).skip(a / 64) {
        *word &= !range_mask(k, a, b);
    }
}

/// The first set column of `row` in `a..=b`, if any.
fn first_set(row: &[u64], a: usize, b: usize) -> Option<usize> {
    if a > b {
        return None;
    }
    (a / 64..=b / 64).find_map(|k| {
        let m = row[k] & range_mask(k, a, b);
        (m != 0).then(|| k * 64 + m.trailing_zeros() as usize)
    })
}

/// Set bits `a..=b` of a row.
fn set_range(row: &mut [u64], a: usize, b: usize) {
    for (k, word) in row.iter_mut().enumerate().take(b / 64 + 1).skip(a / 64) {
        *word |= range_mask(k, a, b);
    }
}

/// The first column of the run of set bits holding column `x` of `row`.
fn run_start(row: &[u64], x: usize) -> usize {
    let mut k = x / 64;
    // Bits at and below x, shifted to the top.
    let mut word = row[k] << (63 - x % 64);
    let mut top = x % 64; // column offset in word k of the top bit of `word`
    loop {
        let ones = (!word).leading_zeros() as usize; // set bits from the top down
        if ones <= top {
            return k * 64 + top + 1 - ones;
        }
        if k == 0 {
            return 0;
        }
        k -= 1;
        word = row[k];
        top = 63;
    }
}

/// The last column of the run of set bits holding column `x` of `row`.
fn run_end(row: &[u64], x: usize) -> usize {
    let mut k = x / 64;
    let mut word = row[k] >> (x % 64);
    let mut low = x % 64;
    loop {
        let ones = (!word).trailing_zeros() as usize;
        if ones < 64 - low {
            return k * 64 + low + ones - 1;
        }
        if k + 1 == row.len() {
            return k * 64 + 63;
        }
        k += 1;
        word = row[k];
        low = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::actions::{ActionScratch, ActionSet, candidates};
    use crate::heuristic::set;
    use crate::problem::{NOT_TARGET, SensorModel};
    use crate::step_cost::StepCosts;
    use proptest::prelude::*;

    #[test]
    fn runs_across_words() {
        let row = [u64::MAX << 60, 0b111, 0];
        assert_eq!(run_start(&row, 66), 60);
        assert_eq!(run_end(&row, 61), 66);
        assert_eq!(run_end(&row, 66), 66);
        assert_eq!(run_start(&row, 60), 60);
        let full = [u64::MAX, u64::MAX];
        assert_eq!(run_start(&full, 100), 0);
        assert_eq!(run_end(&full, 3), 127);
        assert_eq!(range_mask(1, 60, 70), 0b111_1111);
        assert_eq!(range_mask(0, 60, 70), 0b1111 << 60);
    }

    proptest! {
        /// The same cluster representatives, in the same order, as the candidates read off
        /// the step costs' search, on random maps (up to 150 columns, so rows span three
        /// words), perceived sets, robot cells and minimum sizes; also when the fill starts
        /// from R of a smaller perceived set (an ancestor's, the robot at the same cell).
        #[test]
        fn same_as_the_search_based_candidates(
            w in 2usize..150,
            h in 2usize..10,
            walls in proptest::collection::vec(0u8..5, 1500),
            seen in proptest::collection::vec(0u8..4, 1500),
            pick in 0usize..1500,
            min_size in 1usize..4,
            fp in any::<bool>(),
            earlier in proptest::collection::vec(any::<bool>(), 1500),
        ) {
            let model = if fp { SensorModel::Footprint(1.5) } else { SensorModel::Los(1.5) };
            let case = crate::walled_problem(w, h, &walls, pick, model);
            prop_assume!(case.is_some());
            let (p, start) = case.expect("assumed");
            let mut bits = vec![0u64; p.mark_count().div_ceil(64).max(1)];
            let mut rows = ClusterRows::new(&p);
            let mut seen_rows = vec![0u64; rows.words()];
            let mut earlier_rows = vec![0u64; rows.words()];
            for (i, &s) in seen.iter().enumerate().take(w * h) {
                let t = p.mark_index(i);
                if t != NOT_TARGET && (s != 0 || i == start) {
                    set(&mut bits, t);
                    let (k, b) = rows.locate(i);
                    seen_rows[k] |= 1 << b;
                    if earlier[i] || i == start {
                        earlier_rows[k] |= 1 << b;
                    }
                }
            }
            let mut steps = StepCosts::new(&p);
            steps.compute(start as u32, &bits);
            let mut scratch = ActionScratch::new(w * h);
            let mut want = Vec::new();
            let set_ = ActionSet::Clusters { min_size };
            candidates(&p, &bits, steps.settled(), start as u32, set_, &mut scratch, &mut want);
            let mut got = Vec::new();
            rows.candidates(&seen_rows, start as u32, min_size, None, &mut got);
            prop_assert_eq!(&got, &want);
            let fresh = (rows.reach().0.to_vec(), rows.reach().1);
            let mut ancestor = ClusterRows::new(&p);
            ancestor.candidates(&earlier_rows, start as u32, min_size, None, &mut got);
            let base = Some((ancestor.reach(), start as u32));
            rows.candidates(&seen_rows, start as u32, min_size, base, &mut got);
            prop_assert_eq!(&got, &want);
            prop_assert_eq!((rows.reach().0.to_vec(), rows.reach().1), fresh);
        }
    }
}
