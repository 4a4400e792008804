//! `frontier-ros`: frontier's strategies driving a real robot through ROS 2 and Nav2.
//!
//! The node subscribes to a SLAM map (`nav_msgs/OccupancyGrid`), reads the robot's pose,
//! decides goals with any single-robot preset of frontier (`explore::strategy`) and sends
//! them to Nav2's `NavigateToPose` action — an explore_lite replacement with every strategy
//! of the papers, stop reasons, start/stop/resume, return to the start and a publish-only mode.
//!
//! The decisions, the map as belief, the parameters, the command line, ROS names and the
//! robot's pose from TF are `frontier-ros-core`'s (re-exported here as [`explorer`],
//! [`map_belief`], [`params`], [`args`], [`names`] and [`tf`]), a crate of the main
//! workspace that CI tests without DDS; this crate adds `node` (feature `node`, on by
//! default): the ROS 2 node itself (ros2-client, no ROS installation needed).
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub use frontier_ros_core::{args, explorer, map_belief, names, params, tf};
#[cfg(feature = "node")]
pub mod node;

pub use frontier_ros_core::Params;
pub use frontier_ros_core::{Check, Decision, Explorer, ExplorerConfig, GoalPose, StopReason};
