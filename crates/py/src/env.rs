//! The core of `frontier.gym`: one decision per step over [`sim::Session`].
//!
//! A step takes the index of one of at most K goal candidates (the K cheapest to reach,
//! listed in the candidate generator's order), sends the robot there along its shortest
//! path sensing as configured, and ends at the next decision — on arrival, or earlier when
//! the strategy's re-plan policy calls one (e.g. `cf-rr`'s re-check when the goal stops
//! being a frontier). The observation is written into numpy arrays kept for reuse (one
//! array per key, with a leading axis for a vector of environments), so that a vector of
//! environments steps and writes on Rust threads with the GIL released.

use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use bench::explore::ExploreOptions;
use explore::assign::AssignerKind;
use explore::candidates::CandidateKind;
use explore::decision::Goal;
use explore::strategy::Strategy;
use grid::{GridMap, Occ};
use numpy::ndarray::ArrayD;
use numpy::{
    Element, IxDyn, PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArray1, PyReadwriteArrayDyn,
    PyUntypedArrayMethods, npyffi,
};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use sim::changes::CellBox;
use sim::spin_pool::SpinPool;
use sim::{EndReason, Session, SimError, Status};
use world::{EnvKind, EnvSpec};

use crate::map::{Map, memory_mb_arg, read_file, stem};
use crate::{guarded, internal, str_arg, value_error};

/// A generator spec from Python: (kind, size in metres, resolution).
pub type Generator = (String, Option<(f64, f64)>, Option<f64>);

/// Map files from Python: their paths, the resolution to read bitmaps and HouseExpo plans
/// at, and whether the PNGs are dungeon maps (their marked starts kept).
pub type Files = (Vec<PathBuf>, Option<f64>, bool);

/// Features per candidate: x, y (cells), path cost (m), predicted gain (m²).
pub const FEATURES: usize = 4;

/// Where an environment's maps come from.
enum Maps {
    /// A fixed list; each episode picks one by its seed.
    List(Vec<Map>),
    /// A generator kind; each episode generates one from its seed.
    Generated {
        kind: EnvKind,
        size: Option<(f64, f64)>,
        resolution: Option<f64>,
    },
    /// Map files (a folder's); each episode reads the one its seed picks, so that a dataset
    /// of thousands of plans (HouseExpo's 35,000) is never all in memory at once.
    Files {
        paths: Vec<PathBuf>,
        resolution: Option<f64>,
        dungeon: bool,
    },
}

/// Everything fixed across episodes.
struct Spec {
    maps: Maps,
    options: ExploreOptions,
    candidates: Option<CandidateKind>,
    k: usize,
    view: Option<usize>,
    /// Observation height and width.
    shape: (usize, usize),
    lambda: f64,
    max_path_m: Option<f64>,
    max_steps: Option<u64>,
    gain: bool,
    /// The largest map's width and height in cells, and the largest estimated peak bytes of
    /// one run on any of the maps ([`sim::memory::run_bytes`]).
    largest: (usize, usize),
    run_bytes: u64,
    /// Of those, the part runs in one process share ([`sim::memory::shared_bytes`], the
    /// largest on any map) and the largest rest: n environments need the first once and the
    /// second n times.
    shared_bytes: u64,
    own_bytes: u64,
    /// The user's budget in MiB (`memory_mb`, the CLI's `--memory-mb`): every check of the
    /// environment's memory, its maps' loading and generation, is made within it too.
    memory_mb: Option<u64>,
}

/// SplitMix64: the next seed of a stream (episode seeds after an automatic reset).
fn splitmix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Start the run of the episode of `seed` on `map` (named `name`, with the start its file
/// marks) as `spec` configures it, stopped at its first decision.
fn start_session(
    spec: &Spec,
    seed: u64,
    map: GridMap,
    name: &str,
    marked: Option<grid::Cell>,
) -> Result<Session<'static>, String> {
    let mut o = spec.options.clone();
    o.seed = seed;
    o.or_marked_start(marked);
    o.record_trace = false;
    let mut cfg = config_on(&o, &map, name)?;
    if let Some(c) = spec.candidates {
        cfg.strategy.candidates = c;
    }
    // A map read now may be larger than the one the environment was sized on.
    let bytes = sim::memory::run_bytes(map.width() * map.height(), map.resolution, &cfg);
    if bytes > spec.run_bytes {
        sim::memory::check(
            &format!(
                "an episode on map {name} ({}x{} cells)",
                map.width(),
                map.height()
            ),
            bytes,
            spec.memory_mb,
            grid::machine::available(),
            "leave the largest maps out of the folder, or use fewer environments",
        )
        .map_err(|e| e.to_string())?;
    }
    guarded(|| Session::start(Cow::Owned(map), Cow::Owned(cfg), true))?.map_err(|e| match e {
        // An option out of range (--speed, --clearance, --goal) is wrong on every map.
        SimError::BadParameter { .. } => e.to_string(),
        _ => format!("map {name}: {e}"),
    })
}

/// [`bench::explore::config`] of `o` on map `name` (`map`): a start that does not fit the
/// map is the map's problem, named with it.
fn config_on(o: &ExploreOptions, map: &GridMap, name: &str) -> Result<sim::RunConfig, String> {
    bench::explore::config(o, map, None).map_err(|e| {
        match o
            .start
            .and_then(|c| bench::explore::start_problem(map, c, o.start_marked, o.clearance))
        {
            Some(start) => format!("map {name}: {start}"),
            None => e,
        }
    })
}

impl Spec {
    /// The ground truth of the episode with `seed`, its name and the start its file marks:
    /// map `index` of the list or folder if given, else the one the seed picks.
    fn map(
        &self,
        seed: u64,
        index: Option<usize>,
    ) -> Result<(GridMap, String, Option<grid::Cell>), String> {
        let pick = |n: usize| match index {
            None => Ok((splitmix(seed) % n as u64) as usize),
            Some(i) if i < n => Ok(i),
            Some(i) => Err(format!(
                "options['map']: expected the index of one of the {n} maps, 0 to {}, found {i}",
                n - 1
            )),
        };
        match &self.maps {
            Maps::List(maps) => {
                let m = &maps[pick(maps.len())?];
                Ok(((*m.map).clone(), m.name.clone(), m.start))
            }
            Maps::Generated { kind, .. } if index.is_some() => Err(format!(
                "options['map']: the maps are generated ({kind}), each from its episode's seed; \
                 there is no list to pick from"
            )),
            Maps::Generated {
                kind,
                size,
                resolution,
            } => {
                let spec = EnvSpec {
                    kind: *kind,
                    seed,
                    size_m: *size,
                    resolution: *resolution,
                };
                let env = world::generate(&spec).map_err(|e| format!("generating {kind}: {e}"))?;
                Ok((env.map, env.name, None))
            }
            Maps::Files {
                paths,
                resolution,
                dungeon,
            } => {
                let path = &paths[pick(paths.len())?];
                read_file(
                    path,
                    resolution.map(|r| (r, r)),
                    false,
                    None,
                    *dungeon,
                    self.memory_mb,
                )
            }
        }
    }

    fn cells(&self) -> usize {
        self.shape.0 * self.shape.1
    }

    /// The names of the maps an episode may pick, in index order (None for generated maps).
    fn map_names(&self) -> Option<Vec<String>> {
        match &self.maps {
            Maps::List(maps) => Some(maps.iter().map(|m| m.name.clone()).collect()),
            Maps::Files { paths, .. } => Some(paths.iter().map(|p| stem(p)).collect()),
            Maps::Generated { .. } => None,
        }
    }
}

/// What a step returns besides the observation.
#[derive(Clone, Copy, Default)]
struct StepOut {
    reward: f64,
    terminated: bool,
    truncated: bool,
}

