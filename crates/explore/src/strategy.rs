//! Strategies as (candidate generator, assigner, re-plan policy) triples, and the named
//! presets of the papers.
//!
//! | preset | paper | candidates | assigner | re-plan | sensing |
//! |---|---|---|---|---|---|
//! | `yamauchi` | Yamauchi 1997 | region centroids ≥ 0.5 m | nearest by path, skipping visited / inaccessible | on arrival; inaccessible after 30 s without progress | on arrival, 360° sweep |
//! | `cf` | Holz et al. 2010 | all frontier cells | nearest by path | on arrival | continuous |
//! | `cf-rr` | Holz et al. 2010 | all frontier cells | nearest by path | on arrival, or when the target stops being a frontier | continuous |
//! | `random` | Holz et al. 2010 (RF) | all frontier cells | uniform over reachable ones | on arrival | continuous |
//! | `cf-rr-seg` | Holz et al. 2010 | all frontier cells | nearest in the robot's segment first when that segment is room-like (≤ 2 neighbouring segments; see `assign::segment_first`) | as `cf-rr` | continuous |
//! | `cf-rr-seg-any` | Holz et al. 2010, literal | all frontier cells | nearest in the robot's segment first, corridors included | as `cf-rr` | continuous |
//! | `dt`, `dt500` | González-Baños & Latombe, Holz §3.2 | 100 / 500 samples near frontiers | max I·exp(−0.2 L) | on arrival | continuous |
//! | `dt-rr` | beyond the paper | as `dt` | as `dt` | also when the target's utility halves | continuous |
//! | `nearest`, `greedy`, `greedy-utility`, `minpos` | coordination study | all frontier cells | as named | on arrival (per robot) | continuous |
//! | `<a>-<c>` e.g. `ha-cc` | Faigl & Kulich 2013 | `af`, `centroids`, `rfe`, `cc` | `nearest`, `greedy`/`ia`, `ga`, `greedy-utility`, `minpos`, `ha`, `ma`, `sga` | every s_max = 7 moves (team) | continuous |

use crate::assign::AssignerKind;
use crate::candidates::CandidateKind;

/// When a robot senses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensingMode {
    /// At every cell it enters (Holz, Faigl & Kulich, the multi-robot study).
    Continuous,
    /// Only at goals, with a 360° sweep (Yamauchi, Quattrini Li et al.).
    OnArrival,
    /// At every n-th cell it enters (n ≥ 2), at its goal and wherever it stops to decide:
    /// a scan rate slower than the robot's cell rate, as Explore-Bench's grid simulator
    /// senses at every third cell of a path and at its end (`every-3`).
    Every(u32),
}

/// The longest sensing interval accepted, in cells.
pub const MAX_SENSING_INTERVAL: u32 = 1_000_000;

impl std::str::FromStr for SensingMode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || {
            format!(
                "sensing mode: expected 'continuous', 'on-arrival' or 'every-N' (a scan at \
                 every N-th cell, N from 1 to {MAX_SENSING_INTERVAL}), found '{s}'"
            )
        };
        match s {
            "continuous" => Ok(SensingMode::Continuous),
            "on-arrival" => Ok(SensingMode::OnArrival),
            _ => {
                let n: u32 = s
                    .strip_prefix("every-")
                    .and_then(|n| n.parse().ok())
                    .filter(|n| (1..=MAX_SENSING_INTERVAL).contains(n))
                    .ok_or_else(bad)?;
                Ok(if n == 1 {
                    SensingMode::Continuous
                } else {
                    SensingMode::Every(n)
                })
            }
        }
    }
}

impl std::fmt::Display for SensingMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SensingMode::Continuous => f.write_str("continuous"),
            SensingMode::OnArrival => f.write_str("on-arrival"),
            SensingMode::Every(n) => write!(f, "every-{n}"),
        }
    }
}

/// When a robot gives up its current goal and decides again (besides arriving).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplanPolicy {
    /// Re-decide every this many cell moves (Faigl & Kulich's s_max); `None` = on arrival only.
    pub every_moves: Option<u32>,
    /// Repetitive re-checking (Holz): re-decide as soon as the target is no longer a frontier.
    pub recheck: bool,
    /// Yamauchi's inaccessible list: give the goal up when the remaining path has not
    /// shortened for this many seconds.
    pub no_progress_s: Option<f64>,
    /// Decision-theoretic re-checking (`dt-rr`): re-decide when the target's utility,
    /// re-evaluated while travelling, falls below this fraction of its value at decision time.
    pub utility_drop: Option<f64>,
}

/// A strategy: the three swappable pieces of the one loop, plus its sensing mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Strategy {
    /// Preset name, e.g. `cf-rr`.
    pub name: String,
    /// Candidate generator.
    pub candidates: CandidateKind,
    /// Assigner.
    pub assigner: AssignerKind,
    /// Re-plan policy.
    pub replan: ReplanPolicy,
    /// Default sensing mode of the preset.
    pub sensing: SensingMode,
}

