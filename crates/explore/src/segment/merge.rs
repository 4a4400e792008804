//! The split graph and the iterative merge (Holz et al. 2010, Figure 7 steps 5 and 6).
//!
//! Step 5 collects every transition (s1, s2): two 4-adjacent free cells with different
//! initial segments. Step 6 merges two adjacent segments unless they originate from the same
//! split point, and repeats until no such pair is left. A merged segment carries the set of
//! critical points it has a side of; two segments may merge only if those sets are disjoint —
//! otherwise the merged segment would hold both sides of one split.
//!
//! Holz et al. do not say in which order to merge, and with loops in the map the order
//! decides where the remaining cut falls. Here transitions are taken by decreasing length of
//! the shared border (ties by segment ids): pieces that touch along a long line are the same
//! room first. Since a refused merge stays refused (sets only grow), one pass in this order is
//! the fixed point of the repetition.

use super::graph::NONE;

/// Buffers of the merge.
#[derive(Clone, Debug, Default)]
pub struct Merger {
    keys: Vec<u64>,
    pairs: Vec<(u32, u32, u32)>,
    parent: Vec<u32>,
    sides: Vec<Vec<u32>>,
    remap: Vec<u32>,
    scratch: Vec<u32>,
}

impl Merger {
    /// Merge the `count` initial segments in `labels` (a `width`-wide grid; `NONE` = not
    /// free), of which `2 · critical` are sides of critical points, and relabel them
    /// `0..segments` in order of first appearance. Returns the number of segments.
    pub fn merge(&mut self, width: usize, labels: &mut [u32], count: u32, critical: usize) -> u32 {
        let n = labels.len();
        // step 5: transitions
        self.keys.clear();
        for i in 0..n {
            let a = labels[i];
            if a == NONE {
                continue;
            }
            let right = i + 1;
            if right % width != 0 && right < n {
                let b = labels[right];
                if b != NONE && b != a {
                    self.keys.push(key(a, b));
                }
            }
            let down = i + width;
            if down < n {
                let b = labels[down];
                if b != NONE && b != a {
                    self.keys.push(key(a, b));
                }
            }
        }
        self.keys.sort_unstable();
        self.pairs.clear();
        let mut k = 0;
        while k < self.keys.len() {
            let mut e = k;
            while e < self.keys.len() && self.keys[e] == self.keys[k] {
                e += 1;
            }
            let kk = self.keys[k];
            self.pairs
                .push(((kk >> 32) as u32, kk as u32, (e - k) as u32));
            k = e;
        }
        self.pairs
            .sort_unstable_by(|x, y| y.2.cmp(&x.2).then((x.0, x.1).cmp(&(y.0, y.1))));
        // step 6: merge
        let c = count as usize;
        self.parent.clear();
        self.parent.extend(0..count);
        if self.sides.len() < c {
            self.sides.resize_with(c, Vec::new);
        }
        for (s, v) in self.sides.iter_mut().enumerate().take(c) {
            v.clear();
            if s < 2 * critical {
                v.push((s / 2) as u32);
            }
        }
        for p in 0..self.pairs.len() {
            let (a, b, _) = self.pairs[p];
            let (ra, rb) = (self.find(a), self.find(b));
            if ra == rb || intersects(&self.sides[ra as usize], &self.sides[rb as usize]) {
                continue;
            }
            let (root, child) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[child as usize] = root;
            let child_sides = std::mem::take(&mut self.sides[child as usize]);
            self.scratch.clear();
            union_sorted(&self.sides[root as usize], &child_sides, &mut self.scratch);
            std::mem::swap(&mut self.sides[root as usize], &mut self.scratch);
            self.sides[child as usize] = child_sides;
            self.sides[child as usize].clear();
        }
        // relabel in order of first appearance
        self.remap.clear();
        self.remap.resize(c, NONE);
        let mut next = 0;
        for l in labels.iter_mut() {
            if *l == NONE {
                continue;
            }
            let r = self.find(*l) as usize;
            if self.remap[r] == NONE {
                self.remap[r] = next;
                next += 1;
            }
            *l = self.remap[r];
        }
        next
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let gp = self.parent[self.parent[x as usize] as usize];
            self.parent[x as usize] = gp;
            x = gp;
        }
        x
    }
}

#[inline]
fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    (u64::from(lo) << 32) | u64::from(hi)
}

fn intersects(a: &[u32], b: &[u32]) -> bool {
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => return true,
        }
    }
    false
}

fn union_sorted(a: &[u32], b: &[u32], out: &mut Vec<u32>) {
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        if j == b.len() || (i < a.len() && a[i] < b[j]) {
            out.push(a[i]);
            i += 1;
        } else {
            out.push(b[j]);
            j += 1;
        }
    }
}
