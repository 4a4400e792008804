//! The harness end to end on tiny studies: thread-count independence, resumption, shards
//! and merge, CSV export, and scenario errors naming file, line and key.

use std::path::Path;

use bench::{Plan, RunOptions, Shard, Source, Store, TrialRow, Unbuilt};

const TINY: &str = r#"
name = "tiny"
seed = 7
robots = [1, 2]
sensors = ["los:r=3c"]
strategies = ["cf", "random"]
trials = 2

[[env]]
kind = "maze"
seeds = [0]
size = [6, 5]
resolution = 0.5

[[env]]
kind = "office"
seeds = [1]
size = [10, 10]
resolution = 0.5
start = [3, 3]
"#;

fn source(text: &str) -> Source {
    Source {
        file: "tiny.toml".into(),
        text: text.into(),
        dir: None,
    }
}

fn plan() -> Plan {
    Plan::resolve(&source(TINY), Unbuilt::Error).expect("tiny scenario resolves")
}

/// Rows without the wall times, which are the only non-deterministic column.
fn rows(db: &Path) -> Vec<TrialRow> {
    let store = Store::open_read_only(db).expect("open");
    store
        .rows()
        .expect("rows")
        .into_iter()
        .map(|mut r| {
            r.wall_s = 0.0;
            r
        })
        .collect()
}

fn opts(threads: usize) -> RunOptions {
    RunOptions {
        threads: Some(threads),
        ..RunOptions::default()
    }
}

#[test]
fn plan_lists_trials_with_stable_keys_and_seeds() {
    let p = plan();
    // maze: random start per trial -> every strategy 2 trials; office: fixed start ->
    // cf (deterministic) 1 trial, random 2 trials; times 2 robot counts.
    assert_eq!(p.trials.len(), 2 * 2 * 2 + (1 + 2) * 2);
    let again = plan();
    assert_eq!(p.trials, again.trials);
    let t = &p.trials[0];
    assert_eq!(t.key, "maze-s0-6x5m-r0.5|cf|los:r=3c|m=1|start=0|trial=0");
    assert_eq!(
        t.seed,
        sim::seed::derive(7, "maze-s0-6x5m-r0.5|start=0|trial=0")
    );
    // Common random numbers: the same start and trial give the same seed for every strategy.
    let same: Vec<u64> = p
        .trials
        .iter()
        .filter(|t| t.env == 0 && t.start_variant == 0 && t.trial == 1)
        .map(|t| t.seed)
        .collect();
    assert!(same.len() == 4 && same.iter().all(|&s| s == same[0]));
}

/// `trials_for` repeats only the strategies it names (here none): the others run once per
/// fixed start, with the seeds and keys they have in the plan without it.
#[test]
fn trials_for_repeats_only_the_strategies_it_names() {
    let text = TINY.replace("trials = 2\n", "trials = 2\ntrials_for = []\n");
    let narrow = Plan::resolve(&source(&text), Unbuilt::Error).expect("resolves");
    // maze: random starts repeat every strategy (2 trials); office: fixed start, so `cf`
    // (deterministic) and `random` (not named) run once; times 2 robot counts.
    assert_eq!(narrow.trials.len(), 2 * 2 * 2 + (1 + 1) * 2);
    let all = plan();
    for t in &narrow.trials {
        // The same trial, but for its place in the list (`number`).
        let same = |a: &&bench::Trial| {
            (&a.key, a.env, a.variant, a.start_variant, a.trial, a.seed)
                == (&t.key, t.env, t.variant, t.start_variant, t.trial, t.seed)
        };
        assert!(
            all.trials.iter().any(|a| same(&a)),
            "{} not in the full plan",
            t.key
        );
    }
    let random_office = |p: &Plan| {
        p.trials
            .iter()
            .filter(|t| t.env == 1 && t.key.contains("|random|"))
            .count()
    };
    assert_eq!((random_office(&narrow), random_office(&all)), (2, 4));
    let e = error_of((
        "trials = 2",
        "trials = 2\ntrials_for = [\"random\", \"nope\"]",
    ));
    assert!(e.starts_with("tiny.toml:8: key `trials_for[1]`"), "{e}");
    assert!(
        e.contains("expected one of the study's strategies (cf, random), found 'nope'"),
        "{e}"
    );
    // Regression: naming a deterministic strategy was accepted and did nothing (it runs
    // once at a fixed start whatever the list says), so `trials` seemed ignored.
    let e = error_of(("trials = 2", "trials = 2\ntrials_for = [\"cf\"]"));
    assert!(e.starts_with("tiny.toml:8: key `trials_for[0]`"), "{e}");
    assert!(
        e.contains(
            "expected a strategy that draws random numbers (random), found 'cf', which is \
             deterministic"
        ),
        "{e}"
    );
}

/// Faigl & Kulich's protocol: 20 start perturbations of each problem, and 20 trials of
/// each only for the stochastic assignment methods GA and MA (§V): 5 such presets × 36
/// problems × 400 runs, and 7 others × 36 × 20, 77,040 trials.
#[test]
fn faigl2013_repeats_only_the_stochastic_assignment_methods() {
    let p = bench::suites::plan("faigl2013").expect("the suite resolves");
    assert_eq!(p.trials.len(), 5 * 36 * 400 + 7 * 36 * 20);
    for v in &p.variants {
        let repeated = v.label.starts_with("ga-") || v.label.starts_with("ma-");
        assert_eq!(v.repeated, repeated, "{}", v.label);
    }
}

#[test]
fn one_and_two_threads_give_identical_databases() {
    let dir = tempfile::tempdir().unwrap();
    let p = plan();
    let (a, b) = (dir.path().join("a.sqlite"), dir.path().join("b.sqlite"));
    let sa = bench::runner::run(&p, &a, &opts(1)).unwrap();
    let sb = bench::runner::run(&p, &b, &opts(2)).unwrap();
    assert!(sa.failed.is_empty(), "{:?}", sa.failed);
    assert_eq!((sa.ran, sb.ran), (p.trials.len(), p.trials.len()));
    let (ra, rb) = (rows(&a), rows(&b));
    assert_eq!(ra.len(), p.trials.len());
    assert_eq!(ra, rb);
    // Every robot count and both strategies explored something.
    assert!(ra.iter().all(|r| r.coverage > 0.0 && r.max_path > 0.0));
    // A second run resumes: nothing left to do.
    let again = bench::runner::run(&p, &a, &opts(2)).unwrap();
    assert_eq!((again.ran, again.already_done), (0, p.trials.len()));
}