/// Preset names with one-line descriptions, in the order they are listed to users.
/// Besides these, `<assigner>-<candidates>` combines any assigner of Faigl & Kulich's
/// framework (`nearest`, `greedy`, `ia`, `ga`, `greedy-utility`, `minpos`, `ha`, `ma`,
/// `sga`) with any candidate generator (`af`, `centroids`, `rfe`, `cc`), re-planning every
/// s_max = 7 cell moves.
pub const PRESETS: &[(&str, &str)] = &[
    (
        "yamauchi",
        "Yamauchi 1997: nearest accessible unvisited region centroid, 360° sweep on arrival",
    ),
    (
        "cf",
        "Holz et al. 2010: closest frontier cell by path, re-plan on arrival",
    ),
    (
        "cf-rr",
        "Holz et al. 2010: closest frontier with repetitive re-checking",
    ),
    (
        "cf-rr-seg",
        "Holz et al. 2010: closest frontier in the robot's own room segment first, with RR",
    ),
    (
        "cf-rr-seg-any",
        "the same with the literal rule: own segment first in corridors too",
    ),
    (
        "random",
        "Holz et al. 2010: random frontier cell (baseline)",
    ),
    (
        "dt",
        "González-Baños & Latombe as in Holz et al.: max I·exp(-0.2 L) over 100 samples near frontiers",
    ),
    ("dt500", "the same with 500 samples"),
    (
        "dt-rr",
        "dt, re-deciding while travelling when the target's utility drops below half",
    ),
    (
        "nearest",
        "multi-robot study: each robot to its nearest frontier cell, no coordination",
    ),
    (
        "greedy",
        "multi-robot study: repeatedly the globally cheapest robot-frontier pair",
    ),
    (
        "greedy-utility",
        "multi-robot study: greedy on utility minus beta x cost, utility lowered near chosen goals",
    ),
    (
        "minpos",
        "multi-robot study: MinPos, the frontier where the robot ranks best by distance",
    ),
    (
        "ga-af, ia-cc, ha-rfe, ma-cc, sga-af, ...",
        "Faigl & Kulich 2013: <assigner>-<candidates>, re-plan every s_max = 7 moves",
    ),
];

/// The assigners of team names `<assigner>-<candidates>` (Faigl & Kulich's naming; `greedy`
/// and `ia` are the same).
pub const TEAM_ASSIGNERS: &[&str] = &[
    "nearest",
    "greedy",
    "ia",
    "ga",
    "greedy-utility",
    "minpos",
    "ha",
    "ma",
    "sga",
];

/// The candidate generators of team names `<assigner>-<candidates>`.
pub const TEAM_CANDIDATES: &[&str] = &["af", "centroids", "rfe", "cc"];

/// Every strategy name [`Strategy::preset`] takes, with a description: the presets of
/// [`PRESETS`] but its summary line of team names, then each team name spelled out.
pub fn every_name() -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = PRESETS
        .iter()
        .filter(|(name, _)| Strategy::preset(name).is_ok())
        .map(|&(n, d)| (n.to_string(), d.to_string()))
        .collect();
    for a in TEAM_ASSIGNERS {
        for c in TEAM_CANDIDATES {
            out.push((
                format!("{a}-{c}"),
                format!(
                    "Faigl & Kulich 2013: assigner {a} over candidates {c}, re-plan every \
                     s_max = 7 moves"
                ),
            ));
        }
    }
    out
}

/// Error for a strategy name that is not a preset.
#[derive(Debug)]
pub struct UnknownStrategy {
    /// The name given.
    pub found: String,
}

impl std::fmt::Display for UnknownStrategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let presets: Vec<&str> = PRESETS
            .iter()
            .map(|&(name, _)| name)
            .filter(|name| !name.contains(", "))
            .collect();
        write!(
            f,
            "unknown strategy '{}': expected {}, or <assigner>-<candidates> with an assigner \
             of {} and candidates {}",
            self.found,
            presets.join(", "),
            TEAM_ASSIGNERS.join(", "),
            TEAM_CANDIDATES.join(", ")
        )
    }
}

impl std::error::Error for UnknownStrategy {}

fn assigner_named(name: &str) -> Option<AssignerKind> {
    Some(match name {
        "nearest" => AssignerKind::Nearest,
        "greedy" | "ia" => AssignerKind::Greedy,
        "ga" => AssignerKind::RandomOrderGreedy,
        "greedy-utility" => AssignerKind::GreedyUtility {
            beta: crate::assign::greedy_utility::DEFAULT_BETA,
        },
        "minpos" => AssignerKind::MinPos,
        "ha" => AssignerKind::Hungarian,
        "ma" => AssignerKind::Mtsp,
        "sga" => AssignerKind::Sga,
        _ => return None,
    })
}

fn candidates_named(name: &str) -> Option<CandidateKind> {
    Some(match name {
        "af" => CandidateKind::AllFrontiers,
        "centroids" => CandidateKind::RegionCentroids { min_size_m: 0.5 },
        "rfe" => CandidateKind::Rfe {
            min_edge: crate::candidates::rfe::DEFAULT_MIN_EDGE,
        },
        "cc" => CandidateKind::Coverage,
        _ => return None,
    })
}

