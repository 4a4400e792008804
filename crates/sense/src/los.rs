//! The ideal 360° laser of Quattrini Li et al.: a cell is seen iff its centre is joined
//! to the sensor cell's centre by a segment of length ≤ r that crosses only free cells
//! and never squeezes between two non-free cells sharing a vertex (exact semantics in
//! [`crate::segment`]). The occupied cell ending a segment is seen as occupied.
//!
//! A scan walks the shared [`LosTemplate`] prefix tree, skipping the subtree of every
//! blocked cell or vertex, so its cost grows with what is seen (see [`LosTemplate`] for
//! the measured constant). From [`FASTER_FROM_RANGE`] cells of range on, where the walk
//! visits about 0.9 r³ nodes, the scan is computed by shadow casting instead and put back
//! in the walk's order through the template's ranks: the same list of cells either way.
//! Its result equals [`los_visible`](crate::los_visible) for every cell (checked by
//! property tests).
//! A predicted scan ([`Sensor::predict`]) sees the belief with Unknown cells transparent,
//! by the same walk or, from the same range on, the same shadow casting.

use std::sync::Arc;

use grid::{Cell, Grid, Occ};

use crate::error::SenseError;
use crate::ray_template::{LosNode, LosTemplate};
use crate::sensor::{Observation, Pose, Sensor, observed, predicted_transparent};
use crate::shadow::{self, FASTER_FROM_RANGE, ShadowScratch};
use crate::unseen::Unseen;

/// The ideal line-of-sight sensor (360°, range in cells), backed by a shared ray template.
#[derive(Clone, Debug)]
pub struct LosSensor {
    template: Arc<LosTemplate>,
}

impl LosSensor {
    /// A line-of-sight sensor of range `r` cells; its template is shared with other sensors
    /// of the same range. Errors if `r` is negative, not finite or above
    /// [`MAX_TEMPLATE_RANGE_CELLS`](crate::MAX_TEMPLATE_RANGE_CELLS).
    pub fn new(r: f64) -> Result<Self, SenseError> {
        Ok(Self {
            template: LosTemplate::shared(r)?,
        })
    }

    /// A sensor over an existing template.
    pub fn with_template(template: Arc<LosTemplate>) -> Self {
        Self { template }
    }

    /// The ray template this sensor walks.
    pub fn template(&self) -> &Arc<LosTemplate> {
        &self.template
    }

    /// Call `seen(flat index, observed state)` for every cell seen from `origin` in `truth`,
    /// in template pre-order (each cell once). Nothing is seen from outside the grid.
    #[inline]
    pub fn for_each_seen(&self, truth: &Grid<Occ>, origin: Cell, mut seen: impl FnMut(u32, Occ)) {
        self.for_each_through(
            truth,
            origin,
            |s| s == Occ::Free,
            |i, s| seen(i, observed(s)),
        );
    }

    /// Call `seen(flat index, state in grid)` for every cell reached from `origin` when
    /// rays pass through the cells whose state is `transparent` and stop at (and report)
    /// the first other one; the squeeze test blocks between two non-transparent cells.
    #[inline]
    fn for_each_through(
        &self,
        grid: &Grid<Occ>,
        origin: Cell,
        transparent: impl Fn(Occ) -> bool,
        mut seen: impl FnMut(u32, Occ),
    ) {
        let nodes = self.template.nodes();
        let Some(o) = grid.checked_index(origin) else {
            return;
        };
        let (w, h) = (grid.width() as i64, grid.height() as i64);
        let reach = self.template.range().floor() as i64;
        let (ox, oy) = (i64::from(origin.x), i64::from(origin.y));
        let data = grid.data();
        if ox >= reach && oy >= reach && ox + reach < w && oy + reach < h {
            // The whole disc is inside the grid: plain index arithmetic.
            let w = w as isize;
            let at = move |dx: i16, dy: i16| (o as isize + dy as isize * w + dx as isize) as usize;
            walk(nodes, data, at, &transparent, &mut seen);
        } else {
            // Near the border: cells outside the grid are opaque (index `usize::MAX`).
            let at = move |dx: i16, dy: i16| {
                let (x, y) = (ox + i64::from(dx), oy + i64::from(dy));
                if x >= 0 && y >= 0 && x < w && y < h {
                    (y * w + x) as usize
                } else {
                    usize::MAX
                }
            };
            walk(nodes, data, at, &transparent, &mut seen);
        }
    }
}