/// One environment's episode.
struct State {
    spec: Arc<Spec>,
    session: Option<Session<'static>>,
    map_name: String,
    /// Each robot's offered candidates, in the generator's order (empty: not deciding).
    shown: Vec<Vec<Goal>>,
    /// Their predicted gains (when asked for).
    gains: Vec<Vec<f64>>,
    buf: Vec<Goal>,
    steps: u64,
    done: bool,
    /// Why the episode ended at its reset (the first scan saw everything reachable), while
    /// no step has reported it yet: the next step returns it, as terminated (or truncated,
    /// if the move budget ended it).
    unreported_end: Option<EndReason>,
    seed: u64,
    /// Reset at the next step (vector environments reset automatically).
    needs_reset: bool,
    /// How long the last step of a vector environment's call took, in µs (an environment's
    /// consecutive steps take correlated times: one of the keys of `expected_work`).
    last_us: f64,
    /// The step a vector environment's call made but did not return, since another
    /// environment's failed: the next call returns it (with the observation it left) rather
    /// than stepping again.
    pending: Option<StepOut>,
    /// What each kept observation set's part for this environment holds (by the set's
    /// place in its [`ObsPool`]).
    marks: Vec<Mark>,
    /// The assigners' proposals for the pending decision (baseline actions), each made
    /// once: asked again, the session would keep one more proposal, and the last proposal
    /// of the goals taken is the one whose draws the episode takes
    /// ([`sim::Session::propose`]).
    proposals: Vec<(AssignerKind, Vec<Option<Goal>>)>,
}

/// What one kept observation set holds of an environment's belief and frontier layers
/// (full view), so that writing it again copies only what changed since.
#[derive(Default)]
struct Mark {
    /// The part holds this episode's layers as they were, but for the cells in `stale`.
    valid: bool,
    /// The belief's cells changed since the part was written.
    stale: Option<CellBox>,
}

impl State {
    fn new(spec: Arc<Spec>) -> Self {
        Self {
            spec,
            session: None,
            map_name: String::new(),
            shown: Vec::new(),
            gains: Vec::new(),
            buf: Vec::new(),
            steps: 0,
            done: true,
            unreported_end: None,
            seed: 0,
            needs_reset: false,
            last_us: 0.0,
            pending: None,
            marks: Vec::new(),
            proposals: Vec::new(),
        }
    }

    /// The goals `assigner` proposes for the pending decision among `cells` (the same
    /// candidates at every call of the decision), proposed once per decision: asked again,
    /// it gives the same goals without running the assigner again.
    fn propose(
        &mut self,
        assigner: AssignerKind,
        cells: &[u32],
    ) -> Result<&[Option<Goal>], String> {
        let at = match self.proposals.iter().position(|(a, _)| *a == assigner) {
            Some(at) => at,
            None => {
                let s = self.session.as_mut().expect("a session");
                let goals = guarded(|| s.propose(assigner, cells).to_vec())?;
                self.proposals.push((assigner, goals));
                self.proposals.len() - 1
            }
        };
        Ok(&self.proposals[at].1)
    }

    /// Start the episode of `seed` on map `index` of the list or folder (None: the map the
    /// seed picks).
    fn reset(&mut self, seed: u64, index: Option<usize>) -> Result<(), String> {
        let spec = self.spec.clone();
        let (map, name, marked) = spec.map(seed, index)?;
        if spec.view.is_none() && (map.height(), map.width()) != spec.shape {
            return Err(format!(
                "map {name}: {}x{} cells, but the observation is {}x{}; maps of different \
                 sizes need a robot-centred view (view=...)",
                map.width(),
                map.height(),
                spec.shape.1,
                spec.shape.0
            ));
        }
        let mut session = start_session(&spec, seed, map, &name, marked)?;
        if spec.view.is_none() {
            session.track_changes();
        }
        self.session = Some(session);
        self.marks.iter_mut().for_each(|m| m.valid = false);
        self.map_name = name;
        self.steps = 0;
        self.done = false;
        self.seed = seed;
        self.needs_reset = false;
        self.pending = None;
        let ended = self.next_decision()?;
        self.done = ended.is_some();
        self.unreported_end = ended;
        Ok(())
    }

    /// Run to the next decision with a candidate to offer, or to the end: why it ended.
    fn next_decision(&mut self) -> Result<Option<EndReason>, String> {
        let spec = self.spec.clone();
        self.proposals.clear();
        let s = self.session.as_mut().expect("a session");
        let m = s.config().robots;
        self.shown.resize_with(m, Vec::new);
        self.gains.resize_with(m, Vec::new);
        self.shown.iter_mut().for_each(Vec::clear);
        self.gains.iter_mut().for_each(Vec::clear);
        loop {
            match s.advance() {
                Status::Ended(reason) => return Ok(Some(reason)),
                Status::Decide => {
                    let deciding = s.deciding().to_vec();
                    let mut offered = false;
                    for (r, &d) in deciding.iter().enumerate() {
                        self.shown[r].clear();
                        self.gains[r].clear();
                        if !d {
                            continue;
                        }
                        s.nearest_candidates(r, spec.k, &mut self.buf);
                        self.buf
                            .sort_by_key(|g| s.candidate_position(g.cell).unwrap_or(usize::MAX));
                        self.shown[r].extend_from_slice(&self.buf);
                        offered |= !self.buf.is_empty();
                        if spec.gain {
                            let (me, _) = s.pose(r);
                            let w = s.known().width() as i64;
                            let (rx, ry) = (me as i64 % w, me as i64 / w);
                            for g in &self.shown[r] {
                                let (cx, cy) = (g.cell as i64 % w, g.cell as i64 / w);
                                let heading = ((cy - ry) as f64).atan2((cx - rx) as f64);
                                self.gains[r].push(s.information_gain(g.cell, heading));
                            }
                        }
                    }
                    if !offered {
                        // Nothing reachable for the deciding robots: they stop (and retry at
                        // the team's next decision); with none left moving, the run ends.
                        s.choose(&vec![None; m]).map_err(|e| e.to_string())?;
                        continue;
                    }
                    return Ok(None);
                }
            }
        }
    }

    /// One decision: robot r (if deciding) goes to its candidate `actions[r]`; with `wrap`,
    /// an action outside the n candidates offered is taken modulo n (any other is refused).
    /// An episode that ended at its reset ends at its first step: terminated, reward 0.
    /// The move budget (`max_moves`), like `max_path_m` and `max_steps`, truncates.
    fn step(&mut self, actions: &[i64], wrap: bool) -> Result<StepOut, String> {
        if self.session.is_some()
            && let Some(end) = self.unreported_end.take()
        {
            self.steps += 1;
            let budget = end == EndReason::StepLimit;
            return Ok(StepOut {
                terminated: !budget,
                truncated: budget,
                ..StepOut::default()
            });
        }
        if self.done || self.session.is_none() {
            return Err("step() after the episode ended: call reset() first".into());
        }
        let mut goals = vec![None; self.shown.len()];
        for (r, shown) in self.shown.iter().enumerate() {
            if shown.is_empty() {
                continue;
            }
            let (a, chosen) = taken(shown, actions.get(r).copied().unwrap_or(i64::MAX), wrap);
            let who = if self.shown.len() > 1 {
                format!(" of robot {r}")
            } else {
                String::new()
            };
            let Some(g) = chosen else {
                return Err(format!(
                    "action{who} {a}: expected the index of one of the {} candidates offered \
                     (see the action_mask)",
                    shown.len()
                ));
            };
            goals[r] = Some(g.cell);
        }
        let s = self.session.as_mut().expect("a session");
        let (cov0, path0) = (s.covered_cells(), s.total_path_length_m());
        s.choose(&goals).map_err(|e| e.to_string())?;
        let ended = self.next_decision()?;
        let terminated = ended.is_some_and(|r| r != EndReason::StepLimit);
        let s = self.session.as_ref().expect("a session");
        let res = s.truth().resolution;
        let (cov1, path1) = (s.covered_cells(), s.total_path_length_m());
        self.steps += 1;
        let truncated = !terminated
            && (ended == Some(EndReason::StepLimit)
                || self.spec.max_path_m.is_some_and(|m| path1 >= m)
                || self.spec.max_steps.is_some_and(|m| self.steps >= m));
        self.done = terminated || truncated;
        Ok(StepOut {
            reward: (cov1 as f64 - cov0 as f64) * res * res - self.spec.lambda * (path1 - path0),
            terminated,
            truncated,
        })
    }

