//! `viz`: pictures of what happened in an exploration run.
//!
//! [`final_picture`] draws the ground truth faintly under the final belief (known free
//! white, known occupied black), the frontier cells left, every robot's trajectory in its
//! own colour, its start (ring) and its end (square). Pictures are upscaled by a whole
//! factor so that small maps stay legible. [`animate::animate_gif`] makes an animated GIF
//! of a run and [`replay::replay_html`] a self-contained HTML page that replays it. `viz`
//! draws into memory ([`Picture`], RGB, PNG through the `png` crate); the caller decides
//! what to write where.
//!
//! ```
//! use explore::strategy::Strategy;
//! use world::{EnvKind, EnvSpec, generate};
//! let env = generate(&EnvSpec::new(EnvKind::Office, 7)).unwrap();
//! let run = sim::run(&env.map, &sim::RunConfig::new(Strategy::preset("cf").unwrap())).unwrap();
//! let picture = viz::final_picture(&env.map, &run);
//! assert!(picture.width() >= env.map.width() as u32);
//! ```
#![warn(missing_docs)]

pub mod animate;
pub mod picture;
pub mod replay;

pub use picture::Picture;

/// Why a picture could not be made.
#[derive(Debug, thiserror::Error)]
pub enum VizError {
    /// The run was made without a trace.
    #[error("the run has no trace (record_trace was off)")]
    NoTrace,
    /// A frame side would exceed the format's limit.
    #[error("picture side of {0} pixels is too large")]
    TooLarge(u32),
    /// The GIF encoder failed.
    #[error("GIF encoding: {0}")]
    Gif(String),
    /// A PNG could not be encoded or decoded.
    #[error("PNG: {0}")]
    Png(String),
    /// A picture could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

use grid::{Cell, Grid, GridMap, Occ};
use sim::RunResult;

/// Colours of segments (label modulo the list), in the GIF and the replay page.
pub const SEGMENT_COLOURS: [[u8; 3]; 24] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [127, 127, 127],
    [188, 189, 34],
    [23, 190, 207],
    [57, 59, 121],
    [173, 73, 74],
    [99, 121, 57],
    [206, 109, 189],
    [140, 162, 82],
    [231, 186, 82],
    [107, 110, 207],
    [165, 81, 148],
    [82, 84, 163],
    [189, 158, 57],
    [132, 60, 57],
    [214, 97, 107],
    [156, 158, 222],
    [181, 207, 107],
];

/// Colours of the robots' trajectories, cycled for larger teams.
pub const ROBOT_COLOURS: [[u8; 3]; 8] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
    [188, 189, 34],
];

const UNKNOWN_FREE: [u8; 3] = [226, 228, 236];
const UNKNOWN_OCCUPIED: [u8; 3] = [178, 180, 190];
const UNKNOWN_OUTSIDE: [u8; 3] = [205, 205, 205];
const KNOWN_FREE: [u8; 3] = [255, 255, 255];
const KNOWN_OCCUPIED: [u8; 3] = [25, 25, 25];
const FRONTIER: [u8; 3] = [220, 30, 30];
/// Off-plane clutter (tables, chairs): not yet seen, believed free (the laser missed it),
/// believed occupied (sonar or the robot's body found it).
const CLUTTER_UNKNOWN: [u8; 3] = [226, 206, 178];
const CLUTTER_MISSED: [u8; 3] = [246, 178, 90];
const CLUTTER_MAPPED: [u8; 3] = [120, 72, 30];

/// The colour of an off-plane clutter cell believed `belief`.
fn clutter_colour(belief: Occ) -> [u8; 3] {
    match belief {
        Occ::Unknown => CLUTTER_UNKNOWN,
        Occ::Free => CLUTTER_MISSED,
        Occ::Occupied => CLUTTER_MAPPED,
    }
}

/// The whole-number scale at which a `width × height` map is drawn: at least 1, and
/// enough for the longer side to reach about 600 pixels.
pub fn scale_for(width: usize, height: usize) -> u32 {
    let longest = width.max(height).max(1);
    (600usize.div_ceil(longest)).clamp(1, 16) as u32
}

/// Draw a ground-truth map alone (free white, occupied black, outside grey).
pub fn map_picture(map: &Grid<Occ>) -> Picture {
    let s = scale_for(map.width(), map.height());
    let mut img = Picture::new(map.width() as u32 * s, map.height() as u32 * s);
    for i in 0..map.len() {
        let colour = match map[i] {
            Occ::Free => KNOWN_FREE,
            Occ::Occupied => KNOWN_OCCUPIED,
            Occ::Unknown => UNKNOWN_OUTSIDE,
        };
        fill_cell(&mut img, map.cell(i), s, colour);
    }
    img
}

/// Read back a map drawn by [`map_picture`] as `width × height` cells: free where the
/// cell's pixels are free white, occupied where occupied black, unknown otherwise; `None`
/// if the picture is not of that size at [`scale_for`]'s scale.
pub fn map_from_picture(img: &Picture, width: usize, height: usize) -> Option<Grid<Occ>> {
    let s = scale_for(width, height);
    if img.width() != width as u32 * s || img.height() != height as u32 * s {
        return None;
    }
    let mut data = Vec::with_capacity(width * height);
    for y in 0..height as u32 {
        for x in 0..width as u32 {
            data.push(match img.get_pixel(x * s, y * s) {
                KNOWN_FREE => Occ::Free,
                KNOWN_OCCUPIED => Occ::Occupied,
                _ => Occ::Unknown,
            });
        }
    }
    Grid::from_vec(width, height, data)
}

