//! Robot → candidate path costs found only as far as a decision needs them.
//!
//! The coordinated assigners were written on a full robot × candidate cost matrix, one
//! complete reachability map per robot per decision. But greedy needs only the pairs
//! cheaper than the ones it picks, GA and HA a few cheapest goals per robot, MinPos the
//! robots' distances up to the goal it settles on: each robot's Dijkstra search is
//! resumable ([`Reachability::begin`](crate::Reachability::begin)) and grown bucket by
//! bucket (one cell-step of cost per bucket) until the rule can decide. When a search has
//! settled bucket k, every candidate of cost below k + 1 has its final cost, the same bits
//! a full search gives (each cost is the minimum over final neighbour costs), so a rule that
//! reasons "every pair not seen yet costs at least k + 1" decides exactly as on the full
//! matrix. The cost of a decision then follows the area within the chosen goals, not the
//! map. The searches are guided toward the candidates
//! ([`Reachability::begin_guided`](crate::Reachability::begin_guided)): the same costs and
//! bounds, but when the candidates are few (RFE's representatives, CC's covering cells) a
//! robot's search to goals far away covers the way to them, not the disk around the robot.
//!
//! A search also ends, for the assigners, once it has settled every candidate its robot can
//! reach at all: without that, a robot that must know it has found all its goals (fewer
//! free goals than robots, or goals behind walls no robot reaches) searched the whole map
//! past its last goal. The count comes from the decision's flood fill of the robot's
//! component ([`Planner::component`](crate::decision::Planner::component)), asked only
//! once a search has grown past [`COUNT_FROM`] cells (or an eighth of a smaller map), so
//! that small searches never pay for it. The pairs found are the same either way; only the
//! cells beyond the last goal are left unsearched.

use crate::candidates::CandidateSet;
use crate::decision::DecisionCtx;

/// One robot → candidate pair found by a search: its path cost and the candidate's column
/// (position in [`CandidateSet::cells`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair {
    /// Path cost in cells.
    pub cost: f64,
    /// Candidate column.
    pub col: usize,
}

/// Settled cells after which a growing search asks how many candidates its robot can
/// reach (a flood fill of its component, unless the decision has one already).
pub const COUNT_FROM: usize = 1 << 14;

/// The next id of a set of goals guided toward ([`LazyCosts::guide_toward`]); ids are
/// only compared, so results do not depend on them.
static NEXT_GUIDE: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// Per robot, the candidates its search has settled so far, in the order settled.
#[derive(Clone, Debug, Default)]
pub struct LazyCosts {
    found: Vec<Vec<Pair>>,
    /// Per robot: how much of its search's settled list has been looked at, and which
    /// search that was ([`Reachability::search_id`](crate::Reachability::search_id)).
    scanned: Vec<usize>,
    scanned_search: Vec<u32>,
    /// Per robot: how many candidates its component holds (`None`: not counted yet).
    reachable: Vec<Option<usize>>,
    /// Whether the searches are guided toward the candidates.
    guided: bool,
    /// The goals searches begun from now on are guided toward and the set's id, if
    /// `toward_id` is set (else every candidate; see [`guide_toward`](Self::guide_toward)).
    toward: Vec<u32>,
    toward_id: Option<u64>,
}

impl LazyCosts {
    /// Forget the last decision's pairs; ready for `robots` robots, whose searches are
    /// guided toward the candidates if `guided` (a rule that needs every candidate's cost,
    /// as MA's, gains nothing from guidance and pays for its bound).
    pub fn reset(&mut self, robots: usize, guided: bool) {
        self.guided = guided;
        self.found.resize_with(robots, Vec::new);
        self.found.truncate(robots);
        for f in &mut self.found {
            f.clear();
        }
        self.scanned.clear();
        self.scanned.resize(robots, 0);
        self.scanned_search.clear();
        self.scanned_search.resize(robots, 0);
        self.reachable.clear();
        self.reachable.resize(robots, None);
        self.toward.clear();
        self.toward_id = None;
    }

