//! A map from a recording: the last `nav_msgs/OccupancyGrid` of an MCAP file (ROS 2 CDR).
//!
//! This is how a user's bag becomes a reproducible run: `ros2 bag record /map` (MCAP is
//! rosbag2's default storage since Iron), then `frontier explore --map recording.mcap`.
//! The last map on the topic is the most complete one a SLAM node published.

use grid::GridMap;

use crate::cdr::decode;
use crate::msgs::OccupancyGrid;
use crate::occupancy::{MapMsgError, map_from_msg};

/// The longest record read: the largest map message accepted
/// ([`crate::occupancy::MAX_CELLS`] cells) and its header.
const MAX_RECORD_BYTES: usize = crate::occupancy::MAX_CELLS + (1 << 20);

/// How many times its own size a recording's records may add up to once decompressed (a
/// map of unknown cells compresses about this well).
const MAX_EXPANSION: usize = 1024;

/// Schema names an OccupancyGrid channel may carry (rosbag2 writes the first).
const GRID_SCHEMAS: [&str; 2] = ["nav_msgs/msg/OccupancyGrid", "nav_msgs/OccupancyGrid"];

/// Why a recording gave no map.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The bytes are not a readable MCAP file.
    #[error("expected an MCAP file, found: {0}")]
    Mcap(String),
    /// No channel carries OccupancyGrid messages (or the asked topic is missing).
    #[error("expected {expected}, found {found}")]
    NoMap {
        /// What was looked for.
        expected: String,
        /// The recording's topics and their types.
        found: String,
    },
    /// Several OccupancyGrid topics and none named `/map`: the caller must choose.
    #[error("several OccupancyGrid topics ({0}): choose one with --topic")]
    Ambiguous(String),
    /// The chosen topic is not CDR-encoded OccupancyGrid.
    #[error("topic {topic}: expected nav_msgs/msg/OccupancyGrid in cdr encoding, found {found}")]
    WrongType {
        /// The topic.
        topic: String,
        /// Its schema and encoding.
        found: String,
    },
    /// The last message does not decode.
    #[error("topic {topic}, message at {log_time} ns: {why}")]
    Decode {
        /// The topic.
        topic: String,
        /// The message's log time.
        log_time: u64,
        /// What failed.
        why: String,
    },
    /// The last message decodes but is not a usable map.
    #[error("topic {topic}, message at {log_time} ns: {source}")]
    BadMap {
        /// The topic.
        topic: String,
        /// The message's log time.
        log_time: u64,
        /// What is wrong with it.
        source: MapMsgError,
    },
}

/// Recordings larger than this are refused before reading (the map message itself is at
/// most [`crate::occupancy::MAX_CELLS`] bytes).
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// The last OccupancyGrid on `topic` of the MCAP recording at `path` ([`last_map`]); the
/// error names the file. Used by every front end that takes a recording as a map.
pub fn load_map(path: &std::path::Path, topic: Option<&str>) -> Result<GridMap, String> {
    let reading = |e: std::io::Error| format!("reading {}: {e}", path.display());
    let len = std::fs::metadata(path).map_err(reading)?.len();
    if len > MAX_FILE_BYTES {
        return Err(format!(
            "{}: expected a recording of at most {MAX_FILE_BYTES} bytes, found {len}; record \
             only the map topic (ros2 bag record /map)",
            path.display()
        ));
    }
    let bytes = std::fs::read(path).map_err(reading)?;
    let (map, _) = last_map(&bytes, topic).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(map)
}

