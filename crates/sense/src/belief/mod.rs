//! Belief maps: what the robots know, built from observations.
//!
//! Every belief map classifies each cell as Free, Occupied or Unknown and keeps that
//! classification materialised as a `Grid<Occ>` ([`Belief::known`]), so that frontier
//! detection and planning read one plain grid whatever the belief model.

mod evidence;
mod known;
mod reflection;

use std::fmt;
use std::str::FromStr;

use grid::{Grid, Occ};

use crate::error::SenseError;
use crate::sensor::Observation;

pub use evidence::EvidenceGrid;
pub use known::KnownGrid;
pub use reflection::ReflectionMap;

/// A map of what is known, updated from observations.
///
/// Observation entries whose index is outside the map, or whose state is `Unknown`, are
/// ignored.
pub trait Belief: Send {
    /// Integrate an observation; push the flat index of every cell whose class (Occ) changed.
    ///
    /// `changed` is appended to, not cleared; each index is pushed at most once per call
    /// (observations hold no duplicates).
    fn integrate(&mut self, obs: &Observation, changed: &mut Vec<u32>);
    /// The current class of every cell, kept up to date by `integrate` (a materialised `Grid<Occ>`).
    fn known(&self) -> &Grid<Occ>;
    /// Probability that cell i is occupied (0.5 if unknown) — for entropy-based information gain.
    fn p_occupied(&self, i: usize) -> f64;
    /// Whether `p_occupied` is exactly 0 for Free, 1 for Occupied and ½ for Unknown cells of
    /// [`known`](Self::known) (so the class alone gives it); false unless a model says so.
    fn is_ternary(&self) -> bool {
        false
    }
    /// Pin cell `i` to `class` (Free or Occupied) for good: the robot's body was there, or
    /// met an obstacle there, and contact is certain, so no later observation changes it (a
    /// sonar cone's arc would otherwise close a corridor the robot has just driven through,
    /// an ideal planar sensor would see the free plane below a table again at once). Pushes
    /// `i` to `changed` if its class changed; an index outside the map, or `Unknown`, is
    /// ignored.
    fn pin(&mut self, i: usize, class: Occ, changed: &mut Vec<u32>);
    /// Whether cell `i` is pinned.
    fn is_pinned(&self, i: usize) -> bool;
    /// The log-odds evidence grid behind this belief, if it is one (for sensors that add
    /// graded evidence, such as the sonar cone); `None` for the other models.
    fn evidence_mut(&mut self) -> Option<&mut EvidenceGrid> {
        None
    }
}

/// The belief-map models, by name: `known`, `reflection`, `evidence`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum BeliefKind {
    /// [`KnownGrid`]: ternary, the latest observation of a cell wins (ideal sensors).
    #[default]
    Known,
    /// [`ReflectionMap`]: Holz et al.'s hit/miss counts, free iff p ≤ 0.25.
    Reflection,
    /// [`EvidenceGrid`]: Yamauchi's log-odds evidence grid with prior 0.5.
    Evidence,
}

impl BeliefKind {
    /// An empty belief map of this kind, `width × height` cells, everything Unknown.
    pub fn build(self, width: usize, height: usize) -> Box<dyn Belief> {
        match self {
            BeliefKind::Known => Box::new(KnownGrid::new(width, height)),
            BeliefKind::Reflection => Box::new(ReflectionMap::new(width, height)),
            BeliefKind::Evidence => Box::new(EvidenceGrid::new(width, height)),
        }
    }
}

impl fmt::Display for BeliefKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BeliefKind::Known => "known",
            BeliefKind::Reflection => "reflection",
            BeliefKind::Evidence => "evidence",
        })
    }
}

impl FromStr for BeliefKind {
    type Err = SenseError;

    fn from_str(s: &str) -> Result<Self, SenseError> {
        match s.trim() {
            "known" => Ok(BeliefKind::Known),
            "reflection" => Ok(BeliefKind::Reflection),
            "evidence" => Ok(BeliefKind::Evidence),
            _ => Err(SenseError::UnknownBelief(s.into())),
        }
    }
}

/// Cells pinned by contact ([`Belief::pin`]), sorted; empty in most runs,
/// so the check on every observed cell costs one comparison.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Pins(Vec<u32>);

impl Pins {
    /// Whether cell `i` is pinned.
    #[inline]
    pub(crate) fn holds(&self, i: usize) -> bool {
        !self.0.is_empty() && self.0.binary_search(&(i as u32)).is_ok()
    }

    /// Pin cell `i` of `known` to `class` (Free or Occupied; anything else, or an index
    /// outside the map, is ignored), pushing `i` to `changed` if its class changed; returns
    /// whether it pinned.
    pub(crate) fn pin(
        &mut self,
        known: &mut Grid<Occ>,
        i: usize,
        class: Occ,
        changed: &mut Vec<u32>,
    ) -> bool {
        if i >= known.len() || class == Occ::Unknown {
            return false;
        }
        if let Err(k) = self.0.binary_search(&(i as u32)) {
            self.0.insert(k, i as u32);
        }
        set_class(known, i, class, changed);
        true
    }
}

/// Set `known[i]` to `class`, recording `i` in `changed` if it differs.
#[inline]
pub(crate) fn set_class(known: &mut Grid<Occ>, i: usize, class: Occ, changed: &mut Vec<u32>) {
    let slot = &mut known[i];
    if *slot != class {
        *slot = class;
        changed.push(i as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_parse_and_display() {
        for k in [
            BeliefKind::Known,
            BeliefKind::Reflection,
            BeliefKind::Evidence,
        ] {
            assert_eq!(k.to_string().parse::<BeliefKind>(), Ok(k));
            let b = k.build(3, 2);
            assert_eq!((b.known().width(), b.known().height()), (3, 2));
            assert!(b.known().data().iter().all(|c| c.is_unknown()));
            assert_eq!(b.p_occupied(0), 0.5);
        }
        assert_eq!(
            "bayes"
                .parse::<BeliefKind>()
                .expect_err("unknown")
                .to_string(),
            "belief map 'bayes': expected one of known, reflection, evidence"
        );
    }
}
