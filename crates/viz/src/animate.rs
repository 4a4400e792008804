//! Animated GIF of a run: the belief growing over the faint ground truth, frontier cells,
//! goal candidates, each robot's trail, position and current goal — frames sampled evenly
//! over the run's events so that a person can follow it.

use std::borrow::Cow;

use explore::FrontierUpkeep;
use grid::{Grid, GridMap, Occ};
use sim::RunResult;

use crate::VizError;

/// How the animation is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GifOptions {
    /// At most this many frames (the last one is held longer).
    pub max_frames: usize,
    /// The longer side of a frame, in pixels, at most (small maps are upscaled by a whole
    /// factor up to this; large maps are downscaled by a whole factor).
    pub max_side: u32,
    /// Delay between frames in hundredths of a second.
    pub delay_cs: u16,
}

impl Default for GifOptions {
    fn default() -> Self {
        Self {
            max_frames: 150,
            max_side: 640,
            delay_cs: 8,
        }
    }
}

// Palette indices.
use crate::{CLUTTER_MAPPED, CLUTTER_MISSED, CLUTTER_UNKNOWN};

const UNKNOWN_FREE: u8 = 0;
const UNKNOWN_OCCUPIED: u8 = 1;
const OUTSIDE: u8 = 2;
const FREE: u8 = 3;
const OCCUPIED: u8 = 4;
const FRONTIER: u8 = 5;
const CANDIDATE: u8 = 6;
const GOAL: u8 = 7;
const ROBOT0: u8 = 8;
const START: u8 = 16;
/// Off-plane clutter: unseen, believed free, believed occupied (as in the final picture).
const CLUTTER0: u8 = 17;
const NONE: u8 = 255;
/// First palette index of the segment tints.
const SEG0: u8 = 32;

fn palette() -> Vec<u8> {
    let mut p: Vec<[u8; 3]> = vec![
        [226, 228, 236],
        [178, 180, 190],
        [205, 205, 205],
        [255, 255, 255],
        [25, 25, 25],
        [220, 30, 30],
        [255, 160, 0],
        [200, 0, 200],
    ];
    p.extend(crate::ROBOT_COLOURS);
    p.push([0, 150, 0]);
    p.extend([CLUTTER_UNKNOWN, CLUTTER_MISSED, CLUTTER_MAPPED]);
    p.resize(SEG0 as usize, [0, 0, 0]);
    // Segments: each colour at 35 % over known-free white.
    p.extend(
        crate::SEGMENT_COLOURS
            .iter()
            .map(|c| c.map(|v| (255.0 * 0.65 + f64::from(v) * 0.35).round() as u8)),
    );
    p.resize(64, [0, 0, 0]);
    p.concat()
}

/// Pixel geometry: `up` pixels per cell when upscaling, or one pixel per `down` cells.
#[derive(Clone, Copy)]
struct Geometry {
    up: u32,
    down: u32,
    width: u32,
    height: u32,
}

fn geometry(w: usize, h: usize, max_side: u32) -> Geometry {
    let longest = w.max(h).max(1) as u32;
    let max_side = max_side.max(16);
    if longest <= max_side {
        let up = (max_side / longest).clamp(1, 12);
        Geometry {
            up,
            down: 1,
            width: w as u32 * up,
            height: h as u32 * up,
        }
    } else {
        let down = longest.div_ceil(max_side);
        Geometry {
            up: 1,
            down,
            width: (w as u32).div_ceil(down),
            height: (h as u32).div_ceil(down),
        }
    }
}

impl Geometry {
    /// Top-left pixel of cell (x, y) and the side of its square.
    fn cell_px(&self, x: i32, y: i32) -> (i64, i64, i64) {
        if self.down > 1 {
            (
                i64::from(x) / i64::from(self.down),
                i64::from(y) / i64::from(self.down),
                1,
            )
        } else {
            (
                i64::from(x) * i64::from(self.up),
                i64::from(y) * i64::from(self.up),
                i64::from(self.up),
            )
        }
    }

