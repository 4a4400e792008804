//! `frontier-ros-core`: the decisions of frontier's ROS 2 node, without DDS.
//!
//! Everything of the exploration node (`crates/ros`, `frontier-ros`) that can be tested
//! without a DDS stack lives here, in the main workspace, so that `cargo test --workspace`
//! and CI run its tests; the node itself adds only ros2-client's topics and actions.
//!
//! - [`explorer`]: the decisions (map message → belief → goal), with the strategy's
//!   re-plan policy and Yamauchi's visited and inaccessible lists;
//! - [`map_belief`]: the received map as the belief;
//! - [`params`]: the node's parameters from a ROS 2 parameters file;
//! - [`args`] and [`names`]: the command line (`--ros-args` as launch_ros passes it), and
//!   the node's names resolved as rcl resolves them (namespace, remapping rules);
//! - [`tf`]: the robot's pose from the TF tree, for robots that publish no pose topic.
//!
//! The messages and their CDR form live in the `record` crate, shared with the MCAP reader
//! and writer of `frontier explore`.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod args;
pub mod explorer;
pub mod map_belief;
pub mod names;
pub mod params;
pub mod tf;

pub use explorer::{Check, Decision, Explorer, ExplorerConfig, GoalPose, StopReason};
pub use params::Params;
