//! The node's decisions without DDS: map message → belief → frontiers → strategy → goal.
//!
//! [`Explorer`] holds what `sim`'s loop holds for one robot — the belief, incremental
//! frontier upkeep, the planner's buffers, Yamauchi's visited and inaccessible lists, the
//! strategy's memory and its seeded random stream — and decides by the very function `sim`'s
//! loop calls ([`explore::decision::decide`]: the preset's candidate generator, then its
//! assigner). What differs from the simulation is who moves and who senses: a SLAM node
//! builds the map and Nav2 drives, so the explorer is fed map messages and poses and answers
//! with goals in world coordinates.
//!
//! The re-plan policy of the strategy is kept, read for a robot that moves by itself:
//!
//! - **on arrival**: the robot is within `goal_tolerance` of the goal, or Nav2 reports
//!   success ([`Explorer::goal_reached`]); the goal goes on the visited list;
//! - **repetitive re-checking** (Holz's RR, `cf-rr`, `cf-rr-seg`): the goal cell is no longer a
//!   frontier in the latest map — an O(1) test on every map update and pose;
//! - **every s_max moves** (Faigl & Kulich): the robot has travelled s_max cells' length
//!   since the decision;
//! - **no progress** (Yamauchi's inaccessible list, explore_lite's `progress_timeout`): the
//!   straight-line distance to the goal has not shrunk for the timeout, or Nav2 failed the
//!   goal ([`Explorer::goal_failed`]); the goal goes on the inaccessible list.
//!
//! Deviations, and why: progress is measured by straight-line distance (explore_lite's
//! rule) rather than Yamauchi's remaining path, because re-planning a path on every pose would
//! cost a Dijkstra per pose on maps of millions of cells, and Nav2 reports failures of goals
//! it cannot reach anyway; `dt-rr`'s utility-drop re-check is not run (the node re-decides
//! `dt-rr` on arrival, like `dt`), because it needs the predicted scan of the belief at the
//! robot's heading while Nav2, not the node, chooses that heading.

use explore::assign::AssignerKind;
use explore::candidates::CandidateKind;
use explore::decision::{self, DecisionCtx, GoalLists, Memory, Offer, Planner};
use explore::strategy::Strategy;
use explore::upkeep::FrontierUpkeep;
use grid::{Grid, NEIGHBOURS8, Occ};
use rand_pcg::Pcg64Mcg;
use record::msgs::OccupancyGrid;
use record::occupancy::{MapFrame, MapMsgError, classify_into, frame_of};
use sense::{Belief, Sensor, SensorSpec};

use crate::map_belief::MapBelief;

/// What the explorer is configured with (the node's parameters that decisions read).
#[derive(Clone, Debug)]
pub struct ExplorerConfig {
    /// The strategy preset.
    pub strategy: Strategy,
    /// The robot's sensor (for strategies that predict what a goal would show).
    pub sensor: SensorSpec,
    /// The robot's clearance from known obstacles, metres (Holz's d_max).
    pub clearance_m: f64,
    /// Frontier regions shorter than this (metres along the region) are not goals.
    pub min_frontier_size_m: f64,
    /// Seconds without getting closer to the goal before it is given up.
    pub progress_timeout_s: f64,
    /// Distance to the goal at which it counts as reached, metres.
    pub goal_tolerance_m: f64,
    /// Seed of the strategy's random stream (`random`, `dt`).
    pub seed: u64,
    /// Refuse a map whose exploration would need more than this many MiB (`None`: only
    /// the memory the machine has available is checked).
    pub memory_mb: Option<u64>,
}

impl ExplorerConfig {
    /// The defaults for `strategy`: `los:r=5`, clearance 0.2 m, min frontier 0.5 m,
    /// progress timeout 30 s, tolerance 0.5 m, seed 0.
    pub fn new(strategy: Strategy) -> Self {
        Self {
            strategy,
            sensor: SensorSpec::Los {
                r: sense::Range::Metres(5.0),
            },
            clearance_m: 0.2,
            min_frontier_size_m: 0.5,
            progress_timeout_s: 30.0,
            goal_tolerance_m: 0.5,
            seed: 0,
            memory_mb: None,
        }
    }

