//! Regressions of giving a wrong file where a study store is expected (`--db`, resume,
//! `merge` inputs and output, `report`, `export`): another program's SQLite database, a
//! store of another table layout, study or edited scenario, a file that is not SQLite at
//! all, a path under a file. Every opening path refuses it, naming the file, what was
//! expected and what was found, and leaves it byte for byte as it was, with no `-wal`,
//! `-shm` or `-journal` file beside it.

use std::path::{Path, PathBuf};

use bench::{Plan, RunOptions, Source, Store, Unbuilt};
use rusqlite::Connection;

/// A study of two trials on a tiny empty room.
const ONE: &str = r#"
name = "one"
strategies = ["cf", "random"]
sensors = ["los:r=3c"]

[[env]]
kind = "empty"
size = [4, 4]
resolution = 0.5
"#;

fn plan(text: &str) -> Plan {
    let src = Source {
        file: "s.toml".into(),
        text: text.into(),
        dir: None,
    };
    Plan::resolve(&src, Unbuilt::Error).expect("scenario resolves")
}

fn opts() -> RunOptions {
    RunOptions {
        threads: Some(1),
        ..RunOptions::default()
    }
}

/// Run `text` into `db`.
fn run(text: &str, db: &Path) {
    let summary = bench::runner::run(&plan(text), db, &opts()).expect("run");
    assert!(summary.failed.is_empty(), "{:?}", summary.failed);
}

/// The length and a hash (FNV-1a) of the bytes of a file, and the names of every file in
/// its folder: what must not change.
#[derive(Debug, PartialEq)]
struct Snapshot {
    len: usize,
    hash: u64,
    folder: Vec<String>,
}

fn snapshot(path: &Path) -> Snapshot {
    let bytes = std::fs::read(path).unwrap();
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    });
    let mut folder: Vec<String> = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    folder.sort();
    Snapshot {
        len: bytes.len(),
        hash,
        folder,
    }
}

/// The error of every path that opens a store — running a study into it (a new study
/// and, when `resumed` is given, the study it holds), `open_raw`, `open_read_only`,
/// `export`, `report`, and `merge` with it as an input and as the output — each checked
/// to name `db` and to leave it (and its folder) as it was. A merge with it as an input
/// must also leave no output behind.
fn every_opening_error(db: &Path, resumed: Option<&str>) -> Vec<String> {
    let dir = db.parent().unwrap();
    let good = dir.join("good").join("good.sqlite");
    if !good.exists() {
        std::fs::create_dir_all(good.parent().unwrap()).unwrap();
        run(ONE, &good);
    }
    let before = snapshot(db);
    let mut errors = Vec::new();
    let mut check = |what: &str, e: Result<(), bench::BenchError>| {
        let e = e.expect_err(&format!("{what} must refuse {}", db.display()));
        let e = e.to_string();
        assert!(
            e.starts_with(&format!("{}: ", db.display())),
            "{what}: the error names another file: {e}"
        );
        assert_eq!(snapshot(db), before, "{what} changed {}", db.display());
        errors.push(e);
    };
    check(
        "a run",
        bench::runner::run(&plan(&ONE.replace("\"one\"", "\"new\"")), db, &opts()).map(drop),
    );
    if let Some(text) = resumed {
        check(
            "a resumed run",
            bench::runner::run(&plan(text), db, &opts()).map(drop),
        );
    }
    check("open_raw", Store::open_raw(db).map(drop));
    check("open_read_only", Store::open_read_only(db).map(drop));
    let csv = dir.join("good").join("out.csv");
    check(
        "export",
        Store::open_read_only(db).and_then(|s| s.export_csv(&csv).map(drop)),
    );
    assert!(!csv.exists(), "export wrote {}", csv.display());
    let report = dir.join("good").join("report");
    check(
        "report",
        bench::report::write(db, &report, &Default::default()).map(drop),
    );
    assert!(!report.exists(), "report wrote {}", report.display());
    let out = dir.join("good").join("merged.sqlite");
    check(
        "merge of it",
        Store::merge(&out, &[good.clone(), db.to_path_buf()]).map(drop),
    );
    assert!(!out.exists(), "a refused merge wrote {}", out.display());
    check(
        "merge into it",
        Store::merge(db, std::slice::from_ref(&good)).map(drop),
    );
    errors
}