/// Regression: two runs of one study started together into one new database: one of them
/// could fail at once with "database is locked" (switching the new file to WAL mode is
/// answered busy without waiting), and each counted as run now every trial it ran, also
/// those the other had stored first. Every trial is stored once, and counted once as new.
#[test]
fn regression_two_runs_into_one_new_database_count_each_trial_once() {
    for round in 0..4 {
        let dir = tempfile::tempdir().unwrap();
        let p = plan();
        let db = dir.path().join("shared.sqlite");
        let barrier = std::sync::Barrier::new(2);
        let (a, b) = std::thread::scope(|s| {
            let run = || {
                barrier.wait();
                bench::runner::run(&p, &db, &opts(1))
            };
            let a = s.spawn(run);
            let b = s.spawn(run);
            (a.join().unwrap(), b.join().unwrap())
        });
        let (a, b) = (a.unwrap(), b.unwrap());
        let n = p.trials.len();
        assert_eq!(a.ran + b.ran, n, "round {round}: each trial new once");
        for s in [&a, &b] {
            assert_eq!(
                s.already_done + s.ran + s.stored_meanwhile,
                n,
                "round {round}: every trial done before, run now or stored by the other"
            );
        }
        assert_eq!(rows(&db).len(), n);
    }
}

#[test]
fn resuming_an_interrupted_run_gives_the_uninterrupted_results() {
    let dir = tempfile::tempdir().unwrap();
    let p = plan();
    let (whole, parts) = (dir.path().join("w.sqlite"), dir.path().join("p.sqlite"));
    bench::runner::run(&p, &whole, &opts(2)).unwrap();
    let first = bench::runner::run(
        &p,
        &parts,
        &RunOptions {
            limit: Some(5),
            ..opts(2)
        },
    )
    .unwrap();
    assert_eq!(first.ran, 5);
    let rest = bench::runner::run(&p, &parts, &opts(1)).unwrap();
    assert_eq!((rest.already_done, rest.ran), (5, p.trials.len() - 5));
    assert_eq!(rows(&whole), rows(&parts));
}

#[test]
fn merged_shards_equal_the_unsharded_run() {
    let dir = tempfile::tempdir().unwrap();
    let p = plan();
    let whole = dir.path().join("w.sqlite");
    bench::runner::run(&p, &whole, &opts(2)).unwrap();
    let mut shards = Vec::new();
    let mut total = 0;
    for i in 1..=3 {
        let db = dir.path().join(format!("s{i}.sqlite"));
        let s = bench::runner::run(
            &p,
            &db,
            &RunOptions {
                shard: Some(Shard { index: i, count: 3 }),
                ..opts(1)
            },
        )
        .unwrap();
        total += s.ran;
        shards.push(db);
    }
    assert_eq!(total, p.trials.len());
    let merged = dir.path().join("m.sqlite");
    let n = p.trials.len();
    let all = bench::Merged { added: n, total: n };
    assert_eq!(Store::merge(&merged, &shards).unwrap(), all);
    assert_eq!(
        Store::merge(&merged, &shards).unwrap(),
        bench::Merged { added: 0, ..all },
        "merging twice adds nothing"
    );
    let out = Store::open_read_only(&merged).unwrap();
    assert_eq!(out.envs().unwrap().len(), 2);
    drop(out);
    assert_eq!(rows(&whole), rows(&merged));
    // CSV: a header and one line per trial.
    let csv = dir.path().join("t.csv");
    let n = Store::open_read_only(&merged)
        .unwrap()
        .export_csv(&csv)
        .unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(n, p.trials.len());
    assert_eq!(text.lines().count(), n + 1);
    assert!(text.starts_with("key,scenario,env,env_kind,env_seed,"));
    // Regression: a store with no trial (an empty shard) was exported as an empty file,
    // which CSV readers refuse; it is the same header with no row.
    let empty = dir.path().join("empty.sqlite");
    bench::runner::run(
        &p,
        &empty,
        &RunOptions {
            limit: Some(0),
            ..opts(1)
        },
    )
    .unwrap();
    let none = dir.path().join("none.csv");
    let store = Store::open_read_only(&empty).unwrap();
    assert_eq!(store.count().unwrap(), 0);
    assert_eq!(store.export_csv(&none).unwrap(), 0);
    let header = std::fs::read_to_string(&none).unwrap();
    assert_eq!(
        header.lines().collect::<Vec<_>>(),
        [text.lines().next().unwrap()]
    );
}

#[test]
fn a_database_of_other_settings_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let p = plan();
    bench::runner::run(
        &p,
        &db,
        &RunOptions {
            limit: Some(1),
            ..opts(1)
        },
    )
    .unwrap();
    let other = Plan::resolve(
        &source(&TINY.replace("seed = 7", "seed = 8")),
        Unbuilt::Error,
    )
    .unwrap();
    let err = bench::runner::run(&other, &db, &opts(1))
        .unwrap_err()
        .to_string();
    assert!(err.contains("fingerprint"), "{err}");
}

#[test]
fn shard_syntax() {
    assert_eq!("2/8".parse::<Shard>(), Ok(Shard { index: 2, count: 8 }));
    for bad in ["0/3", "4/3", "x/3", "3", "1/0"] {
        assert!(bad.parse::<Shard>().is_err(), "{bad}");
    }
}

/// Regression: `--dry-run --shard 2/2` reported the whole plan's trial count. A shard's
/// share is the number of trials the runner takes for it, with `--trials` too.
#[test]
fn regression_shard_share_is_the_trials_the_shard_runs() {
    let dir = tempfile::tempdir().unwrap();
    for first in [None, Some(1)] {
        let mut p = plan();
        if let Some(n) = first {
            p.first_trials(n);
        }
        for count in 1..6 {
            let mut sum = 0;
            for index in 1..=count {
                let s = Shard { index, count };
                let db = dir
                    .path()
                    .join(format!("{first:?}-{s}.sqlite").replace('/', "of"));
                let shard = Some(s);
                let ran = bench::runner::run(&p, &db, &RunOptions { shard, ..opts(1) })
                    .unwrap()
                    .ran;
                assert_eq!(s.share(&p.trials), ran, "{s} of {}", p.trials.len());
                sum += ran;
            }
            assert_eq!(sum, p.trials.len());
        }
    }
}

