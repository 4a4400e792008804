//! Information gain against brute force: the predicted scan of every sensor equals its
//! oracle on a copy of the belief where Unknown is transparent (`los_visible` cell by cell
//! for `los`, every cell in range for `footprint`, a real scan for `lidar`), and `I(p)`
//! equals the count of Unknown cells (known grid) or the sum of independently computed
//! expected entropy drops (evidence grid) over that set.

use std::collections::BTreeSet;

use grid::{Cell, Grid, Occ};
use proptest::prelude::*;
use sense::{
    Belief, EvidenceGrid, FootprintSensor, GainScratch, InverseModel, KnownGrid, LidarSensor,
    LosSensor, Observation, Pose, Sensor, information_gain, los_visible,
};

/// A belief grid: each cell Free, Occupied or Unknown.
fn belief_grid() -> impl Strategy<Value = Grid<Occ>> {
    (3usize..14, 3usize..14).prop_flat_map(|(w, h)| {
        prop::collection::vec(
            prop_oneof![3 => Just(Occ::Free), 1 => Just(Occ::Occupied), 2 => Just(Occ::Unknown)],
            w * h,
        )
        .prop_map(move |v| Grid::from_vec(w, h, v).expect("sized"))
    })
}

/// The known grid holding exactly `g`'s classes.
fn known_grid(g: &Grid<Occ>) -> KnownGrid {
    let mut b = KnownGrid::new(g.width(), g.height());
    let obs = Observation {
        origin: Cell::new(0, 0),
        cells: g
            .data()
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.is_unknown())
            .map(|(i, &s)| (i as u32, s))
            .collect(),
    };
    b.integrate(&obs, &mut Vec::new());
    assert_eq!(b.known(), g);
    b
}

/// `g` with Unknown made Free: what a predicted ray sees through.
fn transparent(g: &Grid<Occ>) -> Grid<Occ> {
    g.map(|&s| if s == Occ::Unknown { Occ::Free } else { s })
}

/// A non-Occupied cell of `g` picked by `k`, if any.
fn origin(g: &Grid<Occ>, k: usize) -> Option<Cell> {
    let open: Vec<usize> = (0..g.len()).filter(|&i| g[i] != Occ::Occupied).collect();
    (!open.is_empty()).then(|| g.cell(open[k % open.len()]))
}

fn predicted_set(s: &dyn Sensor, g: &Grid<Occ>, pose: Pose) -> BTreeSet<u32> {
    let mut out = Vec::new();
    s.predict(g, pose, &mut out);
    out.into_iter().collect()
}

/// A sensor's Unknown-only prediction lists exactly its prediction's Unknown cells.
fn unknown_only_matches(s: &dyn Sensor, g: &Grid<Occ>, pose: Pose) -> Result<(), TestCaseError> {
    let mut only = Vec::new();
    s.predict_unknown(g, pose, &mut only);
    let only: BTreeSet<u32> = only.into_iter().collect();
    let want: BTreeSet<u32> = predicted_set(s, g, pose)
        .into_iter()
        .filter(|&i| g[i as usize] == Occ::Unknown)
        .collect();
    prop_assert_eq!(only, want);
    Ok(())
}

/// Binary entropy in bits, written out independently of the crate.
fn h(p: f64) -> f64 {
    if p <= 0.0 || p >= 1.0 {
        0.0
    } else {
        -(p * p.ln() + (1.0 - p) * (1.0 - p).ln()) / std::f64::consts::LN_2
    }
}

