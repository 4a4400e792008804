//! What a run reports: DESIGN.md's metrics, the end reason, phase timings and a trace.

use grid::{Cell, Grid, Occ};

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndReason {
    /// No reachable frontier is left and every reachable free cell is known.
    Complete,
    /// The coverage goal G was reached.
    GoalReached,
    /// No reachable frontier is left, but some reachable free cells are still unknown
    /// (they cannot be seen from anywhere the robots can go, or goals were given up).
    NoReachableFrontier,
    /// The move limit was hit.
    StepLimit,
}

impl EndReason {
    /// The reason's stable name, as printed in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            EndReason::Complete => "complete",
            EndReason::GoalReached => "goal reached",
            EndReason::NoReachableFrontier => "no reachable frontier",
            EndReason::StepLimit => "step limit",
        }
    }
}

/// Wall-clock time spent in each phase of the loop, in seconds (not deterministic).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// Sensing and integrating observations into the belief.
    pub sense_s: f64,
    /// Incremental traversability and frontier upkeep.
    pub upkeep_s: f64,
    /// Deciding: candidates, assignment and path extraction.
    pub decide_s: f64,
    /// The whole run.
    pub total_s: f64,
}

/// Per-step record of a run, for pictures and replays.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Every cell each robot stood on, in order (start included).
    pub trails: Vec<Vec<u32>>,
    /// Every decision's outcome: (time s, robot, goal cell or `None`).
    pub goals: Vec<(f64, usize, Option<u32>)>,
    /// Number of frontier cells after each move: (time s, robot, count).
    pub frontier_counts: Vec<(f64, usize, u32)>,
}

/// The result of one run.
#[derive(Clone, Debug)]
pub struct RunResult {
    /// Why it ended.
    pub reason: EndReason,
    /// Known reachable free cells / ground-truth free cells reachable from the start.
    pub coverage: f64,
    /// Ground-truth free cells reachable from the start with the robot's clearance.
    pub reachable_cells: usize,
    /// Path length of each robot in metres.
    pub path_length_m: Vec<f64>,
    /// Exploration time in seconds: when the last robot finished.
    pub time_s: f64,
    /// Number of decisions taken (one per robot that chose a goal or found none).
    pub decisions: u64,
    /// Cell moves of the whole team.
    pub moves: u64,
    /// Start cell of each robot.
    pub starts: Vec<Cell>,
    /// Final cell of each robot.
    pub ends: Vec<Cell>,
    /// Coverage over total distance: (metres travelled by the team, coverage), at every change.
    pub coverage_curve: Vec<(f64, f64)>,
    /// Wall-clock phase timings.
    pub times: PhaseTimes,
    /// The final belief, classified.
    pub belief: Grid<Occ>,
    /// Open frontier cells left at the end: frontier cells not on the visited or inaccessible
    /// lists (none when complete).
    pub frontiers_left: Vec<u32>,
    /// The per-step trace, when asked for.
    pub trace: Option<Trace>,
}

impl RunResult {
    /// Whether every reachable free cell was explored.
    pub fn complete(&self) -> bool {
        self.reason == EndReason::Complete
    }

    /// L: the longest path of one robot (Faigl & Kulich's metric), metres.
    pub fn max_path_length_m(&self) -> f64 {
        self.path_length_m.iter().copied().fold(0.0, f64::max)
    }

    /// Total path length of the team, metres.
    pub fn total_path_length_m(&self) -> f64 {
        self.path_length_m.iter().sum()
    }
}
