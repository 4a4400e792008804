//! HouseExpo rasterising: the same cells and rooms as the obvious scan of every cell (kept
//! here as the oracle), at a cost that follows the outline's crossings and the rooms' cells.

use std::path::Path;

use grid::io::{MAX_CELLS, parse_houseexpo};
use grid::{Grid, Occ};
use proptest::prelude::*;
use serde_json::Value;

/// What a plan rasterises to: size, cells, room ids, room types and origin.
type Raster = (usize, usize, Vec<Occ>, Vec<u32>, Vec<String>, [f64; 3]);

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

/// The oracle: the rasteriser as first written, testing every edge and every cell for each
/// row and every cell for each room box (quadratic, but plainly right); `None` where the
/// plan is refused.
fn oracle(text: &str, resolution: f64) -> Option<Raster> {
    let json: Value = serde_json::from_str(text).ok()?;
    let verts = json.get("verts").and_then(Value::as_array)?;
    let poly: Vec<(f64, f64)> = verts
        .iter()
        .map(|v| numbers(v, 2).map(|p| (p[0], p[1])))
        .collect::<Option<_>>()?;
    if poly.len() < 3 {
        return None;
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
    let w = ((x_max - x_min) / resolution).ceil() + 2.0;
    let h = ((y_max - y_min) / resolution).ceil() + 2.0;
    let (w, h) = (w as u64, h as u64);
    if w == 0 || h == 0 || w.checked_mul(h)? > MAX_CELLS {
        return None;
    }
    let (w, h) = (w as usize, h as usize);
    let (x0, y0) = (x_min - resolution, y_min - resolution);
    let centre = |cx: usize, cy: usize| {
        (
            x0 + (cx as f64 + 0.5) * resolution,
            y0 + ((h - 1 - cy) as f64 + 0.5) * resolution,
        )
    };
    let mut cells = Grid::new(w, h, Occ::Occupied);
    let mut crossings: Vec<f64> = Vec::new();
    for cy in 0..h {
        let (_, y) = centre(0, cy);
        crossings.clear();
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if (a.1 <= y) != (b.1 <= y) {
                crossings.push(a.0 + (y - a.1) / (b.1 - a.1) * (b.0 - a.0));
            }
        }
        crossings.sort_by(f64::total_cmp);
        for pair in crossings.chunks_exact(2) {
            for cx in 0..w {
                let (x, _) = centre(cx, cy);
                if x >= pair[0] && x < pair[1] {
                    cells.data_mut()[cy * w + cx] = Occ::Free;
                }
            }
        }
    }
    let mut rooms = vec![0u32; w * h];
    let mut room_types = Vec::new();
    if let Some(cats) = json.get("room_category").and_then(Value::as_object) {
        // In the file's order: by where each category's quoted name first appears.
        let mut cats: Vec<_> = cats.iter().collect();
        cats.sort_by_key(|(kind, _)| text.find(&format!("\"{kind}\"")));
        for (kind, boxes) in cats {
            for b in boxes.as_array()? {
                let b = numbers(b, 4)?;
                room_types.push(kind.clone());
                let id = room_types.len() as u32;
                for cy in 0..h {
                    for cx in 0..w {
                        let (x, y) = centre(cx, cy);
                        let i = cy * w + cx;
                        if rooms[i] == 0
                            && cells.data()[i] == Occ::Free
                            && (b[0]..b[2]).contains(&x)
                            && (b[1]..b[3]).contains(&y)
                        {
                            rooms[i] = id;
                        }
                    }
                }
            }
        }
    }
    Some((
        w,
        h,
        cells.data().to_vec(),
        rooms,
        room_types,
        [x0, y0, 0.0],
    ))
}

/// The plan as this crate rasterises it; `None` where it is refused.
fn rasterise(text: &str, resolution: f64) -> Option<Raster> {
    let plan = parse_houseexpo(text, Path::new("plan.json"), resolution).ok()?;
    let cells = &plan.map.cells;
    Some((
        cells.width(),
        cells.height(),
        cells.data().to_vec(),
        plan.rooms,
        plan.room_types,
        plan.map.origin,
    ))
}

/// A HouseExpo JSON text of the outline `verts` and the room boxes of each type.
fn plan_text(verts: &[(f64, f64)], rooms: &[(&str, Vec<[f64; 4]>)]) -> String {
    let verts: Vec<String> = verts
        .iter()
        .map(|(x, y)| format!("[{x:?}, {y:?}]"))
        .collect();
    let rooms: Vec<String> = rooms
        .iter()
        .map(|(kind, boxes)| {
            let boxes: Vec<String> = boxes
                .iter()
                .map(|b| format!("[{:?}, {:?}, {:?}, {:?}]", b[0], b[1], b[2], b[3]))
                .collect();
            format!("{kind:?}: [{}]", boxes.join(", "))
        })
        .collect();
    format!(
        r#"{{"id": "t", "verts": [{}], "room_category": {{{}}}}}"#,
        verts.join(", "),
        rooms.join(", ")
    )
}

