//! What one decision sees: the team, the shared belief, and per-robot reachability maps.
//!
//! A decision is the middle of the one exploration loop (ARCHITECTURE.md "Bird's-eye
//! view"): candidates are generated from the belief, then an assigner gives goals to the
//! robots that decide.
//! Costs come from one reachability map per robot per decision (Holz et al.'s
//! "path search without goal specification"), computed lazily: a nearest-frontier
//! query stops at the first candidate it settles, and the team assigners grow each
//! robot's search, guided toward the candidates, bucket by bucket only as far as their rule
//! needs (see
//! [`crate::assign::costs`]); the questions "reachable at all?" are answered by one flood
//! fill shared by the robots of a component.
//!
//! [`decide`] is that middle, written once: the simulation's loop and the ROS node's
//! explorer both call it, so a strategy decides by the same code path in both.

use grid::{Grid, Occ};
use rand_pcg::Pcg64Mcg;

use crate::assign::AssignerKind;
use crate::bits::CellBits;
use crate::candidates::{CandidateKind, CandidateSet};
use crate::frontier::Region;
use crate::plan::component::Component;
use crate::plan::reachability::Reachability;
use crate::upkeep::FrontierUpkeep;

/// How far each robot's reachability map has been computed in the current decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Extent {
    /// Not computed for this decision.
    Stale,
    /// Computed until some goal was settled: costs are valid for settled cells only.
    Partial,
    /// A resumable search, settled bucket by bucket so far.
    Growing,
    /// Every reachable cell has its cost.
    Full,
}

/// The id of [`Planner::grow_unguided`]'s searches among `guided_toward`'s.
const UNGUIDED: u64 = u64::MAX;

/// Per-robot reachability maps, reused across decisions (no allocation in steady state).
pub struct Planner {
    maps: Vec<Reachability>,
    extent: Vec<Extent>,
    /// Per robot: the subset of the candidates its growing search was guided toward
    /// ([`grow_toward`](Self::grow_toward)'s id), `None` if every candidate.
    guided_toward: Vec<Option<u64>>,
    /// The reachable set of one robot's cell, shared by the robots of its component.
    component: Component,
    /// The robot the component was filled from in this decision (`None`: stale).
    component_of: Option<usize>,
    width: usize,
    height: usize,
}

impl Planner {
    /// Buffers for `robots` robots on a `width × height` map.
    pub fn new(width: usize, height: usize, robots: usize) -> Self {
        Self {
            maps: (0..robots)
                .map(|_| Reachability::new(width, height))
                .collect(),
            extent: vec![Extent::Stale; robots],
            guided_toward: vec![None; robots],
            component: Component::new(width, height),
            component_of: None,
            width,
            height,
        }
    }

    /// Number of robots served.
    pub fn robots(&self) -> usize {
        self.maps.len()
    }

    /// Grid size `(width, height)` the buffers are for.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Forget all maps: the belief or the robots moved since they were computed. A map not
    /// searched again in this decision then settles nothing ([`Reachability::forget`]),
    /// so a rule reading every robot's map never reads an earlier decision's costs.
    pub fn invalidate(&mut self) {
        for map in &mut self.maps {
            map.forget();
        }
        self.extent.fill(Extent::Stale);
        self.guided_toward.fill(None);
        self.component_of = None;
    }

    /// Robot `r`'s full reachability map from cell `from` over traversable cells.
    pub fn full(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
    ) -> &Reachability {
        let pass = |i| upkeep.is_traversable(known, i);
        match self.extent[r] {
            Extent::Full => {}
            Extent::Growing => {
                self.maps[r].advance(usize::MAX, pass);
            }
            Extent::Stale | Extent::Partial => self.maps[r].compute(from as usize, pass),
        }
        self.extent[r] = Extent::Full;
        &self.maps[r]
    }

