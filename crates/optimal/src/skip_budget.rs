//! A lower bound for the weaker goal (G < 1) that knows the robot's skip budget is spent
//! once along the whole path: the far ends of the map must still be approached, each the
//! closer the more of the budget the other ends take. Our addition (not in the paper).
//!
//! # The bound
//! Notation as in [`crate::heuristic`]: state (q, M), U = targets not in M, d = shortest
//! path length in the full map, V(t) = reachable positions that perceive t, and
//! s = |E_f| − needed: at most s targets may stay unperceived at the end.
//!
//! Far points p_1..p_K (reachable cells, chosen once by farthest-point sampling from the
//! start in d) each own a disjoint set T_a of targets (ownership below). For a target t let
//! e_a(t) = max_{v ∈ V(t)} d(p_a, v): every viewpoint of t lies within e_a(t) of p_a.
//!
//! Let δ_a be the distance from p_a to the nearest *later* sensing position of the robot.
//! A target t ∈ U ∩ T_a with e_a(t) < δ_a has all its viewpoints nearer to p_a than any later
//! position, so it is never perceived. The T_a are disjoint, so with
//! b_a = |{t ∈ U ∩ T_a : e_a(t) < δ_a}| we have Σ_a b_a ≤ s, and δ_a ≤ E_a[b_a], the
//! (b_a + 1)-th smallest e_a over U ∩ T_a (∞ if there are not that many).
//!
//! The rest of the path stops at a position x_a with d(p_a, x_a) = δ_a for every a, in some
//! order π. By the triangle inequality d(q, x_a) ≥ d(p_a, q) − δ_a and
//! d(x_a, x_b) ≥ d(p_a, p_b) − δ_a − δ_b, so the rest of the path is at least
//! L(π, δ) = [d(p_π1, q) − δ_π1]⁺ + Σ_i [d(p_πi, p_πi+1) − δ_πi − δ_πi+1]⁺,
//! and (a path being no shorter than the distance between its ends) at least
//! [d(p_πK, q) − δ_πK]⁺; we take the larger of the two. Both only fall as any δ grows. The
//! second keeps the bound when δ_π1 = ∞ (the budget covers every unperceived target of
//! p_π1, which then constrains nothing): the chain alone falls to 0 there, the direct term
//! still asks the robot to approach the other far point (3.6 % fewer states on the
//! corridor floor). Hence
//!
//! h = min over splits b_1 + … + b_K ≤ s, min over orders π, of L(π, (E_a[b_a])_a)
//!
//! is admissible. Splits are enumerated exactly when there are few; otherwise each b_a
//! runs over multiples of a step Δ with Σ ⌈b_a/Δ⌉ ≤ ⌊s/Δ⌋ + K, which contains the rounded-up
//! image of every true split (a relaxation, so still a lower bound).
//!
//! Ownership: the bound is computed for the first far point alone (owning every target)
//! and for the first two (each target owned by the far point with the smallest e_a(t),
//! ties to the first), and the larger is used (the first alone is left out where the order
//! statistic takes exact viewpoint distances, which always give at least as much:
//! [`SkipBudget::without_single_point`]). With the footprint sensor V(t) crosses walls, and
//! e_a(t) counts the farthest viewpoint in path distance, so the argument holds for both
//! sensors.
//!
//! Two far points, not more: a third (ownership by three, six orders, a two-dimensional
//! split) was measured. On the corridor floor's ten starts (footprint, G = 0.85) it bounded
//! 1.5 % of the children higher and saved 1.3 % of the states, at a tenth more time; with
//! the line-of-sight sensor it saved 0.8 % of the states, again at a tenth more time; on
//! potholes and on the floor at G = 0.95 it changed no state.
//!
//! On the paper-sized corridor floor (an L of two corridors) the far points are the two
//! corridor ends: a robot starting near the corner must reach near both, less the part of
//! the budget it spends at either end, which the coverage-rate bound cannot see.
//!
//! # Cost
//! Per bound, each list is scanned up to its (s + 1)-th unperceived target, and the splits
//! are enumerated until one gives no more than the other bounds already do (a block of
//! [`SPLIT_BLOCK`] splits is passed over when the δ at its ends show it cannot beat the best
//! split so far). Siblings share their parent's scans: a child perceives only targets it
//! is a viewpoint of, so it cannot change E_a when it is farther from p_a than E_a's last
//! value, and the parent's E_a at the last minimising split bound the child's value from
//! above (the child's E_a are no smaller), which often shows that the child's own scan
//! cannot matter. On the corridor
//! floor this halves the states expanded; on maps where it never beats the coverage-rate
//! bound (the benchmark's cave and potholes) it costs about a tenth of the search's time.

