//! End-to-end tests of the `frontier` binary: outputs, determinism and error messages.

use std::path::Path;
use std::process::{Command, Output};

fn frontier(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_frontier"))
        .args(args)
        .output()
        .expect("run frontier")
}

fn ok(args: &[&str]) -> String {
    let out = frontier(args);
    assert!(
        out.status.success(),
        "frontier {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

fn err(args: &[&str]) -> String {
    let out = frontier(args);
    assert!(!out.status.success(), "frontier {args:?} should fail");
    String::from_utf8(out.stderr).expect("utf-8")
}

#[test]
fn explore_json_has_the_fields_and_is_byte_identical() {
    let args = [
        "explore",
        "--env",
        "office",
        "--seed",
        "4",
        "--strategy",
        "cf-rr",
        "--json",
        "--no-timing",
    ];
    let a = ok(&args);
    let b = ok(&args);
    assert_eq!(a, b, "same seed, same JSON");
    let v: serde_json::Value = serde_json::from_str(&a).unwrap();
    for key in [
        "env",
        "seed",
        "strategy",
        "robots",
        "sensor",
        "complete",
        "reason",
        "coverage",
        "path_length_m",
        "max_path_length_m",
        "total_path_length_m",
        "time_s",
        "decisions",
        "decide_ms",
        "d90_m",
        "t90_s",
        "d98_m",
        "t98_s",
        "d99_m",
        "t99_s",
        "overlap",
        "idle_s",
        "coverage_kind",
    ] {
        assert!(v.get(key).is_some(), "missing {key} in {a}");
    }
    assert_eq!(v["complete"], true);
    assert_eq!(v["reason"], "complete");
    assert_eq!(v["coverage"], 1.0);
    assert_eq!(v["env"], "office-s4");
    assert_eq!(v["decide_ms"], serde_json::Value::Null);
    let other = ok(&[
        "explore",
        "--env",
        "office",
        "--seed",
        "5",
        "--json",
        "--no-timing",
    ]);
    assert_ne!(a, other, "another seed, another run");
    // With timings, the timing fields are numbers.
    let timed: serde_json::Value =
        serde_json::from_str(&ok(&["explore", "--env", "maze", "--json"])).unwrap();
    assert!(timed["decide_ms"].is_number());
}

#[test]
fn explore_writes_pictures_and_trace() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let text = ok(&[
        "explore",
        "--env",
        "maze",
        "--strategy",
        "yamauchi",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(text.contains("ended: complete"), "{text}");
    let bytes = std::fs::read(out.join("final.png")).unwrap();
    let png = viz::Picture::from_png(&bytes, 1 << 24).unwrap();
    assert!(png.width() >= 500, "upscaled picture, got {}", png.width());
    let trace: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("trace.json")).unwrap()).unwrap();
    assert_eq!(trace["strategy"], "yamauchi");
    assert!(trace["trails"][0].as_array().unwrap().len() > 10);
    // the map the robot built, as ROS map_server YAML + PGM: the maze fully explored
    let belief = out.join("belief.yaml");
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", belief.to_str().unwrap(), "--json"])).unwrap();
    assert!(info["free"].as_u64().unwrap() > 100, "{info}");
    assert_eq!(info["resolution"], 0.5, "{info}");
}

#[test]
fn explore_on_a_map_file_from_a_start() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("rooms.txt");
    std::fs::write(
        &map,
        "##########\n#....#...#\n#....#...#\n#.........#\n##########\n"
            .replace(".........#\n", "........#\n"),
    )
    .unwrap();
    let v: serde_json::Value = serde_json::from_str(&ok(&[
        "explore",
        "--map",
        map.to_str().unwrap(),
        "--start",
        "1,1",
        "--sensor",
        "los:r=2",
        "--json",
    ]))
    .unwrap();
    assert_eq!(v["complete"], true);
    assert_eq!(v["starts"][0], serde_json::json!([1, 1]));
}

#[test]
fn env_writes_a_ros_map_that_map_info_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let yaml = dir.path().join("office.yaml");
    let text = ok(&[
        "env",
        "office",
        "--seed",
        "2",
        "--out",
        yaml.to_str().unwrap(),
    ]);
    assert!(text.contains("50x40 cells"), "{text}");
    assert!(Path::new(&dir.path().join("office.pgm")).exists());
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", yaml.to_str().unwrap(), "--json"])).unwrap();
    assert_eq!(info["width"], 50);
    assert_eq!(info["height"], 40);
    assert_eq!(info["resolution"], 0.5);
    assert_eq!(info["free_components"], 1);
    assert_eq!(info["unknown"], 0);
    assert_eq!(info["topic"], serde_json::Value::Null, "not a recording");
}

/// Regression: `map info --json` gave a 604-cell width at 0.05 m as 30.200000000000003 m.
#[test]
fn map_info_gives_sizes_in_metres_without_float_noise() {
    let dir = tempfile::tempdir().unwrap();
    let yaml = dir.path().join("m.yaml");
    std::fs::write(dir.path().join("m.pgm"), {
        let mut b = b"P5\n604 307\n255\n".to_vec();
        b.extend(std::iter::repeat_n(254u8, 604 * 307));
        b
    })
    .unwrap();
    std::fs::write(
        &yaml,
        "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n\
         occupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    .unwrap();
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", yaml.to_str().unwrap(), "--json"])).unwrap();
    assert_eq!(info["width_m"], 30.2);
    assert_eq!(info["height_m"], 15.35);
    let text = ok(&["map", "info", yaml.to_str().unwrap()]);
    assert!(
        text.contains("604 x 307 cells, 30.20 m x 15.35 m"),
        "{text}"
    );
}

/// Regression: `optimal --json` always printed its wall-clock seconds, so two equal runs
/// never printed the same bytes; `--no-timing` leaves them out, as `explore`'s does.
#[test]
fn optimal_json_without_timing_is_the_same_every_time() {
    let args = [
        "optimal",
        "--env",
        "maze",
        "--size",
        "6x5",
        "--resolution",
        "0.5",
        "--json",
        "--no-timing",
    ];
    let first = ok(&args);
    assert_eq!(first, ok(&args));
    let v: serde_json::Value = serde_json::from_str(&first).unwrap();
    assert!(
        v["seconds"].is_null() && v["status"] == "optimal",
        "{first}"
    );
}

/// Regression: a map at 1e-9 m per cell was "0.00 m x 0.00 m" across.
#[test]
fn map_info_gives_sizes_below_a_centimetre() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("t.map");
    std::fs::write(&map, "type octile\nheight 1\nwidth 2\nmap\n..\n").unwrap();
    let text = ok(&["map", "info", map.to_str().unwrap(), "--resolution", "1e-9"]);
    assert!(text.contains("2 x 1 cells, 2e-9 m x 1e-9 m"), "{text}");
    assert!(text.contains("resolution  1e-9 m/cell"), "{text}");
}

#[test]
fn env_list_names_every_kind() {
    let text = ok(&["env", "--list"]);
    for kind in ["office", "hospital", "cave", "maze", "potholes", "empty"] {
        assert!(text.contains(kind), "{text}");
    }
}

#[test]
fn demo_prints_a_table() {
    let dir = tempfile::tempdir().unwrap();
    let text = ok(&[
        "demo",
        "--seeds",
        "2",
        "--envs",
        "office,maze",
        "--strategies",
        "cf,cf-rr",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(text.contains("mean ± sd over 2 seeds"), "{text}");
    assert!(
        text.contains("all 8 runs explored everything reachable"),
        "{text}"
    );
    assert!(dir.path().join("office-cf-rr.png").exists());
}

/// Regression: `--speed -1` and `--clearance -1` were taken for flags, and the error
/// ("unexpected argument '-1' found") named neither the flag nor what it expects.
#[test]
fn negative_numbers_are_refused_naming_their_flag() {
    for (args, expected) in [
        (
            &["explore", "--speed", "-1"][..],
            "--speed: expected a positive number",
        ),
        (
            &["explore", "--clearance", "-1"],
            "--clearance: expected a non-negative",
        ),
        (
            &["explore", "--resolution", "-0.1"],
            "--resolution: expected a positive",
        ),
        (&["explore", "--goal", "-0.5"], "--goal"),
        (
            &["explore", "--seed", "-1"],
            "invalid value '-1' for '--seed <SEED>'",
        ),
        (&["explore", "--robots", "-2"], "for '--robots <ROBOTS>'"),
        (
            &["bench", "report", "x.sqlite", "--out", "r", "--alpha", "-1"],
            "--alpha: expected a level",
        ),
        (&["optimal", "--weight", "-2"], "--weight"),
        (&["sensors", "--resolution", "-1"], "--resolution"),
        // Regression: the text values that start with a number were taken for flags too.
        (&["explore", "--start", "-1,5"], "--start"),
        (&["explore", "--size", "-5x5"], "--size"),
        (&["explore", "--resolution", "-0.1,0.1"], "--resolution"),
        (&["optimal", "--start", "-1,5"], "--start"),
        (
            &["env", "office", "--out", "x.png", "--size", "-5x5"],
            "--size",
        ),
        (&["sensors", "--size", "-5x5"], "--size"),
        (
            &["map", "info", "x.pgm", "--resolution", "-1,1"],
            "--resolution",
        ),
        // Regression: these named the library's field, not the flag.
        (
            &["sensors", "--size", "1x1"],
            "--size: width 1 m for office: too small",
        ),
        (
            &["optimal", "--landmarks", "100000"],
            "--landmarks: expected at most 4096, found 100000",
        ),
    ] {
        let e = err(args);
        assert!(e.contains(expected), "{args:?}: {e}");
        assert!(!e.contains("unexpected argument"), "{args:?}: {e}");
    }
}

/// Regression: `--memory-mb 0` was taken (Python refuses `memory_mb=0`) and then refused
/// an 18-byte file as needing "about 1 MiB, more than --memory-mb 0".
#[test]
fn regression_memory_budget_of_zero_is_refused() {
    for cmd in [
        &["explore", "--memory-mb", "0"][..],
        &[
            "map",
            "info",
            "x.pgm",
            "--resolution",
            "1",
            "--memory-mb",
            "0",
        ],
        &["bench", "--suite", "quick", "--memory-mb", "0"],
        &["segment", "--memory-mb", "0"],
        &["optimal", "--memory-mb", "0"],
    ] {
        let e = err(cmd);
        assert!(
            e.contains("'--memory-mb <MEMORY_MB>': expected a positive number of MiB, found 0"),
            "{cmd:?}: {e}"
        );
    }
    let e = err(&["explore", "--memory-mb", "-4"]);
    assert!(
        e.contains("expected a positive number of MiB, found -4"),
        "{e}"
    );
}

/// Regression: a recorded run whose trace outgrew its estimate (`random` crossing a maze
/// for every goal: 1.4 times the moves expected here) grew past the memory the command had
/// checked. Its trace is capped at what `--memory-mb` leaves beside the run: the run ends
/// there, says so, and still writes what it recorded.
#[test]
fn regression_a_trace_that_outgrows_its_memory_ends_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let args = |mb: &'static str| {
        vec![
            "explore",
            "--env",
            "maze",
            "--env-seed",
            "3",
            "--size",
            "14x10",
            "--resolution",
            "0.05",
            "--sensor",
            "los:r=2c",
            "--strategy",
            "random",
            "--json",
            "--no-timing",
            "--no-progress",
            "--memory-mb",
            mb,
        ]
    };
    let mut capped = args("100");
    capped.extend(["--out", out_dir.to_str().unwrap()]);
    let out = frontier(&capped);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning: the run stopped after")
            && stderr.contains("filled what --memory-mb 100 leaves beside the run"),
        "{stderr}"
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["reason"], "trace limit");
    assert!(j["coverage"].as_f64().unwrap() < 1.0);
    assert!(out_dir.join("trace.json").is_file());
    // A budget below the estimate is refused up front, the trace named as most of it.
    let mut refused = args("40");
    refused.extend(["--out", out_dir.to_str().unwrap()]);
    let e = err(&refused);
    assert!(
        e.contains("more than --memory-mb 40")
            && e.contains("the trace it records for pictures, a replay or trajectories"),
        "{e}"
    );
    // Without a trace the same budget runs to the end.
    let out = frontier(&args("100"));
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["reason"], "complete");
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Regression: `--out DIR` was made, parents and all, before the map was read or the flags
/// checked, so a command that failed left an empty folder behind.
#[test]
fn regression_failed_command_leaves_no_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("new").join("sub");
    let out_s = out.to_str().unwrap();
    for args in [
        &["explore", "--map", "/no/such/map.yaml", "--out", out_s][..],
        &["explore", "--strategy", "bogus", "--out", out_s],
        &["explore", "--robots", "0", "--out", out_s],
        &["optimal", "--map", "/no/such/map.yaml", "--out", out_s],
        &["optimal", "--sensor", "lidar:r=3", "--out", out_s],
    ] {
        err(args);
        assert!(!dir.path().join("new").exists(), "{args:?} left a folder");
    }
    // A file where the folder should be is still refused by name, before any work.
    let file = dir.path().join("f");
    std::fs::write(&file, "").unwrap();
    let e = err(&["explore", "--out", file.to_str().unwrap()]);
    assert!(e.contains("expected a folder, found a file"), "{e}");
}

