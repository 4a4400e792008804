//! A lower bound from how fast the sensor can uncover cells: the robot still has to perceive
//! K = needed − |M| targets, and each unit of path buys at most ρ* new ones, so the rest of
//! the path is at least K / ρ*. Our addition (not in the paper); unlike its Eq. 1 it does
//! not weaken for G < 1, where only a count of cells is required.
//!
//! # Footprint sensor: ρ* = max over offsets v ≠ 0 of |(S + v) \ S| / |v|
//! S is the sensor's set of offsets (every cell whose centre is within r, walls or not).
//! After sensing at p the robot has perceived every target of p + S. Moving on to p' = p + v
//! costs at least the Euclidean |v| (an 8-connected path of 1 and √2 steps is never shorter
//! than the segment), and the new targets lie in (p' + S) \ (p + S), a translate of
//! (S + v) \ S, so they number at most ρ*·cost. Summed over the remaining steps:
//! K ≤ ρ*·(remaining cost). Consistent: a step of cost c lowers K/ρ* by gain/ρ* ≤ c.
//!
//! # Line-of-sight sensor: ⌈K / |S|⌉
//! A laser may see from p' cells of p + S that p's view missed (behind a pillar), so the
//! crescent argument fails. Each position still perceives at most |S| cells and each step to
//! a new position costs at least 1, so at least ⌈K / |S|⌉ more steps remain. Consistent: a
//! step gains at most |S|, lowering the bound by at most 1 ≤ its cost.
//!
//! S is read off the sensor itself (a scan of an empty grid), so the bound uses exactly the
//! sensor's range test. Row intervals make the crescent counts O(r) each; offsets are visited
//! by growing length and the scan stops once |S| / |v| cannot beat the best ratio.

use grid::{Cell, Grid, Occ};
use sense::{FootprintSensor, LosSensor, Observation, Pose, Sensor};

use crate::problem::SensorModel;

/// The coverage-rate bound of one sensor.
#[derive(Clone, Debug)]
pub(crate) struct CoverageRate {
    /// True for the footprint (crescent) bound, false for the per-step bound.
    crescent: bool,
    /// Footprint: ρ*, targets per unit of path; line of sight: |S|, targets per step.
    rate: f64,
}

impl CoverageRate {
    /// The bound for `model` (its range in cells).
    pub(crate) fn new(model: SensorModel) -> Self {
        let rows = offsets(model);
        let size: i64 = rows.iter().map(|&(a, b)| b - a + 1).sum();
        match model {
            SensorModel::Los(_) => Self {
                crescent: false,
                rate: size.max(1) as f64,
            },
            SensorModel::Footprint(_) => Self {
                crescent: true,
                rate: best_ratio(&rows, size),
            },
        }
    }

    /// Lower bound on the path still needed to perceive `left` more targets.
    pub(crate) fn bound(&self, left: usize) -> f64 {
        if left == 0 {
            0.0
        } else if self.crescent {
            left as f64 / self.rate
        } else {
            (left as f64 / self.rate).ceil()
        }
    }
}

/// The sensor's offsets as row intervals: `rows[dy + reach] = (x0, x1)`, empty as x0 > x1.
pub(crate) fn offsets(model: SensorModel) -> Vec<(i64, i64)> {
    let r = model.range();
    let reach = r.floor().max(0.0) as i64;
    let side = (2 * reach + 1) as usize;
    let empty = Grid::new(side, side, Occ::Free);
    let centre = Cell::new(reach as i32, reach as i32);
    let mut obs = Observation::new();
    // Range was validated when the problem was built; an invalid one gives no offsets.
    match model {
        SensorModel::Los(_) => {
            if let Ok(s) = LosSensor::new(r) {
                s.scan(&empty, Pose::new(centre, 0.0), &mut obs);
            }
        }
        SensorModel::Footprint(_) => {
            if let Ok(s) = FootprintSensor::new(r) {
                s.scan(&empty, Pose::new(centre, 0.0), &mut obs);
            }
        }
    }
    let mut rows = vec![(i64::MAX, i64::MIN); side];
    for &(i, _) in &obs.cells {
        let c = empty.cell(i as usize);
        let row = &mut rows[c.y as usize];
        let dx = i64::from(c.x) - reach;
        row.0 = row.0.min(dx);
        row.1 = row.1.max(dx);
    }
    for row in &mut rows {
        if row.0 > row.1 {
            *row = EMPTY;
        }
    }
    rows
}

/// An empty row interval (length 0, and no overflow when intersected).
const EMPTY: (i64, i64) = (1, 0);

