//! Errors of environment generation.

use thiserror::Error;

/// What can go wrong when generating an environment.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WorldError {
    /// A field of the [`EnvSpec`](crate::EnvSpec) has a value the kind cannot use.
    #[error(
        "{} {} m for {kind}: {reason}",
        match *.field { "width_m" => "width", "height_m" => "height", f => f },
        grid::Num(*.value)
    )]
    InvalidSpec {
        /// The field at fault: `width_m`, `height_m` or `resolution`.
        field: &'static str,
        /// The value found.
        value: f64,
        /// The kind being generated.
        kind: crate::EnvKind,
        /// What was expected.
        reason: String,
    },
    /// The grid would have more cells than the limit.
    #[error(
        "size {} m x {} m at resolution {} m gives {cells} cells, more than the limit of \
         {limit}",
        grid::Num(*.width_m),
        grid::Num(*.height_m),
        grid::Num(*.resolution)
    )]
    TooLarge {
        /// Width in metres.
        width_m: f64,
        /// Height in metres.
        height_m: f64,
        /// Resolution in metres per cell.
        resolution: f64,
        /// Number of cells the grid would have.
        cells: f64,
        /// The largest number of cells accepted.
        limit: usize,
    },
    /// The kind's name is not one of the built-in kinds.
    #[error(
        "unknown environment kind {0:?}: expected one of office, hospital, cave, maze, potholes, empty"
    )]
    UnknownKind(String),
}
