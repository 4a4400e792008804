//! The loop (ARCHITECTURE.md "Bird's-eye view"; Faigl & Kulich's steps 1–8).
//!
//! Robots move concurrently: the robot whose clock is earliest (ties: lowest id) makes the
//! next cell move, so the team's moves interleave as they would in continuous time at
//! speed v. After every move the robot senses (continuous mode) and the frontier upkeep
//! sees only the cells that changed; then the re-plan policy decides whether this robot
//! (or, for the periodic s_max trigger, the whole team) decides again.
//!
//! Robots are points on cells and may pass through each other (neither multi-robot paper
//! models inter-robot collisions).
//!
//! With a sonar ring (Yamauchi 1997) the belief can show free space that is not (specular
//! reflections) and the truth can hold obstacles off the laser plane (*imperfect sensing*).
//! A robot whose next cell is an obstacle in the truth, or whose diagonal step passes a
//! corner it cannot squeeze through, bumps: it stops for [`BUMP_S`] seconds, senses again,
//! pins those cells occupied in its belief and re-plans; the cells it stands on are pinned
//! free. A robot that then stands within its clearance of what it met (or of an obstacle
//! its evidence grid believed only once it was near), where no search leads out, backs
//! away before it decides to the nearest cell from which a search does
//! (`Team::back_off`). Yamauchi's no-progress rule then puts a goal that is not approached
//! for its time limit on the inaccessible list, also across such re-plans.
//!
//! A robot that senses only on arrival or every n cells moves blind in between. Before it
//! enters a cell within its clearance of an obstacle its map does not show yet, it stops,
//! looks around (its reactive obstacle avoidance, Yamauchi §2.3) and re-plans if it now
//! sees that it cannot enter; otherwise it would stand where its clearance forbids, and no
//! search could lead it out. Continuous sensing, which looks from every cell it enters, is
//! left as it was.

use std::borrow::Cow;
use std::time::Instant;

use explore::assign::{AssignerKind, utility};
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::{self, DecisionCtx, Goal, GoalLists, Memory, Offer, Planner};
use explore::strategy::SensingMode;

/// `dt-rr` re-evaluates its target's utility every this many moves (one predicted scan).
const DT_RECHECK_MOVES: u32 = 5;

/// Seconds a robot loses when its body meets an obstacle (stop, sense again).
pub const BUMP_S: f64 = 1.0;

/// How many times a penned-in robot backs away before it decides ([`Team::back_off`]).
const BACK_OFF_TRIES: usize = 3;

/// Yamauchi's no-progress limit (the `yamauchi` preset's), applied to every strategy when
/// the map can be wrong about where the robot can go (sonar, off-plane clutter): without
/// it, a goal behind an obstacle the map does not show would be chased forever.
pub const IMPERFECT_NO_PROGRESS_S: f64 = 30.0;
use crate::changes::{CellBox, ChangeTracker};
use crate::motion::{Motion, any_angle_prefix_lengths, grid_prefix_lengths};
use explore::plan::reachability::{PROBE_FROM, PROBE_SHARE};
use explore::upkeep::FrontierUpkeep;
use grid::{Cell, Grid, GridMap, Occ, step_cost};
use rand_pcg::Pcg64Mcg;
use sense::Unseen;
use sense::{Belief, Observation, Pose, Sensor, SensorSpec, SonarMode, SonarReading, SonarSensor};

use crate::config::{CoverageKind, RunConfig, SimError};
use crate::metrics::{
    DtDecision, DtSample, EndReason, MILESTONES, MapAudit, Milestone, PhaseTimes, RunResult, Trace,
    TraceEvent, TraceGoal,
};
use crate::{seed, truth};

/// One robot's state.
struct Robot {
    cell: u32,
    heading: f64,
    /// Seconds: distance / speed (plus waiting).
    clock: f64,
    /// Seconds of `clock` not travelled: stops after bumps and waits for the others.
    stopped_s: f64,
    /// Cells travelled (straight 1, diagonal √2).
    dist_cells: f64,
    /// Cells stood on, in order (kept only for any-angle motion).
    trail: Vec<u32>,
    /// Positions in `trail` where the robot set out on a new path (any-angle motion: the
    /// smoothed route keeps them as corners).
    legs: Vec<usize>,
    /// Remaining cells of the current path (next cell first is at `path_pos`).
    path: Vec<u32>,
    path_pos: usize,
    goal: Option<u32>,
    moves_since_decision: u32,
    /// Cells entered since its last scan (sensing `every-N`).
    unsensed: u32,
    /// Remaining path cost to the goal, its lowest value so far, and the clock then
    /// (Yamauchi's no-progress rule), for the goal `progress_goal`: a new decision for the
    /// same goal keeps them, so a detour is no progress.
    remaining: f64,
    best_remaining: f64,
    progress_clock: f64,
    progress_goal: Option<u32>,
    /// No goal was found at its last decision.
    idle: bool,
    /// `dt-rr`: the target's utility at decision time and the heading it was scored with.
    utility0: f64,
    heading0: f64,
    /// The goal was an open frontier cell when chosen, so repetitive re-checking applies to
    /// it (a coverage cell or region centroid, offered from Python, is not a frontier).
    goal_was_frontier: bool,
}

/// A proposal of the pending decision and what it left: the strategy stream and the
/// assigners' kept state, taken by the session only with the proposal's goals.
struct Asked {
    goals: Vec<Option<Goal>>,
    rng: Pcg64Mcg,
    kept: explore::decision::Kept,
}

/// Everything the loop owns besides the robots.
struct Team<'a> {
    truth: Cow<'a, GridMap>,
    cfg: Cow<'a, RunConfig>,
    /// Goals come from outside ([`Session::choose`]) instead of the strategy's assigner.
    external: bool,
    /// An external decision is due: candidates are generated, goals not yet chosen.
    pending: bool,
    /// No robot can reach a candidate: the exploration is over ("no frontiers are left"),
    /// though robots may still be on their way to goals explored since.
    exhausted: bool,
    /// Candidates offered to an assigner by [`Session::propose`].
    offered: CandidateSet,
    /// Goals an assigner proposed.
    proposed: Vec<Option<Goal>>,
    /// Each proposal of the pending decision ([`Asked`]): the strategy stream and what the
    /// assigners carry between decisions are put back after a proposal, and taken from the
    /// proposal whose goals are chosen ([`Session::choose`]).
    asked: Vec<Asked>,
    /// Buffers of information-gain predictions.
    gain_scratch: sense::gain::GainScratch,
    /// The fill that tells whether a robot is penned in ([`Team::back_off`]).
    pocket: Pocket,
    sensor: Box<dyn Sensor>,
    sweep: Box<dyn Sensor>,
    /// The line of sight remembered per cell, shared with other runs of the same ground
    /// truth ([`Session::share_sight`]): the same scans as `sensor`'s.
    sight: Option<std::sync::Arc<sense::SightCache>>,
    belief: Box<dyn Belief>,
    /// Who sensed which cell: a team's overlap, and what a scan could still tell (`None`
    /// for a single robot whose scans report everything).
    unseen: Option<Unseen>,
    /// Whether scans report only what tells the robot something (not with sonar or
    /// clutter, which are not exact, nor with an evidence grid, which grades repeated
    /// observations).
    skip_known: bool,
    upkeep: FrontierUpkeep,
    planner: Planner,
    lists: GoalLists,
    /// The candidates of the last decision (and the shared decision step's buffers).
    offer: Offer,
    memory: Memory,
    rng: Pcg64Mcg,
    obs: Observation,
    changed: Vec<u32>,
    /// Where the belief changed since a consumer last asked (when one asked to track).
    tracker: Option<ChangeTracker>,
    /// Imperfect sensing (sonar, off-plane clutter): the map can be wrong about where the
    /// robot can go. Then the cells it stands on are pinned free, phantom frontier regions
    /// are counted at every decision (ideal sensors never show a non-free cell free, so
    /// there are none otherwise), and every strategy gets a no-progress limit.
    imperfect: bool,
    /// The no-progress limit in seconds: the strategy's, or [`IMPERFECT_NO_PROGRESS_S`]
    /// under imperfect sensing.
    no_progress_s: Option<f64>,
    regions_buf: Vec<explore::frontier::Region>,
    audit: MapAudit,
    /// Where the robot's body can be, when off-plane clutter makes it differ from the plane.
    body: Option<Grid<Occ>>,
    /// The sonar ring, its noise stream and reading buffers (when sensing with sonar).
    sonar: Option<SonarSensor>,
    sonar_rng: Pcg64Mcg,
    readings: Vec<SonarReading>,
    laser_hits: Vec<u32>,
    /// Ground-truth reachable cells, and which of them are known free.
    reachable: Vec<bool>,
    counted: Vec<bool>,
    covered: usize,
    reachable_cells: usize,
    /// `--coverage known`: the cells the ground truth knows, which of them are known, and
    /// both counts (empty otherwise).
    knowable: Vec<bool>,
    known_counted: Vec<bool>,
    known_covered: usize,
    knowable_cells: usize,
    range_cells: f64,
    // Decision buffers.
    cells_buf: Vec<u32>,
    goals_buf: Vec<Option<u32>>,
    deciding: Vec<bool>,
    out: Vec<Option<Goal>>,
    path_buf: Vec<u32>,
    arrive_buf: Vec<usize>,
    all: Vec<usize>,
    // Metrics.
    decisions: u64,
    moves: u64,
    times: PhaseTimes,
    total_dist_cells: f64,
    curve: Vec<(f64, f64)>,
    milestones: Vec<Milestone>,
    /// With any-angle motion, to measure the curve and the milestones along the routes:
    /// the robot of each move in order, and how many moves had been made at each point of
    /// `curve` and at each milestone (with the robot whose sensing reached it).
    move_log: Vec<u32>,
    curve_moves: Vec<usize>,
    milestone_moves: Vec<(usize, usize)>,
    /// The robot sensing now and its clock (for milestones and overlap).
    now: (usize, f64),
    /// The cells sensed first and sensed by a second robot (teams), from `unseen`.
    sensed_cells: usize,
    overlap_cells: usize,
    /// Scans taken.
    scans: u64,
    /// Goals given up by the no-progress rule.
    gave_up: u64,
    trace: Option<Trace>,
}

/// Run one exploration of `truth` as configured.
pub fn run(truth: &GridMap, cfg: &RunConfig) -> Result<RunResult, SimError> {
    run_sharing(truth, cfg, None)
}

/// A session of `cfg` on `truth` for a whole run, its scans made through `sight` where it
/// serves the run ([`Session::share_sight`]).
fn start_sharing<'a>(
    truth: &'a GridMap,
    cfg: &'a RunConfig,
    sight: Option<&std::sync::Arc<sense::SightCache>>,
) -> Result<Session<'a>, SimError> {
    let mut session = Session::start(Cow::Borrowed(truth), Cow::Borrowed(cfg), false)?;
    if let Some(s) = sight {
        session.share_sight(s.clone());
    }
    Ok(session)
}