    /// Estimated peak heap bytes of exploring a map of `cells` cells of `resolution`
    /// metres: the per-cell state (belief, frontier upkeep, the robot's search, goal
    /// lists) and what the strategy adds per cell, plus what building the sensor takes.
    /// Measured with a counting allocator on generated offices at 0.05 m
    /// (`tests/memory.rs` checks that it bounds the peak): about 31 bytes a cell, 54 with
    /// the decision-theoretic samples, 80 with segmentation; coverage candidates' scans
    /// grow with the range's cube, not the map (up to about 50 MiB on a 120,000-cell
    /// office with an 8 m laser).
    pub fn memory_bytes(&self, cells: usize, resolution: f64) -> u64 {
        let per_cell = PER_CELL
            + match self.strategy.candidates {
                CandidateKind::Coverage => PER_CELL_COVERAGE,
                CandidateKind::DtSamples { .. } => PER_CELL_DT,
                _ => 0,
            }
            + match self.strategy.assigner {
                AssignerKind::SegmentFirst { .. } => PER_CELL_SEGMENTS,
                _ => 0,
            };
        let scans = self.strategy.candidates.scan_bytes_bound(
            cells,
            self.sensor.range_cells(resolution),
            resolution,
        );
        BASE_BYTES
            .saturating_add(per_cell.saturating_mul(cells as u64))
            .saturating_add(scans)
            .saturating_add(self.sensor.build_bytes(resolution))
    }
}

/// Heap bytes of an explorer whatever its map (buffers, tables).
const BASE_BYTES: u64 = 4 << 20;
/// Per-cell heap bytes of every strategy's state (31 measured).
const PER_CELL: u64 = 40;
/// Per-cell bytes segmentation adds (`cf-rr-seg`: 80 in all, measured).
const PER_CELL_SEGMENTS: u64 = 56;
/// Per-cell bytes the decision-theoretic samples' gain evaluation adds (54 in all).
const PER_CELL_DT: u64 = 32;
/// Per-cell bytes coverage candidates add (their covering cells), beside their scans
/// (`scan_bytes_bound`).
const PER_CELL_COVERAGE: u64 = 160;

/// Why the explorer stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum StopReason {
    /// No frontier cell is left, and no free cell borders unknown space: everything the
    /// robot can reach is known.
    Explored,
    /// Frontier cells are left, but none is a goal: unreachable from the robot with its
    /// clearance, on the visited or inaccessible lists, or in regions below the minimum size.
    NoReachableFrontier {
        /// Frontier cells left on the map.
        frontiers: usize,
        /// Of them, goals given up as inaccessible.
        inaccessible: usize,
        /// Frontier cells in regions below `min_frontier_size`.
        too_small: usize,
        /// Known free cells next to unknown space that are not frontier cells because they
        /// are closer to an obstacle than the clearance (a door or gap too narrow).
        narrow: usize,
    },
    /// The robot's pose is outside the map.
    RobotOffMap {
        /// World x.
        x: f64,
        /// World y.
        y: f64,
    },
    /// No traversable cell near the robot (it stands in unknown or occupied space, or
    /// closer to an obstacle than its clearance everywhere around).
    RobotNotOnFreeSpace {
        /// World x.
        x: f64,
        /// World y.
        y: f64,
    },
    /// No map received yet.
    NoMap,
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Explored => write!(f, "explored: no frontier is left"),
            StopReason::NoReachableFrontier {
                frontiers,
                inaccessible,
                too_small,
                narrow,
            } => {
                write!(
                    f,
                    "no reachable frontier: {frontiers} frontier cells left ({inaccessible} given \
                     up as inaccessible, {too_small} in regions below min_frontier_size, the rest \
                     not reachable with the clearance); {narrow} free cells next to unknown space \
                     are closer to obstacles than the clearance"
                )
            }
            StopReason::RobotOffMap { x, y } => {
                write!(f, "the robot at ({x:.2}, {y:.2}) is outside the map")
            }
            StopReason::RobotNotOnFreeSpace { x, y } => write!(
                f,
                "the robot at ({x:.2}, {y:.2}) is not on known free space with its clearance"
            ),
            StopReason::NoMap => write!(f, "no map received"),
        }
    }
}

