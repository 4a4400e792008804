//! The A* search against an exhaustive uniform-cost search written independently from the
//! problem statement (slow visibility from `sense::los_visible`, Floyd–Warshall paths in the
//! perceived free space, states as `(cell, Vec<bool>)` in a `BTreeMap`), on tiny random maps.
//! The Floyd–Warshall table depends only on what is perceived, so one search computes it
//! once per perceived set ([`Paths`]), not once per state.

#![allow(clippy::needless_range_loop)] // Floyd–Warshall reads best with indices.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::time::Duration;

use grid::{Cell, Grid, Occ};
use optimal::{ActionSet, Config, HeuristicKind, Problem, SensorModel, Status, heuristic_value};
use proptest::prelude::*;

const TOL: f64 = 1e-7;

/// Whether a step from `a` to neighbour `b` is legal when `ok` says which cells are passable.
fn legal(map: &Grid<Occ>, ok: &dyn Fn(Cell) -> bool, a: Cell, b: Cell) -> bool {
    if !a.is_neighbour8(b) || !map.contains(b) || !ok(b) {
        return false;
    }
    if a.x != b.x && a.y != b.y {
        let s1 = Cell::new(b.x, a.y);
        let s2 = Cell::new(a.x, b.y);
        return (map.contains(s1) && ok(s1)) || (map.contains(s2) && ok(s2));
    }
    true
}

/// All-pairs shortest paths (Floyd–Warshall) over cells where `ok` holds.
fn all_pairs(map: &Grid<Occ>, ok: &dyn Fn(Cell) -> bool) -> Vec<Vec<f64>> {
    let n = map.len();
    let mut d = vec![vec![f64::INFINITY; n]; n];
    for i in 0..n {
        let a = map.cell(i);
        if !ok(a) {
            continue;
        }
        d[i][i] = 0.0;
        for j in 0..n {
            let b = map.cell(j);
            if legal(map, ok, a, b) {
                d[i][j] = if a.x != b.x && a.y != b.y {
                    grid::SQRT2
                } else {
                    1.0
                };
            }
        }
    }
    for k in 0..n {
        for i in 0..n {
            for j in 0..n {
                if d[i][k] + d[k][j] < d[i][j] {
                    d[i][j] = d[i][k] + d[k][j];
                }
            }
        }
    }
    d
}

/// The problem in plain terms: targets and what each cell sees.
struct Plain {
    map: Grid<Occ>,
    targets: Vec<usize>,
    is_target: Vec<bool>,
    /// `sees[p]` = every cell (free, wall, target or not) seen from reachable cell p.
    sees: Vec<Vec<usize>>,
    reach: Vec<bool>,
}

fn plain(map: &Grid<Occ>, start: Cell, model: SensorModel) -> Plain {
    let n = map.len();
    let free = |c: Cell| map.try_get(c).is_some_and(|o| o.is_free());
    let full = all_pairs(map, &free);
    let s = map.index(start);
    let reach: Vec<bool> = (0..n).map(|i| full[s][i].is_finite()).collect();
    let seen = |p: Cell, t: Cell| match model {
        SensorModel::Los(r) => sense::los_visible(map, p, t, r),
        SensorModel::Footprint(r) => (p.dist2(t) as f64) <= r * r,
    };
    let targets: Vec<usize> = (0..n)
        .filter(|&t| map[t].is_free() && (0..n).any(|p| reach[p] && seen(map.cell(p), map.cell(t))))
        .collect();
    let sees = (0..n)
        .map(|p| {
            (0..n)
                .filter(|&c| reach[p] && seen(map.cell(p), map.cell(c)))
                .collect()
        })
        .collect();
    let mut is_target = vec![false; n];
    for &t in &targets {
        is_target[t] = true;
    }
    Plain {
        map: map.clone(),
        targets,
        is_target,
        sees,
        reach,
    }
}

/// Targets perceived in `perceived` (indexed by cell).
fn perceived_targets(pl: &Plain, perceived: &[bool]) -> usize {
    pl.targets.iter().filter(|&&t| perceived[t]).count()
}