/// An SQLite database of another program at `path`: a notes table and, as many programs
/// have, a `meta (key, value)` table like frontier's; in WAL mode when `wal`.
fn foreign_database(path: &Path, wal: bool) {
    let conn = Connection::open(path).unwrap();
    if wal {
        let mode: String = conn
            .query_row("PRAGMA journal_mode=WAL", [], |r| r.get(0))
            .unwrap();
        assert_eq!(mode, "wal");
    }
    conn.execute_batch(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
         INSERT INTO meta VALUES ('app', 'notes 1.4');
         CREATE TABLE notes (id INTEGER PRIMARY KEY, body TEXT);
         INSERT INTO notes (body) VALUES ('buy milk'), ('call Ada');",
    )
    .unwrap();
}

/// Regression: `--db` naming another program's SQLite database that has a `meta` table
/// gave it frontier's tables and a layout version and switched it to WAL mode (a run
/// then went on into it); readers left `-wal` and `-shm` files beside a WAL-mode one.
/// Every opening path refuses it, naming its tables, and leaves it as it was.
#[test]
fn foreign_sqlite_file_is_refused_unchanged() {
    for wal in [false, true] {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("notes.db");
        foreign_database(&db, wal);
        for e in every_opening_error(&db, None) {
            assert!(
                e.contains(
                    "is not a frontier results database (it has the tables meta, notes, not \
                     frontier's (meta, envs, trials, optimal)); give another file"
                ),
                "wal {wal}: {e}"
            );
        }
        let conn = Connection::open(&db).unwrap();
        let tables: i64 = conn
            .query_row("SELECT COUNT(*) FROM sqlite_master", [], |r| r.get(0))
            .unwrap();
        assert_eq!(tables, 3, "meta, its key index and notes");
    }
}

/// A foreign database without a `meta` table, and one without any table, are refused
/// alike, saying what they hold.
#[test]
fn sqlite_file_without_frontiers_tables_is_refused_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("photos.sqlite");
    Connection::open(&db)
        .unwrap()
        .execute_batch("CREATE TABLE photos (path TEXT); CREATE TABLE albums (name TEXT);")
        .unwrap();
    for e in every_opening_error(&db, None) {
        assert!(
            e.contains("(it has the tables albums, photos, not frontier's (meta, envs, trials"),
            "{e}"
        );
    }
    let none = dir.path().join("none.sqlite");
    Connection::open(&none)
        .unwrap()
        .execute_batch("PRAGMA user_version = 7;")
        .unwrap();
    for e in every_opening_error(&none, None) {
        assert!(
            e.contains("is not a frontier results database (it has no tables)"),
            "{e}"
        );
    }
}

/// A store of layout 2, made by hand as frontier 0.1 wrote it: its trials table lacks
/// the columns layout 3 added (D90/D99, overlap, idle). In WAL mode when `wal`, as an
/// older version left its stores.
fn layout_2_store(path: &Path, wal: bool) {
    let conn = Connection::open(path).unwrap();
    if wal {
        conn.query_row("PRAGMA journal_mode=WAL", [], |_| Ok(()))
            .unwrap();
    }
    conn.execute_batch(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
         INSERT INTO meta VALUES ('schema_version', '2'), ('scenario', 'one'),
             ('fingerprint', 'old');
         CREATE TABLE envs (name TEXT PRIMARY KEY, width INTEGER NOT NULL,
             height INTEGER NOT NULL, resolution REAL NOT NULL, png BLOB NOT NULL);
         CREATE TABLE trials (key TEXT PRIMARY KEY, scenario TEXT NOT NULL,
             max_path REAL NOT NULL, total_path REAL NOT NULL, version TEXT NOT NULL);
         INSERT INTO trials VALUES ('e|cf|los|m=1|start=0|trial=0', 'one', 3.5, 3.5, '0.1.0');
         CREATE TABLE optimal (key TEXT PRIMARY KEY, length_m REAL, lower_m REAL NOT NULL,
             proven INTEGER NOT NULL, expanded INTEGER NOT NULL, wall_s REAL NOT NULL);",
    )
    .unwrap();
}

