//! How path length is measured: grid moves, or any-angle lines through the same cells.
//!
//! frontier's robot moves from cell centre to cell centre (1 straight, √2 diagonal), so
//! it zig-zags wherever its way is not a multiple of 45°. Holz et al.'s robot is
//! differential-drive and follows its planned paths with smooth motion controllers, so it
//! cuts those zig-zags; their path lengths are therefore shorter than grid lengths of the
//! same route, by up to 8 % (the worst grid detour, at 22.5°), more where a route bends.
//!
//! [`Motion::AnyAngle`] reports the length the robot's route would have had as a
//! string-pulled path: the cells the robot stood on on each path it set out on (from one
//! decision to the next, where it stays a corner), in order, replaced by straight
//! segments between some of them, each segment seeing only passable cells
//! ([`line_of_sight`]); the passable cells are those traversable in the final belief with
//! the run's clearance, and the cells the robot stood on. The robot still decides and
//! senses on the grid route (so coverage and decisions are those of grid motion): only the
//! reported length changes. A turning radius or a speed-change cost would need a model of
//! the controller the paper does not give; any-angle paths need none, are a lower bound on
//! the smoothed route, and keep the comparison with the grid length exact (same decisions).

use std::fmt;
use std::str::FromStr;

use grid::step_cost;

/// How travelled distance is measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Motion {
    /// Cell-to-cell moves: 1 straight, √2 diagonal (the default).
    #[default]
    Grid,
    /// The grid route string-pulled into straight segments through passable cells.
    AnyAngle,
}

impl Motion {
    /// The name used on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            Motion::Grid => "grid",
            Motion::AnyAngle => "any-angle",
        }
    }
}

impl fmt::Display for Motion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Motion {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "grid" => Ok(Motion::Grid),
            "any-angle" | "anyangle" => Ok(Motion::AnyAngle),
            _ => Err(format!("unknown motion '{s}': expected grid or any-angle")),
        }
    }
}

/// Whether the straight segment between the centres of cells `a` and `b` (flat indices on
/// a grid `width` wide) passes only through `passable` cells. Every cell the segment enters
/// counts; where it passes exactly through a cell corner, both cells beside the corner must
/// be passable (no squeezing between two blocked cells).
pub fn line_of_sight(width: usize, a: usize, b: usize, passable: impl Fn(usize) -> bool) -> bool {
    let w = width as i64;
    let (mut x, mut y) = ((a % width) as i64, (a / width) as i64);
    let (x1, y1) = ((b % width) as i64, (b / width) as i64);
    let (dx, dy) = ((x1 - x).abs(), (y1 - y).abs());
    let (sx, sy) = ((x1 - x).signum(), (y1 - y).signum());
    let at = |x: i64, y: i64| (y * w + x) as usize;
    if !passable(at(x, y)) {
        return false;
    }
    let (mut ix, mut iy) = (0i64, 0i64);
    while ix < dx || iy < dy {
        // which grid line the segment crosses next: x = x0 + (ix + ½)·sx or y = y0 + (iy + ½)·sy
        let d = (1 + 2 * ix) * dy - (1 + 2 * iy) * dx;
        if d == 0 {
            if !passable(at(x + sx, y)) || !passable(at(x, y + sy)) {
                return false;
            }
            x += sx;
            y += sy;
            ix += 1;
            iy += 1;
        } else if d < 0 {
            x += sx;
            ix += 1;
        } else {
            y += sy;
            iy += 1;
        }
        if !passable(at(x, y)) {
            return false;
        }
    }
    true
}

/// Euclidean distance between the centres of two cells, in cells.
fn distance(width: usize, a: usize, b: usize) -> f64 {
    let dx = (a % width) as f64 - (b % width) as f64;
    let dy = (a / width) as f64 - (b / width) as f64;
    dx.hypot(dy)
}

/// The corners of `trail` (cells stood on, in order, each 8-adjacent to or equal to the one
/// before) string-pulled, into `out` (cleared first): from each corner, the segment reaches
/// the farthest following trail cell it sees through `passable` cells before the first it
/// does not; that cell is the next corner. A step to the next trail cell is always allowed
/// (the robot made it), so consecutive corners are 8-adjacent or in [`line_of_sight`].
pub fn any_angle_corners(
    width: usize,
    trail: &[u32],
    passable: impl Fn(usize) -> bool,
    out: &mut Vec<u32>,
) {
    out.clear();
    out.extend(
        corner_positions(width, trail, &[], passable)
            .into_iter()
            .map(|k| trail[k]),
    );
}