    /// Grow every robot's search (robot `r` from `froms[r]`, guided toward the goals and
    /// listing only them: [`Reachability::begin_goals`]) until it has settled every cell
    /// of `goals` it can reach (a little beyond), or every cell it can reach: the searches
    /// an assigner that needs each robot's cost to every goal (MA) would grow one after
    /// the other, run side by side on rayon's threads. The maps are independent, so each
    /// is the one the sequential growth leaves, whatever the thread count. Called from a
    /// thread of a rayon pool (a bench's trials) or inside [`batched`] (a vector
    /// environment's steps), which keep the cores busy already, they grow one after the
    /// other, so that no run's wall time includes another's stolen work; so they do when
    /// rayon has one thread, which would only be woken and waited for. A search already
    /// begun in this decision is grown on; robots that reach no goal are left as they are.
    pub fn settle_goals(
        &mut self,
        froms: &[u32],
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
        goals: &[u32],
    ) {
        use rayon::prelude::*;
        let m = self.maps.len().min(froms.len());
        let want: Vec<usize> = (0..m)
            .map(|r| {
                let reach = self.component(r, froms[r], known, upkeep);
                goals
                    .iter()
                    .filter(|&&g| reach.contains(g as usize))
                    .count()
            })
            .collect();
        for r in 0..m {
            if matches!(self.extent[r], Extent::Stale | Extent::Partial) {
                self.guided_toward[r] = None; // begun below toward every candidate
            }
        }
        let pass = |i| upkeep.is_traversable(known, i);
        let wanted = |(r, (_, extent)): &(usize, (&mut Reachability, &mut Extent))| {
            want[*r] > 0 && **extent != Extent::Full
        };
        let grow = |(r, (map, extent)): (usize, (&mut Reachability, &mut Extent))| {
            let begun = matches!(*extent, Extent::Stale | Extent::Partial);
            if begun {
                map.begin_goals(froms[r] as usize, pass, goals);
            }
            // Listing only the goals (and the start), the search's settled list holds
            // every goal it has settled; a search begun before lists every cell, and its
            // goals are counted each time it has settled as many new cells as there are
            // goals. Either way counting costs O(1) per settled cell.
            let lists_goals = begun && map.lists_only_goals();
            let mut counted = 0;
            loop {
                let done = map.advance(map.next_bucket(), pass);
                if done {
                    *extent = Extent::Full;
                    break;
                }
                *extent = Extent::Growing;
                let settled = map.settled().len();
                let due = if lists_goals {
                    settled >= want[r] && settled > counted
                } else {
                    settled - counted >= goals.len()
                };
                if due {
                    counted = settled;
                    let found = goals.iter().filter(|&&g| map.is_settled(g as usize));
                    if found.count() >= want[r] {
                        break;
                    }
                }
            }
        };
        let (maps, extents) = (&mut self.maps[..m], &mut self.extent[..m]);
        if rayon::current_thread_index().is_some()
            || rayon::current_num_threads() == 1
            || BATCHED.get()
        {
            let each = maps.iter_mut().zip(extents.iter_mut()).enumerate();
            each.filter(wanted).for_each(grow);
        } else {
            let each = maps.par_iter_mut().zip(extents.par_iter_mut()).enumerate();
            each.filter(wanted).for_each(grow);
        }
    }

    /// Grow robot `r`'s search from cell `from` until every goal of cost below
    /// `through + 1` is settled (a new resumable search guided toward `goals` if this
    /// decision has none yet, see [`Reachability::begin_guided`]; nothing if its map is
    /// full). Returns whether its map is complete. Every call of a decision gives the same
    /// goals, the candidates; a search [`grow_toward`](Self::grow_toward) guided toward
    /// some of them only is begun again.
    pub fn grow(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
        goals: &[u32],
        through: usize,
    ) -> bool {
        self.grow_guided(r, from, (known, upkeep), (goals, None), through)
    }

    /// [`grow`](Self::grow) guided toward `goals`, a subset of the candidates named `id`
    /// (ids differ between subsets within a decision): a rule that may take only some of
    /// the candidates searches toward those. A search begun toward another set is begun
    /// again, so that every goal given is settled below the bucket.
    pub fn grow_toward(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
        (goals, id): (&[u32], u64),
        through: usize,
    ) -> bool {
        self.grow_guided(r, from, (known, upkeep), (goals, Some(id)), through)
    }

    /// [`grow`](Self::grow) unguided: a new resumable search with no guide if this
    /// decision has none begun so, then grown until every cell of cost below `through + 1`
    /// is settled. For a rule that wants the few candidates nearest the robot among many,
    /// where setting a guide costs more than it saves
    /// ([`Reachability::nearest_guided`]); a later [`grow`](Self::grow) begins a guided
    /// search again.
    pub fn grow_unguided(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
        through: usize,
    ) -> bool {
        self.grow_guided(r, from, (known, upkeep), (&[], Some(UNGUIDED)), through)
    }

