//! Exact line of sight by shadow casting: the cells [`segment_clear`] sees, found in time
//! proportional to the cells looked at rather than to the rays cast.
//!
//! The ray template of [`LosSensor`](crate::LosSensor) walks one ray per target cell
//! (about 0.9 r³ tree nodes in open space). Here the map is swept octant by octant, column
//! by column outward from the origin, keeping the set of blocked ray slopes:
//!
//! - a non-transparent cell blocks, for every cell in a later column, exactly the rays
//!   through its open interior: the open interval of slopes between its extreme corners
//!   (in the octant where `0 ≤ y ≤ x`, a ray's x only grows, so a cell in an earlier
//!   column lies before every later target on the ray, and a cell in the same column
//!   never meets the open interior of a ray to another cell of that column);
//! - a grid vertex between two non-transparent cells touching it diagonally blocks the
//!   single ray through it (the squeeze rule of [`crate::segment`]);
//! - a target is seen iff its centre's slope lies in no blocked interval and on no blocked
//!   vertex ray.
//!
//! A column's blocking cells are read as runs (a run blocks one interval), and its
//! targets are read off the gaps between the blocked intervals as runs of rows, so a seen
//! cell costs no slope comparison.
//!
//! Slopes are exact fractions of small integers (doubled coordinates), so the result is
//! [`segment_clear`]'s bit for bit; a property test checks it against that oracle. Only
//! cells whose closed cone of slopes meets an unblocked slope are read: a scan costs about
//! the cells it sees plus its blocking boundary. Which cells were read is reported as a box,
//! for callers that cache a scan until the map changes where it looked.
//!
//! [`segment_clear`]: crate::segment_clear

use grid::{Grid, Occ};

use crate::unseen::Unseen;

/// The range (cells) from which shadow casting is faster than the ray template: per scan
/// on a 400 × 400 map (`cargo bench -p sense --bench scan -- visible_`), open space /
/// rooms, template against shadow casting: r = 12: 5.0 / 4.5 µs against 5.8 / 4.1 µs;
/// r = 15: 10.9 / 7.6 µs against 8.0 / 4.5 µs; r = 28: 66 / 43 µs against 19 / 14 µs;
/// r = 64: 840 / 181 µs against 68 / 31 µs; r = 128: 5.3 ms / 439 µs against 207 / 43 µs.
pub const FASTER_FROM_RANGE: f64 = 14.0;

/// A slope `num / den` (`den > 0`), compared exactly.
#[derive(Clone, Copy, Debug)]
struct Slope {
    num: i64,
    den: i64,
}

impl Slope {
    fn new(num: i64, den: i64) -> Self {
        Self { num, den }
    }
    fn lt(self, o: Slope) -> bool {
        self.num * o.den < o.num * self.den
    }
    fn le(self, o: Slope) -> bool {
        self.num * o.den <= o.num * self.den
    }
    fn eq(self, o: Slope) -> bool {
        self.num * o.den == o.num * self.den
    }
}

/// The blocked slopes of one octant: disjoint open intervals sorted by their ends (two may
/// touch: the shared end stays open), and single blocked slopes (squeezed vertices).
#[derive(Default)]
struct Shadows {
    open: Vec<(Slope, Slope)>,
    points: Vec<Slope>,
}

impl Shadows {
    fn clear(&mut self) {
        self.open.clear();
        self.points.clear();
    }

    /// Block the open interval `(lo, hi)`.
    fn add(&mut self, lo: Slope, hi: Slope) {
        // First interval that ends after `lo`, then every one that starts before `hi`.
        let a = self.open.partition_point(|&(_, h)| h.le(lo));
        let mut b = a;
        let (mut nlo, mut nhi) = (lo, hi);
        while b < self.open.len() && self.open[b].0.lt(hi) {
            if self.open[b].0.lt(nlo) {
                nlo = self.open[b].0;
            }
            if nhi.lt(self.open[b].1) {
                nhi = self.open[b].1;
            }
            b += 1;
        }
        self.open.splice(a..b, [(nlo, nhi)]);
    }