/// The corners of `trail` string-pulled leg by leg ([`any_angle_prefix_lengths`]), as
/// positions in the trail: each leg (from one of `legs` to the next) is pulled as
/// [`any_angle_corners`] describes, and its end is a corner too.
fn corner_positions(
    width: usize,
    trail: &[u32],
    legs: &[usize],
    passable: impl Fn(usize) -> bool,
) -> Vec<usize> {
    let n = trail.len();
    if n == 0 {
        return Vec::new();
    }
    let mut ends: Vec<usize> = legs.iter().copied().filter(|&l| l > 0 && l < n).collect();
    ends.sort_unstable();
    ends.dedup();
    ends.push(n - 1);
    let mut corners = vec![0];
    let mut from = 0;
    for &to in &ends {
        // the anchor, and the farthest trail cell seen from it
        let (mut anchor, mut last) = (from, from);
        for k in from + 1..=to {
            if trail[k] == trail[last] {
                continue;
            }
            if !line_of_sight(width, trail[anchor] as usize, trail[k] as usize, &passable) {
                corners.push(last);
                anchor = last;
            }
            last = k;
        }
        // The leg's end is a corner (the next leg's start), also where it is back at its
        // anchor's cell (a segment of length 0).
        if corners.last() != Some(&last) {
            corners.push(last);
        }
        from = to;
    }
    corners
}

/// Length in cells of a polyline through the centres of `corners`.
pub fn polyline_length(width: usize, corners: &[u32]) -> f64 {
    corners
        .windows(2)
        .map(|p| distance(width, p[0] as usize, p[1] as usize))
        .sum()
}

/// The grid distance in cells travelled along `trail` by the time the robot stood on each
/// of its cells (1 straight, √2 diagonal: the sums the loop adds up move by move).
pub fn grid_prefix_lengths(width: usize, trail: &[u32]) -> Vec<f64> {
    let mut out = Vec::with_capacity(trail.len());
    let mut at = 0.0;
    for (k, &b) in trail.iter().enumerate() {
        if k > 0 {
            let (a, b) = (trail[k - 1] as usize, b as usize);
            if a != b {
                at += step_cost(
                    (b % width) as i32 - (a % width) as i32,
                    (b / width) as i32 - (a / width) as i32,
                );
            }
        }
        out.push(at);
    }
    out
}

/// The distance in cells travelled along `trail` string-pulled leg by leg by the time the
/// robot stood on each of its cells. A leg is the trail from one of `legs` (the positions
/// where the robot set out on a new path) to the next, and each is string-pulled alone
/// ([`any_angle_corners`]): a robot follows its path to its goal smoothly, but it drove to
/// the goal and from there on, so where it decided stays a corner (string-pulling the whole
/// trail at once would cut straight across every goal in open space). Exact at the corners,
/// and in between in proportion to the grid distance travelled (1 straight, √2 diagonal)
/// along the segment. Non-decreasing; with no legs but the first, the last is
/// [`any_angle_length`] (the same sum, in the same order).
pub fn any_angle_prefix_lengths(
    width: usize,
    trail: &[u32],
    legs: &[usize],
    passable: impl Fn(usize) -> bool,
) -> Vec<f64> {
    let n = trail.len();
    let mut out = vec![0.0; n];
    if n == 0 {
        return out;
    }
    let grid = grid_prefix_lengths(width, trail);
    let corners = corner_positions(width, trail, legs, passable);
    let mut at = 0.0;
    for c in corners.windows(2) {
        let (i, j) = (c[0], c[1]);
        let seg = distance(width, trail[i] as usize, trail[j] as usize);
        let span = grid[j] - grid[i];
        for k in i..j {
            out[k] = if span > 0.0 {
                at + seg * ((grid[k] - grid[i]) / span)
            } else {
                at
            };
        }
        at += seg;
    }
    let end = *corners.last().expect("the first cell is a corner");
    out[end..].fill(at);
    out
}

/// Length in cells of `trail` string-pulled ([`any_angle_corners`]): at most the grid length
/// of the trail and at least the distance from its first cell to its last.
pub fn any_angle_length(width: usize, trail: &[u32], passable: impl Fn(usize) -> bool) -> f64 {
    let mut corners = Vec::new();
    any_angle_corners(width, trail, passable, &mut corners);
    polyline_length(width, &corners)
}
