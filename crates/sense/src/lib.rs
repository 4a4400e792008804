//! `sense`: sensor models that read a ground-truth grid, and belief maps built from what
//! they see.
//!
//! Sensors (all implement [`Sensor`], all described by a [`SensorSpec`] string):
//!
//! - [`LosSensor`] (`los:r=5`): the ideal 360° laser of Quattrini Li, Amigoni & Basilico
//!   (2012) — a cell is seen iff the segment between the two cell centres is at most `r`
//!   long, crosses only free cells and never squeezes between two blocked cells sharing a
//!   vertex. Exact semantics and the slow reference test ([`segment_clear`],
//!   [`los_visible`]) are in [`segment`]; the fast scan walks a precomputed, shared ray
//!   template ([`LosTemplate`]). [`shadow`] finds the same cells by shadow casting, in
//!   time ∝ the cells looked at, faster from about 20 cells of range.
//! - [`FootprintSensor`] (`footprint:r=3`): every cell within `r`, Quattrini Li et al.'s
//!   speed-up.
//! - [`LidarSensor`] (`lidar:r=8,fov=180,res=1`): Holz et al.'s planar scanner, beams
//!   traced with Amanatides & Woo's grid traversal; facing one of the eight headings of a
//!   grid move, their cells are replayed from a prefix tree made once and shared.
//! - [`SquareSensor`] (`square:r=3.5`): Explore-Bench's square window, rays from the
//!   robot's cell to every cell of the window's border, replayed from one shared tree.
//! - [`SonarSensor`]: Yamauchi's ring of 16 sonar transducers with specular reflections,
//!   off-plane obstacles, a cone-shaped inverse model for the [`EvidenceGrid`] and
//!   laser-limited sonar ([`sonar`]). It fires with a caller's RNG (range noise) and
//!   integrates graded evidence, so it is driven directly rather than through [`Sensor`].
//!
//! [`Unseen`] keeps which robot of a team sensed which cell, and so what a scan could still
//! tell; [`Sensor::scan_unseen`] reports only such cells (the lidar, the square window and
//! the line-of-sight sensor; the latter also stops each octant's shadow casting after the
//! last block holding one), so that a robot crossing explored space pays little for it.
//!
//! [`SightCache`] remembers, per cell of one ground truth, what the line-of-sight sensor
//! sees from it, for the many runs of a study on one map (the same scans, made once).
//!
//! Information gain ([`gain`]): the expected entropy drop of a predicted scan on a belief
//! ([`Sensor::predict`]), for decision-theoretic exploration.
//!
//! Belief maps (all implement [`Belief`], chosen by [`BeliefKind`]): the ternary
//! [`KnownGrid`], Holz et al.'s [`ReflectionMap`] (free iff p ≤ 0.25) and Yamauchi's
//! log-odds [`EvidenceGrid`] (prior 0.5).
//!
//! Shared conventions: cells `(x, y)` with `y` down, flat row-major indices; in a ground
//! truth, `Unknown` (outside the world) is opaque and seen as Occupied; cells outside the
//! grid are opaque and never reported; headings are radians in grid coordinates (y down).
//!
//! ```
//! use grid::{Cell, io::parse_ascii};
//! use sense::{LosSensor, Observation, Pose, Sensor};
//! let truth = parse_ascii("#######\n#.....#\n#.#...#\n#######\n", 1.0).unwrap();
//! let los = LosSensor::new(3.0).unwrap();
//! let mut seen = Observation::new();
//! los.scan(&truth.cells, Pose::new(Cell::new(1, 1), 0.0), &mut seen);
//! let idx = |x, y| truth.cells.index(Cell::new(x, y)) as u32;
//! assert!(seen.cells.iter().any(|&(i, _)| i == idx(4, 1))); // 3 cells along the row
//! assert!(!seen.cells.iter().any(|&(i, _)| i == idx(5, 1))); // beyond the range
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub(crate) mod beam;
pub mod belief;
pub mod error;
pub mod footprint;
pub mod gain;
pub mod lidar;
pub mod los;
pub mod ray_template;
pub mod segment;
pub mod sensor;
pub mod shadow;
pub mod sight_cache;
pub mod sonar;
pub mod spec;
pub mod square;
#[cfg(test)]
mod test_grids;
pub mod unseen;
pub(crate) mod window;

pub use belief::{Belief, BeliefKind, EvidenceGrid, KnownGrid, ReflectionMap};
pub use error::SenseError;
pub use footprint::{FootprintSensor, MAX_RANGE_CELLS};
pub use gain::{GainScratch, InverseModel, entropy, information_gain, information_gain_gated};
pub use lidar::LidarSensor;
pub use los::LosSensor;
pub use ray_template::{LosTemplate, MAX_TEMPLATE_RANGE_CELLS};
pub use segment::{los_visible, segment_clear};
pub use sensor::{Observation, Pose, Sensor};
pub use sight_cache::{SightBudget, SightCache};
pub use sonar::{SonarError, SonarMode, SonarParams, SonarReading, SonarSensor};
pub use spec::{Range, SensorSpec, YAMAUCHI_RANGE};
pub use square::SquareSensor;
pub use unseen::Unseen;
