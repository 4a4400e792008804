//! The node's parameters, from a ROS 2 parameters file (YAML).
//!
//! The file has the form ROS 2 launch files pass with `--params-file`:
//!
//! ```yaml
//! frontier_explore:          # the node's name, or /** for any node
//!   ros__parameters:
//!     strategy: cf-rr
//!     sensor: "lidar:r=8,fov=360,res=0.5"
//!     planner_frequency: 1.0
//! ```
//!
//! Names shared with explore_lite mean the same: `planner_frequency` (Hz; decisions
//! happen on map updates and goal ends too, this is the fastest periodic re-check),
//! `progress_timeout` (s), `min_frontier_size` (m), `return_to_init`, `visualize`,
//! `robot_base_frame` (with `pose_type: tf`). Any other name is an error, so a misspelt
//! parameter never silently keeps its default.

use std::path::Path;

use yaml_rust2::{Yaml, YamlLoader};

/// Every parameter of the node, with its default.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Strategy preset (`cf-rr`, `yamauchi`, `cf-rr-seg`, `dt500`, ...).
    pub strategy: String,
    /// Sensor model for strategies that predict what a goal shows (`los:r=5`, `lidar:...`).
    pub sensor: String,
    /// Clearance from known obstacles, metres.
    pub clearance: f64,
    /// Periodic re-check rate, Hz (explore_lite's name).
    pub planner_frequency: f64,
    /// Seconds without progress before a goal is given up (explore_lite's name).
    pub progress_timeout: f64,
    /// Smallest frontier region that is a goal, metres (explore_lite's name).
    pub min_frontier_size: f64,
    /// Drive back to the start pose when exploration ends (explore_lite's name).
    pub return_to_init: bool,
    /// Publish frontier and candidate markers (explore_lite's name).
    pub visualize: bool,
    /// Distance to a goal at which it counts as reached, metres.
    pub goal_tolerance: f64,
    /// Only publish goals (on `goal_topic`), never send them to Nav2.
    pub publish_only: bool,
    /// Start exploring at once (else wait for `start`).
    pub autostart: bool,
    /// The map topic (OccupancyGrid, transient local).
    pub map_topic: String,
    /// The robot pose topic.
    pub pose_topic: String,
    /// Its type: `PoseWithCovarianceStamped` (AMCL, slam_toolbox) or `PoseStamped`; or
    /// `tf`: no pose topic, the pose of `robot_base_frame` in the map frame from `/tf`.
    pub pose_type: PoseType,
    /// The robot's frame in TF, with `pose_type: tf` (explore_lite's name).
    pub robot_base_frame: String,
    /// Nav2's NavigateToPose action.
    pub navigate_action: String,
    /// How the action's services map onto DDS, which depends on Nav2's RMW.
    pub service_mapping: ServiceMapping,
    /// Where goals are published (always, and only there in publish-only mode).
    pub goal_topic: String,
    /// Where markers go.
    pub markers_topic: String,
    /// Seed of the strategy's random choices.
    pub seed: u64,
    /// Refuse a map whose exploration would need more than this many MiB (0: only the
    /// memory the machine has available is checked).
    pub memory_mb: u64,
}

/// The message type of the pose topic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PoseType {
    /// `geometry_msgs/msg/PoseWithCovarianceStamped` (AMCL's `/amcl_pose`, slam_toolbox's `/pose`).
    WithCovariance,
    /// `geometry_msgs/msg/PoseStamped`.
    Stamped,
    /// No pose topic: `tf2_msgs/msg/TFMessage` on `/tf` and `/tf_static`.
    Tf,
}

/// How ROS 2 services (the action's goal, result and cancel calls) are carried over DDS:
/// the RMWs do it differently and do not understand one another's way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ServiceMapping {
    /// From `RMW_IMPLEMENTATION` as ROS 2 reads it: `rmw_cyclonedds_cpp` → `Cyclone`, any
    /// other or none (Fast DDS, the default RMW) → `Enhanced`.
    Auto,
    /// The request id in the RTPS message (OMG RPC over DDS, "enhanced"): rmw_fastrtps.
    Enhanced,
    /// The request id at the head of the payload: rmw_cyclonedds_cpp.
    Cyclone,
}

