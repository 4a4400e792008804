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

/// The error of resolving `text`.
fn error_of(text: &str) -> String {
    Plan::resolve(&source(text), Unbuilt::Error)
        .expect_err("bad scenario must fail")
        .to_string()
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

/// Regression: a file given as the report's folder (`bench report s.sqlite --out
/// s.sqlite`) was "s.sqlite: Not a directory (os error 20)".
#[test]
fn regression_report_into_a_file_says_a_folder_is_expected() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("s.sqlite");
    run(ONE, &db);
    let before = std::fs::read(&db).unwrap();
    let e = bench::report::write(&db, &db, &bench::report::ReportOptions::default())
        .expect_err("a file is no folder")
        .to_string();
    assert!(e.contains("is a file; expected the folder"), "{e}");
    assert_eq!(std::fs::read(&db).unwrap(), before);
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

/// Regression: `frontier bench /dev/zero --dry-run` read the "scenario" until memory ran
/// out. Directories, devices and files over the limit are refused before they are read.
#[test]
fn regression_scenario_device_or_huge_file_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let e = Source::read(dir.path()).unwrap_err().to_string();
    assert!(e.starts_with(&dir.path().display().to_string()), "{e}");
    assert!(
        e.contains("expected a scenario file") && e.contains("a directory"),
        "{e}"
    );
    #[cfg(unix)]
    {
        let e = Source::read(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("/dev/zero: expected a scenario file"), "{e}");
        assert!(e.contains("a device, pipe or socket"), "{e}");
    }
    let big = dir.path().join("big.toml");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(bench::scenario::MAX_SCENARIO_BYTES + 1).unwrap();
    let e = Source::read(&big).unwrap_err().to_string();
    assert!(e.starts_with(&big.display().to_string()), "{e}");
    assert!(
        e.contains("at most 16 MiB") && e.contains("found 16777217 bytes"),
        "{e}"
    );
    // A scenario of ordinary size still reads.
    let ok = dir.path().join("ok.toml");
    std::fs::write(&ok, ONE).unwrap();
    assert_eq!(Source::read(&ok).unwrap().text, ONE);
}

/// Regression: `count = 1000000000` generated environments until memory ran out before
/// the trial count was checked. The count is bounded before any environment is generated,
/// and so is the sum over several `[[env]]`s.
#[test]
fn regression_huge_env_count_is_refused_before_generating() {
    let e = error_of(&ONE.replace("size = [4, 4]", "count = 1000000000\nsize = [4, 4]"));
    assert!(e.starts_with("s.toml:8: key `env[0].count`"), "{e}");
    assert!(e.contains("expected at most 10000 environments"), "{e}");
    assert!(e.contains("found 1000000000"), "{e}");
    let two = format!(
        "{}\n[[env]]\nkind = \"maze\"\ncount = 6000\n",
        ONE.replace("size = [4, 4]", "count = 6000\nsize = [4, 4]")
    );
    let e = error_of(&two);
    assert!(e.starts_with("s.toml:14: key `env[1].count`"), "{e}");
    assert!(e.contains("12000 environments"), "{e}");
    // Environments within the bound whose trials are too many: refused by the trial count
    // before the environments are generated.
    let e = error_of(
        &ONE.replace("size = [4, 4]", "count = 10000\nsize = [4, 4]")
            .replace("name = \"one\"", "name = \"one\"\ntrials = 300"),
    );
    assert!(e.starts_with("s.toml:3: key `trials`"), "{e}");
    assert!(e.contains("the study has 3000000 trials"), "{e}");
}

