//! The robot's pose from TF: the latest transform of each frame to its parent (`/tf` and
//! `/tf_static`), chained from the robot's base frame to the map frame.
//!
//! Robots whose localisation publishes no pose topic (Cartographer, or slam_toolbox set up
//! without one) give their pose only as TF: map → odom from the SLAM node, odom →
//! base_footprint → base_link from odometry and the robot's description. The tree keeps the
//! latest transform of each child frame, as explore_lite's costmap reads the latest
//! available; the node moves the robot's goals at map rate, so interpolating between
//! stamps (tf2's buffer) would change nothing it decides. A lookup finds the frames'
//! common ancestor, so the map frame need not be the root. The three rigid-body operations
//! (compose, invert, apply a rotation) are written here rather than taken from a linear
//! algebra crate, which frontier needs nowhere else.

use std::collections::HashMap;

use record::msgs::{Point, Pose, Quaternion, TransformStamped, Vector3};

/// Longest chain of frames followed (a longer one is taken for a loop).
const MAX_DEPTH: usize = 64;

/// Most frames kept: a robot's tree has tens; a stream naming ever new frames is refused
/// past this rather than growing without bound.
pub const MAX_FRAMES: usize = 4096;

/// A frame's name as the tree keys it: without the leading `/` of ROS 1 style names
/// (`/map` and `map` are one frame, as tf2 has them).
pub fn frame_name(frame: &str) -> &str {
    frame.trim_start_matches('/')
}

/// The robot's x, y and yaw from a pose message (a pose topic's), or what is wrong with it:
/// a non-finite position or orientation, or an orientation of zero length, would later be
/// sent to Nav2 as the start pose of `return_to_init`.
pub fn planar_pose(p: &Pose) -> Result<(f64, f64, f64), String> {
    let Point { x, y, z } = p.position;
    let Quaternion {
        x: qx,
        y: qy,
        z: qz,
        w: qw,
    } = p.orientation;
    let norm = (qx * qx + qy * qy + qz * qz + qw * qw).sqrt();
    if ![x, y, z, norm].iter().all(|v| v.is_finite()) || norm < 1e-9 {
        return Err(format!(
            "expected finite numbers and an orientation of non-zero length, found position \
             ({x}, {y}, {z}), orientation ({qx}, {qy}, {qz}, {qw})"
        ));
    }
    Ok((x, y, p.orientation.yaw()))
}

/// A rigid transform: rotate by `q` (unit quaternion x, y, z, w), then translate by `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rigid {
    t: [f64; 3],
    q: [f64; 4],
}

impl Rigid {
    const IDENTITY: Rigid = Rigid {
        t: [0.0; 3],
        q: [0.0, 0.0, 0.0, 1.0],
    };

    /// `self ∘ other`: first `other`, then `self`.
    fn then(&self, other: &Rigid) -> Rigid {
        let r = rotate(self.q, other.t);
        Rigid {
            t: [self.t[0] + r[0], self.t[1] + r[1], self.t[2] + r[2]],
            q: mul(self.q, other.q),
        }
    }

    fn inverse(&self) -> Rigid {
        let qi = [-self.q[0], -self.q[1], -self.q[2], self.q[3]];
        let r = rotate(qi, self.t);
        Rigid {
            t: [-r[0], -r[1], -r[2]],
            q: qi,
        }
    }
}

/// Hamilton product `a b`.
fn mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// `v` rotated by the unit quaternion `q`.
fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = mul(mul(q, [v[0], v[1], v[2], 0.0]), [-q[0], -q[1], -q[2], q[3]]);
    [p[0], p[1], p[2]]
}

/// The latest transform of every frame to its parent.
#[derive(Clone, Debug, Default)]
pub struct TfTree {
    /// Child frame → (parent frame, the child in the parent).
    parent: HashMap<String, (String, Rigid)>,
}

impl TfTree {
    /// An empty tree.
    pub fn new() -> Self {
        Self::default()
    }

