//! What the record crate's tests share: a scratch folder, incompressible bytes, and a
//! recording written with the mcap crate.
#![allow(dead_code)] // each test binary uses a part

use std::path::PathBuf;

use record::msgs::{OccupancyGrid, RosMessage};

/// A fresh scratch folder for one test, removed when the test ends (also when it fails).
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// The folder of test `test` of this binary.
    pub fn new(test: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("frontier-record-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch folder");
        Self(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `n` bytes that do not compress, different for each `seed`.
pub fn noise(n: usize, seed: u64) -> Vec<u8> {
    let mut state = 0x9e37_79b9_7f4a_7c15u64 ^ seed.wrapping_mul(0x2545_f491_4f6c_dd1d);
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        })
        .collect()
}

/// A recording in zstd-compressed chunks: `noise` messages on `/noise`, then the map
/// messages `maps` on `/map`, all logged at 1 ns.
pub fn recording(noise: &[Vec<u8>], maps: &[Vec<u8>]) -> Vec<u8> {
    recording_with(Some(mcap::Compression::Zstd), noise, maps)
}

/// [`recording`] with its chunks compressed as `compression` says (`None`: stored).
pub fn recording_with(
    compression: Option<mcap::Compression>,
    noise: &[Vec<u8>],
    maps: &[Vec<u8>],
) -> Vec<u8> {
    let mut out = mcap::WriteOptions::new()
        .profile("ros2")
        .compression(compression)
        .create(std::io::Cursor::new(Vec::new()))
        .expect("writer");
    let schema = out
        .add_schema(
            OccupancyGrid::TYPE,
            "ros2msg",
            OccupancyGrid::definition().as_bytes(),
        )
        .expect("schema");
    let map = out
        .add_channel(schema, "/map", "cdr", &Default::default())
        .expect("channel");
    let other = out
        .add_channel(0, "/noise", "application/octet-stream", &Default::default())
        .expect("channel");
    let messages = noise
        .iter()
        .map(|m| (other, m))
        .chain(maps.iter().map(|m| (map, m)));
    for (k, (channel_id, data)) in messages.enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: k as u32,
            log_time: 1,
            publish_time: 0,
        };
        out.write_to_known_channel(&header, data).expect("message");
    }
    out.finish().expect("finish");
    out.into_inner().into_inner()
}

/// An OccupancyGrid message (CDR) stating `width × height` cells in its header, with `data`
/// as its cells (which need not be that many).
pub fn grid_message(width: u32, height: u32, data: Vec<i8>) -> Vec<u8> {
    let mut msg = OccupancyGrid::default();
    msg.header.frame_id = "map".into();
    msg.info.resolution = 0.05;
    msg.info.width = width;
    msg.info.height = height;
    msg.info.origin.orientation.w = 1.0;
    msg.data = data;
    record::cdr::encode(&msg)
}
