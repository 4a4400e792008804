//! What reading a map allocates, measured by a counting allocator: a reader may hold the
//! file and the map, and little more, whatever the file claims or repeats.

use std::path::Path;

use grid::io::{LoadOptions, MapErrorKind, load_dungeon, load_map, parse_ascii, parse_png};
use grid::memory::Available;

mod common;
#[path = "common/counting.rs"]
mod counting;

use counting::{peak_of, turn};

/// Regression: an ASCII map's lines were collected into a list first, 16 bytes a line, so a
/// 200 MB file of newlines needed 3.2 GB (and aborted under a 4 GB address-space limit)
/// before it was refused as empty. The lines are now walked, not kept.
#[test]
fn regression_ascii_lines_are_not_collected() {
    let _turn = turn();
    let blank = "\n".repeat(4_000_000);
    let (result, peak) = peak_of(|| parse_ascii(&blank, 1.0));
    assert!(result.is_err(), "a file of blank lines is empty");
    assert!(peak < 1 << 20, "{peak} bytes to refuse 4 MB of blank lines");

    let column = ".\n".repeat(1_000_000);
    let (result, peak) = peak_of(|| parse_ascii(&column, 1.0));
    let map = result.expect("a 1 x 1000000 map");
    assert_eq!((map.width(), map.height()), (1, 1_000_000));
    // The map's cells (a byte each) and nothing of the lines' size.
    assert!(
        peak < 2_000_000,
        "{peak} bytes for a map of 1,000,000 cells"
    );
}

/// `data` as a zlib stream of stored (uncompressed) deflate blocks.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = data.chunks(65_535).collect();
    for (k, block) in blocks.iter().enumerate() {
        out.push(u8::from(k + 1 == blocks.len()));
        let len = block.len() as u16;
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(block);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &x in data {
        a = (a + u32::from(x)) % 65_521;
        b = (b + a) % 65_521;
    }
    out.extend_from_slice(&((b << 16) | a).to_be_bytes());
    out
}

/// A `w × h` PNG of `bit_depth`-bit samples of `color_type` (0 grey, 2 RGB, 4 grey+alpha,
/// 6 RGBA), `pixel(x, y)` giving each pixel's big-endian sample bytes, Adam7-interlaced or
/// not.
fn png_of(
    (w, h): (usize, usize),
    (bit_depth, color_type): (u8, u8),
    interlaced: bool,
    pixel: impl Fn(usize, usize) -> Vec<u8>,
) -> Vec<u8> {
    // The passes' (x0, y0, dx, dy), or one pass over every pixel.
    let passes: &[(usize, usize, usize, usize)] = if interlaced {
        &[
            (0, 0, 8, 8),
            (4, 0, 8, 8),
            (0, 4, 4, 8),
            (2, 0, 4, 4),
            (0, 2, 2, 4),
            (1, 0, 2, 2),
            (0, 1, 1, 2),
        ]
    } else {
        &[(0, 0, 1, 1)]
    };
    let mut raw = Vec::new();
    for &(x0, y0, dx, dy) in passes {
        if w <= x0 {
            continue;
        }
        for y in (y0..h).step_by(dy) {
            raw.push(0); // filter: none
            for x in (x0..w).step_by(dx) {
                raw.extend(pixel(x, y));
            }
        }
    }
    common::png_with_idat(
        (w as u32, h as u32),
        (bit_depth, color_type),
        interlaced,
        &zlib_stored(&raw),
    )
}

/// A 16-bit RGBA pixel of a pattern: channels from the position, some pixels transparent.
fn rgba16(x: usize, y: usize) -> Vec<u8> {
    let r = (x * 977 + y * 131) as u16;
    let g = (x * 17 + y * 7919) as u16;
    let b = (x ^ y) as u16;
    let a = if (x + 3 * y) % 5 == 1 { 0 } else { 40_000 };
    [r, g, b, a].iter().flat_map(|v| v.to_be_bytes()).collect()
}

