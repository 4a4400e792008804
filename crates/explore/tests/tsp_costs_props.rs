//! Route costs computed when read give the routes and costs of a matrix, bit for bit: the
//! TSP solver on costs it reads through [`Costs`] against the same costs as a matrix.

use explore::tsp::{Costs, Dense, FULL_3OPT_UP_TO, OpenTsp, route_cost, route_cost_of};
use proptest::prelude::*;

/// A matrix the solver may only read entry by entry, as it reads costs computed on demand.
struct Computed<'a>(Dense<'a>);

impl Costs for Computed<'_> {
    fn n(&self) -> usize {
        self.0.n()
    }

    fn get(&self, a: u32, b: u32) -> f64 {
        self.0.get(a, b)
    }
}

/// xorshift64*, for the random instances.
fn next(state: &mut u64) -> u64 {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    state.wrapping_mul(0x2545_F491_4F6C_DD1D)
}

/// A random symmetric `n × n` instance: integer costs (many ties) or real ones, some pairs
/// unreachable (infinite) if `holes`.
fn instance(n: usize, seed: u64, integer: bool, holes: bool) -> Vec<f64> {
    let mut state = seed | 1;
    let mut d = vec![0.0; n * n];
    for a in 0..n {
        for b in a + 1..n {
            let v = next(&mut state) % 1000;
            let v = if holes && v.is_multiple_of(13) {
                f64::INFINITY
            } else if integer {
                (v % 7) as f64
            } else {
                v as f64 * 0.37 + 0.1
            };
            d[a * n + b] = v;
            d[b * n + a] = v;
        }
    }
    d
}

proptest! {
    /// Costs read entry by entry give the matrix's routes and cost bits, both efforts, with
    /// and without shared goal lists, small instances (copied into a matrix) and large.
    #[test]
    fn costs_read_when_needed_give_the_matrix_routes(
        n in 0usize..80,
        seed in any::<u64>(),
        integer in any::<bool>(),
        holes in any::<bool>(),
    ) {
        let d = instance(n, seed, integer, holes);
        let computed = Computed(Dense::new(n, &d));
        let (mut lists, mut read) = (Vec::new(), Vec::new());
        if n > FULL_3OPT_UP_TO {
            OpenTsp::new().goal_neighbours(n, &d, &mut lists);
            OpenTsp::new().goal_neighbours_of(&computed, &mut read);
            prop_assert_eq!(&lists, &read);
        }
        let lists = (!lists.is_empty()).then_some(&lists[..]);
        for (starts, kicks) in [(1, 0), (12, 100)] {
            for shared in [None, lists] {
                let mut dense = OpenTsp::with_effort(starts, kicks);
                let mut ondemand = OpenTsp::with_effort(starts, kicks);
                let a = dense.solve_sharing(n, &d, shared);
                let b = ondemand.solve_costs(&computed, shared);
                prop_assert_eq!(a.to_bits(), b.to_bits());
                prop_assert_eq!(dense.route(), ondemand.route());
                prop_assert_eq!(
                    route_cost(n, &d, dense.route()).to_bits(),
                    route_cost_of(&computed, ondemand.route()).to_bits()
                );
            }
        }
    }
}
