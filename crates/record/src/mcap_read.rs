//! A map from a recording: the last `nav_msgs/OccupancyGrid` of an MCAP file (ROS 2 CDR).
//!
//! This is how a user's bag becomes a reproducible run: `ros2 bag record /map` (MCAP is
//! rosbag2's default storage since Iron), then `frontier explore --map recording.mcap`.
//! The last map on the topic is the most complete one a SLAM node published.
//!
//! A recording is read a record at a time, never whole (a long run's recording can be
//! gigabytes around a map of a few megabytes). Given the memory a caller may spend, a record
//! longer than that memory is refused from its length, before it is read, and a map whose
//! loading would need more (the message, the copy of it kept while the rest of the
//! recording is read, and the grid made of it) from its header, before its cells are copied,
//! with the refusal every map loader gives (`grid::io::check_fits`).

use std::io::Read;

use grid::GridMap;
use grid::memory::Available;

use crate::cdr::{decode, decode_prefix};
use crate::msgs::{Header, MapMetaData};
use crate::occupancy::{MapMsgError, cells_of, map_from_bytes};

/// Bytes a map message record holds besides its cells: the record's own fields, the CDR
/// header, the message's header and metadata (about 130 bytes) and its frame id. Kept
/// small so that a map over the cell limit is refused from its record length, before its
/// cells are decompressed; frame ids are a few characters.
const MAX_MAP_FIELD_BYTES: usize = 4 << 10;

/// The longest record read: the largest map message accepted
/// ([`crate::occupancy::MAX_CELLS`] cells) and its other fields.
const MAX_RECORD_BYTES: usize = crate::occupancy::MAX_CELLS + MAX_MAP_FIELD_BYTES;

/// How many times its own size a recording's records may add up to once decompressed (a
/// map of unknown cells compresses about this well).
const MAX_EXPANSION: usize = 1024;

/// Schema names an OccupancyGrid channel may carry (rosbag2 writes the first).
const GRID_SCHEMAS: [&str; 2] = ["nav_msgs/msg/OccupancyGrid", "nav_msgs/OccupancyGrid"];

/// Bytes loading a map message holds per cell besides the message as read: the copy of its
/// cells kept while the rest of the recording is read, and the grid made of it (a byte
/// each). The three counted together bound the peak from above: the reader, and the message
/// in it, is gone before the grid is made, which leaves room for the reader's other buffers
/// (measured on a 1500 x 1200 map: 3.7 MB held at the peak, 5.4 MB estimated).
const BYTES_PER_CELL: u64 = 2;

/// How to make a recording's map fit in memory, said in its refusal.
const MAP_FIX: &str = "record the map with fewer, larger cells (a coarser resolution)";

/// How to make a recording's records fit in memory, said in the refusal of one too long.
const RECORD_FIX: &str =
    "record only the map topic (ros2 bag record /map), and the map with fewer, larger cells";

/// Bytes read from a recording's file at a time (a record longer than this is read at once).
const READ_BUFFER_BYTES: usize = 64 << 10;