/// Regression: an `--out` folder that is there but cannot be written in was found out only
/// when the run, done, wrote its pictures (`error: writing ro/final.png: Permission
/// denied`, naming no flag); `demo` made its `--out` folder before it read `--sensor`, so
/// a refused sensor left an empty folder; a `--gif` path through a file said "no folder".
#[test]
fn regression_an_unwritable_out_folder_is_refused_before_the_run() {
    // Linux's /proc: a folder no one, not even root, can add a file to.
    if std::path::Path::new("/proc/self").exists() {
        let e = err(&["explore", "--env", "maze", "--out", "/proc"]);
        assert!(
            e.contains("--out /proc: expected a folder files can be written in"),
            "{e}"
        );
        assert!(!e.contains("final.png"), "refused after the run: {e}");
    }
    let dir = tempfile::tempdir().unwrap();
    let demo = dir.path().join("demo");
    let e = err(&["demo", "--out", demo.to_str().unwrap(), "--sensor", "sonar"]);
    assert!(e.contains("--sensor"), "{e}");
    assert!(!demo.exists(), "demo left its folder");
    let file = dir.path().join("afile");
    std::fs::write(&file, "").unwrap();
    let gif = file.join("x.gif");
    let e = err(&["explore", "--env", "maze", "--gif", gif.to_str().unwrap()]);
    assert!(e.contains("which is a file"), "{e}");
}

/// Regression: the summary named the folder of `--out` but not the files `--gif`,
/// `--html` and `--mcap` wrote.
#[test]
fn the_summary_names_every_file_written() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (gif, html, mcap) = (file("run.gif"), file("run.html"), file("run.mcap"));
    let out = ok(&[
        "explore", "--env", "office", "--size", "20x15", "--gif", &gif, "--html", &html, "--mcap",
        &mcap,
    ]);
    for (what, path) in [
        ("animation", &gif),
        ("replay page", &html),
        ("recording", &mcap),
    ] {
        assert!(out.contains(&format!("{what} written to {path}")), "{out}");
        assert!(std::path::Path::new(path).is_file(), "{path}");
    }
}

#[test]
fn errors_name_the_flag_and_what_was_found() {
    assert!(err(&["explore", "--strategy", "nearestt"]).contains(
        "--strategy: unknown strategy 'nearestt': expected yamauchi, cf, cf-rr, cf-rr-seg, cf-rr-seg-any, random, dt"
    ));
    let e = err(&["explore", "--sensor", "lidar:r=x"]);
    assert!(
        e.contains("--sensor") && e.contains("'r'") && e.contains("\"x\""),
        "{e}"
    );
    let e = err(&["explore", "--env", "castle"]);
    assert!(e.contains("--env") && e.contains("castle"), "{e}");
    let e = err(&["explore", "--map", "no/such/map.yaml"]);
    assert!(e.contains("no/such/map.yaml"), "{e}");
    let e = err(&["explore", "--env", "office", "--start", "0,0"]);
    assert!(e.contains("--start 0,0: the cell is occupied"), "{e}");
    let e = err(&["explore", "--env", "office", "--start", "500,2"]);
    assert!(e.contains("outside the 50x40 map"), "{e}");
    let e = err(&["explore", "--speed=-1"]);
    assert!(e.contains("--speed: expected a positive number"), "{e}");
    let e = err(&["explore", "--env", "office", "--resolution", "abc"]);
    assert!(e.contains("--resolution") && e.contains("abc"), "{e}");
    let e = err(&["explore", "--env", "office", "--size", "10by3"]);
    assert!(e.contains("--size: expected WxH"), "{e}");
}

#[test]
fn malformed_map_file_is_a_named_error() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("bad.map");
    std::fs::write(&map, "type octile\nheight 2\nwidth 3\nmap\n..x\n...\n").unwrap();
    let e = err(&["map", "info", map.to_str().unwrap()]);
    assert!(e.contains("bad.map") && e.contains("line 5"), "{e}");
}

#[test]
fn sonar_in_a_furnished_office_reports_the_map_audit() {
    let base = [
        "explore",
        "--env",
        "office",
        "--size",
        "12x10",
        "--resolution",
        "0.1",
        "--clutter",
        "--strategy",
        "yamauchi",
        "--json",
        "--no-timing",
    ];
    let run = |sensor: &str| -> serde_json::Value {
        let mut args = base.to_vec();
        args.extend(["--sensor", sensor]);
        serde_json::from_str(&ok(&args)).expect("json")
    };
    let sonar = run("laser-limited-sonar");
    assert_eq!(
        sonar["belief"], "evidence",
        "sonar builds the evidence grid"
    );
    assert_eq!(sonar["sensor"], "laser-limited-sonar:r=3.048");
    let laser = run("laser");
    assert_eq!(laser["sensor"], "lidar:r=3.048,fov=360,res=1");
    for v in [&sonar, &laser] {
        let map = &v["map"];
        assert!(map["clutter_cells"].as_u64().unwrap() > 0, "{map}");
        let acc = map["accuracy"].as_f64().unwrap();
        assert!(acc > 0.0 && acc <= 1.0, "{map}");
    }
    // The laser misses the tables; the sonar hears them.
    assert!(
        sonar["map"]["clutter_mapped"].as_u64() > laser["map"]["clutter_mapped"].as_u64(),
        "{} vs {}",
        sonar["map"],
        laser["map"]
    );
}

