//! Built-in suites, one per paper (issue 9, "Built-in suites"): scenario files shipped in
//! the binary (`crates/bench/suites/*.toml`), resolved like users' files except that a
//! strategy which is not built yet is left out with a note instead of failing the suite.

use crate::error::BenchError;
use crate::plan::{Plan, Unbuilt};
use crate::scenario::Source;

/// The suites: (name, one-line description, scenario text).
pub const SUITES: &[(&str, &str, &str)] = &[
    (
        "quick",
        "a small cross-section that finishes in about a minute on 2 cores",
        include_str!("../suites/quick.toml"),
    ),
    (
        "holz2010",
        "Holz et al. 2010: single-robot presets on cave, office, hospital (Tables 1-3)",
        include_str!("../suites/holz2010.toml"),
    ),
    (
        "multirobot",
        "multi-robot study: nearest, greedy, greedy-utility, MinPos with 1..8 robots",
        include_str!("../suites/multirobot.toml"),
    ),
    (
        "faigl2013",
        "Faigl & Kulich 2013: AF/RFE/CC x GA/IA/HA/MA/SGA, m in {3,5,7,10}, rho in {3,5,7} m",
        include_str!("../suites/faigl2013.toml"),
    ),
    (
        "quattrini2012",
        "Quattrini Li et al. 2012: online strategies with sensing on arrival",
        include_str!("../suites/quattrini2012.toml"),
    ),
];

/// The scenario source of suite `name`.
pub fn source(name: &str) -> Result<Source, BenchError> {
    let (_, _, text) = SUITES.iter().find(|(n, _, _)| *n == name).ok_or_else(|| {
        let names: Vec<&str> = SUITES.iter().map(|(n, _, _)| *n).collect();
        BenchError::Other(format!(
            "--suite: unknown suite '{name}', expected one of {}",
            names.join(", ")
        ))
    })?;
    Ok(Source {
        file: format!("suite:{name}"),
        text: (*text).to_string(),
        dir: None,
    })
}

/// Resolve suite `name`, leaving out strategies that are not built yet (see
/// [`Plan::skipped`]).
pub fn plan(name: &str) -> Result<Plan, BenchError> {
    Plan::resolve(&source(name)?, Unbuilt::Skip)
}