    /// Record `t` (the child frame in its parent), replacing the child's previous one.
    /// A transform with a non-finite number, a rotation of zero length, an empty frame
    /// name, a frame as its own parent, or a new frame beyond [`MAX_FRAMES`] is refused,
    /// with what is wrong; the tree is then unchanged.
    pub fn set(&mut self, t: &TransformStamped) -> Result<(), String> {
        let (parent, child) = (
            frame_name(&t.header.frame_id),
            frame_name(&t.child_frame_id),
        );
        if parent.is_empty() || child.is_empty() {
            return Err(format!(
                "transform '{parent}' → '{child}': expected two frame names, found an empty one"
            ));
        }
        if parent == child {
            return Err(format!(
                "transform '{parent}' → '{child}': expected two different frames"
            ));
        }
        let Vector3 { x, y, z } = t.transform.translation;
        let Quaternion {
            x: qx,
            y: qy,
            z: qz,
            w: qw,
        } = t.transform.rotation;
        let norm = (qx * qx + qy * qy + qz * qz + qw * qw).sqrt();
        if ![x, y, z, norm].iter().all(|v| v.is_finite()) || norm < 1e-9 {
            return Err(format!(
                "transform '{parent}' → '{child}': expected finite numbers and a rotation of \
                 non-zero length, found translation ({x}, {y}, {z}), rotation ({qx}, {qy}, \
                 {qz}, {qw})"
            ));
        }
        if self.parent.len() >= MAX_FRAMES && !self.parent.contains_key(child) {
            return Err(format!(
                "transform '{parent}' → '{child}': already {MAX_FRAMES} frames, expected no more"
            ));
        }
        let rigid = Rigid {
            t: [x, y, z],
            q: [qx / norm, qy / norm, qz / norm, qw / norm],
        };
        self.parent
            .insert(child.to_string(), (parent.to_string(), rigid));
        Ok(())
    }

    /// The frames from `frame` up to its root, each with `frame`'s transform into it.
    fn chain<'a>(&'a self, frame: &'a str) -> Result<Vec<(&'a str, Rigid)>, String> {
        let mut out = Vec::new();
        let mut at: &str = frame;
        let mut acc = Rigid::IDENTITY;
        out.push((frame, acc));
        while let Some((p, t)) = self.parent.get(at) {
            acc = t.then(&acc);
            out.push((p.as_str(), acc));
            at = p.as_str();
            if out.len() > MAX_DEPTH {
                return Err(format!(
                    "the frames above '{frame}' go round in a loop (more than {MAX_DEPTH} links)"
                ));
            }
        }
        Ok(out)
    }

    /// Where frame `source` is in frame `target`: x, y and the yaw of its heading (the
    /// pose of a robot whose base frame is `source` on a map in `target`).
    pub fn lookup(&self, target: &str, source: &str) -> Result<(f64, f64, f64), String> {
        let (target, source) = (frame_name(target), frame_name(source));
        let up = self.chain(source)?;
        let down = self.chain(target)?;
        // The lowest frame of the source's chain that the target's chain also holds.
        for (frame, source_in_frame) in &up {
            if let Some((_, target_in_frame)) = down.iter().find(|(f, _)| f == frame) {
                let r = target_in_frame.inverse().then(source_in_frame);
                let q = Quaternion {
                    x: r.q[0],
                    y: r.q[1],
                    z: r.q[2],
                    w: r.q[3],
                };
                return Ok((r.t[0], r.t[1], q.yaw()));
            }
        }
        let root = |c: &[(&str, Rigid)]| c.last().map_or("", |f| f.0).to_string();
        Err(format!(
            "no transform from '{source}' to '{target}' yet: '{source}' leads up to '{}', \
             '{target}' to '{}'",
            root(&up),
            root(&down)
        ))
    }
}

