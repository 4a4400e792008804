//! `sim`: the one exploration loop of frontier, for one robot or a team.
//!
//! Every strategy of the five papers runs through [`run()`]: robots sense the ground truth,
//! integrate what they see into one shared belief map, keep the frontier cells up to date
//! incrementally, decide goals with the strategy's (candidate generator, assigner,
//! re-plan policy) triple, and move cell by cell along 8-connected shortest paths at speed
//! v — concurrently, in the order of their clocks — until no reachable frontier is left
//! or the coverage goal is met (Faigl & Kulich's steps 1–8; ARCHITECTURE.md "Bird's-eye view").
//! [`Session`] is the same loop stopped at every decision, so that goals can come from
//! outside (a learning agent in the Python package's Gymnasium environment); `run()` is a
//! session whose strategy decides. A batch of runs on the same maps (a study's trials)
//! shares what the line-of-sight sensor sees from each cell ([`BatchSights`],
//! [`run_sharing`]).
//!
//! `sim` is deterministic given (map, configuration, seed): all randomness comes from
//! streams derived from the seed, and ties are broken by robot id and cell index.
//! It touches no files and no serde formats.
//!
//! ```
//! use explore::strategy::Strategy;
//! use sim::RunConfig;
//! use world::{EnvKind, EnvSpec, generate};
//! let env = generate(&EnvSpec::new(EnvKind::Office, 7)).unwrap();
//! let mut cfg = RunConfig::new(Strategy::preset("cf-rr").unwrap());
//! cfg.seed = 3;
//! let run = sim::run(&env.map, &cfg).unwrap();
//! assert!(run.coverage > 0.99, "{}", run.coverage);
//! // The same map, configuration and seed give the same run.
//! assert_eq!(run.path_length_m, sim::run(&env.map, &cfg).unwrap().path_length_m);
//! ```
#![warn(missing_docs)]

pub mod changes;
pub mod config;
pub mod memory;
pub mod metrics;
pub mod motion;
pub mod run;
pub mod seed;
pub mod sight;
pub mod spin_pool;
pub mod truth;

pub use config::{CoverageKind, RunConfig, SimError};
pub use metrics::{
    DtDecision, DtSample, EndReason, MILESTONES, MapAudit, Milestone, PhaseTimes, RunResult, Trace,
    TraceEvent, TraceGoal,
};
pub use motion::Motion;
pub use run::{
    BUMP_S, Session, Status, check_config, check_range_beyond_clearance, check_run,
    check_sensor_range, run, run_pausing, run_sharing,
};
pub use sight::BatchSights;
