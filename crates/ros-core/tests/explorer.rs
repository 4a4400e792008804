//! The node's decisions without DDS: a pretend robot drives to every goal and senses there.

mod common;

use common::World;
use explore::strategy::Strategy;
use frontier_ros_core::{Check, Decision, Explorer, ExplorerConfig, StopReason};
use grid::io::parse_ascii;
use grid::{Cell, GridMap};

fn config(strategy: &str, sensor: &str) -> ExplorerConfig {
    let mut c = ExplorerConfig::new(Strategy::preset(strategy).unwrap());
    c.sensor = sensor.parse().unwrap();
    c.clearance_m = 0.0;
    c.min_frontier_size_m = 0.0;
    c
}

/// The rooms world sensed from cell (1, 1), its map fed to `ex`: the world and the robot's
/// position.
fn start_in_rooms(ex: &mut Explorer) -> (World, f64, f64) {
    let mut world = rooms();
    let (x, y) = world.world(Cell::new(1, 1));
    world.sense_at(x, y);
    ex.update_map(&world.map_msg()).unwrap();
    (world, x, y)
}

/// Drive: decide, teleport to the goal, sense, feed the map; until the explorer stops.
fn explore(
    world: &mut World,
    ex: &mut Explorer,
    start: Cell,
    max_goals: usize,
) -> (StopReason, usize) {
    let (mut x, mut y) = world.world(start);
    world.sense_at(x, y);
    ex.update_map(&world.map_msg()).unwrap();
    for k in 0..max_goals {
        match ex.decide(x, y, k as f64) {
            Decision::Goal(g) => {
                assert_eq!(ex.check(x, y, k as f64), Check::Keep, "a fresh goal stands");
                (x, y) = (g.x, g.y);
                world.sense_at(x, y);
                ex.update_map(&world.map_msg()).unwrap();
                ex.goal_reached();
            }
            Decision::Stop(r) => return (r, k),
        }
    }
    panic!("no stop after {max_goals} goals");
}

fn office() -> GridMap {
    let spec = world::EnvSpec::new(world::EnvKind::Office, 3);
    world::generate(&spec).unwrap().map
}

#[test]
fn every_single_robot_preset_explores_an_office() {
    for preset in [
        "cf",
        "cf-rr",
        "yamauchi",
        "cf-rr-seg",
        "random",
        "dt",
        "nearest-cc",
    ] {
        let truth = office();
        let start = (0..truth.cells.len())
            .map(|i| truth.cells.cell(i))
            .find(|&c| truth.cells[truth.cells.index(c)] == grid::Occ::Free)
            .unwrap();
        let mut world = World::new(truth, "los:r=5");
        let mut ex = Explorer::new(config(preset, "los:r=5"));
        let (reason, goals) = explore(&mut world, &mut ex, start, 2000);
        assert_eq!(reason, StopReason::Explored, "{preset}");
        let cov = world.coverage_from(start);
        assert!(cov > 0.999, "{preset}: coverage {cov} after {goals} goals");
    }
}

const ROOMS: &str = "\
##########
#........#
#........#
#........#
####.#####
#........#
#........#
##########
";

fn rooms() -> World {
    World::new(parse_ascii(ROOMS, 1.0).unwrap(), "los:r=3")
}

#[test]
fn a_failed_goal_is_never_chosen_again() {
    let mut ex = Explorer::new(config("cf", "los:r=3"));
    let (_, x, y) = start_in_rooms(&mut ex);
    let mut failed = Vec::new();
    // Nav2 fails every goal: each goes on the inaccessible list, none comes back.
    loop {
        match ex.decide(x, y, 0.0) {
            Decision::Goal(g) => {
                assert!(!failed.contains(&g.cell), "goal {} chosen again", g.cell);
                failed.push(g.cell);
                ex.goal_failed();
            }
            Decision::Stop(r) => {
                let StopReason::NoReachableFrontier {
                    inaccessible,
                    frontiers,
                    ..
                } = r
                else {
                    panic!("{r:?}");
                };
                assert_eq!(inaccessible, failed.len());
                assert_eq!(frontiers, failed.len(), "every frontier cell was tried");
                break;
            }
        }
    }
    assert_eq!(ex.inaccessible().len(), failed.len());
    assert!(failed.len() > 1);
}

