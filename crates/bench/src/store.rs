//! The results store: one SQLite database per study, one row per trial (issue 9, "Running").
//!
//! Each row holds the full configuration, the seed, the metrics, the program version and
//! the wall time, and is committed on its own as the trial finishes. The database runs in
//! WAL mode, so a process killed at any moment (SIGKILL included) loses at most the trials
//! in flight: SQLite's journal keeps every committed row and never leaves a half-written
//! one. Rows are keyed by the trial's stable key, which is how a re-run skips finished
//! trials and how shard databases merge.
//!
//! A store closed normally goes back to a rollback journal, so a finished database is one
//! file that can be read without writing anything beside it. Reading (export, report, merge
//! inputs) opens it read-only. Opening an existing database checks it first, read-only and
//! before anything is written to it or beside it (SQLite's `quick_check`, frontier's tables
//! and columns, the table layout version, and for a run the study it holds): a wrong path —
//! another program's database, a store of another layout or study, a damaged file, a file
//! that is not SQLite at all — is refused and left exactly as it was, rather than given
//! frontier's tables and switched to WAL mode. A merge checks every input before it writes
//! its output. A run that finds every trial it plans already stored stays read-only, so a
//! finished study's report can be made again from a store the user may only read.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use rusqlite::{Connection, OpenFlags, OptionalExtension, params};
use serde::Serialize;

use crate::error::BenchError;

/// Version of the table layout; databases of another version are refused.
pub const SCHEMA_VERSION: &str = "3";

/// The tables of a results store, as `CREATE` makes them.
const TABLES: [&str; 4] = ["meta", "envs", "trials", "optimal"];

/// The first bytes of every SQLite database file.
const SQLITE_MAGIC: &[u8] = b"SQLite format 3\0";

/// One finished trial, as stored (and as exported to CSV, column for column).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrialRow {
    /// Stable key `ENV|STRATEGY|SENSOR|m=ROBOTS|start=S|trial=T`.
    pub key: String,
    /// Study name.
    pub scenario: String,
    /// Environment name.
    pub env: String,
    /// Built-in kind or `map`.
    pub env_kind: String,
    /// Generation seed of a built-in environment.
    pub env_seed: Option<i64>,
    /// Map file as written in the scenario.
    pub map_file: Option<String>,
    /// Metres per cell.
    pub resolution: f64,
    /// Map width in cells.
    pub width: i64,
    /// Map height in cells.
    pub height: i64,
    /// Strategy label.
    pub strategy: String,
    /// Preset the strategy comes from.
    pub preset: String,
    /// Re-planning period in moves (`None` = on arrival).
    pub s_max: Option<i64>,
    /// Sensor spec.
    pub sensor: String,
    /// Belief map kind.
    pub belief: String,
    /// Sensing mode in force.
    pub sensing: String,
    /// Number of robots.
    pub robots: i64,
    /// Start variant.
    pub start_variant: i64,
    /// Trial number within the start variant.
    pub trial: i64,
    /// The run's seed (decimal; it is an unsigned 64-bit number).
    pub seed: String,
    /// Start cells of the robots, JSON `[[x, y], ...]`.
    pub starts: String,
    /// Clearance in metres.
    pub clearance: f64,
    /// Speed in metres per second.
    pub speed: f64,
    /// Coverage goal.
    pub coverage_goal: Option<f64>,
    /// Move limit.
    pub max_moves: i64,
    /// Path length of each robot in metres, JSON array.
    pub path_lengths: String,
    /// Longest path of one robot (Faigl & Kulich's L), metres.
    pub max_path: f64,
    /// Total path of the team, metres.
    pub total_path: f64,
    /// Exploration time in seconds.
    pub time_s: f64,
    /// Coverage reached.
    pub coverage: f64,
    /// Decisions taken.
    pub decisions: i64,
    /// Cell moves of the team.
    pub moves: i64,
    /// Why the run ended.
    pub reason: String,
    /// Reachable free cells (coverage's denominator).
    pub reachable_cells: i64,
    /// Coverage over team distance, JSON `[[metres, coverage], ...]` (at most 65 points).
    pub coverage_curve: String,
    /// Program version that ran the trial.
    pub version: String,
    /// Wall-clock seconds of the trial (the only column that differs between equal runs).
    pub wall_s: f64,
    /// Best offline exploration path found from the same start, metres (studies with
    /// `[optimal]`; see [`crate::competitive`]).
    pub optimal_m: Option<f64>,
    /// Proven lower bound on the optimal offline path, metres.
    pub optimal_lower_m: Option<f64>,
    /// Whether `optimal_m` is proven optimal.
    pub optimal_proven: Option<bool>,
    /// Competitive ratio: total path over `optimal_m`.
    pub ratio: Option<f64>,
    /// Team distance in metres when coverage first reached 90 % (D90), if it did.
    pub d90_m: Option<f64>,
    /// Time in seconds when coverage first reached 90 % (T90).
    pub t90_s: Option<f64>,
    /// Team distance in metres when coverage first reached 99 % (D99).
    pub d99_m: Option<f64>,
    /// Time in seconds when coverage first reached 99 % (T99).
    pub t99_s: Option<f64>,
    /// Teams: cells sensed by two or more robots over cells sensed by any (0 for one robot).
    pub overlap: f64,
    /// Seconds each robot did not travel before the run ended, JSON array.
    pub idle_s: String,
}

const COLUMNS: &str = "key, scenario, env, env_kind, env_seed, map_file, resolution, width, height, \
strategy, preset, s_max, sensor, belief, sensing, robots, start_variant, trial, seed, starts, \
clearance, speed, coverage_goal, max_moves, path_lengths, max_path, total_path, time_s, coverage, \
decisions, moves, reason, reachable_cells, coverage_curve, version, wall_s, optimal_m, \
optimal_lower_m, optimal_proven, ratio, d90_m, t90_s, d99_m, t99_s, overlap, idle_s";