/// Why a recording gave no map.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The bytes are not a readable MCAP file.
    #[error("expected an MCAP file, found: {0}")]
    Mcap(String),
    /// A checksum the file carries does not match its bytes.
    #[error("damaged: {0} (the file changed after it was written)")]
    Damaged(String),
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
    /// A message longer than the largest map message accepted, or than the file could hold
    /// compressed; refused from its length, before its bytes are decompressed.
    #[error("expected messages of at most {limit} bytes ({why}), found one of {len} bytes")]
    TooLong {
        /// The message record's length in bytes.
        len: u64,
        /// The longest record read.
        limit: usize,
        /// Where the limit comes from.
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
    /// A record longer than the memory left; refused from its length, before it is read.
    #[error("{0}")]
    RecordOutOfMemory(grid::io::MapErrorKind),
    /// Loading the last map would need more memory than is left; refused from the
    /// message's header, before its cells are copied or decoded.
    #[error("topic {topic}, message at {log_time} ns: {source}")]
    OutOfMemory {
        /// The topic.
        topic: String,
        /// The message's log time.
        log_time: u64,
        /// The map's size, the bytes its loading needs and the limit.
        source: grid::io::MapErrorKind,
    },
    /// The recording could not be read.
    #[error("cannot read: {0}")]
    Read(#[source] std::io::Error),
}

impl RecordError {
    /// A compressed chunk whose bytes the decompressor refused (`why`): damage, since a
    /// chunk's checksum is of its decompressed bytes and cannot be checked first.
    fn undecompressed(why: impl std::fmt::Display) -> Self {
        RecordError::Damaged(format!("a compressed chunk does not decompress ({why})"))
    }
}

/// Recordings larger than this are refused before reading (the map message itself is at
/// most [`crate::occupancy::MAX_CELLS`] bytes).
pub const MAX_FILE_BYTES: u64 = 8 << 30;

/// The last OccupancyGrid on `topic` of the MCAP recording at `path`, with its topic name,
/// read a record at a time within `memory` ([`read_last_map`]); the error names the file.
/// Used by every front end that takes a recording as a map, with the memory it checks map
/// files against.
pub fn load_map(
    path: &std::path::Path,
    topic: Option<&str>,
    memory: Option<Available>,
) -> Result<RecordedMap, String> {
    // Bounded like a map file: a device, pipe or directory is refused unopened (`/dev/zero`
    // reports length 0 and reads without end), and so is a file over the limit.
    let (file, len) = grid::io::open_at_most(path, MAX_FILE_BYTES).map_err(|e| match e.kind {
        grid::io::MapErrorKind::FileTooLarge { size, .. } => format!(
            "{}: expected a recording of at most {MAX_FILE_BYTES} bytes, found {size}; record \
             only the map topic (ros2 bag record /map)",
            path.display()
        ),
        _ => e.to_string(),
    })?;
    let source = std::io::BufReader::with_capacity(READ_BUFFER_BYTES, file);
    read_last_map(source, len, topic, memory).map_err(|e| format!("{}: {e}", path.display()))
}

/// A channel of a recording: its topic, its schema's name and its message encoding.
struct Channel {
    topic: String,
    schema: String,
    encoding: String,
}

/// The little-endian fields of a record's body, read front to back; every read checks the
/// length against what is left (`None`: the record is shorter than its fields say).
struct Fields<'a>(&'a [u8]);

impl<'a> Fields<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if self.0.len() < n {
            return None;
        }
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        Some(head)
    }

    fn u16(&mut self) -> Option<u16> {
        Some(u16::from_le_bytes(self.take(2)?.try_into().ok()?))
    }

    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }

    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }

    /// A string: its byte length (u32), then its bytes.
    fn string(&mut self) -> Option<String> {
        let n = usize::try_from(self.u32()?).ok()?;
        Some(String::from_utf8_lossy(self.take(n)?).into_owned())
    }
}