/// Regression: a PNG was decoded whole before its pixels were summed, up to 8 bytes a
/// pixel (16-bit RGBA) and a copy of as many as 16-bit words, beside the raster's 5: a
/// 2 MB 16-bit RGBA PNG of 16384 x 16384 pixels peaked at 5.5 GB (aborted under a 4 GB
/// limit). Rows are now summed as they are decoded.
#[test]
fn regression_png_rows_are_decoded_one_at_a_time() {
    let _turn = turn();
    let (w, h) = (512, 512);
    let png = png_of((w, h), (16, 6), false, rgba16);
    let (raster, peak) = peak_of(|| parse_png(&png, Path::new("rgba16.png")));
    let raster = raster.expect("decodes");
    assert_eq!((raster.width, raster.height), (w, h));
    // The raster: a 4-byte value and a 2-byte alpha a pixel (the estimate's 6 bytes), and
    // some decoder state.
    let pixels = w * h;
    assert!(
        peak < 7 * pixels + (1 << 20),
        "{peak} bytes to decode {pixels} pixels ({} a pixel)",
        peak / pixels
    );
    let x = (7, 3);
    let i = x.1 * w + x.0;
    let px = rgba16(x.0, x.1);
    let sample = |c: usize| u32::from(u16::from_be_bytes([px[2 * c], px[2 * c + 1]]));
    assert_eq!(raster.values[i], sample(0) + sample(1) + sample(2));
    assert_eq!(raster.maxval, 3 * 65_535);
    assert_eq!(raster.is_transparent(i), sample(3) == 0);
}

/// The rows of an interlaced PNG land where Adam7 puts them: the same raster as the same
/// picture not interlaced, for sizes that leave passes empty or partial.
#[test]
fn interlaced_png_decodes_to_the_same_raster() {
    let _turn = turn();
    for (w, h) in [(1, 1), (3, 2), (5, 9), (13, 7), (16, 16), (33, 17)] {
        for (depth, colour) in [(16, 6), (8, 0), (8, 2), (8, 4)] {
            // The pattern's first channels, whole (16 bits) or their high bytes (8 bits).
            let channels = match colour {
                0 => 1,
                2 => 3,
                4 => 2,
                _ => 4,
            };
            let pixel = |x: usize, y: usize| -> Vec<u8> {
                let full = rgba16(x, y);
                match depth {
                    16 => full[..2 * channels].to_vec(),
                    _ => (0..channels).map(|c| full[2 * c]).collect(),
                }
            };
            let plain = parse_png(
                &png_of((w, h), (depth, colour), false, pixel),
                Path::new("p"),
            )
            .expect("plain decodes");
            let adam7 = parse_png(
                &png_of((w, h), (depth, colour), true, pixel),
                Path::new("i"),
            )
            .expect("interlaced decodes");
            assert_eq!(plain, adam7, "{w}x{h}, depth {depth}, colour type {colour}");
            assert!(
                plain.values.iter().any(|&v| v != plain.values[0]) || w * h == 1,
                "the pattern varies"
            );
        }
    }
}

/// The first bytes of a `w × h` 8-bit grey PNG: its header and the start of its image data,
/// enough for a reader to know its size and no pixels.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    common::png_with_idat((w, h), (8, 0), false, &zlib_stored(&[0; 64]))
}