/// Regression: `seeds = []` planned no environment and "0 trials", and the run succeeded
/// doing nothing, while `robots = []` was refused. Every list that must not be empty is
/// refused alike, naming its line.
#[test]
fn regression_empty_lists_are_refused() {
    let e = error_of(&ONE.replace("size = [4, 4]", "seeds = []\nsize = [4, 4]"));
    assert!(e.starts_with("s.toml:8: key `env[0].seeds`"), "{e}");
    assert!(e.contains("expected at least one environment seed"), "{e}");
    let e = error_of(&ONE.replace("[\"cf\"]", "[]"));
    assert!(e.starts_with("s.toml:3: key `strategies`"), "{e}");
    assert!(e.contains("expected at least one strategy"), "{e}");
    let e = error_of(&ONE.replace("[\"los:r=3c\"]", "[]"));
    assert!(e.starts_with("s.toml:4: key `sensors`"), "{e}");
    let e = error_of(&ONE.replace("sensors", "robots = []\nsensors"));
    assert!(e.starts_with("s.toml:4: key `robots`"), "{e}");
    // A sensor listed twice (in two spellings) would plan the same trials twice.
    let e = error_of(&ONE.replace("[\"los:r=3c\"]", "[\"los:r=5\", \"los:r=5.0\"]"));
    assert!(e.starts_with("s.toml:4: key `sensors[1]`"), "{e}");
    assert!(e.contains("listed twice"), "{e}");
}

/// Regression: the study's `name` made the default database path unchecked:
/// `name = "../../etc/x"` wrote `../../etc/x.sqlite`, `name = ""` a hidden `.sqlite`.
#[test]
fn regression_study_name_that_is_a_path_is_refused() {
    for bad in ["", "../../etc/x", "a/b", "a\\\\b", ".hidden", "tab\\there"] {
        let e = error_of(&ONE.replace("\"one\"", &format!("\"{bad}\"")));
        assert!(e.starts_with("s.toml:2: key `name`"), "{bad}: {e}");
        assert!(e.contains("expected a plain file name"), "{bad}: {e}");
    }
    for good in ["one", "faigl2013 rerun", "x.y"] {
        let text = ONE.replace("\"one\"", &format!("\"{good}\""));
        let plan = Plan::resolve(&source(&text), Unbuilt::Error).unwrap();
        assert_eq!(plan.name, good);
    }
}

/// Regression: a coverage strategy with a 1-cell sensor was planned, and each of its trials
/// ended at once with "no reachable frontier" (the cover looks within 0.8 of the range and
/// found no candidate). It is refused at plan time, naming the sensor, the environment and
/// the strategy; 1.25 cells is enough.
#[test]
fn regression_coverage_candidates_with_too_short_a_range_are_refused_at_plan_time() {
    let text = "strategies = [\"ha-rfe\", \"ha-cc\"]\nsensors = [\"los:r=2c\", \"los:r=1c\"]\n\n\
                [[env]]\nkind = \"office\"\nresolution = 0.5\n";
    let e = error_of(text);
    assert!(e.starts_with("s.toml:2: key `sensors[1]`"), "{e}");
    assert!(
        e.contains("office-s0-r0.5 with ha-cc") && e.contains("at least 1.25 cells"),
        "{e}"
    );
    let ok = text.replace("los:r=1c", "los:r=1.25c");
    Plan::resolve(&source(&ok), Unbuilt::Error).expect("1.25 cells");
}

/// Regression: a sonar on 0.5 m cells passed `--dry-run`, then every trial failed when it
/// ran (the sonar needs cells of at most 0.1 m). It is refused at plan time.
#[test]
fn regression_sonar_on_coarse_cells_is_refused_at_plan_time() {
    let text = "strategies = [\"cf\"]\nsensors = [\"los:r=3c\", \"sonar\"]\n\n\
                [[env]]\nkind = \"office\"\nresolution = 0.5\n";
    let e = error_of(text);
    assert!(e.starts_with("s.toml:2: key `sensors[1]`"), "{e}");
    assert!(e.contains("office-s0-r0.5"), "{e}");
    assert!(
        e.contains("at most 0.1 m") && e.contains("found 0.5 m"),
        "{e}"
    );
    assert!(e.contains("`resolution = 0.1`"), "{e}");
    // On fine enough cells it plans.
    let fine = text.replace(
        "kind = \"office\"\nresolution = 0.5",
        "kind = \"empty\"\nsize = [4, 4]\nresolution = 0.1",
    );
    Plan::resolve(&source(&fine), Unbuilt::Error).unwrap();
}