    /// Guide the searches grown from now on toward `goals` (a subset of the candidates)
    /// instead of every candidate: for a rule that wants a robot's cheapest goal among
    /// those it may still take (GA's free goals), the goals it may not take no longer hold
    /// the bound near 0 around the robot. The costs, and the goals of the set settled below
    /// a bucket, are the same; a search begun toward another set is begun again.
    pub fn guide_toward(&mut self, goals: impl IntoIterator<Item = u32>) {
        self.toward.clear();
        self.toward.extend(goals);
        // unique in the process, so that sets of two assigners asked in one decision (a
        // Python policy comparing baselines) never share an id
        self.toward_id = Some(NEXT_GUIDE.fetch_add(1, std::sync::atomic::Ordering::Relaxed));
    }

    /// Grow robot `r`'s search through bucket `through` (every candidate of cost below
    /// `through + 1` settled) and record the candidates newly settled. Returns whether every
    /// pair of robot `r` is known: its search is complete, or has settled every candidate
    /// robot `r` can reach (then the search may stop short of `through`).
    pub fn grow(
        &mut self,
        ctx: &mut DecisionCtx<'_>,
        candidates: &CandidateSet,
        r: usize,
        through: usize,
    ) -> bool {
        if self.has_all(r) {
            return true;
        }
        let (from, known, upkeep) = (ctx.robots[r], ctx.known, &*ctx.upkeep);
        let done = match (self.guided, self.toward_id) {
            (false, _) => ctx.planner.grow(r, from, known, upkeep, &[], through),
            (true, Some(id)) => {
                let goals = (&self.toward[..], id);
                ctx.planner
                    .grow_toward(r, from, known, upkeep, goals, through)
            }
            (true, None) => {
                let goals = candidates.cells();
                ctx.planner.grow(r, from, known, upkeep, goals, through)
            }
        };
        let map = ctx.planner.map(r);
        let settled = map.settled();
        if self.scanned_search[r] != map.search_id() {
            // the planner began this robot's search (again: toward another set of goals)
            self.scanned[r] = 0;
            self.scanned_search[r] = map.search_id();
            self.found[r].clear();
        }
        for &c in &settled[self.scanned[r]..] {
            if let Some(col) = candidates.index_of(c as usize) {
                let cost = map.cost(c as usize).unwrap_or(f64::INFINITY);
                self.found[r].push(Pair { cost, col });
            }
        }
        self.scanned[r] = settled.len();
        let count_from = COUNT_FROM.min(ctx.known.len() / 8);
        if !done && self.reachable[r].is_none() && map.searched() >= count_from {
            let reach = ctx
                .planner
                .component(r, ctx.robots[r], ctx.known, ctx.upkeep);
            let n = candidates
                .cells()
                .iter()
                .filter(|&&c| reach.contains(c as usize))
                .count();
            self.reachable[r] = Some(n);
        }
        done || self.has_all(r)
    }

    /// Whether robot `r`'s search has settled every candidate its robot can reach (as far
    /// as counted).
    fn has_all(&self, r: usize) -> bool {
        self.reachable[r] == Some(self.found[r].len())
    }

    /// Grow robot `r`'s search by at least one bucket (to its end if `to_end`). Returns
    /// whether it is complete.
    pub fn step(
        &mut self,
        ctx: &mut DecisionCtx<'_>,
        candidates: &CandidateSet,
        r: usize,
        to_end: bool,
    ) -> bool {
        let through = if to_end {
            usize::MAX
        } else {
            self.next_bucket(ctx, r)
        };
        self.grow(ctx, candidates, r, through)
    }

    /// The first bucket robot `r`'s search has not settled (0 before it starts): every
    /// pair of robot `r` not found yet costs at least this much, or is unreachable.
    pub fn next_bucket(&self, ctx: &DecisionCtx<'_>, r: usize) -> usize {
        if self.scanned[r] == 0 && self.found[r].is_empty() && !ctx.planner.is_searching(r) {
            0
        } else {
            ctx.planner.map(r).next_bucket()
        }
    }

    /// The pairs of robot `r` found so far, in the order settled.
    pub fn found(&self, r: usize) -> &[Pair] {
        &self.found[r]
    }
}