/// A coordinate in metres: often on a multiple of 1/8 m, so that vertices and crossings
/// fall exactly on cell centres and edges, sometimes anywhere.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-40i32..=40).prop_map(|k| f64::from(k) * 0.125),
        1 => -5.0f64..5.0,
    ]
}

/// A room box, corners in either order.
fn room_box() -> impl Strategy<Value = [f64; 4]> {
    (coordinate(), coordinate(), coordinate(), coordinate()).prop_map(|(a, b, c, d)| [a, b, c, d])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Random outlines (self-crossing, with repeated vertices and horizontal edges) and room
    /// boxes rasterise to exactly the oracle's cells, rooms and origin.
    #[test]
    fn rasterising_matches_the_scan_of_every_cell(
        verts in proptest::collection::vec((coordinate(), coordinate()), 3..16),
        kitchens in proptest::collection::vec(room_box(), 0..4),
        bedrooms in proptest::collection::vec(room_box(), 0..4),
        resolution in prop_oneof![
            Just(0.125), Just(0.25), Just(0.5), Just(1.0), Just(0.1), 0.05f64..1.5
        ],
    ) {
        let text = plan_text(&verts, &[("kitchen", kitchens), ("bedroom", bedrooms)]);
        let want = oracle(&text, resolution);
        let got = rasterise(&text, resolution);
        prop_assert!(want.is_some() && got.is_some(), "{text}");
        let (want, got) = (want.unwrap(), got.unwrap());
        prop_assert_eq!((want.0, want.1), (got.0, got.1), "{}", text);
        prop_assert!(want.2 == got.2, "cells differ: {text} at {resolution}");
        prop_assert!(want.3 == got.3, "rooms differ: {text} at {resolution}");
        prop_assert_eq!(&want.4, &got.4);
        prop_assert_eq!(want.5.map(f64::to_bits), got.5.map(f64::to_bits));
    }
}

/// Regression: room ids followed the categories' alphabetical order (serde_json's map
/// sorts its keys), not the file's, so where boxes overlap the later category won.
#[test]
fn regression_houseexpo_rooms_numbered_in_file_order() {
    let square = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)];
    let text = plan_text(
        &square,
        &[
            ("zeta", vec![[0.0, 0.0, 4.0, 2.0]]),
            ("alpha", vec![[0.0, 0.0, 4.0, 4.0]]),
        ],
    );
    let plan = parse_houseexpo(&text, Path::new("h.json"), 0.5).expect("reads");
    assert_eq!(
        plan.room_types,
        vec!["zeta".to_string(), "alpha".to_string()]
    );
    let count = |id| plan.rooms.iter().filter(|&&r| r == id).count();
    // zeta's box comes first and keeps the half they share; alpha gets the rest.
    assert_eq!((count(1), count(2)), (32, 32));
}

/// Regression: a 227 KB outline, a 20,001-vertex zigzag whose every row crosses 20,000
/// edges, rasterised at 0.1 m to 1002×1002 cells did not finish in 20 s (every crossing pair
/// scanned the whole row). Each pair now fills its own span.
#[test]
fn regression_houseexpo_zigzag_outline_rasterises() {
    let mut verts: Vec<(f64, f64)> = (0..20_000)
        .map(|i| (f64::from(i) * 0.005, if i % 2 == 0 { 0.0 } else { 100.0 }))
        .collect();
    verts.push((100.0, 100.0));
    let text = plan_text(&verts, &[]);
    assert!(text.len() > 200_000, "{} bytes", text.len());
    let plan = parse_houseexpo(&text, Path::new("zigzag.json"), 0.1).expect("rasterises");
    let cells = &plan.map.cells;
    assert_eq!((cells.width(), cells.height()), (1002, 1002));
    let free = cells.data().iter().filter(|&&c| c == Occ::Free).count();
    assert!(free > 0 && free < 1000 * 1000, "{free} free cells");
}

