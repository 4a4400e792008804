//! Holz et al. 2010's Tables 1–3 beside a study's own means (suites `holz2010` and
//! `holz2010-real`).
//!
//! The paper reports mean path length ± standard deviation to full coverage over 10 runs
//! in three environments: Stage's cave (Table 1), the AVZ building's 5th floor (Table 2) and
//! Stage's hospital (Table 3). Absolute lengths are not comparable with a grid robot's (see
//! the guide), so the comparison table gives each mean as a ratio to closest frontier
//! (`cf`) too, and [`ordering`] checks the paper's ordering random > dt > cf > cf-rr ≥
//! cf-rr-seg.

use std::collections::BTreeMap;

use crate::store::TrialRow;

/// One of the paper's tables: environment and (strategy, mean m, sd m) rows.
pub struct PaperTable {
    /// The environment, as the paper names it.
    pub env: &'static str,
    /// (our preset, mean path length m, standard deviation m).
    pub rows: &'static [(&'static str, f64, f64)],
}

/// Tables 1–3 of Holz et al. 2010 (decision-theoretic n = 100 is `dt`, n = 500 `dt500`).
pub const TABLES: [PaperTable; 3] = [
    PaperTable {
        env: "cave (T1)",
        rows: &[
            ("random", 102.84, 34.50),
            ("cf", 73.71, 1.00),
            ("cf-rr", 70.45, 0.97),
            ("cf-rr-seg", 72.89, 5.77),
            ("dt", 100.01, 17.64),
            ("dt500", 98.27, 11.76),
        ],
    },
    PaperTable {
        env: "AVZ (T2)",
        rows: &[
            ("random", 601.51, 141.93),
            ("cf", 382.07, 3.99),
            ("cf-rr", 361.88, 3.01),
            ("cf-rr-seg", 359.77, 12.91),
            ("dt500", 447.68, 32.78),
        ],
    },
    PaperTable {
        env: "hospital (T3)",
        rows: &[
            ("random", 669.17, 186.41),
            ("cf", 281.07, 3.82),
            ("cf-rr", 253.09, 3.12),
            ("cf-rr-seg", 221.37, 19.97),
            ("dt500", 312.68, 38.11),
        ],
    },
];

/// The strategies of the tables, in the paper's order.
pub const STRATEGIES: [&str; 6] = ["random", "cf", "cf-rr", "cf-rr-seg", "dt", "dt500"];

fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    // One value has no sample standard deviation: NaN, and the table shows the mean alone.
    let var = if v.len() > 1 {
        v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0)
    } else {
        f64::NAN
    };
    (m, var.sqrt())
}

/// (mean, sd) of path length per strategy of one environment.
type ByStrategy = BTreeMap<String, (f64, f64)>;

/// Mean path length per (environment, strategy) of `rows`, environments in first-seen order.
fn means(rows: &[TrialRow]) -> Vec<(String, ByStrategy)> {
    let mut envs: Vec<(String, BTreeMap<String, Vec<f64>>)> = Vec::new();
    for r in rows {
        let slot = match envs.iter().position(|(e, _)| *e == r.env) {
            Some(k) => k,
            None => {
                envs.push((r.env.clone(), BTreeMap::new()));
                envs.len() - 1
            }
        };
        envs[slot]
            .1
            .entry(r.strategy.clone())
            .or_default()
            .push(r.max_path);
    }
    envs.into_iter()
        .map(|(e, m)| (e, m.into_iter().map(|(s, v)| (s, mean_sd(&v))).collect()))
        .collect()
}

/// The comparison table: a row per strategy, a column per environment of `rows` (mean ±
/// sd, and × the environment's `cf` mean) and per paper table; `None` when `rows` hold no
/// strategy of the tables.
pub fn comparison(rows: &[TrialRow]) -> Option<(Vec<String>, Vec<Vec<String>>)> {
    let ours = means(rows);
    if !ours
        .iter()
        .any(|(_, m)| STRATEGIES.iter().any(|s| m.contains_key(*s)))
    {
        return None;
    }
    let mut header = vec!["strategy".to_string()];
    header.extend(ours.iter().map(|(e, _)| format!("{e} (ours)")));
    header.extend(TABLES.iter().map(|t| format!("{} (paper)", t.env)));
    let f = |x: f64| format!("{x:.1}");
    let cell = |m: Option<(f64, f64)>, cf: Option<f64>| match (m, cf) {
        (Some((m, sd)), Some(cf)) if cf > 0.0 => {
            format!("{} (×{:.2})", crate::report::mean_sd(m, sd, f), m / cf)
        }
        (Some((m, sd)), _) => crate::report::mean_sd(m, sd, f),
        (None, _) => "–".to_string(),
    };
    let body = STRATEGIES
        .iter()
        .map(|&s| {
            let mut row = vec![s.to_string()];
            for (_, m) in &ours {
                row.push(cell(m.get(s).copied(), m.get("cf").map(|x| x.0)));
            }
            for t in &TABLES {
                let get = |name: &str| {
                    t.rows
                        .iter()
                        .find(|r| r.0 == name)
                        .map(|&(_, m, sd)| (m, sd))
                };
                row.push(cell(get(s), get("cf").map(|x| x.0)));
            }
            row
        })
        .collect();
    Some((header, body))
}

/// Per environment of `rows`, whether the paper's ordering holds between the strategies
/// present — random > dt and dt500 > cf > cf-rr ≥ cf-rr-seg on mean path length — and the
/// first pair that breaks it.
pub fn ordering(rows: &[TrialRow]) -> Vec<(String, Result<(), String>)> {
    const PAIRS: [(&str, &str, bool); 6] = [
        ("random", "dt", true),
        ("random", "dt500", true),
        ("dt", "cf", true),
        ("dt500", "cf", true),
        ("cf", "cf-rr", true),
        ("cf-rr", "cf-rr-seg", false),
    ];
    means(rows)
        .into_iter()
        .map(|(env, m)| {
            let broken = PAIRS.iter().find_map(|&(a, b, strict)| {
                let (x, y) = (m.get(a)?.0, m.get(b)?.0);
                let holds = if strict { x > y } else { x >= y };
                (!holds).then(|| {
                    let sign = if strict { ">" } else { "≥" };
                    format!("{a} {sign} {b} fails ({x:.1} against {y:.1} m)")
                })
            });
            (env, broken.map_or(Ok(()), Err))
        })
        .collect()
}