/// Regression: running a study into a store of an older table layout switched it to WAL
/// mode and back, and gave it any table it lacked, before the layout was refused; the file
/// changed although nothing was run. Every opening path refuses it unchanged, with the
/// layout message.
#[test]
fn old_layout_store_is_refused_unchanged() {
    for wal in [false, true] {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("old.sqlite");
        layout_2_store(&db, wal);
        for e in every_opening_error(&db, Some(ONE)) {
            assert!(
                e.contains("results of table layout 2, written by an older frontier"),
                "wal {wal}: {e}"
            );
            assert!(e.contains("reads and writes layout 3 only"), "{e}");
            assert!(e.contains("its trials were run by version 0.1.0"), "{e}");
        }
    }
}

/// Regression: a store of layout 3 without its `optimal` table (or that claims layout 3
/// over another layout's tables) was given the table and used. It is refused unchanged,
/// saying what differs.
#[test]
fn store_whose_tables_are_not_its_layouts_is_refused_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("odd.sqlite");
    run(ONE, &db);
    let conn = Connection::open(&db).unwrap();
    conn.execute_batch("DROP TABLE optimal; ALTER TABLE trials DROP COLUMN idle_s;")
        .unwrap();
    drop(conn);
    for e in every_opening_error(&db, Some(ONE)) {
        assert!(
            e.contains(
                "records table layout 3, but its tables are not that layout's (its table \
                 trials lacks idle_s; it has no table optimal)"
            ),
            "{e}"
        );
    }
}

/// Regression: resuming with a study of another name or other settings into a store
/// switched it to WAL mode and back before refusing it, changing its bytes. It is refused
/// before anything is written, with the message it had.
#[test]
fn store_of_another_study_is_refused_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("one.sqlite");
    run(ONE, &db);
    let before = snapshot(&db);
    for (text, key) in [
        (ONE.replace("\"one\"", "\"two\""), "scenario"),
        (format!("seed = 9\n{ONE}"), "fingerprint"),
    ] {
        let e = bench::runner::run(&plan(&text), &db, &opts())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&format!("{}: ", db.display())), "{e}");
        assert!(
            e.contains(&format!("holds results of another {key}")),
            "{e}"
        );
        assert!(e.contains("use another database file"), "{e}");
        assert_eq!(snapshot(&db), before, "a refused {key} changed the store");
    }
    // The study it holds still resumes (nothing left to run).
    let again = bench::runner::run(&plan(ONE), &db, &opts()).unwrap();
    assert_eq!((again.ran, again.already_done), (0, 2));
}

/// Regression: a file that is not SQLite at all (a CSV export, a PNG, a short text) given
/// as `--db` was "file is not a database" from SQLite, or "is not an SQLite database"
/// without a word on what it is. The error says what it starts with, and the file is
/// left as it was.
#[test]
fn file_that_is_not_sqlite_is_refused_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let png = [
        0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n', 0, 0, 0, 13, b'I', b'H', b'D', b'R', 0,
        0, 0, 1,
    ];
    let cases: [(&str, &[u8], &str); 4] = [
        (
            "all.csv",
            b"key,scenario,env,env_kind\ne|cf,one,e,empty\n",
            "(it starts with \"key,scenario,env\")",
        ),
        (
            "map.png",
            &png,
            "(it starts with \"\\x89PNG\\r\\n\\x1a\\n\\x00\\x00\\x00\\rIHDR\")",
        ),
        ("short.sqlite", b"abc", "(it starts with \"abc\")"),
        (
            "garbled.sqlite",
            b"SQLite format 3\0",
            "is not an SQLite database; expected a frontier results database",
        ),
    ];
    for (name, bytes, found) in cases {
        let db = dir.path().join(name);
        let mut bytes = bytes.to_vec();
        if name == "garbled.sqlite" {
            // An SQLite header followed by noise: no page size SQLite accepts.
            bytes.resize(4096, 0xff);
        }
        std::fs::write(&db, bytes).unwrap();
        for e in every_opening_error(&db, None) {
            assert!(e.contains("is not an SQLite database"), "{name}: {e}");
            assert!(e.contains(found), "{name}: {e}");
            assert!(
                e.contains("expected a frontier results database"),
                "{name}: {e}"
            );
        }
    }
}

