//! The ROS 2 messages of a frontier node, as serde structs.
//!
//! Field order, names and types follow the ROS 2 (Jazzy) definitions, which
//! [`RosMessage::definition`] repeats in the `ros2msg` form MCAP schemas use (the message's
//! own fields, then each dependency after a line of `=` and `MSG: package/Type`). A CDR
//! encoder writes struct fields in order with natural alignment, so a struct whose fields
//! match the definition is the message on the wire: `int8[]` is `Vec<i8>`, `float64[36]` is
//! `[f64; 36]` (no length), `string` is `String`. The tests check byte layouts by hand, and
//! the Python round trip (`mcap-ros2-support`, which decodes from the definition text alone)
//! checks structs and definitions against each other.

use serde::{Deserialize, Serialize};

/// A message type: its ROS 2 name and `ros2msg` definition with dependencies.
pub trait RosMessage {
    /// `package/msg/Type` as ROS 2 names it (e.g. `nav_msgs/msg/OccupancyGrid`).
    const TYPE: &'static str;
    /// The `.msg` definition followed by its dependencies, for MCAP `ros2msg` schemas.
    fn definition() -> String;
}

const SEP: &str =
    "================================================================================";

/// A definition followed by its dependencies, each after a separator line.
fn with_deps(own: &str, deps: &[(&str, &str)]) -> String {
    let mut s = own.to_string();
    for (name, def) in deps {
        s.push_str(SEP);
        s.push_str("\nMSG: ");
        s.push_str(name);
        s.push('\n');
        s.push_str(def);
    }
    s
}

const TIME: &str = "int32 sec\nuint32 nanosec\n";
const DURATION: &str = "int32 sec\nuint32 nanosec\n";
const HEADER: &str = "builtin_interfaces/Time stamp\nstring frame_id\n";
const POINT: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const QUATERNION: &str = "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n";
const POSE: &str = "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n";
const VECTOR3: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const COLOR: &str = "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n";
const META: &str = "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\ngeometry_msgs/Pose origin\n";
const GRID: &str = "std_msgs/Header header\nnav_msgs/MapMetaData info\nint8[] data\n";
const POSE_STAMPED: &str = "std_msgs/Header header\ngeometry_msgs/Pose pose\n";
const POSE_COV: &str = "geometry_msgs/Pose pose\nfloat64[36] covariance\n";
const POSE_COV_STAMPED: &str = "std_msgs/Header header\ngeometry_msgs/PoseWithCovariance pose\n";
const IMAGE: &str = "std_msgs/Header header\nstring format\nuint8[] data\n";
const UV: &str = "float32 u\nfloat32 v\n";
const MESH: &str = "string filename\nuint8[] data\n";
const MARKER: &str = "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\nint32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\nint32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\nint32 TRIANGLE_LIST=11\nint32 ARROW_STRIP=12\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\nstd_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\ngeometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\nbuiltin_interfaces/Duration lifetime\nbool frame_locked\ngeometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring texture_resource\nsensor_msgs/CompressedImage texture\nvisualization_msgs/UVCoordinate[] uv_coordinates\nstring text\nstring mesh_resource\nvisualization_msgs/MeshFile mesh_file\nbool mesh_use_embedded_materials\n";
const MARKER_ARRAY: &str = "visualization_msgs/Marker[] markers\n";

/// `builtin_interfaces/Time`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Time {
    /// Seconds.
    pub sec: i32,
    /// Nanoseconds within the second.
    pub nanosec: u32,
}

impl Time {
    /// The time `s` seconds after the epoch (negative and non-finite values give 0).
    pub fn from_secs(s: f64) -> Self {
        if !(s.is_finite() && s > 0.0) {
            return Self::default();
        }
        let sec = s.floor().min(i32::MAX as f64);
        Self {
            sec: sec as i32,
            nanosec: (((s - sec) * 1e9) as u32).min(999_999_999),
        }
    }

    /// The time `ns` nanoseconds after the epoch (at most `i32::MAX` seconds).
    pub fn from_nanos(ns: u64) -> Self {
        let sec = (ns / 1_000_000_000).min(i32::MAX as u64);
        Self {
            sec: sec as i32,
            nanosec: (ns % 1_000_000_000) as u32,
        }
    }

    /// Seconds since the epoch.
    pub fn secs(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }

    /// Nanoseconds since the epoch (0 for times before it), as MCAP log times are.
    pub fn nanos(self) -> u64 {
        u64::try_from(self.sec).unwrap_or(0) * 1_000_000_000 + u64::from(self.nanosec)
    }
}

/// `builtin_interfaces/Duration`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Duration {
    /// Seconds.
    pub sec: i32,
    /// Nanoseconds within the second.
    pub nanosec: u32,
}

