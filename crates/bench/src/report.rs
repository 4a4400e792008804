//! `frontier bench report`: tables, tests and charts of a results database, written as
//! `report.md` (with `plots/*.svg` and `envs/*.png` beside it) and a self-contained
//! `report.html` (charts inline as SVG, pictures as data URIs; no network needed). Each
//! environment picture links to `replays/<env>.html`, the replay page of one of its runs
//! (see [`crate::replays`]).
//!
//! A *setting* is (environment, sensor, robot count). Per setting and strategy the report
//! gives n, the share of complete runs, L (the longest path of one robot — the path length
//! for one robot; Holz's and Faigl & Kulich's metric) as mean ± sd, median, IQR, min, max,
//! Shapiro–Wilk's p, and the exploration time; a box plot of L per strategy (Holz Figure 8);
//! mean coverage over team distance; and Faigl & Kulich's +/=/- matrix at α. Strategies are
//! paired by (start variant, trial) when both have the same ones (the seeds are shared, so
//! these are the same starts), else by start variant (means over trials) when at least 5
//! start variants are shared, else compared unpaired (Mann–Whitney U). Per (environment,
//! sensor) with several robot counts, mean time vs robot count is drawn (the multi-robot
//! study's Figures 2–3). The summary at the end counts +/=/- over all settings (Table I).
//! Studies with optimal offline paths also get each strategy's competitive ratio.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use crate::error::BenchError;
use crate::plots;
use crate::stats::{self, Pairing, Verdict};
use crate::store::{Store, TrialRow};

/// Options of the report.
#[derive(Clone, Copy, Debug)]
pub struct ReportOptions {
    /// Significance level of the +/=/- verdicts.
    pub alpha: f64,
}

impl Default for ReportOptions {
    fn default() -> Self {
        Self {
            alpha: stats::DEFAULT_ALPHA,
        }
    }
}

/// A piece of the report, rendered to Markdown and to HTML.
enum Block {
    Heading(u8, String),
    Para(String),
    Table(Vec<String>, Vec<Vec<String>>),
    Svg(String, String),
    /// Environment picture: name, PNG, and the replay page it links to, if any.
    Png(String, Vec<u8>, Option<String>),
}

/// (environment, sensor, robots).
type Setting = (String, String, i64);