/// Regression: loading checked no memory: a valid 16384 x 16384 map (2^28 cells, the cell
/// limit) was decoded, about 1.6 GB and 6 to 23 s, before the run's memory check refused
/// it or an allocation aborted under `ulimit -v`. Given the memory available, every loader
/// now estimates what loading takes from the size in the file's header (or text, or
/// outline) and refuses before the map's cells are allocated, naming the file, the size
/// needed and the limit.
#[test]
fn regression_loading_a_map_too_large_for_memory_is_refused_up_front() {
    let _turn = turn();
    let dir = common::scratch("io-memory", "budget");
    let side = 16_384u32;
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).expect("write");
        path
    };
    let pgm = write("max.pgm", format!("P5\n{side} {side}\n255\n").as_bytes());
    let png = write("max.png", &png_header(side, side));
    let image = write(
        "max-image.pgm",
        format!("P5\n{side} {side}\n255\n").as_bytes(),
    );
    let yaml = write(
        "max.yaml",
        b"image: max-image.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n\
          occupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    let movingai = write(
        "max.map",
        format!("type octile\nheight {side}\nwidth {side}\nmap\n").as_bytes(),
    );
    // A first row 16384 cells wide and 16384 rows, most of them one cell: the rows are
    // counted before any cell is read.
    let mut text = ".".repeat(side as usize);
    text.push_str(&"\n.".repeat(side as usize - 1));
    let ascii = write("max.txt", text.as_bytes());
    // A 1 km square outline at 0.1 m: 10002 x 10002 cells.
    let house = write(
        "max.json",
        br#"{"verts": [[0, 0], [1000, 0], [1000, 1000], [0, 1000]]}"#,
    );
    let budget = 64u64 << 20;
    let opts = LoadOptions {
        resolution: Some((0.1, 0.1)),
        memory: Some(Available::budget(budget)),
        ..LoadOptions::default()
    };
    // The file loaded, the file named (a YAML's image) and what is loaded.
    let cases = [
        (&pgm, &pgm, "loading this 16384x16384 PGM image"),
        (&png, &png, "loading this 16384x16384 PNG image"),
        (&yaml, &image, "loading this 16384x16384 PGM image"),
        (
            &movingai,
            &movingai,
            "loading this 16384x16384 MovingAI map",
        ),
        (&ascii, &ascii, "loading this 16384x16384 ASCII map"),
        (
            &house,
            &house,
            "loading this 10002x10002 HouseExpo floor plan",
        ),
    ];
    for (path, named, what) in cases {
        let (result, peak) = peak_of(|| load_map(path, &opts));
        let err = result.expect_err("over the budget");
        let msg = err.to_string();
        assert!(
            matches!(err.kind, MapErrorKind::OutOfMemory { needed, .. } if needed > budget),
            "{msg}"
        );
        // The file, what was expected and what was found: the size needed and the limit.
        assert!(msg.starts_with(&named.display().to_string()), "{msg}");
        assert!(msg.contains(what), "{msg}");
        assert!(
            msg.contains("MiB, more than the memory budget of 64 MiB"),
            "{msg}"
        );
        // Refused with the file read and nothing of the map's size.
        let file = std::fs::metadata(path).unwrap().len() as usize;
        assert!(
            peak < file + (1 << 20),
            "{peak} bytes to refuse {}",
            path.display()
        );
    }
    // A PGM needs its file, a 4-byte value and a cell a pixel: 1280 MiB for 2^28 pixels.
    let e = load_map(&pgm, &opts).unwrap_err().to_string();
    assert!(e.contains("needs about 1281 MiB"), "{e}");

    let (result, peak) = peak_of(|| load_dungeon(&png, 0.1, &opts));
    let msg = result.expect_err("over the budget").to_string();
    assert!(
        msg.contains("loading this 16384x16384 dungeon PNG"),
        "{msg}"
    );
    assert!(peak < 1 << 20, "{peak} bytes to refuse a dungeon PNG");

    // Within the budget, or with none, the same loaders load.
    let small = write(
        "small.pgm",
        b"P5\n4 3\n255\n\xfe\xfe\xfe\xfe\x00\x00\x00\x00\xcd\xcd\xcd\xcd",
    );
    assert!(load_map(&small, &opts).is_ok());
    let unchecked = LoadOptions::with_resolution(0.1);
    assert!(load_map(&small, &unchecked).is_ok());
}

/// A file larger than the memory available is refused before it is read.
#[test]
fn a_file_larger_than_the_budget_is_refused_unread() {
    let _turn = turn();
    let dir = common::scratch("io-memory", "file");
    let path = dir.join("big.txt");
    std::fs::write(&path, ".".repeat(3 << 20)).expect("write");
    let opts = LoadOptions {
        memory: Some(Available::budget(1 << 20)),
        ..LoadOptions::default()
    };
    let (result, peak) = peak_of(|| load_map(&path, &opts));
    let msg = result.expect_err("over the budget").to_string();
    assert!(
        msg.contains("reading this file of 3 MiB needs about 3 MiB"),
        "{msg}"
    );
    assert!(peak < 1 << 20, "{peak} bytes to refuse a 3 MiB file");
}
