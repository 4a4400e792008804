//! ROS map_server YAML: the fields, then the whole load (YAML and a tiny PGM image beside it).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|text: &str| {
    let _ = grid::io::parse_ros_yaml_meta(text, Path::new("fuzz.yaml"));
    // Through the loader, with a valid 2x2 image at `image: map.pgm`.
    frontier_fuzz::temp_file("map.pgm", b"P5\n2 2\n255\n\x00\xfe\xcd\xfe");
    let yaml = frontier_fuzz::temp_file("fuzz.yaml", text.as_bytes());
    let _ = grid::io::load_map(&yaml, &grid::io::LoadOptions::default());
});
