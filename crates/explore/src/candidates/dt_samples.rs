//! Decision-theoretic samples near frontiers (González-Baños & Latombe 2002, as Holz et al.
//! 2010 ran it, §3.2): `n` poses drawn from the free space "in the vicinity of frontiers",
//! each scored by its expected information gain `I(p)` ([`sense::gain`]).
//!
//! The vicinity is every cell within the sensor range (Euclidean, centre to centre) of an
//! *open* frontier cell — one a deciding robot can reach and not on the visited/inaccessible
//! lists: one exact distance transform from those frontier cells per decision, over their
//! bounding box grown by the range.
//!
//! Termination is the paper's common criterion (§3.1: "there is not any single reachable
//! cell being adjacent to an unknown cell"): with no open frontier cell there are no
//! candidates, so the robot stops, whatever gain a scan could still promise. The gain
//! counts every uncertain cell a scan touches, also cells no robot can reach (free cells
//! closer to a wall than the clearance, specks between the laser's rays behind walls);
//! sampling near unreachable frontiers, or going on while such gains remain, made a run
//! on a large real floor plan travel eight times as far as closest-frontier after every
//! reachable cell was known (regression test
//! `dt_stops_when_no_reachable_frontier_is_left`). Eligible cells are listed in index order within that box. A sample must also be reachable by a
//! deciding robot (its full reachability map) and not stand where a deciding robot stands.
//! Samples are drawn uniformly without replacement (a partial Fisher–Yates shuffle of the
//! eligible cells, listed in index order, driven by the run's `rng`), so a run is
//! deterministic. `I(p)` is stored in [`State::gains`], aligned with the candidate set's
//! order, for the utility assigner.
//!
//! Gated rays (deviation, for the lidar): a predicted ray enters an Unknown cell that
//! borders the known map (8-neighbours) only if that cell also borders an open frontier
//! cell; otherwise the ray ends there (the cell still counts: a real scan would observe
//! it). A 1° laser at 5 cm cells sees a wall as hits a few cells apart and never its far
//! side; with every Unknown cell transparent, a predicted ray slips through such an unseen
//! wall cell into whatever unknown lies behind — the outside of the building, a courtyard, a
//! room behind a door too narrow to pass — and promises thousands of bits that no visit
//! delivers. González-Baños & Latombe count the unexplored area visible through the *free
//! edges* of the known region; the open frontier cells are a grid's free edges. The
//! dt-rr re-check ([`State::gain_at`]) uses the open cells of the last decision. `los` and
//! `footprint` predictions are not gated.
//!
//! Lazy gains (speed, same decisions): the samples are evaluated in draw order only until
//! the first one with a positive gain; the others are stored with gain `NaN` ("not yet
//! evaluated") and the utility assigner evaluates them in order of path cost only while one
//! could still beat the best utility found (see [`crate::assign::utility`]). A sample that
//! turns out to have gain 0 is then skipped, as if it had not been kept. The choice is the
//! one the full evaluation would make; the candidate set may include drawn samples whose gain
//! is 0 but was never evaluated.
//!
//! Heading: a lidar's gain depends on where it looks. We use the heading the robot will
//! have on arrival — the direction of the last step of its planned path to the sample, from
//! the same reachability map the loop takes the path from (for a team: the lowest-index
//! deciding robot that reaches the sample). A robot already on the cell is taken to face
//! its unknown neighbours, as the loop turns it on arrival.
//!
//! Deviations, both to keep the loop's termination guarantee:
//! - a sample whose gain is 0 cannot reveal anything from there, so it is not kept (it
//!   would have utility 0 and never win anyway, unless all do);
//! - when no draw has a positive gain (e.g. the last unknown cells hide behind corners no
//!   nearby pose sees), every reachable, unlisted frontier cell becomes a candidate with
//!   its gain (possibly 0), so the utility assigner degrades to the nearest frontier there.

use grid::Grid;
use grid::edt::{EdtScratch, edt_squared_into};
use rand::RngExt;
use sense::{Belief, GainScratch, InverseModel, Pose, Sensor, information_gain_gated};

