//! The Held–Karp (Lagrangian) lower bound on a shortest Hamiltonian path, used to strengthen
//! the landmark spanning-tree bound of [`crate::heuristic`]. Our addition (not in the
//! paper); written here because it runs on a dense graph of at most a few dozen nodes per
//! search state, with scratch reused across calls, which no crate offers.
//!
//! # The bound
//! Complete graph on nodes 0..n with symmetric weights w; a path starts at node 0 and visits
//! every node once, ending anywhere. In such a path node 0 has degree 1, the end node
//! degree 1 and every other node degree 2. For any real π (one per node) add π_u + π_v to
//! the weight of edge uv; the path's weight grows by Σ_v π_v·deg(v) = π_0 + 2·Σ_{v≥1} π_v
//! − π_end. So
//!
//! path weight = (path weight under w + π) − π_0 − 2·Σ_{v≥1} π_v + π_end
//!             ≥ MST(w + π) − π_0 − 2·Σ_{v≥1} π_v + min_{v≥1} π_v,
//!
//! since the path is a spanning tree and π_end ≥ min_{v≥1} π_v. Every π gives a valid
//! bound; π = 0 gives the plain MST, and the best bound over the iterates is returned, so
//! the result is never below the MST. π follows the subgradient (degree in the tree minus
//! degree in a path), which penalises nodes where the tree branches: on a star whose centre
//! is node 0 (k leaves at distance ℓ, 2ℓ apart) the MST is k·ℓ while every path takes
//! (2k − 1)·ℓ, and the bound reaches the latter.
//!
//! Held & Karp (1970), "The traveling-salesman problem and minimum spanning trees".

/// Subgradient steps per bound.
const ITERATIONS: usize = 30;

/// Scratch for [`PathBound::bound`], reused across calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct PathBound {
    pi: Vec<f64>,
    key: Vec<f64>,
    parent: Vec<usize>,
    done: Vec<bool>,
    deg: Vec<i32>,
}

impl PathBound {
    /// The best Lagrangian lower bound on a Hamiltonian path from node 0 through all `n`
    /// nodes, `w` the n × n weight matrix (row-major, symmetric, not negative).
    pub(crate) fn bound(&mut self, n: usize, w: &[f64]) -> f64 {
        if n <= 1 {
            return 0.0;
        }
        debug_assert_eq!(w.len(), n * n);
        self.pi.clear();
        self.pi.resize(n, 0.0);
        let mut best = f64::NEG_INFINITY;
        let mut step = 0.0;
        for it in 0..ITERATIONS {
            let tree = self.tree(n, w);
            let pi = &self.pi;
            let (mut arg, mut low) = (1, pi[1]);
            for (v, &p) in pi.iter().enumerate().skip(2) {
                if p < low {
                    (arg, low) = (v, p);
                }
            }
            let value = tree - pi[0] - 2.0 * pi[1..].iter().sum::<f64>() + low;
            best = best.max(value);
            // Subgradient: degree in the tree minus degree in a path (1 at node 0 and at
            // the end, taken to be the node with the least π).
            let mut norm = 0;
            for v in 0..n {
                let want = if v == 0 || v == arg { 1 } else { 2 };
                let g = self.deg[v] - want;
                self.deg[v] = g;
                norm += g * g;
            }
            if norm == 0 {
                // The tree is a path from node 0: the bound is exact.
                break;
            }
            if it == 0 {
                // A quarter of the mean tree edge, shrinking geometrically.
                step = 0.25 * tree / (n - 1) as f64;
                if step <= 0.0 {
                    break;
                }
            }
            for v in 0..n {
                self.pi[v] += step * f64::from(self.deg[v]);
            }
            step *= 0.9;
        }
        // Floating-point slack: the bound is a sum of n terms.
        (best - 1e-12 * n as f64 * best.abs().max(1.0)).max(0.0)
    }