impl ServiceMapping {
    /// `Auto` decided by the value of `RMW_IMPLEMENTATION` (`None`: unset); others as they
    /// are.
    pub fn resolve(self, rmw_implementation: Option<&str>) -> ServiceMapping {
        match (self, rmw_implementation.map(str::trim)) {
            (ServiceMapping::Auto, Some("rmw_cyclonedds_cpp")) => ServiceMapping::Cyclone,
            (ServiceMapping::Auto, _) => ServiceMapping::Enhanced,
            (m, _) => m,
        }
    }
}

impl Default for Params {
    fn default() -> Self {
        Self {
            strategy: "cf-rr".into(),
            sensor: "lidar:r=8,fov=360,res=0.5".into(),
            clearance: 0.2,
            planner_frequency: 1.0,
            progress_timeout: 30.0,
            min_frontier_size: 0.5,
            return_to_init: false,
            visualize: true,
            goal_tolerance: 0.5,
            publish_only: false,
            autostart: true,
            map_topic: "/map".into(),
            pose_topic: "/pose".into(),
            pose_type: PoseType::WithCovariance,
            robot_base_frame: "base_link".into(),
            navigate_action: "/navigate_to_pose".into(),
            service_mapping: ServiceMapping::Auto,
            goal_topic: crate::names::GOAL_TOPIC.into(),
            markers_topic: crate::names::MARKERS_TOPIC.into(),
            seed: 0,
            memory_mb: 0,
        }
    }
}

/// A parameters file or value that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{source_name}: {what}")]
pub struct ParamError {
    /// The file (or `--param`) the problem is in.
    pub source_name: String,
    /// What was expected and what was found.
    pub what: String,
}

impl Params {
    /// Read the parameters for node `node` from the YAML file at `path`, over the defaults,
    /// with the warnings about what was taken but not used (see [`Params::apply_yaml`]).
    pub fn from_file(path: &Path, node: &str) -> Result<(Self, Vec<String>), ParamError> {
        Self::from_file_over(Params::default(), path, node)
    }

