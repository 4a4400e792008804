//! `explore`: frontiers, traversability and grid planning for frontier-based exploration.
//!
//! It follows Yamauchi (1997) for frontier cells and regions (centroids, minimum size, the
//! nearest frontier by path cost) and Holz et al. (2010) for traversability with a robot
//! clearance, the reachability map and keeping frontiers up to date as the map grows:
//!
//! - [`traversability`]: known Free and farther than the clearance from every known obstacle,
//!   maintained incrementally;
//! - [`frontier`]: the frontier definitions, a sparse frontier set, regions, and the
//!   from-scratch detector (the test oracle);
//! - [`upkeep`]: incremental frontier upkeep whose cost is proportional to the cells an
//!   observation changed, not to the map;
//! - [`plan`]: Dijkstra reachability maps, the nearest-goal search, and A*;
//! - [`decision`]: what one decision sees (team, belief, per-robot reachability maps,
//!   Yamauchi's visited and inaccessible lists);
//! - [`candidates`]: goal candidates (all frontier cells; Yamauchi's region centroids);
//! - [`assign`]: assigners (nearest by path; Holz's random-frontier baseline);
//! - [`bits`]: sets of cells as one bit per cell, for sets that touch few of a map's pages;
//! - [`strategy`]: strategies as (candidates, assigner, re-plan policy) triples and the
//!   papers' presets.
//!
//! Frontier upkeep, the planners and the decision pieces are written here rather than
//! taken from a crate: the algorithms are the point, and generic graph crates (e.g.
//! `pathfinding`) are hash-map based and far slower on dense grids.
//!
//! The exact Euclidean distance transform used for clearance maps lives in `grid::edt`.
//! Everything is deterministic and reuses its buffers across calls.
//!
//! ```
//! use explore::frontier::frontiers_from_scratch;
//! use explore::traversability::Traversability;
//! use grid::{Cell, io::parse_ascii};
//! // A known room whose right part is still unknown (`?`).
//! let known = parse_ascii("######\n#..??#\n#..??#\n######\n", 1.0).unwrap().cells;
//! let mut trav = Traversability::new(known.width(), known.height(), 0.0);
//! let all: Vec<u32> = (0..known.len() as u32).collect();
//! trav.update(&known, &all, &mut Vec::new());
//! let frontier = frontiers_from_scratch(&known, &trav);
//! // The free cells next to the unknown ones are the frontier.
//! let expect = [Cell::new(2, 1), Cell::new(2, 2)].map(|c| known.index(c) as u32);
//! assert_eq!(frontier, expect);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod assign;
mod belief_rows;
pub mod bits;
pub mod candidates;
pub mod decision;
pub mod frontier;
pub mod kmeans;
pub mod plan;
pub mod segment;
pub mod strategy;
pub mod traversability;
pub mod tsp;
pub mod upkeep;

pub use frontier::{FrontierSet, Region, frontiers_from_scratch, is_frontier};
pub use plan::{AStar, Reachability};
pub use traversability::Traversability;
pub use upkeep::FrontierUpkeep;
