//! What one run is: strategy, sensor, belief, team, motion and limits.

use explore::strategy::{SensingMode, Strategy};
use grid::{Cell, Grid};
use sense::{BeliefKind, SensorSpec};

/// What coverage counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CoverageKind {
    /// Cells known free among the ground truth's free cells reachable from the start with
    /// the robot's clearance (the default).
    #[default]
    ReachableFree,
    /// Explore-Bench's: cells known (free or occupied) among every cell the ground truth
    /// knows (free or occupied; not its unknown outside).
    Known,
}

impl std::str::FromStr for CoverageKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "reachable" => Ok(CoverageKind::ReachableFree),
            "known" => Ok(CoverageKind::Known),
            other => Err(format!(
                "--coverage: expected reachable or known, found '{other}'"
            )),
        }
    }
}

impl std::fmt::Display for CoverageKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            CoverageKind::ReachableFree => "reachable",
            CoverageKind::Known => "known",
        })
    }
}

/// A fully resolved run: everything but the map.
#[derive(Clone, Debug)]
pub struct RunConfig {
    /// The strategy triple (from a preset).
    pub strategy: Strategy,
    /// The sensor every robot carries.
    pub sensor: SensorSpec,
    /// How observations are integrated.
    pub belief: BeliefKind,
    /// Sensing mode; `None` = the strategy's default.
    pub sensing: Option<SensingMode>,
    /// Number of robots.
    pub robots: usize,
    /// Start cells; empty = chosen by seed (the first), the others at the nearest distinct
    /// traversable cells around it.
    pub starts: Vec<Cell>,
    /// The robot's clearance from known obstacles, in metres (Holz's d_max).
    pub clearance_m: f64,
    /// Speed in metres per second.
    pub speed: f64,
    /// Master seed.
    pub seed: u64,
    /// Stop once coverage reaches this share (`None` = explore fully).
    pub coverage_goal: Option<f64>,
    /// What coverage counts (its curve, milestones, goal and reported value).
    pub coverage: CoverageKind,
    /// Stop after this many cell moves of the whole team.
    pub max_moves: u64,
    /// Keep a per-step trace (trails, goals, frontier counts) for pictures.
    pub record_trace: bool,
    /// Most events a recorded trace may hold: the run ends there
    /// ([`crate::EndReason::TraceLimit`]) rather than outgrow the memory left for it
    /// ([`crate::memory::trace_events_within`]). A trace's length is estimated before the
    /// run, but a strategy that wanders (`random`) can outrun any estimate.
    pub trace_events: u64,
    /// Obstacles off the laser plane (same size as the map, true = obstacle): planar
    /// sensors miss them, sonar hears them and the robot's body is stopped by them.
    pub clutter: Option<Grid<bool>>,
    /// How path length is measured (grid moves or any-angle; see [`crate::motion`]).
    pub motion: crate::motion::Motion,
}

impl RunConfig {
    /// A single-robot run of `strategy` with the `los` sensor of range 5 m and the defaults.
    pub fn new(strategy: Strategy) -> Self {
        Self {
            strategy,
            sensor: SensorSpec::Los {
                r: sense::Range::Metres(5.0),
            },
            belief: BeliefKind::Known,
            sensing: None,
            robots: 1,
            starts: Vec::new(),
            clearance_m: 0.0,
            speed: 1.0,
            seed: 0,
            coverage_goal: None,
            coverage: CoverageKind::ReachableFree,
            max_moves: 10_000_000,
            record_trace: false,
            trace_events: u64::MAX,
            clutter: None,
            motion: crate::motion::Motion::Grid,
        }
    }

    /// The sensing mode in force.
    pub fn sensing_mode(&self) -> SensingMode {
        self.sensing.unwrap_or(self.strategy.sensing)
    }
}

/// Why a run could not start.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A parameter is out of range.
    #[error("{field}: expected {expected}, found {found}")]
    BadParameter {
        /// The parameter's name as the user knows it (e.g. "--speed").
        field: &'static str,
        /// What is allowed.
        expected: &'static str,
        /// The value given.
        found: String,
    },
    /// A start cell is outside the map or not traversable.
    #[error("start {cell}: {why}")]
    BadStart {
        /// The start cell.
        cell: Cell,
        /// What is wrong with it.
        why: String,
    },
    /// The map has no traversable cell.
    #[error(
        "the map has no free cell a robot with clearance {} m can stand on",
        grid::Num(*.clearance_m)
    )]
    NoFreeSpace {
        /// The clearance asked for.
        clearance_m: f64,
    },
    /// The sensor cannot be built at this resolution.
    #[error("--sensor: {0}")]
    // Not a `#[source]`: the message already holds it, and error reporters that print the
    // chain would repeat it.
    Sensor(sense::SenseError),
}

impl From<sense::SenseError> for SimError {
    fn from(e: sense::SenseError) -> Self {
        SimError::Sensor(e)
    }
}
