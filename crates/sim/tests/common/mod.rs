//! What the session tests share.

use sim::{RunConfig, Session};

/// The goals the strategy's assigner proposes for the pending decision (one per robot).
pub fn proposed_goals(s: &mut Session<'_>, cfg: &RunConfig) -> Vec<Option<u32>> {
    let cells = s.candidates().to_vec();
    s.propose(cfg.strategy.assigner, &cells)
        .iter()
        .map(|g| g.map(|g| g.cell))
        .collect()
}
