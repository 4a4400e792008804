//! Map write → read round-trips for every format (property tests on small random maps).

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use grid::io::{
    LoadOptions, Raster, Thresholds, encode_pgm, encode_png, load_map, parse_ascii, parse_bitmap,
    parse_movingai, parse_pgm, parse_png, save_map, to_ascii, to_movingai,
};
use grid::{Grid, GridMap, Occ};
use proptest::prelude::*;

/// A fresh scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "frontier-io-roundtrip-{}-{test}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch folder");
    dir
}

/// A unique file name inside `dir`.
fn file(dir: &std::path::Path, ext: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    dir.join(format!("map{}.{ext}", N.fetch_add(1, Ordering::Relaxed)))
}

fn occ() -> impl Strategy<Value = Occ> {
    prop_oneof![Just(Occ::Free), Just(Occ::Occupied), Just(Occ::Unknown)]
}

fn grid() -> impl Strategy<Value = Grid<Occ>> {
    (1usize..=24, 1usize..=24).prop_flat_map(|(w, h)| {
        proptest::collection::vec(occ(), w * h)
            .prop_map(move |d| Grid::from_vec(w, h, d).expect("size"))
    })
}

fn map() -> impl Strategy<Value = GridMap> {
    let res = prop_oneof![Just(0.05), Just(0.025), Just(1.0), 1e-3f64..10.0];
    let coord = prop_oneof![Just(0.0), -1e4f64..1e4];
    (grid(), res, coord.clone(), coord, -3.2f64..3.2).prop_map(|(cells, resolution, x, y, yaw)| {
        GridMap {
            cells,
            resolution,
            origin: [x, y, yaw],
        }
    })
}

