//! From a map message to the first goal, on a 2000 × 2000 map at 0.05 m.
//!
//! The map is a generated 100 m × 100 m office, half explored by a simulated `cf-rr` run
//! (its belief is the message, as a SLAM node would publish it mid-exploration). Measured:
//! the first message (classify 4 M cells, build traversability and frontiers from scratch,
//! then decide) and a later message that changes a small patch (diff, incremental upkeep,
//! decide).

use criterion::{Criterion, criterion_group, criterion_main};
use explore::strategy::Strategy;
use frontier_ros_core::{Decision, Explorer, ExplorerConfig};
use record::msgs::Time;
use record::occupancy::{MapFrame, msg_from_map};

fn setup() -> (record::msgs::OccupancyGrid, (f64, f64)) {
    let mut spec = world::EnvSpec::new(world::EnvKind::Office, 1);
    spec.size_m = Some((100.0, 100.0));
    spec.resolution = Some(0.05);
    let env = world::generate(&spec).unwrap();
    let mut cfg = sim::RunConfig::new(Strategy::preset("cf-rr").unwrap());
    cfg.sensor = "lidar:r=8,fov=360,res=0.5".parse().unwrap();
    cfg.clearance_m = 0.2;
    cfg.coverage_goal = Some(0.5);
    let run = sim::run(&env.map, &cfg).unwrap();
    let belief = grid::GridMap {
        cells: run.belief.clone(),
        resolution: env.map.resolution,
        origin: env.map.origin,
    };
    let end = run.ends[0];
    let at = MapFrame::of(&belief).world_from_cell(end);
    (msg_from_map(&belief, "map", Time::default()), at)
}

fn config() -> ExplorerConfig {
    let mut c = ExplorerConfig::new(Strategy::preset("cf-rr").unwrap());
    c.sensor = "lidar:r=8,fov=360,res=0.5".parse().unwrap();
    c.clearance_m = 0.2;
    c
}

fn bench(c: &mut Criterion) {
    let (msg, (x, y)) = setup();
    if std::env::var_os("FIRST_GOAL_SPLIT").is_some() {
        // Where the first message's time goes (one run each).
        let t = std::time::Instant::now();
        let frame = record::occupancy::frame_of(&msg).unwrap();
        let mut classes = vec![grid::Occ::Unknown; frame.width * frame.height];
        record::occupancy::classify_into(&msg, &frame, &mut classes);
        eprintln!("classify {:?}", t.elapsed());
        let t = std::time::Instant::now();
        let mut up = explore::FrontierUpkeep::new(frame.width, frame.height, 4.0);
        let _pl = explore::decision::Planner::new(frame.width, frame.height, 1);
        eprintln!("allocate upkeep + planner {:?}", t.elapsed());
        let known = grid::Grid::from_vec(frame.width, frame.height, classes).unwrap();
        let t = std::time::Instant::now();
        up.rebuild(&known);
        eprintln!("upkeep rebuild {:?}", t.elapsed());
        let mut ex = Explorer::new(config());
        let t = std::time::Instant::now();
        ex.update_map(&msg).unwrap();
        eprintln!("update_map {:?}", t.elapsed());
        let t = std::time::Instant::now();
        let d = ex.decide(x, y, 0.0);
        eprintln!("decide {:?} {d:?}", t.elapsed());
    }
    let mut g = c.benchmark_group("map message to goal, 2000x2000 at 0.05 m");
    g.sample_size(10);
    g.bench_function("first message", |b| {
        b.iter(|| {
            let mut ex = Explorer::new(config());
            ex.update_map(&msg).unwrap();
            assert!(matches!(ex.decide(x, y, 0.0), Decision::Goal(_)));
        })
    });
    let mut ex = Explorer::new(config());
    ex.update_map(&msg).unwrap();
    // A later message: a 2 m × 2 m patch of unknown cells around the goal becomes free.
    let Decision::Goal(goal) = ex.decide(x, y, 0.0) else {
        panic!("no goal")
    };
    let w = msg.info.width as usize;
    let mut later = msg.clone();
    let (gc, gr) = ((goal.x / 0.05) as usize, (goal.y / 0.05) as usize);
    for r in gr.saturating_sub(20)..(gr + 20).min(msg.info.height as usize) {
        for c in gc.saturating_sub(20)..(gc + 20).min(w) {
            if later.data[r * w + c] < 0 {
                later.data[r * w + c] = 0;
            }
        }
    }
    let mut flip = false;
    g.bench_function("update message", |b| {
        b.iter(|| {
            flip = !flip;
            ex.update_map(if flip { &later } else { &msg }).unwrap();
            assert!(matches!(ex.decide(x, y, 0.0), Decision::Goal(_)));
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
