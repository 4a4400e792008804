//! Decision-theoretic samples and utility against brute force on random small beliefs:
//! every sample is reachable, traversable and near an unlisted frontier cell, and its gain,
//! once evaluated, equals a fresh evaluation; when few cells are eligible, every eligible
//! cell with a gain is a candidate; the fallback takes the frontier cells; the choice (with
//! lazily evaluated gains) maximises the utility over all candidates evaluated afresh; λ = 0
//! picks the greatest gain, a huge λ the nearest; runs are deterministic; the uncertain-cell
//! counts match a brute-force count, and no scan's gain exceeds the count of its square nor
//! that of its disc, cut to the half-plane ahead for a field of view up to 180° (the bounds
//! that let the utility assigner skip candidates).

use explore::FrontierUpkeep;
use explore::Reachability;
use explore::assign::utility;
use explore::candidates::CandidateSet;
use explore::candidates::dt_samples::{self, arrival_heading};
use explore::decision::{DecisionCtx, Goal, GoalLists, Memory, Planner};
use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::{
    Belief, GainScratch, InverseModel, KnownGrid, LidarSensor, LosSensor, Observation, Pose,
    Sensor, information_gain, information_gain_gated,
};

/// Everything a decision context borrows, owned.
struct Fixture {
    belief: KnownGrid,
    upkeep: FrontierUpkeep,
    planner: Planner,
    robots: Vec<u32>,
    deciding: Vec<bool>,
    goals: Vec<Option<u32>>,
    lists: GoalLists,
    rng: Pcg64Mcg,
    sensor: Box<dyn Sensor>,
    memory: Memory,
    candidates: CandidateSet,
}

impl Fixture {
    fn new(known: &Grid<Occ>, robots: Vec<u32>, sensor: Box<dyn Sensor>, seed: u64) -> Self {
        let (w, h) = (known.width(), known.height());
        let mut belief = KnownGrid::new(w, h);
        let obs = Observation {
            origin: Cell::new(0, 0),
            cells: known
                .data()
                .iter()
                .enumerate()
                .filter(|(_, s)| !s.is_unknown())
                .map(|(i, &s)| (i as u32, s))
                .collect(),
        };
        belief.integrate(&obs, &mut Vec::new());
        let mut upkeep = FrontierUpkeep::new(w, h, 0.0);
        upkeep.rebuild(belief.known());
        let m = robots.len();
        Self {
            belief,
            upkeep,
            planner: Planner::new(w, h, m),
            deciding: vec![true; m],
            goals: vec![None; m],
            robots,
            lists: GoalLists::new(w * h),
            rng: Pcg64Mcg::seed_from_u64(seed),
            sensor,
            memory: Memory::default(),
            candidates: CandidateSet::new(w * h),
        }
    }

    /// Generate `n` samples, then assign with `lambda`.
    fn decide(&mut self, n: usize, lambda: f64) -> Vec<Option<Goal>> {
        self.planner.invalidate();
        let mut out = vec![None; self.robots.len()];
        let mut ctx = DecisionCtx {
            known: self.belief.known(),
            upkeep: &mut self.upkeep,
            planner: &mut self.planner,
            robots: &self.robots,
            deciding: &self.deciding,
            goals: &self.goals,
            lists: &self.lists,
            resolution: 0.1,
            sensor_range_cells: self.sensor.range_cells(),
            rng: &mut self.rng,
            belief: &self.belief,
            sensor: self.sensor.as_ref(),
            memory: &mut self.memory,
        };
        self.candidates.clear();
        dt_samples::generate(&mut ctx, n, &mut self.candidates);
        utility::assign(&mut ctx, &self.candidates, lambda, &mut out);
        out
    }
}

/// A belief grid: Free and Occupied cells (6 : 1) with a few Unknown ones, and everything
/// right of a random column Unknown, so that some cells lie far from every frontier.
fn belief_grid() -> impl Strategy<Value = Grid<Occ>> {
    (4usize..18, 4usize..14).prop_flat_map(|(w, h)| {
        (
            prop::collection::vec(
                prop_oneof![60 => Just(Occ::Free), 10 => Just(Occ::Occupied), 3 => Just(Occ::Unknown)],
                w * h,
            ),
            1..=w,
        )
            .prop_map(move |(mut v, cut)| {
                for (i, s) in v.iter_mut().enumerate() {
                    if i % w >= cut {
                        *s = Occ::Unknown;
                    }
                }
                Grid::from_vec(w, h, v).expect("sized")
            })
    })
}

