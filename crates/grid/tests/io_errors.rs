//! Every class of malformed map input gives an error naming the file and what is wrong.

mod common;

use std::path::Path;

use grid::io::{
    LoadOptions, MAX_CELLS, MapErrorKind, encode_png, load_map, parse_ascii, parse_movingai,
    parse_pgm, parse_png, parse_ros_yaml_meta,
};
use grid::{Grid, Occ};

/// The message of an error result.
fn msg<T>(r: Result<T, grid::io::MapError>) -> String {
    match r {
        Ok(_) => panic!("expected an error, got a value"),
        Err(e) => e.to_string(),
    }
}

const GOOD_YAML: &str = "image: office.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n\
                         negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";

fn yaml_with(field: &str, value: &str) -> String {
    GOOD_YAML
        .lines()
        .map(|l| {
            if l.starts_with(&format!("{field}:")) {
                format!("{field}: {value}")
            } else {
                l.into()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn truncated_binary_pgm() {
    let mut bytes = b"P5\n600 400\n255\n".to_vec();
    bytes.extend(std::iter::repeat_n(254u8, 1200));
    assert_eq!(
        msg(parse_pgm(&bytes, Path::new("office.pgm"))),
        "office.pgm: truncated: header says 600x400 pixels (240000 bytes), \
         file has 1200 bytes of pixel data"
    );
    // 16-bit pixels take two bytes each.
    let mut bytes = b"P5 2 2 1000 ".to_vec();
    bytes.extend([0u8; 7]);
    assert_eq!(
        msg(parse_pgm(&bytes, Path::new("a.pgm"))),
        "a.pgm: truncated: header says 2x2 pixels (8 bytes), file has 7 bytes of pixel data"
    );
    // Regression: "file has 1 bytes".
    assert_eq!(
        msg(parse_pgm(b"P5 2 2 255 \x00", Path::new("a.pgm"))),
        "a.pgm: truncated: header says 2x2 pixels (4 bytes), file has 1 byte of pixel data"
    );
}

#[test]
fn truncated_plain_pgm() {
    assert_eq!(
        msg(parse_pgm(b"P2\n3 2\n255\n0 1 2\n3 4\n", Path::new("p.pgm"))),
        "p.pgm: pixel (2, 1): missing: the file ends after 5 of 3x2 pixel values"
    );
    // A header at the size limit with almost no data fails fast, without reserving 2^28
    // pixels first.
    assert_eq!(
        msg(parse_pgm(b"P2 16384 16384 255\n0 1", Path::new("p.pgm"))),
        "p.pgm: pixel (2, 0): missing: the file ends after 2 of 16384x16384 pixel values"
    );
    assert_eq!(
        msg(parse_movingai(
            "type octile\nheight 16384\nwidth 16384\nmap\n",
            Path::new("m.map"),
            1.0
        )),
        "m.map: line 5: the file ends after 0 of 16384 map rows"
    );
    assert_eq!(
        msg(parse_pgm(b"P2 2 1 255 0 x", Path::new("p.pgm"))),
        "p.pgm: pixel (1, 0): expected a number, found 'x'"
    );
}

#[test]
fn truncated_or_bad_pgm_header() {
    assert_eq!(
        msg(parse_pgm(b"P5\n# comment\n600", Path::new("h.pgm"))),
        "h.pgm: bad PGM header: expected height (a number), found end of file"
    );
    assert_eq!(
        msg(parse_pgm(b"P5 4 4 0\n", Path::new("h.pgm"))),
        "h.pgm: bad PGM header: maxval must be between 1 and 65535, found 0"
    );
    assert_eq!(
        msg(parse_pgm(b"P5 1 1 70000\n", Path::new("h.pgm"))),
        "h.pgm: bad PGM header: maxval must be between 1 and 65535, found 70000"
    );
    assert_eq!(
        msg(parse_pgm(
            b"P5 99999999999999999999999 1 255\n",
            Path::new("h.pgm")
        )),
        "h.pgm: bad PGM header: width is too large"
    );
}

#[test]
fn pgm_pixel_above_maxval() {
    assert_eq!(
        msg(parse_pgm(b"P5 2 1 100\n\x05\x65", Path::new("m.pgm"))),
        "m.pgm: pixel (1, 0): value 101 is above maxval 100"
    );
    assert_eq!(
        msg(parse_pgm(b"P2 1 2 7\n7\n8\n", Path::new("m.pgm"))),
        "m.pgm: pixel (0, 1): value 8 is above maxval 7"
    );
}

#[test]
fn mislabelled_images() {
    let png = encode_png(&Grid::new(2, 2, Occ::Free), Path::new("x.png")).expect("encode");
    assert_eq!(
        msg(parse_pgm(&png, Path::new("plan.pgm"))),
        "plan.pgm: not a PGM file: it is a PNG image (mislabelled?)"
    );
    assert_eq!(
        msg(parse_png(b"P5 1 1 255\n\x00", Path::new("plan.png"))),
        "plan.png: not a PNG file: it is a PGM image (mislabelled?)"
    );
    assert_eq!(
        msg(parse_pgm(b"P6 1 1 255\n\x00\x00\x00", Path::new("c.pgm"))),
        "c.pgm: not a PGM file: it is a PPM (colour) image"
    );
    assert_eq!(
        msg(parse_pgm(b"GIF89a..", Path::new("g.pgm"))),
        "g.pgm: not a PGM file: it starts with \"GIF89a..\""
    );
    assert_eq!(
        msg(parse_pgm(b"", Path::new("e.pgm"))),
        "e.pgm: not a PGM file: the file is empty"
    );
    // Through load_map, by extension.
    let dir = scratch("mislabelled");
    let path = dir.join("plan.png");
    std::fs::write(&path, b"P5 1 1 255\n\x00").expect("write");
    let e = msg(load_map(&path, &LoadOptions::with_resolution(0.1)));
    assert!(
        e.ends_with("plan.png: not a PNG file: it is a PGM image (mislabelled?)"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn truncated_png() {
    let png = encode_png(&Grid::new(40, 30, Occ::Free), Path::new("x.png")).expect("encode");
    let cut = &png[..png.len() - 20];
    let truncated = "cut.png: bad PNG: truncated: the file ends before the image data does";
    assert_eq!(msg(parse_png(cut, Path::new("cut.png"))), truncated);
    assert_eq!(msg(parse_png(&png[..20], Path::new("cut.png"))), truncated);
    // A corrupted checksum.
    let mut bad = png.clone();
    bad[30] ^= 0xff;
    let e = msg(parse_png(&bad, Path::new("crc.png")));
    assert!(e.starts_with("crc.png: bad PNG: "), "{e}");
}

#[test]
fn too_large_refused_before_allocating() {
    // PGM header claiming 2^15 x 2^14 = 2^29 pixels with almost no data.
    assert_eq!(
        msg(parse_pgm(b"P5 32768 16384 255\n\x00", Path::new("big.pgm"))),
        format!(
            "big.pgm: map too large: 32768x16384 cells is more than the limit of {MAX_CELLS} cells"
        )
    );
    // Width x height overflowing u64.
    let e = msg(parse_pgm(
        b"P5 18446744073709551615 3 255\n",
        Path::new("big.pgm"),
    ));
    assert!(
        e.contains("map too large: 18446744073709551615x3 cells"),
        "{e}"
    );
    // PNG whose IHDR claims 100000 x 100000 pixels.
    let mut png = encode_png(&Grid::new(1, 1, Occ::Free), Path::new("x.png")).expect("encode");
    png[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    png[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    let crc = common::crc32(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
    assert_eq!(
        msg(parse_png(&png, Path::new("big.png"))),
        format!(
            "big.png: map too large: 100000x100000 cells is more than the limit of {MAX_CELLS} cells"
        )
    );
    // MovingAI header.
    assert_eq!(
        msg(parse_movingai(
            "type octile\nheight 1000000\nwidth 1000000\nmap\n",
            Path::new("big.map"),
            1.0
        )),
        format!(
            "big.map: map too large: 1000000x1000000 cells is more than the limit of {MAX_CELLS} cells"
        )
    );
    // Non-square pixels whose resampled size would be too large.
    let dir = scratch("too-large");
    let path = dir.join("thin.txt");
    std::fs::write(&path, "..\n..\n").expect("write");
    let opts = LoadOptions {
        resolution: Some((1.0, 1e-9)),
        border: false,
        ..LoadOptions::default()
    };
    let e = msg(load_map(&path, &opts));
    assert!(
        e.contains("thin.txt: map too large: 2000000000x2 cells is more than the limit"),
        "{e}"
    );
    // Regression: a side too long for an integer was reported saturated, "2x18446744073709551615";
    // the pixels, the cells and their number (a float) are said instead.
    let opts = LoadOptions {
        resolution: Some((1e-300, 1.0)),
        ..LoadOptions::default()
    };
    let e = msg(load_map(&path, &opts));
    assert!(
        e.contains(
            "thin.txt: map too large: 2x2 pixels of 1e-300 x 1.0 m resampled to square cells \
             of 1e-300 m make about 4.000e300 cells, more than the limit of 268435456 cells"
        ),
        "{e}"
    );
    assert!(!e.contains("18446744073709551615"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn zero_size() {
    assert_eq!(
        msg(parse_pgm(b"P5 0 5 255\n", Path::new("z.pgm"))),
        "z.pgm: empty map: width 0 and height 5 must both be positive"
    );
    assert_eq!(
        msg(parse_movingai(
            "type octile\nheight 0\nwidth 4\nmap\n",
            Path::new("z.map"),
            1.0
        )),
        "z.map: empty map: width 4 and height 0 must both be positive"
    );
    assert_eq!(
        msg(parse_ascii("", 1.0)),
        "<memory>: empty map: width 0 and height 0 must both be positive"
    );
    assert_eq!(
        msg(encode_png(
            &Grid::new(0, 3, Occ::Free),
            Path::new("out.png")
        )),
        "out.png: empty map: width 0 and height 3 must both be positive"
    );
}

#[test]
fn negative_size() {
    assert_eq!(
        msg(parse_movingai(
            "type octile\nheight -3\nwidth 4\nmap\n",
            Path::new("n.map"),
            1.0
        )),
        "n.map: line 2: height must be a whole number, found \"-3\""
    );
    assert_eq!(
        msg(parse_pgm(b"P5 -3 4 255\n", Path::new("n.pgm"))),
        "n.pgm: bad PGM header: expected width (a number), found '-'"
    );
}

#[test]
fn bad_resolution() {
    assert_eq!(
        msg(parse_ascii("..", 0.0)),
        "<memory>: resolution must be a positive number of metres per cell, at most 1000, found 0"
    );
    assert_eq!(
        msg(parse_movingai(
            "type octile\nheight 1\nwidth 1\nmap\n.\n",
            Path::new("r.map"),
            -1.0
        )),
        "r.map: resolution must be a positive number of metres per cell, at most 1000, found -1"
    );
    // Regression: 1e308 m per cell was accepted and every path length came out infinite.
    assert_eq!(
        msg(parse_ascii("..", 1e6)),
        "<memory>: resolution must be a positive number of metres per cell, at most 1000, \
         found 1000000"
    );
    assert!(msg(parse_ascii("..", 1e308)).contains("at most 1000"));
    let dir = scratch("bad-resolution");
    let path = dir.join("a.txt");
    std::fs::write(&path, "..\n").expect("write");
    let opts = LoadOptions {
        resolution: Some((0.1, f64::NAN)),
        border: false,
        ..LoadOptions::default()
    };
    let e = msg(load_map(&path, &opts));
    assert!(
        e.ends_with(
            "a.txt: resolution must be a positive number of metres per cell, at most 1000, found NaN"
        ),
        "{e}"
    );
    let bitmap = dir.join("plan.pgm");
    std::fs::write(&bitmap, b"P5 1 1 255\n\x00").expect("write");
    let e = msg(load_map(&bitmap, &LoadOptions::default()));
    assert!(
        e.ends_with("plan.pgm: --resolution is required for a bare bitmap"),
        "{e}"
    );
    // Regression: a HouseExpo plan without a resolution was called a bare bitmap.
    let house = dir.join("house.json");
    std::fs::write(&house, br#"{"verts": [[0,0],[1,0],[0,1]]}"#).expect("write");
    let e = msg(load_map(&house, &LoadOptions::default()));
    assert!(
        e.ends_with(
            "house.json: --resolution is required for a HouseExpo floor plan (metres per cell \
             to rasterise it at)"
        ),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn yaml_bad_field_types() {
    let p = Path::new("maps/office.yaml");
    let cases = [
        (
            "resolution",
            "abc",
            "field 'resolution': expected a positive number, found \"abc\"",
        ),
        (
            "resolution",
            "-0.05",
            "field 'resolution': expected a positive number, found -0.05",
        ),
        (
            "resolution",
            "0",
            "field 'resolution': expected a positive number, found 0",
        ),
        (
            "resolution",
            ".nan",
            "field 'resolution': expected a positive number, found .nan",
        ),
        (
            "resolution",
            "[1, 2]",
            "field 'resolution': expected a positive number, found a list of 2 items",
        ),
        (
            "origin",
            "[1.0, 2.0]",
            "field 'origin': expected a list of three numbers [x, y, yaw], found a list of 2 items",
        ),
        (
            "origin",
            "7",
            "field 'origin': expected a list of three numbers [x, y, yaw], found 7",
        ),
        // Regression: a NaN in the origin was reported as "found a list of 3 items".
        (
            "origin",
            "[.nan, 0.0, 0.0]",
            "field 'origin': expected a finite number as its x ([x, y, yaw]), found .nan",
        ),
        (
            "origin",
            "[0.0, 0.0, \"north\"]",
            "field 'origin': expected a finite number as its yaw ([x, y, yaw]), found \"north\"",
        ),
        // nav2 reads any integer or a YAML boolean (yes, on, …): see `negate_as_nav2_reads_it`.
        (
            "negate",
            "0.5",
            "field 'negate': expected 0 or 1 (or a boolean), found 0.5",
        ),
        (
            "negate",
            "maybe",
            "field 'negate': expected 0 or 1 (or a boolean), found \"maybe\"",
        ),
        (
            "occupied_thresh",
            "1.5",
            "field 'occupied_thresh': expected a number between 0 and 1, found 1.5",
        ),
        (
            "free_thresh",
            "~",
            "field 'free_thresh': expected a number between 0 and 1, found nothing (null)",
        ),
        (
            "free_thresh",
            "0.7",
            "field 'free_thresh': expected at most occupied_thresh (0.65), found 0.7",
        ),
        (
            "image",
            "{a: 1}",
            "field 'image': expected an image file name, found a mapping",
        ),
        (
            "image",
            "''",
            "field 'image': expected an image file name, found \"\"",
        ),
    ];
    for (field, value, want) in cases {
        let text = yaml_with(field, value);
        assert_eq!(
            msg(parse_ros_yaml_meta(&text, p)),
            format!("maps/office.yaml: {want}"),
            "{text}"
        );
    }
    let text = format!("{GOOD_YAML}mode: fancy\n");
    assert_eq!(
        msg(parse_ros_yaml_meta(&text, p)),
        "maps/office.yaml: field 'mode': expected trinary, scale or raw, found \"fancy\""
    );
    // Regression: `negate: 2` and `negate: yes` were refused, though nav2 reads any
    // integer (not 0: negate) or a boolean in yaml-cpp's spellings.
    for (value, want) in [
        ("2", true),
        ("-1", true),
        ("0", false),
        ("yes", true),
        ("On", true),
        ("no", false),
        ("false", false),
    ] {
        let meta = parse_ros_yaml_meta(&yaml_with("negate", value), p).expect(value);
        assert_eq!(meta.thresholds.negate, want, "negate: {value}");
    }
    // Quoted numbers are numbers (yaml-cpp reads them so too); extra fields are allowed.
    let text = format!("{}\nextra: [1, 2]\n", yaml_with("resolution", "\"0.1\""));
    assert_eq!(
        parse_ros_yaml_meta(&text, p).expect("valid").resolution,
        0.1
    );
}

#[test]
fn yaml_missing_field_and_syntax() {
    let p = Path::new("office.yaml");
    for field in [
        "image",
        "resolution",
        "origin",
        "negate",
        "occupied_thresh",
        "free_thresh",
    ] {
        let text: String = GOOD_YAML
            .lines()
            .filter(|l| !l.starts_with(&format!("{field}:")))
            .map(|l| format!("{l}\n"))
            .collect();
        assert_eq!(
            msg(parse_ros_yaml_meta(&text, p)),
            format!("office.yaml: missing field '{field}'")
        );
    }
    let e = msg(parse_ros_yaml_meta("image: [a, b\nresolution: 1\n", p));
    assert!(e.starts_with("office.yaml: YAML syntax error: "), "{e}");
    assert_eq!(
        msg(parse_ros_yaml_meta("", p)),
        "office.yaml: YAML syntax error: the file is empty: expected a mapping of fields \
         (image, resolution, ...)"
    );
    // Regression: the parser's debug print of the key, `String("image"): duplicated key`.
    assert_eq!(
        msg(parse_ros_yaml_meta("image: a.pgm\nimage: b.pgm\n", p)),
        "office.yaml: YAML syntax error: image: duplicated key in mapping at byte 20 line 2 \
         column 8"
    );
    assert_eq!(
        msg(parse_ros_yaml_meta("- 1\n", p)),
        "office.yaml: YAML syntax error: expected a mapping of fields (image, resolution, ...), \
         found a list of 1 item"
    );
    assert_eq!(
        msg(parse_ros_yaml_meta("- 1\n- 2\n", p)),
        "office.yaml: YAML syntax error: expected a mapping of fields (image, resolution, ...), \
         found a list of 2 items"
    );
}

#[test]
fn yaml_missing_image_file() {
    let dir = scratch("missing-image");
    let yaml = dir.join("office.yaml");
    std::fs::write(&yaml, GOOD_YAML).expect("write");
    let e = msg(load_map(&yaml, &LoadOptions::default()));
    let image = dir.join("office.pgm");
    let want = format!("{}: image file '{}': ", yaml.display(), image.display());
    assert!(e.starts_with(&want), "{e}");
    // An image of a format we cannot read.
    std::fs::write(&yaml, yaml_with("image", "office.bmp")).expect("write");
    std::fs::write(dir.join("office.bmp"), b"BM").expect("write");
    let e = msg(load_map(&yaml, &LoadOptions::default()));
    assert!(
        e.ends_with(
            "office.yaml: field 'image': expected a .pgm or .png file, found \"office.bmp\""
        ),
        "{e}"
    );
    // A truncated image names the image file.
    std::fs::write(&yaml, GOOD_YAML).expect("write");
    std::fs::write(&image, b"P5 4 4 255\n\x00\x00").expect("write");
    let e = msg(load_map(&yaml, &LoadOptions::default()));
    assert!(e.ends_with("office.pgm: truncated: header says 4x4 pixels (16 bytes), file has 2 bytes of pixel data"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn missing_map_file_and_unknown_extension() {
    let dir = scratch("missing-map");
    let path = dir.join("nothere.map");
    let e = msg(load_map(&path, &LoadOptions::default()));
    assert!(
        e.starts_with(&format!("{}: cannot read: ", path.display())),
        "{e}"
    );
    let e = msg(load_map(&dir.join("plan.bmp"), &LoadOptions::default()));
    assert!(
        e.ends_with(
            "plan.bmp: unknown map format \"bmp\": expected .yaml, .yml, .pgm, .png, .map, .json (HouseExpo) or .txt"
        ),
        "{e}"
    );
    // Regression: a folder given as a map was "unknown map format \"\"".
    let e = msg(load_map(&dir, &LoadOptions::default()));
    assert_eq!(
        e,
        format!(
            "{}: is a folder, expected one map file (.yaml, .yml, .pgm, .png, .map, .json or .txt)",
            dir.display()
        )
    );
    // Regression: writing a HouseExpo .json was refused with a list that offered .json.
    let e = msg(grid::io::save_map(
        &grid::GridMap::new(Grid::new(2, 2, Occ::Free), 0.1),
        Path::new("o.json"),
    ));
    assert_eq!(
        e,
        "o.json: cannot write map format \"json\": expected .yaml, .yml, .pgm, .png, .map or .txt"
    );
    // Regression: a folder given to write a map into was an unknown map format "", and a
    // YAML in a missing folder named the PGM beside it, "No such file or directory".
    let m = grid::GridMap::new(Grid::new(2, 2, Occ::Free), 0.1);
    let e = msg(grid::io::save_map(&m, &dir));
    assert_eq!(
        e,
        format!(
            "{}: is a folder, expected the name of a map file to write (.yaml, .yml, .pgm, .png, .map or .txt)",
            dir.display()
        )
    );
    let missing = dir.join("no-such-folder");
    let e = msg(grid::io::save_map(&m, &missing.join("m.yaml")));
    assert_eq!(
        e,
        format!(
            "{}: cannot write: the folder {} does not exist",
            missing.join("m.yaml").display(),
            missing.display()
        )
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn movingai_unknown_character() {
    let text = "type octile\nheight 2\nwidth 3\nmap\n.@T\n.x.\n";
    assert_eq!(
        msg(parse_movingai(text, Path::new("m.map"), 1.0)),
        "m.map: line 6, column 2: unknown character 'x' (allowed: '.', 'G', 'S' free; \
         '@', 'O', 'T', 'W' blocked)"
    );
}

#[test]
fn movingai_bad_header_and_rows() {
    let p = Path::new("m.map");
    let cases = [
        (
            "type grid\nheight 1\nwidth 1\nmap\n.\n",
            "line 1: type must be 'octile', found \"grid\"",
        ),
        (
            "height 1\nwidth 1\nmap\n.\n",
            "line 3: header has no 'type' line",
        ),
        (
            "type octile\nwidth 1\nmap\n.\n",
            "line 3: header has no 'height' line",
        ),
        (
            "type octile\nheight 1\nmap\n.\n",
            "line 3: header has no 'width' line",
        ),
        (
            "type octile\nheight 1\nheight 1\nwidth 1\nmap\n.\n",
            "line 3: height is given twice",
        ),
        (
            "type octile\nheight x\nwidth 1\nmap\n.\n",
            "line 2: height must be a whole number, found \"x\"",
        ),
        (
            "type octile\nsize 1\nmap\n",
            "line 2: unknown header field \"size\" (expected type, height, width or map)",
        ),
        (
            "type octile\nheight 1 2\n",
            "line 2: expected a header line 'type octile', 'height H', 'width W' or 'map', found \"height 1 2\"",
        ),
        (
            "type octile\nheight 1\nwidth 1\n",
            "line 4: the file ends before the 'map' line",
        ),
        (
            "type octile\nheight 2\nwidth 2\nmap\n..\n",
            "line 6: the file ends after 1 of 2 map rows",
        ),
        (
            "type octile\nheight 2\nwidth 2\nmap\n..\n...\n",
            "line 6: map row has 3 cells, but width is 2",
        ),
        (
            "type octile\nheight 1\nwidth 2\nmap\n..\n..\n",
            "line 6: more map rows than the height 1",
        ),
    ];
    for (text, want) in cases {
        assert_eq!(
            msg(parse_movingai(text, p, 1.0)),
            format!("m.map: {want}"),
            "{text}"
        );
    }
}

#[test]
fn ascii_errors() {
    assert_eq!(
        msg(parse_ascii("#.#\n# #\n", 1.0)),
        "<memory>: line 2, column 2: unknown character ' ' (allowed: '#' wall, '.' free, '?' unknown)"
    );
    assert_eq!(
        msg(parse_ascii("#.#\n#.\n###\n", 1.0)),
        "<memory>: line 2: row has 2 cells, but the first row has 3"
    );
    assert_eq!(
        msg(parse_ascii("#.#\n\n###\n", 1.0)),
        "<memory>: line 2: row has 0 cells, but the first row has 3"
    );
}

#[test]
fn not_utf8_text() {
    let dir = scratch("utf8");
    let path = dir.join("bad.map");
    std::fs::write(&path, b"type octile\n\xff\xfe").expect("write");
    let e = msg(load_map(&path, &LoadOptions::default()));
    assert!(
        e.ends_with("bad.map: not a text file: invalid UTF-8 at byte 12"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn error_kind_is_matchable() {
    let e = parse_ascii("", 1.0).expect_err("empty");
    assert!(matches!(
        e.kind,
        MapErrorKind::EmptyMap {
            width: 0,
            height: 0
        }
    ));
    assert_eq!(e.path, Path::new("<memory>"));
}

/// Regression: a few hundred bytes of nested aliases ("billion laughs") made the YAML
/// loader expand them to gigabytes and abort; aliases and oversized files are refused.
#[test]
fn yaml_billion_laughs_is_refused() {
    let p = Path::new("laughs.yaml");
    let mut text = String::from(
        "a: &a [\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\"]\n",
    );
    for (prev, name) in "abcdefghi".chars().zip("bcdefghij".chars()) {
        let refs = vec![format!("*{prev}"); 9].join(",");
        text.push_str(&format!("{name}: &{name} [{refs}]\n"));
    }
    text.push_str(GOOD_YAML);
    assert!(text.len() < 1000);
    let started = std::time::Instant::now();
    let e = msg(parse_ros_yaml_meta(&text, p));
    assert!(
        e.starts_with("laughs.yaml: YAML syntax error: expected plain fields, found 81 alias(es)"),
        "{e}"
    );
    assert!(started.elapsed().as_secs() < 5);
    let big = format!("{GOOD_YAML}# {}\n", "x".repeat(grid::io::MAX_YAML_BYTES));
    let e = msg(parse_ros_yaml_meta(&big, p));
    assert!(e.contains("at most 65536 bytes"), "{e}");
}

/// Regression: `/dev/zero` given as a map (here behind a `.pgm` link) was read for 4 GiB
/// before failing; a device is refused before reading.
#[cfg(unix)]
#[test]
fn dev_zero_as_a_map_is_refused_at_once() {
    let dir = scratch("dev-zero");
    let path = dir.join("zero.pgm");
    std::os::unix::fs::symlink("/dev/zero", &path).expect("symlink");
    let started = std::time::Instant::now();
    let e = msg(load_map(&path, &LoadOptions::with_resolution(0.1)));
    assert!(
        e.ends_with("zero.pgm: not a regular file: a device, pipe or socket"),
        "{e}"
    );
    assert!(started.elapsed().as_secs() < 2);
}

/// A PNG of `side × side` 8-bit grey pixels whose image data stops after a few bytes: a
/// header promising a picture at the cell limit, at no cost to the test.
fn png_header_only(side: u32) -> Vec<u8> {
    // 8-bit grey, deflate, no interlace; the image data stops after the zlib header.
    common::png_with_idat((side, side), (8, 0), false, &[0x78, 0x9c, 0x62, 0x60])
}

/// A 16384 × 16384 picture is at the cell limit; `--border` takes it past, and that is known
/// from the header: the pixels (a gigabyte and seconds to decode) are never decoded.
#[test]
fn png_at_the_cell_limit_with_a_border_is_refused_before_decoding() {
    let dir = scratch("png-limit-border");
    let path = dir.join("huge.png");
    std::fs::write(&path, png_header_only(16_384)).unwrap();
    let opts = LoadOptions {
        resolution: Some((0.05, 0.05)),
        border: true,
        ..LoadOptions::default()
    };
    let err = load_map(&path, &opts).expect_err("past the cell limit");
    assert!(
        matches!(
            err.kind,
            MapErrorKind::TooLarge {
                width: 16_386,
                height: 16_386,
                limit: MAX_CELLS
            }
        ),
        "{err}"
    );
    // Non-square pixels resample to 16384 × 32768: refused on the header too.
    let opts = LoadOptions {
        resolution: Some((0.05, 0.1)),
        border: false,
        ..LoadOptions::default()
    };
    let err = load_map(&path, &opts).expect_err("past the cell limit once resampled");
    assert!(matches!(err.kind, MapErrorKind::TooLarge { .. }), "{err}");
    // Through a ROS YAML naming the picture: the same.
    std::fs::write(
        dir.join("huge.yaml"),
        GOOD_YAML.replace("office.pgm", "huge.png"),
    )
    .unwrap();
    let err = load_map(
        &dir.join("huge.yaml"),
        &LoadOptions {
            resolution: None,
            border: true,
            ..LoadOptions::default()
        },
    )
    .expect_err("past the cell limit");
    assert!(matches!(err.kind, MapErrorKind::TooLarge { .. }), "{err}");
    // Without the border it is within the limit, so the decoder is what refuses it.
    let err = load_map(&path, &LoadOptions::with_resolution(0.05)).expect_err("truncated");
    assert!(!matches!(err.kind, MapErrorKind::TooLarge { .. }), "{err}");
}

/// A binary PGM header at the cell limit with `--border`: refused before its pixels are read.
#[test]
fn pgm_at_the_cell_limit_with_a_border_is_refused_before_reading() {
    let dir = scratch("pgm-limit-border");
    let path = dir.join("huge.pgm");
    std::fs::write(&path, b"P5\n16384 16384\n255\n\x00\x00").unwrap();
    let opts = LoadOptions {
        resolution: Some((0.05, 0.05)),
        border: true,
        ..LoadOptions::default()
    };
    let err = load_map(&path, &opts).expect_err("past the cell limit");
    assert!(
        matches!(err.kind, MapErrorKind::TooLarge { width: 16_386, .. }),
        "{err}"
    );
}

/// A fresh scratch folder for one test, removed when the test ends.
fn scratch(test: &str) -> common::Scratch {
    common::scratch("io-errors", test)
}

/// Regression: a map file beginning with a UTF-8 byte order mark (which YAML 1.2 allows
/// and Windows editors write) was refused: the mark became part of the first key
/// ("missing field 'image'", "unknown header field \u{feff}type", "unknown character").
#[test]
fn regression_byte_order_mark_is_read_past() {
    let dir = scratch("bom");
    std::fs::write(dir.join("m.pgm"), b"P2 2 1 255 0 254").expect("write");
    let bom = |text: &str| [b"\xEF\xBB\xBF".as_slice(), text.as_bytes()].concat();
    let yaml = dir.join("m.yaml");
    std::fs::write(&yaml, bom(&yaml_with("image", "m.pgm"))).expect("write");
    let movingai = dir.join("m.map");
    std::fs::write(&movingai, bom("type octile\nheight 1\nwidth 2\nmap\n@.\n")).expect("write");
    let ascii = dir.join("m.txt");
    std::fs::write(&ascii, bom("#.\n")).expect("write");
    for path in [yaml, movingai, ascii] {
        let map = load_map(&path, &LoadOptions::default()).expect("reads past the mark");
        assert_eq!(
            map.cells.data(),
            &[Occ::Occupied, Occ::Free],
            "{}",
            path.display()
        );
    }
}

/// Regression: a comment between maxval and the raster ("255#made by X\n") was refused,
/// though pgm(5) allows one before the whitespace that delimits the raster.
#[test]
fn regression_pgm_comment_after_maxval() {
    let r = parse_pgm(
        b"P5\n3 1\n255# made by hand\n\x00\x01\x02",
        Path::new("c.pgm"),
    )
    .expect("a comment after maxval is valid");
    assert_eq!(r.values, vec![0, 1, 2]);
    let r = parse_pgm(b"P2 2 1 255#x\r1 2", Path::new("c.pgm")).expect("ends at CR too");
    assert_eq!(r.values, vec![1, 2]);
}

/// Regression: a plain PGM value too large for 32 bits was reported as 4294967295 (the
/// saturated number), which the file does not hold; the error now shows it as written.
#[test]
fn regression_pgm_huge_value_shown_as_written() {
    assert_eq!(
        msg(parse_pgm(b"P2 2 1 255 0 99999999999", Path::new("o.pgm"))),
        "o.pgm: pixel (1, 0): value 99999999999 is above maxval 255"
    );
    let long = format!("P2 1 1 255 {}", "9".repeat(40));
    assert_eq!(
        msg(parse_pgm(long.as_bytes(), Path::new("o.pgm"))),
        "o.pgm: pixel (0, 0): value 99999999999999999999… (40 digits) is above maxval 255"
    );
}

/// Regression: an ASCII map beginning with a blank line was "empty map: width 0 and
/// height 2"; the first row gives the width, so that line is named.
#[test]
fn regression_ascii_map_with_a_blank_first_line() {
    let dir = scratch("ascii-blank");
    let path = dir.join("a.txt");
    std::fs::write(&path, "\n#.\n").expect("write");
    let m = msg(load_map(&path, &LoadOptions::default()));
    assert!(
        m.ends_with("line 1: empty, but the first row gives the map's width"),
        "{m}"
    );
}

/// Regression: a HouseExpo plan given non-square pixels (`--resolution 0.5,2`) was read at
/// the smaller side without a word; it is read at one resolution, so two are refused.
#[test]
fn regression_houseexpo_refuses_non_square_resolution() {
    let dir = scratch("houseexpo-square");
    let path = dir.join("h.json");
    std::fs::write(&path, r#"{"verts": [[0,0],[4,0],[4,4],[0,4]]}"#).expect("write");
    let opts = LoadOptions {
        resolution: Some((0.5, 2.0)),
        ..LoadOptions::default()
    };
    let m = msg(load_map(&path, &opts));
    assert!(m.contains("h.json") && m.contains("found 0.5 x 2 m"), "{m}");
    let bad = dir.join("v.json");
    std::fs::write(&bad, r#"{"verts": [[0,0],[4,0],[4,"x"],[0,4]]}"#).expect("write");
    let m = msg(load_map(&bad, &LoadOptions::with_resolution(0.5)));
    assert!(m.contains(r#"found [4,"x"] at vertex 2"#), "{m}");
}

/// Regression: a bitmap or HouseExpo plan that is not there was said to need a
/// resolution, as if it had been found.
#[test]
fn regression_a_missing_bitmap_is_unreadable_not_short_of_a_resolution() {
    let dir = scratch("missing-bitmap");
    for name in ["plan.png", "plan.pgm", "plan.json"] {
        let path = dir.join(name);
        let e = msg(load_map(&path, &LoadOptions::default()));
        assert!(
            e.starts_with(&format!("{}: cannot read: ", path.display())),
            "{e}"
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}
