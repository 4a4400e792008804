//! Any-angle path length against slow oracles: dense sampling of segments and the grid length.

use grid::step_cost;
use proptest::prelude::*;
use sim::motion::{
    any_angle_corners, any_angle_length, any_angle_prefix_lengths, grid_prefix_lengths,
    line_of_sight, polyline_length,
};

/// The cells a segment between two cell centres touches, found by sampling it densely:
/// every cell containing a sample point, and both cells beside a sample that lies on a cell
/// edge (the slow oracle of `line_of_sight`).
fn sampled_cells(w: usize, a: usize, b: usize) -> Vec<usize> {
    let (ax, ay) = ((a % w) as f64, (a / w) as f64);
    let (bx, by) = ((b % w) as f64, (b / w) as f64);
    let n = 4000;
    let mut out = Vec::new();
    for k in 0..=n {
        let t = k as f64 / n as f64;
        let (x, y) = (ax + t * (bx - ax), ay + t * (by - ay));
        let (cx, cy) = ((x + 0.5).floor(), (y + 0.5).floor());
        if cx >= 0.0 && cy >= 0.0 && (cx as usize) < w {
            out.push(cy as usize * w + cx as usize);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// A random walk of `steps` 8-moves over `passable` cells from `start`.
fn walk(w: usize, h: usize, pass: &[bool], start: usize, dirs: &[u8]) -> Vec<u32> {
    let mut trail = vec![start as u32];
    let mut cur = start;
    for &d in dirs {
        let (dx, dy) = grid::NEIGHBOURS8[d as usize % 8];
        let (x, y) = (
            (cur % w) as i64 + i64::from(dx),
            (cur / w) as i64 + i64::from(dy),
        );
        if x < 0 || y < 0 || x >= w as i64 || y >= h as i64 {
            continue;
        }
        let next = y as usize * w + x as usize;
        if pass[next] {
            cur = next;
            trail.push(cur as u32);
        }
    }
    trail
}

fn grid_length(w: usize, trail: &[u32]) -> f64 {
    trail
        .windows(2)
        .map(|p| {
            let (a, b) = (p[0] as usize, p[1] as usize);
            let dx = (b % w) as i32 - (a % w) as i32;
            let dy = (b / w) as i32 - (a / w) as i32;
            if dx == 0 && dy == 0 {
                0.0
            } else {
                step_cost(dx, dy)
            }
        })
        .sum()
}

/// A random map (passable cells of a `w`-wide grid) and a trail walked on it from a
/// passable start.
fn map_and_trail() -> impl Strategy<Value = (usize, Vec<bool>, Vec<u32>)> {
    (
        2usize..16,
        2usize..16,
        proptest::collection::vec(0u8..10, 256),
        0usize..256,
        proptest::collection::vec(0u8..8, 0..120),
    )
        .prop_map(|(w, h, blocked, start, dirs)| {
            let n = w * h;
            let mut pass: Vec<bool> = (0..n).map(|i| blocked[i] >= 3).collect();
            let start = start % n;
            pass[start] = true;
            let trail = walk(w, h, &pass, start, &dirs);
            (w, pass, trail)
        })
}

proptest! {
    #[test]
    fn line_of_sight_never_passes_a_blocked_cell_a_sample_touches(
        w in 2usize..14, h in 2usize..14,
        blocked in proptest::collection::vec(0u8..10, 196),
        a in 0usize..196, b in 0usize..196,
    ) {
        let n = w * h;
        let (a, b) = (a % n, b % n);
        let pass: Vec<bool> = (0..n).map(|i| blocked[i] >= 3).collect();
        if line_of_sight(w, a, b, |i| pass[i]) {
            for c in sampled_cells(w, a, b) {
                prop_assert!(pass[c], "segment {a}->{b} crosses blocked cell {c}");
            }
        }
        // with nothing blocked every segment is clear
        prop_assert!(line_of_sight(w, a, b, |_| true));
    }

    #[test]
    fn any_angle_length_lies_between_the_straight_line_and_the_grid_length(
        (w, pass, trail) in map_and_trail(),
    ) {
        let mut corners = Vec::new();
        any_angle_corners(w, &trail, |i| pass[i], &mut corners);
        let len = polyline_length(w, &corners);
        prop_assert!((len - any_angle_length(w, &trail, |i| pass[i])).abs() < 1e-12);
        let grid = grid_length(w, &trail);
        prop_assert!(len <= grid + 1e-9, "{len} > grid {grid}");
        let (f, l) = (trail[0] as usize, *trail.last().unwrap() as usize);
        let straight = ((f % w) as f64 - (l % w) as f64).hypot((f / w) as f64 - (l / w) as f64);
        prop_assert!(len >= straight - 1e-9, "{len} < straight {straight}");
        // the polyline starts and ends where the trail does, and each leg is a step the
        // robot made or a segment through passable cells only
        prop_assert_eq!(corners[0], trail[0]);
        prop_assert_eq!(*corners.last().unwrap(), *trail.last().unwrap());
        for leg in corners.windows(2) {
            let (a, b) = (leg[0] as usize, leg[1] as usize);
            let adjacent = (a % w).abs_diff(b % w) <= 1 && (a / w).abs_diff(b / w) <= 1;
            if !adjacent {
                for c in sampled_cells(w, a, b) {
                    prop_assert!(pass[c], "leg {a}->{b} crosses blocked cell {c}");
                }
            }
        }
    }
}

proptest! {
    /// The distance along the string-pulled route at each cell of the trail: exactly the
    /// route's length at its end, the polyline's length at each corner, never decreasing,
    /// and never more than the grid distance walked by then.
    #[test]
    fn prefix_lengths_follow_the_string_pulled_route((w, pass, trail) in map_and_trail()) {
        let n = pass.len();
        let along = any_angle_prefix_lengths(w, &trail, &[], |i| pass[i]);
        let grid = grid_prefix_lengths(w, &trail);
        prop_assert_eq!(along.len(), trail.len());
        prop_assert_eq!(grid.len(), trail.len());
        // exactly (the same sum in the same order; == takes an empty sum's −0 as 0)
        let whole = any_angle_length(w, &trail, |i| pass[i]);
        prop_assert!(*along.last().unwrap() == whole, "{:?} against {}", along.last(), whole);
        prop_assert!((grid.last().unwrap() - grid_length(w, &trail)).abs() < 1e-9);
        for k in 1..trail.len() {
            prop_assert!(along[k] >= along[k - 1], "decreases at {}", k);
            prop_assert!(along[k] <= grid[k] + 1e-9, "{} > grid {} at {}", along[k], grid[k], k);
        }
        // at each corner, the polyline so far (on a trail that visits each cell once, so
        // that a corner's cell names its place on the trail)
        let mut once = vec![false; n];
        if trail.iter().all(|&c| !std::mem::replace(&mut once[c as usize], true)) {
            let mut corners = Vec::new();
            any_angle_corners(w, &trail, |i| pass[i], &mut corners);
            for c in 1..corners.len() {
                let k = trail.iter().position(|&t| t == corners[c]).unwrap();
                let want = polyline_length(w, &corners[..=c]);
                prop_assert!(
                    (along[k] - want).abs() < 1e-9,
                    "corner {}: {} against {}", c, along[k], want
                );
            }
        }
    }
}

proptest! {
    /// Leg by leg: each leg's start stays a corner, so the length to it is at least the
    /// straight lines joining the legs' starts; each leg is pulled as a trail of its own;
    /// and with every cell a leg's start the route is the grid route.
    #[test]
    fn legs_stay_corners(
        (w, pass, trail) in map_and_trail(),
        cuts in proptest::collection::vec(0usize..130, 0..6),
    ) {
        let n = trail.len();
        let mut legs: Vec<usize> = cuts.into_iter().filter(|&c| c < n).collect();
        legs.sort_unstable();
        legs.dedup();
        let along = any_angle_prefix_lengths(w, &trail, &legs, |i| pass[i]);
        let grid = grid_prefix_lengths(w, &trail);
        let mut starts: Vec<usize> = std::iter::once(0).chain(legs.iter().copied()).collect();
        starts.dedup();
        let mut chain = 0.0;
        for p in starts.windows(2) {
            let (a, b) = (p[0], p[1]);
            let (ca, cb) = (trail[a] as usize, trail[b] as usize);
            chain += ((ca % w) as f64 - (cb % w) as f64).hypot((ca / w) as f64 - (cb / w) as f64);
            prop_assert!(along[b] >= chain - 1e-9, "{} < chain {} at {}", along[b], chain, b);
            // the leg a..=b alone, shifted by where it starts
            let leg = any_angle_length(w, &trail[a..=b], |i| pass[i]);
            prop_assert!((along[b] - along[a] - leg).abs() < 1e-9, "leg {}..={}", a, b);
        }
        for k in 1..n {
            prop_assert!(along[k] >= along[k - 1] && along[k] <= grid[k] + 1e-9);
        }
        let every: Vec<usize> = (0..n).collect();
        let stepwise = any_angle_prefix_lengths(w, &trail, &every, |i| pass[i]);
        for k in 0..n {
            prop_assert!((stepwise[k] - grid[k]).abs() < 1e-9, "{} against grid {}", stepwise[k], grid[k]);
        }
    }
}

/// Regression: the whole trail was string-pulled as one, and in open space every later
/// cell is in sight of the first, so a robot that went to a goal and came back was given
/// the straight line from its start to its end (8 × 8 m room, `cf`: 5.3 m for a 19.8 m
/// grid route that crossed the room twice). Where the robot set out on a new path is a
/// corner: there and back is twice the way.
#[test]
fn regression_a_route_there_and_back_is_twice_the_way() {
    let w = 10;
    let there: Vec<u32> = (0..=8).map(|x| x as u32).collect();
    let back: Vec<u32> = (2..8).rev().map(|x| x as u32).collect();
    let trail: Vec<u32> = there.iter().chain(&back).copied().collect();
    let whole = any_angle_prefix_lengths(w, &trail, &[], |_| true);
    assert!((whole.last().unwrap() - 2.0).abs() < 1e-12, "{whole:?}");
    let legs = any_angle_prefix_lengths(w, &trail, &[8], |_| true);
    assert!((legs.last().unwrap() - 14.0).abs() < 1e-12, "{legs:?}");
}

#[test]
fn an_l_shaped_route_in_an_open_room_becomes_one_straight_line() {
    // 10 × 10, all free: right 6 cells then down 8 cells; any-angle is the hypotenuse
    let w = 10;
    let mut trail: Vec<u32> = (0..=6).map(|x| x as u32).collect();
    trail.extend((1..=8).map(|y| (y * w + 6) as u32));
    let len = any_angle_length(w, &trail, |_| true);
    assert!((len - 10.0).abs() < 1e-12, "{len}");
    assert!((grid_length(w, &trail) - 14.0).abs() < 1e-12);
}

#[test]
fn a_wall_corner_keeps_the_route_bent_around_it() {
    // the same L route with the cell inside the bend blocked beside the corner: the straight
    // line would cut through the blocked cells, so the route keeps a corner near (6, 0)
    let w = 10;
    let mut trail: Vec<u32> = (0..=6).map(|x| x as u32).collect();
    trail.extend((1..=8).map(|y| (y * w + 6) as u32));
    let blocked = |i: usize| i % w <= 5 && i / w >= 1; // everything below row 0 left of x = 6
    let len = any_angle_length(w, &trail, |i| !blocked(i));
    assert!((len - 14.0).abs() < 1e-12, "{len}");
}

#[test]
fn motion_names_parse_and_bad_names_say_what_was_expected() {
    assert_eq!("grid".parse::<sim::Motion>(), Ok(sim::Motion::Grid));
    assert_eq!(
        "any-angle".parse::<sim::Motion>(),
        Ok(sim::Motion::AnyAngle)
    );
    let e = "theta".parse::<sim::Motion>().unwrap_err();
    assert!(e.contains("theta") && e.contains("any-angle"), "{e}");
}

#[test]
fn any_angle_motion_changes_only_the_reported_length() {
    use explore::strategy::Strategy;
    use sim::{Motion, RunConfig};
    use world::{EnvKind, EnvSpec};
    for (kind, seed) in [(EnvKind::Office, 1), (EnvKind::Cave, 2)] {
        let env = world::generate(&EnvSpec::new(kind, seed)).expect("generate");
        let mut cfg = RunConfig::new(Strategy::preset("cf").expect("preset"));
        cfg.seed = seed;
        cfg.clearance_m = 0.3;
        let grid = sim::run(&env.map, &cfg).expect("run");
        cfg.motion = Motion::AnyAngle;
        let smooth = sim::run(&env.map, &cfg).expect("run");
        assert_eq!(grid.motion, Motion::Grid);
        assert_eq!(grid.path_length_m, grid.grid_path_length_m);
        assert_eq!(smooth.grid_path_length_m, grid.path_length_m);
        assert_eq!(
            (smooth.decisions, smooth.moves),
            (grid.decisions, grid.moves)
        );
        assert_eq!(smooth.coverage, grid.coverage);
        let (s, g) = (smooth.path_length_m[0], grid.path_length_m[0]);
        assert!(
            s < g && s > 0.5 * g,
            "{kind:?}: any-angle {s} against grid {g}"
        );
        assert!((smooth.time_s - s / cfg.speed).abs() < 1e-9);
    }
}

/// Regression: with `--motion any-angle` the coverage curve and the D/T milestones were
/// still grid distances and times while the lengths and `time_s` were any-angle ones, so
/// that "distance to 99 %" came out longer than the whole run. Now they are measured along
/// the same routes: the curve ends within the team's total any-angle length, no milestone
/// lies beyond the run's length or time, each milestone is where the curve first reaches it,
/// and the curve's coverage values are those of grid motion.
#[test]
fn regression_any_angle_curve_and_milestones_follow_the_route() {
    use explore::strategy::Strategy;
    use sim::{EndReason, Motion, RunConfig};
    use world::{EnvKind, EnvSpec};
    let env = world::generate(&EnvSpec::new(EnvKind::Office, 4)).expect("generate");
    for (preset, robots) in [("cf", 1), ("greedy", 3)] {
        let mut cfg = RunConfig::new(Strategy::preset(preset).expect("preset"));
        cfg.robots = robots;
        cfg.seed = 2;
        let grid = sim::run(&env.map, &cfg).expect("run");
        cfg.motion = Motion::AnyAngle;
        cfg.record_trace = true;
        let r = sim::run(&env.map, &cfg).expect("run");
        assert_eq!(r.reason, EndReason::Complete, "{preset}");
        // The trace (pictures, the HTML replay) ends each robot at its any-angle length
        // (it gave grid distances, so the replay's readout differed from the JSON).
        let trace = r.trace.as_ref().expect("trace");
        for (k, &len) in r.path_length_m.iter().enumerate() {
            let last = trace.events.iter().rev().find(|e| e.robot as usize == k);
            assert_eq!(last.expect("an event").dist_m, len, "{preset}: robot {k}");
        }
        let total: f64 = r.path_length_m.iter().sum();
        let grid_total: f64 = grid.path_length_m.iter().sum();
        assert!(
            total < grid_total - 1.0,
            "{preset}: {total} against {grid_total}"
        );
        let curve = &r.coverage_curve;
        assert_eq!(curve.len(), grid.coverage_curve.len(), "{preset}");
        for (k, (p, g)) in curve.iter().zip(&grid.coverage_curve).enumerate() {
            assert_eq!(p.1, g.1, "{preset}: coverage at point {k}");
            assert!(p.0 <= g.0 + 1e-9, "{preset}: point {k} beyond the grid's");
            if k > 0 {
                assert!(
                    p.0 >= curve[k - 1].0,
                    "{preset}: the curve goes back at {k}"
                );
            }
        }
        // (a run may end a move or, for a team, several after the last cell is seen)
        let last = curve.last().expect("curve").0;
        assert!(
            last <= total + 1e-9,
            "{preset}: curve ends at {last}, runs {total}"
        );
        assert_eq!(r.milestones.len(), grid.milestones.len(), "{preset}");
        for m in &r.milestones {
            assert!(
                m.dist_m <= total + 1e-9,
                "{preset}: D{} {} > {total}",
                m.percent,
                m.dist_m
            );
            assert!(
                m.time_s <= r.time_s + 1e-9,
                "{preset}: T{} {} > {}",
                m.percent,
                m.time_s,
                r.time_s
            );
            let first = curve
                .iter()
                .find(|p| p.1 * 100.0 >= f64::from(m.percent) - 1e-12)
                .expect("reached");
            assert!(
                (first.0 - m.dist_m).abs() < 1e-9,
                "{preset}: D{} off the curve",
                m.percent
            );
        }
    }
}
