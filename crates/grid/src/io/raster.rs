//! A decoded greyscale image and ROS map_server's rule turning pixels into cell states.
//!
//! A pixel of value `v` out of `maxval` has occupancy `p = (maxval - v) / maxval` (with
//! `negate`, `p = v / maxval`), computed in that order as ROS 1 map_server does:
//! `p > occupied_thresh` is Occupied, `p < free_thresh` is Free, anything
//! between is Unknown. Colour pixels use the mean of their colour channels (as ROS 1
//! map_server); in a bare bitmap a fully transparent pixel (alpha 0) is Unknown. A ROS
//! YAML's modes read alpha as the map_servers do: in trinary mode both (ROS 1's and nav2's)
//! average it in with the red, green and blue channels ([`Thresholds::classify_trinary`]);
//! in scale mode nav2 makes every pixel that is not fully opaque Unknown
//! ([`Thresholds::classify_scale`]).

use crate::grid::Grid;
use crate::occ::Occ;

/// A decoded greyscale image: each pixel's brightness is `values[i] / maxval`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Raster {
    /// Number of columns.
    pub width: usize,
    /// Number of rows; row 0 is the top of the image.
    pub height: usize,
    /// The value of a white pixel (for colour images, the sum of the channels' maxima).
    pub maxval: u32,
    /// Brightness of each pixel, row-major, in `0..=maxval` (for colour, the channel sum).
    pub values: Vec<u32>,
    /// Each pixel's alpha in `0..=alpha_max` (0 fully transparent); empty if the image has
    /// no alpha.
    pub alpha: Vec<u16>,
    /// The alpha of an opaque pixel (255 or 65535); 0 if the image has no alpha.
    pub alpha_max: u32,
    /// How many colour channels `values` sums: 1 for grey, 3 for colour.
    pub colours: u32,
}

impl Raster {
    /// Whether pixel `i` is fully transparent.
    #[inline]
    pub fn is_transparent(&self, i: usize) -> bool {
        self.alpha.get(i).is_some_and(|&a| a == 0)
    }

    /// Brightness of pixel `i` in `[0, 1]`.
    #[inline]
    pub fn shade(&self, i: usize) -> f64 {
        f64::from(self.values[i]) / f64::from(self.maxval.max(1))
    }
}

/// ROS map_server's thresholds on occupancy probability.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thresholds {
    /// Occupancy above this is Occupied.
    pub occupied: f64,
    /// Occupancy below this is Free.
    pub free: f64,
    /// Whether dark pixels are free and light ones occupied.
    pub negate: bool,
}

impl Default for Thresholds {
    /// ROS's usual values: occupied 0.65, free 0.196, negate off.
    fn default() -> Self {
        Self {
            occupied: 0.65,
            free: 0.196,
            negate: false,
        }
    }
}

impl Thresholds {
    /// The occupancy probability of a pixel of value `value` out of `maxval`, computed as
    /// ROS 1 map_server does: `(maxval − value) / maxval`, or `value / maxval` with `negate`.
    #[inline]
    pub fn occupancy(&self, value: u32, maxval: u32) -> f64 {
        let (v, m) = (f64::from(value), f64::from(maxval.max(1)));
        if self.negate { v / m } else { (m - v) / m }
    }

    /// The state of a pixel of value `value` out of `maxval` (ROS trinary mode): Occupied
    /// if its occupancy is above `occupied`, Free if below `free`, else Unknown.
    #[inline]
    pub fn classify(&self, value: u32, maxval: u32) -> Occ {
        let p = self.occupancy(value, maxval);
        if p > self.occupied {
            Occ::Occupied
        } else if p < self.free {
            Occ::Free
        } else {
            Occ::Unknown
        }
    }

    /// The states of every pixel of `raster` in a ROS YAML's `trinary` mode, as both
    /// map_servers read it: a pixel with alpha is the mean of red, green, blue and alpha
    /// (a grey pixel's grey counted as red, green and blue), so an opaque pixel reads
    /// lighter than its colour and a transparent one darker ("alpha will be averaged in with
    /// color channels when using trinary mode"). Without alpha, as
    /// [`classify_raster`](Self::classify_raster).
    pub fn classify_trinary(&self, raster: &Raster) -> Grid<Occ> {
        if raster.alpha.is_empty() {
            return self.classify_raster(raster);
        }
        // Red, green and blue sum to `values[i] · 3 / colours` of 3 · channel maxima.
        let scale = 3 / raster.colours.clamp(1, 3);
        let maxval = 4 * raster.alpha_max;
        cells_of(raster, |i| {
            let alpha = raster
                .alpha
                .get(i)
                .map_or(raster.alpha_max, |&a| u32::from(a));
            self.classify(raster.values[i] * scale + alpha, maxval)
        })
    }

    /// The states of every pixel of `raster` (bare bitmaps; transparent → Unknown).
    pub fn classify_raster(&self, raster: &Raster) -> Grid<Occ> {
        cells_of(raster, |i| {
            if raster.is_transparent(i) {
                Occ::Unknown
            } else {
                self.classify(raster.values[i], raster.maxval)
            }
        })
    }

    /// The states of every pixel of `raster` in a ROS YAML's `scale` mode, as nav2's
    /// map_server reads it: a pixel that is not fully opaque is Unknown, and an opaque one
    /// is classified by its colour ([`classify`](Self::classify); its scaled occupancies
    /// between the thresholds are Unknown here too).
    pub fn classify_scale(&self, raster: &Raster) -> Grid<Occ> {
        cells_of(raster, |i| match raster.alpha.get(i) {
            Some(&a) if u32::from(a) != raster.alpha_max => Occ::Unknown,
            _ => self.classify(raster.values[i], raster.maxval),
        })
    }

    /// The states of every pixel of `raster` in ROS `raw` mode.
    ///
    /// The pixel value scaled to `0..=255` (`round(255 · v / maxval)`) *is* the occupancy
    /// in percent, as nav2's map_server: values `≥ 100 · occupied` (up to 100) are Occupied,
    /// values `≤ 100 · free` are Free, everything else (between the thresholds, or above
    /// 100 such as 255 = −1) is Unknown. `negate` and alpha are ignored, as in nav2. The
    /// comparisons are made as `v / 100` against the thresholds, so that a value written as
    /// a threshold (55 for 0.55) is on its side, whatever `100 · 0.55` rounds to.
    pub fn classify_raw(&self, raster: &Raster) -> Grid<Occ> {
        cells_of(raster, |i| {
            let v = (raster.shade(i) * 255.0).round();
            if v > 100.0 {
                Occ::Unknown
            } else if v / 100.0 >= self.occupied {
                Occ::Occupied
            } else if v / 100.0 <= self.free {
                Occ::Free
            } else {
                Occ::Unknown
            }
        })
    }
}

/// The grid of `raster`'s size whose cell `i` is `state(i)`. The raster's length is
/// width × height by construction; an inconsistent one built by hand gives an empty grid
/// rather than a panic.
fn cells_of(raster: &Raster, state: impl Fn(usize) -> Occ) -> Grid<Occ> {
    let data = (0..raster.values.len()).map(state).collect();
    Grid::from_vec(raster.width, raster.height, data)
        .unwrap_or_else(|| Grid::new(0, 0, Occ::Unknown))
}