/// `std_msgs/Header`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Header {
    /// When the data was taken.
    pub stamp: Time,
    /// The coordinate frame of the data.
    pub frame_id: String,
}

/// `geometry_msgs/Point`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// x (m).
    pub x: f64,
    /// y (m).
    pub y: f64,
    /// z (m).
    pub z: f64,
}

/// `geometry_msgs/Quaternion`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

impl Default for Quaternion {
    fn default() -> Self {
        Self::from_yaw(0.0)
    }
}

impl Quaternion {
    /// The rotation by `yaw` radians about z.
    pub fn from_yaw(yaw: f64) -> Self {
        let h = yaw / 2.0;
        Self {
            x: 0.0,
            y: 0.0,
            z: h.sin(),
            w: h.cos(),
        }
    }

    /// The rotation's angle about z (the yaw of its heading).
    pub fn yaw(&self) -> f64 {
        let siny = 2.0 * (self.w * self.z + self.x * self.y);
        let cosy = 1.0 - 2.0 * (self.y * self.y + self.z * self.z);
        siny.atan2(cosy)
    }
}

/// `geometry_msgs/Pose`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position (m).
    pub position: Point,
    /// Orientation.
    pub orientation: Quaternion,
}

impl Pose {
    /// A planar pose at `(x, y)` facing `yaw`.
    pub fn planar(x: f64, y: f64, yaw: f64) -> Self {
        Self {
            position: Point { x, y, z: 0.0 },
            orientation: Quaternion::from_yaw(yaw),
        }
    }
}

/// `geometry_msgs/PoseStamped`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    /// Stamp and frame.
    pub header: Header,
    /// The pose.
    pub pose: Pose,
}

/// `geometry_msgs/PoseWithCovariance`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    /// The pose.
    pub pose: Pose,
    /// Row-major 6 × 6 covariance of (x, y, z, roll, pitch, yaw).
    pub covariance: Covariance,
}

/// A `float64[36]`: a fixed-size array, so CDR writes no length (serde derives arrays only
/// up to 32 elements, hence by hand).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Covariance(pub [f64; 36]);

impl Default for Covariance {
    fn default() -> Self {
        Self([0.0; 36])
    }
}

impl Serialize for Covariance {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(36)?;
        for v in &self.0 {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for Covariance {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = Covariance;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("36 float64 values")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Covariance, A::Error> {
                let mut out = [0.0; 36];
                for (k, v) in out.iter_mut().enumerate() {
                    *v = seq
                        .next_element()?
                        .ok_or_else(|| serde::de::Error::invalid_length(k, &self))?;
                }
                Ok(Covariance(out))
            }
        }
        d.deserialize_tuple(36, V)
    }
}

/// `geometry_msgs/PoseWithCovarianceStamped` (what AMCL and slam_toolbox publish).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovarianceStamped {
    /// Stamp and frame.
    pub header: Header,
    /// The pose and its covariance.
    pub pose: PoseWithCovariance,
}

/// `geometry_msgs/Vector3`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Vector3 {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/Transform`: where a child frame is in its parent frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Transform {
    /// The child frame's origin in the parent frame (m).
    pub translation: Vector3,
    /// The child frame's orientation in the parent frame.
    pub rotation: Quaternion,
}

/// `geometry_msgs/TransformStamped`: one edge of the TF tree.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TransformStamped {
    /// Stamp and the parent frame.
    pub header: Header,
    /// The child frame.
    pub child_frame_id: String,
    /// The child frame in the parent frame.
    pub transform: Transform,
}

/// `tf2_msgs/TFMessage` (the `/tf` and `/tf_static` topics).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TfMessage {
    /// The transforms.
    pub transforms: Vec<TransformStamped>,
}

/// `std_msgs/ColorRGBA`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ColorRgba {
    /// Red in [0, 1].
    pub r: f32,
    /// Green in [0, 1].
    pub g: f32,
    /// Blue in [0, 1].
    pub b: f32,
    /// Alpha in [0, 1].
    pub a: f32,
}

/// `nav_msgs/MapMetaData`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MapMetaData {
    /// When the map was loaded.
    pub map_load_time: Time,
    /// Metres per cell.
    pub resolution: f32,
    /// Cells per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// World pose of cell (0, 0)'s corner.
    pub origin: Pose,
}

/// `nav_msgs/OccupancyGrid`: row-major from the origin, -1 unknown, 0–100 occupancy.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct OccupancyGrid {
    /// Stamp and frame.
    pub header: Header,
    /// Size, resolution, origin.
    pub info: MapMetaData,
    /// Occupancy per cell.
    pub data: Vec<i8>,
}