    /// How long `auto_step(action, wrap)` is expected to take, as a key to order a call's
    /// steps by, longest first: a reset (it takes as long as tens of steps), then a step
    /// offered fewer than K candidates (the next observation's search for K finds fewer and
    /// floods all reachable space: 15 times a step's mean), then by an estimate in µs from
    /// the length of the path to the candidate taken, which the robot walks sensing as it
    /// goes, and the environment's last step. Fitted by least squares on single steps in
    /// Explore-Bench's setting, a step took about 1.6 µs more per cell of its path and 0.37
    /// µs more per µs of the last step; ordered so, the slowest of 16 steps was among the
    /// first three 84 % of the time with `cf-rr` (62 % by the path alone) and 85 % with
    /// random actions (76 %).
    fn expected_work(&self, action: i64, wrap: bool) -> (u8, f64) {
        if self.needs_reset {
            return (2, 0.0);
        }
        let offered = self.offered();
        if offered.is_empty() {
            return (0, 0.0);
        }
        let few = u8::from(offered.len() < self.spec.k);
        let cells = taken(offered, action, wrap).1.map_or(0.0, |g| g.cost);
        (few, 1.6 * cells + 0.37 * self.last_us)
    }

    /// Reset if the last step ended the episode (vector environments), else step; a step
    /// made but not returned by the last call is returned instead. A failed reset moves the
    /// seed on, so that the next call draws the stream's next episode rather than failing
    /// on the same map for ever.
    fn auto_step(&mut self, action: i64, wrap: bool) -> Result<StepOut, String> {
        if let Some(out) = self.pending.take() {
            return Ok(out);
        }
        if self.needs_reset {
            let seed = splitmix(self.seed);
            if let Err(e) = self.reset(seed, None) {
                self.seed = seed;
                return Err(format!(
                    "{e} (the episode of seed {seed}; the next step draws the next one)"
                ));
            }
            return Ok(StepOut::default());
        }
        let out = self.step(&[action], wrap)?;
        self.needs_reset = self.done;
        Ok(out)
    }

    /// Write robot `r`'s observation into one environment's slices of the buffers, those of
    /// the kept set at place `slot` in its pool (`None`: a set kept by no pool).
    fn write(&mut self, r: usize, slot: Option<usize>, o: ObsMut<'_>) {
        let spec = &self.spec;
        if let Some(k) = slot
            && self.marks.len() <= k
        {
            self.marks.resize_with(k + 1, Mark::default);
        }
        let Some(s) = self.session.as_mut() else {
            // Before the first episode: zeros (the buffers may hold an earlier observation).
            o.belief.fill(0);
            o.frontier.fill(0);
            o.pose.fill(0.0);
            o.candidates.fill(0.0);
            o.mask.fill(0);
            if let Some(k) = slot {
                self.marks[k].valid = false;
            }
            return;
        };
        let changed = s.take_changes();
        for m in &mut self.marks {
            m.stale = CellBox::join(m.stale, changed);
        }
        let s = &*s;
        let known = s.known();
        let (w, h) = (known.width(), known.height());
        let (me, heading) = s.pose(r);
        let (rx, ry) = ((me as usize % w) as i64, (me as usize / w) as i64);
        let (oh, ow) = spec.shape;
        match spec.view {
            None => {
                // What the part holds that is not the belief now: the box changed since the
                // set was written, or, for a set not written in this episode, everything.
                let kept = slot.map(|k| &self.marks[k]).filter(|m| m.valid);
                let whole = (w > 0 && h > 0).then(|| CellBox {
                    x0: 0,
                    y0: 0,
                    x1: w as u32 - 1,
                    y1: h as u32 - 1,
                });
                if let Some(b) = kept.map_or(whole, |m| m.stale) {
                    let (x0, x1) = (b.x0 as usize, b.x1 as usize + 1);
                    for y in b.y0 as usize..=b.y1 as usize {
                        let row = y * w;
                        let from = &known.data()[row + x0..row + x1];
                        for (b, &c) in o.belief[row + x0..row + x1].iter_mut().zip(from) {
                            *b = c as u8;
                        }
                    }
                    // The frontier layer by rows of the box its changes lie in, not cell by
                    // cell of the whole frontier: with many environments stepping on one
                    // core, scattered writes over each layer evicted what the next
                    // environment's step reads.
                    let f = s.frontier_box(b);
                    let (x0, x1) = (f.x0 as usize, f.x1 as usize + 1);
                    for y in f.y0 as usize..=f.y1 as usize {
                        let row = y * w;
                        s.frontier_bytes(row + x0, &mut o.frontier[row + x0..row + x1]);
                    }
                }
                if let Some(k) = slot {
                    let m = &mut self.marks[k];
                    m.valid = true;
                    m.stale = None;
                }
            }
            Some(v) => {
                o.frontier.fill(0);
                let (x0, y0) = (rx - (v / 2) as i64, ry - (v / 2) as i64);
                for dy in 0..oh {
                    let y = y0 + dy as i64;
                    let row = &mut o.belief[dy * ow..(dy + 1) * ow];
                    if y < 0 || y >= h as i64 {
                        row.fill(Occ::Unknown as u8);
                        continue;
                    }
                    for (dx, b) in row.iter_mut().enumerate() {
                        let x = x0 + dx as i64;
                        *b = if x < 0 || x >= w as i64 {
                            Occ::Unknown as u8
                        } else {
                            known[(y as usize) * w + x as usize] as u8
                        };
                    }
                }
                for &f in s.frontiers() {
                    let (x, y) = ((f as usize % w) as i64 - x0, (f as usize / w) as i64 - y0);
                    if x >= 0 && y >= 0 && (x as usize) < ow && (y as usize) < oh {
                        o.frontier[y as usize * ow + x as usize] = 1;
                    }
                }
            }
        }
        o.pose[0] = rx as f32;
        o.pose[1] = ry as f32;
        o.pose[2] = heading as f32;
        o.candidates.fill(0.0);
        o.mask.fill(0);
        let res = s.truth().resolution;
        let shown = self.shown.get(r).map_or(&[][..], Vec::as_slice);
        let gains = self.gains.get(r).map_or(&[][..], Vec::as_slice);
        for (k, g) in shown.iter().enumerate() {
            let f = &mut o.candidates[k * FEATURES..(k + 1) * FEATURES];
            f[0] = (g.cell as usize % w) as f32;
            f[1] = (g.cell as usize / w) as f32;
            f[2] = (g.cost * res) as f32;
            f[3] = gains.get(k).map_or(0.0, |&n| (n * res * res) as f32);
            o.mask[k] = 1;
        }
    }

    fn coverage(&self) -> f64 {
        self.session.as_ref().map_or(0.0, |s| s.coverage())
    }

    fn path_length_m(&self) -> f64 {
        self.session
            .as_ref()
            .map_or(0.0, |s| s.total_path_length_m())
    }

    /// Robot 0's offered candidates (the single-robot environments').
    fn offered(&self) -> &[Goal] {
        self.shown.first().map_or(&[], Vec::as_slice)
    }
}

/// The candidate of `shown` that `action` names (with `wrap`, taken modulo their number),
/// and the index it was read as; `None` if it names none.
fn taken(shown: &[Goal], action: i64, wrap: bool) -> (i64, Option<&Goal>) {
    let a = match shown.len() {
        0 => action,
        n if wrap => action.rem_euclid(n as i64),
        _ => action,
    };
    (a, usize::try_from(a).ok().and_then(|i| shown.get(i)))
}

/// One environment's part of the observation buffers.
struct ObsMut<'a> {
    belief: &'a mut [u8],
    frontier: &'a mut [u8],
    pose: &'a mut [f32],
    candidates: &'a mut [f32],
    mask: &'a mut [i8],
}