use sense::Observation;

use crate::block_masks::{BLOCK, BlockMasks};
use crate::heuristic::has;
use crate::problem::{Problem, SensorModel};
use crate::step_cost::FieldCache;
use crate::viewpoint_distance::ViewpointDistance;

/// Most far points.
const MAX_POINTS: usize = 2;
/// Most cells visited scanning every target's viewpoints at set-up (targets × the sensor's
/// disc); beyond it the line-of-sight sensor estimates e_a from the target's own distance.
const SCAN_BUDGET: usize = 1 << 26;
/// Splits bounded together before they are evaluated one by one.
const SPLIT_BLOCK: usize = 16;
/// Most (split, order) pairs evaluated per bound and ownership.
const MAX_WORK: usize = 1024;

/// The skip-budget bound of one problem and goal.
pub(crate) struct SkipBudget {
    /// Targets that may stay unperceived.
    skip: usize,
    /// Per far point: d(p_a, ·) over the flat cells (∞ where unreachable).
    field: Vec<Vec<f64>>,
    /// d(p_a, p_b), `MAX_POINTS` × `MAX_POINTS`.
    between: [[f64; MAX_POINTS]; MAX_POINTS],
    /// Per ownership (the first 1, 2 far points) and far point: its owned targets
    /// (e_a(t), t), by e ascending.
    owned: Vec<Vec<Vec<(f64, u32)>>>,
    /// The owned lists' blocks, list after list.
    blocks: BlockMasks,
    /// Per ownership and far point: its list's first block in `blocks`.
    first_block: Vec<Vec<usize>>,
    /// Per far point: E_a[0..=skip] of the state being bounded (scratch).
    e: Vec<Vec<f64>>,
    /// Per ownership and far point: E_a[0..=skip] of the state whose children are being
    /// bounded ([`SkipBudget::enter`]).
    parent: Vec<Vec<Vec<f64>>>,
    /// Per ownership and far point: the targets behind `parent`'s values, and where in the
    /// list the parent's scan stopped (a child's scan goes on from there).
    parent_t: Vec<Vec<Vec<u32>>>,
    parent_end: Vec<Vec<usize>>,
    /// Per ownership and far point: whether `parent` holds the current parent's E_a.
    parent_ok: Vec<Vec<bool>>,
    /// The ownership that last gave the largest value.
    lead: usize,
    /// The first ownership evaluated ([`SkipBudget::without_single_point`]).
    from: usize,
    /// Per ownership: the split (in steps) that last gave the minimum.
    hint: Vec<usize>,
}