use super::CandidateSet;
use crate::decision::DecisionCtx;
use crate::plan::Reachability;

/// Samples, their gains and the buffers kept across decisions.
pub struct State {
    /// `I(p)` in bits of each candidate, aligned with [`cells`](Self::cells); `NaN` for a
    /// sample not evaluated yet ([`State::gain`] evaluates it).
    pub gains: Vec<f64>,
    /// The candidates the gains belong to, in the candidate set's order.
    pub cells: Vec<u32>,
    /// The heading (radians, grid coordinates) each gain was evaluated with (`NaN` while
    /// the gain is not evaluated).
    pub headings: Vec<f64>,
    /// The robot whose reachability map gives each candidate's arrival heading.
    pub reachers: Vec<u32>,
    /// The simulated update of the gain ([`InverseModel::IDEAL`] unless the loop sets the
    /// belief's own model, see [`InverseModel::for_belief`]).
    pub model: InverseModel,
    /// Whether the last decision fell back to frontier cells (no sample had a gain).
    pub fell_back: bool,
    /// Buffers of the gain evaluation (shared with the utility assigner).
    pub scratch: GainScratch,
    eligible: Vec<u32>,
    /// Visit order of the lazy utility assigner: (bound on the utility, cost, candidate index).
    pub(crate) order: Vec<(f64, f64, u32)>,
    /// Uncertain-cell counts of the belief (a summed-area table) for the gain bound.
    pub(crate) uncertain: crate::assign::utility::UncertainCounts,
    /// The per-candidate gain bound over those counts.
    pub(crate) bound: crate::assign::utility::GainBound,
    near: Grid<f64>,
    edt: EdtScratch,
    /// The open frontier cells of the current decision (map-sized marks, and their list to
    /// clear them), gating the predicted rays (module doc); empty marks: no gating.
    open: Vec<bool>,
    open_cells: Vec<u32>,
}

impl Default for State {
    fn default() -> Self {
        Self {
            gains: Vec::new(),
            cells: Vec::new(),
            headings: Vec::new(),
            reachers: Vec::new(),
            model: InverseModel::IDEAL,
            fell_back: false,
            scratch: GainScratch::new(),
            eligible: Vec::new(),
            order: Vec::new(),
            uncertain: Default::default(),
            bound: Default::default(),
            near: Grid::new(0, 0, f64::INFINITY),
            edt: EdtScratch::new(),
            open: Vec::new(),
            open_cells: Vec::new(),
        }
    }
}

impl State {
    /// Forget the candidates of the last decision (keeps the buffers).
    fn clear(&mut self) {
        self.gains.clear();
        self.cells.clear();
        self.headings.clear();
        self.reachers.clear();
        self.fell_back = false;
        for &c in &self.open_cells {
            self.open[c as usize] = false;
        }
        self.open_cells.clear();
    }

    /// Mark `cell` an open frontier cell of this decision (`len`: the map's cells).
    fn mark_open(&mut self, len: usize, cell: u32) {
        if self.open.len() != len {
            self.open.clear();
            self.open.resize(len, false);
        }
        self.open[cell as usize] = true;
        self.open_cells.push(cell);
    }

    /// Whether some candidate's gain is not evaluated yet.
    pub fn is_lazy(&self) -> bool {
        self.gains.iter().any(|g| g.is_nan())
    }

    /// The gain of candidate `k`, evaluating it (on arrival along `reach`, the map of robot
    /// [`reachers`](Self::reachers)`[k]`) if it is not evaluated yet.
    pub fn gain(
        &mut self,
        k: usize,
        sensor: &dyn Sensor,
        belief: &dyn Belief,
        reach: &Reachability,
    ) -> f64 {
        if self.gains[k].is_nan() {
            let (gain, heading) = self.evaluate(sensor, belief, reach, self.cells[k]);
            self.gains[k] = gain;
            self.headings[k] = heading;
        }
        self.gains[k]
    }

    /// Whether the stored gains belong to exactly these candidates.
    pub fn aligned_with(&self, candidates: &CandidateSet) -> bool {
        self.cells == candidates.cells()
    }