    fn centre_px(&self, x: i32, y: i32) -> (i64, i64) {
        let (px, py, s) = self.cell_px(x, y);
        (px + s / 2, py + s / 2)
    }

    fn put(&self, buf: &mut [u8], x: i64, y: i64, c: u8) {
        if x >= 0 && y >= 0 && (x as u32) < self.width && (y as u32) < self.height {
            buf[(y as u32 * self.width + x as u32) as usize] = c;
        }
    }

    fn fill_cell(&self, buf: &mut [u8], x: i32, y: i32, c: u8) {
        let (px, py, s) = self.cell_px(x, y);
        for dy in 0..s {
            for dx in 0..s {
                self.put(buf, px + dx, py + dy, c);
            }
        }
    }

    fn square(&self, buf: &mut [u8], (cx, cy): (i64, i64), r: i64, fill: u8, edge: u8) {
        for y in -r..=r {
            for x in -r..=r {
                let c = if x.abs() == r || y.abs() == r {
                    edge
                } else {
                    fill
                };
                self.put(buf, cx + x, cy + y, c);
            }
        }
    }

    fn line(&self, buf: &mut [u8], p0: (i64, i64), p1: (i64, i64), c: u8) {
        crate::bresenham(p0, p1, |x, y| self.put(buf, x, y, c));
    }
}

/// The event index shown by each frame: evenly spaced, ending at the last event.
pub fn frame_events(events: usize, max_frames: usize) -> Vec<usize> {
    let frames = events.min(max_frames.max(1));
    (1..=frames).map(|k| k * events / frames - 1).collect()
}

