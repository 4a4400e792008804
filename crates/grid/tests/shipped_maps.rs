//! The real floor plans shipped in the repository's `maps/` folder load as documented in
//! its README (size, resolution, origin, cell counts), so that a changed or damaged file,
//! or a loader that reads them differently, is caught.

use std::path::{Path, PathBuf};

use grid::Occ;
use grid::io::{LoadOptions, load_map};

/// The repository's `maps/` folder.
fn maps() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../maps")
}

/// (free, occupied, unknown) cells of a map.
fn counts(cells: &[Occ]) -> (usize, usize, usize) {
    let n = |s: Occ| cells.iter().filter(|&&c| c == s).count();
    (n(Occ::Free), n(Occ::Occupied), n(Occ::Unknown))
}

#[test]
fn shipped_floor_plans_load_as_documented() {
    // name, (width, height), resolution, origin, (free, occupied, unknown)
    let expected = [
        (
            "willow-full.yaml",
            (1165, 945),
            0.05,
            [0.0, 0.0, 0.0],
            (549_308, 13_459, 538_158),
        ),
        (
            "depot.yaml",
            (604, 307),
            0.05,
            [-7.14, -7.83, 0.0],
            (179_481, 5_947, 0),
        ),
        (
            "warehouse.yaml",
            (1006, 1674),
            0.03,
            [-15.1, -25.0, 0.0],
            (1_422_292, 30_951, 230_801),
        ),
    ];
    for (name, size, resolution, origin, cells) in expected {
        let map = load_map(&maps().join(name), &LoadOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((map.width(), map.height()), size, "{name}: size");
        assert_eq!(map.resolution, resolution, "{name}: resolution");
        assert_eq!(map.origin, origin, "{name}: origin");
        assert_eq!(counts(map.cells.data()), cells, "{name}: cells");
    }
}

/// Willow Garage's plan has no YAML of its own: ours must read it as the bare bitmap is
/// read at 0.05 m (ROS map_server's default thresholds), cell for cell.
#[test]
fn willow_yaml_reads_the_image_as_the_bare_bitmap() {
    let yaml = load_map(&maps().join("willow-full.yaml"), &LoadOptions::default())
        .expect("willow-full.yaml");
    let bare = load_map(
        &maps().join("willow-full.png"),
        &LoadOptions::with_resolution(0.05),
    )
    .expect("willow-full.png");
    assert_eq!(yaml.cells, bare.cells);
    assert_eq!(yaml.resolution, bare.resolution);
}