/// Expected entropy drop of one observation by log-odds: l' = l + logit(q).
fn drop_by_log_odds(p: f64, p_hit: f64, p_miss: f64) -> f64 {
    if p <= 0.0 || p >= 1.0 {
        return 0.0;
    }
    let logit = |x: f64| (x / (1.0 - x)).ln();
    let sigma = |l: f64| 1.0 / (1.0 + (-l).exp());
    let l = logit(p);
    h(p) - (p * h(sigma(l + logit(p_hit))) + (1.0 - p) * h(sigma(l + logit(p_miss))))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn los_prediction_and_gain_match_brute_force(g in belief_grid(), k in 0usize..200, r in 0.0f64..7.0) {
        let Some(o) = origin(&g, k) else { return Ok(()); };
        let s = LosSensor::new(r).expect("range");
        let t = transparent(&g);
        let want: BTreeSet<u32> = g.cells()
            .filter(|&c| los_visible(&t, o, c, r))
            .map(|c| g.index(c) as u32)
            .collect();
        let pose = Pose::new(o, 0.0);
        prop_assert_eq!(&predicted_set(&s, &g, pose), &want);
        let b = known_grid(&g);
        let unknown = want.iter().filter(|&&i| g[i as usize] == Occ::Unknown).count();
        let mut scratch = GainScratch::new();
        let gain = information_gain(&s, &b, &InverseModel::IDEAL, pose, &mut scratch);
        prop_assert_eq!(gain, unknown as f64);
        // The scratch reports each touched uncertain (Unknown) cell once.
        let touched: BTreeSet<u32> = scratch.touched().iter().copied().collect();
        prop_assert_eq!(touched.len(), scratch.touched().len());
        let want_unknown: BTreeSet<u32> =
            want.iter().copied().filter(|&i| g[i as usize] == Occ::Unknown).collect();
        prop_assert_eq!(touched, want_unknown);
        unknown_only_matches(&s, &g, pose)?;
    }

    #[test]
    fn lidar_prediction_is_a_scan_through_unknown(
        g in belief_grid(), k in 0usize..200, r in 0.5f64..9.0,
        fov in prop_oneof![Just(90.0), Just(180.0), Just(360.0)],
        heading in -4.0f64..4.0,
    ) {
        let Some(o) = origin(&g, k) else { return Ok(()); };
        let s = LidarSensor::new(r, fov, 7.0).expect("lidar");
        let pose = Pose::new(o, heading);
        let mut obs = Observation::new();
        s.scan(&transparent(&g), pose, &mut obs);
        let want: BTreeSet<u32> = obs.cells.iter().map(|c| c.0).collect();
        prop_assert_eq!(&predicted_set(&s, &g, pose), &want);
        let unknown = want.iter().filter(|&&i| g[i as usize] == Occ::Unknown).count();
        let gain = information_gain(&s, &known_grid(&g), &InverseModel::IDEAL, pose, &mut GainScratch::new());
        prop_assert_eq!(gain, unknown as f64);
        unknown_only_matches(&s, &g, pose)?;
    }

    #[test]
    fn footprint_prediction_is_the_disc(g in belief_grid(), k in 0usize..200, r in 0.0f64..6.0) {
        let Some(o) = origin(&g, k) else { return Ok(()); };
        let s = FootprintSensor::new(r).expect("range");
        let want: BTreeSet<u32> = g.cells()
            .filter(|&c| (o.dist2(c) as f64) <= r * r)
            .map(|c| g.index(c) as u32)
            .collect();
        prop_assert_eq!(predicted_set(&s, &g, Pose::new(o, 0.0)), want);
        unknown_only_matches(&s, &g, Pose::new(o, 0.0))?;
    }

    #[test]
    fn evidence_gain_is_the_sum_of_expected_drops(
        g in belief_grid(), k in 0usize..200, r in 0.0f64..6.0,
        extra in prop::collection::vec((0usize..196, any::<bool>()), 0..40),
    ) {
        let Some(o) = origin(&g, k) else { return Ok(()); };
        // An evidence grid with the classes of `g` plus repeated random observations, so
        // that probabilities vary and some cells flip.
        let mut b = EvidenceGrid::new(g.width(), g.height());
        let mut obs = Observation::new();
        obs.cells = g.data().iter().enumerate()
            .filter(|(_, s)| !s.is_unknown()).map(|(i, &s)| (i as u32, s)).collect();
        b.integrate(&obs, &mut Vec::new());
        for (i, hit) in extra {
            if i < g.len() {
                obs.cells = vec![(i as u32, if hit { Occ::Occupied } else { Occ::Free })];
                b.integrate(&obs, &mut Vec::new());
            }
        }
        let s = LosSensor::new(r).expect("range");
        let t = transparent(b.known());
        let pose = Pose::new(o, 0.0);
        let want: f64 = g.cells()
            .filter(|&c| los_visible(&t, o, c, r))
            .map(|c| drop_by_log_odds(b.p_occupied(g.index(c)), 0.7, 0.4))
            .sum();
        let gain = information_gain(&s, &b, &InverseModel::EVIDENCE, pose, &mut GainScratch::new());
        prop_assert!((gain - want).abs() < 1e-9, "gain {} want {}", gain, want);
        // The ideal model's gain is the entropy of the touched cells.
        let want_ideal: f64 = g.cells()
            .filter(|&c| los_visible(&t, o, c, r))
            .map(|c| h(b.p_occupied(g.index(c))))
            .sum();
        let ideal = information_gain(&s, &b, &InverseModel::IDEAL, pose, &mut GainScratch::new());
        prop_assert!((ideal - want_ideal).abs() < 1e-9);
    }
}