/// The messages of the MCAP file in `bytes`, chunks decompressed, with every record's length
/// bounded before its bytes are allocated: by [`MAX_RECORD_BYTES`] and by [`MAX_EXPANSION`]
/// times the file's size. (`mcap::MessageStream` trusts a length read from a chunk's
/// decompressed bytes, so a corrupt chunk could make it allocate exabytes and abort.)
fn messages(bytes: &[u8]) -> impl Iterator<Item = mcap::McapResult<mcap::Message<'static>>> + '_ {
    let limit = MAX_RECORD_BYTES.min(bytes.len().saturating_mul(MAX_EXPANSION).max(1 << 20));
    let mut reader = mcap::sans_io::MessageReader::new_with_options(
        mcap::sans_io::LinearReaderOptions::default().with_record_length_limit(limit),
    );
    let mut rest = bytes;
    std::iter::from_fn(move || {
        loop {
            match reader.next_event()? {
                Ok(mcap::sans_io::MessageReadEvent::ReadRequest(need)) => {
                    let n = need.min(rest.len());
                    reader.insert(n).copy_from_slice(&rest[..n]);
                    reader.notify_read(n);
                    rest = &rest[n..];
                }
                Ok(mcap::sans_io::MessageReadEvent::Message(m)) => return Some(Ok(m)),
                Err(e) => return Some(Err(e)),
            }
        }
    })
}

/// The last OccupancyGrid on `topic` (default: the recording's only OccupancyGrid topic, or
/// `/map` among several) of the MCAP file in `bytes`, with its topic name.
pub fn last_map(bytes: &[u8], topic: Option<&str>) -> Result<(GridMap, String), RecordError> {
    // Pass 1: the topics and their types; the latest message on each grid topic.
    let mut topics: Vec<(String, String, String)> = Vec::new(); // topic, schema, encoding
    let mut latest: Vec<(String, u64, Vec<u8>)> = Vec::new();
    for m in messages(bytes) {
        let m = m.map_err(|e| RecordError::Mcap(e.to_string()))?;
        let ch = &m.channel;
        let schema = ch
            .schema
            .as_ref()
            .map(|s| s.name.clone())
            .unwrap_or_default();
        if !topics.iter().any(|(t, _, _)| *t == ch.topic) {
            topics.push((
                ch.topic.clone(),
                schema.clone(),
                ch.message_encoding.clone(),
            ));
        }
        let wanted = match topic {
            Some(t) => ch.topic == t,
            None => GRID_SCHEMAS.contains(&schema.as_str()),
        };
        if !wanted {
            continue;
        }
        match latest.iter_mut().find(|(t, _, _)| *t == ch.topic) {
            Some(slot) if slot.1 > m.log_time => {}
            Some(slot) => {
                slot.1 = m.log_time;
                slot.2 = m.data.into_owned();
            }
            None => latest.push((ch.topic.clone(), m.log_time, m.data.into_owned())),
        }
    }
    let listing = || {
        if topics.is_empty() {
            "no messages".to_string()
        } else {
            topics
                .iter()
                .map(|(t, s, _)| format!("{t} ({s})"))
                .collect::<Vec<_>>()
                .join(", ")
        }
    };
    let chosen = match (topic, latest.len()) {
        (Some(t), 0) => {
            return Err(RecordError::NoMap {
                expected: format!("messages on topic {t}"),
                found: listing(),
            });
        }
        (None, 0) => {
            return Err(RecordError::NoMap {
                expected: "a nav_msgs/msg/OccupancyGrid topic".into(),
                found: listing(),
            });
        }
        (_, 1) => latest.pop().expect("one"),
        (_, _) => match latest.iter().position(|(t, _, _)| t == "/map") {
            Some(k) => latest.swap_remove(k),
            None => {
                let names: Vec<&str> = latest.iter().map(|(t, _, _)| t.as_str()).collect();
                return Err(RecordError::Ambiguous(names.join(", ")));
            }
        },
    };
    let (name, log_time, data) = chosen;
    let (_, schema, encoding) = topics.iter().find(|(t, _, _)| *t == name).expect("listed");
    if !GRID_SCHEMAS.contains(&schema.as_str()) || encoding != "cdr" {
        return Err(RecordError::WrongType {
            topic: name,
            found: format!("{schema} in {encoding} encoding"),
        });
    }
    let msg: OccupancyGrid = decode(&data).map_err(|e| RecordError::Decode {
        topic: name.clone(),
        log_time,
        why: e.to_string(),
    })?;
    let map = map_from_msg(&msg).map_err(|source| RecordError::BadMap {
        topic: name.clone(),
        log_time,
        source,
    })?;
    Ok((map, name))
}