fn free_cell(g: &Grid<Occ>, k: usize) -> Option<u32> {
    let free: Vec<usize> = (0..g.len()).filter(|&i| g[i] == Occ::Free).collect();
    (!free.is_empty()).then(|| free[k % free.len()] as u32)
}

/// A sensor for the property tests: `los` (omnidirectional) or a 180° lidar (heading matters).
fn sensor(kind: bool, r: f64) -> Box<dyn Sensor> {
    if kind {
        Box::new(LosSensor::new(r).expect("range"))
    } else {
        Box::new(LidarSensor::new(r, 180.0, 5.0).expect("lidar"))
    }
}

/// Brute-force facts about one cell for robot 0: reachable with cost, traversable.
fn reach(fx: &Fixture) -> Reachability {
    let known = fx.belief.known();
    let mut r = Reachability::new(known.width(), known.height());
    r.compute(fx.robots[0] as usize, |i| {
        fx.upkeep.is_traversable(known, i)
    });
    r
}

/// Whether frontier cell `i` is open: reachable by robot 0 (the fixtures list nothing).
fn is_open(fx: &Fixture, reach: &Reachability, i: usize) -> bool {
    fx.upkeep.frontiers.contains(i) && reach.cost(i).is_some()
}

/// The gain of `cell` on arrival along `reach`'s path, evaluated afresh, its rays gated as
/// the module says: an Unknown cell with a known 8-neighbour is passed only if one of its
/// 8-neighbours is an open frontier cell (brute force over the neighbours).
fn fresh_gain(fx: &Fixture, reach: &Reachability, cell: u32) -> f64 {
    let known = fx.belief.known();
    let heading = if fx.sensor.is_omnidirectional() {
        0.0
    } else {
        arrival_heading(known, reach, cell)
    };
    let any_open = fx
        .upkeep
        .frontiers
        .cells()
        .iter()
        .any(|&c| is_open(fx, reach, c as usize));
    let neighbours = |i: usize| {
        let c = known.cell(i);
        (-1i32..=1)
            .flat_map(move |dy| (-1i32..=1).map(move |dx| (dx, dy)))
            .filter(|&d| d != (0, 0))
            .filter_map(move |(dx, dy)| known.checked_index(Cell::new(c.x + dx, c.y + dy)))
    };
    let gate = |i: usize| {
        let borders_known = neighbours(i).any(|j| known[j] != Occ::Unknown);
        !borders_known || neighbours(i).any(|j| is_open(fx, reach, j))
    };
    information_gain_gated(
        fx.sensor.as_ref(),
        &fx.belief,
        &InverseModel::IDEAL,
        Pose::new(known.cell(cell as usize), heading),
        any_open.then_some(&gate as &dyn Fn(usize) -> bool),
        &mut GainScratch::new(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn uncertain_counts_bound_every_scan(
        g in belief_grid(), k in 0usize..300, los in any::<bool>(), r in 1.0f64..6.0,
        heading in -3.2f64..3.2, rect in (0usize..20, 0usize..20, 0usize..20, 0usize..20),
    ) {
        let fx_robot = free_cell(&g, k).unwrap_or(0);
        let fx = Fixture::new(&g, vec![fx_robot], sensor(los, r), 0);
        let mut uc = utility::UncertainCounts::default();
        uc.build(&fx.belief);
        let (w, h) = (g.width(), g.height());
        let uncertain = |x: usize, y: usize| g[y * w + x] == Occ::Unknown;
        let (x0, y0, x1, y1) = rect;
        let brute = (y0..y1.min(h)).flat_map(|y| (x0..x1.min(w)).map(move |x| (x, y)))
            .filter(|&(x, y)| uncertain(x, y)).count() as u32;
        prop_assert_eq!(uc.count(x0, y0, x1, y1), brute);
        // the square of half-side ⌊R⌋ + 1 around a cell holds every cell a scan touches
        let c = g.cell(k % g.len());
        let (x, y) = (c.x as usize, c.y as usize);
        let half = fx.sensor.range_cells() as usize + 1;
        let bound = uc.count(x.saturating_sub(half), y.saturating_sub(half), x + half + 1, y + half + 1);
        let gain = information_gain(
            fx.sensor.as_ref(), &fx.belief, &InverseModel::IDEAL, Pose { cell: c, heading },
            &mut GainScratch::new(),
        );
        prop_assert!(gain <= f64::from(bound), "gain {} > bound {}", gain, bound);
        // the disc (cut to the half-plane ahead for a field of view up to 180°) bounds it too
        let disc = utility::GainBound::new(fx.sensor.range_cells(), fx.sensor.field_of_view_deg());
        let b = disc.of(&uc, x, y, heading);
        prop_assert!(gain <= b, "gain {} > disc bound {}", gain, b);
        prop_assert!(b <= f64::from(bound) * (1.0 + 1e-12) + 1e-9, "disc {} looser than square {}", b, bound);
        for fov in [30.0, 90.0, 180.0, 181.0, 270.0] {
            let lidar = LidarSensor::new(r, fov, 3.0).expect("lidar");
            let gain = information_gain(
                &lidar, &fx.belief, &InverseModel::IDEAL, Pose { cell: c, heading },
                &mut GainScratch::new(),
            );
            let b = utility::GainBound::new(r, fov).of(&uc, x, y, heading);
            prop_assert!(gain <= b, "fov {}: gain {} > bound {}", fov, gain, b);
        }
    }

    #[test]
    fn samples_match_brute_force(
        g in belief_grid(), k in 0usize..300, n in prop_oneof![0usize..8, 0usize..200],
        los in any::<bool>(), r in 1.0f64..6.0, seed in any::<u64>(),
    ) {
        let Some(robot) = free_cell(&g, k) else { return Ok(()); };
        let mut fx = Fixture::new(&g, vec![robot], sensor(los, r), seed);
        let goals = fx.decide(n, 0.2);
        let known = fx.belief.known().clone();
        let reach = reach(&fx);
        let range = fx.sensor.range_cells();
        // Samples lie near open frontier cells only (reachable ones; nothing is listed).
        let frontier: Vec<Cell> = fx.upkeep.frontiers.cells().iter()
            .filter(|&&c| is_open(&fx, &reach, c as usize))
            .map(|&c| known.cell(c as usize)).collect();
        // Brute force: the eligible cells and those with a positive gain.
        let eligible: Vec<u32> = (0..known.len() as u32)
            .filter(|&i| i != robot && reach.cost(i as usize).is_some())
            .filter(|&i| {
                let c = known.cell(i as usize);
                frontier.iter().any(|&f| (f.dist2(c) as f64) <= range * range)
            })
            .collect();
        let positive: Vec<u32> = eligible.iter().copied().filter(|&i| fresh_gain(&fx, &reach, i) > 0.0).collect();
        let st = &fx.memory.dt;
        let cells = fx.candidates.cells().to_vec();
        prop_assert!(st.aligned_with(&fx.candidates));
        prop_assert_eq!(st.gains.len(), cells.len());
        // every candidate's gain, evaluated afresh (the stored one may be lazily unevaluated)
        let fresh: Vec<f64> = cells.iter().map(|&c| fresh_gain(&fx, &reach, c)).collect();
        for ((&c, &gain), &want) in cells.iter().zip(&st.gains).zip(&fresh) {
            prop_assert!(reach.cost(c as usize).is_some(), "unreachable sample");
            prop_assert!(c == robot || fx.upkeep.is_traversable(&known, c as usize));
            prop_assert!(gain.is_nan() || gain == want, "stored gain {} fresh {}", gain, want);
        }
        if st.fell_back {
            // No draw had a gain; the candidates are the reachable frontier cells.
            let mut want: Vec<u32> = fx.upkeep.frontiers.cells().iter().copied()
                .filter(|&c| reach.cost(c as usize).is_some()).collect();
            want.sort_unstable();
            let mut got = cells.clone();
            got.sort_unstable();
            prop_assert_eq!(got, want);
            if eligible.len() <= n {
                prop_assert!(positive.is_empty());
            }
        } else {
            prop_assert!(cells.len() <= n);
            for &c in &cells {
                prop_assert!(eligible.contains(&c), "sample {} not eligible", c);
            }
            // the generator keeps samples from its first positive gain on
            if !cells.is_empty() {
                prop_assert!(st.gains[0] > 0.0);
                prop_assert!(!positive.is_empty());
            }
            if eligible.len() <= n {
                // Every eligible cell was drawn: every one with a gain is a candidate.
                for c in &positive {
                    prop_assert!(cells.contains(c), "eligible {} with a gain is missing", c);
                }
            }
        }
        // The assigner's choice maximises ln I − λ L over every candidate evaluated afresh
        // (ties: cost, then index).
        match goals[0] {
            None => prop_assert!(cells.iter().all(|&c| reach.cost(c as usize).is_none())),
            Some(goal) => {
                let u = |gain: f64, cost: f64| gain.ln() - 0.2 * 0.1 * cost;
                let k = cells.iter().position(|&c| c == goal.cell).expect("a candidate");
                prop_assert_eq!(Some(goal.cost), reach.cost(goal.cell as usize));
                prop_assert_eq!(st.gains[k], fresh[k], "the choice's gain was evaluated");
                let ug = u(fresh[k], goal.cost);
                for (j, &c) in cells.iter().enumerate() {
                    let cost = reach.cost(c as usize).expect("reachable");
                    let uj = u(fresh[j], cost);
                    prop_assert!(uj <= ug, "candidate {} beats the choice", c);
                    if uj == ug {
                        prop_assert!(cost > goal.cost || (cost == goal.cost && j >= k));
                    }
                }
            }
        }
    }

    #[test]
    fn lambda_zero_takes_the_greatest_gain_and_huge_lambda_the_nearest(
        g in belief_grid(), k in 0usize..300, seed in any::<u64>(),
    ) {
        let Some(robot) = free_cell(&g, k) else { return Ok(()); };
        let mut fx = Fixture::new(&g, vec![robot], sensor(true, 3.0), seed);
        let Some(goal) = fx.decide(20, 0.0)[0] else { return Ok(()); };
        let reach0 = reach(&fx);
        let fresh: Vec<f64> =
            fx.candidates.cells().iter().map(|&c| fresh_gain(&fx, &reach0, c)).collect();
        let max = fresh.iter().copied().fold(0.0, f64::max);
        let k = fx.candidates.cells().iter().position(|&c| c == goal.cell).expect("candidate");
        prop_assert_eq!(fx.memory.dt.gains[k], max);
        // Same seed, huge λ: the nearest candidate.
        let mut fx = Fixture::new(&g, vec![robot], sensor(true, 3.0), seed);
        let goal = fx.decide(20, 1e12)[0].expect("same candidates");
        let reach = reach(&fx);
        // the nearest candidate with a gain (fallback candidates of gain 0 count too)
        let fell_back = fx.memory.dt.fell_back;
        let nearest = fx.candidates.cells().iter()
            .filter(|&&c| fell_back || fresh_gain(&fx, &reach, c) > 0.0)
            .map(|&c| reach.cost(c as usize).expect("reachable"))
            .fold(f64::INFINITY, f64::min);
        // Equal path lengths summed in different orders may differ in the last bit.
        prop_assert!((goal.cost - nearest).abs() < 1e-9, "cost {} nearest {}", goal.cost, nearest);
    }

    #[test]
    fn deterministic(g in belief_grid(), k in 0usize..300, seed in any::<u64>(), los in any::<bool>()) {
        let Some(robot) = free_cell(&g, k) else { return Ok(()); };
        let run = || {
            let mut fx = Fixture::new(&g, vec![robot], sensor(los, 4.0), seed);
            let goals = fx.decide(10, 0.2);
            let bits: Vec<u64> = fx.memory.dt.gains.iter().map(|g| g.to_bits()).collect();
            (goals, fx.candidates.cells().to_vec(), bits)
        };
        prop_assert_eq!(run(), run());
    }
}

/// `rows` as a grid: '.' Free, '#' Occupied, '?' Unknown.
fn map(rows: &[&str]) -> Grid<Occ> {
    let data = rows
        .iter()
        .flat_map(|r| r.chars())
        .map(|c| match c {
            '.' => Occ::Free,
            '#' => Occ::Occupied,
            _ => Occ::Unknown,
        })
        .collect();
    Grid::from_vec(rows[0].len(), rows.len(), data).expect("rectangular")
}

#[test]
fn the_door_to_a_large_room_beats_a_nook() {
    // A known corridor; a door (bottom, x = 4) opens on a large unknown room; a one-cell
    // unknown nook at the right end of the corridor is nearer. λ = 0.2/m at 0.1 m/cell
    // barely discounts, so the door wins.
    let mut rows = vec![
        "##############",
        "#...........?#",
        "#............#",
        "####.#########",
    ];
    rows.extend(std::iter::repeat_n("??????????????", 10));
    let g = map(&rows);
    let robot = g.index(Cell::new(10, 2)) as u32;
    let mut fx = Fixture::new(&g, vec![robot], sensor(true, 5.0), 1);
    let goal = fx.decide(500, 0.2)[0].expect("a goal");
    let c = g.cell(goal.cell as usize);
    assert!(
        c.x <= 6 && c.y >= 2,
        "goal {c} is not at the door: gains {:?}",
        fx.memory.dt.gains
    );
    // With a huge λ the nearest sample wins instead: next to the robot.
    let mut fx = Fixture::new(&g, vec![robot], sensor(true, 5.0), 1);
    let goal = fx.decide(500, 1e6)[0].expect("a goal");
    assert_eq!(goal.cost, 1.0);
}

#[test]
fn a_team_each_takes_its_own_best() {
    let g = map(&["############", "#?........?#", "############"]);
    let (a, b) = (
        g.index(Cell::new(2, 1)) as u32,
        g.index(Cell::new(9, 1)) as u32,
    );
    let mut fx = Fixture::new(&g, vec![a, b], sensor(true, 1.5), 3);
    let goals = fx.decide(100, 0.2);
    let ga = g.cell(goals[0].expect("a").cell as usize);
    let gb = g.cell(goals[1].expect("b").cell as usize);
    assert!(ga.x <= 2, "robot a goes left: {ga}");
    assert!(gb.x >= 9, "robot b goes right: {gb}");
}

#[test]
fn target_utility_matches_the_chosen_candidate() {
    let mut rows = vec!["##########", "#........#", "####.#####"];
    rows.extend(std::iter::repeat_n("??????????", 6));
    let g = map(&rows);
    let robot = g.index(Cell::new(8, 1)) as u32;
    let mut fx = Fixture::new(
        &g,
        vec![robot],
        Box::new(LidarSensor::new(6.0, 180.0, 2.0).expect("lidar")),
        5,
    );
    let goal = fx.decide(50, 0.2)[0].expect("a goal");
    let heading = utility::chosen_heading(&fx.memory.dt, goal.cell).expect("a candidate");
    let k = fx
        .candidates
        .cells()
        .iter()
        .position(|&c| c == goal.cell)
        .expect("candidate");
    let gain = fx.memory.dt.gains[k];
    let u = utility::target_utility(
        &mut fx.memory.dt,
        &fx.belief,
        fx.sensor.as_ref(),
        Pose::new(g.cell(goal.cell as usize), heading),
        goal.cost,
        0.1,
        0.2,
    );
    assert!(gain > 0.0);
    assert!((u - gain * (-0.2 * goal.cost * 0.1f64).exp()).abs() < 1e-9);
}

/// The fixture's frontiers and traversability recomputed with a clearance of `cells`.
fn with_clearance(fx: &mut Fixture, cells: f64) {
    let known = fx.belief.known();
    fx.upkeep = FrontierUpkeep::new(known.width(), known.height(), cells);
    fx.upkeep.rebuild(known);
}

#[test]
fn dt_stops_when_no_reachable_frontier_is_left() {
    // The right room is seen through a one-cell gap in the wall, too narrow to pass with a
    // clearance of 1.5 cells (the gap's cell is one cell from the wall): its frontier cells (next to the unknown column) cannot be
    // reached. Holz et al.'s termination: no reachable frontier cell, so no goal — however
    // much a scan through the gap could still reveal.
    let g = map(&[
        "###########",
        "#.....#...?",
        "#.....#...?",
        "#..........",
        "#.....#...?",
        "#.....#...?",
        "###########",
    ]);
    let robot = g.index(Cell::new(2, 3)) as u32;
    let mut fx = Fixture::new(&g, vec![robot], sensor(true, 12.0), 2);
    with_clearance(&mut fx, 1.5);
    assert!(!fx.upkeep.frontiers.cells().is_empty());
    assert_eq!(fx.decide(500, 0.2)[0], None);
    assert!(fx.candidates.cells().is_empty());
}

#[test]
fn dt_gain_does_not_leak_through_an_unseen_wall_cell() {
    // A corridor whose only open frontier is its right end; the bottom wall has one unseen
    // cell (x = 9) with a large unknown region behind it. A predicted ray must not pass that
    // cell (module doc), so the samples go to the right end, not to the gap.
    let mut rows = vec![
        "####################",
        "#..................?",
        "#..................?",
        "#..................?",
        "#########?##########",
    ];
    rows.extend(std::iter::repeat_n("????????????????????", 12));
    let g = map(&rows);
    let robot = g.index(Cell::new(2, 2)) as u32;
    let lidar = || Box::new(LidarSensor::new(6.0, 360.0, 1.0).expect("lidar")) as Box<dyn Sensor>;
    let mut fx = Fixture::new(&g, vec![robot], lidar(), 4);
    with_clearance(&mut fx, 1.0);
    let goal = fx.decide(500, 0.2)[0].expect("a goal");
    let c = g.cell(goal.cell as usize);
    assert!(c.x >= 12, "goal {c} is not near the open end");
    // Every sample's gain counts at most the gap cell itself below the wall.
    let known = fx.belief.known().clone();
    for (k, &cell) in fx.candidates.cells().iter().enumerate() {
        let reach = reach(&fx);
        let gain = fresh_gain(&fx, &reach, cell);
        assert!(
            gain <= 1.0 + 3.0 + 1e-9 || known.cell(cell as usize).x >= 12,
            "sample {k}: {gain}"
        );
    }
}
