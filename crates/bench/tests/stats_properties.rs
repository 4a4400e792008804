//! Property tests of the statistics against slow, obviously-correct oracles: brute-force
//! enumeration of every rank assignment (Mann–Whitney) and every sign flip (Wilcoxon), direct
//! pair counting for U, and invariances of the summaries, Shapiro–Wilk and the `+/=/-` matrix.

use bench::stats::{
    Method, MethodUsed, Pairing, Verdict, compare, mann_whitney_u, mann_whitney_u_with,
    pairwise_matrix, shapiro_wilk, summarize, wilcoxon_signed_rank_diffs,
};
use proptest::prelude::*;

/// O(n²) average rank of `v` within `all`.
fn naive_rank(all: &[f64], v: f64) -> f64 {
    let less = all.iter().filter(|&&a| a < v).count() as f64;
    let equal = all.iter().filter(|&&a| a == v).count() as f64;
    less + (equal + 1.0) / 2.0
}

/// Two-sided exact Mann–Whitney p by enumerating every way to give n1 of the ranks 1..=N to x.
fn brute_mwu_p(n1: usize, n2: usize, u_max: f64) -> f64 {
    let n = n1 + n2;
    let (mut hits, mut all) = (0u64, 0u64);
    for mask in 0u32..(1 << n) {
        if mask.count_ones() as usize != n1 {
            continue;
        }
        let r1: usize = (0..n).filter(|i| mask & (1 << i) != 0).map(|i| i + 1).sum();
        let u = r1 as f64 - (n1 * (n1 + 1)) as f64 / 2.0;
        all += 1;
        if u >= u_max {
            hits += 1;
        }
    }
    (2.0 * hits as f64 / all as f64).min(1.0)
}

/// Two-sided p of the complete sign-flip test over the nonzero differences.
fn brute_signflip_p(d: &[f64]) -> f64 {
    let nz: Vec<f64> = d.iter().copied().filter(|v| *v != 0.0).collect();
    let abs: Vec<f64> = nz.iter().map(|v| v.abs()).collect();
    let ranks: Vec<f64> = abs.iter().map(|&a| naive_rank(&abs, a)).collect();
    let obs: f64 = nz
        .iter()
        .zip(&ranks)
        .filter(|(v, _)| **v > 0.0)
        .map(|(_, r)| r)
        .sum();
    let m = nz.len();
    let (mut le, mut ge) = (0u64, 0u64);
    for mask in 0u32..(1 << m) {
        let s: f64 = (0..m)
            .filter(|i| mask & (1 << i) != 0)
            .map(|i| ranks[i])
            .sum();
        if s <= obs + 1e-9 {
            le += 1;
        }
        if s >= obs - 1e-9 {
            ge += 1;
        }
    }
    (2.0 * le.min(ge) as f64 / (1u64 << m) as f64).min(1.0)
}