/// Regression: a shard was picked by a trial's place in the list `--trials` had left, so
/// `--trials 1 --shard I/N` ran trials of other shards, which the shard's later runs into
/// the same store did not find done (and ran again, as other shards did). The first trials
/// of a shard are now a part of it.
#[test]
fn regression_the_first_trials_of_a_shard_are_a_part_of_it() {
    let dir = tempfile::tempdir().unwrap();
    let whole = plan();
    let mut first = plan();
    first.first_trials(1);
    assert!(first.trials.len() < whole.trials.len());
    for index in 1..=3 {
        let shard = Some(Shard { index, count: 3 });
        let db = dir.path().join(format!("s{index}.sqlite"));
        let early = bench::runner::run(&first, &db, &RunOptions { shard, ..opts(1) }).unwrap();
        let later = bench::runner::run(&whole, &db, &RunOptions { shard, ..opts(1) }).unwrap();
        assert_eq!(later.already_done, early.ran, "shard {index}/3");
        assert_eq!(later.total, early.ran + later.ran);
        let keys: std::collections::BTreeSet<String> =
            rows(&db).into_iter().map(|r| r.key).collect();
        let mine: std::collections::BTreeSet<String> = whole
            .trials
            .iter()
            .filter(|t| t.number % 3 == index - 1)
            .map(|t| t.key.clone())
            .collect();
        assert_eq!(keys, mine, "shard {index}/3 holds its own trials only");
    }
}

/// Regression: shards dealt out the study's trials in its order, where the first trials of
/// the repeated strategies' starts lie 20 apart, so `--trials 1 --shard I/1000` of
/// faigl2013 ran 78 trials in one shard and 5 in another. Every shard now gets an even
/// share of the first trials, and of the whole study.
#[test]
fn regression_the_first_trials_spread_evenly_over_the_shards() {
    let whole = bench::suites::plan("faigl2013").expect("faigl2013 resolves");
    let mut first = bench::suites::plan("faigl2013").expect("faigl2013 resolves");
    first.first_trials(1);
    for count in [7, 32, 1000] {
        for p in [&whole, &first] {
            let shares: Vec<usize> = (1..=count)
                .map(|index| Shard { index, count }.share(&p.trials))
                .collect();
            let (lo, hi) = (shares.iter().min().unwrap(), shares.iter().max().unwrap());
            assert!(
                hi - lo <= 1,
                "{count} shards of {} trials: {lo}..{hi}",
                p.trials.len()
            );
            assert_eq!(shares.iter().sum::<usize>(), p.trials.len());
        }
    }
    let mut numbers: Vec<usize> = whole.trials.iter().map(|t| t.number).collect();
    numbers.sort_unstable();
    assert!(
        numbers.iter().enumerate().all(|(i, &n)| i == n),
        "numbers are a permutation"
    );
}

/// The error of resolving `text` with `line` replaced by `with`.
fn error_of(edit: (&str, &str)) -> String {
    assert!(TINY.contains(edit.0), "{}", edit.0);
    let text = TINY.replacen(edit.0, edit.1, 1);
    Plan::resolve(&source(&text), Unbuilt::Error)
        .expect_err("bad scenario must fail")
        .to_string()
}

#[test]
fn bad_scenarios_name_file_line_and_key() {
    let cases = [
        (
            (
                "strategies = [\"cf\", \"random\"]",
                "strategies = [\"cf\", \"nope\"]",
            ),
            "tiny.toml:6: key `strategies[1]`",
            "unknown strategy 'nope'",
        ),
        (
            ("sensors = [\"los:r=3c\"]", "sensors = [\"radar:r=3\"]"),
            "tiny.toml:5: key `sensors[0]`",
            "radar",
        ),
        (
            ("robots = [1, 2]", "robots = [1, 0]"),
            "tiny.toml:4: key `robots[1]`",
            ">= 1",
        ),
        (
            ("kind = \"maze\"", "kind = \"castle\""),
            "tiny.toml:10: key `env[0].kind`",
            "castle",
        ),
        (
            ("trials = 2", "trials = 0"),
            "tiny.toml:7: key `trials`",
            ">= 1",
        ),
        (
            ("start = [3, 3]", "start = [0, 0]"),
            "tiny.toml:20: key `env[1].start`",
            "occupied",
        ),
        (
            ("size = [6, 5]", "size = [6]"),
            "tiny.toml:12: key `env[0].size`",
            "[width, height]",
        ),
        (
            ("kind = \"maze\"", "map = \"no/such/map.yaml\""),
            "tiny.toml:11: key `env[0].seeds`",
            "not to map files",
        ),
    ];
    for ((from, to), place, what) in cases {
        let e = error_of((from, to));
        assert!(e.starts_with(place), "{to}: {e}");
        assert!(e.contains(what), "{to}: {e}");
    }
    // Unknown keys and wrong types: toml's message names line and key.
    let e = error_of(("trials = 2", "trails = 2"));
    assert!(
        e.starts_with("tiny.toml: ") && e.contains("line 7") && e.contains("trails"),
        "{e}"
    );
    let e = error_of(("resolution = 0.5\n\n[[env]]", "resolutoin = 0.5\n\n[[env]]"));
    assert!(e.contains("line 13") && e.contains("resolutoin"), "{e}");
    let e = error_of(("trials = 2", "trials = \"two\""));
    assert!(e.contains("line 7") && e.contains("trials"), "{e}");
}

/// Regression: scenario errors blamed a key the file did not set or that was not at fault:
/// a team too large for a drawn start blamed `clearance`, too many perturbations blamed
/// `env[0].start`, a repeated seed `env[0].name`, and a bitmap without a resolution named
/// the CLI's `--resolution`.
#[test]
fn regression_scenario_errors_blame_the_key_at_fault() {
    let cases = [
        (
            ("robots = [1, 2]", "robots = [1, 1000]"),
            "tiny.toml:4: key `robots`",
            "1000 robots need one each",
        ),
        (
            ("trials = 2", "trials = 2\nperturbations = 500\nradius = 1"),
            "tiny.toml:8: key `perturbations`",
            "500 perturbations of the start within 1 m",
        ),
        (
            ("seeds = [0]", "seeds = [0, 3, 0]"),
            "tiny.toml:11: key `env[0].seeds[2]`",
            "expected distinct seeds, found 0 again (also seeds[0])",
        ),
    ];
    for ((from, to), place, what) in cases {
        let e = error_of((from, to));
        assert!(e.starts_with(place), "{to}: {e}");
        assert!(e.contains(what), "{to}: {e}");
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("plan.pgm"), b"P5\n2 2\n255\n\0\0\0\0").unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "strategies = [\"cf\"]\n[[env]]\nmap = \"plan.pgm\"\n",
    )
    .unwrap();
    let src = Source::read(&path).unwrap();
    let e = Plan::resolve(&src, Unbuilt::Error).unwrap_err().to_string();
    assert!(e.contains("s.toml:3: key `env[0].resolution`"), "{e}");
    assert!(
        e.ends_with("plan.pgm: `resolution` is required for a bare bitmap"),
        "{e}"
    );
}