/// [`run()`], its scans made through `sight` where it serves the run
/// ([`Session::share_sight`]): the same result.
pub fn run_sharing(
    truth: &GridMap,
    cfg: &RunConfig,
    sight: Option<&std::sync::Arc<sense::SightCache>>,
) -> Result<RunResult, SimError> {
    let mut session = start_sharing(truth, cfg, sight)?;
    session.advance();
    Ok(session.finish())
}

/// [`run()`], pausing every `steps` steps of the loop to call `between` with the session
/// (to show progress, or to look at a stop flag), its scans made through `sight` where it
/// serves the run ([`Session::share_sight`]): the same run. `between` returning `false`
/// stops it, without a result (`None`).
pub fn run_pausing(
    truth: &GridMap,
    cfg: &RunConfig,
    sight: Option<&std::sync::Arc<sense::SightCache>>,
    steps: u64,
    mut between: impl FnMut(&Session<'_>) -> bool,
) -> Result<Option<RunResult>, SimError> {
    let mut session = start_sharing(truth, cfg, sight)?;
    while session.advance_for(steps).is_none() {
        if !between(&session) {
            return Ok(None);
        }
    }
    Ok(Some(session.finish()))
}

/// Where a [`Session`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// An external decision is due: read the candidates, then [`Session::choose`].
    Decide,
    /// The run is over.
    Ended(EndReason),
}

/// One run of the loop that can stop at every decision: the stepping form of [`run()`].
///
/// With `external` goals the session stops whenever robots must decide ([`Status::Decide`]):
/// the strategy's candidates are generated, and the caller picks the goals
/// ([`choose`](Self::choose)) — a learning agent, or an assigner through
/// [`propose`](Self::propose). Without, the strategy's assigner decides and
/// [`advance`](Self::advance) runs to the end; that is exactly [`run()`], which is
/// implemented this way, so there is one loop.
pub struct Session<'a> {
    team: Team<'a>,
    robots: Vec<Robot>,
    starts: Vec<Cell>,
    started: Instant,
    reason: Option<EndReason>,
}

impl<'a> Session<'a> {
    /// Set up a run of `truth` as configured: place the robots, let each look around once
    /// and make the first decision (with `external` goals, stop before choosing them).
    pub fn start(
        truth: Cow<'a, GridMap>,
        cfg: Cow<'a, RunConfig>,
        external: bool,
    ) -> Result<Self, SimError> {
        let started = Instant::now();
        check_config(&cfg)?;
        check_clutter(&truth, &cfg)?;
        let res = truth.resolution;
        let cells = &truth.cells;
        let (w, h) = (cells.width(), cells.height());
        // Where the robot's body can be: the plane's free cells less the off-plane clutter.
        let body = cfg.clutter.as_ref().map(|c| truth::with_clutter(cells, c));
        let cells_for_body = body.as_ref().unwrap_or(cells);
        let trav_truth = body_traversable(cells_for_body, &truth, &cfg);
        let components = truth::components(cells_for_body, &trav_truth);
        let starts: Vec<Cell> = if cfg.starts.is_empty() {
            let mut rng = seed::rng(cfg.seed, "start");
            let first = truth::random_start(&components, &mut rng, cfg.clearance_m)?;
            truth::team_starts(cells_for_body, &trav_truth, first, cfg.robots)?
        } else {
            check_given_starts(cells_for_body, &trav_truth, &cfg)?;
            cfg.starts.clone()
        };
        let reachable = truth::reachable_from(&components.0, cells.index(starts[0]));
        let reachable_cells = reachable.iter().filter(|&&r| r).count();
        let knowable: Vec<bool> = match cfg.coverage {
            CoverageKind::ReachableFree => Vec::new(),
            CoverageKind::Known => cells.data().iter().map(|&s| s != Occ::Unknown).collect(),
        };
        drop((trav_truth, components));

        let (sensor, sweep, sonar) = build_sensing(&cfg, res)?;
        let imperfect = sonar.is_some() || cfg.clutter.is_some();
        let m = cfg.robots;
        let len = cells.len();
        let robots: Vec<Robot> = starts
            .iter()
            .map(|&c| Robot {
                cell: cells.index(c) as u32,
                heading: 0.0,
                clock: 0.0,
                stopped_s: 0.0,
                dist_cells: 0.0,
                trail: vec![cells.index(c) as u32],
                legs: Vec::new(),
                path: Vec::new(),
                path_pos: 0,
                goal: None,
                moves_since_decision: 0,
                unsensed: 0,
                remaining: f64::INFINITY,
                best_remaining: f64::INFINITY,
                progress_clock: 0.0,
                progress_goal: None,
                idle: false,
                utility0: 0.0,
                heading0: 0.0,
                goal_was_frontier: false,
            })
            .collect();
        let trace = cfg.record_trace.then(|| Trace {
            robots: m,
            starts: starts.iter().map(|&c| cells.index(c) as u32).collect(),
            ..Trace::default()
        });
        let belief = cfg.belief.build(w, h);
        let skip_known = !imperfect
            && cfg.belief != sense::BeliefKind::Evidence
            && (sensor.skips_known() || sweep.skips_known());
        let unseen = (m > 1 || skip_known).then(|| {
            // Blocks of 8 cells (16 from 64 cells of range): fine enough to leave much of a
            // scan out, coarse enough that listing them costs little beside it.
            let shift = if sensor.range_cells() < 64.0 { 3 } else { 4 };
            Unseen::new(cells, m, shift)
        });
        let team = Team {
            range_cells: sensor.range_cells(),
            sensor,
            sweep,
            sight: None,
            belief,
            unseen,
            skip_known,
            upkeep: FrontierUpkeep::new(w, h, grid::units::cells(cfg.clearance_m, res)),
            planner: Planner::new(w, h, m),
            lists: GoalLists::new(len),
            offer: Offer::new(len),
            memory: {
                let mut memory = Memory::default();
                memory.dt.model = sense::gain::InverseModel::for_belief(cfg.belief);
                memory
            },
            rng: seed::rng(cfg.seed, "strategy"),
            obs: Observation::new(),
            changed: Vec::new(),
            tracker: None,
            imperfect,
            no_progress_s: cfg
                .strategy
                .replan
                .no_progress_s
                .or(imperfect.then_some(IMPERFECT_NO_PROGRESS_S)),
            regions_buf: Vec::new(),
            audit: MapAudit::default(),
            body,
            sonar,
            sonar_rng: seed::rng(cfg.seed, "sonar"),
            readings: Vec::with_capacity(sense::sonar::TRANSDUCERS),
            laser_hits: Vec::new(),
            counted: vec![false; len],
            knowable_cells: knowable.iter().filter(|&&k| k).count(),
            known_counted: vec![false; knowable.len()],
            knowable,
            known_covered: 0,
            reachable,
            covered: 0,
            reachable_cells,
            cells_buf: vec![0; m],
            goals_buf: vec![None; m],
            deciding: vec![false; m],
            out: vec![None; m],
            path_buf: Vec::new(),
            arrive_buf: Vec::new(),
            all: (0..m).collect(),
            decisions: 0,
            moves: 0,
            times: PhaseTimes::default(),
            total_dist_cells: 0.0,
            curve: vec![(0.0, 0.0)],
            milestones: Vec::new(),
            move_log: Vec::new(),
            curve_moves: vec![0],
            milestone_moves: Vec::new(),
            now: (0, 0.0),
            sensed_cells: 0,
            overlap_cells: 0,
            scans: 0,
            gave_up: 0,
            trace,
            external,
            pending: false,
            exhausted: false,
            offered: if external {
                CandidateSet::new(len)
            } else {
                CandidateSet::default()
            },
            proposed: vec![None; m],
            asked: Vec::new(),
            gain_scratch: sense::gain::GainScratch::new(),
            pocket: Pocket::default(),
            truth,
            cfg,
        };
        let mut session = Session {
            team,
            robots,
            starts,
            started,
            reason: None,
        };
        let (team, robots) = (&mut session.team, &mut session.robots);
        // Every robot looks around once where it stands.
        for r in 0..m {
            let pose = Pose {
                cell: team.truth.cells.cell(robots[r].cell as usize),
                heading: 0.0,
            };
            team.sense((r, 0.0), pose, true);
            team.pin_free(robots[r].cell);
            team.record(robots, r);
        }
        let all: Vec<usize> = (0..m).collect();
        team.decide(robots, &all);
        Ok(session)
    }

    /// Run until an external decision is due or the run ends.
    pub fn advance(&mut self) -> Status {
        loop {
            if let Some(status) = self.advance_for(u64::MAX) {
                return status;
            }
        }
    }

    /// [`advance`](Self::advance), but pause after `steps` steps of the loop (a step moves
    /// one robot one cell, or makes it decide) and return `None`: a caller can show
    /// progress between slices. Slices of any size run the same run as one `advance`.
    pub fn advance_for(&mut self, steps: u64) -> Option<Status> {
        if let Some(reason) = self.reason {
            return Some(Status::Ended(reason));
        }
        if self.team.pending {
            return Some(Status::Decide);
        }
        let (team, robots) = (&mut self.team, &mut self.robots);
        let m = robots.len();
        let mut left = steps;
        let reason = loop {
            if let Some(g) = team.cfg.coverage_goal
                && team.coverage() >= g
            {
                break EndReason::GoalReached;
            }
            if team.moves >= team.cfg.max_moves {
                break EndReason::StepLimit;
            }
            if team
                .trace
                .as_ref()
                .is_some_and(|t| t.events.len() as u64 >= team.cfg.trace_events)
            {
                break EndReason::TraceLimit;
            }
            // The active robot with the earliest clock moves next; none is left to move
            // once every robot is idle or no robot can reach a candidate.
            let Some(r) = (0..m)
                .filter(|&r| !robots[r].idle && !team.exhausted)
                .min_by(|&a, &b| robots[a].clock.total_cmp(&robots[b].clock).then(a.cmp(&b)))
            else {
                break if team.covered == team.reachable_cells {
                    EndReason::Complete
                } else {
                    EndReason::NoReachableFrontier
                };
            };
            if left == 0 {
                return None;
            }
            left -= 1;
            team.step(robots, r);
            if team.pending {
                return Some(Status::Decide);
            }
        };
        self.reason = Some(reason);
        Some(Status::Ended(reason))
    }

    /// Which robots the pending decision is for (all false when none is pending).
    pub fn deciding(&self) -> &[bool] {
        if self.team.pending {
            &self.team.deciding
        } else {
            &[]
        }
    }

    /// The candidates the strategy's generator offered at the last decision, in its order.
    pub fn candidates(&self) -> &[u32] {
        self.team.offer.candidates.cells()
    }

    /// The position of `cell` among the candidates of the last decision, if it is one.
    pub fn candidate_position(&self, cell: u32) -> Option<usize> {
        self.team.offer.candidates.index_of(cell as usize)
    }

