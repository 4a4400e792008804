//! `frontier bench`: run a study (a scenario file or a built-in suite) into a resumable
//! SQLite database, and merge, export and report such databases (issue 9).
//!
//! ```text
//! frontier bench study.toml [--db study.sqlite] [--threads N] [--shard I/N] [--trials N]
//!                            [--memory-mb MIB]
//! frontier bench --suite quick --report quick-report
//! frontier bench merge all.sqlite shard-*.sqlite
//! frontier bench export all.sqlite --csv all.csv
//! frontier bench report all.sqlite --out report/
//! ```

use crate::out::outln;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};

/// Flags of `frontier bench`.
#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct BenchArgs {
    /// What to do besides running a study.
    #[command(subcommand)]
    pub command: Option<BenchCommand>,
    /// Running a study.
    #[command(flatten)]
    pub run: RunArgs,
}

/// Flags of running a study.
#[derive(Args, Debug)]
pub struct RunArgs {
    /// Scenario file (TOML; its keys are listed in docs/usage.md, "Your own study").
    #[arg(conflicts_with = "suite", required_unless_present = "suite")]
    pub scenario: Option<PathBuf>,
    /// Built-in suite: quick, holz2010, holz2010-real (with --maps), multirobot, faigl2013,
    /// faigl2013-real (with --maps), quattrini2012.
    #[arg(long)]
    pub suite: Option<String>,
    /// The folder of ROS map_server .yaml maps a map-folder suite runs on (holz2010-real,
    /// faigl2013-real).
    #[arg(long, requires = "suite")]
    pub maps: Option<PathBuf>,
    /// Results database; re-running with the same database resumes (default: NAME.sqlite).
    #[arg(long)]
    pub db: Option<PathBuf>,
    /// Worker threads (default: one per core; never more than the trials to run).
    #[arg(allow_negative_numbers = true, long, short = 'j')]
    pub threads: Option<usize>,
    /// Run only shard I of N (1-based, e.g. 3/8), for job arrays.
    #[arg(allow_hyphen_values = true, long)]
    pub shard: Option<String>,
    /// Run at most this many of the pending trials.
    #[arg(allow_negative_numbers = true, long)]
    pub limit: Option<usize>,
    /// Run only the first N trials of every start variant (a first look at every cell; the
    /// rest can follow later into the same database).
    #[arg(allow_negative_numbers = true, long, value_name = "N")]
    pub trials: Option<u32>,
    /// Only print the plan (environments, variants, trial count); run nothing.
    #[arg(long)]
    pub dry_run: bool,
    /// After the run, write report.md and report.html into this directory.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Never draw the progress bar.
    #[arg(long)]
    pub no_progress: bool,
    /// Refuse the study up front if its environments, or its largest trials one per
    /// thread, would need more than this many MiB (the memory the machine has available
    /// is always checked).
    #[arg(allow_negative_numbers = true, long, value_parser = crate::args::parse_memory_mb)]
    pub memory_mb: Option<u64>,
}

/// Subcommands of `frontier bench`.
#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Combine shard databases into one (trials already in OUT are kept).
    Merge {
        /// The database to write (created if missing).
        out: PathBuf,
        /// Shard databases.
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
    },
    /// Write every trial of a database as one flat CSV table.
    Export {
        /// The database.
        db: PathBuf,
        /// The CSV file to write.
        #[arg(long)]
        csv: PathBuf,
    },
    /// Write report.md and a self-contained report.html (tables, tests, charts).
    Report {
        /// The database.
        db: PathBuf,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// Significance level of the +/=/- verdicts.
        #[arg(allow_negative_numbers = true, long, default_value_t = 0.001)]
        alpha: f64,
    },
    /// List the built-in suites.
    Suites,
}

/// Run `frontier bench`.
pub fn run(a: BenchArgs) -> Result<()> {
    match a.command {
        Some(BenchCommand::Merge { out, inputs }) => {
            if let Some(folder) = grid::io::missing_folder(&out) {
                bail!(
                    "merge {}: expected an output database in an existing folder, found no \
                     folder {}",
                    out.display(),
                    folder.display()
                );
            }
            let bench::Merged { added, total } = bench::Store::merge(&out, &inputs)?;
            outln!(
                "merged {} database(s) into {}: {added} new trial(s), {total} in all",
                inputs.len(),
                out.display()
            );
            Ok(())
        }
        Some(BenchCommand::Export { db, csv }) => {
            crate::files::Files::new().writes("--csv", &csv)?;
            let n = bench::Store::open_read_only(&db)?.export_csv(&csv)?;
            outln!("wrote {n} trial(s) to {}", csv.display());
            Ok(())
        }
        Some(BenchCommand::Report { db, out, alpha }) => report(&db, &out, alpha),
        Some(BenchCommand::Suites) => {
            for (name, what, _) in bench::suites::SUITES {
                outln!("  {name:<14} {what}");
            }
            Ok(())
        }
        None => run_study(a.run),
    }
}

