//! Competitive ratios in a study (`[optimal]`, Quattrini Li et al. 2012): every single-robot
//! trial with a 360° sensor carries the optimal offline path from its own start, the ratio is
//! online over optimal, closest-frontier runs (sensing at boundary cells) are never shorter
//! than the proven optimum, and results do not depend on the thread count.

use std::path::Path;

use bench::{Plan, RunOptions, Source, Store, TrialRow, Unbuilt};

const STUDY: &str = r#"
name = "ratios"
seed = 3
robots = [1, 2]
sensors = ["los:r=3c", "footprint:r=3c"]
strategies = ["cf", "yamauchi", "random"]
sensing = "on-arrival"
trials = 2

[[env]]
kind = "maze"
seeds = [0, 1]
size = [6, 5]
resolution = 0.5

[optimal]
max_nodes = 200000
"#;

fn plan(text: &str) -> Plan {
    let src = Source {
        file: "ratios.toml".into(),
        text: text.into(),
        dir: None,
    };
    Plan::resolve(&src, Unbuilt::Error).expect("scenario resolves")
}

fn rows(db: &Path) -> Vec<TrialRow> {
    Store::open_raw(db)
        .expect("open")
        .rows()
        .expect("rows")
        .into_iter()
        .map(|mut r| {
            r.wall_s = 0.0;
            r
        })
        .collect()
}

fn run(plan: &Plan, db: &Path, threads: usize) {
    let s = bench::runner::run(
        plan,
        db,
        &RunOptions {
            threads: Some(threads),
            ..RunOptions::default()
        },
    )
    .expect("run");
    assert!(s.failed.is_empty(), "{:?}", s.failed);
}

#[test]
fn single_robot_trials_carry_the_optimal_path_and_their_ratio() {
    let dir = tempfile::tempdir().unwrap();
    let p = plan(STUDY);
    assert!(p.optimal.is_some());
    let db = dir.path().join("a.sqlite");
    run(&p, &db, 2);
    let all = rows(&db);
    assert_eq!(all.len(), p.trials.len());
    let mut proven = 0;
    for r in &all {
        if r.robots > 1 {
            assert!(r.optimal_m.is_none() && r.ratio.is_none(), "{}", r.key);
            continue;
        }
        let opt = r.optimal_m.expect("an optimal path");
        let lower = r.optimal_lower_m.expect("a lower bound");
        assert!(lower <= opt + 1e-9, "{}: bounds {lower} > {opt}", r.key);
        let ratio = r.ratio.expect("a ratio");
        assert!((ratio - r.total_path / opt).abs() < 1e-12, "{}", r.key);
        if r.optimal_proven == Some(true) {
            proven += 1;
            assert!((lower - opt).abs() < 1e-9, "{}", r.key);
            if r.strategy == "cf" {
                assert!(
                    ratio >= 1.0 - 1e-9,
                    "{}: cf senses at boundary cells only, so it cannot beat the optimum ({ratio})",
                    r.key
                );
            }
        }
    }
    assert!(proven > 0, "the tiny mazes should be solved to optimality");
    // the same start, sensor and goal share one optimal path
    let store = Store::open_raw(&db).unwrap();
    let paths = store.optimal_paths().unwrap();
    let mut starts: Vec<(String, String, String)> = all
        .iter()
        .filter(|r| r.robots == 1)
        .map(|r| (r.env.clone(), r.sensor.clone(), r.starts.clone()))
        .collect();
    starts.sort();
    starts.dedup();
    assert_eq!(paths.len(), starts.len());
    // the report's table: one row per strategy, n = its single-robot trials of the setting
    let mut by: std::collections::BTreeMap<String, Vec<&TrialRow>> = Default::default();
    for r in all
        .iter()
        .filter(|r| r.robots == 1 && r.sensor == "los:r=3c")
    {
        if r.env == all[0].env {
            by.entry(r.strategy.clone()).or_default().push(r);
        }
    }
    let (header, body) = bench::competitive::ratio_table(&by).expect("a table");
    assert_eq!(header[0], "strategy");
    assert_eq!(body.len(), 3);
    for row in &body {
        assert_eq!(row[1], by[&row[0]].len().to_string());
    }
    let none: std::collections::BTreeMap<String, Vec<&TrialRow>> = all
        .iter()
        .filter(|r| r.robots == 2)
        .map(|r| (r.strategy.clone(), vec![r]))
        .collect();
    assert!(bench::competitive::ratio_table(&none).is_none());
    // the report shows it
    let out = dir.path().join("report");
    bench::report::write(&db, &out, &bench::report::ReportOptions::default()).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("Competitive ratio") && md.contains("ratio mean ± sd"),
        "{md}"
    );
    // and the results do not depend on the thread count
    let db1 = dir.path().join("b.sqlite");
    run(&p, &db1, 1);
    assert_eq!(rows(&db1), all);
}

#[test]
fn bad_optimal_settings_name_the_key() {
    let text = STUDY.replace("max_nodes = 200000", "weight = 0.5");
    let src = Source {
        file: "ratios.toml".into(),
        text,
        dir: None,
    };
    let e = Plan::resolve(&src, Unbuilt::Error).unwrap_err().to_string();
    assert!(
        e.contains("ratios.toml") && e.contains("optimal.weight") && e.contains("0.5"),
        "{e}"
    );
    let src = Source {
        file: "ratios.toml".into(),
        text: STUDY.replace("max_nodes = 200000", "budget = 3"),
        dir: None,
    };
    let e = Plan::resolve(&src, Unbuilt::Error).unwrap_err().to_string();
    assert!(e.contains("budget"), "{e}");
}

/// Regression: the `[optimal]` search's budget was not in a study's memory check, so
/// `memory_mb = 1500` under `--memory-mb 200` with two threads was estimated at 33 MiB and
/// took 2,372 MiB. Each trial that gets an optimal path now counts its search's budget.
#[test]
fn the_optimal_search_budget_counts_in_the_memory_check() {
    let p = plan(&STUDY.replace("max_nodes = 200000", "max_nodes = 200000\nmemory_mb = 300"));
    let dir = tempfile::tempdir().expect("tempdir");
    let db = dir.path().join("r.sqlite");
    let e = bench::runner::run(
        &p,
        &db,
        &RunOptions {
            threads: Some(1),
            memory_mb: Some(200),
            ..RunOptions::default()
        },
    )
    .expect_err("refused");
    let e = e.to_string();
    assert!(
        e.contains("more than --memory-mb 200") && e.contains("[optimal] memory_mb"),
        "{e}"
    );
    // Without the search the trials fit.
    let runs = plan(&STUDY.replace("[optimal]\nmax_nodes = 200000\n", ""));
    bench::runner::run(
        &runs,
        &dir.path().join("s.sqlite"),
        &RunOptions {
            threads: Some(1),
            memory_mb: Some(200),
            ..RunOptions::default()
        },
    )
    .expect("runs without [optimal] fit");
}
