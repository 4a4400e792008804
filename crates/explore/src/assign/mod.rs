//! Assigners: which candidate each deciding robot takes.
//!
//! One file per rule. Single-robot rules (nearest, random) also serve a team, each robot
//! deciding on its own — which is the uncoordinated "nearest frontier" strategy of the
//! multi-robot coordination study.

pub mod costs;
pub mod greedy;
pub mod greedy_utility;
pub mod hungarian;
pub mod minpos;
pub mod mtsp;
pub mod nearest;
pub mod random;
pub mod random_order;
pub mod segment_first;
pub mod sga;
pub mod utility;

use crate::candidates::CandidateSet;
use crate::decision::{DecisionCtx, Goal};

/// Which assigner a strategy uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AssignerKind {
    /// Each robot takes the candidate nearest to it by path (Yamauchi; Holz's CF; the coordination study's
    /// uncoordinated "nearest frontier").
    Nearest,
    /// Each robot takes a reachable candidate uniformly at random (Holz's RF baseline).
    Random,
    /// Repeatedly the globally cheapest free (robot, goal) pair (the coordination study's Alg. 2; Faigl &
    /// Kulich's IA, Broadcast of Local Eligibility).
    Greedy,
    /// Robots in random order each take their cheapest unassigned goal (Faigl & Kulich's GA).
    RandomOrderGreedy,
    /// Greedy on U_j − β·c_ij with utilities lowered near chosen goals (Burgard/Simmons; the coordination study's Alg. 3).
    GreedyUtility {
        /// β: weight of the travel cost against the utility.
        beta: f64,
    },
    /// MinPos (Bautin et al.): each robot takes the goal where it ranks best among the robots.
    MinPos,
    /// The optimal assignment of the cost matrix (Hungarian; Faigl & Kulich's HA).
    Hungarian,
    /// Cluster first, route second: k-means clusters, optimal cluster assignment, open TSP
    /// routes (Faigl & Kulich's MA).
    Mtsp,
    /// Solanas & Garcia's assignment (Faigl & Kulich Eq. 1, SGA).
    Sga,
    /// Maximum utility I(p)·exp(−λ L(p)) (González-Baños & Latombe, as Holz et al. ran it).
    DtUtility {
        /// λ per metre.
        lambda: f64,
    },
    /// The nearest candidate in the robot's own segment, else the nearest overall (Holz's Seg).
    SegmentFirst {
        /// Critical-point rule of the segmentation.
        rule: crate::segment::Rule,
        /// Prefer the own segment only when it touches at most this many others (room-like);
        /// `None`: always (the literal rule).
        max_neighbours: Option<u32>,
    },
}

impl AssignerKind {
    /// Give a goal to every deciding robot that can reach a candidate; others get `None`.
    pub fn assign(
        &self,
        ctx: &mut DecisionCtx<'_>,
        candidates: &CandidateSet,
        out: &mut [Option<Goal>],
    ) {
        match *self {
            AssignerKind::Nearest => nearest::assign(ctx, candidates, out),
            AssignerKind::Random => random::assign(ctx, candidates, out),
            AssignerKind::Greedy => greedy::assign(ctx, candidates, out),
            AssignerKind::RandomOrderGreedy => random_order::assign(ctx, candidates, out),
            AssignerKind::GreedyUtility { beta } => {
                greedy_utility::assign(ctx, candidates, beta, out)
            }
            AssignerKind::MinPos => minpos::assign(ctx, candidates, out),
            AssignerKind::Hungarian => hungarian::assign(ctx, candidates, out),
            AssignerKind::Mtsp => mtsp::assign(ctx, candidates, out),
            AssignerKind::Sga => sga::assign(ctx, candidates, out),
            AssignerKind::DtUtility { lambda } => utility::assign(ctx, candidates, lambda, out),
            AssignerKind::SegmentFirst {
                rule,
                max_neighbours,
            } => segment_first::assign(ctx, candidates, rule, max_neighbours, out),
        }
    }
}