/// A threshold: any in [0, 1], or exactly k/255 so that pixels fall on it.
fn threshold() -> impl Strategy<Value = f64> {
    prop_oneof![
        0.0f64..=1.0,
        (0u32..=255).prop_map(|k| f64::from(k) / 255.0)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn yaml_keeps_everything(m in map()) {
        let dir = scratch("yaml");
        let path = file(&dir, "yaml");
        save_map(&m, &path).expect("save");
        let back = load_map(&path, &LoadOptions::default()).expect("load");
        let _ = std::fs::remove_dir_all(&dir);
        prop_assert_eq!(back, m);
    }

    #[test]
    fn png_and_pgm_keep_cells(m in map(), ext in prop_oneof![Just("png"), Just("pgm")]) {
        let dir = scratch(ext);
        let path = file(&dir, ext);
        save_map(&m, &path).expect("save");
        let back = load_map(&path, &LoadOptions::with_resolution(m.resolution)).expect("load");
        let _ = std::fs::remove_dir_all(&dir);
        prop_assert_eq!(back.cells, m.cells);
        prop_assert_eq!(back.resolution, m.resolution);
    }

    #[test]
    fn ascii_keeps_cells(m in map()) {
        let dir = scratch("txt");
        let path = file(&dir, "txt");
        save_map(&m, &path).expect("save");
        let back = load_map(&path, &LoadOptions::default()).expect("load");
        let _ = std::fs::remove_dir_all(&dir);
        prop_assert_eq!(&back.cells, &m.cells);
        prop_assert_eq!(back.resolution, 1.0);
        // In memory too.
        prop_assert_eq!(parse_ascii(&to_ascii(&m.cells), 0.5).expect("parse").cells, m.cells);
    }

    #[test]
    fn movingai_keeps_cells_unknown_becomes_occupied(m in map()) {
        let dir = scratch("map");
        let path = file(&dir, "map");
        save_map(&m, &path).expect("save");
        let back = load_map(&path, &LoadOptions::with_resolution(m.resolution)).expect("load");
        let _ = std::fs::remove_dir_all(&dir);
        let want = m.cells.map(|&o| if o == Occ::Unknown { Occ::Occupied } else { o });
        prop_assert_eq!(&back.cells, &want);
        prop_assert_eq!(back.resolution, m.resolution);
        let text = to_movingai(&m.cells);
        let parsed = parse_movingai(&text, std::path::Path::new("m.map"), 1.0).expect("parse");
        prop_assert_eq!(parsed.cells, want);
    }

    #[test]
    fn in_memory_images_keep_cells(g in grid()) {
        let name = std::path::Path::new("x");
        let png = parse_png(&encode_png(&g, name).expect("png"), name).expect("decode png");
        prop_assert_eq!(parse_bitmap(&png), g.clone());
        let pgm = parse_pgm(&encode_pgm(&g, name).expect("pgm"), name).expect("decode pgm");
        prop_assert_eq!(parse_bitmap(&pgm), g);
    }

    /// PGM decoding against a plain oracle: random pixels written as P2 or P5, 8 or 16 bit,
    /// with comments and odd whitespace in the header.
    #[test]
    fn pgm_decodes_what_was_written(
        (w, h, maxval, values) in (1usize..=16, 1usize..=16, prop_oneof![Just(1u32), Just(255), 1u32..=65535])
            .prop_flat_map(|(w, h, m)| (Just(w), Just(h), Just(m), proptest::collection::vec(0..=m, w * h))),
        plain in any::<bool>(),
        comment in any::<bool>(),
    ) {
        let sep = if comment { " # a comment\n\t" } else { "\n" };
        let mut bytes = format!("{}{sep}{w} {h}{sep}{maxval}\n", if plain { "P2" } else { "P5" })
            .into_bytes();
        for (i, &v) in values.iter().enumerate() {
            if plain {
                bytes.extend(format!("{v}{}", if i % w == w - 1 { "\n" } else { " " }).bytes());
            } else if maxval < 256 {
                bytes.push(v as u8);
            } else {
                bytes.extend((v as u16).to_be_bytes());
            }
        }
        let r = parse_pgm(&bytes, std::path::Path::new("t.pgm")).expect("decode");
        prop_assert_eq!(r, Raster { width: w, height: h, maxval, values, alpha: vec![], alpha_max: 0, colours: 1 });
    }

    /// The threshold rule against ROS map_server's formula for 8-bit pixels.
    #[test]
    fn thresholds_match_map_server(v in 0u32..=255, occ_t in threshold(), free_t in threshold(), negate in any::<bool>()) {
        let t = Thresholds { occupied: occ_t, free: free_t, negate };
        let r = Raster { width: 1, height: 1, maxval: 255, values: vec![v], alpha: vec![], alpha_max: 0, colours: 1 };
        // map_server: color_avg (255 - v if negate); occ = (255 - color_avg) / 255.0.
        let color_avg = if negate { 255.0 - f64::from(v) } else { f64::from(v) };
        let p = (255.0 - color_avg) / 255.0;
        let want = if p > occ_t { Occ::Occupied } else if p < free_t { Occ::Free } else { Occ::Unknown };
        prop_assert_eq!(t.classify_raster(&r).data()[0], want);
    }
}

/// A pixel whose occupancy equals both thresholds is neither above `occupied_thresh` nor
/// below `free_thresh`: Unknown (map_server compares strictly). Every 8-bit value.
#[test]
fn thresholds_are_strict() {
    for v in 0u32..=255 {
        for negate in [false, true] {
            let p = if negate {
                f64::from(v) / 255.0
            } else {
                f64::from(255 - v) / 255.0
            };
            let t = Thresholds {
                occupied: p,
                free: p,
                negate,
            };
            let r = Raster {
                width: 1,
                height: 1,
                maxval: 255,
                values: vec![v],
                alpha: vec![],
                alpha_max: 0,
                colours: 1,
            };
            assert_eq!(
                t.classify_raster(&r).data()[0],
                Occ::Unknown,
                "v {v} negate {negate}"
            );
        }
    }
}

/// A resolution given with a ROS YAML overrides the YAML's own (the CLI's `--resolution`
/// with `--map X.yaml`), origin kept; non-square pixels are resampled as for bitmaps.
#[test]
fn resolution_given_overrides_a_yamls() {
    let dir = scratch("yaml-override");
    let cells = Grid::from_vec(3, 2, vec![Occ::Free; 6]).expect("size");
    let m = GridMap {
        cells,
        resolution: 0.05,
        origin: [1.0, 2.0, 0.0],
    };
    let path = file(&dir, "yaml");
    save_map(&m, &path).expect("save");
    let own = load_map(&path, &LoadOptions::default()).expect("load");
    assert_eq!((own.resolution, own.width(), own.height()), (0.05, 3, 2));
    let given = load_map(&path, &LoadOptions::with_resolution(0.1)).expect("load");
    assert_eq!(
        (given.resolution, given.width(), given.height()),
        (0.1, 3, 2)
    );
    assert_eq!(given.origin, m.origin);
    let opts = LoadOptions {
        resolution: Some((0.1, 0.2)),
        border: false,
        ..LoadOptions::default()
    };
    let tall = load_map(&path, &opts).expect("load");
    assert_eq!((tall.resolution, tall.width(), tall.height()), (0.1, 3, 4));
    let _ = std::fs::remove_dir_all(&dir);
}