#[test]
fn clutter_flags_are_checked() {
    let e = err(&["explore", "--env", "cave", "--clutter"]);
    assert!(e.contains("--clutter") && e.contains("cave"), "{e}");
    let e = err(&["segment", "--env", "office", "--clutter"]);
    assert!(e.contains("segment reads only the sensor plane"), "{e}");
    let e = err(&["explore", "--sensor", "sonar", "--belief", "known"]);
    assert!(e.contains("--belief") && e.contains("evidence"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let layer = dir.path().join("tables.txt");
    std::fs::write(&layer, "###\n#.#\n###\n").unwrap();
    let e = err(&[
        "explore",
        "--env",
        "office",
        "--clutter-map",
        layer.to_str().unwrap(),
    ]);
    assert!(
        e.contains("tables.txt") && e.contains("expected the map's size"),
        "{e}"
    );
}

#[test]
fn sensors_compares_the_three_setups() {
    let out = ok(&["sensors", "--seeds", "1", "--size", "12x10", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let sensors = v["sensors"].as_array().unwrap();
    let names: Vec<&str> = sensors
        .iter()
        .map(|s| s["sensor"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["sonar", "laser", "laser-limited-sonar"]);
    for s in sensors {
        assert_eq!(s["runs"], 1);
    }
}

/// Regression: `sensors --sensors lidar:r=8,fov=180,res=1` split the spec `frontier list`
/// shows at its commas ("sensor 'fov=180': unknown kind"), and a sensor listed twice ran
/// twice.
#[test]
fn regression_sensors_takes_a_lidar_spec_and_each_sensor_once() {
    let out = ok(&[
        "sensors",
        "--seeds",
        "1",
        "--size",
        "12x10",
        "--sensors",
        "lidar:r=3,fov=180,res=1,laser",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let names: Vec<&str> = v["sensors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["sensor"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["lidar:r=3,fov=180,res=1", "laser"]);
    let e = err(&["sensors", "--sensors", "sonar,laser,sonar"]);
    assert!(
        e.contains("--sensors: expected each sensor once, found sonar twice"),
        "{e}"
    );
}

/// The rows of a results database without the wall times (the only non-deterministic column).
fn bench_rows(db: &Path) -> Vec<bench::TrialRow> {
    let store = bench::Store::open_read_only(db).expect("open the results database");
    let mut rows = store.rows().expect("read the rows");
    for r in &mut rows {
        r.wall_s = 0.0;
    }
    rows
}

/// A study killed with SIGKILL mid-run keeps every committed trial, its database stays
/// readable, and re-running the same command finishes with exactly the results of an
/// uninterrupted run.
#[cfg(unix)]
#[test]
fn bench_killed_with_sigkill_resumes_to_the_uninterrupted_results() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("study.toml");
    std::fs::write(
        &scenario,
        r#"
name = "killed"
seed = 7
robots = [3]
sensors = ["los:r=4c"]
strategies = ["random"]
trials = 24

[[env]]
kind = "office"
seeds = [1]
size = [20, 15]
resolution = 0.25
"#,
    )
    .unwrap();
    let s = scenario.to_str().unwrap();
    let killed = dir.path().join("killed.sqlite");
    let k = killed.to_str().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_frontier"))
        .args(["bench", s, "--db", k, "-j", "2", "--no-progress"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start frontier bench");
    // Kill it once a few trials are committed, while the rest are still to run.
    let started = std::time::Instant::now();
    loop {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the study finished before it could be killed; make it longer"
        );
        // (The database may not have its tables yet when it first appears.)
        let committed = bench::Store::open_read_only(&killed).and_then(|s| s.count());
        if committed.is_ok_and(|n| n >= 2) {
            break;
        }
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "no trial committed in two minutes"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().expect("SIGKILL");
    child.wait().unwrap();
    let kept = bench_rows(&killed);
    assert!(
        kept.len() >= 2 && kept.len() < 24,
        "{} trials kept",
        kept.len()
    );
    // Resume with the same command (one thread this time), and run the study cleanly.
    let out = frontier(&["bench", s, "--db", k, "-j", "1", "--no-progress"]);
    let resumed = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "resume failed: {resumed}");
    assert!(
        resumed.contains(&format!("{} of 24 trials done before", kept.len())),
        "{resumed}"
    );
    let clean = dir.path().join("clean.sqlite");
    ok(&[
        "bench",
        s,
        "--db",
        clean.to_str().unwrap(),
        "-j",
        "2",
        "--no-progress",
    ]);
    let (a, b) = (bench_rows(&killed), bench_rows(&clean));
    assert_eq!(a.len(), 24);
    assert_eq!(a, b, "resumed after SIGKILL vs uninterrupted");
    // The trials kept at the kill are unchanged by the resume.
    for row in &kept {
        assert!(a.contains(row), "trial {} changed on resume", row.key);
    }
}

/// Two rooms joined by a one-cell door (MovingAI `.map`), walls all round.
const TWO_ROOMS: &str = "type octile\nheight 7\nwidth 11\nmap\n@@@@@@@@@@@\n@...@.....@\n\
@...@.....@\n@.........@\n@...@.....@\n@...@.....@\n@@@@@@@@@@@\n";

/// Write the two-room map into `dir` and return the `optimal` arguments that pose it from
/// (1, 1) with `los:r=3c`, followed by `extra`.
fn optimal_on_two_rooms(dir: &Path, extra: &[&str]) -> Vec<String> {
    let map = dir.join("two.map");
    std::fs::write(&map, TWO_ROOMS).unwrap();
    let map = map.to_str().unwrap();
    let base = [
        "optimal",
        "--map",
        map,
        "--resolution",
        "1",
        "--start",
        "1,1",
        "--sensor",
        "los:r=3c",
    ];
    base.iter().chain(extra).map(|a| a.to_string()).collect()
}

fn strs(args: &[String]) -> Vec<&str> {
    args.iter().map(String::as_str).collect()
}

#[test]
fn optimal_on_a_map_file_proves_the_optimum_and_scores_online_strategies() {
    let dir = tempfile::tempdir().unwrap();
    let args = optimal_on_two_rooms(
        dir.path(),
        &["--all-cells", "--compare", "cf,yamauchi", "--json"],
    );
    let args = strs(&args);
    let v: serde_json::Value = serde_json::from_str(&ok(&args)).unwrap();
    assert_eq!(v["optimal"], true, "{v}");
    assert_eq!(v["targets"], 41);
    let length = v["length_m"].as_f64().unwrap();
    assert!((length - v["lower_bound_m"].as_f64().unwrap()).abs() < 1e-9);
    assert_eq!(v["positions"][0], serde_json::json!([1, 1]));
    // Every online strategy perceives the same cells with the same sensor, so none can be
    // shorter than the optimum over all position sequences; each stops at the same goal.
    for c in v["compare"].as_array().unwrap() {
        assert_eq!(c["end"], "goal reached", "{c}");
        assert_eq!(c["coverage"], 1.0, "{c}");
        let ratio = c["competitive_ratio"].as_f64().unwrap();
        assert!(ratio >= 1.0 - 1e-9, "{c}");
        assert!((ratio * length - c["length_m"].as_f64().unwrap()).abs() < 1e-9);
        assert_eq!(c["competitive_ratio_max"], c["competitive_ratio"], "{c}");
    }
    let again: serde_json::Value = serde_json::from_str(&ok(&args)).unwrap();
    assert_eq!(again["positions"], v["positions"]);
    assert_eq!(again["compare"], v["compare"]);
}

/// Regression: a time limit too large for a `Duration` (or for an `Instant` plus it)
/// panicked; it is no limit.
#[test]
fn optimal_time_limit_overflow_is_no_limit() {
    let dir = tempfile::tempdir().unwrap();
    for limit in ["1e19", "1e300"] {
        let args = optimal_on_two_rooms(dir.path(), &["--time-limit", limit, "--json"]);
        let v: serde_json::Value = serde_json::from_str(&ok(&strs(&args))).unwrap();
        assert_eq!(v["optimal"], true, "{limit}: {v}");
    }
}

/// Regression: `--compare cf,cf` ran cf twice and printed it twice, and an unknown preset
/// was named only after the optimal search. Both are refused before it.
#[test]
fn regression_optimal_compares_each_known_preset_once() {
    let dir = tempfile::tempdir().unwrap();
    let args = optimal_on_two_rooms(dir.path(), &["--compare", "cf,cf-rr,cf"]);
    let e = err(&strs(&args));
    assert!(
        e.contains("--compare: expected each preset once, found 'cf' twice"),
        "{e}"
    );
    let args = optimal_on_two_rooms(dir.path(), &["--compare", "cf,nearestt"]);
    assert!(err(&strs(&args)).contains("--compare: unknown strategy 'nearestt'"));
}

#[test]
fn optimal_stopped_early_reports_the_ratio_as_an_interval() {
    let dir = tempfile::tempdir().unwrap();
    let args = optimal_on_two_rooms(
        dir.path(),
        &[
            "--all-cells",
            "--heuristic",
            "zero",
            "--max-nodes",
            "3",
            "--compare",
            "cf",
        ],
    );
    let text = ok(&strs(&args));
    assert!(text.contains("optimal: false"), "{text}");
    assert!(
        text.contains("competitive ratio in [") && text.contains("(optimum not proven)"),
        "{text}"
    );
    let mut json_args = args.clone();
    json_args.push("--json".into());
    let v: serde_json::Value = serde_json::from_str(&ok(&strs(&json_args))).unwrap();
    assert_eq!(v["optimal"], false, "{v}");
    let c = &v["compare"][0];
    let (lo, hi) = (
        c["competitive_ratio"].as_f64().unwrap(),
        c["competitive_ratio_max"].as_f64().unwrap(),
    );
    // The ratio to the best path found is at most the ratio to the lower bound.
    assert!(lo < hi, "{c}");
    let online = c["length_m"].as_f64().unwrap();
    assert!(
        (online / v["lower_bound_m"].as_f64().unwrap() - hi).abs() < 1e-9,
        "{c}"
    );
    assert!(
        (online / v["upper_bound_m"].as_f64().unwrap() - lo).abs() < 1e-9,
        "{c}"
    );
}

#[test]
fn optimal_warns_when_coarsening_closes_the_doors() {
    let dir = tempfile::tempdir().unwrap();
    let out = frontier(&strs(&optimal_on_two_rooms(
        dir.path(),
        &["--cell-size", "2", "--json"],
    )));
    assert!(out.status.success());
    let e = String::from_utf8(out.stderr).unwrap();
    assert!(
        e.contains("warning: --cell-size 2: the coarse map reaches only"),
        "{e}"
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["coarse_kept_area"].as_f64().unwrap() < 0.5, "{v}");
    // The same map at full resolution keeps everything and does not warn.
    let out = frontier(&strs(&optimal_on_two_rooms(dir.path(), &[])));
    assert!(out.status.success());
    assert!(!String::from_utf8(out.stderr).unwrap().contains("warning"));
}

#[test]
fn optimal_flags_are_checked() {
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &["--goal", "1.5"],
            &["--goal: expected a coverage fraction in (0, 1], found 1.5"],
        ),
        (
            &["--sensor", "lidar:r=3"],
            &["--sensor", "los:r=R or footprint:r=R"],
        ),
        (
            &["--cell-size", "0"],
            &["--cell-size: expected a factor in 1..=64, found 0"],
        ),
        (
            &["--weight", "0.5"],
            &["--weight: expected a number ≥ 1, found 0.5"],
        ),
        (
            &["--coarse-incumbent", "1"],
            &["--coarse-incumbent: expected 0 (off) or a factor in 2..=64, found 1"],
        ),
    ];
    for (flags, wanted) in cases {
        let args: Vec<&str> = std::iter::once("optimal")
            .chain(flags.iter().copied())
            .collect();
        let e = err(&args);
        for w in wanted {
            assert!(e.contains(w), "{flags:?}: {e}");
        }
    }
}

/// Ctrl-C during a long optimal search stops it cleanly: the bounds and the best path found
/// are printed, and the exit status (130) says the search did not finish.
#[cfg(unix)]
#[test]
fn optimal_ctrl_c_stops_the_search_with_its_bounds() {
    let dir = tempfile::tempdir().unwrap();
    let map = open_map(dir.path(), 40);
    let child = Command::new(env!("CARGO_BIN_EXE_frontier"))
        .args([
            "optimal",
            "--map",
            map.to_str().unwrap(),
            "--resolution",
            "1",
        ])
        .args(["--sensor", "los:r=1.5c", "--json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run frontier");
    // The problem is set up in milliseconds; the search alone would run for hours.
    std::thread::sleep(std::time::Duration::from_secs(3));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(killed.success());
    let out = child.wait_with_output().expect("wait for frontier");
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["optimal"], false, "{v}");
    assert_eq!(v["stop"], "interrupt", "{v}");
    let (lo, hi) = (
        v["lower_bound_m"].as_f64().unwrap(),
        v["upper_bound_m"].as_f64().unwrap(),
    );
    assert!(0.0 < lo && lo <= hi, "{v}");
    assert!(
        v["positions"].as_array().is_some_and(|p| p.len() > 1),
        "{v}"
    );
}

/// Regression: an `optimal` search stopped by Ctrl-C reported its bounds and exited 0, so
/// scripts took an unfinished search for a result. It exits 130 (128 + SIGINT).
#[test]
fn interrupted_optimal_exits_non_zero() {
    let child = Command::new(env!("CARGO_BIN_EXE_frontier"))
        .args(["optimal", "--env", "cave", "--json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start frontier");
    // The search of the cave takes several seconds; its set-up well under one.
    std::thread::sleep(std::time::Duration::from_millis(2500));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill -INT");
    assert!(sent.success());
    let out = child.wait_with_output().expect("wait");
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value =
        serde_json::from_slice(&out.stdout).expect("the bounds found are still reported");
    assert_eq!(v["stop"], "interrupt", "{v}");
}

/// An open MovingAI map of `n` × `n` cells in `dir`.
fn open_map(dir: &Path, n: usize) -> std::path::PathBuf {
    let path = dir.join(format!("open{n}.map"));
    let rows = vec![".".repeat(n); n].join("\n");
    std::fs::write(
        &path,
        format!("type octile\nheight {n}\nwidth {n}\nmap\n{rows}\n"),
    )
    .unwrap();
    path
}

/// A tiny study named "tiny" (4 trials) with master seed `seed`, written into `dir` as
/// `tiny-SEED.toml`; returns the scenario file.
fn tiny_study(dir: &Path, seed: u64) -> std::path::PathBuf {
    let path = dir.join(format!("tiny-{seed}.toml"));
    std::fs::write(
        &path,
        format!(
            "name = \"tiny\"\nseed = {seed}\nrobots = [1]\nsensors = [\"los:r=3c\"]\n\
strategies = [\"cf\", \"random\"]\ntrials = 2\n\n[[env]]\nkind = \"maze\"\nseeds = [0]\n\
size = [6, 5]\nresolution = 0.5\n"
        ),
    )
    .unwrap();
    path
}

/// Regression: a map at the cell limit was accepted and `explore` aborted allocating its
/// candidate set; the run is refused up front with the memory it would need.
#[test]
fn huge_map_explore_is_refused_with_the_memory_it_needs() {
    let dir = tempfile::tempdir().unwrap();
    let map = open_map(dir.path(), 2000);
    let e = err(&[
        "explore",
        "--map",
        map.to_str().unwrap(),
        "--resolution",
        "0.05",
        "--robots",
        "5",
        "--strategy",
        "ha-cc",
        "--memory-mb",
        "100",
    ]);
    assert!(
        e.contains("exploring this 2000x2000 map with 5 robots (ha-cc)"),
        "{e}"
    );
    assert!(e.contains("needs about"), "{e}");
    assert!(e.contains("more than --memory-mb 100"), "{e}");
}

/// Regression: a 5 m line-of-sight sensor on 2 cm cells built a ray template of 1 GB at its
/// peak on a small map, counted by no estimate; the run is refused under a budget below the
/// template's bound, which the message names.
#[test]
fn fine_los_template_is_counted_in_the_memory_estimate() {
    let e = err(&[
        "explore",
        "--env",
        "cave",
        "--size",
        "4x4",
        "--resolution",
        "0.02",
        "--sensor",
        "los:r=5",
        "--memory-mb",
        "300",
    ]);
    assert!(e.contains("exploring this 200x200 map with 1 robot"), "{e}");
    assert!(e.contains("more than --memory-mb 300"), "{e}");
    assert!(
        e.contains("the los:r=5 sensor's ray template alone needs about"),
        "{e}"
    );
}

/// `segment` estimates its memory before segmenting, like every command that takes a map.
#[test]
fn huge_map_segment_is_refused_with_the_memory_it_needs() {
    let dir = tempfile::tempdir().unwrap();
    let map = open_map(dir.path(), 2000);
    let e = err(&[
        "segment",
        "--map",
        map.to_str().unwrap(),
        "--resolution",
        "0.05",
        "--memory-mb",
        "100",
    ]);
    assert!(e.contains("segmenting this 2000x2000 map"), "{e}");
    assert!(e.contains("needs about 200 MiB"), "{e}");
    assert!(e.contains("more than --memory-mb 100"), "{e}");
}

/// Regression: `optimal --memory-mb 64` on a 1200 × 1200 map spent 840 MB setting up and
/// then reported bounds after 0 expansions as a success; the set-up is estimated first and
/// the command names a `--cell-size` that fits.
#[test]
fn optimal_memory_mb_bounds_the_set_up() {
    let dir = tempfile::tempdir().unwrap();
    let map = open_map(dir.path(), 1200);
    let e = err(&[
        "optimal",
        "--map",
        map.to_str().unwrap(),
        "--resolution",
        "0.1",
        "--sensor",
        "los:r=0.5",
        "--memory-mb",
        "64",
    ]);
    assert!(
        e.contains("setting up the search of this 1200x1200 map"),
        "{e}"
    );
    assert!(e.contains("more than --memory-mb 64"), "{e}");
    assert!(e.contains("use --cell-size"), "{e}");
}

/// `bench --memory-mb` bounds a study as `explore --memory-mb` bounds a run: its
/// environments when they are made, and its largest trials, one per thread, before any
/// runs; a refused study leaves no database behind.
#[test]
fn bench_memory_mb_bounds_the_study_before_its_store_is_made() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("big.toml");
    std::fs::write(
        &scenario,
        "name = \"big\"\nrobots = [5]\nstrategies = [\"ha-cc\"]\n\n[[env]]\n\
         kind = \"office\"\nseeds = [0, 1]\nsize = [50, 50]\nresolution = 0.05\n",
    )
    .unwrap();
    let db = dir.path().join("big.sqlite");
    let run = |mb: &str| {
        err(&[
            "bench",
            scenario.to_str().unwrap(),
            "--db",
            db.to_str().unwrap(),
            "-j",
            "2",
            "--no-progress",
            "--memory-mb",
            mb,
        ])
    };
    // The environment is made within the budget; five robots with CC candidates on its
    // 1000 x 1000 cells are not.
    let e = run("100");
    assert!(e.contains("running 2 trials on 2 threads"), "{e}");
    assert!(e.contains("ha-cc"), "{e}");
    assert!(e.contains("more than --memory-mb 100"), "{e}");
    assert!(!db.exists(), "a refused study made {}", db.display());
    // Generating the environment alone needs more than 30 MiB.
    let e = run("30");
    assert!(e.contains("holding the study's 2 environment(s)"), "{e}");
    assert!(e.contains("more than --memory-mb 30"), "{e}");
    assert!(!db.exists(), "a refused study made {}", db.display());
}

/// Regression: `--memory-mb` bounded the run but not the loading of its map, which was
/// checked against the machine's memory only: a map whose loading needs more than the
/// budget was loaded (an 8000 x 8000 PGM under `--memory-mb 100`: 371 MiB) before the run
/// was refused. Every command that takes a map and `--memory-mb` now refuses it before
/// decoding, naming the flag.
#[test]
fn memory_mb_budget_applies_to_map_loading() {
    let dir = tempfile::tempdir().unwrap();
    // A header claiming 16384 x 16384 pixels and no pixels: the estimate (1281 MiB) refuses
    // it, not the missing pixels.
    let pgm = dir.path().join("claimed.pgm");
    std::fs::write(&pgm, b"P5\n16384 16384\n255\n").unwrap();
    let pgm = pgm.to_str().unwrap();
    let refusal = format!(
        "{pgm}: loading this 16384x16384 PGM image needs about 1281 MiB, more than --memory-mb 64"
    );
    for command in ["explore", "segment", "optimal"] {
        let e = err(&[
            command,
            "--map",
            pgm,
            "--resolution",
            "0.1",
            "--memory-mb",
            "64",
        ]);
        assert!(e.contains(&refusal), "{command}: {e}");
    }
    // map info's loading too (a regression: it checked the machine's memory only).
    let e = err(&[
        "map",
        "info",
        pgm,
        "--resolution",
        "0.1",
        "--memory-mb",
        "64",
    ]);
    assert!(e.contains(&refusal), "map info: {e}");
    // segment's ground truth and explore's off-plane clutter are loaded within it too.
    let small = dir.path().join("small.pgm");
    std::fs::write(
        &small,
        b"P5\n4 3\n255\n\xfe\xfe\xfe\xfe\xfe\x00\x00\xfe\xfe\xfe\xfe\xfe",
    )
    .unwrap();
    let small = small.to_str().unwrap();
    for (command, flag) in [("segment", "--truth"), ("explore", "--clutter-map")] {
        let e = err(&[
            command,
            "--map",
            small,
            flag,
            pgm,
            "--resolution",
            "0.1",
            "--memory-mb",
            "64",
        ]);
        assert!(e.contains(&refusal), "{command} {flag}: {e}");
    }
    // A generated environment's generation too.
    let e = err(&[
        "explore",
        "--env",
        "cave",
        "--size",
        "400x400",
        "--resolution",
        "0.05",
        "--memory-mb",
        "64",
    ]);
    assert!(e.contains("generating this cave of 64000000 cells"), "{e}");
    assert!(e.contains("more than --memory-mb 64"), "{e}");
}

/// Regression: a recording's map was loaded whatever the memory (only its cell count was
/// checked), so `explore --map run.mcap --memory-mb 8` loaded a 2000 x 2000 map before the
/// run was refused; it is refused from the message's header, naming the file, the topic,
/// the map's size, the bytes needed and the budget.
#[test]
fn mcap_map_larger_than_the_budget_is_refused_before_loading() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("run.mcap");
    let map = grid::io::parse_ascii(&vec![".".repeat(2000); 2000].join("\n"), 0.05).unwrap();
    let mut run = record::RunWriter::new(std::fs::File::create(&rec).unwrap()).unwrap();
    run.map(0.0, &map).unwrap();
    run.finish().unwrap();
    drop(map);
    let rec = rec.to_str().unwrap();
    let e = err(&["explore", "--map", rec, "--memory-mb", "8"]);
    assert!(
        e.contains(&format!(
            "{rec}: topic /map, message at 0 ns: loading this 2000x2000 OccupancyGrid needs about \
             12 MiB, more than --memory-mb 8; record the map with fewer, larger cells"
        )),
        "{e}"
    );
    // map info refuses it within the budget the same way.
    let e = err(&["map", "info", rec, "--memory-mb", "8"]);
    assert!(
        e.contains(&format!(
            "{rec}: topic /map, message at 0 ns: loading this 2000x2000 OccupancyGrid needs about \
             12 MiB, more than --memory-mb 8"
        )),
        "{e}"
    );
    // Without a budget the machine's memory is the limit, and the map loads.
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", rec, "--json"])).unwrap();
    assert_eq!(info["width"], 2000);
    // And within a budget that holds it.
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", rec, "--json", "--memory-mb", "64"])).unwrap();
    assert_eq!(info["width"], 2000);
}

/// Regression: `--sensor laser-limited-sonar` on the default office (0.5 m cells) ended
/// after 1 move at 1.4 % coverage as if explored; sonar on cells coarser than 0.1 m is
/// refused, saying the resolution it needs, and the message is not repeated.
#[test]
fn sonar_on_coarse_cells_is_refused_naming_the_resolution() {
    for sensor in ["sonar", "laser-limited-sonar"] {
        let e = err(&["explore", "--sensor", sensor]);
        assert!(e.contains("sonar on 0.5 m cells"), "{e}");
        assert!(e.contains("--resolution 0.1 or finer"), "{e}");
        assert_eq!(
            e.matches("expected cells of at most 0.1 m").count(),
            1,
            "{e}"
        );
    }
    let v: serde_json::Value = serde_json::from_str(&ok(&[
        "explore",
        "--env",
        "office",
        "--size",
        "12x10",
        "--resolution",
        "0.1",
        "--sensor",
        "sonar",
        "--json",
        "--no-timing",
    ]))
    .unwrap();
    assert!(v["coverage"].as_f64().unwrap() > 0.9, "{v}");
}

/// Run shard `shard` (e.g. "1/2") of `scenario` into `db`.
fn bench_shard(scenario: &Path, db: &Path, shard: &str) {
    ok(&[
        "bench",
        scenario.to_str().unwrap(),
        "--db",
        db.to_str().unwrap(),
        "--shard",
        shard,
        "-j",
        "1",
        "--no-progress",
    ]);
}

/// Every file in `dir` with its length and a hash of its bytes (FNV-1a).
fn snapshot(dir: &Path) -> std::collections::BTreeMap<std::path::PathBuf, (usize, u64)> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            let bytes = std::fs::read(&p).unwrap();
            let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
                (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
            });
            (p, (bytes.len(), hash))
        })
        .collect()
}

/// Regression: `bench merge` opened its inputs for writing, so an empty input file became a
/// database and stamped the output with an empty study name (poisoning later merges). Inputs
/// are now opened read-only and checked before anything is written.
#[test]
fn merge_leaves_inputs_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let inputs = dir.path().join("in");
    std::fs::create_dir(&inputs).unwrap();
    let study = tiny_study(dir.path(), 7);
    let (s1, s2) = (inputs.join("s1.sqlite"), inputs.join("s2.sqlite"));
    bench_shard(&study, &s1, "1/2");
    bench_shard(&study, &s2, "2/2");
    let empty = inputs.join("empty.sqlite");
    std::fs::write(&empty, b"").unwrap();
    let before = snapshot(&inputs);
    let out = dir.path().join("all.sqlite");
    let (o, a, b, e) = (
        out.to_str().unwrap(),
        s1.to_str().unwrap(),
        s2.to_str().unwrap(),
        empty.to_str().unwrap(),
    );
    let msg = err(&["bench", "merge", o, a, e, b]);
    assert!(msg.contains(e), "{msg}");
    assert!(msg.contains("not a frontier results database"), "{msg}");
    assert_eq!(
        snapshot(&inputs),
        before,
        "a refused merge changed its inputs"
    );
    assert!(!out.exists(), "a refused merge wrote {o}");
    // Without the empty file the merge succeeds, still without touching its inputs.
    let merged = ok(&["bench", "merge", o, a, b]);
    assert!(merged.contains("4 new trial(s), 4 in all"), "{merged}");
    assert_eq!(snapshot(&inputs), before, "a merge changed its inputs");
    assert_eq!(bench_rows(&out).len(), 4);
}