/// The arrays of one observation dict (with a leading axis of `n` environments for a vector
/// environment), kept by an [`ObsPool`].
struct ObsArrays {
    belief: Py<PyArrayDyn<u8>>,
    frontier: Py<PyArrayDyn<u8>>,
    pose: Py<PyArrayDyn<f32>>,
    candidates: Py<PyArrayDyn<f32>>,
    mask: Py<PyArrayDyn<i8>>,
}

impl ObsArrays {
    /// New arrays of zeros for `n` environments (`None`: one, no leading axis). Their memory
    /// is a Rust vector's, which numpy does not own: an array of it that is read-only cannot
    /// be made writeable again from Python (numpy lets the owner of its data do that, or an
    /// array of a writeable buffer's, and a vector kept for numpy is neither).
    fn zeros(py: Python<'_>, spec: &Spec, n: Option<usize>) -> Self {
        let (h, w) = spec.shape;
        let dims = |rest: &[usize]| {
            IxDyn(
                &n.into_iter()
                    .chain(rest.iter().copied())
                    .collect::<Vec<_>>(),
            )
        };
        // Zeros: every element type here (u8, f32, i8) defaults to 0.
        fn zeros<T: Element + Clone + Default>(py: Python<'_>, dims: IxDyn) -> Py<PyArrayDyn<T>> {
            PyArrayDyn::from_owned_array(py, ArrayD::from_elem(dims, T::default())).unbind()
        }
        Self {
            belief: zeros(py, dims(&[h, w])),
            frontier: zeros(py, dims(&[h, w])),
            pose: zeros(py, dims(&[3])),
            candidates: zeros(py, dims(&[spec.k, FEATURES])),
            mask: zeros(py, dims(&[spec.k])),
        }
    }

    fn clone_ref(&self, py: Python<'_>) -> Self {
        Self {
            belief: self.belief.clone_ref(py),
            frontier: self.frontier.clone_ref(py),
            pose: self.pose.clone_ref(py),
            candidates: self.candidates.clone_ref(py),
            mask: self.mask.clone_ref(py),
        }
    }

    /// Whether only the pool holds the arrays: no dict, view or buffer of Python's (each
    /// holds a reference to its array). Reference counts are exact here: the module is
    /// built for the stable ABI, which only GIL builds of Python load, and the GIL is held.
    #[allow(deprecated)]
    fn unused(&self, py: Python<'_>) -> bool {
        self.belief.get_refcnt(py) == 1
            && self.frontier.get_refcnt(py) == 1
            && self.pose.get_refcnt(py) == 1
            && self.candidates.get_refcnt(py) == 1
            && self.mask.get_refcnt(py) == 1
    }

    /// Lend the arrays to `f` as one part per environment, to be brought up to date. The
    /// belief and frontier layers go back read-only: a write copies only what changed since
    /// the set was last written, so an array changed in place would stay wrong.
    fn write<R>(
        &self,
        py: Python<'_>,
        spec: &Spec,
        f: impl FnOnce(Vec<ObsMut<'_>>) -> R,
    ) -> PyResult<R> {
        for a in [&self.belief, &self.frontier] {
            let a = a.bind(py);
            // SAFETY: the array's data is a Rust vector only the array holds (made by
            // `zeros`), mutable and aligned for its elements, the GIL is held, and only
            // the pool references it (a kept set is lent only when no view, buffer or dict
            // of Python's holds an array of it; a new set is not Python's yet), so making
            // it writeable again lets no one else write.
            unsafe {
                (*npyffi::_PyArray_GET_ITEM_DATA(a.as_array_ptr())).flags |=
                    npyffi::NPY_ARRAY_WRITEABLE;
            }
        }
        let (mut b, mut fr, mut p, mut c, mut m) = (
            lend(self.belief.bind(py))?,
            lend(self.frontier.bind(py))?,
            lend(self.pose.bind(py))?,
            lend(self.candidates.bind(py))?,
            lend(self.mask.bind(py))?,
        );
        let (bs, frs, p, c, m) = (
            slice(&mut b)?,
            slice(&mut fr)?,
            slice(&mut p)?,
            slice(&mut c)?,
            slice(&mut m)?,
        );
        let cells = spec.cells();
        let parts = bs
            .chunks_mut(cells)
            .zip(frs.chunks_mut(cells))
            .zip(p.chunks_mut(3))
            .zip(c.chunks_mut(spec.k * FEATURES))
            .zip(m.chunks_mut(spec.k))
            .map(|((((belief, frontier), pose), candidates), mask)| ObsMut {
                belief,
                frontier,
                pose,
                candidates,
                mask,
            })
            .collect();
        let out = f(parts);
        b.make_nonwriteable();
        fr.make_nonwriteable();
        Ok(out)
    }

    /// The arrays as a dict of numpy arrays. The belief and frontier layers go out as
    /// read-only views of the kept arrays, which own no data (see [`Self::zeros`]): a caller
    /// can make neither writeable again (the view, nor the kept array that is its `base`),
    /// so cannot write into a layer that later observations are written over.
    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("belief", self.belief.bind(py).call_method0("view")?)?;
        d.set_item("frontier", self.frontier.bind(py).call_method0("view")?)?;
        d.set_item("pose", self.pose)?;
        d.set_item("candidates", self.candidates)?;
        d.set_item("action_mask", self.mask)?;
        Ok(d)
    }
}

/// Array `a` borrowed for writing (nothing else borrows a pooled array).
fn lend<'py, T: Element>(a: &Bound<'py, PyArrayDyn<T>>) -> PyResult<PyReadwriteArrayDyn<'py, T>> {
    a.try_readwrite()
        .map_err(|e| internal(format!("observation arrays: {e}")))
}

/// The elements of a borrowed array (contiguous: made by `zeros`).
fn slice<'a, T: Element>(a: &'a mut PyReadwriteArrayDyn<'_, T>) -> PyResult<&'a mut [T]> {
    a.as_slice_mut()
        .map_err(|e| internal(format!("observation arrays: {e}")))
}

/// Observation sets an environment keeps per robot: the one a caller holds, the one the
/// wrapper keeps for the action mask, and two spare.
const OBS_SETS: usize = 4;

/// Observation arrays for reuse. Fresh arrays at every step cost a vector environment
/// more than its step (megabytes allocated, zeroed and faulted in, then freed and
/// returned to the system); a set is written again instead once Python holds none of its
/// arrays, so an observation a caller keeps never changes.
struct ObsPool {
    sets: Vec<ObsArrays>,
    /// The most sets kept.
    cap: usize,
}

impl ObsPool {
    fn new(cap: usize) -> Self {
        Self {
            sets: Vec::new(),
            cap,
        }
    }

    /// Arrays for `n` environments (`None`: one) that nobody else holds: a kept set, or
    /// new ones (kept if there is room), with their place among the kept sets.
    fn take(
        &mut self,
        py: Python<'_>,
        spec: &Spec,
        n: Option<usize>,
    ) -> (ObsArrays, Option<usize>) {
        if let Some(k) = self.sets.iter().position(|s| s.unused(py)) {
            return (self.sets[k].clone_ref(py), Some(k));
        }
        let set = ObsArrays::zeros(py, spec, n);
        if self.sets.len() < self.cap {
            self.sets.push(set.clone_ref(py));
            return (set, Some(self.sets.len() - 1));
        }
        (set, None)
    }
}

/// `preset=` of the baseline actions: a strategy preset's name.
fn preset_arg(v: &Bound<'_, PyAny>) -> PyResult<String> {
    str_arg(v, "preset", "a str")
}

/// A user error or a caught panic, as the right Python exception.
fn py_error(e: String) -> PyErr {
    if e.starts_with("internal error") {
        internal(e)
    } else {
        value_error(e)
    }
}

/// The map of the first episode (seed 0's pick) with its name and marked start, which an
/// environment is sized on and tried with.
type First = (GridMap, String, Option<grid::Cell>);