/// `sensor_msgs/CompressedImage`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CompressedImage {
    /// Stamp and frame.
    pub header: Header,
    /// Image format (`jpeg`, `png`).
    pub format: String,
    /// The compressed image.
    pub data: Vec<u8>,
}

/// `visualization_msgs/UVCoordinate`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct UvCoordinate {
    /// u.
    pub u: f32,
    /// v.
    pub v: f32,
}

/// `visualization_msgs/MeshFile`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshFile {
    /// File name.
    pub filename: String,
    /// File contents.
    pub data: Vec<u8>,
}

/// `visualization_msgs/Marker` (the ROS 2 Humble-and-later layout, with texture fields).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Marker {
    /// Stamp and frame.
    pub header: Header,
    /// Namespace.
    pub ns: String,
    /// Id within the namespace.
    pub id: i32,
    /// Shape (`Marker::POINTS`, ...).
    #[serde(rename = "type")]
    pub kind: i32,
    /// `Marker::ADD`, `DELETE` or `DELETEALL`.
    pub action: i32,
    /// Pose of the marker.
    pub pose: Pose,
    /// Size.
    pub scale: Vector3,
    /// Colour.
    pub color: ColorRgba,
    /// How long it lasts (0: forever).
    pub lifetime: Duration,
    /// Re-transform every frame.
    pub frame_locked: bool,
    /// Points of list shapes.
    pub points: Vec<Point>,
    /// Per-point colours.
    pub colors: Vec<ColorRgba>,
    /// Texture URI.
    pub texture_resource: String,
    /// Embedded texture.
    pub texture: CompressedImage,
    /// Texture coordinates.
    pub uv_coordinates: Vec<UvCoordinate>,
    /// Text of text markers.
    pub text: String,
    /// Mesh URI.
    pub mesh_resource: String,
    /// Embedded mesh.
    pub mesh_file: MeshFile,
    /// Use the mesh's materials.
    pub mesh_use_embedded_materials: bool,
}

impl Marker {
    /// `type` of a sphere.
    pub const SPHERE: i32 = 2;
    /// `type` of a line strip.
    pub const LINE_STRIP: i32 = 4;
    /// `type` of a cube list.
    pub const CUBE_LIST: i32 = 6;
    /// `type` of a sphere list.
    pub const SPHERE_LIST: i32 = 7;
    /// `type` of a points marker.
    pub const POINTS: i32 = 8;
    /// `action`: add or modify.
    pub const ADD: i32 = 0;
    /// `action`: delete every marker (of the namespace).
    pub const DELETEALL: i32 = 3;
}

/// `visualization_msgs/MarkerArray`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MarkerArray {
    /// The markers.
    pub markers: Vec<Marker>,
}

/// `nav2_msgs/action/NavigateToPose` goal.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseGoal {
    /// Where to go.
    pub pose: PoseStamped,
    /// Behaviour tree to use (empty: Nav2's default).
    pub behavior_tree: String,
}

/// `nav2_msgs/action/NavigateToPose` result (Jazzy: an error code and message).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseResult {
    /// 0 = none; 9000 + k for Nav2's errors.
    pub error_code: u16,
    /// What went wrong.
    pub error_msg: String,
}

/// `nav2_msgs/action/NavigateToPose` feedback (the Jazzy fields; later additions are read
/// past).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NavigateToPoseFeedback {
    /// Where the robot is.
    pub current_pose: PoseStamped,
    /// Time since the goal was accepted.
    pub navigation_time: Duration,
    /// Nav2's estimate of the time left.
    pub estimated_time_remaining: Duration,
    /// Recoveries run so far.
    pub number_of_recoveries: i16,
    /// Distance left along the path (m).
    pub distance_remaining: f32,
}

impl RosMessage for OccupancyGrid {
    const TYPE: &'static str = "nav_msgs/msg/OccupancyGrid";
    fn definition() -> String {
        with_deps(
            GRID,
            &[
                ("std_msgs/Header", HEADER),
                ("builtin_interfaces/Time", TIME),
                ("nav_msgs/MapMetaData", META),
                ("geometry_msgs/Pose", POSE),
                ("geometry_msgs/Point", POINT),
                ("geometry_msgs/Quaternion", QUATERNION),
            ],
        )
    }
}

impl RosMessage for PoseStamped {
    const TYPE: &'static str = "geometry_msgs/msg/PoseStamped";
    fn definition() -> String {
        with_deps(
            POSE_STAMPED,
            &[
                ("std_msgs/Header", HEADER),
                ("builtin_interfaces/Time", TIME),
                ("geometry_msgs/Pose", POSE),
                ("geometry_msgs/Point", POINT),
                ("geometry_msgs/Quaternion", QUATERNION),
            ],
        )
    }
}

