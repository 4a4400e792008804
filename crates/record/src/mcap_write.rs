//! A run as an MCAP recording that Foxglove Studio (or `ros2 bag play`) opens.
//!
//! Topics, all in the `map` frame, ROS 2 CDR with `ros2msg` schemas:
//!
//! | topic | type | what |
//! |---|---|---|
//! | `/map` | `nav_msgs/msg/OccupancyGrid` | the map explored (once, at the start) |
//! | `/frontier/belief` | `nav_msgs/msg/OccupancyGrid` | what the robots knew, at every decision |
//! | `/frontier/robot<k>/pose` | `geometry_msgs/msg/PoseStamped` | robot k's pose after every move |
//! | `/frontier/robot<k>/goal` | `geometry_msgs/msg/PoseStamped` | each goal robot k chose |
//! | `/frontier/markers` | `visualization_msgs/msg/MarkerArray` | frontier cells and goal candidates at every decision |
//!
//! Log times and stamps are the run's clock (seconds of robot travel at its speed) in
//! nanoseconds, from 0, or from the log time of the recorded map the run explored, in that
//! map's frame ([`RunWriter::with_clock`]): a run then lines up with its recording.

use std::collections::BTreeMap;
use std::io::{Seek, Write};

use grid::GridMap;

use crate::cdr::encode;
use crate::msgs::{
    ColorRgba, Header, Marker, MarkerArray, OccupancyGrid, Point, Pose, PoseStamped, RosMessage,
    Time, Vector3,
};
use crate::occupancy::msg_from_map;

/// The frame every message of a run is in.
pub const FRAME: &str = "map";

/// Topic of the explored map.
pub const MAP_TOPIC: &str = "/map";
/// Topic of the belief snapshots.
pub const BELIEF_TOPIC: &str = "/frontier/belief";
/// Topic of robot `k`'s poses.
pub fn pose_topic(k: usize) -> String {
    format!("/frontier/robot{k}/pose")
}

/// Topic of robot `k`'s goals.
pub fn goal_topic(k: usize) -> String {
    format!("/frontier/robot{k}/goal")
}
/// Topic of the frontier and candidate markers.
pub const MARKER_TOPIC: &str = "/frontier/markers";

/// Writes a run's messages into an MCAP file.
pub struct RunWriter<W: Write + Seek> {
    out: mcap::Writer<W>,
    map: u16,
    belief: u16,
    pose_schema: u16,
    /// (pose, goal) channels of each robot, added when first used.
    robots: Vec<(u16, u16)>,
    markers: u16,
    sequence: u32,
    /// The frame every message is in.
    frame: String,
    /// Nanoseconds since the epoch at the run's time 0.
    start_ns: u64,
}

/// A channel's metadata under MCAP's `ros2` profile, whose `offered_qos_profiles` key is
/// required: empty, as no publisher offered these topics (a player uses its default QoS;
/// `ros2 bag play --qos-profile-overrides-path` makes `/map` transient local, see ros.md).
fn ros2_metadata() -> BTreeMap<String, String> {
    BTreeMap::from([("offered_qos_profiles".to_string(), String::new())])
}

fn schema<M: RosMessage>(w: &mut mcap::Writer<impl Write + Seek>) -> mcap::McapResult<u16> {
    w.add_schema(M::TYPE, "ros2msg", M::definition().as_bytes())
}

impl<W: Write + Seek> RunWriter<W> {
    /// Start a recording into `out` (zstd-compressed chunks), in the [`FRAME`] frame, its
    /// time 0 at the epoch.
    pub fn new(out: W) -> mcap::McapResult<Self> {
        Self::with_clock(out, FRAME, 0)
    }

    /// Start a recording into `out` whose messages are in `frame`, the run's time 0 being
    /// `start_ns` nanoseconds after the epoch (the log time of the recorded map explored).
    pub fn with_clock(out: W, frame: &str, start_ns: u64) -> mcap::McapResult<Self> {
        let mut out = mcap::WriteOptions::new()
            .profile("ros2")
            .library(concat!("frontier ", env!("CARGO_PKG_VERSION")))
            .create(out)?;
        let grid = schema::<OccupancyGrid>(&mut out)?;
        let pose = schema::<PoseStamped>(&mut out)?;
        let markers = schema::<MarkerArray>(&mut out)?;
        let meta = ros2_metadata();
        let mut channel = |s, t| out.add_channel(s, t, "cdr", &meta);
        let ids = (
            channel(grid, MAP_TOPIC)?,
            channel(grid, BELIEF_TOPIC)?,
            channel(markers, MARKER_TOPIC)?,
        );
        Ok(Self {
            out,
            map: ids.0,
            belief: ids.1,
            pose_schema: pose,
            robots: Vec::new(),
            markers: ids.2,
            sequence: 0,
            frame: frame.to_string(),
            start_ns,
        })
    }

