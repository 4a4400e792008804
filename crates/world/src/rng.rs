//! The generators' random source: a seeded `Pcg64Mcg` and the few draws they need.
//!
//! The draws are computed here from raw 64-bit outputs instead of through `rand`'s
//! distributions, so that the environments depend only on the `Pcg64Mcg` stream (pinned by a
//! golden test), not on how a `rand` release happens to sample ranges.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// A seeded random source with the draws the generators use.
#[derive(Clone, Debug)]
pub struct Draws {
    /// The underlying portable generator.
    rng: Pcg64Mcg,
}

impl Draws {
    /// The source for `seed`: `Pcg64Mcg::seed_from_u64(seed)`.
    pub fn new(seed: u64) -> Self {
        Self {
            rng: Pcg64Mcg::seed_from_u64(seed),
        }
    }

    /// The next raw 64-bit output.
    pub fn u64(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)` (`lo` if the range is empty).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        if hi > lo {
            lo + (hi - lo) * self.unit()
        } else {
            lo
        }
    }

    /// Uniform integer in `0..n` (0 if `n == 0`), by a 128-bit multiply of one draw.
    pub fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.u64()) * n as u128) >> 64) as usize
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
}