/// A goal for Nav2, in the map's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GoalPose {
    /// World x (m).
    pub x: f64,
    /// World y (m).
    pub y: f64,
    /// Heading (rad): from the robot towards the goal.
    pub yaw: f64,
    /// The goal cell (flat index in the current map).
    pub cell: u32,
    /// Length of the planned path to it (m), on the belief with the clearance.
    pub cost_m: f64,
}

/// What a decision gave.
#[derive(Clone, Debug, PartialEq)]
pub enum Decision {
    /// Send this goal.
    Goal(GoalPose),
    /// Stop exploring.
    Stop(StopReason),
}

/// Whether the current goal still stands after a map update or a new pose.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    /// Keep going.
    Keep,
    /// No goal yet (or the last one ended): decide.
    NoGoal,
    /// The robot is within the tolerance of the goal: it was put on the visited list.
    Reached,
    /// Repetitive re-checking: the goal is no longer a frontier.
    TargetExplored,
    /// The strategy's periodic re-plan (s_max) is due.
    Periodic,
    /// No progress for the timeout: the goal was put on the inaccessible list.
    NoProgress,
    /// The map changed frame (size or origin) and the goal is off it or no longer free.
    GoalLost,
}

impl Check {
    /// Whether a new decision is due.
    pub fn replan(self) -> bool {
        self != Check::Keep
    }
}

/// Why a map message was not taken in.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UpdateError {
    /// The message is malformed.
    #[error(transparent)]
    Map(#[from] MapMsgError),
    /// Exploring the map would need more memory than the budget or the machine has.
    #[error(
        "a map of {width} x {height} cells at {resolution} m: exploring it with {strategy} \
         needs about {} MiB, more than {limit}; publish a coarser map, or raise memory_mb \
         or the memory the node may take",
        .needed.div_ceil(1 << 20)
    )]
    TooBig {
        /// Map width, cells.
        width: usize,
        /// Map height, cells.
        height: usize,
        /// Metres per cell, as the message gives it.
        resolution: f32,
        /// The strategy preset.
        strategy: String,
        /// Estimated bytes.
        needed: u64,
        /// The limit exceeded, as a refusal names it.
        limit: grid::memory::Available,
    },
    /// The sensor cannot be built at the map's resolution.
    #[error("sensor {spec} at the map's resolution {resolution} m: {why}")]
    Sensor {
        /// The sensor spec.
        spec: String,
        /// The map's resolution.
        resolution: f64,
        /// What failed.
        why: String,
    },
}

/// What a map message did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MapUpdate {
    /// The frame (size, resolution or origin) changed, so everything was rebuilt.
    pub rebuilt: bool,
    /// Cells whose class changed.
    pub changed: usize,
}

/// The goal being pursued and the progress bookkeeping.
#[derive(Clone, Copy, Debug)]
struct Active {
    goal: GoalPose,
    /// Closest straight-line distance so far, and when it was reached.
    best_dist: f64,
    best_at_s: f64,
    /// Distance travelled since the decision (m) and the last pose seen.
    travelled_m: f64,
    last: (f64, f64),
}

/// Everything one decision needs, sized for the current map; rebuilt when the frame changes.
struct State {
    frame: MapFrame,
    belief: MapBelief,
    upkeep: FrontierUpkeep,
    planner: Planner,
    lists: GoalLists,
    offer: Offer,
    memory: Memory,
    sensor: Box<dyn Sensor>,
    range_cells: f64,
}