/// The all-pairs paths through the perceived reachable free cells, per perceived set.
#[derive(Default)]
struct Paths(HashMap<Vec<bool>, Vec<Vec<f64>>>);

impl Paths {
    /// Floyd–Warshall over the cells perceived in `perceived` that are reachable and free.
    fn get(&mut self, pl: &Plain, perceived: &[bool]) -> &Vec<Vec<f64>> {
        if !self.0.contains_key(perceived) {
            let map = &pl.map;
            let known_free = |c: Cell| {
                map.checked_index(c)
                    .is_some_and(|i| pl.reach[i] && perceived[i])
            };
            self.0
                .insert(perceived.to_vec(), all_pairs(map, &known_free));
        }
        &self.0[perceived]
    }
}

/// The moves from `pos` with `perceived` (indexed by cell) and their costs. A boundary
/// cell is a perceived reachable free cell with an unperceived 8-neighbour of any kind (the
/// paper's "unknown"); when no boundary move perceives a new target, every perceived
/// reachable cell is a move.
fn actions(
    pl: &Plain,
    paths: &mut Paths,
    pos: usize,
    perceived: &[bool],
    set: ActionSet,
) -> Vec<(usize, f64)> {
    let map = &pl.map;
    let known_free = |c: Cell| {
        map.checked_index(c)
            .is_some_and(|i| pl.reach[i] && perceived[i])
    };
    let d = paths.get(pl, perceived);
    let boundary = |i: usize| {
        let c = map.cell(i);
        grid::NEIGHBOURS8.iter().any(|&(dx, dy)| {
            map.checked_index(c.offset(dx, dy))
                .is_some_and(|j| !perceived[j])
        })
    };
    let new_target = |q: usize| pl.sees[q].iter().any(|&c| pl.is_target[c] && !perceived[c]);
    let moves = |only_boundary: bool| -> Vec<(usize, f64)> {
        (0..map.len())
            .filter(|&q| known_free(map.cell(q)) && d[pos][q].is_finite())
            .filter(|&q| !only_boundary || boundary(q))
            .map(|q| (q, d[pos][q]))
            .collect()
    };
    if set == ActionSet::All {
        return moves(false);
    }
    let b = moves(true);
    if b.iter().any(|&(q, _)| new_target(q)) {
        b
    } else {
        moves(false)
    }
}

/// Exhaustive uniform-cost search from (pos, perceived); `None` if the goal is unreachable.
fn oracle(
    pl: &Plain,
    paths: &mut Paths,
    pos: usize,
    perceived: Vec<bool>,
    need: usize,
    set: ActionSet,
) -> Option<f64> {
    assert!(!matches!(set, ActionSet::Clusters { .. }));
    let mut best: BTreeMap<(usize, Vec<bool>), f64> = BTreeMap::new();
    // Priority queue as an ordered set of (cost bits, state).
    let mut open: BTreeSet<(u64, usize, Vec<bool>)> = BTreeSet::new();
    best.insert((pos, perceived.clone()), 0.0);
    open.insert((0f64.to_bits(), pos, perceived));
    while let Some((cbits, p, m)) = open.pop_first() {
        let c = f64::from_bits(cbits);
        if best.get(&(p, m.clone())).is_some_and(|&b| b < c) {
            continue;
        }
        if perceived_targets(pl, &m) >= need {
            return Some(c);
        }
        for (q, step) in actions(pl, paths, p, &m, set) {
            let mut m2 = m.clone();
            for &k in &pl.sees[q] {
                m2[k] = true;
            }
            let c2 = c + step;
            let key = (q, m2.clone());
            if best.get(&key).is_none_or(|&b| c2 < b - 1e-12) {
                best.insert(key, c2);
                open.insert((c2.to_bits(), q, m2));
            }
        }
    }
    None
}

fn initial(pl: &Plain, start: usize) -> Vec<bool> {
    let mut m = vec![false; pl.map.len()];
    for &k in &pl.sees[start] {
        m[k] = true;
    }
    m
}