/// Encode the run as an animated GIF (needs the run's trace).
pub fn animate_gif(
    truth: &GridMap,
    result: &RunResult,
    opts: &GifOptions,
) -> Result<Vec<u8>, VizError> {
    let trace = result.trace.as_ref().ok_or(VizError::NoTrace)?;
    let cells = &truth.cells;
    let (w, h) = (cells.width(), cells.height());
    let g = geometry(w, h, opts.max_side);
    let (gw, gh) = (
        u16::try_from(g.width).map_err(|_| VizError::TooLarge(g.width))?,
        u16::try_from(g.height).map_err(|_| VizError::TooLarge(g.height))?,
    );
    let mut out = Vec::new();
    {
        let mut enc = gif::Encoder::new(&mut out, gw, gh, &palette())
            .map_err(|e| VizError::Gif(e.to_string()))?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| VizError::Gif(e.to_string()))?;
        let mut known = Grid::new(w, h, Occ::Unknown);
        let mut upkeep = FrontierUpkeep::new(w, h, result.clearance_cells);
        let mut changed: Vec<u32> = Vec::new();
        let mut trails = vec![NONE; (g.width * g.height) as usize];
        let mut last_px: Vec<(i64, i64)> = trace
            .starts
            .iter()
            .map(|&s| {
                let c = cells.cell(s as usize);
                g.centre_px(c.x, c.y)
            })
            .collect();
        let mut robot_cell: Vec<u32> = trace.starts.clone();
        let mut goal: Vec<Option<u32>> = vec![None; trace.robots];
        let mut next_goal = 0usize;
        let mut candidates: &[u32] = &[];
        let mut next_candidates = 0usize;
        let mut segments: Option<Vec<u32>> = None;
        let mut next_segments = 0usize;
        let mut buf = vec![0u8; (g.width * g.height) as usize];
        let frames = frame_events(trace.events.len(), opts.max_frames);
        let mut done = 0usize;
        for (f, &upto) in frames.iter().enumerate() {
            while done <= upto {
                changed.clear();
                for &(c, state) in trace.changes_of(done) {
                    known[c as usize] = state;
                    changed.push(c);
                }
                upkeep.update(&known, &changed);
                let e = trace.events[done];
                let r = e.robot as usize;
                let c = cells.cell(e.cell as usize);
                let p = g.centre_px(c.x, c.y);
                g.line(&mut trails, last_px[r], p, ROBOT0 + (r % 8) as u8);
                last_px[r] = p;
                robot_cell[r] = e.cell;
                done += 1;
                while next_goal < trace.goals.len() && trace.goals[next_goal].event as usize <= done
                {
                    let d = trace.goals[next_goal];
                    goal[d.robot as usize] = d.goal;
                    next_goal += 1;
                }
                while next_candidates < trace.candidates.len()
                    && trace.candidates[next_candidates].0 as usize <= done
                {
                    candidates = &trace.candidates[next_candidates].1;
                    next_candidates += 1;
                }
                while next_segments < trace.segments.len()
                    && trace.segments[next_segments].event as usize <= done
                {
                    segments = Some(trace.segments[next_segments].labels());
                    next_segments += 1;
                }
            }
            // Base layer: belief over faint truth.
            for y in 0..h {
                for x in 0..w {
                    let i = y * w + x;
                    let c = match (known[i], cells[i]) {
                        (Occ::Free, _) => match segments.as_ref().and_then(|l| l.get(i)) {
                            Some(&l) if l != u32::MAX => {
                                SEG0 + (l as usize % crate::SEGMENT_COLOURS.len()) as u8
                            }
                            _ => FREE,
                        },
                        (Occ::Occupied, _) => OCCUPIED,
                        (Occ::Unknown, Occ::Free) => UNKNOWN_FREE,
                        (Occ::Unknown, Occ::Occupied) => UNKNOWN_OCCUPIED,
                        (Occ::Unknown, Occ::Unknown) => OUTSIDE,
                    };
                    let c = match &result.clutter {
                        Some(cl) if cl[i] => CLUTTER0 + known[i] as u8,
                        _ => c,
                    };
                    if g.down > 1 {
                        // Sample: the cell at the block's corner, obstacles winning.
                        let (px, py, _) = g.cell_px(x as i32, y as i32);
                        let k = (py as u32 * g.width + px as u32) as usize;
                        if (x as u32).is_multiple_of(g.down) && (y as u32).is_multiple_of(g.down)
                            || c == OCCUPIED
                        {
                            buf[k] = c;
                        }
                    } else {
                        g.fill_cell(&mut buf, x as i32, y as i32, c);
                    }
                }
            }
            for &fc in upkeep.frontiers.cells() {
                let c = cells.cell(fc as usize);
                g.fill_cell(&mut buf, c.x, c.y, FRONTIER);
            }
            for &cc in candidates {
                let c = cells.cell(cc as usize);
                g.square(
                    &mut buf,
                    g.centre_px(c.x, c.y),
                    (g.up as i64 / 2).max(1),
                    CANDIDATE,
                    CANDIDATE,
                );
            }
            for (k, &t) in trails.iter().enumerate() {
                if t != NONE {
                    buf[k] = t;
                }
            }
            let marker = (g.up as i64 * 3 / 2).max(4);
            for (r, &s) in trace.starts.iter().enumerate() {
                let _ = r;
                let c = cells.cell(s as usize);
                g.square(&mut buf, g.centre_px(c.x, c.y), marker / 2 + 1, FREE, START);
            }
            for r in 0..trace.robots {
                if let Some(gc) = goal[r] {
                    let c = cells.cell(gc as usize);
                    let (cx, cy) = g.centre_px(c.x, c.y);
                    let m = marker;
                    g.line(&mut buf, (cx - m, cy - m), (cx + m, cy + m), GOAL);
                    g.line(&mut buf, (cx - m, cy + m), (cx + m, cy - m), GOAL);
                }
                let c = cells.cell(robot_cell[r] as usize);
                g.square(
                    &mut buf,
                    g.centre_px(c.x, c.y),
                    marker,
                    ROBOT0 + (r % 8) as u8,
                    OCCUPIED,
                );
            }
            let mut frame = gif::Frame {
                width: gw,
                height: gh,
                buffer: Cow::Borrowed(&buf),
                delay: if f + 1 == frames.len() {
                    300
                } else {
                    opts.delay_cs
                },
                ..gif::Frame::default()
            };
            frame.dispose = gif::DisposalMethod::Keep;
            enc.write_frame(&frame)
                .map_err(|e| VizError::Gif(e.to_string()))?;
        }
    }
    Ok(out)
}
