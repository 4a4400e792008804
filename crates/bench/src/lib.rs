//! `bench`: the benchmark harness of frontier (issue 9) — scenario files resolved into flat
//! lists of seeded trials, parallel runs into a resumable SQLite store, shards, merging,
//! CSV export, statistics, reports and one built-in suite per paper.
//!
//! ```text
//! scenario TOML --plan::Plan::resolve--> trials --runner::run (rayon)--> store (SQLite)
//! store --merge / export_csv / report::write--> merged DB, CSV, report.md + report.html
//! ```
#![warn(missing_docs)]

pub mod built;
pub mod competitive;
pub mod error;
pub mod plan;
pub mod plots;
pub mod replays;
pub mod report;
pub mod runner;
pub mod scenario;
pub mod stats;
pub mod store;
pub mod suites;

pub use error::BenchError;
pub use plan::{Plan, Trial, Unbuilt};
pub use runner::{RunOptions, RunSummary, Shard};
pub use scenario::Source;
pub use store::{Merged, Store, TrialRow};
