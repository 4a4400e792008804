//! The footprint sensor's distance to perception: for the robot at q and a target t,
//! D(q, t) = min over the viewpoints v of t of d(q, v), the shortest path from q to a
//! reachable cell whose footprint holds t. Our strengthening of the paper's Eq. 1 for the
//! footprint sensor (its order statistic, [`crate::heuristic`]): to perceive t the robot
//! must stop at some viewpoint, so the rest of the path is at least D(q, t); the paper's
//! bound uses d(q, t) − r√2 instead, which the footprint sensor breaks (it perceives
//! through walls), and the Euclidean |q − t| − c that replaced it ignores walls altogether:
//! around the corner of an L of corridors D is the path along both arms, the Euclidean
//! bound the hypotenuse.
//!
//! The footprint sees every cell whose centre is within r, walls or not, so the viewpoints
//! of t are the reachable cells of t + S, S the sensor's offsets (symmetric). Hence
//! D(q, ·) is the erosion of the distance field d(q, ·) (∞ off the reachable cells) by S:
//! S is a union of row intervals [−w_dy, w_dy] (read off the sensor's own scan of an empty
//! grid), so with H_w(x, y) = min over |dx| ≤ w of d(q, (x + dx, y)), built for w = 0..=r
//! by H_w = min(H_{w−1}, d shifted by ±w), D(q, t) = min over dy of H_{w_dy}(t + (0, dy)).
//! That is r + 1 passes over each map row, then one pass per row of the footprint over the
//! target columns of the row it serves, all branch-free so that they vectorise, instead of
//! a scan of the disc per target. The map is eroded row by row, one row's layers in a
//! small scratch that stays in cache (whole-map layers were 2.5 % slower on the corridor
//! floor, their memory being touched afresh per solve). Written here: no crate erodes by an arbitrary row-interval shape.

use crate::problem::Problem;

/// The erosion of distance fields by the footprint's offsets.
pub(crate) struct ViewpointDistance {
    /// Half-width w_dy of the footprint's row at dy, for dy = −reach..=reach (`None` for an
    /// empty row).
    half: Vec<Option<usize>>,
    /// Largest half-width.
    reach: usize,
    /// H_w for w = 0..=reach along the map row being eroded (scratch; H_0 is ∞ outside
    /// the row's `span`, the others are written only inside it).
    h: Vec<f64>,
    /// Per row: the columns where some H_w can be finite (within `reach` of the row's
    /// reachable cells), set on first use.
    span: Vec<(usize, usize)>,
    /// The rows holding targets: (row, first target, end of its targets, first column,
    /// last column), set on first use.
    target_rows: Vec<(usize, usize, usize, usize, usize)>,
    /// Per row: its entry in `target_rows`, or `usize::MAX`.
    row_entry: Vec<usize>,
    /// D over each target row's target columns, gathered map row by map row (scratch,
    /// row-major like the map).
    acc: Vec<f64>,
}

impl ViewpointDistance {
    /// The erosion for the footprint whose row intervals (`rows[dy + reach] = (x0, x1)`,
    /// empty as x0 > x1) are symmetric; `None` if they are not.
    pub(crate) fn new(rows: &[(i64, i64)]) -> Option<Self> {
        let mut half = Vec::with_capacity(rows.len());
        for &(x0, x1) in rows {
            if x0 > x1 {
                half.push(None);
            } else if x0 == -x1 {
                half.push(Some(x1 as usize));
            } else {
                return None;
            }
        }
        let reach = half.iter().flatten().copied().max().unwrap_or(0);
        Some(Self {
            half,
            reach,
            h: Vec::new(),
            span: Vec::new(),
            target_rows: Vec::new(),
            row_entry: Vec::new(),
            acc: Vec::new(),
        })
    }

