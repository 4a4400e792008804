//! Expected information gain of a sensing action: the drop in map entropy that a simulated
//! scan and map update would bring (González-Baños & Latombe 2002, as Holz et al. 2010 ran
//! it, §3.2: `I(p) = H_p(x) − Ĥ_p(x)`, with the binary cell entropy
//! `H = −Σ [p log p + (1 − p) log(1 − p)]`).
//!
//! The simulated scan is the sensor's [`predict`](crate::Sensor::predict) on the belief's
//! classes: rays pass through Free and Unknown cells and stop at known Occupied ones. Only
//! the cells the scan touches change, so `I(p)` is a sum over those cells (each counted
//! once) of the expected entropy drop of one simulated observation.
//!
//! The simulated update (our choice; the paper does not spell it out) is an
//! [`InverseModel`]: a touched cell with occupancy `p` is observed as a hit with
//! probability `p` and as a miss otherwise, and its probability becomes the Bayesian
//! (log-odds) posterior under the model's `p(occ | hit)` or `p(occ | miss)`. With the
//! [`InverseModel::IDEAL`] model every touched cell becomes certain, so the drop is just
//! its entropy: on the ternary known grid (p ∈ {0, ½, 1}) `I(p)` is the number of
//! Unknown cells the scan would reveal, one bit each. Entropies are in bits.
//!
//! Deviation: Holz et al. simulate one scan with one outcome; we take the expectation over
//! each cell's two outcomes, which needs no guess of what the unknown cells hold.

use crate::belief::{Belief, BeliefKind};
use crate::sensor::{Pose, Sensor};

/// Binary entropy in bits of a cell that is occupied with probability `p` (0 at 0 and 1).
#[inline]
pub fn entropy(p: f64) -> f64 {
    if p <= 0.0 || p >= 1.0 {
        0.0
    } else {
        -(p * p.log2() + (1.0 - p) * (1.0 - p).log2())
    }
}

/// The inverse sensor model of a simulated observation: `p(occupied | observed Occupied)`
/// and `p(occupied | observed Free)`, applied as a Bayesian log-odds update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseModel {
    /// `p(occupied | hit)`, in `(0.5, 1]`; 1 makes a hit certain.
    pub p_hit: f64,
    /// `p(occupied | miss)`, in `[0, 0.5)`; 0 makes a miss certain.
    pub p_miss: f64,
}

impl Default for InverseModel {
    fn default() -> Self {
        Self::IDEAL
    }
}

impl InverseModel {
    /// An ideal sensor: every observed cell becomes certain (the ternary known grid).
    pub const IDEAL: Self = Self {
        p_hit: 1.0,
        p_miss: 0.0,
    };

    /// Yamauchi's evidence grid defaults (`p_hit = 0.7`, `p_miss = 0.4`, as in
    /// [`EvidenceGrid::new`](crate::EvidenceGrid::new)).
    pub const EVIDENCE: Self = Self {
        p_hit: 0.7,
        p_miss: 0.4,
    };

    /// The model that matches a belief kind's own update: [`IDEAL`](Self::IDEAL) for the
    /// known grid, [`EVIDENCE`](Self::EVIDENCE) for the evidence grid, and `IDEAL` for the
    /// reflection map, whose count update depends on the number of past observations, which
    /// a probability alone does not give (so an observed cell is taken as settled).
    pub fn for_belief(kind: BeliefKind) -> Self {
        match kind {
            BeliefKind::Known | BeliefKind::Reflection => Self::IDEAL,
            BeliefKind::Evidence => Self::EVIDENCE,
        }
    }

    /// Occupancy after one observation of a cell with occupancy `p` whose sensor model says
    /// `q = p(occupied | observation)`, by Bayes' rule in odds form (prior ½).
    #[inline]
    fn posterior(p: f64, q: f64) -> f64 {
        let num = p * q;
        let den = num + (1.0 - p) * (1.0 - q);
        if den <= 0.0 { p } else { num / den }
    }

    /// Expected entropy drop (bits) of one simulated observation of a cell with occupancy
    /// `p`: `H(p) − [p·H(post_hit) + (1 − p)·H(post_miss)]`; 0 for a certain cell.
    #[inline]
    pub fn expected_drop(&self, p: f64) -> f64 {
        if p <= 0.0 || p >= 1.0 || p.is_nan() {
            return 0.0;
        }
        let after = p * entropy(Self::posterior(p, self.p_hit))
            + (1.0 - p) * entropy(Self::posterior(p, self.p_miss));
        entropy(p) - after
    }
}

