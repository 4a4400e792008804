//! A copy of the belief kept from one decision to the next, brought up to date by the rows
//! that changed: what decisions that pool the whole map (CC's blocks and visibility, SGA's
//! unknown cells) use to redo only the parts where the map changed.

use grid::{Grid, Occ};

/// Bring `prev` (a copy of an earlier belief of the same size) up to `known` row by row,
/// calling `changed(y, k, new, old)` for each chunk k of `chunk` cells of row y that
/// differed, with the chunk's cells now and before (work ∝ the rows that changed: equal
/// rows are compared whole).
pub(crate) fn sync_rows(
    known: &Grid<Occ>,
    prev: &mut Grid<Occ>,
    chunk: usize,
    mut changed: impl FnMut(usize, usize, &[Occ], &[Occ]),
) {
    let w = known.width();
    for (y, (row, old)) in known
        .data()
        .chunks(w)
        .zip(prev.data_mut().chunks_mut(w))
        .enumerate()
    {
        if row == old {
            continue;
        }
        for (k, (a, b)) in row.chunks(chunk).zip(old.chunks(chunk)).enumerate() {
            if a != b {
                changed(y, k, a, b);
            }
        }
        old.copy_from_slice(row);
    }
}
