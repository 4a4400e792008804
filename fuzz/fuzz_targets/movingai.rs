//! MovingAI `.map` files, parsed and through the loader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = grid::io::parse_movingai(text, std::path::Path::new("fuzz.map"), 1.0);
    let path = frontier_fuzz::temp_file("fuzz.map", text.as_bytes());
    let _ = grid::io::load_map(&path, &grid::io::LoadOptions::default());
});