    /// Block the single slope `p` (kept sorted).
    fn add_point(&mut self, p: Slope) {
        let k = self.points.partition_point(|&q| q.lt(p));
        if !self.points.get(k).is_some_and(|&q| q.eq(p)) {
            self.points.insert(k, p);
        }
    }
}

/// Scratch buffers of [`visible`], reused between scans.
#[derive(Default)]
pub struct ShadowScratch {
    shadows: Shadows,
    /// Unblocked closed intervals of slopes of the current column.
    gaps: Vec<(Slope, Slope)>,
    /// Rows of the current column to look at, as inclusive ranges.
    rows: Vec<(i64, i64)>,
    /// Runs of blocking cells of the current column (first and last row).
    blocking: Vec<(i64, i64)>,
    /// Per column x of an octant, the last row within the blockers' reach and the last
    /// within range (see [`top_row`]), for the squared range and reach `tops_for`.
    tops: Vec<(i64, i64)>,
    tops_for: (i64, i64),
}

/// The box of grid cells a scan read: columns `x0..=x1`, rows `y0..=y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadBox {
    /// Leftmost column read.
    pub x0: usize,
    /// Topmost row read.
    pub y0: usize,
    /// Rightmost column read.
    pub x1: usize,
    /// Bottom row read.
    pub y1: usize,
}

/// Call `seen(flat index, state)` for every cell of `grid` within `range` cells of
/// `origin` whose segment from `origin` crosses only `transparent` cells and squeezes
/// between no two non-transparent ones ([`crate::segment`]'s rule with `transparent` for
/// "free"); cells outside the grid are opaque and never reported. Each cell is reported
/// once, in no particular order. Returns the box of cells whose state was read (`None` if
/// `origin` is outside the grid).
pub fn visible(
    grid: &Grid<Occ>,
    origin: grid::Cell,
    range: f64,
    transparent: impl Fn(Occ) -> bool,
    scratch: &mut ShadowScratch,
    seen: impl FnMut(u32, Occ),
) -> Option<ReadBox> {
    visible_within(
        grid,
        origin,
        range,
        &[i64::MAX; 8],
        transparent,
        scratch,
        |_, _| true,
        seen,
    )
}

