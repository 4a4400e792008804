//! The last step of every generator: one connected free space and compact room ids.
//!
//! Generators connect their free space by construction; this step guarantees it. Every free
//! cell not in the largest motion-connected component (8-connected without corner squeezing,
//! see `grid::components`) becomes Occupied and loses its room id. Room ids are then
//! renumbered `1..=room_count` in row-major order of each room's first cell, so every id in
//! that range is used.

use grid::components::{Connectivity, component_sizes, label, largest};
use grid::{Grid, Occ};

/// Keep only the largest motion-connected free component, renumber `rooms` compactly (if
/// given) and return the number of rooms.
pub fn finish(cells: &mut Grid<Occ>, rooms: Option<&mut Grid<u32>>) -> u32 {
    let (labels, count) = label(
        cells.width(),
        cells.height(),
        |i| cells[i] == Occ::Free,
        Connectivity::Motion,
    );
    let keep = largest(&component_sizes(&labels, count)).unwrap_or(0);
    for (c, &l) in cells.data_mut().iter_mut().zip(labels.data()) {
        if l != keep && *c == Occ::Free {
            *c = Occ::Occupied;
        }
    }
    let Some(rooms) = rooms else { return 0 };
    // old id -> new id, assigned on first sight in row-major order
    let max_id = rooms.data().iter().copied().max().unwrap_or(0) as usize;
    let mut new_id = vec![0u32; max_id + 1];
    let mut next = 0u32;
    for (r, &c) in rooms.data_mut().iter_mut().zip(cells.data()) {
        if c != Occ::Free || *r == 0 {
            *r = 0;
            continue;
        }
        let slot = &mut new_id[*r as usize];
        if *slot == 0 {
            next += 1;
            *slot = next;
        }
        *r = *slot;
    }
    next
}