/// Walk the template: `at(dx, dy)` gives the flat index of an offset (`usize::MAX` outside
/// the grid). A node whose squeeze check fails or whose cell is not transparent (or
/// outside) has its subtree skipped; target cells inside the grid are reported with their
/// state.
#[inline(always)]
fn walk(
    nodes: &[LosNode],
    data: &[Occ],
    at: impl Fn(i16, i16) -> usize,
    transparent: &impl Fn(Occ) -> bool,
    seen: &mut impl FnMut(u32, Occ),
) {
    let free = |i: usize| data.get(i).is_some_and(|&s| transparent(s));
    let mut k = 0;
    while k < nodes.len() {
        let n = nodes[k];
        if n.squeeze() {
            let (sx, sy) = (n.dx.signum(), n.dy.signum());
            if !free(at(n.dx - sx, n.dy)) && !free(at(n.dx, n.dy - sy)) {
                k = n.end();
                continue;
            }
        }
        let i = at(n.dx, n.dy);
        let Some(&state) = data.get(i) else {
            k = n.end();
            continue;
        };
        if n.is_target() {
            seen(i as u32, state);
        }
        k = if transparent(state) { k + 1 } else { n.end() };
    }
}

thread_local! {
    /// Buffers of the shadow-casting scan, kept per thread so that a scan allocates nothing
    /// once it has run.
    static SCAN: std::cell::RefCell<ShadowScan> = std::cell::RefCell::new(ShadowScan::default());
}

/// Scratch of a shadow-casting scan: the sweep's buffers and the seen cells by rank.
#[derive(Default)]
struct ShadowScan {
    shadows: ShadowScratch,
    /// Per rank: the seen cell and its state, valid where `stamp == epoch`.
    slot: Vec<(u32, Occ)>,
    stamp: Vec<u32>,
    epoch: u32,
    /// The ranks filled, for a scan that reports few cells.
    ranks: Vec<u32>,
}

impl LosSensor {
    /// [`Sensor::scan`] by shadow casting ([`crate::shadow`]), which from
    /// [`FASTER_FROM_RANGE`] cells on looks at fewer cells than the template walk: the same
    /// cells (both are `segment_clear`'s), put back in the walk's order through the
    /// template's ranks, so that an observation is the same list either way.
    fn scan_by_shadows(
        &self,
        truth: &Grid<Occ>,
        origin: Cell,
        columns: &[i64; 8],
        keep: impl Fn(usize) -> bool,
        out: &mut Vec<(u32, Occ)>,
    ) {
        self.for_each_by_shadows(
            truth,
            origin,
            columns,
            |s| s == Occ::Free,
            |i, _| keep(i),
            |i, s| out.push((i, observed(s))),
        );
    }

    /// [`Self::for_each_through`] by shadow casting: `seen(flat index, state in grid)` for
    /// the cells `keep` accepts, in the template walk's order (through the template's
    /// ranks), stopping each octant after `columns[k]`.
    fn for_each_by_shadows(
        &self,
        grid: &Grid<Occ>,
        origin: Cell,
        columns: &[i64; 8],
        transparent: impl Fn(Occ) -> bool,
        keep: impl Fn(usize, Occ) -> bool,
        mut seen: impl FnMut(u32, Occ),
    ) {
        let t = &self.template;
        let w = grid.width() as i64;
        let (ox, oy) = (i64::from(origin.x), i64::from(origin.y));
        SCAN.with(|scan| {
            let mut scan = scan.borrow_mut();
            let ShadowScan {
                shadows,
                slot,
                stamp,
                epoch,
                ranks,
            } = &mut *scan;
            if slot.len() < t.targets() {
                slot.resize(t.targets(), (0, Occ::Unknown));
                stamp.resize(t.targets(), 0);
            }
            if *epoch == u32::MAX {
                stamp.fill(0);
                *epoch = 0;
            }
            *epoch += 1;
            let e = *epoch;
            let mut last = 0usize;
            ranks.clear();
            shadow::visible_within(
                grid,
                origin,
                t.range(),
                columns,
                transparent,
                shadows,
                |i, s| keep(i as usize, s),
                |i, s| {
                    let (x, y) = (i64::from(i) % w, i64::from(i) / w);
                    if let Some(k) = t.rank((x - ox) as i32, (y - oy) as i32) {
                        let k = k as usize;
                        slot[k] = (i, s);
                        stamp[k] = e;
                        last = last.max(k + 1);
                        ranks.push(k as u32);
                    }
                },
            );
            // Few cells (scans of what is new): sort their ranks rather than read every
            // rank up to the last.
            if ranks.len() * 16 < last {
                ranks.sort_unstable();
                for &k in ranks.iter() {
                    let (i, s) = slot[k as usize];
                    seen(i, s);
                }
            } else {
                for k in 0..last {
                    if stamp[k] == e {
                        let (i, s) = slot[k];
                        seen(i, s);
                    }
                }
            }
        });
    }