impl SkipBudget {
    /// Set up the bound for `problem` when `skip` targets may stay unperceived; `None` when
    /// there is no budget (G = 1) or no far point worth a constraint.
    pub(crate) fn new(problem: &Problem, skip: usize, fields: &mut FieldCache) -> Option<Self> {
        if skip == 0 {
            return None;
        }
        let n = problem.cells().len();
        // The full map's path costs from a reachable cell, by flat cell: the search's
        // per-position fields (the start's is the root's anyway).
        let costs = |fields: &mut FieldCache, p: usize| -> Vec<f64> {
            let c = fields.costs(p as u32);
            (0..n).map(c).collect()
        };
        // Farthest-point sampling from the start.
        let mut nearest = costs(fields, problem.start() as usize);
        let mut points = Vec::new();
        let mut field: Vec<Vec<f64>> = Vec::new();
        let reach = problem.model().range();
        while points.len() < MAX_POINTS {
            let mut best: Option<(f64, usize)> = None;
            for (i, &d) in nearest.iter().enumerate() {
                if problem.reachable(i) && best.is_none_or(|(bd, _)| d > bd) {
                    best = Some((d, i));
                }
            }
            // A point within the sensor's reach of a chosen one adds nothing.
            let Some((_, p)) = best.filter(|&(d, _)| d > 2.0 * reach) else {
                break;
            };
            let f = costs(fields, p);
            for (m, &x) in nearest.iter_mut().zip(&f) {
                *m = m.min(x);
            }
            points.push(p);
            field.push(f);
        }
        let k = points.len();
        if k == 0 {
            return None;
        }
        let mut between = [[0.0; MAX_POINTS]; MAX_POINTS];
        for a in 0..k {
            for b in 0..k {
                between[a][b] = field[a][points[b]].min(field[b][points[a]]);
            }
        }
        // e_a(t) for every target and far point; per ownership, each target goes to the
        // far point with the smallest. On maps too large to scan every target's viewpoints
        // the line-of-sight sensor uses e_a(t) ≤ d(p_a, t) + c (every viewpoint is within
        // c of t in path length, `crate::heuristic`'s module doc): counting fewer targets
        // is still a lower bound. The footprint's farthest viewpoints are a dilation of
        // each field by its disc (`viewpoint_reach`), cheap on any map.
        let r = problem.model().range();
        let scan = problem
            .targets()
            .len()
            .saturating_mul(problem.model().disc_cells());
        // The footprint's viewpoints come from an erosion, cheap on any map.
        let estimate = match problem.model() {
            SensorModel::Los(_) if scan > SCAN_BUDGET => Some(crate::heuristic::max_l1_within(r)),
            _ => None,
        };
        let mut owned = vec![Vec::new(); k];
        for (j, o) in owned.iter_mut().enumerate() {
            *o = vec![Vec::new(); j + 1];
        }
        for (t, e) in viewpoint_reach(problem, &field, estimate)
            .iter()
            .enumerate()
        {
            if e[0] == f64::NEG_INFINITY {
                continue; // no viewpoint (not a target of this problem)
            }
            for (j, o) in owned.iter_mut().enumerate() {
                let (mut best, mut arg) = (f64::INFINITY, 0);
                for (a, &x) in e[..=j].iter().enumerate() {
                    if x < best {
                        (best, arg) = (x, a);
                    }
                }
                if best.is_finite() {
                    o[arg].push((best, t as u32));
                }
            }
        }
        let mut blocks = BlockMasks::default();
        let mut first_block = Vec::new();
        let mut next = 0;
        for o in owned.iter_mut() {
            let mut firsts = Vec::new();
            for list in o.iter_mut() {
                list.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                blocks.push_list(list.iter().map(|&(_, t)| t));
                firsts.push(next);
                next += list.len().div_ceil(BLOCK);
            }
            first_block.push(firsts);
        }
        Some(Self {
            skip,
            field,
            between,
            hint: vec![0; k],
            lead: 0,
            from: 0,
            parent_ok: owned.iter().map(|o| vec![false; o.len()]).collect(),
            parent: owned.iter().map(|o| vec![Vec::new(); o.len()]).collect(),
            parent_t: owned.iter().map(|o| vec![Vec::new(); o.len()]).collect(),
            parent_end: owned.iter().map(|o| vec![0; o.len()]).collect(),
            owned,
            blocks,
            first_block,
            e: vec![Vec::new(); k],
        })
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.field.iter().map(|f| f.len() * 8).sum::<usize>()
            + self.blocks.bytes()
            + self
                .owned
                .iter()
                .flatten()
                .map(|o| o.len() * 16)
                .sum::<usize>()
            + self.e.iter().map(|e| e.capacity() * 8).sum::<usize>()
            + self
                .parent
                .iter()
                .flatten()
                .map(|e| e.capacity() * 12)
                .sum::<usize>()
    }

    /// Append to `e` the values of the unperceived targets of `list` from entry `from` on
    /// (and their targets to `t`, when given) until `e` holds skip + 1: E_a[0..=skip] for
    /// the perceived set `bits` when both start empty. Returns where the scan stopped.
    fn scan_from(
        list: &[(f64, u32)],
        blocks: (&BlockMasks, usize),
        from: usize,
        bits: &[u64],
        skip: usize,
        e: &mut Vec<f64>,
        mut t: Option<&mut Vec<u32>>,
    ) -> usize {
        // Blocks wholly perceived are passed over with a few popcounts
        // ([`crate::block_masks`]); the others are walked without branches: every entry is
        // written at the end and kept only when unperceived (perceived and unperceived
        // targets interleave, so a branch would mispredict).
        let want = skip + 1;
        let mut len = e.len();
        if len >= want {
            return from;
        }
        e.resize(want, 0.0);
        if let Some(t) = t.as_deref_mut() {
            t.resize(want, 0);
        }
        let (masks, first) = blocks;
        let mut k = from;
        while k < list.len() {
            let end = ((k / BLOCK + 1) * BLOCK).min(list.len());
            // (A block without pairs would be counted entry by entry: walked at once.)
            let b = first + k / BLOCK;
            if k.is_multiple_of(BLOCK)
                && masks.has_pairs(b)
                && masks.open(b, bits, &list[k..end]) == 0
            {
                k = end;
                continue;
            }
            for (i, &(x, target)) in list[..end].iter().enumerate().skip(k) {
                e[len] = x;
                if let Some(t) = t.as_deref_mut() {
                    t[len] = target;
                }
                len += usize::from(!has(bits, target));
                if len == want {
                    return i + 1;
                }
            }
            k = end;
        }
        e.truncate(len);
        if let Some(t) = t {
            t.truncate(len);
        }
        list.len()
    }

