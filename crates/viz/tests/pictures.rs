//! The GIF decodes with the expected frame count and size; the replay page carries the run.

use explore::strategy::Strategy;
use sim::RunConfig;
use viz::animate::{GifOptions, animate_gif, frame_events};
use world::{EnvKind, EnvSpec};

fn run(kind: EnvKind, robots: usize) -> (grid::GridMap, sim::RunResult) {
    run_preset(kind, "cf-rr", robots)
}

/// A traced run of `preset` with `robots` robots on the default environment of `kind`, seed 1.
fn run_preset(kind: EnvKind, preset: &str, robots: usize) -> (grid::GridMap, sim::RunResult) {
    let env = world::generate(&EnvSpec {
        kind,
        seed: 1,
        size_m: None,
        resolution: None,
    })
    .unwrap();
    let mut cfg = RunConfig::new(Strategy::preset(preset).unwrap());
    cfg.record_trace = true;
    cfg.robots = robots;
    let r = sim::run(&env.map, &cfg).unwrap();
    (env.map, r)
}

#[test]
fn gif_has_the_frames_and_size_asked_for() {
    let (map, r) = run(EnvKind::Office, 2);
    let opts = GifOptions {
        max_frames: 40,
        max_side: 300,
        delay_cs: 5,
    };
    let bytes = animate_gif(&map, &r, &opts).unwrap();
    let mut decoder = gif::DecodeOptions::new();
    decoder.set_color_output(gif::ColorOutput::Indexed);
    let mut d = decoder.read_info(bytes.as_slice()).unwrap();
    // 50 x 40 cells upscaled by the whole factor 300 / 50 = 6.
    assert_eq!((d.width(), d.height()), (300, 240));
    let mut frames = 0;
    while let Some(f) = d.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height), (300, 240));
        frames += 1;
    }
    assert_eq!(frames, 40);
}

#[test]
fn large_maps_are_downscaled() {
    let (map, r) = run_preset(EnvKind::Cave, "cf", 1);
    let bytes = animate_gif(
        &map,
        &r,
        &GifOptions {
            max_frames: 3,
            max_side: 100,
            delay_cs: 5,
        },
    )
    .unwrap();
    let d = gif::DecodeOptions::new()
        .read_info(bytes.as_slice())
        .unwrap();
    // 160 cells, two per pixel.
    assert_eq!((d.width(), d.height()), (80, 80));
}

#[test]
fn frames_are_spread_over_the_run_and_end_at_its_end() {
    assert_eq!(frame_events(10, 5), vec![1, 3, 5, 7, 9]);
    assert_eq!(frame_events(3, 150), vec![0, 1, 2]);
    assert_eq!(*frame_events(1234, 150).last().unwrap(), 1233);
}

#[test]
fn replay_page_is_self_contained_and_carries_the_run() {
    let (map, r) = run(EnvKind::Maze, 1);
    let page = viz::replay::replay_html(&map, &r, "maze-s1", "cf-rr").unwrap();
    assert!(!page.contains("/*DATA*/null"), "data inlined");
    assert!(
        !page.contains("http://") && !page.contains("https://"),
        "no network references"
    );
    assert!(page.contains("\"title\":\"maze-s1\""));
    let trace = r.trace.as_ref().unwrap();
    assert!(page.contains(&format!("\"robots\":{}", trace.robots)));
}

/// The frames of a GIF, as palette indices.
fn gif_frames(bytes: &[u8]) -> Vec<Vec<u8>> {
    let mut decoder = gif::DecodeOptions::new();
    decoder.set_color_output(gif::ColorOutput::Indexed);
    let mut d = decoder.read_info(bytes).unwrap();
    let mut out = Vec::new();
    while let Some(f) = d.read_next_frame().unwrap() {
        out.push(f.buffer.to_vec());
    }
    out
}

