//! The initial assignment of free cells to split points (Holz et al. 2010, Figure 7 steps 3
//! and 4): each critical point gives two segments, seeded at its two neighbours on the
//! Voronoi graph, and every free cell joins the seed nearest to it — a nearest-neighbour
//! transform.
//!
//! Deviation: distances are measured *inside free space* (8-connected moves without corner
//! squeezing, chamfer weights 5 and 7 for straight and diagonal steps) instead of by the
//! straight-line EDT. The split line at a doorway is the same (the bisector of the two seeds,
//! through the critical point), but a cell behind a wall is never given to the seed of the
//! room next door, which with small rooms side by side happens often under Euclidean distance.
//! Free cells that no seed reaches (a free component without critical points) form one extra
//! segment per component.

use grid::{Grid, Occ};

use super::critical::CriticalPoint;
use super::graph::NONE;

const STRAIGHT: u32 = 5;
const DIAGONAL: u32 = 7;
const RING: usize = 8;

/// Buffers of the nearest-seed transform.
#[derive(Clone, Debug, Default)]
pub struct Assigner {
    dist: Vec<u32>,
    buckets: Vec<Vec<u32>>,
}

impl Assigner {
    /// Label every free cell of `known` with its initial segment: `2k` / `2k + 1` for the
    /// sides of critical point `k`, then one label per seedless free component. Cells that
    /// are not free get [`NONE`]. Returns the number of labels.
    pub fn assign(
        &mut self,
        known: &Grid<Occ>,
        critical: &[CriticalPoint],
        labels: &mut Vec<u32>,
    ) -> u32 {
        let (w, h) = (known.width(), known.height());
        let n = w * h;
        let cells = known.data();
        labels.clear();
        labels.resize(n, NONE);
        self.dist.clear();
        self.dist.resize(n, u32::MAX);
        if self.buckets.len() != RING {
            self.buckets = vec![Vec::new(); RING];
        }
        for b in &mut self.buckets {
            b.clear();
        }
        let mut pending = 0usize;
        for (k, cp) in critical.iter().enumerate() {
            for (side, seed) in [cp.side_a, cp.side_b].into_iter().enumerate() {
                let s = seed as usize;
                if self.dist[s] != 0 {
                    self.dist[s] = 0;
                    labels[s] = (2 * k + side) as u32;
                    self.buckets[0].push(seed);
                    pending += 1;
                }
            }
        }
        // Dial's algorithm: a ring of buckets, one per distance modulo RING.
        let mut d = 0u32;
        let mut cur = Vec::new();
        while pending > 0 {
            let slot = (d as usize) % RING;
            std::mem::swap(&mut cur, &mut self.buckets[slot]);
            let mut idx = 0;
            while idx < cur.len() {
                let i = cur[idx] as usize;
                idx += 1;
                pending -= 1;
                if self.dist[i] != d {
                    continue;
                }
                let label = labels[i];
                let (x, y) = ((i % w) as i64, (i / w) as i64);
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        if dx == 0 && dy == 0 {
                            continue;
                        }
                        let (nx, ny) = (x + dx, y + dy);
                        if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                            continue;
                        }
                        let j = (ny as usize) * w + nx as usize;
                        if !cells[j].is_free() {
                            continue;
                        }
                        let step = if dx != 0 && dy != 0 {
                            let a = cells[(y as usize) * w + nx as usize].is_free();
                            let b = cells[(ny as usize) * w + x as usize].is_free();
                            if !a && !b {
                                continue;
                            }
                            DIAGONAL
                        } else {
                            STRAIGHT
                        };
                        let nd = d + step;
                        if nd < self.dist[j] {
                            self.dist[j] = nd;
                            labels[j] = label;
                            // steps are shorter than RING, so never the bucket in use
                            self.buckets[(nd as usize) % RING].push(j as u32);
                            pending += 1;
                        }
                    }
                }
            }
            cur.clear();
            std::mem::swap(&mut cur, &mut self.buckets[slot]);
            d += 1;
        }
        // seedless free components
        let mut next = 2 * critical.len() as u32;
        let stack = &mut self.buckets[0];
        for s in 0..n {
            if !cells[s].is_free() || labels[s] != NONE {
                continue;
            }
            labels[s] = next;
            stack.clear();
            stack.push(s as u32);
            while let Some(i) = stack.pop() {
                let i = i as usize;
                let (x, y) = ((i % w) as i64, (i / w) as i64);
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let (nx, ny) = (x + dx, y + dy);
                        if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                            continue;
                        }
                        let j = (ny as usize) * w + nx as usize;
                        if !cells[j].is_free() || labels[j] != NONE {
                            continue;
                        }
                        if dx != 0 && dy != 0 {
                            let a = cells[(y as usize) * w + nx as usize].is_free();
                            let b = cells[(ny as usize) * w + x as usize].is_free();
                            if !a && !b {
                                continue;
                            }
                        }
                        labels[j] = next;
                        stack.push(j as u32);
                    }
                }
            }
            next += 1;
        }
        stack.clear();
        next
    }
}
