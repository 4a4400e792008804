//! k-means clustering (Lloyd with k-means++ seeding, seeded), for RFE, MTSP and SGA.
//!
//! Faigl & Kulich (2013) use "the K-means algorithm" three times without further detail: for
//! the representatives of a free edge (RFE), for the clusters of goals of the MTSP assignment
//! (MA, started from the last decision's centres), and for Solanas & Garcia's clusters of
//! unknown cells (SGA, initialised at the map centre, then from the previous centres). This
//! is the standard algorithm:
//!
//! - seeding by k-means++ (Arthur & Vassilvitskii 2007): the first centre drawn with
//!   probability ∝ weight, each next one ∝ weight · D² (D = distance to the nearest centre
//!   chosen so far), all draws from the caller's seeded generator; or given initial centres;
//! - Lloyd's iterations: label every point with its nearest centre (ties: the lower centre
//!   index), move every centre to the weighted mean of its points, until no label changes
//!   (at most [`MAX_ITERATIONS`]).
//!
//! Points may carry weights (SGA clusters blocks of unknown cells weighted by their counts).
//! An emptied cluster is moved to the point farthest from its centre among the clusters
//! with at least two points (ties: the lower point index), the usual repair; with fewer
//! distinct points than centres some clusters necessarily stay empty and keep their centre.
//! Centre `j` keeps its index through the iterations, which SGA relies on to keep a cluster
//! per robot. Deterministic for a given generator state; buffers are reused across calls.

use rand::{Rng, RngExt};

/// Upper bound on Lloyd iterations (convergence is usually reached in a few dozen).
pub const MAX_ITERATIONS: usize = 100;

/// A point in the plane `(x, y)`, in cells.
pub type Point = (f64, f64);

/// Where Lloyd's iterations start.
#[derive(Clone, Copy, Debug)]
pub enum Init<'a> {
    /// k-means++ seeding of `k` centres (at most the number of points).
    PlusPlus(usize),
    /// These initial centres (their number is the number of clusters).
    Centres(&'a [Point]),
}

/// k-means state: centres, labels and buffers, reused across calls.
#[derive(Clone, Debug, Default)]
pub struct KMeans {
    centres: Vec<Point>,
    labels: Vec<u32>,
    /// Per cluster: Σ w·x, Σ w·y, Σ w, number of points.
    sums: Vec<(f64, f64, f64, usize)>,
    d2: Vec<f64>,
    iterations: usize,
    converged: bool,
}

/// Squared Euclidean distance.
#[inline]
fn dist2(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a.0 - b.0, a.1 - b.1);
    dx * dx + dy * dy
}

impl KMeans {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Cluster `points` (with optional non-negative `weights`, one per point; `None` = all 1)
    /// starting from `init`, drawing any random choice from `rng`.
    ///
    /// # Panics
    /// If `weights` is given with a length other than `points.len()`.
    pub fn fit<R: Rng + ?Sized>(
        &mut self,
        points: &[Point],
        weights: Option<&[f64]>,
        init: Init<'_>,
        rng: &mut R,
    ) {
        if let Some(w) = weights {
            assert_eq!(w.len(), points.len(), "one weight per point");
        }
        let weight = |i: usize| weights.map_or(1.0, |w| w[i]);
        self.centres.clear();
        self.labels.clear();
        self.iterations = 0;
        self.converged = false;
        match init {
            Init::Centres(c) => self.centres.extend_from_slice(c),
            Init::PlusPlus(k) => self.plus_plus(points, &weight, k.min(points.len()), rng),
        }
        let k = self.centres.len();
        if k == 0 || points.is_empty() {
            self.labels.resize(points.len(), 0);
            self.converged = true;
            return;
        }
        self.labels.resize(points.len(), u32::MAX);
        let mut repaired = false;
        for it in 0..MAX_ITERATIONS {
            self.iterations = it + 1;
            let mut changed = false;
            for (p, label) in points.iter().zip(self.labels.iter_mut()) {
                let l = nearest(&self.centres, *p) as u32;
                if l != *label {
                    *label = l;
                    changed = true;
                }
            }
            if !changed && !repaired {
                self.converged = true;
                return;
            }
            self.sums.clear();
            self.sums.resize(k, (0.0, 0.0, 0.0, 0));
            for (i, (p, &l)) in points.iter().zip(&self.labels).enumerate() {
                let w = weight(i);
                let s = &mut self.sums[l as usize];
                s.0 += w * p.0;
                s.1 += w * p.1;
                s.2 += w;
                s.3 += 1;
            }
            for (c, s) in self.centres.iter_mut().zip(&self.sums) {
                if s.2 > 0.0 {
                    *c = (s.0 / s.2, s.1 / s.2);
                }
            }
            repaired = self.repair_empty(points);
        }
        // Out of iterations: leave labels consistent with the final centres.
        for (p, label) in points.iter().zip(self.labels.iter_mut()) {
            *label = nearest(&self.centres, *p) as u32;
        }
    }