    /// Nanoseconds since the epoch at the run's time `t_s`.
    fn nanos(&self, t_s: f64) -> u64 {
        self.start_ns.saturating_add(Time::from_secs(t_s).nanos())
    }

    fn put(&mut self, channel_id: u16, t_s: f64, data: &[u8]) -> mcap::McapResult<()> {
        let t = self.nanos(t_s);
        self.sequence += 1;
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: self.sequence,
            log_time: t,
            publish_time: t,
        };
        self.out.write_to_known_channel(&header, data)
    }

    fn header(&self, t_s: f64) -> Header {
        Header {
            stamp: Time::from_nanos(self.nanos(t_s)),
            frame_id: self.frame.clone(),
        }
    }

    /// The explored map, at time `t_s`.
    pub fn map(&mut self, t_s: f64, map: &GridMap) -> mcap::McapResult<()> {
        let msg = msg_from_map(map, &self.frame, Time::from_nanos(self.nanos(t_s)));
        self.put(self.map, t_s, &encode(&msg))
    }

    /// A belief snapshot (same frame as the map).
    pub fn belief(&mut self, t_s: f64, belief: &GridMap) -> mcap::McapResult<()> {
        let msg = msg_from_map(belief, &self.frame, Time::from_nanos(self.nanos(t_s)));
        self.put(self.belief, t_s, &encode(&msg))
    }

    fn robot(&mut self, k: usize) -> mcap::McapResult<(u16, u16)> {
        while self.robots.len() <= k {
            let r = self.robots.len();
            let meta = ros2_metadata();
            let pose = self
                .out
                .add_channel(self.pose_schema, &pose_topic(r), "cdr", &meta)?;
            let goal = self
                .out
                .add_channel(self.pose_schema, &goal_topic(r), "cdr", &meta)?;
            self.robots.push((pose, goal));
        }
        Ok(self.robots[k])
    }

    /// Robot `k`'s pose (world metres and yaw).
    pub fn pose(&mut self, t_s: f64, k: usize, x: f64, y: f64, yaw: f64) -> mcap::McapResult<()> {
        let msg = PoseStamped {
            header: self.header(t_s),
            pose: Pose::planar(x, y, yaw),
        };
        let ch = self.robot(k)?.0;
        self.put(ch, t_s, &encode(&msg))
    }

    /// A goal robot `k` chose.
    pub fn goal(&mut self, t_s: f64, k: usize, x: f64, y: f64) -> mcap::McapResult<()> {
        let msg = PoseStamped {
            header: self.header(t_s),
            pose: Pose::planar(x, y, 0.0),
        };
        let ch = self.robot(k)?.1;
        self.put(ch, t_s, &encode(&msg))
    }

    /// Frontier cells and goal candidates (world points) as markers of side `cell_m`.
    pub fn markers(
        &mut self,
        t_s: f64,
        frontiers: &[(f64, f64)],
        candidates: &[(f64, f64)],
        cell_m: f64,
    ) -> mcap::McapResult<()> {
        let msg = markers(&self.header(t_s), frontiers, candidates, cell_m);
        self.put(self.markers, t_s, &encode(&msg))
    }

    /// Write the summary and hand back the output.
    pub fn finish(mut self) -> mcap::McapResult<W> {
        self.out.finish()?;
        Ok(self.out.into_inner())
    }
}

