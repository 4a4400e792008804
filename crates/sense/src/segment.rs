//! The direct segment test: line of sight between two cell centres, decided cell by cell
//! with exact integer arithmetic (Quattrini Li et al.'s laser model).
//!
//! This is the slow, obviously-correct definition that the fast [`LosSensor`] must
//! reproduce, and the "direct segment test" other crates use as an oracle.
//!
//! # Semantics
//!
//! Cell `(x, y)` is the closed unit square `[x, x+1] × [y, y+1]`; its centre is
//! `(x + ½, y + ½)`. The segment `from → to` joins the two centres.
//!
//! - The segment *crosses* a cell iff it meets the cell's open interior (the cells at both
//!   ends are crossed). Since both ends are centres, the segment never runs along a grid
//!   line; it can only pass exactly through grid vertices.
//! - At a grid vertex on the segment, the segment crosses the two cells diagonal along it
//!   and only *touches* the other two. It is blocked there iff **both** touched cells are
//!   non-free (the "passes between two occupied cells sharing a vertex" rule).
//! - The segment is *clear* iff every crossed cell other than `to` is free and no vertex
//!   blocks it. `to` itself may be anything. The cell `from` counts as crossed, so from an
//!   occupied cell nothing but the cell itself is clear.
//! - Non-free means `Occupied` or `Unknown` (ground-truth `Unknown` is outside the world and
//!   opaque); cells outside the grid are opaque as well.
//!
//! All geometry is done in doubled coordinates (cell `(x, y)` spans `[2x, 2x+2]`, its
//! centre is `2x+1`), so every point of interest is an integer and every parameter along
//! the segment an exact fraction.
//!
//! [`LosSensor`]: crate::LosSensor

use grid::{Cell, Grid, Occ};

use crate::sensor::within_range;

/// An exact fraction `num / den` with `den > 0`.
#[derive(Clone, Copy)]
struct Frac {
    num: i128,
    den: i128,
}

impl Frac {
    fn lt(self, other: Frac) -> bool {
        self.num * other.den < other.num * self.den
    }
}

/// Whether the segment `p0 → p0 + d` (doubled coordinates) meets the open interior of
/// `cell`.
fn crosses(cell: Cell, p0: [i128; 2], d: [i128; 2]) -> bool {
    let lo = [2 * i128::from(cell.x), 2 * i128::from(cell.y)];
    // The set of t in [0, 1] with lo < p0 + t d < lo + 2 on both axes.
    let mut lower = Frac { num: 0, den: 1 }; // t ≥ 0 (closed)
    let mut lower_open = false;
    let mut upper = Frac { num: 1, den: 1 }; // t ≤ 1 (closed)
    let mut upper_open = false;
    for axis in 0..2 {
        let (a, b) = (lo[axis], lo[axis] + 2);
        let (p, dd) = (p0[axis], d[axis]);
        if dd == 0 {
            if !(a < p && p < b) {
                return false;
            }
            continue;
        }
        // Open interval of t on this axis, with positive denominators.
        let (l, u) = if dd > 0 {
            (
                Frac {
                    num: a - p,
                    den: dd,
                },
                Frac {
                    num: b - p,
                    den: dd,
                },
            )
        } else {
            (
                Frac {
                    num: p - b,
                    den: -dd,
                },
                Frac {
                    num: p - a,
                    den: -dd,
                },
            )
        };
        if !l.lt(lower) {
            lower = l;
            lower_open = true;
        }
        if !upper.lt(u) {
            upper = u;
            upper_open = true;
        }
    }
    if lower_open || upper_open {
        lower.lt(upper)
    } else {
        !upper.lt(lower)
    }
}

/// Whether `cell` is inside `truth` and free.
fn is_free(truth: &Grid<Occ>, cell: Cell) -> bool {
    truth.try_get(cell).is_some_and(|s| s.is_free())
}