/// Call `each(channel, log_time, data)` for every message of the MCAP file of `len` bytes
/// read from `source`, in file order, chunks decompressed; the file is read as the records
/// need it, never whole. mcap's sans-io reader frames and decompresses the records with
/// every record's length bounded before its bytes are allocated (by [`MAX_RECORD_BYTES`],
/// by [`MAX_EXPANSION`] times the file's size and by `memory`); the three records a map
/// needs (schema, channel, message) are read here with every inner length checked against
/// the record, and the others are skipped unread. (`mcap::MessageStream` trusts lengths
/// read from the file, inside chunks and inside records, so a corrupt file could make it
/// allocate gigabytes to exabytes and abort.)
fn for_each_message(
    mut source: impl Read,
    len: u64,
    memory: Option<Available>,
    mut each: impl FnMut(&Channel, u64, &[u8]),
) -> Result<(), RecordError> {
    use mcap::records::op;
    use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};
    let file_len = usize::try_from(len).unwrap_or(usize::MAX);
    let expanded = file_len.saturating_mul(MAX_EXPANSION).max(1 << 20);
    let room = memory.map_or(usize::MAX, |m| {
        usize::try_from(m.bytes).unwrap_or(usize::MAX)
    });
    let limit = MAX_RECORD_BYTES.min(expanded).min(room);
    let why = || {
        if limit == MAX_RECORD_BYTES {
            format!(
                "a map of at most {} cells and its header",
                crate::occupancy::MAX_CELLS
            )
        } else {
            format!("{MAX_EXPANSION} times the file's {len} bytes, as no map compresses better")
        }
    };
    // A record or chunk longer than the memory left has the refusal of a map loader.
    let out_of_memory = |len: u64| {
        let what = format!("reading a record of {} MiB", len.div_ceil(1 << 20));
        let kind = grid::io::check_fits(&what, len, memory?, RECORD_FIX).err()?;
        Some(RecordError::RecordOutOfMemory(kind))
    };
    let refused = |e: mcap::McapError| {
        if let mcap::McapError::RecordTooLarge { len, .. } | mcap::McapError::ChunkTooLarge(len) = e
            && let Some(refused) = out_of_memory(len)
        {
            return refused;
        }
        match e {
            // A message this long is a map over the cell limit (or another topic's huge
            // message): say so, rather than calling the file corrupt.
            mcap::McapError::RecordTooLarge {
                opcode: op::MESSAGE,
                len,
            } => RecordError::TooLong {
                len,
                limit,
                why: why(),
            },
            e @ (mcap::McapError::BadChunkCrc { .. }
            | mcap::McapError::BadDataCrc { .. }
            | mcap::McapError::BadSummaryCrc { .. }) => RecordError::Damaged(e.to_string()),
            // The reader does no I/O of its own (the file is read here): its I/O errors
            // are its decompressors', like its decompression errors.
            mcap::McapError::Io(e) => RecordError::undecompressed(e),
            mcap::McapError::DecompressionError(e) => RecordError::undecompressed(e),
            mcap::McapError::UnexpectedEof if len == 0 => RecordError::Mcap("an empty file".into()),
            mcap::McapError::UnexpectedEof => RecordError::Mcap(
                "a file that ends in the middle of a record: cut short, or still being \
                 written"
                    .into(),
            ),
            e => RecordError::Mcap(e.to_string()),
        }
    };
    // Every checksum the file carries is checked (a CRC of 0 means none was written), so
    // that a damaged recording is refused rather than read as another map. A chunk is
    // checked as its end is read: checking it first would hold it whole, decompressed,
    // where its records are now read as they come.
    let mut reader = LinearReader::new_with_options(
        LinearReaderOptions::default()
            .with_record_length_limit(limit)
            .with_validate_chunk_crcs(true)
            .with_validate_data_section_crc(true)
            .with_validate_summary_section_crc(true),
    );
    let short = |what: &str| RecordError::Mcap(format!("a {what} record shorter than its fields"));
    let mut schemas: std::collections::HashMap<u16, String> = Default::default();
    let mut channels: std::collections::HashMap<u16, Channel> = Default::default();
    let mut left = len;
    while let Some(event) = reader.next_event() {
        let event = event.map_err(refused)?;
        match event {
            LinearReadEvent::ReadRequest(need) => {
                // Never more than the file has left, however long a record claims to be.
                let n = need.min(usize::try_from(left).unwrap_or(usize::MAX));
                let buf = reader.insert(n);
                let got = loop {
                    match source.read(buf) {
                        Ok(got) => break got,
                        Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                        Err(e) => return Err(RecordError::Read(e)),
                    }
                };
                // 0 (the file ended, or shrank while read) is the end of the recording.
                reader.notify_read(got);
                left -= got as u64;
            }
            LinearReadEvent::Record { opcode, data } => match opcode {
                op::SCHEMA => {
                    let mut f = Fields(data);
                    let (id, name) = (f.u16(), f.string());
                    let (Some(id), Some(name)) = (id, name) else {
                        return Err(short("schema"));
                    };
                    schemas.insert(id, name);
                }
                op::CHANNEL => {
                    let mut f = Fields(data);
                    let (id, schema_id) = (f.u16(), f.u16());
                    let (topic, encoding) = (f.string(), f.string());
                    let (Some(id), Some(schema_id), Some(topic), Some(encoding)) =
                        (id, schema_id, topic, encoding)
                    else {
                        return Err(short("channel"));
                    };
                    let schema = match schema_id {
                        0 => String::new(),
                        s => schemas.get(&s).cloned().ok_or_else(|| {
                            RecordError::Mcap(format!("channel {id} names unknown schema {s}"))
                        })?,
                    };
                    channels.insert(
                        id,
                        Channel {
                            topic,
                            schema,
                            encoding,
                        },
                    );
                }
                op::MESSAGE => {
                    let mut f = Fields(data);
                    let (channel, _sequence, log_time, _publish) =
                        (f.u16(), f.u32(), f.u64(), f.u64());
                    let (Some(channel), Some(log_time)) = (channel, log_time) else {
                        return Err(short("message"));
                    };
                    let ch = channels.get(&channel).ok_or_else(|| {
                        RecordError::Mcap(format!("a message on unknown channel {channel}"))
                    })?;
                    each(ch, log_time, f.0);
                }
                _ => {}
            },
        }
    }
    Ok(())
}

