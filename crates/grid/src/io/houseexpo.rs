//! HouseExpo floor plans (Li et al. 2019, "HouseExpo: a large-scale 2D indoor layout
//! dataset"): a JSON object whose `verts` is the house's outline, one polygon in metres,
//! and whose `room_category` maps a room type to the bounding boxes `[x0, y0, x1, y1]` (in
//! metres) of its rooms. Its simulator fills the outline as free space and leaves the rest
//! an obstacle; so does this reader, at a chosen resolution: a cell is free when its centre
//! lies inside the outline (even–odd rule), and a ring of one obstacle cell surrounds the
//! outline's bounding box. Each room's box gives its cells a room id (1, 2, … in the order
//! of the file; 0 outside every room), for scoring a segmentation.

use std::path::Path;

use serde::de::{Deserialize, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde_json::Value;

use super::error::{MapError, MapErrorKind};
use super::{SizeCheck, check_size};
use crate::grid::Grid;
use crate::occ::{GridMap, Occ};

/// A HouseExpo floor plan rasterised, with its rooms.
#[derive(Clone, Debug)]
pub struct HouseExpoMap {
    /// The map (origin at the outline's lower-left corner less one cell).
    pub map: GridMap,
    /// Room id of every cell (row-major; 0 = no room).
    pub rooms: Vec<u32>,
    /// Room type of room id `k` at index `k − 1`.
    pub room_types: Vec<String>,
}

fn bad(name: &Path, field: &'static str, expected: &str, found: String) -> MapError {
    MapError::new(
        name,
        MapErrorKind::BadField {
            field,
            expected: expected.into(),
            found,
        },
    )
}

/// How far from the origin, in cells, a plan's vertices may lie (2^40): cell centres there
/// are still exact to a ten-thousandth of a cell.
const FAR_CELLS: f64 = 1_099_511_627_776.0;

/// The `[x, y]` pairs (or `[x0, y0, x1, y1]` boxes) of a JSON array, as numbers.
fn numbers(v: &Value, n: usize) -> Option<Vec<f64>> {
    let a = v.as_array()?;
    (a.len() == n)
        .then(|| {
            a.iter()
                .map(|x| x.as_f64().filter(|f| f.is_finite()))
                .collect()
        })
        .flatten()
}

/// The cell centres along one axis: the `i`-th of `n` at `start + (i + 0.5) × step`, which
/// increase with `i` (non-strictly, after rounding) as long as the last one is finite.
#[derive(Clone, Copy)]
struct Centres {
    start: f64,
    step: f64,
    n: usize,
}

impl Centres {
    /// The `i`-th centre.
    fn at(self, i: usize) -> f64 {
        self.start + (i as f64 + 0.5) * self.step
    }

    /// How many centres lie below `t`: the first index whose centre is at or above `t`.
    ///
    /// Guessed from the spacing and confirmed against the centres themselves (rounding can
    /// put a centre on either side of the guess), else found by binary search.
    fn below(self, t: f64) -> usize {
        // The cast saturates: below the first centre (or NaN) is 0.
        let guess = (((t - self.start) / self.step + 0.5) as usize).min(self.n);
        let is_boundary =
            |i: usize| (i == 0 || self.at(i - 1) < t) && (i == self.n || self.at(i) >= t);
        if is_boundary(guess) {
            return guess;
        }
        let (mut lo, mut hi) = (0, self.n);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.at(mid) < t {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        lo
    }
}

/// Mark Free the cells of the row-major grid `cells` whose centre is inside the polygon
/// `poly` (even–odd rule): `xs` are the columns' centres and `ys` the rows', the bottom
/// row (the grid's last) first.
///
/// A row's crossings come from the edges spanning its height only (an active-edge list,
/// edges sorted by their lower end), and each pair of crossings fills its span of cells:
/// the work is the rows times their crossings plus the cells filled, so that an outline of
/// many vertices in a small file costs what its crossings do, not rows × edges × columns.
fn fill_outline(poly: &[(f64, f64)], xs: Centres, ys: Centres, cells: &mut [Occ]) {
    let (w, h) = (xs.n, ys.n);
    // Edge k runs from poly[k] to poly[k + 1] and crosses heights in [lo, hi); horizontal
    // edges cross none.
    let mut edges: Vec<(f64, f64, usize)> = (0..poly.len())
        .filter_map(|k| {
            let (a, b) = (poly[k].1, poly[(k + 1) % poly.len()].1);
            (a != b).then(|| (a.min(b), a.max(b), k))
        })
        .collect();
    edges.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut next = 0;
    // (crossing x, edge) of the edges spanning the row, kept in the order of the previous
    // row's crossings, which is nearly this row's.
    let mut active: Vec<(f64, usize)> = Vec::new();
    for r in 0..h {
        let y = ys.at(r);
        while next < edges.len() && edges[next].0 <= y {
            active.push((0.0, next));
            next += 1;
        }
        active.retain(|&(_, e)| y < edges[e].1);
        for (cross, e) in &mut active {
            let k = edges[*e].2;
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            *cross = a.0 + (y - a.1) / (b.1 - a.1) * (b.0 - a.0);
        }
        active.sort_by(|p, q| p.0.total_cmp(&q.0));
        let row = &mut cells[(h - 1 - r) * w..(h - r) * w];
        for pair in active.chunks_exact(2) {
            let first = xs.below(pair[0].0);
            // Most pairs of a detailed outline hold no centre: no need to find the end.
            if first < w && xs.at(first) < pair[1].0 {
                row[first..xs.below(pair[1].0)].fill(Occ::Free);
            }
        }
    }
}

/// The most room boxes a plan may have. HouseExpo's houses have tens; each box costs a step
/// per row it spans, so a small file of many boxes over a large map would take hours.
pub const MAX_ROOM_BOXES: usize = 65_536;

/// The free cells no room box has labelled yet, as "the next unlabelled free cell at or
/// after `i`" pointers with path halving, so that boxes overlapping cells already labelled
/// (the first box in the file wins) skip them instead of visiting them again: labelling
/// costs the cells labelled plus a step per row of each box, not the boxes' areas.
struct Unlabelled {
    /// `next[i] == i` for an unlabelled free cell, else a cell index further on (`next[n]
    /// == n` is the end).
    next: Vec<u32>,
}

impl Unlabelled {
    /// Every free cell of `cells` unlabelled (the map has at most [`MAX_CELLS`] cells, so
    /// indices fit in 32 bits).
    ///
    /// [`MAX_CELLS`]: super::MAX_CELLS
    fn new(cells: &[Occ]) -> Self {
        let mut next: Vec<u32> = (0..cells.len())
            .map(|i| if cells[i] == Occ::Free { i } else { i + 1 } as u32)
            .collect();
        next.push(cells.len() as u32);
        Self { next }
    }

    /// The first unlabelled free cell at or after `i` (or the end).
    fn find(&mut self, mut i: usize) -> usize {
        while self.next[i] as usize != i {
            let up = self.next[i] as usize;
            self.next[i] = self.next[up];
            i = up;
        }
        i
    }

    /// Label (call `label` on, then mark labelled) every unlabelled free cell in `span`.
    fn take(&mut self, span: std::ops::Range<usize>, mut label: impl FnMut(usize)) {
        let mut i = self.find(span.start);
        while i < span.end {
            label(i);
            self.next[i] = (i + 1) as u32;
            i = self.find(i + 1);
        }
    }
}

/// Read a HouseExpo JSON text (`name` is the file named in errors) at `resolution` metres
/// per cell.
pub fn parse_houseexpo(text: &str, name: &Path, resolution: f64) -> Result<HouseExpoMap, MapError> {
    parse_houseexpo_checked(text, name, resolution, &check_size)
}

/// Bytes a cell of the rasterised plan takes while it is made: the grid, its room label
/// (`u32`) and the list of cells not yet in a room (`u32`).
pub(crate) const BYTES_PER_CELL: u64 = 1 + 4 + 4;

/// Read a HouseExpo plan once `fits(width, height, name)` accepts the size of the grid its
/// outline makes at `resolution`.
pub(crate) fn parse_houseexpo_checked(
    text: &str,
    name: &Path,
    resolution: f64,
    fits: &SizeCheck,
) -> Result<HouseExpoMap, MapError> {
    super::check_resolution(resolution, name)?;
    // serde reads a struct from an array too, by position: a plan is an object.
    if let Some(c) = text.trim_start().chars().next().filter(|&c| c != '{') {
        return Err(bad(
            name,
            "json",
            "a HouseExpo JSON object",
            format!("a value starting with {c:?}"),
        ));
    }
    let plan: Plan = serde_json::from_str(text)
        .map_err(|e| bad(name, "json", "a HouseExpo JSON object", e.to_string()))?;
    let verts = plan
        .verts
        .as_ref()
        .and_then(Value::as_array)
        .ok_or_else(|| MapError::new(name, MapErrorKind::MissingField("verts")))?;
    let mut poly: Vec<(f64, f64)> = Vec::with_capacity(verts.len());
    for (k, v) in verts.iter().enumerate() {
        let Some(p) = numbers(v, 2) else {
            let mut shown = v.to_string();
            if shown.len() > 60 {
                shown = format!("{}…", shown.chars().take(57).collect::<String>());
            }
            return Err(bad(
                name,
                "verts",
                "[x, y] pairs of finite metres",
                format!("{shown} at vertex {k}"),
            ));
        };
        poly.push((p[0], p[1]));
    }
    if poly.len() < 3 {
        return Err(bad(
            name,
            "verts",
            "an outline of at least 3 points",
            format!("{} points", poly.len()),
        ));
    }
    let (x_min, x_max) = poly
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (y_min, y_max) = poly
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    // Cell centres are offsets from the outline's corner: far from the origin they are no
    // longer distinct numbers (a square offset by 1e17 m lost 44 % of its cells), and the
    // outline's size would overflow the cell count.
    let far = [x_min, x_max, y_min, y_max]
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    if far / resolution > FAR_CELLS {
        return Err(bad(
            name,
            "verts",
            &format!(
                "vertices within {FAR_CELLS:e} cells of the origin ({} m at {resolution} m a \
                 cell), where cell centres stay exact",
                FAR_CELLS * resolution
            ),
            format!("a vertex {far:e} m away"),
        ));
    }
    // One obstacle cell around the outline's box.
    let w = ((x_max - x_min) / resolution).ceil() + 2.0;
    let h = ((y_max - y_min) / resolution).ceil() + 2.0;
    fits(w as u64, h as u64, name)?;
    let (w, h) = (w as usize, h as usize);
    let (x0, y0) = (x_min - resolution, y_min - resolution);
    // Row 0 is the top of the map: y grows downwards in cells, upwards in metres, so the
    // rows' centres go from the bottom row (h − 1) up.
    let xs = Centres {
        start: x0,
        step: resolution,
        n: w,
    };
    let ys = Centres {
        start: y0,
        step: resolution,
        n: h,
    };
    // The spans are found from the centres' order: finite end centres give it (each centre
    // is a correctly rounded, hence monotone, function of its index), and finite coordinates
    // at a resolution of at most a kilometre have them.
    if ![xs.at(0), xs.at(w - 1), ys.at(0), ys.at(h - 1)]
        .iter()
        .all(|v| v.is_finite())
    {
        return Err(bad(
            name,
            "verts",
            "coordinates whose cell centres are finite numbers at this resolution",
            format!("an outline from ({x_min}, {y_min}) to ({x_max}, {y_max})"),
        ));
    }
    let mut cells = Grid::new(w, h, Occ::Occupied);
    fill_outline(&poly, xs, ys, cells.data_mut());
    let mut rooms = vec![0u32; w * h];
    let mut room_types = Vec::new();
    if let Some(Categories(Some(cats))) = plan.room_category {
        let count: usize = cats
            .iter()
            .filter_map(|(_, v)| v.as_array())
            .map(Vec::len)
            .sum();
        if count > MAX_ROOM_BOXES {
            return Err(bad(
                name,
                "room_category",
                &format!("at most {MAX_ROOM_BOXES} room boxes"),
                format!("{count} boxes"),
            ));
        }
        let mut unlabelled = Unlabelled::new(cells.data());
        for (kind, boxes) in &cats {
            let boxes = boxes.as_array().ok_or_else(|| {
                bad(
                    name,
                    "room_category",
                    "lists of [x0, y0, x1, y1] boxes",
                    format!("{kind}: {boxes}"),
                )
            })?;
            for b in boxes {
                let b = numbers(b, 4).ok_or_else(|| {
                    bad(
                        name,
                        "room_category",
                        "[x0, y0, x1, y1] boxes in metres",
                        format!("{kind}: {b}"),
                    )
                })?;
                room_types.push(kind.clone());
                let id = room_types.len() as u32;
                // The cells whose centre is in [b0, b2) × [b1, b3), free and in no room yet:
                // each of the box's rows jumps over the cells already labelled.
                let columns = xs.below(b[0])..xs.below(b[2]);
                if columns.is_empty() {
                    continue;
                }
                for r in ys.below(b[1])..ys.below(b[3]) {
                    let row = (h - 1 - r) * w;
                    unlabelled.take(row + columns.start..row + columns.end, |i| rooms[i] = id);
                }
            }
        }
    }
    let mut map = GridMap::new(cells, resolution);
    map.origin = [x0, y0, 0.0];
    Ok(HouseExpoMap {
        map,
        rooms,
        room_types,
    })
}

/// The parts of a plan this reader uses; other fields are skipped unread.
#[derive(serde::Deserialize)]
#[serde(expecting = "a HouseExpo JSON object")]
struct Plan {
    /// The outline, checked point by point where it is used.
    verts: Option<Value>,
    /// The room boxes by room type.
    room_category: Option<Categories>,
}

/// `room_category`'s entries in the order of the file (a `Value`'s map would sort them), or
/// `None` when it is not an object: such a field is ignored, as the plan's other fields are.
struct Categories(Option<Vec<(String, Value)>>);

impl<'de> Deserialize<'de> for Categories {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// Collects an object's entries as they come and skips any other value.
        struct Entries;
        impl<'de> Visitor<'de> for Entries {
            type Value = Categories;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("any JSON value")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut a: A) -> Result<Categories, A::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = a.next_entry::<String, Value>()? {
                    entries.push(entry);
                }
                Ok(Categories(Some(entries)))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut a: A) -> Result<Categories, A::Error> {
                while a.next_element::<IgnoredAny>()?.is_some() {}
                Ok(Categories(None))
            }
            fn visit_bool<E>(self, _: bool) -> Result<Categories, E> {
                Ok(Categories(None))
            }
            fn visit_i64<E>(self, _: i64) -> Result<Categories, E> {
                Ok(Categories(None))
            }
            fn visit_u64<E>(self, _: u64) -> Result<Categories, E> {
                Ok(Categories(None))
            }
            fn visit_f64<E>(self, _: f64) -> Result<Categories, E> {
                Ok(Categories(None))
            }
            fn visit_str<E>(self, _: &str) -> Result<Categories, E> {
                Ok(Categories(None))
            }
            fn visit_unit<E>(self) -> Result<Categories, E> {
                Ok(Categories(None))
            }
        }
        d.deserialize_any(Entries)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_l_shaped_house_with_two_rooms() {
        // An L: 4 x 2 m along the bottom and 2 x 2 m above its left half, at 0.5 m.
        let text = r#"{"id": "t", "verts": [[0,0],[4,0],[4,2],[2,2],[2,4],[0,4]],
            "room_category": {"kitchen": [[0,0,4,2]], "bedroom": [[0,2,2,4]]},
            "room_num": 2, "bbox": {"min": [0,0], "max": [4,4]}}"#;
        let h = parse_houseexpo(text, Path::new("t.json"), 0.5).expect("reads");
        let g = &h.map.cells;
        assert_eq!((g.width(), g.height()), (10, 10));
        let free = g.data().iter().filter(|&&s| s == Occ::Free).count();
        assert_eq!(free, 8 * 4 + 4 * 4, "12 m² of floor in 0.25 m² cells");
        // The ring and the missing upper-right square are obstacles.
        assert_eq!(g[0], Occ::Occupied);
        assert_eq!(g[g.index(crate::Cell::new(7, 2))], Occ::Occupied);
        assert_eq!(g[g.index(crate::Cell::new(2, 2))], Occ::Free);
        // Room ids in the file's order.
        assert_eq!(
            h.room_types,
            vec!["kitchen".to_string(), "bedroom".to_string()]
        );
        let count = |id| h.rooms.iter().filter(|&&r| r == id).count();
        assert_eq!((count(1), count(2)), (32, 16));
        assert_eq!(h.map.origin, [-0.5, -0.5, 0.0]);
    }

    /// Regression: a 32 x 32 m square offset by 1e17 m rasterised to 2304 free cells at 0.5 m
    /// instead of 4096 (its cell centres were no longer distinct numbers), without a word,
    /// and a vertex at 1e300 m was "18446744073709551615x18446744073709551615 cells".
    #[test]
    fn a_plan_far_from_the_origin_is_refused() {
        for (text, found) in [
            (
                r#"{"verts": [[1e17,1e17],[1.00000000000000032e17,1e17],
                    [1.00000000000000032e17,1.00000000000000032e17],[1e17,1.00000000000000032e17]]}"#,
                "found a vertex 1.0000000000000003e17 m away",
            ),
            (
                r#"{"verts": [[0,0],[1e300,0],[1e300,1e300]]}"#,
                "found a vertex 1e300 m away",
            ),
        ] {
            let e = parse_houseexpo(text, Path::new("t.json"), 0.5)
                .expect_err("refused")
                .to_string();
            assert!(
                e.contains("field 'verts': expected vertices within") && e.contains(found),
                "{e}"
            );
        }
    }

    #[test]
    fn a_room_category_that_is_not_an_object_is_ignored() {
        for cats in [
            "null",
            "3",
            "-1",
            "2.5",
            "true",
            "\"rooms\"",
            "[[0, 0, 1, 1], {}]",
        ] {
            let text =
                format!(r#"{{"verts": [[0,0],[1,0],[1,1],[0,1]], "room_category": {cats}}}"#);
            let h = parse_houseexpo(&text, Path::new("t.json"), 0.5).expect(&text);
            assert!(
                h.room_types.is_empty() && h.rooms.iter().all(|&r| r == 0),
                "{text}"
            );
        }
    }

    #[test]
    fn errors_name_the_file_and_the_field() {
        let p = Path::new("maps/h.json");
        for (text, want) in [
            ("{", "json"),
            ("{}", "verts"),
            ("[[[0,0],[1,0],[0,1]]]", "expected a HouseExpo JSON object"),
            ("3", "expected a HouseExpo JSON object"),
            (r#"{"verts": 3}"#, "verts"),
            (r#"{"verts": [[0,0],[1]]}"#, "verts"),
            (r#"{"verts": [[0,0],[1,0]]}"#, "3 points"),
            (
                r#"{"verts": [[0,0],[1,0],[0,1]], "room_category": {"a": [[0,0,1]]}}"#,
                "room_category",
            ),
        ] {
            let msg = parse_houseexpo(text, p, 0.1).expect_err(text).to_string();
            assert!(
                msg.contains("maps/h.json") && msg.contains(want),
                "{text}: {msg}"
            );
        }
    }
}