/// Regression: when a later input of `bench merge` was refused (another study), the rows of
/// the earlier inputs stayed in the output. The merge is now all or nothing.
#[test]
fn merge_refusing_a_later_input_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (tiny, other) = (tiny_study(dir.path(), 7), tiny_study(dir.path(), 8));
    let (s1, s2, x) = (
        dir.path().join("s1.sqlite"),
        dir.path().join("s2.sqlite"),
        dir.path().join("x.sqlite"),
    );
    bench_shard(&tiny, &s1, "1/2");
    bench_shard(&tiny, &s2, "2/2");
    bench_shard(&other, &x, "1/2");
    let out = dir.path().join("all.sqlite");
    let (o, a, b, c) = (
        out.to_str().unwrap(),
        s1.to_str().unwrap(),
        s2.to_str().unwrap(),
        x.to_str().unwrap(),
    );
    let msg = err(&["bench", "merge", o, a, c]);
    assert!(msg.contains(c) && msg.contains("fingerprint"), "{msg}");
    assert!(!out.exists(), "a refused merge wrote {o}");
    // Into an existing output: the refused merge leaves it as it was.
    ok(&["bench", "merge", o, a]);
    let kept = bench_rows(&out);
    assert_eq!(kept.len(), 2);
    let msg = err(&["bench", "merge", o, b, c]);
    assert!(msg.contains(c), "{msg}");
    assert_eq!(bench_rows(&out), kept, "a refused merge changed the output");
}

/// Regression: `bench merge OUT present.sqlite missing.sqlite` failed on the missing input
/// but left OUT behind, holding the first input's trials.
#[test]
fn merge_with_a_missing_input_leaves_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let study = tiny_study(dir.path(), 7);
    let s1 = dir.path().join("s1.sqlite");
    bench_shard(&study, &s1, "1/2");
    let out = dir.path().join("all.sqlite");
    let missing = dir.path().join("s2.sqlite");
    let m = missing.to_str().unwrap();
    let msg = err(&[
        "bench",
        "merge",
        out.to_str().unwrap(),
        s1.to_str().unwrap(),
        m,
    ]);
    assert!(msg.contains(m), "{msg}");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with("all"))
        .collect();
    assert!(left.is_empty(), "a failed merge left {left:?}");
}

/// Run `frontier args` as a user who cannot write `db` or its directory: the file and the
/// directory lose their write bits, and when the tests run as root (who writes anyway) the
/// command runs as `nobody`. Returns the output; `writable` is a directory the user can
/// write its results into.
#[cfg(unix)]
fn frontier_on_a_read_only_database(db: &Path, writable: &Path, args: &[&str]) -> Output {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    use std::os::unix::process::CommandExt;
    let parent = db.parent().unwrap();
    let mode = |p: &Path, m: u32| std::fs::set_permissions(p, std::fs::Permissions::from_mode(m));
    mode(db, 0o444).unwrap();
    mode(parent, 0o555).unwrap();
    mode(writable, 0o777).unwrap();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_frontier"));
    cmd.args(args);
    if std::fs::metadata(writable).unwrap().uid() == 0 {
        cmd.uid(65534).gid(65534);
    }
    let out = cmd.output().expect("run frontier");
    mode(parent, 0o755).unwrap();
    out
}

/// A finished tiny study `ro/tiny.sqlite` under `dir`, and an empty `out` folder beside
/// it: (ro, out, db).
#[cfg(unix)]
fn finished_study_in_ro(
    dir: &Path,
) -> (std::path::PathBuf, std::path::PathBuf, std::path::PathBuf) {
    study_in_ro(dir, "1/1")
}

/// The tiny study's `shard` run into `ro/tiny.sqlite` under `dir`, and an empty `out`
/// folder beside it: (ro, out, db).
#[cfg(unix)]
fn study_in_ro(
    dir: &Path,
    shard: &str,
) -> (std::path::PathBuf, std::path::PathBuf, std::path::PathBuf) {
    let ro = dir.join("ro");
    let out = dir.join("out");
    std::fs::create_dir(&ro).unwrap();
    std::fs::create_dir(&out).unwrap();
    let study = tiny_study(dir, 7);
    let db = ro.join("tiny.sqlite");
    bench_shard(&study, &db, shard);
    (ro, out, db)
}

/// Regression: `bench export` opened the database for writing, so it failed on a database
/// the user may only read (a finished study on a shared, read-only file system).
#[cfg(unix)]
#[test]
fn export_reads_a_read_only_database() {
    let dir = tempfile::tempdir().unwrap();
    let (ro, out, db) = finished_study_in_ro(dir.path());
    let before = snapshot(&ro);
    let csv = out.join("tiny.csv");
    let args = [
        "bench",
        "export",
        db.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
    ];
    let o = frontier_on_a_read_only_database(&db, &out, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 5);
    assert_eq!(
        snapshot(&ro),
        before,
        "export changed the database's directory"
    );
}

/// Regression: `bench report` opened the database for writing, so it failed on a database
/// the user may only read.
#[cfg(unix)]
#[test]
fn report_reads_a_read_only_database() {
    let dir = tempfile::tempdir().unwrap();
    let (ro, out, db) = finished_study_in_ro(dir.path());
    let before = snapshot(&ro);
    let report = out.join("report");
    let args = [
        "bench",
        "report",
        db.to_str().unwrap(),
        "--out",
        report.to_str().unwrap(),
    ];
    let o = frontier_on_a_read_only_database(&db, &out, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(report.join("report.html").exists());
    assert_eq!(
        snapshot(&ro),
        before,
        "report changed the database's directory"
    );
}

/// Regression: re-running a finished study to regenerate its report (`bench STUDY --db
/// FILE --report DIR`) from a store the user may only read (a shared folder, a read-only
/// mount) failed: the run opened the store for writing though no trial was left, and said
/// it "cannot be written by this user". It finds every trial done, reports, and leaves the
/// store's folder byte for byte as it was, with no `-wal` or `-shm` file beside the store;
/// an edited scenario is still refused as before.
#[cfg(unix)]
#[test]
fn finished_study_reruns_from_a_read_only_store() {
    let dir = tempfile::tempdir().unwrap();
    let (ro, out, db) = finished_study_in_ro(dir.path());
    let before = snapshot(&ro);
    let study = tiny_study(dir.path(), 7);
    let report = out.join("report");
    let (s, d) = (study.to_str().unwrap(), db.to_str().unwrap());
    let args = [
        "bench",
        s,
        "--db",
        d,
        "-j",
        "1",
        "--no-progress",
        "--report",
        report.to_str().unwrap(),
    ];
    let o = frontier_on_a_read_only_database(&db, &out, &args);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{e}");
    assert!(e.contains("4 of 4 trials done before, 0 run now"), "{e}");
    assert!(report.join("report.md").exists() && report.join("report.html").exists());
    for suffix in ["-wal", "-shm", "-journal"] {
        let beside = ro.join(format!("tiny.sqlite{suffix}"));
        assert!(!beside.exists(), "the re-run left {}", beside.display());
    }
    assert_eq!(
        snapshot(&ro),
        before,
        "the re-run changed the store's folder"
    );
    // A scenario edited since (a start fixed) is refused from the read-only store too.
    let edited = dir.path().join("edited.toml");
    let text = std::fs::read_to_string(&study).unwrap();
    std::fs::write(
        &edited,
        text.replace("resolution = 0.5", "resolution = 0.5\nstart = [1, 1]"),
    )
    .unwrap();
    let args = [
        "bench",
        edited.to_str().unwrap(),
        "--db",
        d,
        "-j",
        "1",
        "--no-progress",
    ];
    let o = frontier_on_a_read_only_database(&db, &out, &args);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "the edited study should be refused");
    let want = format!(
        "{d}: holds trial maze-s0-6x5m-r0.5|cf|los:r=3c|m=1|start=0|trial=0 run with starts \
         [[3,7]], but {} now runs it with starts [[1,1]]: the study changed since these \
         results were stored",
        edited.display()
    );
    assert!(e.contains(&want), "{e}");
    assert_eq!(
        snapshot(&ro),
        before,
        "the refused run changed the store's folder"
    );
}

