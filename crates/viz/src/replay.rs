//! A self-contained HTML page that replays a run in the browser: inline script and data,
//! no network, no server. The trace is stored compactly — the belief changes of each
//! event as packed little-endian `u32` (cell << 2 | class), the ground truth run-length
//! encoded — base64 in one JSON object, so a long run on a 1000 × 1000 map stays a few MB.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use grid::GridMap;
use serde_json::json;
use sim::RunResult;

use crate::VizError;

const TEMPLATE: &str = include_str!("replay.html");

fn b64_u32(v: impl Iterator<Item = u32>) -> String {
    let bytes: Vec<u8> = v.flat_map(u32::to_le_bytes).collect();
    STANDARD.encode(bytes)
}

fn b64_f64(v: impl Iterator<Item = f64>) -> String {
    let bytes: Vec<u8> = v.flat_map(f64::to_le_bytes).collect();
    STANDARD.encode(bytes)
}

/// Run-length encoding of the ground truth: (run length << 2 | class) per run; class 0
/// outside, 1 free, 2 occupied, 3 off-plane clutter.
fn rle(cells: &[u32]) -> Vec<u32> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < cells.len() {
        let v = cells[i];
        let mut n = 1usize;
        while i + n < cells.len() && cells[i + n] == v && n < (1 << 29) {
            n += 1;
        }
        out.push(((n as u32) << 2) | v);
        i += n;
    }
    out
}

/// The replay page of a run (needs the run's trace). `title` names the run; `meta` is shown
/// as given (e.g. strategy, sensor, seed).
pub fn replay_html(
    truth: &GridMap,
    result: &RunResult,
    title: &str,
    meta: &str,
) -> Result<String, VizError> {
    let trace = result.trace.as_ref().ok_or(VizError::NoTrace)?;
    let cells = &truth.cells;
    let candidate_events: Vec<u32> = trace.candidates.iter().map(|c| c.0).collect();
    let mut candidate_ends = Vec::with_capacity(trace.candidates.len());
    let mut candidate_cells = Vec::new();
    for (_, cs) in &trace.candidates {
        candidate_cells.extend_from_slice(cs);
        candidate_ends.push(candidate_cells.len() as u32);
    }
    let seg_events: Vec<u32> = trace.segments.iter().map(|x| x.event).collect();
    let mut seg_ends = Vec::with_capacity(trace.segments.len());
    let mut seg_runs = Vec::new();
    for snap in &trace.segments {
        for &(label, n) in &snap.runs {
            seg_runs.push(label);
            seg_runs.push(n);
        }
        seg_ends.push(seg_runs.len() as u32 / 2);
    }
    let truth_classes: Vec<u32> = (0..cells.len())
        .map(|i| match &result.clutter {
            Some(c) if c[i] => 3,
            _ => cells[i] as u32,
        })
        .collect();
    let data = json!({
        "title": title,
        "meta": meta,
        "width": cells.width(),
        "height": cells.height(),
        "resolution": truth.resolution,
        "robots": trace.robots,
        "starts": trace.starts,
        "truth": STANDARD.encode(rle(&truth_classes).iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>()),
        "clutter": result.clutter.as_ref().is_some_and(|c| c.data().iter().any(|&v| v)),
        "changes": b64_u32(trace.changes.iter().map(|&(c, s)| (c << 2) | s as u32)),
        "changeEnds": b64_u32(trace.change_ends.iter().copied()),
        "evRobot": b64_u32(trace.events.iter().map(|e| e.robot)),
        "evCell": b64_u32(trace.events.iter().map(|e| e.cell)),
        "evFrontiers": b64_u32(trace.events.iter().map(|e| e.frontiers)),
        "evT": b64_f64(trace.events.iter().map(|e| e.t)),
        "evDist": b64_f64(trace.events.iter().map(|e| e.dist_m)),
        "evCoverage": b64_f64(trace.events.iter().map(|e| e.coverage)),
        "goalEvent": b64_u32(trace.goals.iter().map(|g| g.event)),
        "goalRobot": b64_u32(trace.goals.iter().map(|g| g.robot)),
        "goalCell": b64_u32(trace.goals.iter().map(|g| g.goal.unwrap_or(u32::MAX))),
        "candEvent": b64_u32(candidate_events.into_iter()),
        "candEnds": b64_u32(candidate_ends.into_iter()),
        "candCells": b64_u32(candidate_cells.into_iter()),
        "segEvent": b64_u32(seg_events.into_iter()),
        "segEnds": b64_u32(seg_ends.into_iter()),
        "segRuns": b64_u32(seg_runs.into_iter()),
        "segColours": crate::SEGMENT_COLOURS,
        "colours": crate::ROBOT_COLOURS,
    });
    // `</` cannot appear in the JSON of numbers, base64 and our names, but escape it anyway
    // so that no title can close the script element.
    let data = data.to_string().replace("</", "<\\/");
    Ok(TEMPLATE
        .replacen("/*DATA*/null", &data, 1)
        .replacen("<!--TITLE-->", &html_escape(title), 1))
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
