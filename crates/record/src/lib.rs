//! `record`: the ROS 2 messages frontier speaks and MCAP recordings of maps and runs.
//!
//! - [`msgs`]: the standard messages a frontier node reads and writes
//!   (`nav_msgs/OccupancyGrid`, `geometry_msgs/PoseStamped`, `nav2_msgs/action/NavigateToPose`,
//!   `visualization_msgs/MarkerArray`) as serde structs whose field order is the ROS 2
//!   definition's, so that CDR (the DDS wire format and MCAP's `cdr` encoding) of the struct
//!   is the message; each carries its `.msg` text for MCAP schemas;
//! - [`occupancy`]: an `OccupancyGrid` message to a frontier map and back (rows flipped,
//!   the origin pose kept), with every malformation (wrong sizes, NaN resolution, an empty
//!   map) an error rather than a panic, and world ⇄ cell transforms;
//! - [`mcap_read`]: the last `OccupancyGrid` of a recording, as a map, read a record at a
//!   time and checked against the memory available before it is loaded;
//! - [`map_file`]: any map file a front end takes (a recording, a dungeon PNG or one of
//!   grid's formats), read by one rule;
//! - [`mcap_write`]: a run as a recording (map, belief over time, poses, goals, frontiers)
//!   that Foxglove Studio opens beside the user's own data.
//!
//! Apart from [`mcap_read::load_map`] and [`map_file::load`], which open the file they are
//! given, nothing here touches the file system: readers take bytes or any `Read`, writers
//! take any `Write + Seek`.
//!
//! A map recorded as a run and read back, as `frontier explore --map run.mcap` does:
//!
//! ```
//! use grid::io::parse_ascii;
//!
//! let map = parse_ascii("#####\n#...#\n#.#.#\n#####\n", 0.05).unwrap();
//! let mut run = record::RunWriter::new(std::io::Cursor::new(Vec::new())).unwrap();
//! run.map(0.0, &map).unwrap();
//! run.pose(0.0, 0, 0.075, 0.075, 0.0).unwrap();
//! let bytes = run.finish().unwrap().into_inner();
//!
//! let (back, topic) = record::last_map(&bytes, None).unwrap();
//! assert_eq!(topic, "/map");
//! assert_eq!(back.cells, map.cells);
//! assert!((back.resolution - map.resolution).abs() < 1e-7); // ROS's float32
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod cdr;
pub mod map_file;
pub mod mcap_read;
pub mod mcap_write;
pub mod msgs;
pub mod occupancy;

pub use mcap_read::{RecordError, last_map};
pub use mcap_write::RunWriter;
pub use occupancy::{MapFrame, MapMsgError};
