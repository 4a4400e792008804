//! HouseExpo JSON floor plans, raw text, rasterised by the parser and through the map
//! loader. A small text can describe a large house (the raster is the outline's box at the
//! resolution, up to the loader's cell limit); inputs whose numbers reach beyond 2048 cells
//! of the origin are left out, so that an input stays within the fuzzer's time and memory.
#![no_main]
use libfuzzer_sys::fuzz_target;

/// The resolutions tried, in metres per cell.
const RESOLUTIONS: [f64; 2] = [0.25, 1.0];

/// Whether every number in `v` lies within 2048 cells of 0 at the finest resolution.
fn small(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => n.as_f64().is_some_and(|x| x.abs() <= 2048.0 * 0.25),
        serde_json::Value::Array(a) => a.iter().all(small),
        serde_json::Value::Object(o) => o.values().all(small),
        _ => true,
    }
}

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    if serde_json::from_str::<serde_json::Value>(text).is_ok_and(|v| !small(&v)) {
        return;
    }
    let name = std::path::Path::new("fuzz.json");
    for resolution in RESOLUTIONS {
        let _ = grid::io::parse_houseexpo(text, name, resolution);
    }
    let path = frontier_fuzz::temp_file("fuzz.json", bytes);
    let _ = grid::io::load_map(&path, &grid::io::LoadOptions::with_resolution(0.25));
});