    /// Append to `out` (D(q, t), t) for every target t of `problem`, given `field`, the
    /// path distances from q by flat cell (∞ where not reached); `f64::INFINITY` for a target
    /// whose viewpoints q cannot reach.
    pub(crate) fn append(
        &mut self,
        problem: &Problem,
        field: impl Fn(usize) -> f64,
        out: &mut Vec<(f64, u32)>,
    ) {
        self.nearest(problem, field, |t, v| out.push((v, t)));
    }

    /// The rows' spans and the target rows of `problem`, on first use.
    fn set_up(&mut self, problem: &Problem) {
        let cells = problem.cells();
        let (w, h) = (cells.width(), cells.height());
        if self.span.len() == h {
            return;
        }
        self.h.clear();
        self.h.resize((self.reach + 1) * w, f64::INFINITY);
        self.span = (0..h)
            .map(|y| {
                let reached = (0..w).filter(|&x| problem.reachable(y * w + x));
                match (reached.clone().min(), reached.max()) {
                    (Some(a), Some(b)) => {
                        (a.saturating_sub(self.reach), (b + self.reach).min(w - 1))
                    }
                    _ => (1, 0),
                }
            })
            .collect();
        // The targets are listed row by row.
        let targets = problem.targets();
        self.target_rows.clear();
        self.row_entry.clear();
        self.row_entry.resize(h, usize::MAX);
        let mut k = 0;
        while k < targets.len() {
            let y = targets[k] as usize / w;
            let end = k + targets[k..].partition_point(|&i| i as usize / w == y);
            let (x0, x1) = (targets[k] as usize % w, targets[end - 1] as usize % w);
            self.row_entry[y] = self.target_rows.len();
            self.target_rows.push((y, k, end, x0, x1));
            k = end;
        }
        self.acc.clear();
        self.acc.resize(w * h, f64::INFINITY);
    }

