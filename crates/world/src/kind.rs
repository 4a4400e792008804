//! The built-in environment kinds and their defaults.

use std::fmt;
use std::str::FromStr;

use crate::error::WorldError;

/// A kind of built-in environment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EnvKind {
    /// Corridors with rooms and doors (the multi-robot study's offices).
    Office,
    /// Many small rooms off long corridors (like Stage's hospital).
    Hospital,
    /// Irregular open caves with island obstacles (like Stage's cave).
    Cave,
    /// A perfect random maze (the multi-robot study's mazes).
    Maze,
    /// A large open area with scattered obstacles (Faigl & Kulich's potholes).
    Potholes,
    /// An open rectangle (Faigl & Kulich's em).
    Empty,
}

/// A kind's defaults: size, resolution and a one-line description.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KindInfo {
    /// The kind described.
    pub kind: EnvKind,
    /// Default size `(width, height)` in metres.
    pub size_m: (f64, f64),
    /// Default resolution in metres per cell.
    pub resolution: f64,
    /// What the kind looks like, in one line.
    pub description: &'static str,
}

/// All kinds in a fixed order.
const ALL: [EnvKind; 6] = [
    EnvKind::Office,
    EnvKind::Hospital,
    EnvKind::Cave,
    EnvKind::Maze,
    EnvKind::Potholes,
    EnvKind::Empty,
];

impl EnvKind {
    /// Every kind, in a fixed order (office, hospital, cave, maze, potholes, empty).
    pub fn all() -> &'static [EnvKind] {
        &ALL
    }

    /// The kind's lower-case name, as parsed by `FromStr` and shown by `Display`.
    pub fn name(self) -> &'static str {
        match self {
            EnvKind::Office => "office",
            EnvKind::Hospital => "hospital",
            EnvKind::Cave => "cave",
            EnvKind::Maze => "maze",
            EnvKind::Potholes => "potholes",
            EnvKind::Empty => "empty",
        }
    }

    /// The kind's default size and resolution and a description.
    pub fn info(self) -> KindInfo {
        let (size_m, resolution, description) = match self {
            EnvKind::Office => (
                (25.0, 20.0),
                0.5,
                "corridors with rooms and doors, room ids (multi-robot study's offices)",
            ),
            EnvKind::Hospital => (
                (40.0, 24.0),
                0.2,
                "many small rooms off long corridors, room ids (like Stage's hospital)",
            ),
            EnvKind::Cave => (
                (16.0, 16.0),
                0.1,
                "irregular open caves with island obstacles (like Stage's cave)",
            ),
            EnvKind::Maze => (
                (25.0, 20.0),
                0.5,
                "perfect random maze on a 1 m lattice (multi-robot study's mazes)",
            ),
            EnvKind::Potholes => (
                (40.0, 40.0),
                0.2,
                "large open area with scattered obstacles (Faigl's potholes)",
            ),
            EnvKind::Empty => (
                (21.0, 24.0),
                0.2,
                "open rectangle inside a wall (Faigl's em)",
            ),
        };
        KindInfo {
            kind: self,
            size_m,
            resolution,
            description,
        }
    }

    /// Smallest accepted size `(width, height)` in metres: at least 3 cells at the coarsest
    /// accepted resolution, so every size from here up is accepted at every resolution.
    pub fn min_size_m(self) -> (f64, f64) {
        match self {
            EnvKind::Office => (10.0, 10.0),
            EnvKind::Hospital => (12.0, 12.0),
            EnvKind::Cave => (4.0, 4.0),
            EnvKind::Maze => (3.0, 3.0),
            EnvKind::Potholes => (6.0, 6.0),
            EnvKind::Empty => (3.0, 3.0),
        }
    }

    /// Coarsest accepted resolution in metres per cell (features must stay a cell or more).
    pub fn max_resolution(self) -> f64 {
        match self {
            EnvKind::Office | EnvKind::Hospital | EnvKind::Maze | EnvKind::Cave => 0.5,
            EnvKind::Potholes => 0.5,
            EnvKind::Empty => 1.0,
        }
    }
}

impl fmt::Display for EnvKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for EnvKind {
    type Err = WorldError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        ALL.iter()
            .copied()
            .find(|k| k.name().eq_ignore_ascii_case(t))
            .ok_or_else(|| WorldError::UnknownKind(s.to_string()))
    }
}
