//! Assigners: which candidate each deciding robot takes.
//!
//! One file per rule. Single-robot rules (nearest, random) also serve a team, each robot
//! deciding on its own — which is the uncoordinated "nearest frontier" strategy of the
//! multi-robot study (seed 002).

pub mod nearest;
pub mod random;

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Which assigner a strategy uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AssignerKind {
    /// Each robot takes the candidate nearest to it by path (Yamauchi; Holz's CF).
    Nearest,
    /// Each robot takes a reachable candidate uniformly at random (Holz's RF baseline).
    Random,
}

impl AssignerKind {
    /// Give a goal to every deciding robot that can reach a candidate; others get `None`.
    pub fn assign(
        &self,
        ctx: &mut DecisionCtx<'_>,
        candidates: &CandidateSet,
        out: &mut [Option<Goal>],
    ) {
        match self {
            AssignerKind::Nearest => nearest::assign(ctx, candidates, out),
            AssignerKind::Random => random::assign(ctx, candidates, out),
        }
    }
}
