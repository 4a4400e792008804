//! A ring of sonar transducers with specular reflections, its cone-shaped inverse sensor
//! model for the log-odds [`EvidenceGrid`], and laser-limited sonar.
//!
//! Follows Yamauchi (1997), §2.1 and §3: sixteen sonar transducers around the robot, each
//! with a cone of about 25° and a range of about 10 ft; a surface struck at a steep
//! incidence angle reflects the sound away (a specular reflection), so that the echo is
//! lost and the transducer reports a farther surface or its maximum range — which paints
//! phantom open space into the evidence grid. Laser-limited sonar (§2.1) caps each sonar
//! reading at the planar laser's range along the transducer's axis and marks the laser's
//! hits occupied.
//!
//! # Semantics
//!
//! - Transducer `k` (of [`TRANSDUCERS`]) looks along `heading + k · 22.5°` (radians in grid
//!   coordinates, `y` down). Its cone is sampled by rays at most 1° (and at most half a cell
//!   at full range) apart, traced from the centre of the sensor cell with Amanatides & Woo's
//!   grid traversal; the axis is one of them.
//! - A ray stops at the first blocking cell: a plane cell that is not Free, or an off-plane
//!   obstacle (`clutter`, e.g. table tops, which sonar hears but a planar laser misses).
//!   Leaving the grid ends it without an echo. The surface normal at the struck cell is the
//!   sum of the unit offsets to its free 4-neighbours that face the sensor (a flat wall gives
//!   its true normal, a staircase diagonal gives the diagonal); when no free neighbour faces
//!   the sensor (a thin wall struck through its corner), the normal of the cell side the ray
//!   entered through is used. If the angle between the ray and the normal exceeds the
//!   incidence threshold, the sound reflects away: that ray returns nothing.
//! - The reading is the distance (in cells, from the sensor cell's centre to the struck
//!   surface) of the nearest returning ray in the cone, plus Gaussian noise of the given
//!   standard deviation drawn from the caller's RNG; no returning ray, or a noisy range at
//!   or beyond the maximum, gives a max-range reading (`echo == false`).
//!
//! # Inverse sensor model
//!
//! For a reading of range ρ along axis α, a cell whose centre lies at distance `d` and
//! bearing `α + φ` with `|φ| ≤ cone/2` gets weight `w = 1 − (φ / (cone/2))²`
//! (Moravec & Elfes' angular fall-off), and then:
//!
//! - echo, `d + ½ ≤ ρ` (wholly nearer than the surface): `w · l_free`;
//! - echo, `ρ − ½ < d < ρ + band + ½` (the arc the echo may come from):
//!   `w · l_occ · min(1, 2p)`, `p` the cell's occupancy before this scan (Elfes: the echo
//!   came from some cell of the arc, less likely from one already believed empty);
//! - max range, `d + ½ ≤ range` and [`SonarParams::max_range_free`]: `w · l_free`
//!   (the sonar heard nothing, so the cone is taken as empty — the source of Yamauchi's
//!   phantom open space); otherwise nothing.
//!
//! The sensor's own cell gets one full `l_free`. Contributions of all transducers (and of
//! laser hits, `l_occ` each) are summed per cell before they are added to the grid.
//!
//! Deviations from the paper: Yamauchi's inverse model is Moravec & Elfes' probabilistic
//! one, with its own constants; here it is the same shape (free inside the cone, occupied on
//! the arc, weighted by the angle off axis) expressed in the evidence grid's log-odds
//! steps. Specular reflection is modelled by the incidence threshold alone (no multi-path
//! bounce back to the transducer).

use grid::{Cell, Grid, Occ};
use rand::RngExt;

use crate::belief::{Belief, EvidenceGrid};
use crate::footprint::MAX_RANGE_CELLS;
use crate::sensor::Pose;

