//! Holz et al.'s probabilistic reflection map: per cell, the number of beams reflected in
//! it (hits) and the number that passed through it (misses).
//!
//! `p = hits / (hits + misses)`; a cell is Unknown iff it was never observed, Free iff
//! `p ≤ p_free` (0.25 by default, their traversability threshold), Occupied otherwise.
//! An observed Occupied cell counts as a hit, an observed Free cell as a miss.

use grid::{Grid, Occ};

use super::{Belief, Pins, set_class};
use crate::error::SenseError;
use crate::sensor::Observation;

/// Holz et al.'s default free threshold: free iff p ≤ 0.25.
pub const P_FREE: f64 = 0.25;

/// Hit/miss counts per cell with the Free/Occupied/Unknown classification kept up to date.
#[derive(Clone, Debug, PartialEq)]
pub struct ReflectionMap {
    hits: Vec<u32>,
    misses: Vec<u32>,
    p_free: f64,
    known: Grid<Occ>,
    pins: Pins,
}

impl ReflectionMap {
    /// An unobserved map of `width × height` cells with `p_free = 0.25`.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            hits: vec![0; width * height],
            misses: vec![0; width * height],
            p_free: P_FREE,
            known: Grid::new(width, height, Occ::Unknown),
            pins: Pins::default(),
        }
    }

    /// An unobserved map with free threshold `p_free` in `[0, 1]`.
    pub fn with_p_free(width: usize, height: usize, p_free: f64) -> Result<Self, SenseError> {
        if !(0.0..=1.0).contains(&p_free) {
            return Err(SenseError::BadProbability {
                what: "p_free",
                found: p_free,
            });
        }
        Ok(Self {
            p_free,
            ..Self::new(width, height)
        })
    }

    /// Number of hits (observed Occupied) of cell `i` (0 outside the map).
    pub fn hits(&self, i: usize) -> u32 {
        self.hits.get(i).copied().unwrap_or(0)
    }

    /// Number of misses (observed Free) of cell `i` (0 outside the map).
    pub fn misses(&self, i: usize) -> u32 {
        self.misses.get(i).copied().unwrap_or(0)
    }

    /// The free threshold.
    pub fn p_free(&self) -> f64 {
        self.p_free
    }

    fn classify(&self, i: usize) -> Occ {
        let (h, m) = (u64::from(self.hits[i]), u64::from(self.misses[i]));
        if h + m == 0 {
            Occ::Unknown
        } else if h as f64 <= self.p_free * (h + m) as f64 {
            // p = h / (h + m) ≤ p_free, without dividing (exact for p_free = 0.25).
            Occ::Free
        } else {
            Occ::Occupied
        }
    }
}

impl Belief for ReflectionMap {
    fn integrate(&mut self, obs: &Observation, changed: &mut Vec<u32>) {
        let n = self.known.len();
        for &(i, o) in &obs.cells {
            let i = i as usize;
            if i >= n || self.pins.holds(i) {
                continue;
            }
            match o {
                Occ::Occupied => self.hits[i] = self.hits[i].saturating_add(1),
                Occ::Free => self.misses[i] = self.misses[i].saturating_add(1),
                Occ::Unknown => continue,
            }
            // One more hit only raises p and one more miss only lowers it, so a cell already
            // of the class observed keeps it: only the others are classified again.
            if self.known[i] != o {
                let class = self.classify(i);
                set_class(&mut self.known, i, class, changed);
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

    fn p_occupied(&self, i: usize) -> f64 {
        let (h, m) = (self.hits(i), self.misses(i));
        if self.pins.holds(i) {
            if self.known[i] == Occ::Occupied {
                1.0
            } else {
                0.0
            }
        } else if h + m == 0 {
            0.5
        } else {
            f64::from(h) / (f64::from(h) + f64::from(m))
        }
    }
}
