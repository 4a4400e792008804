//! Holz et al.'s Seg assigner on a hand-built hospital wing: in a room the robot finishes the
//! room although a corridor frontier is nearer; in the corridor the room-like rule
//! (`cf-rr-seg`) takes the nearest frontier overall while the literal rule (`cf-rr-seg-any`)
//! keeps to the corridor.

mod common;

use common::Fixture;
use explore::assign::AssignerKind;
use explore::assign::segment_first::ROOM_MAX_NEIGHBOURS;
use explore::candidates::{CandidateKind, CandidateSet};
use explore::decision::Goal;
use explore::segment::Rule;
use grid::{Grid, Occ};

const ROOM: usize = 12;
const DEPTH: usize = 30;
const CORRIDOR: usize = 8;
const DOOR: usize = 4;
const N: usize = 3;

fn fill(g: &mut Grid<Occ>, x0: usize, y0: usize, x1: usize, y1: usize, v: Occ) {
    let w = g.width();
    for y in y0..=y1 {
        for x in x0..=x1 {
            g.data_mut()[y * w + x] = v;
        }
    }
}

/// Door column of room `k`.
fn door_x(k: usize) -> usize {
    1 + k * (ROOM + 1) + (ROOM - DOOR) / 2 + k % 2
}

/// A corridor with `N` rooms above and below; the far ends of top rooms 0 (rows 1–3) and 2
/// (rows 1–15) are unknown (frontiers inside those rooms) and bottom room 0 is unknown behind its door (a frontier
/// in the corridor's segment, at the door).
fn wing() -> Grid<Occ> {
    let w = N * (ROOM + 1) + 1;
    let h = 2 * DEPTH + CORRIDOR + 4;
    let mut g = Grid::new(w, h, Occ::Occupied);
    let cy0 = DEPTH + 2;
    fill(&mut g, 1, cy0, w - 2, cy0 + CORRIDOR - 1, Occ::Free);
    let below = cy0 + CORRIDOR + 1;
    for k in 0..N {
        let x0 = 1 + k * (ROOM + 1);
        fill(&mut g, x0, 1, x0 + ROOM - 1, DEPTH, Occ::Free);
        fill(
            &mut g,
            x0,
            below,
            x0 + ROOM - 1,
            below + DEPTH - 1,
            Occ::Free,
        );
        let dx = door_x(k);
        fill(&mut g, dx, DEPTH + 1, dx + DOOR - 1, DEPTH + 1, Occ::Free);
        fill(&mut g, dx, below - 1, dx + DOOR - 1, below - 1, Occ::Free);
    }
    fill(&mut g, 1, 1, ROOM, 3, Occ::Unknown);
    let x2 = 1 + 2 * (ROOM + 1);
    fill(&mut g, x2, 1, x2 + ROOM - 1, 15, Occ::Unknown);
    fill(&mut g, 1, below, ROOM, below + DEPTH - 1, Occ::Unknown);
    g
}

/// The goal `assigner` gives a robot standing at `robot` (all frontier cells as candidates).
fn goal_of(known: &Grid<Occ>, robot: (usize, usize), assigner: AssignerKind) -> Goal {
    let w = known.width();
    let mut f = Fixture::new(known.clone(), vec![(robot.1 * w + robot.0) as u32], 5.0, 1);
    let mut cands = CandidateSet::new(known.len());
    let mut out = vec![None];
    let mut ctx = f.ctx();
    CandidateKind::AllFrontiers.generate(&mut ctx, &mut cands);
    assigner.assign(&mut ctx, &cands, &mut out);
    out[0].expect("a goal")
}

fn decide(known: &Grid<Occ>, robot: (usize, usize), max_neighbours: Option<u32>) -> Goal {
    let seg = AssignerKind::SegmentFirst {
        rule: Rule::Holz,
        max_neighbours,
    };
    goal_of(known, robot, seg)
}

fn nearest(known: &Grid<Occ>, robot: (usize, usize)) -> Goal {
    goal_of(known, robot, AssignerKind::Nearest)
}

fn xy(known: &Grid<Occ>, g: Goal) -> (usize, usize) {
    let w = known.width();
    (g.cell as usize % w, g.cell as usize / w)
}

#[test]
fn in_a_room_the_robot_finishes_the_room_first() {
    let known = wing();
    // just inside top room 0, by its door
    let robot = (door_x(0) + 1, DEPTH);
    let plain = xy(&known, nearest(&known, robot));
    assert!(
        plain.1 > DEPTH,
        "closest frontier should be the door of the unknown room below, got {plain:?}"
    );
    for rule in [Some(ROOM_MAX_NEIGHBOURS), None] {
        let (x, y) = xy(&known, decide(&known, robot, rule));
        assert!(
            y == 4 && (1..=ROOM).contains(&x),
            "{rule:?}: expected the frontier at the room's far end, got ({x},{y})"
        );
    }
}

#[test]
fn in_a_corridor_only_the_literal_rule_keeps_to_the_corridor() {
    let known = wing();
    // in the corridor, under the door of top room 2
    let robot = (door_x(2) + 1, DEPTH + 3);
    let plain = nearest(&known, robot);
    let room_like = decide(&known, robot, Some(ROOM_MAX_NEIGHBOURS));
    assert_eq!(
        room_like.cell, plain.cell,
        "corridors are not rooms: nearest overall"
    );
    let (x, y) = xy(&known, plain);
    assert!(
        y == 16 && x > 2 * (ROOM + 1),
        "nearest is in top room 2, got ({x},{y})"
    );
    let (x, y) = xy(&known, decide(&known, robot, None));
    assert!(
        y == DEPTH + 2 + CORRIDOR && (door_x(0)..door_x(0) + DOOR).contains(&x),
        "literal rule: the corridor's own frontier at bottom door 0, got ({x},{y})"
    );
}