#[test]
fn unreadable_map_file_names_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(
        &path,
        "strategies = [\"cf\"]\n[[env]]\nmap = \"missing.pgm\"\nresolution = 0.1\n",
    )
    .unwrap();
    let src = Source::read(&path).unwrap();
    let e = Plan::resolve(&src, Unbuilt::Error).unwrap_err().to_string();
    assert!(e.contains("s.toml:3: key `env[0].map`"), "{e}");
    assert!(e.contains("missing.pgm"), "{e}");
}

#[test]
fn report_is_written_and_self_contained() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    bench::runner::run(&plan(), &db, &opts(2)).unwrap();
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(md.contains("| strategy | n |"), "{md}");
    assert!(md.contains("+/=/- of L"));
    assert!(md.contains("time vs robots"));
    assert!(out.join("envs").join("maze-s0-6x5m-r0.5.png").exists());
    // Charts inline as SVG with text elements (no font files), pictures as data URIs,
    // and nothing fetched from the network.
    assert!(html.contains("<svg") && html.contains("<text"));
    assert!(html.contains("data:image/png;base64,"));
    assert!(!html.contains("src=\"http") && !html.contains("href=\"http"));
}

#[test]
fn suites_resolve() {
    for (name, _, _) in bench::suites::SUITES {
        if *name == "faigl2013" {
            continue; // resolved by `faigl2013_repeats_only_the_stochastic_assignment_methods`
        }
        if bench::suites::MAP_FOLDER_SUITES.contains(name) {
            let e = bench::suites::plan(name).unwrap_err().to_string();
            assert!(e.contains("--maps"), "{e}");
            continue;
        }
        let p = bench::suites::plan(name).unwrap();
        assert!(!p.trials.is_empty(), "{name}");
    }
}

#[test]
fn report_links_each_environment_to_a_replay_of_one_of_its_runs() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let plan = plan();
    bench::runner::run(&plan, &db, &opts(2)).unwrap();
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let store = Store::open_raw(&db).unwrap();
    let pictures = store.envs().unwrap();
    let all = store.rows().unwrap();
    assert_eq!(pictures.len(), plan.envs.len());
    for env in &plan.envs {
        let name = &env.name;
        let page = out.join("replays").join(format!("{name}.html"));
        let text = std::fs::read_to_string(&page).unwrap();
        assert!(text.contains("<script") && !text.contains("src=\"http"));
        assert!(
            md.contains(&format!(
                "[![{name}](envs/{name}.png)](replays/{name}.html)"
            )),
            "{md}"
        );
        assert!(html.contains(&format!("<a href=\"replays/{name}.html\"")));
        // The picture gives back the ground truth, and the re-run is the stored trial.
        let pic = pictures.iter().find(|p| &p.name == name).unwrap();
        let truth = bench::replays::truth_from_picture(pic).unwrap();
        assert!(truth.cells == env.map.cells, "{name}: truth from picture");
        let row = bench::replays::representative(&all, name).unwrap();
        assert_eq!(row.strategy, "cf");
        assert_eq!((row.start_variant, row.trial, row.robots), (0, 0, 1));
        let result = sim::run(&truth, &bench::replays::config_of(row).unwrap()).unwrap();
        assert!(result.trace.is_some());
        let stored: Vec<f64> = serde_json::from_str(&row.path_lengths).unwrap();
        let lengths: Vec<f64> = result.path_length_m.clone();
        assert_eq!(lengths.len(), stored.len());
        for (a, b) in lengths.iter().zip(&stored) {
            assert!((a - b).abs() < 1e-6, "{name}: {a} vs stored {b}");
        }
    }
}

/// Regression: a scenario's `description`, "free text shown in reports", was read and then
/// dropped: neither the store nor the report held it. It is kept in the store, carried by a
/// merge of its shards, and printed under the report's title.
#[test]
fn regression_a_scenario_description_reaches_its_report() {
    let dir = tempfile::tempdir().unwrap();
    let text = TINY.replace(
        "seed = 7\n",
        "seed = 7\ndescription = \"Mazes & offices <small>\"\n",
    );
    let plan = Plan::resolve(&source(&text), Unbuilt::Error).unwrap();
    let shard = dir.path().join("s.sqlite");
    let one_of_two = RunOptions {
        shard: Some(Shard { index: 1, count: 2 }),
        ..opts(1)
    };
    bench::runner::run(&plan, &shard, &one_of_two).unwrap();
    let merged = dir.path().join("m.sqlite");
    Store::merge(&merged, &[shard]).unwrap();
    let out = dir.path().join("report");
    bench::report::write(&merged, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        md.starts_with("# Benchmark report: tiny\n\nMazes & offices <small>\n"),
        "{md}"
    );
    assert!(
        html.contains("<p>Mazes &amp; offices &lt;small&gt;</p>"),
        "{html}"
    );
}

/// Regression: a finished study run again with its scenario's `description` edited, for
/// its report, kept the store read-only, so the report printed the old text.
#[test]
fn regression_an_edited_description_reaches_a_finished_studys_report() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let with = |words: &str| {
        let text = TINY.replace(
            "seed = 7\n",
            &format!("seed = 7\ndescription = \"{words}\"\n"),
        );
        Plan::resolve(&source(&text), Unbuilt::Error).unwrap()
    };
    bench::runner::run(&with("First words"), &db, &opts(1)).unwrap();
    let again = bench::runner::run(&with("Second words"), &db, &opts(1)).unwrap();
    assert_eq!(again.ran, 0, "nothing left to run");
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.starts_with("# Benchmark report: tiny\n\nSecond words\n"),
        "{md}"
    );
}

/// Regression: a sonar trial's row named the scenario's belief (`known`) though the run
/// built the evidence grid, and the report's replay re-ran it with `known`, which a sonar
/// refuses, so `--report` failed after every trial had run.
#[test]
fn regression_sonar_rows_name_the_evidence_grid_they_built() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let text = r#"
name = "sonar"
sensors = ["sonar", "los:r=3c"]
strategies = ["yamauchi"]
[[env]]
kind = "empty"
size = [5, 5]
resolution = 0.1
start = [20, 20]
"#;
    let plan = Plan::resolve(&source(text), Unbuilt::Error).unwrap();
    bench::runner::run(&plan, &db, &opts(1)).unwrap();
    let beliefs: Vec<(String, String)> = rows(&db)
        .into_iter()
        .map(|r| (r.sensor, r.belief))
        .collect();
    assert_eq!(beliefs.len(), 2, "{beliefs:?}");
    for (sensor, belief) in &beliefs {
        let want = if sensor.starts_with("sonar") {
            "evidence"
        } else {
            "known"
        };
        assert_eq!(belief, want, "{sensor}");
    }
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    // A store written before the fix holds `known` for the sonar trial: its replay still runs.
    let mut old = rows(&db)
        .into_iter()
        .find(|r| r.sensor.starts_with("sonar"))
        .unwrap();
    old.belief = "known".into();
    let cfg = bench::replays::config_of(&old).unwrap();
    assert_eq!(cfg.belief, sense::BeliefKind::Evidence);
}