/// Regression: a study run, resumed or merged into a folder the user may not write failed
/// with SQLite's "unable to open database file" or "attempt to write a readonly database",
/// which did not say what was wrong. It says which file or folder must be writable, and
/// the store is left as it was. (The store holds half the study, so the run has trials
/// to write.)
#[cfg(unix)]
#[test]
fn regression_bench_into_a_read_only_folder_says_what_must_be_writable() {
    let dir = tempfile::tempdir().unwrap();
    let (ro, out, db) = study_in_ro(dir.path(), "1/2");
    let before = snapshot(&ro);
    let study = tiny_study(dir.path(), 7);
    let (s, d, r) = (
        study.to_str().unwrap(),
        db.to_str().unwrap(),
        ro.to_str().unwrap(),
    );
    let new = ro.join("new.sqlite");
    let n = new.to_str().unwrap();
    // The study's other half, to merge into the read-only store.
    let other = out.join("other.sqlite");
    bench_shard(&study, &other, "2/2");
    let o2 = other.to_str().unwrap();
    let cases: [(&[&str], String); 3] = [
        (
            &["bench", s, "--db", d, "-j", "1", "--no-progress"],
            format!(
                "{d}: cannot be written by this user: a run or merge writes into it and keeps \
                 SQLite's -wal and -shm files beside it, so expected the file and its folder \
                 {r} to be writable"
            ),
        ),
        (
            &["bench", s, "--db", n, "-j", "1", "--no-progress"],
            format!(
                "{n}: cannot be created by this user: expected a folder ({r}) this user may write"
            ),
        ),
        (
            &["bench", "merge", d, o2],
            format!("{d}: cannot be written by this user"),
        ),
    ];
    for (args, want) in cases {
        let o = frontier_on_a_read_only_database(&db, &out, args);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(e.contains(&want), "{args:?}: {e}");
        assert_eq!(snapshot(&ro), before, "{args:?} changed the store's folder");
    }
}

/// Regression: `bench STUDY --db notes.db`, naming another program's SQLite database by
/// mistake, gave it frontier's tables and switched it to WAL mode before (or instead of)
/// refusing it, and `export`, `report` and `merge` left `-wal` and `-shm` files beside it.
/// Every bench command refuses it, saying what it holds, and leaves its folder as it was;
/// a file that is not SQLite at all is named by what it starts with.
#[test]
fn regression_bench_refuses_a_foreign_database_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let study = tiny_study(dir.path(), 7);
    let good = dir.path().join("good.sqlite");
    bench_shard(&study, &good, "1/1");
    let theirs = dir.path().join("theirs");
    std::fs::create_dir(&theirs).unwrap();
    let notes = theirs.join("notes.db");
    let conn = rusqlite::Connection::open(&notes).unwrap();
    conn.query_row("PRAGMA journal_mode=WAL", [], |_| Ok(()))
        .unwrap();
    conn.execute_batch(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
         CREATE TABLE notes (body TEXT); INSERT INTO notes VALUES ('buy milk');",
    )
    .unwrap();
    drop(conn);
    let csv = theirs.join("all.csv");
    std::fs::write(&csv, "key,scenario,env\n").unwrap();
    let before = snapshot(&theirs);
    let (s, g) = (study.to_str().unwrap(), good.to_str().unwrap());
    let out = dir.path().join("out");
    let o = out.to_str().unwrap();
    for (db, found) in [
        (
            &notes,
            "is not a frontier results database (it has the tables meta, notes, not frontier's \
             (meta, envs, trials, optimal)); give another file",
        ),
        (
            &csv,
            "is not an SQLite database (it starts with \"key,scenario,env\"); expected a \
             frontier results database",
        ),
    ] {
        let d = db.to_str().unwrap();
        let merged = format!("{o}.sqlite");
        let commands: [&[&str]; 6] = [
            &["bench", s, "--db", d, "-j", "1", "--no-progress"],
            &["bench", "export", d, "--csv", &format!("{o}.csv")],
            &["bench", "report", d, "--out", o],
            &["bench", "merge", &merged, g, d],
            &["bench", "merge", d, g],
            &["bench", "merge", d, d],
        ];
        for args in commands {
            let e = err(args);
            assert!(e.contains(&format!("{d}: {found}")), "{args:?}: {e}");
            assert!(!e.contains("panicked"), "{args:?}: {e}");
            assert_eq!(snapshot(&theirs), before, "{args:?} changed {d}");
        }
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.starts_with("out"))
            .collect();
        assert!(left.is_empty(), "a refused command wrote {left:?}");
    }
}

#[test]
fn a_run_recorded_as_mcap_is_a_map_again() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("run.mcap");
    let rec_s = rec.to_str().unwrap();
    let base = [
        "--env",
        "office",
        "--size",
        "15x12",
        "--resolution",
        "0.25",
        "--seed",
        "3",
    ];
    let mut args = vec!["explore", "--mcap", rec_s, "--json", "--no-timing"];
    args.extend(base);
    ok(&args);
    // The recording's /map is the generated office; exploring it again gives the same run.
    let mut direct = vec!["explore", "--json", "--no-timing"];
    direct.extend(base);
    let again = ok(&[
        "explore",
        "--map",
        rec_s,
        "--json",
        "--no-timing",
        "--seed",
        "3",
    ]);
    let a: serde_json::Value = serde_json::from_str(&ok(&direct)).unwrap();
    let b: serde_json::Value = serde_json::from_str(&again).unwrap();
    for k in [
        "width",
        "height",
        "resolution",
        "path_length_m",
        "coverage",
        "decisions",
    ] {
        assert_eq!(a[k], b[k], "{k}");
    }
    // The last belief is a map too, and `map info` reads either topic.
    ok(&["explore", "--map", rec_s, "--topic", "/frontier/belief"]);
    let info = |topic: &str| -> serde_json::Value {
        serde_json::from_str(&ok(&["map", "info", rec_s, "--topic", topic, "--json"])).unwrap()
    };
    assert_eq!(info("/map")["width"], a["width"]);
    assert_eq!(info("/frontier/belief")["height"], a["height"]);
    // It says which topic it read: the one asked for (by its name without the slash too),
    // or, among several grid topics, /map.
    assert_eq!(info("/frontier/belief")["topic"], "/frontier/belief");
    assert_eq!(info("map")["topic"], "/map");
    let chosen: serde_json::Value =
        serde_json::from_str(&ok(&["map", "info", rec_s, "--json"])).unwrap();
    assert_eq!(chosen["topic"], "/map");
    let text = ok(&["map", "info", rec_s]);
    assert!(text.contains("topic       /map (its last map)"), "{text}");
    let e = err(&[
        "explore",
        "--map",
        rec_s,
        "--topic",
        "/frontier/robot0/pose",
    ]);
    assert!(e.contains("expected nav_msgs/msg/OccupancyGrid"), "{e}");
    let e = err(&["explore", "--env", "office", "--topic", "/map"]);
    assert!(e.contains("--topic"), "{e}");
    let bad = dir.path().join("bad.mcap");
    std::fs::write(&bad, b"not a recording").unwrap();
    let e = err(&["explore", "--map", bad.to_str().unwrap()]);
    assert!(e.contains("bad.mcap: expected an MCAP file"), "{e}");
}

#[test]
fn a_dungeon_png_gives_its_marked_start() {
    // A 12 x 8 room: walls (0) around free space (255), a start blob (208) of two pixels.
    let (w, h) = (12u32, 8u32);
    let mut pixels = vec![255u8; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            if x == 0 || y == 0 || x == w - 1 || y == h - 1 {
                pixels[(y * w + x) as usize] = 0;
            }
        }
    }
    pixels[(3 * w + 4) as usize] = 208;
    pixels[(3 * w + 5) as usize] = 208;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dungeon.png");
    let bytes = grid::io::png::encode_grey(&pixels, w, h).unwrap();
    std::fs::write(&path, bytes).unwrap();
    let p = path.to_str().unwrap();
    let out = ok(&[
        "explore",
        "--map",
        p,
        "--dungeon",
        "--resolution",
        "0.1",
        "--json",
        "--no-timing",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["starts"],
        serde_json::json!([[5, 3]]),
        "the middle of the blob"
    );
    assert_eq!(v["coverage"], 1.0);
    // `map info` reads it too and shows the mark.
    let info: serde_json::Value = serde_json::from_str(&ok(&[
        "map",
        "info",
        p,
        "--dungeon",
        "--resolution",
        "0.1",
        "--json",
    ]))
    .unwrap();
    assert_eq!(info["start"], serde_json::json!([5, 3]));
    assert_eq!(info["free"], 60);
    // Regression: `optimal` started at the free cell nearest the centre, not the mark.
    let opt: serde_json::Value = serde_json::from_str(&ok(&[
        "optimal",
        "--map",
        p,
        "--dungeon",
        "--resolution",
        "0.1",
        "--sensor",
        "los:r=2c",
        "--max-nodes",
        "100",
        "--json",
        "--no-timing",
    ]))
    .unwrap();
    assert_eq!(opt["start"], serde_json::json!([5, 3]), "{opt}");
    // --border walls it (a regression: it was ignored), and the start moves with the cells.
    let info: serde_json::Value = serde_json::from_str(&ok(&[
        "map",
        "info",
        p,
        "--dungeon",
        "--border",
        "--resolution",
        "0.1",
        "--json",
    ]))
    .unwrap();
    assert_eq!((&info["width"], &info["height"]), (&14.into(), &10.into()));
    assert_eq!(info["start"], serde_json::json!([6, 4]));
    assert_eq!((&info["free"], &info["occupied"]), (&60.into(), &80.into()));
    // Regression: a marked start the robot does not fit in was refused as "--start 5,3",
    // a flag the user never gave.
    let e = err(&[
        "explore",
        "--map",
        p,
        "--dungeon",
        "--resolution",
        "0.1",
        "--clearance",
        "0.35",
    ]);
    assert!(
        e.contains("the start the map marks, 5,3: the cell is free but closer to an obstacle")
            && !e.contains("--start"),
        "{e}"
    );
    // Without a marker: an error naming the file.
    pixels[(3 * w + 4) as usize] = 255;
    pixels[(3 * w + 5) as usize] = 255;
    let bytes = grid::io::png::encode_grey(&pixels, w, h).unwrap();
    std::fs::write(&path, bytes).unwrap();
    let msg = err(&["explore", "--map", p, "--dungeon", "--resolution", "0.1"]);
    assert!(msg.contains("dungeon.png") && msg.contains("208"), "{msg}");
}

#[test]
fn a_houseexpo_plan_is_explored() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("house.json");
    std::fs::write(
        &path,
        r#"{"id": "h", "verts": [[0,0],[6,0],[6,3],[3,3],[3,6],[0,6]],
           "room_category": {"living_room": [[0,0,6,3]], "bedroom": [[0,3,3,6]]}}"#,
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let out = ok(&[
        "explore",
        "--map",
        p,
        "--resolution",
        "0.1",
        "--json",
        "--no-timing",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["coverage"], 1.0);
    assert_eq!(v["width"], 62);
    let msg = err(&["explore", "--map", p]);
    assert!(
        msg.contains("house.json") && msg.contains("resolution"),
        "{msg}"
    );
}