    /// Leave out the ownership of the first far point alone, for a caller whose order
    /// statistic takes each target's exact viewpoint distance D(q, t): it can never give
    /// more. For every viewpoint v of t, d(q, v) ≥ d(p, q) − d(p, v) ≥ d(p, q) − e(t), so
    /// D(q, t) ≥ d(p, q) − e(t) for every target, and the (s + 1)-th largest D over U is at
    /// least d(p, q) minus the (s + 1)-th smallest e over U, which is this ownership's
    /// bound (its one far point, every target owned, δ ≤ E[s]).
    pub(crate) fn without_single_point(&mut self) {
        self.from = 1;
    }

    /// Start bounding the children of a new state (`parent` of [`SkipBudget::bound`]): its
    /// E_a are scanned on first use. A child reuses its parent's E_a when it perceives
    /// nothing of E_a's prefix: every target t it perceives has e_a(t) ≥ d(p_a, child), the
    /// child being a viewpoint of t (with the large-map estimate too: d(p_a, child) ≤
    /// d(p_a, t) + c), so none is in the prefix when d(p_a, child) exceeds its last e.
    pub(crate) fn enter(&mut self) {
        for ok in self.parent_ok.iter_mut().flatten() {
            *ok = false;
        }
    }

    /// The bound for the robot at flat cell `pos` having perceived `bits`, the largest over
    /// the ownerships, or `floor` if that is larger (an ownership stops as soon as one of
    /// its splits gives no more than the best so far).
    /// With `Some(parent)`, `bits` is what `pos` perceives added to `parent`, the perceived
    /// set of the state last [`SkipBudget::enter`]ed. Once the value reaches `cut` the other
    /// ownerships are skipped (it is then at least `cut`, exact below).
    pub(crate) fn bound(
        &mut self,
        pos: u32,
        bits: &[u64],
        floor: f64,
        parent: Option<&[u64]>,
        cut: f64,
    ) -> f64 {
        let to_robot: [f64; MAX_POINTS] =
            std::array::from_fn(|a| self.field.get(a).map_or(0.0, |f| f[pos as usize]));
        let mut best = floor;
        // The ownership that gave the last largest value first: its value raises the floor
        // the others must beat, so they more often stop at once.
        let n = self.owned.len();
        if n <= self.from {
            return best;
        }
        let first = self.lead.clamp(self.from, n - 1);
        let mut lead = None;
        for j in std::iter::once(first).chain((self.from..n).filter(|&j| j != first)) {
            let v = self.bound_owned(j, pos, &to_robot, bits, best, parent);
            if v > best {
                best = v;
                lead = Some(j);
            }
            if best >= cut {
                break;
            }
        }
        if let Some(j) = lead {
            self.lead = j;
        }
        best
    }