/// Build the fixed part of an environment from the Python arguments, and the first map.
#[allow(clippy::too_many_arguments)]
fn spec(
    py: Python<'_>,
    maps: Option<Vec<PyRef<'_, Map>>>,
    generator: Option<Generator>,
    files: Option<Files>,
    kwargs: Option<&Bound<'_, PyDict>>,
    candidates: Option<String>,
    k: usize,
    view: Option<usize>,
    lambda: f64,
    max_path_m: Option<f64>,
    max_steps: Option<u64>,
    gain: bool,
    team: bool,
    memory_mb: Option<u64>,
) -> PyResult<(Spec, First)> {
    let options = crate::run::options(kwargs)?;
    if !team && options.robots != 1 {
        return Err(value_error(format!(
            "--robots: the environment drives one robot (a team: frontier.pettingzoo), found {}",
            options.robots
        )));
    }
    if let Some(m) = options.motion.as_deref()
        && matches!(m.parse::<sim::Motion>(), Ok(sim::Motion::AnyAngle))
    {
        // A step's reward and the budget read the travel as it happens, and an any-angle
        // length is known only at a run's end (each leg string-pulled on the final map), so
        // the environment would reward and report grid metres under an any-angle name.
        return Err(value_error(format!(
            "motion: an environment moves on the grid (its rewards and max_path_m count each \
             step's travel, and any-angle lengths are measured once a run ends), found \
             {m:?}; frontier.explore(..., motion={m:?}) gives them"
        )));
    }
    if k == 0 {
        return Err(value_error("k: expected at least 1 candidate, found 0"));
    }
    if view == Some(0) {
        return Err(value_error("view: expected at least 1 cell, found 0"));
    }
    if let Some(m) = max_path_m
        && (m.is_nan() || m <= 0.0)
    {
        return Err(value_error(format!(
            "max_path_m: expected a positive number of metres, found {m}"
        )));
    }
    if max_steps == Some(0) {
        return Err(value_error(
            "max_steps: expected at least 1 decision, found 0",
        ));
    }
    if !lambda.is_finite() {
        return Err(value_error(format!(
            "lam: expected a finite number, found {lambda}"
        )));
    }
    if lambda < 0.0 {
        // A negative price would reward travelling for its own sake.
        return Err(value_error(format!(
            "lam: expected a price per metre travelled of at least 0, found {}",
            grid::Num(lambda)
        )));
    }
    let candidates = candidates
        .map(|c| {
            Strategy::preset(&format!("nearest-{c}"))
                .map(|s| s.candidates)
                .map_err(|_| {
                    value_error(format!(
                        "candidates: expected af, centroids, rfe or cc, found '{c}'"
                    ))
                })
        })
        .transpose()?;
    let maps = match (maps, generator, files) {
        (Some(list), None, None) if !list.is_empty() => {
            Maps::List(list.iter().map(|m| (**m).clone()).collect())
        }
        (None, None, Some((paths, resolution, dungeon))) if !paths.is_empty() => {
            if let Some(r) = resolution {
                crate::map::check_resolution(r)?;
            }
            Maps::Files {
                paths,
                resolution,
                dungeon,
            }
        }
        (None, Some((kind, size, resolution)), None) => {
            // As Map.generate checks them, before a map is generated.
            let kind: EnvKind = kind
                .parse()
                .map_err(|e| value_error(format!("--env: {e}")))?;
            size.map(crate::map::check_size).transpose()?;
            resolution.map(crate::map::check_resolution).transpose()?;
            let first = EnvSpec {
                kind,
                seed: 0,
                size_m: size,
                resolution,
            };
            bench::explore::check_generate_memory(&first, memory_mb).map_err(value_error)?;
            Maps::Generated {
                kind,
                size,
                resolution,
            }
        }
        _ => {
            return Err(value_error(
                "maps: give a non-empty list of maps, map files or a generator kind",
            ));
        }
    };
    let mut s = Spec {
        maps,
        options,
        candidates,
        k,
        view,
        shape: (0, 0),
        lambda,
        max_path_m,
        max_steps,
        gain,
        largest: (0, 0),
        run_bytes: 0,
        shared_bytes: 0,
        own_bytes: 0,
        memory_mb,
    };
    // Check the options on the first map, and learn the observation's size.
    let (first, name, marked) = py.detach(|| s.map(0, None)).map_err(value_error)?;
    let cfg = config_on(&s.options, &first, &name).map_err(value_error)?;
    s.largest = match &s.maps {
        Maps::List(list) => list
            .iter()
            .map(|m| (m.map.width(), m.map.height()))
            .max_by_key(|&(w, h)| w * h)
            .unwrap_or((first.width(), first.height())),
        Maps::Generated { .. } | Maps::Files { .. } => (first.width(), first.height()),
    };
    // The largest estimate: the largest map's arrays, or the finest map's sensor template.
    let sized: Vec<(usize, f64)> = match &s.maps {
        Maps::List(list) => list
            .iter()
            .map(|m| (m.map.width() * m.map.height(), m.map.resolution))
            .collect(),
        Maps::Generated { .. } | Maps::Files { .. } => {
            vec![(first.width() * first.height(), first.resolution)]
        }
    };
    for &(cells, res) in &sized {
        let (run, shared) = (
            sim::memory::run_bytes(cells, res, &cfg),
            sim::memory::shared_bytes(res, &cfg),
        );
        s.run_bytes = s.run_bytes.max(run);
        s.shared_bytes = s.shared_bytes.max(shared);
        s.own_bytes = s.own_bytes.max(run.saturating_sub(shared));
    }
    s.shape = match view {
        Some(v) => (v, v),
        None => {
            if let Some((other, w, h)) = py.detach(|| odd_size(&s, &first))? {
                return Err(value_error(format!(
                    "maps: {other} is {w}x{h} cells but {name} is {}x{}; maps of different \
                     sizes need a robot-centred view (view=...)",
                    first.width(),
                    first.height()
                )));
            }
            (first.height(), first.width())
        }
    };
    if let (Maps::List(list), Some(start)) = (&s.maps, s.options.start) {
        py.detach(|| list_start_problem(list, start, s.options.clearance))
            .map_or(Ok(()), |e| Err(value_error(e)))?;
    }
    Ok((s, (first, name, marked)))
}

/// Why a fixed `start` cannot start a run on some map of a list (outside it, or not a free
/// cell the robot fits in), checked on every map when the environment is made: the first
/// episode's run checks only the first map, and another would be refused only at the
/// episode that draws it (a vector environment's, inside `step()`).
fn list_start_problem(list: &[Map], start: grid::Cell, clearance_m: f64) -> Option<String> {
    list.iter().find_map(|m| {
        bench::explore::start_problem(&m.map, start, false, clearance_m)
            .map(|e| format!("map {}: {e}", m.name))
    })
}

/// The first map of the list or folder whose size is not `first`'s, with its size. Every
/// file is read (on all cores) to tell: without a robot-centred view an odd one could never
/// be observed, so it is refused when the environment is made rather than at the episode
/// that draws it, perhaps hours into training.
fn odd_size(s: &Spec, first: &GridMap) -> PyResult<Option<(String, usize, usize)>> {
    let size = (first.width(), first.height());
    match &s.maps {
        Maps::List(list) => Ok(list
            .iter()
            .find(|m| (m.map.width(), m.map.height()) != size)
            .map(|m| (m.name.clone(), m.map.width(), m.map.height()))),
        Maps::Files { paths, .. } => {
            let sizes: Vec<Result<_, String>> = (0..paths.len())
                .into_par_iter()
                .map(|i| {
                    let (m, name, _) = s.map(0, Some(i))?;
                    Ok((name, m.width(), m.height()))
                })
                .collect();
            for got in sizes {
                let (name, w, h) = got.map_err(value_error)?;
                if (w, h) != size {
                    return Ok(Some((name, w, h)));
                }
            }
            Ok(None)
        }
        Maps::Generated { .. } => Ok(None),
    }
}