/// `rows` as a grid: '.' Free, '#' Occupied, '?' Unknown.
fn map(rows: &[&str]) -> Grid<Occ> {
    let data = rows
        .iter()
        .flat_map(|r| r.chars())
        .map(|c| match c {
            '.' => Occ::Free,
            '#' => Occ::Occupied,
            _ => Occ::Unknown,
        })
        .collect();
    Grid::from_vec(rows[0].len(), rows.len(), data).expect("rectangular")
}

#[test]
fn facing_a_large_unknown_room_beats_facing_a_wall() {
    // A known corridor (rows 0-4) above an unknown room; a known wall to the left.
    let mut rows = vec![
        "##############################",
        "#............................#",
        "#............................#",
        "#............................#",
        "#............................#",
    ];
    rows.extend(std::iter::repeat_n("??????????????????????????????", 14));
    let g = map(&rows);
    let b = known_grid(&g);
    let s = LidarSensor::new(10.0, 180.0, 1.0).expect("lidar");
    let at = Cell::new(3, 3);
    let mut scratch = GainScratch::new();
    let down = information_gain(
        &s,
        &b,
        &InverseModel::IDEAL,
        Pose::new(at, std::f64::consts::FRAC_PI_2),
        &mut scratch,
    );
    let left = information_gain(
        &s,
        &b,
        &InverseModel::IDEAL,
        Pose::new(at, std::f64::consts::PI),
        &mut scratch,
    );
    let up = information_gain(
        &s,
        &b,
        &InverseModel::IDEAL,
        Pose::new(at, -std::f64::consts::FRAC_PI_2),
        &mut scratch,
    );
    // Facing the top wall: the corridor around is all known.
    assert_eq!(up, 0.0);
    assert!(down > 50.0, "the room below: {down}");
    // Facing the left wall, only the edge beams (±90°) reach into the room.
    assert!(down > left && left > up, "down {down} left {left}");
}

#[test]
fn a_known_wall_hides_the_unknown_behind_it() {
    let g = map(&["..#??", ".....", "?????"]);
    let b = known_grid(&g);
    let s = LosSensor::new(1.5).expect("range");
    // From (1, 0): sees (0..=2, 0..=1) but not (3, 0), which is two cells away anyway;
    // unknown cells within 1.5: none on row 0 past the wall; row 2 is 2 away.
    let gain = information_gain(
        &s,
        &b,
        &InverseModel::IDEAL,
        Pose::new(Cell::new(1, 0), 0.0),
        &mut GainScratch::new(),
    );
    assert_eq!(gain, 0.0);
    // From (3, 1): (3, 0), (4, 0), (2..=4, 2) are unknown within 1.5 → 5 bits.
    let gain = information_gain(
        &s,
        &b,
        &InverseModel::IDEAL,
        Pose::new(Cell::new(3, 1), 0.0),
        &mut GainScratch::new(),
    );
    assert_eq!(gain, 5.0);
}

#[test]
fn evidence_model_matches_the_evidence_grid_update() {
    // One hit on a prior cell gives the model's p_hit, one miss its p_miss.
    let mut b = EvidenceGrid::new(2, 1);
    let obs = Observation {
        origin: Cell::new(0, 0),
        cells: vec![(0, Occ::Occupied), (1, Occ::Free)],
    };
    b.integrate(&obs, &mut Vec::new());
    assert!((b.p_occupied(0) - InverseModel::EVIDENCE.p_hit).abs() < 1e-12);
    assert!((b.p_occupied(1) - InverseModel::EVIDENCE.p_miss).abs() < 1e-12);
}
