//! `bench`: scenario files, parallel seeded sweeps, a resumable results store, statistics and reports (being written).

pub mod stats;