/// Whether the segment between the centres of `from` and `to` is clear: every cell it
/// crosses other than `to` is free and it never squeezes between two non-free cells that
/// share a vertex (see the module docs). `false` if either end lies outside the grid.
///
/// Tests every cell of the segment's bounding box with exact integer arithmetic; slow
/// (O(box area)), meant as the reference the fast sensors are checked against.
pub fn segment_clear(truth: &Grid<Occ>, from: Cell, to: Cell) -> bool {
    if !truth.contains(from) || !truth.contains(to) {
        return false;
    }
    if from == to {
        return true;
    }
    let p0 = [2 * i128::from(from.x) + 1, 2 * i128::from(from.y) + 1];
    let p1 = [2 * i128::from(to.x) + 1, 2 * i128::from(to.y) + 1];
    let d = [p1[0] - p0[0], p1[1] - p0[1]];
    let (x0, x1) = (from.x.min(to.x), from.x.max(to.x));
    let (y0, y1) = (from.y.min(to.y), from.y.max(to.y));
    // Cells: the segment stays inside the box of the two centres, hence inside these cells.
    for y in y0..=y1 {
        for x in x0..=x1 {
            let c = Cell::new(x, y);
            if c != to && crosses(c, p0, d) && !is_free(truth, c) {
                return false;
            }
        }
    }
    // Vertices (2a, 2b) strictly between the two centres.
    let len2 = d[0] * d[0] + d[1] * d[1];
    for b in (y0 + 1)..=y1 {
        for a in (x0 + 1)..=x1 {
            let v = [2 * i128::from(a) - p0[0], 2 * i128::from(b) - p0[1]];
            let on_line = d[0] * v[1] - d[1] * v[0] == 0;
            let dot = d[0] * v[0] + d[1] * v[1];
            if !on_line || dot <= 0 || dot >= len2 {
                continue;
            }
            let around = [
                Cell::new(a - 1, b - 1),
                Cell::new(a, b - 1),
                Cell::new(a - 1, b),
                Cell::new(a, b),
            ];
            let mut touched = 0;
            let mut touched_blocked = 0;
            for c in around {
                if !crosses(c, p0, d) {
                    touched += 1;
                    if !is_free(truth, c) {
                        touched_blocked += 1;
                    }
                }
            }
            if touched > 0 && touched_blocked == touched {
                return false;
            }
        }
    }
    true
}

/// Whether the segment from `from` to `to` is clear with `from` taken as free: for a free
/// `from`, [`segment_clear`] by walking the cells the segment crosses (time ∝ its length).
/// By the symmetry of the rule, it is also whether `from` would be seen from `to` if `to`
/// is free; walking from a cell that is hard to see stops where the view of it is blocked,
/// which is mostly near it.
///
/// The walk steps to the next cell across whichever grid line the segment meets first
/// (exact integer comparisons in doubled coordinates); where it meets a vertex, it crosses
/// into the diagonal cell and touches the two beside it, and is blocked if both are
/// non-free.
pub fn walk_clear_to(grid: &Grid<Occ>, from: Cell, to: Cell) -> bool {
    if !grid.contains(from) || !grid.contains(to) {
        return false;
    }
    if from == to {
        return true;
    }
    let (dx, dy) = (i64::from(to.x - from.x), i64::from(to.y - from.y));
    let (sx, sy) = (dx.signum(), dy.signum());
    let (adx, ady) = (dx.abs(), dy.abs());
    let (mut x, mut y) = (i64::from(from.x), i64::from(from.y));
    // Doubled distances from the start centre to the next vertical and horizontal grid
    // lines ahead: 1, then 3, 5, … The next line meets the segment at parameter
    // t = nx / (2 |dx|) (resp. ny / (2 |dy|)), so nx |dy| and ny |dx| compare the two.
    let (mut nx, mut ny) = (1i64, 1i64);
    let free = |x: i64, y: i64| is_free(grid, Cell::new(x as i32, y as i32));
    loop {
        let across_x = if adx == 0 { i64::MAX } else { nx * ady };
        let across_y = if ady == 0 { i64::MAX } else { ny * adx };
        if across_x < across_y {
            x += sx;
            nx += 2;
        } else if across_y < across_x {
            y += sy;
            ny += 2;
        } else {
            // through the vertex: touches (x + sx, y) and (x, y + sy)
            if !free(x + sx, y) && !free(x, y + sy) {
                return false;
            }
            x += sx;
            y += sy;
            nx += 2;
            ny += 2;
        }
        if x == i64::from(to.x) && y == i64::from(to.y) {
            return true;
        }
        if !free(x, y) {
            return false;
        }
    }
}

/// Whether the laser model at free cell `from` sees `to` within range `r` cells, walked from
/// `to` ([`walk_clear_to`]): the same answer as [`los_visible`] for a free `from`.
pub fn seen_from(grid: &Grid<Occ>, from: Cell, to: Cell, r: f64) -> bool {
    within_range(from.dist2(to), r) && walk_clear_to(grid, to, from)
}

