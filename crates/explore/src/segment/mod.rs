//! Room segmentation of partial maps (Holz et al. 2010 §2.4, Figure 7).
//!
//! (Being written.)

/// Which critical points split the map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Rule {
    /// Holz's relaxed rule: adjacent to a junction or to a node adjacent to one.
    #[default]
    Holz,
    /// Wurm et al.: adjacent to a junction.
    Wurm,
    /// Thrun: any local minimum of clearance of degree 2.
    Thrun,
}

/// The segmentation kept between decisions.
#[derive(Default)]
pub struct State {}