    /// k-means++: `k ≤ points.len()` centres.
    fn plus_plus<R: Rng + ?Sized>(
        &mut self,
        points: &[Point],
        weight: &impl Fn(usize) -> f64,
        k: usize,
        rng: &mut R,
    ) {
        if k == 0 {
            return;
        }
        self.d2.clear();
        self.d2.resize(points.len(), f64::INFINITY);
        let first = {
            let total: f64 = (0..points.len()).map(weight).sum();
            draw(rng, total, points.len(), weight)
        };
        self.centres.push(points[first]);
        while self.centres.len() < k {
            let last = *self.centres.last().expect("one centre");
            let mut total = 0.0;
            for (i, p) in points.iter().enumerate() {
                let d = dist2(*p, last);
                if d < self.d2[i] {
                    self.d2[i] = d;
                }
                total += weight(i) * self.d2[i];
            }
            let d2 = &self.d2;
            let next = draw(rng, total, points.len(), |i| weight(i) * d2[i]);
            self.centres.push(points[next]);
        }
    }

    /// Move each empty cluster's centre to the farthest point of a cluster with ≥ 2 points.
    /// Returns whether anything moved.
    fn repair_empty(&mut self, points: &[Point]) -> bool {
        let mut moved = false;
        for j in 0..self.centres.len() {
            if self.sums[j].3 > 0 {
                continue;
            }
            let mut best: Option<(f64, usize)> = None;
            for (i, (p, &l)) in points.iter().zip(&self.labels).enumerate() {
                let l = l as usize;
                if self.sums[l].3 < 2 {
                    continue;
                }
                let d = dist2(*p, self.centres[l]);
                if d > 0.0 && best.is_none_or(|(bd, _)| d > bd) {
                    best = Some((d, i));
                }
            }
            let Some((_, i)) = best else {
                continue;
            };
            let from = self.labels[i] as usize;
            self.sums[from].3 -= 1;
            self.sums[j].3 = 1;
            self.labels[i] = j as u32;
            self.centres[j] = points[i];
            moved = true;
        }
        moved
    }

    /// The centres.
    pub fn centres(&self) -> &[Point] {
        &self.centres
    }

    /// The cluster of every point (index into [`centres`](Self::centres)).
    pub fn labels(&self) -> &[u32] {
        &self.labels
    }

    /// Lloyd iterations run by the last [`fit`](Self::fit).
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// Whether the last [`fit`](Self::fit) stopped because no label changed.
    pub fn converged(&self) -> bool {
        self.converged
    }

    /// Weighted sum of squared distances of the points to their centres (the k-means cost).
    pub fn cost(&self, points: &[Point], weights: Option<&[f64]>) -> f64 {
        points
            .iter()
            .zip(&self.labels)
            .enumerate()
            .map(|(i, (p, &l))| weights.map_or(1.0, |w| w[i]) * dist2(*p, self.centres[l as usize]))
            .sum()
    }
}

/// Index of the centre nearest to `p` (ties: the lower index); `centres` must not be empty.
#[inline]
pub fn nearest(centres: &[Point], p: Point) -> usize {
    let mut best = 0;
    let mut bd = f64::INFINITY;
    for (j, c) in centres.iter().enumerate() {
        let d = dist2(p, *c);
        if d < bd {
            bd = d;
            best = j;
        }
    }
    best
}

/// Draw an index in `0..n` with probability ∝ `mass(i)`; uniform if the total is zero.
fn draw<R: Rng + ?Sized>(rng: &mut R, total: f64, n: usize, mass: impl Fn(usize) -> f64) -> usize {
    if !(total > 0.0 && total.is_finite()) {
        return rng.random_range(0..n);
    }
    let u = rng.random_range(0.0..total);
    let mut acc = 0.0;
    let mut last_positive = 0;
    for i in 0..n {
        let m = mass(i);
        if m > 0.0 {
            acc += m;
            last_positive = i;
            if u < acc {
                return i;
            }
        }
    }
    last_positive
}
