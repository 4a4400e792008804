//! Rasterising metric geometry: which cells a wall, a rectangle or a disc covers.
//!
//! Generators describe their worlds in metres; these helpers turn metres into cells at any
//! resolution with one rule, so the same layout gives the same picture at 0.5 m and 0.05 m.
//! A coordinate `m` metres from the top-left corner falls on cell boundary `round(m / res)`;
//! a wall centred on `a` with thickness `t` covers cells `round((a - t/2) / res)` up to
//! `round((a + t/2) / res)`, and always at least one cell.

use grid::{Grid, Occ};

/// Wall thickness used by all generators, in metres (at least one cell is drawn).
pub const WALL_M: f64 = 0.15;

/// Metres-to-cells conversion at one resolution.
#[derive(Clone, Copy, Debug)]
pub struct Scale {
    /// Metres per cell.
    pub res: f64,
}

impl Scale {
    /// The cell boundary nearest to `m` metres.
    pub fn cell(self, m: f64) -> i64 {
        (m / self.res).round() as i64
    }

    /// Number of cells covering `m` metres, at least one.
    pub fn cells_at_least_one(self, m: f64) -> i64 {
        self.cell(m).max(1)
    }

    /// First cell of a wall centred on `a` metres with thickness `t`.
    pub fn wall_start(self, a: f64, t: f64) -> i64 {
        self.cell(a - t / 2.0)
    }

    /// One past the last cell of a wall centred on `a` metres with thickness `t`.
    pub fn wall_end(self, a: f64, t: f64) -> i64 {
        let s = self.wall_start(a, t);
        self.cell(a + t / 2.0).max(s + 1)
    }

    /// Centre of cell `i` in metres.
    pub fn centre(self, i: usize) -> f64 {
        (i as f64 + 0.5) * self.res
    }
}

/// Set the cells of the half-open rectangle `[x0, x1) × [y0, y1)` (clipped to the grid).
pub fn fill_rect<T: Copy>(g: &mut Grid<T>, x0: i64, x1: i64, y0: i64, y1: i64, v: T) {
    let (w, h) = (g.width() as i64, g.height() as i64);
    let (x0, x1, y0, y1) = (x0.max(0), x1.min(w), y0.max(0), y1.min(h));
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    let data = g.data_mut();
    for y in y0..y1 {
        let row = (y * w) as usize;
        data[row + x0 as usize..row + x1 as usize].fill(v);
    }
}

/// Make the outermost `t` cells on every side Occupied (the boundary wall).
pub fn border(g: &mut Grid<Occ>, t: i64) {
    let (w, h) = (g.width() as i64, g.height() as i64);
    fill_rect(g, 0, w, 0, t, Occ::Occupied);
    fill_rect(g, 0, w, h - t, h, Occ::Occupied);
    fill_rect(g, 0, t, 0, h, Occ::Occupied);
    fill_rect(g, w - t, w, 0, h, Occ::Occupied);
}
