//! What a run reports: its metrics (path lengths, time, coverage, decisions, map audit), the
//! end reason, phase timings and a trace.

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
    /// The recorded trace reached the most events the memory left for it holds
    /// ([`crate::RunConfig::trace_events`]): the run stopped rather than outgrow it.
    TraceLimit,
}

impl EndReason {
    /// Whether the run explored what it was asked to (everything reachable, or its goal):
    /// only then does its length compare with an optimal path's.
    pub fn reached_goal(self) -> bool {
        matches!(self, EndReason::Complete | EndReason::GoalReached)
    }

    /// The reason's stable name, as printed in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            EndReason::Complete => "complete",
            EndReason::GoalReached => "goal reached",
            EndReason::NoReachableFrontier => "no reachable frontier",
            EndReason::StepLimit => "step limit",
            EndReason::TraceLimit => "trace limit",
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

/// One moment of a run: a robot moved one cell (and sensed, in continuous mode), or looked
/// around where it stands (at its start, or on arrival).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceEvent {
    /// Time of the event in seconds (the robot's clock).
    pub t: f64,
    /// The robot.
    pub robot: u32,
    /// The robot's cell after the event.
    pub cell: u32,
    /// The robot's distance travelled so far, in metres.
    pub dist_m: f64,
    /// Coverage after the event.
    pub coverage: f64,
    /// Number of frontier cells after the event.
    pub frontiers: u32,
}

/// A decision in the trace: after which event, which robot, which goal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceGoal {
    /// Number of events before the decision.
    pub event: u32,
    /// The robot.
    pub robot: u32,
    /// Its new goal, or `None` if it found none.
    pub goal: Option<u32>,
}

/// One sample of a decision-theoretic decision, as the trace records it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DtSample {
    /// The sample's cell.
    pub cell: u32,
    /// Its expected information gain `I(p)` in bits.
    pub gain: f64,
    /// Its path cost `L(p)` in metres from the deciding robot (infinite if unreachable).
    pub cost_m: f64,
    /// Its utility `I·exp(−λ·L)`.
    pub utility: f64,
}

/// A decision of the decision-theoretic strategy in the trace.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DtDecision {
    /// Number of events before the decision.
    pub event: u32,
    /// The deciding robot.
    pub robot: u32,
    /// Whether no sample had a gain, so the frontier cells were the candidates.
    pub fell_back: bool,
    /// Every candidate with its gain, cost and utility (gains the decision did not need
    /// are evaluated for the trace; the decision is unchanged).
    pub samples: Vec<DtSample>,
    /// The chosen goal.
    pub chosen: Option<u32>,
}

/// Per-step record of a run, for pictures and replays: every event with the belief changes
/// it made (only what changed, so a long run stays compact).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Number of robots.
    pub robots: usize,
    /// Start cell of each robot.
    pub starts: Vec<u32>,
    /// Every event in order.
    pub events: Vec<TraceEvent>,
    /// Belief changes (cell, new class); event k made `changes[change_ends[k-1]..change_ends[k]]`.
    pub changes: Vec<(u32, Occ)>,
    /// End of each event's changes in `changes`.
    pub change_ends: Vec<u32>,
    /// Every decision's outcome.
    pub goals: Vec<TraceGoal>,
    /// Every decision-theoretic decision (`dt`, `dt500`, `dt-rr`) in detail: its samples
    /// with `I`, `L` and utility, and the chosen goal.
    pub dt: Vec<DtDecision>,
    /// Goal candidates of each decision (not recorded when the candidates are all frontier
    /// cells, which the frontier layer shows): (events before it, candidate cells).
    pub candidates: Vec<(u32, Vec<u32>)>,
    /// Snapshots of the segmentation of segmenting strategies, taken after decisions that
    /// changed it, at most [`MAX_SEGMENT_SNAPSHOTS`] spread over the run.
    pub segments: Vec<SegmentSnapshot>,
    /// Segmentation counters (full runs, patches) at the last decision seen.
    pub segment_counters: (usize, usize),
    /// Changed segmentations seen so far.
    pub segment_changes: usize,
    /// Every how many changed segmentations one is kept (doubles when the cap is hit).
    pub segment_stride: usize,
}

/// At most this many segmentation snapshots are kept in a trace.
pub const MAX_SEGMENT_SNAPSHOTS: usize = 100;