/// Start the first episode's run and drop it, once the memory it takes has been checked:
/// options that only a run checks (`speed`, `clearance`, `goal`, a start cell that is not
/// free) are refused when the environment is made, not at every reset after.
fn try_first(py: Python<'_>, spec: &Spec, (map, name, marked): First) -> PyResult<()> {
    py.detach(|| guarded(|| start_session(spec, 0, map, &name, marked).map(drop)).and_then(|r| r))
        .map_err(py_error)
}

/// Bytes of one agent's observation, counted [`OBS_SETS`] + 2 times: the arrays the
/// environment keeps for reuse (the ones the caller holds among them), and the observation
/// space's low and high bounds, which have the same shapes.
fn observation_bytes(spec: &Spec) -> u64 {
    let cells = (spec.shape.0 as u64).saturating_mul(spec.shape.1 as u64);
    let layers = cells.saturating_mul(2); // belief and frontier, one byte a cell
    let candidates = (spec.k as u64).saturating_mul(FEATURES as u64 * 4 + 1); // f32s and the mask
    layers
        .saturating_add(candidates)
        .saturating_add(12)
        .saturating_mul(OBS_SETS as u64 + 2)
}

/// Refuse `envs` environments of `agents` observations each whose runs and observations
/// would need more memory than `memory_mb` MiB or the machine has available, before any is
/// allocated.
fn check_memory(spec: &Spec, envs: usize, agents: usize) -> PyResult<()> {
    // What the environments' runs share (the program, a sensor's ray template) once.
    let per_env = spec
        .own_bytes
        .saturating_add(observation_bytes(spec).saturating_mul(agents as u64));
    let (w, h) = spec.largest;
    let what = format!(
        "{} ({w}x{h}-cell maps, {}x{}-cell observations, k = {})",
        match (envs, agents) {
            (1, 1) => "running this environment".to_string(),
            (1, r) => format!("running this environment of {r} robots"),
            (n, _) => format!("running these {n} environments"),
        },
        spec.shape.1,
        spec.shape.0,
        spec.k
    );
    sim::memory::check(
        &what,
        per_env
            .saturating_mul(envs as u64)
            .saturating_add(spec.shared_bytes),
        spec.memory_mb,
        grid::machine::available(),
        "use a smaller k or view (a robot-centred crop), smaller maps, or fewer environments",
    )
    .map_err(|e| value_error(e.to_string()))
}

/// Start the episode of `seed` (on map `map` if given) of a single or team environment's
/// state, with the GIL released.
fn reset_one(
    py: Python<'_>,
    state: &mut Mutex<State>,
    seed: u64,
    map: Option<usize>,
) -> PyResult<()> {
    let state = state.get_mut().unwrap_or_else(|p| p.into_inner());
    py.detach(|| guarded(|| state.reset(seed, map)).and_then(|r| r))
        .map_err(py_error)
}

/// The state behind `m` (a panic inside never leaves it poisoned for good).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// One exploration environment (the core of `frontier.gym.ExploreEnv`).
#[pyclass(module = "frontier._native")]
pub struct EnvCore {
    /// Locked only to satisfy Python's sharing rules; never contended.
    state: Mutex<State>,
    /// Observation arrays for reuse.
    obs: Mutex<ObsPool>,
}

impl EnvCore {
    fn st(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }
}

#[pymethods]
impl EnvCore {
    /// A new environment; see `frontier.gym.ExploreEnv` for the arguments.
    #[new]
    #[pyo3(signature = (maps=None, generator=None, files=None, kwargs=None, candidates=None, k=16, view=None, lam=0.0, max_path_m=None, max_steps=None, gain=false, memory_mb=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        maps: Option<Vec<PyRef<'_, Map>>>,
        generator: Option<Generator>,
        files: Option<Files>,
        kwargs: Option<&Bound<'_, PyDict>>,
        candidates: Option<String>,
        k: usize,
        view: Option<usize>,
        lam: f64,
        max_path_m: Option<f64>,
        max_steps: Option<u64>,
        gain: bool,
        #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
    ) -> PyResult<Self> {
        let (s, first) = spec(
            py, maps, generator, files, kwargs, candidates, k, view, lam, max_path_m, max_steps,
            gain, false, memory_mb,
        )?;
        check_memory(&s, 1, 1)?;
        try_first(py, &s, first)?;
        Ok(Self {
            state: Mutex::new(State::new(Arc::new(s))),
            obs: Mutex::new(ObsPool::new(OBS_SETS)),
        })
    }

    /// Observation (height, width) of the belief and frontier layers.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.st().spec.shape
    }

    /// K: the most candidates offered.
    #[getter]
    fn k(&self) -> usize {
        self.st().spec.k
    }

    /// Start an episode from `seed` (on map `map` of the list or folder if given); returns
    /// the observation.
    #[pyo3(signature = (seed, map=None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seed: u64,
        map: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        reset_one(py, &mut self.state, seed, map)?;
        self.observation(py)
    }

    /// The names of the maps an episode may pick, by index (None for generated maps).
    #[getter]
    fn map_names(&self) -> Option<Vec<String>> {
        self.st().spec.map_names()
    }

    /// Go to candidate `action` (with `wrap`, modulo the candidates offered); returns
    /// (observation, reward, terminated, truncated).
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        action: i64,
        wrap: bool,
    ) -> PyResult<(Bound<'py, PyDict>, f64, bool, bool)> {
        let state = self.state.get_mut().unwrap_or_else(|p| p.into_inner());
        let out = py
            .detach(|| guarded(|| state.step(&[action], wrap)).and_then(|r| r))
            .map_err(py_error)?;
        Ok((
            self.observation(py)?,
            out.reward,
            out.terminated,
            out.truncated,
        ))
    }

    /// The current observation.
    fn observation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mut st = self.st();
        let spec = st.spec.clone();
        let (set, slot) = lock(&self.obs).take(py, &spec, None);
        set.write(py, &spec, |parts| {
            if let Some(o) = parts.into_iter().next() {
                st.write(0, slot, o);
            }
        })?;
        set.into_dict(py)
    }

    /// Coverage, path length, decisions, moves, steps, candidates offered and the map's name.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let st = self.st();
        d.set_item("coverage", st.coverage())?;
        d.set_item("path_length_m", st.path_length_m())?;
        if let Some(s) = &st.session {
            d.set_item("decisions", s.decisions())?;
            d.set_item("moves", s.moves())?;
        }
        d.set_item("steps", st.steps)?;
        d.set_item("candidates", st.offered().len())?;
        d.set_item("map", st.map_name.clone())?;
        Ok(d)
    }

    /// The action a paper's preset would take now: its assigner's choice among the offered
    /// candidates (drawing from a copy of the episode's strategy stream, which the episode
    /// takes only if the step takes this action; asked again, the same action).
    fn baseline_action(
        &mut self,
        #[pyo3(from_py_with = preset_arg)] preset: String,
    ) -> PyResult<usize> {
        let strategy =
            Strategy::preset(&preset).map_err(|e| value_error(format!("--strategy: {e}")))?;
        let st = self.state.get_mut().unwrap_or_else(|p| p.into_inner());
        if st.unreported_end.is_some() {
            // Ended at its reset: nothing is offered, and the next step ends the episode.
            return Ok(0);
        }
        let cells: Vec<u32> = st.offered().iter().map(|g| g.cell).collect();
        if st.session.is_none() || st.done {
            return Err(value_error(
                "baseline_action() after the episode ended: call reset() first",
            ));
        }
        let chosen = st
            .propose(strategy.assigner, &cells)
            .map_err(internal)?
            .first()
            .copied()
            .flatten();
        Ok(chosen
            .and_then(|g| cells.iter().position(|&c| c == g.cell))
            .unwrap_or(0))
    }
}