/// Reusable buffers for [`information_gain`]: the predicted scan and a generation-stamped
/// mark per cell, so that repeated cells count once without sorting.
#[derive(Clone, Debug, Default)]
pub struct GainScratch {
    touched: Vec<u32>,
    mark: Vec<u32>,
    generation: u32,
    /// The drop of a cell at p = ½ under the model last used, cached with that model.
    half: Option<(InverseModel, f64)>,
}

impl GainScratch {
    /// Empty buffers; they grow to the map size on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// Start a new deduplication round over a map of `len` cells.
    fn next_round(&mut self, len: usize) {
        if self.mark.len() != len {
            self.mark.clear();
            self.mark.resize(len, 0);
            self.generation = 0;
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.mark.fill(0);
            self.generation = 1;
        }
    }

    /// The uncertain cells (0 < p < 1) the last predicted scan touched, each once, in scan
    /// order: the cells its gain sums over.
    pub fn touched(&self) -> &[u32] {
        &self.touched
    }
}

/// Expected information gain `I(pose)` in bits: the expected entropy drop, under `model`,
/// of the cells that `sensor` would observe from `pose` on `belief` (each counted once).
///
/// On the ternary known grid with [`InverseModel::IDEAL`] this is the number of Unknown
/// cells the predicted scan touches; for a ternary belief only the scan's Unknown cells
/// are listed ([`Sensor::predict_unknown`]). Allocates nothing once `scratch` has the
/// map's size.
pub fn information_gain(
    sensor: &dyn Sensor,
    belief: &dyn Belief,
    model: &InverseModel,
    pose: Pose,
    scratch: &mut GainScratch,
) -> f64 {
    information_gain_gated(sensor, belief, model, pose, None, scratch)
}

/// [`information_gain`] of a scan whose rays pass an Unknown cell only where `passable`
/// says so ([`Sensor::predict_gated`]); `None` lets every Unknown cell through.
pub fn information_gain_gated(
    sensor: &dyn Sensor,
    belief: &dyn Belief,
    model: &InverseModel,
    pose: Pose,
    passable: Option<&dyn Fn(usize) -> bool>,
    scratch: &mut GainScratch,
) -> f64 {
    let known = belief.known();
    scratch.next_round(known.len());
    let half = match scratch.half {
        Some((m, d)) if m == *model => d,
        _ => {
            let d = model.expected_drop(0.5);
            scratch.half = Some((*model, d));
            d
        }
    };
    let ternary = belief.is_ternary();
    match passable {
        // Only Unknown cells are uncertain (p = ½) in a ternary belief: the others need
        // not be listed.
        Some(gate) => sensor.predict_gated(known, pose, ternary, gate, &mut scratch.touched),
        None if ternary => sensor.predict_unknown(known, pose, &mut scratch.touched),
        None => sensor.predict(known, pose, &mut scratch.touched),
    }
    let generation = scratch.generation;
    let mut gain = 0.0;
    let mut unique = 0;
    for k in 0..scratch.touched.len() {
        let i = scratch.touched[k] as usize;
        let Some(m) = scratch.mark.get_mut(i) else {
            continue;
        };
        if *m == generation {
            continue;
        }
        *m = generation;
        let p = if ternary { 0.5 } else { belief.p_occupied(i) };
        let drop = if p == 0.5 {
            half
        } else if p <= 0.0 || p >= 1.0 {
            continue;
        } else {
            model.expected_drop(p)
        };
        gain += drop;
        scratch.touched[unique] = i as u32;
        unique += 1;
    }
    scratch.touched.truncate(unique);
    gain
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entropy_values() {
        assert_eq!(entropy(0.5), 1.0);
        assert_eq!(entropy(0.0), 0.0);
        assert_eq!(entropy(1.0), 0.0);
        assert!((entropy(0.25) - 0.811_278_124_459_132_8).abs() < 1e-12);
    }

    #[test]
    fn ideal_drop_is_the_entropy() {
        for p in [0.0, 0.1, 0.3, 0.5, 0.9, 1.0] {
            assert!((InverseModel::IDEAL.expected_drop(p) - entropy(p)).abs() < 1e-12);
        }
    }

    #[test]
    fn evidence_drop_at_prior() {
        // p = ½: hit → 0.7, miss → 0.4; drop = 1 − (½ H(0.7) + ½ H(0.4)).
        let want = 1.0 - 0.5 * (entropy(0.7) + entropy(0.4));
        assert!((InverseModel::EVIDENCE.expected_drop(0.5) - want).abs() < 1e-12);
        assert!(want > 0.0);
    }
}
