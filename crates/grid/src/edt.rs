//! Exact Euclidean distance transform (Felzenszwalb & Huttenlocher, "Distance Transforms of
//! Sampled Functions", 2012).
//!
//! For every cell, the Euclidean distance (in cells, centre to centre) to the nearest obstacle
//! cell. The transform is separable: a 1-D pass down every column (nearest obstacle in the
//! column) followed by a 1-D pass along every row that takes the lower envelope of the parabolas
//! `(x − q)² + f(q)`. Both passes are linear, so the whole transform is O(width · height).
//!
//! Cells with no obstacle anywhere in the grid get `f64::INFINITY`.
//!
//! ```
//! use grid::edt::edt;
//! // a 3 × 1 grid with an obstacle at x = 0
//! let d = edt(3, 1, |i| i == 0);
//! assert_eq!(d.data(), &[0.0, 1.0, 2.0]);
//! ```

use crate::grid::Grid;

/// Reusable buffers for [`edt_squared_into`], so repeated transforms do not allocate.
#[derive(Clone, Debug, Default)]
pub struct EdtScratch {
    /// One row or column of input values.
    f: Vec<f64>,
    /// Positions of the parabolas in the lower envelope.
    v: Vec<usize>,
    /// Boundaries between the envelope's parabolas.
    z: Vec<f64>,
}

impl EdtScratch {
    /// Empty scratch buffers; they grow to the largest grid side on first use.
    pub fn new() -> Self {
        Self::default()
    }
}

/// Squared Euclidean distance (in cells²) from each cell centre to the nearest obstacle centre;
/// `f64::INFINITY` if there is no obstacle. `is_obstacle` is called with flat row-major indices.
pub fn edt_squared(width: usize, height: usize, is_obstacle: impl Fn(usize) -> bool) -> Grid<f64> {
    let mut out = Grid::new(width, height, f64::INFINITY);
    edt_squared_into(width, height, is_obstacle, &mut out, &mut EdtScratch::new());
    out
}

/// Euclidean distance (in cells) from each cell centre to the nearest obstacle centre;
/// `f64::INFINITY` if there is no obstacle.
pub fn edt(width: usize, height: usize, is_obstacle: impl Fn(usize) -> bool) -> Grid<f64> {
    let mut out = edt_squared(width, height, is_obstacle);
    for d in out.data_mut() {
        *d = d.sqrt();
    }
    out
}

/// [`edt_squared`] into an existing grid (resized to `width × height` if it differs), reusing
/// `scratch`; allocates nothing once the buffers have the right sizes.
pub fn edt_squared_into(
    width: usize,
    height: usize,
    is_obstacle: impl Fn(usize) -> bool,
    out: &mut Grid<f64>,
    scratch: &mut EdtScratch,
) {
    if out.width() != width || out.height() != height {
        *out = Grid::new(width, height, f64::INFINITY);
    }
    let d = out.data_mut();
    // Pass 1: down each column, the squared distance to the nearest obstacle in that column.
    for x in 0..width {
        // forward sweep: distance to the nearest obstacle above (or at) the cell
        let mut last: Option<usize> = None;
        for y in 0..height {
            let i = y * width + x;
            if is_obstacle(i) {
                last = Some(y);
            }
            d[i] = match last {
                Some(ly) => sq((y - ly) as f64),
                None => f64::INFINITY,
            };
        }
        // backward sweep: distance to the nearest obstacle below
        let mut last: Option<usize> = None;
        for y in (0..height).rev() {
            let i = y * width + x;
            if d[i] == 0.0 {
                last = Some(y);
            }
            if let Some(ly) = last {
                let below = sq((ly - y) as f64);
                if below < d[i] {
                    d[i] = below;
                }
            }
        }
    }
    // Pass 2: along each row, the lower envelope of parabolas.
    scratch.f.resize(width, 0.0);
    scratch.v.resize(width, 0);
    scratch.z.resize(width + 1, 0.0);
    for y in 0..height {
        let row = &mut d[y * width..(y + 1) * width];
        scratch.f.copy_from_slice(row);
        envelope_1d(&scratch.f, &mut scratch.v, &mut scratch.z, row);
    }
}