    fn grow_guided(
        &mut self,
        r: usize,
        from: u32,
        (known, upkeep): (&Grid<Occ>, &FrontierUpkeep),
        (goals, id): (&[u32], Option<u64>),
        through: usize,
    ) -> bool {
        let pass = |i| upkeep.is_traversable(known, i);
        match self.extent[r] {
            Extent::Full => return true,
            Extent::Growing if self.guided_toward[r] == id => {}
            Extent::Growing | Extent::Stale | Extent::Partial => {
                if id == Some(UNGUIDED) {
                    self.maps[r].begin(from as usize, pass);
                } else {
                    self.maps[r].begin_guided(from as usize, pass, goals);
                }
                self.guided_toward[r] = id;
                self.extent[r] = Extent::Growing;
            }
        }
        let done = self.maps[r].advance(through, pass);
        if done {
            self.extent[r] = Extent::Full;
        }
        done
    }

    /// The cells robot `r` (at `from`) can reach at all: one flood fill per decision,
    /// shared by every robot in the same component of passable cells.
    pub fn component(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
    ) -> &Component {
        debug_assert_eq!(known.len(), upkeep.trav.passable().len());
        let pass = upkeep.trav.passable();
        let fresh = match self.component_of {
            Some(q) if q == r => true,
            Some(_) => self.component.same_from(from as usize, pass),
            None => false,
        };
        if !fresh {
            self.component.compute(from as usize, pass);
            self.component_of = Some(r);
        }
        &self.component
    }

    /// The goal nearest to robot `r` (at `from`) by path, stopping the search as soon as one
    /// is settled; `None` if no goal is reachable. The goals are the cells with
    /// `is_goal`, all of them among `cells`, toward which the search is guided.
    pub fn nearest(
        &mut self,
        r: usize,
        from: u32,
        known: &Grid<Occ>,
        upkeep: &FrontierUpkeep,
        cells: &[u32],
        is_goal: impl Fn(usize) -> bool,
    ) -> Option<u32> {
        let pass = |i| upkeep.is_traversable(known, i);
        let found = self.maps[r].nearest_guided(from as usize, pass, cells, is_goal);
        self.extent[r] = Extent::Partial;
        found.map(|g| g as u32)
    }

    /// Whether robot `r` has a resumable or full search in this decision (see
    /// [`grow`](Self::grow)).
    pub fn is_searching(&self, r: usize) -> bool {
        matches!(self.extent[r], Extent::Growing | Extent::Full)
    }

    /// Robot `r`'s reachability map as last computed (full or partial).
    pub fn map(&self, r: usize) -> &Reachability {
        &self.maps[r]
    }

    /// Write robot `r`'s path to `goal` (start and goal included) into `out`; false if the
    /// goal was not settled by the last search of robot `r`.
    pub fn path(&self, r: usize, goal: u32, out: &mut Vec<u32>) -> bool {
        self.extent[r] != Extent::Stale && self.maps[r].path_to(goal as usize, out)
    }
}

thread_local! {
    /// Whether this thread runs one of several runs side by side ([`batched`]).
    static BATCHED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Run `f` as one of several runs going on side by side on the machine's threads (a
/// vector environment's steps): its decisions then grow their searches one after the
/// other instead of spreading them over rayon's threads, which the other runs keep busy.
pub fn batched<R>(f: impl FnOnce() -> R) -> R {
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            BATCHED.set(self.0);
        }
    }
    let _restore = Restore(BATCHED.replace(true));
    f()
}

/// Goals that must not be chosen again: Yamauchi's lists of visited and inaccessible
/// frontiers. A reached goal that is still a frontier after sensing from it cannot be
/// explored from there, so choosing it again would loop forever.
#[derive(Clone, Debug, Default)]
pub struct GoalLists {
    /// The listed goals as bits, allocated by the first listing: until a goal is listed,
    /// the test that every frontier cell goes through touches no memory of the map's size.
    excluded: CellBits,
    cells: usize,
    /// Goals reached and sensed from, in order.
    pub visited: Vec<u32>,
    /// Goals given up as inaccessible (no progress for the time limit), in order.
    pub inaccessible: Vec<u32>,
}

impl GoalLists {
    /// Empty lists for a map of `cells` cells.
    pub fn new(cells: usize) -> Self {
        Self {
            excluded: CellBits::default(),
            cells,
            visited: Vec::new(),
            inaccessible: Vec::new(),
        }
    }

    /// List `goal` as excluded; false if it already was.
    fn exclude(&mut self, goal: u32) -> bool {
        if self.excluded.is_empty() {
            self.excluded = CellBits::new(self.cells);
        }
        let fresh = !self.excluded.contains(goal as usize);
        if fresh {
            self.excluded.insert(goal as usize);
        }
        fresh
    }