    /// [`Params::from_file`] over `params` rather than the defaults (for several files, as
    /// ROS 2 takes them: later ones win).
    pub fn from_file_over(
        mut params: Params,
        path: &Path,
        node: &str,
    ) -> Result<(Self, Vec<String>), ParamError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ParamError {
            source_name: name.clone(),
            what: format!("cannot read: {e}"),
        })?;
        let warnings = params.apply_yaml(&text, node, &name)?;
        Ok((params, warnings))
    }

    /// Resolve the names the parameters give (`map_topic`, …, `navigate_action`) as the node
    /// `names` describes resolves them: expanded to fully qualified names in its namespace
    /// (`map` in `/robot1` is `/robot1/map`, `~/goal` is `/robot1/NODE/goal`), then remapped
    /// by its rules. An error names the parameter and its value.
    pub fn resolve_names(&mut self, names: &crate::names::NameResolver) -> Result<(), String> {
        for (param, name) in [
            ("map_topic", &mut self.map_topic),
            ("pose_topic", &mut self.pose_topic),
            ("navigate_action", &mut self.navigate_action),
            ("goal_topic", &mut self.goal_topic),
            ("markers_topic", &mut self.markers_topic),
        ] {
            *name = names.resolve(name).map_err(|why| {
                format!(
                    "{param}: expected a ROS 2 name ({}), found '{name}' ({why})",
                    crate::names::NAME_FORM
                )
            })?;
        }
        Ok(())
    }

    /// Apply the parameters of `node` (or `/**`) in YAML `text` from `source_name`; returns
    /// warnings, each naming the source: `use_sim_time` (taken, though the node times with
    /// the wall clock), and names of the shared `/**` section that are not the node's (such
    /// a section is meant for every node of a launch file), which are skipped.
    pub fn apply_yaml(
        &mut self,
        text: &str,
        node: &str,
        source_name: &str,
    ) -> Result<Vec<String>, ParamError> {
        let err = |what: String| ParamError {
            source_name: source_name.into(),
            what,
        };
        let docs = YamlLoader::load_from_str(text).map_err(|e| err(format!("not YAML: {e}")))?;
        let Some(Yaml::Hash(top)) = docs.first() else {
            return Err(err(
                "expected a mapping of node names to ros__parameters".into()
            ));
        };
        let mut found = false;
        let mut warnings = Vec::new();
        for (k, v) in top {
            let key = k.as_str().unwrap_or("");
            let bare = key.trim_start_matches('/');
            // The node's name, bare or with its namespace (`/ns/node`, as launch_ros writes).
            let full = node.trim_start_matches('/');
            let base = full.rsplit('/').next().unwrap_or(full);
            if key != "/**" && bare != full && bare != base {
                continue;
            }
            let Some(params) = v["ros__parameters"].as_hash() else {
                return Err(err(format!("{key}: expected a ros__parameters mapping")));
            };
            found = true;
            for (pk, pv) in params {
                let name = pk
                    .as_str()
                    .ok_or_else(|| err("a parameter name is not a string".into()))?;
                if let Some(w) = self
                    .set_param(name, &yaml_value(pv), key == "/**")
                    .map_err(err)?
                {
                    warnings.push(format!("{source_name}: {w}"));
                }
            }
        }
        if !found {
            return Err(err(format!(
                "expected a section for node {node} (or /**), found none"
            )));
        }
        Ok(warnings)
    }

    /// Set one parameter as [`Params::set`] does, but take `use_sim_time` (with a warning
    /// when true: the node times goals with the wall clock, not `/clock`), and, when the
    /// parameter comes from a section `shared` by every node (`/**`), warn about a name that
    /// is not the node's rather than refuse it. `Ok(Some(w))`: set or skipped, with warning
    /// `w`.
    pub fn set_param(
        &mut self,
        name: &str,
        value: &str,
        shared: bool,
    ) -> Result<Option<String>, String> {
        if name == "use_sim_time" {
            return match value {
                "true" | "True" => Ok(Some(
                    "use_sim_time: true taken, but the node times progress_timeout and \
                     planner_frequency with the wall clock, not /clock"
                        .into(),
                )),
                "false" | "False" => Ok(None),
                _ => Err(format!(
                    "use_sim_time: expected true or false, found '{value}'"
                )),
            };
        }
        match self.set(name, value) {
            Err(e) if shared && e.starts_with("unknown parameter") => Ok(Some(format!(
                "parameter '{name}' of the shared /** section is not one of this node's: \
                 skipped"
            ))),
            r => r.map(|()| None),
        }
    }

    /// Set one parameter from its text form (as on a command line, `name:=value`).
    pub fn set(&mut self, name: &str, value: &str) -> Result<(), String> {
        fn num(name: &str, v: &str, min: f64) -> Result<f64, String> {
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() && x >= min => Ok(x),
                _ => Err(format!("{name}: expected a number ≥ {min}, found '{v}'")),
            }
        }
        fn bounded(name: &str, v: &str) -> Result<f64, String> {
            let (min, max, unit) = bounds(name).expect("a bounded parameter");
            match v.parse::<f64>() {
                Ok(x) if (min..=max).contains(&x) => Ok(x),
                _ => Err(format!(
                    "{name}: expected a number from {min} to {max} {unit}, found '{v}'"
                )),
            }
        }
        fn flag(name: &str, v: &str) -> Result<bool, String> {
            match v {
                "true" | "True" => Ok(true),
                "false" | "False" => Ok(false),
                _ => Err(format!("{name}: expected true or false, found '{v}'")),
            }
        }
        fn topic(name: &str, v: &str) -> Result<String, String> {
            if v.is_empty() || v.contains(char::is_whitespace) {
                Err(format!("{name}: expected a topic name, found '{v}'"))
            } else {
                Ok(v.to_string())
            }
        }
        match name {
            "strategy" => {
                explore::strategy::Strategy::preset(value).map_err(|e| format!("strategy: {e}"))?;
                self.strategy = value.into();
            }
            "sensor" => {
                value
                    .parse::<sense::SensorSpec>()
                    .map_err(|e| format!("sensor: {e}"))?;
                self.sensor = value.into();
            }
            "clearance" => self.clearance = bounded(name, value)?,
            "planner_frequency" => self.planner_frequency = bounded(name, value)?,
            "progress_timeout" => self.progress_timeout = bounded(name, value)?,
            "min_frontier_size" => self.min_frontier_size = num(name, value, 0.0)?,
            "goal_tolerance" => self.goal_tolerance = num(name, value, 0.0)?,
            "return_to_init" => self.return_to_init = flag(name, value)?,
            "visualize" => self.visualize = flag(name, value)?,
            "publish_only" => self.publish_only = flag(name, value)?,
            "autostart" => self.autostart = flag(name, value)?,
            "map_topic" => self.map_topic = topic(name, value)?,
            "pose_topic" => self.pose_topic = topic(name, value)?,
            "navigate_action" => self.navigate_action = topic(name, value)?,
            "goal_topic" => self.goal_topic = topic(name, value)?,
            "markers_topic" => self.markers_topic = topic(name, value)?,
            "pose_type" => {
                self.pose_type = match value {
                    "PoseWithCovarianceStamped" => PoseType::WithCovariance,
                    "PoseStamped" => PoseType::Stamped,
                    "tf" => PoseType::Tf,
                    _ => {
                        return Err(format!(
                            "pose_type: expected PoseWithCovarianceStamped, PoseStamped or tf, found '{value}'"
                        ));
                    }
                }
            }
            "robot_base_frame" => {
                let frame = crate::tf::frame_name(value);
                if frame.is_empty() || frame.contains(char::is_whitespace) {
                    return Err(format!(
                        "robot_base_frame: expected a frame name, found '{value}'"
                    ));
                }
                self.robot_base_frame = frame.into();
            }
            "service_mapping" => {
                self.service_mapping = match value {
                    "auto" => ServiceMapping::Auto,
                    "enhanced" => ServiceMapping::Enhanced,
                    "cyclone" => ServiceMapping::Cyclone,
                    _ => {
                        return Err(format!(
                            "service_mapping: expected auto, enhanced or cyclone, found '{value}'"
                        ));
                    }
                }
            }
            "seed" => {
                self.seed = value.parse().map_err(|_| {
                    format!("seed: expected a non-negative integer, found '{value}'")
                })?
            }
            "memory_mb" => {
                self.memory_mb = value.parse().map_err(|_| {
                    format!(
                        "memory_mb: expected a non-negative integer of MiB (0: no budget), \
                         found '{value}'"
                    )
                })?
            }
            _ => {
                return Err(format!(
                    "unknown parameter '{name}': expected one of strategy, sensor, clearance, \
                     planner_frequency, progress_timeout, min_frontier_size, goal_tolerance, \
                     return_to_init, visualize, publish_only, autostart, map_topic, pose_topic, \
                     pose_type, robot_base_frame, navigate_action, service_mapping, goal_topic, \
                     markers_topic, seed, memory_mb"
                ));
            }
        }
        Ok(())
    }

    /// Check the bounded numbers again (the fields are public, so they may have been set
    /// without [`Params::set`]).
    pub fn validate(&self) -> Result<(), String> {
        for (name, v) in [
            ("planner_frequency", self.planner_frequency),
            ("progress_timeout", self.progress_timeout),
            ("clearance", self.clearance),
        ] {
            let (min, max, unit) = bounds(name).expect("a bounded parameter");
            if !(min..=max).contains(&v) {
                return Err(format!(
                    "{name}: expected a number from {min} to {max} {unit}, found '{v}'"
                ));
            }
        }
        Ok(())
    }

    /// The period of the periodic re-check, from `planner_frequency`.
    pub fn planner_period(&self) -> Result<std::time::Duration, String> {
        self.validate()?;
        std::time::Duration::try_from_secs_f64(1.0 / self.planner_frequency).map_err(|e| {
            format!(
                "planner_frequency: expected a rate giving a period, found '{}' ({e})",
                self.planner_frequency
            )
        })
    }

    /// The explorer configuration these parameters give.
    pub fn explorer_config(&self) -> Result<crate::explorer::ExplorerConfig, String> {
        self.validate()?;
        let strategy =
            explore::strategy::Strategy::preset(&self.strategy).map_err(|e| e.to_string())?;
        let sensor = self
            .sensor
            .parse()
            .map_err(|e: sense::SenseError| e.to_string())?;
        Ok(crate::explorer::ExplorerConfig {
            strategy,
            sensor,
            clearance_m: self.clearance,
            min_frontier_size_m: self.min_frontier_size,
            progress_timeout_s: self.progress_timeout,
            goal_tolerance_m: self.goal_tolerance,
            seed: self.seed,
            memory_mb: (self.memory_mb > 0).then_some(self.memory_mb),
        })
    }
}