/// `--trials 1` runs one trial per start variant, with the keys and seeds of the whole
/// study: running the study later into the same database adds only the rest, and ends
/// with exactly the rows of a run of the whole study.
#[test]
fn bench_first_trials_then_the_rest_equals_the_whole_study() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("study.toml");
    std::fs::write(
        &scenario,
        r#"
name = "first"
seed = 3
robots = [2]
sensors = ["los:r=4c"]
strategies = ["random", "cf"]
trials = 3
perturbations = 2
radius = 1.0

[[env]]
kind = "office"
seeds = [1]
size = [16, 12]
resolution = 0.5
"#,
    )
    .unwrap();
    let s = scenario.to_str().unwrap();
    let db = dir.path().join("first.sqlite");
    let d = db.to_str().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["bench", s, "--db", d, "-j", "1", "--no-progress"];
        args.extend_from_slice(extra);
        frontier(&args)
    };
    let out = run(&["--trials", "1"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let first = bench_rows(&db);
    // `random` is stochastic (3 trials per start), `cf` is not (1): one of each per start.
    let mut keys: Vec<&str> = first.iter().map(|r| r.key.as_str()).collect();
    keys.sort_unstable();
    assert_eq!(keys.len(), 4, "{keys:?}");
    assert!(keys.iter().all(|k| k.ends_with("trial=0")), "{keys:?}");
    let out = run(&[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("4 of 8 trials done before"), "{stderr}");
    let whole = dir.path().join("whole.sqlite");
    ok(&[
        "bench",
        s,
        "--db",
        whole.to_str().unwrap(),
        "-j",
        "2",
        "--no-progress",
    ]);
    assert_eq!(bench_rows(&db), bench_rows(&whole));
    // Regression: a shard of the first trials said "shard 1/2 of 4 trials" for a share of
    // the whole study's 8, so its count read as a wrong share of 4.
    let out = frontier(&["bench", s, "--dry-run", "--trials", "1", "--shard", "1/2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("variants, shard 1/2 of the study's 8 trials, within the 4 of --trials 1)"),
        "{stderr}"
    );
    // Zero trials is a mistake, not an empty study.
    let msg = err(&["bench", s, "--db", d, "--trials", "0"]);
    assert!(msg.contains("--trials: expected at least 1"), "{msg}");
}

/// Regression: `frontier ... | head` panicked in `println!` ("failed printing to stdout:
/// Broken pipe") with a backtrace once the reader had gone.
#[cfg(unix)]
#[test]
fn regression_closed_stdout_pipe_ends_quietly() {
    use std::os::fd::FromRawFd;
    use std::os::unix::process::ExitStatusExt;
    use std::process::Stdio;
    // A pipe whose read end is closed before the run starts: its first write to stdout
    // meets no reader. (Closing the read end after spawning raced the run: a short
    // output fits in the pipe's buffer, and a run that printed it first ended well.)
    let mut ends = [0; 2];
    // SAFETY: `pipe` writes two new descriptors into `ends`.
    assert_eq!(unsafe { libc::pipe(ends.as_mut_ptr()) }, 0, "pipe");
    // SAFETY: both descriptors are ours and each is owned once.
    let (read_end, write_end) = unsafe {
        (
            std::fs::File::from_raw_fd(ends[0]),
            std::fs::File::from_raw_fd(ends[1]),
        )
    };
    drop(read_end);
    let child = Command::new(env!("CARGO_BIN_EXE_frontier"))
        .args(["explore", "--env", "office", "--seed", "1", "--json"])
        .stdout(Stdio::from(write_end))
        .stderr(Stdio::piped())
        .spawn()
        .expect("run frontier");
    let out = child.wait_with_output().expect("wait for frontier");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(
        out.status.signal(),
        Some(13),
        "ended by SIGPIPE: {:?}",
        out.status
    );
}

/// Regression: with `--coverage known` the summary said "coverage 98.95 % of 1525
/// reachable cells", the denominator of the other coverage.
#[test]
fn regression_coverage_known_summary_names_what_it_counts() {
    let out = ok(&["explore", "--env", "office", "--coverage", "known"]);
    assert!(
        out.contains("of the cells the map knows (--coverage known)"),
        "{out}"
    );
    assert!(!out.contains("reachable cells"), "{out}");
}

/// Regression: `--border`, `--dungeon` and `--env-seed` were silently ignored where they do
/// not apply.
#[test]
fn regression_map_flags_that_do_not_apply_are_refused() {
    let e = err(&["explore", "--env", "office", "--border"]);
    assert!(
        e.contains("--border adds a wall around a --map, not to --env"),
        "{e}"
    );
    let e = err(&["explore", "--env", "office", "--dungeon"]);
    assert!(e.contains("--dungeon reads --map as a dungeon PNG"), "{e}");
    let dir = tempfile::tempdir().expect("temp dir");
    let yaml = dir.path().join("o.yaml");
    let y = yaml.to_str().expect("utf-8 path");
    ok(&["env", "office", "--size", "12x10", "--out", y]);
    let e = err(&["explore", "--map", y, "--env-seed", "3"]);
    assert!(
        e.contains("--env-seed applies to generated environments"),
        "{e}"
    );
}

/// Regression: `demo --seeds 4294967296` generated environments until the memory was gone,
/// and `demo --sensor sonar` blamed a `--belief` flag demo does not have.
#[test]
fn regression_demo_refuses_what_it_cannot_run() {
    let e = err(&["demo", "--seeds", "4294967296"]);
    assert!(e.contains("--seeds: expected 1 to 1000"), "{e}");
    let e = err(&["sensors", "--seeds", "100000"]);
    assert!(e.contains("--seeds: expected 1 to 1000"), "{e}");
    let e = err(&["demo", "--seeds", "1", "--sensor", "sonar"]);
    assert!(e.contains("--sensor: expected a range sensor"), "{e}");
}

/// Regression: output paths were tried only after the run (`--out` naming a file failed
/// with "File exists" once the exploration was done).
#[test]
fn regression_output_paths_are_checked_before_the_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("afile");
    std::fs::write(&file, b"x").expect("write");
    let f = file.to_str().expect("utf-8 path");
    let e = err(&["explore", "--env", "office", "--out", f]);
    assert!(e.contains("expected a folder, found a file"), "{e}");
    let e = err(&["optimal", "--env", "office", "--size", "6x5", "--out", f]);
    assert!(e.contains("expected a folder, found a file"), "{e}");
    let gif = dir.path().join("no-such-folder").join("run.gif");
    let e = err(&[
        "explore",
        "--env",
        "office",
        "--gif",
        gif.to_str().expect("utf-8"),
    ]);
    assert!(
        e.contains("--gif") && e.contains("expected a file in an existing folder"),
        "{e}"
    );
    // Regression: a file in a folder that exists but takes no new file (/proc) was written
    // only after the whole run, and the error did not name the flag.
    // (Linux's /proc: a folder no one, not even root, can add a file to.)
    let proc_fs = std::path::Path::new("/proc/self").exists();
    for (flag, ext) in [("--gif", "gif"), ("--html", "html"), ("--mcap", "mcap")]
        .into_iter()
        .filter(|_| proc_fs)
    {
        let file = format!("/proc/frontier-test.{ext}");
        let e = err(&["explore", "--env", "office", flag, &file]);
        assert!(
            e.contains(&format!(
                "{flag} {file}: expected a file that can be written"
            )),
            "{e}"
        );
    }
    // A file that exists is left as it is by the check; a new one is not left behind.
    let kept = dir.path().join("kept.gif");
    std::fs::write(&kept, b"old").expect("write");
    let e = err(&[
        "explore",
        "--env",
        "castle",
        "--gif",
        kept.to_str().expect("utf-8"),
    ]);
    assert!(e.contains("castle"), "{e}");
    assert_eq!(std::fs::read(&kept).expect("read"), b"old");
    let new = dir.path().join("new.gif");
    let e = err(&[
        "explore",
        "--env",
        "castle",
        "--gif",
        new.to_str().expect("utf-8"),
    ]);
    assert!(e.contains("castle"), "{e}");
    assert!(!new.exists(), "the check left {}", new.display());
    // Regression: one file named by two outputs kept only the one written last.
    let same = dir.path().join("same.gif");
    let same = same.to_str().expect("utf-8");
    let e = err(&["explore", "--env", "office", "--gif", same, "--html", same]);
    assert!(
        e.contains(&format!(
            "--html {same}: expected a file of its own, found the file --gif writes ({same})"
        )),
        "{e}"
    );
    let d = dir.path().to_str().expect("utf-8 path");
    let e = err(&["explore", "--env", "office", "--html", d]);
    assert!(e.contains("expected a file name, found a folder"), "{e}");
    // `segment --out` and `bench export --csv` ended in "Is a directory (os error 21)".
    let e = err(&["segment", "--env", "office", "--out", d]);
    assert!(
        e.contains("--out") && e.contains("expected a file name, found a folder"),
        "{e}"
    );
    let e = err(&["env", "office", "--out", d]);
    assert!(
        e.contains("--out") && e.contains("expected a file name, found a folder"),
        "{e}"
    );
    let e = err(&["bench", "export", "--csv", d, "any.sqlite"]);
    assert!(
        e.contains("--csv") && e.contains("expected a file name, found a folder"),
        "{e}"
    );
}

/// Regression: `bench export --csv ok.sqlite ok.sqlite` overwrote the results database with
/// CSV and exited 0; `bench report --out DIR` did the same to a database named `report.md`
/// in DIR. Both are refused, and the database is left as it was.
#[test]
fn regression_bench_export_onto_its_own_database_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = tiny_study(dir.path(), 1);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).expect("mkdir");
    let db = out.join("report.md");
    let d = db.to_str().expect("utf-8 path");
    let s = study.to_str().expect("utf-8 path");
    ok(&[
        "bench",
        s,
        "--db",
        d,
        "--trials",
        "1",
        "-j",
        "1",
        "--no-progress",
    ]);
    let before = std::fs::read(&db).expect("read the database");
    let e = err(&["bench", "export", "--csv", d, d]);
    assert!(
        e.contains(&format!("{d}: is the results database being read")),
        "{e}"
    );
    let e = err(&[
        "bench",
        "report",
        d,
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(
        e.contains(&format!("{d}: is the results database being read")),
        "{e}"
    );
    assert_eq!(std::fs::read(&db).expect("read the database"), before);
    assert!(!out.join("report.html").exists());
    assert_eq!(bench_rows(&db).len(), 2);
}

/// Regression: `bench /dev/zero --dry-run` read the "scenario" until memory ran out, and a
/// sonar on 0.5 m cells passed `--dry-run` before every trial failed when run. Both are
/// refused before anything runs, naming the file (and the line and key).
#[test]
fn regression_bench_dry_run_refuses_what_cannot_run() {
    #[cfg(unix)]
    {
        let e = err(&["bench", "/dev/zero", "--dry-run"]);
        assert!(e.contains("/dev/zero: expected a scenario file"), "{e}");
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let study = dir.path().join("sonar.toml");
    std::fs::write(
        &study,
        "strategies = [\"cf\"]\nsensors = [\"sonar\"]\n\n[[env]]\nkind = \"office\"\n\
         resolution = 0.5\n",
    )
    .expect("write the scenario");
    let e = err(&["bench", study.to_str().expect("utf-8 path"), "--dry-run"]);
    assert!(e.contains("sonar.toml:2: key `sensors[0]`"), "{e}");
    assert!(e.contains("at most 0.1 m"), "{e}");
}

/// Regression: `bench FILE --dry-run --shard 2/2` printed the whole study's trial count
/// ("1 trials") while the shard runs none; it prints the count the shard runs.
#[test]
fn regression_bench_dry_run_counts_the_shards_trials() {
    let dir = tempfile::tempdir().expect("temp dir");
    let study = tiny_study(dir.path(), 1);
    let s = study.to_str().expect("utf-8 path");
    // 4 trials: cf and random, 2 each from random starts; shard 3/3 holds trial 2 only.
    for (shard, line) in [
        (
            "3/3",
            "tiny: 1 trials (1 environments, 2 variants, shard 3/3 of 4 trials)",
        ),
        (
            "1/3",
            "tiny: 2 trials (1 environments, 2 variants, shard 1/3 of 4 trials)",
        ),
        (
            "5/5",
            "tiny: 0 trials (1 environments, 2 variants, shard 5/5 of 4 trials)",
        ),
    ] {
        let out = frontier(&["bench", s, "--dry-run", "--shard", shard]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        assert!(stderr.contains(line), "{stderr}");
    }
    // Regression: `--shard -1/2` was clap's "unexpected argument '-1'" with a tip to write
    // `-- -1/2`; a negative shard is a value the shard parser refuses plainly.
    let e = err(&["bench", s, "--dry-run", "--shard", "-1/2"]);
    assert!(
        e.contains("--shard: expected I/N with 1 <= I <= N (e.g. 2/8), found '-1/2'"),
        "{e}"
    );
    let db = dir.path().join("s3.sqlite");
    bench_shard(&study, &db, "3/3");
    assert_eq!(
        bench_rows(&db).len(),
        1,
        "the shard runs what the dry run counted"
    );
}

/// Regression: `--dungeon --map /dev/zero` read the device until the memory was gone.
#[cfg(unix)]
#[test]
fn regression_dungeon_map_from_a_device_is_refused() {
    let e = err(&[
        "explore",
        "--dungeon",
        "--map",
        "/dev/zero",
        "--resolution",
        "0.1",
    ]);
    assert!(
        e.contains("/dev/zero") && e.contains("a device, pipe or socket"),
        "{e}"
    );
}

/// Regression: `frontier list` left out the `square` sensor (Explore-Bench's window). It
/// lists every sensor kind the `--sensor` parser names when it refuses an unknown one.
#[test]
fn regression_list_names_every_sensor_kind() {
    let listed = ok(&["list"]);
    let refused = err(&["explore", "--sensor", "nosuchkind"]);
    let kinds = refused
        .split("expected one of ")
        .nth(1)
        .expect("the parser lists the kinds");
    for kind in kinds.trim().split(", ") {
        assert!(
            listed
                .lines()
                .any(|l| l.trim_start().starts_with(&format!("{kind} "))
                    || l.trim_start().starts_with(&format!("{kind}:"))),
            "{kind} is not in `frontier list`:\n{listed}"
        );
    }
}

/// Regression: the memory a run may take was read from the machine's free memory only, so
/// under an address-space limit (`ulimit -v`, as a batch system sets) a run the estimate
/// knew was too large started and aborted with "memory allocation of … bytes failed"
/// (SIGABRT). The limit is now room the check counts, and the run is refused up front.
#[cfg(target_os = "linux")]
#[test]
fn regression_run_over_the_address_space_limit_is_refused() {
    let under_limit = |kib: u32, args: &[&str]| {
        Command::new("sh")
            .arg("-c")
            .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
            .arg(env!("CARGO_BIN_EXE_frontier"))
            .args(args)
            .output()
            .expect("run frontier under sh")
    };
    // 8000 x 8000 cells: about 3.5 GiB to explore, under a limit of about 1 GiB.
    let explore = [
        "explore",
        "--env",
        "office",
        "--size",
        "400x400",
        "--resolution",
        "0.05",
        "--max-moves",
        "10",
        "--no-progress",
    ];
    // 4000 x 4000 cells: about 800 MiB to segment, under a limit of about 300 MiB.
    let segment = [
        "segment",
        "--env",
        "office",
        "--size",
        "200x200",
        "--resolution",
        "0.05",
    ];
    for (kib, args) in [(1_000_000, &explore[..]), (300_000, &segment[..])] {
        let out = under_limit(kib, args);
        let e = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(1),
            "{args:?} under ulimit -v {kib}: {e}"
        );
        // The limit that applies is named: ulimit -v, not the machine's free memory.
        assert!(
            e.contains("needs about") && e.contains("MiB ulimit -v leaves"),
            "{e}"
        );
    }
}

/// Regression: a map was loaded before any memory was checked: a valid 16384 x 16384 PGM
/// (the cell limit) took about 1.6 GB and 6 to 23 s to load, and under `ulimit -v` the load
/// aborted. The loader now estimates from the header and refuses before decoding.
#[cfg(target_os = "linux")]
#[test]
fn regression_map_over_the_address_space_limit_is_refused_before_loading() {
    let dir = tempfile::tempdir().unwrap();
    let pgm = dir.path().join("max.pgm");
    // The header of a 16384 x 16384 8-bit PGM; the pixels are never read.
    std::fs::write(&pgm, "P5\n16384 16384\n255\n").unwrap();
    let pgm = pgm.to_str().unwrap();
    for args in [
        &["map", "info", pgm, "--resolution", "0.1"][..],
        &[
            "explore",
            "--map",
            pgm,
            "--resolution",
            "0.1",
            "--max-moves",
            "1",
            "--no-progress",
        ][..],
    ] {
        let out = Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 1000000 && exec \"$0\" \"$@\"")
            .arg(env!("CARGO_BIN_EXE_frontier"))
            .args(args)
            .output()
            .expect("run frontier under sh");
        let e = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {e}");
        assert!(
            e.contains(&format!(
                "{pgm}: loading this 16384x16384 PGM image needs about"
            )) && e.contains("MiB ulimit -v leaves"),
            "{e}"
        );
    }
}

/// Regression: `--clearance -0` was taken as given and printed as `"clearance_m": -0.0`.
#[test]
fn regression_a_negative_zero_clearance_is_no_clearance() {
    let json = ok(&[
        "explore",
        "--env",
        "maze",
        "--clearance=-0",
        "--json",
        "--no-timing",
    ]);
    assert!(json.contains("\"clearance_m\": 0.0"), "{json}");
}

/// Regression: a sensor range no longer than the clearance was taken, and the run stopped
/// early with "no reachable frontier" (`--sensor los:r=4c --clearance 1` on a 0.2 m
/// hospital: 22 % coverage): the robot sees an obstacle only from within its clearance,
/// where no search leads out.
#[test]
fn regression_a_range_within_the_clearance_is_refused() {
    let e = err(&[
        "explore",
        "--env",
        "hospital",
        "--resolution",
        "0.2",
        "--sensor",
        "los:r=4c",
        "--clearance",
        "1",
    ]);
    assert!(
        e.contains("--sensor: expected a range beyond the clearance")
            && e.contains("found los:r=4c: 0.8 m, with a clearance of 1 m"),
        "{e}"
    );
}

/// Regression: `optimal` refused a range beyond a sensor's limit with the search's terse
/// "sensor range: expected a finite number of cells in [0, 256], found 300" (no spec, no
/// metres, and 0 is refused); it now checks the sensor as `explore` does.
#[test]
fn regression_optimal_refuses_a_long_range_as_explore_does() {
    let args = |cmd| {
        [
            cmd,
            "--env",
            "office",
            "--size",
            "12x10",
            "--resolution",
            "0.1",
            "--sensor",
            "los:r=30",
        ]
    };
    let want = "sensor 'los:r=30': range 300 cells at 0.1 m per cell: expected 1 to 256 cells \
                (0.1 to 25.6 m)";
    for cmd in ["optimal", "explore"] {
        let e = err(&args(cmd));
        assert!(e.contains(want), "{cmd}: {e}");
    }
}

/// Regression: `frontier segment --map plan.json` printed `"scores": null` though a
/// HouseExpo plan's room boxes are its ground truth: two rooms joined by a door, found.
#[test]
fn regression_segment_scores_a_houseexpo_plan_against_its_rooms() {
    let dir = tempfile::tempdir().unwrap();
    let plan = dir.path().join("house.json");
    std::fs::write(
        &plan,
        r#"{"verts": [[0,0],[4,0],[4,1.6],[5,1.6],[5,0],[9,0],[9,4],[5,4],[5,2.4],[4,2.4],[4,4],[0,4]],
            "room_category": {"bedroom": [[0,0,4,4]], "kitchen": [[5,0,9,4]]}}"#,
    )
    .unwrap();
    let p = plan.to_str().unwrap();
    for extra in [&[][..], &["--border"]] {
        let mut args = vec!["segment", "--map", p, "--resolution", "0.1", "--json"];
        args.extend_from_slice(extra);
        let json: serde_json::Value = serde_json::from_str(&ok(&args)).unwrap();
        let s = &json["scores"];
        assert_eq!(
            (s["rooms"].as_u64(), s["matched"].as_u64()),
            (Some(2), Some(2)),
            "{json}"
        );
    }
}

/// Regression: a size or resolution a generated kind cannot use was named by the library's
/// field (`invalid width_m = 1 for office`), not by the flag that set it.
#[test]
fn regression_generation_errors_name_the_flag() {
    let e = err(&["env", "office", "--size", "1x12", "--out", "x.png"]);
    assert!(
        e.contains("--size: width 1 m for office: too small, expected at least 10 m"),
        "{e}"
    );
    let e = err(&["explore", "--env", "office", "--resolution", "10"]);
    assert!(
        e.contains("--resolution: resolution 10 m for office: too coarse"),
        "{e}"
    );
}

/// Regression: `--goal 1` ended "goal reached" at full coverage with `"complete": false`,
/// though everything reachable was explored.
#[test]
fn regression_a_full_coverage_goal_reached_is_complete() {
    let run = |goal: &str| -> serde_json::Value {
        let args = [
            "explore",
            "--env",
            "maze",
            "--goal",
            goal,
            "--json",
            "--no-timing",
        ];
        serde_json::from_str(&ok(&args)).unwrap()
    };
    let full = run("1");
    assert_eq!(
        (full["reason"].as_str(), full["complete"].as_bool()),
        (Some("goal reached"), Some(true)),
        "{full}"
    );
    let half = run("0.5");
    assert_eq!(half["complete"].as_bool(), Some(false), "{half}");
}

/// Regression: `explore --map run.mcap --mcap run.mcap` wrote its own recording over the
/// one it read, losing the user's other topics; an output that is the map file (however
/// spelled) is refused, and the file is left as it was.
#[test]
fn an_output_is_never_the_map_it_reads() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("rec.mcap");
    let rec_s = rec.to_str().unwrap();
    ok(&[
        "explore",
        "--env",
        "maze",
        "--size",
        "6x5",
        "--resolution",
        "0.5",
        "--mcap",
        rec_s,
    ]);
    let before = std::fs::read(&rec).unwrap();
    let same = dir.path().join("sub").join("..").join("rec.mcap");
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    for out in [rec_s, same.to_str().unwrap()] {
        let e = err(&["explore", "--map", rec_s, "--mcap", out]);
        assert!(
            e.contains("--mcap")
                && e.contains(
                    "expected a file other than the files the command reads, found the --map \
                     it reads"
                ),
            "{e}"
        );
    }
    let e = err(&["segment", "--map", rec_s, "--out", rec_s]);
    assert!(
        e.contains(
            "expected a file other than the files the command reads, found the --map it reads"
        ),
        "{e}"
    );
    assert_eq!(std::fs::read(&rec).unwrap(), before);
}