/// [`visible`], leaving out the cells beyond column `columns[k]` of octant `k` (columns
/// counted from the origin along the octant's main axis; see [`octant_columns`]) and the
/// cells `keep(flat index, state)` rejects. A column depends only on the columns before
/// it, so the cells reported are exactly `visible`'s up to those columns. `keep` is asked
/// of every cell seen and should be cheap (it is inlined; a scan that reports few of the
/// cells it sees then costs no call per cell left out).
#[allow(clippy::too_many_arguments)]
pub fn visible_within(
    grid: &Grid<Occ>,
    origin: grid::Cell,
    range: f64,
    columns: &[i64; 8],
    transparent: impl Fn(Occ) -> bool,
    scratch: &mut ShadowScratch,
    keep: impl Fn(u32, Occ) -> bool,
    mut seen: impl FnMut(u32, Occ),
) -> Option<ReadBox> {
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let (ox, oy) = (i64::from(origin.x), i64::from(origin.y));
    if ox < 0 || oy < 0 || ox >= w || oy >= h {
        return None;
    }
    let data = grid.data();
    let o = (oy * w + ox) as usize;
    let mut rb = ReadBox {
        x0: ox as usize,
        y0: oy as usize,
        x1: ox as usize,
        y1: oy as usize,
    };
    if keep(o as u32, data[o]) {
        seen(o as u32, data[o]);
    }
    if !transparent(data[o]) || range.is_nan() || range < 1.0 {
        return Some(rb);
    }
    let reach = range.floor().min((w + h) as f64) as i64;
    // Targets: squared distance within range² (integers, as `within_range`).
    let r2 = (range * range).floor().min((4 * (w + h) * (w + h)) as f64) as i64;
    // Blockers beyond the range cannot lie on a segment to a target within it; one cell
    // more is read as a margin (reading a cell is always safe).
    let blocker_reach2 = (reach + 1) * (reach + 1);
    if scratch.tops_for != (r2, reach) {
        scratch.tops_for = (r2, reach);
        scratch.tops.clear();
        scratch
            .tops
            .extend((0..=reach + 1).map(|x| (top_row(x, blocker_reach2), top_row(x, r2))));
    }
    for octant in 0..8u8 {
        let swap = octant & 4 != 0;
        let sx = if octant & 1 == 0 { 1 } else { -1 };
        let sy = if octant & 2 == 0 { 1 } else { -1 };
        // Local (x, y), 0 ≤ y ≤ x, to grid coordinates.
        let to_grid = |x: i64, y: i64| {
            let (a, b) = if swap { (y, x) } else { (x, y) };
            (ox + sx * a, oy + sy * b)
        };
        // The flat index of local (x, y) is o + x·dx + y·dy; a local cell lies in the grid
        // iff x ≤ xin and y ≤ yin (x and y are never negative).
        let (dx, dy) = if swap { (sy * w, sx) } else { (sx, sy * w) };
        let room = |o: i64, s: i64, n: i64| if s > 0 { n - 1 - o } else { o };
        let (xin, yin) = if swap {
            (room(oy, sy, h), room(ox, sx, w))
        } else {
            (room(ox, sx, w), room(oy, sy, h))
        };
        let index = |x: i64, y: i64| (o as i64 + x * dx + y * dy) as usize;
        let state = |x: i64, y: i64| (x <= xin && y <= yin).then(|| data[index(x, y)]);
        // Each boundary cell once: the axes in one octant of each pair, the diagonals in
        // the unswapped ones.
        let skip_axis = if swap { sx != 1 } else { sy != 1 };
        // The local box of the cells read: columns 0..=xmax, rows ymin..=ymax.
        let (mut xmax, mut ymin, mut ymax) = (0i64, 0i64, 0i64);
        let sh = &mut scratch.shadows;
        sh.clear();
        for x in 1..=(reach + 1).min(columns[usize::from(octant)]) {
            // The last rows within the blockers' reach and within range.
            let (blocker_top, target_top) = scratch.tops[x as usize];
            // The unblocked closed intervals of slopes in [0, 1] (the ends of blocked open
            // intervals are not blocked), and the rows whose closed cone meets one.
            scratch.gaps.clear();
            scratch.rows.clear();
            let (zero, one) = (Slope::new(0, 1), Slope::new(1, 1));
            let mut from = zero;
            for &(l, hgh) in &sh.open {
                if hgh.le(zero) {
                    continue;
                }
                if one.lt(l) {
                    break;
                }
                if from.le(l) {
                    scratch.gaps.push((from, l));
                }
                from = hgh;
            }
            if from.le(one) {
                scratch.gaps.push((from, one));
            }
            for &(g0, g1) in &scratch.gaps {
                // (2y − 1)/(2x + 1) ≤ g1 and (2y + 1)/(2x − 1) ≥ g0.
                let hi = (g1.num * (2 * x + 1) + g1.den).div_euclid(2 * g1.den);
                let lo = -((-(g0.num * (2 * x - 1) - g0.den)).div_euclid(2 * g0.den));
                let (lo, hi) = (lo.max(0), hi.min(x));
                if lo <= hi {
                    match scratch.rows.last_mut() {
                        Some(last) if last.1 >= lo - 1 => last.1 = last.1.max(hi),
                        _ => scratch.rows.push((lo, hi)),
                    }
                }
            }
            if scratch.rows.is_empty() {
                break;
            }
            // The column lies in the grid up to row `yin` (not at all beyond column `xin`).
            let col_top = if x <= xin { yin } else { -1 };
            let base = o as i64 + x * dx;
            // Pass 1: the blocking cells of this column, as runs of rows, widen the shadows
            // (after pass 2). Only blockers within the range plus one can hide a target.
            scratch.blocking.clear();
            for &(lo, hi) in &scratch.rows {
                // Read: columns up to x, rows lo..=hi + 1 (the cell up-left of a corner).
                xmax = x;
                ymin = ymin.min(lo);
                ymax = ymax.max(hi + 1);
                for y in lo..=hi.min(blocker_top) {
                    // (Its closed cone meets an unblocked slope, so it is not hidden.)
                    if y <= col_top && transparent(data[(base + y * dy) as usize]) {
                        continue;
                    }
                    match scratch.blocking.last_mut() {
                        Some(run) if run.1 == y - 1 => run.1 = y,
                        _ => scratch.blocking.push((y, y)),
                    }
                    // The vertex at its upper-left corner (local), between it and the
                    // cell diagonally up-left, when that ray is in this octant.
                    if y < x && !state(x - 1, y + 1).is_some_and(&transparent) {
                        sh.add_point(Slope::new(2 * y + 1, 2 * x - 1));
                    }
                }
            }
            // Pass 2: the targets of this column, gap by gap: the rows whose centre's slope
            // y/x lies in a gap and on no blocked vertex ray, within range and the grid.
            let (first, last) = (
                i64::from(skip_axis),
                (if swap { x - 1 } else { x }).min(target_top).min(col_top),
            );
            let mut kp = 0;
            for &(g0, g1) in &scratch.gaps {
                let mut y = (-((-(g0.num * x)).div_euclid(g0.den))).max(first);
                let top = (g1.num * x).div_euclid(g1.den).min(last);
                while kp < sh.points.len() && sh.points[kp].lt(g0) {
                    kp += 1;
                }
                while y <= top {
                    // The next blocked vertex ray through a target of the gap, if any.
                    let mut stop = top + 1;
                    while kp < sh.points.len() && sh.points[kp].le(g1) {
                        let p = sh.points[kp];
                        let (q, rem) =
                            ((p.num * x).div_euclid(p.den), (p.num * x).rem_euclid(p.den));
                        if rem == 0 && q >= y {
                            stop = q.min(top + 1);
                            break;
                        }
                        kp += 1;
                    }
                    let mut i = base + y * dy;
                    for _ in y..stop {
                        let i_ = i as usize;
                        if keep(i_ as u32, data[i_]) {
                            seen(i_ as u32, data[i_]);
                        }
                        i += dy;
                    }
                    y = stop + 1;
                }
            }
            for k in 0..scratch.blocking.len() {
                let (a, b) = scratch.blocking[k];
                sh.add(
                    Slope::new(2 * a - 1, 2 * x + 1),
                    Slope::new(2 * b + 1, 2 * x - 1),
                );
            }
        }
        for (lx, ly) in [(0, ymin), (xmax, ymax)] {
            let (gx, gy) = to_grid(lx, ly);
            let (cx, cy) = (gx.clamp(0, w - 1) as usize, gy.clamp(0, h - 1) as usize);
            rb.x0 = rb.x0.min(cx);
            rb.x1 = rb.x1.max(cx);
            rb.y0 = rb.y0.min(cy);
            rb.y1 = rb.y1.max(cy);
        }
    }
    Some(rb)
}