/// Regression: a store path under a file (`afile/s.sqlite`, `afile` a file) was "the
/// folder afile does not exist; create it first" when running and "Not a directory (os
/// error 20)" when reading. Both say that `afile` is a file.
#[test]
fn store_under_a_file_says_the_file_is_in_the_way() {
    let dir = tempfile::tempdir().unwrap();
    let afile = dir.path().join("afile");
    std::fs::write(&afile, "not a folder").unwrap();
    let good = dir.path().join("good.sqlite");
    run(ONE, &good);
    for db in [afile.join("s.sqlite"), afile.join("sub").join("s.sqlite")] {
        let errors = [
            bench::runner::run(&plan(ONE), &db, &opts()).map(drop),
            Store::open_raw(&db).map(drop),
            Store::open_read_only(&db).map(drop),
            Store::merge(&db, std::slice::from_ref(&good)).map(drop),
            Store::merge(&dir.path().join("m.sqlite"), &[good.clone(), db.clone()]).map(drop),
        ];
        for e in errors {
            let e = e.unwrap_err().to_string();
            assert!(e.starts_with(&format!("{}: ", db.display())), "{e}");
            assert!(
                e.contains(&format!(
                    "expected a results database in a folder, but {} is a file",
                    afile.display()
                )),
                "{e}"
            );
            assert!(!e.contains("os error"), "{e}");
        }
    }
    assert_eq!(std::fs::read_to_string(&afile).unwrap(), "not a folder");
    assert!(!dir.path().join("m.sqlite").exists());
}

/// Regression: a folder given where a store is read (`export DIR`, a merge input) was "is
/// not a file"; it is called a folder, as where a store is written.
#[test]
fn folder_given_as_a_store_to_read_is_called_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.sqlite");
    let folder = dir.path().to_path_buf();
    for e in [
        Store::open_read_only(&folder).map(drop),
        Store::merge(&out, std::slice::from_ref(&folder)).map(drop),
        Store::open_raw(&folder).map(drop),
    ] {
        let e = e.unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "{}: is a folder; expected a results database file (e.g. study.sqlite)",
                folder.display()
            )
        );
    }
    assert!(!out.exists());
}

/// The files beside `db` that SQLite makes (`-wal`, `-shm`, `-journal`).
fn siblings(db: &Path) -> Vec<PathBuf> {
    ["-wal", "-shm", "-journal"]
        .iter()
        .map(|s| PathBuf::from(format!("{}{s}", db.display())))
        .filter(|p| p.exists())
        .collect()
}

/// Regression: reading a store left in WAL mode (by an older version, which kept its
/// stores so) — `report`, `export`, a merge input, Python's `load` — left a `-wal` and a
/// `-shm` file beside it. Reading writes nothing now, and reads every trial.
#[test]
fn reading_a_wal_mode_store_writes_nothing_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("w.sqlite");
    run(ONE, &db);
    let conn = Connection::open(&db).unwrap();
    conn.query_row("PRAGMA journal_mode=WAL", [], |_| Ok(()))
        .unwrap();
    drop(conn);
    assert!(siblings(&db).is_empty(), "{:?}", siblings(&db));
    let before = snapshot(&db);
    let header = std::fs::read(&db).unwrap();
    assert_eq!(&header[18..20], &[2, 2], "the store is in WAL mode");
    assert_eq!(Store::open_read_only(&db).unwrap().count().unwrap(), 2);
    assert_eq!(
        Store::open_read_only(&db)
            .unwrap()
            .export_csv(&dir.path().join("w.csv"))
            .unwrap(),
        2
    );
    bench::report::write(&db, &dir.path().join("report"), &Default::default()).unwrap();
    let merged = Store::merge(&dir.path().join("m.sqlite"), std::slice::from_ref(&db)).unwrap();
    assert_eq!(merged.total, 2);
    assert!(siblings(&db).is_empty(), "{:?}", siblings(&db));
    assert_eq!(
        (snapshot(&db).len, snapshot(&db).hash),
        (before.len, before.hash)
    );
    // Resuming it finds every trial done, and leaves it one file.
    let again = bench::runner::run(&plan(ONE), &db, &opts()).unwrap();
    assert_eq!(again.already_done, 2);
    assert!(siblings(&db).is_empty(), "{:?}", siblings(&db));
}

