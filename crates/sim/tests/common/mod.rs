//! What the session tests share.
#![allow(dead_code)] // each test file uses what it needs

use sim::{RunConfig, RunResult, Session};

/// The same run: paths, decisions, moves, scans, end, coverage curve, overlap, belief and
/// starts.
pub fn assert_same_run(got: &RunResult, want: &RunResult, what: &str) {
    assert_eq!(got.path_length_m, want.path_length_m, "{what}");
    assert_eq!(got.decisions, want.decisions, "{what}");
    assert_eq!(got.moves, want.moves, "{what}");
    assert_eq!(got.scans, want.scans, "{what}");
    assert_eq!(got.reason, want.reason, "{what}");
    assert_eq!(got.coverage_curve, want.coverage_curve, "{what}");
    assert_eq!(got.overlap, want.overlap, "{what}");
    assert_eq!(got.belief, want.belief, "{what}");
    assert_eq!(got.starts, want.starts, "{what}");
}

/// The goals the strategy's assigner proposes for the pending decision (one per robot).
pub fn proposed_goals(s: &mut Session<'_>, cfg: &RunConfig) -> Vec<Option<u32>> {
    let cells = s.candidates().to_vec();
    s.propose(cfg.strategy.assigner, &cells)
        .iter()
        .map(|g| g.map(|g| g.cell))
        .collect()
}
