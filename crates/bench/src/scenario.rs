//! Scenario files: the TOML schema of a study (issue 9, "Scenario files").
//!
//! A scenario lists environments (built-in kinds with seeds, size and resolution, or map
//! files with their resolution), robot counts, sensors, strategies (preset names, with an
//! optional s_max), start positions (one per trial drawn by seed, a fixed start, or k
//! perturbations within a radius of a base start), trials per variant, speed, clearance,
//! coverage goal and a master seed:
//!
//! ```toml
//! name = "example"
//! seed = 1                      # master seed
//! robots = [1, 2]
//! sensors = ["los:r=4c"]
//! strategies = ["cf", "random"]
//! trials = 3                    # per start variant (deterministic strategies with a fixed start: 1)
//! trials_for = ["random"]       # optional: only these repeat (default: every stochastic one)
//!
//! [[strategy]]                  # a preset with parameters
//! preset = "ha-cc"
//! s_max = 5                     # -1 = re-plan on arrival only
//!
//! [[env]]
//! kind = "maze"
//! seeds = [0, 1]
//! size = [12, 10]               # metres
//! resolution = 0.5
//! start = [2, 2]                # optional base start cell (x, y)
//!
//! [[env]]
//! map = "maps/lab.yaml"         # relative to the scenario file
//!
//! [optimal]                     # optional: optimal offline paths and competitive ratios;
//!                               # online runs then stop at coverage_goal (default 1)
//! cell_size = 1                 # coarsening factor
//! min_cluster = 1               # cluster representatives only (omit: every boundary cell)
//! weight = 1.0                  # weighted A* (1 = optimal)
//! max_nodes = 2000000           # expansion budget (never wall time: results stay exact)
//! memory_mb = 1024
//! ```
//!
//! Unknown keys are rejected by serde (`deny_unknown_fields`) and toml reports the line and
//! column; values that parse but are not acceptable (an unknown preset, a bad sensor spec,
//! an unreadable map) are reported by [`crate::plan`] with the file, line and key, using
//! the spans kept here.

use serde::Deserialize;
use toml::Spanned;

use crate::error::BenchError;

/// The whole scenario file, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Name of the study (default: the file's stem); also the default database file name.
    pub name: Option<Spanned<String>>,
    /// Free text, shown in reports.
    pub description: Option<String>,
    /// Master seed of every trial seed.
    pub seed: Option<Spanned<i64>>,
    /// Environments, one `[[env]]` table each.
    #[serde(default)]
    pub env: Vec<Spanned<EnvEntry>>,
    /// Robot counts (default `[1]`).
    pub robots: Option<Spanned<Vec<Spanned<i64>>>>,
    /// Sensor specs, e.g. `los:r=5` (default `["los:r=5"]`).
    pub sensors: Option<Spanned<Vec<Spanned<String>>>>,
    /// Preset names.
    pub strategies: Option<Spanned<Vec<Spanned<String>>>>,
    /// Presets with parameters, one `[[strategy]]` table each.
    #[serde(default)]
    pub strategy: Vec<Spanned<StrategyEntry>>,
    /// Re-planning period of the presets that re-plan every s_max moves (-1 = on arrival).
    pub s_max: Option<Spanned<i64>>,
    /// Trials per start variant (default 1).
    pub trials: Option<Spanned<i64>>,
    /// Also repeat deterministic strategies `trials` times at a fixed start.
    pub repeat_deterministic: Option<bool>,
    /// The strategies (labels as listed) that run `trials` times per start variant when
    /// they draw random numbers; the others run once per variant (default: every
    /// strategy that draws random numbers).
    pub trials_for: Option<Spanned<Vec<Spanned<String>>>>,
    /// Number of start perturbations around each environment's base start (default 0).
    pub perturbations: Option<Spanned<i64>>,
    /// Radius of the perturbations in metres.
    pub radius: Option<Spanned<f64>>,
    /// Speed in metres per second (default 1).
    pub speed: Option<Spanned<f64>>,
    /// Clearance from obstacles in metres (default 0).
    pub clearance: Option<Spanned<f64>>,
    /// Stop at this coverage in (0, 1] (default: explore everything reachable).
    pub coverage_goal: Option<Spanned<f64>>,
    /// Stop after this many cell moves of the team.
    pub max_moves: Option<Spanned<i64>>,
    /// Belief map of the range sensors' trials: known, reflection, evidence (a sonar's
    /// trials always build the evidence grid, so one study can set lasers beside sonar).
    pub belief: Option<Spanned<String>>,
    /// Sensing mode: continuous, on-arrival or every-N (default: each strategy's).
    pub sensing: Option<Spanned<String>>,
    /// Give single-robot trials the optimal offline path and their competitive ratio.
    pub optimal: Option<Spanned<OptimalEntry>>,
}

/// The `[optimal]` table: settings of the optimal offline search (Quattrini Li et al. 2012).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptimalEntry {
    /// Coarsening factor of the map (the paper's cell sizes 1, 2, 4; default 1).
    pub cell_size: Option<Spanned<i64>>,
    /// Search cluster representatives only, dropping clusters smaller than this.
    pub min_cluster: Option<Spanned<i64>>,
    /// Weight of weighted A* (default 1: optimal).
    pub weight: Option<Spanned<f64>>,
    /// Expansion budget (default 2,000,000).
    pub max_nodes: Option<Spanned<i64>>,
    /// Memory budget of one search in MiB (default 1024).
    pub memory_mb: Option<Spanned<i64>>,
}

