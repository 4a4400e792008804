//! PNG images through the map loader: square and non-square pixels, with and without a
//! border and a memory budget.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let path = frontier_fuzz::temp_file("fuzz.png", bytes);
    let _ = grid::io::load_map(&path, &grid::io::LoadOptions::with_resolution(0.05));
    let opts = grid::io::LoadOptions {
        resolution: Some((0.05, 0.1)),
        border: true,
        // The memory check on the loader's estimate, below libFuzzer's 2 GB limit.
        memory: Some(grid::memory::Available::budget(1 << 30)),
    };
    let _ = grid::io::load_map(&path, &opts);
});