/// N exploration environments stepped together on Rust threads (the core of
/// `frontier.gym.ExploreVectorEnv`); an ended episode resets at the next step.
#[pyclass(module = "frontier._native")]
pub struct VecEnvCore {
    /// Locked only to satisfy Python's sharing rules; never contended.
    states: Vec<Mutex<State>>,
    /// The caller and its helper threads, which step the environments side by side.
    pool: SpinPool,
    /// Observation arrays for reuse.
    obs: Mutex<ObsPool>,
}

impl VecEnvCore {
    fn observations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let spec = self.spec();
        let (set, slot) = lock(&self.obs).take(py, &spec, Some(self.states.len()));
        let (states, pool) = (&self.states, &self.pool);
        set.write(py, &spec, |parts| {
            py.detach(|| pool.each(parts, |i, o| lock(&states[i]).write(0, slot, o)))
        })?;
        set.into_dict(py)
    }

    fn spec(&self) -> Arc<Spec> {
        lock(&self.states[0]).spec.clone()
    }
}

#[pymethods]
impl VecEnvCore {
    /// `n` environments like `EnvCore(...)` on `threads` threads (default: one per core).
    #[new]
    #[pyo3(signature = (n, maps=None, generator=None, files=None, kwargs=None, candidates=None, k=16, view=None, lam=0.0, max_path_m=None, max_steps=None, gain=false, threads=None, memory_mb=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        n: usize,
        maps: Option<Vec<PyRef<'_, Map>>>,
        generator: Option<Generator>,
        files: Option<Files>,
        kwargs: Option<&Bound<'_, PyDict>>,
        candidates: Option<String>,
        k: usize,
        view: Option<usize>,
        lam: f64,
        max_path_m: Option<f64>,
        max_steps: Option<u64>,
        gain: bool,
        threads: Option<usize>,
        #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
    ) -> PyResult<Self> {
        if n == 0 {
            return Err(value_error("num_envs: expected at least 1, found 0"));
        }
        if threads == Some(0) {
            return Err(value_error("threads: expected at least 1, found 0"));
        }
        let (s, first) = spec(
            py, maps, generator, files, kwargs, candidates, k, view, lam, max_path_m, max_steps,
            gain, false, memory_mb,
        )?;
        check_memory(&s, n, 1)?;
        try_first(py, &s, first)?;
        let s = Arc::new(s);
        // No more threads than environments: a helper with nothing to take would only spin.
        let pool = SpinPool::new(threads.unwrap_or_else(rayon::current_num_threads).min(n))
            .map_err(|e| PyRuntimeError::new_err(format!("starting helper threads: {e}")))?;
        Ok(Self {
            states: (0..n).map(|_| Mutex::new(State::new(s.clone()))).collect(),
            pool,
            obs: Mutex::new(ObsPool::new(OBS_SETS)),
        })
    }

    /// Observation (height, width) of the belief and frontier layers.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.spec().shape
    }

    /// The names of the maps an episode may pick, by index (None for generated maps).
    #[getter]
    fn map_names(&self) -> Option<Vec<String>> {
        self.spec().map_names()
    }

    /// K: the most candidates offered.
    #[getter]
    fn k(&self) -> usize {
        self.spec().k
    }

    /// Start every environment's episode, environment i from `seeds[i]` (on map `maps[i]`
    /// of the list or folder where given). Returns (observations, coverage, path lengths),
    /// the last two as arrays, as `step` does.
    #[allow(clippy::type_complexity)]
    #[pyo3(signature = (seeds, maps=None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seeds: Vec<u64>,
        maps: Option<Vec<Option<usize>>>,
    ) -> PyResult<(
        Bound<'py, PyDict>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let n = self.states.len();
        if seeds.len() != n {
            return Err(value_error(format!(
                "seeds: expected {n} seeds, found {}",
                seeds.len()
            )));
        }
        let maps = maps.unwrap_or_else(|| vec![None; n]);
        if maps.len() != n {
            return Err(value_error(format!(
                "options['map']: expected one map index (or None) per environment, {n}, \
                 found {}",
                maps.len()
            )));
        }
        let (states, pool) = (&self.states, &self.pool);
        let items: Vec<(u64, Option<usize>)> = seeds.into_iter().zip(maps).collect();
        py.detach(|| {
            pool.each(items, |i, (seed, map)| {
                guarded(|| lock(&states[i]).reset(seed, map))
                    .and_then(|r| r)
                    .map_err(|e| format!("environment {i}: {e}"))
            })
            .into_iter()
            .collect::<Result<Vec<()>, String>>()
        })
        .map_err(py_error)?;
        let obs = self.observations(py)?;
        let states = || self.states.iter().map(|s| lock(s));
        Ok((
            obs,
            PyArray1::from_iter(py, states().map(|s| s.coverage())),
            PyArray1::from_iter(py, states().map(|s| s.path_length_m())),
        ))
    }

    /// Step environment i with `actions[i]` (an ended episode resets instead); with `wrap`,
    /// an action outside the offered candidates 0..n−1 is taken modulo n. Returns
    /// (observations, rewards, terminated, truncated, coverage, path lengths), the last five
    /// as arrays.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: PyReadonlyArray1<'py, i64>,
        wrap: bool,
    ) -> PyResult<(
        Bound<'py, PyDict>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
        Bound<'py, PyArray1<bool>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let actions: Vec<i64> = actions.as_array().iter().copied().collect();
        if actions.len() != self.states.len() {
            return Err(value_error(format!(
                "actions: expected {} actions, found {}",
                self.states.len(),
                actions.len()
            )));
        }
        let spec = self.spec();
        let (set, slot) = lock(&self.obs).take(py, &spec, Some(self.states.len()));
        let (states, pool) = (&self.states, &self.pool);
        // Longest first (`State::expected_work`), so that the call does not wait for a
        // long step started last. Each environment's step is the same in any order.
        let work: Vec<(u8, f64)> = (0..states.len())
            .map(|i| lock(&states[i]).expected_work(actions[i], wrap))
            .collect();
        let mut order: Vec<usize> = (0..states.len()).collect();
        order.sort_by(|&a, &b| {
            let (x, y) = (work[a], work[b]);
            y.0.cmp(&x.0).then(y.1.total_cmp(&x.1))
        });
        // One parallel pass per call: each environment steps, then writes its observation.
        let results = set.write(py, &spec, |parts| {
            let items: Vec<_> = actions.into_iter().zip(parts).collect();
            py.detach(|| {
                pool.each_in_order(items, &order, |i, (a, o)| -> Result<StepOut, String> {
                    let mut st = lock(&states[i]);
                    let (started, resets) = (std::time::Instant::now(), st.needs_reset);
                    let out = guarded(|| st.auto_step(a, wrap))
                        .and_then(|r| r)
                        .map_err(|e| format!("environment {i}: {e}"))?;
                    // a reset says nothing of the first step after it
                    st.last_us = if resets {
                        0.0
                    } else {
                        started.elapsed().as_secs_f64() * 1e6
                    };
                    st.write(0, slot, o);
                    Ok(out)
                })
            })
        })?;
        // One environment's error is raised, but the others' steps were made: each keeps
        // its own to return at the next call, so no transition is lost and none is made
        // twice.
        if let Some(e) = results.iter().find_map(|r| r.as_ref().err()) {
            for (st, r) in states.iter().zip(&results) {
                if let Ok(out) = r {
                    lock(st).pending = Some(*out);
                }
            }
            return Err(value_error(format!(
                "{e}; the other environments' steps are kept: the next step() returns them \
                 (and retries this one), or reset() starts over"
            )));
        }
        let outs: Vec<StepOut> = results.into_iter().flatten().collect();
        let obs = set.into_dict(py)?;
        let states = || self.states.iter().map(|s| lock(s));
        Ok((
            obs,
            PyArray1::from_iter(py, outs.iter().map(|o| o.reward)),
            PyArray1::from_iter(py, outs.iter().map(|o| o.terminated)),
            PyArray1::from_iter(py, outs.iter().map(|o| o.truncated)),
            PyArray1::from_iter(py, states().map(|s| s.coverage())),
            PyArray1::from_iter(py, states().map(|s| s.path_length_m())),
        ))
    }

    /// Each environment's baseline action (see `EnvCore.baseline_action`); 0 for an
    /// environment about to reset.
    fn baseline_actions(
        &mut self,
        py: Python<'_>,
        #[pyo3(from_py_with = preset_arg)] preset: String,
    ) -> PyResult<Vec<usize>> {
        let strategy =
            Strategy::preset(&preset).map_err(|e| value_error(format!("--strategy: {e}")))?;
        let (states, pool) = (&self.states, &self.pool);
        py.detach(|| {
            pool.each(states.iter().collect(), |_, st| {
                let mut guard = lock(st);
                let st = &mut *guard;
                let cells: Vec<u32> = st.offered().iter().map(|g| g.cell).collect();
                if st.session.is_none() || st.done {
                    return Ok(0);
                }
                let chosen = st
                    .propose(strategy.assigner, &cells)?
                    .first()
                    .copied()
                    .flatten();
                Ok(chosen
                    .and_then(|g| cells.iter().position(|&c| c == g.cell))
                    .unwrap_or(0))
            })
            .into_iter()
            .collect::<Result<Vec<usize>, String>>()
        })
        .map_err(internal)
    }
}