/// The marker array of a decision: a DELETEALL, frontier cells as a blue cube list and goal
/// candidates as orange spheres (what the ROS node publishes too).
pub fn markers(
    header: &Header,
    frontiers: &[(f64, f64)],
    candidates: &[(f64, f64)],
    cell_m: f64,
) -> MarkerArray {
    let pts = |v: &[(f64, f64)]| v.iter().map(|&(x, y)| Point { x, y, z: 0.0 }).collect();
    let clear = Marker {
        header: header.clone(),
        action: Marker::DELETEALL,
        ..Marker::default()
    };
    let list = |ns: &str, kind, side: f64, color, points| Marker {
        header: header.clone(),
        ns: ns.into(),
        id: 0,
        kind,
        action: Marker::ADD,
        pose: Pose::planar(0.0, 0.0, 0.0),
        scale: Vector3 {
            x: side,
            y: side,
            z: side,
        },
        color,
        points,
        ..Marker::default()
    };
    MarkerArray {
        markers: vec![
            clear,
            list(
                "frontiers",
                Marker::CUBE_LIST,
                cell_m,
                ColorRgba {
                    r: 0.1,
                    g: 0.4,
                    b: 1.0,
                    a: 0.8,
                },
                pts(frontiers),
            ),
            list(
                "candidates",
                Marker::SPHERE_LIST,
                (3.0 * cell_m).max(0.1),
                ColorRgba {
                    r: 1.0,
                    g: 0.5,
                    b: 0.0,
                    a: 1.0,
                },
                pts(candidates),
            ),
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mcap_read::last_map;
    use grid::io::parse_ascii;

    /// A run written on its recording's clock: its messages are in the recording's frame and
    /// logged from the recorded map's log time on, their stamps the same times.
    #[test]
    fn a_run_on_a_recordings_clock_keeps_its_frame_and_time() {
        use crate::mcap_read::read_last_map;
        let map = parse_ascii("####\n#..#\n####\n", 0.1).unwrap();
        let start = 1_700_000_000_250_000_000u64;
        let mut w =
            RunWriter::with_clock(std::io::Cursor::new(Vec::new()), "world", start).unwrap();
        w.map(0.0, &map).unwrap();
        w.belief(2.5, &map).unwrap();
        let bytes = w.finish().unwrap().into_inner();
        let len = bytes.len() as u64;
        let on = |topic| {
            read_last_map(&bytes[..], len, Some(topic), None)
                .unwrap()
                .at
        };
        let at = on(MAP_TOPIC);
        assert_eq!((at.frame_id.as_str(), at.log_time), ("world", start));
        let at = on(BELIEF_TOPIC);
        assert_eq!(
            (at.frame_id.as_str(), at.log_time),
            ("world", start + 2_500_000_000)
        );
        assert_eq!(
            Time::from_nanos(start + 2_500_000_000),
            Time {
                sec: 1_700_000_002,
                nanosec: 750_000_000
            }
        );
        // Without a clock: the `map` frame, from 0.
        let mut w = RunWriter::new(std::io::Cursor::new(Vec::new())).unwrap();
        w.map(1.0, &map).unwrap();
        let bytes = w.finish().unwrap().into_inner();
        let at = read_last_map(&bytes[..], bytes.len() as u64, None, None)
            .unwrap()
            .at;
        assert_eq!((at.frame_id.as_str(), at.log_time), (FRAME, 1_000_000_000));
    }

    #[test]
    fn a_run_written_reads_back() {
        let mut map = parse_ascii("#####\n#..?#\n#.#.#\n#####\n", 0.1).unwrap();
        map.origin = [1.0, 2.0, 0.0];
        let mut w = RunWriter::new(std::io::Cursor::new(Vec::new())).unwrap();
        w.map(0.0, &map).unwrap();
        let mut later = map.clone();
        later.cells.data_mut()[8] = grid::Occ::Free;
        w.belief(1.0, &later).unwrap();
        w.pose(1.0, 0, 1.2, 2.2, 0.5).unwrap();
        w.goal(1.5, 0, 1.3, 2.3).unwrap();
        w.markers(1.5, &[(1.25, 2.25)], &[(1.35, 2.25)], 0.1)
            .unwrap();
        let bytes = w.finish().unwrap().into_inner();
        // `/map` is the only map topic named /map, the belief the other.
        let (back, topic) = last_map(&bytes, None).unwrap();
        assert_eq!((back.cells, topic.as_str()), (map.cells.clone(), "/map"));
        let (back, _) = last_map(&bytes, Some(BELIEF_TOPIC)).unwrap();
        assert_eq!(back.cells, later.cells);
        let e = last_map(&bytes, Some(&pose_topic(0)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("expected nav_msgs/msg/OccupancyGrid"), "{e}");
        let e = last_map(&bytes, Some("/nothing")).unwrap_err().to_string();
        assert!(
            e.contains("/frontier/robot0/pose (geometry_msgs/msg/PoseStamped)"),
            "{e}"
        );
    }

    #[test]
    fn garbage_is_an_error_not_a_panic() {
        for bytes in [&b""[..], b"\x89MCAP0\r\n", b"not an mcap file at all"] {
            assert!(last_map(bytes, None).is_err());
        }
    }
}
