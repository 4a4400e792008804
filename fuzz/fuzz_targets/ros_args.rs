//! The command line of `frontier-ros`: its options and the `--ros-args` that launch_ros
//! passes (`-r` remapping rules, `__node`, `__ns`), one argument per line; then every name
//! the node uses resolved through the rules. A resolved name must be fully qualified.
#![no_main]
use frontier_ros_core::args::parse;
use frontier_ros_core::names::{
    COMMAND_TOPIC, GOAL_TOPIC, MARKERS_TOPIC, RESUME_TOPIC, STATUS_TOPIC, TF_STATIC_TOPIC, TF_TOPIC,
};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let Ok(args) = parse(text.lines().map(str::to_owned)) else {
        return;
    };
    let Ok(names) = args.names() else {
        return;
    };
    let used = [
        "map",
        "/map",
        "~/status",
        "{node}/x",
        "navigate_to_pose",
        RESUME_TOPIC,
        COMMAND_TOPIC,
        STATUS_TOPIC,
        GOAL_TOPIC,
        MARKERS_TOPIC,
        TF_TOPIC,
        TF_STATIC_TOPIC,
    ];
    for n in used {
        if let Ok(full) = names.resolve(n) {
            assert!(
                full.starts_with('/') && !full.contains("//"),
                "{n} → {full}"
            );
        }
    }
    assert!(names.fully_qualified_node_name().starts_with('/'));
    let _ = names.unused_rules(&used);
    let _ = names.own_topics();
});
