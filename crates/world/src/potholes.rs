//! `potholes`: a large open area with scattered obstacles, like Faigl & Kulich's (2013)
//! "potholes" environment (40 m × 40 m).
//!
//! About one obstacle per 45 m² is placed by rejection sampling. Each obstacle is an
//! irregular blob: a star-shaped outline `r(θ) = r0 (1 + Σ Aₖ cos kθ + Bₖ sin kθ)`, k = 2..4,
//! with `r0` 0.5–2.2 m and `|Aₖ|, |Bₖ| ≤ 0.085`. The multiple-angle terms are computed from
//! `cos θ` and `sin θ` by polynomials, without calling trigonometric functions, so the
//! rasterised cells do not depend on the platform's maths library. Obstacles keep at least 1.2 m from each other and 1 m from
//! the boundary wall, so the free space stays connected by construction.

use grid::{Grid, Occ};

use crate::raster::{Scale, WALL_M, border};
use crate::rng::Draws;

/// Clear gap kept between two obstacles, in metres.
const GAP_M: f64 = 1.2;
/// Clear gap kept between an obstacle and the boundary wall, in metres.
const WALL_GAP_M: f64 = 1.0;
/// Floor area per obstacle, in m².
const AREA_PER_OBSTACLE: f64 = 45.0;

/// One blob obstacle.
struct Blob {
    cx: f64,
    cy: f64,
    r0: f64,
    /// `(Aₖ, Bₖ)` for k = 2, 3, 4.
    harmonics: [(f64, f64); 3],
}

/// Largest `|Aₖ|` or `|Bₖ|`.
const HARMONIC_MAX: f64 = 0.085;

impl Blob {
    /// Largest radius the outline can reach.
    fn r_max(&self) -> f64 {
        self.r0
            * (1.0
                + self
                    .harmonics
                    .iter()
                    .map(|h| (h.0 * h.0 + h.1 * h.1).sqrt())
                    .sum::<f64>())
    }

    /// Radius of the outline in the direction `(cos θ, sin θ) = (c, s)`.
    fn radius(&self, c: f64, s: f64) -> f64 {
        let (c2, s2) = (c * c - s * s, 2.0 * s * c);
        let (c3, s3) = (c * (4.0 * c * c - 3.0), s * (3.0 - 4.0 * s * s));
        let (c4, s4) = (2.0 * c2 * c2 - 1.0, 2.0 * s2 * c2);
        let [(a2, b2), (a3, b3), (a4, b4)] = self.harmonics;
        self.r0 * (1.0 + a2 * c2 + b2 * s2 + a3 * c3 + b3 * s3 + a4 * c4 + b4 * s4)
    }
}

/// Generate a potholes field of `width_m × height_m` metres at `res` m/cell.
pub fn potholes(width_m: f64, height_m: f64, res: f64, rng: &mut Draws) -> Grid<Occ> {
    let scale = Scale { res };
    let (w, h) = (
        scale.cell(width_m).max(1) as usize,
        scale.cell(height_m).max(1) as usize,
    );
    let mut cells = Grid::new(w, h, Occ::Free);
    let edge = scale.cells_at_least_one(WALL_M) as f64 * res;
    let want = (width_m * height_m / AREA_PER_OBSTACLE).round() as usize;
    let mut blobs: Vec<Blob> = Vec::with_capacity(want);
    for _ in 0..want * 40 {
        if blobs.len() == want {
            break;
        }
        let r0 = rng.range(0.5, 2.2);
        let mut harmonics = [(0.0, 0.0); 3];
        for hm in &mut harmonics {
            *hm = (
                rng.range(-HARMONIC_MAX, HARMONIC_MAX),
                rng.range(-HARMONIC_MAX, HARMONIC_MAX),
            );
        }
        let mut b = Blob {
            cx: 0.0,
            cy: 0.0,
            r0,
            harmonics,
        };
        let rm = b.r_max();
        let margin = edge + WALL_GAP_M + rm;
        b.cx = rng.range(margin, width_m - margin);
        b.cy = rng.range(margin, height_m - margin);
        let fits = b.cx >= margin
            && b.cx <= width_m - margin
            && b.cy >= margin
            && b.cy <= height_m - margin
            && blobs.iter().all(|o| {
                let d = ((o.cx - b.cx).powi(2) + (o.cy - b.cy).powi(2)).sqrt();
                d >= o.r_max() + rm + GAP_M
            });
        if fits {
            blobs.push(b);
        }
    }
    for b in &blobs {
        let rm = b.r_max();
        let x0 = ((b.cx - rm) / res).floor().max(0.0) as usize;
        let x1 = (((b.cx + rm) / res).ceil() as usize).min(w);
        let y0 = ((b.cy - rm) / res).floor().max(0.0) as usize;
        let y1 = (((b.cy + rm) / res).ceil() as usize).min(h);
        for y in y0..y1 {
            for x in x0..x1 {
                let (dx, dy) = (scale.centre(x) - b.cx, scale.centre(y) - b.cy);
                let d2 = dx * dx + dy * dy;
                let d = d2.sqrt();
                if d2 <= rm * rm && (d == 0.0 || d <= b.radius(dx / d, dy / d)) {
                    cells[y * w + x] = Occ::Occupied;
                }
            }
        }
    }
    border(&mut cells, scale.cells_at_least_one(WALL_M));
    cells
}
