//! `frontier-ros`: frontier's strategies driving a real robot through ROS 2 and Nav2.
//!
//! The node subscribes to a SLAM map (`nav_msgs/OccupancyGrid`), reads the robot's pose,
//! decides goals with any single-robot preset of frontier (`explore::strategy`) and sends
//! them to Nav2's `NavigateToPose` action — an explore_lite replacement with every strategy
//! of the papers, stop reasons, start/stop/resume, return to the start and a publish-only mode.
//!
//! - [`explorer`]: the decisions, without DDS (map message → belief → goal), with the
//!   strategy's re-plan policy and Yamauchi's visited and inaccessible lists;
//! - [`map_belief`]: the received map as the belief;
//! - [`params`]: the node's parameters from a ROS 2 parameters file;
//! - `node` (feature `node`, on by default): the ROS 2 node itself (ros2-client, no ROS
//!   installation needed).
//!
//! The messages and their CDR form live in the `record` crate, shared with the MCAP reader
//! and writer of `frontier explore`.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod explorer;
pub mod map_belief;
#[cfg(feature = "node")]
pub mod node;
pub mod params;

pub use explorer::{Check, Decision, Explorer, ExplorerConfig, GoalPose, StopReason};
pub use params::Params;