/// Write the report of database `db` into directory `out`; returns the files written.
pub fn write(
    db: &Path,
    out: &Path,
    opts: &ReportOptions,
) -> Result<Vec<std::path::PathBuf>, BenchError> {
    let store = Store::open_read_only(db)?;
    let rows = store.rows()?;
    let envs = store.envs()?;
    let scenario = store.meta("scenario")?.unwrap_or_default();
    let fingerprint = store.meta("fingerprint")?.unwrap_or_default();
    let description = store.meta("description")?;
    drop(store);
    let mut blocks = build(&scenario, &fingerprint, &rows, &envs, opts)?;
    if let Some(text) = description {
        // The scenario's own words, under the title.
        blocks.insert(1, Block::Para(text));
    }
    // One replay page per environment picture, re-run from a stored trial: made before
    // anything is written, so that a trial that cannot be re-run (its map file moved)
    // leaves no half-written report behind.
    let mut pages = Vec::new();
    for b in &mut blocks {
        let Block::Png(name, _, link) = b else {
            continue;
        };
        let Some(pic) = envs.iter().find(|e| slug(&e.name) == *name) else {
            continue;
        };
        let Some(row) = crate::replays::representative(&rows, &pic.name) else {
            continue;
        };
        let rel = format!("replays/{name}.html");
        pages.push((out.join(&rel), crate::replays::replay_page(pic, row)?));
        *link = Some(rel);
    }
    check_report_folder(out)?;
    std::fs::create_dir_all(out.join("plots")).map_err(BenchError::io(out))?;
    std::fs::create_dir_all(out.join("envs")).map_err(BenchError::io(out))?;
    // Every file the report writes, checked against the database it reads before any is
    // written (with the directories made, so that each path resolves as it will).
    let mut targets = vec![out.join("report.md"), out.join("report.html")];
    for b in &blocks {
        match b {
            Block::Svg(name, _) => targets.push(out.join("plots").join(format!("{name}.svg"))),
            Block::Png(name, _, _) => {
                targets.push(out.join("envs").join(format!("{name}.png")));
                targets.push(out.join("replays").join(format!("{name}.html")));
            }
            _ => {}
        }
    }
    for t in &targets {
        crate::store::refuse_overwriting(db, t, "the report")?;
    }
    let mut files = Vec::new();
    for (path, page) in pages {
        std::fs::create_dir_all(out.join("replays")).map_err(BenchError::io(out))?;
        std::fs::write(&path, page).map_err(BenchError::io(&path))?;
        files.push(path);
    }
    for b in &blocks {
        let (path, bytes) = match b {
            Block::Svg(name, svg) => (
                out.join("plots").join(format!("{name}.svg")),
                svg.as_bytes(),
            ),
            Block::Png(name, png, _) => {
                (out.join("envs").join(format!("{name}.png")), png.as_slice())
            }
            _ => continue,
        };
        std::fs::write(&path, bytes).map_err(BenchError::io(&path))?;
        files.push(path);
    }
    let md = out.join("report.md");
    std::fs::write(&md, markdown(&blocks)).map_err(BenchError::io(&md))?;
    let html = out.join("report.html");
    std::fs::write(&html, html_page(&scenario, &blocks)).map_err(BenchError::io(&html))?;
    files.push(md);
    files.push(html);
    Ok(files)
}

/// Refuses `out` when it, or the nearest of its parents that exists, is not a folder: the
/// report is written into `out`, made with its missing parents. A run that writes a report
/// after it checks this before it starts.
pub fn check_report_folder(out: &Path) -> Result<(), BenchError> {
    for dir in out.ancestors().filter(|d| !d.as_os_str().is_empty()) {
        let Ok(meta) = std::fs::metadata(dir) else {
            continue;
        };
        if meta.is_dir() {
            return Ok(());
        }
        let message = if dir == out {
            "is a file; expected the folder to write the report into".to_string()
        } else {
            format!(
                "expected a folder to write the report into (made with its missing parents), \
                 but {} is a file, so no folder can be made there; give a path outside it",
                dir.display()
            )
        };
        return Err(BenchError::File {
            path: out.to_path_buf(),
            message,
        });
    }
    Ok(())
}

