"""MCAP round trip: recordings written by `frontier explore --mcap` read back by the `mcap`
and `mcap-ros2-support` packages (which decode ROS 2 CDR from the schema text alone, so
they check frontier's message structs against their definitions), and a map recorded by
`mcap-ros2-support` read by `frontier explore --map`."""

import json
import subprocess

from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from mcap_ros2.writer import Writer as Ros2Writer

# The ROS 2 definition of nav_msgs/msg/OccupancyGrid with its dependencies, as rosbag2 writes
# it into a recording's schema (written here independently of frontier's).
GRID_SCHEMA = """std_msgs/Header header
MapMetaData info
int8[] data
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
================================================================================
MSG: nav_msgs/MapMetaData
builtin_interfaces/Time map_load_time
float32 resolution
uint32 width
uint32 height
geometry_msgs/Pose origin
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
"""


def read_all(path):
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        return [(ch.topic, sch.name, msg.log_time, ros) for sch, ch, msg, ros in reader.iter_decoded_messages()]


def test_a_run_recorded_by_frontier_decodes_with_mcap_ros2(cli, tmp_path):
    out = tmp_path / "run.mcap"
    r = subprocess.run(
        [cli, "explore", "--env", "office", "--size", "15x12", "--resolution", "0.25", "--seed", "3",
         "--strategy", "cf-rr", "--mcap", str(out), "--json", "--no-timing"],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    msgs = read_all(out)
    topics = {t for t, _, _, _ in msgs}
    assert topics == {"/map", "/frontier/belief", "/frontier/robot0/pose", "/frontier/robot0/goal", "/frontier/markers"}
    maps = [m for t, _, _, m in msgs if t == "/map"]
    assert len(maps) == 1
    grid = maps[0]
    assert (grid.info.width, grid.info.height) == (60, 48)
    assert abs(grid.info.resolution - 0.25) < 1e-6
    assert len(grid.data) == 60 * 48
    assert set(grid.data) <= {-1, 0, 100}
    beliefs = [m for t, _, _, m in msgs if t == "/frontier/belief"]
    # Regression: the final belief was written twice at the same log time.
    belief_times = [lt for t, _, lt, _ in msgs if t == "/frontier/belief"]
    assert len(belief_times) == len(set(belief_times)), belief_times
    # The last belief knows every cell the run covered and nothing the map does not have.
    last = beliefs[-1]
    known_free = sum(1 for v in last.data if v == 0)
    assert known_free > 0.9 * sum(1 for v in grid.data if v == 0)
    assert all(b == m or b == -1 for b, m in zip(last.data, grid.data))
    poses = [m for t, _, _, m in msgs if t == "/frontier/robot0/pose"]
    assert len(poses) > 10
    assert all(p.header.frame_id == "map" for p in poses)
    # Poses stay on the map.
    w_m, h_m = 60 * 0.25, 48 * 0.25
    assert all(0 <= p.pose.position.x <= w_m and 0 <= p.pose.position.y <= h_m for p in poses)
    markers = [m for t, _, _, m in msgs if t == "/frontier/markers"]
    assert markers and [mk.ns for mk in markers[0].markers] == ["", "frontiers", "candidates"]
    # Log times never go backwards within a topic and end at the run's time.
    times = [lt for t, _, lt, _ in msgs if t == "/frontier/robot0/pose"]
    assert times == sorted(times)
    assert abs(times[-1] / 1e9 - summary["time_s"]) < 1e-3

    # frontier reads its own recording back: the map topic, and a belief by --topic.
    for topic in ("/map", "/frontier/belief"):
        again = subprocess.run(
            [cli, "explore", "--map", str(out), "--topic", topic, "--json", "--no-timing"],
            capture_output=True, text=True)
        assert again.returncode == 0, again.stderr
        back = json.loads(again.stdout)
        assert (back["width"], back["height"], back["resolution"]) == (60, 48, 0.25)
    info = subprocess.run([cli, "map", "info", str(out)], capture_output=True, text=True)
    assert info.returncode == 0, info.stderr
    assert "60 x 48 cells" in info.stdout, info.stdout

    # Regression: the channels lacked the `offered_qos_profiles` metadata MCAP's ros2
    # profile requires; every checksum holds too.
    with open(out, "rb") as f:
        reader = make_reader(f, validate_crcs=True)
        index = reader.get_summary()
        assert index is not None and index.channels
        for ch in index.channels.values():
            assert ch.metadata == {"offered_qos_profiles": ""}, (ch.topic, ch.metadata)
        assert sum(1 for _ in reader.iter_messages()) == len(msgs)


def test_a_map_recorded_with_mcap_ros2_is_explored_by_frontier(cli, tmp_path):
    # A 12 x 8 room (walls around), origin at (-1, 2), as a SLAM node would publish it.
    w, h = 12, 8
    data = []
    for row_up in range(h):
        for x in range(w):
            wall = x in (0, w - 1) or row_up in (0, h - 1)
            data.append(100 if wall else 0)
    path = tmp_path / "bag.mcap"
    with open(path, "wb") as f:
        writer = Ros2Writer(f)
        schema = writer.register_msgdef("nav_msgs/msg/OccupancyGrid", GRID_SCHEMA)
        for k, t in enumerate((1, 2)):
            msg = {
                "header": {"stamp": {"sec": t, "nanosec": 0}, "frame_id": "map"},
                "info": {
                    "map_load_time": {"sec": 0, "nanosec": 0},
                    "resolution": 0.5, "width": w, "height": h,
                    "origin": {"position": {"x": -1.0, "y": 2.0, "z": 0.0},
                               "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}},
                },
                # The first message knows only the bottom half; the last one, everything.
                "data": data if k == 1 else [v if i < w * h // 2 else -1 for i, v in enumerate(data)],
            }
            writer.write_message("/map", schema, msg, log_time=t * 10**9, publish_time=t * 10**9)
        writer.finish()
    r = subprocess.run(
        [cli, "explore", "--map", str(path), "--strategy", "cf", "--json", "--no-timing"],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert (out["width"], out["height"], out["resolution"]) == (w, h, 0.5), out
    assert out["coverage"] == 1.0
    # A wrong topic names what the recording has.
    bad = subprocess.run(
        [cli, "explore", "--map", str(path), "--topic", "/nope"], capture_output=True, text=True)
    assert bad.returncode != 0
    assert "/map (nav_msgs/msg/OccupancyGrid)" in bad.stderr, bad.stderr
