//! Holz et al.'s closest frontier with re-checking and segmentation (`cf-rr-seg`) explores
//! small offices and hospitals completely, deterministically.

use explore::strategy::Strategy;
use sim::{EndReason, RunConfig};
use world::{EnvKind, EnvSpec};

fn run(spec: &EnvSpec, seed: u64) -> sim::RunResult {
    let env = world::generate(spec).expect("generate");
    let mut cfg = RunConfig::new(Strategy::preset("cf-rr-seg").expect("preset"));
    cfg.seed = seed;
    sim::run(&env.map, &cfg).expect("run")
}

#[test]
fn cf_rr_seg_explores_offices_and_hospitals_completely() {
    let specs = [
        EnvSpec::new(EnvKind::Office, 1),
        EnvSpec::new(EnvKind::Office, 2),
        EnvSpec::new(EnvKind::Hospital, 1).with_size(24.0, 16.0),
        EnvSpec::new(EnvKind::Hospital, 2).with_size(24.0, 16.0),
    ];
    for spec in &specs {
        let r = run(spec, 3);
        let what = spec.name();
        assert_eq!(
            r.reason,
            EndReason::Complete,
            "{what}: ended '{}' at coverage {}",
            r.reason.as_str(),
            r.coverage
        );
        assert_eq!(r.coverage, 1.0, "{what}");
        assert!(r.frontiers_left.is_empty(), "{what}: frontiers left");
        let again = run(spec, 3);
        assert_eq!(
            again.path_length_m, r.path_length_m,
            "{what}: not deterministic"
        );
    }
}
