//! Belief maps: `changed` lists exactly the cells whose class changed, and each model
//! classifies as documented (checked against independent oracles).

use grid::{Cell, Occ};
use proptest::prelude::*;
use sense::{Belief, BeliefKind, EvidenceGrid, KnownGrid, Observation, ReflectionMap};

const W: usize = 6;
const H: usize = 5;

/// A sequence of observations over a W×H map, each without duplicate indices.
fn arb_observations() -> impl Strategy<Value = Vec<Observation>> {
    proptest::collection::vec(
        proptest::collection::btree_map(0u32..(W * H) as u32, any::<bool>(), 0..20),
        1..12,
    )
    .prop_map(|steps| {
        steps
            .into_iter()
            .map(|m| Observation {
                origin: Cell::new(0, 0),
                cells: m
                    .into_iter()
                    .map(|(i, occ)| (i, if occ { Occ::Occupied } else { Occ::Free }))
                    .collect(),
            })
            .collect()
    })
}

fn check_changed(mut b: Box<dyn Belief>, steps: &[Observation]) -> Result<(), TestCaseError> {
    for obs in steps {
        let before = b.known().clone();
        let mut changed = vec![u32::MAX]; // `integrate` appends, never clears
        b.integrate(obs, &mut changed);
        prop_assert_eq!(changed[0], u32::MAX);
        let mut got = changed[1..].to_vec();
        got.sort_unstable();
        let want: Vec<u32> = (0..before.len())
            .filter(|&i| before[i] != b.known()[i])
            .map(|i| i as u32)
            .collect();
        prop_assert_eq!(got, want);
        prop_assert_eq!(changed.len() - 1, changed[1..].len());
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn changed_lists_exactly_the_changed_cells(steps in arb_observations()) {
        for kind in [BeliefKind::Known, BeliefKind::Reflection, BeliefKind::Evidence] {
            check_changed(kind.build(W, H), &steps)?;
        }
    }

    #[test]
    fn reflection_classes_follow_the_counts_at_any_threshold(steps in arb_observations()) {
        for p_free in [0.0, 0.1, 0.25, 0.5, 0.9, 1.0] {
            let mut refl = ReflectionMap::with_p_free(W, H, p_free).expect("a probability");
            let mut changed = Vec::new();
            for obs in &steps {
                refl.integrate(obs, &mut changed);
            }
            for i in 0..W * H {
                let (h, m) = (f64::from(refl.hits(i)), f64::from(refl.misses(i)));
                let want = if h + m == 0.0 {
                    Occ::Unknown
                } else if h / (h + m) <= p_free {
                    Occ::Free
                } else {
                    Occ::Occupied
                };
                prop_assert_eq!(refl.known()[i], want, "p_free {} cell {}", p_free, i);
            }
        }
    }

    #[test]
    fn models_match_their_oracles(steps in arb_observations()) {
        let mut known = KnownGrid::new(W, H);
        let mut refl = ReflectionMap::new(W, H);
        let mut evid = EvidenceGrid::new(W, H);
        let mut last = [Occ::Unknown; W * H];
        let mut hits = [0u32; W * H];
        let mut misses = [0u32; W * H];
        // Evidence oracle in probability space: Bayes' rule with clamping at [0.01, 0.99].
        let mut p = vec![0.5f64; W * H];
        let mut changed = Vec::new();
        for obs in &steps {
            known.integrate(obs, &mut changed);
            refl.integrate(obs, &mut changed);
            evid.integrate(obs, &mut changed);
            for &(i, o) in &obs.cells {
                let i = i as usize;
                last[i] = o;
                let a = if o == Occ::Occupied { hits[i] += 1; 0.7 } else { misses[i] += 1; 0.4 };
                let q = p[i] * a / (p[i] * a + (1.0 - p[i]) * (1.0 - a));
                p[i] = q.clamp(0.01, 0.99);
            }
        }
        for i in 0..W * H {
            prop_assert_eq!(known.known()[i], last[i]);
            let want = match (hits[i], misses[i]) {
                (0, 0) => Occ::Unknown,
                (h, m) if 4 * h <= h + m => Occ::Free,
                _ => Occ::Occupied,
            };
            prop_assert_eq!(refl.known()[i], want, "cell {} hits {} misses {}", i, hits[i], misses[i]);
            prop_assert_eq!((refl.hits(i), refl.misses(i)), (hits[i], misses[i]));
            // Evidence: compare away from the prior, where rounding cannot flip the class.
            prop_assert!((evid.p_occupied(i) - p[i]).abs() < 1e-9);
            if (p[i] - 0.5).abs() > 1e-6 {
                let want = if p[i] < 0.5 { Occ::Free } else { Occ::Occupied };
                prop_assert_eq!(evid.known()[i], want);
            }
        }
    }
}

fn obs(cells: &[(u32, Occ)]) -> Observation {
    Observation {
        origin: Cell::new(0, 0),
        cells: cells.to_vec(),
    }
}

#[test]
fn reflection_map_thresholds() {
    let mut m = ReflectionMap::new(2, 1);
    let mut changed = Vec::new();
    assert_eq!(m.p_occupied(0), 0.5);
    m.integrate(&obs(&[(0, Occ::Occupied)]), &mut changed);
    assert_eq!((m.known()[0], m.p_occupied(0)), (Occ::Occupied, 1.0));
    // 1 hit, 2 misses: p = 1/3 > 0.25 → still Occupied.
    m.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    m.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    assert_eq!(m.known()[0], Occ::Occupied);
    assert_eq!(changed, vec![0]);
    // 1 hit, 3 misses: p = 0.25 ≤ p_free → Free.
    m.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    assert_eq!((m.known()[0], m.p_occupied(0)), (Occ::Free, 0.25));
    assert_eq!(changed, vec![0, 0]);
    // Never seen stays Unknown; a miss alone is Free.
    assert_eq!(m.known()[1], Occ::Unknown);
    m.integrate(&obs(&[(1, Occ::Free)]), &mut changed);
    assert_eq!(m.known()[1], Occ::Free);
    // Custom threshold.
    let mut strict = ReflectionMap::with_p_free(1, 1, 0.1).expect("valid");
    for _ in 0..5 {
        strict.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    }
    strict.integrate(&obs(&[(0, Occ::Occupied)]), &mut changed); // p = 1/6 > 0.1
    assert_eq!(strict.known()[0], Occ::Occupied);
    assert!(ReflectionMap::with_p_free(1, 1, 1.5).is_err());
}

#[test]
fn evidence_grid_classification() {
    let mut g = EvidenceGrid::new(3, 1);
    let mut changed = Vec::new();
    // Occupied once: p = 0.7.
    g.integrate(&obs(&[(0, Occ::Occupied), (1, Occ::Free)]), &mut changed);
    assert!((g.p_occupied(0) - 0.7).abs() < 1e-12);
    assert!((g.p_occupied(1) - 0.4).abs() < 1e-12);
    assert_eq!(g.known().data(), &[Occ::Occupied, Occ::Free, Occ::Unknown]);
    assert_eq!(g.p_occupied(2), 0.5);
    // 1 hit + 2 misses: log-odds 0.847 − 0.811 = 0.036 > 0 → still Occupied;
    // + 3 misses: −0.369 → Free.
    g.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    g.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    assert_eq!(g.known()[0], Occ::Occupied);
    g.integrate(&obs(&[(0, Occ::Free)]), &mut changed);
    assert_eq!(g.known()[0], Occ::Free);
    // Clamping: many hits saturate at 0.99 and a few misses bring the cell back.
    for _ in 0..100 {
        g.integrate(&obs(&[(2, Occ::Occupied)]), &mut changed);
    }
    assert!((g.p_occupied(2) - 0.99).abs() < 1e-12);
    for _ in 0..12 {
        g.integrate(&obs(&[(2, Occ::Free)]), &mut changed);
    }
    assert_eq!(g.known()[2], Occ::Free);
    assert_eq!(EvidenceGrid::classify(0.0), Occ::Unknown);
    assert!(EvidenceGrid::with_model(1, 1, 0.4, 0.3).is_err());
    assert!(EvidenceGrid::with_model(1, 1, 0.9, 0.2).is_ok());
}

#[test]
fn out_of_range_and_unknown_entries_are_ignored() {
    for kind in [
        BeliefKind::Known,
        BeliefKind::Reflection,
        BeliefKind::Evidence,
    ] {
        let mut b = kind.build(2, 2);
        let mut changed = Vec::new();
        b.integrate(&obs(&[(9, Occ::Free), (1, Occ::Unknown)]), &mut changed);
        assert!(changed.is_empty(), "{kind}");
        assert!(b.known().data().iter().all(|c| c.is_unknown()));
    }
}

proptest! {
    /// Pinned cells keep their pinned class whatever is observed after, in every model;
    /// the other cells behave as without pins, and `changed` still lists exactly the cells
    /// whose class changed.
    #[test]
    fn pinned_cells_never_change(steps in arb_observations(), pins in proptest::collection::btree_map(0u32..(W * H) as u32, any::<bool>(), 0..6)) {
        for kind in [BeliefKind::Known, BeliefKind::Reflection, BeliefKind::Evidence] {
            let mut pinned = kind.build(W, H);
            let mut free = kind.build(W, H);
            for (&i, &occ) in &pins {
                let class = if occ { Occ::Occupied } else { Occ::Free };
                let before = pinned.known()[i as usize];
                let mut changed = Vec::new();
                pinned.pin(i as usize, class, &mut changed);
                prop_assert_eq!(changed.len(), usize::from(before != class));
                prop_assert!(pinned.is_pinned(i as usize));
            }
            for o in &steps {
                let before = pinned.known().clone();
                let mut changed = Vec::new();
                pinned.integrate(o, &mut changed);
                free.integrate(o, &mut Vec::new());
                let mut want: Vec<u32> = (0..(W * H) as u32)
                    .filter(|&i| before[i as usize] != pinned.known()[i as usize])
                    .collect();
                changed.sort_unstable();
                want.sort_unstable();
                prop_assert_eq!(changed, want);
                for i in 0..W * H {
                    match pins.get(&(i as u32)) {
                        Some(&occ) => prop_assert_eq!(
                            pinned.known()[i],
                            if occ { Occ::Occupied } else { Occ::Free }
                        ),
                        None => prop_assert_eq!(pinned.known()[i], free.known()[i]),
                    }
                }
            }
        }
    }
}
