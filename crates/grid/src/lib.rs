//! `grid`: cells, flat row-major grids, rasters and map files for frontier.
//!
//! Everything else in frontier stands on these types: [`Cell`] and 8-connected motion
//! (straight steps cost 1, diagonal √2, no squeezing between two blocked cells sharing a
//! vertex), [`Grid`], the three known states [`Occ`] and a map with its resolution
//! ([`GridMap`]). Raster algorithms live here too: the exact Euclidean distance transform
//! (Felzenszwalb & Huttenlocher) and connected components. Map files (ROS map_server
//! YAML + PGM/PNG, bare bitmaps, MovingAI `.map`, ASCII art) are read and written by
//! [`io`], which also reads HouseExpo JSON floor plans with their rooms and the dungeon PNGs
//! of learned exploration with their marked start.
//!
//! `grid` knows nothing about robots, sensors or strategies.
//!
//! ```
//! use grid::{Cell, io::parse_ascii};
//! // `#` wall, `.` free, `?` unknown, at 0.1 m per cell.
//! let map = parse_ascii("#####\n#..?#\n#####\n", 0.1).unwrap();
//! assert_eq!((map.width(), map.height()), (5, 3));
//! assert!(map.cells.get(Cell::new(1, 1)).is_free());
//! assert!(!map.cells.get(Cell::new(3, 1)).is_free());
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod cell;
pub mod components;
pub mod edt;
pub mod grid;
pub mod io;
pub mod machine;
pub mod memory;
pub mod num;
pub mod occ;
pub mod resample;
pub mod units;

pub use cell::{Cell, NEIGHBOURS4, NEIGHBOURS8, SQRT2, for_each_move, step_cost};
pub use grid::Grid;
pub use num::Num;
pub use occ::{GridMap, Occ};