/// The decision logic of the exploration node.
pub struct Explorer {
    cfg: ExplorerConfig,
    rng: Pcg64Mcg,
    state: Option<State>,
    /// Visited and inaccessible goals in world coordinates, to carry them over a rebuild.
    visited_world: Vec<(f64, f64)>,
    inaccessible_world: Vec<(f64, f64)>,
    active: Option<Active>,
    // Buffers.
    changed: Vec<u32>,
    queue: Vec<u32>,
    seen: Vec<u32>,
}

impl Explorer {
    /// An explorer that has seen no map yet.
    pub fn new(cfg: ExplorerConfig) -> Self {
        let rng = explore_rng(cfg.seed);
        Self {
            cfg,
            rng,
            state: None,
            visited_world: Vec::new(),
            inaccessible_world: Vec::new(),
            active: None,
            changed: Vec::new(),
            queue: Vec::new(),
            seen: Vec::new(),
        }
    }

    /// The configuration.
    pub fn config(&self) -> &ExplorerConfig {
        &self.cfg
    }

    /// The frame of the current map, if one was received.
    pub fn frame(&self) -> Option<&MapFrame> {
        self.state.as_ref().map(|s| &s.frame)
    }

    /// The current goal.
    pub fn goal(&self) -> Option<GoalPose> {
        self.active.map(|a| a.goal)
    }

    /// Goals given up as inaccessible, in world coordinates, in order.
    pub fn inaccessible(&self) -> &[(f64, f64)] {
        &self.inaccessible_world
    }

    /// Take in a map message: classify its cells and bring frontiers up to date (cost ∝
    /// changed cells, plus one pass over the map to find them); a new size, resolution or
    /// origin rebuilds everything, carrying the goal lists over in world coordinates.
    /// A malformed message changes nothing and is an error.
    pub fn update_map(&mut self, msg: &OccupancyGrid) -> Result<MapUpdate, UpdateError> {
        let frame = frame_of(msg)?;
        let n = frame.width * frame.height;
        let rebuilt = self.state.as_ref().is_none_or(|s| s.frame != frame);
        let changed = if rebuilt {
            // A whole new map: classified straight into the new belief, and frontiers
            // counted from scratch, which beats updating every known cell.
            let sensor = self.sensor_for(&frame)?;
            self.check_memory(&frame)?;
            // The old map's state goes before the new one is built, so that the two are
            // never held at once.
            self.state = None;
            let mut cells = vec![Occ::Unknown; n];
            classify_into(msg, &frame, &mut cells);
            let known = Grid::from_vec(frame.width, frame.height, cells).expect("sized above");
            let known_cells = known.data().iter().filter(|c| !c.is_unknown()).count();
            let st = self.state.insert(self.fresh_state(frame, known, sensor));
            st.upkeep.rebuild(st.belief.known());
            known_cells
        } else {
            let st = self.state.as_mut().expect("not rebuilt");
            self.changed.clear();
            st.belief.set_from_msg(msg, &frame, &mut self.changed);
            st.upkeep.update(st.belief.known(), &self.changed);
            self.changed.len()
        };
        let st = self.state.as_mut().expect("built above");
        if rebuilt {
            // Goal lists in the new frame's cells.
            for &(x, y) in &self.visited_world {
                if let Some(c) = frame.cell_from_world(x, y) {
                    st.lists.mark_visited(st.belief.known().index(c) as u32);
                }
            }
            for &(x, y) in &self.inaccessible_world {
                if let Some(c) = frame.cell_from_world(x, y) {
                    st.lists
                        .mark_inaccessible(st.belief.known().index(c) as u32);
                }
            }
            if let Some(a) = self.active.as_mut() {
                match frame.cell_from_world(a.goal.x, a.goal.y) {
                    Some(c) => a.goal.cell = st.belief.known().index(c) as u32,
                    None => self.active = None,
                }
            }
        }
        Ok(MapUpdate { rebuilt, changed })
    }