    /// Call `emit(t, v)` for every target t of `problem`, in target order, with v the least
    /// `value` over t's viewpoints (∞ without one). With `value` the negated distances from
    /// a point, −v is the distance to t's farthest viewpoint.
    pub(crate) fn nearest(
        &mut self,
        problem: &Problem,
        field: impl Fn(usize) -> f64,
        mut emit: impl FnMut(u32, f64),
    ) {
        self.set_up(problem);
        let cells = problem.cells();
        let (w, h) = (cells.width(), cells.height());
        for &(y, _, _, x0, x1) in &self.target_rows {
            self.acc[y * w + x0..=y * w + x1].fill(f64::INFINITY);
        }
        let reach = self.half.len() / 2;
        // Map row by map row: its layers H_w (kept in `h`, small enough to stay in cache),
        // each then lowering D on the target row it serves, y = yy − dy for the footprint's
        // row dy with half-width w. (D is a minimum, so the order does not change it.)
        for (yy, &(a, b)) in self.span.iter().enumerate() {
            if a > b {
                continue;
            }
            // No target row within the footprint's reach: nothing to lower.
            let (ylo, yhi) = (yy.saturating_sub(reach), (yy + reach).min(h - 1));
            if self.row_entry[ylo..=yhi].iter().all(|&e| e == usize::MAX) {
                continue;
            }
            let (first, rest) = self.h.split_at_mut(w);
            first.fill(f64::INFINITY);
            for (x, d) in first.iter_mut().enumerate().take(b + 1).skip(a) {
                let i = yy * w + x;
                if problem.reachable(i) {
                    *d = field(i);
                }
            }
            // H_w = min(H_{w−1}, d(x − w), d(x + w)), with d = H_0, over the row's span.
            let mut prev: &[f64] = first;
            for (k, out) in rest.chunks_mut(w).enumerate() {
                let wd = k + 1;
                // The columns with both neighbours on the map, without branches (so the
                // loop vectorises), then the few at either edge.
                let (lo, hi) = (a.max(wd), b.min(w.saturating_sub(wd + 1)));
                // (No interior: every column of the span is an edge.)
                let (lo, hi) = if lo <= hi { (lo, hi) } else { (b + 1, b) };
                if lo <= hi {
                    let (o, pm) = (&mut out[lo..=hi], &prev[lo..=hi]);
                    let (dl, dr) = (&first[lo - wd..=hi - wd], &first[lo + wd..=hi + wd]);
                    for (((o, &v), &l), &r) in o.iter_mut().zip(pm).zip(dl).zip(dr) {
                        let m = if l < r { l } else { r };
                        *o = if m < v { m } else { v };
                    }
                }
                for x in (a..lo).chain(hi + 1..b + 1) {
                    let mut v = prev[x];
                    if x >= wd {
                        v = v.min(first[x - wd]);
                    }
                    if x + wd < w {
                        v = v.min(first[x + wd]);
                    }
                    out[x] = v;
                }
                prev = out;
            }
            // Footprint row dy (index j = dy + reach) with half-width w_dy serves target
            // row yy − dy, over its target columns inside this row's span (∞ outside).
            for (j, hw) in self.half.iter().enumerate() {
                let Some(hw) = *hw else { continue };
                let Some(y) = (yy + reach).checked_sub(j).filter(|&y| y < h) else {
                    continue;
                };
                let e = self.row_entry[y];
                if e == usize::MAX {
                    continue;
                }
                let (_, _, _, x0, x1) = self.target_rows[e];
                let (c0, c1) = (x0.max(a), x1.min(b));
                if c0 > c1 {
                    continue;
                }
                let layer = &self.h[hw * w + c0..=hw * w + c1];
                let row = &mut self.acc[y * w + c0..=y * w + c1];
                for (r, &v) in row.iter_mut().zip(layer) {
                    *r = if v < *r { v } else { *r };
                }
            }
        }
        let targets = problem.targets();
        for &(y, k, end, _, _) in &self.target_rows {
            for (t, &i) in targets[k..end].iter().enumerate() {
                emit((k + t) as u32, self.acc[y * w + i as usize % w]);
            }
        }
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        (self.h.capacity() + self.acc.capacity()) * 8
            + self.target_rows.capacity() * 40
            + self.row_entry.capacity() * 8
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::SensorModel;
    use explore::plan::Reachability;
    use proptest::prelude::*;
    use sense::Observation;

    proptest! {
        /// D(q, t) equals the minimum of d(q, v) over the viewpoints v of t listed by the
        /// problem itself (the footprint's scan), on random maps, ranges and robot cells.
        #[test]
        fn erosion_is_the_distance_to_the_nearest_viewpoint(
            w in 2usize..20,
            h in 2usize..14,
            walls in proptest::collection::vec(0u8..4, 280),
            pick in 0usize..280,
            r in 0.5f64..4.5,
        ) {
            let case = crate::walled_problem(w, h, &walls, pick, SensorModel::Footprint(r));
            prop_assume!(case.is_some());
            let (p, _) = case.expect("assumed");
            let reach: Vec<usize> = (0..w * h).filter(|&i| p.reachable(i)).collect();
            let q = reach[pick % reach.len()];
            let mut dij = Reachability::new(w, h);
            dij.compute(q, |i| p.reachable(i));
            let d = |i: usize| dij.cost(i).unwrap_or(f64::INFINITY);
            let mut vd = ViewpointDistance::new(&crate::coverage_rate::offsets(p.model())).expect("symmetric");
            let mut got = Vec::new();
            vd.append(&p, d, &mut got);
            prop_assert_eq!(got.len(), p.targets().len());
            let mut obs = Observation::new();
            for &(v, t) in &got {
                let mut views = Vec::new();
                p.viewpoints(p.targets()[t as usize], &mut obs, &mut views);
                let want = views.iter().map(|&v| d(v as usize)).fold(f64::INFINITY, f64::min);
                prop_assert_eq!(v.to_bits(), want.to_bits(), "target {}", t);
            }
        }
    }
}