/// The segmentation as it was after a decision, labels run-length encoded.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SegmentSnapshot {
    /// Number of events before the decision.
    pub event: u32,
    /// Whether the segmentation was recomputed whole (else patched) since the last decision.
    pub full: bool,
    /// (label, run length) pairs in cell order; label `u32::MAX` = not segmented.
    pub runs: Vec<(u32, u32)>,
}

impl SegmentSnapshot {
    /// The label of every cell.
    pub fn labels(&self) -> Vec<u32> {
        let mut out = Vec::new();
        for &(label, n) in &self.runs {
            out.extend(std::iter::repeat_n(label, n as usize));
        }
        out
    }
}

impl Trace {
    /// Every cell each robot stood on, in order (start included).
    pub fn trails(&self) -> Vec<Vec<u32>> {
        let mut trails: Vec<Vec<u32>> = self.starts.iter().map(|&s| vec![s]).collect();
        for e in &self.events {
            let trail = &mut trails[e.robot as usize];
            if trail.last() != Some(&e.cell) {
                trail.push(e.cell);
            }
        }
        trails
    }

    /// After a decision (after `event` events): keep a snapshot of the segmentation `labels`
    /// if the segmenter's counters (`full_runs`, `patches`) moved since the last decision.
    /// Only every `segment_stride`-th change is kept; when [`MAX_SEGMENT_SNAPSHOTS`] are
    /// held, every other one is dropped and the stride doubles, so the snapshots stay
    /// spread over the whole run.
    pub fn record_segments(
        &mut self,
        event: u32,
        full_runs: usize,
        patches: usize,
        labels: &[u32],
    ) {
        let before = self.segment_counters;
        if (full_runs, patches) == before || labels.is_empty() {
            return;
        }
        self.segment_counters = (full_runs, patches);
        let stride = self.segment_stride.max(1);
        self.segment_changes += 1;
        if !(self.segment_changes - 1).is_multiple_of(stride) {
            return;
        }
        let mut runs: Vec<(u32, u32)> = Vec::new();
        for &l in labels {
            match runs.last_mut() {
                Some((last, n)) if *last == l => *n += 1,
                _ => runs.push((l, 1)),
            }
        }
        self.segments.push(SegmentSnapshot {
            event,
            full: full_runs != before.0,
            runs,
        });
        if self.segments.len() >= MAX_SEGMENT_SNAPSHOTS {
            let mut k = 0;
            self.segments.retain(|_| {
                k += 1;
                k % 2 == 1
            });
            self.segment_stride = stride * 2;
        }
    }

    /// The belief changes made by event `k`.
    pub fn changes_of(&self, k: usize) -> &[(u32, Occ)] {
        let start = if k == 0 {
            0
        } else {
            self.change_ends[k - 1] as usize
        };
        &self.changes[start..self.change_ends[k] as usize]
    }
}

/// Coverage levels (per cent) whose first reaching a run records: D90/T90, D98/T98 (the
/// level Explore-Bench reports) and D99/T99.
pub const MILESTONES: [u32; 3] = [90, 98, 99];