    /// Refuse `frame` if exploring it would need more than `memory_mb` or the memory the
    /// machine has available (the old map's state, freed before the new one is built,
    /// counts as available).
    fn check_memory(&self, frame: &MapFrame) -> Result<(), UpdateError> {
        let needed = self
            .cfg
            .memory_bytes(frame.width * frame.height, frame.resolution);
        let held = self.state.as_ref().map_or(0, |s| {
            self.cfg
                .memory_bytes(s.frame.width * s.frame.height, s.frame.resolution)
        });
        let machine = grid::machine::available().map(|mut a| {
            a.bytes = a.bytes.saturating_add(held);
            a
        });
        let budget = self
            .cfg
            .memory_mb
            .map(|mb| grid::memory::Available::flag("memory_mb", mb));
        match grid::memory::least([budget, machine]) {
            Some(limit) if needed > limit.bytes => Err(UpdateError::TooBig {
                width: frame.width,
                height: frame.height,
                resolution: frame.resolution as f32,
                strategy: self.cfg.strategy.name.clone(),
                needed,
                limit,
            }),
            _ => Ok(()),
        }
    }

    /// The robot's sensor at the resolution of `frame`.
    fn sensor_for(&self, frame: &MapFrame) -> Result<Box<dyn Sensor>, UpdateError> {
        self.cfg
            .sensor
            .build(frame.resolution)
            .map_err(|e| UpdateError::Sensor {
                spec: self.cfg.sensor.to_string(),
                resolution: frame.resolution,
                why: e.to_string(),
            })
    }

    /// Everything sized for `frame`, with the belief `known` (the map's classes).
    fn fresh_state(&self, frame: MapFrame, known: Grid<Occ>, sensor: Box<dyn Sensor>) -> State {
        let (w, h) = (frame.width, frame.height);
        let mut memory = Memory::default();
        memory.dt.model = sense::gain::InverseModel::for_belief(sense::BeliefKind::Known);
        State {
            range_cells: sensor.range_cells(),
            sensor,
            frame,
            belief: MapBelief::from_known(known),
            upkeep: FrontierUpkeep::new(
                w,
                h,
                grid::units::cells(self.cfg.clearance_m, frame.resolution),
            ),
            planner: Planner::new(w, h, 1),
            lists: GoalLists::new(w * h),
            offer: Offer::new(w * h),
            memory,
        }
    }

    /// Whether the current goal stands, given the robot at world `(x, y)` at time `now_s`
    /// (call on every pose and after every map update). Applies the strategy's re-plan
    /// policy and the no-progress rule; a goal reached or given up goes on its list.
    pub fn check(&mut self, x: f64, y: f64, now_s: f64) -> Check {
        let timeout = self.progress_timeout_s();
        let tolerance = self.cfg.goal_tolerance_m;
        let replan = self.cfg.strategy.replan;
        let (Some(st), Some(a)) = (self.state.as_ref(), self.active.as_mut()) else {
            return Check::NoGoal;
        };
        a.travelled_m += (x - a.last.0).hypot(y - a.last.1);
        a.last = (x, y);
        let goal = a.goal;
        let dist = (goal.x - x).hypot(goal.y - y);
        let known = st.belief.known();
        let verdict = if dist <= tolerance {
            Check::Reached
        } else if goal.cell as usize >= known.len() || known[goal.cell as usize] != Occ::Free {
            Check::GoalLost
        } else if replan.recheck && !st.upkeep.frontiers.contains(goal.cell as usize) {
            Check::TargetExplored
        } else if dist < a.best_dist - 1e-3 {
            a.best_dist = dist;
            a.best_at_s = now_s;
            Check::Keep
        } else if now_s - a.best_at_s > timeout {
            Check::NoProgress
        } else {
            Check::Keep
        };
        let verdict = match (verdict, replan.every_moves) {
            (Check::Keep, Some(s)) if a.travelled_m >= f64::from(s) * st.frame.resolution => {
                Check::Periodic
            }
            (v, _) => v,
        };
        match verdict {
            Check::Keep => {}
            Check::Reached => self.goal_reached(),
            Check::NoProgress => self.goal_failed(),
            _ => self.active = None,
        }
        verdict
    }

