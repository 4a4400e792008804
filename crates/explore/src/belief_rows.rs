//! A copy of the belief kept from one decision to the next, brought up to date by the rows
//! that changed: what decisions that pool the whole map (CC's blocks and visibility, SGA's
//! unknown cells) use to redo only the parts where the map changed.
//!
//! Which rows changed comes from a [`RowLog`] kept by whoever changes the grid (the
//! frontier upkeep for the belief): a copy that followed the log up to some update compares
//! only the rows changed since, so a decision's cost follows the cells that changed, not
//! the map (comparing a 0.05 m floor plan whole at every decision was a tenth of a 5-robot
//! CC run). When the copy did not follow this log (a new lineage), rows are compared whole.

use std::sync::atomic::{AtomicU64, Ordering};

use grid::{Grid, Occ};

/// Lineages handed out so far (0 is never one: a [`LogPos`] that followed nothing).
static LINEAGES: AtomicU64 = AtomicU64::new(0);

/// A lineage no log has had.
fn fresh_lineage() -> u64 {
    LINEAGES.fetch_add(1, Ordering::Relaxed) + 1
}

/// Per row of a grid, the last update that changed a cell of it. A lineage names one
/// history of the grid: a clone (which may change apart) or a [`restart`](Self::restart)
/// (anything may have changed) begins a new one, so copies that followed the old one are
/// compared whole once.
#[derive(Debug)]
pub(crate) struct RowLog {
    lineage: u64,
    updates: u64,
    row_changed: Vec<u64>,
}

impl Default for RowLog {
    fn default() -> Self {
        Self::new(0)
    }
}

impl Clone for RowLog {
    fn clone(&self) -> Self {
        Self {
            lineage: fresh_lineage(),
            updates: self.updates,
            row_changed: self.row_changed.clone(),
        }
    }
}

impl RowLog {
    /// A log of a grid of `rows` rows.
    pub(crate) fn new(rows: usize) -> Self {
        Self {
            lineage: fresh_lineage(),
            updates: 0,
            row_changed: vec![0; rows],
        }
    }

    /// One update changed the cells of flat indices `cells` of a grid `width` wide (cells
    /// past its rows are ignored).
    pub(crate) fn note(&mut self, width: usize, cells: &[u32]) {
        self.begin();
        for &c in cells {
            self.mark_row(c as usize / width.max(1));
        }
    }

    /// Begin an update (its rows follow with [`mark_row`](Self::mark_row)).
    pub(crate) fn begin(&mut self) {
        self.updates += 1;
    }

    /// The update begun last changed row `y` (ignored past the grid's rows).
    pub(crate) fn mark_row(&mut self, y: usize) {
        if let Some(r) = self.row_changed.get_mut(y) {
            *r = self.updates;
        }
    }

    /// Anything may have changed: copies that followed this log are compared whole once.
    pub(crate) fn restart(&mut self) {
        self.lineage = fresh_lineage();
    }

    /// Where the log is now.
    pub(crate) fn now(&self) -> LogPos {
        LogPos {
            lineage: self.lineage,
            updates: self.updates,
        }
    }
}

/// How far a copy has followed a [`RowLog`] (the default: not at all).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LogPos {
    lineage: u64,
    updates: u64,
}

/// Bring `prev` (a copy of an earlier state of `known`, of the same size) up to `known` row
/// by row, calling `changed(y, k, new, old)` for each chunk k of `chunk` cells of row y that
/// differed, with the chunk's cells now and before. If the copy followed `log` (kept for
/// `known`) to `pos`, only the rows the log has changed since are compared; otherwise every
/// row is (equal rows are compared whole). `pos` is left where the log is.
pub(crate) fn sync_rows(
    known: &Grid<Occ>,
    prev: &mut Grid<Occ>,
    chunk: usize,
    (log, pos): (&RowLog, &mut LogPos),
    mut changed: impl FnMut(usize, usize, &[Occ], &[Occ]),
) {
    let w = known.width();
    let chunk = chunk.max(1);
    let follows = log.lineage == pos.lineage && log.row_changed.len() == known.height();
    let rows = known.data().chunks(w).zip(prev.data_mut().chunks_mut(w));
    for (y, (row, old)) in rows.enumerate() {
        if follows && log.row_changed[y] <= pos.updates {
            continue;
        }
        let Some(mut d) = first_difference(row, old, 0) else {
            continue;
        };
        // Each chunk that holds a difference, in order: the same calls as comparing every
        // chunk, without comparing the equal ones cell by cell.
        loop {
            let k = d / chunk;
            let (lo, hi) = (k * chunk, ((k + 1) * chunk).min(w));
            changed(y, k, &row[lo..hi], &old[lo..hi]);
            match first_difference(row, old, hi) {
                Some(next) => d = next,
                None => break,
            }
        }
        old.copy_from_slice(row);
    }
    *pos = log.now();
}

/// The first index from `from` on where `a` and `b` (of the same length) differ. Compares
/// blocks of [`DIFF_BLOCK`] cells without an exit inside a block, which the compiler turns
/// into a few vector operations; a cell-by-cell comparison (the derived `==` of `Occ`
/// slices) stops at every cell and was most of this module's time on a 0.05 m floor plan.
fn first_difference(a: &[Occ], b: &[Occ], from: usize) -> Option<usize> {
    let (a, b) = (a.get(from..)?, b.get(from..)?);
    let mut at = from;
    for (x, y) in a.chunks(DIFF_BLOCK).zip(b.chunks(DIFF_BLOCK)) {
        let any = x
            .iter()
            .zip(y)
            .fold(0u8, |acc, (&p, &q)| acc | (p as u8 ^ q as u8));
        if any != 0 {
            return x.iter().zip(y).position(|(p, q)| p != q).map(|i| at + i);
        }
        at += x.len();
    }
    None
}