#[test]
fn segmentation_runs_record_segments_and_show_them() {
    let (map, r) = run_preset(EnvKind::Office, "cf-rr-seg", 1);
    let trace = r.trace.as_ref().unwrap();
    assert!(!trace.segments.is_empty());
    assert!(trace.segments.len() <= sim::metrics::MAX_SEGMENT_SNAPSHOTS);
    assert!(trace.segments.windows(2).all(|w| w[0].event <= w[1].event));
    // Labels only on cells known free in the belief rebuilt at the snapshot's event.
    let n = map.cells.len();
    let mut known = vec![grid::Occ::Unknown; n];
    let mut done = 0usize;
    for snap in &trace.segments {
        while done < snap.event as usize {
            for &(c, s) in trace.changes_of(done) {
                known[c as usize] = s;
            }
            done += 1;
        }
        let labels = snap.labels();
        assert_eq!(labels.len(), n);
        assert!(labels.iter().any(|&l| l != u32::MAX));
        for (i, &l) in labels.iter().enumerate() {
            assert!(l == u32::MAX || known[i] == grid::Occ::Free, "cell {i}");
        }
    }
    // The GIF shows them: the same run without snapshots draws different frames.
    let opts = GifOptions {
        max_frames: 20,
        max_side: 300,
        delay_cs: 5,
    };
    let with = gif_frames(&animate_gif(&map, &r, &opts).unwrap());
    let mut plain = r.clone();
    plain.trace.as_mut().unwrap().segments.clear();
    let without = gif_frames(&animate_gif(&map, &plain, &opts).unwrap());
    assert_eq!(with.len(), without.len());
    assert_ne!(with.last(), without.last());
    // The replay page carries them, with the layer toggle.
    let html = viz::replay::replay_html(&map, &r, "seg", "cf-rr-seg").unwrap();
    assert!(html.contains("id=\"l-segments\"") && html.contains("\"segRuns\":\""));
    assert!(!html.contains("\"segRuns\":\"\""));
    let plain_html = viz::replay::replay_html(&map, &plain, "seg", "cf-rr-seg").unwrap();
    assert!(plain_html.contains("\"segRuns\":\"\""));
}

#[test]
fn furniture_off_the_laser_plane_is_drawn_in_every_picture() {
    let env = world::generate(&EnvSpec {
        kind: EnvKind::Office,
        seed: 2,
        size_m: Some((12.0, 10.0)),
        resolution: Some(0.1),
    })
    .unwrap();
    let clutter = world::clutter::furnish(&env, 2, &world::clutter::ClutterParams::default());
    let mut cfg = RunConfig::new(Strategy::preset("cf").unwrap());
    cfg.record_trace = true;
    cfg.clutter = Some(clutter.clone());
    let r = sim::run(&env.map, &cfg).unwrap();
    assert_eq!(r.clutter.as_ref(), Some(&clutter));
    // The laser plane's sensor misses the tables: believed free there, drawn orange; a
    // table cell the body bumped into is believed occupied, drawn brown.
    let img = viz::final_picture(&env.map, &r);
    let s = viz::scale_for(env.map.width(), env.map.height());
    let colour_of = |i: usize| {
        let c = env.map.cells.cell(i);
        img.get_pixel(c.x as u32 * s, c.y as u32 * s)
    };
    let tables: Vec<usize> = (0..clutter.len()).filter(|&i| clutter[i]).collect();
    assert!(!tables.is_empty());
    for &i in &tables {
        let want = match r.belief[i] {
            grid::Occ::Free => [246, 178, 90],
            grid::Occ::Occupied => [120, 72, 30],
            grid::Occ::Unknown => [226, 206, 178],
        };
        if !r.frontiers_left.contains(&(i as u32)) {
            assert_eq!(colour_of(i), want, "cell {i}");
        }
    }
    assert!(tables.iter().any(|&i| r.belief[i] == grid::Occ::Free));
    // The GIF has the clutter colours in its palette and uses them.
    let opts = GifOptions {
        max_frames: 5,
        max_side: 240,
        delay_cs: 5,
    };
    let frames = gif_frames(&animate_gif(&env.map, &r, &opts).unwrap());
    assert!(
        frames
            .last()
            .unwrap()
            .iter()
            .any(|&p| (17..20).contains(&p))
    );
    // The replay page marks them as truth class 3 and shows the legend.
    let html = viz::replay::replay_html(&env.map, &r, "office", "cf").unwrap();
    assert!(html.contains("\"clutter\":true"));
    let mut plain = r.clone();
    plain.clutter = None;
    let html = viz::replay::replay_html(&env.map, &plain, "office", "cf").unwrap();
    assert!(html.contains("\"clutter\":false"));
}
