//! `bench`: the benchmark harness of frontier (issue 9) — scenario files resolved into flat
//! lists of seeded trials, parallel runs into a resumable SQLite store, shards, merging,
//! CSV export, statistics, reports and one built-in suite per paper.
//!
//! ```text
//! scenario TOML --plan::Plan::resolve--> trials --runner::run (rayon)--> store (SQLite)
//! store --merge / export_csv / report::write--> merged DB, CSV, report.md + report.html
//! ```
//!
//! ```
//! use bench::{Plan, Source, Unbuilt};
//! let text = r#"
//! name = "tiny"
//! seed = 7
//! robots = [1]
//! sensors = ["los:r=3c"]
//! strategies = ["cf", "random"]
//! trials = 2
//!
//! [[env]]
//! kind = "maze"
//! seeds = [0, 1]
//! size = [6, 5]
//! resolution = 0.5
//! "#;
//! let src = Source { file: "tiny.toml".into(), text: text.into(), dir: None };
//! let plan = Plan::resolve(&src, Unbuilt::Error).unwrap();
//! // 2 mazes × 2 strategies × 2 trials, each from its own start drawn by the seed.
//! assert_eq!(plan.trials.len(), 8);
//! let keys: std::collections::BTreeSet<_> = plan.trials.iter().map(|t| &t.key).collect();
//! assert_eq!(keys.len(), 8);
//! ```
#![warn(missing_docs)]

pub mod built;
pub mod competitive;
pub mod error;
pub mod explore;
pub mod holz_tables;
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
pub use store::{Merged, Store, TrialRow, TrialSetup};