/// Regression: errors about keys that are absent printed line 0 ("s.toml:0: key
/// `sensors`"); they now leave the line out.
#[test]
fn regression_absent_keys_print_no_line_zero() {
    // The default sensor (los:r=5) is too long for 1 mm cells.
    let e = error_of(&ONE.replace("sensors = [\"los:r=3c\"]\n", "").replace(
        "size = [4, 4]\nresolution = 0.5",
        "size = [3, 3]\nresolution = 0.001",
    ));
    assert!(e.starts_with("s.toml: key `sensors`: los:r=5 on"), "{e}");
    let e = error_of(&ONE.replace("strategies = [\"cf\"]\n", ""));
    assert!(e.starts_with("s.toml: key `strategies`"), "{e}");
    let e = error_of("strategies = [\"cf\"]\n");
    assert!(e.starts_with("s.toml: key `env`"), "{e}");
    assert!(!e.contains(":0:"), "{e}");
}

/// Regression: `bench report` printed "222.5 ± NaN" for cells of one trial (the sample sd
/// of one value is undefined), in report.md and report.html; Holz's table printed
/// "± 0.0". They print the mean alone.
#[test]
fn regression_report_of_single_trials_prints_no_nan() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("h.sqlite");
    let text = ONE
        .replace("\"one\"", "\"holz2010-single\"")
        .replace("[\"cf\"]", "[\"cf\", \"random\"]");
    run(&text, &db);
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for (name, text) in [("report.md", &md), ("report.html", &html)] {
        assert!(!text.contains("NaN"), "{name}: {text}");
    }
    assert!(md.contains("Holz et al. 2010, Tables 1–3"), "{md}");
    // Our cells (the first after the strategy) hold a mean alone; the paper's keep their sd.
    let row = md
        .lines()
        .find(|l| l.starts_with("| cf | ") && l.contains("(×"))
        .unwrap_or_else(|| panic!("no Holz row for cf: {md}"));
    let ours = row.split(" | ").nth(1).unwrap();
    assert!(!ours.contains('±'), "{row}");
    assert!(
        row.contains("±"),
        "the paper's columns keep their sd: {row}"
    );
}

/// Regression: a scenario's `speed = 1e-308` was accepted and every trial's time was
/// infinite in the store and the CSV.
#[test]
fn regression_scenario_speed_near_zero_is_refused() {
    let e = error_of(&format!("speed = 1e-308\n{ONE}"));
    assert!(
        e.starts_with("s.toml:1: key `speed`: expected a positive number of metres per second, from 0.001 to 1000"),
        "{e}"
    );
}

/// Regression: a missing file's cause was printed twice by reporters that print the
/// error's chain ("x.toml: No such file ... : No such file ...").
#[test]
fn regression_io_error_cause_is_printed_once() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("x.toml");
    let e = Source::read(&missing).expect_err("missing file");
    let chain = chain(&e);
    assert_eq!(chain.matches("os error 2").count(), 1, "{chain}");
}

/// What `{:#}` of anyhow prints of `e`: the error, then each source after ": ".
fn chain(e: &dyn std::error::Error) -> String {
    let mut chain = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        chain += &format!(": {s}");
        source = s.source();
    }
    chain
}

/// Regression: a study store in a folder that does not exist, or a folder given as the
/// store, printed SQLite's "unable to open database file" three times ("x.sqlite: unable
/// to open database file: x.sqlite: unable to open database file: x.sqlite: Error code
/// 14: ...") and not why.
#[test]
fn regression_store_path_errors_say_why_once() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-folder").join("s.sqlite");
    let e = Store::open_raw(&missing).err().expect("no folder");
    let text = chain(&e);
    assert!(text.contains("no-such-folder does not exist"), "{text}");
    assert!(!text.contains("unable to open"), "{text}");
    let e = Store::open_raw(dir.path()).err().expect("a folder");
    let text = chain(&e);
    assert!(text.contains("is a folder"), "{text}");
    assert!(!text.contains("unable to open"), "{text}");
    // In a folder that exists, the store is made.
    let db = dir.path().join("s.sqlite");
    Store::open_raw(&db).expect("a new store");
}