/// Regression: `bench FILE --report R` with R a file ran every trial, then failed to
/// write the report ("is a file; expected the folder"): a long study ended in an error. The
/// folder is checked before anything runs (and by `--dry-run`).
#[test]
fn regression_bench_report_into_a_file_is_refused_before_running() {
    let dir = tempfile::tempdir().unwrap();
    let study = tiny_study(dir.path(), 2);
    let db = dir.path().join("r.sqlite");
    for dry in [true, false] {
        let mut args = vec![
            "bench",
            study.to_str().unwrap(),
            "--db",
            db.to_str().unwrap(),
            "--no-progress",
            "--report",
            study.to_str().unwrap(),
        ];
        if dry {
            args.push("--dry-run");
        }
        let e = err(&args);
        assert!(
            e.contains("is a file; expected the folder to write the report into"),
            "{e}"
        );
        assert!(!db.exists(), "trials ran before the refusal");
    }
    // Regression: a report folder that is the --db's path, that cannot be made, or that
    // holds a folder where report.html goes failed after every trial had run (the second
    // with "No such file or directory" and no flag named).
    let inner = dir.path().join("rr");
    std::fs::create_dir_all(inner.join("report.html")).unwrap();
    for (report, says) in [
        (
            db.clone(),
            "--report".to_string()
                + " "
                + db.to_str().unwrap()
                + ": expected a folder for the report, found the path of the --db",
        ),
        (
            Path::new("/proc/frontier-report").to_path_buf(),
            "--report /proc/frontier-report: expected a folder that can be made".to_string(),
        ),
        (
            inner.clone(),
            format!(
                "--report {}: expected a folder where report.html can be written",
                inner.display()
            ),
        ),
    ] {
        // /proc takes no new folder (Linux).
        if report.starts_with("/proc") && !Path::new("/proc/self").exists() {
            continue;
        }
        let e = err(&[
            "bench",
            study.to_str().unwrap(),
            "--db",
            db.to_str().unwrap(),
            "--no-progress",
            "--report",
            report.to_str().unwrap(),
        ]);
        assert!(e.contains(&says), "{e}");
        assert!(!db.exists(), "trials ran before the refusal");
    }
}

/// Regression: a store copied from a run killed in WAL mode, with its `-wal` but not its
/// `-shm`, into a folder the user may only read gave "unable to open database file" from
/// export, report and merge: SQLite must make the `-shm` to read the `-wal`. The message
/// says so and what to do.
#[cfg(unix)]
#[test]
fn regression_a_killed_store_without_its_shm_in_a_read_only_folder_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let study = tiny_study(dir.path(), 7);
    let good = dir.path().join("good.sqlite");
    bench_shard(&study, &good, "1/1");
    let ro = dir.path().join("ro");
    let out = dir.path().join("out");
    std::fs::create_dir(&ro).unwrap();
    std::fs::create_dir(&out).unwrap();
    let db = ro.join("tiny.sqlite");
    // A write in WAL mode not yet checkpointed: the store and its -wal as a killed run
    // leaves them, copied while the connection is open.
    let conn = rusqlite::Connection::open(&good).unwrap();
    conn.query_row("PRAGMA journal_mode = WAL", [], |_| Ok(()))
        .unwrap();
    conn.query_row("PRAGMA wal_autocheckpoint = 0", [], |_| Ok(()))
        .unwrap();
    conn.execute("INSERT INTO meta VALUES ('note', 'written last')", [])
        .unwrap();
    assert!(Path::new(&format!("{}-wal", good.display())).exists());
    std::fs::copy(&good, &db).unwrap();
    std::fs::copy(
        format!("{}-wal", good.display()),
        format!("{}-wal", db.display()),
    )
    .unwrap();
    drop(conn);
    let d = db.to_str().unwrap();
    let csv = out.join("all.csv");
    let o = frontier_on_a_read_only_database(
        &db,
        &out,
        &["bench", "export", d, "--csv", csv.to_str().unwrap()],
    );
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{e}");
    assert!(
        e.contains(&format!(
            "{d}: has a -wal file beside it (a run killed while writing) but no -shm"
        )) && e.contains("copy its -shm file too"),
        "{e}"
    );
}

/// Regression: `--strategy random --s-max 1` drew a new random frontier cell at every
/// move, a random walk that did not finish on the default office in 120 s (with `--s-max
/// 2`: 3,854 km against 788 m); `dt --s-max 1` travelled 25 times as far. A strategy that
/// draws its goals takes no periodic re-plan, from the CLI or a scenario.
#[test]
fn regression_s_max_is_refused_for_strategies_that_draw_their_goals() {
    for preset in ["random", "dt", "dt500", "dt-rr"] {
        let e = err(&["explore", "--strategy", preset, "--s-max", "3"]);
        assert!(
            e.contains(&format!(
                "--s-max: expected -1 for {preset}, found 3: it draws each goal at random"
            )),
            "{e}"
        );
    }
    ok(&[
        "explore",
        "--strategy",
        "random",
        "--s-max",
        "-1",
        "--size",
        "12x10",
    ]);
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("s.toml");
    std::fs::write(
        &study,
        "strategies = []\n[[strategy]]\npreset = \"random\"\ns_max = 2\n\n[[env]]\n\
         kind = \"office\"\n",
    )
    .unwrap();
    let e = err(&["bench", study.to_str().unwrap(), "--dry-run"]);
    assert!(
        e.contains("key `strategy[0].s_max`") && e.contains("expected -1 for random, found 2"),
        "{e}"
    );
}

/// Regression: a write to standard output that failed (a full disk behind `> file`)
/// panicked in `println!` with a backtrace and exit code 101; it is an error that says
/// what failed. `/dev/full` fails every write with "No space left on device".
#[test]
fn a_full_standard_output_is_an_error_not_a_panic() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    for args in [
        &["list"][..],
        &["explore", "--env", "office", "--size", "12x10", "--json"],
        &["env", "--list"],
        &["bench", "suites"],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_frontier"))
            .args(args)
            .stdout(full.try_clone().unwrap())
            .output()
            .expect("run frontier");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("error: writing to standard output:")
                && !stderr.contains("panicked"),
            "{args:?}: {stderr}"
        );
    }
}

