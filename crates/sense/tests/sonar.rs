//! The sonar ring: echoes from walls head-on, lost echoes at grazing angles, tables the laser
//! misses, laser-limited sonar and the cone-shaped inverse model in the evidence grid.

use grid::{Cell, Grid, Occ};
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use sense::sonar::TRANSDUCERS;
use sense::{
    Belief, EvidenceGrid, KnownGrid, LidarSensor, Observation, Pose, Sensor, SonarParams,
    SonarReading, SonarSensor,
};

/// An exact (noise-free) sonar of range 30 cells with the default cone and threshold.
fn exact_sonar() -> SonarSensor {
    SonarSensor::new(SonarParams {
        range: 30.0,
        noise_sd: 0.0,
        ..SonarParams::yamauchi(0.1)
    })
    .expect("valid sonar")
}

/// A free `w × h` grid.
fn open(w: usize, h: usize) -> Grid<Occ> {
    Grid::new(w, h, Occ::Free)
}

fn fire(
    sonar: &SonarSensor,
    plane: &Grid<Occ>,
    clutter: Option<&Grid<bool>>,
    pose: Pose,
) -> Vec<SonarReading> {
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    let mut out = Vec::new();
    sonar.fire(plane, clutter, pose, &mut rng, &mut out);
    assert_eq!(out.len(), TRANSDUCERS);
    out
}

/// A vertical wall at column 20 of a 40 × 30 grid.
fn wall_at_x20() -> Grid<Occ> {
    let mut g = open(40, 30);
    for y in 0..30 {
        g.set(Cell::new(20, y), Occ::Occupied);
    }
    g
}

/// A horizontal wall at row 20 of a 70 × 30 grid.
fn wall_at_y20() -> Grid<Occ> {
    let mut g = open(70, 30);
    for x in 0..70 {
        g.set(Cell::new(x, 20), Occ::Occupied);
    }
    g
}

#[test]
fn a_wall_head_on_is_heard_at_its_distance() {
    let plane = wall_at_x20();
    let r = fire(
        &exact_sonar(),
        &plane,
        None,
        Pose::new(Cell::new(10, 15), 0.0),
    );
    assert!(r[0].echo, "{:?}", r[0]);
    assert!((r[0].range - 9.5).abs() < 1e-9, "{:?}", r[0]);
    // The transducer looking away hears nothing within its range.
    assert!(!r[8].echo);
    assert_eq!(r[8].range, 30.0);
}

#[test]
fn a_wall_at_a_grazing_angle_is_not_heard() {
    let plane = wall_at_y20();
    // Axis 10° below the wall's direction: every ray of the 25° cone meets the wall at
    // 67.5°–92.5° from its normal, beyond the 20° threshold.
    let heading = 10f64.to_radians();
    let r = fire(
        &exact_sonar(),
        &plane,
        None,
        Pose::new(Cell::new(5, 15), heading),
    );
    assert!(!r[0].echo, "{:?}", r[0]);
    assert_eq!(r[0].range, 30.0);
    // The transducer facing the wall (10° off its normal) hears it at 4.5 cells.
    assert!(r[4].echo, "{:?}", r[4]);
    assert!((r[4].range - 4.5).abs() < 0.05, "{:?}", r[4]);
    // With a higher threshold the same wall is heard.
    let lenient = SonarSensor::new(SonarParams {
        incidence_deg: 89.0,
        ..*exact_sonar().params()
    })
    .expect("valid");
    let r = fire(&lenient, &plane, None, Pose::new(Cell::new(5, 15), heading));
    assert!(r[0].echo && r[0].range < 30.0, "{:?}", r[0]);
}

#[test]
fn a_lost_echo_returns_from_a_farther_surface() {
    let mut plane = wall_at_y20();
    for y in 0..30 {
        plane.set(Cell::new(25, y), Occ::Occupied);
    }
    let r = fire(
        &exact_sonar(),
        &plane,
        None,
        Pose::new(Cell::new(5, 15), 10f64.to_radians()),
    );
    assert!(r[0].echo, "{:?}", r[0]);
    // The wall at column 25 (surface at 19.5 cells along x), struck within the cone.
    assert!(r[0].range > 19.0 && r[0].range < 20.0, "{:?}", r[0]);
}