    /// The bound with the first `j + 1` far points and their ownership, or a value no
    /// larger than `floor` once it cannot exceed it.
    fn bound_owned(
        &mut self,
        j: usize,
        pos: u32,
        to_robot: &[f64; MAX_POINTS],
        bits: &[u64],
        floor: f64,
        parent: Option<&[u64]>,
    ) -> f64 {
        let k = j + 1;
        let s = self.skip;
        // With every δ_a = 0 the path is longest: if even that is no more than `floor`, no
        // split can beat it.
        let zero = [0.0; MAX_POINTS];
        if path(&self.between, k, to_robot, &zero) <= floor {
            return floor;
        }
        // Split step: exact while the splits are few; else the relaxation of the module doc.
        let combos = |step: usize| (s / step + 1).pow(j as u32) * (1..=k).product::<usize>();
        let mut step = 1;
        while combos(step) > MAX_WORK {
            step *= 2;
        }
        let units = s / step + if step > 1 { k } else { 0 };
        let hi = self.hint[j].min(units);
        let mut reuse = [false; MAX_POINTS];
        if let Some(pb) = parent {
            for (a, list) in self.owned[j].iter().enumerate() {
                if !self.parent_ok[j][a] {
                    self.parent[j][a].clear();
                    self.parent_t[j][a].clear();
                    self.parent_end[j][a] = Self::scan_from(
                        &list[..],
                        (&self.blocks, self.first_block[j][a]),
                        0,
                        pb,
                        s,
                        &mut self.parent[j][a],
                        Some(&mut self.parent_t[j][a]),
                    );
                    self.parent_ok[j][a] = true;
                }
                let pe = &self.parent[j][a];
                reuse[a] = pe.last().is_none_or(|&l| self.field[a][pos as usize] > l);
            }
            // The child's E_a are no smaller than its parent's (fewer targets unperceived),
            // so the parent's at any split bound the child's value from above: if that is
            // no more than `floor`, the child's lists need no scan.
            if !reuse[..k].iter().all(|&r| r) {
                let pe: [&[f64]; MAX_POINTS] =
                    std::array::from_fn(|a| self.parent[j].get(a).map_or(&[][..], |e| &e[..]));
                let v = path(
                    &self.between,
                    k,
                    to_robot,
                    &split_delta(&pe, k, step, s, units, hi, hi),
                );
                if v <= floor {
                    return floor;
                }
            }
        }
        for (a, list) in self.owned[j].iter().enumerate() {
            if reuse[a] {
                continue;
            }
            if parent.is_some() {
                // The child's unperceived targets are the parent's less what it perceives:
                // the parent's entries still unperceived, then the list from where the
                // parent's scan stopped.
                let e = &mut self.e[a];
                e.clear();
                let pe = &self.parent[j][a];
                e.resize(pe.len(), 0.0);
                let mut len = 0;
                for (&v, &t) in pe.iter().zip(&self.parent_t[j][a]) {
                    e[len] = v;
                    len += usize::from(!has(bits, t));
                }
                e.truncate(len);
                if e.len() <= s {
                    let blocks = (&self.blocks, self.first_block[j][a]);
                    Self::scan_from(list, blocks, self.parent_end[j][a], bits, s, e, None);
                }
            } else {
                self.e[a].clear();
                let blocks = (&self.blocks, self.first_block[j][a]);
                Self::scan_from(list, blocks, 0, bits, s, &mut self.e[a], None);
            }
        }
        let e: [&[f64]; MAX_POINTS] = std::array::from_fn(|a| {
            if a >= k {
                &[][..]
            } else if reuse[a] {
                &self.parent[j][a][..]
            } else {
                &self.e[a][..]
            }
        });
        // Split (i, units − i) in steps; the last minimising split is tried first,
        // as siblings usually share it and it often settles the comparison with `floor`.
        // The bound only falls as either δ grows, and over splits lo..=hi δ_0 is at most
        // its value at hi and δ_1 at most its value at lo: a block of splits whose bound
        // at those δ is no less than the best so far cannot hold a smaller value.
        let between = &self.between;
        let delta = |i0: usize, i1: usize| split_delta(&e, k, step, s, units, i0, i1);
        let value = |i: usize| path(between, k, to_robot, &delta(i, i));
        let mut best = value(hi);
        let mut arg = hi;
        if best > floor && k > 1 {
            'blocks: for lo in (0..=units).step_by(SPLIT_BLOCK) {
                let top = (lo + SPLIT_BLOCK - 1).min(units);
                if path(between, k, to_robot, &delta(top, lo)) >= best {
                    continue;
                }
                for i in lo..=top {
                    let v = value(i);
                    if v < best {
                        (best, arg) = (v, i);
                        if best <= floor {
                            break 'blocks;
                        }
                    }
                }
            }
        }
        self.hint[j] = arg;
        best.max(0.0)
    }
}