    /// The (at most) `k` candidates of the pending decision cheapest for robot `r` to reach,
    /// by (path cost in cells, cell index), into `out`. The search from the robot stops as
    /// soon as `k` candidates are settled, so the cost follows the area nearer than them.
    pub fn nearest_candidates(&mut self, r: usize, k: usize, out: &mut Vec<Goal>) {
        out.clear();
        let team = &mut self.team;
        if r >= self.robots.len() || k == 0 || team.offer.candidates.is_empty() {
            return;
        }
        let from = self.robots[r].cell;
        let known = team.belief.known();
        let mut seen = 0;
        let mut through = 0;
        // As the nearest rule does (`Reachability::nearest_guided`): among many candidates
        // an unguided search first, up to a budget of settled cells, then a guided one.
        let many = team.offer.candidates.len();
        let mut probe = (many > PROBE_FROM && !team.planner.is_searching(r))
            .then(|| (many - PROBE_FROM) / PROBE_SHARE);
        let mut search = None;
        loop {
            let goals = team.offer.candidates.cells();
            let done = match probe {
                Some(_) => team
                    .planner
                    .grow_unguided(r, from, known, &team.upkeep, through),
                None => team
                    .planner
                    .grow(r, from, known, &team.upkeep, goals, through),
            };
            let map = team.planner.map(r);
            if search != Some(map.search_id()) {
                // a search begun (again, guided after the probe): read it from its start
                (search, seen) = (Some(map.search_id()), 0);
                out.clear();
            }
            let settled = map.settled();
            for &c in &settled[seen.min(settled.len())..] {
                if team.offer.candidates.contains(c as usize) {
                    let cost = map.cost(c as usize).unwrap_or(f64::INFINITY);
                    out.push(Goal { cell: c, cost });
                }
            }
            seen = settled.len();
            if done || out.len() >= k {
                break;
            }
            through = map.next_bucket();
            if probe.is_some_and(|budget| seen > budget) {
                // too far for the probe: the guided search from the start
                (probe, through) = (None, 0);
            }
        }
        out.sort_by(|a, b| a.cost.total_cmp(&b.cost).then(a.cell.cmp(&b.cell)));
        out.truncate(k);
    }

    /// The goals `assigner` would give the deciding robots if only `cells` (candidates of the
    /// pending decision, in this order) were offered: a paper's rule acting as a policy.
    /// Draws from a copy of the run's strategy stream, and works on a copy of what the
    /// assigners keep across decisions (SGA's and MA's centres), as the rule would in a run:
    /// the run takes both only if [`Session::choose`] then gives these goals (from the last
    /// proposal of them), so asking for a proposal that is not taken leaves the run as it
    /// was.
    pub fn propose(&mut self, assigner: AssignerKind, cells: &[u32]) -> &[Option<Goal>] {
        let t = &mut self.team;
        let before = t.pending.then(|| (t.rng.clone(), t.memory.kept()));
        self.propose_drawing(assigner, cells);
        let t = &mut self.team;
        if let Some((rng, kept)) = before {
            t.asked.push(Asked {
                goals: t.proposed.clone(),
                rng: std::mem::replace(&mut t.rng, rng),
                kept: t.memory.put_back(kept),
            });
        }
        &self.team.proposed
    }

    /// [`Session::propose`] into `proposed`, drawing from the run's strategy stream itself.
    fn propose_drawing(&mut self, assigner: AssignerKind, cells: &[u32]) {
        let t = &mut self.team;
        if !t.pending {
            t.proposed.fill(None);
            return;
        }
        t.offered.clear();
        for &c in cells {
            if t.offer.candidates.contains(c as usize) {
                t.offered.insert(c);
            }
        }
        if assigner == AssignerKind::Nearest && t.nearest_from_searches(&self.robots) {
            return;
        }
        let mut ctx = DecisionCtx {
            known: t.belief.known(),
            upkeep: &mut t.upkeep,
            planner: &mut t.planner,
            robots: &t.cells_buf,
            deciding: &t.deciding,
            goals: &t.goals_buf,
            lists: &t.lists,
            resolution: t.truth.resolution,
            sensor_range_cells: t.range_cells,
            rng: &mut t.rng,
            belief: t.belief.as_ref(),
            sensor: t.sensor.as_ref(),
            memory: &mut t.memory,
        };
        assigner.assign(&mut ctx, &t.offered, &mut t.proposed);
    }

    /// Give the deciding robots their goals (one entry per robot; `None` = no goal, the robot
    /// waits and retries at the next decision; entries of robots not deciding are ignored),
    /// then carry on as after an assigner's choice.
    pub fn choose(&mut self, goals: &[Option<u32>]) -> Result<(), SimError> {
        let t = &mut self.team;
        let m = self.robots.len();
        if !t.pending {
            return Err(SimError::BadParameter {
                field: "goal",
                expected: "a pending decision",
                found: "none is pending".into(),
            });
        }
        if goals.len() != m {
            return Err(SimError::BadParameter {
                field: "goals",
                expected: "one entry per robot",
                found: format!("{} entries for {m} robots", goals.len()),
            });
        }
        for (r, &goal) in goals.iter().enumerate() {
            t.out[r] = None;
            let Some(cell) = goal.filter(|_| t.deciding[r]) else {
                continue;
            };
            if cell as usize >= t.truth.cells.len() {
                return Err(SimError::BadParameter {
                    field: "goal",
                    expected: "a cell of the map",
                    found: format!("cell index {cell}"),
                });
            }
            let from = self.robots[r].cell;
            if !t.planner.path(r, cell, &mut t.path_buf) {
                t.planner.full(r, from, t.belief.known(), &t.upkeep);
            }
            let Some(cost) = t.planner.map(r).cost(cell as usize) else {
                return Err(SimError::BadParameter {
                    field: "goal",
                    expected: "a cell the robot can reach",
                    found: format!("{} for robot {r}", t.truth.cells.cell(cell as usize)),
                });
            };
            t.out[r] = Some(Goal { cell, cost });
        }
        // The stream and kept state as the last proposal of these goals left them, if one
        // was asked for: the one the caller acted on (asked for after any other that
        // happened to propose the same goals).
        let taken = t.asked.iter().rposition(|a| {
            (0..m).all(|r| !t.deciding[r] || a.goals[r].map(|g| g.cell) == goals[r])
        });
        if let Some(k) = taken {
            let a = t.asked.swap_remove(k);
            t.rng = a.rng;
            t.memory.put_back(a.kept);
        }
        t.asked.clear();
        t.pending = false;
        t.conclude(&mut self.robots, Instant::now());
        Ok(())
    }

    /// Expected information gain of sensing from `cell` facing `heading` (radians): on the
    /// ternary belief, the number of unknown cells a predicted scan would see.
    pub fn information_gain(&mut self, cell: u32, heading: f64) -> f64 {
        let t = &mut self.team;
        let pose = Pose {
            cell: t.truth.cells.cell(cell as usize),
            heading,
        };
        sense::gain::information_gain(
            t.sensor.as_ref(),
            t.belief.as_ref(),
            &t.memory.dt.model,
            pose,
            &mut t.gain_scratch,
        )
    }

    /// The belief's known grid.
    pub fn known(&self) -> &Grid<Occ> {
        self.team.belief.known()
    }

    /// Track where the belief changes from now on ([`Session::take_changes`]).
    pub fn track_changes(&mut self) {
        let w = self.team.truth.cells.width();
        self.team
            .tracker
            .get_or_insert_with(|| ChangeTracker::new(w));
    }

    /// The box of the belief's cells changed since the last call (or since tracking began);
    /// `None` when none changed or nothing is tracked.
    pub fn take_changes(&mut self) -> Option<CellBox> {
        self.team.tracker.as_mut().and_then(ChangeTracker::take)
    }

    /// The current frontier cells (unordered).
    pub fn frontiers(&self) -> &[u32] {
        self.team.upkeep.frontiers.cells()
    }

    /// The box of every cell whose frontier status can have changed while the belief changed
    /// only within `changed` (a box from [`take_changes`](Self::take_changes)): `changed`
    /// grown by the frontier test's reach ([`FrontierUpkeep::reach`]), within the map.
    pub fn frontier_box(&self, changed: CellBox) -> CellBox {
        let g = self.team.upkeep.reach() as u32;
        let known = self.known();
        let (w, h) = (known.width() as u32, known.height() as u32);
        CellBox {
            x0: changed.x0.saturating_sub(g),
            y0: changed.y0.saturating_sub(g),
            x1: changed.x1.saturating_add(g).min(w.saturating_sub(1)),
            y1: changed.y1.saturating_add(g).min(h.saturating_sub(1)),
        }
    }

    /// Cells `from..from + out.len()` as bytes, 1 for a frontier cell and 0 otherwise (a row
    /// of a frontier layer).
    ///
    /// # Panics
    /// If the cells run past the map.
    pub fn frontier_bytes(&self, from: usize, out: &mut [u8]) {
        self.team.upkeep.frontiers.bytes_into(from, out);
    }

    /// Robot `r`'s cell index and heading (radians, x right, y down).
    pub fn pose(&self, r: usize) -> (u32, f64) {
        (self.robots[r].cell, self.robots[r].heading)
    }

    /// Robot `r`'s current goal.
    pub fn goal(&self, r: usize) -> Option<u32> {
        self.robots[r].goal
    }

    /// Metres robot `r` has travelled.
    pub fn path_length_m(&self, r: usize) -> f64 {
        self.robots[r].dist_cells * self.team.truth.resolution
    }

    /// Metres the whole team has travelled.
    pub fn total_path_length_m(&self) -> f64 {
        self.team.total_dist_cells * self.team.truth.resolution
    }

    /// Share of the reachable free cells known free.
    pub fn coverage(&self) -> f64 {
        self.team.coverage()
    }

    /// Reachable free cells known free so far.
    pub fn covered_cells(&self) -> usize {
        self.team.covered
    }

    /// Free cells of the ground truth reachable from the first start.
    pub fn reachable_cells(&self) -> usize {
        self.team.reachable_cells
    }

    /// Decisions made so far (one per deciding robot).
    pub fn decisions(&self) -> u64 {
        self.team.decisions
    }

    /// Cell moves of the whole team so far.
    pub fn moves(&self) -> u64 {
        self.team.moves
    }

    /// The ground truth explored.
    pub fn truth(&self) -> &GridMap {
        &self.team.truth
    }

    /// The run's configuration.
    pub fn config(&self) -> &RunConfig {
        &self.team.cfg
    }

    /// Scan through `sight`, the line of sight of this run's ground truth remembered per
    /// cell and shared with other runs of it: the same scans, made once for all of them.
    /// Taken only if the run senses with the line-of-sight sensor of the cache's range on
    /// the very ground truth the cache was made for; returns whether it was.
    pub fn share_sight(&mut self, sight: std::sync::Arc<sense::SightCache>) -> bool {
        let team = &mut self.team;
        let los = matches!(team.cfg.sensor, SensorSpec::Los { .. });
        let serves = los && sight.serves(&team.truth.cells, team.sensor.range_cells());
        if serves {
            team.sight = Some(sight);
        }
        serves
    }