/// Draw the end of a run: truth (faint), belief, frontiers left, trajectories, starts, ends.
/// Trajectories need the run's trace; without it only starts and ends are marked. Off-plane
/// clutter is drawn in its own colours: tan where unseen, orange where believed free (the
/// laser missed it), brown where believed occupied.
pub fn final_picture(truth: &GridMap, result: &RunResult) -> Picture {
    let cells = &truth.cells;
    let s = scale_for(cells.width(), cells.height());
    let mut img = Picture::new(cells.width() as u32 * s, cells.height() as u32 * s);
    for i in 0..cells.len() {
        let colour = match (result.belief[i], cells[i]) {
            (Occ::Free, _) => KNOWN_FREE,
            (Occ::Occupied, _) => KNOWN_OCCUPIED,
            (Occ::Unknown, Occ::Free) => UNKNOWN_FREE,
            (Occ::Unknown, Occ::Occupied) => UNKNOWN_OCCUPIED,
            (Occ::Unknown, Occ::Unknown) => UNKNOWN_OUTSIDE,
        };
        let colour = match &result.clutter {
            Some(c) if c[i] => clutter_colour(result.belief[i]),
            _ => colour,
        };
        fill_cell(&mut img, cells.cell(i), s, colour);
    }
    for &f in &result.frontiers_left {
        fill_cell(&mut img, cells.cell(f as usize), s, FRONTIER);
    }
    if let Some(trace) = &result.trace {
        for (r, trail) in trace.trails().iter().enumerate() {
            let colour = ROBOT_COLOURS[r % ROBOT_COLOURS.len()];
            for w in trail.windows(2) {
                let (a, b) = (cells.cell(w[0] as usize), cells.cell(w[1] as usize));
                line(&mut img, centre(a, s), centre(b, s), colour, s >= 4);
            }
        }
    }
    let marker = (s * 2).max(3) as i64;
    for (r, (&start, &end)) in result.starts.iter().zip(&result.ends).enumerate() {
        let colour = ROBOT_COLOURS[r % ROBOT_COLOURS.len()];
        ring(&mut img, centre(start, s), marker, [0, 150, 0]);
        square(&mut img, centre(end, s), marker, colour);
    }
    img
}

fn centre(c: Cell, s: u32) -> (i64, i64) {
    let s = i64::from(s);
    (i64::from(c.x) * s + s / 2, i64::from(c.y) * s + s / 2)
}

fn fill_cell(img: &mut Picture, c: Cell, s: u32, colour: [u8; 3]) {
    for dy in 0..s {
        for dx in 0..s {
            img.put_pixel(c.x as u32 * s + dx, c.y as u32 * s + dy, colour);
        }
    }
}

fn put(img: &mut Picture, x: i64, y: i64, colour: [u8; 3]) {
    if x >= 0 && y >= 0 && (x as u32) < img.width() && (y as u32) < img.height() {
        img.put_pixel(x as u32, y as u32, colour);
    }
}

/// Call `f(x, y)` for every pixel of the Bresenham line from `(x0, y0)` to `(x1, y1)`.
pub(crate) fn bresenham(
    (mut x0, mut y0): (i64, i64),
    (x1, y1): (i64, i64),
    mut f: impl FnMut(i64, i64),
) {
    let dx = (x1 - x0).abs();
    let dy = -(y1 - y0).abs();
    let sx = if x0 < x1 { 1 } else { -1 };
    let sy = if y0 < y1 { 1 } else { -1 };
    let mut err = dx + dy;
    loop {
        f(x0, y0);
        if x0 == x1 && y0 == y1 {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x0 += sx;
        }
        if e2 <= dx {
            err += dx;
            y0 += sy;
        }
    }
}

/// A line, two pixels thick when `thick`.
fn line(img: &mut Picture, p0: (i64, i64), p1: (i64, i64), colour: [u8; 3], thick: bool) {
    bresenham(p0, p1, |x, y| {
        put(img, x, y, colour);
        if thick {
            put(img, x + 1, y, colour);
            put(img, x, y + 1, colour);
        }
    });
}

fn ring(img: &mut Picture, (cx, cy): (i64, i64), r: i64, colour: [u8; 3]) {
    for y in -r..=r {
        for x in -r..=r {
            let d2 = x * x + y * y;
            if d2 <= r * r && d2 >= (r - 2).max(0).pow(2) {
                put(img, cx + x, cy + y, colour);
            }
        }
    }
}

fn square(img: &mut Picture, (cx, cy): (i64, i64), r: i64, colour: [u8; 3]) {
    let r = (r * 2 / 3).max(2);
    for y in -r..=r {
        for x in -r..=r {
            let edge = x.abs() == r || y.abs() == r;
            put(img, cx + x, cy + y, if edge { [0, 0, 0] } else { colour });
        }
    }
}