/// Regression: generating an environment was not estimated first: `frontier env cave
/// --size 1000x1000` took 1.6 GB and minutes before anything was checked.
#[test]
fn regression_generation_memory_is_estimated_first() {
    let cave = world::EnvSpec {
        kind: world::EnvKind::Cave,
        seed: 0,
        size_m: Some((1000.0, 1000.0)),
        resolution: Some(0.1),
    };
    let e = bench::explore::check_generate_memory(&cave, Some(100)).expect_err("over 100 MB");
    assert!(e.contains("generating this cave of 100000000 cells"), "{e}");
    let office = world::EnvSpec::new(world::EnvKind::Office, 0);
    assert!(bench::explore::check_generate_memory(&office, Some(100)).is_ok());
}

/// Regression: an environment's name was barely checked. `name = ""` made trial keys
/// start with '|' and the report write `envs/.png`; `name = "a|b"` made keys ambiguous
/// (a strategy label with '|' was already refused); and "a/b" beside "a_b" wrote the same
/// report files (`envs/a_b.png`, its replay and plots), one over the other. Each is refused
/// at plan time, naming the key.
#[test]
fn regression_environment_names_that_break_keys_or_files_are_refused() {
    let named = |name: &str| {
        ONE.replace(
            "kind = \"empty\"",
            &format!("name = \"{name}\"\nkind = \"empty\""),
        )
    };
    // Regression too: a newline split the report's headings and table rows, and a name of
    // 300 characters ran its trials, then no report could be written ("File name too
    // long"). Written as TOML strings, then as the message quotes them.
    let long = "e".repeat(101);
    for (bad, found) in [
        ("", r#""""#.to_string()),
        ("a|b", r#""a|b""#.to_string()),
        (r"a\nb", r#""a\nb""#.to_string()),
        (long.as_str(), format!("{long:?}")),
    ] {
        let e = error_of(&named(bad));
        assert!(e.starts_with("s.toml:7: key `env[0].name`"), "{bad}: {e}");
        assert!(
            e.contains(&format!(
                "expected a non-empty name of at most 100 characters, without '|' or control \
                 characters, found {found}"
            )),
            "{bad}: {e}"
        );
    }
    Plan::resolve(&source(&named(&"e".repeat(100))), Unbuilt::Error)
        .expect("100 characters are a name");
    let label = format!(
        "{}\n[[strategy]]\npreset = \"cf\"\nlabel = \"a\\tb\"\n",
        ONE.replace("strategies = [\"cf\"]\n", "")
    );
    let e = error_of(&label);
    assert!(
        e.contains("key `strategy[0].label`") && e.contains(r#"found "a\tb""#),
        "{e}"
    );
    let two = format!(
        "{}\n[[env]]\nname = \"a_b\"\nkind = \"empty\"\nsize = [4, 4]\nresolution = 0.5\n",
        named("a/b")
    );
    let e = error_of(&two);
    assert!(e.starts_with("s.toml:13: key `env[1].name`"), "{e}");
    assert!(
        e.contains("'a_b' would write the report files of 'a/b'")
            && e.contains("'a_b' in file names"),
        "{e}"
    );
    let fine = two.replace("\"a_b\"", "\"a-b\"");
    Plan::resolve(&source(&fine), Unbuilt::Error).expect("a/b and a-b");
}

/// Regression: a clearance no robot has room for (`clearance = 1e300`, or one that leaves
/// fewer cells than the team) passed planning and every trial failed when it ran ("the map
/// has no free cell a robot with clearance ... can stand on"). It is refused at plan time
/// at the `clearance` key, naming the environment.
#[test]
fn regression_a_clearance_with_no_room_is_refused_at_plan_time() {
    let wide = ONE.replace("sensors", "clearance = 1e300\nsensors");
    let e = error_of(&wide);
    assert!(e.starts_with("s.toml:4: key `clearance`"), "{e}");
    assert!(e.contains("no free cell a robot with clearance"), "{e}");
    // 4 x 4 m of open space at 0.5 m with 1.2 m of clearance: room for one robot, not ten.
    let team = ONE.replace("sensors", "clearance = 1.2\nrobots = [10]\nsensors");
    let e = error_of(&team);
    assert!(
        e.contains("key `clearance`") && e.contains("10 robots need one each"),
        "{e}"
    );
    let one = ONE.replace("sensors", "clearance = 1.2\nsensors");
    Plan::resolve(&source(&one), Unbuilt::Error).expect("room for one");
}

/// Regression: an `[optimal]` cell size that leaves a map no free cell passed planning, and
/// every trial then ran and was thrown away ("the map coarsened by 2 has no free cell"),
/// its key printed twice in the failure. It is refused at plan time at `optimal.cell_size`.
#[test]
fn regression_an_optimal_cell_size_with_no_free_cell_is_refused_at_plan_time() {
    // An open 4 x 4 m room at 0.5 m: its 8 x 8 cells, walls around, coarsen by 2 to free
    // cells inside and by 8 to one cell that holds walls.
    let coarse = |k: u32| ONE.replace("[[env]]", &format!("[optimal]\ncell_size = {k}\n\n[[env]]"));
    let e = error_of(&coarse(8));
    assert!(e.starts_with("s.toml:7: key `optimal.cell_size`"), "{e}");
    assert!(
        e.contains("empty-s0-4x4m-r0.5: the map coarsened by 8 (4 m cells) has no free cell"),
        "{e}"
    );
    Plan::resolve(&source(&coarse(2)), Unbuilt::Error).expect("room at 1 m cells");
    // Only runs that get an optimal path are checked: a team's do not.
    let team = coarse(8).replace("sensors", "robots = [2]\nsensors");
    Plan::resolve(&source(&team), Unbuilt::Error).expect("no single-robot run");
}

/// Regression: a sensor whose range is no longer than the clearance passed planning, and
/// every trial stopped early with frontiers left: it is refused at the sensor's key.
#[test]
fn regression_a_range_within_the_clearance_is_refused_at_plan_time() {
    // One cell of range at 0.5 m: 0.5 m.
    let short = ONE.replace("los:r=3c", "los:r=1c");
    let e = error_of(&short.replace("sensors", "clearance = 0.5\nsensors"));
    assert!(e.starts_with("s.toml:5: key `sensors[0]`"), "{e}");
    assert!(e.contains("expected a range beyond the clearance"), "{e}");
    let fine = short.replace("sensors", "clearance = 0.4\nsensors");
    Plan::resolve(&source(&fine), Unbuilt::Error).expect("0.5 m of range beyond 0.4 m");
}

/// Regression: three scenario errors did not say what they found: a file with a byte that
/// is not UTF-8 ("stream did not contain valid UTF-8", without where), `robots = [1001]`
/// ("at most 1000 robots") and `start = [1, 1, 1]` ("expected a cell [x, y]").
#[test]
fn regression_scenario_errors_say_what_they_found() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(&path, b"name = \"one\"\nseed = 1 # caf\xe9\n").unwrap();
    let e = Source::read(&path).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "expected a scenario file of UTF-8 text (TOML), found a byte that is not UTF-8 at \
             line 2, column 15 (byte 27)"
        ),
        "{e}"
    );
    let e = error_of(&ONE.replace("name = \"one\"", "name = \"one\"\nrobots = [1001]"));
    assert!(
        e.contains("key `robots[0]`") && e.contains("expected at most 1000 robots, found 1001"),
        "{e}"
    );
    let e = error_of(&ONE.replace("kind = \"empty\"", "kind = \"empty\"\nstart = [1, 1, 1]"));
    assert!(
        e.contains("key `env[0].start`") && e.contains("found [1, 1, 1]"),
        "{e}"
    );
}

/// Regression: a study's trials and their keys were made before any memory check: 2 M
/// trials with names of 100 characters took 1.5 GiB under `--memory-mb 40` before the
/// trials' own check refused them. Their memory is estimated from the counts first.
#[test]
fn planning_many_trials_is_checked_before_they_are_made() {
    let text = ONE
        .replace("sensors =", "trials = 200000\nsensors =")
        .replace("strategies = [\"cf\"]", "strategies = [\"random\"]");
    let src = source(&text);
    let e = Plan::resolve_within(&src, Unbuilt::Error, Some(20))
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("key `trials`: planning the study's 200000 trials needs about")
            && e.contains("more than --memory-mb 20"),
        "{e}"
    );
    assert!(Plan::resolve_within(&src, Unbuilt::Error, Some(1000)).is_ok());
}