#[inline]
fn sq(a: f64) -> f64 {
    a * a
}

/// 1-D squared distance transform of the sampled function `f` (entries may be infinite, meaning
/// "no parabola here") into `out`; `v` and `z` hold at least `f.len()` and `f.len() + 1` entries.
fn envelope_1d(f: &[f64], v: &mut [usize], z: &mut [f64], out: &mut [f64]) {
    let n = f.len();
    // k = index of the rightmost parabola in the envelope; None until the first finite one.
    let mut k: Option<usize> = None;
    for q in 0..n {
        if !f[q].is_finite() {
            continue;
        }
        let Some(mut kk) = k else {
            k = Some(0);
            v[0] = q;
            z[0] = f64::NEG_INFINITY;
            z[1] = f64::INFINITY;
            continue;
        };
        loop {
            let p = v[kk];
            let s = ((f[q] + sq(q as f64)) - (f[p] + sq(p as f64))) / (2.0 * (q - p) as f64);
            // z[0] = −∞, so the first parabola is never popped
            if kk > 0 && s <= z[kk] {
                kk -= 1;
                continue;
            }
            kk += 1;
            v[kk] = q;
            z[kk] = s;
            z[kk + 1] = f64::INFINITY;
            break;
        }
        k = Some(kk);
    }
    if k.is_none() {
        out.fill(f64::INFINITY);
        return;
    }
    let mut kk = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[kk + 1] < q as f64 {
            kk += 1;
        }
        let p = v[kk];
        let dq = q as f64 - p as f64;
        *o = dq * dq + f[p];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute(width: usize, height: usize, obst: &[bool]) -> Vec<f64> {
        let mut out = vec![f64::INFINITY; width * height];
        for (i, o) in out.iter_mut().enumerate() {
            let (x, y) = ((i % width) as i64, (i / width) as i64);
            for (j, &b) in obst.iter().enumerate() {
                if b {
                    let (ox, oy) = ((j % width) as i64, (j / width) as i64);
                    let d2 = ((x - ox) * (x - ox) + (y - oy) * (y - oy)) as f64;
                    if d2 < *o {
                        *o = d2;
                    }
                }
            }
        }
        out
    }

    #[test]
    fn worked_example() {
        // . . .
        // . # .
        // . . .
        let d = edt_squared(3, 3, |i| i == 4);
        assert_eq!(d.data(), &[2.0, 1.0, 2.0, 1.0, 0.0, 1.0, 2.0, 1.0, 2.0]);
        let d = edt(3, 3, |i| i == 4);
        assert_eq!(d[0], std::f64::consts::SQRT_2);
    }

    #[test]
    fn no_obstacle_is_infinite_and_empty_grid_is_fine() {
        let d = edt(4, 3, |_| false);
        assert!(d.data().iter().all(|v| *v == f64::INFINITY));
        let d = edt(0, 0, |_| true);
        assert!(d.is_empty());
        let d = edt(5, 0, |_| true);
        assert!(d.is_empty());
    }

    #[test]
    fn into_reuses_and_resizes() {
        let mut out = Grid::new(1, 1, 0.0);
        let mut s = EdtScratch::new();
        edt_squared_into(4, 2, |i| i == 7, &mut out, &mut s);
        assert_eq!(out.width(), 4);
        assert_eq!(
            out.data(),
            brute(
                4,
                2,
                &[false, false, false, false, false, false, false, true]
            )
        );
        edt_squared_into(4, 2, |i| i == 0, &mut out, &mut s);
        assert_eq!(out[7], 10.0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn matches_brute_force(
            (w, h, obst) in (1usize..24, 1usize..24).prop_flat_map(|(w, h)| {
                (Just(w), Just(h), proptest::collection::vec(prop::bool::weighted(0.08), w * h))
            })
        ) {
            let got = edt_squared(w, h, |i| obst[i]);
            let want = brute(w, h, &obst);
            // squared distances of integer cells are integers: exact equality
            prop_assert_eq!(got.data(), &want[..]);
            let root = edt(w, h, |i| obst[i]);
            for (r, s) in root.data().iter().zip(want.iter()) {
                prop_assert_eq!(*r, s.sqrt());
            }
        }
    }
}
