//! The Voronoi graph G = (V, E) of Holz et al. 2010, Figure 7 step 1: the skeleton as a
//! graph of nodes with degree and clearance.
//!
//! Nodes are the skeleton cells that are not plain curve cells: end points (one skeleton
//! neighbour), junctions (three or more; 8-adjacent junction cells form one node) and
//! isolated cells. Edges are the chains of degree-2 cells between two nodes, kept in order so
//! that clearance can be read along them. A closed loop without any node gets one node of
//! degree 2 (its lowest-index cell) so that every skeleton cell lies on an edge or is a node.

use super::skeleton::Skeleton;

/// "No node" / "no label" marker.
pub const NONE: u32 = u32::MAX;

/// What kind of node of the Voronoi graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// Three or more branches meet.
    Junction,
    /// A branch ends.
    End,
    /// A skeleton cell with no skeleton neighbour (a free component of one cell's width).
    Isolated,
    /// The chosen cell of a closed loop that has no junction.
    Loop,
}

/// A node of the Voronoi graph.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Its lowest-index cell (a junction may span a few cells).
    pub cell: u32,
    /// Number of edge ends at the node (a loop edge counts twice).
    pub degree: u32,
    /// Largest clearance over its cells, in cells.
    pub clearance: f64,
    /// Its kind.
    pub kind: NodeKind,
}

impl Node {
    /// Whether the node is a junction (degree ≥ 3).
    pub fn is_junction(&self) -> bool {
        self.degree >= 3
    }
}

/// An edge of the Voronoi graph: a chain of skeleton cells between two nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// Node at the start.
    pub a: u32,
    /// Node at the end.
    pub b: u32,
    /// The cell of node `a` the chain leaves from.
    pub a_cell: u32,
    /// The cell of node `b` the chain arrives at.
    pub b_cell: u32,
    start: u32,
    len: u32,
}

/// The Voronoi graph, with buffers reused across calls.
#[derive(Clone, Debug, Default)]
pub struct VoronoiGraph {
    /// The nodes, in order of their lowest cell index.
    pub nodes: Vec<Node>,
    /// The edges.
    pub edges: Vec<Edge>,
    chain_cells: Vec<u32>,
    node_of: Vec<u32>,
    in_chain: Vec<bool>,
    degree: Vec<u8>,
    stack: Vec<u32>,
}

impl VoronoiGraph {
    /// Empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// The degree-2 cells of `edge`, from `a` to `b`.
    pub fn chain(&self, edge: &Edge) -> &[u32] {
        &self.chain_cells[edge.start as usize..(edge.start + edge.len) as usize]
    }

    /// The node a skeleton cell belongs to, if it is a node cell.
    pub fn node_at(&self, cell: usize) -> Option<u32> {
        self.node_of.get(cell).copied().filter(|&v| v != NONE)
    }

    /// Build the graph of `skel`.
    pub fn build(&mut self, skel: &Skeleton) {
        let n = skel.width() * skel.height();
        self.nodes.clear();
        self.edges.clear();
        self.chain_cells.clear();
        self.node_of.clear();
        self.node_of.resize(n, NONE);
        self.in_chain.clear();
        self.in_chain.resize(n, false);
        self.degree.clear();
        self.degree.resize(n, 0);
        let mut nb = [0usize; 8];
        for i in skel.cells() {
            self.degree[i] = skel.neighbours(i, &mut nb) as u8;
        }
        // nodes: junction clusters, ends and isolated cells, in index order
        for i in skel.cells() {
            if self.node_of[i] != NONE || self.degree[i] == 2 {
                continue;
            }
            let id = self.nodes.len() as u32;
            let d = self.degree[i];
            let kind = match d {
                0 => NodeKind::Isolated,
                1 => NodeKind::End,
                _ => NodeKind::Junction,
            };
            let mut clearance = skel.clearance(i);
            self.node_of[i] = id;
            if kind == NodeKind::Junction {
                self.stack.clear();
                self.stack.push(i as u32);
                while let Some(c) = self.stack.pop() {
                    let k = skel.neighbours(c as usize, &mut nb);
                    for &q in &nb[..k] {
                        if self.degree[q] >= 3 && self.node_of[q] == NONE {
                            self.node_of[q] = id;
                            clearance = clearance.max(skel.clearance(q));
                            self.stack.push(q as u32);
                        }
                    }
                }
            }
            self.nodes.push(Node {
                cell: i as u32,
                degree: 0,
                clearance,
                kind,
            });
        }
        // chains from every node cell
        for p in skel.cells() {
            let a = self.node_of[p];
            if a == NONE {
                continue;
            }
            let k = skel.neighbours(p, &mut nb);
            let first = nb;
            for &q in &first[..k] {
                let b = self.node_of[q];
                if b != NONE {
                    if a < b {
                        self.push_edge(a, b, p, q, self.chain_cells.len());
                    }
                    continue;
                }
                if self.in_chain[q] {
                    continue;
                }
                self.walk(skel, a, p, q);
            }
        }
        // closed loops without nodes
        for p in skel.cells() {
            if self.degree[p] != 2 || self.in_chain[p] || self.node_of[p] != NONE {
                continue;
            }
            let id = self.nodes.len() as u32;
            self.node_of[p] = id;
            self.nodes.push(Node {
                cell: p as u32,
                degree: 0,
                clearance: skel.clearance(p),
                kind: NodeKind::Loop,
            });
            skel.neighbours(p, &mut nb);
            self.walk(skel, id, p, nb[0]);
        }
        for e in 0..self.edges.len() {
            let (a, b) = (self.edges[e].a, self.edges[e].b);
            self.nodes[a as usize].degree += 1;
            self.nodes[b as usize].degree += 1;
        }
    }

    fn push_edge(&mut self, a: u32, b: u32, a_cell: usize, b_cell: usize, start: usize) {
        self.edges.push(Edge {
            a,
            b,
            a_cell: a_cell as u32,
            b_cell: b_cell as u32,
            start: start as u32,
            len: (self.chain_cells.len() - start) as u32,
        });
    }

    /// Follow the chain that leaves node `a` at cell `from` through cell `first`.
    fn walk(&mut self, skel: &Skeleton, a: u32, from: usize, first: usize) {
        let start = self.chain_cells.len();
        let mut nb = [0usize; 8];
        let mut prev = from;
        let mut cur = first;
        loop {
            if self.node_of[cur] != NONE {
                let b = self.node_of[cur];
                self.push_edge(a, b, from, cur, start);
                return;
            }
            if self.in_chain[cur] {
                // a degenerate knot: close the chain at its own start
                self.push_edge(a, a, from, from, start);
                return;
            }
            self.in_chain[cur] = true;
            self.chain_cells.push(cur as u32);
            let k = skel.neighbours(cur, &mut nb);
            debug_assert_eq!(k, 2);
            let next = if nb[0] == prev { nb[1] } else { nb[0] };
            prev = cur;
            cur = next;
        }
    }
}