/// Regression: outputs were checked against the `--map` path alone, as text. `--out r1`
/// wrote over the `r1/belief.yaml` the run read, `--gif depot.pgm` over the image a map
/// YAML names, `--mcap` over a hard link of the map, and `--gif same --html ./same` or
/// `--out od --gif od/final.png` kept only the output written last; a dangling symbolic
/// link given as an output was replaced by a file; `-` became a file named `-`; a folder
/// where `--out` writes `trace.json` failed after the run; and a run refused after its
/// `--out` folder was made left the folder behind.
#[test]
fn regression_outputs_are_never_inputs_nor_each_other() {
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let small = ["--env", "office", "--size", "12x10"];
    let explore = |extra: &[&str]| {
        let mut args = vec!["explore"];
        args.extend_from_slice(&small);
        args.extend_from_slice(extra);
        err(&args)
    };
    // A built map explored again into its own folder.
    let r1 = at("r1");
    let mut args = vec!["explore"];
    args.extend_from_slice(&small);
    args.extend_from_slice(&["--out", &r1]);
    ok(&args);
    let belief = at("r1/belief.yaml");
    let before = std::fs::read(&belief).unwrap();
    let e = err(&["explore", "--map", &belief, "--out", &r1]);
    assert!(
        e.contains(&format!(
            "--out {r1}: expected a folder whose belief.yaml is not a file the command reads, \
             found the --map it reads"
        )),
        "{e}"
    );
    // The image its YAML names, and a hard link of it.
    let pgm = at("r1/belief.pgm");
    let e = err(&["explore", "--map", &belief, "--gif", &pgm]);
    assert!(e.contains("found the image of the --map it reads"), "{e}");
    let link = at("hard.pgm");
    std::fs::hard_link(&pgm, &link).unwrap();
    let e = err(&["explore", "--map", &belief, "--mcap", &link]);
    assert!(e.contains("found the image of the --map it reads"), "{e}");
    assert_eq!(std::fs::read(&belief).unwrap(), before);
    // Two outputs on one file, however spelled.
    let same = at("same.gif");
    let dotted = format!("{}/./same.gif", dir.path().display());
    let e = explore(&["--gif", &same, "--html", &dotted]);
    assert!(
        e.contains("expected a file of its own, found the file --gif writes"),
        "{e}"
    );
    let od = at("od");
    std::fs::create_dir(&od).unwrap();
    let inside = at("od/final.png");
    let e = explore(&["--out", &od, "--gif", &inside]);
    assert!(
        e.contains(&format!(
            "--gif {inside}: expected a file of its own, found the file --out writes ({inside})"
        )),
        "{e}"
    );
    let fresh = at("fresh");
    let e = explore(&["--out", &fresh, "--gif", &fresh]);
    assert!(
        e.contains(&format!(
            "--gif {fresh}: expected a file of its own, found the folder --out writes"
        )),
        "{e}"
    );
    // A dangling symbolic link: the file it names is written, the link stays.
    let target = at("target.gif");
    let sym = at("link.gif");
    std::os::unix::fs::symlink(&target, &sym).unwrap();
    let e = explore(&["--gif", &sym, "--robots", "0"]);
    assert!(e.contains("--robots"), "{e}");
    assert!(
        std::fs::symlink_metadata(&sym)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(!Path::new(&target).exists());
    // `-`.
    // A format under another's name.
    let e = explore(&["--gif", &at("run.png")]);
    assert!(
        e.contains("expected a file name ending in .gif (it writes a GIF animation), found '.png'"),
        "{e}"
    );
    let e = err(&["segment", "--env", "office", "--out", &at("seg.gif")]);
    assert!(e.contains("expected a file name ending in .png"), "{e}");
    let e = explore(&["--gif", "-"]);
    assert!(
        e.contains("--gif -: expected a file name, found '-'"),
        "{e}"
    );
    let e = err(&["bench", "--suite", "quick", "--db", "-", "--dry-run"]);
    assert!(
        e.contains("--db -: expected a database file name, found '-'"),
        "{e}"
    );
    // A folder where a file of --out goes.
    let od5 = at("od5");
    std::fs::create_dir_all(dir.path().join("od5/trace.json")).unwrap();
    let e = explore(&["--out", &od5]);
    assert!(e.contains("found a folder"), "{e}");
    // A run refused after its folder was made leaves none.
    let edx = at("edx");
    let e = explore(&["--out", &edx, "--start", "0,0"]);
    assert!(e.contains("start"), "{e}");
    assert!(!Path::new(&edx).exists());
}

/// Regression: a team's recording stamped each goal, belief and marker message with the
/// time of the event it followed, and a team's events come in the order its robots set
/// out, not the order their moves end: `/frontier/robot1/goal` went from 20.1776 s back to
/// 20.1678 s. Every topic's log times now never go back.
#[test]
fn regression_a_team_recording_never_goes_back_in_time() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("team.mcap");
    ok(&[
        "explore",
        "--env",
        "office",
        "--size",
        "20x15",
        "--robots",
        "3",
        "--strategy",
        "ha-rfe",
        "--mcap",
        rec.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&rec).unwrap();
    let mut last = std::collections::HashMap::<String, u64>::new();
    let mut count = 0;
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        let t = last.entry(m.channel.topic.clone()).or_insert(0);
        assert!(
            m.log_time >= *t,
            "{}: {} after {}",
            m.channel.topic,
            m.log_time,
            t
        );
        *t = m.log_time;
        count += 1;
    }
    assert!(
        count > 100 && last.contains_key("/frontier/robot1/goal"),
        "{last:?}"
    );
}

/// Regression: `bench merge nod/x.sqlite ...` made the missing folder, where `bench --db
/// nod/x.sqlite` refuses it.
#[test]
fn regression_merge_refuses_a_missing_folder() {
    let dir = tempfile::tempdir().unwrap();
    let study = tiny_study(dir.path(), 5);
    let q = dir.path().join("q.sqlite");
    bench_shard(&study, &q, "1/1");
    let out = dir.path().join("nod").join("x.sqlite");
    let e = err(&["bench", "merge", out.to_str().unwrap(), q.to_str().unwrap()]);
    assert!(
        e.contains("expected an output database in an existing folder"),
        "{e}"
    );
    assert!(!dir.path().join("nod").exists());
}

/// Regression: `optimal --compare` ran its presets on the full map with no memory check;
/// only the coarse search's set-up was checked (`--cell-size 40` on a 4000 x 4000 map
/// passed `--memory-mb 150` and took 416 MiB). Each compared run is checked before the
/// search.
#[test]
fn regression_optimal_checks_its_compared_runs_memory() {
    let args = [
        "optimal",
        "--env",
        "empty",
        "--size",
        "60x60",
        "--resolution",
        "0.05",
        "--cell-size",
        "10",
        "--sensor",
        "los:r=2",
        "--memory-mb",
        "60",
        "--max-nodes",
        "10",
    ];
    ok(&args);
    let mut compared = args.to_vec();
    compared.extend(["--compare", "cf"]);
    let e = err(&compared);
    assert!(
        e.contains("--compare cf: exploring this 1200x1200 map with 1 robot (cf) needs about")
            && e.contains("more than --memory-mb 60"),
        "{e}"
    );
}

/// Regression: `map info` counted the free components (4 bytes a cell of labels and a list
/// of runs) after loading within `--memory-mb` without counting them: an 8000 x 8000 open
/// map passed `--memory-mb 130` and took 310 MiB. That count is checked too.
#[test]
fn regression_map_info_checks_the_components_memory() {
    let dir = tempfile::tempdir().unwrap();
    let map = open_map(dir.path(), 2000);
    let map = map.to_str().unwrap();
    let e = err(&["map", "info", map, "--memory-mb", "30"]);
    assert!(
        e.contains("counting the free components of this 2000x2000 map needs about")
            && e.contains("more than --memory-mb 30"),
        "{e}"
    );
    assert!(ok(&["map", "info", map, "--memory-mb", "60"]).contains("1 connected component"));
}

/// Regression: `sensors` generated every furnished environment and ran its runs side by
/// side with no memory estimate and no `--memory-mb`, and aborted under `ulimit -v`
/// ("memory allocation of 32000000 bytes failed"). It is checked before anything is
/// generated.
#[test]
fn regression_sensors_checks_its_memory_first() {
    let e = err(&[
        "sensors",
        "--env",
        "office",
        "--size",
        "40x30",
        "--resolution",
        "0.05",
        "--seeds",
        "2",
        "--sensors",
        "laser",
        "--memory-mb",
        "30",
    ]);
    assert!(
        e.contains("comparing 1 sensor on 2 furnished offices of 480000 cells")
            && e.contains("more than --memory-mb 30"),
        "{e}"
    );
}

/// Regression: `segment --truth` scored against any plan of the map's size, counting only
/// the cells free in both: a truth of walls only scored ARI 1 with 0 rooms, and one with a
/// single free cell F1 1 and ARI 1 against 7 segments. A truth sharing no free cell is
/// refused, and one covering less than half the free cells is warned about.
#[test]
fn regression_segment_truth_must_cover_the_map() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("office.txt");
    let m = map.to_str().unwrap();
    ok(&["env", "office", "--size", "12x10", "--out", m]);
    let text = std::fs::read_to_string(&map).unwrap();
    let walls = dir.path().join("walls.txt");
    std::fs::write(&walls, text.replace('.', "#")).unwrap();
    let e = err(&["segment", "--map", m, "--truth", walls.to_str().unwrap()]);
    assert!(
        e.contains("expected rooms that cover the map's free cells, found none of its"),
        "{e}"
    );
    let one = dir.path().join("one.txt");
    let first = text.find('.').unwrap();
    let mut cells = text.replace('.', "#").into_bytes();
    cells[first] = b'.';
    std::fs::write(&one, cells).unwrap();
    let out = frontier(&["segment", "--map", m, "--truth", one.to_str().unwrap()]);
    assert!(out.status.success());
    let warning = String::from_utf8_lossy(&out.stderr);
    assert!(
        warning.contains("its rooms cover 1 of the map's")
            && warning.contains("the scores count only those"),
        "{warning}"
    );
}

/// Regression: a missing `--truth` or `--clutter-map` file was reported as needing
/// `--resolution` (so was a missing `--map` bitmap), without naming the flag; and a bare
/// bitmap given beside a map with its own resolution could not be read without repeating
/// it. A layer of the map is the same plan: it takes the map's cell size.
#[test]
fn regression_map_layers_name_their_flag_and_take_the_map_cell_size() {
    let dir = tempfile::tempdir().unwrap();
    let yaml = dir.path().join("plan.yaml");
    let y = yaml.to_str().unwrap();
    ok(&[
        "env",
        "office",
        "--size",
        "12x10",
        "--resolution",
        "0.1",
        "--out",
        y,
    ]);
    let pgm = dir.path().join("plan.pgm");
    assert!(
        pgm.is_file(),
        "env --out plan.yaml writes plan.pgm beside it"
    );
    let missing = dir.path().join("missing.png");
    let m = missing.to_str().unwrap();
    let e = err(&["segment", "--map", y, "--truth", m]);
    assert!(e.contains(&format!("--truth: {m}: cannot read")), "{e}");
    let e = err(&["explore", "--map", y, "--clutter-map", m]);
    assert!(
        e.contains(&format!("--clutter-map: {m}: cannot read")),
        "{e}"
    );
    let e = err(&["explore", "--map", m]);
    assert!(e.contains(&format!("{m}: cannot read")), "{e}");
    assert!(!e.contains("--resolution"), "{e}");
    // the bitmap of the map's own plan, read at the map's 0.1 m
    let out = frontier(&["segment", "--map", y, "--truth", pgm.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = frontier(&[
        "explore",
        "--map",
        y,
        "--clutter-map",
        pgm.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Regression: `demo --envs office,office` ran every office run twice, with the same seeds.
#[test]
fn regression_demo_lists_refuse_an_item_given_twice() {
    let e = err(&["demo", "--envs", "office, cave,office"]);
    assert!(
        e.contains("--envs: expected each item once, found office twice in 'office, cave,office'"),
        "{e}"
    );
    let e = err(&["demo", "--strategies", "cf,cf"]);
    assert!(
        e.contains("--strategies: expected each item once, found cf twice"),
        "{e}"
    );
}

/// Regression: of two `bench` runs started together into one new database, one could fail
/// at once with "database is locked": switching the new file to WAL mode is answered busy
/// without waiting for the other run. (A race: the rounds make it show.)
#[test]
fn regression_two_bench_runs_started_together_into_one_new_database_both_finish() {
    for round in 0..20 {
        let dir = tempfile::tempdir().unwrap();
        let db = dir.path().join("shared.sqlite");
        let args = [
            "bench",
            "--suite",
            "multirobot",
            "--limit",
            "5",
            "-j",
            "1",
            "--no-progress",
            "--db",
            db.to_str().unwrap(),
        ];
        let spawn = || {
            Command::new(env!("CARGO_BIN_EXE_frontier"))
                .args(args)
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("run frontier")
        };
        let (a, b) = (spawn(), spawn());
        for child in [a, b] {
            let out = child.wait_with_output().unwrap();
            assert!(
                out.status.success(),
                "round {round}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
}

/// Regression: a sensor whose range the map's cells cannot carry was reported as "sensor:
/// sensor 'los:r=…': …", not under its flag as every other sensor error is.
#[test]
fn regression_a_sensor_range_beyond_the_map_names_the_flag() {
    let e = err(&["explore", "--sensor", "los:r=1e9"]);
    assert!(
        e.contains("error: --sensor: sensor 'los:r=1000000000': range 2000000000 cells"),
        "{e}"
    );
}

/// A run on a recording's map, written with `--mcap`, is in the recording's frame and
/// starts at its map's log time, so that it lines up with the recording (it was in the
/// `map` frame from 1970). `map info` tells both.
#[test]
fn a_run_on_a_recording_keeps_its_frame_and_clock() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("bag.mcap");
    let map = grid::io::parse_ascii(
        &[
            "##########",
            "#........#",
            "#..##....#",
            "#........#",
            "##########",
        ]
        .join("\n"),
        0.25,
    )
    .unwrap();
    let start = 1_750_000_000_000_000_000u64;
    let file = std::fs::File::create(&rec).unwrap();
    let mut w = record::RunWriter::with_clock(file, "odom", start).unwrap();
    w.map(3.0, &map).unwrap();
    w.finish().unwrap();
    let out = dir.path().join("run.mcap");
    let (r, o) = (rec.to_str().unwrap(), out.to_str().unwrap());
    ok(&["explore", "--map", r, "--sensor", "los:r=1", "--mcap", o]);
    let bytes = std::fs::read(&out).unwrap();
    let len = bytes.len() as u64;
    let on = |topic| {
        record::mcap_read::read_last_map(&bytes[..], len, Some(topic), None)
            .unwrap()
            .at
    };
    let recorded = start + 3_000_000_000;
    assert_eq!(
        on("/map"),
        record::mcap_read::RecordedAt {
            frame_id: "odom".into(),
            log_time: recorded
        }
    );
    let belief = on("/frontier/belief");
    assert_eq!(belief.frame_id, "odom");
    assert!(belief.log_time > recorded, "{belief:?}");
    let info: serde_json::Value = serde_json::from_str(&ok(&["map", "info", r, "--json"])).unwrap();
    assert_eq!(
        (info["frame_id"].as_str(), info["log_time_ns"].as_u64()),
        (Some("odom"), Some(recorded))
    );
}