/// Why a map message stating `width × height` cells, `len` bytes as read, is refused from
/// its header: over the cell limit, or (given `memory`) needing more than it to load.
fn refusal(width: u32, height: u32, len: usize, memory: Option<Available>) -> Option<Refusal> {
    let cells = match cells_of(width, height) {
        Ok(cells) => cells as u64,
        Err(too_large) => return Some(Refusal::Map(too_large)),
    };
    let needed = (len as u64).saturating_add(BYTES_PER_CELL * cells);
    let what = format!("loading this {width}x{height} OccupancyGrid");
    grid::io::check_fits(&what, needed, memory?, MAP_FIX)
        .err()
        .map(Refusal::Memory)
}

/// Why a map message is refused from its header ([`refusal`]).
enum Refusal {
    /// Over the cell limit.
    Map(MapMsgError),
    /// Over the memory.
    Memory(grid::io::MapErrorKind),
}

impl Refusal {
    /// The error of this refusal of the message on `topic` at `log_time`.
    fn at(self, topic: &str, log_time: u64) -> RecordError {
        let topic = topic.to_string();
        match self {
            Refusal::Map(source) => RecordError::BadMap {
                topic,
                log_time,
                source,
            },
            Refusal::Memory(source) => RecordError::OutOfMemory {
                topic,
                log_time,
                source,
            },
        }
    }
}

/// The fields of an OccupancyGrid before its cells.
#[derive(serde::Deserialize)]
struct GridHead {
    header: Header,
    info: MapMetaData,
}

/// The `(width, height)` an OccupancyGrid message on `ch` says it has, read from its header
/// without its cells; `None` if `ch` does not carry CDR OccupancyGrids or the header does not
/// decode (the whole message's decoding then says why).
fn grid_size(ch: &Channel, data: &[u8]) -> Option<(u32, u32)> {
    if !GRID_SCHEMAS.contains(&ch.schema.as_str()) || ch.encoding != "cdr" {
        return None;
    }
    let head: GridHead = decode(data).ok()?;
    Some((head.info.width, head.info.height))
}

/// The last OccupancyGrid on `topic` (default: the recording's only OccupancyGrid topic, or
/// `/map` among several) of the MCAP file in `bytes`, with its topic name.
pub fn last_map(bytes: &[u8], topic: Option<&str>) -> Result<(GridMap, String), RecordError> {
    read_last_map(bytes, bytes.len() as u64, topic, None).map(|r| (r.map, r.topic))
}

/// A recording's map, with where and when it was recorded.
#[derive(Clone, Debug)]
pub struct RecordedMap {
    /// The map.
    pub map: GridMap,
    /// The topic it was read from.
    pub topic: String,
    /// The frame and log time of its message.
    pub at: RecordedAt,
}

/// Where and when a recording's map was recorded: what a run on it keeps, so that the run
/// written as a recording lines up with the one it came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RecordedAt {
    /// The frame its header names ([`crate::mcap_write::FRAME`] if it names none).
    pub frame_id: String,
    /// Its log time, in nanoseconds since the epoch.
    pub log_time: u64,
}

