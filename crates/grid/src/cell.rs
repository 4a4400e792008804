//! Cells and 8-connected motion on a grid.
//!
//! A cell is `(x, y)` with `x` to the right and `y` downwards (image rows), so that a
//! grid's row 0 is the top row of its image. Straight steps cost 1, diagonal steps √2.
//!
//! The diagonal step's cost is √2 rounded to a multiple of 2⁻³² ([`SQRT2`], 1.1 × 10⁻¹¹
//! below √2), so that every sum of steps below 2²¹ cells is exact in `f64`: a path's cost
//! is the same bits whatever order its steps are added in, and two searches that find
//! different shortest paths to a cell, or reach it from different sides, agree on its
//! cost to the last bit. With `f64::consts::SQRT_2` the sums rounded, and equal lengths
//! differed by the order of their steps.

/// √2 to 32 binary places (6074001000 / 2³²), the cost of a diagonal step in cells (see the
/// module docs for why it is rounded).
pub const SQRT2: f64 = 6_074_001_000.0 / 4_294_967_296.0;

/// A cell of a grid: column `x` (to the right) and row `y` (downwards).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Cell {
    /// Column, 0 at the left.
    pub x: i32,
    /// Row, 0 at the top.
    pub y: i32,
}

impl Cell {
    /// The cell at column `x`, row `y`.
    pub const fn new(x: i32, y: i32) -> Self {
        Self { x, y }
    }

    /// The cell moved by `(dx, dy)`.
    pub const fn offset(self, dx: i32, dy: i32) -> Self {
        Self {
            x: self.x + dx,
            y: self.y + dy,
        }
    }

    /// Euclidean distance between the two cells' centres, in cells.
    pub fn dist(self, other: Cell) -> f64 {
        let dx = f64::from(self.x - other.x);
        let dy = f64::from(self.y - other.y);
        (dx * dx + dy * dy).sqrt()
    }

    /// Squared Euclidean distance between the two cells' centres, in cells².
    pub fn dist2(self, other: Cell) -> i64 {
        let dx = i64::from(self.x - other.x);
        let dy = i64::from(self.y - other.y);
        dx * dx + dy * dy
    }

    /// Octile distance: the length of the shortest 8-connected path on an empty grid.
    pub fn octile(self, other: Cell) -> f64 {
        let dx = (self.x - other.x).unsigned_abs();
        let dy = (self.y - other.y).unsigned_abs();
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        f64::from(hi - lo) + SQRT2 * f64::from(lo)
    }

    /// Whether the two cells are 8-neighbours (and not the same cell).
    pub fn is_neighbour8(self, other: Cell) -> bool {
        let dx = (self.x - other.x).abs();
        let dy = (self.y - other.y).abs();
        dx <= 1 && dy <= 1 && (dx, dy) != (0, 0)
    }
}

impl std::fmt::Display for Cell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "({}, {})", self.x, self.y)
    }
}

/// The 8 neighbour offsets `(dx, dy)`: the 4 straight ones first, then the 4 diagonals.
pub const NEIGHBOURS8: [(i32, i32); 8] = [
    (1, 0),
    (0, 1),
    (-1, 0),
    (0, -1),
    (1, 1),
    (-1, 1),
    (-1, -1),
    (1, -1),
];

/// The 4 straight neighbour offsets `(dx, dy)`.
pub const NEIGHBOURS4: [(i32, i32); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];

/// Cost in cells of a step by `(dx, dy)` with `|dx|, |dy| ≤ 1`: 1 straight, √2 diagonal.
pub fn step_cost(dx: i32, dy: i32) -> f64 {
    if dx != 0 && dy != 0 { SQRT2 } else { 1.0 }
}

/// Call `f(j, step)` for every allowed move from cell `i` of a `width × height` grid to a
/// passable neighbour `j`, applying the no-corner-squeezing rule.
#[inline]
pub fn for_each_move(
    width: usize,
    height: usize,
    i: usize,
    passable: &impl Fn(usize) -> bool,
    mut f: impl FnMut(usize, f64),
) {
    let (x, y) = (i % width, i / width);
    let (left, right, up, down) = (x > 0, x + 1 < width, y > 0, y + 1 < height);
    let pr = right && passable(i + 1);
    let pd = down && passable(i + width);
    let pl = left && passable(i - 1);
    let pu = up && passable(i - width);
    if pr {
        f(i + 1, 1.0);
    }
    if pd {
        f(i + width, 1.0);
    }
    if pl {
        f(i - 1, 1.0);
    }
    if pu {
        f(i - width, 1.0);
    }
    if right && down && (pr || pd) && passable(i + width + 1) {
        f(i + width + 1, SQRT2);
    }
    if left && down && (pl || pd) && passable(i + width - 1) {
        f(i + width - 1, SQRT2);
    }
    if left && up && (pl || pu) && passable(i - width - 1) {
        f(i - width - 1, SQRT2);
    }
    if right && up && (pr || pu) && passable(i - width + 1) {
        f(i - width + 1, SQRT2);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_diagonal_cost_is_root_two_to_32_binary_places() {
        let err = SQRT2 - std::f64::consts::SQRT_2;
        assert!(err.abs() < 2f64.powi(-33), "{err}");
        assert_eq!((SQRT2 * 2f64.powi(32)).fract(), 0.0);
    }

    proptest! {
        /// Any order of the same steps gives the same bits, which are s + d·SQRT2 exactly.
        #[test]
        fn sums_of_steps_do_not_depend_on_their_order(
            steps in prop::collection::vec(any::<bool>(), 0..3000),
            seed in any::<u64>(),
            base in 0u32..2_000_000,
        ) {
            let cost = |diagonal: bool| if diagonal { SQRT2 } else { 1.0 };
            let forward = steps.iter().fold(f64::from(base), |c, &d| c + cost(d));
            let mut shuffled = steps.clone();
            let mut s = seed | 1;
            for i in (1..shuffled.len()).rev() {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                shuffled.swap(i, (s % (i as u64 + 1)) as usize);
            }
            let back = shuffled.iter().rev().fold(f64::from(base), |c, &d| c + cost(d));
            let d = steps.iter().filter(|&&d| d).count() as f64;
            let s = steps.len() as f64 - d;
            prop_assert_eq!(forward.to_bits(), back.to_bits());
            prop_assert_eq!(forward.to_bits(), (f64::from(base) + s + d * SQRT2).to_bits());
        }
    }
}