/// Random maps of `widths` × `heights` cells, each a wall with probability up to
/// `max_density` %, a sensor of either kind with a range from `radii`, a goal from `goals`
/// and a start on a free cell (the first cell, freed, if none is free).
fn arb_case_in(
    widths: std::ops::RangeInclusive<usize>,
    heights: std::ops::RangeInclusive<usize>,
    max_density: u32,
    radii: &'static [f64],
    goals: &'static [f64],
) -> impl Strategy<Value = (Grid<Occ>, Cell, SensorModel, f64)> {
    (
        widths,
        heights,
        0u32..=max_density,
        any::<bool>(),
        0..radii.len(),
        0..goals.len(),
    )
        .prop_flat_map(move |(w, h, density, fp, ri, gi)| {
            proptest::collection::vec(0u32..100, w * h).prop_flat_map(move |rolls| {
                let data: Vec<Occ> = rolls
                    .iter()
                    .map(|&r| {
                        if r < density {
                            Occ::Occupied
                        } else {
                            Occ::Free
                        }
                    })
                    .collect();
                let map = Grid::from_vec(w, h, data).expect("w*h");
                let free: Vec<usize> = (0..w * h).filter(|&i| map[i].is_free()).collect();
                let r = radii[ri];
                let model = if fp {
                    SensorModel::Footprint(r)
                } else {
                    SensorModel::Los(r)
                };
                let g = goals[gi];
                let n = free.len().max(1);
                (0..n).prop_map(move |k| {
                    let mut map = map.clone();
                    let start = if free.is_empty() {
                        map[0] = Occ::Free;
                        map.cell(0)
                    } else {
                        map.cell(free[k])
                    };
                    (map, start, model, g)
                })
            })
        })
}

/// Tiny maps (up to 6 × 5), every goal.
fn arb_case() -> impl Strategy<Value = (Grid<Occ>, Cell, SensorModel, f64)> {
    arb_case_in(
        2..=6,
        2..=5,
        35,
        &[1.0, 1.5, 2.0, 2.3, 3.0, 1.2],
        &[1.0, 0.9, 0.7],
    )
}

/// The root (start cell `s`, what it perceives) and up to `children` of its children under
/// all actions: states the exhaustive search reaches in its first step.
fn early_states(pl: &Plain, s: usize, children: usize) -> Vec<(usize, Vec<bool>)> {
    let m0 = initial(pl, s);
    let mut states = vec![(s, m0.clone())];
    for (q, _) in actions(pl, &mut Paths::default(), s, &m0, ActionSet::All)
        .into_iter()
        .take(children)
    {
        let mut m = m0.clone();
        for &k in &pl.sees[q] {
            m[k] = true;
        }
        states.push((q, m));
    }
    states
}

fn cfg(goal: f64, actions: ActionSet, heuristic: HeuristicKind) -> Config {
    Config {
        goal,
        actions,
        heuristic,
        landmarks: 4,
        ..Config::default()
    }
}

