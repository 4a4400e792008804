//! Region centroids as candidates (Yamauchi 1997, §2.2).
//!
//! Frontier cells are grouped into 8-connected regions; regions smaller than a minimum
//! size (about the robot's size) are ignored; each remaining region contributes its
//! centroid, snapped to the nearest region cell that a deciding robot can reach (the
//! centroid of a curved region may lie in unknown space or behind a wall).
//!
//! Deviation: when no region of the minimum size has a reachable, unvisited cell, the
//! smaller regions are taken too. Yamauchi's filter is there to ignore sensor noise; with
//! the ideal sensors of a simulation a small region is real unexplored space (a narrow
//! passage, a wall seen at a grazing angle), and without the fallback the robot would stop
//! with reachable space unexplored.

use super::CandidateSet;
use crate::decision::DecisionCtx;
use crate::frontier::Region;

/// Buffers reused across decisions.
#[derive(Default)]
pub struct Scratch {
    regions: Vec<Region>,
}

/// One snapped centroid per region of at least `min_cells` cells.
pub fn generate(ctx: &mut DecisionCtx<'_>, min_cells: usize, out: &mut CandidateSet) {
    let mut scratch = std::mem::take(&mut ctx.memory.centroids);
    generate_min(ctx, min_cells, out, &mut scratch);
    if out.is_empty() && min_cells > 1 {
        generate_min(ctx, 1, out, &mut scratch);
    }
    ctx.memory.centroids = scratch;
}

fn generate_min(
    ctx: &mut DecisionCtx<'_>,
    min_cells: usize,
    out: &mut CandidateSet,
    scratch: &mut Scratch,
) {
    let width = ctx.known.width();
    ctx.upkeep.regions(width, min_cells, &mut scratch.regions);
    let Some(r) = ctx.deciding.iter().position(|&d| d) else {
        return;
    };
    let reach = ctx
        .planner
        .component(r, ctx.robots[r], ctx.known, ctx.upkeep);
    for region in &scratch.regions {
        let (cx, cy) = region.centroid;
        let mut best: Option<(f64, u32)> = None;
        for &c in &region.cells {
            if ctx.lists.is_excluded(c) || !reach.contains(c as usize) {
                continue;
            }
            let x = (c as usize % width) as f64;
            let y = (c as usize / width) as f64;
            let d = (x - cx).powi(2) + (y - cy).powi(2);
            if best.is_none_or(|(bd, bc)| d < bd || (d == bd && c < bc)) {
                best = Some((d, c));
            }
        }
        if let Some((_, c)) = best {
            out.insert(c);
        }
    }
}
