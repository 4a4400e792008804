//! `frontier`: the command-line program.
//!
//! Arguments are parsed and validated in two stages (as ripgrep does): clap turns flags
//! into raw values, then each command resolves them — loading or generating the map,
//! parsing the sensor, looking up the strategy preset — into ready-to-run objects before
//! any simulation starts, so every mistake is reported up front with the flag it came from.

mod args;
mod bench_cmd;
mod demo;
mod env_cmd;
mod explore_cmd;
mod files;
mod map_cmd;
mod mcap_out;
mod optimal_cmd;
mod out;
mod report;
mod segment_cmd;
mod sensors_cmd;

use clap::{Parser, Subcommand};
use out::outln;

/// Frontier-based robot exploration: every strategy from the classic papers, on real and
/// generated maps.
#[derive(Parser)]
#[command(name = "frontier", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Explore built-in environments with the single-robot presets and print a table
    /// of path lengths (mean ± sd over seeds), like Holz et al.'s Table 1.
    Demo(demo::DemoArgs),
    /// Run one exploration and print a summary (or JSON); write pictures with --out.
    Explore(Box<explore_cmd::ExploreArgs>),
    /// Generate a built-in environment and write it as PNG or ROS YAML + PGM.
    Env(env_cmd::EnvArgs),
    /// Inspect map files.
    Map {
        #[command(subcommand)]
        command: map_cmd::MapCommand,
    },
    /// Segment a map into rooms (Holz et al.'s Figure 7) and score it against ground truth.
    Segment(Box<segment_cmd::SegmentArgs>),
    /// Offline optimal exploration path (Quattrini Li et al. 2012) and competitive ratios.
    Optimal(Box<optimal_cmd::OptimalArgs>),
    /// Compare sonar, laser and laser-limited sonar on offices furnished with clutter off
    /// the laser plane (Yamauchi 1997): map accuracy, phantom frontiers, coverage, path.
    Sensors(sensors_cmd::SensorsArgs),
    /// Run, merge, export and report benchmark studies (scenario files or built-in suites).
    Bench(Box<bench_cmd::BenchArgs>),
    /// List strategies, environments and sensors.
    List,
}

fn main() {
    die_quietly_on_closed_pipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo(a) => demo::run(a),
        Command::Explore(a) => explore_cmd::run(*a),
        Command::Env(a) => env_cmd::run(a),
        Command::Map { command } => map_cmd::run(command),
        Command::Segment(a) => segment_cmd::run(*a),
        Command::Optimal(a) => optimal_cmd::run(*a),
        Command::Bench(a) => bench_cmd::run(*a),
        Command::Sensors(a) => sensors_cmd::run(a),
        Command::List => list(),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

/// Restore the default action of SIGPIPE (end the process), which Rust's runtime sets to
/// "ignore": `frontier explore --json | head` then ends quietly when `head` stops reading,
/// as `cat` or `grep` do, instead of panicking in `println!` on the broken pipe.
#[cfg(unix)]
fn die_quietly_on_closed_pipe() {
    // SAFETY: called first thing in `main`, before any other thread exists; `signal` with
    // `SIG_DFL` installs no handler code of ours.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// SIGPIPE exists only on Unix; elsewhere a closed pipe stays an I/O error.
#[cfg(not(unix))]
fn die_quietly_on_closed_pipe() {}

fn list() -> anyhow::Result<()> {
    outln!("strategies (--strategy):");
    // names aligned to the longest single name (the family line of Faigl & Kulich's
    // presets is longer and runs over)
    let width = explore::strategy::PRESETS
        .iter()
        .map(|(name, _)| name.len())
        .filter(|&n| n <= 16)
        .max()
        .unwrap_or(10);
    for (name, what) in explore::strategy::PRESETS {
        outln!("  {name:<width$} {what}");
    }
    outln!("\nenvironments (--env):");
    env_cmd::print_kinds()?;
    outln!("\nsensors (--sensor), ranges in metres or in cells with suffix c:");
    outln!("  los:r=5                   360° line of sight (Quattrini Li et al.'s laser)");
    outln!("  footprint:r=5             every cell within r, through walls");
    outln!("  lidar:r=8,fov=180,res=1   beams over a field of view (Holz: 180°, 1°)");
    outln!("  sonar                     Yamauchi's ring of 16 sonars, 25° cones, 10 ft (r=...)");
    outln!("  laser-limited-sonar       the sonar ring, each reading capped by the planar laser");
    outln!("  laser                     planar laser, 360° at 1°, 10 ft (= lidar:r=3.048,fov=360)");
    outln!(
        "  square:r=3.5              Explore-Bench's grid simulator: the square window of side 2r"
    );
    outln!("  (sonar needs --belief evidence, the default with it; --clutter adds furniture");
    outln!("   off the laser plane to generated offices and hospitals)");
    outln!("\nbelief maps (--belief): known (ternary), reflection (Holz), evidence (Yamauchi)");
    Ok(())
}
