//! Scenario files built from structure: well-formed TOML with every key the schema has,
//! names mostly drawn from the valid ones and numbers anywhere, so the fuzzer spends its
//! time in `Plan::resolve`'s checks rather than in the TOML parser. Environment sizes stay
//! small (a big valid environment is slow to generate, not wrong).
#![no_main]
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;

const KINDS: &[&str] = &["maze", "office", "hospital", "cave", "potholes", "empty"];
const SENSORS: &[&str] = &[
    "los:r=3c",
    "los:r=1",
    "footprint:r=2c",
    "lidar:r=2,fov=90",
    "sonar",
    "laser",
];
const STRATEGIES: &[&str] = &[
    "cf",
    "cf-rr",
    "random",
    "yamauchi",
    "ha-cc",
    "cf-rr-seg",
    "mtsp",
];
const BELIEFS: &[&str] = &["known", "reflection", "evidence"];
const SENSINGS: &[&str] = &["continuous", "on-arrival"];

/// A name from `list`, or any text.
#[derive(Debug, Arbitrary)]
enum Name {
    Known(u8),
    Other(String),
}

impl Name {
    fn get(&self, list: &[&str]) -> String {
        match self {
            Name::Known(i) => list[usize::from(*i) % list.len()].to_string(),
            Name::Other(s) => s.clone(),
        }
    }
}

#[derive(Debug, Arbitrary)]
struct Env {
    kind: Name,
    seeds: Vec<i64>,
    count: Option<i64>,
    size: (u8, u8),
    resolution: u8,
    start: Option<(i64, i64)>,
    border: Option<bool>,
}

#[derive(Debug, Arbitrary)]
struct Scenario {
    seed: Option<i64>,
    robots: Vec<i64>,
    sensors: Vec<Name>,
    strategies: Vec<Name>,
    presets: Vec<(Name, Option<i64>, Option<String>)>,
    s_max: Option<i64>,
    trials: Option<i64>,
    repeat_deterministic: Option<bool>,
    perturbations: Option<i64>,
    radius: Option<f64>,
    speed: Option<f64>,
    clearance: Option<f64>,
    coverage_goal: Option<f64>,
    max_moves: Option<i64>,
    belief: Option<Name>,
    sensing: Option<Name>,
    optimal: Option<(
        Option<i64>,
        Option<i64>,
        Option<f64>,
        Option<i64>,
        Option<i64>,
    )>,
    envs: Vec<Env>,
}

/// A TOML float (TOML spells the non-finite ones nan, inf and -inf).
fn float(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{v:?}")
    }
}

fn quoted(s: &str) -> String {
    format!("{s:?}")
}

fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    let items: Vec<String> = items.iter().map(f).collect();
    format!("[{}]", items.join(", "))
}

impl Scenario {
    fn toml(&self) -> String {
        let mut t = String::from("name = \"fuzz\"\n");
        let mut key = |k: &str, v: Option<String>| {
            if let Some(v) = v {
                t.push_str(&format!("{k} = {v}\n"));
            }
        };
        key("seed", self.seed.map(|v| v.to_string()));
        key("robots", Some(list(&self.robots, |v| v.to_string())));
        key(
            "sensors",
            Some(list(&self.sensors, |n| quoted(&n.get(SENSORS)))),
        );
        key(
            "strategies",
            Some(list(&self.strategies, |n| quoted(&n.get(STRATEGIES)))),
        );
        key("s_max", self.s_max.map(|v| v.to_string()));
        key("trials", self.trials.map(|v| v.to_string()));
        key(
            "repeat_deterministic",
            self.repeat_deterministic.map(|v| v.to_string()),
        );
        key("perturbations", self.perturbations.map(|v| v.to_string()));
        key("radius", self.radius.map(float));
        key("speed", self.speed.map(float));
        key("clearance", self.clearance.map(float));
        key("coverage_goal", self.coverage_goal.map(float));
        key("max_moves", self.max_moves.map(|v| v.to_string()));
        key(
            "belief",
            self.belief.as_ref().map(|n| quoted(&n.get(BELIEFS))),
        );
        key(
            "sensing",
            self.sensing.as_ref().map(|n| quoted(&n.get(SENSINGS))),
        );
        for (preset, s_max, label) in &self.presets {
            t.push_str(&format!(
                "\n[[strategy]]\npreset = {}\n",
                quoted(&preset.get(STRATEGIES))
            ));
            if let Some(s) = s_max {
                t.push_str(&format!("s_max = {s}\n"));
            }
            if let Some(l) = label {
                t.push_str(&format!("label = {}\n", quoted(l)));
            }
        }
        if let Some((cell_size, min_cluster, weight, max_nodes, memory_mb)) = &self.optimal {
            t.push_str("\n[optimal]\n");
            let mut key = |k: &str, v: Option<String>| {
                if let Some(v) = v {
                    t.push_str(&format!("{k} = {v}\n"));
                }
            };
            key("cell_size", cell_size.map(|v| v.to_string()));
            key("min_cluster", min_cluster.map(|v| v.to_string()));
            key("weight", weight.map(float));
            key("max_nodes", max_nodes.map(|v| v.to_string()));
            key("memory_mb", memory_mb.map(|v| v.to_string()));
        }
        for e in self.envs.iter().take(3) {
            let resolution = [0.25, 0.5, 1.0, 0.0, -1.0][usize::from(e.resolution) % 5];
            t.push_str(&format!(
                "\n[[env]]\nkind = {}\nseeds = {}\nsize = [{}, {}]\nresolution = {resolution}\n",
                quoted(&e.kind.get(KINDS)),
                list(&e.seeds, |v| v.to_string()),
                e.size.0 % 24,
                e.size.1 % 24,
            ));
            if let Some(c) = e.count {
                t.push_str(&format!("count = {c}\n"));
            }
            if let Some((x, y)) = e.start {
                t.push_str(&format!("start = [{x}, {y}]\n"));
            }
            if let Some(b) = e.border {
                t.push_str(&format!("border = {b}\n"));
            }
        }
        t
    }
}

fuzz_target!(|s: Scenario| {
    let src = bench::Source {
        file: "fuzz.toml".into(),
        text: s.toml(),
        dir: None,
    };
    let _ = bench::Plan::resolve(&src, bench::Unbuilt::Error);
});
