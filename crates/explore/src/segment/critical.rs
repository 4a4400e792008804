//! Critical points of the Voronoi graph (Holz et al. 2010 §2.4 and Figure 7 step 2; Thrun
//! 1998; Wurm et al. 2008).
//!
//! A *candidate* is a local minimum of clearance along an edge of the graph — a cell of
//! degree 2 by construction. A run of equal clearance (a plateau, common on a grid) is one
//! minimum, represented by its middle cell. The rules then keep:
//!
//! - [`Rule::Thrun`]: every candidate;
//! - [`Rule::Wurm`]: candidates adjacent to a junction, i.e. with no other candidate between
//!   them and a junction node along their edge;
//! - [`Rule::Holz`] (default): those, and candidates adjacent to a node (another candidate, of
//!   degree 2) that is adjacent to a junction — at most one candidate in between.
//!
//! "Adjacent" is read on the graph whose nodes are the junctions, end points and candidates,
//! since on a grid skeleton every cell is a node and pixel adjacency would be meaningless.
//!
//! Deviation (significance): a grid skeleton's clearance wobbles by fractions of a cell, so
//! raw local minima appear everywhere — e.g. in a corridor between two doors, where the
//! clearance bulges slightly at each door. A candidate must therefore be a real narrowing:
//! on at least one side along its edge the clearance must rise to [`MIN_RATIO`] times its
//! own and by at least one cell. Both sides must still rise (it is a local minimum). The same
//! filter is applied under all three rules, so they differ only in the adjacency condition.
//!
//! Deviation (narrowing at a junction): on coarse grids a doorway onto a corridor as narrow
//! as the door is itself a junction of the skeleton (the corridor's skeleton runs through the
//! door cell), so no degree-2 cell lies in the doorway. A plateau that reaches a junction
//! node which is no wider than the plateau counts as closed on that side: the minimum is
//! then the first cells of the branch leaving the junction, which still must widen by the
//! significance test above.

use super::Rule;
use super::graph::VoronoiGraph;
use super::skeleton::Skeleton;

/// A narrowing must widen to this many times its clearance on at least one side.
pub const MIN_RATIO: f64 = 1.5;

/// A critical point: where the map is split.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CriticalPoint {
    /// The cell (flat index).
    pub cell: u32,
    /// Clearance there, in cells (half the width of the passage).
    pub clearance: f64,
    /// The skeleton cell before it along its edge (a seed of step 3).
    pub side_a: u32,
    /// The skeleton cell after it along its edge.
    pub side_b: u32,
}

/// Buffers for finding critical points.
#[derive(Clone, Debug, Default)]
pub struct Finder {
    values: Vec<u32>,
    cells: Vec<u32>,
    prefix: Vec<u32>,
    suffix: Vec<u32>,
    candidates: Vec<usize>,
}

impl Finder {
    /// The critical points of `graph` under `rule`, appended to `out` (cleared first) in
    /// edge order, along each edge from its start.
    pub fn find(
        &mut self,
        skel: &Skeleton,
        graph: &VoronoiGraph,
        rule: Rule,
        out: &mut Vec<CriticalPoint>,
    ) {
        out.clear();
        for edge in &graph.edges {
            let chain = graph.chain(edge);
            if chain.is_empty() || (edge.a == edge.b && chain.len() < 3) {
                continue;
            }
            // the values along the edge, node cells at both ends
            self.cells.clear();
            self.cells.push(edge.a_cell);
            self.cells.extend_from_slice(chain);
            self.cells.push(edge.b_cell);
            self.values.clear();
            self.values
                .extend(self.cells.iter().map(|&c| skel.clearance2(c as usize)));
            let m = self.values.len();
            self.prefix.clear();
            self.prefix.resize(m, 0);
            self.suffix.clear();
            self.suffix.resize(m, 0);
            let mut run = 0;
            for k in 0..m {
                run = run.max(self.values[k]);
                self.prefix[k] = run;
            }
            run = 0;
            for k in (0..m).rev() {
                run = run.max(self.values[k]);
                self.suffix[k] = run;
            }
            // plateau minima among the chain cells (positions 1..m-1); a plateau may also
            // end at a junction node no wider than itself (see the module documentation)
            let ja = graph.nodes[edge.a as usize].is_junction();
            let jb = graph.nodes[edge.b as usize].is_junction();
            self.candidates.clear();
            let mut k = 1;
            while k < m - 1 {
                let v = self.values[k];
                let mut end = k;
                while end + 1 < m - 1 && self.values[end + 1] == v {
                    end += 1;
                }
                let left = self.values[k - 1];
                let right = self.values[end + 1];
                let left_ok = left > v || (k == 1 && ja);
                let right_ok = right > v || (end + 2 == m && jb);
                if left_ok && right_ok {
                    let c = f64::from(v).sqrt();
                    let wide = f64::from(self.prefix[k - 1].max(self.suffix[end + 1])).sqrt();
                    if wide >= MIN_RATIO * c && wide - c >= 1.0 {
                        self.candidates.push((k + end) / 2);
                    }
                }
                k = end + 1;
            }
            let r = self.candidates.len();
            for (idx, &pos) in self.candidates.iter().enumerate() {
                let keep = match rule {
                    Rule::Thrun => true,
                    Rule::Wurm => (idx == 0 && ja) || (idx + 1 == r && jb),
                    Rule::Holz => (idx <= 1 && ja) || (idx + 2 >= r && jb),
                };
                if keep {
                    let cell = self.cells[pos];
                    out.push(CriticalPoint {
                        cell,
                        clearance: skel.clearance(cell as usize),
                        side_a: self.cells[pos - 1],
                        side_b: self.cells[pos + 1],
                    });
                }
            }
        }
    }
}