/// [`last_map`] of the MCAP file of `len` bytes read from `source` a record at a time (a
/// file's size and the file), within `memory`: given it, a record longer than `memory`
/// leaves is refused from its length, before it is read, and a map whose loading would
/// need more (the message, a copy of its cells and the grid) from its header, before its
/// cells are copied ([`RecordError::OutOfMemory`] names the map's size, the bytes needed and
/// the limit). `None`: not checked (maps are still bounded by
/// [`crate::occupancy::MAX_CELLS`]).
pub fn read_last_map(
    source: impl Read,
    len: u64,
    topic: Option<&str>,
    memory: Option<Available>,
) -> Result<RecordedMap, RecordError> {
    // Pass 1: the topics and their types; the latest message on each grid topic, or, for a
    // map whose header is over the cell limit or the memory, why it is refused (its cells
    // are not copied).
    let mut topics: Vec<(String, String, String)> = Vec::new(); // topic, schema, encoding
    let mut latest: Vec<(String, u64, Result<Vec<u8>, RecordError>)> = Vec::new();
    for_each_message(source, len, memory, |ch, log_time, data| {
        if !topics.iter().any(|(t, _, _)| *t == ch.topic) {
            topics.push((ch.topic.clone(), ch.schema.clone(), ch.encoding.clone()));
        }
        let wanted = match topic {
            Some(t) => same_topic(&ch.topic, t),
            None => GRID_SCHEMAS.contains(&ch.schema.as_str()),
        };
        if !wanted {
            return;
        }
        if latest
            .iter()
            .any(|(t, time, _)| *t == ch.topic && *time > log_time)
        {
            return;
        }
        let refused = grid_size(ch, data)
            .and_then(|(w, h)| refusal(w, h, data.len(), memory))
            .map(|why| why.at(&ch.topic, log_time));
        let slot = match latest.iter().position(|(t, _, _)| *t == ch.topic) {
            Some(k) => &mut latest[k],
            None => {
                latest.push((ch.topic.clone(), log_time, Ok(Vec::new())));
                latest.last_mut().expect("pushed")
            }
        };
        slot.1 = log_time;
        match (refused, &mut slot.2) {
            (Some(refused), kept) => *kept = Err(refused),
            // The previous message's buffer is reused: never two maps in memory at once.
            (None, Ok(kept)) => {
                kept.clear();
                kept.extend_from_slice(data);
            }
            (None, kept) => *kept = Ok(data.to_vec()),
        }
    })?;
    let listing = || {
        if topics.is_empty() {
            "no messages".to_string()
        } else {
            topics
                .iter()
                .map(|(t, s, _)| format!("{t} ({})", schema_name(s)))
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
            found: format!("{} in {encoding} encoding", schema_name(schema)),
        });
    }
    let data = data?;
    let map = map_from_cdr(&data).map_err(|e| match e {
        CdrMapError::Decode(why) => RecordError::Decode {
            topic: name.clone(),
            log_time,
            why,
        },
        CdrMapError::Map(source) => RecordError::BadMap {
            topic: name.clone(),
            log_time,
            source,
        },
    })?;
    // The header decoded as the map's was: it cannot fail here.
    let frame_id = decode_prefix::<GridHead>(&data)
        .map(|h| h.value.header.frame_id)
        .unwrap_or_default();
    let frame_id = match frame_id.trim() {
        "" => crate::mcap_write::FRAME.to_string(),
        f => f.to_string(),
    };
    Ok(RecordedMap {
        map,
        topic: name,
        at: RecordedAt { frame_id, log_time },
    })
}

/// Whether a recording's topic `recorded` is the one `asked` names: the same name, or the
/// same but for the leading `/` of a ROS 2 name (`--topic map` finds `/map`).
fn same_topic(recorded: &str, asked: &str) -> bool {
    recorded.strip_prefix('/').unwrap_or(recorded) == asked.strip_prefix('/').unwrap_or(asked)
}

/// A channel's schema name as messages show it (a channel may have none).
fn schema_name(schema: &str) -> &str {
    if schema.is_empty() {
        "no schema"
    } else {
        schema
    }
}

/// Why a CDR OccupancyGrid gave no map.
#[derive(Debug, PartialEq)]
enum CdrMapError {
    /// The bytes do not decode as an OccupancyGrid.
    Decode(String),
    /// They decode, but not to a usable map.
    Map(MapMsgError),
}

