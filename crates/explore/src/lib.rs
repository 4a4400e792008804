//! `explore`: everything one decision of frontier-based exploration needs — frontiers,
//! traversability, grid planning, goal candidates, assigners, and the strategies built from
//! them. The simulation's loop (`sim`) and the ROS node's explorer both decide through
//! [`decision::decide`].
//!
//! - [`traversability`]: known Free and no closer than the robot's clearance to any known
//!   obstacle (Holz et al. 2010's `d_max`), maintained incrementally;
//! - [`frontier`]: frontier cells and regions (Yamauchi 1997), a sparse frontier set, and the
//!   from-scratch detector (the test oracle);
//! - [`upkeep`]: incremental frontier upkeep whose cost is proportional to the cells an
//!   observation changed, not to the map;
//! - [`plan`]: Holz et al.'s reachability map (Dijkstra on a bucket queue, in Sturtevant &
//!   Rabin's canonical order), the nearest-goal search (Yamauchi's nearest frontier), the
//!   same searches resumed and guided toward goals, a flood fill, and A*;
//! - [`decision`]: what one decision sees (team, belief, per-robot reachability maps,
//!   Yamauchi's visited and inaccessible lists), the state kept between decisions
//!   ([`decision::Memory`]), and the decision step itself ([`decision::decide`]);
//! - [`candidates`]: goal candidates — all frontier cells, Yamauchi's region centroids,
//!   Faigl & Kulich's (2013) representatives of free edges (RFE) and coverage candidates
//!   (CC), and decision-theoretic samples near frontiers (González-Baños & Latombe 2002);
//! - [`assign`]: assigners — nearest by path; Holz's random frontier; the coordination
//!   study's greedy (Faigl & Kulich's IA), greedy with utility and MinPos (Bautin et al.
//!   2012); Faigl & Kulich's random-order greedy (GA), Hungarian (HA), multiple-TSP (MA) and
//!   Solanas & Garcia's (SGA); the decision-theoretic utility `I·exp(−λL)`; and Holz's same
//!   segment first;
//! - [`kmeans`]: k-means with k-means++ seeding, for RFE, MA and SGA;
//! - [`tsp`]: open travelling-salesman routes by path distance, for MA;
//! - [`segment`]: room segmentation of partial maps (Holz et al. 2010 §2.4), kept between
//!   decisions for same segment first, and scored against ground-truth rooms;
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