/// The smallest and largest value of a bounded number parameter, and its unit.
///
/// `planner_frequency` is the rate of a timer: below 0.01 Hz the period overflows no
/// `Duration` but is longer than a run, and above 100 Hz the re-checks only queue up behind
/// one another. `progress_timeout` below 1 s would give up a goal before Nav2 has planned a
/// path to it. `clearance` is a robot's radius: beyond 5 m, the disk the frontier upkeep
/// keeps per cell grows towards the map's side (hundreds of MB per rebuild) for no robot.
fn bounds(name: &str) -> Option<(f64, f64, &'static str)> {
    match name {
        "planner_frequency" => Some((0.01, 100.0, "Hz")),
        "progress_timeout" => Some((1.0, 86_400.0, "s")),
        "clearance" => Some((0.0, 5.0, "m")),
        _ => None,
    }
}

/// The highest DDS domain id ROS 2 uses (ROS_DOMAIN_ID; the ports of higher ones overflow
/// on Linux).
pub const MAX_DOMAIN_ID: u16 = 232;

/// A DDS domain id from `source` (`--domain`, `ROS_DOMAIN_ID`): 0 to [`MAX_DOMAIN_ID`].
pub fn domain_id(source: &str, value: &str) -> Result<u16, String> {
    match value.trim().parse::<u16>() {
        Ok(d) if d <= MAX_DOMAIN_ID => Ok(d),
        _ => Err(format!(
            "{source}: expected 0–{MAX_DOMAIN_ID}, found '{value}'"
        )),
    }
}