impl Strategy {
    /// Whether each decision draws the goal at random (a random frontier cell, or the best
    /// of random samples): re-planning such a strategy every few moves would discard each
    /// drawn goal before it is reached and walk at random, so it re-plans on arrival only.
    pub fn draws_its_goal(&self) -> bool {
        matches!(self.assigner, AssignerKind::Random)
            || matches!(self.candidates, CandidateKind::DtSamples { .. })
    }

    /// The preset called `name`.
    pub fn preset(name: &str) -> Result<Strategy, UnknownStrategy> {
        let on_arrival = ReplanPolicy {
            every_moves: None,
            recheck: false,
            no_progress_s: None,
            utility_drop: None,
        };
        let rr = ReplanPolicy {
            recheck: true,
            ..on_arrival
        };
        let dt = |n| CandidateKind::DtSamples { n };
        let dt_utility = AssignerKind::DtUtility { lambda: 0.2 };
        let (candidates, assigner, replan, sensing) = match name {
            "yamauchi" => (
                CandidateKind::RegionCentroids { min_size_m: 0.5 },
                AssignerKind::Nearest,
                ReplanPolicy {
                    no_progress_s: Some(30.0),
                    ..on_arrival
                },
                SensingMode::OnArrival,
            ),
            "cf" => (
                CandidateKind::AllFrontiers,
                AssignerKind::Nearest,
                on_arrival,
                SensingMode::Continuous,
            ),
            "cf-rr" => (
                CandidateKind::AllFrontiers,
                AssignerKind::Nearest,
                rr,
                SensingMode::Continuous,
            ),
            "cf-rr-seg" => (
                CandidateKind::AllFrontiers,
                AssignerKind::SegmentFirst {
                    rule: crate::segment::Rule::Holz,
                    max_neighbours: Some(crate::assign::segment_first::ROOM_MAX_NEIGHBOURS),
                },
                rr,
                SensingMode::Continuous,
            ),
            "cf-rr-seg-any" => (
                CandidateKind::AllFrontiers,
                AssignerKind::SegmentFirst {
                    rule: crate::segment::Rule::Holz,
                    max_neighbours: None,
                },
                rr,
                SensingMode::Continuous,
            ),
            "random" => (
                CandidateKind::AllFrontiers,
                AssignerKind::Random,
                on_arrival,
                SensingMode::Continuous,
            ),
            "dt" => (dt(100), dt_utility, on_arrival, SensingMode::Continuous),
            "dt500" => (dt(500), dt_utility, on_arrival, SensingMode::Continuous),
            "dt-rr" => (
                dt(100),
                dt_utility,
                ReplanPolicy {
                    utility_drop: Some(0.5),
                    ..on_arrival
                },
                SensingMode::Continuous,
            ),
            "nearest" | "greedy" | "greedy-utility" | "minpos" => (
                CandidateKind::AllFrontiers,
                assigner_named(name).expect("listed above"),
                on_arrival,
                SensingMode::Continuous,
            ),
            _ => {
                let unknown = || UnknownStrategy {
                    found: name.to_string(),
                };
                let (a, c) = name.rsplit_once('-').ok_or_else(unknown)?;
                let assigner = assigner_named(a).ok_or_else(unknown)?;
                let candidates = candidates_named(c).ok_or_else(unknown)?;
                (
                    candidates,
                    assigner,
                    ReplanPolicy {
                        every_moves: Some(7),
                        ..on_arrival
                    },
                    SensingMode::Continuous,
                )
            }
        };
        Ok(Strategy {
            name: name.to_string(),
            candidates,
            assigner,
            replan,
            sensing,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: the names front ends list held the summary line "ga-af, ia-cc, …",
    /// which no run takes. Every name listed is one a run takes, and every team name is
    /// listed.
    #[test]
    fn regression_every_name_listed_is_a_strategy() {
        let names = every_name();
        for (n, _) in &names {
            assert!(Strategy::preset(n).is_ok(), "{n}");
        }
        let summaries = PRESETS.iter().filter(|(n, _)| n.contains(", ")).count();
        assert_eq!(summaries, 1);
        assert_eq!(
            names.len(),
            PRESETS.len() - summaries + TEAM_ASSIGNERS.len() * TEAM_CANDIDATES.len()
        );
        assert!(names.iter().any(|(n, _)| n == "ha-rfe"));
    }

    #[test]
    fn an_unknown_name_is_answered_with_every_name() {
        let e = Strategy::preset("ha-xyz").unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown strategy 'ha-xyz': expected yamauchi, cf, cf-rr, cf-rr-seg, \
             cf-rr-seg-any, random, dt, dt500, dt-rr, nearest, greedy, greedy-utility, minpos, \
             or <assigner>-<candidates> with an assigner of nearest, greedy, ia, ga, \
             greedy-utility, minpos, ha, ma, sga and candidates af, centroids, rfe, cc"
        );
    }
}