/// Number of transducers in the ring (Yamauchi's Nomad 200: 16, 22.5° apart).
pub const TRANSDUCERS: usize = 16;
/// Default maximum range in metres (10 ft).
pub const DEFAULT_RANGE_M: f64 = 3.048;
/// Default cone width in degrees.
pub const DEFAULT_CONE_DEG: f64 = 25.0;
/// Default incidence threshold in degrees from the surface normal, per ray of the cone: a
/// flat wall is heard when its normal is within about 32° (20° plus half the cone) of the
/// transducer's axis, as smooth office walls return a wide-beam sonar's pulse only near
/// perpendicular incidence; beyond that the pulse glances off (specular reflection).
pub const DEFAULT_INCIDENCE_DEG: f64 = 20.0;
/// Default standard deviation of the range noise in metres.
pub const DEFAULT_NOISE_M: f64 = 0.03;

/// Which sonar ring a run senses with ([`crate::SensorSpec::sonar_mode`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SonarMode {
    /// Sonar alone: specular reflections paint phantom open space.
    Sonar,
    /// Laser-limited sonar: each reading is capped at the planar laser's range along the
    /// transducer's axis, and the laser's hits are marked occupied.
    LaserLimited,
}

/// A sonar parameter out of its allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("sonar {what}: expected {expected}, found {found}")]
pub struct SonarError {
    /// The parameter.
    pub what: &'static str,
    /// What is allowed.
    pub expected: &'static str,
    /// The value given.
    pub found: f64,
}

/// The parameters of a sonar ring, with ranges in cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SonarParams {
    /// Maximum range in cells.
    pub range: f64,
    /// Full cone width in degrees, in (0, 180).
    pub cone_deg: f64,
    /// Incidence angle from the surface normal beyond which the echo is lost, in (0, 90].
    pub incidence_deg: f64,
    /// Standard deviation of the Gaussian range noise, in cells (0 = exact).
    pub noise_sd: f64,
    /// Depth of the occupied arc beyond the reading, in cells.
    pub band: f64,
    /// Whether a max-range reading marks its cone free.
    pub max_range_free: bool,
}

impl SonarParams {
    /// Yamauchi's sonar on a map of `resolution` metres per cell: 10 ft range, 25° cone,
    /// 20° incidence threshold, 3 cm noise, an occupied arc one cell deep, max-range
    /// readings mark free space.
    pub fn yamauchi(resolution: f64) -> Self {
        Self {
            range: grid::units::cells(DEFAULT_RANGE_M, resolution),
            cone_deg: DEFAULT_CONE_DEG,
            incidence_deg: DEFAULT_INCIDENCE_DEG,
            noise_sd: DEFAULT_NOISE_M / resolution,
            band: 1.0,
            max_range_free: true,
        }
    }
}

/// What one transducer reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SonarReading {
    /// The transducer's axis in radians (grid coordinates, y down).
    pub axis: f64,
    /// The range in cells (the maximum range when there was no echo).
    pub range: f64,
    /// Whether an echo came back (false: max-range reading).
    pub echo: bool,
}

/// A ring of [`TRANSDUCERS`] sonar transducers.
#[derive(Clone, Debug)]
pub struct SonarSensor {
    params: SonarParams,
    /// Per-cell evidence of one integration, reused (no allocation per scan).
    deltas: Vec<(u32, f64)>,
    /// Ray offsets from the axis across the cone, in radians.
    offsets: Vec<f64>,
    cos_incidence: f64,
}

/// Where a ray first struck a blocking cell.
struct Strike {
    /// Distance from the sensor cell's centre to the entry point, in cells.
    t: f64,
    /// Flat index of the struck cell.
    i: usize,
    /// Whether the ray entered through a vertical cell side (an x step).
    x_side: bool,
    /// Steps of the traversal.
    step: (i64, i64),
}