    /// The cells a predicted scan from `pose` sees whose state in `known` passes `keep`, in
    /// the template walk's order: Unknown cells are transparent; from [`FASTER_FROM_RANGE`]
    /// on by shadow casting, as [`Sensor::scan`] (the same list).
    fn predict_where(
        &self,
        known: &Grid<Occ>,
        pose: Pose,
        keep: impl Fn(Occ) -> bool,
        out: &mut Vec<u32>,
    ) {
        out.clear();
        if self.template.range() >= FASTER_FROM_RANGE {
            let all = [i64::MAX; 8];
            let (cell, transparent) = (pose.cell, predicted_transparent);
            let kept = |_, s| keep(s);
            self.for_each_by_shadows(known, cell, &all, transparent, kept, |i, _| out.push(i));
        } else {
            self.for_each_through(known, pose.cell, predicted_transparent, |i, s| {
                if keep(s) {
                    out.push(i);
                }
            });
        }
    }
}

impl Sensor for LosSensor {
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation) {
        out.clear();
        out.origin = pose.cell;
        if self.template.range() >= FASTER_FROM_RANGE {
            self.scan_by_shadows(truth, pose.cell, &[i64::MAX; 8], |_| true, &mut out.cells);
            return;
        }
        let cells = &mut out.cells;
        self.for_each_seen(truth, pose.cell, |i, s| cells.push((i, s)));
    }

    fn skips_known(&self) -> bool {
        true
    }

    /// Only the cells that tell the robot scanning something are reported; shadow casting
    /// also stops each octant after the last column holding a block with such cells, and
    /// with none in range the template walk is not started.
    fn scan_unseen(&self, truth: &Grid<Occ>, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        let columns = shadow::octant_columns(pose.cell, self.template.range(), unseen);
        self.scan_unseen_within(truth, pose, unseen, &columns, out);
    }

    fn range_cells(&self) -> f64 {
        self.template.range()
    }

    fn predict(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        self.predict_where(known, pose, |_| true, out);
    }

    fn predict_unknown(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        self.predict_where(known, pose, |s| s == Occ::Unknown, out);
    }
}

impl LosSensor {
    /// [`Sensor::scan_unseen`] with `columns`, the [`shadow::octant_columns`] of `pose`
    /// for `unseen`, already found.
    pub(crate) fn scan_unseen_within(
        &self,
        truth: &Grid<Occ>,
        pose: Pose,
        unseen: &Unseen,
        columns: &[i64; 8],
        out: &mut Observation,
    ) {
        out.clear();
        out.origin = pose.cell;
        if columns.iter().all(|&c| c == 0) {
            if let Some(i) = truth.checked_index(pose.cell)
                && unseen.tells(i)
            {
                out.cells.push((i as u32, observed(truth.data()[i])));
            }
            return;
        }
        let keep = |i: usize| unseen.tells(i);
        if self.template.range() >= FASTER_FROM_RANGE {
            self.scan_by_shadows(truth, pose.cell, columns, keep, &mut out.cells);
        } else {
            let cells = &mut out.cells;
            self.for_each_seen(truth, pose.cell, |i, s| {
                if keep(i as usize) {
                    cells.push((i, s));
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_area_sees_the_whole_disc() {
        let g = Grid::new(11, 11, Occ::Free);
        let s = LosSensor::new(3.0).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(5, 5), 0.0), &mut obs);
        assert_eq!(obs.len(), 29);
        assert!(obs.cells.iter().all(|&(_, o)| o == Occ::Free));
        // At the corner, only the in-grid quarter: offsets with dx, dy ≥ 0 and d² ≤ 9.
        s.scan(&g, Pose::new(Cell::new(0, 0), 0.0), &mut obs);
        assert_eq!(obs.len(), 11);
        // Outside the grid nothing is seen.
        s.scan(&g, Pose::new(Cell::new(-1, 0), 0.0), &mut obs);
        assert!(obs.is_empty());
    }

    #[test]
    fn wall_is_seen_and_hides_what_is_behind() {
        // Row 0: sensor at x=0, wall at x=2.
        let mut g = Grid::new(5, 1, Occ::Free);
        g.set(Cell::new(2, 0), Occ::Occupied);
        let s = LosSensor::new(4.0).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(0, 0), 0.0), &mut obs);
        let mut seen = obs.cells.clone();
        seen.sort_unstable();
        assert_eq!(
            seen,
            vec![(0, Occ::Free), (1, Occ::Free), (2, Occ::Occupied)]
        );
    }

    #[test]
    fn unknown_truth_is_seen_as_occupied() {
        let mut g = Grid::new(3, 1, Occ::Free);
        g.set(Cell::new(1, 0), Occ::Unknown);
        let s = LosSensor::new(2.0).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(0, 0), 0.0), &mut obs);
        let mut seen = obs.cells.clone();
        seen.sort_unstable();
        assert_eq!(seen, vec![(0, Occ::Free), (1, Occ::Occupied)]);
    }
}