#[test]
fn no_progress_for_the_timeout_gives_the_goal_up() {
    let mut c = config("cf", "los:r=3");
    c.progress_timeout_s = 5.0;
    c.goal_tolerance_m = 0.1;
    let mut ex = Explorer::new(c);
    let (_, x, y) = start_in_rooms(&mut ex);
    let Decision::Goal(g) = ex.decide(x, y, 100.0) else {
        panic!()
    };
    assert_eq!(ex.check(x, y, 104.0), Check::Keep);
    assert_eq!(ex.check(x, y, 105.5), Check::NoProgress);
    assert_eq!(ex.inaccessible(), &[(g.x, g.y)]);
    // Getting closer resets the clock.
    let Decision::Goal(g) = ex.decide(x, y, 200.0) else {
        panic!()
    };
    let (mx, my) = ((x + g.x) / 2.0, (y + g.y) / 2.0);
    assert_eq!(ex.check(mx, my, 204.0), Check::Keep);
    assert_eq!(ex.check(mx, my, 208.0), Check::Keep);
    assert_eq!(ex.check(mx, my, 209.5), Check::NoProgress);
}

#[test]
fn repetitive_rechecking_drops_a_goal_that_stopped_being_a_frontier() {
    let mut ex = Explorer::new(config("cf-rr", "los:r=3"));
    let (mut world, x, y) = start_in_rooms(&mut ex);
    let Decision::Goal(g) = ex.decide(x, y, 0.0) else {
        panic!()
    };
    // The robot has not moved, but the map now shows everything around the goal.
    world.sense_at(g.x, g.y);
    ex.update_map(&world.map_msg()).unwrap();
    assert_eq!(ex.check(x, y, 1.0), Check::TargetExplored);
    // Plain cf keeps it.
    let mut world = rooms();
    let mut ex = Explorer::new(config("cf", "los:r=3"));
    world.sense_at(x, y);
    ex.update_map(&world.map_msg()).unwrap();
    let Decision::Goal(g) = ex.decide(x, y, 0.0) else {
        panic!()
    };
    world.sense_at(g.x, g.y);
    ex.update_map(&world.map_msg()).unwrap();
    assert_eq!(ex.check(x, y, 1.0), Check::Keep);
}