impl SonarSensor {
    /// A sonar ring with `params`, checked.
    pub fn new(params: SonarParams) -> Result<Self, SonarError> {
        let bad = |what, expected, found| SonarError {
            what,
            expected,
            found,
        };
        if !(params.range.is_finite() && params.range > 0.0 && params.range <= MAX_RANGE_CELLS) {
            return Err(bad(
                "range",
                "a positive number of cells within the sensor limit",
                params.range,
            ));
        }
        if !(params.cone_deg > 0.0 && params.cone_deg < 180.0) {
            return Err(bad("cone", "degrees in (0, 180)", params.cone_deg));
        }
        if !(params.incidence_deg > 0.0 && params.incidence_deg <= 90.0) {
            return Err(bad("incidence", "degrees in (0, 90]", params.incidence_deg));
        }
        if !(params.noise_sd.is_finite() && params.noise_sd >= 0.0) {
            return Err(bad(
                "noise",
                "a non-negative number of cells",
                params.noise_sd,
            ));
        }
        if !(params.band.is_finite() && params.band >= 0.0) {
            return Err(bad("band", "a non-negative number of cells", params.band));
        }
        let half = params.cone_deg.to_radians() / 2.0;
        let max_step = 1f64.to_radians().min(0.5 / params.range);
        // An even number of intervals, so that the axis itself is one of the rays.
        let n = ((2.0 * half / max_step).ceil() as usize)
            .max(2)
            .next_multiple_of(2);
        let offsets = (0..=n)
            .map(|k| -half + 2.0 * half * k as f64 / n as f64)
            .collect();
        Ok(Self {
            params,
            deltas: Vec::new(),
            offsets,
            cos_incidence: params.incidence_deg.to_radians().cos(),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &SonarParams {
        &self.params
    }

    /// The axis of transducer `k` for a robot heading `heading` (radians, grid coordinates).
    pub fn axis(heading: f64, k: usize) -> f64 {
        heading + (k as f64) * std::f64::consts::TAU / TRANSDUCERS as f64
    }

    /// Fire the ring from `pose`: clears `out`, then pushes one reading per transducer.
    ///
    /// `plane` is the ground truth in the laser plane; `clutter`, when given (same size),
    /// marks off-plane obstacles that sonar hears too. Noise is drawn from `rng` (nothing is
    /// drawn when the noise is 0 or there is no echo).
    pub fn fire<R: rand::Rng + ?Sized>(
        &self,
        plane: &Grid<Occ>,
        clutter: Option<&Grid<bool>>,
        pose: Pose,
        rng: &mut R,
        out: &mut Vec<SonarReading>,
    ) {
        out.clear();
        let range = self.params.range;
        let blocked = |i: usize| plane[i] != Occ::Free || clutter.is_some_and(|c| c[i]);
        for k in 0..TRANSDUCERS {
            let axis = Self::axis(pose.heading, k);
            let mut nearest = f64::INFINITY;
            if plane.checked_index(pose.cell).is_some_and(|i| !blocked(i)) {
                for &off in &self.offsets {
                    let (dy, dx) = (axis + off).sin_cos();
                    let Some(s) = strike(plane, pose.cell, (dx, dy), range, blocked) else {
                        continue;
                    };
                    if s.t < nearest && self.returns(plane, &s, (dx, dy), blocked) {
                        nearest = s.t;
                    }
                }
            } else {
                // A sensor inside an obstacle hears it at once.
                nearest = 0.0;
            }
            let mut reading = SonarReading {
                axis,
                range,
                echo: false,
            };
            if nearest.is_finite() {
                let noisy = if self.params.noise_sd > 0.0 {
                    nearest + self.params.noise_sd * gaussian(rng)
                } else {
                    nearest
                };
                if noisy < range {
                    reading.range = noisy.max(0.0);
                    reading.echo = true;
                }
            }
            out.push(reading);
        }
    }

    /// Whether a ray striking `s` along `dir` comes back: its incidence angle from the
    /// surface normal is within the threshold.
    fn returns(
        &self,
        plane: &Grid<Occ>,
        s: &Strike,
        dir: (f64, f64),
        blocked: impl Fn(usize) -> bool,
    ) -> bool {
        let c = plane.cell(s.i);
        let (mut nx, mut ny) = (0.0, 0.0);
        for (ox, oy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
            let facing = f64::from(ox) * dir.0 + f64::from(oy) * dir.1 < 0.0;
            let free = plane
                .checked_index(c.offset(ox, oy))
                .is_some_and(|j| !blocked(j));
            if facing && free {
                nx += f64::from(ox);
                ny += f64::from(oy);
            }
        }
        if nx == 0.0 && ny == 0.0 {
            if s.x_side {
                nx = -(s.step.0 as f64);
            } else {
                ny = -(s.step.1 as f64);
            }
        }
        let cos_inc = -(nx * dir.0 + ny * dir.1) / (nx * nx + ny * ny).sqrt();
        cos_inc >= self.cos_incidence - 1e-12
    }

    /// Laser-limited sonar: for each reading, trace the planar laser along the transducer's
    /// axis in `plane` (off-plane clutter is invisible to it); where the laser reads shorter
    /// than the sonar, the reading becomes the laser's range (an echo), and the laser's hit
    /// cell is pushed to `hits` (to be marked occupied). `hits` is appended to.
    pub fn limit_by_laser(
        &self,
        plane: &Grid<Occ>,
        cell: Cell,
        readings: &mut [SonarReading],
        hits: &mut Vec<u32>,
    ) {
        if plane
            .checked_index(cell)
            .is_none_or(|i| plane[i] != Occ::Free)
        {
            return;
        }
        for r in readings.iter_mut() {
            let (dy, dx) = r.axis.sin_cos();
            let Some(s) = strike(plane, cell, (dx, dy), self.params.range, |i| {
                plane[i] != Occ::Free
            }) else {
                continue;
            };
            if s.t < r.range {
                r.range = s.t;
                r.echo = true;
                hits.push(s.i as u32);
            }
        }
    }

    /// Add the cone-shaped inverse sensor model of `readings` taken at `origin`, and `l_occ`
    /// for each cell in `occupied` (laser hits), to `belief`; push every cell whose class
    /// changed to `changed` (once each).
    pub fn integrate(
        &mut self,
        origin: Cell,
        readings: &[SonarReading],
        occupied: &[u32],
        belief: &mut EvidenceGrid,
        changed: &mut Vec<u32>,
    ) {
        let known = belief.known();
        let (w, h) = (known.width() as i64, known.height() as i64);
        let Some(origin_i) = known.checked_index(origin) else {
            return;
        };
        let (l_occ, l_free) = (belief.l_occ(), belief.l_free());
        let half = self.params.cone_deg.to_radians() / 2.0;
        let band = self.params.band;
        let mut deltas = std::mem::take(&mut self.deltas);
        deltas.clear();
        deltas.push((origin_i as u32, l_free));
        deltas.extend(occupied.iter().map(|&i| (i, l_occ)));
        for r in readings {
            let reach = if r.echo {
                r.range + band + 0.5
            } else if self.params.max_range_free {
                r.range
            } else {
                continue;
            };
            let (ox, oy) = (i64::from(origin.x), i64::from(origin.y));
            let (x0, x1, y0, y1) = sector_box(r.axis, half, reach);
            for y in (oy + y0).max(0)..=(oy + y1).min(h - 1) {
                for x in (ox + x0).max(0)..=(ox + x1).min(w - 1) {
                    let (dx, dy) = ((x - ox) as f64, (y - oy) as f64);
                    let d = (dx * dx + dy * dy).sqrt();
                    if d < 0.5 || d >= reach {
                        continue;
                    }
                    let phi = wrap(dy.atan2(dx) - r.axis);
                    if phi.abs() > half {
                        continue;
                    }
                    let weight = 1.0 - (phi / half).powi(2);
                    let delta = if !r.echo {
                        if d + 0.5 <= r.range {
                            weight * l_free
                        } else {
                            continue;
                        }
                    } else if d + 0.5 <= r.range {
                        weight * l_free
                    } else if d > r.range - 0.5 {
                        // Elfes: the echo came from some cell of the arc, less likely from
                        // one already believed empty.
                        let p = belief.p_occupied((y * w + x) as usize);
                        weight * l_occ * (2.0 * p).min(1.0)
                    } else {
                        continue;
                    };
                    deltas.push(((y * w + x) as u32, delta));
                }
            }
        }
        // Sum the contributions per cell in place (sorted by cell, merged).
        deltas.sort_unstable_by_key(|&(i, _)| i);
        let mut n = 0;
        for k in 0..deltas.len() {
            if n > 0 && deltas[n - 1].0 == deltas[k].0 {
                deltas[n - 1].1 += deltas[k].1;
            } else {
                deltas[n] = deltas[k];
                n += 1;
            }
        }
        deltas.truncate(n);
        belief.add_evidence(&deltas, changed);
        self.deltas = deltas;
    }
}

/// Trace a ray from the centre of `from` along unit `dir` (Amanatides & Woo) to the first
/// cell that is `blocked`, entered at a distance below `range`; `None` if the ray reaches
/// its range or leaves the grid first.
fn strike(
    grid: &Grid<Occ>,
    from: Cell,
    dir: (f64, f64),
    range: f64,
    blocked: impl Fn(usize) -> bool,
) -> Option<Strike> {
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let (dx, dy) = dir;
    let step = (if dx < 0.0 { -1 } else { 1 }, if dy < 0.0 { -1 } else { 1 });
    let (delta_x, delta_y) = (1.0 / dx.abs(), 1.0 / dy.abs());
    let (mut t_x, mut t_y) = (0.5 * delta_x, 0.5 * delta_y);
    let (mut x, mut y) = (i64::from(from.x), i64::from(from.y));
    loop {
        let (t, x_side) = if t_x < t_y {
            x += step.0;
            let t = t_x;
            t_x += delta_x;
            (t, true)
        } else {
            y += step.1;
            let t = t_y;
            t_y += delta_y;
            (t, false)
        };
        if t >= range || x < 0 || y < 0 || x >= w || y >= h {
            return None;
        }
        let i = (y * w + x) as usize;
        if blocked(i) {
            return Some(Strike { t, i, x_side, step });
        }
    }
}

/// The cell offsets `(x_min, x_max, y_min, y_max)` bounding the circular sector of radius
/// `reach` around `axis` ± `half` (radians): its two edge ends, the apex, and the
/// points at the compass directions the sector spans.
fn sector_box(axis: f64, half: f64, reach: f64) -> (i64, i64, i64, i64) {
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut take = |a: f64| {
        let (sy, sx) = a.sin_cos();
        x0 = x0.min(reach * sx);
        x1 = x1.max(reach * sx);
        y0 = y0.min(reach * sy);
        y1 = y1.max(reach * sy);
    };
    take(axis - half);
    take(axis + half);
    for k in 0..4 {
        let compass = f64::from(k) * std::f64::consts::FRAC_PI_2;
        if wrap(compass - axis).abs() <= half {
            take(compass);
        }
    }
    (
        x0.floor() as i64 - 1,
        x1.ceil() as i64 + 1,
        y0.floor() as i64 - 1,
        y1.ceil() as i64 + 1,
    )
}

/// An angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let r = a.rem_euclid(tau);
    if r > std::f64::consts::PI { r - tau } else { r }
}

/// A standard normal draw (Box–Muller) from `rng`.
fn gaussian<R: rand::Rng + ?Sized>(rng: &mut R) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_is_in_half_open_range() {
        assert!((wrap(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
        assert!((wrap(-0.25) + 0.25).abs() < 1e-12);
        assert!((wrap(std::f64::consts::TAU + 0.5) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn bad_parameters_are_rejected() {
        let ok = SonarParams::yamauchi(0.1);
        assert!(SonarSensor::new(ok).is_ok());
        for p in [
            SonarParams { range: -1.0, ..ok },
            SonarParams {
                cone_deg: 0.0,
                ..ok
            },
            SonarParams {
                incidence_deg: 95.0,
                ..ok
            },
            SonarParams {
                noise_sd: f64::NAN,
                ..ok
            },
        ] {
            assert!(SonarSensor::new(p).is_err());
        }
    }

    #[test]
    fn sector_boxes_hold_their_sectors() {
        // Every point of a sampled sector lies in its box.
        for k in 0..64 {
            let axis = f64::from(k) * 0.1 - 3.0;
            let half = 12.5f64.to_radians();
            let (x0, x1, y0, y1) = sector_box(axis, half, 20.0);
            for i in 0..=20 {
                for j in 0..=20 {
                    let a = axis - half + 2.0 * half * f64::from(i) / 20.0;
                    let d = 20.0 * f64::from(j) / 20.0;
                    let (x, y) = (d * a.cos(), d * a.sin());
                    assert!(x >= x0 as f64 && x <= x1 as f64 && y >= y0 as f64 && y <= y1 as f64);
                }
            }
        }
    }

    #[test]
    fn axes_are_a_ring() {
        let a = SonarSensor::axis(0.0, 4);
        assert!((a - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    }
}