/// e_a(t) for every target t and far point a (fields `field`): the farthest viewpoint's
/// distance, scanned, or with `estimate = Some(c)` (line of sight only) d(p_a, t) + c;
/// `-∞` for a target without a reachable viewpoint.
fn viewpoint_reach(
    problem: &Problem,
    field: &[Vec<f64>],
    estimate: Option<f64>,
) -> Vec<[f64; MAX_POINTS]> {
    let targets = problem.targets();
    let mut out = vec![[f64::NEG_INFINITY; MAX_POINTS]; targets.len()];
    // The footprint's viewpoints are the reachable cells of a disc: a dilation of each
    // field (an erosion of its negation) gives every target's farthest at once.
    if estimate.is_none()
        && problem.model().through_walls()
        && let Some(mut vd) =
            ViewpointDistance::new(&crate::coverage_rate::offsets(problem.model()))
    {
        for (a, f) in field.iter().enumerate() {
            vd.nearest(problem, |i| -f[i], |t, v| out[t as usize][a] = -v);
        }
        return out;
    }
    scanned_reach(problem, field, estimate, out)
}

/// [`viewpoint_reach`] by scanning each target's viewpoints (or with the estimate).
fn scanned_reach(
    problem: &Problem,
    field: &[Vec<f64>],
    estimate: Option<f64>,
    mut out: Vec<[f64; MAX_POINTS]>,
) -> Vec<[f64; MAX_POINTS]> {
    let targets = problem.targets();
    let mut obs = Observation::new();
    let mut seen = Vec::new();
    for (e, &cell) in out.iter_mut().zip(targets) {
        if let Some(c) = estimate {
            for (x, f) in e.iter_mut().zip(field) {
                *x = f[cell as usize] + c;
            }
            continue;
        }
        seen.clear();
        problem.viewpoints(cell, &mut obs, &mut seen);
        for &v in &seen {
            for (x, f) in e.iter_mut().zip(field) {
                *x = x.max(f[v as usize]);
            }
        }
    }
    out
}

/// The δ of the first `k` far points, whose E_a are `e`, at split (i, units − i) in steps of
/// `step` (capped at `s`; ∞ past a list's end): δ_0 at split `i0` and δ_1 at split `i1`
/// (the same split, or a block's two ends). One far point alone takes the whole budget.
fn split_delta(
    e: &[&[f64]; MAX_POINTS],
    k: usize,
    step: usize,
    s: usize,
    units: usize,
    i0: usize,
    i1: usize,
) -> [f64; MAX_POINTS] {
    let radius = |a: usize, i: usize| {
        e[a].get((i * step).min(s))
            .copied()
            .unwrap_or(f64::INFINITY)
    };
    if k == 1 {
        [radius(0, units), 0.0]
    } else {
        [radius(0, i0), radius(1, units - i1)]
    }
}

