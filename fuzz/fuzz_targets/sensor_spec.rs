//! Sensor specs (`los:r=5`, `lidar:r=8,fov=180,res=1`, `sonar`, ...): parsed, printed back,
//! and built for a coarse and a fine map resolution (a range in cells, `r=...c`, reaches
//! any size).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let Ok(spec) = text.parse::<sense::spec::SensorSpec>() else {
        return;
    };
    // The canonical form parses back to the same spec.
    let again: sense::spec::SensorSpec = spec.to_string().parse().expect("canonical form parses");
    assert_eq!(again, spec, "{text}");
    // Building is bounded: ranges beyond what a map could hold are refused, not allocated.
    // A valid long line-of-sight range builds a big ray template (256 cells, the most
    // accepted, takes seconds and hundreds of MB by design; 64 cells take milliseconds), so
    // only short ranges are built: the building code is the same at every range, and the
    // fuzzer runs a thousand times more inputs.
    for resolution in [1.0, 0.05] {
        if spec.range_cells(resolution) <= 12.0 || !spec.range_cells(resolution).is_finite() {
            let _ = spec.build(resolution);
            let _ = spec.sonar(resolution);
        }
    }
});
