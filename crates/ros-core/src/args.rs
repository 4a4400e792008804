//! The node's command line: its own options, and the `--ros-args` that launch_ros passes.

use std::path::PathBuf;

use crate::names::{NameResolver, Remap, parse_remap};
use crate::params::domain_id;

/// The node's name when neither `--node` nor `-r __node:=` gives one.
pub const DEFAULT_NODE_NAME: &str = "frontier_explore";

/// The help text.
pub const USAGE: &str = "\
usage: frontier-ros [--params-file FILE] [--node NAME] [--domain ID] [-p NAME:=VALUE]...
                    [-r [NODE:]FROM:=TO]...
       frontier-ros --ros-args [--params-file FILE] [-p NAME:=VALUE] [-r __node:=NAME]
                    [-r __ns:=/NS] [-r [NODE:]FROM:=TO] [--log-level LEVEL] [--]

Runs frontier's exploration node: subscribes to the map and the robot's pose and sends
goals to Nav2's NavigateToPose action. Parameters come from ROS 2 parameters files
(the section of the node's name, or /**) and -p overrides; ROS_DOMAIN_ID is read when
--domain is not given. The --ros-args form is the one launch_ros passes. Names resolve
as in any ROS 2 node: relative ones (map, explore/status) in the namespace of __ns, ~/x
in the node's own; -r FROM:=TO remaps a topic or the action (both sides expanded, the
first matching rule wins; NODE: limits a rule to the node of that name). Ctrl-C,
SIGTERM and SIGHUP stop it.";

/// What the command line asks for.
#[derive(Clone, Debug, PartialEq)]
pub struct Args {
    /// `--params-file`, in order (later ones win).
    pub params_files: Vec<PathBuf>,
    /// `-p NAME:=VALUE`, in order.
    pub overrides: Vec<String>,
    /// `--node`: the node's name before the `__node` rules.
    pub node: String,
    /// `-r`: every rule, `__node` and `__ns` ones too, in order.
    pub remaps: Vec<Remap>,
    /// `--domain`.
    pub domain: Option<u16>,
    /// `-h` / `--help`.
    pub help: bool,
}

impl Default for Args {
    fn default() -> Self {
        Self {
            params_files: Vec::new(),
            overrides: Vec::new(),
            node: DEFAULT_NODE_NAME.into(),
            remaps: Vec::new(),
            domain: None,
            help: false,
        }
    }
}

impl Args {
    /// The node's name, namespace and name rules (see [`NameResolver::new`]).
    pub fn names(&self) -> Result<NameResolver, String> {
        NameResolver::new(&self.node, &self.remaps)
            .map_err(|e| format!("--node {}: {e}", self.node))
    }
}

/// Read the arguments (without the program's name). An error names the option and says
/// what was expected and found.
pub fn parse<I: IntoIterator<Item = String>>(args: I) -> Result<Args, String> {
    let mut out = Args::default();
    let mut args = args.into_iter();
    while let Some(a) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .ok_or_else(|| format!("{name}: expected a value"))
        };
        match a.as_str() {
            "--params-file" => out.params_files.push(value(&a)?.into()),
            // launch_ros's form: the same options after --ros-args, up to --.
            "--ros-args" | "--" => {}
            "-p" | "--param" => out.overrides.push(value(&a)?),
            "-r" | "--remap" => {
                let r = value(&a)?;
                out.remaps
                    .push(parse_remap(&r).map_err(|e| format!("{a} {r}: {e}"))?);
            }
            "--log-level" => {
                let _ = value(&a)?; // the log level comes from RUST_LOG
            }
            "--enable-rosout-logs"
            | "--disable-rosout-logs"
            | "--enable-stdout-logs"
            | "--disable-stdout-logs"
            | "--disable-external-lib-logs" => {}
            "--node" => out.node = value(&a)?,
            "--domain" => out.domain = Some(domain_id("--domain", &value(&a)?)?),
            "-h" | "--help" => out.help = true,
            other => return Err(format!("unexpected argument '{other}'\n{USAGE}")),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Result<Args, String> {
        parse(s.split_whitespace().map(String::from))
    }

    /// launch_ros's command line for `Node(name=..., namespace=..., parameters=[...],
    /// remappings=[...])`.
    #[test]
    fn launch_ros_arguments_give_the_name_namespace_and_rules() {
        let a = args(
            "--ros-args -r __node:=explorer -r __ns:=/robot1 --params-file p.yaml \
             -r /map:=map -r explorer:/tf:=tf --remap /tf_static:=tf_static -p seed:=3 --",
        )
        .unwrap();
        assert_eq!(a.params_files, vec![PathBuf::from("p.yaml")]);
        assert_eq!(a.overrides, vec!["seed:=3"]);
        assert_eq!(a.remaps.len(), 5);
        let n = a.names().unwrap();
        assert_eq!(n.fully_qualified_node_name(), "/robot1/explorer");
        assert_eq!(n.resolve("/map").unwrap(), "/robot1/map");
        let own = n.own_topics().unwrap();
        assert_eq!(own.status, "/robot1/explore/status");
        assert_eq!(own.tf, "/robot1/tf");
        assert_eq!(own.tf_static, "/robot1/tf_static");
        // Without any, the node is /frontier_explore and every name stays.
        let n = args("").unwrap().names().unwrap();
        assert_eq!(n.fully_qualified_node_name(), "/frontier_explore");
        assert_eq!(n.own_topics().unwrap().status, "/explore/status");
    }

    #[test]
    fn a_bad_argument_names_the_option_and_the_rule() {
        assert_eq!(
            args("-r /map").unwrap_err(),
            "-r /map: expected a remapping rule FROM:=TO (or __node:=NAME, __ns:=/NAMESPACE), \
             found '/map' without ':='"
        );
        let e = args("--ros-args --remap map:=").unwrap_err();
        assert!(
            e.starts_with("--remap map:=: expected a name after ':='"),
            "{e}"
        );
        let e = args("-r __ns:=robot1").unwrap_err();
        assert!(
            e.starts_with("-r __ns:=robot1: after '__ns:=': expected"),
            "{e}"
        );
        assert_eq!(args("-r").unwrap_err(), "-r: expected a value");
        assert_eq!(
            args("--domain 300").unwrap_err(),
            "--domain: expected 0–232, found '300'"
        );
        assert!(
            args("--map x")
                .unwrap_err()
                .starts_with("unexpected argument '--map'")
        );
        let e = args("--node my-node").unwrap().names().unwrap_err();
        assert!(e.starts_with("--node my-node: expected a node name"), "{e}");
        assert!(args("--help").unwrap().help);
    }
}
