//! `frontier explore --mcap`: a run as an MCAP recording (see `record::mcap_write`).
//!
//! The trace is replayed: every event gives the robot's pose; at most
//! [`MAX_SNAPSHOTS`] decisions, spread evenly over the run, give a belief snapshot and the
//! frontier markers (each is a whole map, so a long run on a large map would otherwise write
//! gigabytes), and every decision gives its goal. Frontier cells are kept up to date
//! incrementally from the trace's belief changes, as the run kept them.

use std::io::{Seek, Write};

use anyhow::{Context, Result};
use explore::FrontierUpkeep;
use grid::{Grid, GridMap, Occ};
use record::RunWriter;
use record::mcap_read::RecordedAt;
use record::occupancy::MapFrame;
use sim::{RunConfig, RunResult};

/// Belief snapshots written at most.
pub const MAX_SNAPSHOTS: usize = 60;

/// Write the run `result` of `cfg` on `map` (which must have a trace) to `out`: in the
/// frame of the recorded map the run explored and from its log time (`recorded`), so that
/// it lines up with that recording, or in the `map` frame from time 0.
pub fn write_run<W: Write + Seek>(
    out: W,
    map: &GridMap,
    recorded: Option<&RecordedAt>,
    cfg: &RunConfig,
    result: &RunResult,
) -> Result<()> {
    let trace = result
        .trace
        .as_ref()
        .context("the run kept no trace to record")?;
    let frame = MapFrame::of(map);
    let (w, h) = (map.width(), map.height());
    let mut rec = match recorded {
        Some(r) => RunWriter::with_clock(out, &r.frame_id, r.log_time)?,
        None => RunWriter::new(out)?,
    };
    rec.map(0.0, map)?;
    let mut belief = GridMap {
        cells: Grid::new(w, h, Occ::Unknown),
        resolution: map.resolution,
        origin: map.origin,
    };
    let mut upkeep = FrontierUpkeep::new(w, h, grid::units::cells(cfg.clearance_m, map.resolution));
    let world = |i: u32| frame.world_from_cell(belief_cell(w, i));
    let every = trace.goals.len().div_ceil(MAX_SNAPSHOTS).max(1);
    let mut next_goal = 0;
    let mut start = 0usize;
    let mut frontiers = Vec::new();
    let mut heading = vec![0.0f64; trace.robots];
    let mut last = trace.starts.clone();
    // Decisions taken before any event (the first ones) come first.
    let mut emit_goals = |upto: u32,
                          t: f64,
                          belief: &GridMap,
                          upkeep: &FrontierUpkeep,
                          rec: &mut RunWriter<W>,
                          next_goal: &mut usize|
     -> Result<bool> {
        let mut wrote_belief = false;
        while *next_goal < trace.goals.len() && trace.goals[*next_goal].event <= upto {
            let g = trace.goals[*next_goal];
            if let Some(cell) = g.goal {
                let (x, y) = world(cell);
                rec.goal(t, g.robot as usize, x, y)?;
            }
            if (*next_goal).is_multiple_of(every) {
                rec.belief(t, belief)?;
                wrote_belief = true;
                frontiers.clear();
                frontiers.extend(upkeep.frontiers.cells().iter().map(|&c| world(c)));
                let candidates: Vec<(f64, f64)> = trace
                    .candidates
                    .iter()
                    .rev()
                    .find(|(e, _)| *e <= upto)
                    .map(|(_, c)| c.iter().map(|&c| world(c)).collect())
                    .unwrap_or_default();
                rec.markers(t, &frontiers, &candidates, belief.resolution)?;
            }
            *next_goal += 1;
        }
        Ok(wrote_belief)
    };
    // Whether the last belief written is the belief as it is now.
    let mut written = false;
    // A team's events come in the order its robots set out, and a later move can end
    // earlier: the shared topics (goals, belief, markers) are stamped with the latest time
    // reached, so that each topic's times never go back.
    let mut now = 0.0f64;
    let mut changed = Vec::new();
    for (k, ev) in trace.events.iter().enumerate() {
        let end = trace.change_ends[k] as usize;
        changed.clear();
        for &(c, occ) in &trace.changes[start..end] {
            belief.cells.data_mut()[c as usize] = occ;
            changed.push(c);
        }
        start = end;
        written &= changed.is_empty();
        upkeep.update(&belief.cells, &changed);
        let r = ev.robot as usize;
        let (from, to) = (belief_cell(w, last[r]), belief_cell(w, ev.cell));
        if from != to {
            heading[r] = -f64::from(to.y - from.y).atan2(f64::from(to.x - from.x)) + map.origin[2];
        }
        last[r] = ev.cell;
        let (x, y) = world(ev.cell);
        rec.pose(ev.t, r, x, y, heading[r])?;
        now = now.max(ev.t);
        written |= emit_goals(
            k as u32 + 1,
            now,
            &belief,
            &upkeep,
            &mut rec,
            &mut next_goal,
        )?;
    }
    let t_end = now;
    written |= emit_goals(u32::MAX, t_end, &belief, &upkeep, &mut rec, &mut next_goal)?;
    // The final belief, unless a snapshot just wrote it (at the run's last decision).
    if !written {
        rec.belief(t_end, &belief)?;
    }
    let mut out = rec.finish()?;
    out.flush()?;
    Ok(())
}

/// The cell of flat index `i` on a map `w` cells wide.
fn belief_cell(w: usize, i: u32) -> grid::Cell {
    grid::Cell::new((i as usize % w) as i32, (i as usize / w) as i32)
}
