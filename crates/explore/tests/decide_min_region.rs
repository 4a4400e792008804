//! The loop's shared decision step ([`explore::decision::decide`]) on a worked example:
//! explore_lite's minimum frontier size keeps a robot from a nearer but smaller region.

mod common;

use common::Fixture;
use explore::assign::AssignerKind;
use explore::candidates::CandidateKind;
use explore::decision::{Offer, decide};
use grid::io::parse_ascii;

// A small unknown pocket in the top-left corner (3 frontier cells: (2,1), (1,2), (2,2)) and
// an unknown band on the right (7 frontier cells at x = 10); the robot stands near the
// pocket. Cells are 0.2 m (the fixture's resolution).
const MAP: &str = "\
############
#?.........?
#..........?
#..........?
#..........?
#..........?
#..........?
#..........?
############
";

fn fixture() -> Fixture {
    let known = parse_ascii(MAP, 0.2).unwrap().cells;
    let robot = known.index(grid::Cell::new(2, 4)) as u32;
    Fixture::new(known, vec![robot], 5.0, 7)
}

#[test]
fn regions_below_the_minimum_are_not_offered() {
    let mut fx = fixture();
    let w = fx.known.width() as u32;
    let mut offer = Offer::new(fx.known.len());
    let mut out = [None];
    // No minimum: the pocket is nearest.
    decide(
        &mut fx.ctx(),
        CandidateKind::AllFrontiers,
        Some(AssignerKind::Nearest),
        0.0,
        &mut offer,
        &mut out,
    );
    assert_eq!(out[0].unwrap().cell, 2 * w + 2);
    assert_eq!((offer.candidates.len(), offer.too_small), (10, 0));
    // 0.8 m = 4 cells: the 3-cell pocket is left out, the band is the goal.
    decide(
        &mut fx.ctx(),
        CandidateKind::AllFrontiers,
        Some(AssignerKind::Nearest),
        0.8,
        &mut offer,
        &mut out,
    );
    let goal = out[0].unwrap().cell;
    assert_eq!(goal % w, 10, "goal {goal} is on the band");
    assert_eq!(
        goal,
        4 * w + 10,
        "the band cell on the robot's row is nearest"
    );
    // The generator's candidates are all kept for the caller; 3 cells were too small.
    assert_eq!((offer.candidates.len(), offer.too_small), (10, 3));
    // Without an assigner, only the candidates are generated.
    out[0] = None;
    decide(
        &mut fx.ctx(),
        CandidateKind::AllFrontiers,
        None,
        0.8,
        &mut offer,
        &mut out,
    );
    assert_eq!((out[0], offer.candidates.len()), (None, 10));
}

#[test]
fn the_minimum_raises_the_centroid_generators_own() {
    let mut fx = fixture();
    let mut offer = Offer::new(fx.known.len());
    let mut out = [None];
    let centroids = CandidateKind::RegionCentroids { min_size_m: 0.2 };
    decide(
        &mut fx.ctx(),
        centroids,
        Some(AssignerKind::Nearest),
        0.0,
        &mut offer,
        &mut out,
    );
    assert_eq!(offer.candidates.len(), 2, "one centroid per region");
    decide(
        &mut fx.ctx(),
        centroids,
        Some(AssignerKind::Nearest),
        0.8,
        &mut offer,
        &mut out,
    );
    assert_eq!(offer.candidates.len(), 1, "only the band's centroid");
    assert_eq!(out[0].unwrap().cell % fx.known.width() as u32, 10);
    assert_eq!(
        offer.too_small, 0,
        "counted for all-frontier candidates only"
    );
}