impl RosMessage for PoseWithCovarianceStamped {
    const TYPE: &'static str = "geometry_msgs/msg/PoseWithCovarianceStamped";
    fn definition() -> String {
        with_deps(
            POSE_COV_STAMPED,
            &[
                ("std_msgs/Header", HEADER),
                ("builtin_interfaces/Time", TIME),
                ("geometry_msgs/PoseWithCovariance", POSE_COV),
                ("geometry_msgs/Pose", POSE),
                ("geometry_msgs/Point", POINT),
                ("geometry_msgs/Quaternion", QUATERNION),
            ],
        )
    }
}

impl RosMessage for MarkerArray {
    const TYPE: &'static str = "visualization_msgs/msg/MarkerArray";
    fn definition() -> String {
        with_deps(
            MARKER_ARRAY,
            &[
                ("visualization_msgs/Marker", MARKER),
                ("std_msgs/Header", HEADER),
                ("builtin_interfaces/Time", TIME),
                ("geometry_msgs/Pose", POSE),
                ("geometry_msgs/Point", POINT),
                ("geometry_msgs/Quaternion", QUATERNION),
                ("geometry_msgs/Vector3", VECTOR3),
                ("std_msgs/ColorRGBA", COLOR),
                ("builtin_interfaces/Duration", DURATION),
                ("sensor_msgs/CompressedImage", IMAGE),
                ("visualization_msgs/UVCoordinate", UV),
                ("visualization_msgs/MeshFile", MESH),
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cdr::{decode, encode};

    #[test]
    fn yaw_survives_a_quaternion() {
        for yaw in [-3.0, -1.0, 0.0, 0.5, 3.1] {
            assert!((Quaternion::from_yaw(yaw).yaw() - yaw).abs() < 1e-12);
        }
    }

    #[test]
    fn a_covariance_is_36_doubles_without_a_length() {
        let mut p = PoseWithCovarianceStamped {
            header: Header::default(),
            pose: PoseWithCovariance {
                pose: Pose::planar(1.0, 2.0, 0.0),
                covariance: Covariance::default(),
            },
        };
        p.pose.covariance.0[35] = 0.25;
        let b = encode(&p);
        // header (4 + 4 + 4-byte empty-string length... aligned) then 7 doubles, then 36.
        assert_eq!(&b[b.len() - 8..], &0.25f64.to_le_bytes());
        let body = b.len() - 4;
        assert_eq!(body, 16 + 7 * 8 + 36 * 8);
        assert_eq!(decode::<PoseWithCovarianceStamped>(&b).unwrap(), p);
    }

    #[test]
    fn time_converts_both_ways() {
        let t = Time::from_secs(12.25);
        assert_eq!((t.sec, t.nanosec), (12, 250_000_000));
        assert_eq!(t.nanos(), 12_250_000_000);
        assert_eq!(Time::from_secs(f64::NAN), Time::default());
    }

    #[test]
    fn occupancy_grid_layout_matches_the_definition() {
        let m = OccupancyGrid {
            header: Header {
                stamp: Time { sec: 1, nanosec: 2 },
                frame_id: String::new(),
            },
            info: MapMetaData {
                map_load_time: Time::default(),
                resolution: 0.05,
                width: 2,
                height: 1,
                origin: Pose::planar(0.0, 0.0, 0.0),
            },
            data: vec![-1, 100],
        };
        let b = encode(&m);
        // Body offsets: stamp 0..8, frame_id length 8..12 (0 bytes, no NUL for empty?).
        let body = &b[4..];
        assert_eq!(&body[0..8], &[1, 0, 0, 0, 2, 0, 0, 0]);
        // The data sequence ends the message: length 2, then 0xff, 0x64.
        assert_eq!(&b[b.len() - 6..], &[2, 0, 0, 0, 0xff, 100]);
        assert_eq!(decode::<OccupancyGrid>(&b).unwrap(), m);
    }

    #[test]
    fn definitions_name_every_dependency_once() {
        for def in &[
            OccupancyGrid::definition(),
            PoseStamped::definition(),
            PoseWithCovarianceStamped::definition(),
            MarkerArray::definition(),
        ] {
            let mut named: Vec<&str> = def
                .lines()
                .filter_map(|l| l.strip_prefix("MSG: "))
                .collect();
            let n = named.len();
            named.sort_unstable();
            named.dedup();
            assert_eq!(named.len(), n, "{def}");
            // Every complex field type is defined below.
            for line in def
                .lines()
                .filter(|l| !l.starts_with("MSG: ") && !l.starts_with('='))
            {
                let ty = line.split_whitespace().next().unwrap_or("");
                let base = ty.split('[').next().unwrap();
                if base.contains('/') {
                    assert!(named.contains(&base), "{base} is not defined in {def}");
                }
            }
        }
    }
}