    fn progress_timeout_s(&self) -> f64 {
        // The strategy's own limit (Yamauchi's 30 s) or the node's, whichever is shorter.
        let own = self
            .cfg
            .strategy
            .replan
            .no_progress_s
            .unwrap_or(f64::INFINITY);
        own.min(self.cfg.progress_timeout_s)
    }

    /// Nav2 reports the goal reached (or the robot is within tolerance): visited list.
    pub fn goal_reached(&mut self) {
        if let Some(a) = self.active.take() {
            self.visited_world.push((a.goal.x, a.goal.y));
            if let Some(st) = self.state.as_mut() {
                st.lists.mark_visited(a.goal.cell);
            }
        }
    }

    /// Nav2 rejected or aborted the goal, or it made no progress: inaccessible list.
    pub fn goal_failed(&mut self) {
        if let Some(a) = self.active.take() {
            self.inaccessible_world.push((a.goal.x, a.goal.y));
            if let Some(st) = self.state.as_mut() {
                st.lists.mark_inaccessible(a.goal.cell);
            }
        }
    }

    /// Start the current goal's no-progress time again at `now_s`: Nav2 has only now taken
    /// the goal, or has not yet, so the robot could not get closer to it before.
    pub fn restart_progress(&mut self, now_s: f64) {
        if let Some(a) = self.active.as_mut() {
            a.best_at_s = now_s;
        }
    }

    /// Drop the current goal without listing it (the node was stopped).
    pub fn forget_goal(&mut self) {
        self.active = None;
    }

    /// Decide a goal for the robot at world `(x, y)` at time `now_s` with the strategy.
    ///
    /// A goal within `goal_tolerance` of the robot is reached at once, as in the simulation:
    /// it goes on the visited list (the sensor has looked from there) and the strategy
    /// decides again.
    pub fn decide(&mut self, x: f64, y: f64, now_s: f64) -> Decision {
        loop {
            let d = self.decide_once(x, y, now_s);
            match d {
                Decision::Goal(g) if (g.x - x).hypot(g.y - y) <= self.cfg.goal_tolerance_m => {
                    self.goal_reached();
                }
                d => return d,
            }
        }
    }

    fn decide_once(&mut self, x: f64, y: f64, now_s: f64) -> Decision {
        self.active = None;
        let Some(st) = self.state.as_mut() else {
            return Decision::Stop(StopReason::NoMap);
        };
        let Some(cell) = st.frame.cell_from_world(x, y) else {
            return Decision::Stop(StopReason::RobotOffMap { x, y });
        };
        let known = st.belief.known();
        let at = known.index(cell) as u32;
        let radius =
            grid::units::cells(self.cfg.clearance_m, st.frame.resolution).ceil() as usize + 2;
        let Some(start) = nearest_traversable(st, at, radius, &mut self.queue, &mut self.seen)
        else {
            return Decision::Stop(StopReason::RobotNotOnFreeSpace { x, y });
        };
        let robots = [start];
        let deciding = [true];
        let goals = [None];
        let mut out = [None];
        st.planner.invalidate();
        let mut ctx = DecisionCtx {
            known: st.belief.known(),
            upkeep: &mut st.upkeep,
            planner: &mut st.planner,
            robots: &robots,
            deciding: &deciding,
            goals: &goals,
            lists: &st.lists,
            resolution: st.frame.resolution,
            sensor_range_cells: st.range_cells,
            rng: &mut self.rng,
            belief: &st.belief,
            sensor: st.sensor.as_ref(),
            memory: &mut st.memory,
        };
        // The loop's one decision step; explore_lite's min_frontier_size is its minimum
        // frontier region size.
        let strategy = &self.cfg.strategy;
        decision::decide(
            &mut ctx,
            strategy.candidates,
            Some(strategy.assigner),
            self.cfg.min_frontier_size_m,
            &mut st.offer,
            &mut out,
        );
        let Some(goal) = out[0] else {
            let frontiers = &st.upkeep.frontiers;
            let open = frontiers
                .cells()
                .iter()
                .filter(|&&c| !st.lists.is_excluded(c))
                .count();
            let inaccessible = st
                .lists
                .inaccessible
                .iter()
                .filter(|&&c| frontiers.contains(c as usize))
                .count();
            let known = st.belief.known();
            let narrow = (0..known.len())
                .filter(|&i| {
                    known[i] == Occ::Free
                        && !st.upkeep.is_traversable(known, i)
                        && known.neighbours8(i).any(|n| known[n] == Occ::Unknown)
                })
                .count();
            return Decision::Stop(if open == 0 && inaccessible == 0 && narrow == 0 {
                StopReason::Explored
            } else {
                StopReason::NoReachableFrontier {
                    frontiers: frontiers.len(),
                    inaccessible,
                    too_small: st.offer.too_small,
                    narrow,
                }
            });
        };
        let (gx, gy) = st
            .frame
            .world_from_cell(st.belief.known().cell(goal.cell as usize));
        let pose = GoalPose {
            x: gx,
            y: gy,
            yaw: (gy - y).atan2(gx - x),
            cell: goal.cell,
            cost_m: goal.cost * st.frame.resolution,
        };
        self.active = Some(Active {
            goal: pose,
            best_dist: (gx - x).hypot(gy - y),
            best_at_s: now_s,
            travelled_m: 0.0,
            last: (x, y),
        });
        Decision::Goal(pose)
    }