/// When a run first reached a coverage level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Milestone {
    /// The level in per cent.
    pub percent: u32,
    /// Distance the team had travelled, in metres (summed over robots).
    pub dist_m: f64,
    /// Time in seconds: the clock of the robot whose sensing reached it, or the level
    /// below's time if that is later (a team's moves are taken in the order the robots set
    /// out on them, so a move taken later can end earlier).
    pub time_s: f64,
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
    /// Path length of each robot in metres, measured as [`RunResult::motion`] says.
    pub path_length_m: Vec<f64>,
    /// Path length of each robot in metres as grid moves (equal to `path_length_m` under
    /// grid motion).
    pub grid_path_length_m: Vec<f64>,
    /// How `path_length_m` and `time_s` are measured.
    pub motion: crate::motion::Motion,
    /// Exploration time in seconds: when the last robot finished (its clock: travel at
    /// `speed`, the stops after bumps, the waits for the others).
    pub time_s: f64,
    /// Number of decisions taken (one per robot that chose a goal or found none).
    pub decisions: u64,
    /// Cell moves of the whole team.
    pub moves: u64,
    /// Scans taken by the team (start and arrival sweeps included).
    pub scans: u64,
    /// Goals the team gave up under Yamauchi's no-progress rule (put on the inaccessible
    /// list because they came no closer for the limit).
    pub gave_up: u64,
    /// The robot's clearance in cells (traversability of the belief used clearance this big).
    pub clearance_cells: f64,
    /// Start cell of each robot.
    pub starts: Vec<Cell>,
    /// Final cell of each robot.
    pub ends: Vec<Cell>,
    /// Coverage over total distance: (metres travelled by the team, coverage), at every change.
    pub coverage_curve: Vec<(f64, f64)>,
    /// The levels of [`MILESTONES`] the run reached, in order, with distance and time.
    pub milestones: Vec<Milestone>,
    /// Cells sensed by two or more robots over cells sensed by any (0 for one robot): the
    /// team's overlap ratio.
    pub overlap: f64,
    /// Seconds each robot did not travel before the run's end (`time_s` less its own
    /// travel time): idle without a goal, stopped after a bump, or done before the others.
    pub idle_s: Vec<f64>,
    /// Wall-clock phase timings.
    pub times: PhaseTimes,
    /// The final belief, classified.
    pub belief: Grid<Occ>,
    /// Open frontier cells left at the end: frontier cells not on the visited or inaccessible
    /// lists (none when complete).
    pub frontiers_left: Vec<u32>,
    /// The map built against the ground truth.
    pub audit: MapAudit,
    /// The run's obstacles off the laser plane (the configured layer), for pictures.
    pub clutter: Option<Grid<bool>>,
    /// The per-step trace, when asked for.
    pub trace: Option<Trace>,
}

/// How the map a run built compares with the ground truth — what Yamauchi's sonar, its
/// specular reflections and furniture off the laser plane put at risk.
///
/// The *building* is every cell that is free or occupied in the ground truth (cells
/// outside the map's world are not counted), with off-plane clutter counted occupied: a
/// table is an obstacle for the robot whether or not its laser sees it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapAudit {
    /// Share of the building's cells whose final believed class equals the ground truth's
    /// (a cell never seen counts as wrong).
    pub accuracy: f64,
    /// Cells believed free at the end that are not free in the ground truth (phantom open
    /// space: walls erased by specular reflections, space outside the building, tables).
    pub false_free_cells: usize,
    /// Off-plane clutter cells believed occupied at the end.
    pub clutter_mapped: usize,
    /// Off-plane clutter cells in the ground truth.
    pub clutter_cells: usize,
    /// Phantom frontier regions — 8-connected frontier regions with a cell that is not free
    /// in the ground truth — summed over the decisions of the run.
    pub phantom_regions: u64,
    /// All frontier regions, summed over the decisions of the run (when phantoms are
    /// counted: with sonar, clutter or a probabilistic belief).
    pub frontier_regions: u64,
    /// The most phantom frontier regions at one decision.
    pub phantom_regions_max: u64,
    /// Goals chosen on cells that are not free in the ground truth.
    pub phantom_goals: u64,
}

impl RunResult {
    /// Distance and time (metres, seconds) at which coverage first reached `percent` (one of
    /// [`MILESTONES`]), if it did.
    pub fn milestone(&self, percent: u32) -> Option<(f64, f64)> {
        self.milestones
            .iter()
            .find(|m| m.percent == percent)
            .map(|m| (m.dist_m, m.time_s))
    }
}

impl MapAudit {
    /// The share of frontier regions that were phantoms, over all decisions (0 if none).
    pub fn phantom_share(&self) -> f64 {
        if self.frontier_regions == 0 {
            0.0
        } else {
            self.phantom_regions as f64 / self.frontier_regions as f64
        }
    }

    /// Phantom frontier regions per decision, on average.
    pub fn phantom_regions_mean(&self, decisions: u64) -> f64 {
        if decisions == 0 {
            0.0
        } else {
            self.phantom_regions as f64 / decisions as f64
        }
    }
}

impl RunResult {
    /// Whether every reachable free cell was explored: the run ended with nothing left to
    /// explore, or at a coverage goal of all of it.
    pub fn complete(&self) -> bool {
        self.reason == EndReason::Complete
            || (self.reason == EndReason::GoalReached && self.coverage >= 1.0)
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