/// Regression: `trials = 1_000_000_000` planned (and held) a billion trials before anything
/// ran, until memory ran out. The count is checked before a trial is built.
#[test]
fn huge_trials_scenario_is_refused_before_planning() {
    let e = error_of(("trials = 2", "trials = 1000000000"));
    assert!(e.contains("tiny.toml:7: key `trials`"), "{e}");
    assert!(e.contains("expected at most 2000000"), "{e}");
}

/// Regression: `perturbations` above 2^32 wrapped to a small count, and a huge count drew
/// start variants for minutes before the trial count was checked.
#[test]
fn huge_perturbations_are_refused_before_drawing() {
    for n in ["4294967297", "50000000"] {
        let e = error_of((
            "trials = 2",
            &format!("trials = 2\nperturbations = {n}\nradius = 1.0"),
        ));
        assert!(e.contains("key `perturbations`"), "{e}");
        assert!(e.contains(&format!("found {n}")), "{e}");
    }
}

/// More start variants than reachable cells within the radius can only repeat cells: the
/// scenario is refused, naming the count that fits.
#[test]
fn more_perturbations_than_cells_is_refused() {
    let e = error_of((
        "trials = 2",
        "trials = 2\nperturbations = 500\nradius = 0.5",
    ));
    assert!(e.contains("500 perturbations"), "{e}");
    assert!(e.contains("reachable cells lie there"), "{e}");
}

/// Regression: start perturbations were drawn with replacement, so the `faigl2013` suite's
/// "20 variants of each problem" were 15–18 distinct cells, and a deterministic strategy
/// repeated its run on the copies (paired tests over them overstate the sample). As many
/// perturbations as cells within the radius now take every cell once.
#[test]
fn regression_start_perturbations_are_distinct() {
    // The distinct first-robot cells of an environment's start variants.
    let distinct = |env: &bench::plan::EnvInstance| {
        env.starts
            .iter()
            .map(|s| s.as_ref().expect("a fixed start")[0])
            .collect::<std::collections::BTreeSet<_>>()
            .len()
    };
    let p = bench::suites::plan("faigl2013").expect("the suite resolves");
    for env in &p.envs {
        assert_eq!(distinct(env), 20, "{}", env.name);
    }
    let e = error_of((
        "trials = 2",
        "trials = 2\nperturbations = 500\nradius = 0.5",
    ));
    let n: u32 = e
        .split("only ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no cell count in: {e}"));
    assert!(n >= 3, "{e}");
    let text = TINY.replacen(
        "trials = 2",
        &format!("trials = 2\nperturbations = {n}\nradius = 0.5"),
        1,
    );
    let p = Plan::resolve(&source(&text), Unbuilt::Error).expect("every cell once fits");
    for env in &p.envs {
        assert_eq!(distinct(env), env.starts.len(), "{}", env.name);
    }
}

/// Regression: a database with a zeroed page in the middle resumed as "all trials done"
/// (the key index was intact, the rows behind it were gone) and only `export` failed on it.
/// Opening an existing database now runs SQLite's quick_check and refuses a damaged one,
/// naming the file and what to do.
#[test]
fn zeroed_page_database_is_refused_on_resume() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let p = plan();
    bench::runner::run(&p, &db, &opts(2)).unwrap();
    assert!(
        !dir.path().join("a.sqlite-wal").exists(),
        "the closed store is checkpointed into one file"
    );
    let mut bytes = std::fs::read(&db).unwrap();
    let page_size = match u16::from_be_bytes([bytes[16], bytes[17]]) {
        1 => 65536,
        n => usize::from(n),
    };
    // A leaf page of the trials table: b-tree page type 13 holding trial keys.
    let leaf = (1..bytes.len() / page_size)
        .find(|&i| {
            let page = &bytes[i * page_size..(i + 1) * page_size];
            page[0] == 13 && page.windows(7).any(|w| w == b"|trial=")
        })
        .expect("a leaf page of the trials table");
    bytes[leaf * page_size..(leaf + 1) * page_size].fill(0);
    std::fs::write(&db, &bytes).unwrap();
    let e = bench::runner::run(&p, &db, &opts(1))
        .expect_err("a damaged database must be refused")
        .to_string();
    assert!(e.contains(&db.display().to_string()), "{e}");
    assert!(e.contains("damaged"), "{e}");
    assert!(e.contains("new database file"), "{e}");
    // The damaged file is left as it was, for whoever wants to rescue it.
    assert_eq!(std::fs::read(&db).unwrap(), bytes);
}

/// A ROS map_server map `NAME.yaml` + `NAME.pgm` in `dir`: three rooms joined by doors.
fn write_ros_map(dir: &std::path::Path, name: &str) {
    write_walled_map(dir, name, (60, 20), 0.5, |x, y| {
        (x == 20 && !(2..5).contains(&y)) || (x == 40 && !(15..18).contains(&y))
    });
}

/// A ROS map_server map `NAME.yaml` + `NAME.pgm` in `dir` of `(w, h)` cells of `resolution`
/// metres: free inside a wall around the border, with `wall(x, y)` cells occupied.
fn write_walled_map(
    dir: &std::path::Path,
    name: &str,
    (w, h): (usize, usize),
    resolution: f64,
    wall: impl Fn(usize, usize) -> bool,
) {
    let mut px = vec![0u8; w * h];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            px[y * w + x] = if wall(x, y) { 0 } else { 254 };
        }
    }
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&px);
    std::fs::write(dir.join(format!("{name}.pgm")), pgm).unwrap();
    std::fs::write(
        dir.join(format!("{name}.yaml")),
        format!(
            "image: {name}.pgm\nresolution: {resolution}\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n\
             occupied_thresh: 0.65\nfree_thresh: 0.196\n"
        ),
    )
    .unwrap();
}

