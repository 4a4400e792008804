//! Dungeon PNGs of the learned-exploration papers (the start marked by pixel value 208),
//! raw bytes, through the dungeon reader.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = grid::io::parse_dungeon(bytes, std::path::Path::new("fuzz.png"), 0.1);
});
