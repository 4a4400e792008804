//! Changing a map's cell size: conservative coarsening by an integer factor, and
//! nearest-neighbour resampling of non-square pixels to square cells.

use crate::grid::Grid;
use crate::io::MAX_CELLS;
use crate::occ::{GridMap, Occ};

/// How strongly a state wins when cells are merged: Occupied > Unknown > Free.
#[inline]
fn rank(o: Occ) -> u8 {
    match o {
        Occ::Free => 0,
        Occ::Unknown => 1,
        Occ::Occupied => 2,
    }
}

/// The map with cells `factor` times larger: each coarse cell covers `factor × factor`
/// cells and is Occupied if any of them is, else Unknown if any is (or if the block runs
/// past the map's edge, where the world is unknown), else Free.
///
/// The coarse map is `ceil(width / factor) × ceil(height / factor)` cells at
/// `resolution × factor`; its top-left corner stays put, so the origin (lower-left corner)
/// moves down by the rows added at the bottom. `factor` 0 is taken as 1.
pub fn coarsen(map: &GridMap, factor: usize) -> GridMap {
    let f = factor.max(1);
    let (w, h) = (map.width(), map.height());
    let (cw, ch) = (w.div_ceil(f), h.div_ceil(f));
    let mut cells = Grid::new(cw, ch, Occ::Free);
    // Blocks that run past the right or bottom edge hold unknown space.
    if w % f != 0 {
        for y in 0..ch {
            cells[y * cw + cw - 1] = Occ::Unknown;
        }
    }
    if h % f != 0 {
        for x in 0..cw {
            cells[(ch - 1) * cw + x] = Occ::Unknown;
        }
    }
    for y in 0..h {
        let row = &map.cells.data()[y * w..(y + 1) * w];
        let crow = (y / f) * cw;
        for (x, &o) in row.iter().enumerate() {
            let c = &mut cells[crow + x / f];
            if rank(o) > rank(*c) {
                *c = o;
            }
        }
    }
    let extra = (ch * f - h) as f64 * map.resolution;
    let [ox, oy, yaw] = map.origin;
    let (s, c) = yaw.sin_cos();
    GridMap {
        cells,
        resolution: map.resolution * f as f64,
        origin: [ox + extra * s, oy - extra * c, yaw],
    }
}

/// The size of a `width × height` grid of `src_res = (rx, ry)` pixels resampled to square
/// cells of side `dst_res`: `round(width · rx / dst_res) × round(height · ry / dst_res)`,
/// at least 1 × 1 for a non-empty grid.
///
/// `None` if a resolution is not positive and finite or the result has more than
/// [`MAX_CELLS`] cells.
pub fn resampled_size(
    width: usize,
    height: usize,
    (rx, ry): (f64, f64),
    dst_res: f64,
) -> Option<(usize, usize)> {
    if ![rx, ry, dst_res].iter().all(|r| r.is_finite() && *r > 0.0) {
        return None;
    }
    let side = |n: usize, r: f64| -> Option<usize> {
        if n == 0 {
            return Some(0);
        }
        let m = (n as f64 * r / dst_res).round().max(1.0);
        (m <= MAX_CELLS as f64).then_some(m as usize)
    };
    let (w, h) = (side(width, rx)?, side(height, ry)?);
    ((w as u64).checked_mul(h as u64)? <= MAX_CELLS).then_some((w, h))
}

/// `src`, whose pixels are `rx × ry` metres, resampled by nearest neighbour to square
/// cells of side `dst_res`: each new cell takes the pixel under its centre.
///
/// The size is [`resampled_size`]; `None` where that is `None`.
pub fn resample_nearest<T: Clone>(
    src: &Grid<T>,
    (rx, ry): (f64, f64),
    dst_res: f64,
) -> Option<Grid<T>> {
    let (w, h) = resampled_size(src.width(), src.height(), (rx, ry), dst_res)?;
    let (sw, sh) = (src.width(), src.height());
    let pick = |i: usize, r: f64, n: usize| -> usize {
        let s = ((i as f64 + 0.5) * dst_res / r).floor();
        (s.max(0.0) as usize).min(n.saturating_sub(1))
    };
    let cols: Vec<usize> = (0..w).map(|x| pick(x, rx, sw)).collect();
    let mut data = Vec::with_capacity(w * h);
    for y in 0..h {
        let sy = pick(y, ry, sh);
        let row = &src.data()[sy * sw..(sy + 1) * sw];
        data.extend(cols.iter().map(|&sx| row[sx].clone()));
    }
    Grid::from_vec(w, h, data)
}