/// Independent check of a returned path: legal steps through perceived free cells,
/// sensing only at the positions, length as reported, goal met.
fn check_solution(pl: &Plain, start: Cell, sol: &optimal::Solution, need: usize) {
    let map = &pl.map;
    let mut m = initial(pl, map.index(start));
    assert_eq!(sol.positions[0], start);
    assert_eq!(sol.path[0], start);
    let mut len = 0.0;
    let mut next = 1;
    for w in sol.path.windows(2) {
        let (a, b) = (w[0], w[1]);
        let known_free = |c: Cell| map.checked_index(c).is_some_and(|i| pl.reach[i] && m[i]);
        assert!(legal(map, &known_free, a, b), "illegal step {a} -> {b}");
        len += if a.x != b.x && a.y != b.y {
            grid::SQRT2
        } else {
            1.0
        };
        if next < sol.positions.len() && b == sol.positions[next] {
            for &k in &pl.sees[map.index(b)] {
                m[k] = true;
            }
            next += 1;
        }
    }
    assert_eq!(next, sol.positions.len(), "path misses positions");
    assert!(
        (len - sol.length).abs() < TOL,
        "length {len} vs {}",
        sol.length
    );
    let got = perceived_targets(pl, &m);
    assert!(got >= need, "perceived {got} < {need}");
    assert_eq!(got, sol.perceived);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(160))]

    /// Boundary actions (the paper) and all actions (exact): A* = exhaustive search.
    #[test]
    fn astar_matches_exhaustive_search((map, start, model, g) in arb_case(), all in any::<bool>(), hk in 0usize..3) {
        let set = if all { ActionSet::All } else { ActionSet::Boundary };
        let heuristic = [HeuristicKind::Zero, HeuristicKind::Paper, HeuristicKind::Landmarks][hk];
        let problem = Problem::new(&map, start, model).expect("valid problem");
        let pl = plain(&map, start, model);
        let mut paths = Paths::default();
        prop_assert_eq!(problem.targets().len(), pl.targets.len());
        let need = problem.needed(g);
        let s = map.index(start);
        let expected = oracle(&pl, &mut paths, s, initial(&pl, s), need, set);
        if !all {
            // The boundary actions are complete: they reach the goal whenever any sequence does.
            let any = oracle(&pl, &mut paths, s, initial(&pl, s), need, ActionSet::All);
            prop_assert_eq!(any.is_some(), expected.is_some());
        }
        let out = optimal::solve(&problem, &cfg(g, set, heuristic)).expect("solve");
        match expected {
            None => prop_assert_eq!(out.status, Status::NoSolution),
            Some(opt) => {
                prop_assert_eq!(out.status, Status::Optimal, "{}", out.message);
                prop_assert!((out.upper_bound - opt).abs() < TOL, "A* {} vs oracle {}", out.upper_bound, opt);
                prop_assert!((out.lower_bound - opt).abs() < TOL);
                let sol = out.solution.expect("a solution");
                check_solution(&pl, start, &sol, need);
                if g == 1.0 {
                    prop_assert_eq!(sol.perceived, pl.targets.len());
                }
            }
        }
    }

    /// Heuristics never exceed the exact cost-to-go over all position sequences, on every
    /// state the exhaustive search reaches in its first steps.
    #[test]
    fn heuristics_are_admissible((map, start, model, g) in arb_case()) {
        let problem = Problem::new(&map, start, model).expect("valid problem");
        let pl = plain(&map, start, model);
        let mut paths = Paths::default();
        let need = problem.needed(g);
        for (p, m) in early_states(&pl, map.index(start), 6) {
            let Some(exact) = oracle(&pl, &mut paths, p, m.clone(), need, ActionSet::All) else { continue };
            for hk in [HeuristicKind::Paper, HeuristicKind::Landmarks] {
                let by_target: Vec<bool> = pl.targets.iter().map(|&t| m[t]).collect();
                let h = heuristic_value(&problem, &cfg(g, ActionSet::All, hk), map.cell(p), &by_target);
                prop_assert!(h <= exact + TOL, "{:?} h = {} > h* = {} at {}", hk, h, exact, map.cell(p));
            }
        }
    }

    /// A search stopped after a few expansions (optimal or weighted) brackets the optimum: its
    /// lower bound (least open g + h, or the largest popped priority over w) is at most the
    /// optimum, its upper bound at least it.
    #[test]
    fn stopped_searches_bracket_the_optimum(
        (map, start, model, g) in arb_case(),
        nodes in 1u64..40,
        weighted in any::<bool>(),
    ) {
        let problem = Problem::new(&map, start, model).expect("valid problem");
        let exact = optimal::solve(&problem, &cfg(g, ActionSet::Boundary, HeuristicKind::Landmarks)).expect("solve");
        if exact.status != Status::Optimal { return Ok(()); }
        let mut c = cfg(g, ActionSet::Boundary, HeuristicKind::Landmarks);
        c.max_nodes = nodes;
        if weighted {
            c.weight = 2.0;
        }
        let cut = optimal::solve(&problem, &c).expect("solve");
        prop_assert!(cut.lower_bound <= exact.upper_bound + TOL, "{} > {}", cut.lower_bound, exact.upper_bound);
        prop_assert!(cut.upper_bound >= exact.upper_bound - TOL);
        // An observer shown the progress before every expansion that never stops the search
        // changes nothing, and every running bound it sees brackets the optimum too.
        let mut shown = Vec::new();
        let seen = optimal::solve_with(&problem, &c, Duration::ZERO, &mut |p| { shown.push(*p); true }).expect("solve");
        prop_assert_eq!((seen.lower_bound, seen.upper_bound, seen.stats.expanded), (cut.lower_bound, cut.upper_bound, cut.stats.expanded));
        prop_assert_eq!(shown.len() as u64, cut.stats.expanded);
        for p in &shown {
            prop_assert!(p.lower_bound <= exact.upper_bound + TOL, "running {} > {}", p.lower_bound, exact.upper_bound);
            prop_assert!(p.upper_bound >= exact.upper_bound - TOL);
        }
    }

    /// Weighted A* stays within its bound, clusters never beat the boundary optimum.
    #[test]
    fn weighted_and_clusters_are_bounded((map, start, model, g) in arb_case()) {
        let problem = Problem::new(&map, start, model).expect("valid problem");
        let exact = optimal::solve(&problem, &cfg(g, ActionSet::Boundary, HeuristicKind::Landmarks)).expect("solve");
        if exact.status != Status::Optimal { return Ok(()); }
        let mut c = cfg(g, ActionSet::Boundary, HeuristicKind::Landmarks);
        c.weight = 1.5;
        let w = optimal::solve(&problem, &c).expect("solve");
        prop_assert!(w.upper_bound <= 1.5 * exact.upper_bound + TOL);
        prop_assert!(w.lower_bound <= exact.upper_bound + TOL);
        let cl = optimal::solve(&problem, &cfg(g, ActionSet::Clusters { min_size: 1 }, HeuristicKind::Landmarks)).expect("solve");
        if let Some(sol) = &cl.solution {
            prop_assert!(sol.length >= exact.upper_bound - TOL);
            let pl = plain(&map, start, model);
            check_solution(&pl, start, sol, problem.needed(g));
        }
    }
}