/// Whether the laser model sees `to` from `from` with range `r` cells: both cells inside the
/// grid, centres at most `r` apart (squared distances compared, `r` may be fractional) and
/// [`segment_clear`]. The sensor's own cell is always seen.
pub fn los_visible(truth: &Grid<Occ>, from: Cell, to: Cell, r: f64) -> bool {
    within_range(from.dist2(to), r) && segment_clear(truth, from, to)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(rows: &[&str]) -> Grid<Occ> {
        let w = rows[0].len();
        let data = rows
            .iter()
            .flat_map(|r| r.chars())
            .map(|c| match c {
                '#' => Occ::Occupied,
                '?' => Occ::Unknown,
                _ => Occ::Free,
            })
            .collect();
        Grid::from_vec(w, rows.len(), data).expect("rectangular")
    }

    #[test]
    fn crossing_counts_on_a_diagonal() {
        // (0,0) -> (2,2): crosses the three diagonal cells only.
        let p0 = [1, 1];
        let d = [4, 4];
        let crossed: Vec<Cell> = (0..3)
            .flat_map(|y| (0..3).map(move |x| Cell::new(x, y)))
            .filter(|&c| crosses(c, p0, d))
            .collect();
        assert_eq!(
            crossed,
            vec![Cell::new(0, 0), Cell::new(1, 1), Cell::new(2, 2)]
        );
    }

    #[test]
    fn crossing_a_shallow_line() {
        // (0,0) -> (2,1): doubled (1,1) -> (5,3); passes (3,2), an edge midpoint of (1,0)/(1,1).
        let p0 = [1, 1];
        let d = [4, 2];
        let crossed: Vec<Cell> = (0..2)
            .flat_map(|y| (0..3).map(move |x| Cell::new(x, y)))
            .filter(|&c| crosses(c, p0, d))
            .collect();
        assert_eq!(
            crossed,
            vec![
                Cell::new(0, 0),
                Cell::new(1, 0),
                Cell::new(1, 1),
                Cell::new(2, 1)
            ]
        );
    }

    #[test]
    fn vertex_squeeze_blocks_only_when_both_sides_are_blocked() {
        let open = map(&["...", ".#.", "..."]);
        // Diagonal through the occupied centre cell is blocked.
        assert!(!segment_clear(&open, Cell::new(0, 0), Cell::new(2, 2)));
        // The centre cell itself is seen.
        assert!(segment_clear(&open, Cell::new(0, 0), Cell::new(1, 1)));

        let one = map(&[".#", ".."]);
        assert!(segment_clear(&one, Cell::new(0, 0), Cell::new(1, 1)));
        let both = map(&[".#", "#."]);
        assert!(!segment_clear(&both, Cell::new(0, 0), Cell::new(1, 1)));
        // Unknown is opaque too.
        let unknown = map(&[".?", "#."]);
        assert!(!segment_clear(&unknown, Cell::new(0, 0), Cell::new(1, 1)));
    }

    #[test]
    fn end_cell_may_be_occupied_but_not_the_ones_before() {
        let g = map(&["..#", "..."]);
        assert!(segment_clear(&g, Cell::new(0, 0), Cell::new(2, 0)));
        let g = map(&[".##", "..."]);
        assert!(!segment_clear(&g, Cell::new(0, 0), Cell::new(2, 0)));
        // Occupied origin sees only itself.
        let g = map(&["#..", "..."]);
        assert!(segment_clear(&g, Cell::new(0, 0), Cell::new(0, 0)));
        assert!(!segment_clear(&g, Cell::new(0, 0), Cell::new(1, 0)));
    }

    #[test]
    fn range_and_grid_bounds() {
        let g = map(&["....", "...."]);
        assert!(los_visible(&g, Cell::new(0, 0), Cell::new(3, 0), 3.0));
        assert!(!los_visible(&g, Cell::new(0, 0), Cell::new(3, 0), 2.99));
        assert!(los_visible(
            &g,
            Cell::new(0, 0),
            Cell::new(3, 1),
            10f64.sqrt() + 1e-12
        ));
        assert!(!los_visible(&g, Cell::new(0, 0), Cell::new(4, 0), 9.0));
        assert!(!los_visible(&g, Cell::new(-1, 0), Cell::new(0, 0), 9.0));
    }

    proptest::proptest! {
        /// Walking the crossed cells decides every segment from a free cell as the box test
        /// does, either way, on random grids of free, occupied and unknown cells, ends and
        /// range included.
        #[test]
        fn the_walk_agrees_with_the_box_test(
            w in 1usize..14, h in 1usize..14, seed: u64,
            fx in 0i32..14, fy in 0i32..14, tx in -1i32..15, ty in -1i32..15, r in 0.0f64..16.0,
        ) {
            let mut s = seed;
            let data = (0..w * h)
                .map(|_| {
                    s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    match s >> 61 {
                        0 => Occ::Occupied,
                        1 => Occ::Unknown,
                        _ => Occ::Free,
                    }
                })
                .collect();
            let g = Grid::from_vec(w, h, data).unwrap();
            let (from, to) = (Cell::new(fx % w as i32, fy % h as i32), Cell::new(tx, ty));
            if g.try_get(from).is_some_and(|s| s.is_free()) {
                proptest::prop_assert_eq!(
                    walk_clear_to(&g, from, to),
                    segment_clear(&g, from, to)
                );
                let both_ways = seen_from(&g, from, to, r);
                proptest::prop_assert_eq!(both_ways, los_visible(&g, from, to, r));
            }
        }
    }
}