/// min over orders π of the first `k` far points of L(π, δ) (module doc).
fn path(
    between: &[[f64; MAX_POINTS]; MAX_POINTS],
    k: usize,
    to_robot: &[f64; MAX_POINTS],
    delta: &[f64; MAX_POINTS],
) -> f64 {
    // Plain comparisons (no NaN arises: distances are finite, δ may be ∞).
    let pos = |x: f64| if x > 0.0 { x } else { 0.0 };
    let (f0, f1) = (pos(to_robot[0] - delta[0]), pos(to_robot[1] - delta[1]));
    if k == 1 {
        return f0;
    }
    // `between` is symmetric. Visiting x_a then x_b costs at least d(q, x_a) + d(x_a, x_b)
    // and, the path being at least as long as its ends' distance, at least d(q, x_b).
    let leg = pos(between[0][1] - delta[0] - delta[1]);
    let (a, b) = (f0 + leg, f1 + leg);
    let first_0 = if a > f1 { a } else { f1 };
    let first_1 = if b > f0 { b } else { f0 };
    if first_0 < first_1 { first_0 } else { first_1 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heuristic::set;
    use crate::problem::SensorModel;
    use explore::plan::Reachability;
    use grid::{Cell, Occ};
    use proptest::prelude::*;

    /// Add what flat cell `pos` perceives to `bits`.
    fn perceive(p: &Problem, pos: u32, bits: &mut [u64]) {
        let mut seen = Vec::new();
        p.seen_marks(pos, &mut Observation::new(), &mut seen);
        for t in seen {
            set(bits, t);
        }
    }

    /// [`budget_case`]'s problem, reachable cells, bound, perceived marks and budget.
    type BudgetCase = (Problem, Vec<u32>, SkipBudget, Vec<u64>, usize);

    /// A random walled map's problem from its first free cell, its reachable cells, the
    /// skip-budget bound for `skip` (capped below the target count) and what the start and
    /// the reachable cells picked by `stops` perceive; `None` without a free cell or a
    /// bound.
    fn budget_case(
        w: usize,
        h: usize,
        walls: &[u8],
        model: SensorModel,
        stops: &[usize],
        skip: usize,
    ) -> Option<BudgetCase> {
        let map = crate::walled_map(w, h, walls);
        let start = (0..w * h).find(|&i| map.data()[i].is_free())?;
        let p = Problem::new(
            &map,
            Cell::new((start % w) as i32, (start / w) as i32),
            model,
        )
        .expect("problem");
        let reach: Vec<u32> = (0..w * h)
            .filter(|&i| p.reachable(i))
            .map(|i| i as u32)
            .collect();
        let skip = skip.min(p.targets().len().saturating_sub(1));
        let sb = SkipBudget::new(&p, skip, &mut FieldCache::new(&p, usize::MAX))?;
        let mut bits = vec![0u64; p.mark_count().div_ceil(64).max(1)];
        perceive(&p, start as u32, &mut bits);
        for &s in stops {
            perceive(&p, reach[s % reach.len()], &mut bits);
        }
        Some((p, reach, sb, bits, skip))
    }

    proptest! {
        /// The line-of-sight estimate d(p_a, t) + c of the farthest viewpoint's distance is
        /// never below the scanned one (so it counts no target the scan would not), and the
        /// footprint's dilation gives exactly its scan's values.
        #[test]
        fn farthest_viewpoints_estimated_and_dilated(
            w in 4usize..14,
            h in 2usize..10,
            walls in proptest::collection::vec(0u8..4, 140),
            r in 1.0f64..4.0,
        ) {
            let mut map = crate::walled_map(w, h, &walls);
            map.data_mut()[0] = Occ::Free;
            let p = Problem::new(&map, Cell::new(0, 0), SensorModel::Los(r)).expect("problem");
            let data = map.data();
            let mut dij = Reachability::new(w, h);
            let field: Vec<Vec<f64>> = (0..w * h)
                .filter(|&i| p.reachable(i))
                .take(MAX_POINTS)
                .map(|i| {
                    dij.compute(i, |j| data[j] == Occ::Free);
                    (0..w * h).map(|j| dij.cost(j).unwrap_or(f64::INFINITY)).collect()
                })
                .collect();
            let c = crate::heuristic::max_l1_within(r);
            let scanned = viewpoint_reach(&p, &field, None);
            let estimated = viewpoint_reach(&p, &field, Some(c));
            // The footprint's dilation gives its scan's values exactly.
            let fp = Problem::new(&map, Cell::new(0, 0), SensorModel::Footprint(r)).expect("problem");
            let blank = vec![[f64::NEG_INFINITY; MAX_POINTS]; fp.targets().len()];
            let eroded = viewpoint_reach(&fp, &field, None);
            prop_assert_eq!(eroded, scanned_reach(&fp, &field, None, blank));
            for (s, e) in scanned.iter().zip(&estimated) {
                for a in 0..field.len() {
                    prop_assert!(e[a] >= s[a] - 1e-9, "{} < {}", e[a], s[a]);
                }
            }
        }

        /// With the footprint sensor the first far point's ownership alone never exceeds the
        /// order statistic over exact viewpoint distances (why
        /// [`SkipBudget::without_single_point`] may leave it out), on random maps, perceived
        /// sets, robot cells and budgets.
        #[test]
        fn single_point_ownership_is_dominated_by_viewpoint_distances(
            w in 6usize..16,
            h in 2usize..10,
            walls in proptest::collection::vec(0u8..6, 160),
            stops in proptest::collection::vec(0usize..160, 0..4),
            robot in 0usize..160,
            skip in 1usize..12,
            r in 0.5f64..3.5,
        ) {
            let case = budget_case(w, h, &walls, SensorModel::Footprint(r), &stops, skip);
            let Some((p, reach, mut sb, bits, skip)) = case else { return Ok(()) };
            let q = reach[robot % reach.len()];
            let to_robot: [f64; MAX_POINTS] =
                std::array::from_fn(|a| sb.field.get(a).map_or(0.0, |f| f[q as usize]));
            let single = sb.bound_owned(0, q, &to_robot, &bits, 0.0, None);
            let mut dij = Reachability::new(w, h);
            dij.compute(q as usize, |i| p.reachable(i));
            let mut obs = Observation::new();
            let mut d: Vec<f64> = (0..p.targets().len() as u32)
                .filter(|&t| !crate::heuristic::has(&bits, t))
                .map(|t| {
                    let mut views = Vec::new();
                    p.viewpoints(p.targets()[t as usize], &mut obs, &mut views);
                    views
                        .iter()
                        .map(|&v| dij.cost(v as usize).unwrap_or(f64::INFINITY))
                        .fold(f64::INFINITY, f64::min)
                })
                .collect();
            d.sort_by(|a, b| b.total_cmp(a));
            let order_statistic = d.get(skip).copied().unwrap_or(0.0);
            prop_assert!(single <= order_statistic + 1e-9, "{} > {}", single, order_statistic);
        }

        /// Two far points' bound is the least path bound over every split of the budget,
        /// each evaluated alone (the blocks of splits skipped by their joint bound hide
        /// none smaller), on random maps, perceived sets, robot cells and budgets.
        #[test]
        fn split_blocks_keep_the_least_split(
            w in 6usize..16,
            h in 2usize..10,
            walls in proptest::collection::vec(0u8..6, 160),
            stops in proptest::collection::vec(0usize..160, 0..4),
            robot in 0usize..160,
            skip in 1usize..60,
            fp in any::<bool>(),
        ) {
            let model = if fp { SensorModel::Footprint(1.5) } else { SensorModel::Los(2.0) };
            let case = budget_case(w, h, &walls, model, &stops, skip);
            let Some((_, reach, mut sb, bits, skip)) = case else { return Ok(()) };
            prop_assume!(sb.owned.len() == 2);
            let q = reach[robot % reach.len()];
            let to_robot: [f64; MAX_POINTS] = std::array::from_fn(|a| sb.field[a][q as usize]);
            let got = sb.bound_owned(1, q, &to_robot, &bits, -1.0, None);
            let e = [sb.e[0].clone(), sb.e[1].clone()];
            let at = |l: &[f64], i: usize| l.get(i).copied().unwrap_or(f64::INFINITY);
            let want = (0..=skip)
                .map(|i| path(&sb.between, 2, &to_robot, &[at(&e[0], i), at(&e[1], skip - i)]))
                .fold(f64::INFINITY, f64::min)
                .max(0.0);
            prop_assert_eq!(got.to_bits(), want.to_bits(), "{} vs {}", got, want);
        }

        /// A child bounded with its parent's lists (reused, or skipped against the floor)
        /// gets exactly the value it gets alone, on random maps, paths, floors and budgets.
        #[test]
        fn sharing_the_parents_lists_changes_nothing(
            w in 6usize..16,
            h in 2usize..10,
            walls in proptest::collection::vec(0u8..6, 160),
            stops in proptest::collection::vec(0usize..160, 0..4),
            child in 0usize..160,
            skip in 1usize..12,
            floor in 0.0f64..20.0,
            fp in any::<bool>(),
        ) {
            let model = if fp { SensorModel::Footprint(1.5) } else { SensorModel::Los(2.0) };
            let case = budget_case(w, h, &walls, model, &stops, skip);
            let Some((p, reach, mut sb, parent, _)) = case else { return Ok(()) };
            let pos = reach[child % reach.len()];
            let mut bits = parent.clone();
            perceive(&p, pos, &mut bits);
            let alone = sb.bound(pos, &bits, floor, None, f64::INFINITY);
            sb.enter();
            let shared = sb.bound(pos, &bits, floor, Some(&parent), f64::INFINITY);
            prop_assert_eq!(alone.to_bits(), shared.to_bits());
            // Siblings after it share the scanned lists too.
            let other = reach[(child + 1) % reach.len()];
            let mut bits2 = parent.clone();
            perceive(&p, other, &mut bits2);
            let alone2 = sb.bound(other, &bits2, floor, None, f64::INFINITY);
            sb.enter();
            sb.bound(pos, &bits, floor, Some(&parent), f64::INFINITY);
            let shared2 = sb.bound(other, &bits2, floor, Some(&parent), f64::INFINITY);
            prop_assert_eq!(alone2.to_bits(), shared2.to_bits());
        }
    }
}
