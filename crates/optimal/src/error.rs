//! Why an optimal-path problem cannot be set up.

use grid::Cell;

/// A problem that cannot be solved as posed.
#[derive(Debug, thiserror::Error)]
pub enum OptimalError {
    /// The start cell is outside the map or not free.
    #[error("start {cell}: {why}")]
    BadStart {
        /// The start cell.
        cell: Cell,
        /// What is wrong with it.
        why: String,
    },
    /// A parameter is out of range.
    #[error("{field}: expected {expected}, found {found}")]
    BadParameter {
        /// The parameter's name as the user knows it.
        field: &'static str,
        /// What is allowed.
        expected: &'static str,
        /// The value given.
        found: String,
    },
    /// The sensor cannot be used by the offline search.
    #[error("sensor: {0}")]
    Sensor(String),
    /// Setting up the search would take more memory than its budget.
    #[error(
        "setting up the search needs about {} MiB, more than its memory budget of {} MiB",
        .needed.div_ceil(1 << 20),
        .budget / (1 << 20)
    )]
    Memory {
        /// Estimated bytes of the set-up.
        needed: u64,
        /// The budget ([`crate::Config::max_bytes`]).
        budget: u64,
    },
}