    /// Prim's MST under w + π (dense, O(n²)); fills `deg` with the tree's degrees.
    fn tree(&mut self, n: usize, w: &[f64]) -> f64 {
        self.key.clear();
        self.key.resize(n, f64::INFINITY);
        self.parent.clear();
        self.parent.resize(n, 0);
        self.done.clear();
        self.done.resize(n, false);
        self.deg.clear();
        self.deg.resize(n, 0);
        let pi = &self.pi;
        self.done[0] = true;
        for v in 1..n {
            self.key[v] = w[v] + pi[0] + pi[v];
        }
        let mut total = 0.0;
        for _ in 1..n {
            let mut u = usize::MAX;
            let mut ku = f64::INFINITY;
            for v in 1..n {
                if !self.done[v] && (u == usize::MAX || self.key[v] < ku) {
                    (u, ku) = (v, self.key[v]);
                }
            }
            self.done[u] = true;
            total += ku;
            self.deg[u] += 1;
            self.deg[self.parent[u]] += 1;
            let row = &w[u * n..(u + 1) * n];
            for v in 1..n {
                if !self.done[v] {
                    let k = row[v] + pi[u] + pi[v];
                    if k < self.key[v] {
                        self.key[v] = k;
                        self.parent[v] = u;
                    }
                }
            }
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Cheapest Hamiltonian path from node 0, by trying every order.
    fn brute(n: usize, w: &[f64]) -> f64 {
        fn go(n: usize, w: &[f64], at: usize, left: &mut Vec<usize>, acc: f64, best: &mut f64) {
            if left.is_empty() {
                *best = best.min(acc);
                return;
            }
            for k in 0..left.len() {
                let v = left.swap_remove(k);
                go(n, w, v, left, acc + w[at * n + v], best);
                left.push(v);
                let last = left.len() - 1;
                left.swap(k, last);
            }
        }
        let mut best = f64::INFINITY;
        go(n, w, 0, &mut (1..n).collect(), 0.0, &mut best);
        if n <= 1 { 0.0 } else { best }
    }

    fn mst(n: usize, w: &[f64]) -> f64 {
        let mut s = PathBound {
            pi: vec![0.0; n],
            ..PathBound::default()
        };
        s.tree(n, w)
    }

    #[test]
    fn a_star_around_the_start_gets_the_path_length() {
        // Node 0 at the centre, k = 5 leaves at distance 3, 6 apart: MST 15, path 27.
        let n = 6;
        let mut w = vec![0.0; n * n];
        for u in 0..n {
            for v in 0..n {
                w[u * n + v] = match (u, v) {
                    _ if u == v => 0.0,
                    (0, _) | (_, 0) => 3.0,
                    _ => 6.0,
                };
            }
        }
        assert!((mst(n, &w) - 15.0).abs() < 1e-12);
        let b = PathBound::default().bound(n, &w);
        assert!(b > 26.0 && b <= 27.0, "{b}");
        assert_eq!(brute(n, &w), 27.0);
    }

    proptest! {
        /// Between the MST and the cheapest path, on random metric and non-metric weights.
        #[test]
        fn between_the_tree_and_the_cheapest_path(
            n in 1usize..8,
            raw in proptest::collection::vec(0u32..20, 64),
            metric in any::<bool>(),
        ) {
            let mut w = vec![0.0; n * n];
            if metric {
                // Points on a line with integer coordinates: |x_u − x_v|.
                for u in 0..n {
                    for v in 0..n {
                        w[u * n + v] = (f64::from(raw[u]) - f64::from(raw[v])).abs();
                    }
                }
            } else {
                for u in 0..n {
                    for v in u + 1..n {
                        let x = f64::from(raw[(u * 8 + v) % 64]);
                        w[u * n + v] = x;
                        w[v * n + u] = x;
                    }
                }
            }
            let b = PathBound::default().bound(n, &w);
            let exact = brute(n, &w);
            prop_assert!(b <= exact + 1e-9, "bound {} above the cheapest path {}", b, exact);
            if n > 1 {
                prop_assert!(b >= mst(n, &w) - 1e-9, "bound {} below the MST {}", b, mst(n, &w));
            }
        }
    }
}
