//! CDR with its encapsulation header, as ROS 2 puts it on the wire and MCAP stores it.
//!
//! A serialized ROS 2 message is a 4-byte encapsulation header (`00 01 00 00` for little-endian
//! plain CDR, `00 00 00 00` for big-endian) followed by the CDR body; alignment counts from
//! the body's start.

use byteorder::{BigEndian, LittleEndian};
use serde::{Serialize, de::DeserializeOwned};

/// Encapsulation header of little-endian plain CDR.
pub const CDR_LE: [u8; 4] = [0, 1, 0, 0];

/// Why bytes are not a message of the expected type.
#[derive(Debug, thiserror::Error)]
pub enum CdrError {
    /// Shorter than the 4-byte encapsulation header.
    #[error("expected a 4-byte CDR encapsulation header, found {0} bytes")]
    Short(usize),
    /// An encapsulation this reader does not speak (e.g. XCDR2 or parameter lists).
    #[error("expected plain CDR (encapsulation 0 or 1), found encapsulation {0}")]
    Encapsulation(u16),
    /// The body does not decode as the message.
    #[error("{0}")]
    Body(String),
}

/// Serialize `msg` as little-endian CDR with its encapsulation header.
pub fn encode<T: Serialize>(msg: &T) -> Vec<u8> {
    let body = cdr_encoding::to_vec::<T, LittleEndian>(msg)
        .expect("CDR serialization of plain structs, strings and sequences cannot fail");
    let mut out = Vec::with_capacity(body.len() + 4);
    out.extend_from_slice(&CDR_LE);
    out.extend_from_slice(&body);
    out
}

/// Deserialize a message from CDR bytes with their encapsulation header.
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, CdrError> {
    decode_prefix(bytes).map(|p| p.value)
}

/// The leading fields of a message, decoded as `T`, and where the rest of its body begins.
pub struct Prefix<T> {
    /// The fields decoded.
    pub value: T,
    /// Bytes of the body `value` took.
    pub consumed: usize,
    /// Whether the body is big-endian.
    pub big_endian: bool,
}

impl<T> Prefix<T> {
    /// The body of the message `bytes` this prefix was decoded from: the bytes after the
    /// encapsulation header, from whose start CDR's alignment counts.
    pub fn body<'a>(&self, bytes: &'a [u8]) -> &'a [u8] {
        &bytes[4..]
    }
}

/// Deserialize the first fields of a message from CDR bytes with their encapsulation header
/// as `T` (a struct of the message's leading fields), leaving the rest unread: how a large
/// field is read in place rather than copied.
pub fn decode_prefix<T: DeserializeOwned>(bytes: &[u8]) -> Result<Prefix<T>, CdrError> {
    if bytes.len() < 4 {
        return Err(CdrError::Short(bytes.len()));
    }
    let kind = u16::from_be_bytes([bytes[0], bytes[1]]);
    let body = &bytes[4..];
    let r = match kind {
        0 => cdr_encoding::from_bytes::<T, BigEndian>(body),
        1 => cdr_encoding::from_bytes::<T, LittleEndian>(body),
        k => return Err(CdrError::Encapsulation(k)),
    };
    let (value, consumed) = r.map_err(|e| CdrError::Body(e.to_string()))?;
    Ok(Prefix {
        value,
        consumed,
        big_endian: kind == 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msgs::{Point, Pose, PoseStamped, Quaternion};

    #[test]
    fn pose_stamped_round_trips_and_has_the_ros_layout() {
        let mut p = PoseStamped::default();
        p.header.stamp.sec = 7;
        p.header.frame_id = "map".into();
        p.pose = Pose {
            position: Point {
                x: 1.5,
                y: -2.0,
                z: 0.0,
            },
            orientation: Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.0,
                w: 1.0,
            },
        };
        let bytes = encode(&p);
        // header: sec (4) nanosec (4) frame_id (len 4 + "map\0"), then pad to 8 for f64s.
        assert_eq!(&bytes[..4], &CDR_LE);
        assert_eq!(&bytes[4..8], &7i32.to_le_bytes());
        assert_eq!(&bytes[12..16], &4u32.to_le_bytes());
        assert_eq!(&bytes[16..20], b"map\0");
        assert_eq!(&bytes[20..28], &1.5f64.to_le_bytes());
        assert_eq!(bytes.len(), 4 + 16 + 7 * 8);
        assert_eq!(decode::<PoseStamped>(&bytes).unwrap(), p);
    }

    /// `tf2_msgs/TFMessage` as a ROS 2 node sends it, written out byte by byte.
    #[test]
    fn tf_message_has_the_ros_layout() {
        use crate::msgs::{TfMessage, Transform, TransformStamped, Vector3};
        let mut body = Vec::new();
        body.extend(1u32.to_le_bytes()); // one transform
        body.extend(7i32.to_le_bytes()); // stamp
        body.extend(9u32.to_le_bytes());
        body.extend(4u32.to_le_bytes()); // parent frame
        body.extend(b"map\0");
        body.extend(5u32.to_le_bytes()); // child frame
        body.extend(b"odom\0");
        body.extend([0u8; 3]); // to the f64s' alignment, 8, at 32
        for v in [1.0f64, -2.0, 0.5, 0.0, 0.0, 0.6, 0.8] {
            body.extend(v.to_le_bytes());
        }
        let mut bytes = CDR_LE.to_vec();
        bytes.extend(&body);
        let mut t = TransformStamped::default();
        t.header.stamp.sec = 7;
        t.header.stamp.nanosec = 9;
        t.header.frame_id = "map".into();
        t.child_frame_id = "odom".into();
        t.transform = Transform {
            translation: Vector3 {
                x: 1.0,
                y: -2.0,
                z: 0.5,
            },
            rotation: Quaternion {
                x: 0.0,
                y: 0.0,
                z: 0.6,
                w: 0.8,
            },
        };
        let m = TfMessage {
            transforms: vec![t],
        };
        assert_eq!(decode::<TfMessage>(&bytes).unwrap(), m);
        assert_eq!(encode(&m), bytes);
    }

    #[test]
    fn short_or_foreign_bytes_are_errors() {
        assert!(matches!(
            decode::<PoseStamped>(&[0, 1]),
            Err(CdrError::Short(2))
        ));
        assert!(matches!(
            decode::<PoseStamped>(&[0, 7, 0, 0, 1, 2]),
            Err(CdrError::Encapsulation(7))
        ));
        assert!(matches!(
            decode::<PoseStamped>(&[0, 1, 0, 0, 1, 2]),
            Err(CdrError::Body(_))
        ));
    }
}