    /// The result of the run so far (a run stopped before its end reports the step limit).
    pub fn finish(self) -> RunResult {
        let Session {
            mut team,
            robots,
            starts,
            started,
            reason,
        } = self;
        let reason = reason.unwrap_or(EndReason::StepLimit);
        let res = team.truth.resolution;
        let cells = &team.truth.cells;
        let frontiers_left: Vec<u32> = {
            // Frontier cells still open: not on the visited or inaccessible lists (a visited
            // goal that is still a frontier borders cells no position can see, such as a
            // wall cell behind a corner squeeze).
            let mut f: Vec<u32> = team
                .upkeep
                .frontiers
                .cells()
                .iter()
                .copied()
                .filter(|&c| !team.lists.is_excluded(c))
                .collect();
            f.sort_unstable();
            f
        };
        let ends = robots.iter().map(|r| cells.cell(r.cell as usize)).collect();
        team.final_audit();
        team.times.total_s = started.elapsed().as_secs_f64();
        let speed = team.cfg.speed;
        let grid_path_length_m: Vec<f64> = robots.iter().map(|r| r.dist_cells * res).collect();
        let path_length_m: Vec<f64> = match team.cfg.motion {
            Motion::Grid => grid_path_length_m.clone(),
            Motion::AnyAngle => {
                let known = team.belief.known();
                let w = known.width();
                let mut stood = vec![false; known.len()];
                for r in &robots {
                    for &c in &r.trail {
                        stood[c as usize] = true;
                    }
                }
                let passable = |i: usize| stood[i] || team.upkeep.trav.is_traversable(known, i);
                let along: Vec<Vec<f64>> = robots
                    .iter()
                    .map(|r| any_angle_prefix_lengths(w, &r.trail, &r.legs, passable))
                    .collect();
                let grid: Vec<Vec<f64>> = robots
                    .iter()
                    .map(|r| grid_prefix_lengths(w, &r.trail))
                    .collect();
                team.measure_along(&along, &grid);
                along
                    .iter()
                    .map(|a| a.last().copied().unwrap_or(0.0) * res)
                    .collect()
            }
        };
        // Each robot's clock when it stopped, as the milestones and the trace read it: its
        // travel (along the routes it is measured on) and its stops after bumps and waits
        // for the others.
        let time_s = path_length_m
            .iter()
            .zip(&robots)
            .map(|(&d, r)| d / speed + r.stopped_s)
            .fold(0.0, f64::max);
        let idle_s = path_length_m.iter().map(|&d| time_s - d / speed).collect();
        let overlap = if team.sensed_cells == 0 {
            0.0
        } else {
            team.overlap_cells as f64 / team.sensed_cells as f64
        };
        RunResult {
            reason,
            coverage: team.coverage(),
            reachable_cells: team.reachable_cells,
            path_length_m,
            grid_path_length_m,
            motion: team.cfg.motion,
            time_s,
            decisions: team.decisions,
            moves: team.moves,
            scans: team.scans,
            gave_up: team.gave_up,
            clearance_cells: grid::units::cells(team.cfg.clearance_m, res),
            starts,
            ends,
            coverage_curve: team.curve.iter().map(|&(d, c)| (d * res, c)).collect(),
            milestones: team.milestones,
            overlap,
            idle_s,
            times: team.times,
            belief: team.belief.known().clone(),
            frontiers_left,
            audit: team.audit,
            clutter: team.cfg.clutter.clone(),
            trace: team.trace,
        }
    }
}

/// Refuse a clutter layer that is not of `truth`'s size.
fn check_clutter(truth: &GridMap, cfg: &RunConfig) -> Result<(), SimError> {
    let (w, h) = (truth.cells.width(), truth.cells.height());
    match &cfg.clutter {
        Some(c) if (c.width(), c.height()) != (w, h) => Err(SimError::BadParameter {
            field: "clutter",
            expected: "a layer of the map's size",
            found: format!("{}x{} for a {w}x{h} map", c.width(), c.height()),
        }),
        _ => Ok(()),
    }
}

/// Where the robot's body may stand in `body` (the plane's cells less the clutter): free
/// and keeping the clearance.
fn body_traversable(body: &Grid<Occ>, truth: &GridMap, cfg: &RunConfig) -> Vec<bool> {
    truth::traversable(body, grid::units::cells(cfg.clearance_m, truth.resolution))
}

/// Refuse starts given that are not one per robot, or where a robot cannot stand.
fn check_given_starts(body: &Grid<Occ>, trav: &[bool], cfg: &RunConfig) -> Result<(), SimError> {
    if cfg.starts.len() != cfg.robots {
        return Err(SimError::BadParameter {
            field: "--start",
            expected: "one start cell per robot (or one, for the whole team)",
            found: format!("{} starts for {} robots", cfg.starts.len(), cfg.robots),
        });
    }
    for &s in &cfg.starts {
        truth::check_start(body, trav, s)?;
    }
    Ok(())
}

/// The sensor, its 360° sweep and (for the sonar kinds) the ring, built for cells of `res`
/// metres, with the checks of the range against the candidates and the clearance.
#[allow(clippy::type_complexity)]
fn build_sensing(
    cfg: &RunConfig,
    res: f64,
) -> Result<(Box<dyn Sensor>, Box<dyn Sensor>, Option<SonarSensor>), SimError> {
    let sensor = cfg.sensor.build(res)?;
    check_sensor_range(cfg.strategy.candidates, &cfg.sensor, res)?;
    check_range_beyond_clearance(&cfg.sensor, cfg.clearance_m, res)?;
    let sweep = cfg.sensor.sweep().build(res)?;
    let sonar = cfg.sensor.sonar(res).transpose()?;
    Ok((sensor, sweep, sonar))
}

/// Whether a run of `truth` as `cfg` says would start: every check [`Session::start`] makes
/// before it runs (parameters, clutter, sensor for the map's cells, starts given), without
/// running it, so that a batch can refuse a bad run before any other starts. `sensing`
/// false leaves the sensor's checks out (a batch makes them once per sensor and
/// resolution).
pub fn check_run(truth: &GridMap, cfg: &RunConfig, sensing: bool) -> Result<(), SimError> {
    check_config(cfg)?;
    check_clutter(truth, cfg)?;
    if sensing {
        build_sensing(cfg, truth.resolution)?;
    }
    if !cfg.starts.is_empty() {
        let body = cfg
            .clutter
            .as_ref()
            .map(|c| truth::with_clutter(&truth.cells, c));
        let body = body.as_ref().unwrap_or(&truth.cells);
        check_given_starts(body, &body_traversable(body, truth, cfg), cfg)?;
    }
    Ok(())
}

/// The robot speeds accepted, in metres per second: a millimetre to a kilometre a second.
/// Times are path lengths over the speed, so a speed near 0 made them infinite.
pub const SPEED_RANGE: std::ops::RangeInclusive<f64> = 0.001..=1000.0;

/// Whether `candidates` can be found with `sensor` on cells of `resolution` metres: with a
/// range too short for the coverage candidates' cover there would be none, and the run
/// would end at once with "no reachable frontier".
pub fn check_sensor_range(
    candidates: CandidateKind,
    sensor: &SensorSpec,
    resolution: f64,
) -> Result<(), SimError> {
    let range = sensor.range_cells(resolution);
    if range < candidates.min_range_cells() {
        return Err(SimError::BadParameter {
            field: "--sensor",
            expected: "a range of at least 1.25 cells with coverage candidates (the `-cc` \
                       strategies cover from within 0.8 of the range)",
            found: format!("{sensor}, {range} cell(s) at {resolution} m per cell"),
        });
    }
    Ok(())
}

/// Whether `sensor` sees beyond the clearance on cells of `resolution` metres: with a range
/// of at most `clearance_m` a robot sees an obstacle only from where its clearance forbids
/// it to stand, and no search leads out of there, so the run would stop early with
/// frontiers left ("no reachable frontier").
pub fn check_range_beyond_clearance(
    sensor: &SensorSpec,
    clearance_m: f64,
    resolution: f64,
) -> Result<(), SimError> {
    let range = sensor.range_cells(resolution);
    let clearance = grid::units::cells(clearance_m, resolution);
    if clearance > 0.0 && range <= clearance {
        return Err(SimError::BadParameter {
            field: "--sensor",
            expected: "a range beyond the clearance (a robot would see obstacles only from \
                       within its clearance, where no path leads out)",
            found: format!(
                "{sensor}: {} m, with a clearance of {} m",
                grid::Num(range * resolution),
                grid::Num(clearance_m)
            ),
        });
    }
    Ok(())
}

/// Whether `cfg`'s parameters are in range (robots, speed, clearance, goal, belief for the
/// sensor, …), as a run checks them when it starts: a front end asks before it makes
/// output folders or loads more.
pub fn check_config(cfg: &RunConfig) -> Result<(), SimError> {
    let bad = |field, expected, found: String| {
        Err(SimError::BadParameter {
            field,
            expected,
            found,
        })
    };
    if cfg.robots == 0 {
        return bad("--robots", "at least 1", cfg.robots.to_string());
    }
    if cfg.sensor.sonar_mode().is_some() && cfg.belief != sense::BeliefKind::Evidence {
        return bad(
            "--belief",
            "evidence with a sonar sensor",
            cfg.belief.to_string(),
        );
    }
    if !SPEED_RANGE.contains(&cfg.speed) {
        return bad(
            "--speed",
            "a positive number of metres per second, from 0.001 to 1000",
            grid::Num(cfg.speed).to_string(),
        );
    }
    if !(cfg.clearance_m.is_finite() && cfg.clearance_m >= 0.0) {
        return bad(
            "--clearance",
            "a non-negative number of metres",
            grid::Num(cfg.clearance_m).to_string(),
        );
    }
    if let Some(g) = cfg.coverage_goal
        && !(g > 0.0 && g <= 1.0)
    {
        return bad(
            "--goal",
            "a coverage share in (0, 1]",
            grid::Num(g).to_string(),
        );
    }
    Ok(())
}

