//! Room segmentation of generated hospitals and offices against their ground-truth rooms
//! (Holz et al. 2010 §2.4): with the Holz rule most rooms are recovered.
//!
//! `cargo test -p explore --test segment_rooms -- --nocapture` prints the three rules side
//! by side.

use explore::segment::score::{RoomScores, score};
use explore::segment::{Rule, segment};
use world::{EnvKind, EnvSpec};

const SEEDS: std::ops::RangeInclusive<u64> = 1..=6;

fn scores(kind: EnvKind, seed: u64, rule: Rule) -> RoomScores {
    let env = world::generate(&EnvSpec::new(kind, seed)).expect("generate");
    let seg = segment(&env.map.cells, rule);
    let truth = env.rooms.as_ref().expect("rooms");
    score(&seg.labels, truth.data())
}

#[test]
fn rules_side_by_side() {
    println!("kind      rule   precision recall  F1     ARI    segments rooms");
    for kind in [EnvKind::Hospital, EnvKind::Office] {
        for rule in Rule::ALL {
            let all: Vec<RoomScores> = SEEDS.map(|s| scores(kind, s, rule)).collect();
            let mean =
                |f: fn(&RoomScores) -> f64| all.iter().map(f).sum::<f64>() / all.len() as f64;
            println!(
                "{:<9} {:<6} {:>9.3} {:>6.3} {:>6.3} {:>6.3} {:>8.1} {:>5.1}",
                kind.to_string(),
                rule.name(),
                mean(|s| s.precision),
                mean(|s| s.recall),
                mean(|s| s.f1),
                mean(|s| s.ari),
                mean(|s| s.segments as f64),
                mean(|s| s.rooms as f64),
            );
            for s in &all {
                assert!(s.precision <= 1.0 && s.recall <= 1.0 && s.ari <= 1.0 + 1e-12);
            }
        }
    }
}

#[test]
fn the_holz_rule_recovers_most_rooms_of_hospitals_and_offices() {
    for kind in [EnvKind::Hospital, EnvKind::Office] {
        let recalls: Vec<f64> = SEEDS.map(|s| scores(kind, s, Rule::Holz).recall).collect();
        let mean = recalls.iter().sum::<f64>() / recalls.len() as f64;
        assert!(
            mean >= 0.8,
            "{kind}: recall per seed {recalls:?}, mean {mean}"
        );
        for (seed, r) in SEEDS.zip(&recalls) {
            assert!(*r >= 0.7, "{kind} seed {seed}: recall {r}");
        }
    }
}