const CREATE: &str = "
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS envs (name TEXT PRIMARY KEY, width INTEGER NOT NULL,
    height INTEGER NOT NULL, resolution REAL NOT NULL, png BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS trials (
    key TEXT PRIMARY KEY, scenario TEXT NOT NULL, env TEXT NOT NULL, env_kind TEXT NOT NULL,
    env_seed INTEGER, map_file TEXT, resolution REAL NOT NULL, width INTEGER NOT NULL,
    height INTEGER NOT NULL, strategy TEXT NOT NULL, preset TEXT NOT NULL, s_max INTEGER,
    sensor TEXT NOT NULL, belief TEXT NOT NULL, sensing TEXT NOT NULL, robots INTEGER NOT NULL,
    start_variant INTEGER NOT NULL, trial INTEGER NOT NULL, seed TEXT NOT NULL,
    starts TEXT NOT NULL, clearance REAL NOT NULL, speed REAL NOT NULL, coverage_goal REAL,
    max_moves INTEGER NOT NULL, path_lengths TEXT NOT NULL, max_path REAL NOT NULL,
    total_path REAL NOT NULL, time_s REAL NOT NULL, coverage REAL NOT NULL,
    decisions INTEGER NOT NULL, moves INTEGER NOT NULL, reason TEXT NOT NULL,
    reachable_cells INTEGER NOT NULL, coverage_curve TEXT NOT NULL, version TEXT NOT NULL,
    wall_s REAL NOT NULL, optimal_m REAL, optimal_lower_m REAL, optimal_proven INTEGER,
    ratio REAL, d90_m REAL, t90_s REAL, d99_m REAL, t99_s REAL, overlap REAL NOT NULL,
    idle_s TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS optimal (key TEXT PRIMARY KEY, length_m REAL, lower_m REAL NOT NULL,
    proven INTEGER NOT NULL, expanded INTEGER NOT NULL, wall_s REAL NOT NULL);";

/// A picture of one environment of the study, kept in the database for reports.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvPicture {
    /// Environment name.
    pub name: String,
    /// Width in cells.
    pub width: i64,
    /// Height in cells.
    pub height: i64,
    /// Metres per cell.
    pub resolution: f64,
    /// The ground truth as PNG.
    pub png: Vec<u8>,
}

/// An [`EnvPicture`] from a row of `SELECT name, width, height, resolution, png FROM envs`.
fn env_picture(r: &rusqlite::Row<'_>) -> rusqlite::Result<EnvPicture> {
    Ok(EnvPicture {
        name: r.get(0)?,
        width: r.get(1)?,
        height: r.get(2)?,
        resolution: r.get(3)?,
        png: r.get(4)?,
    })
}

impl EnvPicture {
    /// How `new` (of `source`: the scenario, or a database being merged) differs from this
    /// stored picture of the same name, in words; `None` when both draw the same map (the
    /// same size, resolution and cells, however the PNG was encoded).
    pub fn difference(&self, new: &EnvPicture, source: &str) -> Option<String> {
        let size =
            |e: &EnvPicture| format!("{} x {} cells at {} m", e.width, e.height, e.resolution);
        if (self.width, self.height, self.resolution) != (new.width, new.height, new.resolution) {
            return Some(format!(
                "holds environment '{}' as {}, but {source} gives {}",
                self.name,
                size(self),
                size(new)
            ));
        }
        if self.png == new.png {
            return None;
        }
        let cells = |e: &EnvPicture| crate::replays::truth_from_picture(e).map(|m| m.cells);
        match (cells(self), cells(new)) {
            (Ok(a), Ok(b)) if a == b => None,
            (Ok(a), Ok(b)) => {
                let differ = (0..a.len()).filter(|&i| a[i] != b[i]).count();
                Some(format!(
                    "holds environment '{}' ({}) with other cells than {source} gives ({differ} \
                     of {} cells differ)",
                    self.name,
                    size(self),
                    a.len()
                ))
            }
            (Err(e), _) | (_, Err(e)) => Some(format!(
                "holds environment '{}' ({}), which cannot be compared with the one {source} \
                 gives: {e}",
                self.name,
                size(self)
            )),
        }
    }
}

/// What a trial was run with, beyond what its key spells out (environment, strategy label,
/// sensor, robots, start variant, trial) and the study's fingerprint holds (seed, speed,
/// clearance, goal, belief, ...). A scenario edited after some of its trials ran — another
/// `start`, `s_max` or map under the same names — gives trials of the same keys that run
/// otherwise; comparing setups keeps them from passing for the stored ones.
#[derive(Clone, Debug, PartialEq)]
pub struct TrialSetup {
    /// Built-in kind or `map`.
    pub env_kind: String,
    /// Generation seed of a built-in environment.
    pub env_seed: Option<i64>,
    /// Metres per cell.
    pub resolution: f64,
    /// Map width in cells.
    pub width: i64,
    /// Map height in cells.
    pub height: i64,
    /// Preset the strategy comes from.
    pub preset: String,
    /// Re-planning period in moves (`None` = on arrival).
    pub s_max: Option<i64>,
    /// Sensing mode in force.
    pub sensing: String,
    /// The run's seed.
    pub seed: String,
    /// Start cells, JSON `[[x, y], ...]`; `None` where a planned trial draws them from its
    /// seed (they are known only once it runs, and then follow from the seed and the map).
    pub starts: Option<String>,
}

impl TrialSetup {
    /// The setup stored in `r`.
    pub fn of(r: &TrialRow) -> TrialSetup {
        TrialSetup {
            env_kind: r.env_kind.clone(),
            env_seed: r.env_seed,
            resolution: r.resolution,
            width: r.width,
            height: r.height,
            preset: r.preset.clone(),
            s_max: r.s_max,
            sensing: r.sensing.clone(),
            seed: r.seed.clone(),
            starts: Some(r.starts.clone()),
        }
    }

    /// The first setting in which `self` and `other` differ: (column, value in `self`,
    /// value in `other`). Starts are compared only when both know them.
    pub fn difference(&self, other: &TrialSetup) -> Option<(&'static str, String, String)> {
        fn opt<T: std::fmt::Display>(v: &Option<T>) -> String {
            v.as_ref().map_or("none".into(), |v| v.to_string())
        }
        let fields = [
            ("env_kind", self.env_kind.clone(), other.env_kind.clone()),
            ("env_seed", opt(&self.env_seed), opt(&other.env_seed)),
            (
                "resolution",
                self.resolution.to_string(),
                other.resolution.to_string(),
            ),
            ("width", self.width.to_string(), other.width.to_string()),
            ("height", self.height.to_string(), other.height.to_string()),
            ("preset", self.preset.clone(), other.preset.clone()),
            ("s_max", opt(&self.s_max), opt(&other.s_max)),
            ("sensing", self.sensing.clone(), other.sensing.clone()),
            ("seed", self.seed.clone(), other.seed.clone()),
        ];
        if let Some(d) = fields.into_iter().find(|(_, a, b)| a != b) {
            return Some(d);
        }
        match (&self.starts, &other.starts) {
            (Some(a), Some(b)) if a != b => Some(("starts", a.clone(), b.clone())),
            _ => None,
        }
    }
}

/// An open results database.
pub struct Store {
    conn: Connection,
    path: PathBuf,
    /// Opened for writing: switched back to a rollback journal when closed.
    writable: bool,
}

impl Drop for Store {
    /// A store in WAL mode can only be read by someone who may create its `-shm` file
    /// beside it, and every reader leaves a `-wal` and `-shm` there. So a store opened for
    /// writing goes back to a rollback journal when it closes (after a last checkpoint):
    /// finished databases are single files that read-only users (`export`, `report`,
    /// `merge` inputs, a read-only file system) read without writing anything. If another
    /// connection still has it open, or the process is killed, it stays in WAL mode, as
    /// safe as before.
    fn drop(&mut self) {
        if self.writable {
            let _ = self
                .conn
                .query_row("PRAGMA journal_mode=DELETE", [], |_| Ok(()));
        }
    }
}

/// What [`Store::merge`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Merged {
    /// Trials new to the output.
    pub added: usize,
    /// Trials in the output after the merge.
    pub total: usize,
}

