//! `frontier-ros`: the exploration node. See `docs/ros.md`.

use std::path::PathBuf;

use anyhow::Context as _;
use frontier_ros::Params;
use frontier_ros::params::domain_id;

const USAGE: &str =
    "usage: frontier-ros [--params-file FILE] [--node NAME] [--domain ID] [-p NAME:=VALUE]...
       frontier-ros --ros-args [--params-file FILE] [-p NAME:=VALUE] [-r __node:=NAME]
                    [-r __ns:=/NS] [--log-level LEVEL] [--]

Runs frontier's exploration node: subscribes to the map and the robot's pose and sends
goals to Nav2's NavigateToPose action. Parameters come from ROS 2 parameters files
(the section of the node's name, or /**) and -p overrides; ROS_DOMAIN_ID is read when
--domain is not given. The --ros-args form is the one launch_ros passes; relative topic
names are resolved in the namespace of __ns. Ctrl-C, SIGTERM and SIGHUP stop it.";

fn main() -> anyhow::Result<()> {
    env_logger_init();
    let mut args = std::env::args().skip(1);
    let mut files: Vec<PathBuf> = Vec::new();
    let mut namespace = "/".to_string();
    let mut node = "frontier_explore".to_string();
    let mut domain: Option<u16> = None;
    let mut overrides: Vec<String> = Vec::new();
    while let Some(a) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .with_context(|| format!("{name}: expected a value"))
        };
        match a.as_str() {
            "--params-file" => files.push(value("--params-file")?.into()),
            // launch_ros's form: the same options after --ros-args, up to --.
            "--ros-args" | "--" => {}
            "--param" => overrides.push(value("--param")?),
            "-r" | "--remap" => {
                let r = value("-r")?;
                match r.split_once(":=") {
                    Some(("__node" | "__name", n)) => node = n.to_string(),
                    Some(("__ns", ns)) => namespace = ns.to_string(),
                    _ => anyhow::bail!(
                        "-r {r}: expected __node:=NAME or __ns:=/NAMESPACE (topic remaps are \
                         not taken: set map_topic, pose_topic, navigate_action, goal_topic or \
                         markers_topic)"
                    ),
                }
            }
            "--log-level" => {
                let _ = value("--log-level")?; // the log level comes from RUST_LOG
            }
            "--enable-rosout-logs"
            | "--disable-rosout-logs"
            | "--enable-stdout-logs"
            | "--disable-stdout-logs"
            | "--disable-external-lib-logs" => {}
            "--node" => node = value("--node")?,
            "--domain" => {
                let v = value("--domain")?;
                domain = Some(domain_id("--domain", &v).map_err(anyhow::Error::msg)?);
            }
            "-p" => overrides.push(value("-p")?),
            "-h" | "--help" => {
                println!("{USAGE}");
                return Ok(());
            }
            other => anyhow::bail!("unexpected argument '{other}'\n{USAGE}"),
        }
    }
    let mut params = Params::default();
    let full_name = format!("{}/{node}", namespace.trim_end_matches('/'));
    for f in &files {
        let (p, warnings) = Params::from_file_over(params, f, &full_name)?;
        params = p;
        for w in warnings {
            log::warn!("{w}");
        }
    }
    for o in &overrides {
        let (k, v) = o
            .split_once(":=")
            .with_context(|| format!("-p {o}: expected NAME:=VALUE"))?;
        if let Some(w) = params
            .set_param(k, v, false)
            .map_err(|e| anyhow::anyhow!("-p {o}: {e}"))?
        {
            log::warn!("-p {o}: {w}");
        }
    }
    params
        .resolve_names(&namespace)
        .map_err(|e| anyhow::anyhow!("-r __ns:={namespace}: {e}"))?;
    let domain = match domain {
        Some(d) => d,
        None => match std::env::var("ROS_DOMAIN_ID") {
            Ok(v) if !v.is_empty() => domain_id("ROS_DOMAIN_ID", &v).map_err(anyhow::Error::msg)?,
            _ => 0,
        },
    };
    let ctx = frontier_ros::node::context(domain)?;
    let (stop_tx, stop_rx) = async_channel::bounded(1);
    ctrlc::set_handler(move || {
        let _ = stop_tx.try_send(());
    })
    .context("cannot install the Ctrl-C handler")?;
    let mode = frontier_ros::node::run(params, &node, &ctx, stop_rx)?;
    eprintln!("frontier-ros: {mode:?}");
    Ok(())
}

/// Log to stderr at the level in RUST_LOG (default info).
fn env_logger_init() {
    struct Stderr(log::LevelFilter);
    impl log::Log for Stderr {
        fn enabled(&self, m: &log::Metadata) -> bool {
            m.level() <= self.0 && m.target().starts_with("frontier_ros")
        }
        fn log(&self, r: &log::Record) {
            if self.enabled(r.metadata()) {
                eprintln!("[{}] {}", r.level(), r.args());
            }
        }
        fn flush(&self) {}
    }
    let level = match std::env::var("RUST_LOG").as_deref() {
        Ok("debug") => log::LevelFilter::Debug,
        Ok("warn") => log::LevelFilter::Warn,
        Ok("error") => log::LevelFilter::Error,
        _ => log::LevelFilter::Info,
    };
    let _ = log::set_boxed_logger(Box::new(Stderr(level)));
    log::set_max_level(level);
}
