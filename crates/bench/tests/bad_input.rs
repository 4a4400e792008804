//! Regressions of the harness on bad input — scenario files, output paths — and of what
//! its reports print. Each refusal names the file (and the line and key) and what was
//! expected, and comes before anything is read, generated or written.

use std::path::Path;

use bench::{Plan, RunOptions, Source, Store, Unbuilt};

/// A study of one trial on a tiny empty room.
const ONE: &str = r#"
name = "one"
strategies = ["cf"]
sensors = ["los:r=3c"]

[[env]]
kind = "empty"
size = [4, 4]
resolution = 0.5
"#;

fn source(text: &str) -> Source {
    Source {
        file: "s.toml".into(),
        text: text.into(),
        dir: None,
    }
}

/// Run `text` into `db`.
fn run(text: &str, db: &Path) {
    let plan = Plan::resolve(&source(text), Unbuilt::Error).expect("scenario resolves");
    let opts = RunOptions {
        threads: Some(1),
        ..RunOptions::default()
    };
    let summary = bench::runner::run(&plan, db, &opts).expect("run");
    assert!(summary.failed.is_empty(), "{:?}", summary.failed);
}

/// Regression: `frontier bench export --csv ok.sqlite ok.sqlite` overwrote the results
/// database with CSV. Every spelling of the database (the path itself, through `..`, a
/// symbolic or a hard link) is refused before anything is written.
#[test]
fn regression_export_onto_its_own_database_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("ok.sqlite");
    run(ONE, &db);
    let before = std::fs::read(&db).unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let mut spellings = vec![
        db.clone(),
        dir.path().join("sub").join("..").join("ok.sqlite"),
    ];
    #[cfg(unix)]
    {
        let link = dir.path().join("link.csv");
        std::os::unix::fs::symlink(&db, &link).unwrap();
        spellings.push(link);
    }
    let hard = dir.path().join("hard.csv");
    std::fs::hard_link(&db, &hard).unwrap();
    spellings.push(hard);
    let store = Store::open_read_only(&db).unwrap();
    for csv in &spellings {
        let e = store
            .export_csv(csv)
            .expect_err("exporting onto the database must fail")
            .to_string();
        assert!(e.starts_with(&csv.display().to_string()), "{e}");
        assert!(e.contains("is the results database being read"), "{e}");
        assert!(e.contains("expected another output path"), "{e}");
    }
    drop(store);
    assert_eq!(
        std::fs::read(&db).unwrap(),
        before,
        "the database is unchanged"
    );
    // A CSV file that does not exist yet, beside it, is written as before.
    let csv = dir.path().join("new.csv");
    let n = Store::open_read_only(&db)
        .unwrap()
        .export_csv(&csv)
        .unwrap();
    assert_eq!(n, 1);
    assert!(std::fs::read_to_string(&csv).unwrap().starts_with("key,"));
}

/// Regression: a database named like a file the report writes (`report.html` in the
/// `--out` directory) was overwritten by the report. It is refused before any file of the
/// report is written.
#[test]
fn regression_report_onto_its_own_database_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    std::fs::create_dir(&out).unwrap();
    for name in ["report.html", "report.md"] {
        let db = out.join(name);
        run(ONE, &db);
        let before = std::fs::read(&db).unwrap();
        let e = bench::report::write(&db, &out, &bench::report::ReportOptions::default())
            .expect_err("a report onto its database must fail")
            .to_string();
        assert!(e.contains("is the results database being read"), "{e}");
        assert_eq!(std::fs::read(&db).unwrap(), before, "{name} is unchanged");
        for written in ["report.md", "report.html"] {
            assert!(
                written == name || !out.join(written).exists(),
                "{written} was written"
            );
        }
        std::fs::remove_file(&db).unwrap();
    }
}

/// Merging into one of the inputs destroys nothing: inputs are read only, the output keeps
/// its trials and gains the others'.
#[test]
fn merge_into_one_of_its_inputs_keeps_every_trial() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.sqlite");
    let b = dir.path().join("b.sqlite");
    run(ONE, &a);
    run(&ONE.replace("[\"cf\"]", "[\"cf\", \"random\"]"), &b);
    let merged = Store::merge(&a, &[a.clone(), b.clone()]).unwrap();
    assert_eq!((merged.added, merged.total), (1, 2));
    assert_eq!(Store::open_read_only(&a).unwrap().count().unwrap(), 2);
}