/// The last row `y ≥ 0` of column `x` with `x² + y² ≤ r2` (−1 if none).
fn top_row(x: i64, r2: i64) -> i64 {
    let rest = r2 - x * x;
    if rest < 0 {
        return -1;
    }
    let mut y = (rest as f64).sqrt() as i64;
    while y * y > rest {
        y -= 1;
    }
    while (y + 1) * (y + 1) <= rest {
        y += 1;
    }
    y
}

/// Per octant of [`visible`] from `origin` (range `range` cells), the last column that
/// holds a cell of a block where `unseen` has something to tell the robot scanning: the
/// columns [`visible_within`] needs so that every cell it leaves out tells it nothing.
pub fn octant_columns(origin: grid::Cell, range: f64, unseen: &Unseen) -> [i64; 8] {
    let mut columns = [0i64; 8];
    let (ox, oy) = (i64::from(origin.x), i64::from(origin.y));
    let reach = range.floor() as i64 + 1;
    let r2 = (range * range).floor() as i64;
    unseen.for_each_telling_block(
        (ox - reach, oy - reach),
        (ox + reach, oy + reach),
        |x0, y0, x1, y1| {
            let (dx0, dx1, dy0, dy1) = (x0 - ox, x1 - ox, y0 - oy, y1 - oy);
            // Its nearest cell out of range: nothing in it is a target.
            let (nx, ny) = (dx0.max(0).max(-dx1), dy0.max(0).max(-dy1));
            if nx * nx + ny * ny > r2 {
                return;
            }
            for (octant, column) in columns.iter_mut().enumerate() {
                let swap = octant & 4 != 0;
                // The block's range of local coordinates a = sx·dx, b = sy·dy.
                let (a0, a1) = if octant & 1 == 0 {
                    (dx0, dx1)
                } else {
                    (-dx1, -dx0)
                };
                let (b0, b1) = if octant & 2 == 0 {
                    (dy0, dy1)
                } else {
                    (-dy1, -dy0)
                };
                let ((_, xhi), (ylo, yhi)) = if swap {
                    ((b0, b1), (a0, a1))
                } else {
                    ((a0, a1), (b0, b1))
                };
                // Some cell with 0 ≤ y ≤ x.
                if xhi >= 0 && yhi >= 0 && ylo <= xhi {
                    *column = (*column).max(xhi);
                }
            }
        },
    );
    columns
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::segment::los_visible;
    use crate::test_grids::grid_from;
    use crate::{LosSensor, sensor::observed};
    use grid::Cell;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Exactly the cells the segment oracle sees, each once.
        #[test]
        fn shadow_casting_equals_the_segment_oracle(
            bits in proptest::collection::vec(any::<u8>(), 16..300),
            density in 0u8..60,
            w in 1usize..24,
            h in 1usize..24,
            ox in 0i32..24,
            oy in 0i32..24,
            range in 0.0f64..14.0,
        ) {
            let g = grid_from(w, h, &bits, density);
            let origin = Cell::new(ox % w as i32, oy % h as i32);
            let mut got = vec![0u8; w * h];
            let mut scratch = ShadowScratch::default();
            visible(&g, origin, range, |s| s == Occ::Free, &mut scratch, |i, s| {
                got[i as usize] += 1;
                assert_eq!(s, g.data()[i as usize]);
            });
            for (i, &n) in got.iter().enumerate() {
                let c = g.cell(i);
                let want = c == origin
                    || (*g.get(origin) == Occ::Free && los_visible(&g, origin, c, range));
                prop_assert_eq!(n, u8::from(want), "cell {:?} from {:?}", c, origin);
            }
        }
    }

    /// The same cells as the ray template, at the ranges CC uses on fine maps.
    #[test]
    fn shadow_casting_equals_the_template_on_a_large_map() {
        let bits: Vec<u8> = (0..977u32).map(|i| (i * 37 % 251) as u8).collect();
        for (density, range) in [(3u8, 60.0), (10, 45.5), (0, 70.0), (25, 30.0)] {
            let g = grid_from(150, 130, &bits, density);
            let los = LosSensor::new(range).unwrap();
            let mut scratch = ShadowScratch::default();
            for origin in [Cell::new(75, 65), Cell::new(3, 4), Cell::new(149, 60)] {
                let mut want = Vec::new();
                los.for_each_seen(&g, origin, |i, s| want.push((i, s)));
                let mut got = Vec::new();
                visible(
                    &g,
                    origin,
                    range,
                    |s| s == Occ::Free,
                    &mut scratch,
                    |i, s| got.push((i, observed(s))),
                );
                want.sort_unstable_by_key(|p| p.0);
                got.sort_unstable_by_key(|p| p.0);
                assert_eq!(
                    got, want,
                    "density {density}, range {range}, origin {origin:?}"
                );
            }
        }
    }
}