/// Cells compared at once by [`first_difference`].
const DIFF_BLOCK: usize = 32;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Every call `sync_rows` makes, in order.
    fn calls(
        known: &Grid<Occ>,
        prev: &mut Grid<Occ>,
        chunk: usize,
        follow: (&RowLog, &mut LogPos),
    ) -> Vec<(usize, usize, Vec<Occ>, Vec<Occ>)> {
        let mut v = Vec::new();
        sync_rows(known, prev, chunk, follow, |y, k, a, b| {
            v.push((y, k, a.to_vec(), b.to_vec()))
        });
        v
    }

    /// The calls of a copy compared whole, chunk by chunk, written plainly: the oracle of
    /// the block-wise search for differences.
    fn plain_calls(
        known: &Grid<Occ>,
        prev: &Grid<Occ>,
        chunk: usize,
    ) -> Vec<(usize, usize, Vec<Occ>, Vec<Occ>)> {
        let w = known.width();
        let mut v = Vec::new();
        for (y, (row, old)) in known
            .data()
            .chunks(w)
            .zip(prev.data().chunks(w))
            .enumerate()
        {
            for (k, (a, b)) in row.chunks(chunk).zip(old.chunks(chunk)).enumerate() {
                if a != b {
                    v.push((y, k, a.to_vec(), b.to_vec()));
                }
            }
        }
        v
    }

    proptest! {
        /// Compared whole, the calls are those of comparing every chunk of every row, for
        /// rows longer and shorter than the blocks compared at once and changes anywhere.
        #[test]
        fn the_calls_are_every_chunk_that_differs(
            (w, h) in (1usize..150, 1usize..6),
            chunk in 1usize..70,
            before in prop::collection::vec(0u8..3, 900),
            changes in prop::collection::vec((0usize..900, 0u8..3), 0..60),
        ) {
            let occ = |o: u8| [Occ::Unknown, Occ::Free, Occ::Occupied][o as usize];
            let mut prev = Grid::new(w, h, Occ::Unknown);
            for i in 0..w * h {
                prev[i] = occ(before[i % before.len()]);
            }
            let mut known = prev.clone();
            for (i, o) in changes {
                known[i % (w * h)] = occ(o);
            }
            let want = plain_calls(&known, &prev, chunk);
            let mut copy = prev.clone();
            let log = RowLog::new(h);
            let got = calls(&known, &mut copy, chunk, (&log, &mut LogPos::default()));
            prop_assert_eq!(got, want);
            prop_assert_eq!(copy.data(), known.data());
        }

        /// A copy that follows the log makes the calls and ends as a copy compared whole
        /// does, through changes, clones of the log (changing apart) and restarts.
        #[test]
        fn following_the_log_equals_comparing_whole(
            (w, h) in (1usize..80, 1usize..30),
            chunk in 1usize..20,
            steps in prop::collection::vec(
                (prop::collection::vec((0usize..2400, 0u8..3), 0..40), 0u8..8),
                1..12,
            ),
        ) {
            let mut known = Grid::new(w, h, Occ::Unknown);
            let mut log = RowLog::new(h);
            let (mut followed, mut pos) = (known.clone(), LogPos::default());
            let mut whole = known.clone();
            for (cells, event) in steps {
                let mut changed = Vec::new();
                for (i, o) in cells {
                    let i = i % (w * h);
                    let o = [Occ::Unknown, Occ::Free, Occ::Occupied][o as usize];
                    if known[i] != o {
                        known[i] = o;
                        changed.push(i as u32);
                    }
                }
                log.note(w, &changed);
                match event {
                    // a clone changes apart: the copy that followed the original is
                    // compared whole when it is given the clone
                    0 => log = log.clone(),
                    1 => log.restart(),
                    _ => {}
                }
                let a = calls(&known, &mut followed, chunk, (&log, &mut pos));
                // a copy that followed no log is compared whole
                let b = calls(&known, &mut whole, chunk, (&log, &mut LogPos::default()));
                prop_assert_eq!(a, b);
                prop_assert_eq!(followed.data(), known.data());
            }
        }

        /// A copy that followed a log given a clone that changed apart, or a log with
        /// unnoted changes after a restart, still ends equal to the grid.
        #[test]
        fn a_copy_never_trusts_another_history(
            (w, h) in (1usize..40, 1usize..20),
            first in prop::collection::vec(0usize..800, 0..30),
            apart in prop::collection::vec(0usize..800, 1..30),
        ) {
            let mut known = Grid::new(w, h, Occ::Unknown);
            let mut log = RowLog::new(h);
            let (mut copy, mut pos) = (known.clone(), LogPos::default());
            let mut cells: Vec<u32> = first.iter().map(|&i| (i % (w * h)) as u32).collect();
            for &c in &cells {
                known[c as usize] = Occ::Free;
            }
            log.note(w, &cells);
            sync_rows(&known, &mut copy, 4, (&log, &mut pos), |_, _, _, _| {});
            // another history: a clone changes cells the original's copy never saw
            let mut other = log.clone();
            let mut known2 = known.clone();
            cells = apart.iter().map(|&i| (i % (w * h)) as u32).collect();
            for &c in &cells {
                known2[c as usize] = Occ::Occupied;
            }
            // the clone notes nothing: only a whole compare can find the change
            other.begin();
            sync_rows(&known2, &mut copy, 4, (&other, &mut pos), |_, _, _, _| {});
            prop_assert_eq!(copy.data(), known2.data());
        }
    }
}