impl Team<'_> {
    /// The nearest assigner's goals among the offered candidates, read from the searches
    /// this pending decision already grew ([`Session::nearest_candidates`]) instead of a
    /// new search per robot: each deciding robot's search must start at its cell and be
    /// guided toward a superset of the offered cells (the decision's candidates), so every
    /// offered cell cheaper than its next bucket is settled; the least (cost, cell) among
    /// them is then the cell the nearest search would settle first, and its path the same.
    /// Returns false, when that fails for some deciding robot, with `proposed` partly
    /// written: the assigner then writes every deciding robot's entry again.
    fn nearest_from_searches(&mut self, robots: &[Robot]) -> bool {
        let m = robots.len().min(self.proposed.len());
        for r in (0..m).filter(|&r| self.deciding[r]) {
            let map = self.planner.map(r);
            if !self.planner.is_searching(r) || map.start() != Some(robots[r].cell as usize) {
                return false;
            }
            let best = self
                .offered
                .cells()
                .iter()
                .filter_map(|&c| map.cost(c as usize).map(|cost| (cost, c)))
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            self.proposed[r] = match best {
                Some((cost, cell)) if map.is_complete() || cost < map.next_bucket() as f64 => {
                    Some(Goal { cell, cost })
                }
                None if map.is_complete() || self.offered.is_empty() => None,
                _ => return false,
            };
        }
        true
    }

    fn coverage(&self) -> f64 {
        let (covered, total) = self.coverage_counts();
        if total == 0 {
            1.0
        } else {
            covered as f64 / total as f64
        }
    }

    /// Coverage's numerator and denominator for the configured kind.
    fn coverage_counts(&self) -> (usize, usize) {
        match self.cfg.coverage {
            CoverageKind::ReachableFree => (self.covered, self.reachable_cells),
            CoverageKind::Known => (self.known_covered, self.knowable_cells),
        }
    }

    /// Robot `r` senses from `cell` with its heading at its clock (see [`sense`](Self::sense));
    /// its count of cells entered unsensed starts again.
    fn look(&mut self, robots: &mut [Robot], r: usize, cell: Cell, sweep: bool) {
        let pose = Pose {
            cell,
            heading: robots[r].heading,
        };
        self.sense((r, robots[r].clock), pose, sweep);
        robots[r].unsensed = 0;
    }

    /// Sense from `pose` (with the 360° sweep if `sweep`), integrate, keep frontiers and
    /// coverage up to date.
    fn sense(&mut self, who: (usize, f64), pose: Pose, sweep: bool) {
        let t0 = Instant::now();
        self.now = who;
        self.scans += 1;
        self.changed.clear();
        if let Some(sonar) = &mut self.sonar {
            let plane = &self.truth.cells;
            sonar.fire(
                plane,
                self.cfg.clutter.as_ref(),
                pose,
                &mut self.sonar_rng,
                &mut self.readings,
            );
            self.laser_hits.clear();
            if self.cfg.sensor.sonar_mode() == Some(SonarMode::LaserLimited) {
                sonar.limit_by_laser(plane, pose.cell, &mut self.readings, &mut self.laser_hits);
            }
            let evidence = self
                .belief
                .evidence_mut()
                .expect("validated: sonar runs with the evidence belief");
            sonar.integrate(
                pose.cell,
                &self.readings,
                &self.laser_hits,
                evidence,
                &mut self.changed,
            );
        } else {
            let sensor = if sweep { &self.sweep } else { &self.sensor };
            let sight = self.sight.as_ref().filter(|_| !sweep);
            match (&mut self.unseen, sight) {
                (Some(u), Some(sight)) if self.skip_known => {
                    u.look_as(who.0);
                    sight.scan_unseen(pose, u, &mut self.obs);
                }
                (Some(u), None) if self.skip_known => {
                    u.look_as(who.0);
                    sensor.scan_unseen(&self.truth.cells, pose, u, &mut self.obs);
                }
                (_, Some(sight)) => sight.scan(pose, &mut self.obs),
                _ => sensor.scan(&self.truth.cells, pose, &mut self.obs),
            }
            self.belief.integrate(&self.obs, &mut self.changed);
        }
        if let Some(u) = &mut self.unseen {
            // What the scan sensed (for sonar, the cells it changed).
            let (first, overlap) = if self.sonar.is_some() {
                u.record(who.0, self.changed.iter().copied())
            } else {
                u.record(who.0, self.obs.cells.iter().map(|&(i, _)| i))
            };
            self.sensed_cells += first;
            self.overlap_cells += overlap;
        }
        self.times.sense_s += t0.elapsed().as_secs_f64();
        self.absorb_changes();
    }

    /// Bring frontiers, trace and coverage up to date with the cells in `changed`.
    fn absorb_changes(&mut self) {
        let t1 = Instant::now();
        let known = self.belief.known();
        self.upkeep.update(known, &self.changed);
        let t2 = Instant::now();
        if let Some(t) = self.tracker.as_mut() {
            t.record(&self.changed);
        }
        if let Some(t) = self.trace.as_mut() {
            t.changes
                .extend(self.changed.iter().map(|&c| (c, known[c as usize])));
        }
        let before = self.coverage_counts().0;
        for &c in &self.changed {
            let c = c as usize;
            if self.knowable.get(c) == Some(&true) {
                let known_now = known[c] != Occ::Unknown;
                if known_now != self.known_counted[c] {
                    self.known_counted[c] = known_now;
                    if known_now {
                        self.known_covered += 1
                    } else {
                        self.known_covered -= 1
                    }
                }
            }
            if self.reachable[c] {
                let free = known[c] == Occ::Free;
                if free != self.counted[c] {
                    self.counted[c] = free;
                    if free {
                        self.covered += 1
                    } else {
                        self.covered -= 1
                    }
                }
            }
        }
        let (covered, total) = self.coverage_counts();
        if covered != before {
            let cov = self.coverage();
            self.curve.push((self.total_dist_cells, cov));
            let any_angle = self.cfg.motion == Motion::AnyAngle;
            if any_angle {
                self.curve_moves.push(self.move_log.len());
            }
            while let Some(&percent) = MILESTONES.get(self.milestones.len())
                && covered as u128 * 100 >= u128::from(percent) * total as u128
            {
                // Moves are taken in the order robots set out, so a later one can end
                // earlier: a level is reached no earlier than the one below it.
                let below = self.milestones.last().map_or(0.0, |m| m.time_s);
                self.milestones.push(Milestone {
                    percent,
                    dist_m: self.total_dist_cells * self.truth.resolution,
                    time_s: self.now.1.max(below),
                });
                if any_angle {
                    self.milestone_moves.push((self.move_log.len(), self.now.0));
                }
            }
        }
        self.times.upkeep_s += (t2 - t1).as_secs_f64();
    }

    /// Under imperfect sensing, pin a cell the robot's body stands on free in the belief:
    /// the body was there, so no sonar arc may close the way back (sensing has run).
    fn pin_free(&mut self, cell: u32) {
        if self.imperfect && !self.belief.is_pinned(cell as usize) {
            self.changed.clear();
            self.belief.pin(cell as usize, Occ::Free, &mut self.changed);
            if !self.changed.is_empty() {
                self.absorb_changes();
            }
        }
    }

    /// The ground truth where the robot's body can be: the plane, less any clutter.
    fn body(&self) -> &Grid<Occ> {
        self.body.as_ref().unwrap_or(&self.truth.cells)
    }

    /// Whether cell `i` is free in the ground truth (where the robot's body can be).
    fn truly_free(&self, i: usize) -> bool {
        self.body()[i] == Occ::Free
    }

    /// Fill the map-accuracy part of the audit from the final belief.
    fn final_audit(&mut self) {
        let known = self.belief.known();
        let plane = &self.truth.cells;
        let body = self.body();
        let (mut building, mut right, mut false_free, mut clutter, mut mapped) = (0, 0, 0, 0, 0);
        for i in 0..plane.len() {
            let truth = body[i];
            if known[i] == Occ::Free && truth != Occ::Free {
                false_free += 1;
            }
            if plane[i] == Occ::Free && truth == Occ::Occupied {
                clutter += 1;
                mapped += usize::from(known[i] == Occ::Occupied);
            }
            if truth != Occ::Unknown {
                building += 1;
                right += usize::from(known[i] == truth);
            }
        }
        self.audit.accuracy = if building == 0 {
            1.0
        } else {
            right as f64 / building as f64
        };
        self.audit.false_free_cells = false_free;
        self.audit.clutter_cells = clutter;
        self.audit.clutter_mapped = mapped;
    }

    /// Count the frontier regions with a cell that is not free in the ground truth.
    fn count_phantoms(&mut self) {
        let mut regions = std::mem::take(&mut self.regions_buf);
        self.upkeep
            .regions(self.truth.cells.width(), 1, &mut regions);
        let phantoms = regions
            .iter()
            .filter(|g| g.cells.iter().any(|&c| !self.truly_free(c as usize)))
            .count() as u64;
        self.audit.frontier_regions += regions.len() as u64;
        self.regions_buf = regions;
        self.audit.phantom_regions += phantoms;
        self.audit.phantom_regions_max = self.audit.phantom_regions_max.max(phantoms);
    }

    /// Robot `r`'s body met obstacles in `blocked` (its next cell, or the two cells beside a
    /// diagonal step, which its belief showed passable):
    /// it stops for [`BUMP_S`], senses again, pins those cells occupied and re-plans; a goal
    /// not approached for the no-progress limit goes on the inaccessible list.
    fn bump(&mut self, robots: &mut [Robot], r: usize, blocked: &[u32]) {
        robots[r].clock += BUMP_S;
        robots[r].stopped_s += BUMP_S;
        let cell = self.truth.cells.cell(robots[r].cell as usize);
        self.look(robots, r, cell, false);
        self.changed.clear();
        for &i in blocked {
            self.belief
                .pin(i as usize, Occ::Occupied, &mut self.changed);
        }
        self.absorb_changes();
        self.record(robots, r);
        self.give_up_if_stuck(robots, r);
        self.decide(robots, &[r]);
    }

    /// Under imperfect sensing robot `r` may come to stand within its clearance of an
    /// obstacle (one its body met, or one its evidence grid believed only once it was near),
    /// or in a pocket of cells that keep it, cut off by such obstacles. A search leaves a
    /// cell only through neighbours that keep the clearance, so there the run would end with
    /// frontiers left. Before it decides, a robot whose search cannot get farther than
    /// `reach` cells (twice the clearance and three cells) backs away along the cheapest
    /// way over cells its belief shows free to the nearest cell that keeps the clearance and
    /// from which a search gets that far. A cell its body meets on the way is pinned
    /// occupied and ends the retreat there; what it senses on the way may pen it in again,
    /// so it tries again, [`BACK_OFF_TRIES`] times in all.
    fn back_off(&mut self, robots: &mut [Robot], r: usize) {
        let reach = 2.0 * grid::units::cells(self.cfg.clearance_m, self.truth.resolution) + 3.0;
        for _ in 0..BACK_OFF_TRIES {
            let known = self.belief.known();
            let here = robots[r].cell as usize;
            let origin = known.cell(here);
            let trav = |i: usize| self.upkeep.is_traversable(known, i);
            let mut pocket = std::mem::take(&mut self.pocket);
            if !pocket.confined(known, &trav, here, origin, reach) {
                self.pocket = pocket;
                return;
            }
            let route = retreat(known, here, reach, |i| {
                trav(i) && !pocket.confined(known, &trav, i, origin, reach)
            });
            self.pocket = pocket;
            if route.is_empty() {
                return;
            }
            for next in route {
                if self.body()[next as usize] != Occ::Free {
                    self.changed.clear();
                    self.belief
                        .pin(next as usize, Occ::Occupied, &mut self.changed);
                    self.absorb_changes();
                    break;
                }
                self.travel(robots, r, next);
                if self.cfg.sensing_mode() == SensingMode::Continuous {
                    let cell = self.truth.cells.cell(next as usize);
                    self.look(robots, r, cell, false);
                }
                self.pin_free(next);
                self.record(robots, r);
            }
        }
    }

    /// Robot `r` moves to the neighbouring cell `next`: its heading, distance, clock and
    /// (any-angle motion) trail, and the run's move count and distance.
    fn travel(&mut self, robots: &mut [Robot], r: usize, next: u32) {
        let cells = &self.truth.cells;
        let (a, b) = (
            cells.cell(robots[r].cell as usize),
            cells.cell(next as usize),
        );
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let len = step_cost(dx, dy);
        let robot = &mut robots[r];
        robot.cell = next;
        robot.heading = f64::from(dy).atan2(f64::from(dx));
        robot.dist_cells += len;
        if self.cfg.motion == Motion::AnyAngle {
            robot.trail.push(next);
            self.move_log.push(r as u32);
        }
        robot.clock += len * self.truth.resolution / self.cfg.speed;
        robot.unsensed = robot.unsensed.saturating_add(1);
        self.moves += 1;
        self.total_dist_cells += len;
    }

    /// Yamauchi's no-progress rule: if robot `r`'s goal has not come closer for the limit,
    /// put it on the inaccessible list and drop it (the caller decides again). A robot that
    /// senses on arrival then sweeps where it stands (§2.3: it "will then conduct a sensor
    /// sweep, update the evidence grid, and attempt to navigate to the closest remaining
    /// accessible, unvisited frontier"). Returns whether it gave up.
    fn give_up_if_stuck(&mut self, robots: &mut [Robot], r: usize) -> bool {
        let (Some(goal), Some(limit)) = (robots[r].goal, self.no_progress_s) else {
            return false;
        };
        if robots[r].clock - robots[r].progress_clock <= limit {
            return false;
        }
        self.lists.mark_inaccessible(goal);
        robots[r].goal = None;
        self.gave_up += 1;
        if self.cfg.sensing_mode() == SensingMode::OnArrival {
            let cell = self.truth.cells.cell(robots[r].cell as usize);
            self.look(robots, r, cell, true);
            self.record(robots, r);
        }
        true
    }

    /// With any-angle motion: the coverage curve's distances and the milestones' distances
    /// and times measured along the robots' string-pulled routes (`along[r][k]`: robot r's
    /// distance in cells when it stood on its k-th trail cell; `grid[r][k]`: the same on
    /// the grid), as its lengths are; each milestone's time is its robot's clock less the
    /// time the any-angle route saves it by then.
    fn measure_along(&mut self, along: &[Vec<f64>], grid: &[Vec<f64>]) {
        let res = self.truth.resolution;
        let log = &self.move_log;
        // Each robot's trail position once the first `moves` moves were made, in order.
        let positions = |marks: &mut dyn Iterator<Item = usize>, f: &mut dyn FnMut(&[usize])| {
            let (mut at, mut done) = (vec![0usize; along.len()], 0);
            for moves in marks {
                for &r in &log[done..moves] {
                    at[r as usize] += 1;
                }
                done = moves;
                f(&at);
            }
        };
        // The trace's events (pictures, the HTML replay) along the routes too: an event
        // follows each move, so a robot's events step along its trail as its cell changes.
        if let Some(trace) = self.trace.as_mut() {
            // (position on the trail, its cell), from each robot's start
            let mut at: Vec<(usize, u32)> = trace.starts.iter().map(|&c| (0, c)).collect();
            for e in &mut trace.events {
                let r = e.robot as usize;
                let Some(&(k, cell)) = at.get(r) else {
                    continue;
                };
                let k = if cell != e.cell { k + 1 } else { k };
                at[r] = (k, e.cell);
                if let (Some(a), Some(g)) = (along[r].get(k), grid[r].get(k)) {
                    e.dist_m = a * res;
                    e.t -= (g - a) * res / self.cfg.speed;
                }
            }
        }
        let sum = |at: &[usize]| -> f64 { along.iter().zip(at).map(|(a, &k)| a[k]).sum() };
        let mut curve = self.curve_moves.iter().copied();
        let mut k = 0;
        positions(&mut curve, &mut |at| {
            self.curve[k].0 = sum(at);
            k += 1;
        });
        let mut marks = self.milestone_moves.iter().map(|&(moves, _)| moves);
        let mut k = 0;
        let speed = self.cfg.speed;
        let mut below = 0.0f64;
        positions(&mut marks, &mut |at| {
            let r = self.milestone_moves[k].1;
            let m = &mut self.milestones[k];
            m.dist_m = sum(at) * res;
            m.time_s -= (grid[r][at[r]] - along[r][at[r]]) * res / speed;
            // as on the grid: no level earlier than the one below it
            m.time_s = m.time_s.max(below);
            below = m.time_s;
            k += 1;
        });
    }

    /// Close the trace's current event: robot `r` is where it is, with the changes sensed
    /// since the last event.
    fn record(&mut self, robots: &[Robot], r: usize) {
        let coverage = self.coverage();
        let frontiers = self.upkeep.frontiers.len() as u32;
        if let Some(t) = self.trace.as_mut() {
            t.events.push(TraceEvent {
                t: robots[r].clock,
                robot: r as u32,
                cell: robots[r].cell,
                dist_m: robots[r].dist_cells * self.truth.resolution,
                coverage,
                frontiers,
            });
            t.change_ends.push(t.changes.len() as u32);
        }
    }

    /// Whether `cell` is a frontier that still needs a visit.
    fn is_open_frontier(&self, cell: u32) -> bool {
        self.upkeep.frontiers.contains(cell as usize)
    }

    /// Whether some robot can still reach one of the last decision's candidates: one
    /// heading for a goal that still is one can; else each robot's free component is
    /// searched (a flood fill, made only when a deciding robot found no goal).
    fn any_candidate_reachable(&mut self, robots: &[Robot]) -> bool {
        let candidates = &self.offer.candidates;
        if candidates.is_empty() {
            return false;
        }
        let heading_for_one = robots.iter().any(|r| {
            !r.idle
                && r.goal
                    .is_some_and(|g| candidates.index_of(g as usize).is_some())
        });
        if heading_for_one {
            return true;
        }
        let known = self.belief.known();
        for (r, robot) in robots.iter().enumerate() {
            let reach = self.planner.component(r, robot.cell, known, &self.upkeep);
            if candidates
                .cells()
                .iter()
                .any(|&c| reach.contains(c as usize))
            {
                return true;
            }
        }
        false
    }

    /// Decide goals for the robots in `who` (plus any idle robot, which retries).
    // Robot r's state is spread over several parallel buffers, so index loops read best.
    #[allow(clippy::needless_range_loop)]
    fn decide(&mut self, robots: &mut [Robot], who: &[usize]) {
        if matches!(self.cfg.sensing_mode(), SensingMode::Every(_)) {
            // Sensing every n-th cell: a robot looks before it decides where it stands.
            for &r in who {
                if robots[r].unsensed > 0 {
                    let cell = self.truth.cells.cell(robots[r].cell as usize);
                    self.look(robots, r, cell, false);
                    self.record(robots, r);
                }
            }
        }
        if self.imperfect && self.cfg.clearance_m > 0.0 {
            // After what it has just seen.
            for &r in who {
                self.back_off(robots, r);
            }
        }
        let t0 = Instant::now();
        let m = robots.len();
        self.deciding.fill(false);
        for &r in who {
            self.deciding[r] = true;
        }
        for r in 0..m {
            if robots[r].idle {
                self.deciding[r] = true;
            }
            self.cells_buf[r] = robots[r].cell;
            self.goals_buf[r] = if self.deciding[r] {
                None
            } else {
                robots[r].goal
            };
            self.out[r] = None;
        }
        self.planner.invalidate();
        {
            let mut ctx = DecisionCtx {
                known: self.belief.known(),
                upkeep: &mut self.upkeep,
                planner: &mut self.planner,
                robots: &self.cells_buf,
                deciding: &self.deciding,
                goals: &self.goals_buf,
                lists: &self.lists,
                resolution: self.truth.resolution,
                sensor_range_cells: self.range_cells,
                rng: &mut self.rng,
                belief: self.belief.as_ref(),
                sensor: self.sensor.as_ref(),
                memory: &mut self.memory,
            };
            let strategy = &self.cfg.strategy;
            let assigner = (!self.external).then_some(strategy.assigner);
            decision::decide(
                &mut ctx,
                strategy.candidates,
                assigner,
                0.0,
                &mut self.offer,
                &mut self.out,
            );
        }
        if self.external {
            // The caller chooses (`Session::choose`), then `conclude` carries on.
            self.pending = true;
            self.times.decide_s += t0.elapsed().as_secs_f64();
            return;
        }
        self.conclude(robots, t0);
    }

    /// The rest of a decision once goals are in `out`: trace, paths, progress bookkeeping,
    /// idle robots' clocks, and arrival at goals under the robots' feet.
    #[allow(clippy::needless_range_loop)]
    fn conclude(&mut self, robots: &mut [Robot], t0: Instant) {
        let m = robots.len();
        if let Some(t) = self.trace.as_mut()
            && self.cfg.strategy.candidates != CandidateKind::AllFrontiers
        {
            t.candidates.push((
                t.events.len() as u32,
                self.offer.candidates.cells().to_vec(),
            ));
        }
        let seg = &self.memory.segments;
        if let Some(t) = self.trace.as_mut()
            && seg.full_runs() + seg.patches() > 0
        {
            t.record_segments(
                t.events.len() as u32,
                seg.full_runs(),
                seg.patches(),
                &seg.segmentation().labels,
            );
        }
        if self.imperfect {
            self.count_phantoms();
        }
        for r in 0..m {
            if !self.deciding[r] {
                continue;
            }
            self.decisions += 1;
            if self.imperfect
                && let Some(goal) = self.out[r]
                && !self.truly_free(goal.cell as usize)
            {
                self.audit.phantom_goals += 1;
            }
            let robot = &mut robots[r];
            robot.moves_since_decision = 0;
            robot.path.clear();
            robot.path_pos = 0;
            if self.cfg.motion == Motion::AnyAngle {
                let here = robot.trail.len() - 1;
                if robot.legs.last() != Some(&here) {
                    robot.legs.push(here);
                }
            }
            match self.out[r] {
                Some(goal) if self.planner.path(r, goal.cell, &mut self.path_buf) => {
                    robot.goal = Some(goal.cell);
                    robot.goal_was_frontier = self.upkeep.frontiers.contains(goal.cell as usize);
                    robot.idle = false;
                    robot.path.extend_from_slice(&self.path_buf[1..]);
                    robot.remaining = goal.cost;
                    if let (Some(_), AssignerKind::DtUtility { lambda }) = (
                        self.cfg.strategy.replan.utility_drop,
                        self.cfg.strategy.assigner,
                    ) {
                        robot.heading0 = utility::chosen_heading(&self.memory.dt, goal.cell)
                            .unwrap_or(robot.heading);
                        let pose = Pose {
                            cell: self.truth.cells.cell(goal.cell as usize),
                            heading: robot.heading0,
                        };
                        robot.utility0 = utility::target_utility(
                            &mut self.memory.dt,
                            self.belief.as_ref(),
                            self.sensor.as_ref(),
                            pose,
                            goal.cost,
                            self.truth.resolution,
                            lambda,
                        );
                    }
                    if robot.progress_goal == Some(goal.cell) {
                        robot.best_remaining = robot.best_remaining.min(goal.cost);
                    } else {
                        robot.best_remaining = goal.cost;
                        robot.progress_clock = robot.clock;
                        robot.progress_goal = Some(goal.cell);
                    }
                }
                _ => {
                    robot.goal = None;
                    robot.idle = true;
                }
            }
            if let (Some(t), AssignerKind::DtUtility { lambda }) =
                (self.trace.as_mut(), self.cfg.strategy.assigner)
            {
                let dt = &mut self.memory.dt;
                let reach = self.planner.map(r);
                let mut samples = Vec::with_capacity(dt.cells.len());
                for k in 0..dt.cells.len() {
                    let by = self.planner.map(dt.reachers[k] as usize);
                    let gain = dt.gain(k, self.sensor.as_ref(), self.belief.as_ref(), by);
                    let cost_m = reach
                        .cost(dt.cells[k] as usize)
                        .map_or(f64::INFINITY, |c| c * self.truth.resolution);
                    samples.push(DtSample {
                        cell: dt.cells[k],
                        gain,
                        cost_m,
                        utility: gain * (-lambda * cost_m).exp(),
                    });
                }
                t.dt.push(DtDecision {
                    event: t.events.len() as u32,
                    robot: r as u32,
                    fell_back: dt.fell_back,
                    samples,
                    chosen: robot.goal,
                });
            }
            if let Some(t) = self.trace.as_mut() {
                t.goals.push(TraceGoal {
                    event: t.events.len() as u32,
                    robot: r as u32,
                    goal: robot.goal,
                });
            }
        }
        // A team whose deciding robot found no goal may be done: both multi-robot papers end
        // when no frontier is left, not when the last robot reaches a goal that was
        // explored on its way (a single robot that finds none is done anyway).
        if m > 1 && (0..m).any(|r| self.deciding[r] && robots[r].idle) {
            self.exhausted = !self.any_candidate_reachable(robots);
        }
        // An idle robot waits for the others: its clock follows the earliest active one.
        if let Some(t) = robots
            .iter()
            .filter(|r| !r.idle)
            .map(|r| r.clock)
            .min_by(f64::total_cmp)
        {
            for robot in robots.iter_mut().filter(|r| r.idle) {
                if t > robot.clock {
                    robot.stopped_s += t - robot.clock;
                    robot.clock = t;
                }
            }
        }
        self.times.decide_s += t0.elapsed().as_secs_f64();
        // A goal under the robot's feet is reached at once (a nested decision may follow,
        // so collect first).
        let mut arriving = std::mem::take(&mut self.arrive_buf);
        arriving.clear();
        arriving.extend((0..m).filter(|&r| {
            self.deciding[r] && robots[r].goal.is_some() && robots[r].path.is_empty()
        }));
        for &r in &arriving {
            if robots[r].goal.is_some() && robots[r].path_pos >= robots[r].path.len() {
                self.arrive(robots, r);
            }
        }
        self.arrive_buf = arriving;
    }

    /// Robot `r` stands on its goal: sweep if sensing on arrival, face any unknown
    /// neighbour the sensor could not see, put the goal on the visited list, decide again.
    fn arrive(&mut self, robots: &mut [Robot], r: usize) {
        let goal = robots[r].goal.expect("arriving robot has a goal");
        let cell = self.truth.cells.cell(goal as usize);
        if self.cfg.sensing_mode() == SensingMode::OnArrival {
            self.look(robots, r, cell, true);
            self.record(robots, r);
        } else if self.is_open_frontier(goal) && !self.sensor.is_omnidirectional() {
            // Turn towards the unknown it is next to and look again: first towards all of
            // it at once (the mean direction), then, while some neighbour is still unknown
            // (the mean fell between unknown cells on opposite sides, or a narrow field of
            // view missed some), towards each such neighbour in turn, each at most once.
            let known = self.belief.known();
            let (mut sx, mut sy) = (0.0, 0.0);
            for n in known.neighbours8(goal as usize) {
                if known[n] == Occ::Unknown {
                    let c = known.cell(n);
                    sx += f64::from(c.x - cell.x);
                    sy += f64::from(c.y - cell.y);
                }
            }
            robots[r].heading = sy.atan2(sx);
            self.look(robots, r, cell, false);
            self.record(robots, r);
            // The neighbours faced, by their place in `neighbours8`'s order.
            let mut faced = 0u8;
            while self.is_open_frontier(goal) {
                let known = self.belief.known();
                let Some((k, n)) = known
                    .neighbours8(goal as usize)
                    .enumerate()
                    .find(|&(k, n)| known[n] == Occ::Unknown && faced & (1 << k) == 0)
                else {
                    break;
                };
                faced |= 1 << k;
                let c = known.cell(n);
                robots[r].heading = f64::from(c.y - cell.y).atan2(f64::from(c.x - cell.x));
                self.look(robots, r, cell, false);
                self.record(robots, r);
            }
        }
        self.lists.mark_visited(goal);
        robots[r].goal = None;
        self.decide(robots, &[r]);
    }

    /// Robot `r` makes one cell move along its path, senses, and applies the re-plan policy.
    fn step(&mut self, robots: &mut [Robot], r: usize) {
        let Some(&next) = robots[r].path.get(robots[r].path_pos) else {
            self.decide(robots, &[r]);
            return;
        };
        // Never enter a cell the belief does not show traversable: re-plan instead.
        if !self
            .upkeep
            .is_traversable(self.belief.known(), next as usize)
        {
            self.decide(robots, &[r]);
            return;
        }
        // The body meets what the map does not show: the next cell, or both cells beside a
        // diagonal step (a corner it cannot squeeze through).
        let body = self.body();
        if body[next as usize] != Occ::Free {
            self.bump(robots, r, &[next]);
            return;
        }
        let (a, b) = (body.cell(robots[r].cell as usize), body.cell(next as usize));
        // A free cell beside a diagonal step: the body passed it (pinned free below).
        let mut passed_beside = None;
        if a.x != b.x && a.y != b.y {
            let beside = [
                body.index(Cell::new(b.x, a.y)) as u32,
                body.index(Cell::new(a.x, b.y)) as u32,
            ];
            passed_beside = beside.into_iter().find(|&i| body[i as usize] == Occ::Free);
            if passed_beside.is_none() {
                self.bump(robots, r, &beside);
                return;
            }
        }
        if !self.reachable[next as usize] && self.cfg.sensing_mode() != SensingMode::Continuous {
            // Free, but within the clearance of an obstacle the map does not show yet: a
            // robot that senses only now and then would drive on and stand where its
            // clearance forbids, and no search could lead it out. Its reactive obstacle
            // avoidance (Yamauchi §2.3) stops it first: it looks around where it stands
            // and re-plans if what it sees keeps it out of the next cell.
            self.look(robots, r, a, true);
            self.record(robots, r);
            if !self
                .upkeep
                .is_traversable(self.belief.known(), next as usize)
            {
                self.decide(robots, &[r]);
                return;
            }
        }
        self.travel(robots, r, next);
        {
            let robot = &mut robots[r];
            robot.remaining -= step_cost(b.x - a.x, b.y - a.y);
            robot.path_pos += 1;
            robot.moves_since_decision += 1;
        }
        let scan = match self.cfg.sensing_mode() {
            SensingMode::Continuous => true,
            SensingMode::OnArrival => false,
            SensingMode::Every(n) => robots[r].unsensed >= n || Some(next) == robots[r].goal,
        };
        if scan {
            self.look(robots, r, b, false);
        }
        self.pin_free(next);
        if let Some(i) = passed_beside {
            // So that the way back stays a legal (unsqueezed) path in the belief.
            self.pin_free(i);
        }
        self.record(robots, r);
        let goal = robots[r].goal.expect("a moving robot has a goal");
        let replan = self.cfg.strategy.replan;
        if next != goal && self.no_progress_s.is_some() {
            let robot = &mut robots[r];
            if robot.remaining < robot.best_remaining - 1e-9 {
                robot.best_remaining = robot.remaining;
                robot.progress_clock = robot.clock;
            } else if self.give_up_if_stuck(robots, r) {
                self.decide(robots, &[r]);
                return;
            }
        }
        if next == goal {
            self.arrive(robots, r);
        } else if replan.recheck && robots[r].goal_was_frontier && !self.is_open_frontier(goal) {
            // Repetitive re-checking (Holz): an O(1) look-up per move. A goal that was not
            // a frontier cell when chosen (other candidates than frontier cells, from
            // Python) is not a target the rule watches; otherwise it would decide again at
            // every move.
            self.decide(robots, &[r]);
        } else if let (Some(fraction), AssignerKind::DtUtility { lambda }) =
            (replan.utility_drop, self.cfg.strategy.assigner)
            && robots[r]
                .moves_since_decision
                .is_multiple_of(DT_RECHECK_MOVES)
            && {
                let pose = Pose {
                    cell: self.truth.cells.cell(goal as usize),
                    heading: robots[r].heading0,
                };
                let u = utility::target_utility(
                    &mut self.memory.dt,
                    self.belief.as_ref(),
                    self.sensor.as_ref(),
                    pose,
                    robots[r].remaining,
                    self.truth.resolution,
                    lambda,
                );
                u < fraction * robots[r].utility0
            }
        {
            // `dt-rr`: the target is no longer worth the trip.
            self.decide(robots, &[r]);
        } else if replan
            .every_moves
            .is_some_and(|s| robots[r].moves_since_decision >= s)
        {
            let all = std::mem::take(&mut self.all);
            self.decide(robots, &all);
            self.all = all;
        }
    }
}