/// Regression: resuming a study whose scenario was edited (a start moved, an environment
/// added) gave the store the new environment's picture, and switched it to WAL mode and
/// back, before the moved start was found and the run refused. It is refused before
/// anything is written, with the message it had.
#[test]
fn edited_scenario_is_refused_before_anything_is_written() {
    let fixed = ONE.replace("resolution = 0.5", "resolution = 0.5\nstart = [2, 2]");
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("one.sqlite");
    run(&fixed, &db);
    let before = snapshot(&db);
    let edited = format!(
        "{}\n[[env]]\nkind = \"empty\"\nname = \"more\"\nsize = [5, 4]\nresolution = 0.5\n",
        fixed.replace("start = [2, 2]", "start = [3, 2]")
    );
    let e = bench::runner::run(&plan(&edited), &db, &opts())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{}: holds trial ", db.display())),
        "{e}"
    );
    assert!(
        e.contains("run with starts [[2,2]], but s.toml now runs it with starts [[3,2]]"),
        "{e}"
    );
    assert_eq!(snapshot(&db), before, "a refused run changed the store");
    assert_eq!(Store::open_read_only(&db).unwrap().envs().unwrap().len(), 1);
}

/// A copy at `copy` of the database `db` as a process killed in the middle of a write
/// leaves it: `update` run on it in a transaction large enough that SQLite wrote some of
/// its pages into the file, and the `-journal` that holds what they were beside it.
fn cut_short_copy(db: &Path, update: &str, copy: &Path) {
    let journal = |p: &Path| PathBuf::from(format!("{}-journal", p.display()));
    let conn = Connection::open(db).unwrap();
    conn.execute_batch("PRAGMA cache_size = 1; BEGIN;").unwrap();
    for _ in 0..40 {
        conn.execute(update, ["x".repeat(500)]).unwrap();
    }
    std::fs::copy(db, copy).unwrap();
    std::fs::copy(journal(db), journal(copy)).unwrap();
    conn.execute_batch("ROLLBACK").unwrap();
}

/// A store whose last write was cut short (a hot `-journal` beside it) still resumes,
/// though a read-only connection cannot roll the journal back: the file is told to be a
/// store without the journal, and only then opened for writing, which rolls it back.
/// Another program's database left so is refused by every path with its journal unchanged;
/// readers of a store left so say what to do.
#[test]
fn store_with_a_write_cut_short_resumes_and_a_foreign_one_is_refused_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("one.sqlite");
    run(ONE, &db);
    let cut = dir.path().join("cut").join("one.sqlite");
    std::fs::create_dir(cut.parent().unwrap()).unwrap();
    cut_short_copy(&db, "UPDATE trials SET reason = reason || ?1", &cut);
    assert!(!siblings(&cut).is_empty(), "the copy has a journal");
    let e = Store::open_read_only(&cut).err().unwrap().to_string();
    assert!(
        e.starts_with(&format!(
            "{}: has a write that was cut short (SQLite's -journal file beside it)",
            cut.display()
        )),
        "{e}"
    );
    assert!(e.contains("resume the study into it once"), "{e}");
    let again = bench::runner::run(&plan(ONE), &cut, &opts()).unwrap();
    assert_eq!((again.ran, again.already_done), (0, 2));
    assert!(siblings(&cut).is_empty(), "{:?}", siblings(&cut));
    let rows = |p: &Path| Store::open_read_only(p).unwrap().rows().unwrap();
    assert_eq!(rows(&cut), rows(&db), "the cut-short write is rolled back");

    let theirs = dir.path().join("theirs");
    std::fs::create_dir(&theirs).unwrap();
    let notes = theirs.join("notes.db");
    foreign_database(&notes, false);
    let cut = dir.path().join("cut").join("notes.db");
    cut_short_copy(&notes, "UPDATE notes SET body = body || ?1", &cut);
    assert!(!siblings(&cut).is_empty(), "the copy has a journal");
    let journal = std::fs::read(format!("{}-journal", cut.display())).unwrap();
    for e in every_opening_error(&cut, None) {
        assert!(
            e.contains("is not a frontier results database (it has the tables meta, notes,"),
            "{e}"
        );
    }
    assert_eq!(
        std::fs::read(format!("{}-journal", cut.display())).unwrap(),
        journal
    );
}

