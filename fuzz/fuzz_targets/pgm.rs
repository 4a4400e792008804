//! PGM images (P2 and P5), raw bytes, through the map loader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Ok(raster) = grid::io::parse_pgm(bytes, std::path::Path::new("fuzz.pgm")) {
        let _ = grid::io::parse_bitmap(&raster);
    }
    let path = frontier_fuzz::temp_file("fuzz.pgm", bytes);
    let _ = grid::io::load_map(&path, &grid::io::LoadOptions::with_resolution(0.05));
});