/// Run `f` again while SQLite answers that the database is busy, for up to the 30 s the
/// connections wait for a lock. Switching to WAL mode needs the file to itself and is
/// answered busy at once, without the busy handler's wait, when another run is opening the
/// same new store: one of two runs started together failed with "database is locked".
fn while_busy<T>(mut f: impl FnMut() -> rusqlite::Result<T>) -> rusqlite::Result<T> {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    loop {
        match f() {
            Err(e)
                if e.sqlite_error_code() == Some(rusqlite::ErrorCode::DatabaseBusy)
                    && std::time::Instant::now() < deadline =>
            {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            other => return other,
        }
    }
}

/// A read-only connection to `path`, whose SQLite header says whether it is in WAL mode.
/// A database in WAL mode (left so by an older version or a killed run, or another
/// program's) makes every reader create a `-wal` and `-shm` file beside it and leave them
/// there. When no `-wal` file holds unfinished work, or in a directory the user cannot
/// write, it is opened as immutable instead: nothing is written to it or beside it then,
/// and no writer is at work on it (a writer keeps a `-wal` file while it runs).
fn open_read_only(path: &Path, wal_mode: bool) -> Result<Connection, BenchError> {
    let flags = OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX;
    if wal_mode && !sibling(path, "-wal").exists() {
        return open_immutable(path);
    }
    let first = Connection::open_with_flags(path, flags).and_then(|c| {
        c.busy_timeout(std::time::Duration::from_secs(30))?;
        c.query_row("SELECT COUNT(*) FROM sqlite_master", [], |_| Ok(()))?;
        Ok(c)
    });
    match first {
        Err(rusqlite::Error::SqliteFailure(e, _))
            if matches!(
                e.extended_code,
                rusqlite::ffi::SQLITE_READONLY_DIRECTORY | rusqlite::ffi::SQLITE_CANTOPEN
            ) && !sibling(path, "-wal").exists() =>
        {
            open_immutable(path)
        }
        // A `-wal` beside it (a run killed in WAL mode) that SQLite cannot read without a
        // `-shm` it may not make there: its unfinished work cannot be read as it is.
        Err(rusqlite::Error::SqliteFailure(e, _))
            if matches!(
                e.extended_code,
                rusqlite::ffi::SQLITE_READONLY_DIRECTORY | rusqlite::ffi::SQLITE_CANTOPEN
            ) && !sibling(path, "-shm").exists() =>
        {
            Err(BenchError::Store {
                path: path.to_path_buf(),
                message: format!(
                    "has a -wal file beside it (a run killed while writing) but no -shm, which \
                     SQLite must make to read it, in a folder this user cannot write: copy \
                     its -shm file too, or resume the study into it once where it may be \
                     written (SQLite: {e})"
                ),
            })
        }
        other => other.map_err(|e| sql_error(path, e)),
    }
}

/// A read-only connection to `path` as an immutable file: SQLite neither locks it nor
/// reads or writes any file beside it (no `-wal`, `-shm` or `-journal`).
fn open_immutable(path: &Path) -> Result<Connection, BenchError> {
    let uri = format!("file:{}?immutable=1", uri_path(path));
    let flags = OpenFlags::SQLITE_OPEN_READ_ONLY
        | OpenFlags::SQLITE_OPEN_NO_MUTEX
        | OpenFlags::SQLITE_OPEN_URI;
    Connection::open_with_flags(uri, flags).map_err(|e| sql_error(path, e))
}

/// Whether a `-journal` file lies beside `path`: a write in rollback mode is under way, or
/// was cut short (its process killed) and must be rolled back before the file is read.
fn has_journal(path: &Path) -> bool {
    std::fs::metadata(sibling(path, "-journal")).is_ok_and(|m| m.len() > 0)
}

/// The first 100 bytes of `path` (SQLite's file header; fewer in a shorter file), read
/// without SQLite: a file that does not begin as an SQLite database does is refused,
/// saying what it begins with.
fn sqlite_header(path: &Path) -> Result<Vec<u8>, BenchError> {
    use std::io::Read;
    let mut head = Vec::with_capacity(100);
    std::fs::File::open(path)
        .and_then(|f| f.take(100).read_to_end(&mut head))
        .map_err(BenchError::io(path))?;
    if head.starts_with(SQLITE_MAGIC) {
        return Ok(head);
    }
    Err(BenchError::Store {
        path: path.to_path_buf(),
        message: format!(
            "is not an SQLite database (it starts with \"{}\"); expected a frontier results \
             database",
            head[..head.len().min(16)].escape_ascii()
        ),
    })
}

/// Whether an SQLite header says the database is in WAL mode (its read and write
/// versions, bytes 18 and 19, are 2).
fn wal_mode(header: &[u8]) -> bool {
    header.get(18..20) == Some(&[2, 2])
}

/// An SQLite error on `path`, in words when it says the file is not a database or is
/// damaged.
fn sql_error(path: &Path, e: rusqlite::Error) -> BenchError {
    let code = e.sqlite_error_code();
    let message = match code {
        Some(rusqlite::ErrorCode::NotADatabase) => {
            "is not an SQLite database; expected a frontier results database".to_string()
        }
        Some(rusqlite::ErrorCode::DatabaseCorrupt) => damaged(&e.to_string()),
        Some(rusqlite::ErrorCode::ReadOnly)
            if e.sqlite_error().map(|f| f.extended_code)
                == Some(rusqlite::ffi::SQLITE_READONLY_ROLLBACK) =>
        {
            "has a write that was cut short (SQLite's -journal file beside it), which must be \
             rolled back before it can be read, and reading writes nothing: resume the study \
             into it once (which rolls it back), or open it with a program that may write it"
                .to_string()
        }
        _ => return BenchError::sql(path)(e),
    };
    BenchError::Store {
        path: path.to_path_buf(),
        message,
    }
}

/// What to say about a damaged database, given what SQLite found.
fn damaged(what: &str) -> String {
    format!(
        "is damaged ({what}); its results cannot be trusted: run the study into a new database file, or restore this one from a copy"
    )
}

/// `path` with `suffix` appended to its file name (SQLite's `-wal`, `-shm`, `-journal`).
fn sibling(path: &Path, suffix: &str) -> PathBuf {
    let mut p = path.as_os_str().to_owned();
    p.push(suffix);
    PathBuf::from(p)
}

/// `path` as the path of an SQLite `file:` URI (made absolute, `%`, `?` and `#` escaped).
fn uri_path(path: &Path) -> String {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = String::new();
    for c in abs.to_string_lossy().chars() {
        match c {
            '%' => out.push_str("%25"),
            '?' => out.push_str("%3f"),
            '#' => out.push_str("%23"),
            c => out.push(c),
        }
    }
    out
}

/// Run SQLite's `quick_check` on `conn` and turn any finding into an error naming `path`.
fn check_integrity(conn: &Connection, path: &Path) -> Result<(), BenchError> {
    let found = conn.prepare("PRAGMA quick_check(5)").and_then(|mut st| {
        st.query_map([], |r| r.get::<_, String>(0))?
            .collect::<Result<Vec<_>, _>>()
    });
    match found {
        Ok(lines) if lines.len() == 1 && lines[0] == "ok" => Ok(()),
        Ok(lines) => Err(BenchError::Store {
            path: path.to_path_buf(),
            message: damaged(&format!("SQLite's quick_check: {}", lines.join("; "))),
        }),
        Err(e) => Err(sql_error(path, e)),
    }
}

/// The names of the tables of the database (SQLite's own left out), sorted.
fn table_names(conn: &Connection, path: &Path) -> Result<Vec<String>, BenchError> {
    conn.prepare(
        "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite\\_%' \
         ESCAPE '\\' ORDER BY name",
    )
    .and_then(|mut st| {
        st.query_map([], |r| r.get::<_, String>(0))?
            .collect::<Result<Vec<_>, _>>()
    })
    .map_err(BenchError::sql(path))
}

/// The column names of `table` in the database, in order (none if there is no such table).
fn columns(conn: &Connection, table: &str) -> rusqlite::Result<Vec<String>> {
    conn.prepare("SELECT name FROM pragma_table_info(?1)")?
        .query_map([table], |r| r.get::<_, String>(0))?
        .collect()
}

/// How the tables of the database differ from those `CREATE` makes (a table missing, a
/// column missing or added), in words; `None` when they have the same columns. Other
/// tables beside frontier's are no difference.
fn layout_difference(conn: &Connection, path: &Path) -> Result<Option<String>, BenchError> {
    let ours = Connection::open_in_memory()
        .and_then(|c| c.execute_batch(CREATE).map(|()| c))
        .map_err(BenchError::sql(path))?;
    let mut found = Vec::new();
    for table in TABLES {
        let want = columns(&ours, table).map_err(BenchError::sql(path))?;
        let have = columns(conn, table).map_err(BenchError::sql(path))?;
        if have.is_empty() {
            found.push(format!("it has no table {table}"));
            continue;
        }
        let lacks: Vec<&str> = want
            .iter()
            .filter(|c| !have.contains(c))
            .map(String::as_str)
            .collect();
        let extra: Vec<&str> = have
            .iter()
            .filter(|c| !want.contains(c))
            .map(String::as_str)
            .collect();
        if !lacks.is_empty() {
            found.push(format!("its table {table} lacks {}", lacks.join(", ")));
        }
        if !extra.is_empty() {
            found.push(format!(
                "its table {table} has {}, which layout {SCHEMA_VERSION} does not",
                extra.join(", ")
            ));
        }
    }
    Ok((!found.is_empty()).then(|| found.join("; ")))
}

/// `tables` in words: at most 8 names, then how many there are in all.
fn list_tables(tables: &[String]) -> String {
    if tables.len() <= 8 {
        return tables.join(", ");
    }
    format!("{}, ... ({} in all)", tables[..8].join(", "), tables.len())
}

/// The nearest existing ancestor of `path` that is not a folder: a file where the folder
/// of `path` should be, so no database can be there.
fn file_in_the_way(path: &Path) -> Option<&Path> {
    path.ancestors()
        .skip(1)
        .filter(|d| !d.as_os_str().is_empty())
        .find(|d| d.exists())
        .filter(|d| !d.is_dir())
}

/// The error for a store path under `file`, a file and not a folder.
fn under_a_file(path: &Path, file: &Path) -> BenchError {
    BenchError::Store {
        path: path.to_path_buf(),
        message: format!(
            "expected a results database in a folder, but {} is a file; give a path outside it",
            file.display()
        ),
    }
}

/// Refuse to write `out` when it is the database `db` or one of its SQLite files beside it
/// (`-wal`, `-shm`, `-journal`): writing there would destroy the results being read.
/// `what` names what was to be written ("the CSV", "the report"). Check right before
/// anything is written, once the directories of `out` exist.
pub fn refuse_overwriting(db: &Path, out: &Path, what: &str) -> Result<(), BenchError> {
    for suffix in ["", "-wal", "-shm", "-journal"] {
        if grid::io::same_existing_file(&sibling(db, suffix), out) {
            let which = if suffix.is_empty() {
                "the results database".to_string()
            } else {
                format!("SQLite's {suffix} file of the results database")
            };
            return Err(BenchError::Store {
                path: out.to_path_buf(),
                message: format!(
                    "is {which} being read ({}); writing {what} there would destroy its \
                     results: expected another output path",
                    db.display()
                ),
            });
        }
    }
    Ok(())
}

/// The error for a store that this user cannot create or write, given SQLite's; any other
/// SQLite error as it is. A run or merge writes into the file and keeps SQLite's `-wal`
/// and `-shm` files beside it, so both the file and its folder must be writable.
fn not_writable(path: &Path, e: rusqlite::Error) -> BenchError {
    use rusqlite::ErrorCode::{CannotOpen, PermissionDenied, ReadOnly};
    if !matches!(
        e.sqlite_error_code(),
        Some(CannotOpen | PermissionDenied | ReadOnly)
    ) {
        return BenchError::sql(path)(e);
    }
    let folder = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let message = if path.exists() {
        format!(
            "cannot be written by this user: a run or merge writes into it and keeps SQLite's \
             -wal and -shm files beside it, so expected the file and its folder {} to be \
             writable; give a path you may write",
            folder.display()
        )
    } else {
        format!(
            "cannot be created by this user: expected a folder ({}) this user may write, where \
             a run or merge makes the file and SQLite's -wal and -shm files beside it",
            folder.display()
        )
    };
    BenchError::Store {
        path: path.to_path_buf(),
        message,
    }
}

/// The error for a store path that ends with a path separator (`study.sqlite/`), if it
/// does: the file system looks for a folder there, SQLite opens the file, so a file's
/// checks would be skipped while SQLite wrote into it.
fn ends_as_a_folder(path: &Path) -> Result<(), BenchError> {
    let text = path.as_os_str().to_string_lossy();
    if text.ends_with(std::path::is_separator) && text.len() > 1 {
        return Err(BenchError::Store {
            path: path.to_path_buf(),
            message: "ends with a path separator, so it names a folder; expected a results \
                      database file (e.g. study.sqlite)"
                .into(),
        });
    }
    Ok(())
}

/// The error for an SQLite database that is not a results store, given its `tables`.
fn not_a_store(path: &Path, tables: &[String]) -> BenchError {
    let found = if tables.is_empty() {
        "it has no tables".to_string()
    } else {
        format!(
            "it has the tables {}, not frontier's ({})",
            list_tables(tables),
            TABLES.join(", ")
        )
    };
    BenchError::Store {
        path: path.to_path_buf(),
        message: format!("is not a frontier results database ({found}); give another file"),
    }
}

impl Store {
    /// Open (or create) the database at `path` for study `scenario` with `fingerprint`
    /// (see [`crate::plan::Plan::fingerprint`]); a database of another study or
    /// fingerprint is refused, so results of different settings never mix. An existing
    /// database is checked read-only first — that it holds no other study, then `check`
    /// (a run's: that it holds the plan's environments and trials as the plan runs them) —
    /// so a refused one is left as it was.
    ///
    /// When `check` finds that the store holds everything the run needs (`true`), it is
    /// kept read-only: re-running a finished study to write its report then works on a
    /// store the user may only read (a shared folder, a read-only mount), and writes
    /// nothing to it or beside it. A store that does not record its layout or study yet, or
    /// has a `-journal` or `-wal` file beside it (a write cut short, a run killed in WAL
    /// mode), is opened for writing all the same, which rolls it back or checkpoints it
    /// into one file.
    pub fn open_unless_finished(
        path: &Path,
        scenario: &str,
        fingerprint: &str,
        check: impl FnOnce(&Store) -> Result<bool, BenchError>,
    ) -> Result<Store, BenchError> {
        let store = Store::open_or_read(path, |s| {
            s.check_study(scenario, fingerprint)?;
            let finished = check(s)?;
            Ok(finished && s.meta("scenario")?.is_some() && s.meta("fingerprint")?.is_some())
        })?;
        if store.writable {
            store.claim(scenario, fingerprint)?;
        }
        Ok(store)
    }

    /// Keep the scenario's free-text `description` for the report (an empty one is not
    /// kept; a later run's replaces an earlier one).
    pub fn describe(&self, description: &str) -> Result<(), BenchError> {
        match description.trim() {
            "" => Ok(()),
            text => self.set_meta("description", text),
        }
    }

    /// Whether the store keeps `description` as [`describe`](Self::describe) would
    /// (an empty one is never written, so any kept text stands for it).
    pub fn description_is(&self, description: &str) -> Result<bool, BenchError> {
        Ok(match description.trim() {
            "" => true,
            text => self.meta("description")?.as_deref() == Some(text),
        })
    }

    /// Whether this store was opened for writing (see [`Store::open_unless_finished`] for
    /// one that is not).
    pub fn is_writable(&self) -> bool {
        self.writable
    }

    /// Open (or create) the database for writing without checking what study it holds.
    ///
    /// An existing, non-empty file is first opened read-only and checked (see
    /// [`Store::open_read_only`]; a store with frontier's tables that does not record its
    /// layout yet, as when its making was cut short, passes too): it must pass SQLite's
    /// `quick_check` (a damaged file would otherwise resume as "all done" from an intact
    /// key index over lost rows) and be a results store of this table layout, not some
    /// other database. Only a store that passes is opened for writing, so a refused file is
    /// left byte for byte as it was, with nothing written beside it. Only a new or empty
    /// file, or such a store, gets frontier's tables and WAL mode.
    pub fn open_raw(path: &Path) -> Result<Store, BenchError> {
        Store::open_or_read(path, |_| Ok(false))
    }

    /// [`Store::open_raw`] with `check` given the store read-only after its checks, except
    /// that an existing store for which `check` returns `true` (nothing to write) is
    /// returned as it was checked, read-only, provided it records its table layout and
    /// nothing lies beside it: a `-journal` (a write cut
    /// short, rolled back only by opening it for writing) or a `-wal` (a run killed in WAL
    /// mode, which a reader would leave a `-shm` beside) takes the write path.
    fn open_or_read(
        path: &Path,
        check: impl FnOnce(&Store) -> Result<bool, BenchError>,
    ) -> Result<Store, BenchError> {
        ends_as_a_folder(path)?;
        if path.is_dir() {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: "is a folder; expected a results database file (e.g. study.sqlite)".into(),
            });
        }
        if let Some(file) = file_in_the_way(path) {
            return Err(under_a_file(path, file));
        }
        if let Some(dir) = grid::io::missing_folder(path) {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: format!(
                    "the folder {} does not exist; create it first",
                    dir.display()
                ),
            });
        }
        let existing = std::fs::metadata(path).is_ok_and(|m| m.len() > 0);
        if existing {
            let journal = has_journal(path);
            if journal {
                // A write cut short must be rolled back before the file can be read, which a
                // read-only connection cannot do. Whether the file is a store this program
                // may write is told without the journal first, so that only a store (or a
                // database holding nothing) is rolled back (by merely reading it for
                // writing).
                Store::inspect(path, false)?;
                Connection::open(path)
                    .and_then(|c| {
                        c.busy_timeout(std::time::Duration::from_secs(30))?;
                        c.query_row("SELECT COUNT(*) FROM sqlite_master", [], |_| Ok(()))
                    })
                    .map_err(|e| not_writable(path, e))?;
            }
            // A database that holds nothing, not even a table (what a first run cut short
            // while it made the file leaves), is made into a store as a new file is.
            if let Some((store, versioned)) = Store::inspect(path, true)? {
                let finished = check(&store)?;
                if finished && versioned && !journal && !sibling(path, "-wal").exists() {
                    return Ok(store);
                }
            }
        }
        let conn = Connection::open(path).map_err(|e| not_writable(path, e))?;
        let sql = BenchError::sql(path);
        conn.busy_timeout(std::time::Duration::from_secs(30))
            .map_err(sql)?;
        let mode: String =
            while_busy(|| conn.query_row("PRAGMA journal_mode=WAL", [], |r| r.get(0)))
                .map_err(|e| not_writable(path, e))?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: format!("could not switch to WAL mode (journal mode is {mode})"),
            });
        }
        conn.execute_batch("PRAGMA synchronous=NORMAL;")
            .map_err(BenchError::sql(path))?;
        conn.execute_batch(CREATE).map_err(BenchError::sql(path))?;
        let store = Store {
            conn,
            path: path.to_path_buf(),
            writable: true,
        };
        match store.meta("schema_version")? {
            None => store.set_meta("schema_version", SCHEMA_VERSION)?,
            Some(v) => store.check_schema(&v)?,
        }
        Ok(store)
    }

    /// Open an existing database for reading only (export, report, merge inputs): the
    /// file is never written, nor anything beside it, so a database on a read-only file
    /// system or owned by someone else can be read, and a wrong file given as an input
    /// stays as it was. It must be an SQLite database that passes `quick_check` and a
    /// results store of this table layout.
    pub fn open_read_only(path: &Path) -> Result<Store, BenchError> {
        ends_as_a_folder(path)?;
        let meta = match std::fs::metadata(path) {
            Ok(m) => m,
            Err(e) => {
                if let Some(file) = file_in_the_way(path) {
                    return Err(under_a_file(path, file));
                }
                if e.kind() == std::io::ErrorKind::NotFound {
                    return Err(BenchError::Store {
                        path: path.to_path_buf(),
                        message: "no such file; expected a results database".into(),
                    });
                }
                return Err(BenchError::io(path)(e));
            }
        };
        if meta.is_dir() {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: "is a folder; expected a results database file (e.g. study.sqlite)".into(),
            });
        }
        if !meta.is_file() {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: "is not a file; expected a results database".into(),
            });
        }
        if meta.len() == 0 {
            return Err(BenchError::Store {
                path: path.to_path_buf(),
                message: "is an empty file, not a frontier results database".into(),
            });
        }
        if has_journal(path) {
            // Told without the journal first, so that another program's database says so
            // rather than that it cannot be read as it is.
            Store::inspect(path, false)?;
        }
        match Store::inspect(path, true)? {
            Some((store, true)) => Ok(store),
            None => Err(not_a_store(path, &[])),
            Some((_, false)) => Err(BenchError::Store {
                path: path.to_path_buf(),
                message: "is not a frontier results database (it has frontier's tables but no \
                          table layout version: it was never finished being made); give \
                          another file"
                    .into(),
            }),
        }
    }

    /// Open the existing, non-empty file `path` read-only and check that it is a results
    /// store this program can use, writing nothing to it or beside it: an SQLite database
    /// (by its header), passing `quick_check`, with frontier's `meta` table, a table
    /// layout version this program reads and, at that version, frontier's tables and
    /// columns. Also whether it records its layout version: a store whose making was cut
    /// short before it did, with frontier's tables and columns, passes without.
    ///
    /// Not `whole`: only what the file is, read as immutable (any `-journal` beside it
    /// ignored) and without `quick_check`, for a file whose last write was cut short and
    /// which cannot be read whole before it is rolled back.
    ///
    /// `None`: the database holds nothing, not even a table or a user version (what a
    /// first run cut short while it made the file leaves; one with a user version belongs
    /// to some program), and may be made into a store as a new file is.
    fn inspect(path: &Path, whole: bool) -> Result<Option<(Store, bool)>, BenchError> {
        let header = sqlite_header(path)?;
        let conn = if whole {
            open_read_only(path, wal_mode(&header))?
        } else {
            open_immutable(path)?
        };
        conn.busy_timeout(std::time::Duration::from_secs(30))
            .map_err(BenchError::sql(path))?;
        if whole {
            check_integrity(&conn, path)?;
        }
        let (schema, user_version): (i64, i64) = conn
            .query_row(
                "SELECT (SELECT COUNT(*) FROM sqlite_master), (SELECT user_version FROM \
                 pragma_user_version)",
                [],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .map_err(BenchError::sql(path))?;
        if schema == 0 && user_version == 0 {
            return Ok(None);
        }
        let tables = table_names(&conn, path)?;
        let meta_columns = columns(&conn, "meta").map_err(BenchError::sql(path))?;
        if meta_columns != ["key", "value"] {
            return Err(not_a_store(path, &tables));
        }
        let store = Store {
            conn,
            path: path.to_path_buf(),
            writable: false,
        };
        let version = store.meta("schema_version")?;
        if let Some(v) = &version {
            store.check_schema(v)?;
        }
        match (layout_difference(&store.conn, path)?, &version) {
            (None, _) => Ok(Some((store, version.is_some()))),
            (Some(_), None) => Err(not_a_store(path, &tables)),
            (Some(why), Some(v)) => Err(store.problem(format!(
                "records table layout {v}, but its tables are not that layout's ({why}); it \
                 was not written by frontier, or was changed since: give another file"
            ))),
        }
    }

    fn check_schema(&self, version: &str) -> Result<(), BenchError> {
        if version == SCHEMA_VERSION {
            return Ok(());
        }
        // The program versions that ran its trials, when its trials table says (best effort:
        // a foreign layout may not have that column).
        let ran_by: Vec<String> = self
            .conn
            .prepare("SELECT DISTINCT version FROM trials ORDER BY version")
            .and_then(|mut q| {
                q.query_map([], |r| r.get::<_, String>(0))?
                    .collect::<Result<Vec<_>, _>>()
            })
            .unwrap_or_default();
        let which = if ran_by.is_empty() {
            "the frontier version that wrote it".to_string()
        } else {
            format!(
                "the frontier version that wrote it (its trials were run by version {})",
                ran_by.join(", ")
            )
        };
        let age = match (version.parse::<u32>(), SCHEMA_VERSION.parse::<u32>()) {
            (Ok(v), Ok(ours)) if v > ours => "a newer",
            (Ok(_), Ok(_)) => "an older",
            _ => "another",
        };
        Err(self.problem(format!(
            "results of table layout {version}, written by {age} frontier; this program reads \
             and writes layout {SCHEMA_VERSION} only and cannot convert it. To report, export or \
             resume it, use {which}; to continue the study with this program, run it into a new \
             database file (its trials are run again there)"
        )))
    }

    /// The study (scenario name, fingerprint) the database holds; a database that holds
    /// none (never claimed by a run) is refused.
    pub fn study(&self) -> Result<(String, String), BenchError> {
        match (self.meta("scenario")?, self.meta("fingerprint")?) {
            (Some(s), Some(f)) => Ok((s, f)),
            _ => Err(self.problem(
                "holds no study (no scenario name or fingerprint); it was never written by `frontier bench`".into(),
            )),
        }
    }

    fn problem(&self, message: String) -> BenchError {
        BenchError::Store {
            path: self.path.clone(),
            message,
        }
    }

    /// Record the study in an empty database, or check that it is the same study.
    pub fn claim(&self, scenario: &str, fingerprint: &str) -> Result<(), BenchError> {
        self.check_study(scenario, fingerprint)?;
        for (key, want) in [("scenario", scenario), ("fingerprint", fingerprint)] {
            if self.meta(key)?.is_none() {
                self.set_meta(key, want)?;
            }
        }
        Ok(())
    }

    /// Refuse a database that holds another study than `scenario` with `fingerprint`
    /// (one that holds none yet is no conflict); reads only.
    pub fn check_study(&self, scenario: &str, fingerprint: &str) -> Result<(), BenchError> {
        for (key, want) in [("scenario", scenario), ("fingerprint", fingerprint)] {
            match self.meta(key)? {
                Some(have) if have != want => {
                    return Err(self.problem(format!(
                        "holds results of another {key} ('{have}', not '{want}'); use another database file"
                    )));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// A value of the meta table.
    pub fn meta(&self, key: &str) -> Result<Option<String>, BenchError> {
        self.conn
            .query_row("SELECT value FROM meta WHERE key = ?1", [key], |r| r.get(0))
            .optional()
            .map_err(BenchError::sql(&self.path))
    }

    fn set_meta(&self, key: &str, value: &str) -> Result<(), BenchError> {
        self.conn
            .execute(
                "INSERT OR REPLACE INTO meta (key, value) VALUES (?1, ?2)",
                [key, value],
            )
            .map(|_| ())
            .map_err(BenchError::sql(&self.path))
    }

    /// Keys of the finished trials.
    pub fn finished(&self) -> Result<BTreeSet<String>, BenchError> {
        let mut st = self
            .conn
            .prepare("SELECT key FROM trials")
            .map_err(BenchError::sql(&self.path))?;
        let keys = st
            .query_map([], |r| r.get::<_, String>(0))
            .map_err(BenchError::sql(&self.path))?
            .collect::<Result<BTreeSet<_>, _>>()
            .map_err(BenchError::sql(&self.path))?;
        Ok(keys)
    }

    /// Insert one finished trial, committed at once (a trial already stored is kept);
    /// whether the row was new.
    pub fn insert(&self, r: &TrialRow) -> Result<bool, BenchError> {
        let mut st = self
            .conn
            .prepare_cached(&format!(
                "INSERT OR IGNORE INTO trials ({COLUMNS}) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21, ?22, ?23, ?24, ?25, ?26, ?27, ?28, ?29, ?30, ?31, ?32, ?33, ?34, ?35, ?36, ?37, ?38, ?39, ?40, ?41, ?42, ?43, ?44, ?45, ?46)"
            ))
            .map_err(BenchError::sql(&self.path))?;
        st.execute(params![
            r.key,
            r.scenario,
            r.env,
            r.env_kind,
            r.env_seed,
            r.map_file,
            r.resolution,
            r.width,
            r.height,
            r.strategy,
            r.preset,
            r.s_max,
            r.sensor,
            r.belief,
            r.sensing,
            r.robots,
            r.start_variant,
            r.trial,
            r.seed,
            r.starts,
            r.clearance,
            r.speed,
            r.coverage_goal,
            r.max_moves,
            r.path_lengths,
            r.max_path,
            r.total_path,
            r.time_s,
            r.coverage,
            r.decisions,
            r.moves,
            r.reason,
            r.reachable_cells,
            r.coverage_curve,
            r.version,
            r.wall_s,
            r.optimal_m,
            r.optimal_lower_m,
            r.optimal_proven,
            r.ratio,
            r.d90_m,
            r.t90_s,
            r.d99_m,
            r.t99_s,
            r.overlap,
            r.idle_s,
        ])
        .map(|n| n == 1)
        .map_err(BenchError::sql(&self.path))
    }

    /// Store the picture of an environment unless it is there already; one of the same
    /// name that draws another map (`source`, the scenario or a database being merged,
    /// changed it) is refused, as results of the two maps would pass for one.
    pub fn put_env(&self, e: &EnvPicture, source: &str) -> Result<(), BenchError> {
        if self.check_env(e, source)? {
            return Ok(());
        }
        self.conn
            .execute(
                "INSERT OR IGNORE INTO envs (name, width, height, resolution, png) VALUES (?1, ?2, ?3, ?4, ?5)",
                params![e.name, e.width, e.height, e.resolution, e.png],
            )
            .map(|_| ())
            .map_err(BenchError::sql(&self.path))
    }

    /// Refuse `e` (of `source`) when the store holds a picture of the same name that draws
    /// another map, as [`Store::put_env`] does, without writing anything; whether the store
    /// holds it already.
    pub fn check_env(&self, e: &EnvPicture, source: &str) -> Result<bool, BenchError> {
        let Some(have) = self.env(&e.name)? else {
            return Ok(false);
        };
        match have.difference(e, source) {
            None => Ok(true),
            Some(why) => Err(self.problem(format!(
                "{why}; these results are of another environment: use another database file"
            ))),
        }
    }

    /// Store the optimal path of `key` (see [`crate::competitive::key`]), committed at once.
    pub fn put_optimal(
        &self,
        key: &str,
        p: &crate::competitive::OptimalPath,
    ) -> Result<(), BenchError> {
        self.conn
            .execute(
                "INSERT OR IGNORE INTO optimal (key, length_m, lower_m, proven, expanded, wall_s) VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
                params![key, p.length_m, p.lower_m, p.optimal, p.expanded as i64, p.wall_s],
            )
            .map(|_| ())
            .map_err(BenchError::sql(&self.path))
    }

    /// Every stored optimal path, by key.
    pub fn optimal_paths(
        &self,
    ) -> Result<Vec<(String, crate::competitive::OptimalPath)>, BenchError> {
        let mut st = self
            .conn
            .prepare(
                "SELECT key, length_m, lower_m, proven, expanded, wall_s FROM optimal ORDER BY key",
            )
            .map_err(BenchError::sql(&self.path))?;
        let rows = st
            .query_map([], |r| {
                Ok((
                    r.get::<_, String>(0)?,
                    crate::competitive::OptimalPath {
                        length_m: r.get(1)?,
                        lower_m: r.get(2)?,
                        optimal: r.get(3)?,
                        expanded: r.get::<_, i64>(4)? as u64,
                        wall_s: r.get(5)?,
                    },
                ))
            })
            .map_err(BenchError::sql(&self.path))?
            .collect::<Result<Vec<_>, _>>()
            .map_err(BenchError::sql(&self.path))?;
        Ok(rows)
    }

    /// The stored picture of environment `name`, if any.
    pub fn env(&self, name: &str) -> Result<Option<EnvPicture>, BenchError> {
        self.conn
            .query_row(
                "SELECT name, width, height, resolution, png FROM envs WHERE name = ?1",
                [name],
                env_picture,
            )
            .optional()
            .map_err(BenchError::sql(&self.path))
    }

    /// The setup of every stored trial, by key.
    pub fn setups(&self) -> Result<std::collections::BTreeMap<String, TrialSetup>, BenchError> {
        let mut st = self
            .conn
            .prepare(
                "SELECT key, env_kind, env_seed, resolution, width, height, preset, s_max, \
                 sensing, seed, starts FROM trials",
            )
            .map_err(BenchError::sql(&self.path))?;
        let rows = st
            .query_map([], |r| {
                Ok((
                    r.get::<_, String>(0)?,
                    TrialSetup {
                        env_kind: r.get(1)?,
                        env_seed: r.get(2)?,
                        resolution: r.get(3)?,
                        width: r.get(4)?,
                        height: r.get(5)?,
                        preset: r.get(6)?,
                        s_max: r.get(7)?,
                        sensing: r.get(8)?,
                        seed: r.get(9)?,
                        starts: Some(r.get(10)?),
                    },
                ))
            })
            .map_err(BenchError::sql(&self.path))?
            .collect::<Result<_, _>>()
            .map_err(BenchError::sql(&self.path))?;
        Ok(rows)
    }

    /// The stored environment pictures, ordered by name.
    pub fn envs(&self) -> Result<Vec<EnvPicture>, BenchError> {
        let mut st = self
            .conn
            .prepare("SELECT name, width, height, resolution, png FROM envs ORDER BY name")
            .map_err(BenchError::sql(&self.path))?;
        let rows = st
            .query_map([], env_picture)
            .map_err(BenchError::sql(&self.path))?
            .collect::<Result<Vec<_>, _>>()
            .map_err(BenchError::sql(&self.path))?;
        Ok(rows)
    }

    /// Every stored trial, ordered by key.
    pub fn rows(&self) -> Result<Vec<TrialRow>, BenchError> {
        let mut st = self
            .conn
            .prepare(&format!("SELECT {COLUMNS} FROM trials ORDER BY key"))
            .map_err(BenchError::sql(&self.path))?;
        let rows = st
            .query_map([], |r| {
                Ok(TrialRow {
                    key: r.get(0)?,
                    scenario: r.get(1)?,
                    env: r.get(2)?,
                    env_kind: r.get(3)?,
                    env_seed: r.get(4)?,
                    map_file: r.get(5)?,
                    resolution: r.get(6)?,
                    width: r.get(7)?,
                    height: r.get(8)?,
                    strategy: r.get(9)?,
                    preset: r.get(10)?,
                    s_max: r.get(11)?,
                    sensor: r.get(12)?,
                    belief: r.get(13)?,
                    sensing: r.get(14)?,
                    robots: r.get(15)?,
                    start_variant: r.get(16)?,
                    trial: r.get(17)?,
                    seed: r.get(18)?,
                    starts: r.get(19)?,
                    clearance: r.get(20)?,
                    speed: r.get(21)?,
                    coverage_goal: r.get(22)?,
                    max_moves: r.get(23)?,
                    path_lengths: r.get(24)?,
                    max_path: r.get(25)?,
                    total_path: r.get(26)?,
                    time_s: r.get(27)?,
                    coverage: r.get(28)?,
                    decisions: r.get(29)?,
                    moves: r.get(30)?,
                    reason: r.get(31)?,
                    reachable_cells: r.get(32)?,
                    coverage_curve: r.get(33)?,
                    version: r.get(34)?,
                    wall_s: r.get(35)?,
                    optimal_m: r.get(36)?,
                    optimal_lower_m: r.get(37)?,
                    optimal_proven: r.get(38)?,
                    ratio: r.get(39)?,
                    d90_m: r.get(40)?,
                    t90_s: r.get(41)?,
                    d99_m: r.get(42)?,
                    t99_s: r.get(43)?,
                    overlap: r.get(44)?,
                    idle_s: r.get(45)?,
                })
            })
            .map_err(BenchError::sql(&self.path))?
            .collect::<Result<Vec<_>, _>>()
            .map_err(BenchError::sql(&self.path))?;
        Ok(rows)
    }

    /// Merge the databases `inputs` into the database `out` (created if missing; trials
    /// already there are kept).
    ///
    /// Every input is opened read-only and checked first — it exists, is a results store
    /// that passes `quick_check`, and holds the same study and fingerprint as the others
    /// and as `out` — so a bad input changes nothing: no input is written, and `out` is
    /// neither created nor changed. The copy is one transaction, all or nothing.
    pub fn merge(out: &Path, inputs: &[PathBuf]) -> Result<Merged, BenchError> {
        ends_as_a_folder(out)?;
        let mut study: Option<(String, String, &Path)> = None;
        for input in inputs {
            let (scenario, fingerprint) = Store::open_read_only(input)?.study()?;
            if let Some((s, f, first)) = &study {
                for (key, have, want) in
                    [("scenario", &scenario, s), ("fingerprint", &fingerprint, f)]
                {
                    if have != want {
                        return Err(BenchError::Store {
                            path: input.clone(),
                            message: format!(
                                "holds results of another {key} ('{have}', not '{want}' as {}); merge only shards of one study",
                                first.display()
                            ),
                        });
                    }
                }
            } else {
                study = Some((scenario, fingerprint, input));
            }
        }
        let Some((scenario, fingerprint, first)) = study else {
            return Err(BenchError::Other("merge: no input databases".into()));
        };
        let existed = std::fs::metadata(out).is_ok_and(|m| m.len() > 0);
        if existed {
            let have = Store::open_read_only(out)?;
            if have.meta("scenario")?.is_some() || have.meta("fingerprint")?.is_some() {
                let (s, f) = have.study()?;
                if (&s, &f) != (&scenario, &fingerprint) {
                    let (key, held, want) = if s != scenario {
                        ("study", &s, &scenario)
                    } else {
                        ("fingerprint (settings)", &f, &fingerprint)
                    };
                    let inputs = if inputs.len() == 1 {
                        format!("the input {}, which holds", first.display())
                    } else {
                        format!(
                            "the {} inputs ({} and the others), which hold",
                            inputs.len(),
                            first.display()
                        )
                    };
                    return Err(have.problem(format!(
                        "holds results of another {key}, '{held}', than {inputs} '{want}'; \
                         merge into another file"
                    )));
                }
            }
        }
        let created = !out.exists();
        let result =
            Store::open_raw(out).and_then(|store| store.copy_in(&scenario, &fingerprint, inputs));
        if result.is_err() && created {
            for suffix in ["", "-wal", "-shm", "-journal"] {
                let _ = std::fs::remove_file(sibling(out, suffix));
            }
        }
        result
    }

    /// Copy the checked `inputs` into this store in one transaction.
    fn copy_in(
        &self,
        scenario: &str,
        fingerprint: &str,
        inputs: &[PathBuf],
    ) -> Result<Merged, BenchError> {
        let tx = self
            .conn
            .unchecked_transaction()
            .map_err(BenchError::sql(&self.path))?;
        self.claim(scenario, fingerprint)?;
        // Where each trial held so far comes from, and how it was run: a trial of the same
        // key run otherwise (shards of an edited scenario) is refused, not dropped.
        let mut held: std::collections::BTreeMap<String, (TrialSetup, &Path)> = self
            .setups()?
            .into_iter()
            .map(|(k, s)| (k, (s, self.path.as_path())))
            .collect();
        let mut added = 0;
        for input in inputs {
            let other = Store::open_read_only(input)?;
            let source = input.display().to_string();
            if self.meta("description")?.is_none()
                && let Some(text) = other.meta("description")?
            {
                self.describe(&text)?;
            }
            for e in &other.envs()? {
                self.put_env(e, &source)?;
            }
            for (k, p) in &other.optimal_paths()? {
                self.put_optimal(k, p)?;
            }
            for r in &other.rows()? {
                let setup = TrialSetup::of(r);
                if let Some((have, from)) = held.get(&r.key) {
                    if let Some((column, a, b)) = have.difference(&setup) {
                        return Err(BenchError::Store {
                            path: input.clone(),
                            message: format!(
                                "holds trial {} run with {column} {b}, but {} holds it run \
                                 with {column} {a}: these are not shards of one study \
                                 (was the scenario changed between them?)",
                                r.key,
                                from.display()
                            ),
                        });
                    }
                    continue;
                }
                added += usize::from(self.insert(r)?);
                held.insert(r.key.clone(), (setup, input.as_path()));
            }
        }
        let total = self.count()?;
        tx.commit().map_err(BenchError::sql(&self.path))?;
        Ok(Merged { added, total })
    }

    /// Number of stored trials.
    pub fn count(&self) -> Result<usize, BenchError> {
        self.conn
            .query_row("SELECT COUNT(*) FROM trials", [], |r| r.get::<_, i64>(0))
            .map(|n| n as usize)
            .map_err(BenchError::sql(&self.path))
    }

    /// Write every trial as CSV (header = column names, also when there is no trial; rows
    /// ordered by key); `out` must not be this database (nor its journal), which is checked
    /// before anything is written.
    pub fn export_csv(&self, out: &Path) -> Result<usize, BenchError> {
        refuse_overwriting(&self.path, out, "the CSV")?;
        let rows = self.rows()?;
        let mut w = csv::Writer::from_path(out)
            .map_err(|e| BenchError::Other(format!("{}: {e}", out.display())))?;
        if rows.is_empty() {
            // The header a row would have written (the columns are the row's fields), so
            // that an empty study still reads as a table of no rows.
            w.write_record(COLUMNS.split(',').map(str::trim))
                .map_err(|e| BenchError::Other(format!("{}: {e}", out.display())))?;
        }
        for r in &rows {
            w.serialize(r)
                .map_err(|e| BenchError::Other(format!("{}: {e}", out.display())))?;
        }
        w.flush().map_err(BenchError::io(out))?;
        Ok(rows.len())
    }
}
