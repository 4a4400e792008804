//! Strategies as (candidate generator, assigner, re-plan policy) triples, and the named
//! presets of the papers.
//!
//! | preset | paper | candidates | assigner | re-plan | sensing |
//! |---|---|---|---|---|---|
//! | `yamauchi` | Yamauchi 1997 | region centroids ≥ 0.5 m | nearest by path, skipping visited / inaccessible | on arrival; inaccessible after 30 s without progress | on arrival, 360° sweep |
//! | `cf` | Holz et al. 2010 | all frontier cells | nearest by path | on arrival | continuous |
//! | `cf-rr` | Holz et al. 2010 | all frontier cells | nearest by path | on arrival, or when the target stops being a frontier | continuous |
//! | `random` | Holz et al. 2010 (RF) | all frontier cells | uniform over reachable ones | on arrival | continuous |

use crate::assign::AssignerKind;
use crate::candidates::CandidateKind;

/// When a robot senses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensingMode {
    /// At every cell it enters (Holz, Faigl & Kulich, the multi-robot study).
    Continuous,
    /// Only at goals, with a 360° sweep (Yamauchi, Quattrini Li et al.).
    OnArrival,
}

impl std::str::FromStr for SensingMode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "continuous" => Ok(SensingMode::Continuous),
            "on-arrival" => Ok(SensingMode::OnArrival),
            _ => Err(format!(
                "sensing mode: expected 'continuous' or 'on-arrival', found '{s}'"
            )),
        }
    }
}

impl std::fmt::Display for SensingMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SensingMode::Continuous => "continuous",
            SensingMode::OnArrival => "on-arrival",
        })
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
        "random",
        "Holz et al. 2010: random frontier cell (baseline)",
    ),
];

/// Error for a strategy name that is not a preset.
#[derive(Debug, thiserror::Error)]
#[error("unknown strategy '{found}': expected one of {}", PRESETS.iter().map(|p| p.0).collect::<Vec<_>>().join(", "))]
pub struct UnknownStrategy {
    /// The name given.
    pub found: String,
}

impl Strategy {
    /// The preset called `name`.
    pub fn preset(name: &str) -> Result<Strategy, UnknownStrategy> {
        let on_arrival = ReplanPolicy {
            every_moves: None,
            recheck: false,
            no_progress_s: None,
        };
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
                ReplanPolicy {
                    recheck: true,
                    ..on_arrival
                },
                SensingMode::Continuous,
            ),
            "random" => (
                CandidateKind::AllFrontiers,
                AssignerKind::Random,
                on_arrival,
                SensingMode::Continuous,
            ),
            _ => {
                return Err(UnknownStrategy {
                    found: name.to_string(),
                });
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