#[test]
fn the_real_floor_plan_suite_runs_on_the_yaml_maps_of_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    write_ros_map(dir.path(), "b-rooms");
    write_ros_map(dir.path(), "a \"quoted\" plan");
    std::fs::write(dir.path().join("notes.txt"), "not a map").unwrap();
    let p = bench::suites::plan_with_maps("holz2010-real", Some(dir.path()), None).unwrap();
    let names: Vec<&str> = p.envs.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names.len(), 2, "{names:?}");
    assert!(
        names[0].contains("quoted") && names[1] == "b-rooms",
        "{names:?}"
    );
    assert_eq!(p.trials.len(), 2 * 6 * 5);
    // run it and put the paper's tables beside ours in the report
    let db = dir.path().join("real.sqlite");
    bench::runner::run(&p, &db, &opts(2)).unwrap();
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("Holz et al. 2010, Tables 1–3"), "{md}");
    assert!(
        md.contains("| strategy | a \"quoted\" plan (ours) | b-rooms (ours) | cave (T1) (paper)"),
        "{md}"
    );
    assert!(
        md.contains("| cf-rr-seg |") && md.contains("221.4 ± 20.0 (×0.79)"),
        "{md}"
    );
    assert!(
        md.contains("Ordering random > dt > cf > cf-rr ≥ cf-rr-seg: "),
        "{md}"
    );
    assert!(!md.contains("| cf | 0.0 ± 0.0"), "{md}");
    // an empty folder and a suite with its own environments say what was expected
    let empty = tempfile::tempdir().unwrap();
    let e = bench::suites::plan_with_maps("holz2010-real", Some(empty.path()), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains(".yaml") && e.contains("found none"), "{e}");
    let e = bench::suites::plan_with_maps("holz2010", Some(dir.path()), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--maps") && e.contains("holz2010-real"), "{e}");
}

/// Faigl & Kulich on the real floor plans of a folder: the paper's twelve strategies at
/// ρ = 5 m with 3 and 5 robots, 20 distinct starts per plan and one run of each (paired
/// starts, as the paper's Table I compares them), s_max = 7, the robot's 0.3 m clearance.
#[test]
fn the_real_faigl2013_suite_pairs_twenty_starts_per_floor_plan() {
    let dir = tempfile::tempdir().unwrap();
    // 10 × 6 m at 0.1 m: two rooms joined by a door 1.5 m wide
    write_walled_map(dir.path(), "plan", (100, 60), 0.1, |x, y| {
        x == 50 && !(20..35).contains(&y)
    });
    let p = bench::suites::plan_with_maps("faigl2013-real", Some(dir.path()), None).unwrap();
    assert_eq!(p.envs.len(), 1);
    assert_eq!(p.variants.len(), 12 * 2);
    assert_eq!(p.trials.len(), 12 * 2 * 20, "one run per start and variant");
    assert!(
        p.variants
            .iter()
            .all(|v| v.sensor.to_string() == "los:r=5" && [3, 5].contains(&v.robots)),
        "{:?}",
        p.variants
            .iter()
            .map(|v| (v.sensor.to_string(), v.robots))
            .collect::<Vec<_>>()
    );
    assert_eq!(p.common.clearance_m, 0.3);
    let firsts: std::collections::BTreeSet<_> = p.envs[0]
        .starts
        .iter()
        .map(|s| s.as_ref().expect("a fixed start")[0])
        .collect();
    assert_eq!(firsts.len(), 20, "20 distinct starts");
    // a shard of it runs
    let db = dir.path().join("real.sqlite");
    let o = RunOptions {
        shard: Some(Shard {
            index: 1,
            count: 48,
        }),
        ..opts(2)
    };
    let s = bench::runner::run(&p, &db, &o).unwrap();
    assert!(s.failed.is_empty(), "{:?}", s.failed);
    assert_eq!(s.ran, 10);
    assert!(
        rows(&db)
            .iter()
            .all(|r| r.coverage == 1.0 && r.max_path > 0.0)
    );
}

/// `TINY` with `edits` applied (each `(from, to)` must occur), and `extra` appended.
fn edited(edits: &[(&str, &str)], extra: &str) -> Plan {
    let mut text = TINY.to_string();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    text.push_str(extra);
    Plan::resolve(&source(&text), Unbuilt::Error).expect("the edited scenario resolves")
}

const MINE: &str = "\n[[strategy]]\npreset = \"ha-cc\"\ns_max = 5\nlabel = \"mine\"\n";

/// Regression: a scenario edited after its trials ran (another `start`, another `s_max`
/// under the same label, another map under the same name) planned trials of the same keys
/// and the same fingerprint, so resuming counted them as done ("2 of 2 trials done before")
/// and the store kept the old settings' results under the new scenario.
#[test]
fn regression_edited_scenario_is_not_resumed_as_done() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let named = [("seeds = [0]", "seeds = [0]\nname = \"m\"")];
    let p = edited(&named, MINE);
    bench::runner::run(&p, &db, &opts(2)).unwrap();
    let before = rows(&db);
    // the same scenario resumes: nothing to do
    let again = bench::runner::run(&p, &db, &opts(2)).unwrap();
    assert_eq!((again.ran, again.already_done), (0, p.trials.len()));
    let cases = [
        (
            edited(&[named[0], ("start = [3, 3]", "start = [4, 3]")], MINE),
            "starts [[3,3]",
        ),
        (edited(&named, &MINE.replace("5", "7")), "s_max 5"),
        (
            edited(&[("seeds = [0]", "seeds = [1]\nname = \"m\"")], MINE),
            "environment 'm'",
        ),
    ];
    for (changed, what) in cases {
        let e = bench::runner::run(&changed, &db, &opts(2))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&db.display().to_string()), "{e}");
        assert!(e.contains(what), "{what}: {e}");
        assert!(e.contains("another database file"), "{e}");
    }
    assert_eq!(rows(&db), before, "a refused run changes nothing");
}

/// Regression: shards of an edited scenario (the same keys and fingerprint, another start)
/// merged silently, the first shard's trial kept and the other's dropped.
#[test]
fn regression_merge_refuses_shards_of_an_edited_scenario() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.sqlite"), dir.path().join("b.sqlite"));
    bench::runner::run(&plan(), &a, &opts(1)).unwrap();
    let moved = edited(&[("start = [3, 3]", "start = [4, 3]")], "");
    bench::runner::run(&moved, &b, &opts(1)).unwrap();
    let out = dir.path().join("m.sqlite");
    let e = Store::merge(&out, &[a.clone(), b.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with(&b.display().to_string()), "{e}");
    assert!(
        e.contains("starts [[4,3]") && e.contains("not shards of one study"),
        "{e}"
    );
    assert!(!out.exists(), "nothing is written");
    // the same shard twice is no conflict
    let n = plan().trials.len();
    let all = bench::Merged { added: n, total: n };
    assert_eq!(Store::merge(&out, &[a.clone(), a]).unwrap(), all);
}