#[cfg(test)]
mod tests {
    /// A pose with a NaN orientation was taken (only x and y were checked), and its NaN
    /// quaternion later went to Nav2 as the goal of `return_to_init`.
    #[test]
    fn a_pose_with_a_non_finite_or_zero_orientation_is_refused() {
        use super::planar_pose;
        use record::msgs::{Pose, Quaternion};
        let good = Pose::planar(1.0, 2.0, 0.5);
        let (x, y, yaw) = planar_pose(&good).unwrap();
        assert_eq!((x, y), (1.0, 2.0));
        assert!((yaw - 0.5).abs() < 1e-12);
        for q in [
            Quaternion {
                x: 0.0,
                y: 0.0,
                z: f64::NAN,
                w: 1.0,
            },
            Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.0,
                w: f64::INFINITY,
            },
            Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.0,
                w: 0.0,
            },
        ] {
            let mut p = good;
            p.orientation = q;
            let e = planar_pose(&p).unwrap_err();
            assert!(e.starts_with("expected finite numbers"), "{e}");
            assert!(e.contains("orientation ("), "{e}");
        }
        let mut p = good;
        p.position.x = f64::NAN;
        assert!(planar_pose(&p).is_err());
    }

    use super::*;
    use record::msgs::{Header, Transform};

    fn edge(parent: &str, child: &str, x: f64, y: f64, z: f64, yaw: f64) -> TransformStamped {
        TransformStamped {
            header: Header {
                frame_id: parent.into(),
                ..Header::default()
            },
            child_frame_id: child.into(),
            transform: Transform {
                translation: Vector3 { x, y, z },
                rotation: Quaternion::from_yaw(yaw),
            },
        }
    }

    fn close(a: (f64, f64, f64), b: (f64, f64, f64)) -> bool {
        let dyaw = (a.2 - b.2 + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9 && dyaw.abs() < 1e-9
    }

    #[test]
    fn a_planar_chain_composes_as_poses_do() {
        use std::f64::consts::FRAC_PI_2;
        let mut tf = TfTree::new();
        // The odometry frame 2 m east of the map origin, turned 90°; the robot 1 m ahead of
        // the odometry origin, turned 90° more; its base_link 0.1 m above base_footprint.
        tf.set(&edge("map", "odom", 2.0, 0.0, 0.0, FRAC_PI_2))
            .unwrap();
        tf.set(&edge("odom", "base_footprint", 1.0, 0.0, 0.0, FRAC_PI_2))
            .unwrap();
        tf.set(&edge("base_footprint", "base_link", 0.0, 0.0, 0.1, 0.0))
            .unwrap();
        let p = tf.lookup("map", "base_link").unwrap();
        assert!(close(p, (2.0, 1.0, std::f64::consts::PI)), "{p:?}");
        // Leading slashes (ROS 1 style) name the same frames; a frame in itself is the origin.
        assert!(close(tf.lookup("/map", "/base_link").unwrap(), p));
        assert!(close(tf.lookup("odom", "odom").unwrap(), (0.0, 0.0, 0.0)));
        // The map in the robot's frame is the inverse.
        let (x, y, yaw) = tf.lookup("base_link", "map").unwrap();
        let (c, s) = (p.2.cos(), p.2.sin());
        assert!(close(
            (x, y, yaw),
            (-(c * p.0 + s * p.1), s * p.0 - c * p.1, -p.2)
        ));
    }

    #[test]
    fn the_latest_transform_of_a_frame_replaces_the_earlier() {
        let mut tf = TfTree::new();
        tf.set(&edge("map", "odom", 0.0, 0.0, 0.0, 0.0)).unwrap();
        tf.set(&edge("odom", "base_link", 1.0, 0.0, 0.0, 0.0))
            .unwrap();
        tf.set(&edge("odom", "base_link", 3.0, 4.0, 0.0, 0.5))
            .unwrap();
        assert!(close(
            tf.lookup("map", "base_link").unwrap(),
            (3.0, 4.0, 0.5)
        ));
    }

    #[test]
    fn frames_under_a_common_root_meet_there() {
        // map and odom both hang under a world frame, as with several SLAM maps.
        let mut tf = TfTree::new();
        tf.set(&edge("world", "map", 10.0, 0.0, 0.0, 0.0)).unwrap();
        tf.set(&edge("world", "odom", 12.0, 3.0, 0.0, 0.0)).unwrap();
        tf.set(&edge("odom", "base_link", 1.0, 1.0, 0.0, 0.25))
            .unwrap();
        assert!(close(
            tf.lookup("map", "base_link").unwrap(),
            (3.0, 4.0, 0.25)
        ));
    }

    /// The tree against a slow oracle: random planar chains, each pose composed by hand
    /// in 2-D (x, y, yaw), equal to the tree's lookup.
    #[test]
    fn random_planar_chains_equal_poses_composed_by_hand() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let n = 1 + (rnd() * 6.0) as usize;
            let mut tf = TfTree::new();
            let (mut x, mut y, mut yaw) = (0.0f64, 0.0f64, 0.0f64);
            for k in 0..n {
                let (dx, dy, dyaw) = (rnd() * 20.0 - 10.0, rnd() * 20.0 - 10.0, rnd() * 7.0 - 3.5);
                tf.set(&edge(
                    &format!("f{k}"),
                    &format!("f{}", k + 1),
                    dx,
                    dy,
                    rnd(),
                    dyaw,
                ))
                .unwrap();
                x += yaw.cos() * dx - yaw.sin() * dy;
                y += yaw.sin() * dx + yaw.cos() * dy;
                yaw += dyaw;
            }
            let got = tf.lookup("f0", &format!("f{n}")).unwrap();
            let d = (got.0 - x).abs().max((got.1 - y).abs());
            let dyaw = (got.2 - yaw + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(
                d < 1e-9 && dyaw.abs() < 1e-9,
                "{got:?} against {x}, {y}, {yaw}"
            );
        }
    }

    #[test]
    fn missing_links_loops_and_bad_numbers_say_what_is_wrong() {
        let mut tf = TfTree::new();
        tf.set(&edge("odom", "base_link", 1.0, 0.0, 0.0, 0.0))
            .unwrap();
        let e = tf.lookup("map", "base_link").unwrap_err();
        assert_eq!(
            e,
            "no transform from 'base_link' to 'map' yet: 'base_link' leads up to 'odom', \
             'map' to 'map'"
        );
        tf.set(&edge("base_link", "odom", 0.0, 0.0, 0.0, 0.0))
            .unwrap();
        assert!(tf.lookup("map", "base_link").unwrap_err().contains("loop"));
        let mut bad = edge("map", "odom", f64::NAN, 0.0, 0.0, 0.0);
        assert!(tf.set(&bad).unwrap_err().contains("finite"));
        bad = edge("map", "odom", 0.0, 0.0, 0.0, 0.0);
        bad.transform.rotation = Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 0.0,
        };
        assert!(tf.set(&bad).unwrap_err().contains("non-zero length"));
        assert!(tf.set(&edge("map", "map", 0.0, 0.0, 0.0, 0.0)).is_err());
        assert!(tf.set(&edge("", "odom", 0.0, 0.0, 0.0, 0.0)).is_err());
    }

    #[test]
    fn a_stream_of_new_frames_stops_at_the_bound() {
        let mut tf = TfTree::new();
        for k in 0..MAX_FRAMES {
            tf.set(&edge("map", &format!("f{k}"), 0.0, 0.0, 0.0, 0.0))
                .unwrap();
        }
        let e = tf
            .set(&edge("map", "one_more", 0.0, 0.0, 0.0, 0.0))
            .unwrap_err();
        assert!(e.contains("already 4096 frames"), "{e}");
        // A frame already kept is still updated.
        tf.set(&edge("map", "f7", 1.0, 2.0, 0.0, 0.0)).unwrap();
        assert!(close(tf.lookup("map", "f7").unwrap(), (1.0, 2.0, 0.0)));
    }
}
