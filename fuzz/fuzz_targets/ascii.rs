//! ASCII-art maps (`#` wall, `.` free, `?` unknown), parsed and through the loader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = grid::io::parse_ascii(text, 1.0);
    let _ = grid::io::parse_ascii(text, 0.0);
    let path = frontier_fuzz::temp_file("fuzz.txt", text.as_bytes());
    let _ = grid::io::load_map(&path, &grid::io::LoadOptions::with_resolution(0.25));
});