/// A study's settings as its fingerprint names them ([`crate::plan::Plan::fingerprint`]),
/// worded for a reader: the strategies' revision named as one, and the coverage goal as a
/// number or "none" rather than in the program's own notation.
fn readable_settings(fingerprint: &str) -> String {
    fingerprint
        .split(' ')
        .map(|part| match part.split_once('=') {
            Some(("strategies", n)) => format!("strategy revision {n},"),
            Some(("goal", "None")) => "goal=none".to_string(),
            Some(("goal", g)) => format!(
                "goal={}",
                g.strip_prefix("Some(")
                    .and_then(|g| g.strip_suffix(')'))
                    .unwrap_or(g)
            ),
            _ => part.to_string(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A file-name-safe version of `s` (the report's file names of environments and variants).
pub(crate) fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The file-name part of an environment and sensor's plots: their slugs joined by `+`,
/// which no slug holds, so that two settings never share a file (environment `a` with
/// sensor `b-c`, and `a-b` with `c`, were both `a-b-c`).
fn setting_slug(env: &str, sensor: &str) -> String {
    format!("{}+{}", slug(env), slug(sensor))
}

/// "mean ± sd" written with `f`, or the mean alone when the sd is undefined (one value).
pub(crate) fn mean_sd(mean: f64, sd: f64, f: impl Fn(f64) -> String) -> String {
    if sd.is_finite() {
        format!("{} ± {}", f(mean), f(sd))
    } else {
        f(mean)
    }
}

fn fmt(x: f64) -> String {
    if x.abs() >= 100.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

fn build(
    scenario: &str,
    fingerprint: &str,
    rows: &[TrialRow],
    envs: &[crate::store::EnvPicture],
    opts: &ReportOptions,
) -> Result<Vec<Block>, BenchError> {
    let mut blocks = vec![Block::Heading(1, format!("Benchmark report: {scenario}"))];
    let versions: std::collections::BTreeSet<&str> =
        rows.iter().map(|r| r.version.as_str()).collect();
    // (0.0 +: an empty sum is −0.0, which would print as "-0.0 s")
    let wall: f64 = 0.0 + rows.iter().map(|r| r.wall_s).sum::<f64>();
    let settings = readable_settings(fingerprint);
    let versions = match versions.len() {
        0 => "none (no trial)".to_string(),
        _ => versions.into_iter().collect::<Vec<_>>().join(", "),
    };
    blocks.push(Block::Para(format!(
        "{} trials; settings: {settings}; program version {versions}; {wall:.1} s of trial wall time. \
         L = longest path of one robot (m); verdicts at α = {} (Faigl & Kulich: row vs column, \
         + = row significantly lower).",
        rows.len(),
        opts.alpha
    )));
    if scenario.starts_with("holz2010")
        && let Some((header, body)) = crate::holz_tables::comparison(rows)
    {
        blocks.push(Block::Heading(2, "Holz et al. 2010, Tables 1–3".into()));
        blocks.push(Block::Para(
            "Mean path length to full coverage ± sd (m) and, in brackets, the ratio to closest \
             frontier (cf) in the same environment: ours beside the paper's Tables 1–3 (cave, \
             AVZ 5th floor, Stage hospital). Compare ratios and orderings, not metres."
                .into(),
        ));
        blocks.push(Block::Table(header, body));
        let lines: Vec<String> = crate::holz_tables::ordering(rows)
            .into_iter()
            .map(|(env, r)| match r {
                Ok(()) => format!("{env}: the paper's ordering holds"),
                Err(why) => format!("{env}: {why}"),
            })
            .collect();
        blocks.push(Block::Para(format!(
            "Ordering random > dt > cf > cf-rr ≥ cf-rr-seg: {}.",
            lines.join("; ")
        )));
    }
    let mut settings: BTreeMap<Setting, BTreeMap<String, Vec<&TrialRow>>> = BTreeMap::new();
    for r in rows {
        settings
            .entry((r.env.clone(), r.sensor.clone(), r.robots))
            .or_default()
            .entry(r.strategy.clone())
            .or_default()
            .push(r);
    }
    // Faigl-style totals: (a, b) -> [+, =, -, of the = those that could not be + or -].
    let mut totals: BTreeMap<(String, String), [usize; 4]> = BTreeMap::new();
    let env_names: Vec<String> = {
        let mut v: Vec<String> = settings.keys().map(|k| k.0.clone()).collect();
        v.dedup();
        v
    };
    for env in &env_names {
        blocks.push(Block::Heading(2, format!("Environment {env}")));
        if let Some(p) = envs.iter().find(|e| &e.name == env) {
            blocks.push(Block::Para(format!(
                "{} x {} cells at {} m per cell.",
                p.width, p.height, p.resolution
            )));
            blocks.push(Block::Png(slug(env), p.png.clone(), None));
        }
        for ((e, sensor, robots), by_strategy) in settings.iter().filter(|(k, _)| &k.0 == env) {
            let name = format!("{e} · {sensor} · {robots} robot(s)");
            let id = format!("{}+m{robots}", setting_slug(e, sensor));
            blocks.push(Block::Heading(3, name.clone()));
            blocks.push(summary_table(by_strategy));
            blocks.push(Block::Para(
                "Distance (team, m) and time (s) to 90 % and 99 % coverage (D90, T90, D99, T99; \
                 over the trials that reached it)"
                    .to_string()
                    + if *robots > 1 {
                        ", the overlap ratio (cells sensed by two or more robots over cells \
                         sensed) and the mean idle time per robot (s)."
                    } else {
                        "."
                    },
            ));
            blocks.push(milestones_table(by_strategy, *robots > 1));
            if let Some((header, body)) = crate::competitive::ratio_table(by_strategy) {
                blocks.push(Block::Para(
                    "Competitive ratio (Quattrini Li et al. 2012): path length over the optimal \
                     offline path from the same start with the same sensor."
                        .into(),
                ));
                blocks.push(Block::Table(header, body));
            }
            let labels: Vec<String> = by_strategy.keys().cloned().collect();
            let data: Vec<Vec<f64>> = by_strategy
                .values()
                .map(|v| v.iter().map(|r| r.max_path).collect())
                .collect();
            blocks.push(Block::Svg(
                format!("box-{id}"),
                plots::box_plot(&format!("L per strategy — {name}"), "L (m)", &labels, &data)?,
            ));
            blocks.push(Block::Svg(
                format!("coverage-{id}"),
                plots::line_chart(
                    &format!("Mean coverage over team distance — {name}"),
                    "team distance (m)",
                    "coverage",
                    &coverage_curves(by_strategy),
                )?,
            ));
            if by_strategy.len() >= 2 {
                let (table, notes, verdicts) = matrix(by_strategy, opts.alpha);
                blocks.push(Block::Para(format!("+/=/- of L at α = {}:", opts.alpha)));
                blocks.push(table);
                blocks.extend(notes.into_iter().map(Block::Para));
                for (a, b, v, weak) in verdicts {
                    let slot = match v {
                        Verdict::Better => 0,
                        Verdict::Same => 1,
                        Verdict::Worse => 2,
                    };
                    let t = totals.entry((a, b)).or_default();
                    t[slot] += 1;
                    t[3] += usize::from(weak);
                }
            }
        }
        // Time vs robot count per sensor.
        let sensors: std::collections::BTreeSet<&String> = settings
            .keys()
            .filter(|k| &k.0 == env)
            .map(|k| &k.1)
            .collect();
        for sensor in sensors {
            let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
            for ((_, _, robots), by_strategy) in settings
                .iter()
                .filter(|(k, _)| &k.0 == env && &k.1 == sensor)
            {
                for (s, rs) in by_strategy {
                    let mean = rs.iter().map(|r| r.time_s).sum::<f64>() / rs.len() as f64;
                    series
                        .entry(s.clone())
                        .or_default()
                        .push((*robots as f64, mean));
                }
            }
            if series.values().any(|p| p.len() >= 2) {
                let series: Vec<(String, Vec<(f64, f64)>)> = series.into_iter().collect();
                blocks.push(Block::Heading(
                    3,
                    format!("{env} · {sensor}: time vs robots"),
                ));
                blocks.push(Block::Svg(
                    format!("time-{}", setting_slug(env, sensor)),
                    plots::line_chart(
                        &format!("Mean exploration time vs robots — {env} · {sensor}"),
                        "robots",
                        "time (s)",
                        &series,
                    )?,
                ));
            }
        }
    }
    if !totals.is_empty() {
        blocks.push(Block::Heading(
            2,
            "All settings: +/=/- counts (Faigl & Kulich Table I)".into(),
        ));
        let names: Vec<String> = {
            let mut v: Vec<String> = totals
                .keys()
                .flat_map(|(a, b)| [a.clone(), b.clone()])
                .collect();
            v.sort();
            v.dedup();
            v
        };
        let mut header = vec!["row vs column".to_string()];
        header.extend(names.iter().cloned());
        let body = names
            .iter()
            .map(|a| {
                let mut row = vec![a.clone()];
                for b in &names {
                    row.push(match totals.get(&(a.clone(), b.clone())) {
                        Some([p, e, m, 0]) => format!("{p}/{e}/{m}"),
                        Some([p, e, m, w]) => format!("{p}/{e}/{m} ({w} {UNDERPOWERED})"),
                        None => String::new(),
                    });
                }
                row
            })
            .collect();
        blocks.push(Block::Para("Cells: settings where the row strategy is significantly better / not different / significantly worse.".into()));
        blocks.push(Block::Table(header, body));
        let weak: usize = totals.values().map(|t| t[3]).sum();
        if weak > 0 {
            let all: usize = totals.values().map(|t| t[0] + t[1] + t[2]).sum();
            blocks.push(Block::Para(format!(
                "{UNDERPOWERED}: {weak} of these {all} verdicts are = only because their setting \
                 has too few observations for any p below α = {} (marked {UNDERPOWERED} and \
                 explained under the setting's table): they say nothing about a difference.",
                opts.alpha
            )));
        }
    }
    Ok(blocks)
}

fn summary_table(by_strategy: &BTreeMap<String, Vec<&TrialRow>>) -> Block {
    let header = [
        "strategy",
        "n",
        "complete",
        "L mean ± sd",
        "median",
        "IQR",
        "min",
        "max",
        "Shapiro–Wilk p",
        "time mean ± sd (s)",
    ]
    .map(String::from)
    .to_vec();
    let body = by_strategy
        .iter()
        .map(|(s, rs)| {
            let l: Vec<f64> = rs.iter().map(|r| r.max_path).collect();
            let t: Vec<f64> = rs.iter().map(|r| r.time_s).collect();
            let complete = rs
                .iter()
                .filter(|r| r.reason == "complete" || r.reason == "goal reached")
                .count();
            let mut row = vec![
                s.clone(),
                rs.len().to_string(),
                format!("{complete}/{}", rs.len()),
            ];
            match stats::summarize(&l) {
                Ok(x) => row.extend([
                    mean_sd(x.mean, x.sd, fmt),
                    fmt(x.median),
                    fmt(x.iqr),
                    fmt(x.min),
                    fmt(x.max),
                ]),
                Err(e) => row.extend([
                    e.to_string(),
                    String::new(),
                    String::new(),
                    String::new(),
                    String::new(),
                ]),
            }
            row.push(stats::shapiro_wilk(&l).map_or("–".into(), |w| format!("{:.3}", w.p_value)));
            row.push(stats::summarize(&t).map_or("–".into(), |x| mean_sd(x.mean, x.sd, fmt)));
            row
        })
        .collect();
    Block::Table(header, body)
}

/// D90/T90/D99/T99 per strategy (mean ± sd over the trials that reached the level, with
/// their count when some did not) and, for teams, the overlap ratio and idle time.
fn milestones_table(by_strategy: &BTreeMap<String, Vec<&TrialRow>>, team: bool) -> Block {
    let mut header: Vec<String> = ["strategy", "D90 (m)", "T90 (s)", "D99 (m)", "T99 (s)"]
        .map(String::from)
        .to_vec();
    if team {
        header.extend(["overlap", "idle per robot (s)"].map(String::from));
    }
    let cell = |rs: &[&TrialRow], get: &dyn Fn(&TrialRow) -> Option<f64>| {
        let v: Vec<f64> = rs.iter().filter_map(|r| get(r)).collect();
        let reached = if v.len() < rs.len() {
            format!(" ({}/{})", v.len(), rs.len())
        } else {
            String::new()
        };
        match stats::summarize(&v) {
            Ok(x) => format!("{}{reached}", mean_sd(x.mean, x.sd, fmt)),
            Err(_) => format!("–{reached}"),
        }
    };
    let body = by_strategy
        .iter()
        .map(|(s, rs)| {
            let mut row = vec![
                s.clone(),
                cell(rs, &|r| r.d90_m),
                cell(rs, &|r| r.t90_s),
                cell(rs, &|r| r.d99_m),
                cell(rs, &|r| r.t99_s),
            ];
            if team {
                row.push(cell(rs, &|r| Some(r.overlap)));
                row.push(cell(rs, &|r| {
                    let idle: Vec<f64> = serde_json::from_str(&r.idle_s).ok()?;
                    (!idle.is_empty()).then(|| idle.iter().sum::<f64>() / idle.len() as f64)
                }));
            }
            row
        })
        .collect();
    Block::Table(header, body)
}

/// The values of `a` and `b` to compare, and how (see the module doc).
/// The last item names what one observation is, for the notes under the table.
fn samples(a: &[&TrialRow], b: &[&TrialRow]) -> (Vec<f64>, Vec<f64>, Pairing, &'static str) {
    let by_trial = |rs: &[&TrialRow]| -> BTreeMap<(i64, i64), f64> {
        rs.iter()
            .map(|r| ((r.start_variant, r.trial), r.max_path))
            .collect()
    };
    let (ta, tb) = (by_trial(a), by_trial(b));
    if ta.len() >= 2 && ta.keys().eq(tb.keys()) {
        return (
            ta.into_values().collect(),
            tb.into_values().collect(),
            Pairing::Paired,
            "pairs (same start variant and trial)",
        );
    }
    let by_start = |rs: &[&TrialRow]| -> BTreeMap<i64, (f64, usize)> {
        let mut m: BTreeMap<i64, (f64, usize)> = BTreeMap::new();
        for r in rs {
            let e = m.entry(r.start_variant).or_default();
            e.0 += r.max_path;
            e.1 += 1;
        }
        m
    };
    let (sa, sb) = (by_start(a), by_start(b));
    if sa.len() >= 5 && sa.keys().eq(sb.keys()) {
        let mean =
            |m: BTreeMap<i64, (f64, usize)>| m.into_values().map(|(s, n)| s / n as f64).collect();
        return (
            mean(sa),
            mean(sb),
            Pairing::Paired,
            "pairs (start variants, means over trials)",
        );
    }
    (
        a.iter().map(|r| r.max_path).collect(),
        b.iter().map(|r| r.max_path).collect(),
        Pairing::Unpaired,
        "trials per strategy",
    )
}

/// Marks a `=` that no outcome could have turned into `+` or `-` (see [`underpowered_note`]).
const UNDERPOWERED: &str = "ⁿ";

/// One verdict of a setting's table: a vs b, the verdict, and whether it was underpowered.
type Verdicts = Vec<(String, String, Verdict, bool)>;

/// The +/=/- table of one setting, the notes to print under it (one per kind of
/// underpowered comparison), and its verdicts.
fn matrix(
    by_strategy: &BTreeMap<String, Vec<&TrialRow>>,
    alpha: f64,
) -> (Block, Vec<String>, Verdicts) {
    let names: Vec<&String> = by_strategy.keys().collect();
    let mut header = vec!["row vs column".to_string()];
    header.extend(names.iter().map(|s| (*s).clone()));
    let mut verdicts = Vec::new();
    let mut notes = std::collections::BTreeSet::new();
    let mut body = Vec::new();
    for a in &names {
        let mut row = vec![(*a).clone()];
        for b in &names {
            if a == b {
                row.push("·".into());
                continue;
            }
            let (x, y, pairing, unit) = samples(&by_strategy[*a], &by_strategy[*b]);
            match stats::compare(&x, &y, alpha, pairing) {
                Ok(c) => {
                    let weak = c.underpowered(alpha);
                    verdicts.push(((*a).clone(), (*b).clone(), c.verdict, weak));
                    let how = if pairing == Pairing::Paired { "W" } else { "U" };
                    let mark = if weak {
                        notes.insert(underpowered_note(&x, &y, pairing, unit, &c, alpha));
                        format!(" {UNDERPOWERED}")
                    } else {
                        String::new()
                    };
                    row.push(format!(
                        "{}{mark} (p={:.2e}, {how})",
                        c.verdict.symbol(),
                        c.p_value
                    ));
                }
                Err(e) => row.push(format!("? ({e})")),
            }
        }
        body.push(row);
    }
    (
        Block::Table(header, body),
        notes.into_iter().collect(),
        verdicts,
    )
}

/// The note under a table with an underpowered cell: α, the sample, the smallest p its test
/// can give, and how many observations would be needed.
fn underpowered_note(
    x: &[f64],
    y: &[f64],
    pairing: Pairing,
    unit: &str,
    c: &stats::Comparison,
    alpha: f64,
) -> String {
    let (test, sample, need) = match pairing {
        Pairing::Paired => {
            let zeros = x.iter().zip(y).filter(|(a, b)| a == b).count();
            let zeros = if zeros > 0 {
                format!(", {zeros} of them equal and dropped,")
            } else {
                String::new()
            };
            (
                "Wilcoxon signed-rank test",
                format!("{} {unit}{zeros}", x.len()),
                "pairs",
            )
        }
        Pairing::Unpaired => (
            "Mann–Whitney U test",
            format!("{} and {} {unit}", x.len(), y.len()),
            "trials per strategy",
        ),
    };
    let needed = stats::needed(alpha, pairing).map_or_else(
        || format!("more than 10,000 {need}"),
        |n| format!("at least {n} {need} (without ties or equal pairs)"),
    );
    format!(
        "{UNDERPOWERED}: with {sample} the smallest two-sided p the {test} can give is {:.2e} \
         ≥ α = {alpha}, so a = marked {UNDERPOWERED} could not be + or -: it does not show \
         that there is no difference. Significance at α = {alpha} needs {needed}, or a \
         larger --alpha.",
        c.min_p_value
    )
}

/// Mean coverage over team distance per strategy, on 41 distances from 0 to the longest.
fn coverage_curves(
    by_strategy: &BTreeMap<String, Vec<&TrialRow>>,
) -> Vec<(String, Vec<(f64, f64)>)> {
    let curves: BTreeMap<&String, Vec<Vec<(f64, f64)>>> = by_strategy
        .iter()
        .map(|(s, rs)| {
            (
                s,
                rs.iter()
                    .map(|r| {
                        serde_json::from_str::<Vec<(f64, f64)>>(&r.coverage_curve)
                            .unwrap_or_default()
                    })
                    .collect(),
            )
        })
        .collect();
    let longest = curves
        .values()
        .flatten()
        .filter_map(|c| c.last().map(|p| p.0))
        .fold(0.0, f64::max)
        .max(1e-9);
    let at = |c: &[(f64, f64)], d: f64| -> f64 {
        c.iter()
            .take_while(|p| p.0 <= d)
            .last()
            .map_or(0.0, |p| p.1)
    };
    curves
        .into_iter()
        .map(|(s, cs)| {
            let pts = (0..=40)
                .map(|k| {
                    let d = longest * k as f64 / 40.0;
                    let mean = cs.iter().map(|c| at(c, d)).sum::<f64>() / cs.len().max(1) as f64;
                    (d, mean)
                })
                .collect();
            (s.clone(), pts)
        })
        .collect()
}

fn markdown(blocks: &[Block]) -> String {
    let mut s = String::new();
    for b in blocks {
        match b {
            Block::Heading(l, t) => {
                let _ = writeln!(s, "{} {t}\n", "#".repeat(*l as usize));
            }
            Block::Para(t) => {
                let _ = writeln!(s, "{t}\n");
            }
            Block::Table(h, rows) => {
                let cell = |c: &String| c.replace('|', "\\|");
                let _ = writeln!(
                    s,
                    "| {} |",
                    h.iter().map(cell).collect::<Vec<_>>().join(" | ")
                );
                let _ = writeln!(s, "|{}", "---|".repeat(h.len()));
                for r in rows {
                    let _ = writeln!(
                        s,
                        "| {} |",
                        r.iter().map(cell).collect::<Vec<_>>().join(" | ")
                    );
                }
                s.push('\n');
            }
            Block::Svg(name, _) => {
                let _ = writeln!(s, "![{name}](plots/{name}.svg)\n");
            }
            Block::Png(name, _, None) => {
                let _ = writeln!(s, "![{name}](envs/{name}.png)\n");
            }
            Block::Png(name, _, Some(link)) => {
                let _ = writeln!(
                    s,
                    "[![{name}](envs/{name}.png)]({link}) (click the picture for a replay of one run)\n"
                );
            }
        }
    }
    s
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn html_page(scenario: &str, blocks: &[Block]) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title>\n<style>\
body{{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}}\
table{{border-collapse:collapse;margin:1em 0;font-size:90%}}td,th{{border:1px solid #bbb;padding:3px 7px;text-align:right}}\
td:first-child,th:first-child{{text-align:left}}th{{background:#eee}}img.env{{image-rendering:pixelated;max-width:500px;border:1px solid #999}}\
</style></head><body>\n",
        escape(&format!("Benchmark report: {scenario}"))
    );
    for b in blocks {
        match b {
            Block::Heading(l, t) => {
                let _ = writeln!(s, "<h{l}>{}</h{l}>", escape(t));
            }
            Block::Para(t) => {
                let _ = writeln!(s, "<p>{}</p>", escape(t));
            }
            Block::Table(h, rows) => {
                s.push_str("<table><tr>");
                for c in h {
                    let _ = write!(s, "<th>{}</th>", escape(c));
                }
                s.push_str("</tr>\n");
                for r in rows {
                    s.push_str("<tr>");
                    for c in r {
                        let _ = write!(s, "<td>{}</td>", escape(c));
                    }
                    s.push_str("</tr>\n");
                }
                s.push_str("</table>\n");
            }
            Block::Svg(_, svg) => {
                // Drop the XML declaration, if any: the SVG is inlined.
                let body = svg.find("<svg").map_or(svg.as_str(), |i| &svg[i..]);
                let _ = writeln!(s, "<div>{body}</div>");
            }
            Block::Png(name, png, link) => {
                let img = format!(
                    "<img class=\"env\" alt=\"{}\" src=\"data:image/png;base64,{}\">",
                    escape(name),
                    base64(png)
                );
                match link {
                    Some(l) => {
                        let _ = writeln!(
                            s,
                            "<a href=\"{}\" title=\"replay of one run\">{img}</a> \
                             <p><a href=\"{}\">replay of one run</a></p>",
                            escape(l),
                            escape(l)
                        );
                    }
                    None => {
                        let _ = writeln!(s, "{img}");
                    }
                }
            }
        }
    }
    s.push_str("</body></html>\n");
    s
}

#[cfg(test)]
mod tests {
    /// Regression: the report's header printed the fingerprint as the program writes it:
    /// "strategies=12" (the revision, read as a count of strategies), "goal=None",
    /// "goal=Some(1.0)".
    #[test]
    fn regression_settings_read_as_words() {
        assert_eq!(
            super::readable_settings(
                "strategies=12 seed=1 speed=1 clearance=0.3 goal=None max_moves=10 belief=known"
            ),
            "strategy revision 12, seed=1 speed=1 clearance=0.3 goal=none max_moves=10 belief=known"
        );
        assert!(super::readable_settings("strategies=12 goal=Some(0.9)").ends_with("goal=0.9"));
    }

    use super::*;

    #[test]
    fn base64_matches_rfc4648_examples() {
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc);
        }
    }
}
