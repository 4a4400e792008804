//! k-means: Lloyd fixed points against a direct recomputation, monotone cost, determinism.

use explore::kmeans::{Init, KMeans, Point, nearest};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

/// Slow check that labels are nearest centres and centres are weighted means.
fn assert_fixed_point(km: &KMeans, pts: &[Point], w: Option<&[f64]>) {
    let c = km.centres();
    for (i, p) in pts.iter().enumerate() {
        // nearest by brute force, ties to the lower index
        let mut best = 0;
        for j in 1..c.len() {
            let dj = (p.0 - c[j].0).powi(2) + (p.1 - c[j].1).powi(2);
            let db = (p.0 - c[best].0).powi(2) + (p.1 - c[best].1).powi(2);
            if dj < db {
                best = j;
            }
        }
        assert_eq!(
            km.labels()[i] as usize,
            best,
            "point {i} not with its nearest centre"
        );
    }
    for (j, cj) in c.iter().enumerate() {
        let (mut sx, mut sy, mut sw) = (0.0, 0.0, 0.0);
        for (i, p) in pts.iter().enumerate() {
            if km.labels()[i] as usize == j {
                let wi = w.map_or(1.0, |w| w[i]);
                sx += wi * p.0;
                sy += wi * p.1;
                sw += wi;
            }
        }
        if sw > 0.0 {
            assert!((sx / sw - cj.0).abs() < 1e-9 && (sy / sw - cj.1).abs() < 1e-9);
        }
    }
}

#[test]
fn two_blobs_worked_example() {
    let pts: Vec<Point> = vec![
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (1.0, 1.0),
        (10.0, 10.0),
        (11.0, 10.0),
        (10.0, 11.0),
        (11.0, 11.0),
    ];
    for seed in 0..20 {
        let mut km = KMeans::new();
        km.fit(
            &pts,
            None,
            Init::PlusPlus(2),
            &mut Pcg64Mcg::seed_from_u64(seed),
        );
        assert!(km.converged());
        let mut c = km.centres().to_vec();
        c.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(c, vec![(0.5, 0.5), (10.5, 10.5)]);
    }
    // Weights pull the centre; given centres keep their index.
    let mut km = KMeans::new();
    let w = [3.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let init = [(20.0, 20.0), (-5.0, -5.0)];
    km.fit(
        &pts,
        Some(&w),
        Init::Centres(&init),
        &mut Pcg64Mcg::seed_from_u64(0),
    );
    assert_eq!(km.centres(), &[(10.5, 10.5), (0.25, 0.0)]);
    assert_eq!(nearest(km.centres(), (2.0, 2.0)), 1);
}

#[test]
fn empty_input_and_more_centres_than_points() {
    let mut km = KMeans::new();
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    km.fit(&[], None, Init::PlusPlus(3), &mut rng);
    assert!(km.centres().is_empty() && km.labels().is_empty());
    km.fit(&[(1.0, 1.0)], None, Init::PlusPlus(3), &mut rng);
    assert_eq!(km.centres(), &[(1.0, 1.0)]);
    let init = [(0.0, 0.0), (5.0, 5.0), (9.0, 9.0)];
    km.fit(
        &[(1.0, 1.0), (2.0, 2.0)],
        None,
        Init::Centres(&init),
        &mut rng,
    );
    assert_eq!(km.centres().len(), 3);
    assert_fixed_point(&km, &[(1.0, 1.0), (2.0, 2.0)], None);
}

fn points() -> impl Strategy<Value = Vec<Point>> {
    prop::collection::vec((0..40i32, 0..40i32), 1..120)
        .prop_map(|v| v.into_iter().map(|(x, y)| (x as f64, y as f64)).collect())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn lloyd_fixed_point_and_nonempty(pts in points(), k in 1usize..8, seed in 0u64..1000) {
        let mut km = KMeans::new();
        km.fit(&pts, None, Init::PlusPlus(k), &mut Pcg64Mcg::seed_from_u64(seed));
        prop_assert!(km.converged());
        let distinct = {
            let mut d = pts.clone();
            d.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            d.dedup();
            d.len()
        };
        prop_assert_eq!(km.centres().len(), k.min(pts.len()));
        assert_fixed_point(&km, &pts, None);
        if distinct >= km.centres().len() {
            for j in 0..km.centres().len() {
                prop_assert!(km.labels().iter().any(|&l| l as usize == j), "cluster {} empty", j);
            }
        }
    }

    #[test]
    fn weighted_from_given_centres_never_worse(
        pts in points(),
        init in prop::collection::vec((0.0..40.0f64, 0.0..40.0f64), 1..6),
        wseed in prop::collection::vec(0u8..5, 120),
    ) {
        let w: Vec<f64> = (0..pts.len()).map(|i| f64::from(wseed[i])).collect();
        // Cost of the initial centres with nearest labels.
        let before: f64 = pts.iter().enumerate().map(|(i, p)| {
            let c = init[nearest(&init, *p)];
            w[i] * ((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2))
        }).sum();
        let mut km = KMeans::new();
        km.fit(&pts, Some(&w), Init::Centres(&init), &mut Pcg64Mcg::seed_from_u64(0));
        prop_assert_eq!(km.centres().len(), init.len());
        prop_assert!(km.cost(&pts, Some(&w)) <= before + 1e-6);
        if km.converged() {
            assert_fixed_point(&km, &pts, Some(&w));
        }
    }

    #[test]
    fn deterministic_per_seed(pts in points(), k in 1usize..6, seed in 0u64..1000) {
        let mut a = KMeans::new();
        let mut b = KMeans::new();
        a.fit(&pts, None, Init::PlusPlus(k), &mut Pcg64Mcg::seed_from_u64(seed));
        b.fit(&pts[..1], None, Init::PlusPlus(1), &mut Pcg64Mcg::seed_from_u64(9));
        b.fit(&pts, None, Init::PlusPlus(k), &mut Pcg64Mcg::seed_from_u64(seed));
        prop_assert_eq!(a.centres(), b.centres());
        prop_assert_eq!(a.labels(), b.labels());
    }
}