/// A random split of a shuffled 1..=n1+n2 (no ties), scaled to non-integers.
fn untied_pair() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (1usize..=7, 1usize..=7).prop_flat_map(|(n1, n2)| {
        Just(
            (1..=n1 + n2)
                .map(|i| i as f64 * 0.37 - 1.0)
                .collect::<Vec<f64>>(),
        )
        .prop_shuffle()
        .prop_map(move |v| (v[..n1].to_vec(), v[n1..].to_vec()))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn mwu_exact_equals_enumeration((x, y) in untied_pair()) {
        let r = mann_whitney_u(&x, &y).unwrap();
        prop_assert_eq!(r.method, MethodUsed::Exact);
        let want = brute_mwu_p(x.len(), y.len(), r.u1.max(r.u2));
        prop_assert!((r.p_value - want).abs() <= 1e-12 * want.max(1e-300), "{} vs {}", r.p_value, want);
    }

    #[test]
    fn mwu_u_is_pair_count(
        x in prop::collection::vec(0i32..6, 1..30),
        y in prop::collection::vec(0i32..6, 1..30),
    ) {
        let (x, y): (Vec<f64>, Vec<f64>) = (x.iter().map(|&v| v as f64).collect(), y.iter().map(|&v| v as f64).collect());
        let mut u1 = 0.0;
        for a in &x {
            for b in &y {
                u1 += if a > b { 1.0 } else if a == b { 0.5 } else { 0.0 };
            }
        }
        for m in [Method::Auto, Method::Asymptotic, Method::Exact] {
            let r = mann_whitney_u_with(&x, &y, m).unwrap();
            prop_assert_eq!(r.u1, u1);
            prop_assert_eq!(r.u1 + r.u2, (x.len() * y.len()) as f64);
            prop_assert!((0.0..=1.0).contains(&r.p_value));
            // Swapping the samples swaps U and keeps the two-sided p.
            let s = mann_whitney_u_with(&y, &x, m).unwrap();
            prop_assert_eq!((s.u1, s.u2), (r.u2, r.u1));
            prop_assert!((s.p_value - r.p_value).abs() <= 1e-12);
        }
    }

    #[test]
    fn wilcoxon_small_equals_signflip_enumeration(d in prop::collection::vec(-4i32..=4, 1..=12)) {
        // Integer differences: plenty of ties and zeros, and the untied case too.
        let d: Vec<f64> = d.iter().map(|&v| v as f64 * 0.5).collect();
        let r = wilcoxon_signed_rank_diffs(&d, Method::Auto).unwrap();
        let want = brute_signflip_p(&d);
        prop_assert!((r.p_value - want).abs() <= 1e-12 * want.max(1e-300), "{} vs {} ({:?})", r.p_value, want, r.method);
        let neg: Vec<f64> = d.iter().map(|v| -v).collect();
        let s = wilcoxon_signed_rank_diffs(&neg, Method::Auto).unwrap();
        prop_assert_eq!((s.r_plus, s.r_minus), (r.r_minus, r.r_plus));
        prop_assert!((s.p_value - r.p_value).abs() <= 1e-12);
    }

    #[test]
    fn wilcoxon_untied_exact_equals_signflip(v in Just((1..=14).map(f64::from).collect::<Vec<f64>>()).prop_shuffle(), signs in prop::collection::vec(any::<bool>(), 14), n in 1usize..=14) {
        let d: Vec<f64> = v[..n].iter().zip(&signs).map(|(a, s)| if *s { *a } else { -*a }).collect();
        let r = wilcoxon_signed_rank_diffs(&d, Method::Auto).unwrap();
        prop_assert_eq!(r.method, MethodUsed::Exact);
        let want = brute_signflip_p(&d);
        prop_assert!((r.p_value - want).abs() <= 1e-12 * want.max(1e-300), "{} vs {}", r.p_value, want);
    }

    #[test]
    fn summary_is_ordered_and_shift_invariant(x in prop::collection::vec(-1e3f64..1e3, 1..60), shift in -1e3f64..1e3) {
        let s = summarize(&x).unwrap();
        prop_assert!(s.min <= s.q1 && s.q1 <= s.median && s.median <= s.q3 && s.q3 <= s.max);
        prop_assert!(s.min <= s.mean + 1e-9 && s.mean <= s.max + 1e-9);
        prop_assert!(s.iqr >= 0.0);
        let moved: Vec<f64> = x.iter().map(|v| v + shift).collect();
        let t = summarize(&moved).unwrap();
        prop_assert!((t.median - s.median - shift).abs() < 1e-9);
        prop_assert!((t.mean - s.mean - shift).abs() < 1e-9);
        if x.len() > 1 {
            prop_assert!((t.sd - s.sd).abs() < 1e-8 * s.sd.max(1.0));
        }
    }

    #[test]
    fn shapiro_is_affine_invariant(x in prop::collection::vec(-100f64..100.0, 3..80), a in -50f64..50.0, b in 0.1f64..10.0) {
        let r = shapiro_wilk(&x).unwrap();
        prop_assert!(r.w > 0.0 && r.w <= 1.0 + 1e-12, "W = {}", r.w);
        prop_assert!((0.0..=1.0).contains(&r.p_value));
        let y: Vec<f64> = x.iter().map(|v| a + b * v).collect();
        let s = shapiro_wilk(&y).unwrap();
        prop_assert!((s.w - r.w).abs() < 1e-9, "{} vs {}", s.w, r.w);
    }

    #[test]
    fn matrix_is_antisymmetric(groups in prop::collection::vec(prop::collection::vec(0i32..40, 12), 1..5), alpha in prop_oneof![Just(0.001), Just(0.05)]) {
        let groups: Vec<Vec<f64>> = groups.iter().map(|g| g.iter().map(|&v| v as f64).collect()).collect();
        let refs: Vec<&[f64]> = groups.iter().map(Vec::as_slice).collect();
        for pairing in [Pairing::Unpaired, Pairing::Paired] {
            let m = pairwise_matrix(&refs, alpha, pairing).unwrap();
            for a in 0..refs.len() {
                prop_assert!(m.get(a, a).is_none());
                for b in 0..refs.len() {
                    if a == b { continue; }
                    let (ab, ba) = (m.get(a, b).unwrap(), m.get(b, a).unwrap());
                    prop_assert_eq!(ab.verdict, ba.verdict.flip());
                    prop_assert_eq!(ab.p_value, ba.p_value);
                    let direct = compare(refs[a], refs[b], alpha, pairing).unwrap();
                    prop_assert_eq!(direct.verdict, ab.verdict);
                    let significant = ab.p_value < alpha;
                    prop_assert_eq!(ab.verdict != Verdict::Same, significant && ab.mean_a != ab.mean_b);
                    if ab.verdict == Verdict::Better { prop_assert!(ab.mean_a < ab.mean_b); }
                }
            }
        }
    }
}
