//! Errors of the `sense` crate.

/// Everything that can go wrong when describing or building a sensor or a belief map.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SenseError {
    /// A key of a sensor spec has a value of the wrong form.
    #[error("sensor '{spec}': key '{key}': expected {expected}, found \"{found}\"")]
    BadValue {
        /// The whole spec as written.
        spec: String,
        /// The key whose value is wrong.
        key: String,
        /// What the value should have been.
        expected: String,
        /// The value as written.
        found: String,
    },
    /// A sensor spec names a kind that does not exist.
    #[error(
        "sensor '{spec}': unknown kind '{kind}': expected one of los, footprint, lidar, square, sonar, laser-limited-sonar, laser"
    )]
    UnknownKind {
        /// The whole spec as written.
        spec: String,
        /// The kind as written.
        kind: String,
    },
    /// A sensor spec has a key its kind does not take.
    #[error("sensor '{spec}': unknown key '{key}': expected one of {valid}")]
    UnknownKey {
        /// The whole spec as written.
        spec: String,
        /// The key as written.
        key: String,
        /// The keys this kind takes, comma-separated.
        valid: &'static str,
    },
    /// A sensor spec lacks a required key.
    #[error("sensor '{spec}': missing key '{key}': expected {expected}")]
    MissingKey {
        /// The whole spec as written.
        spec: String,
        /// The missing key.
        key: &'static str,
        /// What its value should be.
        expected: &'static str,
    },
    /// A sensor spec gives the same key twice.
    #[error("sensor '{spec}': key '{key}' given more than once")]
    DuplicateKey {
        /// The whole spec as written.
        spec: String,
        /// The repeated key.
        key: String,
    },
    /// A sensor spec item is not of the form `key=value`.
    #[error("sensor '{spec}': item '{item}': expected key=value")]
    Malformed {
        /// The whole spec as written.
        spec: String,
        /// The item as written.
        item: String,
    },
    /// A range in cells is negative, not finite, or too large for a precomputed template.
    #[error("sensor range: expected a finite number of cells in [0, {max}], found {found}")]
    BadRange {
        /// The largest range accepted, in cells.
        max: f64,
        /// The range given, in cells.
        found: f64,
    },
    /// A lidar's field of view or angular resolution is out of bounds.
    #[error("lidar: expected {expected}, found {found}")]
    BadAngle {
        /// What the angle should have been.
        expected: &'static str,
        /// The angle given, in degrees.
        found: f64,
    },
    /// A sensor's range, at the map's resolution, is under one cell or over the kind's
    /// largest: the robot would see only its own cell, or the scan could not be built.
    #[error(
        "sensor '{spec}': range {} cells at {} m per cell: expected 1 to {max} \
         cells ({} to {} m){why}",
        grid::Num(*.cells),
        grid::Num(*.resolution),
        grid::Num(*.resolution),
        grid::Num(*.max * *.resolution),
        why = if *cells < 1.0 { "; with less the robot sees only the cell it stands on" } else { "" }
    )]
    RangeOutOfBounds {
        /// The spec as written back (`los:r=0.01`).
        spec: String,
        /// The range in cells at this resolution.
        cells: f64,
        /// The map's metres per cell.
        resolution: f64,
        /// The kind's largest range in cells.
        max: f64,
    },
    /// A map resolution (metres per cell) is not a positive finite number.
    #[error("map resolution: expected a positive number of metres per cell, found {0}")]
    BadResolution(f64),
    /// A sonar ring on cells too coarse for its cones (see [`crate::spec::SONAR_MAX_CELL_M`]).
    #[error(
        "sonar on {0} m cells: expected cells of at most {max} m (on coarser cells the 25° \
         cones and the echo band paint corridors occupied and exploration stops early); \
         use --resolution {max} or finer, or a map of finer cells",
        max = crate::spec::SONAR_MAX_CELL_M
    )]
    SonarTooCoarse(f64),
    /// A belief-map probability parameter is out of bounds.
    #[error("belief map: {what}: expected a probability in the allowed range, found {found}")]
    BadProbability {
        /// Which parameter.
        what: &'static str,
        /// The value given.
        found: f64,
    },
    /// A sonar parameter is out of bounds.
    #[error(transparent)]
    BadSonar(#[from] crate::sonar::SonarError),
    /// A belief-map kind does not exist.
    #[error("belief map '{0}': expected one of known, reflection, evidence")]
    UnknownBelief(String),
}