/// Regression: a plan of 20,000 room boxes did not finish (every cell of the map was tested
/// against every box). Each box now visits the cells inside it only.
#[test]
fn regression_houseexpo_many_room_boxes_rasterise() {
    let square = [(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (0.0, 100.0)];
    // 200 × 100 boxes of 0.5 m × 1 m tiling the square.
    let boxes: Vec<[f64; 4]> = (0..200)
        .flat_map(|i| {
            (0..100).map(move |j| {
                let (x, y) = (f64::from(i) * 0.5, f64::from(j));
                [x, y, x + 0.5, y + 1.0]
            })
        })
        .collect();
    let text = plan_text(&square, &[("room", boxes)]);
    let plan = parse_houseexpo(&text, Path::new("rooms.json"), 0.1).expect("rasterises");
    assert_eq!(plan.room_types.len(), 20_000);
    let cells = plan.map.cells.data();
    let free = cells.iter().filter(|&&c| c == Occ::Free).count();
    assert_eq!(free, 1000 * 1000);
    let roomless = (0..cells.len())
        .filter(|&i| cells[i] == Occ::Free && plan.rooms[i] == 0)
        .count();
    assert_eq!(roomless, 0, "the boxes tile the square");
}

/// Regression: a 400 KB plan of 20,000 room boxes, each over the whole 1000 m square, ran
/// for over a minute at 0.5 m (every box visited every one of its 4 million cells, though
/// the first box had labelled them all). Boxes now jump over cells already labelled.
#[test]
fn regression_houseexpo_overlapping_room_boxes_rasterise() {
    let square = [(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (0.0, 100.0)];
    let boxes = vec![[0.0, 0.0, 100.0, 100.0]; 20_000];
    let mut rooms = vec![("hall", vec![[0.0, 0.0, 50.0, 100.0]])];
    rooms.push(("room", boxes));
    let text = plan_text(&square, &rooms);
    let start = std::time::Instant::now();
    let plan = parse_houseexpo(&text, Path::new("rooms.json"), 0.1).expect("rasterises");
    assert!(start.elapsed().as_secs() < 20, "took {:?}", start.elapsed());
    assert_eq!(plan.room_types.len(), 20_001);
    let count = |id| plan.rooms.iter().filter(|&&r| r == id).count();
    // The hall (first in the file) keeps its half; the first full box takes the rest.
    assert_eq!((count(1), count(2), count(3)), (500 * 1000, 500 * 1000, 0));
}

/// Regression: more room boxes than any house has are refused, naming the count, before
/// any is rasterised.
#[test]
fn regression_houseexpo_too_many_room_boxes_are_refused() {
    let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let n = grid::io::houseexpo::MAX_ROOM_BOXES + 1;
    let text = plan_text(&square, &[("room", vec![[0.0, 0.0, 1.0, 1.0]; n])]);
    let msg = parse_houseexpo(&text, Path::new("rooms.json"), 0.1)
        .expect_err("refused")
        .to_string();
    assert!(
        msg.contains("rooms.json") && msg.contains("room_category") && msg.contains("65537"),
        "{msg}"
    );
}

/// Regression: the room boxes were read and then dropped by every loader, so `frontier
/// segment --map house.json` scored nothing though the docs promise it. `load_houseexpo`
/// keeps them, grown with the map by `--border`.
#[test]
fn regression_load_houseexpo_keeps_the_rooms_with_the_border() {
    let dir = std::env::temp_dir().join(format!("grid-houseexpo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("two.json");
    std::fs::write(
        &path,
        r#"{"verts": [[0,0],[4,0],[4,2],[0,2]], "room_category": {"a": [[0,0,2,2]], "b": [[2,0,4,2]]}}"#,
    )
    .unwrap();
    let opts = |border| grid::io::LoadOptions {
        resolution: Some((0.5, 0.5)),
        border,
        memory: None,
    };
    let plain = grid::io::load_houseexpo(&path, &opts(false)).unwrap();
    let bordered = grid::io::load_houseexpo(&path, &opts(true)).unwrap();
    assert_eq!(plain.room_types, ["a", "b"]);
    let (w, h) = (plain.map.width(), plain.map.height());
    assert_eq!(
        (bordered.map.width(), bordered.map.height()),
        (w + 2, h + 2)
    );
    assert_eq!(bordered.rooms.len(), (w + 2) * (h + 2));
    for y in 0..h + 2 {
        for x in 0..w + 2 {
            let inner = (1..=w).contains(&x) && (1..=h).contains(&y);
            let want = if inner {
                plain.rooms[(y - 1) * w + x - 1]
            } else {
                0
            };
            assert_eq!(bordered.rooms[y * (w + 2) + x], want, "({x}, {y})");
        }
    }
    let count = |id| plain.rooms.iter().filter(|&&r| r == id).count();
    assert_eq!((count(1), count(2)), (16, 16));
    // load_map reads the same map.
    assert!(grid::io::load_map(&path, &opts(true)).unwrap().cells == bordered.map.cells);
    std::fs::remove_dir_all(&dir).unwrap();
}