/// Long, thin maps (up to 11 × 2) with short sensors and G < 1, where the skip-budget
/// bound has far points at both ends.
fn arb_corridor_case() -> impl Strategy<Value = (Grid<Occ>, Cell, SensorModel, f64)> {
    arb_case_in(7..=11, 1..=2, 20, &[1.0, 1.5], &[0.9, 0.8, 0.7])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The weaker-goal bounds (order statistic, coverage rate, skip budget) never exceed
    /// the exact cost-to-go over all position sequences on corridor-like maps, at the root
    /// and its first children; and A* over boundary actions matches the exhaustive search.
    #[test]
    fn weaker_goal_bounds_hold_on_corridors((map, start, model, g) in arb_corridor_case()) {
        let problem = Problem::new(&map, start, model).expect("valid problem");
        let pl = plain(&map, start, model);
        let mut paths = Paths::default();
        let need = problem.needed(g);
        let s = map.index(start);
        for (p, m) in early_states(&pl, s, 4) {
            let Some(exact) = oracle(&pl, &mut paths, p, m.clone(), need, ActionSet::All) else { continue };
            let by_target: Vec<bool> = pl.targets.iter().map(|&t| m[t]).collect();
            let h = heuristic_value(&problem, &cfg(g, ActionSet::All, HeuristicKind::Landmarks), map.cell(p), &by_target);
            prop_assert!(h <= exact + TOL, "h = {} > h* = {} at {}", h, exact, map.cell(p));
        }
        let expected = oracle(&pl, &mut paths, s, initial(&pl, s), need, ActionSet::Boundary);
        let out = optimal::solve(&problem, &cfg(g, ActionSet::Boundary, HeuristicKind::Landmarks)).expect("solve");
        match expected {
            None => prop_assert_eq!(out.status, Status::NoSolution),
            Some(opt) => prop_assert!((out.upper_bound - opt).abs() < TOL, "A* {} vs oracle {}", out.upper_bound, opt),
        }
    }
}

