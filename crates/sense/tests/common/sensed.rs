//! Random cases of who sensed what, for the tests of scans that leave out what a robot
//! already knows (`Sensor::scan_unseen`, `SightCache::scan_unseen`).
#![allow(dead_code)] // each test file uses what it needs

use grid::{Grid, Occ};
use proptest::prelude::*;
use sense::Unseen;

/// Who sensed a cell before the scan: nobody, one robot, or two.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sensed {
    None,
    One(usize),
    Two(usize, usize),
}

/// A random ground truth of up to `side` × `side` cells (some of it Unknown, the outside of
/// a plan), the number of robots and, per cell, who of them has sensed it.
pub fn arb_case(side: usize) -> impl Strategy<Value = (Grid<Occ>, usize, Vec<Sensed>)> {
    (
        1usize..=side,
        1usize..=side,
        0u32..=60,
        1usize..=3,
        0u32..=100,
    )
        .prop_flat_map(|(w, h, density, robots, known)| {
            proptest::collection::vec((0u32..100, 0u32..100, 0usize..3, 0usize..3), w * h).prop_map(
                move |rolls| {
                    let truth: Vec<Occ> = rolls
                        .iter()
                        .map(|&(roll, ..)| match roll {
                            r if r < density && r % 4 == 0 => Occ::Unknown,
                            r if r < density => Occ::Occupied,
                            _ => Occ::Free,
                        })
                        .collect();
                    let sensed = rolls
                        .iter()
                        .map(|&(_, k, a, b)| {
                            let (a, b) = (a % robots, b % robots);
                            match k {
                                k if k >= known => Sensed::None,
                                k if k % 3 == 0 && a != b => Sensed::Two(a, b),
                                _ => Sensed::One(a),
                            }
                        })
                        .collect();
                    (
                        Grid::from_vec(w, h, truth).expect("w*h cells"),
                        robots,
                        sensed,
                    )
                },
            )
        })
}

/// The record of `robots` robots of `truth` (blocks of 2^`shift` cells) after they sensed
/// what `sensed` says.
pub fn unseen_of(truth: &Grid<Occ>, robots: usize, sensed: &[Sensed], shift: u32) -> Unseen {
    let mut unseen = Unseen::new(truth, robots, shift);
    for (i, &s) in sensed.iter().enumerate() {
        match s {
            Sensed::None => {}
            Sensed::One(a) => {
                unseen.record(a, [i as u32]);
            }
            Sensed::Two(a, b) => {
                unseen.record(a, [i as u32]);
                unseen.record(b, [i as u32]);
            }
        }
    }
    unseen
}