#[test]
fn a_table_is_invisible_to_the_laser_and_heard_by_sonar() {
    let plane = open(40, 30);
    let mut clutter = Grid::new(40, 30, false);
    for y in 14..=16 {
        for x in 18..=20 {
            clutter.set(Cell::new(x, y), true);
        }
    }
    let pose = Pose::new(Cell::new(10, 15), 0.0);
    let table = plane.index(Cell::new(18, 15));

    let laser = LidarSensor::new(30.0, 360.0, 1.0).expect("valid lidar");
    let mut obs = Observation::new();
    laser.scan(&plane, pose, &mut obs);
    let mut laser_map = KnownGrid::new(40, 30);
    laser_map.integrate(&obs, &mut Vec::new());
    assert_eq!(laser_map.known()[table], Occ::Free);

    let mut sonar = exact_sonar();
    let r = fire(&sonar, &plane, Some(&clutter), pose);
    assert!(r[0].echo && (r[0].range - 7.5).abs() < 1e-9, "{:?}", r[0]);
    let mut belief = EvidenceGrid::new(40, 30);
    let mut changed = Vec::new();
    sonar.integrate(pose.cell, &r, &[], &mut belief, &mut changed);
    assert_eq!(belief.known()[table], Occ::Occupied);
    assert_eq!(belief.known()[plane.index(Cell::new(14, 15))], Occ::Free);

    // Laser-limited sonar keeps the sonar's shorter echo from the table.
    let mut limited = r.clone();
    let mut hits = Vec::new();
    sonar.limit_by_laser(&plane, pose.cell, &mut limited, &mut hits);
    assert_eq!(limited[0], r[0]);
}

#[test]
fn the_cone_model_marks_free_space_then_the_wall() {
    let plane = wall_at_x20();
    let mut sonar = exact_sonar();
    let pose = Pose::new(Cell::new(10, 15), 0.0);
    let r = fire(&sonar, &plane, None, pose);
    let mut belief = EvidenceGrid::new(40, 30);
    let mut changed = Vec::new();
    sonar.integrate(pose.cell, &r, &[], &mut belief, &mut changed);
    let k = |x, y| belief.known()[plane.index(Cell::new(x, y))];
    assert_eq!(k(10, 15), Occ::Free);
    assert_eq!(k(15, 15), Occ::Free);
    assert_eq!(k(20, 15), Occ::Occupied);
    assert_eq!(k(23, 15), Occ::Unknown, "beyond the echo nothing is learnt");
    // Off-axis cells get less evidence than on-axis cells at the same distance.
    let on = belief.log_odds(plane.index(Cell::new(15, 15)));
    let off = belief.log_odds(plane.index(Cell::new(15, 16)));
    assert!(on < off && off < 0.0, "on {on}, off {off}");
    // Every changed cell is reported once and is now classified.
    let mut sorted = changed.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), changed.len());
    assert!(
        changed
            .iter()
            .all(|&i| !belief.known()[i as usize].is_unknown())
    );
}

#[test]
fn specular_max_range_paints_phantom_space_that_the_laser_limits() {
    let plane = wall_at_y20();
    let mut sonar = exact_sonar();
    let pose = Pose::new(Cell::new(5, 15), 10f64.to_radians());
    let behind_wall = plane.index(Cell::new(30, 21)); // on the axis, just past the wall
    let r = fire(&sonar, &plane, None, pose);

    let mut sonar_only = EvidenceGrid::new(70, 30);
    sonar.integrate(pose.cell, &r, &[], &mut sonar_only, &mut Vec::new());
    assert_eq!(
        sonar_only.known()[behind_wall],
        Occ::Free,
        "phantom open space"
    );

    let mut limited = r.clone();
    let mut hits = Vec::new();
    sonar.limit_by_laser(&plane, pose.cell, &mut limited, &mut hits);
    assert!(
        limited[0].echo && limited[0].range < 30.0,
        "{:?}",
        limited[0]
    );
    assert!(
        hits.iter()
            .any(|&i| plane.cell(i as usize).y == 20 && plane[i as usize] == Occ::Occupied)
    );
    let mut with_laser = EvidenceGrid::new(70, 30);
    sonar.integrate(pose.cell, &limited, &hits, &mut with_laser, &mut Vec::new());
    assert_ne!(with_laser.known()[behind_wall], Occ::Free);
    for &i in &hits {
        assert_eq!(with_laser.known()[i as usize], Occ::Occupied);
    }
}

#[test]
fn range_noise_is_seeded() {
    let plane = wall_at_x20();
    let sonar = SonarSensor::new(SonarParams {
        range: 30.0,
        noise_sd: 0.5,
        ..SonarParams::yamauchi(0.1)
    })
    .expect("valid");
    let pose = Pose::new(Cell::new(10, 15), 0.0);
    let draw = |seed| {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let mut out = Vec::new();
        sonar.fire(&plane, None, pose, &mut rng, &mut out);
        out
    };
    assert_eq!(draw(7), draw(7));
    assert_ne!(draw(7)[0].range, draw(8)[0].range);
    // Mean over many draws is close to the true distance.
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let mut out = Vec::new();
    let n = 400;
    let mut sum = 0.0;
    for _ in 0..n {
        sonar.fire(&plane, None, pose, &mut rng, &mut out);
        sum += out[0].range;
    }
    assert!(
        (sum / f64::from(n) - 9.5).abs() < 0.15,
        "mean {}",
        sum / 400.0
    );
}
