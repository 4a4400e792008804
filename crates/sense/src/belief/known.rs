//! The ternary known grid: the fast path for ideal sensors.

use grid::{Grid, Occ};

use super::{Belief, Pins, set_class};
use crate::sensor::Observation;

/// A ternary map: each cell is Unknown until observed, then takes the state of its
/// latest observation (for ideal sensors every observation of a cell agrees).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KnownGrid {
    known: Grid<Occ>,
    pins: Pins,
}

impl KnownGrid {
    /// An all-Unknown map of `width × height` cells.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            known: Grid::new(width, height, Occ::Unknown),
            pins: Pins::default(),
        }
    }
}

impl Belief for KnownGrid {
    fn integrate(&mut self, obs: &Observation, changed: &mut Vec<u32>) {
        let n = self.known.len();
        for &(i, o) in &obs.cells {
            let i = i as usize;
            if i < n && o != Occ::Unknown && !self.pins.holds(i) {
                set_class(&mut self.known, i, o, changed);
            }
        }
    }

    fn pin(&mut self, i: usize, class: Occ, changed: &mut Vec<u32>) {
        self.pins.pin(&mut self.known, i, class, changed);
    }

    fn is_pinned(&self, i: usize) -> bool {
        self.pins.holds(i)
    }

    fn known(&self) -> &Grid<Occ> {
        &self.known
    }

    fn is_ternary(&self) -> bool {
        true
    }

    fn p_occupied(&self, i: usize) -> f64 {
        match self.known.data().get(i) {
            Some(Occ::Free) => 0.0,
            Some(Occ::Occupied) => 1.0,
            _ => 0.5,
        }
    }
}