/// Regression: a first run cut short while it made its store (an SQLite file with no table
/// yet, in WAL mode, perhaps with an empty `-wal` beside it) left a file every later run
/// refused as "not a frontier results database (it has no tables)", so an interrupted
/// Slurm shard failed at every resubmission. A database that holds nothing is made into a
/// store as a new file is; one a program set a version on is still refused (above).
#[test]
fn regression_a_store_cut_short_before_its_tables_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole.sqlite");
    run(ONE, &whole);
    for wal in [false, true] {
        let db = dir.path().join(format!("cut-{wal}.sqlite"));
        let conn = Connection::open(&db).unwrap();
        if wal {
            conn.query_row("PRAGMA journal_mode=WAL", [], |_| Ok(()))
                .unwrap();
        } else {
            conn.execute_batch("PRAGMA page_size = 4096; VACUUM;")
                .unwrap();
        }
        drop(conn);
        assert!(
            std::fs::metadata(&db).unwrap().len() > 0,
            "an SQLite header"
        );
        if wal {
            // What a process killed right after switching to WAL leaves beside the file.
            std::fs::write(format!("{}-wal", db.display()), [0u8; 0]).unwrap();
        }
        let summary = bench::runner::run(&plan(ONE), &db, &opts()).unwrap();
        assert_eq!((summary.ran, summary.already_done), (2, 0));
        // The same rows as a run into a new file, but for the wall-clock time.
        let rows = |p: &Path| {
            let mut rows = Store::open_read_only(p).unwrap().rows().unwrap();
            rows.iter_mut().for_each(|r| r.wall_s = 0.0);
            rows
        };
        assert_eq!(rows(&db), rows(&whole));
    }
}

/// Regression: a store path with a trailing separator (`notes.db/`) skipped every check of
/// an existing file (the file system found no file there) while SQLite opened the file and
/// added frontier's tables to another program's database. It is refused, unchanged.
#[test]
fn regression_a_store_path_ending_in_a_separator_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let notes = dir.path().join("notes.db");
    foreign_database(&notes, false);
    let good = dir.path().join("good.sqlite");
    run(ONE, &good);
    let before = snapshot(&notes);
    let slashed = PathBuf::from(format!("{}/", notes.display()));
    for (what, e) in [
        (
            "a run",
            bench::runner::run(&plan(ONE), &slashed, &opts()).map(drop),
        ),
        ("open_raw", Store::open_raw(&slashed).map(drop)),
        ("open_read_only", Store::open_read_only(&slashed).map(drop)),
        (
            "merge into it",
            Store::merge(&slashed, std::slice::from_ref(&good)).map(drop),
        ),
        (
            "merge of it",
            Store::merge(
                &dir.path().join("m.sqlite"),
                &[good.clone(), slashed.clone()],
            )
            .map(drop),
        ),
    ] {
        let e = e.expect_err(what).to_string();
        assert_eq!(
            e,
            format!(
                "{}: ends with a path separator, so it names a folder; expected a results \
                 database file (e.g. study.sqlite)",
                slashed.display()
            ),
            "{what}"
        );
        assert_eq!(snapshot(&notes), before, "{what}");
    }
    assert!(!dir.path().join("m.sqlite").exists());
}

/// Regression: a run into an existing store that its memory check refused had first
/// written the scenario's new environments and description into the store; it is checked
/// while the store is still read-only, and a refused run leaves the store as it was.
#[test]
fn regression_a_run_refused_for_its_memory_leaves_the_store_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("one.sqlite");
    run(ONE, &db);
    let before = snapshot(&db);
    let bigger = format!(
        "{}\n[[env]]\nkind = \"office\"\nseeds = [0]\nsize = [60, 60]\nresolution = 0.05\n",
        ONE.replace(
            "name = \"one\"",
            "name = \"one\"\ndescription = \"new text\""
        )
    );
    let plan = plan(&bigger);
    let e = bench::runner::run(
        &plan,
        &db,
        &RunOptions {
            memory_mb: Some(20),
            ..opts()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("more than --memory-mb 20"), "{e}");
    assert_eq!(snapshot(&db), before);
}