/// One `[[env]]` table: a built-in kind or a map file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvEntry {
    /// Built-in kind (office, hospital, cave, maze, potholes, empty).
    pub kind: Option<Spanned<String>>,
    /// Environment seeds of a built-in kind.
    pub seeds: Option<Spanned<Vec<Spanned<i64>>>>,
    /// Seeds 0..count of a built-in kind (instead of `seeds`).
    pub count: Option<Spanned<i64>>,
    /// Size `[width, height]` in metres of a built-in kind.
    pub size: Option<Spanned<Vec<f64>>>,
    /// Metres per cell: generation resolution, or the map file's pixel size (a number, or
    /// `[x, y]` for a bitmap's non-square pixels, as `--resolution RX,RY`).
    pub resolution: Option<Spanned<Resolution>>,
    /// A map file (ROS YAML, PGM/PNG, MovingAI .map, HouseExpo .json, ASCII .txt, MCAP).
    pub map: Option<Spanned<String>>,
    /// The map topic of an MCAP recording (`--topic`).
    pub topic: Option<Spanned<String>>,
    /// Add a wall around a bare bitmap.
    pub border: Option<bool>,
    /// Name in results (default: the generated name or the file's stem).
    pub name: Option<Spanned<String>>,
    /// Base start cell `[x, y]`.
    pub start: Option<Spanned<Vec<i64>>>,
}

/// A `resolution` as written: one number of metres per cell, or `[x, y]`.
#[derive(Clone, Debug)]
pub enum Resolution {
    /// Square cells.
    Square(f64),
    /// Pixels of `[x, y]` metres (anything else is refused with its key).
    Pixels(Vec<f64>),
}

impl<'de> Deserialize<'de> for Resolution {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// Takes a number or a list of numbers.
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = Resolution;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("metres per cell: a number, or [x, y] for non-square pixels")
            }
            fn visit_f64<E>(self, v: f64) -> Result<Resolution, E> {
                Ok(Resolution::Square(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<Resolution, E> {
                Ok(Resolution::Square(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<Resolution, E> {
                Ok(Resolution::Square(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Resolution, A::Error> {
                let mut out = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    out.push(x);
                }
                Ok(Resolution::Pixels(out))
            }
        }
        d.deserialize_any(V)
    }
}

/// One `[[strategy]]` table: a preset with parameters.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrategyEntry {
    /// Preset name.
    pub preset: Spanned<String>,
    /// Re-plan every this many moves (-1 = on arrival only).
    pub s_max: Option<Spanned<i64>>,
    /// Name in results (default: the preset, with `/s_max=N` when given).
    pub label: Option<Spanned<String>>,
}

/// A scenario's text and where it came from, for error messages.
#[derive(Clone, Debug)]
pub struct Source {
    /// File name, or `suite:NAME` for built-in suites.
    pub file: String,
    /// The TOML text.
    pub text: String,
    /// Directory that relative map paths start from (`None` for suites).
    pub dir: Option<std::path::PathBuf>,
}

/// Largest scenario file read, in bytes: a scenario is a page of text, so anything larger
/// is the wrong file (and a device such as `/dev/zero` is refused before it is read).
pub const MAX_SCENARIO_BYTES: u64 = 16 << 20;

impl Source {
    /// Read a scenario file: a regular file of at most [`MAX_SCENARIO_BYTES`] of UTF-8.
    pub fn read(path: &std::path::Path) -> Result<Source, BenchError> {
        let refuse = |message: String| BenchError::File {
            path: path.to_path_buf(),
            message,
        };
        let meta = std::fs::metadata(path).map_err(BenchError::io(path))?;
        if !meta.is_file() {
            let found = if meta.is_dir() {
                "a directory"
            } else {
                "a device, pipe or socket"
            };
            return Err(refuse(format!(
                "expected a scenario file (TOML text), found {found}"
            )));
        }
        let too_large = |found: String| {
            refuse(format!(
                "expected a scenario file (TOML text) of at most {} MiB, found {found}",
                MAX_SCENARIO_BYTES >> 20
            ))
        };
        if meta.len() > MAX_SCENARIO_BYTES {
            return Err(too_large(format!("{} bytes", meta.len())));
        }
        // The file may grow between the check and the read: read no more than the limit.
        let file = std::fs::File::open(path).map_err(BenchError::io(path))?;
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(file, MAX_SCENARIO_BYTES + 1),
            &mut bytes,
        )
        .map_err(BenchError::io(path))?;
        if bytes.len() as u64 > MAX_SCENARIO_BYTES {
            return Err(too_large("more, growing while read".into()));
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            // Where the first byte that is not UTF-8 is, as a line and a column.
            let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
            let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
            let column = 1 + good.iter().rev().take_while(|&&b| b != b'\n').count();
            refuse(format!(
                "expected a scenario file of UTF-8 text (TOML), found a byte that is not UTF-8 \
                 at line {line}, column {column} (byte {})",
                good.len()
            ))
        })?;
        Ok(Source {
            file: path.display().to_string(),
            text,
            dir: path.parent().map(|p| p.to_path_buf()),
        })
    }

    /// Parse the text against the schema.
    pub fn parse(&self) -> Result<ScenarioFile, BenchError> {
        toml::from_str(&self.text).map_err(|e| BenchError::Toml {
            file: self.file.clone(),
            message: e.to_string().trim_end().to_string(),
        })
    }

    /// 1-based line of byte offset `at`.
    pub fn line_of(&self, at: usize) -> usize {
        let at = at.min(self.text.len());
        self.text.as_bytes()[..at]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1
    }

    /// An error about `key`, at the value spanning `span` (`None`: the key is missing).
    pub fn error(
        &self,
        span: Option<std::ops::Range<usize>>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> BenchError {
        BenchError::Scenario {
            file: self.file.clone(),
            line: span.map(|s| self.line_of(s.start)),
            key: key.into(),
            message: message.into(),
        }
    }
}