/// Cells of interval `a` not in interval `b` (either may be empty).
fn minus(a: (i64, i64), b: (i64, i64)) -> i64 {
    let len = |(x0, x1): (i64, i64)| (x1 - x0 + 1).max(0);
    let inter = (a.0.max(b.0), a.1.min(b.1));
    len(a) - len(inter)
}

/// |(S + v) \ S| for S given by row intervals centred at row `reach`.
fn crescent(rows: &[(i64, i64)], vx: i64, vy: i64) -> i64 {
    let reach = (rows.len() / 2) as i64;
    let at = |dy: i64| -> (i64, i64) {
        if dy.abs() > reach {
            EMPTY
        } else {
            rows[(dy + reach) as usize]
        }
    };
    let mut n = 0;
    for dy in -reach..=reach {
        let (x0, x1) = at(dy);
        if x0 > x1 {
            continue;
        }
        n += minus((x0 + vx, x1 + vx), at(dy + vy));
    }
    n
}

/// ρ* = max over offsets v ≠ 0 of crescent(v) / |v|.
fn best_ratio(rows: &[(i64, i64)], size: i64) -> f64 {
    if size == 0 {
        return 1.0;
    }
    let reach = (rows.len() / 2) as i64;
    // Beyond 2·reach + 1 the translate is disjoint and the ratio only falls.
    let far = 2 * reach + 1;
    let mut vs: Vec<(i64, i64, i64)> = Vec::new();
    for vy in 0..=far {
        for vx in 0..=far {
            // S is symmetric under x → −x and y → −y, so one quadrant of offsets suffices.
            if (vx, vy) != (0, 0) {
                vs.push((vx * vx + vy * vy, vx, vy));
            }
        }
    }
    vs.sort_unstable();
    let mut best: f64 = 0.0;
    for (d2, vx, vy) in vs {
        let len = (d2 as f64).sqrt();
        if size as f64 / len <= best {
            break;
        }
        best = best.max(crescent(rows, vx, vy) as f64 / len);
    }
    best.max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the set difference of two translates of the offset set.
    fn crescent_slow(rows: &[(i64, i64)], vx: i64, vy: i64) -> i64 {
        let reach = (rows.len() / 2) as i64;
        let inside = |x: i64, y: i64| {
            y.abs() <= reach && {
                let (a, b) = rows[(y + reach) as usize];
                a <= x && x <= b
            }
        };
        let mut n = 0;
        let span = 4 * reach + 8;
        for y in -span..=span {
            for x in -span..=span {
                if inside(x - vx, y - vy) && !inside(x, y) {
                    n += 1;
                }
            }
        }
        n
    }

    #[test]
    fn crescents_match_brute_force() {
        for r in [0.5, 1.0, 1.5, 2.3, 3.0, 4.7] {
            let rows = offsets(SensorModel::Footprint(r));
            for vy in -6..=6 {
                for vx in -6..=6 {
                    assert_eq!(
                        crescent(&rows, vx, vy),
                        crescent_slow(&rows, vx, vy),
                        "r {r} v ({vx}, {vy})"
                    );
                }
            }
        }
    }

    #[test]
    fn footprint_rate_is_the_best_crescent_ratio() {
        // r = 1: S is the plus of 5 cells; a unit step uncovers 3 cells, a diagonal one 4
        // (4/√2 ≈ 2.83), a step of 2 uncovers 5 (2.5 per unit): ρ* = 3.
        let b = CoverageRate::new(SensorModel::Footprint(1.0));
        assert!((b.rate - 3.0).abs() < 1e-12, "{}", b.rate);
        assert!((b.bound(7) - 7.0 / 3.0).abs() < 1e-12);
        // Brute-force maximum over all offsets in a wide box.
        for r in [1.5, 2.3, 3.0, 7.5] {
            let rows = offsets(SensorModel::Footprint(r));
            let reach = r.floor() as i64;
            let mut best: f64 = 0.0;
            for vy in -(2 * reach + 3)..=2 * reach + 3 {
                for vx in -(2 * reach + 3)..=2 * reach + 3 {
                    if (vx, vy) != (0, 0) {
                        let len = ((vx * vx + vy * vy) as f64).sqrt();
                        best = best.max(crescent_slow(&rows, vx, vy) as f64 / len);
                    }
                }
            }
            let got = CoverageRate::new(SensorModel::Footprint(r)).rate;
            assert!((got - best).abs() < 1e-12, "r {r}: {got} vs {best}");
        }
    }

    #[test]
    fn los_counts_steps() {
        // r = 1: 5 cells per position at most.
        let b = CoverageRate::new(SensorModel::Los(1.0));
        assert_eq!(b.bound(0), 0.0);
        assert_eq!(b.bound(5), 1.0);
        assert_eq!(b.bound(6), 2.0);
    }
}
