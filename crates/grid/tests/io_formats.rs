//! Worked examples of each map format, with hand-computed expected cells.

use std::path::{Path, PathBuf};

use grid::io::{
    LoadOptions, ascii_map, load_dungeon, load_map, parse_ascii, parse_movingai, save_map, to_ascii,
};
use grid::{Cell, Grid, GridMap, Occ};

use Occ::{Free as F, Occupied as O, Unknown as U};

/// A fresh scratch folder for one test.
fn scratch(test: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("frontier-io-formats-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch folder");
    dir
}

fn row(map: &GridMap) -> Vec<Occ> {
    map.cells.data().to_vec()
}

const PIXELS: &str = "0 89 90 204 205 206 254 255";

fn ros_yaml(image: &str, extra: &str) -> String {
    format!(
        "image: {image}\nresolution: 0.05\norigin: [-10.0, -2.5, 0.0]\n{extra}\
         occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
}

#[test]
fn ros_trinary_thresholds_on_plain_pgm() {
    let dir = scratch("trinary");
    std::fs::create_dir_all(dir.join("img")).expect("mkdir");
    std::fs::write(
        dir.join("img/office.pgm"),
        format!("P2\n# made by hand\n8 1\n255\n{PIXELS}\n"),
    )
    .expect("write");
    let yaml = dir.join("office.yaml");
    std::fs::write(
        &yaml,
        ros_yaml("img/office.pgm", "negate: 0\nmode: trinary\n"),
    )
    .expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    // p = (255 - v) / 255: 0 → 1, 89 → 0.651, 90 → 0.647, 204 → 0.2, 205 → 0.19608,
    // 206 → 0.192, 254 → 0.004, 255 → 0.
    assert_eq!(row(&map), vec![O, O, U, U, U, F, F, F]);
    assert_eq!(map.resolution, 0.05);
    assert_eq!(map.origin, [-10.0, -2.5, 0.0]);
    // negate: p = v / 255.
    std::fs::write(&yaml, ros_yaml("img/office.pgm", "negate: 1\n")).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!(row(&map), vec![F, U, U, O, O, O, O, O]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ros_rows_top_first() {
    let dir = scratch("rows");
    std::fs::write(dir.join("m.pgm"), b"P5 2 3 255\n\x00\x00\xfe\xfe\xcd\xcd").expect("write");
    let yaml = dir.join("m.yaml");
    std::fs::write(&yaml, ros_yaml("m.pgm", "negate: 0\n")).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!((map.width(), map.height()), (2, 3));
    assert_eq!(map.cells.data(), &[O, O, F, F, U, U]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ros_sixteen_bit_pgm_scales_by_maxval() {
    let dir = scratch("16bit");
    let mut bytes = b"P5\n4 1\n65535\n".to_vec();
    for v in [0u16, 65535, 205 * 257, 206 * 257] {
        bytes.extend(v.to_be_bytes());
    }
    std::fs::write(dir.join("m.pgm"), bytes).expect("write");
    // maxval 1000: 1000 is white, 0 black, 196 → p = 0.804.
    std::fs::write(dir.join("n.pgm"), b"P2 3 1 1000 1000 0 196").expect("write");
    let yaml = dir.join("m.yaml");
    std::fs::write(&yaml, ros_yaml("m.pgm", "negate: 0\n")).expect("write");
    assert_eq!(
        row(&load_map(&yaml, &LoadOptions::default()).expect("load")),
        vec![O, F, U, F]
    );
    std::fs::write(&yaml, ros_yaml("n.pgm", "negate: 0\n")).expect("write");
    assert_eq!(
        row(&load_map(&yaml, &LoadOptions::default()).expect("load")),
        vec![F, O, O]
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A `w × h` PNG of `colour` and `depth` holding the samples `data` (big-endian if 16-bit).
fn encode_png(
    w: u32,
    h: u32,
    colour: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, w, h);
    encoder.set_color(colour);
    encoder.set_depth(depth);
    let mut writer = encoder.write_header().expect("header");
    writer.write_image_data(data).expect("pixels");
    writer.finish().expect("end");
    out
}

/// Regression: `border` was ignored for dungeon PNGs (the CLI's `--dungeon --border` and
/// Python's `Map.load(..., border=True, dungeon=True)` read the picture as it was); it adds
/// a wall around the map, as around a bare bitmap, and the marked start moves with it.
#[test]
fn dungeon_border_adds_a_wall_and_moves_the_start() {
    let dir = scratch("dungeon-border");
    let path = dir.join("d.png");
    // 3 x 2: free, with the start marked at column 0 of row 1.
    let pixels = [255, 255, 255, 208, 255, 255];
    let png = grid::io::png::encode_grey(&pixels, 3, 2).expect("encode");
    std::fs::write(&path, png).expect("write");
    let plain = load_dungeon(&path, 0.5, &LoadOptions::default()).expect("reads");
    let opts = LoadOptions {
        border: true,
        ..LoadOptions::default()
    };
    let walled = load_dungeon(&path, 0.5, &opts).expect("reads");
    assert_eq!((plain.map.width(), plain.map.height()), (3, 2));
    assert_eq!(plain.start, Cell::new(0, 1));
    assert_eq!((walled.map.width(), walled.map.height()), (5, 4));
    assert_eq!(walled.start, Cell::new(1, 2));
    #[rustfmt::skip]
    let want = vec![
        O, O, O, O, O,
        O, F, F, F, O,
        O, F, F, F, O,
        O, O, O, O, O,
    ];
    assert_eq!(row(&walled.map), want);
    assert_eq!(walled.map.origin, [-0.5, -0.5, 0.0]);
    assert_eq!(walled.map.resolution, 0.5);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn ros_png_colour_and_alpha() {
    let dir = scratch("png");
    let px: [[u8; 4]; 5] = [
        [255, 255, 255, 0], // transparent: unknown
        [255, 0, 0, 255],   // mean 85: p = 0.667, occupied
        [254, 254, 254, 255],
        [205, 205, 205, 255],
        [0, 0, 0, 1], // barely opaque black: unknown in scale mode, occupied in trinary
    ];
    let rgba = encode_png(
        5,
        1,
        png::ColorType::Rgba,
        png::BitDepth::Eight,
        &px.concat(),
    );
    std::fs::write(dir.join("m.png"), rgba).expect("save png");
    let yaml = dir.join("m.yaml");
    // Scale mode: the colour channels' mean; a pixel not fully opaque is Unknown, as nav2
    // reads it (regression: the barely opaque black was Occupied, as ROS 1 reads it, while
    // the transparent white was Unknown, as nav2 does). nav2 lower-cases the mode.
    std::fs::write(&yaml, ros_yaml("m.png", "negate: 0\nmode: Scale\n")).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!(row(&map), vec![U, O, F, U, U]);
    // A bare bitmap reads colour alone: only the fully transparent pixel is Unknown.
    let bare = LoadOptions {
        resolution: Some((1.0, 1.0)),
        ..LoadOptions::default()
    };
    assert_eq!(
        row(&load_map(&dir.join("m.png"), &bare).expect("load")),
        vec![U, O, F, U, O]
    );
    // Trinary mode: alpha averaged in with red, green and blue, as both map_servers do:
    // (255·3 + 0)/4 → p 0.25; (255 + 255)/4 → 0.5; (254·3 + 255)/4 → 0.003;
    // (205·3 + 255)/4 → 0.147; (0 + 1)/4 → 0.999.
    std::fs::write(&yaml, ros_yaml("m.png", "negate: 0\nmode: trinary\n")).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!(row(&map), vec![U, U, F, F, O]);
    // A 16-bit grey PNG.
    let wide: Vec<u8> = [0u16, 65535, 52685]
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect();
    let grey16 = encode_png(
        3,
        1,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &wide,
    );
    std::fs::write(dir.join("g.png"), grey16).expect("save png");
    std::fs::write(&yaml, ros_yaml("g.png", "negate: 0\n")).expect("write");
    assert_eq!(
        row(&load_map(&yaml, &LoadOptions::default()).expect("load")),
        vec![O, F, U]
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Both map_servers average a PNG's alpha in with its colour in trinary mode ("alpha will
/// be averaged in with color channels when using trinary mode", ROS 1's image_loader and
/// nav2's map_io); frontier read the colour alone, so an opaque map_server grey of 205
/// (free there) was Unknown and greys of 26–89 (Unknown there) walls. A grey+alpha pixel's
/// grey counts three times, as red, green and blue.
#[test]
fn regression_trinary_png_averages_alpha_as_map_server() {
    let dir = scratch("trinary-alpha");
    let greys = [0u8, 50, 80, 150, 200, 205, 254];
    let yaml = dir.join("m.yaml");
    std::fs::write(&yaml, ros_yaml("m.png", "negate: 0\nmode: trinary\n")).expect("write");
    // map_server: (3·g + 255) / 4 for an opaque pixel, then p = 1 − shade.
    let want: Vec<Occ> = greys
        .iter()
        .map(|&g| {
            let p = 1.0 - (3.0 * f64::from(g) + 255.0) / 4.0 / 255.0;
            if p > 0.65 {
                O
            } else if p < 0.196 {
                F
            } else {
                U
            }
        })
        .collect();
    assert_eq!(want, vec![O, U, U, U, F, F, F]);
    let rgba: Vec<u8> = greys.iter().flat_map(|&g| [g, g, g, 255]).collect();
    let grey_alpha: Vec<u8> = greys.iter().flat_map(|&g| [g, 255]).collect();
    for (pixels, colour) in [
        (rgba, png::ColorType::Rgba),
        (grey_alpha, png::ColorType::GrayscaleAlpha),
    ] {
        let png = encode_png(7, 1, colour, png::BitDepth::Eight, &pixels);
        std::fs::write(dir.join("m.png"), png).expect("save png");
        let map = load_map(&yaml, &LoadOptions::default()).expect("load");
        assert_eq!(row(&map), want, "{colour:?}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// A raw value written as a threshold is on its side: 55 with `occupied_thresh: 0.55` is
/// Occupied and 29 with `free_thresh: 0.29` Free, although `100 · 0.55` is
/// 55.00000000000001 and `100 · 0.29` 28.999999999999996 in floating point.
#[test]
fn regression_raw_value_at_a_threshold_is_on_its_side() {
    let dir = scratch("raw-threshold");
    std::fs::write(dir.join("m.pgm"), b"P2 4 1 255 55 29 56 28").expect("write");
    let yaml = dir.join("m.yaml");
    let text = "image: m.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n\
                occupied_thresh: 0.55\nfree_thresh: 0.29\nmode: raw\n";
    std::fs::write(&yaml, text).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!(row(&map), vec![O, F, O, F]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ros_raw_mode() {
    let dir = scratch("raw");
    std::fs::write(dir.join("m.pgm"), b"P2 8 1 255 0 19 20 64 65 100 101 255").expect("write");
    let yaml = dir.join("m.yaml");
    // Values are occupancy percentages; negate is ignored in raw mode (as nav2).
    std::fs::write(&yaml, ros_yaml("m.pgm", "negate: 1\nmode: raw\n")).expect("write");
    let map = load_map(&yaml, &LoadOptions::default()).expect("load");
    assert_eq!(row(&map), vec![F, F, U, U, O, O, U, U]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ros_yaml_written_for_ros_tools() {
    let dir = scratch("write-yaml");
    let map = GridMap {
        cells: Grid::from_vec(3, 1, vec![F, O, U]).expect("grid"),
        resolution: 0.05,
        origin: [-10.0, 2.5, 0.0],
    };
    let yaml = dir.join("office.yaml");
    save_map(&map, &yaml).expect("save");
    assert_eq!(
        std::fs::read_to_string(&yaml).expect("read"),
        "image: \"office.pgm\"\nmode: trinary\nresolution: 0.05\norigin: [-10.0, 2.5, 0.0]\n\
         negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    );
    let pgm = std::fs::read(dir.join("office.pgm")).expect("read pgm");
    let header = b"P5\n# frontier occupancy map: free 254, occupied 0, unknown 205\n3 1\n255\n";
    assert_eq!(&pgm[..header.len()], header);
    assert_eq!(&pgm[header.len()..], &[254, 0, 205]);
    // A PNG is 8-bit grey with the same levels.
    let png = dir.join("office.png");
    save_map(&map, &png).expect("save");
    let mut reader = png::Decoder::new(std::io::Cursor::new(std::fs::read(&png).expect("read")))
        .read_info()
        .expect("a PNG");
    let mut px = vec![0; reader.output_buffer_size().expect("size")];
    let frame = reader.next_frame(&mut px).expect("decode");
    assert_eq!(
        (frame.color_type, frame.bit_depth),
        (png::ColorType::Grayscale, png::BitDepth::Eight)
    );
    assert_eq!(&px[..frame.buffer_size()], &[254, 0, 205]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bare_bitmap_with_border() {
    let dir = scratch("border");
    let path = dir.join("plan.pgm");
    std::fs::write(&path, b"P5 2 1 255\n\xff\xcd").expect("write");
    let opts = LoadOptions {
        resolution: Some((0.5, 0.5)),
        border: true,
        ..LoadOptions::default()
    };
    let map = load_map(&path, &opts).expect("load");
    assert_eq!(to_ascii(&map.cells), "####\n#.?#\n####\n");
    assert_eq!(map.resolution, 0.5);
    assert_eq!(map.origin, [-0.5, -0.5, 0.0]);
    let plain = load_map(&path, &LoadOptions::with_resolution(0.5)).expect("load");
    assert_eq!(to_ascii(&plain.cells), ".?\n");
    // Dark is obstacle with the ROS default thresholds.
    std::fs::write(&path, b"P5 3 1 255\n\x00\x59\x5a").expect("write");
    let map = load_map(&path, &LoadOptions::with_resolution(1.0)).expect("load");
    assert_eq!(row(&map), vec![O, O, U]);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn border_moves_origin_along_yaw() {
    let map = GridMap {
        cells: Grid::new(1, 1, F),
        resolution: 2.0,
        origin: [10.0, 20.0, std::f64::consts::FRAC_PI_2],
    };
    let b = grid::io::add_border(&map);
    // One cell down-left in the map frame: map x is world y, map y is world -x.
    assert!(
        (b.origin[0] - 12.0).abs() < 1e-12 && (b.origin[1] - 18.0).abs() < 1e-12,
        "{:?}",
        b.origin
    );
}

#[test]
fn movingai_characters() {
    let text = "type octile\r\nheight 2\r\nwidth 4\r\nmap\r\n.GS@\r\nOTW.\r\n";
    let map = parse_movingai(text, Path::new("m.map"), 0.25).expect("parse");
    assert_eq!(row(&map), vec![F, F, F, O, O, O, O, F]);
    assert_eq!(map.resolution, 0.25);
    // Header fields in another order, blank trailing lines.
    let text = "type octile\nwidth 1\nheight 2\nmap\n.\n@\n\n";
    assert_eq!(
        row(&parse_movingai(text, Path::new("m.map"), 1.0).expect("parse")),
        vec![F, O]
    );
    // Regression: a CRLF file without its final newline kept the last row's '\r', an
    // "unknown character"; so did ASCII art.
    let text = "type octile\r\nheight 2\r\nwidth 4\r\nmap\r\n.GS@\r\nOTW.\r";
    let map = parse_movingai(text, Path::new("m.map"), 0.25).expect("parse");
    assert_eq!(row(&map), vec![F, F, F, O, O, O, O, F]);
    let art = parse_ascii("#.\r\n.#\r", 1.0).expect("parse");
    assert_eq!(row(&art), vec![O, F, F, O]);
}

#[test]
fn non_square_pixels_resample_to_square_cells() {
    let dir = scratch("non-square");
    let path = dir.join("a.txt");
    std::fs::write(&path, "#.\n?.\n").expect("write");
    // Pixels 0.1 wide, 0.2 tall → cells of 0.1, each row doubled.
    let opts = LoadOptions {
        resolution: Some((0.1, 0.2)),
        border: false,
        ..LoadOptions::default()
    };
    let map = load_map(&path, &opts).expect("load");
    assert_eq!(to_ascii(&map.cells), "#.\n#.\n?.\n?.\n");
    assert_eq!(map.resolution, 0.1);
    // Pixels 0.3 wide, 0.1 tall → each column tripled.
    let opts = LoadOptions {
        resolution: Some((0.3, 0.1)),
        border: true,
        ..LoadOptions::default()
    };
    let map = load_map(&path, &opts).expect("load");
    assert_eq!(
        to_ascii(&map.cells),
        "########\n####...#\n#???...#\n########\n"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn ascii_art() {
    let map = parse_ascii("#.?\r\n...\n", 0.5).expect("parse");
    assert_eq!(row(&map), vec![O, F, U, F, F, F]);
    assert_eq!((map.width(), map.height(), map.resolution), (3, 2, 0.5));
    let m = ascii_map(
        "
        ###
        #.?
        ",
    );
    assert_eq!(to_ascii(&m.cells), "###\n#.?\n");
    assert_eq!(m.resolution, 1.0);
}

#[test]
#[should_panic(
    expected = "ascii_map: bad test map: <memory>: line 1, column 2: unknown character 'x'"
)]
fn ascii_map_panics_clearly() {
    let _ = ascii_map("#x#");
}

#[test]
fn yml_extension_and_absolute_image_path() {
    let dir = scratch("yml");
    let map = GridMap {
        cells: ascii_map("#.?").cells,
        resolution: 0.1,
        origin: [1.0, 2.0, 0.5],
    };
    let yml = dir.join("m.yml");
    save_map(&map, &yml).expect("save");
    assert_eq!(load_map(&yml, &LoadOptions::default()).expect("load"), map);
    // A YAML elsewhere naming the image by absolute path.
    std::fs::create_dir_all(dir.join("other")).expect("mkdir");
    let other = dir.join("other/abs.yaml");
    let image = dir.join("m.pgm");
    let text = ros_yaml(&format!("{:?}", image.display().to_string()), "negate: 0\n");
    std::fs::write(&other, text).expect("write");
    assert_eq!(
        load_map(&other, &LoadOptions::default())
            .expect("load")
            .cells,
        map.cells
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// Regression: a PNG whose header chunk fails its checksum was refused with the decoder's
/// debug print of the chunk type ("ChunkType { type: IHDR, critical: true, … }").
#[test]
fn regression_png_errors_name_chunks_plainly() {
    let dir = scratch("png-crc");
    let mut bytes = encode_png(
        2,
        2,
        png::ColorType::Grayscale,
        png::BitDepth::Eight,
        &[0, 255, 255, 0],
    );
    bytes[29] ^= 0xff; // the IHDR chunk's CRC
    let path = dir.join("bad.png");
    std::fs::write(&path, bytes).expect("write");
    let opts = LoadOptions {
        resolution: Some((0.1, 0.1)),
        ..LoadOptions::default()
    };
    let e = load_map(&path, &opts).expect_err("bad CRC").to_string();
    assert!(e.contains("bad.png") && e.contains("IHDR"), "{e}");
    assert!(!e.contains("ChunkType"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}