/// The eight moves from a cell, as (dx, dy).
const STEPS: [(i32, i32); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Whether the step (dx, dy) from `c` squeezes between two cells `open` refuses (a diagonal
/// step with both straight neighbours refused), which neither the planner nor the body
/// takes.
fn squeezes(c: Cell, (dx, dy): (i32, i32), open: impl Fn(Cell) -> bool) -> bool {
    dx != 0 && dy != 0 && !open(Cell::new(c.x + dx, c.y)) && !open(Cell::new(c.x, c.y + dy))
}

/// A fill of the cells a search from one cell reaches near it, telling whether they stay
/// within a disk (a pocket) or get out of it; kept between fills, so that a fill allocates
/// nothing once warm.
#[derive(Default)]
struct Pocket {
    seen: std::collections::HashSet<u32>,
    stack: Vec<u32>,
}

impl Pocket {
    /// Whether a search from `from` (any cell) over the cells `trav` accepts, as the
    /// planner's (8 neighbours, none squeezing between two refused cells), reaches no cell
    /// farther than `reach` cells from `origin`.
    fn confined(
        &mut self,
        known: &Grid<Occ>,
        trav: &impl Fn(usize) -> bool,
        from: usize,
        origin: Cell,
        reach: f64,
    ) -> bool {
        self.seen.clear();
        self.stack.clear();
        self.seen.insert(from as u32);
        self.stack.push(from as u32);
        let passes = |c: Cell| known.contains(c) && trav(known.index(c));
        while let Some(i) = self.stack.pop() {
            let c = known.cell(i as usize);
            let (dx, dy) = (f64::from(c.x - origin.x), f64::from(c.y - origin.y));
            if dx * dx + dy * dy > reach * reach {
                return false;
            }
            for (ox, oy) in STEPS {
                let n = Cell::new(c.x + ox, c.y + oy);
                if passes(n)
                    && !squeezes(c, (ox, oy), passes)
                    && self.seen.insert(known.index(n) as u32)
                {
                    self.stack.push(known.index(n) as u32);
                }
            }
        }
        true
    }
}

/// The cells, in order, of the cheapest way (octile steps, none squeezing between two
/// blocked cells) from `from` over
/// cells `known` shows free, within `reach` cells of it, to the nearest cell `keeps` accepts;
/// empty if none lies within reach. Ties go to the lower cell index.
fn retreat(
    known: &Grid<Occ>,
    from: usize,
    reach: f64,
    mut keeps: impl FnMut(usize) -> bool,
) -> Vec<u32> {
    use std::cmp::Reverse;
    use std::collections::{BinaryHeap, HashMap};
    let origin = known.cell(from);
    let free = |c: Cell| known.contains(c) && *known.get(c) == Occ::Free;
    let within = |c: Cell| {
        let (dx, dy) = (f64::from(c.x - origin.x), f64::from(c.y - origin.y));
        dx * dx + dy * dy <= reach * reach
    };
    // Costs are queued as the bits of non-negative f64s, which order as the values do.
    let mut best: HashMap<usize, (f64, usize)> = HashMap::new();
    let mut queue = BinaryHeap::new();
    best.insert(from, (0.0, from));
    queue.push(Reverse((0u64, from)));
    while let Some(Reverse((bits, i))) = queue.pop() {
        let cost = f64::from_bits(bits);
        if best.get(&i).is_some_and(|&(c, _)| c < cost) {
            continue;
        }
        if i != from && keeps(i) {
            let mut route = Vec::new();
            let mut at = i;
            while at != from {
                route.push(at as u32);
                at = best[&at].1;
            }
            route.reverse();
            return route;
        }
        let c = known.cell(i);
        for (dx, dy) in STEPS {
            let n = Cell::new(c.x + dx, c.y + dy);
            if !free(n) || !within(n) || squeezes(c, (dx, dy), free) {
                continue;
            }
            let j = known.index(n);
            let next = cost + step_cost(dx, dy);
            if best.get(&j).is_none_or(|&(c, _)| next < c) {
                best.insert(j, (next, i));
                queue.push(Reverse((next.to_bits(), j)));
            }
        }
    }
    Vec::new()
}

#[cfg(test)]
mod tests {
    use super::{Pocket, STEPS, retreat};
    use grid::io::parse_ascii;
    use grid::{Cell, Grid, Occ, step_cost};
    use proptest::prelude::*;

    /// The oracle: the least cost from `from` to every cell, by relaxing every legal step
    /// (over free cells within `reach`, none squeezing between two blocked cells) until
    /// nothing changes.
    fn costs_by_relaxing(known: &Grid<Occ>, from: usize, reach: f64) -> Vec<f64> {
        let o = known.cell(from);
        let free = |c: Cell| known.contains(c) && *known.get(c) == Occ::Free;
        let within = |c: Cell| {
            let (dx, dy) = (f64::from(c.x - o.x), f64::from(c.y - o.y));
            dx * dx + dy * dy <= reach * reach
        };
        let mut cost = vec![f64::INFINITY; known.len()];
        cost[from] = 0.0;
        let mut changed = true;
        while changed {
            changed = false;
            for i in 0..known.len() {
                if !cost[i].is_finite() {
                    continue;
                }
                let c = known.cell(i);
                for (dx, dy) in STEPS {
                    let n = Cell::new(c.x + dx, c.y + dy);
                    let squeezed = dx != 0
                        && dy != 0
                        && !free(Cell::new(c.x + dx, c.y))
                        && !free(Cell::new(c.x, c.y + dy));
                    if free(n) && within(n) && !squeezed {
                        let j = known.index(n);
                        if cost[i] + step_cost(dx, dy) < cost[j] - 1e-12 {
                            cost[j] = cost[i] + step_cost(dx, dy);
                            changed = true;
                        }
                    }
                }
            }
        }
        cost
    }

    proptest! {
        /// The retreat is a legal way to an accepted cell, and no accepted cell within
        /// reach is cheaper to get to (the oracle's costs); none when no accepted cell can
        /// be got to.
        #[test]
        fn retreat_is_a_cheapest_legal_way(
            cells in proptest::collection::vec(prop::bool::weighted(0.7), 8 * 7),
            accepted in proptest::collection::vec(prop::bool::weighted(0.15), 8 * 7),
            from in 0usize..8 * 7,
            reach in 1.0f64..6.0,
        ) {
            let occ = cells.iter().map(|&f| if f { Occ::Free } else { Occ::Occupied }).collect();
            let known = Grid::from_vec(8, 7, occ).unwrap();
            let keeps = |i: usize| accepted[i] && known[i] == Occ::Free;
            let route = retreat(&known, from, reach, keeps);
            let best = costs_by_relaxing(&known, from, reach);
            let cheapest = (0..known.len())
                .filter(|&i| i != from && keeps(i))
                .map(|i| best[i])
                .fold(f64::INFINITY, f64::min);
            if route.is_empty() {
                prop_assert!(cheapest.is_infinite(), "no route, but a cell at {}", cheapest);
            } else {
                let mut at = known.cell(from);
                let mut total = 0.0;
                for &next in &route {
                    let n = known.cell(next as usize);
                    let (dx, dy) = (n.x - at.x, n.y - at.y);
                    prop_assert!(dx.abs() <= 1 && dy.abs() <= 1 && (dx, dy) != (0, 0));
                    prop_assert!(best[next as usize].is_finite(), "off the free cells in reach");
                    let beside = [Cell::new(at.x + dx, at.y), Cell::new(at.x, at.y + dy)];
                    let open = |c: Cell| known.contains(c) && *known.get(c) == Occ::Free;
                    prop_assert!(dx == 0 || dy == 0 || beside.into_iter().any(open), "squeezed");
                    total += step_cost(dx, dy);
                    at = n;
                }
                prop_assert!(keeps(*route.last().unwrap() as usize));
                prop_assert!((total - cheapest).abs() < 1e-9, "{} vs {}", total, cheapest);
            }
        }

        /// A pocket is what the flood fill from the cell, unbounded (the oracle, with every
        /// cell reachable, not only those within reach), keeps within the disk.
        #[test]
        fn confined_is_the_fill_staying_in_the_disk(
            cells in proptest::collection::vec(prop::bool::weighted(0.6), 9 * 8),
            from in 0usize..9 * 8,
            origin in (0i32..9, 0i32..8),
            reach in 0.5f64..6.0,
        ) {
            let occ = cells.iter().map(|&f| if f { Occ::Free } else { Occ::Occupied }).collect();
            let known = Grid::from_vec(9, 8, occ).unwrap();
            let trav = |i: usize| known[i] == Occ::Free;
            let origin = Cell::new(origin.0, origin.1);
            // Every cell the fill reaches, by relaxing with unbounded reach from `from`.
            let mut seen = vec![false; known.len()];
            seen[from] = true;
            let mut changed = true;
            while changed {
                changed = false;
                for i in 0..known.len() {
                    if !seen[i] {
                        continue;
                    }
                    let c = known.cell(i);
                    for (dx, dy) in STEPS {
                        let n = Cell::new(c.x + dx, c.y + dy);
                        let passes = |c: Cell| known.contains(c) && trav(known.index(c));
                        let squeezed = dx != 0
                            && dy != 0
                            && !passes(Cell::new(c.x + dx, c.y))
                            && !passes(Cell::new(c.x, c.y + dy));
                        if passes(n) && !squeezed && !seen[known.index(n)] {
                            seen[known.index(n)] = true;
                            changed = true;
                        }
                    }
                }
            }
            let beyond = (0..known.len()).filter(|&i| seen[i]).any(|i| {
                let c = known.cell(i);
                let (dx, dy) = (f64::from(c.x - origin.x), f64::from(c.y - origin.y));
                dx * dx + dy * dy > reach * reach
            });
            let mut pocket = Pocket::default();
            prop_assert_eq!(pocket.confined(&known, &trav, from, origin, reach), !beyond);
        }
    }

    /// A pocket: the cells a search reaches from a cell all lie within the disk, or one
    /// lies beyond it; a diagonal step between two refused cells does not count.
    #[test]
    fn a_pocket_is_what_a_search_cannot_get_out_of() {
        let map = parse_ascii(
            "##########\n#..#......\n#..#......\n###.......\n##........\n",
            0.1,
        )
        .unwrap();
        let known = &map.cells;
        let trav = |i: usize| known[i] == grid::Occ::Free;
        let at = |x, y| known.index(grid::Cell::new(x, y));
        let origin = grid::Cell::new(1, 1);
        let mut pocket = Pocket::default();
        // The 2 x 2 room in the corner is shut; the open side reaches beyond 4 cells.
        assert!(pocket.confined(known, &trav, at(1, 1), origin, 4.0));
        assert!(pocket.confined(known, &trav, at(2, 2), origin, 4.0));
        assert!(!pocket.confined(known, &trav, at(4, 1), origin, 4.0));
        // From a refused cell, the search starts all the same (the wall cell at (3, 1)
        // touches the open side).
        assert!(!pocket.confined(known, &trav, at(3, 1), origin, 4.0));
        // Within a large enough disk nothing is a way out.
        assert!(pocket.confined(known, &trav, at(4, 1), origin, 20.0));
        // (2, 2) to the open (3, 3) would squeeze between the walls at (3, 2) and (2, 3).
        assert!(pocket.confined(known, &trav, at(2, 2), origin, 4.0));
        assert!(!pocket.confined(known, &trav, at(3, 3), origin, 4.0));
    }

    /// The way out of a corridor's dead end: the cheapest over free cells, never cutting a
    /// corner, to the nearest accepted cell within reach; none beyond reach.
    #[test]
    fn retreat_takes_the_cheapest_way_to_the_nearest_accepted_cell() {
        let map = parse_ascii("#######\n#.....#\n#.#...#\n#######\n", 0.1).unwrap();
        let known = &map.cells;
        let at = |x, y| known.index(grid::Cell::new(x, y)) as u32;
        // From (1, 2), to the nearest cell of column 4: diagonally past the wall cell at
        // (2, 2), whose other side (1, 1) is free, then along row 1.
        let route = retreat(known, at(1, 2) as usize, 5.0, |i| known.cell(i).x == 4);
        assert_eq!(route, [at(2, 1), at(3, 1), at(4, 1)]);
        // Between two wall cells there is no way: from (1, 2) with (1, 1) walled too.
        let mut shut = map.cells.clone();
        shut.set(grid::Cell::new(1, 1), grid::Occ::Occupied);
        assert!(retreat(&shut, at(1, 2) as usize, 5.0, |i| shut.cell(i).x == 4).is_empty());
        // Column 5 lies beyond a reach of 3 cells.
        let none = retreat(known, at(1, 2) as usize, 3.0, |i| known.cell(i).x == 5);
        assert!(none.is_empty());
    }
}