    /// Evaluate `cell` as seen on arrival along `reach`'s path, and record it as the next
    /// candidate (gain and heading); returns the gain.
    pub(crate) fn record(
        &mut self,
        sensor: &dyn Sensor,
        belief: &dyn Belief,
        reach: &Reachability,
        robot: usize,
        cell: u32,
    ) -> f64 {
        let (gain, heading) = self.evaluate(sensor, belief, reach, cell);
        self.push(cell, gain, heading, robot);
        gain
    }

    /// Append a candidate.
    pub(crate) fn push(&mut self, cell: u32, gain: f64, heading: f64, robot: usize) {
        self.cells.push(cell);
        self.gains.push(gain);
        self.headings.push(heading);
        self.reachers.push(robot as u32);
    }

    /// `(I(p), heading)` of `cell` on arrival along `reach`'s path.
    fn evaluate(
        &mut self,
        sensor: &dyn Sensor,
        belief: &dyn Belief,
        reach: &Reachability,
        cell: u32,
    ) -> (f64, f64) {
        let known = belief.known();
        let heading = if sensor.is_omnidirectional() {
            0.0
        } else {
            arrival_heading(known, reach, cell)
        };
        let pose = Pose::new(known.cell(cell as usize), heading);
        (self.gain_at(sensor, belief, pose), heading)
    }

    /// `I(p)` of a scan from `pose`, its rays gated by the open frontier cells of the last
    /// decision (module doc; ungated before the first).
    pub fn gain_at(&mut self, sensor: &dyn Sensor, belief: &dyn Belief, pose: Pose) -> f64 {
        let known = belief.known();
        let open = &self.open;
        let gate = |i: usize| passable(known, open, i);
        let gate: Option<&dyn Fn(usize) -> bool> = if self.open_cells.is_empty() {
            None
        } else {
            Some(&gate)
        };
        information_gain_gated(sensor, belief, &self.model, pose, gate, &mut self.scratch)
    }
}

/// Whether a predicted ray may pass the Unknown cell `i` (module doc): it may unless it
/// borders the known map (8-neighbours) without bordering an open frontier cell (`open`).
fn passable(known: &Grid<grid::Occ>, open: &[bool], i: usize) -> bool {
    let (w, h) = (known.width(), known.height());
    let (x, y) = (i % w, i / w);
    let data = known.data();
    let mut borders_known = false;
    for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
        for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
            let j = ny * w + nx;
            if j == i || data[j] == grid::Occ::Unknown {
                continue;
            }
            if open[j] {
                return true;
            }
            borders_known = true;
        }
    }
    !borders_known
}

/// The heading on arrival at `cell` along `reach`'s shortest path: the direction of its last
/// step; at the start itself, towards the mean of its Unknown 8-neighbours (0 if none).
pub fn arrival_heading(known: &Grid<grid::Occ>, reach: &Reachability, cell: u32) -> f64 {
    let at = known.cell(cell as usize);
    if let Some(from) = reach.predecessor(cell as usize) {
        let from = known.cell(from);
        return f64::from(at.y - from.y).atan2(f64::from(at.x - from.x));
    }
    let (mut sx, mut sy) = (0.0, 0.0);
    for n in known.neighbours8(cell as usize) {
        if known[n].is_unknown() {
            let c = known.cell(n);
            sx += f64::from(c.x - at.x);
            sy += f64::from(c.y - at.y);
        }
    }
    if sx == 0.0 && sy == 0.0 {
        0.0
    } else {
        f64::atan2(sy, sx)
    }
}

/// Fill `out` with those of `n` reachable samples near frontiers that have a positive gain
/// (or, failing that, the reachable frontier cells), and their gains in `ctx.memory.dt`.
pub fn generate(ctx: &mut DecisionCtx<'_>, n: usize, out: &mut CandidateSet) {
    let mut st = std::mem::take(&mut ctx.memory.dt);
    st.clear();
    fill(ctx, n, out, &mut st);
    ctx.memory.dt = st;
}