    /// Record that a robot reached `goal` and sensed there.
    pub fn mark_visited(&mut self, goal: u32) {
        if self.exclude(goal) {
            self.visited.push(goal);
        }
    }

    /// Record that `goal` could not be reached.
    pub fn mark_inaccessible(&mut self, goal: u32) {
        if self.exclude(goal) {
            self.inaccessible.push(goal);
        }
    }

    /// Whether `cell` is on either list.
    #[inline]
    pub fn is_excluded(&self, cell: u32) -> bool {
        self.excluded.contains(cell as usize)
    }
}

/// Everything a candidate generator and an assigner may look at or use in one decision.
pub struct DecisionCtx<'a> {
    /// The shared belief, classified.
    pub known: &'a Grid<Occ>,
    /// Traversability and the incrementally kept frontier cells.
    pub upkeep: &'a mut FrontierUpkeep,
    /// Per-robot reachability maps.
    pub planner: &'a mut Planner,
    /// Cell (flat index) of every robot.
    pub robots: &'a [u32],
    /// Whether each robot takes part in this decision (others keep `goals[r]`).
    pub deciding: &'a [bool],
    /// Current goal of every robot (`None` for those without one).
    pub goals: &'a [Option<u32>],
    /// Goals that must not be chosen.
    pub lists: &'a GoalLists,
    /// Metres per cell.
    pub resolution: f64,
    /// Sensor range in cells.
    pub sensor_range_cells: f64,
    /// The run's seeded random stream.
    pub rng: &'a mut Pcg64Mcg,
    /// The shared belief itself (occupancy probabilities, for information gain).
    pub belief: &'a dyn sense::Belief,
    /// The robots' sensor (for simulated scans on the belief).
    pub sensor: &'a dyn sense::Sensor,
    /// State that candidate generators and assigners keep across decisions.
    pub memory: &'a mut Memory,
}

/// State kept across decisions by the pieces that need it (buffers, cluster centres,
/// segmentations, samples). Each piece owns its part; all start empty.
#[derive(Default)]
pub struct Memory {
    /// Region buffers of the centroid generator.
    pub centroids: crate::candidates::centroids::Scratch,
    /// Free edges and k-means state of the RFE generator.
    pub rfe: crate::candidates::rfe::State,
    /// Visibility buffers of the coverage (CC) generator.
    pub coverage: crate::candidates::coverage::State,
    /// Sampled poses and their information gain (decision-theoretic generator).
    pub dt: crate::candidates::dt_samples::State,
    /// Utilities of the greedy-with-utility assigner.
    pub greedy_utility: crate::assign::greedy_utility::State,
    /// Clusters and routes of the MTSP assigner.
    pub mtsp: crate::assign::mtsp::State,
    /// Cluster centres of Solanas & Garcia's assigner, kept between decisions.
    pub sga: crate::assign::sga::State,
    /// The segmentation of the belief used by the same-segment-first assigner.
    pub segments: crate::segment::State,
}

/// What assigners carry from one decision to the next and so changes what they decide
/// later: Solanas & Garcia's cluster centres and the MTSP assigner's (the others keep only
/// buffers). A proposal that is only asked for ([`Memory::put_back`]) must not leave it
/// changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Kept {
    sga_centres: Vec<crate::kmeans::Point>,
    mtsp_centres: Vec<crate::kmeans::Point>,
}

impl Memory {
    /// A copy of what the assigners carry between decisions.
    pub fn kept(&self) -> Kept {
        Kept {
            sga_centres: self.sga.centres().to_vec(),
            mtsp_centres: self.mtsp.centres().to_vec(),
        }
    }

    /// Put `kept` back as what the assigners carry, returning what they carried.
    pub fn put_back(&mut self, kept: Kept) -> Kept {
        Kept {
            sga_centres: self.sga.replace_centres(kept.sga_centres),
            mtsp_centres: self.mtsp.replace_centres(kept.mtsp_centres),
        }
    }
}

/// A goal chosen for one robot, with its path cost in cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Goal {
    /// The goal cell (flat index).
    pub cell: u32,
    /// Length of the shortest path to it, in cells.
    pub cost: f64,
}

/// The candidates of a decision and the buffers [`decide`] reuses across decisions.
#[derive(Clone, Debug, Default)]
pub struct Offer {
    /// The generator's candidates at the last decision, in its order.
    pub candidates: CandidateSet,
    /// The candidates in frontier regions of the minimum size, when that narrows them.
    narrowed: CandidateSet,
    regions: Vec<Region>,
    /// Frontier cells left out at the last decision because their region is below the
    /// minimum size.
    pub too_small: usize,
}

