//! The explorer's memory estimate against what it takes: a counting allocator measures the
//! peak heap of exploring a generated office as the node would (map messages in, goals
//! out), and the estimate the node checks a map message with must bound it.

mod common;
#[path = "../../grid/tests/common/counting.rs"]
mod counting;

use common::World;
use explore::strategy::Strategy;
use frontier_ros_core::{Decision, Explorer, ExplorerConfig};

/// Peak heap bytes of `preset` exploring an office of `size` metres at 0.05 m with Holz's
/// laser, for at most `goals` goals; and the map's cells.
fn peak(preset: &str, size: (f64, f64), goals: usize) -> (usize, usize, ExplorerConfig) {
    let mut spec = world::EnvSpec::new(world::EnvKind::Office, 3);
    spec.size_m = Some(size);
    spec.resolution = Some(0.05);
    let truth = world::generate(&spec).unwrap().map;
    let n = truth.cells.len();
    let start = (0..n)
        .map(|i| truth.cells.cell(i))
        .find(|&c| truth.cells[truth.cells.index(c)] == grid::Occ::Free)
        .unwrap();
    let mut world = World::new(truth, "lidar:r=8,fov=180,res=1");
    let (mut x, mut y) = world.world(start);
    world.sense_at(x, y);
    let first = world.map_msg();
    let mut cfg = ExplorerConfig::new(Strategy::preset(preset).unwrap());
    cfg.sensor = "lidar:r=8,fov=180,res=1".parse().unwrap();
    let c = cfg.clone();
    let (_, bytes) = counting::peak_of(move || {
        let mut ex = Explorer::new(c);
        ex.update_map(&first).unwrap();
        for k in 0..goals {
            match ex.decide(x, y, k as f64) {
                Decision::Goal(g) => {
                    (x, y) = (g.x, g.y);
                    world.sense_at(x, y);
                    ex.update_map(&world.map_msg()).unwrap();
                    ex.goal_reached();
                }
                Decision::Stop(_) => break,
            }
        }
        ex
    });
    (bytes, n, cfg)
}

/// The estimate a map message is checked with bounds the explorer's peak, for every kind
/// of strategy the node runs, on two map sizes (so that neither the fixed nor the per-cell
/// part alone carries it).
#[test]
fn the_memory_estimate_bounds_what_exploring_takes() {
    let _turn = counting::turn();
    for preset in [
        "cf-rr",
        "yamauchi",
        "cf-rr-seg",
        "dt500",
        "random",
        "nearest-rfe",
        "nearest-cc",
    ] {
        for size in [(14.0, 10.0), (28.0, 20.0)] {
            // The candidates that cost most per decision are followed for fewer goals.
            let goals = match preset {
                "nearest-cc" => 30,
                "dt500" => 40,
                _ => 150,
            };
            let (bytes, cells, cfg) = peak(preset, size, goals);
            let estimate = cfg.memory_bytes(cells, 0.05);
            assert!(
                bytes as u64 <= estimate,
                "{preset} on {cells} cells: took {} MiB, estimated {} MiB",
                bytes >> 20,
                estimate >> 20
            );
        }
    }
}
