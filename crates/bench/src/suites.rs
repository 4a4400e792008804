//! Built-in suites, one per paper (issue 9, "Built-in suites"): scenario files shipped in
//! the binary (`crates/bench/suites/*.toml`), resolved like users' files except that a
//! strategy which is not built yet is left out with a note instead of failing the suite.

use crate::error::BenchError;
use crate::plan::{Plan, Unbuilt};
use std::path::Path;

use crate::scenario::Source;

/// The suites: (name, one-line description, scenario text).
pub const SUITES: &[(&str, &str, &str)] = &[
    (
        "quick",
        "a small cross-section that finishes in seconds on 2 cores",
        include_str!("../suites/quick.toml"),
    ),
    (
        "holz2010",
        "Holz et al. 2010: single-robot presets on cave, office, hospital (Tables 1-3)",
        include_str!("../suites/holz2010.toml"),
    ),
    (
        "holz2010-real",
        "Holz et al. 2010 on the real floor plans in a folder (--maps DIR: its ROS .yaml maps)",
        include_str!("../suites/holz2010-real.toml"),
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
        "faigl2013-real",
        "Faigl & Kulich 2013 on the real floor plans in a folder (--maps DIR), rho = 5 m, m in {3,5}",
        include_str!("../suites/faigl2013-real.toml"),
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

/// The suites whose environments are the maps of a folder (`--maps DIR`).
pub const MAP_FOLDER_SUITES: &[&str] = &["holz2010-real", "faigl2013-real"];

/// Resolve suite `name`, leaving out strategies that are not built yet (see
/// [`Plan::skipped`]).
pub fn plan(name: &str) -> Result<Plan, BenchError> {
    plan_with_maps(name, None, None)
}

/// Resolve suite `name`; the suites of [`MAP_FOLDER_SUITES`] take their environments from
/// the ROS map_server YAML files of `maps` (sorted by file name), which they require;
/// the environments are loaded within `memory_mb` MiB ([`Plan::resolve_within`]).
pub fn plan_with_maps(
    name: &str,
    maps: Option<&Path>,
    memory_mb: Option<u64>,
) -> Result<Plan, BenchError> {
    let mut src = source(name)?;
    let wants = MAP_FOLDER_SUITES.contains(&name);
    match (wants, maps) {
        (true, None) => {
            return Err(BenchError::Other(format!(
                "--suite {name}: expected --maps DIR, a folder of ROS map_server .yaml maps \
                 (the repository's maps/ holds three real floor plans)"
            )));
        }
        (false, Some(_)) => {
            return Err(BenchError::Other(format!(
                "--maps: suite '{name}' has its own environments; --maps goes with {}",
                MAP_FOLDER_SUITES.join(", ")
            )));
        }
        (true, Some(dir)) => {
            let files = yaml_maps(dir)?;
            for f in &files {
                src.text
                    .push_str(&format!("\n[[env]]\nmap = \"{}\"\n", toml_escape(f)));
            }
            src.dir = Some(dir.to_path_buf());
        }
        (false, None) => {}
    }
    Plan::resolve_within(&src, Unbuilt::Skip, memory_mb)
}

/// The file names of the `.yaml` / `.yml` files in `dir`, sorted; an error when there are
/// none or the folder cannot be read.
pub fn yaml_maps(dir: &Path) -> Result<Vec<String>, BenchError> {
    let entries = std::fs::read_dir(dir).map_err(BenchError::io(dir))?;
    let mut names = Vec::new();
    for e in entries {
        let e = e.map_err(BenchError::io(dir))?;
        let name = e.file_name().to_string_lossy().into_owned();
        let lower = name.to_ascii_lowercase();
        if (lower.ends_with(".yaml") || lower.ends_with(".yml")) && e.path().is_file() {
            names.push(name);
        }
    }
    names.sort();
    if names.is_empty() {
        return Err(BenchError::Other(format!(
            "--maps {}: expected ROS map_server .yaml maps in the folder, found none \
             (a bare .png or .pgm needs a .yaml beside it giving its resolution)",
            dir.display()
        )));
    }
    Ok(names)
}

/// `s` as the inside of a TOML basic string.
fn toml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '"' => out.push_str("\\\""),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out
}