/// A YAML scalar as the text `Params::set` takes.
fn yaml_value(v: &Yaml) -> String {
    match v {
        Yaml::Real(s) | Yaml::String(s) => s.clone(),
        Yaml::Integer(i) => i.to_string(),
        Yaml::Boolean(b) => b.to_string(),
        Yaml::Null => String::new(),
        other => format!("{other:?}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = "frontier_explore:\n  ros__parameters:\n    strategy: yamauchi\n    planner_frequency: 2\n    progress_timeout: 12.5\n    min_frontier_size: 0.3\n    return_to_init: true\n    sensor: \"los:r=4\"\n    pose_type: PoseStamped\n";

    #[test]
    fn a_params_file_sets_what_it_names() {
        let mut p = Params::default();
        p.apply_yaml(FILE, "frontier_explore", "p.yaml").unwrap();
        assert_eq!(p.strategy, "yamauchi");
        assert_eq!(p.planner_frequency, 2.0);
        assert_eq!(p.progress_timeout, 12.5);
        assert_eq!(p.min_frontier_size, 0.3);
        assert!(p.return_to_init);
        assert_eq!(p.sensor, "los:r=4");
        assert_eq!(p.pose_type, PoseType::Stamped);
        assert_eq!(p.clearance, Params::default().clearance);
        let c = p.explorer_config().unwrap();
        assert_eq!(c.strategy.name, "yamauchi");
    }

    #[test]
    fn the_example_params_file_is_valid() {
        let mut p = Params::default();
        // The file shipped beside the node (crates/ros/params).
        let text = include_str!("../../ros/params/explore.yaml");
        p.apply_yaml(text, "frontier_explore", "explore.yaml")
            .unwrap();
        assert_eq!((p.clearance, p.return_to_init), (0.25, true));
        p.explorer_config().unwrap();
    }

    /// `memory_mb` is a budget in MiB for the explorer, 0 for none.
    #[test]
    fn memory_mb_is_a_budget_or_none() {
        let mut p = Params::default();
        assert_eq!(p.explorer_config().unwrap().memory_mb, None);
        p.set("memory_mb", "512").unwrap();
        assert_eq!(p.explorer_config().unwrap().memory_mb, Some(512));
        p.set("memory_mb", "0").unwrap();
        assert_eq!(p.explorer_config().unwrap().memory_mb, None);
        let e = p.set("memory_mb", "-1").unwrap_err();
        assert!(
            e.starts_with("memory_mb: expected a non-negative integer"),
            "{e}"
        );
    }

    /// The example file is where docs/ros.md sends a user for the parameters: it sets every
    /// one the node takes (those its refusal of an unknown one lists).
    #[test]
    fn the_example_params_file_names_every_parameter() {
        let text = include_str!("../../ros/params/explore.yaml");
        let e = Params::default().set("zzz_unknown", "1").unwrap_err();
        let list = e.split("expected one of ").nth(1).expect("a list of names");
        for name in list.split(", ") {
            assert!(
                text.lines()
                    .any(|l| l.trim_start().starts_with(&format!("{name}:"))),
                "explore.yaml does not set `{name}`"
            );
        }
    }

    #[test]
    fn wildcard_sections_apply_to_any_node() {
        let mut p = Params::default();
        p.apply_yaml("/**:\n  ros__parameters:\n    seed: 9\n", "x", "p.yaml")
            .unwrap();
        assert_eq!(p.seed, 9);
    }

    #[test]
    fn mistakes_name_the_file_the_parameter_and_the_value() {
        let mut p = Params::default();
        let e = p
            .apply_yaml("n:\n  ros__parameters:\n    stratgy: cf\n", "n", "p.yaml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.yaml: unknown parameter 'stratgy'"), "{e}");
        let e = p
            .apply_yaml(
                "n:\n  ros__parameters:\n    progress_timeout: .nan\n",
                "n",
                "p.yaml",
            )
            .unwrap_err()
            .to_string();
        assert!(e.contains("progress_timeout: expected a number"), "{e}");
        let e = p
            .apply_yaml("m:\n  ros__parameters: {}\n", "n", "p.yaml")
            .unwrap_err();
        assert!(e.what.contains("section for node n"), "{e}");
        assert!(
            p.set("strategy", "closest")
                .unwrap_err()
                .contains("unknown strategy")
        );
        assert!(p.set("sensor", "radar:r=5").is_err());
        assert!(p.set("planner_frequency", "0").is_err());
        assert!(p.apply_yaml(": : :", "n", "p.yaml").is_err());
        let e = p.set("service_mapping", "fastdds").unwrap_err();
        assert_eq!(
            e,
            "service_mapping: expected auto, enhanced or cyclone, found 'fastdds'"
        );
    }

    /// `planner_frequency: 1e-300` panicked in `Duration::from_secs_f64` and `1e12` gave a
    /// zero period whose timer flooded the event queue; `progress_timeout: 0` gave every
    /// goal up at once.
    #[test]
    fn an_extreme_planner_frequency_or_progress_timeout_is_refused() {
        let mut p = Params::default();
        for v in ["1e-300", "1e12", "0", "-1", "inf", "NaN", "0.001", "101"] {
            let e = p.set("planner_frequency", v).unwrap_err();
            assert_eq!(
                e,
                format!("planner_frequency: expected a number from 0.01 to 100 Hz, found '{v}'")
            );
        }
        for v in ["0", "0.5", "-3", "1e300"] {
            let e = p.set("progress_timeout", v).unwrap_err();
            assert!(
                e.starts_with("progress_timeout: expected a number from 1 to 86400 s"),
                "{e}"
            );
            assert!(e.ends_with(&format!("found '{v}'")), "{e}");
        }
        let e = p
            .apply_yaml(
                "n:\n  ros__parameters:\n    planner_frequency: 1.0e12\n",
                "n",
                "p.yaml",
            )
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "p.yaml: planner_frequency: expected a number from 0.01 to 100 Hz, found '1.0e12'"
        );
        for (f, period) in [("0.01", 100.0), ("100", 0.01), ("2", 0.5)] {
            p.set("planner_frequency", f).unwrap();
            assert_eq!(p.planner_period().unwrap().as_secs_f64(), period);
        }
        p.set("progress_timeout", "1").unwrap();
        // Set directly, the fields are checked when used.
        p.planner_frequency = 1e-300;
        assert!(p.planner_period().is_err());
        assert!(p.explorer_config().is_err());
        p.planner_frequency = 1.0;
        p.progress_timeout = 0.0;
        assert!(
            p.explorer_config()
                .unwrap_err()
                .starts_with("progress_timeout")
        );
    }

    /// `clearance` had no upper bound: the clearance disk grew towards the map's side,
    /// hundreds of MB per rebuild.
    #[test]
    fn a_clearance_beyond_a_robots_size_is_refused() {
        let mut p = Params::default();
        for v in ["5.01", "1e6", "-0.1", "inf"] {
            assert_eq!(
                p.set("clearance", v).unwrap_err(),
                format!("clearance: expected a number from 0 to 5 m, found '{v}'")
            );
        }
        p.set("clearance", "5").unwrap();
        p.set("clearance", "0").unwrap();
        p.clearance = 50.0;
        assert!(p.explorer_config().unwrap_err().starts_with("clearance"));
    }

    /// `--domain 9999` and `ROS_DOMAIN_ID=500` were taken despite "expected 0–232".
    #[test]
    fn a_domain_id_above_232_is_refused() {
        assert_eq!(domain_id("--domain", "0"), Ok(0));
        assert_eq!(domain_id("ROS_DOMAIN_ID", " 232 "), Ok(232));
        for v in ["233", "9999", "-1", "x", ""] {
            assert_eq!(
                domain_id("ROS_DOMAIN_ID", v).unwrap_err(),
                format!("ROS_DOMAIN_ID: expected 0–232, found '{v}'")
            );
        }
    }

    /// `use_sim_time`, which launch files set for every node, was a fatal "unknown
    /// parameter", and so was any name of another node in a shared `/**` section.
    #[test]
    fn use_sim_time_and_other_nodes_shared_parameters_warn_not_fail() {
        let mut p = Params::default();
        let w = p
            .apply_yaml(
                "/**:\n  ros__parameters:\n    use_sim_time: true\n    \
                 controller_frequency: 20.0\n    seed: 3\n",
                "n",
                "p.yaml",
            )
            .unwrap();
        assert_eq!(p.seed, 3);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!(
            w[0].starts_with("p.yaml: use_sim_time: true taken"),
            "{w:?}"
        );
        assert_eq!(
            w[1],
            "p.yaml: parameter 'controller_frequency' of the shared /** section is not one \
             of this node's: skipped"
        );
        // In the node's own section a misspelt name is still an error.
        let e = p
            .apply_yaml(
                "n:\n  ros__parameters:\n    controller_frequency: 20.0\n",
                "n",
                "p.yaml",
            )
            .unwrap_err();
        assert!(e.what.starts_with("unknown parameter"), "{e}");
        assert_eq!(p.set_param("use_sim_time", "false", false), Ok(None));
        assert!(p.set_param("use_sim_time", "yes", false).is_err());
    }

    /// launch_ros starts a node with `--ros-args -r __ns:=/robot1 --params-file F`, where F
    /// has a section `/robot1/frontier_explore`; relative topic names are the namespace's.
    #[test]
    fn a_namespace_resolves_relative_names_and_finds_its_section() {
        let mut p = Params::default();
        p.apply_yaml(
            "/robot1/frontier_explore:\n  ros__parameters:\n    map_topic: map\n    seed: 4\n",
            "/robot1/frontier_explore",
            "p.yaml",
        )
        .unwrap();
        assert_eq!(p.seed, 4);
        let robot1 = |rules: &[&str]| {
            let rules: Vec<_> = rules
                .iter()
                .map(|r| crate::names::parse_remap(r).unwrap())
                .collect();
            crate::names::NameResolver::new("frontier_explore", &rules).unwrap()
        };
        p.resolve_names(&robot1(&["__ns:=/robot1"])).unwrap();
        assert_eq!(p.map_topic, "/robot1/map");
        assert_eq!(p.pose_topic, "/pose");
        let mut q = Params::default();
        q.apply_yaml(
            "frontier_explore:\n  ros__parameters:\n    seed: 5\n",
            "/robot1/frontier_explore",
            "p.yaml",
        )
        .unwrap();
        assert_eq!(q.seed, 5);
        q.map_topic = "map".into();
        q.resolve_names(&robot1(&[])).unwrap();
        assert_eq!(q.map_topic, "/map");
        assert!(crate::names::parse_remap("__ns:=robot1").is_err());
    }

    /// Topic remaps (`-r /map:=/x`, a launch file's `remappings`) were refused with an
    /// error; they apply to the parameters' names after their expansion, as in rcl.
    #[test]
    fn remaps_apply_to_the_names_the_parameters_give() {
        let rules: Vec<_> = [
            "__ns:=/robot1",
            "map:=/slam/map",
            "/pose:=amcl_pose",
            "other:navigate_to_pose:=/x",
            "frontier_explore:/navigate_to_pose:=navigate_to_pose",
        ]
        .iter()
        .map(|r| crate::names::parse_remap(r).unwrap())
        .collect();
        let names = crate::names::NameResolver::new("frontier_explore", &rules).unwrap();
        let mut p = Params {
            map_topic: "map".into(),
            ..Params::default()
        };
        p.resolve_names(&names).unwrap();
        assert_eq!(p.map_topic, "/slam/map");
        assert_eq!(p.pose_topic, "/robot1/amcl_pose");
        assert_eq!(p.navigate_action, "/robot1/navigate_to_pose");
        assert_eq!(p.goal_topic, "/robot1/explore/goal");
        assert_eq!(p.markers_topic, "/robot1/explore/frontiers");
        let mut q = Params::default();
        q.set("goal_topic", "ns/~goal").unwrap();
        assert_eq!(
            q.resolve_names(&names).unwrap_err(),
            "goal_topic: expected a ROS 2 name (letters, digits and '_' between '/'), found \
             'ns/~goal' ('~' other than as '~' or '~/…' at the start)"
        );
    }

    #[test]
    fn the_service_mapping_follows_the_rmw_unless_named() {
        use ServiceMapping::*;
        assert_eq!(Auto.resolve(None), Enhanced);
        assert_eq!(Auto.resolve(Some("rmw_fastrtps_cpp")), Enhanced);
        assert_eq!(Auto.resolve(Some("rmw_fastrtps_dynamic_cpp")), Enhanced);
        assert_eq!(Auto.resolve(Some("rmw_cyclonedds_cpp")), Cyclone);
        assert_eq!(Cyclone.resolve(Some("rmw_fastrtps_cpp")), Cyclone);
        assert_eq!(Enhanced.resolve(Some("rmw_cyclonedds_cpp")), Enhanced);
        let mut p = Params::default();
        assert_eq!(p.service_mapping, Auto);
        p.apply_yaml(
            "n:\n  ros__parameters:\n    service_mapping: cyclone\n",
            "n",
            "p.yaml",
        )
        .unwrap();
        assert_eq!(p.service_mapping, Cyclone);
    }

    #[test]
    fn the_pose_from_tf_names_the_robot_frame() {
        let mut p = Params::default();
        assert_eq!(p.robot_base_frame, "base_link");
        p.apply_yaml(
            "n:\n  ros__parameters:\n    pose_type: tf\n    robot_base_frame: /base_footprint\n",
            "n",
            "p.yaml",
        )
        .unwrap();
        assert_eq!(
            (p.pose_type, p.robot_base_frame.as_str()),
            (PoseType::Tf, "base_footprint")
        );
        assert_eq!(
            p.set("pose_type", "Odometry").unwrap_err(),
            "pose_type: expected PoseWithCovarianceStamped, PoseStamped or tf, found 'Odometry'"
        );
        assert!(p.set("robot_base_frame", "").is_err());
    }
}