fn fill(ctx: &mut DecisionCtx<'_>, n: usize, out: &mut CandidateSet, st: &mut State) {
    let m = ctx.robots.len();
    let mut any = false;
    for r in (0..m).filter(|&r| ctx.deciding[r]) {
        ctx.planner.full(r, ctx.robots[r], ctx.known, ctx.upkeep);
        any = true;
    }
    let lists = ctx.lists;
    let frontiers = &ctx.upkeep.frontiers;
    let planner = &*ctx.planner;
    let reacher = |i: usize| (0..m).find(|&r| ctx.deciding[r] && planner.map(r).is_settled(i));
    // The frontiers that count (module doc): unlisted and reachable by a deciding robot.
    let open = |c: u32| !lists.is_excluded(c) && reacher(c as usize).is_some();
    if !any || !frontiers.cells().iter().any(|&c| open(c)) {
        return;
    }
    let len = ctx.known.len();
    for &c in frontiers.cells() {
        if open(c) {
            st.mark_open(len, c);
        }
    }
    // The distance transform runs on the open frontier cells' bounding box grown by the
    // range (clipped): every cell within range of one lies in it, and every one too, so
    // distances there are exact.
    let (w, h) = (ctx.known.width(), ctx.known.height());
    let range = ctx.sensor_range_cells.max(0.0);
    let r2 = range * range;
    let grow = range.ceil().min((w + h) as f64) as usize;
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for &c in frontiers.cells() {
        if open(c) {
            let (x, y) = (c as usize % w, c as usize / w);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
    }
    let (x0, y0) = (x0.saturating_sub(grow), y0.saturating_sub(grow));
    let (x1, y1) = ((x1 + grow).min(w - 1), (y1 + grow).min(h - 1));
    let (bw, bh) = (x1 - x0 + 1, y1 - y0 + 1);
    let to_map = |j: usize| (y0 + j / bw) * w + x0 + j % bw;
    // Reuse the buffer's allocation whatever the box size.
    let mut buf = std::mem::replace(&mut st.near, Grid::new(0, 0, 0.0)).into_vec();
    buf.clear();
    buf.resize(bw * bh, f64::INFINITY);
    st.near = Grid::from_vec(bw, bh, buf).unwrap_or_else(|| Grid::new(bw, bh, f64::INFINITY));
    edt_squared_into(
        bw,
        bh,
        |j| {
            let i = to_map(j);
            frontiers.contains(i) && open(i as u32)
        },
        &mut st.near,
        &mut st.edt,
    );
    st.eligible.clear();
    for (j, &d2) in st.near.data().iter().enumerate() {
        let i = to_map(j);
        if d2 <= r2
            && !lists.is_excluded(i as u32)
            && !(0..m).any(|r| ctx.deciding[r] && ctx.robots[r] as usize == i)
            && reacher(i).is_some()
        {
            st.eligible.push(i as u32);
        }
    }

    // Partial Fisher–Yates: n draws without replacement. Gains are evaluated in draw order
    // until the first positive one (samples of gain 0 before it are dropped); the rest wait
    // for the utility assigner (module doc).
    let len = st.eligible.len();
    let draws = len.min(n);
    for k in 0..draws {
        let j = ctx.rng.random_range(k..len);
        st.eligible.swap(k, j);
    }
    let mut found = false;
    for k in 0..draws {
        let c = st.eligible[k];
        let Some(r) = reacher(c as usize) else {
            continue;
        };
        if found {
            out.insert(c);
            st.push(c, f64::NAN, f64::NAN, r);
            continue;
        }
        let (gain, heading) = st.evaluate(ctx.sensor, ctx.belief, planner.map(r), c);
        if gain > 0.0 {
            out.insert(c);
            st.push(c, gain, heading, r);
            found = true;
        }
    }
    if found {
        return;
    }
    // Fallback: the reachable, unlisted frontier cells themselves.
    st.fell_back = true;
    for &c in frontiers.cells() {
        if lists.is_excluded(c) || out.contains(c as usize) {
            continue;
        }
        if let Some(r) = reacher(c as usize) {
            out.insert(c);
            st.record(ctx.sensor, ctx.belief, planner.map(r), r, c);
        }
    }
}
