//! The received map as frontier's belief: on a robot the map *is* what the robot knows.
//!
//! A SLAM node (slam_toolbox, Cartographer) integrates the scans; the node only reads its
//! map. So the belief is a ternary grid whose cells take whatever class the latest map
//! message gives them — including back to Unknown, which a SLAM map may do after a loop
//! closure — and reports which cells changed so that frontier upkeep stays incremental.

use grid::{Grid, Occ};
use record::msgs::OccupancyGrid;
use record::occupancy::{MapFrame, class_of};
use sense::{Belief, Observation};

/// Cells compared at once by [`MapBelief::set_from_msg`].
const CHUNK: usize = 64;

/// A ternary belief set from map messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapBelief {
    known: Grid<Occ>,
}

impl MapBelief {
    /// An all-Unknown belief of `width × height` cells.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            known: Grid::new(width, height, Occ::Unknown),
        }
    }

    /// The belief whose cells are `known` (a map's classes, taken whole).
    pub fn from_known(known: Grid<Occ>) -> Self {
        Self { known }
    }

    /// Set every cell to its class in `msg` (whose frame, `frame`, has this belief's size),
    /// pushing the index of each cell whose class changed to `changed`, in index order:
    /// one pass over the message, classifying as [`record::occupancy::classify_into`].
    pub fn set_from_msg(&mut self, msg: &OccupancyGrid, frame: &MapFrame, changed: &mut Vec<u32>) {
        let (w, h) = (frame.width, frame.height);
        debug_assert_eq!(w * h, self.known.len());
        debug_assert_eq!(msg.data.len(), self.known.len());
        let data = self.known.data_mut();
        for (row, dst) in data.chunks_exact_mut(w).enumerate().take(h) {
            // The message's rows run from the bottom (its origin) up, the belief's down.
            let src = &msg.data[(h - 1 - row) * w..(h - row) * w];
            // Most of a map is as it was: compare a chunk at a time without branches, and
            // look cell by cell only at the chunks that differ.
            for (k, (dst, src)) in dst.chunks_mut(CHUNK).zip(src.chunks(CHUNK)).enumerate() {
                let diff = dst.iter().zip(src).fold(0u8, |acc, (&slot, &v)| {
                    acc | (slot as u8 ^ class_of(v) as u8)
                });
                if diff == 0 {
                    continue;
                }
                let first = row * w + k * CHUNK;
                for (x, (slot, &v)) in dst.iter_mut().zip(src).enumerate() {
                    let c = class_of(v);
                    if *slot != c {
                        *slot = c;
                        changed.push((first + x) as u32);
                    }
                }
            }
        }
    }

    /// Set every cell to `classes` (same size, row-major), pushing the index of each cell
    /// whose class changed to `changed`.
    pub fn set_all(&mut self, classes: &[Occ], changed: &mut Vec<u32>) {
        debug_assert_eq!(classes.len(), self.known.len());
        for (i, (slot, &c)) in self.known.data_mut().iter_mut().zip(classes).enumerate() {
            if *slot != c {
                *slot = c;
                changed.push(i as u32);
            }
        }
    }
}

impl Belief for MapBelief {
    fn integrate(&mut self, obs: &Observation, changed: &mut Vec<u32>) {
        let n = self.known.len();
        for &(i, o) in &obs.cells {
            let i = i as usize;
            if i < n && self.known[i] != o {
                self.known[i] = o;
                changed.push(i as u32);
            }
        }
    }

    fn known(&self) -> &Grid<Occ> {
        &self.known
    }

    fn p_occupied(&self, i: usize) -> f64 {
        match self.known.data().get(i) {
            Some(Occ::Free) => 0.0,
            Some(Occ::Occupied) => 1.0,
            _ => 0.5,
        }
    }

    fn is_ternary(&self) -> bool {
        true
    }

    fn pin(&mut self, i: usize, class: Occ, changed: &mut Vec<u32>) {
        // The SLAM node owns the map; the node never pins, but honour the contract.
        if i < self.known.len() && class != Occ::Unknown && self.known[i] != class {
            self.known[i] = class;
            changed.push(i as u32);
        }
    }

    fn is_pinned(&self, _i: usize) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_all_reports_exactly_the_changed_cells() {
        let mut b = MapBelief::new(3, 1);
        let mut changed = Vec::new();
        b.set_all(&[Occ::Free, Occ::Unknown, Occ::Occupied], &mut changed);
        assert_eq!(changed, [0, 2]);
        changed.clear();
        b.set_all(&[Occ::Free, Occ::Free, Occ::Unknown], &mut changed);
        assert_eq!(changed, [1, 2]);
        assert_eq!(b.known().data(), &[Occ::Free, Occ::Free, Occ::Unknown]);
    }

    #[test]
    fn set_from_msg_is_classify_then_set_all() {
        // A 3 × 2 map: the message's first row is the belief's last.
        let mut msg = OccupancyGrid::default();
        msg.info.width = 3;
        msg.info.height = 2;
        msg.info.resolution = 0.5;
        let frame = |m: &OccupancyGrid| record::occupancy::frame_of(m).unwrap();
        let mut a = MapBelief::new(3, 2);
        let mut b = MapBelief::new(3, 2);
        for data in [[-1, 0, 100, 30, 25, 65], [0, 0, 100, 100, -1, 70], [-1; 6]] {
            msg.data = data.to_vec();
            let f = frame(&msg);
            let mut classes = vec![Occ::Unknown; 6];
            record::occupancy::classify_into(&msg, &f, &mut classes);
            let (mut ca, mut cb) = (Vec::new(), Vec::new());
            a.set_all(&classes, &mut ca);
            b.set_from_msg(&msg, &f, &mut cb);
            assert_eq!(ca, cb);
            assert_eq!(a, b);
        }
        assert_eq!(a.known().data(), &[Occ::Unknown; 6]);
    }
}