fn report(db: &std::path::Path, out: &std::path::Path, alpha: f64) -> Result<()> {
    if !(alpha > 0.0 && alpha < 1.0) {
        bail!("--alpha: expected a level in (0, 1), found {alpha}");
    }
    bench::report::write(db, out, &bench::report::ReportOptions { alpha })?;
    outln!(
        "wrote {} and {}",
        out.join("report.md").display(),
        out.join("report.html").display()
    );
    Ok(())
}

fn run_study(a: RunArgs) -> Result<()> {
    let shard = a
        .shard
        .as_deref()
        .map(|s| s.parse::<bench::Shard>())
        .transpose()
        .map_err(|e| anyhow::anyhow!(e))?;
    if a.threads == Some(0) {
        bail!("--threads: expected at least 1");
    }
    let plan = match (&a.suite, &a.scenario) {
        (Some(name), _) => bench::suites::plan_with_maps(name, a.maps.as_deref(), a.memory_mb)?,
        (None, Some(path)) => bench::Plan::resolve_within(
            &bench::Source::read(path)?,
            bench::Unbuilt::Error,
            a.memory_mb,
        )?,
        (None, None) => bail!("give a scenario file or --suite NAME"),
    };
    let mut plan = plan;
    let whole = plan.trials.len();
    match a.trials {
        Some(0) => bail!("--trials: expected at least 1 trial per start variant, found 0"),
        Some(n) => plan.first_trials(n),
        None => {}
    }
    for s in &plan.skipped {
        eprintln!("note: skipping strategy {s}");
    }
    let db =
        a.db.clone()
            .unwrap_or_else(|| PathBuf::from(format!("{}.sqlite", plan.name)));
    if db.as_os_str() == "-" {
        bail!("--db -: expected a database file name, found '-'");
    }
    // The trials this command runs: the shard's share of the plan, when it runs one.
    let (trials, shard_text) = match shard {
        // A shard is a share of the whole study, of which --trials keeps the first trials
        // per start: say both, or 78 of 8,640 trials reads as a wrong share.
        Some(s) => (
            s.share(&plan.trials),
            match a.trials {
                Some(n) if plan.trials.len() < whole => format!(
                    ", shard {s} of the study's {whole} trials, within the {} of --trials {n}",
                    plan.trials.len()
                ),
                _ => format!(", shard {s} of {} trials", plan.trials.len()),
            },
        ),
        None => (plan.trials.len(), String::new()),
    };
    eprintln!(
        "{}: {trials} trials ({} environments, {} variants{shard_text}) -> {}",
        plan.name,
        plan.envs.len(),
        plan.variants.len(),
        db.display()
    );
    // The report is written once every trial has run: a folder it cannot be written into
    // is refused now, not after the whole study.
    if let Some(out) = &a.report {
        bench::report::check_report_folder(out)?;
        if crate::files::same_file(&db, out) {
            bail!(
                "--report {}: expected a folder for the report, found the path of the --db",
                out.display()
            );
        }
        crate::files::Files::new().writes_into("--report", out, &["report.md", "report.html"])?;
    }
    // Made now, so that a folder that cannot be made is refused before the study (and
    // removed again if the study fails before the report is written).
    let _report_folder = match (&a.report, a.dry_run) {
        (Some(out), false) => Some(crate::files::make_output_folder("--report", out)?),
        _ => None,
    };
    if a.dry_run {
        for env in &plan.envs {
            outln!(
                "env {:<28} {}x{} cells at {} m, {} start variant(s)",
                env.name,
                env.map.width(),
                env.map.height(),
                env.map.resolution,
                env.starts.len()
            );
        }
        for v in &plan.variants {
            outln!(
                "variant {:<22} {:<28} robots {:<3}{}",
                v.label,
                v.sensor.to_string(),
                v.robots,
                match (v.stochastic, v.repeated) {
                    (true, true) => " stochastic",
                    (true, false) => " stochastic, once per start",
                    _ => "",
                }
            );
        }
        return Ok(());
    }
    let opts = bench::RunOptions {
        threads: a.threads,
        shard,
        progress: !a.no_progress && bench::runner::progress_wanted(),
        limit: a.limit,
        memory_mb: a.memory_mb,
    };
    let summary =
        bench::runner::run(&plan, &db, &opts).with_context(|| format!("running {}", plan.name))?;
    let run_now = summary.ran + summary.stored_meanwhile;
    let rate = if summary.wall_s > 0.0 {
        run_now as f64 / summary.wall_s
    } else {
        0.0
    };
    eprintln!(
        "{} of {} trials done before, {run_now} run now in {:.1} s ({rate:.2} trials/s), {} failed",
        summary.already_done,
        summary.total,
        summary.wall_s,
        summary.failed.len()
    );
    if summary.stored_meanwhile > 0 {
        eprintln!(
            "  {} of them another run into {} had stored meanwhile (the first row of a \
             trial is kept): run a study once per database, or its shards into one each",
            summary.stored_meanwhile,
            db.display()
        );
    }
    for (key, why) in &summary.failed {
        eprintln!("  failed: {key}: {why}");
    }
    if let Some(out) = &a.report {
        report(&db, out, bench::stats::DEFAULT_ALPHA)?;
    }
    if !summary.failed.is_empty() {
        bail!(
            "{} trial(s) failed; they are not stored, so running the same command again retries them",
            summary.failed.len()
        );
    }
    Ok(())
}
