//! What every sensor shares: the pose it senses from, the observation it fills, and the
//! [`Sensor`] trait.

use crate::unseen::Unseen;
use grid::{Cell, Grid, Occ};

/// Where a sensor senses from: a cell (the sensor sits at its centre) and a heading.
///
/// The heading is in radians in *grid* coordinates: heading θ looks along
/// `(cos θ, sin θ)` with `x` to the right and `y` **down**, so θ = 0 looks right
/// (+x) and θ = π/2 looks down (+y, the next image row). Omnidirectional sensors
/// ignore it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Pose {
    /// The cell the sensor sits in (at its centre).
    pub cell: Cell,
    /// Heading in radians, grid coordinates (y down).
    pub heading: f64,
}

impl Pose {
    /// A pose at `cell` looking along `heading` (radians, y down).
    pub const fn new(cell: Cell, heading: f64) -> Self {
        Self { cell, heading }
    }
}

/// What one scan saw: flat indices of the seen cells with their observed state.
///
/// Every state is `Free` or `Occupied` (never `Unknown`), and no index appears twice.
/// Reuse one `Observation` across scans: [`Sensor::scan`] clears it and keeps its
/// allocation.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Observation {
    /// The cell the scan was taken from.
    pub origin: Cell,
    /// `(flat index, observed state)` of every seen cell, without duplicates.
    pub cells: Vec<(u32, Occ)>,
}

impl Observation {
    /// An empty observation.
    pub fn new() -> Self {
        Self::default()
    }

    /// Forget every seen cell, keeping the allocation.
    pub fn clear(&mut self) {
        self.cells.clear();
    }

    /// Number of seen cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether no cell was seen.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }
}

/// A range sensor reading a ground-truth grid.
///
/// Ground-truth `Unknown` cells (outside the world) are opaque and reported as
/// `Occupied` when seen; cells outside the grid are opaque and never reported.
pub trait Sensor: Send + Sync {
    /// Clears `out`, then fills it with what is seen from `pose` in `truth`.
    fn scan(&self, truth: &Grid<Occ>, pose: Pose, out: &mut Observation);
    /// Like [`scan`](Self::scan), but cells that tell the robot scanning nothing
    /// ([`Unseen::tells`]: it sensed them before, or two robots did) may be left out; a
    /// belief whose classes do not change once known gains nothing from them. The default
    /// scans everything.
    fn scan_unseen(&self, truth: &Grid<Occ>, pose: Pose, unseen: &Unseen, out: &mut Observation) {
        let _ = unseen;
        self.scan(truth, pose, out);
    }
    /// Whether [`scan_unseen`](Self::scan_unseen) leaves anything out (so that keeping an
    /// [`Unseen`] for it is worth its upkeep).
    fn skips_known(&self) -> bool {
        false
    }
    /// The sensor's range in cells.
    fn range_cells(&self) -> f64;
    /// The field of view in degrees, centred on the heading (360 for sensors that see all
    /// around, the default).
    fn field_of_view_deg(&self) -> f64 {
        360.0
    }
    /// Whether the sensor sees all around (360°), so that its heading does not matter.
    fn is_omnidirectional(&self) -> bool {
        self.field_of_view_deg() >= 360.0
    }

    /// Clears `out`, then fills it with the flat indices of the cells a scan from `pose`
    /// would observe on the *belief* `known`: a predicted scan, for information gain.
    ///
    /// Rays pass through Free and Unknown cells (an unknown cell would be observed and is
    /// assumed not to block) and stop at known Occupied cells, which are included; cells
    /// outside the grid are opaque and never reported. Indices may repeat (overlapping
    /// beams): callers deduplicate. The default scans a copy of `known` with Unknown made
    /// Free, which allocates; the built-in sensors walk the belief directly.
    fn predict(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        let transparent = known.map(|&s| if s == Occ::Unknown { Occ::Free } else { s });
        let mut obs = Observation::new();
        self.scan(&transparent, pose, &mut obs);
        out.clear();
        out.extend(obs.cells.iter().map(|&(i, _)| i));
    }

    /// Like [`predict`](Self::predict), but only the cells that are Unknown in `known`
    /// (indices may repeat): all a ternary belief's information gain needs. The default
    /// filters `predict`; the built-in sensors skip the others as they walk.
    fn predict_unknown(&self, known: &Grid<Occ>, pose: Pose, out: &mut Vec<u32>) {
        self.predict(known, pose, out);
        let data = known.data();
        out.retain(|&i| data.get(i as usize) == Some(&Occ::Unknown));
    }

    /// Like [`predict`](Self::predict) (or [`predict_unknown`](Self::predict_unknown) when
    /// `unknown_only`), but an Unknown cell lets a ray through only where `passable(index)`
    /// says so; otherwise the ray ends there (after reporting it), as at an obstacle. The
    /// lidar honours the gate; the default ignores it.
    fn predict_gated(
        &self,
        known: &Grid<Occ>,
        pose: Pose,
        unknown_only: bool,
        passable: &dyn Fn(usize) -> bool,
        out: &mut Vec<u32>,
    ) {
        let _ = passable;
        if unknown_only {
            self.predict_unknown(known, pose, out);
        } else {
            self.predict(known, pose, out);
        }
    }
}

/// Whether a belief cell lets a predicted ray through: everything but known Occupied.
#[inline]
pub(crate) fn predicted_transparent(s: Occ) -> bool {
    s != Occ::Occupied
}

/// The observed state of a ground-truth state: Free stays Free, anything else is opaque
/// and seen as Occupied.
#[inline]
pub(crate) fn observed(truth: Occ) -> Occ {
    if truth == Occ::Free {
        Occ::Free
    } else {
        Occ::Occupied
    }
}

/// Whether a squared distance in cells² is within range `r` (cells).
///
/// The one comparison every circular sensor and the oracle use, so that they agree
/// exactly for fractional `r`.
#[inline]
pub(crate) fn within_range(d2: i64, r: f64) -> bool {
    (d2 as f64) <= r * r
}
