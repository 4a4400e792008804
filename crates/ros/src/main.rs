//! `frontier-ros`: the exploration node. See `docs/ros.md`.

use anyhow::Context as _;
use frontier_ros::Params;
use frontier_ros::args::{self, USAGE};
use frontier_ros::params::domain_id;

fn main() -> anyhow::Result<()> {
    env_logger_init();
    let args = args::parse(std::env::args().skip(1)).map_err(anyhow::Error::msg)?;
    if args.help {
        println!("{USAGE}");
        return Ok(());
    }
    // The name and namespace first: a parameters file's section may be /NS/NAME.
    let names = args.names().map_err(anyhow::Error::msg)?;
    let mut params = Params::default();
    let full_name = names.fully_qualified_node_name();
    for f in &args.params_files {
        let (p, warnings) = Params::from_file_over(params, f, &full_name)?;
        params = p;
        for w in warnings {
            log::warn!("{w}");
        }
    }
    for o in &args.overrides {
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
    let domain = match args.domain {
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
    let mode = frontier_ros::node::run_with(params, &names, &ctx, stop_rx)?;
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
