//! The loop benchmark: one full `cf-rr` exploration of a 100 m × 100 m office at
//! 0.05 m (2000 × 2000 cells) with `los:r=5`, reporting the total wall time and its split
//! into sensing, frontier upkeep and deciding. One run takes minutes, so this is a plain
//! harness (`cargo bench -p sim --bench office_2000`) rather than criterion's repeated
//! samples. Set `FRONTIER_BENCH_SIZE=50` for a 50 m × 50 m office.

use explore::strategy::Strategy;
use sim::RunConfig;
use world::{EnvKind, EnvSpec};

fn main() {
    if std::env::args().any(|a| a == "--list") {
        println!("office_2000: bench");
        return;
    }
    let size: f64 = std::env::var("FRONTIER_BENCH_SIZE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100.0);
    let t = std::time::Instant::now();
    let env = world::generate(&EnvSpec {
        kind: EnvKind::Office,
        seed: 1,
        size_m: Some((size, size)),
        resolution: Some(0.05),
    })
    .expect("generate office");
    let generate_s = t.elapsed().as_secs_f64();
    let mut cfg = RunConfig::new(Strategy::preset("cf-rr").expect("preset"));
    cfg.sensor = "los:r=5".parse().expect("sensor");
    cfg.seed = 1;
    let r = sim::run(&env.map, &cfg).expect("run");
    let t = r.times;
    println!(
        "office {size} m x {size} m at 0.05 m ({}x{} cells), cf-rr, los:r=5: {} after {:.1} m, {} moves, {} decisions",
        env.map.width(),
        env.map.height(),
        r.reason.as_str(),
        r.path_length_m[0],
        r.moves,
        r.decisions
    );
    println!(
        "generate {generate_s:.2} s; run {:.2} s = sense {:.2} s + frontier upkeep {:.2} s + decide {:.2} s + rest {:.2} s",
        t.total_s,
        t.sense_s,
        t.upkeep_s,
        t.decide_s,
        t.total_s - t.sense_s - t.upkeep_s - t.decide_s
    );
    println!(
        "per move: sense {:.1} µs, upkeep {:.2} µs; per decision: {:.1} µs",
        t.sense_s / r.moves as f64 * 1e6,
        t.upkeep_s / r.moves as f64 * 1e6,
        t.decide_s / r.decisions as f64 * 1e6
    );
}