impl Offer {
    /// Buffers for a map of `cells` cells.
    pub fn new(cells: usize) -> Self {
        Self {
            candidates: CandidateSet::new(cells),
            // Allocated on first use: only a minimum region size over all frontiers needs it.
            narrowed: CandidateSet::default(),
            regions: Vec::new(),
            too_small: 0,
        }
    }
}

/// One decision of the exploration loop (which exists once; ARCHITECTURE.md "Bird's-eye
/// view"): the generator `candidates` fills `offer.candidates`; frontier regions shorter
/// than `min_region_m` metres (explore_lite's `min_frontier_size`; 0 keeps every region)
/// are not offered; then `assigner`, if given, writes the deciding robots' goals to `out`
/// (without one, the caller chooses among the candidates).
///
/// The minimum region size acts on the generators that offer frontier cells or regions:
/// for all frontier cells it drops the cells of smaller regions (counted in
/// `offer.too_small`), for region centroids it raises the generator's own minimum; the
/// other generators choose their candidates by their papers' rules and are left as they are.
pub fn decide(
    ctx: &mut DecisionCtx<'_>,
    candidates: CandidateKind,
    assigner: Option<AssignerKind>,
    min_region_m: f64,
    offer: &mut Offer,
    out: &mut [Option<Goal>],
) {
    let kind = match candidates {
        CandidateKind::RegionCentroids { min_size_m } if min_region_m > 0.0 => {
            CandidateKind::RegionCentroids {
                min_size_m: min_size_m.max(min_region_m),
            }
        }
        other => other,
    };
    kind.generate(ctx, &mut offer.candidates);
    offer.too_small = 0;
    let min_cells = grid::units::cells(min_region_m, ctx.resolution)
        .ceil()
        .max(1.0) as usize;
    let narrow = kind == CandidateKind::AllFrontiers && min_cells > 1;
    if narrow {
        if !offer.narrowed.fits(ctx.known.len()) {
            offer.narrowed = CandidateSet::new(ctx.known.len());
        }
        ctx.upkeep.regions(ctx.known.width(), 1, &mut offer.regions);
        offer.narrowed.clear();
        for r in &offer.regions {
            if r.cells.len() >= min_cells {
                for &c in &r.cells {
                    if offer.candidates.contains(c as usize) {
                        offer.narrowed.insert(c);
                    }
                }
            } else {
                offer.too_small += r.cells.len();
            }
        }
    }
    if let Some(assigner) = assigner {
        let offered = if narrow {
            &offer.narrowed
        } else {
            &offer.candidates
        };
        assigner.assign(ctx, offered, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn batched_marks_its_thread_until_it_returns_or_unwinds() {
        assert!(!BATCHED.get());
        assert!(batched(|| BATCHED.get() && batched(|| BATCHED.get())));
        assert!(!BATCHED.get(), "nested calls restore the mark");
        let r = std::panic::catch_unwind(|| batched(|| panic!("in a run")));
        assert!(r.is_err());
        assert!(!BATCHED.get(), "a panic restores the mark");
        let other = std::thread::spawn(|| BATCHED.get());
        assert!(
            !batched(|| other.join().unwrap_or(true)),
            "only this thread is marked"
        );
    }

    proptest! {
        /// Goals listed in any order: the lists hold each goal once, on the list it was first
        /// put on, and exactly the listed cells are excluded (a `bool` per cell as oracle).
        #[test]
        fn lists_behave_as_a_bool_per_cell(
            ops in proptest::collection::vec((0u32..30, any::<bool>()), 0..60)
        ) {
            let mut lists = GoalLists::new(30);
            let mut excluded = [false; 30];
            let (mut visited, mut inaccessible) = (Vec::new(), Vec::new());
            for (goal, reached) in ops {
                if reached {
                    lists.mark_visited(goal);
                } else {
                    lists.mark_inaccessible(goal);
                }
                if !excluded[goal as usize] {
                    excluded[goal as usize] = true;
                    if reached {
                        visited.push(goal);
                    } else {
                        inaccessible.push(goal);
                    }
                }
                for (c, &e) in excluded.iter().enumerate() {
                    prop_assert_eq!(lists.is_excluded(c as u32), e);
                }
            }
            prop_assert_eq!(&lists.visited, &visited);
            prop_assert_eq!(&lists.inaccessible, &inaccessible);
        }
    }
}
