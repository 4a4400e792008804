//! Yamauchi's evidence grid: per-cell occupancy probability with prior 0.5, kept in
//! log-odds.
//!
//! Inverse sensor model: a cell observed Occupied has `p(occ | hit) = 0.7`, one observed
//! Free has `p(occ | miss) = 0.4`, so every observation adds `l_occ = ln(0.7/0.3) ≈ 0.847`
//! or `l_free = ln(0.4/0.6) ≈ −0.405` to the cell's log-odds (the prior's log-odds is 0).
//! Log-odds are clamped to `±ln(0.99/0.01)` so that a cell can still change its mind.
//! Classes (Yamauchi: open < prior < occupied): Free iff `p < 0.5 − ε`, Occupied iff
//! `p > 0.5 + ε`, Unknown iff `p` equals the prior within ε (ε = 1e-9 on the log-odds,
//! which is about 2.5e-10 in probability).

use grid::{Grid, Occ};

use super::{Belief, Pins, set_class};
use crate::error::SenseError;
use crate::sensor::Observation;

/// Default `p(occupied | cell observed Occupied)`.
pub const P_HIT: f64 = 0.7;
/// Default `p(occupied | cell observed Free)`.
pub const P_MISS: f64 = 0.4;
/// Probability at which log-odds are clamped (and `1 −` it on the free side).
pub const P_CLAMP: f64 = 0.99;
/// Log-odds within ±EPS_LOG_ODDS of 0 count as the prior (Unknown).
pub const EPS_LOG_ODDS: f64 = 1e-9;

fn logit(p: f64) -> f64 {
    (p / (1.0 - p)).ln()
}

/// A log-odds occupancy grid with prior 0.5 and the classification kept up to date.
#[derive(Clone, Debug, PartialEq)]
pub struct EvidenceGrid {
    log_odds: Vec<f64>,
    l_occ: f64,
    l_free: f64,
    l_max: f64,
    known: Grid<Occ>,
    pins: Pins,
}

impl EvidenceGrid {
    /// An all-prior map of `width × height` cells with the default inverse sensor model.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            log_odds: vec![0.0; width * height],
            l_occ: logit(P_HIT),
            l_free: logit(P_MISS),
            l_max: logit(P_CLAMP),
            known: Grid::new(width, height, Occ::Unknown),
            pins: Pins::default(),
        }
    }

    /// An all-prior map with inverse sensor model `p_hit` in (0.5, 1) and `p_miss` in
    /// (0, 0.5).
    pub fn with_model(
        width: usize,
        height: usize,
        p_hit: f64,
        p_miss: f64,
    ) -> Result<Self, SenseError> {
        if !(p_hit > 0.5 && p_hit < 1.0) {
            return Err(SenseError::BadProbability {
                what: "p_hit",
                found: p_hit,
            });
        }
        if !(p_miss > 0.0 && p_miss < 0.5) {
            return Err(SenseError::BadProbability {
                what: "p_miss",
                found: p_miss,
            });
        }
        Ok(Self {
            l_occ: logit(p_hit),
            l_free: logit(p_miss),
            ..Self::new(width, height)
        })
    }

    /// Log-odds of occupancy of cell `i` (0 = prior; 0 outside the map).
    pub fn log_odds(&self, i: usize) -> f64 {
        self.log_odds.get(i).copied().unwrap_or(0.0)
    }

    /// The log-odds a full-weight Occupied observation adds (`ln(p_hit / (1 − p_hit))`).
    pub fn l_occ(&self) -> f64 {
        self.l_occ
    }

    /// The log-odds a full-weight Free observation adds (`ln(p_miss / (1 − p_miss))`, < 0).
    pub fn l_free(&self) -> f64 {
        self.l_free
    }

    /// Add graded evidence: `delta` log-odds to each listed cell (clamped as in
    /// [`Belief::integrate`]); push the index of every cell whose class changed.
    ///
    /// For inverse sensor models that weigh cells (the sonar cone). Indices outside the map
    /// are ignored; callers merge duplicates first, so that each index is pushed at most
    /// once per call.
    pub fn add_evidence(&mut self, deltas: &[(u32, f64)], changed: &mut Vec<u32>) {
        let n = self.known.len();
        for &(i, delta) in deltas {
            let i = i as usize;
            if i >= n || !delta.is_finite() {
                continue;
            }
            if self.pins.holds(i) {
                continue;
            }
            let l = (self.log_odds[i] + delta).clamp(-self.l_max, self.l_max);
            self.log_odds[i] = l;
            set_class(&mut self.known, i, Self::classify(l), changed);
        }
    }

    /// The class of a log-odds value.
    pub fn classify(l: f64) -> Occ {
        if l < -EPS_LOG_ODDS {
            Occ::Free
        } else if l > EPS_LOG_ODDS {
            Occ::Occupied
        } else {
            Occ::Unknown
        }
    }
}

impl Belief for EvidenceGrid {
    fn integrate(&mut self, obs: &Observation, changed: &mut Vec<u32>) {
        let n = self.known.len();
        for &(i, o) in &obs.cells {
            let i = i as usize;
            if i >= n {
                continue;
            }
            let delta = match o {
                Occ::Occupied => self.l_occ,
                Occ::Free => self.l_free,
                Occ::Unknown => continue,
            };
            if self.pins.holds(i) {
                continue;
            }
            let l = (self.log_odds[i] + delta).clamp(-self.l_max, self.l_max);
            self.log_odds[i] = l;
            set_class(&mut self.known, i, Self::classify(l), changed);
        }
    }

    fn known(&self) -> &Grid<Occ> {
        &self.known
    }

    fn p_occupied(&self, i: usize) -> f64 {
        1.0 / (1.0 + (-self.log_odds(i)).exp())
    }

    fn pin(&mut self, i: usize, class: Occ, changed: &mut Vec<u32>) {
        if self.pins.pin(&mut self.known, i, class, changed) {
            self.log_odds[i] = if class == Occ::Free {
                -self.l_max
            } else {
                self.l_max
            };
        }
    }

    fn is_pinned(&self, i: usize) -> bool {
        self.pins.holds(i)
    }

    fn evidence_mut(&mut self) -> Option<&mut EvidenceGrid> {
        Some(self)
    }
}