/// Regression: with 10 pairs the smallest two-sided Wilcoxon p is 2/2¹⁰ = 1.95·10⁻³, above
/// the default α = 0.001, so every cell of the +/=/- table was `=` and the report did not say
/// that no other verdict was possible. Such cells are marked, with a note naming α, the pairs
/// and how many would be needed.
#[test]
fn regression_report_marks_verdicts_that_cannot_be_significant() {
    let text = r#"
name = "ten"
sensors = ["los:r=4c"]
strategies = ["cf", "cf-rr"]
trials = 10

[[env]]
kind = "office"
seeds = [0]
size = [12, 10]
resolution = 0.5
"#;
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("ten.sqlite");
    let plan = Plan::resolve(&source(text), Unbuilt::Error).unwrap();
    bench::runner::run(&plan, &db, &opts(2)).unwrap();
    let report = |alpha: f64, name: &str| {
        let out = dir.path().join(name);
        bench::report::write(&db, &out, &bench::report::ReportOptions { alpha }).unwrap();
        std::fs::read_to_string(out.join("report.md")).unwrap()
    };
    let md = report(0.001, "r1");
    assert!(md.contains("| cf | · | = ⁿ (p="), "{md}");
    assert!(
        md.contains(
            "with 10 pairs (same start variant and trial) the smallest two-sided p the Wilcoxon \
             signed-rank test can give is 1.95e-3 ≥ α = 0.001"
        ),
        "{md}"
    );
    assert!(md.contains("needs at least 11 pairs"), "{md}");
    assert!(md.contains("0/1/0 (1 ⁿ)"), "{md}");
    // At α = 0.01 the 10 pairs can be significant: nothing is marked.
    let md = report(0.01, "r2");
    assert!(
        md.contains("+/=/- of L at α = 0.01") && !md.contains('ⁿ'),
        "{md}"
    );
}

/// Regression: `radius` without `perturbations` (or with `perturbations = 0`) was accepted
/// and silently ignored: every trial ran from the one start. It is refused, naming the file,
/// the key and what it needs.
#[test]
fn regression_radius_without_perturbations_is_refused() {
    let e = error_of(("trials = 2", "trials = 2\nradius = 1.5"));
    assert!(e.contains("tiny.toml:8: key `radius`"), "{e}");
    assert!(e.contains("no effect with no `perturbations`"), "{e}");
    assert!(e.contains("add `perturbations = N`"), "{e}");
    let e = error_of(("trials = 2", "trials = 2\nperturbations = 0\nradius = 1.5"));
    assert!(e.contains("tiny.toml:9: key `radius`"), "{e}");
    assert!(e.contains("with `perturbations = 0`"), "{e}");
    // With perturbations the radius is used, as before.
    let text = TINY.replacen(
        "trials = 2",
        "trials = 2\nperturbations = 2\nradius = 1.5",
        1,
    );
    Plan::resolve(&source(&text), Unbuilt::Error).expect("radius with perturbations");
}

/// Regression: merging into a database of another study said only "holds results of another
/// scenario than the inputs", naming neither study nor the input. Both studies' names and the
/// input file are named.
#[test]
fn regression_merge_conflict_names_both_studies() {
    let dir = tempfile::tempdir().unwrap();
    let one = |text: &str, file: &str| {
        let db = dir.path().join(file);
        let plan = Plan::resolve(&source(text), Unbuilt::Error).unwrap();
        let limit = RunOptions {
            limit: Some(1),
            ..opts(1)
        };
        bench::runner::run(&plan, &db, &limit).unwrap();
        db
    };
    let m = one(
        &TINY.replace("name = \"tiny\"", "name = \"other\""),
        "m.sqlite",
    );
    let j1 = one(TINY, "j1.sqlite");
    let e = Store::merge(&m, std::slice::from_ref(&j1))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with(&format!("{}: ", m.display())), "{e}");
    assert!(
        e.contains(&format!(
            "another study, 'other', than the input {}, which holds 'tiny'",
            j1.display()
        )),
        "{e}"
    );
    // Same study, other settings: both fingerprints are named.
    let s = one(&TINY.replace("seed = 7", "seed = 8"), "s.sqlite");
    let e = Store::merge(&s, std::slice::from_ref(&j1))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("another fingerprint (settings), 'strategies="),
        "{e}"
    );
    assert!(e.contains("seed=8") && e.contains("seed=7"), "{e}");
}

/// Regression: `bench report --out afile/sub`, with `afile` a file, failed with only
/// "afile/sub: Not a directory (os error 20)". It says what was expected and what was found,
/// and writes nothing.
#[test]
fn regression_report_under_a_file_says_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let limit = RunOptions {
        limit: Some(1),
        ..opts(1)
    };
    bench::runner::run(&plan(), &db, &limit).unwrap();
    let afile = dir.path().join("afile");
    std::fs::write(&afile, "not a folder").unwrap();
    let opts = bench::report::ReportOptions::default();
    for out in [afile.join("sub"), afile.join("sub").join("deeper")] {
        let e = bench::report::write(&db, &out, &opts)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&format!("{}: ", out.display())), "{e}");
        assert!(
            e.contains(&format!(
                "expected a folder to write the report into (made with its missing parents), \
                 but {} is a file",
                afile.display()
            )),
            "{e}"
        );
        assert!(!e.contains("os error"), "{e}");
    }
    let e = bench::report::write(&db, &afile, &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("is a file; expected the folder"), "{e}");
    assert_eq!(std::fs::read_to_string(&afile).unwrap(), "not a folder");
}

/// Regression: `trials = 99999999999999` was refused with only "too many trials"; the error
/// gives the limit and what was found, with the file, line and key.
#[test]
fn regression_too_many_trials_gives_the_limit() {
    let e = error_of(("trials = 2", "trials = 99999999999999"));
    assert!(e.contains("tiny.toml:7: key `trials`"), "{e}");
    assert!(
        e.contains("expected at most 2000000 runs per start variant"),
        "{e}"
    );
    assert!(e.contains("found 99999999999999"), "{e}");
}

