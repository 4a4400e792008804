//! The footprint sensor of Quattrini Li et al.'s speed-up: every cell whose centre lies
//! within range `r` of the sensor cell's centre is seen, walls or not.

use grid::{Grid, Occ};

use crate::error::SenseError;
use crate::sensor::{Observation, Pose, Sensor, observed, within_range};

/// The largest range, in cells, of sensors without a precomputed ray template.
pub const MAX_RANGE_CELLS: f64 = 1_000_000.0;

/// Check that `r` is a finite range in `[0, MAX_RANGE_CELLS]` cells.
pub(crate) fn check_plain_range(r: f64) -> Result<(), SenseError> {
    if r.is_finite() && (0.0..=MAX_RANGE_CELLS).contains(&r) {
        Ok(())
    } else {
        Err(SenseError::BadRange {
            max: MAX_RANGE_CELLS,
            found: r,
        })
    }
}

/// Sees every cell whose centre is within `r` cells (360°, through obstacles).
#[derive(Clone, Debug)]
pub struct FootprintSensor {
    range: f64,
    /// `half[dy + reach]` = largest `dx ≥ 0` with `dx² + dy² ≤ r²` (every row has one).
    half: Vec<i32>,
}

impl FootprintSensor {
    /// A footprint sensor of range `r` cells (finite, `0 ≤ r ≤` [`MAX_RANGE_CELLS`]).
    pub fn new(r: f64) -> Result<Self, SenseError> {
        check_plain_range(r)?;
        let reach = r.floor() as i64;
        let half = (-reach..=reach)
            .map(|dy| {
                let mut dx = ((r * r - (dy * dy) as f64).max(0.0)).sqrt().floor() as i64;
                while dx > 0 && !within_range(dx * dx + dy * dy, r) {
                    dx -= 1;
                }
                while within_range((dx + 1) * (dx + 1) + dy * dy, r) {
                    dx += 1;
                }
                dx as i32
            })
            .collect();
        Ok(Self { range: r, half })
    }
}

impl FootprintSensor {
    /// Call `seen(flat index)` for every in-grid cell within range of `pose`'s cell.
    #[inline]
    fn for_each_in_range(&self, grid: &Grid<Occ>, pose: Pose, mut seen: impl FnMut(usize)) {
        let o = pose.cell;
        if !grid.contains(o) {
            return;
        }
        let (w, h) = (grid.width() as i64, grid.height() as i64);
        let reach = (self.half.len() / 2) as i64;
        for (row, &half) in self.half.iter().enumerate() {
            let y = i64::from(o.y) + row as i64 - reach;
            if y < 0 || y >= h {
                continue;
            }
            let x0 = (i64::from(o.x) - i64::from(half)).max(0);
            let x1 = (i64::from(o.x) + i64::from(half)).min(w - 1);
            for x in x0..=x1 {
                seen((y * w + x) as usize);
            }
        }
    }
}

impl Sensor for FootprintSensor {
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation) {
        out.clear();
        out.origin = pose.cell;
        let data = truth.data();
        let cells = &mut out.cells;
        self.for_each_in_range(truth, pose, |i| cells.push((i as u32, observed(data[i]))));
    }

    fn range_cells(&self) -> f64 {
        self.range
    }

    /// Every cell within range, as in a real scan: walls do not block a footprint.
    fn predict(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        out.clear();
        self.for_each_in_range(known, pose, |i| out.push(i as u32));
    }

    fn predict_unknown(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        out.clear();
        let data = known.data();
        self.for_each_in_range(known, pose, |i| {
            if data[i] == Occ::Unknown {
                out.push(i as u32);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use grid::Cell;

    #[test]
    fn sees_through_walls() {
        let mut g = Grid::new(7, 7, Occ::Occupied);
        g.set(Cell::new(3, 3), Occ::Free);
        let s = FootprintSensor::new(1.5).expect("valid");
        let mut obs = Observation::new();
        s.scan(&g, Pose::new(Cell::new(3, 3), 0.0), &mut obs);
        assert_eq!(obs.len(), 9);
        assert_eq!(obs.cells.iter().filter(|c| c.1 == Occ::Free).count(), 1);
        assert!(FootprintSensor::new(-0.5).is_err());
        assert!(FootprintSensor::new(f64::INFINITY).is_err());
    }
}