/// The skip-budget bound's worked example: a 21-cell corridor, `los` r = 1 from its middle,
/// G = 0.9 (19 of 21 cells, so 2 may stay unseen). The robot must go to one end and then to
/// the other; the best is to leave both unseen cells at the end it visits first (stop at
/// cell 3, 7 away, leaving cells 0 and 1), then cross to cell 19 (16 further): 23. The
/// skip-budget bound finds exactly that at the root: the ends are the far points, E = 1,
/// 2, 3 on each side, and the split (2, 0) gives 10 − 3 + (20 − 3 − 1) = 23. The order
/// statistic (8) and the coverage rate (4) are far below.
#[test]
fn skip_budget_worked_example() {
    let map = Grid::new(21, 1, Occ::Free);
    let start = Cell::new(10, 0);
    let p = Problem::new(&map, start, SensorModel::Los(1.0)).expect("valid");
    assert_eq!(p.needed(0.9), 19);
    let c = cfg(0.9, ActionSet::Boundary, HeuristicKind::Landmarks);
    let mut seen = vec![false; 21];
    for x in 9..=11 {
        seen[x] = true;
    }
    let h = heuristic_value(&p, &c, start, &seen);
    assert!((h - 23.0).abs() < TOL, "root bound {h}");
    let paper = heuristic_value(
        &p,
        &cfg(0.9, ActionSet::Boundary, HeuristicKind::Paper),
        start,
        &seen,
    );
    assert!((paper - 8.0).abs() < TOL, "order statistic {paper}");
    let out = optimal::solve(&p, &c).expect("solve");
    assert_eq!(out.status, Status::Optimal);
    assert!((out.upper_bound - 23.0).abs() < TOL, "{}", out.upper_bound);
    // The search is guided straight to it: one state expanded per stop.
    assert!(out.stats.expanded <= 20, "{} expanded", out.stats.expanded);
}

/// A worked example: a 1-wide corridor of 12 cells, `los` r = 3 from the left end. The
/// boundary formulation must stop next to the unseen part each time (0 → 3 → 6 → 9: 9
/// cells); over all positions the last stop can be cell 8, which already sees cell 11 (8
/// cells) — the paper's "end of a corridor" remark.
#[test]
fn corridor_worked_example() {
    let map = Grid::new(12, 1, Occ::Free);
    let p = Problem::new(&map, Cell::new(0, 0), SensorModel::Los(3.0)).expect("valid");
    let out = optimal::solve(&p, &Config::default()).expect("solve");
    assert_eq!(out.status, Status::Optimal);
    assert!((out.upper_bound - 9.0).abs() < TOL, "{}", out.upper_bound);
    let cells: Vec<i32> = out
        .solution
        .expect("solution")
        .positions
        .iter()
        .map(|c| c.x)
        .collect();
    assert_eq!(cells, vec![0, 3, 6, 9]);
    let all =
        optimal::solve(&p, &cfg(1.0, ActionSet::All, HeuristicKind::Landmarks)).expect("solve");
    assert!((all.upper_bound - 8.0).abs() < TOL, "{}", all.upper_bound);
}