    /// World points of the current frontier cells (for markers).
    pub fn frontier_points(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
        if let Some(st) = &self.state {
            let known = st.belief.known();
            out.extend(
                st.upkeep
                    .frontiers
                    .cells()
                    .iter()
                    .map(|&c| st.frame.world_from_cell(known.cell(c as usize))),
            );
        }
    }

    /// World points of the last decision's goal candidates (for markers).
    pub fn candidate_points(&self, out: &mut Vec<(f64, f64)>) {
        out.clear();
        if let Some(st) = &self.state {
            let known = st.belief.known();
            out.extend(
                st.offer
                    .candidates
                    .cells()
                    .iter()
                    .map(|&c| st.frame.world_from_cell(known.cell(c as usize))),
            );
        }
    }

    /// Number of frontier cells in the current map.
    pub fn frontier_count(&self) -> usize {
        self.state.as_ref().map_or(0, |s| s.upkeep.frontiers.len())
    }
}

/// The strategy's random stream for seed `seed` (the same derivation for every seed).
fn explore_rng(seed: u64) -> Pcg64Mcg {
    Pcg64Mcg::new(0xcafe_f00d_d15e_a5e5_u128 ^ (u128::from(seed) << 64 | u128::from(seed)))
}

/// The traversable cell nearest to `at` (breadth-first over non-occupied cells, at most
/// `radius` steps): the robot's own cell is often inside its clearance from a wall, or
/// still Unknown under a SLAM map's first scan.
fn nearest_traversable(
    st: &State,
    at: u32,
    radius: usize,
    queue: &mut Vec<u32>,
    seen: &mut Vec<u32>,
) -> Option<u32> {
    let known = st.belief.known();
    if st.upkeep.is_traversable(known, at as usize) {
        return Some(at);
    }
    let (w, h) = (known.width() as i32, known.height() as i32);
    queue.clear();
    seen.clear();
    queue.push(at);
    seen.push(at);
    let mut head = 0;
    for _ in 0..radius {
        let end = queue.len();
        let mut best: Option<u32> = None;
        while head < end {
            let c = queue[head];
            head += 1;
            let (x, y) = ((c as i32) % w, (c as i32) / w);
            for &(dx, dy) in &NEIGHBOURS8 {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx >= w || ny >= h {
                    continue;
                }
                let n = (ny * w + nx) as u32;
                if seen.contains(&n) || known[n as usize] == Occ::Occupied {
                    continue;
                }
                seen.push(n);
                queue.push(n);
                if st.upkeep.is_traversable(known, n as usize) {
                    best = Some(best.map_or(n, |b| b.min(n)));
                }
            }
        }
        if best.is_some() {
            return best;
        }
    }
    None
}