/// Regression: a store of another table layout was refused with only "results of table
/// layout 2; this program writes layout 3", not saying what could be done with it.
#[test]
fn regression_other_table_layout_says_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("old.sqlite");
    let limit = RunOptions {
        limit: Some(1),
        ..opts(1)
    };
    bench::runner::run(&plan(), &db, &limit).unwrap();
    let conn = rusqlite::Connection::open(&db).unwrap();
    conn.execute(
        "UPDATE meta SET value = '2' WHERE key = 'schema_version'",
        [],
    )
    .unwrap();
    drop(conn);
    let version = env!("CARGO_PKG_VERSION");
    for e in [
        Store::open_read_only(&db).err().unwrap().to_string(),
        bench::runner::run(&plan(), &db, &opts(1))
            .unwrap_err()
            .to_string(),
    ] {
        assert!(
            e.contains("results of table layout 2, written by an older frontier"),
            "{e}"
        );
        assert!(e.contains("reads and writes layout 3 only"), "{e}");
        assert!(
            e.contains(&format!(
                "use the frontier version that wrote it (its trials were run by version {version})"
            )),
            "{e}"
        );
        assert!(e.contains("run it into a new database file"), "{e}");
    }
}

/// Regression: a scenario's `map` could not be an MCAP recording ("unknown map format"),
/// though `--map` reads one, and `resolution` took one number only, so a plan of
/// non-square pixels (`--resolution RX,RY`) could not be studied.
#[test]
fn regression_scenario_maps_read_as_the_map_flag() {
    let dir = tempfile::tempdir().unwrap();
    let cells = grid::Grid::from_vec(
        6,
        5,
        "######\
         #....#\
         #....#\
         #....#\
         ######"
            .bytes()
            .map(|b| {
                if b == b'#' {
                    grid::Occ::Occupied
                } else {
                    grid::Occ::Free
                }
            })
            .collect(),
    )
    .unwrap();
    let map = grid::GridMap::new(cells, 0.5);
    let mut rec = record::mcap_write::RunWriter::new(std::io::BufWriter::new(
        std::fs::File::create(dir.path().join("run.mcap")).unwrap(),
    ))
    .unwrap();
    rec.map(0.0, &map).unwrap();
    rec.finish().unwrap();
    grid::io::save_map(&map, &dir.path().join("plan.pgm")).unwrap();
    let path = dir.path().join("s.toml");
    let head = "strategies = [\"cf\"]\nsensors = [\"los:r=2\"]\n";
    std::fs::write(
        &path,
        format!(
            "{head}[[env]]\nmap = \"run.mcap\"\ntopic = \"/map\"\n\
             [[env]]\nmap = \"plan.pgm\"\nresolution = [0.5, 0.25]\n"
        ),
    )
    .unwrap();
    let plan = Plan::resolve(&Source::read(&path).unwrap(), Unbuilt::Error).unwrap();
    let sizes: Vec<_> = plan
        .envs
        .iter()
        .map(|e| (e.map.width(), e.map.height(), e.map.resolution))
        .collect();
    // The recording's own 0.5 m; the bitmap's 0.5 × 0.25 m pixels resampled to 0.25 m
    // cells, twice as many columns.
    assert_eq!(sizes, vec![(6, 5, 0.5), (12, 5, 0.25)]);
    for (env, want) in [
        (
            "[[env]]\nmap = \"run.mcap\"\nresolution = 0.1\n",
            "key `env[0].resolution`: an MCAP recording's map carries its own resolution",
        ),
        (
            "[[env]]\nmap = \"plan.pgm\"\nresolution = 0.5\ntopic = \"/map\"\n",
            "key `env[0].topic`: chooses the map topic of an MCAP recording",
        ),
        (
            "[[env]]\nkind = \"office\"\nresolution = [0.5, 0.25]\n",
            "key `env[0].resolution`: a built-in environment has square cells",
        ),
        (
            "[[env]]\nmap = \"plan.pgm\"\nresolution = [0.5]\n",
            "or [x, y] of them, found [0.5]",
        ),
        (
            "[[env]]\nmap = \"plan.pgm\"\nresolution = \"fine\"\n",
            "expected metres per cell: a number, or [x, y]",
        ),
    ] {
        std::fs::write(&path, format!("{head}{env}")).unwrap();
        let e = Plan::resolve(&Source::read(&path).unwrap(), Unbuilt::Error)
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "{env}: {e}");
    }
}

/// Regression: a report whose replay could not be made (a trial that cannot be re-run, here
/// a damaged picture of its environment) failed after writing some of the report, leaving a
/// half-written folder; the replays are now made before anything is written.
#[test]
fn regression_a_failed_replay_leaves_no_report_behind() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("a.sqlite");
    let plan = plan();
    bench::runner::run(&plan, &db, &opts(2)).unwrap();
    let last = &plan.envs.last().unwrap().name;
    let conn = rusqlite::Connection::open(&db).unwrap();
    let damaged = conn
        .execute(
            "UPDATE envs SET png = x'89504e47' WHERE name = ?1",
            [last.as_str()],
        )
        .unwrap();
    assert_eq!(damaged, 1);
    drop(conn);
    let out = dir.path().join("report");
    let e = bench::report::write(&db, &out, &bench::report::ReportOptions::default());
    assert!(e.is_err(), "a damaged picture cannot be replayed");
    assert!(
        !out.exists(),
        "{:?}",
        std::fs::read_dir(&out).map(|d| d.count())
    );
}

/// Regression: a setting's plot files were named by its environment and sensor joined by
/// '-', so environment `a` with `laser-limited-sonar` and `a-laser-limited` with `sonar`
/// wrote the same `box-…svg` and `coverage-…svg`, and report.md showed one setting's
/// charts under the other's heading. Every setting has files of its own.
#[test]
fn regression_two_settings_never_share_a_plot_file() {
    let text = r#"
name = "slug"
seed = 1
robots = [1]
sensors = ["sonar", "laser-limited-sonar"]
strategies = ["cf"]

[[env]]
kind = "empty"
name = "a"
size = [3, 3]
resolution = 0.1

[[env]]
kind = "empty"
name = "a-laser-limited"
size = [3, 3]
resolution = 0.1
"#;
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("slug.sqlite");
    let plan = Plan::resolve(&source(text), Unbuilt::Error).unwrap();
    bench::runner::run(&plan, &db, &opts(2)).unwrap();
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let mut boxes: Vec<&str> = md
        .lines()
        .filter_map(|l| l.strip_prefix("![")?.split("](plots/box-").nth(1))
        .collect();
    assert_eq!(boxes.len(), 4, "{md}");
    boxes.sort_unstable();
    boxes.dedup();
    assert_eq!(boxes.len(), 4, "two settings share a box plot: {md}");
    for b in boxes {
        let file = b.trim_end_matches(')');
        assert!(
            out.join("plots").join(format!("box-{file}")).exists(),
            "{file}"
        );
    }
}
