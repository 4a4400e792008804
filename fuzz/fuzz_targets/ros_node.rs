//! What `frontier-ros` takes from the network and its parameters file, without DDS: a
//! parameters file; an OccupancyGrid message (CDR) into the explorer, then a decision from
//! the map's centre; a TFMessage (CDR) into the TF tree, then the lookups between its
//! frames.
#![no_main]
use frontier_ros_core::params::Params;
use frontier_ros_core::tf::TfTree;
use frontier_ros_core::{Explorer, ExplorerConfig};
use libfuzzer_sys::fuzz_target;
use record::cdr::decode;
use record::msgs::{OccupancyGrid, TfMessage};

fuzz_target!(|bytes: &[u8]| {
    if let Ok(text) = std::str::from_utf8(bytes) {
        let mut p = Params::default();
        let _ = p.apply_yaml(text, "frontier_explore", "fuzz.yaml");
        if let Some((name, value)) = text.split_once(":=") {
            let _ = p.set(name, value);
        }
    }
    if let Ok(msg) = decode::<OccupancyGrid>(bytes) {
        let cfg = Params::default()
            .explorer_config()
            .expect("the default parameters");
        let mut e = Explorer::new(ExplorerConfig {
            clearance_m: 0.0,
            ..cfg
        });
        if e.update_map(&msg).is_ok() {
            let o = &msg.info.origin.position;
            let r = f64::from(msg.info.resolution);
            let (x, y) = (
                o.x + r * f64::from(msg.info.width) / 2.0,
                o.y + r * f64::from(msg.info.height) / 2.0,
            );
            let _ = e.decide(x, y, 0.0);
            let _ = e.check(x, y, 1.0);
            // The same message again changes nothing; a second decision must hold too.
            let _ = e.update_map(&msg);
            let _ = e.decide(x, y, 2.0);
        }
    }
    if let Ok(m) = decode::<TfMessage>(bytes) {
        let mut tf = TfTree::new();
        for t in &m.transforms {
            let _ = tf.set(t);
        }
        for a in &m.transforms {
            for b in &m.transforms {
                let _ = tf.lookup(&a.header.frame_id, &b.child_frame_id);
            }
        }
    }
});
