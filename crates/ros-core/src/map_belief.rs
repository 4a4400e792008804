//! The received map as frontier's belief: on a robot the map *is* what the robot knows.
//!
//! A SLAM node (slam_toolbox, Cartographer) integrates the scans; the node only reads its
//! map. So the belief is a ternary grid whose cells take whatever class the latest map
//! message gives them — including back to Unknown, which a SLAM map may do after a loop
//! closure — and reports which cells changed so that frontier upkeep stays incremental.

use grid::{Grid, Occ};
use sense::{Belief, Observation};

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
}