/// The map of a CDR-encoded OccupancyGrid (with its encapsulation header), classified from
/// the message's bytes in place: the same map as decoding the message and
/// [`map_from_msg`](crate::occupancy::map_from_msg), without a decoded copy of its cells (at the cell limit, 256 MiB
/// fewer while loading).
fn map_from_cdr(bytes: &[u8]) -> Result<GridMap, CdrMapError> {
    let head = decode_prefix::<GridHead>(bytes).map_err(|e| CdrMapError::Decode(e.to_string()))?;
    // `data`: a sequence<int8>, its u32 length aligned to 4 from the body's start.
    let at = head.consumed.next_multiple_of(4);
    let short = || CdrMapError::Decode("the message ends inside its data".into());
    let len: [u8; 4] = head
        .body(bytes)
        .get(at..at + 4)
        .and_then(|b| b.try_into().ok())
        .ok_or_else(short)?;
    let len = if head.big_endian {
        u32::from_be_bytes(len)
    } else {
        u32::from_le_bytes(len)
    } as usize;
    let data = head
        .body(bytes)
        .get(at + 4..)
        .and_then(|d| d.get(..len))
        .ok_or_else(short)?;
    map_from_bytes(&head.value.info, data).map_err(CdrMapError::Map)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msgs::OccupancyGrid;
    use crate::occupancy::map_from_msg;
    use proptest::prelude::*;

    /// The slow, obvious way: decode the whole message, then build its map.
    fn oracle(bytes: &[u8]) -> Result<GridMap, CdrMapError> {
        let msg: OccupancyGrid = decode(bytes).map_err(|e| CdrMapError::Decode(e.to_string()))?;
        map_from_msg(&msg).map_err(CdrMapError::Map)
    }

    /// `msg` as CDR in either byte order, with its encapsulation header.
    fn encode_as(msg: &OccupancyGrid, big_endian: bool) -> Vec<u8> {
        if !big_endian {
            return crate::cdr::encode(msg);
        }
        let body = cdr_encoding::to_vec::<_, byteorder::BigEndian>(msg).unwrap();
        [&[0u8, 0, 0, 0][..], &body].concat()
    }

    fn grid_msg(w: u32, h: u32, frame: &str, data: Vec<i8>) -> OccupancyGrid {
        let mut m = OccupancyGrid::default();
        m.header.frame_id = frame.into();
        m.info.width = w;
        m.info.height = h;
        m.info.resolution = 0.05;
        m.info.origin.orientation.w = 1.0;
        m.data = data;
        m
    }

    #[test]
    fn an_empty_or_truncated_message_is_a_decode_error() {
        let bytes = crate::cdr::encode(&grid_msg(3, 2, "map", vec![0, 100, -1, 0, 0, 0]));
        assert!(map_from_cdr(&bytes).is_ok());
        for cut in [0, 3, 10, bytes.len() - 7, bytes.len() - 1] {
            assert!(
                matches!(map_from_cdr(&bytes[..cut]), Err(CdrMapError::Decode(_))),
                "cut at {cut}"
            );
        }
    }

    proptest! {
        /// Read in place, a message gives the map its full decoding gives, or fails the
        /// same way: for any size, frame id, byte order, cells (the data's length need not
        /// match the size), trailing bytes and truncation.
        #[test]
        fn in_place_reading_equals_full_decoding(
            w in 0u32..9, h in 0u32..9, frame in "[a-z_/]{0,9}",
            extra in -2i32..3, big_endian: bool, trailing in 0usize..5, cut in 0usize..8,
            seed: u64,
        ) {
            let n = ((w * h) as i32 + extra).max(0) as usize;
            let data: Vec<i8> = (0..n).map(|k| seed.rotate_left(k as u32 % 64) as i8).collect();
            let mut bytes = encode_as(&grid_msg(w, h, &frame, data), big_endian);
            bytes.extend(std::iter::repeat_n(0u8, trailing));
            let bytes = &bytes[..bytes.len().saturating_sub(cut)];
            match (map_from_cdr(bytes), oracle(bytes)) {
                (Ok(a), Ok(b)) => {
                    prop_assert_eq!(a.cells, b.cells);
                    prop_assert_eq!(a.resolution, b.resolution);
                    prop_assert_eq!(a.origin, b.origin);
                }
                (Err(CdrMapError::Decode(_)), Err(CdrMapError::Decode(_))) => {}
                (Err(CdrMapError::Map(a)), Err(CdrMapError::Map(b))) => prop_assert_eq!(a, b),
                (a, b) => prop_assert!(false, "in place {:?}, decoded {:?}", a.err(), b.err()),
            }
        }
    }
}