/// A pocket behind a wall that only the footprint sensor perceives (through the wall): no
/// boundary cell borders it, so every reachable perceived cell becomes a candidate and the
/// robot walks to where the pocket is within range (`. . . . # .`, r = 2, start at 0: the
/// first position within 2 of cell 5 is cell 3).
#[test]
fn footprint_pocket_behind_a_wall_is_reached() {
    let mut map = Grid::new(6, 1, Occ::Free);
    map.set(Cell::new(4, 0), Occ::Occupied);
    let p = Problem::new(&map, Cell::new(0, 0), SensorModel::Footprint(2.0)).expect("valid");
    assert_eq!(p.targets().len(), 5);
    for set in [
        ActionSet::Boundary,
        ActionSet::Clusters { min_size: 1 },
        ActionSet::All,
    ] {
        let out = optimal::solve(&p, &cfg(1.0, set, HeuristicKind::Landmarks)).expect("solve");
        assert_eq!(out.status, Status::Optimal, "{set:?}: {}", out.message);
        assert!(
            (out.upper_bound - 3.0).abs() < TOL,
            "{set:?}: {}",
            out.upper_bound
        );
        let sol = out.solution.expect("solution");
        assert_eq!(sol.perceived, 5);
        assert_eq!(sol.positions.last().map(|c| c.x), Some(3));
    }
}

/// An observer that asks to stop ends the search cleanly with bounds (as Ctrl-C does in the
/// CLI), after it was shown the progress at least once.
#[test]
fn observer_stops_the_search_with_bounds() {
    let map = Grid::new(40, 40, Occ::Free);
    let p = Problem::new(&map, Cell::new(20, 20), SensorModel::Los(1.5)).expect("valid");
    let mut shown = Vec::new();
    let every = Duration::from_millis(100);
    // Stop at the first report after an expansion (on a loaded machine the first report
    // can come before any).
    let out = optimal::solve_with(&p, &Config::default(), every, &mut |progress| {
        shown.push(*progress);
        progress.expanded == 0
    })
    .expect("solve");
    assert_eq!(out.status, Status::Stopped, "{}", out.message);
    assert_eq!(out.stop, Some(optimal::StopReason::Interrupted));
    assert!(out.message.contains("interrupt"), "{}", out.message);
    assert!(shown[..shown.len() - 1].iter().all(|p| p.expanded == 0));
    let last = *shown.last().expect("a report");
    assert!(last.expanded > 0 && last.seconds >= 0.1);
    assert!(last.lower_bound > 0.0 && last.lower_bound <= out.lower_bound + TOL);
    assert!(out.lower_bound <= out.upper_bound);
    let sol = out.solution.expect("the best path found");
    assert_eq!(sol.perceived, p.targets().len());
}

/// The limits stop the search with bounds that bracket the optimum.
#[test]
fn node_limit_gives_bracketing_bounds() {
    let mut map = Grid::new(14, 9, Occ::Free);
    for y in 0..7 {
        map.set(Cell::new(4, y), Occ::Occupied);
        map.set(Cell::new(9, 8 - y), Occ::Occupied);
    }
    let p = Problem::new(&map, Cell::new(0, 0), SensorModel::Los(2.5)).expect("valid");
    let full =
        optimal::solve(&p, &cfg(1.0, ActionSet::Boundary, HeuristicKind::Paper)).expect("solve");
    assert_eq!(full.status, Status::Optimal);
    let mut c = cfg(1.0, ActionSet::Boundary, HeuristicKind::Paper);
    c.max_nodes = 3;
    let cut = optimal::solve(&p, &c).expect("solve");
    assert_eq!(cut.status, Status::Stopped);
    assert!(cut.lower_bound <= full.upper_bound + TOL);
    assert!(cut.upper_bound >= full.upper_bound - TOL);
    assert!(cut.solution.is_some(), "the greedy incumbent is kept");
    // The budget covers the set-up (refused up front when it does not fit) and leaves the
    // search 16 KiB.
    let mut c = cfg(1.0, ActionSet::Boundary, HeuristicKind::Paper);
    c.max_bytes = optimal::setup_bytes(p.cells().len(), p.model()) as usize + (1 << 14);
    let mem = optimal::solve(&p, &c).expect("solve");
    assert!(matches!(mem.status, Status::Stopped | Status::Optimal));
    assert!(mem.stats.bytes <= c.max_bytes || mem.status == Status::Optimal);
    c.max_bytes = 1 << 16;
    assert!(matches!(
        optimal::solve(&p, &c),
        Err(optimal::OptimalError::Memory { .. })
    ));
}
