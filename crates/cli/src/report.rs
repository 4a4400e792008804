//! What a run prints: the human summary, the JSON summary and the trace file.

use std::io::Write;

use serde::Serialize;
use serde_json::{Value, json};
use sim::{RunConfig, RunResult};

use crate::args::Truth;

fn cell_json(map: &grid::Grid<grid::Occ>, i: u32) -> Value {
    let c = map.cell(i as usize);
    json!([c.x, c.y])
}

/// Round to `digits` decimals so that JSON stays short and stable.
fn round(v: f64, digits: i32) -> f64 {
    let f = 10f64.powi(digits);
    (v * f).round() / f
}

/// The JSON summary of a run (`timing`: include wall-clock times).
pub fn summary_json(truth: &Truth, cfg: &RunConfig, r: &RunResult, timing: bool) -> Value {
    bench::explore::summary_json(&truth.name, &truth.map, cfg, r, timing)
}

/// A list of flat cell indices, written as a JSON array of `[x, y]` one cell at a time.
struct CellList<'a> {
    cells: &'a grid::Grid<grid::Occ>,
    list: Vec<u32>,
}

impl Serialize for CellList<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.list.iter().map(|&i| cell_json(self.cells, i)))
    }
}

/// Write `items` as a JSON array, one element at a time: a run's trace can hold millions
/// of events, and a JSON tree of them all took 28 times the memory of the run itself.
fn write_seq<W: Write, T: Serialize>(
    w: &mut W,
    items: impl Iterator<Item = T>,
) -> serde_json::Result<()> {
    w.write_all(b"[").map_err(serde_json::Error::io)?;
    for (k, item) in items.enumerate() {
        if k > 0 {
            w.write_all(b",").map_err(serde_json::Error::io)?;
        }
        serde_json::to_writer(&mut *w, &item)?;
    }
    w.write_all(b"]").map_err(serde_json::Error::io)
}

/// Write `key` and the array `items` (or `null` without a trace), then `,`.
fn write_field<W: Write, T: Serialize, I: Iterator<Item = T>>(
    w: &mut W,
    key: &str,
    items: Option<I>,
) -> serde_json::Result<()> {
    write!(w, "\"{key}\":").map_err(serde_json::Error::io)?;
    match items {
        Some(items) => write_seq(w, items)?,
        None => w.write_all(b"null").map_err(serde_json::Error::io)?,
    }
    w.write_all(b",").map_err(serde_json::Error::io)
}

/// Write the trace file of a run (`trace.json`: trails, goals, events, the
/// decision-theoretic samples, frontier cells left) to `w`, compact, keys in order,
/// element by element.
pub fn write_trace_json<W: Write>(
    w: &mut W,
    truth: &Truth,
    cfg: &RunConfig,
    r: &RunResult,
) -> serde_json::Result<()> {
    let cells = &truth.map.cells;
    let trace = r.trace.as_ref();
    let io = serde_json::Error::io;
    let scalar = |w: &mut W, key: &str, v: Value| -> serde_json::Result<()> {
        write!(w, "\"{key}\":{v},").map_err(io)
    };
    w.write_all(b"{").map_err(io)?;
    write_field(
        w,
        "dt_decisions",
        trace.map(|t| {
            t.dt.iter().map(|d| {
                json!({
                    "event": d.event, "robot": d.robot, "fell_back": d.fell_back,
                    "chosen": d.chosen.map(|c| cell_json(cells, c)),
                    "samples": d.samples.iter().map(|s| json!([cell_json(cells, s.cell), round(s.gain, 3), if s.cost_m.is_finite() { json!(round(s.cost_m, 3)) } else { Value::Null }, round(s.utility, 6)])).collect::<Vec<_>>(),
                })
            })
        }),
    )?;
    scalar(w, "env", json!(truth.name))?;
    write_field(
        w,
        "events",
        trace.map(|t| {
            t.events.iter().map(|e| {
                json!([
                    round(e.t, 4),
                    e.robot,
                    cell_json(cells, e.cell),
                    round(e.dist_m, 4),
                    round(e.coverage, 6),
                    e.frontiers
                ])
            })
        }),
    )?;
    write_field(
        w,
        "frontiers_left",
        Some(r.frontiers_left.iter().map(|&i| cell_json(cells, i))),
    )?;
    write_field(
        w,
        "goals",
        trace.map(|t| {
            t.goals.iter().map(|g| {
                json!({
                    "t": round(t.events.get((g.event as usize).saturating_sub(1)).map_or(0.0, |e| e.t), 4),
                    "event": g.event, "robot": g.robot, "goal": g.goal.map(|c| cell_json(cells, c)),
                })
            })
        }),
    )?;
    scalar(w, "height", json!(cells.height()))?;
    scalar(w, "resolution", json!(truth.map.resolution))?;
    scalar(w, "seed", json!(cfg.seed))?;
    scalar(w, "strategy", json!(cfg.strategy.name))?;
    write_field(
        w,
        "trails",
        trace.map(|t| t.trails().into_iter().map(|list| CellList { cells, list })),
    )?;
    write!(w, "\"width\":{}}}", cells.width()).map_err(io)
}

/// A few lines for people.
pub fn summary_text(truth: &Truth, cfg: &RunConfig, r: &RunResult) -> String {
    let mut s = String::new();
    let (w, h) = (truth.map.width(), truth.map.height());
    s += &format!(
        "{} ({}x{} cells at {} m) · strategy {} · {} robot(s) · sensor {} ({}) · seed {}\n",
        truth.name,
        w,
        h,
        truth.map.resolution,
        cfg.strategy.name,
        cfg.robots,
        cfg.sensor,
        cfg.sensing_mode(),
        cfg.seed
    );
    let of = match cfg.coverage {
        sim::CoverageKind::ReachableFree => format!("of {} reachable cells", r.reachable_cells),
        sim::CoverageKind::Known => "of the cells the map knows (--coverage known)".to_string(),
    };
    s += &format!(
        "ended: {} · coverage {:.2} % {of}\n",
        r.reason.as_str(),
        r.coverage * 100.0,
    );
    if r.path_length_m.len() == 1 {
        s += &format!(
            "path length {:.2} m · time {:.1} s at {} m/s\n",
            r.path_length_m[0], r.time_s, cfg.speed
        );
    } else {
        let each: Vec<String> = r.path_length_m.iter().map(|l| format!("{l:.1}")).collect();
        s += &format!(
            "path lengths [{}] m · L = max {:.2} m · total {:.2} m · time {:.1} s\n",
            each.join(", "),
            r.max_path_length_m(),
            r.total_path_length_m(),
            r.time_s
        );
    }
    let a = &r.audit;
    s += &format!(
        "map: {:.2} % of the building's cells right · {} phantom free cells",
        a.accuracy * 100.0,
        a.false_free_cells
    );
    if a.clutter_cells > 0 {
        s += &format!(
            " · {} of {} off-plane clutter cells mapped",
            a.clutter_mapped, a.clutter_cells
        );
    }
    if a.phantom_regions > 0 {
        s += &format!(
            " · {:.2} phantom frontier regions per decision, {} goals on phantoms",
            a.phantom_regions_mean(r.decisions),
            a.phantom_goals
        );
    }
    s += "\n";
    s += &format!(
        "{} decisions, {} moves · wall time {:.0} ms (sense {:.0}, frontier upkeep {:.0}, decide {:.0})\n",
        r.decisions,
        r.moves,
        r.times.total_s * 1e3,
        r.times.sense_s * 1e3,
        r.times.upkeep_s * 1e3,
        r.times.decide_s * 1e3
    );
    s
}
