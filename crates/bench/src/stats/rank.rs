//! Average ("mid") ranks with tie information, as `scipy.stats.rankdata(method='average')`.

use std::cmp::Ordering;

/// Tie information of a ranking.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ties {
    /// Σ (t³ − t) over groups of t equal values (0 without ties).
    pub term: f64,
    /// Whether any value occurs more than once.
    pub any: bool,
}

/// Writes the 1-based average ranks of `values` into `ranks` (same order as `values`), using
/// `order` as scratch. Values must not be NaN; -0.0 and 0.0 are equal (tied), as in NumPy.
pub(crate) fn average_ranks(values: &[f64], order: &mut Vec<usize>, ranks: &mut Vec<f64>) -> Ties {
    let n = values.len();
    order.clear();
    order.extend(0..n);
    order.sort_by(|&a, &b| values[a].partial_cmp(&values[b]).unwrap_or(Ordering::Equal));
    ranks.clear();
    ranks.resize(n, 0.0);
    let mut ties = Ties {
        term: 0.0,
        any: false,
    };
    let mut start = 0;
    while start < n {
        let v = values[order[start]];
        let mut end = start + 1;
        while end < n && values[order[end]] == v {
            end += 1;
        }
        let t = (end - start) as f64;
        // Ordinal ranks start+1 ..= end; their mean:
        let r = (start + 1) as f64 + (t - 1.0) / 2.0;
        for &i in &order[start..end] {
            ranks[i] = r;
        }
        if end - start > 1 {
            ties.any = true;
            ties.term += t * t * t - t;
        }
        start = end;
    }
    ties
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worked_example() {
        // scipy: rankdata([3, 2, 1, 2, 2, 2, 1]) = [7, 4.5, 1.5, 4.5, 4.5, 4.5, 1.5]
        let (mut o, mut r) = (Vec::new(), Vec::new());
        let t = average_ranks(&[3.0, 2.0, 1.0, 2.0, 2.0, 2.0, 1.0], &mut o, &mut r);
        assert_eq!(r, vec![7.0, 4.5, 1.5, 4.5, 4.5, 4.5, 1.5]);
        assert!(t.any);
        assert_eq!(t.term, (8.0 - 2.0) + (64.0 - 4.0));
    }
}