/// A team exploring together, one agent per robot (the core of
/// `frontier.pettingzoo.ExploreParallelEnv`). At a decision only the deciding robots' actions
/// count (the others' action masks are empty); the reward is the team's.
#[pyclass(module = "frontier._native")]
pub struct TeamEnvCore {
    /// Locked only to satisfy Python's sharing rules; never contended.
    state: Mutex<State>,
    /// Observation arrays for reuse.
    obs: Mutex<ObsPool>,
}

impl TeamEnvCore {
    fn st(&self) -> MutexGuard<'_, State> {
        lock(&self.state)
    }

    /// One observation dict per robot (the shared layers are copied into each).
    fn observations<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let mut st = self.st();
        let spec = st.spec.clone();
        let m = spec.options.robots;
        let mut team = Vec::with_capacity(m * 3);
        if let Some(s) = &st.session {
            let w = s.known().width();
            for r in 0..m {
                let (c, heading) = s.pose(r);
                team.extend([
                    (c as usize % w) as f32,
                    (c as usize / w) as f32,
                    heading as f32,
                ]);
            }
        } else {
            team.resize(m * 3, 0.0);
        }
        let mut sets = lock(&self.obs);
        (0..m)
            .map(|r| {
                let (set, slot) = sets.take(py, &spec, None);
                set.write(py, &spec, |parts| {
                    if let Some(o) = parts.into_iter().next() {
                        st.write(r, slot, o);
                    }
                })?;
                let d = set.into_dict(py)?;
                d.set_item(
                    "team",
                    PyArray1::from_vec(py, team.clone()).reshape([m, 3])?,
                )?;
                Ok(d)
            })
            .collect()
    }
}

#[pymethods]
impl TeamEnvCore {
    /// A new team environment; `kwargs["robots"]` is the team's size.
    #[new]
    #[pyo3(signature = (maps=None, generator=None, files=None, kwargs=None, candidates=None, k=16, view=None, lam=0.0, max_path_m=None, max_steps=None, gain=false, memory_mb=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        maps: Option<Vec<PyRef<'_, Map>>>,
        generator: Option<Generator>,
        files: Option<Files>,
        kwargs: Option<&Bound<'_, PyDict>>,
        candidates: Option<String>,
        k: usize,
        view: Option<usize>,
        lam: f64,
        max_path_m: Option<f64>,
        max_steps: Option<u64>,
        gain: bool,
        #[pyo3(from_py_with = memory_mb_arg)] memory_mb: Option<u64>,
    ) -> PyResult<Self> {
        let (s, first) = spec(
            py, maps, generator, files, kwargs, candidates, k, view, lam, max_path_m, max_steps,
            gain, true, memory_mb,
        )?;
        check_memory(&s, 1, s.options.robots)?;
        try_first(py, &s, first)?;
        let sets = OBS_SETS * s.options.robots;
        Ok(Self {
            state: Mutex::new(State::new(Arc::new(s))),
            obs: Mutex::new(ObsPool::new(sets)),
        })
    }

    /// Number of robots (agents).
    #[getter]
    fn robots(&self) -> usize {
        self.st().spec.options.robots
    }

    /// Observation (height, width) of the belief and frontier layers.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.st().spec.shape
    }

    /// K: the most candidates offered to one robot.
    #[getter]
    fn k(&self) -> usize {
        self.st().spec.k
    }

    /// Start an episode from `seed` (on map `map` of the list or folder if given); returns
    /// one observation per robot.
    #[pyo3(signature = (seed, map=None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seed: u64,
        map: Option<usize>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        reset_one(py, &mut self.state, seed, map)?;
        self.observations(py)
    }

    /// The names of the maps an episode may pick, by index (None for generated maps).
    #[getter]
    fn map_names(&self) -> Option<Vec<String>> {
        self.st().spec.map_names()
    }

    /// Robot r goes to its candidate `actions[r]` if it is deciding (with `wrap`, modulo
    /// the candidates offered to it); returns (observations, team reward, terminated,
    /// truncated).
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: Vec<i64>,
        wrap: bool,
    ) -> PyResult<(Vec<Bound<'py, PyDict>>, f64, bool, bool)> {
        let state = self.state.get_mut().unwrap_or_else(|p| p.into_inner());
        let out = py
            .detach(|| guarded(|| state.step(&actions, wrap)).and_then(|r| r))
            .map_err(py_error)?;
        Ok((
            self.observations(py)?,
            out.reward,
            out.terminated,
            out.truncated,
        ))
    }

    /// Which robots decide now (their actions count).
    fn deciding(&self) -> Vec<bool> {
        self.st().shown.iter().map(|s| !s.is_empty()).collect()
    }

    /// Coverage, per-robot path lengths, decisions, moves, steps and the map's name.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let st = self.st();
        d.set_item("coverage", st.coverage())?;
        if let Some(s) = &st.session {
            let m = st.spec.options.robots;
            let paths: Vec<f64> = (0..m).map(|r| s.path_length_m(r)).collect();
            d.set_item("path_length_m", paths)?;
            d.set_item("decisions", s.decisions())?;
            d.set_item("moves", s.moves())?;
        }
        d.set_item("steps", st.steps)?;
        d.set_item("map", st.map_name.clone())?;
        Ok(d)
    }

    /// Each robot's action under `preset`'s assigner, choosing for the deciding robots
    /// together among the candidates offered to any of them (0 for the others).
    fn baseline_actions(
        &mut self,
        #[pyo3(from_py_with = preset_arg)] preset: String,
    ) -> PyResult<Vec<usize>> {
        let strategy =
            Strategy::preset(&preset).map_err(|e| value_error(format!("--strategy: {e}")))?;
        let st = self.state.get_mut().unwrap_or_else(|p| p.into_inner());
        if st.unreported_end.is_some() {
            // Ended at its reset: nothing is offered, and the next step ends the episode.
            return Ok(vec![0; st.spec.options.robots]);
        }
        let Some(s) = st.session.as_ref().filter(|_| !st.done) else {
            return Err(value_error(
                "baseline_actions() after the episode ended: call reset() first",
            ));
        };
        let mut cells: Vec<u32> = st.shown.iter().flatten().map(|g| g.cell).collect();
        cells.sort_by_key(|&c| s.candidate_position(c).unwrap_or(usize::MAX));
        cells.dedup();
        let chosen = st
            .propose(strategy.assigner, &cells)
            .map_err(internal)?
            .to_vec();
        Ok(st
            .shown
            .iter()
            .zip(chosen)
            .map(|(shown, g)| {
                g.and_then(|g| shown.iter().position(|c| c.cell == g.cell))
                    .unwrap_or(0)
            })
            .collect())
    }
}