#[test]
fn a_door_narrower_than_the_clearance_stops_with_the_reason() {
    let mut world = World::new(parse_ascii(ROOMS, 1.0).unwrap(), "los:r=9");
    let mut c = config("cf", "los:r=9");
    c.clearance_m = 1.5;
    let mut ex = Explorer::new(c);
    let (x, y) = world.world(Cell::new(4, 2));
    world.sense_at(x, y);
    ex.update_map(&world.map_msg()).unwrap();
    match ex.decide(x, y, 0.0) {
        Decision::Stop(StopReason::NoReachableFrontier {
            frontiers, narrow, ..
        }) => {
            // No free cell in the lower room is clear enough to be a frontier: the gap is named.
            assert_eq!(frontiers, 0);
            assert!(narrow > 0);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_robot_off_the_map_or_in_a_wall_is_a_stop_reason() {
    let mut ex = Explorer::new(config("cf", "los:r=3"));
    assert_eq!(ex.decide(0.0, 0.0, 0.0), Decision::Stop(StopReason::NoMap));
    let (world, _, _) = start_in_rooms(&mut ex);
    assert!(matches!(
        ex.decide(-5.0, 1.0, 0.0),
        Decision::Stop(StopReason::RobotOffMap { .. })
    ));
    let (wx, wy) = world.world(Cell::new(8, 6)); // unknown, far from anything seen
    assert!(matches!(
        ex.decide(wx, wy, 0.0),
        Decision::Stop(StopReason::RobotNotOnFreeSpace { .. })
    ));
}

#[test]
fn bad_map_messages_are_errors_and_change_nothing() {
    let mut ex = Explorer::new(config("cf", "los:r=3"));
    let (world, x, y) = start_in_rooms(&mut ex);
    let before = ex.decide(x, y, 0.0);
    for bad in [
        {
            let mut m = world.map_msg();
            m.data.pop();
            m
        },
        {
            let mut m = world.map_msg();
            m.info.resolution = f32::NAN;
            m
        },
        {
            let mut m = world.map_msg();
            m.info.width = 0;
            m.data.clear();
            m
        },
    ] {
        assert!(ex.update_map(&bad).is_err());
    }
    assert_eq!(ex.decide(x, y, 0.0), before);
}

/// A map message whose exploration would need more than `memory_mb` is refused before
/// anything is built on it, naming its size, the memory and the budget; the explorer goes
/// on with the last map.
#[test]
fn a_map_beyond_memory_mb_is_refused_and_the_last_one_kept() {
    let mut c = config("cf", "los:r=3");
    c.memory_mb = Some(64);
    let mut ex = Explorer::new(c);
    let (_, x, y) = start_in_rooms(&mut ex);
    let before = ex.decide(x, y, 0.0);
    let huge = record::occupancy::msg_from_map(
        &GridMap::new(grid::Grid::new(2000, 2000, grid::Occ::Free), 0.05),
        "map",
        record::msgs::Time::default(),
    );
    let e = ex.update_map(&huge).unwrap_err().to_string();
    assert!(
        e.starts_with("a map of 2000 x 2000 cells at 0.05 m: exploring it with cf needs about"),
        "{e}"
    );
    assert!(e.contains("more than memory_mb 64"), "{e}");
    assert_eq!(ex.decide(x, y, 0.0), before);
}

#[test]
fn a_growing_map_keeps_its_inaccessible_goals() {
    // A SLAM map grows: the same world with a border of unknown cells added on the left and
    // the bottom, so the origin moves; the goal given up stays given up.
    let mut ex = Explorer::new(config("cf", "los:r=3"));
    let (world, x, y) = start_in_rooms(&mut ex);
    let Decision::Goal(g) = ex.decide(x, y, 0.0) else {
        panic!()
    };
    ex.goal_failed();
    let mut grown = world.map_msg();
    let (w, h) = (grown.info.width as usize, grown.info.height as usize);
    let mut data = vec![-1i8; (w + 3) * (h + 2)];
    for row in 0..h {
        data[(row + 2) * (w + 3) + 3..(row + 2) * (w + 3) + 3 + w]
            .copy_from_slice(&grown.data[row * w..(row + 1) * w]);
    }
    grown.info.width += 3;
    grown.info.height += 2;
    grown.info.origin.position.x -= 3.0;
    grown.info.origin.position.y -= 2.0;
    grown.data = data;
    assert!(ex.update_map(&grown).unwrap().rebuilt);
    let Decision::Goal(g2) = ex.decide(x, y, 1.0) else {
        panic!()
    };
    assert!(
        (g2.x, g2.y) != (g.x, g.y),
        "the inaccessible goal came back"
    );
}

#[test]
fn the_same_seed_gives_the_same_goals() {
    let goals = |seed| {
        let mut c = config("random", "los:r=3");
        c.seed = seed;
        let mut ex = Explorer::new(c);
        let (_, x, y) = start_in_rooms(&mut ex);
        (0..5)
            .map(|_| {
                let d = ex.decide(x, y, 0.0);
                ex.goal_failed();
                d
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(goals(4), goals(4));
}

/// A goal Nav2 rejected (its bt_navigator does until it is active) or left unanswered was
/// blacklisted; now the node sends it again later and restarts its no-progress time, so
/// waiting for Nav2 does not give a reachable goal up either.
#[test]
fn a_goal_waiting_for_nav2_is_not_given_up_for_no_progress() {
    let mut c = config("cf", "los:r=3");
    c.progress_timeout_s = 5.0;
    c.goal_tolerance_m = 0.1;
    let mut ex = Explorer::new(c);
    let (_, x, y) = start_in_rooms(&mut ex);
    let Decision::Goal(g) = ex.decide(x, y, 100.0) else {
        panic!()
    };
    for t in [104.0, 108.0, 112.0] {
        ex.restart_progress(t);
        assert_eq!(ex.check(x, y, t + 1.0), Check::Keep);
    }
    assert!(ex.inaccessible().is_empty());
    assert_eq!(ex.goal(), Some(g));
    // Once taken, it is given up after the timeout as before.
    assert_eq!(ex.check(x, y, 117.5), Check::NoProgress);
    assert_eq!(ex.inaccessible(), &[(g.x, g.y)]);
}
